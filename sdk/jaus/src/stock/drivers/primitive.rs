//! The Primitive Driver (Part 1 §5.3): wrench efforts and discrete devices applied to
//! the [`Actuators`](crate::stock::hardware::Actuators), braking when not refreshed.
//!
//! Platform queries: Query Platform Specifications is answered from
//! [`PrimitiveConfig::specifications`] (static), Query Platform Operational Data from
//! [`Actuators::operational_data`] (read at each query). Each answer carries the fields
//! the query's presence vector asks for that the platform has (the report's presence
//! vector says which: Part 1 §2, a clear bit is a field not present), so it may carry
//! none of them. A platform that gives nothing at all leaves the query unanswered
//! (refused as invalid, counted in the component's statistics): RA 3.3 has no negative
//! answer to a query, and a requester tells "not supported" by the silence, as with
//! OpenJAUS 3.3, which does not answer the queries it does not implement.

use std::time::{Duration, Instant};

use crate::codec::Encode;
use crate::component::{CoreState, Refused, StopReason};
use crate::components::primitive_driver as pd;
use crate::messages::*;
use crate::stock::hardware::{Actuators, OperationalData, Wrench};
use crate::stock::motion::{wrench_message, wrench_of};

/// Settings of the Primitive Driver.
#[derive(Debug, Clone)]
pub struct PrimitiveConfig {
    /// A wrench not refreshed within this time is replaced by brakes (watchdog).
    pub command_timeout: Duration,
    /// The platform's specifications (dimensions, centre of gravity, turning radius,
    /// top speeds), answered to Query Platform Specifications with the fields the query
    /// asks for; `None` refuses the query (the platform did not say).
    pub specifications: Option<ReportPlatformSpecifications>,
}

impl Default for PrimitiveConfig {
    fn default() -> Self {
        Self {
            command_timeout: Duration::from_millis(300),
            specifications: None,
        }
    }
}

/// The Primitive Driver: applies wrench efforts to [`Actuators`] while Ready; brakes on
/// leaving Ready and when commands stop arriving.
#[derive(Debug)]
pub struct StockPrimitiveDriver<A> {
    actuators: A,
    config: PrimitiveConfig,
    commanded: Option<(Instant, SetWrenchEffort)>,
    applied: Wrench,
    devices: ReportDiscreteDevices,
    watchdog_trips: u64,
}

impl<A: Actuators> StockPrimitiveDriver<A> {
    /// Over `actuators`.
    pub fn new(actuators: A, config: PrimitiveConfig) -> Self {
        Self {
            actuators,
            config,
            commanded: None,
            applied: Wrench::ZERO,
            devices: ReportDiscreteDevices::default(),
            watchdog_trips: 0,
        }
    }

    /// The effort applied last.
    pub fn applied(&self) -> Wrench {
        self.applied
    }

    /// Times the command watchdog braked.
    pub fn watchdog_trips(&self) -> u64 {
        self.watchdog_trips
    }

    fn apply(&mut self, now: Instant, w: Wrench) {
        self.applied = w;
        self.actuators.apply(now, &w);
    }
}

impl<A: Actuators> pd::PrimitiveDriver for StockPrimitiveDriver<A> {
    fn on_set_wrench_effort(
        &mut self,
        ctx: &mut pd::Ctx<'_>,
        msg: &SetWrenchEffort,
    ) -> Result<(), Refused> {
        let w = wrench_of(msg);
        if !w.is_valid() {
            return Err(Refused::Invalid(
                "wrench effort outside -100..100 % (0..100 % resistive) or not finite".into(),
            ));
        }
        self.commanded = Some((ctx.now(), msg.clone()));
        if ctx.state() == CoreState::Ready {
            self.apply(ctx.now(), w);
        }
        Ok(())
    }

    fn on_set_discrete_devices(
        &mut self,
        _ctx: &mut pd::Ctx<'_>,
        msg: &SetDiscreteDevices,
    ) -> Result<(), Refused> {
        let d = &mut self.devices;
        d.propulsion = msg.propulsion.or(d.propulsion);
        d.parking_brake_and_horn = msg.parking_brake_and_horn.or(d.parking_brake_and_horn);
        d.gear = msg.gear.or(d.gear);
        d.transfer_case = msg.transfer_case.or(d.transfer_case);
        Ok(())
    }

    fn on_query_wrench_effort(
        &mut self,
        _ctx: &mut pd::Ctx<'_>,
        _q: &QueryWrenchEffort,
    ) -> Result<ReportWrenchEffort, Refused> {
        let m = wrench_message(&self.applied);
        Ok(ReportWrenchEffort {
            propulsive_linear_effort_x: m.propulsive_linear_effort_x,
            propulsive_rotational_effort_z: m.propulsive_rotational_effort_z,
            resistive_linear_effort_x: m.resistive_linear_effort_x,
            ..Default::default()
        })
    }

    fn on_query_discrete_devices(
        &mut self,
        _ctx: &mut pd::Ctx<'_>,
        _q: &QueryDiscreteDevices,
    ) -> Result<ReportDiscreteDevices, Refused> {
        Ok(self.devices.clone())
    }

    fn on_query_platform_specifications(
        &mut self,
        _ctx: &mut pd::Ctx<'_>,
        q: &QueryPlatformSpecifications,
    ) -> Result<ReportPlatformSpecifications, Refused> {
        let mut r = self.config.specifications.clone().ok_or_else(|| {
            Refused::Invalid("this platform's specifications are not configured".into())
        })?;
        r.keep_present(u64::from(q.presence_vector));
        Ok(r)
    }

    fn on_query_platform_operational_data(
        &mut self,
        ctx: &mut pd::Ctx<'_>,
        q: &QueryPlatformOperationalData,
    ) -> Result<ReportPlatformOperationalData, Refused> {
        let data = self.actuators.operational_data(ctx.now()).ok_or_else(|| {
            Refused::Invalid(
                "Query Platform Operational Data: this platform gives no operational data".into(),
            )
        })?;
        Ok(operational_report(&data, q.presence_vector))
    }

    fn stop(&mut self, ctx: &mut pd::Ctx<'_>, _reason: StopReason) {
        self.commanded = None;
        self.apply(ctx.now(), Wrench::brake());
    }

    fn state_changed(&mut self, ctx: &mut pd::Ctx<'_>, _from: CoreState, to: CoreState) {
        if to != CoreState::Ready {
            self.commanded = None;
            self.apply(ctx.now(), Wrench::brake());
        }
    }

    fn tick(&mut self, ctx: &mut pd::Ctx<'_>) {
        let now = ctx.now();
        if let Some((t, _)) = &self.commanded {
            if now.saturating_duration_since(*t) > self.config.command_timeout {
                self.commanded = None;
                self.watchdog_trips += 1;
                tracing::info!(address = %ctx.address(), "primitive driver: wrench not refreshed; braking");
                self.apply(now, Wrench::brake());
            }
        }
    }
}

/// Report Platform Operational Data from `data`, with the fields `presence_vector` asks
/// for that `data` has. A value that is not finite (or a negative odometer) is left out
/// with a warning; the others are clamped to the message's ranges, the odometer rounded
/// down to whole metres (at most `u32::MAX`).
fn operational_report(
    data: &OperationalData,
    presence_vector: u8,
) -> ReportPlatformOperationalData {
    fn finite(field: &str, v: Option<f64>) -> Option<f64> {
        match v {
            Some(x) if !x.is_finite() => {
                tracing::warn!(
                    field,
                    value = x,
                    "Report Platform Operational Data: value not finite; field left out"
                );
                None
            }
            v => v,
        }
    }
    let odometer = match finite("odometer", data.odometer) {
        Some(m) if m < 0.0 => {
            tracing::warn!(
                field = "odometer",
                value = m,
                "Report Platform Operational Data: negative distance; field left out"
            );
            None
        }
        // `as` saturates: above u32::MAX metres, u32::MAX.
        m => m.map(|m| m.floor() as u32),
    };
    let mut r = ReportPlatformOperationalData {
        engine_temperature: finite("engine_temperature", data.engine_temperature),
        odometer,
        battery_voltage: finite("battery_voltage", data.battery_voltage),
        fuel_level: finite("fuel_level", data.fuel_level),
        oil_pressure: finite("oil_pressure", data.oil_pressure),
    };
    r.clamp_to_range();
    r.keep_present(u64::from(presence_vector));
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::component::local::{LocalBus, Probe};
    use crate::component::Config;
    use crate::Address;

    const PD: Address = Address::new(1, 1, 33, 1);
    const OCU: Address = Address::new(1, 2, 40, 1);

    /// A platform with an odometer and a battery gauge (or nothing at all).
    struct Fake(Option<OperationalData>);

    impl Actuators for Fake {
        fn apply(&mut self, _now: Instant, _effort: &Wrench) {}
        fn operational_data(&mut self, _now: Instant) -> Option<OperationalData> {
            self.0
        }
    }

    /// The answers the OCU gets to Query Platform Operational Data with `presence_vector`.
    fn ask(
        data: Option<OperationalData>,
        presence_vector: u8,
    ) -> Vec<ReportPlatformOperationalData> {
        let t0 = Instant::now();
        let mut bus = LocalBus::new(t0);
        let driver = StockPrimitiveDriver::new(Fake(data), PrimitiveConfig::default());
        bus.add(pd::component(PD, driver, Config::default(), t0));
        bus.add(Probe::new(OCU));
        bus.run_for(Duration::from_millis(20));
        bus.send(OCU, PD, QueryPlatformOperationalData { presence_vector });
        bus.run_for(Duration::from_millis(20));
        bus.get::<Probe>(OCU)
            .unwrap()
            .messages()
            .filter_map(|m| match m {
                Message::ReportPlatformOperationalData(r) => Some(r.clone()),
                _ => None,
            })
            .collect()
    }

    const DATA: OperationalData = OperationalData {
        engine_temperature: None,
        odometer: Some(1234.9),
        battery_voltage: Some(98.5),
        fuel_level: None,
        oil_pressure: None,
    };

    #[test]
    fn answers_the_fields_asked_that_the_platform_has() {
        let all = ask(Some(DATA), 0x1F);
        assert_eq!(all.len(), 1);
        assert_eq!(all[0].odometer, Some(1234), "whole metres, rounded down");
        assert!((all[0].battery_voltage.unwrap() - 98.5).abs() < 0.5);
        assert_eq!(all[0].engine_temperature, None);
        assert_eq!(all[0].fuel_level, None);
        assert_eq!(all[0].oil_pressure, None);
        let odometer = ask(Some(DATA), 1 << 1);
        assert_eq!(
            odometer,
            [ReportPlatformOperationalData {
                odometer: Some(1234),
                ..Default::default()
            }]
        );
        // Fields the platform lacks: an answer with none (an empty presence vector).
        assert_eq!(
            ask(Some(DATA), 1 << 3),
            [ReportPlatformOperationalData::default()]
        );
    }

    #[test]
    fn a_platform_without_operational_data_leaves_the_query_unanswered() {
        assert_eq!(ask(None, 0x1F), []);
    }

    #[test]
    fn bad_values_are_left_out_or_clamped() {
        let r = operational_report(
            &OperationalData {
                engine_temperature: Some(f64::NAN),
                odometer: Some(-1.0),
                battery_voltage: Some(500.0),
                fuel_level: Some(f64::INFINITY),
                oil_pressure: Some(50.0),
            },
            0x1F,
        );
        assert_eq!(r.engine_temperature, None);
        assert_eq!(r.odometer, None);
        assert_eq!(r.battery_voltage, Some(127.0));
        assert_eq!(r.fuel_level, None);
        assert_eq!(r.oil_pressure, Some(50.0));
        let far = operational_report(
            &OperationalData {
                odometer: Some(1e12),
                ..Default::default()
            },
            0x02,
        );
        assert_eq!(far.odometer, Some(u32::MAX));
    }
}
