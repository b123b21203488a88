//! The Mission Spooler accepting and starting a 10,000-task mission: Spool Mission and
//! Run Mission handed to the component (decoded, validated, stored) until the first
//! message leaves for its destination. Median of 30 runs.
//!
//! `cargo bench -p jaus --bench spooler`

use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::component::{Config, ControlPolicy};
use jaus::components::mission_spooler;
use jaus::messages::*;
use jaus::stock::spooler::{command, SpoolerConfig, StockMissionSpooler};
use jaus::{Address, Header, JausMessage};

const MS: Address = Address::new(1, 1, 36, 1);
const OCU: Address = Address::new(1, 2, 40, 1);
const DEST: Address = Address::new(1, 1, 200, 1);

fn mission(tasks: u16) -> SpoolMission {
    let children = (1..=tasks)
        .map(|t| MissionTask {
            task_id: t,
            child_count: 0,
            child_offsets: Vec::new(),
            messages: vec![command(
                t,
                MS,
                DEST,
                &SetDiscreteDevices {
                    gear: Some((t % 200) as u8),
                    ..Default::default()
                }
                .into(),
                false,
            )
            .unwrap()],
            children: Vec::new(),
        })
        .collect::<Vec<_>>();
    SpoolMission {
        mission_id: 1,
        append_flag: 0,
        root: MissionTask {
            task_id: 0,
            child_count: tasks,
            child_offsets: vec![0; usize::from(tasks)],
            messages: Vec::new(),
            children,
        },
    }
}

fn main() {
    let m = mission(10_000);
    let body = m.to_bytes().unwrap();
    let run = RunMission { mission_id: 1 }.to_bytes().unwrap();
    println!("Spool Mission of 10,000 tasks: {} bytes", body.len());
    let mut times = Vec::new();
    for _ in 0..30 {
        let t0 = Instant::now();
        let cfg = Config {
            control: ControlPolicy::Open,
            ..Config::default()
        };
        let spooler = StockMissionSpooler::new(SpoolerConfig {
            probe_timeout: Duration::ZERO,
            ..SpoolerConfig::default()
        });
        let mut c = mission_spooler::component(MS, spooler, cfg, t0);
        c.handle_timeout(t0);
        c.handle_message(t0, &Header::new(Resume::CODE, MS, OCU), &Resume {}.into());
        // The destination is probed first (a zero probe timeout: raw delivery at once).
        c.handle_timeout(t0);
        while c.poll_transmit().is_some() {}
        let start = Instant::now();
        c.handle(t0, &Header::new(SpoolMission::CODE, MS, OCU), &body);
        c.handle(t0, &Header::new(RunMission::CODE, MS, OCU), &run);
        let mut first = None;
        for _ in 0..4 {
            c.handle_timeout(t0 + Duration::from_millis(1));
            while let Some(t) = c.poll_transmit() {
                if t.header.destination == DEST && first.is_none() {
                    first = Some(start.elapsed());
                }
            }
            if first.is_some() {
                break;
            }
        }
        times.push(first.expect("the first message left"));
    }
    times.sort();
    println!(
        "accept + start a 10,000-task mission: median {:.2} ms, min {:.2} ms, max {:.2} ms (target ≤ 10 ms)",
        times[15].as_secs_f64() * 1e3,
        times[0].as_secs_f64() * 1e3,
        times[29].as_secs_f64() * 1e3
    );
}
