//! The store on its own: round trips of every record, a World Model and a Mission
//! Spooler rebuilt from what was committed, a record that does not decode refused with
//! the file, table and key, and a transaction that never committed never loaded.

use std::path::PathBuf;
use std::sync::atomic::{AtomicU32, Ordering};

use jaus::messages::*;
use jaus::stock::spooler::{
    command, ItemState, MissionJournal, MissionMessage, MissionRecord, MissionState, SpoolerConfig,
};
use jaus::stock::world_model::{StoreConfig, VksChange, VksJournal, VksSnapshot, WorldModelConfig};
use jaus::Address;
use jaus_store::{record, Store, StoreError};

fn temp(name: &str) -> PathBuf {
    static NEXT: AtomicU32 = AtomicU32::new(0);
    let dir = std::env::temp_dir().join(format!(
        "jaus-store-test-{}-{}",
        std::process::id(),
        NEXT.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn object(id: u32, lat: f64) -> VksStoredObject {
    VksStoredObject {
        object_id: id,
        object_type: VksObjectType::Polygon,
        buffer: 2.5,
        feature_classes: vec![VksFeatureClass {
            id: 7,
            attribute: VksAttribute::Integer(id as i32),
        }],
        points: vec![
            VksPoint {
                latitude: lat,
                longitude: 10.0,
            },
            VksPoint {
                latitude: lat + 0.001,
                longitude: 10.0,
            },
            VksPoint {
                latitude: lat,
                longitude: 10.001,
            },
        ],
    }
}

/// `o` as it comes back from its wire encoding (the scaled fields quantised).
fn wire(o: &VksStoredObject) -> VksStoredObject {
    use jaus::codec::{Decode, Encode};
    VksStoredObject::from_bytes(&o.to_bytes().unwrap()).unwrap()
}

fn mission(id: u16) -> MissionRecord {
    let me = Address::new(1, 1, 36, 1);
    let to = Address::new(1, 1, 45, 1);
    let cmd = |uid, blocking| command(uid, me, to, &Message::from(Resume {}), blocking).unwrap();
    MissionRecord {
        mission_id: id,
        owner: Address::new(1, 2, 40, 1),
        state: MissionState::Running,
        cursor: 2,
        waiting: Some(2),
        paused_tasks: vec![5],
        aborted_tasks: vec![],
        parents: vec![(0, 0), (1, 0), (5, 1)],
        remote_started: vec![Address::new(2, 1, 36, 1)],
        messages: vec![
            MissionMessage {
                task: 1,
                state: ItemState::Finished,
                command: cmd(1, false),
            },
            MissionMessage {
                task: 1,
                state: ItemState::Sent,
                command: cmd(2, true),
            },
            MissionMessage {
                task: 5,
                state: ItemState::Pending,
                command: cmd(3, false),
            },
            MissionMessage {
                task: 5,
                state: ItemState::Removed,
                command: cmd(4, false),
            },
        ],
    }
}

#[test]
fn records_round_trip() {
    let o = wire(&object(9, 30.0));
    assert_eq!(
        record::decode_object(&record::encode_object(&o).unwrap()),
        Ok(o)
    );
    assert_eq!(
        record::decode_metadata(&record::encode_metadata("roads")),
        Ok("roads".to_string())
    );
    let m = mission(3);
    assert_eq!(
        record::decode_mission(3, &record::encode_mission(&m).unwrap()),
        Ok(m.clone())
    );
    // Every truncation of a mission record is refused with a reason, never a panic.
    let bytes = record::encode_mission(&m).unwrap();
    for n in 0..bytes.len() {
        assert!(record::decode_mission(3, &bytes[..n]).is_err(), "{n} bytes");
    }
    // Another format or kind is refused.
    let mut other = bytes.clone();
    other[0] = 2;
    assert!(record::decode_mission(3, &other)
        .unwrap_err()
        .contains("format 2"));
    assert!(record::decode_object(&bytes)
        .unwrap_err()
        .contains("kind 3"));
}

#[test]
fn a_world_model_is_rebuilt_with_its_ids_and_metadata() {
    let path = temp("wm.jstore");
    {
        let s = Store::open(&path).unwrap();
        let mut j = s.vks_journal(1);
        let created: Vec<VksChange> = (1..=50)
            .map(|i| VksChange::Created(wire(&object(i, 30.0 + f64::from(i) * 0.01))))
            .collect();
        j.commit(&created).unwrap();
        j.commit(&[
            VksChange::Deleted(7),
            VksChange::Metadata {
                class: 7,
                text: "obstacles".into(),
            },
            VksChange::Metadata {
                class: 8,
                text: "gone".into(),
            },
        ])
        .unwrap();
        j.commit(&[VksChange::Metadata {
            class: 8,
            text: String::new(),
        }])
        .unwrap();
        // Another instance in the same file is kept apart.
        s.vks_journal(2)
            .commit(&[VksChange::Created(wire(&object(1, 45.0)))])
            .unwrap();
        assert_eq!(s.stats().commits, 5);
        assert_eq!(s.stats().written, 53);
    }
    let s = Store::open(&path).unwrap();
    let wm = s.world_model(1, WorldModelConfig::default()).unwrap();
    assert!(wm.is_durable());
    let ids: Vec<u32> = wm.store().ids().collect();
    assert_eq!(ids.len(), 49);
    assert!(!ids.contains(&7));
    assert_eq!(wm.store().get(50), Some(&wire(&object(50, 30.5))));
    assert_eq!(wm.store().metadata(7), "obstacles");
    assert_eq!(wm.store().metadata(8), "");
    // New ids continue after the highest.
    assert_eq!(wm.store().next_id(), 51);
    let other = s.load_vks(2).unwrap();
    assert_eq!(other.objects.len(), 1);
    assert_eq!(other.objects[0], wire(&object(1, 45.0)));
    assert_eq!(s.load_vks(3).unwrap(), VksSnapshot::default());
}

#[test]
fn a_store_beyond_the_limits_is_refused_not_half_loaded() {
    let path = temp("limits.jstore");
    let s = Store::open(&path).unwrap();
    let created: Vec<VksChange> = (1..=10)
        .map(|i| VksChange::Created(wire(&object(i, 30.0))))
        .collect();
    s.vks_journal(1).commit(&created).unwrap();
    let config = WorldModelConfig {
        store: StoreConfig {
            max_objects: 9,
            ..StoreConfig::default()
        },
        ..WorldModelConfig::default()
    };
    let e = s.world_model(1, config).unwrap_err();
    assert!(matches!(e, StoreError::Restore { .. }), "{e}");
    assert!(e.to_string().contains("max_objects"), "{e}");
    let spooler = SpoolerConfig {
        max_missions: 1,
        ..SpoolerConfig::default()
    };
    let mut j = s.mission_journal(1);
    j.put(&mission(1)).unwrap();
    j.put(&mission(2)).unwrap();
    let e = s.mission_spooler(1, spooler).unwrap_err();
    assert!(e.to_string().contains("max_missions"), "{e}");
}

#[test]
fn missions_come_back_paused_where_they_stood() {
    let path = temp("missions.jstore");
    {
        let s = Store::open(&path).unwrap();
        let mut j = s.mission_journal(1);
        j.put(&mission(4)).unwrap();
        let mut done = mission(5);
        done.state = MissionState::Finished;
        j.put(&done).unwrap();
        // A later put replaces the record.
        let mut m = mission(4);
        m.messages[2].state = ItemState::Sent;
        m.cursor = 3;
        j.put(&m).unwrap();
    }
    let s = Store::open(&path).unwrap();
    let sp = s.mission_spooler(1, SpoolerConfig::default()).unwrap();
    assert!(sp.is_durable());
    assert_eq!(sp.missions(), 2);
    let (status, done, total) = sp.status(4).unwrap();
    assert_eq!((status, done, total), (MissionStatus::Paused, 3, 4));
    assert_eq!(sp.status(5).unwrap().0, MissionStatus::Finished);
    let r = sp.record(4).unwrap();
    assert_eq!(r.state, MissionState::Paused);
    assert_eq!(r.cursor, 3);
    assert_eq!(r.messages, {
        let mut m = mission(4).messages;
        m[2].state = ItemState::Sent;
        m
    });
}

#[test]
fn a_record_that_does_not_decode_names_the_file_table_and_key() {
    let path = temp("corrupt.jstore");
    {
        let s = Store::open(&path).unwrap();
        s.vks_journal(1)
            .commit(&[VksChange::Created(wire(&object(1, 30.0)))])
            .unwrap();
    }
    {
        // Someone else's bytes under a key of the table.
        let db = redb::Database::create(&path).unwrap();
        let tx = db.begin_write().unwrap();
        {
            let def: redb::TableDefinition<'_, (u8, u32), &[u8]> =
                redb::TableDefinition::new("vks_objects");
            let mut t = tx.open_table(def).unwrap();
            t.insert((1, 2), [1u8, 1, 0, 0].as_slice()).unwrap();
        }
        tx.commit().unwrap();
    }
    let s = Store::open(&path).unwrap();
    let e = s.world_model(1, WorldModelConfig::default()).unwrap_err();
    match &e {
        StoreError::Corrupt {
            file, table, key, ..
        } => {
            assert_eq!(file, &path);
            assert_eq!(*table, "vks_objects");
            assert_eq!(key, "(1, 2)");
        }
        other => panic!("{other:?}"),
    }
    let text = e.to_string();
    assert!(
        text.contains(&path.display().to_string()) && text.contains("(1, 2)"),
        "{text}"
    );
}

#[test]
fn a_transaction_never_committed_is_never_loaded() {
    let path = temp("torn.jstore");
    {
        let s = Store::open(&path).unwrap();
        s.vks_journal(1)
            .commit(&[VksChange::Created(wire(&object(1, 30.0)))])
            .unwrap();
    }
    {
        // A writer that dies before its commit: inserted, never committed.
        let db = redb::Database::create(&path).unwrap();
        let tx = db.begin_write().unwrap();
        {
            let def: redb::TableDefinition<'_, (u8, u32), &[u8]> =
                redb::TableDefinition::new("vks_objects");
            let mut t = tx.open_table(def).unwrap();
            let bytes = record::encode_object(&wire(&object(2, 31.0))).unwrap();
            t.insert((1, 2), bytes.as_slice()).unwrap();
        }
        drop(tx);
    }
    let s = Store::open(&path).unwrap();
    let ids: Vec<u32> = s
        .load_vks(1)
        .unwrap()
        .objects
        .iter()
        .map(|o| o.object_id)
        .collect();
    assert_eq!(ids, vec![1]);
}

#[test]
fn a_record_over_the_limit_is_refused_and_counted() {
    let path = temp("limit.jstore");
    let s = Store::open_with_limit(&path, 32).unwrap();
    let big = wire(&object(1, 30.0));
    let e = s
        .vks_journal(1)
        .commit(&[VksChange::Created(big)])
        .unwrap_err();
    assert!(e.0.contains("limit of 32"), "{e}");
    assert_eq!(s.stats().failed, 1);
    assert_eq!(s.stats().too_large, 1);
    assert!(s.load_vks(1).unwrap().objects.is_empty());
}

#[test]
fn a_store_in_use_by_another_process_is_refused() {
    let path = temp("busy.jstore");
    let _first = Store::open(&path).unwrap();
    let e = Store::open(&path).unwrap_err();
    assert!(matches!(e, StoreError::Open { .. }), "{e}");
}
