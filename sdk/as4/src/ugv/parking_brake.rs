//! The Parking Brake Driver over the parking brake bit of an RA 3.3 Primitive Driver's
//! discrete devices (Set/Query/Report Discrete Devices).
//!
//! RA 3.3 has the brake on or off: a level above 0 % sets the bit (braking at least as
//! hard as asked), 0 % clears it; the measured level is 100 % with the bit set, 0 %
//! without. The machines (`defs/ugv_services.yaml`) take Set Parking Brake from the
//! controlling client: any level while the component is Ready, only a harder one
//! (`isEngage`, against the measured level) in its other controlled states; leaving
//! Ready applies the brake (`engageBrake`).

use jaus::messages as ra;
use jaus::{Address, JausMessage};

use super::ServiceIds;
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::parking_brake_driver as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::{QueryParkingBrake, ReportParkingBrake, SetParkingBrake};
use crate::ra33::{Ra33Control, Ra33Side};
use crate::service::Cx;

/// The parking brake bit and horn bit the RA 3.3 driver at `pd` last reported (`None`
/// before a Report Discrete Devices came). A report without the field (the stock
/// driver's before the devices were ever set) reads as both off.
pub(super) fn measured(env: &Ra33Side, pd: Address) -> Option<ra::ParkingBrakeHorn> {
    match env.latest(pd, ra::ReportDiscreteDevices::CODE) {
        Some((_, ra::Message::ReportDiscreteDevices(r))) => {
            Some(r.parking_brake_and_horn.unwrap_or_default())
        }
        _ => None,
    }
}

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

/// The Parking Brake Driver's data: the RA 3.3 Primitive Driver, the level last set,
/// the command waiting for RA 3.3 control.
#[derive(Debug)]
pub struct ParkingBrake {
    driver: Address,
    commanded: Option<f64>,
    pending: Option<ra::SetDiscreteDevices>,
}

impl ParkingBrakeDriver {
    /// The service over the RA 3.3 Primitive Driver at `driver` (whose discrete devices
    /// the gateway polls, [`super::services`]).
    pub fn new(driver: Address) -> Self {
        OnMachines::from_impl(ParkingBrake {
            driver,
            commanded: None,
            pending: None,
        })
    }
}

impl ParkingBrake {
    /// Sends the parking brake bit `engaged` to the RA 3.3 driver (the horn bit as it
    /// reports it), now if the gateway holds it, else when it does ([`Self::flush`]).
    fn command(&mut self, env: &mut Ra33Side, engaged: bool) {
        let horn = measured(env, self.driver).is_some_and(|d| d.horn);
        let command = ra::SetDiscreteDevices {
            parking_brake_and_horn: Some(ra::ParkingBrakeHorn {
                parking_brake: engaged,
                horn,
                ..Default::default()
            }),
            ..Default::default()
        };
        env.ensure_control(self.driver);
        if env.control_of(self.driver) == Ra33Control::Granted {
            env.send(self.driver, command);
            self.pending = None;
        } else {
            self.pending = Some(command);
        }
    }

    /// Applies the brake (leaving Ready).
    fn engage(&mut self, env: &mut Ra33Side) {
        self.commanded = Some(100.0);
        self.command(env, true);
    }

    /// Sends the command kept in `pending` once RA 3.3 control is granted; drops it
    /// when no AS-4 client controls the component any more.
    fn flush(&mut self, env: &mut Ra33Side) {
        if !env.controlled() {
            self.pending = None;
        } else if env.control_of(self.driver) == Ra33Control::Granted {
            if let Some(c) = self.pending.take() {
                env.send(self.driver, c);
            }
        }
    }
}

machined!(
    ParkingBrake,
    parking_brake_driver,
    ServiceIds::PARKING_BRAKE_DRIVER,
    management {
        fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
            self.flush(cx.env);
        }

    }
);

impl generated::ParkingBrakeDriver for On<'_, ParkingBrake> {
    fn is_engage(&self, msg: &SetParkingBrake) -> bool {
        let now = measured(self.env, self.svc.driver).is_some_and(|d| d.parking_brake);
        msg.parking_brake > level(now)
    }

    fn engage_brake(&mut self) {
        self.svc.engage(self.env);
    }

    fn send_report_parking_brake(&mut self, _msg: &QueryParkingBrake, transport: &Receive) {
        let Some(d) = measured(self.env, self.svc.driver) else {
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
        self.svc.command(self.env, asked > 0.0);
    }
}
