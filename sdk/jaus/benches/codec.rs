//! Encode/decode speed of the reference packets (`jaus::json::REFERENCE_PACKETS`).
//!
//! Body only: encode = serialise the body into a preallocated buffer; decode = parse the
//! body into the typed message. Full packet (the method of ../shared/perf, to compare
//! with OpenJAUS): encode = the 16-byte header and the body into a reused buffer;
//! decode = from the datagram's bytes, header parse and body decode by command code
//! into `jaus::messages::Message` (and, for comparison, into the typed message); the
//! decoded value is kept alive through a reference and dropped, not copied out (a
//! by-value `black_box` of the 344-byte `Message` would time a memcpy), as
//! `examples/codec_lines.rs`, the side-by-side tool, does.
//! Run: `cargo bench -p jaus --bench codec`.

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use jaus::codec::{Decode, Encode, Writer};
use jaus::messages::{Message, ReportGlobalPose, SetGlobalPathSegment, SetWrenchEffort};
use jaus::wire::HEADER_LEN;
use jaus::{Header, JausMessage, PacketRef};

fn body(i: usize) -> Vec<u8> {
    jaus::hex::decode(jaus::json::REFERENCE_PACKETS[i].1).unwrap()[16..].to_vec()
}

fn packet(i: usize) -> Vec<u8> {
    jaus::hex::decode(jaus::json::REFERENCE_PACKETS[i].1).unwrap()
}

/// The full-packet path on reference packet `i`.
fn bench_packet<M: JausMessage>(c: &mut Criterion, name: &str, i: usize) {
    let bytes = packet(i);
    let header = Header::parse(&bytes).unwrap();
    let msg = M::from_bytes(&bytes[HEADER_LEN..]).unwrap();
    let mut buf = [0u8; 128];
    let mut g = c.benchmark_group(format!("{name}/packet"));
    g.throughput(Throughput::Bytes(bytes.len() as u64));
    g.bench_function("encode", |b| {
        b.iter(|| {
            black_box(&header)
                .write_packet(black_box(&msg), &mut buf)
                .unwrap()
        })
    });
    g.bench_function("header_parse", |b| {
        b.iter(|| PacketRef::parse(black_box(&bytes)).unwrap().header)
    });
    g.bench_function("decode_by_code", |b| {
        b.iter(|| {
            let p = PacketRef::parse(black_box(&bytes)).unwrap();
            let m = Message::decode(p.header.command_code, p.body);
            black_box(&m);
        })
    });
    g.bench_function("decode_typed", |b| {
        b.iter(|| {
            let p = PacketRef::parse(black_box(&bytes)).unwrap();
            let m = M::decode_body(p.body);
            black_box(&m);
        })
    });
    g.finish();
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
    bench_packet::<ReportGlobalPose>(c, "report_global_pose", 0);
    bench_packet::<SetWrenchEffort>(c, "set_wrench_effort", 1);
    bench_packet::<SetGlobalPathSegment>(c, "set_global_path_segment", 2);
}

criterion_group!(benches, codec);
criterion_main!(benches);
