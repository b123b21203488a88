//! The Illumination service, hosted natively over a vehicle's lights ([`Lights`], the
//! small hardware trait a vendor implements): RA 3.3 has no lights, so this service
//! does not go through the gateway's RA 3.3 side. It is the generated `Hosted` adapter
//! (a [`GeneratedService`](crate::service::GeneratedService)) over its own guards and
//! actions ([`Illumination`]), on its generated machines (`defs/ugv_services.yaml`), so any AS-4 component hosts it
//! (`As4Component::with_service`, or beside a gateway's services with
//! [`crate::gateway::DualNode::with_service`]).
//!
//! * Query Illumination Configuration: the lights [`Lights::supported`] names.
//! * Query Illumination State: the lights [`Lights::state`] reads, any client.
//! * Set Illumination State: from the controlling client (the machine's
//!   `isControllingClient`), in any of the component's controlled states; refused
//!   (`isSupported`) when it turns on a light the vehicle does not have, or gives a
//!   level to a variable light it does not have, and then nothing changes. Taken, the
//!   state given is handed to [`Lights::set`] whole: each light on or off as given.

use std::fmt;

use crate::messages::services::illumination_service as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::{
    IlluminationState, QueryIlluminationConfiguration, QueryIlluminationState,
    ReportIlluminationConfiguration, ReportIlluminationState, SetIlluminationState,
    SupportedIllumination,
};
use crate::service::Outbox;

/// A vehicle's lights, as the Illumination service drives them (sans-IO: the vendor's
/// implementation reaches its hardware; the simulator's is its model's lamps).
pub trait Lights: fmt::Debug + Send + 'static {
    /// Which lights the vehicle has.
    fn supported(&self) -> SupportedIllumination;

    /// Which lights are on now (the levels of the variable ones).
    fn state(&self) -> IlluminationState;

    /// Turns the lights on and off as `state` gives (only lights [`Self::supported`]
    /// names are ever on in it).
    fn set(&mut self, state: IlluminationState);
}

/// The first light `state` turns on (or gives a level, for a variable light) that
/// `supported` does not name.
pub fn unsupported(
    supported: SupportedIllumination,
    state: &IlluminationState,
) -> Option<&'static str> {
    let s = supported;
    let asked = [
        ("headlights", state.headlights, s.headlights),
        (
            "left turn signal",
            state.left_turn_signal,
            s.left_turn_signal,
        ),
        (
            "right turn signal",
            state.right_turn_signal,
            s.right_turn_signal,
        ),
        ("running lights", state.running_lights, s.running_lights),
        ("brake lights", state.brake_lights, s.brake_lights),
        ("backup lights", state.backup_lights, s.backup_lights),
        (
            "visible light source",
            state.visible_light_source,
            s.visible_light_source,
        ),
        (
            "infrared light source",
            state.ir_light_source,
            s.ir_light_source,
        ),
        (
            "variable light 1",
            state.variable_light1 > 0,
            s.variable_light1,
        ),
        (
            "variable light 2",
            state.variable_light2 > 0,
            s.variable_light2,
        ),
        (
            "variable light 3",
            state.variable_light3 > 0,
            s.variable_light3,
        ),
        (
            "variable light 4",
            state.variable_light4 > 0,
            s.variable_light4,
        ),
        ("high beams", state.high_beams, s.high_beams),
        ("parking lights", state.parking_lights, s.parking_lights),
        ("fog lights", state.fog_lights, s.fog_lights),
        ("hazard lights", state.hazard_lights, s.hazard_lights),
    ];
    asked
        .into_iter()
        .find(|(_, on, has)| *on && !*has)
        .map(|(name, _, _)| name)
}

/// The Illumination service's own guards and actions over the lights `L` (the
/// inherited ones run on the component's Core).
#[derive(Debug)]
pub struct Illumination<L> {
    lights: L,
    outbox: Outbox,
}

impl<L> Illumination<L> {
    /// The lights.
    pub fn lights(&self) -> &L {
        &self.lights
    }
}

impl<L> AsMut<Outbox> for Illumination<L> {
    fn as_mut(&mut self) -> &mut Outbox {
        &mut self.outbox
    }
}

impl<L: Lights> generated::IlluminationService for Illumination<L> {
    fn is_supported(&self, msg: &SetIlluminationState) -> bool {
        unsupported(self.lights.supported(), &msg.illumination).is_none()
    }

    fn send_report_illumination_configuration(
        &mut self,
        _msg: &QueryIlluminationConfiguration,
        transport_data: &Receive,
    ) {
        let supported = self.lights.supported();
        self.outbox.reply(
            transport_data,
            &ReportIlluminationConfiguration { supported },
        );
    }

    fn send_report_illumination_state(
        &mut self,
        _msg: &QueryIlluminationState,
        transport_data: &Receive,
    ) {
        let illumination = self.lights.state();
        self.outbox
            .reply(transport_data, &ReportIlluminationState { illumination });
    }

    fn set_illumination_state(&mut self, msg: &SetIlluminationState) {
        // Only supported lights (the guard): the reserved bits are not passed on.
        let illumination = IlluminationState {
            reserved: 0,
            ..msg.illumination
        };
        self.lights.set(illumination);
    }
}

/// The Illumination service over the lights `L` on its generated machines: the
/// generated `Hosted` adapter, a [`GeneratedService`] any AS-4 component hosts.
///
/// [`GeneratedService`]: crate::service::GeneratedService
pub type IlluminationService<L> = generated::Hosted<Illumination<L>>;

impl<L: Lights> generated::Hosted<Illumination<L>> {
    /// The service over `lights`, its machines not started (they follow the Core's at
    /// the first message).
    pub fn over(lights: L) -> Self {
        Self::new(Illumination {
            lights,
            outbox: Outbox::new(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_light_or_a_level_the_vehicle_lacks_is_named() {
        let has = SupportedIllumination {
            headlights: true,
            variable_light2: true,
            ..Default::default()
        };
        let on = |f: fn(&mut IlluminationState)| {
            let mut s = IlluminationState::default();
            f(&mut s);
            s
        };
        assert_eq!(unsupported(has, &IlluminationState::default()), None);
        assert_eq!(unsupported(has, &on(|s| s.headlights = true)), None);
        assert_eq!(unsupported(has, &on(|s| s.variable_light2 = 7)), None);
        assert_eq!(
            unsupported(has, &on(|s| s.fog_lights = true)),
            Some("fog lights")
        );
        assert_eq!(
            unsupported(has, &on(|s| s.variable_light1 = 1)),
            Some("variable light 1")
        );
    }
}
