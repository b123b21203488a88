//! The simulated vehicle's lamps (`jaus_sim::lights`) as the lights of an AS-4
//! Illumination service (`jaus_as4::ugv::Lights`): the adapter between the two crates,
//! which know nothing of each other. `host: [vehicle]` with `as4:` hosts the service on
//! the gateway's component over them.

use jaus_as4::messages::{IlluminationState, SupportedIllumination};
use jaus_sim::{Lamp, SimVehicle};

/// The lamps of a simulated vehicle, as `jaus_as4::ugv::Lights`: headlights, high
/// beams, running, brake and backup lights, the turn signals and the hazard lights
/// (no visible or infrared light source, no variable lights, no parking or fog lights).
#[derive(Debug, Clone)]
pub struct SimLights(pub SimVehicle);

/// Whether `lamp`'s bit is set in `s`.
fn lit(s: &IlluminationState, lamp: Lamp) -> bool {
    match lamp {
        Lamp::Headlights => s.headlights,
        Lamp::HighBeams => s.high_beams,
        Lamp::RunningLights => s.running_lights,
        Lamp::BrakeLights => s.brake_lights,
        Lamp::BackupLights => s.backup_lights,
        Lamp::LeftTurnSignal => s.left_turn_signal,
        Lamp::RightTurnSignal => s.right_turn_signal,
        Lamp::HazardLights => s.hazard_lights,
    }
}

/// Sets `lamp`'s bit of `s` to `on`.
fn light(s: &mut IlluminationState, lamp: Lamp, on: bool) {
    let bit = match lamp {
        Lamp::Headlights => &mut s.headlights,
        Lamp::HighBeams => &mut s.high_beams,
        Lamp::RunningLights => &mut s.running_lights,
        Lamp::BrakeLights => &mut s.brake_lights,
        Lamp::BackupLights => &mut s.backup_lights,
        Lamp::LeftTurnSignal => &mut s.left_turn_signal,
        Lamp::RightTurnSignal => &mut s.right_turn_signal,
        Lamp::HazardLights => &mut s.hazard_lights,
    };
    *bit = on;
}

impl jaus_as4::ugv::Lights for SimLights {
    fn supported(&self) -> SupportedIllumination {
        // The bits of the lamps the model has (`Lamp::ALL`), from a state with all on.
        let mut all = IlluminationState::default();
        for lamp in Lamp::ALL {
            light(&mut all, lamp, true);
        }
        SupportedIllumination {
            headlights: all.headlights,
            left_turn_signal: all.left_turn_signal,
            right_turn_signal: all.right_turn_signal,
            running_lights: all.running_lights,
            brake_lights: all.brake_lights,
            backup_lights: all.backup_lights,
            high_beams: all.high_beams,
            hazard_lights: all.hazard_lights,
            ..Default::default()
        }
    }

    fn state(&self) -> IlluminationState {
        let v = self.0.lock();
        let mut s = IlluminationState::default();
        for lamp in v.lights().on() {
            light(&mut s, lamp, true);
        }
        s
    }

    fn set(&mut self, state: IlluminationState) {
        let mut v = self.0.lock();
        for lamp in Lamp::ALL {
            v.lights_mut().set(lamp, lit(&state, lamp));
        }
    }
}

#[cfg(test)]
mod tests {
    use jaus_as4::ugv::Lights;
    use jaus_sim::VehicleParams;

    use super::*;

    #[test]
    fn the_models_lamps_read_and_switch_as_illumination_bits() {
        let vehicle = SimVehicle::new(VehicleParams::default());
        let mut l = SimLights(vehicle.clone());
        let has = l.supported();
        assert!(has.headlights && has.hazard_lights && has.high_beams);
        assert!(!(has.fog_lights || has.ir_light_source || has.variable_light1));
        assert_eq!(l.state(), IlluminationState::default());
        l.set(IlluminationState {
            headlights: true,
            left_turn_signal: true,
            ..Default::default()
        });
        assert!(vehicle.lock().lights().is_on(Lamp::Headlights));
        assert!(vehicle.lock().lights().is_on(Lamp::LeftTurnSignal));
        assert!(!vehicle.lock().lights().is_on(Lamp::HazardLights));
        let s = l.state();
        assert!(s.headlights && s.left_turn_signal && !s.right_turn_signal);
        l.set(IlluminationState::default());
        assert_eq!(vehicle.lock().lights().on().count(), 0);
    }
}
