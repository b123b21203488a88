//! Fields that depend on other fields: a count kept in its own field (computed on
//! encode from the list it counts, or checked for lists nested deeper), presence flags
//! with no bytes that decide whether nested fields are there, and computed offsets.

use jaus::codec::{Decode, Encode, EncodeError};
use jaus::{JausMessage, JausRecord};

#[derive(Debug, Clone, PartialEq, JausRecord)]
struct Pose {
    time: u16,
    #[jaus(count_var = "num_joints")]
    joints: Vec<u8>,
}

#[derive(Debug, Clone, PartialEq, JausMessage)]
#[jaus(code = 0xD200)]
struct Motion {
    #[jaus(var = "num_joints")]
    num_joints: u8,
    #[jaus(var = "num_poses")]
    num_poses: u8,
    #[jaus(count_var = "num_poses")]
    poses: Vec<Pose>,
}

#[derive(Debug, Clone, PartialEq, JausRecord)]
struct Object {
    kind: u8,
    #[jaus(present_if = "buffered")]
    buffer: Option<f32>,
}

#[derive(Debug, Clone, PartialEq, JausMessage)]
#[jaus(code = 0xD201, presence = u8)]
struct Objects {
    #[jaus(flag = 0, var = "buffered")]
    buffered: bool,
    #[jaus(var = "count")]
    count: u16,
    #[jaus(bit = 1, count_var = "count")]
    objects: Option<Vec<Object>>,
}

#[derive(Debug, Clone, PartialEq, JausRecord)]
struct Task {
    id: u16,
    #[jaus(var = "child_count")]
    child_count: u16,
    #[jaus(count_var = "child_count", offsets = "children")]
    child_offsets: Vec<u32>,
    #[jaus(count_var = "child_count")]
    children: Vec<Task>,
}

fn main() {
    // The count of poses is computed from the list; the joint count is checked.
    let m = Motion { num_joints: 2, num_poses: 0, poses: vec![Pose { time: 1, joints: vec![7, 8] }] };
    let b = m.to_bytes().unwrap();
    assert_eq!(b, [2, 1, 1, 0, 7, 8]);
    assert_eq!(Motion::from_bytes(&b).unwrap().num_poses, 1);
    let bad = Motion { num_joints: 3, ..m.clone() };
    assert!(matches!(bad.to_bytes(), Err(EncodeError::CountMismatch { expected: 3, len: 2, .. })));
    assert!(Motion::from_bytes(&[9, 1, 0, 0, 1]).is_err(), "a count beyond the buffer is an error");

    // Flags: the buffer of every object is there exactly when the flag is set.
    let o = Objects { buffered: true, count: 0, objects: Some(vec![Object { kind: 1, buffer: Some(2.5) }]) };
    let b = o.to_bytes().unwrap();
    assert_eq!(b, [0b11, 1, 0, 1, 0, 0, 0x20, 0x40]);
    assert_eq!(Objects::from_bytes(&b).unwrap(), Objects { count: 1, ..o.clone() });
    let only_count = Objects { buffered: false, count: 9339, objects: None };
    assert_eq!(Objects::from_bytes(&only_count.to_bytes().unwrap()).unwrap(), only_count);
    let wrong = Objects { buffered: false, ..o };
    assert!(matches!(wrong.to_bytes(), Err(EncodeError::PresenceMismatch { .. })));

    // Offsets left empty are computed: absolute positions in the body.
    let leaf = |id| Task { id, child_count: 0, child_offsets: vec![], children: vec![] };
    let root = Task {
        id: 1,
        child_count: 2,
        child_offsets: vec![],
        children: vec![leaf(2), Task { id: 3, child_count: 1, child_offsets: vec![], children: vec![leaf(4)] }],
    };
    let b = root.to_bytes().unwrap();
    let at = |i: usize| u32::from_le_bytes(b[i..i + 4].try_into().unwrap()) as usize;
    assert_eq!(&b[at(4)..at(4) + 2], &2u16.to_le_bytes());
    assert_eq!(&b[at(8)..at(8) + 2], &3u16.to_le_bytes());
    let child3 = at(8);
    assert_eq!(&b[at(child3 + 4)..at(child3 + 4) + 2], &4u16.to_le_bytes(), "nested offsets are absolute too");
    let back = Task::from_bytes(&b).unwrap();
    assert_eq!(back.children[1].children[0].id, 4);
    assert_eq!(back.child_offsets, vec![at(4) as u32, at(8) as u32]);
    // Offsets given with one per child (as received) are written as given, so a
    // received message re-encodes byte for byte.
    let given = Task { child_offsets: vec![999, 998], ..back.clone() };
    let b2 = given.to_bytes().unwrap();
    assert_eq!(&b2[4..12], &[0xE7, 3, 0, 0, 0xE6, 3, 0, 0]);
    assert_eq!(Task::from_bytes(&b2).unwrap(), given);
}
