//! The persistence seam of the stock cores on a `LocalBus`, with journals that record
//! what they are given or fail on demand: what is confirmed was committed first, a
//! change the journal refuses is undone and refused, and a spooler restored after a
//! restart holds its missions paused until told to go on.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use jaus::component::local::{LocalBus, Probe};
use jaus::component::Config;
use jaus::components::{mission_spooler as ms, world_model_vector_knowledge_store as wmvks};
use jaus::messages::*;
use jaus::stock::spooler::{
    command, leaf_task, mission_of, ItemState, JournalError, MissionJournal, MissionRecord,
    MissionState, SpoolerConfig, StockMissionSpooler,
};
use jaus::stock::world_model::{
    StockWorldModel, VksChange, VksJournal, VksSnapshot, WorldModelConfig,
};
use jaus::Address;

const WM: Address = Address::new(1, 1, 61, 1);
const SP: Address = Address::new(1, 1, 36, 1);
const PD: Address = Address::new(1, 1, 33, 1);
const CLIENT: Address = Address::new(1, 1, 40, 1);

/// Records what it commits; fails while `fail` is set.
#[derive(Debug, Clone, Default)]
struct Log {
    vks: Arc<Mutex<Vec<VksChange>>>,
    missions: Arc<Mutex<Vec<MissionRecord>>>,
    fail: Arc<Mutex<bool>>,
}

impl VksJournal for Log {
    fn commit(&mut self, changes: &[VksChange]) -> Result<(), JournalError> {
        if *self.fail.lock().unwrap() {
            return Err(JournalError("disk full".into()));
        }
        self.vks.lock().unwrap().extend_from_slice(changes);
        Ok(())
    }
}

impl MissionJournal for Log {
    fn put(&mut self, mission: &MissionRecord) -> Result<(), JournalError> {
        if *self.fail.lock().unwrap() {
            return Err(JournalError("disk full".into()));
        }
        self.missions.lock().unwrap().push(mission.clone());
        Ok(())
    }
}

fn config() -> Config {
    Config {
        heartbeat: None,
        ..Config::default()
    }
}

fn ask(bus: &mut LocalBus, to: Address, msg: impl Into<Message>) -> Vec<Message> {
    bus.get_mut::<Probe>(CLIENT).unwrap().clear();
    bus.send(CLIENT, to, msg);
    bus.run_for(Duration::from_millis(20));
    bus.get::<Probe>(CLIENT)
        .unwrap()
        .messages()
        .cloned()
        .collect()
}

fn point(lat: f64) -> VksObject {
    VksObject {
        object_type: VksObjectType::Point,
        buffer: None,
        feature_classes: vec![],
        points: vec![VksPoint {
            latitude: lat,
            longitude: 10.0,
        }],
    }
}

fn create(request_id: u8, n: usize) -> CreateVksObjects {
    CreateVksObjects {
        buffered: false,
        message_properties: 1,
        request_id,
        objects: (0..n).map(|i| point(i as f64 * 0.01)).collect(),
    }
}

fn created_ids(m: &[Message]) -> Vec<u32> {
    match m {
        [Message::ReportVksObjectsCreation(r)] => r.object_ids.clone(),
        other => panic!("{other:?}"),
    }
}

fn wm_bus(log: &Log) -> LocalBus {
    let t0 = Instant::now();
    let core = StockWorldModel::restore(
        WorldModelConfig::default(),
        VksSnapshot::default(),
        Box::new(log.clone()),
    )
    .unwrap();
    let mut bus = LocalBus::new(t0);
    bus.add(wmvks::component(WM, core, config(), t0));
    bus.add(Probe::new(CLIENT));
    bus.run_for(Duration::from_millis(10));
    bus
}

fn wm(bus: &LocalBus) -> &StockWorldModel {
    &bus.get::<jaus::component::Component<wmvks::Dispatch<StockWorldModel>>>(WM)
        .unwrap()
        .behaviour()
        .0
}

#[test]
fn world_model_commits_before_confirming_and_undoes_what_it_cannot_commit() {
    let log = Log::default();
    let mut bus = wm_bus(&log);
    let ids = created_ids(&ask(&mut bus, WM, create(1, 3)));
    assert_eq!(ids, vec![1, 2, 3]);
    // What the report confirmed was committed, with the ids it gave.
    let committed: Vec<u32> = log
        .vks
        .lock()
        .unwrap()
        .iter()
        .filter_map(|c| match c {
            VksChange::Created(o) => Some(o.object_id),
            _ => None,
        })
        .collect();
    assert_eq!(committed, ids);

    *log.fail.lock().unwrap() = true;
    // A create the journal refuses: nothing stored, every id 0.
    assert_eq!(created_ids(&ask(&mut bus, WM, create(2, 2))), vec![0, 0]);
    assert_eq!(wm(&bus).store().len(), 3);
    assert_eq!(wm(&bus).journal_failures(), 1);
    // A delete it refuses deletes nothing.
    let delete = DeleteVksObjects {
        request_id: 3,
        object_ids: Some(vec![1, 2]),
        ..Default::default()
    };
    ask(&mut bus, WM, delete.clone());
    assert_eq!(wm(&bus).store().len(), 3);
    // Metadata it refuses keeps the old text.
    let set = |text: &str| SetVksFeatureClassMetadata {
        feature_class_id: 4,
        metadata_option: VksMetadataOption::Overwrite,
        metadata: text.into(),
    };
    *log.fail.lock().unwrap() = false;
    ask(&mut bus, WM, set("roads"));
    *log.fail.lock().unwrap() = true;
    ask(&mut bus, WM, set("rivers"));
    assert_eq!(wm(&bus).store().metadata(4), "roads");

    *log.fail.lock().unwrap() = false;
    ask(&mut bus, WM, delete);
    assert_eq!(wm(&bus).store().ids().collect::<Vec<_>>(), vec![3]);
    let log = log.vks.lock().unwrap();
    assert_eq!(
        log[log.len() - 3..],
        [
            VksChange::Metadata {
                class: 4,
                text: "roads".into()
            },
            VksChange::Deleted(1),
            VksChange::Deleted(2)
        ]
    );
}

fn sp_bus(core: StockMissionSpooler) -> LocalBus {
    let t0 = Instant::now();
    let mut bus = LocalBus::new(t0);
    bus.add(ms::component(SP, core, config(), t0));
    bus.add(Probe::new(CLIENT));
    bus.add(Probe::new(PD));
    bus.run_for(Duration::from_millis(10));
    bus.send(
        CLIENT,
        SP,
        RequestComponentControl {
            authority_code: 100,
        },
    );
    bus.send(CLIENT, SP, Resume {});
    bus.run_for(Duration::from_millis(10));
    bus
}

fn sp(bus: &LocalBus) -> &StockMissionSpooler {
    &bus.get::<jaus::component::Component<ms::Dispatch<StockMissionSpooler>>>(SP)
        .unwrap()
        .behaviour()
        .0
}

fn mission() -> SpoolMission {
    // Each message says its uid.
    let cmd = |uid: u16, blocking| {
        let effort = SetWrenchEffort {
            propulsive_linear_effort_x: Some(f64::from(uid)),
            ..Default::default()
        };
        command(uid, SP, PD, &Message::from(effort), blocking).unwrap()
    };
    mission_of(
        7,
        vec![
            leaf_task(1, vec![cmd(1, false), cmd(2, true)]),
            leaf_task(2, vec![cmd(3, false)]),
        ],
    )
}

fn status(bus: &mut LocalBus) -> MissionStatus {
    let q = QueryMissionStatus {
        presence_vector: 1,
        status_type: MissionStatusType::Mission,
        mission_id: 7,
        task_id: 0,
        task_msg_id: 0,
    };
    match &ask(bus, SP, q)[..] {
        [Message::ReportMissionStatus(r)] => r.status,
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_spool_the_journal_refuses_is_not_kept() {
    let log = Log::default();
    *log.fail.lock().unwrap() = true;
    let core =
        StockMissionSpooler::restore(SpoolerConfig::default(), vec![], Box::new(log.clone()))
            .unwrap();
    let mut bus = sp_bus(core);
    ask(&mut bus, SP, mission());
    assert_eq!(sp(&bus).missions(), 0);
    assert_eq!(sp(&bus).journal_failures(), 1);
    *log.fail.lock().unwrap() = false;
    ask(&mut bus, SP, mission());
    assert_eq!(sp(&bus).missions(), 1);
    assert_eq!(log.missions.lock().unwrap().len(), 1);
}

#[test]
fn a_restored_mission_is_paused_until_resumed_then_goes_on_from_its_task() {
    // First life: spooled, run until the blocking message is being executed.
    let log = Log::default();
    let core =
        StockMissionSpooler::restore(SpoolerConfig::default(), vec![], Box::new(log.clone()))
            .unwrap();
    let mut bus = sp_bus(core);
    ask(&mut bus, SP, mission());
    ask(&mut bus, SP, RunMission { mission_id: 7 });
    bus.run_for(Duration::from_secs(2));
    let last = log.missions.lock().unwrap().last().cloned().unwrap();
    assert_eq!(last.state, MissionState::Running);
    assert_eq!(last.waiting, Some(2), "{last:?}");
    assert_eq!(last.messages[1].state, ItemState::Sent);

    // Second life, from what was committed: paused, nothing sent on its own.
    let log2 = Log::default();
    let core =
        StockMissionSpooler::restore(SpoolerConfig::default(), vec![last], Box::new(log2.clone()))
            .unwrap();
    let mut bus = sp_bus(core);
    assert_eq!(status(&mut bus), MissionStatus::Paused);
    bus.get_mut::<Probe>(PD).unwrap().clear();
    bus.run_for(Duration::from_secs(3));
    assert_eq!(bus.get::<Probe>(PD).unwrap().messages().count(), 0);
    // Resume: runs again from the start of task 1.
    ask(
        &mut bus,
        SP,
        ResumeMission {
            mission_id: 7,
            task_id: 0,
        },
    );
    bus.run_for(Duration::from_secs(2));
    assert_eq!(status(&mut bus), MissionStatus::Spooling);
    let sent: Vec<u16> = bus
        .get::<Probe>(PD)
        .unwrap()
        .messages()
        .filter_map(|m| match m {
            Message::SetWrenchEffort(w) => w.propulsive_linear_effort_x.map(|x| x.round() as u16),
            _ => None,
        })
        .collect();
    // Task 1 again from its first message, up to its blocking one.
    assert_eq!(sent, vec![1, 2]);
    let r = log2.missions.lock().unwrap().last().cloned().unwrap();
    assert_eq!(r.state, MissionState::Running);
}
