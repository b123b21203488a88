//! The Annunciator over the horn bit of an RA 3.3 Primitive Driver's discrete devices
//! (Set/Query/Report Discrete Devices): the only annunciator RA 3.3 has.
//!
//! What AS-4 asks and RA 3.3 cannot do:
//!
//! * **One annunciator.** Report Annunciator Configuration names the horn alone. Set
//!   Annunciator State that sounds the siren, the reversing alarm or either variable
//!   annunciator (a level above 0) is refused by the machine's `isSupported` guard,
//!   and nothing changes (the horn neither); their levels read 0.
//! * **On or off.** RA 3.3's horn has no volume: any horn level above 0 sounds it, 0
//!   silences it; the horn reads 15 (the loudest, its only level) while the driver
//!   reports the bit set, 0 otherwise.
//! * The reserved bits are not read (they sound nothing).
//!
//! Only the controlling client sets the annunciators, in any of the component's
//! controlled states (the machines, `defs/ugv_services.yaml`); queries are answered
//! to any client from the driver's Report Discrete Devices (polled). The horn bit goes
//! with the parking brake bit in one RA 3.3 message ([`crate::ra33::discrete`]): the
//! parking brake is kept as commanded or reported, and the Parking Brake Driver keeps
//! the horn the same way. RA 3.3 control of the driver is asked for with the command,
//! which waits (the latest one) until it is granted.

use jaus::Address;

use super::ServiceIds;
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::annunciator_service as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::{
    AnnunciatorState, QueryAnnunciatorConfiguration, QueryAnnunciatorState,
    ReportAnnunciatorConfiguration, ReportAnnunciatorState, SetAnnunciatorState,
    SupportedAnnunciators,
};
use crate::ra33::{DiscreteChange, Ra33Side};
use crate::service::Cx;

/// The horn level read while the RA 3.3 horn bit is set (4 bits: the loudest).
pub const HORN_ON: u8 = 15;

/// The Annunciator over the RA 3.3 Primitive Driver at an address, on its generated
/// machines.
pub type AnnunciatorService = OnMachines<Annunciator>;

/// The Annunciator's data: the RA 3.3 Primitive Driver whose horn it sounds.
#[derive(Debug)]
pub struct Annunciator {
    driver: Address,
}

impl AnnunciatorService {
    /// The service over the RA 3.3 Primitive Driver at `driver` (whose discrete devices
    /// the gateway polls, [`super::services`]).
    pub fn new(driver: Address) -> Self {
        OnMachines::from_impl(Annunciator { driver })
    }
}

machined!(
    Annunciator,
    annunciator_service,
    ServiceIds::ANNUNCIATOR,
    access_control {
        fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
            cx.env.flush_discrete_devices(cx.now);
        }
    }
);

/// Whether `a` sounds only annunciators RA 3.3 has (the horn).
fn only_horn(a: &AnnunciatorState) -> bool {
    a.siren == 0 && a.backup == 0 && a.variable1 == 0 && a.variable2 == 0
}

impl generated::AnnunciatorService for On<'_, Annunciator> {
    fn is_supported(&self, msg: &SetAnnunciatorState) -> bool {
        only_horn(&msg.annunciator)
    }

    fn send_report_annunciator_configuration(
        &mut self,
        _msg: &QueryAnnunciatorConfiguration,
        transport: &Receive,
    ) {
        let supported = SupportedAnnunciators {
            horn: true,
            ..Default::default()
        };
        self.reply(transport, ReportAnnunciatorConfiguration { supported });
    }

    fn send_report_annunciator_state(&mut self, _msg: &QueryAnnunciatorState, transport: &Receive) {
        let Some(d) = self.env.reported_discrete_devices(self.svc.driver) else {
            return self.refuse(format!(
                "Query Annunciator State: no Report Discrete Devices from the RA 3.3 Primitive Driver {} yet",
                self.svc.driver
            ));
        };
        let annunciator = AnnunciatorState {
            horn: if d.horn { HORN_ON } else { 0 },
            ..Default::default()
        };
        self.reply(transport, ReportAnnunciatorState { annunciator });
    }

    fn set_annunciator_state(&mut self, msg: &SetAnnunciatorState) {
        let change = DiscreteChange {
            horn: Some(msg.annunciator.horn > 0),
            ..Default::default()
        };
        self.env
            .set_discrete_devices(self.now, self.svc.driver, change);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_horn_is_supported() {
        let horn = AnnunciatorState {
            horn: 3,
            ..Default::default()
        };
        assert!(only_horn(&horn));
        assert!(only_horn(&AnnunciatorState::default()));
        for other in [
            AnnunciatorState { siren: 1, ..horn },
            AnnunciatorState { backup: 15, ..horn },
            AnnunciatorState {
                variable1: 2,
                ..Default::default()
            },
            AnnunciatorState {
                variable2: 2,
                ..Default::default()
            },
        ] {
            assert!(!only_horn(&other), "{other:?}");
        }
    }
}
