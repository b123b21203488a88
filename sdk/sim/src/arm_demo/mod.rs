//! The arm phase of `jaus demo` (`jaus demo --arm`): the ten stock manipulator
//! components over one simulated 6-axis arm on the in-process bus, and a scripted
//! operator running a pick-and-place sequence through four of the drivers.
//!
//! Node 1.3 hosts the Primitive Manipulator (49), the joint position, velocity and
//! force/torque sensors (51–53) and the six drivers (54–59). The operator (a System
//! Commander, 1.2.40.1) learns the arm from Report Manipulator Specifications, follows the
//! joints by service connection, and for each move takes control of the driver, resumes
//! it, commands it, waits until the tool point has settled on the target (computed with
//! the kinematics from the reported joints), then puts the driver back in Standby and
//! releases it so the next driver can take the Primitive Manipulator, whose holding
//! controller keeps the arm where the last move left it meanwhile:
//!
//! 1. End-Effector Pose Driver: above the pick point, down to it, back up;
//! 2. Joint Move Driver: two timed joint sets to the place configuration;
//! 3. End-Effector Velocity State Driver: a 2 s sideways jog in the vehicle frame;
//! 4. End-Effector Discrete Pose Driver: back above the pick point, then a timed square.
//!
//! The run reports, per move, when it started, the time taken, the final error of the
//! true tool pose against the commanded one, how far the joints left their held
//! positions while the arm passed to the move's driver and how far they went past where
//! the move left them ([`measure`]), and traces joint angles and the tool path for the
//! plot.

mod measure;
mod operator;

use std::time::{Duration, Instant};

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use crate::arm::{ArmParams, SimArm};
use jaus::component::local::{Endpoint, LocalBus};
use jaus::component::Config;
use jaus::components::system_commander;
use jaus::components::{
    manipulator_end_effector_discrete_pose_driver as dpd,
    manipulator_end_effector_pose_driver as epd,
    manipulator_end_effector_velocity_state_driver as evd,
    manipulator_joint_force_torque_sensor as fts, manipulator_joint_move_driver as jmd,
    manipulator_joint_position_sensor as jps, manipulator_joint_positions_driver as jpd,
    manipulator_joint_velocities_driver as jvd, manipulator_joint_velocity_sensor as jvs,
    primitive_manipulator as pm,
};
use jaus::stock::manipulator::link::ArmDriverConfig;
use jaus::stock::manipulator::{
    PrimitiveManipulatorConfig, StockEndEffectorDiscretePoseDriver, StockEndEffectorPoseDriver,
    StockEndEffectorVelocityStateDriver, StockJointMoveDriver, StockJointPositionsDriver,
    StockJointSensor, StockJointVelocitiesDriver, StockPrimitiveManipulator,
};
use jaus::Address;
pub use measure::{excursion_deg, overshoot_deg, sample_at};
use operator::Step;
pub use operator::{ArmOcu, ArmOperator};

/// Addresses of the arm node.
pub mod addr {
    use jaus::components as c;
    use jaus::Address;
    /// Primitive Manipulator.
    pub const PM: Address = Address::new(1, 3, c::primitive_manipulator::ID, 1);
    /// Joint Position Sensor.
    pub const JPS: Address = Address::new(1, 3, c::manipulator_joint_position_sensor::ID, 1);
    /// Joint Velocity Sensor.
    pub const JVS: Address = Address::new(1, 3, c::manipulator_joint_velocity_sensor::ID, 1);
    /// Joint Force/Torque Sensor.
    pub const FTS: Address = Address::new(1, 3, c::manipulator_joint_force_torque_sensor::ID, 1);
    /// Joint Positions Driver.
    pub const JPD: Address = Address::new(1, 3, c::manipulator_joint_positions_driver::ID, 1);
    /// End-Effector Pose Driver.
    pub const EPD: Address = Address::new(1, 3, c::manipulator_end_effector_pose_driver::ID, 1);
    /// Joint Velocities Driver.
    pub const JVD: Address = Address::new(1, 3, c::manipulator_joint_velocities_driver::ID, 1);
    /// End-Effector Velocity State Driver.
    pub const EVD: Address = Address::new(
        1,
        3,
        c::manipulator_end_effector_velocity_state_driver::ID,
        1,
    );
    /// Joint Move Driver.
    pub const JMD: Address = Address::new(1, 3, c::manipulator_joint_move_driver::ID, 1);
    /// End-Effector Discrete Pose Driver.
    pub const DPD: Address = Address::new(
        1,
        3,
        c::manipulator_end_effector_discrete_pose_driver::ID,
        1,
    );
    /// The operator.
    pub const OCU: Address = Address::new(1, 2, c::system_commander::ID, 1);
}

/// Control period of the arm components.
pub const CONTROL_PERIOD: Duration = Duration::from_millis(10);

/// Options of an arm demo run.
#[derive(Debug, Clone)]
pub struct ArmOptions {
    /// Seed of the joint sensor noise.
    pub seed: u64,
    /// Joint position noise (standard deviation, rad).
    pub noise: f64,
    /// Give up after this much simulated time.
    pub timeout: Duration,
    /// Progress line every this much simulated time (`None`: no progress).
    pub progress: Option<Duration>,
}

impl Default for ArmOptions {
    fn default() -> Self {
        Self {
            seed: 7,
            noise: 2e-5,
            timeout: Duration::from_secs(120),
            progress: Some(Duration::from_secs(2)),
        }
    }
}

/// The tool point used by the demo (end-effector frame, m): a 10 cm gripper.
pub const TOOL: [f64; 3] = [0.0, 0.0, 0.1];

/// A tool orientation pointing the tool down (end-effector z along vehicle z, which
/// points down).
fn down() -> UnitQuaternion<f64> {
    UnitQuaternion::identity()
}

fn pose(x: f64, y: f64, z: f64) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::new(x, y, z), down())
}

/// Above the pick point, the pick point, and the place configuration's neighbourhood
/// (vehicle frame: x forward, y right, z down; the arm base is at the origin).
pub fn pick_above() -> Isometry3<f64> {
    pose(0.45, -0.20, -0.10)
}

/// The pick point, 12 cm below [`pick_above`].
pub fn pick() -> Isometry3<f64> {
    pose(0.45, -0.20, 0.02)
}

/// The place configuration of the joint move (rad), reached in two timed sets.
pub const PLACE_JOINTS: [[f64; 6]; 2] = [
    [0.3, -0.5, 0.9, 0.0, 0.9, 0.0],
    [0.8, -0.6, 1.1, 0.1, 1.0, 0.2],
];

/// Times of the two joint sets, s after the start of the move.
pub const PLACE_TIMES: [f64; 2] = [2.5, 4.5];

/// The sideways jog: vehicle-frame velocity (m/s) and duration.
pub const JOG: ([f64; 3], Duration) = ([0.0, 0.06, 0.0], Duration::from_secs(2));

/// Corners of the square path, offsets from [`pick_above`] (m, vehicle frame), one
/// every [`SQUARE_STEP`] after the first 3 s.
pub const SQUARE: [[f64; 3]; 4] = [
    [0.08, 0.0, 0.0],
    [0.08, 0.08, 0.0],
    [0.0, 0.08, 0.0],
    [0.0, 0.0, 0.0],
];

/// Seconds between the corners of the square.
pub const SQUARE_STEP: f64 = 1.5;

/// One move of the sequence, measured on the simulated arm's true tool pose.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    /// What the move was.
    pub name: &'static str,
    /// The driver that executed it.
    pub driver: Address,
    /// When the move was commanded, s from the start of the run.
    pub start: f64,
    /// Time from the command to settled (s).
    pub seconds: f64,
    /// Final position error of the tool point, mm.
    pub position_error_mm: f64,
    /// Final orientation error of the tool, degrees.
    pub angle_error_deg: f64,
    /// When the move's driver is not the previous move's (or for the first move): the
    /// largest excursion of any joint, degrees, from where the previous move settled (the
    /// first: from where the arm was at the start) until this move was commanded, while
    /// the arm passed from one driver to the next. `None` when the same driver carried
    /// on.
    pub handover_deg: Option<f64>,
    /// The largest distance any joint went past where the move left it, degrees, in the
    /// direction it travelled over the move's last leg ([`overshoot_deg`]; the last leg
    /// is the whole move, except for the joint move its second set, for the jog its stop
    /// and for the square its last side).
    pub overshoot_deg: f64,
}

/// What the operator saw and measured.
#[derive(Debug, Clone, Default)]
pub struct ArmReport {
    /// The moves in order.
    pub moves: Vec<Move>,
    /// Joint angles over time: (s, joints).
    pub joints: Vec<(f64, Vec<f64>)>,
    /// Tool point over time (vehicle frame, m).
    pub tool: Vec<(f64, Vector3<f64>)>,
    /// Commanded tool targets (vehicle frame, m), in order.
    pub targets: Vec<Vector3<f64>>,
    /// Simulated duration, s.
    pub duration: f64,
    /// Messages delivered on the bus.
    pub messages: u64,
    /// Velocity tracking of the jog in its steady part (from 0.5 s after the command to
    /// its end), on the true tool point: (RMS, largest) error of the tool velocity
    /// against the commanded one, m/s, from positions 50 ms apart.
    pub jog_tracking: Option<(f64, f64)>,
}

fn arm_config() -> Config {
    Config {
        tick: CONTROL_PERIOD,
        ..Config::default()
    }
}

/// The ten manipulator components of node `ss`.`node` over `arm` (the drivers command
/// the Primitive Manipulator and read the sensors of the same node).
pub fn arm_components(arm: &SimArm, ss: u8, node: u8, t0: Instant) -> Vec<Box<dyn Endpoint>> {
    let at = |id: u8| Address::new(ss, node, id, 1);
    let chain = arm.lock().chain().clone();
    let drivers = ArmDriverConfig {
        output: at(pm::ID),
        position_sensor: at(jps::ID),
        velocity_sensor: Some(at(jvs::ID)),
        ..ArmDriverConfig::default()
    };
    let cfg = arm_config;
    vec![
        Box::new(pm::component(
            at(pm::ID),
            StockPrimitiveManipulator::new(
                arm.clone(),
                chain,
                PrimitiveManipulatorConfig::default(),
            )
            .with_hold(arm.holding_controller()),
            cfg(),
            t0,
        )),
        Box::new(jps::component(
            at(jps::ID),
            StockJointSensor::new(arm.clone()),
            cfg(),
            t0,
        )),
        Box::new(jvs::component(
            at(jvs::ID),
            StockJointSensor::new(arm.clone()),
            cfg(),
            t0,
        )),
        Box::new(fts::component(
            at(fts::ID),
            StockJointSensor::new(arm.clone()),
            cfg(),
            t0,
        )),
        Box::new(jpd::component(
            at(jpd::ID),
            StockJointPositionsDriver::new(drivers.clone()),
            cfg(),
            t0,
        )),
        Box::new(epd::component(
            at(epd::ID),
            StockEndEffectorPoseDriver::new(drivers.clone()),
            cfg(),
            t0,
        )),
        Box::new(jvd::component(
            at(jvd::ID),
            StockJointVelocitiesDriver::new(drivers.clone()),
            cfg(),
            t0,
        )),
        Box::new(evd::component(
            at(evd::ID),
            StockEndEffectorVelocityStateDriver::new(drivers.clone()),
            cfg(),
            t0,
        )),
        Box::new(jmd::component(
            at(jmd::ID),
            StockJointMoveDriver::new(drivers.clone()),
            cfg(),
            t0,
        )),
        Box::new(dpd::component(
            at(dpd::ID),
            StockEndEffectorDiscretePoseDriver::new(drivers),
            cfg(),
            t0,
        )),
    ]
}

/// Builds the arm node and the operator on a bus starting at `t0`.
pub fn build(t0: Instant, opts: &ArmOptions) -> (LocalBus, SimArm) {
    let mut params = ArmParams::six_axis();
    params.position_noise = opts.noise;
    params.seed = opts.seed;
    let arm = SimArm::new(params);
    let mut bus = LocalBus::new(t0);
    for p in arm_components(&arm, 1, 3, t0) {
        bus.add_boxed(p);
    }
    bus.add(system_commander::component(
        addr::OCU,
        ArmOperator::default(),
        Config {
            authority: 200,
            ..Config::default()
        },
        t0,
    ));
    (bus, arm)
}

/// Runs the arm demo; `print` receives progress lines.
pub fn run(opts: &ArmOptions, mut print: impl FnMut(&str)) -> Result<ArmReport, String> {
    let t0 = Instant::now();
    let (mut bus, arm) = build(t0, opts);
    let mut report = ArmReport::default();
    let mut next_progress = Duration::ZERO;
    let mut next_trace = Duration::ZERO;
    // The true joint angles every control period, for the hand-over and overshoot
    // measurements.
    let mut fine: Vec<(f64, Vec<f64>)> = Vec::new();
    loop {
        let elapsed = bus.now() - t0;
        fine.push((elapsed.as_secs_f64(), arm.lock().positions().to_vec()));
        let op = &bus
            .get::<ArmOcu>(addr::OCU)
            .ok_or("operator missing")?
            .behaviour()
            .0;
        if elapsed >= next_trace {
            next_trace = elapsed + Duration::from_millis(50);
            let a = arm.lock();
            let t = elapsed.as_secs_f64();
            report.joints.push((t, a.positions().to_vec()));
            report
                .tool
                .push((t, a.tool_pose(&Vector3::from(TOOL)).translation.vector));
        }
        let step = op.step;
        if let Some(every) = opts.progress {
            if elapsed >= next_progress || step == Step::Done {
                next_progress = elapsed + every;
                let p = arm
                    .lock()
                    .tool_pose(&Vector3::from(TOOL))
                    .translation
                    .vector;
                let phase = match step {
                    Step::Start => "starting",
                    Step::Acquire(p) | Step::Hold(p) | Step::Settle(p) => p.name(),
                    Step::Done => "done",
                };
                print(&format!(
                    "t = {:5.1} s  {:<40} tool x {:6.3} m  y {:6.3} m  z {:6.3} m",
                    elapsed.as_secs_f64(),
                    phase,
                    p.x,
                    p.y,
                    p.z
                ));
            }
        }
        if step == Step::Done {
            break;
        }
        if elapsed > opts.timeout {
            return Err(format!(
                "the arm sequence did not finish within {:?} of simulated time (stuck at {step:?})",
                opts.timeout
            ));
        }
        bus.run_for(Duration::from_millis(10));
    }
    let op = &bus
        .get::<ArmOcu>(addr::OCU)
        .ok_or("operator missing")?
        .behaviour()
        .0;
    // Each move's error is measured at the instant it settled, on the true arm: the
    // joint angles sampled nearest to that instant.
    let mut chain = arm.lock().chain().clone();
    chain.tool = Vector3::from(TOOL);
    let mut previous: Option<(Address, f64)> = None;
    for (phase, start, end, target) in &op.done {
        let (t_start, t_end) = ((*start - t0).as_secs_f64(), (*end - t0).as_secs_f64());
        let q_end = sample_at(&fine, t_end).unwrap_or_default();
        let t_leg = t_start + phase.last_leg();
        let q_leg = sample_at(&fine, t_leg).unwrap_or_default();
        let actual = chain.tool_pose(&q_end);
        let handover_deg = match previous {
            Some((driver, _)) if driver == phase.driver() => None,
            Some((_, settled)) => {
                let held = sample_at(&fine, settled).unwrap_or_default();
                Some(excursion_deg(&fine, settled, t_start, &held))
            }
            None => {
                let held = sample_at(&fine, 0.0).unwrap_or_default();
                Some(excursion_deg(&fine, 0.0, t_start, &held))
            }
        };
        previous = Some((phase.driver(), t_end));
        report.moves.push(Move {
            name: phase.name(),
            driver: phase.driver(),
            start: t_start,
            seconds: t_end - t_start,
            position_error_mm: (actual.translation.vector - target.translation.vector).norm()
                * 1000.0,
            angle_error_deg: actual.rotation.angle_to(&target.rotation).to_degrees(),
            handover_deg,
            overshoot_deg: overshoot_deg(&fine, t_leg, t_end, &q_leg, &q_end),
        });
    }
    report.targets = op.targets.clone();
    report.duration = (bus.now() - t0).as_secs_f64();
    report.messages = bus.stats().delivered;
    if let Some(start) = op.jog_started {
        let (from, to) = (
            (start - t0).as_secs_f64() + 0.5,
            (start - t0 + JOG.1).as_secs_f64(),
        );
        let commanded = Vector3::from(JOG.0);
        let errors: Vec<f64> = report
            .tool
            .windows(2)
            .filter(|w| w[0].0 >= from && w[1].0 <= to)
            .map(|w| ((w[1].1 - w[0].1) / (w[1].0 - w[0].0) - commanded).norm())
            .collect();
        if !errors.is_empty() {
            let rms = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
            report.jog_tracking = Some((rms, errors.iter().copied().fold(0.0, f64::max)));
        }
    }
    Ok(report)
}
