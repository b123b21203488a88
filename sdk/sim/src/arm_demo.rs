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
//! releases it so the next driver can take the Primitive Manipulator:
//!
//! 1. End-Effector Pose Driver: above the pick point, down to it, back up;
//! 2. Joint Move Driver: two timed joint sets to the place configuration;
//! 3. End-Effector Velocity State Driver: a 2 s sideways jog in the vehicle frame;
//! 4. End-Effector Discrete Pose Driver: back above the pick point, then a timed square.
//!
//! The run reports, per move, the time taken and the final error of the true tool pose
//! against the commanded one, and traces joint angles and the tool path for the plot.

use std::time::{Duration, Instant};

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use crate::arm::{ArmParams, SimArm};
use jaus::component::local::{Endpoint, LocalBus};
use jaus::component::{Config, CoreState, Refused};
use jaus::components::system_commander::{self, Ctx, SystemCommander};
use jaus::components::{
    manipulator_end_effector_discrete_pose_driver as dpd,
    manipulator_end_effector_pose_driver as epd,
    manipulator_end_effector_velocity_state_driver as evd,
    manipulator_joint_force_torque_sensor as fts, manipulator_joint_move_driver as jmd,
    manipulator_joint_position_sensor as jps, manipulator_joint_positions_driver as jpd,
    manipulator_joint_velocities_driver as jvd, manipulator_joint_velocity_sensor as jvs,
    primitive_manipulator as pm,
};
use jaus::messages::*;
use jaus::stock::manipulator::kinematics::Chain;
use jaus::stock::manipulator::link::ArmDriverConfig;
use jaus::stock::manipulator::{
    PrimitiveManipulatorConfig, StockEndEffectorDiscretePoseDriver, StockEndEffectorPoseDriver,
    StockEndEffectorVelocityStateDriver, StockJointMoveDriver, StockJointPositionsDriver,
    StockJointSensor, StockJointVelocitiesDriver, StockPrimitiveManipulator,
};
use jaus::{Address, JausMessage};

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
    /// Time from the command to settled (s).
    pub seconds: f64,
    /// Final position error of the tool point, mm.
    pub position_error_mm: f64,
    /// Final orientation error of the tool, degrees.
    pub angle_error_deg: f64,
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

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
enum Step {
    #[default]
    Start,
    /// Taking control of `Phase`'s driver.
    Acquire(Phase),
    /// Resumed, waiting for the driver to hold the arm still.
    Hold(Phase),
    /// Commanded, waiting to settle.
    Settle(Phase),
    Done,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Above,
    Pick,
    Lift,
    JointMove,
    Jog,
    Square,
}

impl Phase {
    fn driver(self) -> Address {
        match self {
            Phase::Above | Phase::Pick | Phase::Lift => addr::EPD,
            Phase::JointMove => addr::JMD,
            Phase::Jog => addr::EVD,
            Phase::Square => addr::DPD,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Phase::Above => "pose: above the pick point",
            Phase::Pick => "pose: down to the pick point",
            Phase::Lift => "pose: lift",
            Phase::JointMove => "joint move: to the place configuration",
            Phase::Jog => "velocity state: sideways jog",
            Phase::Square => "discrete poses: a timed square",
        }
    }

    fn next(self) -> Option<Phase> {
        match self {
            Phase::Above => Some(Phase::Pick),
            Phase::Pick => Some(Phase::Lift),
            Phase::Lift => Some(Phase::JointMove),
            Phase::JointMove => Some(Phase::Jog),
            Phase::Jog => Some(Phase::Square),
            Phase::Square => None,
        }
    }
}

/// Tool point within this of the target and joints this still count as settled.
const SETTLED_MM: f64 = 0.5;
const STILL_RAD_S: f64 = 0.002;

/// The scripted arm operator.
#[derive(Debug, Default)]
pub struct ArmOperator {
    step: Step,
    chain: Option<Chain>,
    joints: Option<Vec<f64>>,
    rates: Option<Vec<f64>>,
    target: Option<Isometry3<f64>>,
    commanded_at: Option<Instant>,
    last_request: Option<Instant>,
    next_jog: Option<Instant>,
    resumed_at: Option<Instant>,
    jog_started: Option<Instant>,
    jog_until: Option<Instant>,
    /// Moves done: (phase, commanded at, settled at, target).
    done: Vec<(Phase, Instant, Instant, Isometry3<f64>)>,
    targets: Vec<Vector3<f64>>,
}

impl ArmOperator {
    fn tool_pose(&self) -> Option<Isometry3<f64>> {
        Some(self.chain.as_ref()?.tool_pose(self.joints.as_ref()?))
    }

    /// Whether the joints are still and, except after the jog (whose end point is only
    /// as exact as the integration of the commanded velocity), the tool point is on the
    /// target.
    fn settled(&self, phase: Phase) -> bool {
        let (Some(target), Some(p)) = (self.target, self.tool_pose()) else {
            return false;
        };
        let still = self
            .rates
            .as_ref()
            .is_some_and(|r| r.iter().all(|v| v.abs() < STILL_RAD_S));
        let err = (p.translation.vector - target.translation.vector).norm() * 1000.0;
        still && (phase == Phase::Jog || err < SETTLED_MM)
    }

    fn command(&mut self, ctx: &mut Ctx<'_>, phase: Phase) {
        let now = ctx.now();
        let start = self.tool_pose().unwrap_or_else(pick_above);
        self.commanded_at = Some(now);
        let target = match phase {
            Phase::Above | Phase::Pick | Phase::Lift => {
                let t = match phase {
                    Phase::Pick => pick(),
                    _ => pick_above(),
                };
                if phase == Phase::Above {
                    ctx.send(
                        addr::EPD,
                        SetToolPoint {
                            x: TOOL[0],
                            y: TOOL[1],
                            z: TOOL[2],
                        },
                    );
                }
                let q = t.rotation.quaternion();
                let p = t.translation.vector;
                ctx.send(
                    addr::EPD,
                    SetEndEffectorPose {
                        x: p.x,
                        y: p.y,
                        z: p.z,
                        d: q.w,
                        a: q.i,
                        b: q.j,
                        c: q.k,
                    },
                );
                t
            }
            Phase::JointMove => {
                let poses = PLACE_JOINTS
                    .iter()
                    .zip(PLACE_TIMES)
                    .map(|(q, time)| JointMotionPose {
                        pose_time: time,
                        joints: q
                            .iter()
                            .map(|&position| JointMotionLimits {
                                position,
                                max_velocity: 1.0,
                                max_acceleration: 2.0,
                                max_deceleration: 2.0,
                            })
                            .collect(),
                    })
                    .collect::<Vec<_>>();
                ctx.send(
                    addr::JMD,
                    SetJointMotion {
                        num_joints: 6,
                        num_poses: poses.len() as u8,
                        poses,
                    },
                );
                self.chain
                    .as_ref()
                    .map(|c| c.tool_pose(&PLACE_JOINTS[1]))
                    .unwrap_or(start)
            }
            Phase::Jog => {
                self.jog_until = Some(now + JOG.1);
                self.jog_started = Some(now);
                self.next_jog = Some(now);
                let d = Vector3::from(JOG.0) * JOG.1.as_secs_f64();
                Isometry3::from_parts(
                    Translation3::from(start.translation.vector + d),
                    start.rotation,
                )
            }
            Phase::Square => {
                // Back above the pick point in 3 s, then round the square. The Discrete
                // Pose Driver has no tool point (Set Tool Point is the Pose Driver's):
                // its poses are of the end-effector frame, so the tool offset comes off.
                let centre = pick_above();
                let q = centre.rotation.quaternion();
                let flange = centre.rotation * -Vector3::from(TOOL);
                let at = |time: f64, tool: Vector3<f64>| {
                    let p = tool + flange;
                    EndEffectorPathPose {
                        pose_time: time,
                        x: p.x,
                        y: p.y,
                        z: p.z,
                        d: q.w,
                        a: q.i,
                        b: q.j,
                        c: q.k,
                    }
                };
                let mut poses = vec![at(3.0, centre.translation.vector)];
                poses.extend(SQUARE.iter().enumerate().map(|(i, o)| {
                    at(
                        3.0 + SQUARE_STEP * (i + 1) as f64,
                        centre.translation.vector + Vector3::from(*o),
                    )
                }));
                ctx.send(addr::DPD, SetEndEffectorPathMotion { poses });
                centre
            }
        };
        self.targets.push(target.translation.vector);
        self.target = Some(target);
    }

    fn jog(&mut self, ctx: &mut Ctx<'_>) {
        let now = ctx.now();
        let (Some(until), Some(next)) = (self.jog_until, self.next_jog) else {
            return;
        };
        if now >= next {
            // The jog velocity every 100 ms while it lasts, then one zero velocity: a
            // velocity command holds until it is replaced or goes stale.
            let moving = now < until;
            let v = if moving { JOG.0 } else { [0.0; 3] };
            self.next_jog = moving.then(|| now + Duration::from_millis(100));
            ctx.send(
                addr::EVD,
                SetEndEffectorVelocityState {
                    coordinate_system: 1,
                    x_linear: v[0],
                    y_linear: v[1],
                    z_linear: v[2],
                    ..Default::default()
                },
            );
        }
    }
}

impl SystemCommander for ArmOperator {
    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        let now = ctx.now();
        match self.step {
            Step::Start => {
                ctx.send(addr::PM, QueryManipulatorSpecifications {});
                for (provider, code) in [
                    (addr::JPS, ReportJointPositions::CODE),
                    (addr::JVS, ReportJointVelocities::CODE),
                ] {
                    if let Err(e) = ctx.create_service_connection(provider, code, 50.0, 0) {
                        tracing::warn!("arm operator: no joint feedback: {e}");
                    }
                }
                self.step = Step::Acquire(Phase::Above);
            }
            Step::Acquire(phase) => {
                if self.chain.is_none() || self.joints.is_none() {
                    if self
                        .last_request
                        .is_none_or(|t| now >= t + Duration::from_secs(1))
                    {
                        self.last_request = Some(now);
                        ctx.send(addr::PM, QueryManipulatorSpecifications {});
                    }
                    return;
                }
                let driver = phase.driver();
                if ctx.has_control_of(driver) {
                    ctx.send_core(driver, Resume {});
                    self.resumed_at = Some(now);
                    self.step = Step::Hold(phase);
                } else if self
                    .last_request
                    .is_none_or(|t| now >= t + Duration::from_millis(500))
                {
                    self.last_request = Some(now);
                    ctx.request_control(driver);
                }
            }
            Step::Hold(phase) => {
                // Between drivers the arm has no effort (the previous driver zeroes it
                // on leaving Ready): command once the new one holds the arm still.
                let resumed = self.resumed_at.unwrap_or(now);
                let still = self
                    .rates
                    .as_ref()
                    .is_some_and(|r| r.iter().all(|v| v.abs() < STILL_RAD_S));
                if now >= resumed + Duration::from_millis(300) && still {
                    self.command(ctx, phase);
                    self.step = Step::Settle(phase);
                }
            }
            Step::Settle(phase) => {
                if phase == Phase::Jog {
                    self.jog(ctx);
                }
                let jogging = self.next_jog.is_some();
                let started = self.commanded_at.unwrap_or(now);
                if !jogging && now > started + Duration::from_millis(200) && self.settled(phase) {
                    let Some(target) = self.target else {
                        return;
                    };
                    self.done.push((phase, started, now, target));
                    let driver = phase.driver();
                    let next = phase.next();
                    if next.map(Phase::driver) != Some(driver) {
                        ctx.send_core(driver, Standby {});
                        ctx.release_control(driver);
                    }
                    self.step = next.map_or(Step::Done, Step::Acquire);
                    if let Some(n) = next {
                        if n.driver() == driver {
                            self.command(ctx, n);
                            self.step = Step::Settle(n);
                        }
                    }
                }
            }
            Step::Done => {}
        }
    }

    fn on_other_message(
        &mut self,
        ctx: &mut Ctx<'_>,
        msg: &Message,
    ) -> Result<Option<Message>, Refused> {
        match msg {
            Message::ReportManipulatorSpecifications(r) => match Chain::from_specifications(r) {
                Ok(mut c) => {
                    c.tool = Vector3::from(TOOL);
                    self.chain = Some(c);
                }
                Err(e) => tracing::warn!("arm operator: unusable specifications: {e}"),
            },
            Message::ReportJointPositions(r) => self.joints = Some(r.joint_position.clone()),
            Message::ReportJointVelocities(r) => self.rates = Some(r.joint_velocity.clone()),
            Message::RejectComponentControl(_) => {
                tracing::warn!(source = ?ctx.source(), "arm operator: control rejected");
            }
            _ => {}
        }
        Ok(None)
    }

    fn state_changed(&mut self, _ctx: &mut Ctx<'_>, _from: CoreState, _to: CoreState) {}
}

/// The operator component.
pub type ArmOcu = jaus::component::Component<system_commander::Dispatch<ArmOperator>>;

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
            ),
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
    loop {
        let elapsed = bus.now() - t0;
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
    // Each move's error is measured at the instant it settled, on the true arm: replay
    // the traced tool pose nearest to that instant.
    for (phase, start, end, target) in &op.done {
        let t_end = (*end - t0).as_secs_f64();
        let (_, q) = report
            .joints
            .iter()
            .min_by(|a, b| (a.0 - t_end).abs().total_cmp(&(b.0 - t_end).abs()))
            .cloned()
            .unwrap_or_default();
        let chain = arm.lock().chain().clone();
        let mut c = chain;
        c.tool = Vector3::from(TOOL);
        let actual = c.tool_pose(&q);
        report.moves.push(Move {
            name: phase.name(),
            driver: phase.driver(),
            seconds: (*end - *start).as_secs_f64(),
            position_error_mm: (actual.translation.vector - target.translation.vector).norm()
                * 1000.0,
            angle_error_deg: actual.rotation.angle_to(&target.rotation).to_degrees(),
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
