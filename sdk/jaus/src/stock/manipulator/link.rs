//! What every closed-loop manipulator driver shares (Part 1 §5.4.6–§5.4.11): the arm's
//! kinematics from Report Manipulator Specifications, joint feedback by service
//! connection from the joint sensors, control of the Primitive Manipulator, the joint
//! servo that turns a joint reference into Set Joint Efforts, and the watchdog on stale
//! feedback.

use std::time::{Duration, Instant};

use super::kinematics::Chain;
use super::servo::{JointServo, ServoGains};
use crate::component::{Context, EmittedBy, Interface, Refused};
use crate::messages::{
    QueryJointEfforts, QueryManipulatorSpecifications, ReportJointEfforts, ReportJointPositions,
    ReportJointVelocities, ReportManipulatorSpecifications, SetJointEfforts,
};
use crate::stock::output::OutputControl;
use crate::{Address, JausMessage};

/// Settings shared by the manipulator drivers.
#[derive(Debug, Clone)]
pub struct ArmDriverConfig {
    /// The Primitive Manipulator the efforts go to (and the specifications come from).
    pub output: Address,
    /// The Joint Position Sensor.
    pub position_sensor: Address,
    /// The Joint Velocity Sensor (used by the drivers whose interface takes Report Joint
    /// Velocities; the others differentiate the positions).
    pub velocity_sensor: Option<Address>,
    /// Rate of the joint feedback service connections, Hz.
    pub feedback_rate_hz: f64,
    /// Feedback older than this sets every effort to zero (watchdog).
    pub feedback_timeout: Duration,
    /// A velocity command (joint or end-effector) older than this is replaced by
    /// holding still.
    pub command_timeout: Duration,
    /// The joint servo's gains.
    pub gains: ServoGains,
    /// Fraction of each joint's maximum rate the position drivers (joint positions,
    /// end-effector pose) move at.
    pub speed_fraction: f64,
    /// Time a joint takes to reach its maximum rate at the largest acceleration the
    /// drivers ask of it: each joint's acceleration limit is its maximum rate (Report
    /// Manipulator Specifications) over this time. Report Manipulator Specifications
    /// carries no acceleration, so this is the drivers' setting.
    pub acceleration_time: Duration,
    /// Time over which the position and velocity drivers' acceleration builds up and
    /// dies away (their jerk limit): a move to a joint target or pose is smoothed over it
    /// ([`SynchronisedMove`](super::profile::SynchronisedMove)), and so are the changes
    /// of a commanded velocity. Zero: acceleration in steps.
    pub jerk_time: Duration,
    /// How long a driver that took the Primitive Manipulator waits for the efforts it
    /// applies (Query Joint Efforts) before it starts its servo from zero: the servo
    /// starts from them, so the hand-over does not change the effort.
    pub takeover_timeout: Duration,
}

/// The defaults: output 1.1.49.1, sensors 1.1.51.1 and 1.1.52.1, feedback at 100 Hz with a
/// 100 ms watchdog, velocity commands stale after 500 ms, [`ServoGains::default`], moves
/// at 50 % of the joints' rates, a joint's full rate reached in 0.5 s at the most,
/// accelerations smoothed over 300 ms, up to 200 ms to learn the efforts applied when
/// taking the arm.
///
/// ```
/// use std::time::Duration;
/// let c = jaus::stock::manipulator::link::ArmDriverConfig::default();
/// assert_eq!(c.output, jaus::Address::new(1, 1, 49, 1));
/// assert_eq!((c.feedback_rate_hz, c.feedback_timeout), (100.0, Duration::from_millis(100)));
/// assert_eq!((c.command_timeout, c.speed_fraction), (Duration::from_millis(500), 0.5));
/// assert_eq!(c.acceleration_time, Duration::from_millis(500));
/// assert_eq!(c.jerk_time, Duration::from_millis(300));
/// assert_eq!(c.takeover_timeout, Duration::from_millis(200));
/// ```
impl Default for ArmDriverConfig {
    fn default() -> Self {
        Self {
            output: Address::new(1, 1, 49, 1),
            position_sensor: Address::new(1, 1, 51, 1),
            velocity_sensor: Some(Address::new(1, 1, 52, 1)),
            feedback_rate_hz: 100.0,
            feedback_timeout: Duration::from_millis(100),
            command_timeout: Duration::from_millis(500),
            gains: ServoGains::default(),
            speed_fraction: 0.5,
            acceleration_time: Duration::from_millis(500),
            jerk_time: Duration::from_millis(300),
            takeover_timeout: Duration::from_millis(200),
        }
    }
}

/// Counters of a manipulator driver.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ArmCounters {
    /// Times the watchdog zeroed the efforts for stale joint feedback.
    pub watchdog_trips: u64,
    /// Joint reports ignored (wrong joint count, not finite).
    pub bad_feedback: u64,
    /// Report Manipulator Specifications that did not describe a usable arm.
    pub bad_specifications: u64,
}

/// Kinematics, feedback, output and servo of one manipulator driver.
#[derive(Debug)]
pub struct ArmLink {
    /// Settings.
    pub config: ArmDriverConfig,
    output: OutputControl,
    chain: Option<Chain>,
    tool: Option<nalgebra::Vector3<f64>>,
    last_spec_query: Option<Instant>,
    positions: Option<(Instant, Vec<f64>)>,
    velocities: Option<(Instant, Vec<f64>)>,
    measured_positions: bool,
    measured_velocities: bool,
    servo: JointServo,
    last_servo: Option<Instant>,
    efforts: Vec<f64>,
    sending: bool,
    takeover: Takeover,
    counters: ArmCounters,
}

/// Where a driver is in taking the arm over from whoever held it.
#[derive(Debug, Clone, PartialEq)]
enum Takeover {
    /// The efforts applied now are not known yet.
    Needed,
    /// Query Joint Efforts sent first at this instant (last at the second).
    Asked(Instant, Instant),
    /// The servo starts from them (or from zero after the timeout).
    Done,
}

impl ArmLink {
    /// With `config`.
    pub fn new(config: ArmDriverConfig) -> Self {
        Self {
            output: OutputControl::new(config.output),
            config,
            chain: None,
            tool: None,
            last_spec_query: None,
            positions: None,
            velocities: None,
            measured_positions: true,
            measured_velocities: false,
            servo: JointServo::default(),
            last_servo: None,
            efforts: Vec::new(),
            sending: false,
            takeover: Takeover::Needed,
            counters: ArmCounters::default(),
        }
    }

    /// Subscribes to joint positions when `positions` and to joint velocities when
    /// `velocities` (what the driver's interface takes). A driver without positions
    /// integrates the velocities (its references are then relative to where the arm was
    /// when the feedback started); one without velocities differentiates the positions.
    pub fn subscribe<I: Interface>(
        &mut self,
        ctx: &mut Context<'_, I>,
        positions: bool,
        velocities: bool,
    ) {
        let rate = self.config.feedback_rate_hz;
        let mut requests = Vec::new();
        if positions {
            requests.push((self.config.position_sensor, ReportJointPositions::CODE));
        }
        self.measured_positions = positions;
        self.measured_velocities = false;
        if velocities {
            if let Some(v) = self.config.velocity_sensor {
                requests.push((v, ReportJointVelocities::CODE));
                self.measured_velocities = true;
            }
        }
        for (provider, report) in requests {
            if let Err(e) = ctx.create_service_connection(provider, report, rate, 0) {
                // The watchdog keeps the arm without effort while no feedback arrives.
                tracing::warn!(address = %ctx.address(), %provider, "joint feedback {report} not requested: {e}");
            }
        }
    }

    /// The arm, once its specifications arrived (with the tool point set last).
    pub fn chain(&self) -> Option<&Chain> {
        self.chain.as_ref()
    }

    /// The arm for a command: a refusal naming the Primitive Manipulator when its
    /// specifications have not arrived yet.
    pub fn arm(&self) -> Result<&Chain, Refused> {
        self.chain.as_ref().ok_or_else(|| {
            Refused::Invalid(format!(
                "the arm's specifications have not arrived from {} yet",
                self.config.output
            ))
        })
    }

    /// The joint positions a move or path starts from: a refusal naming the position
    /// sensor when there are none fresh.
    pub fn start_positions(&self, now: Instant) -> Result<Vec<f64>, Refused> {
        self.feedback(now).map(|(q, _)| q.to_vec()).ok_or_else(|| {
            Refused::Invalid(format!(
                "no current joint positions from {} to start from",
                self.config.position_sensor
            ))
        })
    }

    /// Counters.
    pub fn counters(&self) -> ArmCounters {
        self.counters
    }

    /// The efforts sent last (empty before the first).
    pub fn last_efforts(&self) -> &[f64] {
        &self.efforts
    }

    /// Sets the tool point (end-effector frame, m), kept across new specifications.
    pub fn set_tool(&mut self, tool: nalgebra::Vector3<f64>) {
        self.tool = Some(tool);
        if let Some(c) = &mut self.chain {
            c.tool = tool;
        }
    }

    /// The tool point (end-effector frame, m).
    pub fn tool(&self) -> nalgebra::Vector3<f64> {
        self.tool
            .or_else(|| self.chain.as_ref().map(|c| c.tool))
            .unwrap_or_else(nalgebra::Vector3::zeros)
    }

    /// Takes Report Manipulator Specifications (from the output component).
    pub fn on_specifications<I: Interface>(
        &mut self,
        ctx: &Context<'_, I>,
        r: &ReportManipulatorSpecifications,
    ) {
        match Chain::from_specifications(r) {
            Ok(mut chain) => {
                if let Some(t) = self.tool {
                    chain.tool = t;
                }
                if self.chain.as_ref().map(Chain::dof) != Some(chain.dof()) {
                    self.servo.reset();
                    self.takeover = Takeover::Needed;
                    self.positions = None;
                    self.velocities = None;
                }
                self.chain = Some(chain);
            }
            Err(e) => {
                self.counters.bad_specifications += 1;
                tracing::warn!(
                    address = %ctx.address(),
                    source = ?ctx.source(),
                    "Report Manipulator Specifications (0x4600) does not describe a usable arm: {e}"
                );
            }
        }
    }

    fn joint_list_ok(&mut self, values: &[f64]) -> bool {
        let dof_ok = self.chain.as_ref().is_none_or(|c| c.dof() == values.len());
        let ok = dof_ok && !values.is_empty() && values.iter().all(|v| v.is_finite());
        if !ok {
            self.counters.bad_feedback += 1;
        }
        ok
    }

    /// Takes Report Joint Positions (from the position sensor).
    pub fn on_positions(&mut self, now: Instant, r: &ReportJointPositions) {
        if !self.joint_list_ok(&r.joint_position) {
            return;
        }
        if !self.measured_velocities {
            // Differentiate: the drivers without a velocity sensor in their interface.
            match &self.positions {
                Some((t, q)) if q.len() == r.joint_position.len() => {
                    if now > *t {
                        let dt = now.duration_since(*t).as_secs_f64();
                        let previous = self.velocities.as_ref().map(|v| &v.1);
                        let estimate = r
                            .joint_position
                            .iter()
                            .zip(q)
                            .enumerate()
                            .map(|(j, (a, b))| {
                                let raw = (a - b) / dt;
                                // A light low-pass against quantisation and noise.
                                match previous {
                                    Some(p) if p.len() == q.len() => 0.5 * raw + 0.5 * p[j],
                                    _ => raw,
                                }
                            })
                            .collect();
                        self.velocities = Some((now, estimate));
                    } else if let Some(v) = &mut self.velocities {
                        // Two reports at one instant: keep the estimate, refresh its age.
                        v.0 = now;
                    }
                }
                _ => self.velocities = Some((now, vec![0.0; r.joint_position.len()])),
            }
        }
        self.positions = Some((now, r.joint_position.clone()));
    }

    /// Takes Report Joint Efforts from the Primitive Manipulator (`source`): while taking
    /// the arm over, the servo starts from them.
    pub fn on_efforts(&mut self, source: Option<Address>, r: &ReportJointEfforts) {
        let dof = self.chain.as_ref().map(Chain::dof);
        if source != Some(self.config.output) || !matches!(self.takeover, Takeover::Asked(..)) {
            return;
        }
        if dof != Some(r.joint_effort.len()) || !r.joint_effort.iter().all(|e| e.is_finite()) {
            self.counters.bad_feedback += 1;
            return;
        }
        self.servo.preload(&self.config.gains, &r.joint_effort);
        self.takeover = Takeover::Done;
    }

    /// Takes Report Joint Velocities (from the velocity sensor).
    pub fn on_velocities(&mut self, now: Instant, r: &ReportJointVelocities) {
        if !self.joint_list_ok(&r.joint_velocity) {
            return;
        }
        if !self.measured_positions {
            // Integrate: the driver without a position sensor in its interface.
            let n = r.joint_velocity.len();
            let q = match (&self.positions, &self.velocities) {
                (Some((t, q)), Some((_, v))) if q.len() == n && v.len() == n && now > *t => {
                    let dt = now.duration_since(*t).as_secs_f64();
                    q.iter()
                        .zip(v.iter().zip(&r.joint_velocity))
                        .map(|(q, (a, b))| q + 0.5 * (a + b) * dt)
                        .collect()
                }
                _ => vec![0.0; n],
            };
            self.positions = Some((now, q));
        }
        self.velocities = Some((now, r.joint_velocity.clone()));
    }

    /// Joint positions and velocities, unless stale or of another joint count than the
    /// arm's.
    pub fn feedback(&self, now: Instant) -> Option<(&[f64], &[f64])> {
        let fresh = |t: &Instant| now.saturating_duration_since(*t) <= self.config.feedback_timeout;
        let dof = self.chain.as_ref()?.dof();
        match (&self.positions, &self.velocities) {
            (Some((tp, q)), Some((tv, v)))
                if fresh(tp) && fresh(tv) && q.len() == dof && v.len() == dof =>
            {
                Some((q, v))
            }
            _ => None,
        }
    }

    /// The latest joint positions even if stale (to plan from, not to drive).
    pub fn last_positions(&self) -> Option<&[f64]> {
        self.positions.as_ref().map(|p| p.1.as_slice())
    }

    /// Keeps control of the Primitive Manipulator and asks for its specifications until
    /// they arrive. Call every tick while Ready.
    pub fn hold_output<I: Interface>(&mut self, ctx: &mut Context<'_, I>)
    where
        QueryManipulatorSpecifications: EmittedBy<I>,
    {
        self.request_specifications(ctx);
        self.output.hold(ctx);
    }

    /// Asks the Primitive Manipulator for its specifications (once a second until they
    /// arrive).
    pub fn request_specifications<I: Interface>(&mut self, ctx: &mut Context<'_, I>)
    where
        QueryManipulatorSpecifications: EmittedBy<I>,
    {
        let now = ctx.now();
        if self.chain.is_none()
            && self
                .last_spec_query
                .is_none_or(|t| now.saturating_duration_since(t) >= Duration::from_secs(1))
        {
            self.last_spec_query = Some(now);
            ctx.send(self.config.output, QueryManipulatorSpecifications {});
        }
    }

    /// Gives control of the Primitive Manipulator back (after [`stop`](Self::stop)).
    pub fn release_output<I: Interface>(&mut self, ctx: &mut Context<'_, I>) {
        self.output.release(ctx);
    }

    /// Whether the driver may command the arm now: it controls the Primitive
    /// Manipulator, knows the arm, has fresh feedback and knows the efforts the
    /// Primitive Manipulator applies (asked for once control is granted, up to
    /// [`ArmDriverConfig::takeover_timeout`]; meanwhile whoever held the arm keeps it).
    /// Without fresh feedback the efforts go to zero (the watchdog, counted once per
    /// loss).
    pub fn ready_to_drive<I: Interface>(&mut self, ctx: &mut Context<'_, I>) -> bool
    where
        SetJointEfforts: EmittedBy<I>,
        QueryJointEfforts: EmittedBy<I>,
    {
        if !self.output.granted(ctx) || self.chain.is_none() {
            self.takeover = Takeover::Needed;
            return false;
        }
        if self.feedback(ctx.now()).is_none() {
            if self.sending {
                self.counters.watchdog_trips += 1;
                tracing::warn!(
                    component = I::NAME,
                    address = %ctx.address(),
                    "watchdog: no joint feedback from {} for {:?}; efforts to zero",
                    self.config.position_sensor,
                    self.config.feedback_timeout
                );
            }
            self.stop(ctx);
            return false;
        }
        let now = ctx.now();
        let (first, ask) = match self.takeover {
            Takeover::Done => return true,
            Takeover::Needed => (now, true),
            Takeover::Asked(first, last) => (
                first,
                now.saturating_duration_since(last) >= Duration::from_millis(50),
            ),
        };
        if now.saturating_duration_since(first) >= self.config.takeover_timeout {
            tracing::info!(
                component = I::NAME,
                address = %ctx.address(),
                "no Report Joint Efforts from {}; the servo starts from zero",
                self.config.output
            );
            self.takeover = Takeover::Done;
            return true;
        }
        if ask {
            ctx.send(self.config.output, QueryJointEfforts {});
            self.takeover = Takeover::Asked(first, now);
        }
        false
    }

    /// Servoes the joints toward `q_ref`, `qd_ref` (call once per control period, after
    /// [`ready_to_drive`](Self::ready_to_drive) said yes).
    pub fn servo_to<I: Interface>(
        &mut self,
        ctx: &mut Context<'_, I>,
        q_ref: &[f64],
        qd_ref: &[f64],
    ) where
        SetJointEfforts: EmittedBy<I>,
    {
        let now = ctx.now();
        let dt = self
            .last_servo
            .map_or(0.01, |t| now.saturating_duration_since(t).as_secs_f64())
            .clamp(0.001, 0.1);
        self.last_servo = Some(now);
        let Some((q, qd)) = self.feedback(now) else {
            return;
        };
        let (q, qd) = (q.to_vec(), qd.to_vec());
        let mut out = std::mem::take(&mut self.efforts);
        self.servo
            .efforts(&self.config.gains, dt, &q, &qd, q_ref, qd_ref, &mut out);
        self.efforts = out;
        self.sending = true;
        ctx.send(
            self.config.output,
            SetJointEfforts {
                joint_effort: self.efforts.clone(),
            },
        );
    }

    /// Stops commanding without a word: the Primitive Manipulator's holding controller
    /// (or its watchdog) takes the arm. For hand-overs (Standby, control lost); then
    /// [`release_output`](Self::release_output).
    pub fn let_go(&mut self) {
        self.servo.reset();
        self.last_servo = None;
        self.sending = false;
        self.takeover = Takeover::Needed;
    }

    /// Sets every effort to zero: sends Set Joint Efforts of zeros once (the Primitive
    /// Manipulator keeps zero effort until an effort is commanded again).
    pub fn stop<I: Interface>(&mut self, ctx: &mut Context<'_, I>)
    where
        SetJointEfforts: EmittedBy<I>,
    {
        self.servo.reset();
        self.last_servo = None;
        self.takeover = Takeover::Needed;
        if self.sending {
            self.sending = false;
            let n = self.chain.as_ref().map_or(self.efforts.len(), Chain::dof);
            self.efforts = vec![0.0; n];
            ctx.send(
                self.config.output,
                SetJointEfforts {
                    joint_effort: self.efforts.clone(),
                },
            );
        }
    }
}
