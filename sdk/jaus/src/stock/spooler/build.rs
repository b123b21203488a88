//! Builders of missions for other modules (the operator station, tests): Mission Command
//! records, tasks and Spool Mission.

use crate::messages::*;
use crate::Address;

/// Builds a Mission Command record around `msg` addressed to `to` from `from`.
pub fn command(
    uid: u16,
    from: Address,
    to: Address,
    msg: &Message,
    blocking: bool,
) -> Result<MissionCommand, crate::codec::EncodeError> {
    use crate::codec::Encode;
    let body = msg.to_bytes()?;
    let header = crate::Header::new(msg.code(), to, from);
    Ok(MissionCommand {
        uid,
        message: crate::Packet::new(header, body),
        blocking: u8::from(blocking),
    })
}

/// A task without child tasks: `messages` in spooling order.
pub fn leaf_task(task_id: u16, messages: Vec<MissionCommand>) -> MissionTask {
    MissionTask {
        task_id,
        child_count: 0,
        child_offsets: Vec::new(),
        messages,
        children: Vec::new(),
    }
}

/// A Spool Mission replacing the current mission: a root task 0 without messages whose
/// children are `tasks`, run in order (child counts and offsets are computed on encode).
pub fn mission_of(mission_id: u16, tasks: Vec<MissionTask>) -> SpoolMission {
    let count = tasks.len();
    SpoolMission {
        mission_id,
        append_flag: 0,
        root: MissionTask {
            task_id: 0,
            child_count: count as u16,
            child_offsets: vec![0; count],
            messages: Vec::new(),
            children: tasks,
        },
    }
}
