//! Throughput of large messages: Report VKS Objects with many polygons, and Spool
//! Mission with a large task tree. Run: `cargo bench -p jaus --bench large`.
//! Criterion reports time per message and bytes per second (MB/s).

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use jaus::codec::{Decode, Encode, Writer};
use jaus::messages::{
    MissionCommand, MissionTask, ReportVksObjects, SpoolMission, VksAttribute, VksFeatureClass,
    VksObjectType, VksPoint, VksStoredObject,
};
use jaus::{Address, CommandCode, Header, Packet};

/// `polygons` polygons of `points` vertices with `classes` feature classes each — the
/// reference message (docs/performance.md) is `vks(10, 40, 3)`.
fn vks(polygons: usize, points: usize, classes: usize) -> ReportVksObjects {
    ReportVksObjects {
        request_id: 9,
        object_count: 0,
        objects: Some(
            (0..polygons)
                .map(|o| VksStoredObject {
                    object_id: 1000 + o as u32,
                    object_type: VksObjectType::Polygon,
                    buffer: 2.5,
                    feature_classes: (0..classes)
                        .map(|f| VksFeatureClass {
                            id: (10 * o + f) as u16,
                            attribute: VksAttribute::UnsignedInteger(123_456 + f as u32),
                        })
                        .collect(),
                    points: (0..points)
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

/// A mission of `tasks` tasks: a root with children of `fanout` children each, every
/// task holding one blocking Set Travel Speed.
fn mission(tasks: usize, fanout: usize) -> SpoolMission {
    let header = Header::new(
        CommandCode(0x040A),
        Address::new(1, 1, 45, 1),
        Address::new(1, 1, 36, 1),
    );
    let leaf = |id: usize| MissionTask {
        task_id: id as u16,
        child_count: 0,
        child_offsets: Vec::new(),
        messages: vec![MissionCommand {
            uid: id as u16,
            message: Packet::new(header, vec![0x10, 0x27]),
            blocking: 1,
        }],
        children: Vec::new(),
    };
    // Breadth-first ids; build bottom-up.
    fn build(
        id: usize,
        tasks: usize,
        fanout: usize,
        leaf: &dyn Fn(usize) -> MissionTask,
    ) -> MissionTask {
        let mut t = leaf(id);
        t.children = (1..=fanout)
            .map(|k| id * fanout + k)
            .filter(|c| *c < tasks)
            .map(|c| build(c, tasks, fanout, leaf))
            .collect();
        t.child_count = t.children.len() as u16;
        t
    }
    SpoolMission {
        mission_id: 7,
        append_flag: 0,
        root: build(0, tasks, fanout, &leaf),
    }
}

fn bench_msg<M: Encode + Decode>(c: &mut Criterion, name: &str, msg: &M) {
    let bytes = msg.to_bytes().unwrap();
    let mut buf = vec![0u8; bytes.len()];
    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Bytes(bytes.len() as u64));
    g.bench_function("encode", |b| {
        b.iter(|| {
            let mut w = Writer::new(&mut buf);
            black_box(msg).encode(&mut w).unwrap();
            black_box(w.position())
        })
    });
    g.bench_function("decode", |b| {
        b.iter(|| M::from_bytes(black_box(&bytes)).unwrap())
    });
    g.finish();
}

fn large(c: &mut Criterion) {
    let reference = vks(10, 40, 3);
    assert_eq!(
        reference.to_bytes().unwrap().len() + 16,
        3550,
        "the reference packet size"
    );
    bench_msg(c, "report_vks_objects_10x40", &reference);
    bench_msg(c, "report_vks_objects_1000x100", &vks(1000, 100, 3));
    bench_msg(c, "spool_mission_1000_tasks", &mission(1000, 4));
}

criterion_group!(benches, large);
criterion_main!(benches);
