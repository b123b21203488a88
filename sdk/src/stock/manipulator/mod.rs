//! Stock manipulator components (Part 1 §5.4): a serial arm of revolute and prismatic
//! joints, its kinematics from Report Manipulator Specifications, and the ten manipulator
//! components over two small hardware traits ([`hardware`]). `jaus_sim::arm` implements
//! those traits with a simulated arm, so every component runs end to end without hardware.

pub mod hardware;
