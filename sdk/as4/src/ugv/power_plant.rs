//! The Power Plant Manager over what an RA 3.3 Primitive Driver knows of its engine:
//! the main propulsion bit of its discrete devices (Set/Query/Report Discrete Devices)
//! and its Report Platform Operational Data.
//!
//! RA 3.3 has one engine, switched on or off, and a few gauges; AS-4 has a list of
//! power plants of five kinds, each with settings, limits and a condition. The service
//! presents one power plant, [`POWER_PLANT_ID`] named [`NAME`], a gasoline engine (the
//! kind whose fields RA 3.3's gauges fill: engine temperature, fuel, oil pressure; RA
//! 3.3 does not say which fuel, and a diesel engine would add only glow plugs RA 3.3
//! has not):
//!
//! | AS-4 | RA 3.3 |
//! |---|---|
//! | Set Power Plant Configuration, power On / Off | Set Discrete Devices, main propulsion bit set / cleared ([`crate::ra33::discrete`]: the parking brake, the horn and the propulsion byte's other bits kept) |
//! | Set Power Plant Configuration, power Standby, an engine speed or a throttle, another power plant id or kind | none: refused (`isSupported`), nothing changed |
//! | Report Power Plant Configuration: power | Report Discrete Devices (polled): On with the main propulsion bit set, Off without it (or without the field: the stock driver leaves out devices never set) |
//! | Report Power Plant Configuration: engine speed, throttle | absent (RA 3.3 has neither) |
//! | Report Power Plant Status: engine temperature (°C) | Report Platform Operational Data: engine temperature (°C, the same range −75..=180) |
//! | Report Power Plant Status: percent remaining fuel | fuel level (%) |
//! | Report Power Plant Status: percent oil pressure | oil pressure (% of nominal; RA 3.3 carries up to 127 %, AS-4 up to 200 %) |
//! | Report Power Plant Status: oil level and temperature, engine hours, tachometer, coolant, air intake, exhaust | absent (RA 3.3 has none of them) |
//! | Report Power Plant Capabilities | the engine's id and name, every limit absent (RA 3.3 gives no capacity or limit) |
//!
//! Left out: RA 3.3's battery voltage. It is a percentage of the nominal voltage, and
//! AS-4's battery status has the voltage in volts and the charge remaining, neither of
//! the same meaning; the nominal voltage is not known to convert it. RA 3.3's odometer
//! is the Odometry service's ([`super::odometry`]).
//!
//! A query lists the power plants it asks about (none: all); the report has the one
//! this service has if listed, and no entry for an id it has not. Only the controlling
//! client sets the configuration, in any of the component's controlled states (the
//! machines, `defs/ugv_services.yaml`); RA 3.3 control of the driver is asked for with
//! the command, which waits (the latest one) until it is granted. The SDK's stock
//! Primitive Driver records the main propulsion bit and reports it back, but its
//! actuators do not act on it: the demo vehicle drives with its engine "off".

use jaus::messages as ra;
use jaus::{Address, JausMessage};

use super::ServiceIds;
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::power_plant_manager as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::{
    GasEngineCapabilities, GasEngineSettings, GasEngineStatus, PowerPlantCapabilities,
    PowerPlantCondition, PowerPlantConfiguration, PowerPlantLimits, PowerPlantSettings,
    PowerPlantStatus, PowerState, QueryPowerPlantCapabilities, QueryPowerPlantConfiguration,
    QueryPowerPlantStatus, ReportPowerPlantCapabilities, ReportPowerPlantConfiguration,
    ReportPowerPlantStatus, SetPowerPlantConfiguration,
};
use crate::ra33::{DiscreteChange, Ra33Side};
use crate::service::Cx;

/// The id of the one power plant: the RA 3.3 platform's engine.
pub const POWER_PLANT_ID: u8 = 1;

/// Its name in the reports.
pub const NAME: &str = "main propulsion";

/// The Power Plant Manager over the RA 3.3 Primitive Driver at an address, on its
/// generated machines.
pub type PowerPlantManager = OnMachines<PowerPlant>;

/// The Power Plant Manager's data: the RA 3.3 Primitive Driver whose engine it
/// switches.
#[derive(Debug)]
pub struct PowerPlant {
    driver: Address,
}

impl PowerPlantManager {
    /// The service over the RA 3.3 Primitive Driver at `driver` (whose discrete devices
    /// and operational data the gateway polls, [`super::services`]).
    pub fn new(driver: Address) -> Self {
        OnMachines::from_impl(PowerPlant { driver })
    }
}

machined!(
    PowerPlant,
    power_plant_manager,
    ServiceIds::POWER_PLANT_MANAGER,
    access_control {
        fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
            cx.env.flush_discrete_devices(cx.now);
        }
    }
);

/// Whether a query listing `ids` (none: all) asks about the one power plant.
fn asked(ids: &[u8]) -> bool {
    ids.is_empty() || ids.contains(&POWER_PLANT_ID)
}

/// The main propulsion bit `entry` commands, if RA 3.3 can do what it asks: the one
/// power plant, a gasoline engine, switched on or off, no engine speed, no throttle.
fn main_propulsion(entry: &PowerPlantConfiguration) -> Option<bool> {
    if entry.power_plant_id != POWER_PLANT_ID {
        return None;
    }
    let PowerPlantSettings::GasEngine(g) = &entry.settings else {
        return None;
    };
    if g.rpm.is_some() || g.throttle.is_some() {
        return None;
    }
    match g.power {
        PowerState::On => Some(true),
        PowerState::Off => Some(false),
        _ => None,
    }
}

/// The engine's condition from RA 3.3 operational data (`None`: none reported).
fn condition(data: Option<&ra::ReportPlatformOperationalData>) -> GasEngineStatus {
    let Some(d) = data else {
        return GasEngineStatus::default();
    };
    GasEngineStatus {
        percent_remaining_fuel: d.fuel_level,
        percent_oil_pressure: d.oil_pressure,
        engine_temp: d.engine_temperature,
        ..Default::default()
    }
}

impl generated::PowerPlantManager for On<'_, PowerPlant> {
    fn is_supported(&self, msg: &SetPowerPlantConfiguration) -> bool {
        msg.power_plants
            .iter()
            .all(|p| main_propulsion(p).is_some())
    }

    fn send_report_power_plant_capabilities(
        &mut self,
        msg: &QueryPowerPlantCapabilities,
        transport: &Receive,
    ) {
        let mut power_plants = Vec::new();
        if asked(&msg.power_plant_ids) {
            power_plants.push(PowerPlantCapabilities {
                power_plant_id: POWER_PLANT_ID,
                name: NAME.into(),
                limits: PowerPlantLimits::GasEngine(GasEngineCapabilities::default()),
            });
        }
        self.reply(transport, ReportPowerPlantCapabilities { power_plants });
    }

    fn send_report_power_plant_configuration(
        &mut self,
        msg: &QueryPowerPlantConfiguration,
        transport: &Receive,
    ) {
        let Some(p) = self.env.reported_propulsion(self.svc.driver) else {
            return self.refuse(format!(
                "Query Power Plant Configuration: no Report Discrete Devices from the RA 3.3 Primitive Driver {} yet",
                self.svc.driver
            ));
        };
        let mut power_plants = Vec::new();
        if asked(&msg.power_plant_ids) {
            let power = if p.main_propulsion {
                PowerState::On
            } else {
                PowerState::Off
            };
            power_plants.push(PowerPlantConfiguration {
                power_plant_id: POWER_PLANT_ID,
                settings: PowerPlantSettings::GasEngine(GasEngineSettings {
                    power,
                    ..Default::default()
                }),
            });
        }
        self.reply(transport, ReportPowerPlantConfiguration { power_plants });
    }

    fn send_report_power_plant_status(&mut self, msg: &QueryPowerPlantStatus, transport: &Receive) {
        let mut power_plants = Vec::new();
        if asked(&msg.power_plant_ids) {
            let data = match self
                .env
                .latest(self.svc.driver, ra::ReportPlatformOperationalData::CODE)
            {
                Some((_, ra::Message::ReportPlatformOperationalData(r))) => Some(r),
                _ => None,
            };
            power_plants.push(PowerPlantStatus {
                power_plant_id: POWER_PLANT_ID,
                name: NAME.into(),
                condition: PowerPlantCondition::GasEngine(condition(data)),
            });
        }
        self.reply(transport, ReportPowerPlantStatus { power_plants });
    }

    fn set_power_plant_configuration(&mut self, msg: &SetPowerPlantConfiguration) {
        // The guard let through only entries of the one engine: the last one wins.
        let Some(on) = msg.power_plants.iter().rev().find_map(main_propulsion) else {
            return;
        };
        let change = DiscreteChange {
            main_propulsion: Some(on),
            ..Default::default()
        };
        self.env
            .set_discrete_devices(self.now, self.svc.driver, change);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn engine(power: PowerState) -> PowerPlantConfiguration {
        PowerPlantConfiguration {
            power_plant_id: POWER_PLANT_ID,
            settings: PowerPlantSettings::GasEngine(GasEngineSettings {
                power,
                ..Default::default()
            }),
        }
    }

    #[test]
    fn only_the_engine_switched_on_or_off_is_supported() {
        assert_eq!(main_propulsion(&engine(PowerState::On)), Some(true));
        assert_eq!(main_propulsion(&engine(PowerState::Off)), Some(false));
        assert_eq!(main_propulsion(&engine(PowerState::Standby)), None);
        assert_eq!(main_propulsion(&engine(PowerState::Unknown(9))), None);
        let mut other = engine(PowerState::On);
        other.power_plant_id = 2;
        assert_eq!(main_propulsion(&other), None);
        let throttle = PowerPlantConfiguration {
            settings: PowerPlantSettings::GasEngine(GasEngineSettings {
                power: PowerState::On,
                throttle: Some(40.0),
                ..Default::default()
            }),
            ..engine(PowerState::On)
        };
        assert_eq!(main_propulsion(&throttle), None);
        let battery = PowerPlantConfiguration {
            settings: PowerPlantSettings::Battery(PowerState::On),
            ..engine(PowerState::On)
        };
        assert_eq!(main_propulsion(&battery), None);
    }

    #[test]
    fn the_condition_has_the_gauges_of_the_same_meaning() {
        let d = ra::ReportPlatformOperationalData {
            engine_temperature: Some(85.0),
            odometer: Some(1200),
            battery_voltage: Some(98.0),
            fuel_level: Some(40.0),
            oil_pressure: Some(110.0),
        };
        let c = condition(Some(&d));
        assert_eq!(c.engine_temp, Some(85.0));
        assert_eq!(c.percent_remaining_fuel, Some(40.0));
        assert_eq!(c.percent_oil_pressure, Some(110.0));
        assert_eq!(c.tachometer, None);
        assert_eq!(condition(None), GasEngineStatus::default());
    }
}
