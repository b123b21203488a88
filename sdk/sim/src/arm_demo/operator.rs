//! The scripted arm operator (a System Commander): learns the arm, follows its joints,
//! and for each move takes control of the driver, resumes it, commands it, waits until
//! the tool point has settled on the target, then puts the driver in Standby and
//! releases it so the next driver can take the Primitive Manipulator.

use std::time::{Duration, Instant};

use nalgebra::{Isometry3, Translation3, Vector3};

use super::{addr, pick, pick_above, JOG, PLACE_JOINTS, PLACE_TIMES, SQUARE, SQUARE_STEP, TOOL};
use jaus::component::{CoreState, Refused};
use jaus::components::system_commander::{self, Ctx, SystemCommander};
use jaus::messages::*;
use jaus::stock::manipulator::kinematics::Chain;
use jaus::{Address, JausMessage};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(super) enum Step {
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
pub(super) enum Phase {
    Above,
    Pick,
    Lift,
    JointMove,
    Jog,
    Square,
}

impl Phase {
    pub(super) fn driver(self) -> Address {
        match self {
            Phase::Above | Phase::Pick | Phase::Lift => addr::EPD,
            Phase::JointMove => addr::JMD,
            Phase::Jog => addr::EVD,
            Phase::Square => addr::DPD,
        }
    }

    pub(super) fn name(self) -> &'static str {
        match self {
            Phase::Above => "pose: above the pick point",
            Phase::Pick => "pose: down to the pick point",
            Phase::Lift => "pose: lift",
            Phase::JointMove => "joint move: to the place configuration",
            Phase::Jog => "velocity state: sideways jog",
            Phase::Square => "discrete poses: a timed square",
        }
    }

    /// When the move's last leg starts, s after the command (its joints then travel one
    /// way to where the move leaves them).
    pub(super) fn last_leg(self) -> f64 {
        match self {
            Phase::JointMove => PLACE_TIMES[0],
            Phase::Jog => JOG.1.as_secs_f64(),
            Phase::Square => 3.0 + SQUARE_STEP * (SQUARE.len() - 1) as f64,
            _ => 0.0,
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

/// Tool point within this of the target (position and orientation) and joints this
/// still count as settled.
const SETTLED_MM: f64 = 0.5;
const SETTLED_DEG: f64 = 0.08;
const STILL_RAD_S: f64 = 0.002;

/// The scripted arm operator.
#[derive(Debug, Default)]
pub struct ArmOperator {
    pub(super) step: Step,
    chain: Option<Chain>,
    joints: Option<Vec<f64>>,
    rates: Option<Vec<f64>>,
    target: Option<Isometry3<f64>>,
    commanded_at: Option<Instant>,
    last_request: Option<Instant>,
    next_jog: Option<Instant>,
    resumed_at: Option<Instant>,
    pub(super) jog_started: Option<Instant>,
    jog_until: Option<Instant>,
    /// Moves done: (phase, commanded at, settled at, target).
    pub(super) done: Vec<(Phase, Instant, Instant, Isometry3<f64>)>,
    pub(super) targets: Vec<Vector3<f64>>,
}

impl ArmOperator {
    fn tool_pose(&self) -> Option<Isometry3<f64>> {
        Some(self.chain.as_ref()?.tool_pose(self.joints.as_ref()?))
    }

    /// Whether the joints are still and, except after the jog (whose end point is only
    /// as exact as the integration of the commanded velocity), the tool point is on the
    /// target, in position and orientation.
    fn settled(&self, phase: Phase) -> bool {
        let (Some(target), Some(p)) = (self.target, self.tool_pose()) else {
            return false;
        };
        let still = self
            .rates
            .as_ref()
            .is_some_and(|r| r.iter().all(|v| v.abs() < STILL_RAD_S));
        let err = (p.translation.vector - target.translation.vector).norm() * 1000.0;
        let turn = p.rotation.angle_to(&target.rotation).to_degrees();
        still && (phase == Phase::Jog || (err < SETTLED_MM && turn < SETTLED_DEG))
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
                // Between drivers the Primitive Manipulator holds the arm; the new driver
                // takes it over from there: command once it holds the arm still.
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
