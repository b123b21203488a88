//! The Tool Offset Service over the RA 3.3 End-Effector Pose Driver's tool point: Set
//! Tool Offset from the controlling client → RA 3.3 Set Tool Point (the same point, in
//! the frame of the last link), Query Tool Offset → the driver's Report Tool Point.
//!
//! The tool point is the one the End-Effector Pose Sensor and Driver place and report
//! ([`Arm::chain`](super::Arm::chain) reads it from the same driver), so a new offset
//! moves what they report. Set Tool Point is a command: it leaves once the gateway
//! holds RA 3.3 control of the driver (asked for when the AS-4 client takes control;
//! the latest offset waits until then), without resuming the driver or stopping
//! another (a tool point moves nothing). The driver is asked for its tool point right
//! after, and until its report shows the offset ([`SETTLED`] at most) the offset sent
//! is what Query Tool Offset answers.

use std::time::{Duration, Instant};

use jaus::messages as ra;
use jaus::{Address, JausMessage};

use super::ServiceIds;
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::manipulator_tool_offset_service as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::{ReportToolOffset, SetToolOffset};
use crate::ra33::{Ra33Control, Ra33Side};
use crate::service::Cx;

/// How long after an offset is sent the driver's report is taken as it is, even when it
/// does not show the offset (the driver refused it, or another client set another).
pub const SETTLED: Duration = Duration::from_secs(1);

machined!(
    ToolPoint,
    manipulator_tool_offset_service,
    ServiceIds::TOOL_OFFSET,
    access_control {
        fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
            let now = cx.now;
            self.flush(cx.env, now);
        }
    }
);

/// The Tool Offset Service over an RA 3.3 End-Effector Pose Driver.
pub type ToolOffsetService = OnMachines<ToolPoint>;

/// The Tool Offset Service's data: the RA 3.3 driver, the offset waiting for control
/// of it, and the offset sent last with when.
#[derive(Debug)]
pub struct ToolPoint {
    driver: Address,
    pending: Option<[f64; 3]>,
    sent: Option<(Instant, [f64; 3])>,
}

impl ToolOffsetService {
    /// The service over the RA 3.3 End-Effector Pose Driver at `driver` (the
    /// Manipulator services poll its tool point: [`Arm::tool_from`](super::Arm::tool_from)).
    pub fn new(driver: Address) -> Self {
        OnMachines::from_impl(ToolPoint {
            driver,
            pending: None,
            sent: None,
        })
    }
}

impl ToolPoint {
    /// Sends the waiting offset once RA 3.3 control of the driver is held, then asks the
    /// driver for its tool point.
    fn flush(&mut self, env: &mut Ra33Side, now: Instant) {
        if env.control_of(self.driver) != Ra33Control::Granted {
            return;
        }
        if let Some([x, y, z]) = self.pending.take() {
            env.send(self.driver, ra::SetToolPoint { x, y, z });
            env.send(self.driver, ra::QueryToolPoint {});
            self.sent = Some((now, [x, y, z]));
        }
    }
}

impl generated::ManipulatorToolOffsetService for On<'_, ToolPoint> {
    fn send_report_tool_offset(&mut self, transport: &Receive) {
        let reported = match self.env.latest(self.svc.driver, ra::ReportToolPoint::CODE) {
            Some((at, ra::Message::ReportToolPoint(t))) => Some((at, [t.x, t.y, t.z])),
            _ => None,
        };
        // The driver's report once it shows the offset sent (or, a report later than
        // SETTLED after it, whatever the driver holds); the offset sent until then.
        let point = match (reported, self.svc.sent) {
            (Some((at, p)), Some((sent_at, s)))
                if at >= sent_at
                    && (at.saturating_duration_since(sent_at) > SETTLED
                        || p.iter().zip(&s).all(|(a, b)| (a - b).abs() < 1e-6)) =>
            {
                Some(p)
            }
            (_, Some((_, s))) => Some(s),
            (Some((_, p)), None) => Some(p),
            (None, None) => None,
        };
        match point {
            Some([x, y, z]) => self.reply(
                transport,
                ReportToolOffset {
                    tool_point_x: x,
                    tool_point_y: y,
                    tool_point_z: z,
                },
            ),
            None => self.refuse(format!(
                "no tool point from the RA 3.3 end-effector pose driver {} yet",
                self.svc.driver
            )),
        }
    }

    fn set_tool_offset(&mut self, msg: &SetToolOffset) {
        let p = [msg.tool_point_x, msg.tool_point_y, msg.tool_point_z];
        if !p.iter().all(|v| v.is_finite()) {
            return self.refuse("tool offset is not finite");
        }
        self.svc.pending = Some(p);
        self.env.ensure_control(self.svc.driver);
        let now = self.now;
        self.svc.flush(self.env, now);
    }
}
