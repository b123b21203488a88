//! Encode/decode speed of the TARGETS.md reference packets.
//!
//! Encode = serialise the body into a preallocated buffer; decode = parse the body into
//! the typed message. Run: `cargo bench -p jaus --bench codec`.

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use jaus::codec::{Decode, Encode, Writer};
use jaus::messages::{ReportGlobalPose, SetGlobalPathSegment, SetWrenchEffort};

fn body(i: usize) -> Vec<u8> {
    jaus::hex::decode(jaus::json::REFERENCE_PACKETS[i].1).unwrap()[16..].to_vec()
}

fn bench_one<M: Encode + Decode>(c: &mut Criterion, name: &str, body: &[u8]) {
    let msg = M::from_bytes(body).unwrap();
    let mut buf = [0u8; 64];
    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Bytes(body.len() as u64 + 16));
    g.bench_function("encode", |b| {
        b.iter(|| {
            let mut w = Writer::new(&mut buf);
            black_box(&msg).encode(&mut w).unwrap();
            black_box(w.position())
        })
    });
    g.bench_function("decode", |b| {
        b.iter(|| M::from_bytes(black_box(body)).unwrap())
    });
    g.finish();
}

fn codec(c: &mut Criterion) {
    bench_one::<ReportGlobalPose>(c, "report_global_pose", &body(0));
    bench_one::<SetWrenchEffort>(c, "set_wrench_effort", &body(1));
    bench_one::<SetGlobalPathSegment>(c, "set_global_path_segment", &body(2));
}

criterion_group!(benches, codec);
criterion_main!(benches);
