//! The AS-4 Illumination service hosted natively beside the gateway's services
//! (`jaus_as4::ugv::IlluminationService` over the `jaus_as4::ugv::Lights` of the
//! simulated vehicle's lamps, `jaus_node::SimLights`): RA 3.3 has no lights, so no RA
//! 3.3 component stands behind it. An AS-4 client of the demo vehicle asks which lights
//! it has, switches them only while it controls the component, a light the vehicle lacks
//! refused, and reads them back, from the service and from the simulated model. The
//! same service comes with `host: [vehicle]` and `as4:` in a node file, as `jaus node`
//! runs it.

use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;
use jaus_as4::ugv::IlluminationService;
use jaus_as4::{
    IlluminationState, Message, QueryIlluminationConfiguration, QueryIlluminationState,
    ReleaseControl, SetIlluminationState,
};
use jaus_node::{NodeFile, SimLights};
use jaus_sim::{Lamp, SimVehicle};

mod common;
use common::as4::As4Rig;

const VEHICLE: As4Id = As4Id::new(1, 1, 1);
const WAIT: Duration = Duration::from_millis(500);

struct Rig(As4Rig);

impl Rig {
    /// The demo vehicle behind its gateway, the Illumination service over its lamps;
    /// the vehicle's model.
    fn demo() -> (Self, SimVehicle) {
        let t0 = Instant::now();
        let (node, vehicle) = As4Rig::demo_vehicle_node(t0, None);
        let lights = IlluminationService::over(SimLights(vehicle.clone()));
        let rig = As4Rig::hosting(
            t0,
            node,
            vec![Box::new(lights)],
            VEHICLE,
            "demo vehicle",
            Duration::from_secs(3),
        );
        (Rig(rig), vehicle)
    }

    fn one(&mut self, m: impl Into<Message>) -> Message {
        self.0.one_within(m, WAIT)
    }

    fn lights(&mut self) -> IlluminationState {
        match self.one(QueryIlluminationState {}) {
            Message::ReportIlluminationState(r) => r.illumination,
            other => panic!("{other:?}"),
        }
    }

    /// Sends Set Illumination State; nothing comes back (taken or refused).
    fn switch(&mut self, illumination: IlluminationState) {
        let got = self.0.ask(SetIlluminationState { illumination }, WAIT);
        assert!(got.is_empty(), "{got:?}");
    }

    fn refused(&self) -> u64 {
        self.0.refused()
    }
}

fn headlights_and_left() -> IlluminationState {
    IlluminationState {
        headlights: true,
        left_turn_signal: true,
        ..Default::default()
    }
}

fn on(vehicle: &SimVehicle) -> Vec<Lamp> {
    vehicle.lock().lights().on().collect()
}

#[test]
fn the_controlling_client_switches_the_simulated_vehicles_lights() {
    let (mut r, vehicle) = Rig::demo();
    let uris = r.0.service_uris();
    assert!(
        uris.iter()
            .any(|u| u == "urn:jaus:jss:ugv:IlluminationService"),
        "{uris:?}"
    );
    let Message::ReportIlluminationConfiguration(c) = r.one(QueryIlluminationConfiguration {})
    else {
        panic!("no Report Illumination Configuration");
    };
    let has = c.supported;
    assert!(has.headlights && has.high_beams && has.hazard_lights);
    assert!(has.left_turn_signal && has.right_turn_signal && has.brake_lights);
    assert!(!(has.fog_lights || has.parking_lights || has.ir_light_source));
    assert!(!(has.variable_light1 || has.variable_light4));
    assert_eq!(r.lights(), IlluminationState::default());

    // Without control: refused, all off.
    let refused = r.refused();
    r.switch(headlights_and_left());
    assert_eq!(r.refused(), refused + 1);
    assert_eq!(r.lights(), IlluminationState::default());
    assert!(on(&vehicle).is_empty());

    // The controller switches them on, read back from the service and the model.
    r.0.take_control();
    r.switch(headlights_and_left());
    assert_eq!(r.lights(), headlights_and_left());
    assert_eq!(on(&vehicle), vec![Lamp::Headlights, Lamp::LeftTurnSignal]);

    // Fog lights the vehicle does not have, a level for a variable light: refused,
    // nothing changes.
    for lacking in [
        IlluminationState {
            fog_lights: true,
            ..IlluminationState::default()
        },
        IlluminationState {
            variable_light2: 5,
            ..headlights_and_left()
        },
    ] {
        let refused = r.refused();
        r.switch(lacking);
        assert_eq!(r.refused(), refused + 1);
        assert_eq!(r.lights(), headlights_and_left());
    }

    // The state given is the state: hazards on, the rest off.
    let hazards = IlluminationState {
        hazard_lights: true,
        ..Default::default()
    };
    r.switch(hazards);
    assert_eq!(r.lights(), hazards);
    assert_eq!(on(&vehicle), vec![Lamp::HazardLights]);

    // Control released: refused again.
    r.0.ask(ReleaseControl {}, WAIT);
    let refused = r.refused();
    r.switch(IlluminationState::default());
    assert_eq!(r.refused(), refused + 1);
    assert_eq!(on(&vehicle), vec![Lamp::HazardLights]);
}

#[test]
fn a_node_file_hosting_the_vehicle_offers_illumination_on_its_gateway() {
    let dir = std::env::temp_dir().join(format!("jaus-as4-lights-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("vehicle.yaml");
    std::fs::write(
        &path,
        "subsystem: 1\nnode: 1\nbind: 127.0.0.1:3794\nhost: [vehicle]\nas4: { name: demo vehicle }\n",
    )
    .unwrap();
    let file = NodeFile::load(&path).unwrap();
    assert!(file.as4_config().is_some());
    let t0 = Instant::now();
    let (node, native) = file.build_node_and_as4(&path, t0).unwrap();
    assert_eq!(
        native.len(),
        2,
        "Illumination over the vehicle's lamps, the Range Sensor over its scanner"
    );
    let mut r = Rig(As4Rig::hosting(
        t0,
        node,
        native,
        VEHICLE,
        "demo vehicle",
        Duration::from_secs(3),
    ));
    let uris = r.0.service_uris();
    for want in [
        "urn:jaus:jss:ugv:IlluminationService",
        "urn:jaus:jss:ugv:AnnunciatorService",
        "urn:jaus:jss:ugv:ParkingBrakeDriver",
    ] {
        assert_eq!(
            uris.iter().filter(|u| *u == want).count(),
            1,
            "{want} once in {uris:?}"
        );
    }
    r.0.take_control();
    r.switch(headlights_and_left());
    assert_eq!(r.lights(), headlights_and_left());
    let _ = std::fs::remove_dir_all(&dir);
}
