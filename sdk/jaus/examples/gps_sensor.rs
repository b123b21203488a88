//! A Global Pose Sensor fed by a (fake) GPS receiver: the only code a vendor writes.
//! An operator subscribes to Report Global Pose at 5 Hz; everything else (status,
//! control, heartbeat, service connections, events) is the component runtime's.
//!
//! Run: `cargo run -p jaus --example gps_sensor`

use std::time::{Duration, Instant};

use jaus::component::local::{LocalBus, Probe};
use jaus::component::{Config, InitError, Refused};
use jaus::components::global_pose_sensor::{self, Ctx, GlobalPoseSensor};
use jaus::messages::{CreateServiceConnection, Message, QueryGlobalPose, ReportGlobalPose};
use jaus::Address;

/// Stand-in for a serial GPS receiver: drives north-east at about 1 m/s.
struct FakeGps {
    start: Option<Instant>,
}

impl FakeGps {
    fn fix(&self, now: Instant) -> (f64, f64, f64) {
        let t = self.start.map_or(0.0, |s| (now - s).as_secs_f64());
        (29.6436 + t * 6.4e-6, -82.3549 + t * 7.3e-6, 41.0)
    }
}

impl GlobalPoseSensor for FakeGps {
    fn initialize(&mut self, ctx: &mut Ctx<'_>) -> Result<(), InitError> {
        self.start = Some(ctx.now()); // open the serial port here
        Ok(())
    }

    fn on_query_global_pose(
        &mut self,
        ctx: &mut Ctx<'_>,
        query: &QueryGlobalPose,
    ) -> Result<ReportGlobalPose, Refused> {
        let (lat, lon, elevation) = self.fix(ctx.now());
        let want = |bit: u16| query.presence_vector & (1 << bit) != 0;
        Ok(ReportGlobalPose {
            latitude: want(0).then_some(lat),
            longitude: want(1).then_some(lon),
            elevation: want(2).then_some(elevation),
            ..Default::default()
        })
    }
}

fn main() {
    let (gps, ocu) = (Address::new(1, 1, 38, 1), Address::new(1, 2, 40, 1));
    let t0 = Instant::now();
    let mut bus = LocalBus::new(t0);
    let sensor = FakeGps { start: None };
    bus.add(global_pose_sensor::component(
        gps,
        sensor,
        Config::default(),
        t0,
    ));
    bus.add(Probe::new(ocu));

    let subscribe = CreateServiceConnection {
        service_connection_command_code: 0x4402,
        requested_periodic_update_rate: 5.0,
        presence_vector: 0b111,
    };
    bus.send(ocu, gps, subscribe);
    bus.run_for(Duration::from_secs(2)); // virtual time: returns at once

    let probe: &Probe = bus.get(ocu).expect("operator on the bus");
    for r in probe.received() {
        let t = (r.at - t0).as_secs_f64();
        match &r.message {
            Message::ReportGlobalPose(p) => println!(
                "{t:6.3} s  #{:<3} lat {:.7}  lon {:.7}  elev {:.1} m",
                r.header.sequence_number,
                p.latitude.unwrap_or(f64::NAN),
                p.longitude.unwrap_or(f64::NAN),
                p.elevation.unwrap_or(f64::NAN)
            ),
            other => println!("{t:6.3} s  {}", other.name()),
        }
    }
}
