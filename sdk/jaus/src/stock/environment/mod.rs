//! Stock environment-sensor components (Part 1 §5.5), each over a small hardware trait
//! that `jaus-sim` implements with a simulated device: the Range Sensor ([`range`]),
//! whose detections can be kept in a world model ([`map_feed`]), and the Visual Sensor
//! ([`camera`]) with its image encodings ([`image`]).

pub mod camera;
pub mod image;
pub mod map_feed;
pub mod range;
pub mod scan;
