//! The full-packet codec timed the way `../shared/perf` times OpenJAUS 3.3, printing
//! the lines its `run_codec.sh` alternates and `summarize_codec.py` tabulates:
//!
//! ```text
//! rust <message> <encode|decode|decode_typed> <median ns> <min ns> <max ns>
//! ```
//!
//! encode = the 16-byte header and the body written into a reused buffer; decode = from
//! the datagram's bytes, header parse and body decode by command code into
//! `jaus::messages::Message` (the value dropped, as OpenJAUS destroys its message);
//! decode_typed = the same into the message's own type. These are the calls of the
//! README's first example: `Header::write_packet`, `PacketRef::parse`, then
//! `Message::decode` or `M::decode_body`. 11 runs of 200,000 iterations
//! (20,000 for the 3.5 kB VKS packet; `ITER_SCALE` scales both), as `ojcodec.c` does.
//!
//! `cargo run --release -p jaus --example codec_lines` times;
//! `cargo run --release -p jaus --example codec_lines -- hex > packets.hex` writes the
//! four reference packets (`name hex` lines) for `ojcodec`.

use jaus::messages::{
    Message, ReportGlobalPose, ReportVksObjects, SetGlobalPathSegment, SetWrenchEffort,
    VksAttribute, VksFeatureClass, VksObjectType, VksPoint, VksStoredObject,
};
use jaus::wire::HEADER_LEN;
use jaus::{Address, Header, JausMessage, PacketRef};
use std::hint::black_box;
use std::time::Instant;

const RUNS: usize = 11;

/// The reference Report VKS Objects of TARGETS.md: 10 polygons × 40 points, 3 feature
/// classes each.
fn vks() -> ReportVksObjects {
    ReportVksObjects {
        request_id: 9,
        object_count: 0,
        objects: Some(
            (0..10)
                .map(|o| VksStoredObject {
                    object_id: 1000 + o as u32,
                    object_type: VksObjectType::Polygon,
                    buffer: 2.5,
                    feature_classes: (0..3)
                        .map(|f| VksFeatureClass {
                            id: (10 * o + f) as u16,
                            attribute: VksAttribute::UnsignedInteger(123_456 + f as u32),
                        })
                        .collect(),
                    points: (0..40)
                        .map(|p| VksPoint {
                            latitude: 29.65 + 0.0001 * p as f64,
                            longitude: -82.32 - 0.0001 * o as f64,
                        })
                        .collect(),
                })
                .collect(),
        ),
    }
}

fn packets() -> Vec<(&'static str, Vec<u8>)> {
    let reference =
        |i: usize| jaus::hex::decode(jaus::json::REFERENCE_PACKETS[i].1).unwrap_or_default();
    let v = vks();
    let header = Header::new(
        ReportVksObjects::CODE,
        Address::new(1, 2, 3, 4),
        Address::new(5, 6, 7, 8),
    );
    let mut buf = vec![0u8; 8192];
    let n = header.write_packet(&v, &mut buf).unwrap_or(0);
    buf.truncate(n);
    vec![
        ("report_global_pose", reference(0)),
        ("set_wrench_effort", reference(1)),
        ("set_global_path_segment", reference(2)),
        ("report_vks_objects", buf),
    ]
}

fn report(name: &str, dir: &str, mut v: Vec<f64>) {
    v.sort_by(f64::total_cmp);
    println!(
        "rust {name} {dir} {:.1} {:.1} {:.1}",
        v[RUNS / 2],
        v[0],
        v[RUNS - 1]
    );
}

fn time(iters: usize, mut f: impl FnMut()) -> Vec<f64> {
    for _ in 0..iters / 10 {
        f();
    }
    (0..RUNS)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..iters {
                f();
            }
            t.elapsed().as_nanos() as f64 / iters as f64
        })
        .collect()
}

fn bench<M: JausMessage>(name: &str, bytes: &[u8], iters: usize) {
    let Ok(p) = PacketRef::parse(bytes) else {
        eprintln!("{name}: not a packet");
        std::process::exit(1);
    };
    let header = p.header;
    let Ok(msg) = M::decode_body(p.body) else {
        eprintln!("{name}: does not decode");
        std::process::exit(1);
    };
    let mut out = vec![0u8; 8192];
    // Same bytes back.
    let n = header.write_packet(&msg, &mut out).unwrap_or(0);
    if out[..n] != *bytes {
        eprintln!("{name}: re-encoded packet differs");
        std::process::exit(1);
    }
    report(
        name,
        "encode",
        time(iters, || {
            let n = black_box(&header)
                .write_packet(black_box(&msg), &mut out)
                .unwrap_or(0);
            black_box(out[n.min(HEADER_LEN + 4)]);
        }),
    );
    report(
        name,
        "decode",
        time(iters, || {
            if let Ok(p) = PacketRef::parse(black_box(bytes)) {
                let m = Message::decode(p.header.command_code, p.body);
                black_box(&m);
            }
        }),
    );
    report(
        name,
        "decode_typed",
        time(iters, || {
            if let Ok(p) = PacketRef::parse(black_box(bytes)) {
                let m = M::decode_body(p.body);
                black_box(&m);
            }
        }),
    );
}

fn main() {
    let packets = packets();
    if std::env::args().nth(1).as_deref() == Some("hex") {
        for (name, bytes) in &packets {
            println!("{name} {}", jaus::hex::encode(bytes));
        }
        return;
    }
    let scale: f64 = std::env::var("ITER_SCALE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1.0);
    let (n, nv) = ((200_000.0 * scale) as usize, (20_000.0 * scale) as usize);
    bench::<ReportGlobalPose>(packets[0].0, &packets[0].1, n);
    bench::<SetWrenchEffort>(packets[1].0, &packets[1].1, n);
    bench::<SetGlobalPathSegment>(packets[2].0, &packets[2].1, n);
    bench::<ReportVksObjects>(packets[3].0, &packets[3].1, nv);
}
