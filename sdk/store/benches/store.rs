//! Bulk insert of 10,000 World Model objects and a region query, in memory and with
//! the store on, side by side (docs/performance.md):
//! `cargo bench -p jaus-store --bench store`.
//!
//! * insert: 10,000 points stored as one Create VKS Objects would (`create_all`), and
//!   with the store on also committed (one durable write transaction), or as 100
//!   messages of 100 objects (100 transactions).
//! * query: a 0.01° square around the middle of the 1° grid the points fill; the store
//!   does not change queries (the index is in memory), so this is measured once on a
//!   store rebuilt from the database, to show it is the same index.
//! * restore: a World Model rebuilt from the 10,000 committed objects (read, decode,
//!   bulk index).

use std::path::PathBuf;
use std::sync::atomic::{AtomicU32, Ordering};

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use jaus::messages::{VksObject, VksObjectType, VksPoint};
use jaus::stock::world_model::{
    Filter, Geometry, Shape, StoreConfig, VectorStore, VksChange, VksJournal, WorldModelConfig,
};
use jaus_store::Store;

const N: usize = 10_000;

fn objects() -> Vec<VksObject> {
    (0..N)
        .map(|i| VksObject {
            object_type: VksObjectType::Point,
            buffer: None,
            feature_classes: vec![],
            points: vec![VksPoint {
                latitude: 30.0 + (i / 100) as f64 * 0.01,
                longitude: -80.0 + (i % 100) as f64 * 0.01,
            }],
        })
        .collect()
}

fn temp_store() -> (Store, PathBuf) {
    static NEXT: AtomicU32 = AtomicU32::new(0);
    let path = std::env::temp_dir().join(format!(
        "jaus-store-bench-{}-{}.jstore",
        std::process::id(),
        NEXT.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_file(&path);
    (Store::open(&path).expect("open the store"), path)
}

/// Stores `objs` in `batches` messages, committing each to `store` if given.
fn insert(objs: &[VksObject], batches: usize, store: Option<&Store>) -> VectorStore {
    let mut vs = VectorStore::new(StoreConfig::default());
    let mut journal = store.map(|s| s.vks_journal(1));
    for chunk in objs.chunks(objs.len().div_ceil(batches)) {
        let ids = vs.create_all(chunk);
        if let Some(j) = journal.as_mut() {
            let changes: Vec<VksChange> = ids
                .iter()
                .filter_map(|r| r.as_ref().ok())
                .filter_map(|id| vs.get(*id))
                .map(|o| VksChange::Created(o.clone()))
                .collect();
            j.commit(&changes).expect("commit");
        }
    }
    vs
}

fn region() -> Filter {
    let (lat, lon, h) = (30.5, -79.5, 0.005);
    Filter {
        region: Some(
            Geometry::new(
                Shape::Polygon,
                vec![
                    VksPoint {
                        latitude: lat - h,
                        longitude: lon - h,
                    },
                    VksPoint {
                        latitude: lat - h,
                        longitude: lon + h,
                    },
                    VksPoint {
                        latitude: lat + h,
                        longitude: lon + h,
                    },
                    VksPoint {
                        latitude: lat + h,
                        longitude: lon - h,
                    },
                ],
                0.0,
            )
            .expect("region"),
        ),
        ..Filter::default()
    }
}

fn bench(c: &mut Criterion) {
    let objs = objects();
    let mut g = c.benchmark_group("world_model_10k");
    g.sample_size(10);
    g.bench_function("insert/memory/1 message", |b| {
        b.iter(|| insert(&objs, 1, None))
    });
    g.bench_function("insert/store/1 message", |b| {
        b.iter_batched(
            temp_store,
            |(s, path)| {
                insert(&objs, 1, Some(&s));
                drop(s);
                let _ = std::fs::remove_file(path);
            },
            BatchSize::PerIteration,
        )
    });
    g.bench_function("insert/memory/100 messages", |b| {
        b.iter(|| insert(&objs, 100, None))
    });
    g.bench_function("insert/store/100 messages", |b| {
        b.iter_batched(
            temp_store,
            |(s, path)| {
                insert(&objs, 100, Some(&s));
                drop(s);
                let _ = std::fs::remove_file(path);
            },
            BatchSize::PerIteration,
        )
    });
    let filter = region();
    let memory = insert(&objs, 1, None);
    let (s, path) = temp_store();
    insert(&objs, 1, Some(&s));
    let restored = s
        .world_model(1, WorldModelConfig::default())
        .expect("restore");
    assert_eq!(
        memory.query(&filter),
        restored.store().query(&filter),
        "the same answer from both"
    );
    g.bench_function("query/memory", |b| b.iter(|| memory.query(&filter)));
    g.bench_function("query/store (restored)", |b| {
        b.iter(|| restored.store().query(&filter))
    });
    g.bench_function("restore/store", |b| {
        b.iter(|| {
            s.world_model(1, WorldModelConfig::default())
                .expect("restore")
        })
    });
    g.finish();
    drop(restored);
    drop(s);
    let _ = std::fs::remove_file(path);
}

criterion_group!(benches, bench);
criterion_main!(benches);
