//! The parking brake, horn and main propulsion bits of RA 3.3 Primitive Drivers as
//! this gateway commands them: the one place a Set Discrete Devices is built.
//!
//! Three AS-4 services write RA 3.3 Set Discrete Devices: the Parking Brake Driver its
//! parking brake bit and the Annunciator its horn bit (the one byte that carries both),
//! the Power Plant Manager the main propulsion bit of the propulsion byte
//! ([`crate::ugv`]). Each asks for its own bit ([`DiscreteChange`]) and
//! [`Ra33Side::set_discrete_devices`] builds the message, so none clobbers another:
//!
//! * a bit asked for is the one sent;
//! * a bit not asked for is the one this gateway last commanded while that command may
//!   not show in the driver's reports yet (it waits for RA 3.3 control, or was sent
//!   less than [`SETTLE`] ago), else the one the driver last reported (off before a
//!   report, or in one without the field: the stock driver leaves out devices never
//!   set);
//! * the parking brake and horn byte is always sent; the propulsion byte only with a
//!   main propulsion bit asked for or still settling, its other bits (fuel supplies,
//!   auxiliary power, starter, cold start, automatic start and stop) kept the same way
//!   as the others, so a brake or a horn never switches the engine and a driver that
//!   was never sent one keeps its own.
//!
//! Gear and transfer case are never sent (RA 3.3 leaves their meaning to the vendor).
//!
//! RA 3.3 control of the driver is asked for with the command; the command goes at once
//! if control is held, else the latest one per driver (every bit) waits until it is
//! granted ([`Ra33Side::flush_discrete_devices`]) and is dropped when no AS-4 client
//! controls the component any more.

use std::collections::HashMap;
use std::time::{Duration, Instant};

use jaus::messages::{
    DiscretePropulsion, Message as Ra33Message, ParkingBrakeHorn, ReportDiscreteDevices,
    SetDiscreteDevices,
};
use jaus::{Address, JausMessage};

use super::{Ra33Control, Ra33Side};

/// How long a bit this gateway commanded is kept over what the driver reports (the
/// report may have been asked for before the command arrived).
pub const SETTLE: Duration = Duration::from_secs(2);

/// A change of an RA 3.3 driver's parking brake, horn and main propulsion bits: `None`
/// keeps a bit.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct DiscreteChange {
    /// The parking brake bit to command.
    pub parking_brake: Option<bool>,
    /// The horn bit to command.
    pub horn: Option<bool>,
    /// The main propulsion bit to command (engine on or off).
    pub main_propulsion: Option<bool>,
}

/// The bits last commanded to one driver (the propulsion byte if it was sent): when
/// sent (`None`: waiting for control).
#[derive(Debug, Clone, Copy)]
struct Commanded {
    bits: ParkingBrakeHorn,
    propulsion: Option<DiscretePropulsion>,
    sent: Option<Instant>,
}

impl Commanded {
    /// Whether it may not show in the driver's reports yet at `now`.
    fn settling(&self, now: Instant) -> bool {
        self.sent
            .is_none_or(|at| now.saturating_duration_since(at) < SETTLE)
    }
}

/// The bits last commanded to each driver (one entry per Primitive Driver commanded).
#[derive(Debug, Default)]
pub(super) struct DiscreteDevices {
    commanded: HashMap<Address, Commanded>,
}

/// Set Discrete Devices with `c`'s bits (the propulsion byte if any).
fn message(c: &Commanded) -> SetDiscreteDevices {
    SetDiscreteDevices {
        propulsion: c.propulsion,
        parking_brake_and_horn: Some(c.bits),
        ..Default::default()
    }
}

impl Ra33Side {
    /// The parking brake and horn bits the RA 3.3 driver at `driver` last reported
    /// (`None` before a Report Discrete Devices came; a report without the field reads
    /// as both off).
    pub fn reported_discrete_devices(&self, driver: Address) -> Option<ParkingBrakeHorn> {
        match self.latest(driver, ReportDiscreteDevices::CODE) {
            Some((_, Ra33Message::ReportDiscreteDevices(r))) => {
                Some(r.parking_brake_and_horn.unwrap_or_default())
            }
            _ => None,
        }
    }

    /// The propulsion bits the RA 3.3 driver at `driver` last reported (`None` before a
    /// Report Discrete Devices came; a report without the field reads as all off).
    pub fn reported_propulsion(&self, driver: Address) -> Option<DiscretePropulsion> {
        match self.latest(driver, ReportDiscreteDevices::CODE) {
            Some((_, Ra33Message::ReportDiscreteDevices(r))) => {
                Some(r.propulsion.unwrap_or_default())
            }
            _ => None,
        }
    }

    /// Commands `change` to the RA 3.3 driver at `driver` at `now`, the bits not changed
    /// kept (see the module's documentation), through RA 3.3 control of the driver.
    pub fn set_discrete_devices(&mut self, now: Instant, driver: Address, change: DiscreteChange) {
        let settling = self
            .discrete
            .commanded
            .get(&driver)
            .filter(|c| c.settling(now))
            .copied();
        let base = settling
            .map(|c| c.bits)
            .unwrap_or_else(|| self.reported_discrete_devices(driver).unwrap_or_default());
        let bits = ParkingBrakeHorn {
            parking_brake: change.parking_brake.unwrap_or(base.parking_brake),
            horn: change.horn.unwrap_or(base.horn),
            ..Default::default()
        };
        let kept = settling.and_then(|c| c.propulsion);
        let propulsion = match change.main_propulsion {
            Some(on) => Some(DiscretePropulsion {
                main_propulsion: on,
                ..kept
                    .or_else(|| self.reported_propulsion(driver))
                    .unwrap_or_default()
            }),
            None => kept,
        };
        self.ensure_control(driver);
        let mut c = Commanded {
            bits,
            propulsion,
            sent: None,
        };
        if self.control_of(driver) == Ra33Control::Granted {
            self.send(driver, message(&c));
            c.sent = Some(now);
        }
        self.discrete.commanded.insert(driver, c);
    }

    /// Sends the discrete devices commands waiting for RA 3.3 control to the drivers
    /// that granted it, at `now`; drops them all when no AS-4 client controls the
    /// component any more.
    pub fn flush_discrete_devices(&mut self, now: Instant) {
        if !self.controlled() {
            self.discrete.commanded.retain(|_, c| c.sent.is_some());
            return;
        }
        let ready: Vec<(Address, Commanded)> = self
            .discrete
            .commanded
            .iter()
            .filter(|(d, c)| c.sent.is_none() && self.control_of(**d) == Ra33Control::Granted)
            .map(|(d, c)| (*d, *c))
            .collect();
        for (driver, mut c) in ready {
            self.send(driver, message(&c));
            c.sent = Some(now);
            self.discrete.commanded.insert(driver, c);
        }
    }
}

#[cfg(test)]
mod tests {
    use jaus::messages::{ConfirmComponentControl, ControlResponse};

    use super::*;
    use crate::ra33::Targets;

    const PD: Address = Address::new(1, 1, 33, 1);

    fn side(t0: Instant) -> Ra33Side {
        let mut s = Ra33Side::new(
            Address::new(1, 1, 200, 1),
            Targets::default(),
            255,
            Duration::from_millis(100),
        );
        s.set_controlled(true);
        grant(&mut s, t0);
        while s.poll_transmit().is_some() {}
        s
    }

    /// The driver grants the gateway RA 3.3 control at `at`.
    fn grant(s: &mut Ra33Side, at: Instant) {
        s.on_message(
            at,
            PD,
            Ra33Message::ConfirmComponentControl(ConfirmComponentControl {
                response_code: ControlResponse::ControlAccepted,
            }),
        );
    }

    fn report(s: &mut Ra33Side, at: Instant, parking_brake: bool, horn: bool) {
        s.on_message(
            at,
            PD,
            Ra33Message::ReportDiscreteDevices(ReportDiscreteDevices {
                parking_brake_and_horn: Some(ParkingBrakeHorn {
                    parking_brake,
                    horn,
                    ..Default::default()
                }),
                ..Default::default()
            }),
        );
    }

    /// The bits of the Set Discrete Devices sent, if one was.
    fn sent(s: &mut Ra33Side) -> Option<(bool, bool)> {
        let mut last = None;
        while let Some((to, m)) = s.poll_transmit() {
            if let (PD, Ra33Message::SetDiscreteDevices(d)) = (to, m) {
                let b = d.parking_brake_and_horn.expect("the bits");
                last = Some((b.parking_brake, b.horn));
            }
        }
        last
    }

    #[test]
    fn each_bit_keeps_the_other_as_commanded_then_as_reported() {
        let t0 = Instant::now();
        let mut s = side(t0);
        report(&mut s, t0, false, false);
        let brake = DiscreteChange {
            parking_brake: Some(true),
            ..Default::default()
        };
        let horn = DiscreteChange {
            horn: Some(true),
            ..Default::default()
        };
        s.set_discrete_devices(t0, PD, brake);
        assert_eq!(sent(&mut s), Some((true, false)));
        // Before the driver reports the brake, the horn keeps it.
        s.set_discrete_devices(t0, PD, horn);
        assert_eq!(sent(&mut s), Some((true, true)));
        // Long after, what the driver reports wins (another client released the brake).
        let later = t0 + SETTLE * 2;
        report(&mut s, later, false, true);
        s.set_discrete_devices(
            later,
            PD,
            DiscreteChange {
                horn: Some(false),
                ..Default::default()
            },
        );
        assert_eq!(sent(&mut s), Some((false, false)));
    }

    #[test]
    fn commands_wait_for_control_with_both_bits_and_are_dropped_without_a_controller() {
        let t0 = Instant::now();
        let mut s = Ra33Side::new(
            Address::new(1, 1, 200, 1),
            Targets::default(),
            255,
            Duration::from_millis(100),
        );
        s.set_controlled(true);
        report(&mut s, t0, false, false);
        s.set_discrete_devices(
            t0,
            PD,
            DiscreteChange {
                parking_brake: Some(true),
                ..Default::default()
            },
        );
        s.set_discrete_devices(
            t0,
            PD,
            DiscreteChange {
                horn: Some(true),
                ..Default::default()
            },
        );
        assert_eq!(sent(&mut s), None, "waits for control");
        grant(&mut s, t0);
        s.flush_discrete_devices(t0);
        assert_eq!(sent(&mut s), Some((true, true)));
        s.flush_discrete_devices(t0);
        assert_eq!(sent(&mut s), None, "sent once");

        // Waiting when the controller leaves: dropped.
        s.set_controlled(false);
        s.set_discrete_devices(
            t0,
            PD,
            DiscreteChange {
                horn: Some(false),
                ..Default::default()
            },
        );
        s.flush_discrete_devices(t0);
        s.set_controlled(true);
        grant(&mut s, t0);
        s.flush_discrete_devices(t0);
        assert_eq!(sent(&mut s), None);
    }

    /// The propulsion byte of the Set Discrete Devices sent, if one was (`Some(None)`:
    /// sent without it).
    fn propulsion_sent(s: &mut Ra33Side) -> Option<Option<DiscretePropulsion>> {
        let mut last = None;
        while let Some((to, m)) = s.poll_transmit() {
            if let (PD, Ra33Message::SetDiscreteDevices(d)) = (to, m) {
                last = Some(d.propulsion);
            }
        }
        last
    }

    #[test]
    fn the_main_propulsion_bit_keeps_the_other_bits_and_is_sent_only_when_asked_for() {
        let t0 = Instant::now();
        let mut s = side(t0);
        let fuel = DiscretePropulsion {
            main_fuel_supply: true,
            ..Default::default()
        };
        s.on_message(
            t0,
            PD,
            Ra33Message::ReportDiscreteDevices(ReportDiscreteDevices {
                propulsion: Some(fuel),
                parking_brake_and_horn: Some(ParkingBrakeHorn {
                    parking_brake: true,
                    ..Default::default()
                }),
                ..Default::default()
            }),
        );
        // A brake or a horn alone leaves the propulsion byte out.
        s.set_discrete_devices(
            t0,
            PD,
            DiscreteChange {
                horn: Some(true),
                ..Default::default()
            },
        );
        assert_eq!(propulsion_sent(&mut s), Some(None));
        // The engine on: the fuel supply bit reported kept, the brake and horn too.
        s.set_discrete_devices(
            t0,
            PD,
            DiscreteChange {
                main_propulsion: Some(true),
                ..Default::default()
            },
        );
        let on = DiscretePropulsion {
            main_propulsion: true,
            ..fuel
        };
        let c = s.discrete.commanded.get(&PD).copied().expect("commanded");
        assert!(c.bits.parking_brake && c.bits.horn, "{c:?}");
        assert_eq!(propulsion_sent(&mut s), Some(Some(on)));
        // The horn right after, before the driver reports the engine: the engine kept.
        s.set_discrete_devices(
            t0,
            PD,
            DiscreteChange {
                horn: Some(false),
                ..Default::default()
            },
        );
        assert_eq!(propulsion_sent(&mut s), Some(Some(on)));
        // Long after, the horn leaves the propulsion byte out again.
        let later = t0 + SETTLE * 2;
        s.set_discrete_devices(
            later,
            PD,
            DiscreteChange {
                horn: Some(true),
                ..Default::default()
            },
        );
        assert_eq!(propulsion_sent(&mut s), Some(None));
    }
}
