//! The Primitive Driver over an RA 3.3 Primitive Driver: Set Wrench Effort passes
//! through (the same twelve efforts in percent), Query Wrench Effort answers from the
//! RA 3.3 driver's latest report.

use jaus::codec::Encode;
use jaus::messages as ra;
use jaus::{Address, CommandCode, JausMessage};

use super::{efforts, is, ServiceIds};
use crate::messages::{QueryWrenchEffort, ReportWrenchEffort, SetWrenchEffort};
use crate::ra33::Ra33Side;
use crate::service::{Cx, Handled, Request, Service, ServiceId};
use crate::Message;

/// The Primitive Driver over the RA 3.3 one at an address.
#[derive(Debug)]
pub struct PrimitiveDriver {
    driver: Address,
}

impl PrimitiveDriver {
    /// The service over the RA 3.3 Primitive Driver at `driver`; `side` keeps its
    /// report fresh.
    pub fn new(side: &mut Ra33Side, now: std::time::Instant, driver: Address) -> Self {
        side.keep_polling(
            now,
            driver,
            ra::QueryWrenchEffort {
                presence_vector: 0x0FFF,
            },
        );
        Self { driver }
    }
}

impl Service<Ra33Side> for PrimitiveDriver {
    fn id(&self) -> ServiceId {
        ServiceIds::PRIMITIVE_DRIVER
    }

    fn receives(&self, code: CommandCode) -> bool {
        is(code, &[SetWrenchEffort::CODE, QueryWrenchEffort::CODE])
    }

    fn handle(&mut self, cx: &mut Cx<'_, Ra33Side>, request: &Request<'_>) -> Handled {
        match request.message {
            Message::SetWrenchEffort(s) => {
                // Efforts from the AS-4 client: the gateway takes the RA 3.3 driver
                // (a waypoint list executed later gives it back to the drivers).
                cx.env.activate(self.driver);
                cx.env.send(self.driver, efforts!(s => RaSetWrenchEffort));
                Handled::Done
            }
            Message::QueryWrenchEffort(q) => {
                let mut report = match cx.env.latest(self.driver, ra::ReportWrenchEffort::CODE) {
                    Some((_, ra::Message::ReportWrenchEffort(r))) => {
                        efforts!(r => ReportWrenchEffort)
                    }
                    _ => ReportWrenchEffort::default(),
                };
                report.keep_present(u64::from(q.presence_vector));
                Handled::Reply(report.into())
            }
            _ => Handled::NotMine,
        }
    }

    fn state_changed(
        &mut self,
        cx: &mut Cx<'_, Ra33Side>,
        from: crate::ComponentState,
        to: crate::ComponentState,
    ) {
        // Leaving Ready stops the efforts at once, when the gateway drives the RA 3.3
        // Primitive Driver itself (its standby follows from the gateway's control).
        if from == crate::ComponentState::Ready
            && to != crate::ComponentState::Ready
            && cx.env.control_of(self.driver) == crate::ra33::Ra33Control::Granted
        {
            cx.env.send(
                self.driver,
                RaSetWrenchEffort {
                    propulsive_linear_effort_x: Some(0.0),
                    propulsive_rotational_effort_z: Some(0.0),
                    ..Default::default()
                },
            );
        }
    }
}

use ra::SetWrenchEffort as RaSetWrenchEffort;
