//! The Unmanned Ground Vehicle services (AS6091, `urn:jaus:jss:ugv`) over RA 3.3
//! components (Illumination over a hardware trait: RA 3.3 has no lights), as the [`crate::mobility`], [`crate::manipulator`] and
//! [`crate::environment`] services are: their machines are `defs/ugv_services.yaml`,
//! run by [`crate::machined`].
//!
//! | AS-4 service | RA 3.3 component | messages |
//! |---|---|---|
//! | Parking Brake Driver | Primitive Driver | Set Parking Brake → RA 3.3 Set Discrete Devices (the parking brake bit: set for any level above 0, the horn bit kept, [`crate::ra33::discrete`]); Query Parking Brake answered from the driver's Report Discrete Devices (polled once answered): measured 100 % with the bit set, 0 % without (or without the field); commanded, the level last set (before any, the measured one) |
//! | Annunciator | Primitive Driver | Set Annunciator State → RA 3.3 Set Discrete Devices (the horn bit: set for any horn level above 0, the parking brake bit kept); a siren, reversing alarm or variable annunciator refused; Query Annunciator State answered from the driver's Report Discrete Devices: horn 15 with the bit set, 0 without; Query Annunciator Configuration: the horn alone ([`annunciator`]) |
//! | Platform Specifications | Primitive Driver | Query Platform Specifications answered from the driver's Report Platform Specifications (asked once, on discovery): name, extent, centre of gravity, wheel base, pitch-over and roll-over angles, maximum forward speed (RA 3.3 maximum velocity x) and rotational speed (maximum yaw rate); the steering kind Ackermann (minimum turning radius, wheel separation = track width) when the turning radius is above 0, else skid steer (track separation = track width) |
//! | Odometry | Primitive Driver | Query Odometry answered from the odometer of the driver's Report Platform Operational Data (polled once answered): the platform odometer as RA 3.3 reports it (m); trips A, B and C kept by the gateway from the platform odometer, each reset by Reset Odometry from the controlling client ([`odometry`]) |
//! | Skid Steer Driver | Primitive Driver | Set Skid Steer Effort → RA 3.3 Set Wrench Effort: linear effort x the mean of the two sides, rotational effort z half the left one's excess (positive z turns right in RA 3.3's frame, z down), the brake released; Query Skid Steer Effort answered with the efforts last commanded; offered as soon as the driver is found, beside the Mobility Primitive Driver (the latest command of either wins, [`skid_steer`]) |
//! | Power Plant Manager | Primitive Driver | one power plant (id 1, a gasoline engine): Set Power Plant Configuration On / Off → RA 3.3 Set Discrete Devices (the main propulsion bit, the other bits kept, [`crate::ra33::discrete`]), Standby, engine speed and throttle refused; Query Power Plant Configuration answered from the driver's Report Discrete Devices (On with the bit set); Query Power Plant Status from its Report Platform Operational Data (engine temperature, fuel level, oil pressure; the battery voltage, a percentage of nominal, left out); Query Power Plant Capabilities: the engine, no limits ([`power_plant`]) |
//! | Illumination | none (RA 3.3 has no lights) | hosted natively over a [`Lights`] hardware trait, not through the RA 3.3 side: [`IlluminationService`], a generated-machine service any AS-4 component hosts (the demo vehicle's gateway over its simulated lamps) |
//!
//! The Skid Steer Driver reads nothing: it is offered when the Primitive Driver is found
//! ([`found`]), as the Mobility Primitive Driver is. A service that reads a report is
//! offered once the driver has answered the query it reads, asked once when the driver
//! is found ([`ask`]) and again when it is discovered again ([`rediscovered`]) until
//! answered ([`services`]); the Parking Brake Driver, the Annunciator and the Power
//! Plant Manager read Report Discrete Devices. The SDK's stock driver answers all three
//! queries (the platform's specifications and operational data with what its hardware
//! gives), so the demo vehicle gets all six services; a driver that answers fewer gets
//! fewer.
//!
//! RA 3.3 control of the Primitive Driver is asked for when the controlling AS-4 client
//! sets the parking brake, the horn or the engine ([`Ra33Side::ensure_control`]), as for
//! its efforts; the command waits (the latest one, with every bit) until it is granted.
//! The stock driver takes Set Discrete Devices in Standby as in Ready, so the driver is
//! not resumed and the vehicle's other drivers are left as they are. Skid-steer efforts
//! take the driver as the Mobility Primitive Driver's do (resumed while Ready).
//!
//! Not served: the Drive Train Driver (RA 3.3 Set Discrete Devices carries the gear and
//! the transfer case as raw numbers that RA 3.3 leaves to the vendor: no mapping onto
//! AS-4's Park/Neutral/Reverse/Drive/... and transfer case states), the Ackermann Driver
//! (RA 3.3's Primitive Driver takes efforts, not a steering angle) and the Stabilizer
//! Driver (RA 3.3 has no stabilizers). Their messages and machines are defined and
//! generated.

use std::time::Instant;

use jaus::messages as ra;
use jaus::{Address, JausMessage};

use crate::core::generated_id;
use crate::ra33::{Ra33Side, Targets};
use crate::service::{Service, ServiceId};

pub mod annunciator;
pub mod illumination;
pub mod odometry;
pub mod parking_brake;
pub mod platform;
pub mod power_plant;
pub mod skid_steer;

pub use annunciator::AnnunciatorService;
pub use illumination::{IlluminationService, Lights};
pub use odometry::OdometryService;
pub use parking_brake::ParkingBrakeDriver;
pub use platform::PlatformSpecificationsService;
pub use power_plant::PowerPlantManager;
pub use skid_steer::SkidSteerDriver;

/// The URIs and versions of the UGV services served, as `defs/ugv_services.yaml` gives
/// them.
#[derive(Debug)]
pub struct ServiceIds;

impl ServiceIds {
    /// `urn:jaus:jss:ugv:ParkingBrakeDriver`.
    pub const PARKING_BRAKE_DRIVER: ServiceId = generated_id!(parking_brake_driver);
    /// `urn:jaus:jss:ugv:PlatformSpecifications`.
    pub const PLATFORM_SPECIFICATIONS: ServiceId = generated_id!(platform_specifications_service);
    /// `urn:jaus:jss:ugv:OdometryService`.
    pub const ODOMETRY: ServiceId = generated_id!(odometry_service);
    /// `urn:jaus:jss:ugv:AnnunciatorService`.
    pub const ANNUNCIATOR: ServiceId = generated_id!(annunciator_service);
    /// `urn:jaus:jss:ugv:IlluminationService`.
    pub const ILLUMINATION: ServiceId = generated_id!(illumination_service);
    /// `urn:jaus:jss:ugv:SkidSteerDriver`.
    pub const SKID_STEER_DRIVER: ServiceId = generated_id!(skid_steer_driver);
    /// `urn:jaus:jss:ugv:PowerPlantManager`.
    pub const POWER_PLANT_MANAGER: ServiceId = generated_id!(power_plant_manager);
}

/// Which UGV services a gateway has offered (each once, when the RA 3.3 report it
/// reads first came).
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct Offered {
    /// The Parking Brake Driver.
    pub parking_brake: bool,
    /// The Platform Specifications service.
    pub platform_specifications: bool,
    /// The Odometry service.
    pub odometry: bool,
    /// The Annunciator.
    pub annunciator: bool,
    /// The Power Plant Manager.
    pub power_plant: bool,
}

/// The UGV services offered as soon as the RA 3.3 components just found (`new`) are:
/// the Skid Steer Driver over the Primitive Driver (it reads no report; its efforts
/// go the Mobility Primitive Driver's way, [`skid_steer`]).
pub fn found(new: &Targets) -> Vec<Box<dyn Service<Ra33Side>>> {
    let mut out: Vec<Box<dyn Service<Ra33Side>>> = Vec::new();
    if let Some(pd) = new.primitive_driver {
        out.push(Box::new(SkidSteerDriver::new(pd)));
    }
    out
}

/// Asks the RA 3.3 components just found (`new`) what the UGV services read, once: the
/// Primitive Driver's discrete devices and platform specifications. Not polled until
/// answered ([`services`]), so a driver that answers neither (OpenJAUS 3.3's answers
/// little but efforts) is not asked again and again.
pub fn ask(env: &mut Ra33Side, new: &Targets) {
    if let Some(pd) = new.primitive_driver {
        ask_driver(env, pd, &Offered::default());
    }
}

/// `component` was discovered again: what the UGV services read from it and it has not
/// answered yet is asked again, once.
pub fn rediscovered(env: &mut Ra33Side, component: Address, offered: &Offered) {
    if env.targets().primitive_driver == Some(component) {
        ask_driver(env, component, offered);
    }
}

fn ask_driver(env: &mut Ra33Side, pd: Address, offered: &Offered) {
    if !offered.parking_brake || !offered.annunciator || !offered.power_plant {
        env.send(pd, discrete_devices());
    }
    if !offered.platform_specifications {
        env.send(
            pd,
            ra::QueryPlatformSpecifications {
                presence_vector: 0x001F_FFFF,
            },
        );
    }
    if !offered.odometry || !offered.power_plant {
        env.send(pd, odometry::query());
    }
}

/// Query Discrete Devices, every field.
fn discrete_devices() -> ra::QueryDiscreteDevices {
    ra::QueryDiscreteDevices {
        presence_vector: 0x0F,
    }
}

/// The UGV services not offered yet whose RA 3.3 report has come (`offered` records
/// them): the Parking Brake Driver, the Annunciator and the Power Plant Manager once
/// the Primitive Driver reported its discrete devices (a report without the field
/// reads as brake released, horn silent, engine off: the stock driver leaves out the
/// devices never set), from then on polled; the Platform Specifications once it
/// reported them (asked once: they do not change); the Odometry once it reported its
/// odometer, from then on polled, as its operational data are for the Power Plant
/// Manager once it reported them.
pub fn services(
    env: &mut Ra33Side,
    now: Instant,
    offered: &mut Offered,
) -> Vec<Box<dyn Service<Ra33Side>>> {
    let mut out: Vec<Box<dyn Service<Ra33Side>>> = Vec::new();
    let Some(pd) = env.targets().primitive_driver else {
        return out;
    };
    let devices = env.reported_discrete_devices(pd).is_some();
    if devices && !(offered.parking_brake && offered.annunciator && offered.power_plant) {
        env.keep_polling(now, pd, discrete_devices());
    }
    if !offered.parking_brake && devices {
        offered.parking_brake = true;
        out.push(Box::new(ParkingBrakeDriver::new(pd)));
    }
    if !offered.annunciator && devices {
        offered.annunciator = true;
        out.push(Box::new(AnnunciatorService::new(pd)));
    }
    if !offered.power_plant && devices {
        offered.power_plant = true;
        out.push(Box::new(PowerPlantManager::new(pd)));
    }
    if offered.power_plant
        && env
            .latest(pd, ra::ReportPlatformOperationalData::CODE)
            .is_some()
    {
        // Once per pair: a no-op after the first.
        env.keep_polling(now, pd, odometry::query());
    }
    if !offered.platform_specifications && specifications(env, pd).is_some() {
        offered.platform_specifications = true;
        out.push(Box::new(PlatformSpecificationsService::new(pd)));
    }
    if !offered.odometry {
        if let Some(now_m) = odometry::odometer(env, pd) {
            offered.odometry = true;
            env.keep_polling(now, pd, odometry::query());
            out.push(Box::new(OdometryService::new(pd, now_m)));
        }
    }
    out
}

/// The latest Report Platform Specifications of the RA 3.3 driver at `pd`.
fn specifications(env: &Ra33Side, pd: Address) -> Option<&ra::ReportPlatformSpecifications> {
    match env.latest(pd, ra::ReportPlatformSpecifications::CODE) {
        Some((_, ra::Message::ReportPlatformSpecifications(r))) => Some(r),
        _ => None,
    }
}
