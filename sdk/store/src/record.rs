//! What the store writes: each record is a small versioned envelope (format byte, kind
//! byte) around a payload in the SDK's own wire codec wherever a JAUS record already
//! carries the content (a VKS object is the bytes of its `VksStoredObject` record, a
//! mission message those of its `MissionCommand`), and a few fixed-width little-endian
//! fields for the rest (where a mission stands). Decoding checks every length against
//! what is left before allocating and fails with the reason; nothing is guessed.

use jaus::codec::{Decode, Encode};
use jaus::messages::{MissionCommand, VksStoredObject};
use jaus::stock::spooler::{ItemState, MissionMessage, MissionRecord, MissionState};
use jaus::Address;

/// Format of the envelope written by this version.
pub const FORMAT: u8 = 1;

/// Kind byte of a VKS object record.
pub const KIND_OBJECT: u8 = 1;
/// Kind byte of a feature-class metadata record.
pub const KIND_METADATA: u8 = 2;
/// Kind byte of a mission record.
pub const KIND_MISSION: u8 = 3;

fn envelope(kind: u8, payload_len: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(2 + payload_len);
    out.push(FORMAT);
    out.push(kind);
    out
}

/// The payload of a record after checking its envelope.
fn open(bytes: &[u8], kind: u8) -> Result<&[u8], String> {
    match bytes {
        [f, _, ..] if *f != FORMAT => Err(format!(
            "record format {f}, this build reads format {FORMAT}"
        )),
        [_, k, rest @ ..] if *k == kind => Ok(rest),
        [_, k, ..] => Err(format!("record kind {k}, expected {kind}")),
        _ => Err(format!("{} bytes: no envelope", bytes.len())),
    }
}

/// A VKS object record.
pub fn encode_object(o: &VksStoredObject) -> Result<Vec<u8>, String> {
    let body = o.to_bytes().map_err(|e| e.to_string())?;
    let mut out = envelope(KIND_OBJECT, body.len());
    out.extend_from_slice(&body);
    Ok(out)
}

/// A VKS object from its record.
pub fn decode_object(bytes: &[u8]) -> Result<VksStoredObject, String> {
    VksStoredObject::from_bytes(open(bytes, KIND_OBJECT)?).map_err(|e| e.to_string())
}

/// A metadata record (UTF-8 text).
pub fn encode_metadata(text: &str) -> Vec<u8> {
    let mut out = envelope(KIND_METADATA, text.len());
    out.extend_from_slice(text.as_bytes());
    out
}

/// Metadata text from its record.
pub fn decode_metadata(bytes: &[u8]) -> Result<String, String> {
    String::from_utf8(open(bytes, KIND_METADATA)?.to_vec()).map_err(|e| e.to_string())
}

fn item_state(s: ItemState) -> u8 {
    match s {
        ItemState::Pending => 0,
        ItemState::Sent => 1,
        ItemState::Finished => 2,
        ItemState::Removed => 3,
    }
}

fn mission_state(s: MissionState) -> u8 {
    match s {
        MissionState::Pending => 0,
        MissionState::Running => 1,
        MissionState::Paused => 2,
        MissionState::Aborted => 3,
        MissionState::Finished => 4,
    }
}

fn put_address(out: &mut Vec<u8>, a: Address) {
    out.extend_from_slice(&[a.subsystem, a.node, a.component, a.instance]);
}

fn put_len(out: &mut Vec<u8>, n: usize) -> Result<(), String> {
    let n = u32::try_from(n).map_err(|_| format!("{n} entries do not fit a record"))?;
    out.extend_from_slice(&n.to_le_bytes());
    Ok(())
}

/// A mission record (the id is the record's key).
pub fn encode_mission(m: &MissionRecord) -> Result<Vec<u8>, String> {
    let mut out = envelope(KIND_MISSION, 32 + m.messages.len() * 24);
    put_address(&mut out, m.owner);
    out.push(mission_state(m.state));
    out.extend_from_slice(&m.cursor.to_le_bytes());
    match m.waiting {
        Some(w) => {
            out.push(1);
            out.extend_from_slice(&w.to_le_bytes());
        }
        None => out.extend_from_slice(&[0, 0, 0]),
    }
    for list in [&m.paused_tasks, &m.aborted_tasks] {
        put_len(&mut out, list.len())?;
        list.iter()
            .for_each(|t| out.extend_from_slice(&t.to_le_bytes()));
    }
    put_len(&mut out, m.parents.len())?;
    for (task, parent) in &m.parents {
        out.extend_from_slice(&task.to_le_bytes());
        out.extend_from_slice(&parent.to_le_bytes());
    }
    put_len(&mut out, m.remote_started.len())?;
    m.remote_started
        .iter()
        .for_each(|a| put_address(&mut out, *a));
    put_len(&mut out, m.messages.len())?;
    for msg in &m.messages {
        out.extend_from_slice(&msg.task.to_le_bytes());
        out.push(item_state(msg.state));
        let body = msg
            .command
            .to_bytes()
            .map_err(|e| format!("message {}: {e}", msg.command.uid))?;
        put_len(&mut out, body.len())?;
        out.extend_from_slice(&body);
    }
    Ok(out)
}

/// Reads fixed-width fields, checking every length.
struct Cursor<'a> {
    rest: &'a [u8],
    at: usize,
}

impl<'a> Cursor<'a> {
    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], String> {
        if self.rest.len() < n {
            return Err(format!(
                "{what} at byte {}: {n} bytes needed, {} left",
                self.at,
                self.rest.len()
            ));
        }
        let (head, tail) = self.rest.split_at(n);
        self.rest = tail;
        self.at += n;
        Ok(head)
    }

    fn u8(&mut self, what: &str) -> Result<u8, String> {
        Ok(self.take(1, what)?[0])
    }

    fn u16(&mut self, what: &str) -> Result<u16, String> {
        let b = self.take(2, what)?;
        Ok(u16::from_le_bytes([b[0], b[1]]))
    }

    fn u32(&mut self, what: &str) -> Result<u32, String> {
        let b = self.take(4, what)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    fn address(&mut self, what: &str) -> Result<Address, String> {
        let b = self.take(4, what)?;
        Ok(Address::new(b[0], b[1], b[2], b[3]))
    }

    /// A count of entries of at least `min` bytes each, checked against what is left.
    fn count(&mut self, min: usize, what: &str) -> Result<usize, String> {
        let at = self.at;
        let n = self.u32(what)? as usize;
        if n.saturating_mul(min) > self.rest.len() {
            return Err(format!(
                "{what} at byte {at}: {n} entries cannot fit in the {} bytes left",
                self.rest.len()
            ));
        }
        Ok(n)
    }
}

/// A mission from its record (`id`: its key).
pub fn decode_mission(id: u16, bytes: &[u8]) -> Result<MissionRecord, String> {
    let mut c = Cursor {
        rest: open(bytes, KIND_MISSION)?,
        at: 2,
    };
    let owner = c.address("owner")?;
    let state = match c.u8("state")? {
        0 => MissionState::Pending,
        1 => MissionState::Running,
        2 => MissionState::Paused,
        3 => MissionState::Aborted,
        4 => MissionState::Finished,
        v => return Err(format!("mission state {v} is not 0..=4")),
    };
    let cursor = c.u32("cursor")?;
    let waiting = match (c.u8("waiting flag")?, c.u16("waiting uid")?) {
        (0, _) => None,
        (1, uid) => Some(uid),
        (v, _) => return Err(format!("waiting flag {v} is not 0 or 1")),
    };
    let mut tasks = || -> Result<Vec<u16>, String> {
        let n = c.count(2, "task list")?;
        (0..n).map(|_| c.u16("task")).collect()
    };
    let paused_tasks = tasks()?;
    let aborted_tasks = tasks()?;
    let n = c.count(4, "parents")?;
    let parents = (0..n)
        .map(|_| Ok((c.u16("task")?, c.u16("parent")?)))
        .collect::<Result<Vec<_>, String>>()?;
    let n = c.count(4, "remote spoolers")?;
    let remote_started = (0..n)
        .map(|_| c.address("remote spooler"))
        .collect::<Result<Vec<_>, String>>()?;
    let n = c.count(7, "messages")?;
    let mut messages = Vec::with_capacity(n);
    for i in 0..n {
        let task = c.u16("message task")?;
        let state = match c.u8("message state")? {
            0 => ItemState::Pending,
            1 => ItemState::Sent,
            2 => ItemState::Finished,
            3 => ItemState::Removed,
            v => return Err(format!("message {i}: state {v} is not 0..=3")),
        };
        let len = c.count(1, "message length")?;
        let body = c.take(len, "message")?;
        let command = MissionCommand::from_bytes(body).map_err(|e| format!("message {i}: {e}"))?;
        messages.push(MissionMessage {
            task,
            state,
            command,
        });
    }
    if !c.rest.is_empty() {
        return Err(format!(
            "{} bytes left over after the mission",
            c.rest.len()
        ));
    }
    Ok(MissionRecord {
        mission_id: id,
        owner,
        state,
        cursor,
        waiting,
        paused_tasks,
        aborted_tasks,
        parents,
        remote_started,
        messages,
    })
}
