//! Seeds the `packet` fuzz target's corpus with the demos' traffic (issue 17): up to three
//! packets (header + body) per command code from the vehicle demo and the arm demo, as
//! they crossed the in-process bus. Run by hand when the demos change:
//!
//! `cargo test -p jaus-tests --test fuzz_seeds -- --ignored`
//!
//! (then `cargo fuzz cmin packet` in `fuzz/`, see fuzz/README.md).

use std::collections::BTreeMap;
use std::path::Path;
use std::time::{Duration, Instant};

use jaus::codec::Encode;

fn seeds_from(bus: &jaus::component::local::LocalBus, out: &mut BTreeMap<u16, Vec<Vec<u8>>>) {
    for d in bus.trace() {
        let Some(m) = &d.message else { continue };
        let Ok(body) = m.to_bytes() else { continue };
        let Ok(h) = d.header.encode_with_size(body.len()) else {
            continue;
        };
        let packet = [h.as_slice(), &body].concat();
        let list = out.entry(d.header.command_code.0).or_default();
        if list.len() < 3 && !list.contains(&packet) {
            list.push(packet);
        }
    }
}

#[test]
#[ignore = "writes fuzz/corpus/packet; run by hand"]
fn write_demo_traffic_seeds() {
    let mut seeds = BTreeMap::new();
    let t0 = Instant::now();
    let (bus, _) = jaus_sim::demo::build(t0, &jaus_sim::demo::Options::default());
    let mut bus = bus.with_trace(500_000);
    bus.run_for(Duration::from_secs(120));
    seeds_from(&bus, &mut seeds);
    let (arm, _) = jaus_sim::arm_demo::build(t0, &jaus_sim::arm_demo::ArmOptions::default());
    let mut arm = arm.with_trace(500_000);
    arm.run_for(Duration::from_secs(40));
    seeds_from(&arm, &mut seeds);
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/corpus/packet");
    std::fs::create_dir_all(&dir).unwrap();
    let mut n = 0;
    for (code, list) in &seeds {
        for (i, p) in list.iter().enumerate() {
            std::fs::write(dir.join(format!("demo-{code:04x}-{i}")), p).unwrap();
            n += 1;
        }
    }
    println!(
        "{n} seeds of {} command codes written to {}",
        seeds.len(),
        dir.display()
    );
}
