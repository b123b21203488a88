//! The Primitive Driver over an RA 3.3 Primitive Driver: Set Wrench Effort passes
//! through (the same twelve efforts in percent), Query Wrench Effort answers from the
//! RA 3.3 driver's latest report; the machines (`defs/mobility_services.yaml`) take Set
//! Wrench Effort from the controlling client while the component is Ready.
//!
//! `command_efforts` and `stop_efforts` are the one path of efforts from AS-4 to the
//! RA 3.3 driver: the UGV Skid Steer Driver ([`crate::ugv::skid_steer`]) sends its
//! efforts through them too, so both services command the same RA 3.3 driver the same
//! way and the latest command of either wins.

use jaus::codec::Encode;
use jaus::messages as ra;
use jaus::{Address, JausMessage};

use super::ServiceIds;
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::primitive_driver as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::{QueryWrenchEffort, ReportWrenchEffort, SetWrenchEffort};
use crate::ra33::efforts;
use crate::ra33::Ra33Side;
use crate::service::Cx;

/// The Primitive Driver over the RA 3.3 one at an address, on its generated machines.
pub type PrimitiveDriver = OnMachines<Primitive>;

/// The Primitive Driver's data: the RA 3.3 Primitive Driver it drives.
#[derive(Debug)]
pub struct Primitive {
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
        OnMachines::from_impl(Primitive { driver })
    }
}

impl generated::PrimitiveDriver for On<'_, Primitive> {
    fn send_report_wrench_effort(&mut self, msg: &QueryWrenchEffort, transport: &Receive) {
        let mut report = match self
            .env
            .latest(self.svc.driver, ra::ReportWrenchEffort::CODE)
        {
            Some((_, ra::Message::ReportWrenchEffort(r))) => efforts!(r => ReportWrenchEffort),
            _ => ReportWrenchEffort::default(),
        };
        report.keep_present(u64::from(msg.presence_vector));
        self.reply(transport, report);
    }

    fn set_wrench_effort(&mut self, msg: &SetWrenchEffort) {
        command_efforts(
            self.env,
            self.svc.driver,
            efforts!(msg => RaSetWrenchEffort),
        );
    }
}

/// Sends `efforts` from the AS-4 client to the RA 3.3 Primitive Driver at `driver`: the
/// gateway takes the driver ([`Ra33Side::activate`]: RA 3.3 control asked for if not
/// held, the driver resumed while the component is Ready, the group's other drivers put
/// in standby; a waypoint list executed later gives it back to the drivers). Streamed
/// ([`crate::ra33::STREAMED`]): the next command replaces a lost one.
pub(crate) fn command_efforts(env: &mut Ra33Side, driver: Address, efforts: RaSetWrenchEffort) {
    env.activate(driver);
    env.send(driver, efforts);
}

/// Stops the efforts of the RA 3.3 Primitive Driver at `driver` at once (linear x and
/// rotational z at 0), when the gateway drives it itself (holds RA 3.3 control; its
/// standby follows from the gateway's control).
pub(crate) fn stop_efforts(env: &mut Ra33Side, driver: Address) {
    if env.control_of(driver) == crate::ra33::Ra33Control::Granted {
        env.send(
            driver,
            RaSetWrenchEffort {
                propulsive_linear_effort_x: Some(0.0),
                propulsive_rotational_effort_z: Some(0.0),
                ..Default::default()
            },
        );
    }
}

machined!(
    Primitive,
    primitive_driver,
    ServiceIds::PRIMITIVE_DRIVER,
    management {
    fn state_changed(
        &mut self,
        cx: &mut Cx<'_, Ra33Side>,
        from: crate::ComponentState,
        to: crate::ComponentState,
    ) {
        // Leaving Ready stops the efforts at once, when the gateway drives the RA 3.3
        // Primitive Driver itself.
        if from == crate::ComponentState::Ready && to != crate::ComponentState::Ready {
            stop_efforts(cx.env, self.driver);
        }
    }
    }
);

use ra::SetWrenchEffort as RaSetWrenchEffort;
