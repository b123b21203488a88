//! The Parking Brake Driver over the parking brake bit of an RA 3.3 Primitive Driver's
//! discrete devices (Set/Query/Report Discrete Devices).
//!
//! RA 3.3 has the brake on or off: a level above 0 % sets the bit (braking at least as
//! hard as asked), 0 % clears it; the measured level is 100 % with the bit set, 0 %
//! without. The machines (`defs/ugv_services.yaml`) take Set Parking Brake from the
//! controlling client: any level while the component is Ready, only a harder one
//! (`isEngage`, against the measured level) in its other controlled states; leaving
//! Ready applies the brake (`engageBrake`).
//!
//! The horn bit of the same RA 3.3 message is the Annunciator's ([`super::annunciator`]):
//! both bits are put together in one place ([`crate::ra33::discrete`]), so setting the
//! brake keeps the horn as commanded or reported and the reverse.

use std::time::Instant;

use jaus::Address;

use super::ServiceIds;
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::parking_brake_driver as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::{QueryParkingBrake, ReportParkingBrake, SetParkingBrake};
use crate::ra33::{DiscreteChange, Ra33Side};
use crate::service::Cx;

/// The AS-4 level (percent) of an RA 3.3 parking brake bit.
fn level(engaged: bool) -> f64 {
    if engaged {
        100.0
    } else {
        0.0
    }
}

/// The Parking Brake Driver over the RA 3.3 Primitive Driver at an address, on its
/// generated machines.
pub type ParkingBrakeDriver = OnMachines<ParkingBrake>;

/// The Parking Brake Driver's data: the RA 3.3 Primitive Driver and the level last set.
#[derive(Debug)]
pub struct ParkingBrake {
    driver: Address,
    commanded: Option<f64>,
}

impl ParkingBrakeDriver {
    /// The service over the RA 3.3 Primitive Driver at `driver` (whose discrete devices
    /// the gateway polls, [`super::services`]).
    pub fn new(driver: Address) -> Self {
        OnMachines::from_impl(ParkingBrake {
            driver,
            commanded: None,
        })
    }
}

impl ParkingBrake {
    /// Commands the parking brake bit `engaged` to the RA 3.3 driver at `now`, the horn
    /// bit kept ([`crate::ra33::discrete`]: the one place both bits are put together);
    /// sent once the gateway holds RA 3.3 control of the driver.
    fn command(&mut self, env: &mut Ra33Side, now: Instant, engaged: bool) {
        let change = DiscreteChange {
            parking_brake: Some(engaged),
            ..Default::default()
        };
        env.set_discrete_devices(now, self.driver, change);
    }

    /// Applies the brake (leaving Ready).
    fn engage(&mut self, env: &mut Ra33Side, now: Instant) {
        self.commanded = Some(100.0);
        self.command(env, now, true);
    }
}

machined!(
    ParkingBrake,
    parking_brake_driver,
    ServiceIds::PARKING_BRAKE_DRIVER,
    management {
        fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
            cx.env.flush_discrete_devices(cx.now);
        }

    }
);

impl generated::ParkingBrakeDriver for On<'_, ParkingBrake> {
    fn is_engage(&self, msg: &SetParkingBrake) -> bool {
        let now = self
            .env
            .reported_discrete_devices(self.svc.driver)
            .is_some_and(|d| d.parking_brake);
        msg.parking_brake > level(now)
    }

    fn engage_brake(&mut self) {
        self.svc.engage(self.env, self.now);
    }

    fn send_report_parking_brake(&mut self, _msg: &QueryParkingBrake, transport: &Receive) {
        let Some(d) = self.env.reported_discrete_devices(self.svc.driver) else {
            return self.refuse(format!(
                "Query Parking Brake: no Report Discrete Devices from the RA 3.3 Primitive Driver {} yet",
                self.svc.driver
            ));
        };
        let actual = level(d.parking_brake);
        let report = ReportParkingBrake {
            commanded_parking_brake: self.svc.commanded.unwrap_or(actual),
            actual_parking_brake: actual,
        };
        self.reply(transport, report);
    }

    fn set_parking_brake(&mut self, msg: &SetParkingBrake) {
        let asked = msg.parking_brake;
        if !(0.0..=100.0).contains(&asked) {
            return self.refuse(format!(
                "Set Parking Brake: field parking_brake {asked} outside 0..100 %"
            ));
        }
        self.svc.commanded = Some(asked);
        self.svc.command(self.env, self.now, asked > 0.0);
    }
}
