//! A vendor implements a generated trait and gets a running component.
use std::time::{Duration, Instant};

use jaus::component::local::{LocalBus, Probe};
use jaus::component::{Config, Refused};
use jaus::components::global_pose_sensor::{self, Ctx, GlobalPoseSensor};
use jaus::messages::{Message, QueryGlobalPose, ReportGlobalPose};
use jaus::Address;

struct Gps;

impl GlobalPoseSensor for Gps {
    fn on_query_global_pose(
        &mut self,
        _ctx: &mut Ctx<'_>,
        _q: &QueryGlobalPose,
    ) -> Result<ReportGlobalPose, Refused> {
        Ok(ReportGlobalPose { latitude: Some(10.0), ..Default::default() })
    }
}

fn main() {
    let t0 = Instant::now();
    let (gps, ocu) = (Address::new(1, 1, 38, 1), Address::new(1, 2, 40, 1));
    let mut bus = LocalBus::new(t0);
    bus.add(global_pose_sensor::component(gps, Gps, Config::default(), t0));
    bus.add(Probe::new(ocu));
    bus.send(ocu, gps, QueryGlobalPose { presence_vector: 1 });
    bus.run_for(Duration::from_millis(10));
    let p: &Probe = bus.get(ocu).unwrap();
    assert!(p.messages().any(|m| matches!(m, Message::ReportGlobalPose(r) if r.latitude.is_some())));
}
