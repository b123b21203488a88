//! The Odometry service over the odometer of an RA 3.3 Primitive Driver's Report
//! Platform Operational Data (polled once answered, [`super::services`]).
//!
//! The platform odometer is RA 3.3's, whole metres as the driver reports them. The
//! three trip odometers are the gateway's: each reads the distance since it was last
//! reset (Reset Odometry, from the controlling client), and since the service was
//! offered before its first reset. A trip reading never goes below 0: an RA 3.3
//! odometer that went back (a driver restarted) restarts the trips at its reading.

use jaus::messages as ra;
use jaus::{Address, JausMessage};

use super::ServiceIds;
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::odometry_service as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::{Odometer, QueryOdometry, ReportOdometry, ResetOdometry, TripOdometer};
use crate::ra33::Ra33Side;

/// The odometer (m) the RA 3.3 driver at `pd` last reported (`None` before a Report
/// Platform Operational Data with it came).
pub(super) fn odometer(env: &Ra33Side, pd: Address) -> Option<u32> {
    match env.latest(pd, ra::ReportPlatformOperationalData::CODE) {
        Some((_, ra::Message::ReportPlatformOperationalData(r))) => r.odometer,
        _ => None,
    }
}

/// Query Platform Operational Data, every field: the odometer for this service, the
/// engine's gauges for the Power Plant Manager ([`super::power_plant`]); one poll of
/// the driver serves both.
pub(super) fn query() -> ra::QueryPlatformOperationalData {
    ra::QueryPlatformOperationalData {
        presence_vector: 0x1F,
    }
}

/// The Odometry service over the RA 3.3 Primitive Driver at an address, on its
/// generated machines.
pub type OdometryService = OnMachines<Odometry>;

/// The Odometry service's data: the RA 3.3 Primitive Driver and the platform odometer's
/// reading at each trip odometer's last reset (A, B, C).
#[derive(Debug)]
pub struct Odometry {
    driver: Address,
    trips: [u32; 3],
}

impl OdometryService {
    /// The service over the RA 3.3 Primitive Driver at `driver`, whose odometer reads
    /// `now` (m): the trip odometers start there.
    pub fn new(driver: Address, now: u32) -> Self {
        OnMachines::from_impl(Odometry {
            driver,
            trips: [now; 3],
        })
    }
}

machined!(
    Odometry,
    odometry_service,
    ServiceIds::ODOMETRY,
    access_control
);

/// The index of a trip odometer (`None` for a value the definition does not name).
fn trip(t: TripOdometer) -> Option<usize> {
    match t {
        TripOdometer::TripA => Some(0),
        TripOdometer::TripB => Some(1),
        TripOdometer::TripC => Some(2),
        TripOdometer::Unknown(_) => None,
    }
}

impl generated::OdometryService for On<'_, Odometry> {
    fn send_report_odometry(&mut self, msg: &QueryOdometry, transport: &Receive) {
        let Some(now) = odometer(self.env, self.svc.driver) else {
            return self.refuse(format!(
                "Query Odometry: no odometer in a Report Platform Operational Data from the RA 3.3 Primitive Driver {} yet",
                self.svc.driver
            ));
        };
        let k = match msg.odometer {
            Odometer::Platform => None,
            Odometer::TripA => Some(0),
            Odometer::TripB => Some(1),
            Odometer::TripC => Some(2),
            Odometer::Unknown(v) => {
                return self.refuse(format!(
                "Query Odometry: field odometer {v} names no odometer (1 platform, 2-4 trips A-C)"
            ))
            }
        };
        let odometry = match k {
            None => now,
            Some(k) => {
                let start = &mut self.svc.trips[k];
                if *start > now {
                    *start = now;
                }
                now - *start
            }
        };
        self.reply(
            transport,
            ReportOdometry {
                odometer: msg.odometer,
                odometry,
            },
        );
    }

    fn reset_trip_odometer(&mut self, msg: &ResetOdometry) {
        let Some(k) = trip(msg.odometer) else {
            return self.refuse(format!(
                "Reset Odometry: field odometer {:?} names no trip odometer (2-4, trips A-C)",
                msg.odometer
            ));
        };
        match odometer(self.env, self.svc.driver) {
            Some(now) => self.svc.trips[k] = now,
            None => self.refuse(format!(
                "Reset Odometry: no odometer from the RA 3.3 Primitive Driver {} yet",
                self.svc.driver
            )),
        }
    }
}
