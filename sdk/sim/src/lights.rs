//! The simulated vehicle's lamps: which it has ([`Lamp::ALL`]) and which are on. The
//! model only keeps their state (a lamp draws no power, lights nothing up in the
//! camera); an AS-4 Illumination service drives them through `jaus-node`'s adapter.

use std::collections::BTreeSet;

/// A lamp of the simulated vehicle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Lamp {
    /// Headlights (low beams).
    Headlights,
    /// High beams.
    HighBeams,
    /// Running lights.
    RunningLights,
    /// Brake lights.
    BrakeLights,
    /// Reversing lights.
    BackupLights,
    /// Left turn signal.
    LeftTurnSignal,
    /// Right turn signal.
    RightTurnSignal,
    /// Hazard lights.
    HazardLights,
}

impl Lamp {
    /// Every lamp the simulated vehicle has.
    pub const ALL: [Lamp; 8] = [
        Lamp::Headlights,
        Lamp::HighBeams,
        Lamp::RunningLights,
        Lamp::BrakeLights,
        Lamp::BackupLights,
        Lamp::LeftTurnSignal,
        Lamp::RightTurnSignal,
        Lamp::HazardLights,
    ];
}

/// Which of the vehicle's lamps are on (all off at first).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Lights {
    on: BTreeSet<Lamp>,
}

impl Lights {
    /// Whether `lamp` is on.
    pub fn is_on(&self, lamp: Lamp) -> bool {
        self.on.contains(&lamp)
    }

    /// Turns `lamp` on or off.
    pub fn set(&mut self, lamp: Lamp, on: bool) {
        if on {
            self.on.insert(lamp);
        } else {
            self.on.remove(&lamp);
        }
    }

    /// The lamps on, in [`Lamp`] order.
    pub fn on(&self) -> impl Iterator<Item = Lamp> + '_ {
        self.on.iter().copied()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lamps_switch_on_and_off() {
        let mut l = Lights::default();
        assert!(Lamp::ALL.iter().all(|x| !l.is_on(*x)));
        l.set(Lamp::Headlights, true);
        l.set(Lamp::HazardLights, true);
        l.set(Lamp::HazardLights, false);
        assert_eq!(l.on().collect::<Vec<_>>(), vec![Lamp::Headlights]);
    }
}
