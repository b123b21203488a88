//! A mission's task tree: validation, run order and the edits of what remains
//! (sans-IO, no time: plain data checked against [`Bounds`]).
//!
//! The tree is the `tasks` list of Spool Mission: task 0 is the root, each task names
//! its children by index in the list. A valid tree has every child index in range, no
//! cycle, every task but the root the child of exactly one task (so each is reached
//! once from the root), unique task ids, unique message uids across the mission, every
//! embedded message at least 2 bytes (its message ID) and at most
//! [`Bounds::max_message_bytes`], no broadcast destination, and fits the bounds.
//!
//! Run order: a task's messages in their order, then its children, depth first, in the
//! order the task lists them ([`Plan::run_order`]).

use std::collections::{BTreeMap, BTreeSet};

use jaus::net::as5669a::As4Id;

use crate::messages::{
    InsertMessages, InsertMissionTask, JausAddress, MessageInsertPosition, MissionTask,
    RemoveMessages, RemoveMissionTask, SpooledMessage, TaskInsertPosition,
};

/// The bounds a mission must fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Bounds {
    /// Tasks in a mission at most.
    pub max_tasks: usize,
    /// Messages in a mission at most (all tasks together).
    pub max_messages: usize,
    /// Bytes of one embedded message at most (message ID and body).
    pub max_message_bytes: usize,
}

/// Why a mission or an edit is refused: the field (its path in the message) and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Refusal {
    /// The field, as a path in the message (`tasks[2].child_tasks[0]`).
    pub field: String,
    /// Why.
    pub why: String,
}

impl Refusal {
    fn new(field: impl Into<String>, why: impl Into<String>) -> Self {
        Self {
            field: field.into(),
            why: why.into(),
        }
    }
}

impl std::fmt::Display for Refusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.field, self.why)
    }
}

/// The AS-4 id a mission's 32-bit address names.
pub fn id_of(a: &JausAddress) -> As4Id {
    As4Id::new(a.subsystem_id, a.node_id, a.component_id)
}

/// The 32-bit address of an AS-4 id.
pub fn address_of(id: As4Id) -> JausAddress {
    JausAddress {
        component_id: id.component,
        node_id: id.node,
        subsystem_id: id.subsystem,
        ..Default::default()
    }
}

/// Where a message is in the tree: task index, message index in the task.
pub type Place = (usize, usize);

/// A mission's task tree (task 0 the root).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Plan {
    /// The tasks; each names its children by index here.
    pub tasks: Vec<MissionTask>,
}

impl Plan {
    /// `tasks` checked against `bounds`.
    pub fn new(tasks: Vec<MissionTask>, bounds: &Bounds) -> Result<Self, Refusal> {
        let plan = Self { tasks };
        plan.validate(bounds)?;
        Ok(plan)
    }

    /// Checks the tree (see the module's documentation).
    pub fn validate(&self, bounds: &Bounds) -> Result<(), Refusal> {
        let n = self.tasks.len();
        if n == 0 {
            return Err(Refusal::new(
                "tasks",
                "a mission has at least its root task",
            ));
        }
        if n > bounds.max_tasks {
            return Err(Refusal::new(
                "tasks",
                format!("{n} tasks, at most {} are taken", bounds.max_tasks),
            ));
        }
        let mut parent: Vec<Option<usize>> = vec![None; n];
        let mut ids = BTreeSet::new();
        let mut uids = BTreeSet::new();
        let mut messages = 0usize;
        for (i, t) in self.tasks.iter().enumerate() {
            if !ids.insert(t.task_id) {
                return Err(Refusal::new(
                    format!("tasks[{i}].task_id"),
                    format!("task id {} given twice", t.task_id),
                ));
            }
            for (j, &c) in t.child_tasks.iter().enumerate() {
                let field = format!("tasks[{i}].child_tasks[{j}]");
                let c = usize::from(c);
                if c >= n {
                    return Err(Refusal::new(field, format!("index {c} past the {n} tasks")));
                }
                if c == 0 {
                    return Err(Refusal::new(
                        field,
                        "the root task (index 0) is no one's child",
                    ));
                }
                if parent[c].is_some() {
                    return Err(Refusal::new(field, format!("task {c} is reached twice")));
                }
                parent[c] = Some(i);
            }
            for (j, m) in t.messages.iter().enumerate() {
                messages += 1;
                let field = |f: &str| format!("tasks[{i}].messages[{j}].{f}");
                if !uids.insert(m.uid) {
                    return Err(Refusal::new(
                        field("uid"),
                        format!("uid {} given twice", m.uid),
                    ));
                }
                if m.jaus_message.len() < 2 {
                    return Err(Refusal::new(
                        field("jaus_message"),
                        "shorter than a message ID (2 bytes)",
                    ));
                }
                if m.jaus_message.len() > bounds.max_message_bytes {
                    return Err(Refusal::new(
                        field("jaus_message"),
                        format!(
                            "{} bytes, at most {} are taken",
                            m.jaus_message.len(),
                            bounds.max_message_bytes
                        ),
                    ));
                }
                let d = id_of(&m.destination_id);
                if d.subsystem == 0xFFFF || d.node == 0xFF || d.component == 0xFF {
                    return Err(Refusal::new(
                        field("destination_id"),
                        format!("{d} is a broadcast: a command goes to one component"),
                    ));
                }
            }
        }
        if messages > bounds.max_messages {
            return Err(Refusal::new(
                "tasks",
                format!(
                    "{messages} messages, at most {} are taken",
                    bounds.max_messages
                ),
            ));
        }
        // Every task but the root has one parent; a cycle among them is not reached
        // from the root.
        let reached = self.preorder().len();
        if reached != n {
            let lost = (0..n)
                .find(|i| !self.preorder().contains(i))
                .unwrap_or_default();
            return Err(Refusal::new(
                format!("tasks[{lost}]"),
                "not reached from the root task (a cycle, or no parent)",
            ));
        }
        Ok(())
    }

    /// The task indices from the root, depth first (each at most once, even in a tree
    /// that does not validate).
    pub fn preorder(&self) -> Vec<usize> {
        let mut out = Vec::new();
        let mut seen = vec![false; self.tasks.len()];
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            if i >= self.tasks.len() || seen[i] {
                continue;
            }
            seen[i] = true;
            out.push(i);
            for &c in self.tasks[i].child_tasks.iter().rev() {
                stack.push(usize::from(c));
            }
        }
        out
    }

    /// Every message in run order: a task's messages, then its children depth first.
    pub fn run_order(&self) -> Vec<Place> {
        self.preorder()
            .into_iter()
            .flat_map(|t| (0..self.tasks[t].messages.len()).map(move |m| (t, m)))
            .collect()
    }

    /// The message at `p`.
    pub fn message(&self, p: Place) -> Option<&SpooledMessage> {
        self.tasks.get(p.0).and_then(|t| t.messages.get(p.1))
    }

    /// The index of the task with id `id`.
    pub fn task(&self, id: u16) -> Option<usize> {
        self.tasks.iter().position(|t| t.task_id == id)
    }

    /// [`task`](Self::task) of a message's `task_id`, or the refusal naming it.
    fn task_named(&self, id: u16) -> Result<usize, Refusal> {
        self.task(id)
            .ok_or_else(|| Refusal::new("task_id", format!("no task {id}")))
    }

    /// Where the message `uid` is.
    pub fn find(&self, uid: u16) -> Option<Place> {
        self.tasks.iter().enumerate().find_map(|(t, task)| {
            task.messages
                .iter()
                .position(|m| m.uid == uid)
                .map(|m| (t, m))
        })
    }

    /// The parent of task `i`.
    pub fn parent(&self, i: usize) -> Option<usize> {
        let i = u16::try_from(i).ok()?;
        self.tasks.iter().position(|t| t.child_tasks.contains(&i))
    }

    /// The task indices of the subtree of `i` (itself first).
    pub fn subtree(&self, i: usize) -> Vec<usize> {
        Plan {
            tasks: self.tasks.clone(),
        }
        .preorder_from(i)
    }

    fn preorder_from(&self, root: usize) -> Vec<usize> {
        let mut out = Vec::new();
        let mut seen = vec![false; self.tasks.len()];
        let mut stack = vec![root];
        while let Some(i) = stack.pop() {
            if i >= self.tasks.len() || seen[i] {
                continue;
            }
            seen[i] = true;
            out.push(i);
            for &c in self.tasks[i].child_tasks.iter().rev() {
                stack.push(usize::from(c));
            }
        }
        out
    }

    /// Every message uid.
    pub fn uids(&self) -> impl Iterator<Item = u16> + '_ {
        self.tasks
            .iter()
            .flat_map(|t| t.messages.iter().map(|m| m.uid))
    }

    /// The plan without the tasks in `gone`, the others' child indices renumbered.
    fn without(&self, gone: &BTreeSet<usize>) -> Plan {
        let mut map = BTreeMap::new();
        let mut next = 0u16;
        for i in 0..self.tasks.len() {
            if !gone.contains(&i) {
                map.insert(i, next);
                next = next.saturating_add(1);
            }
        }
        let tasks = self
            .tasks
            .iter()
            .enumerate()
            .filter(|(i, _)| !gone.contains(i))
            .map(|(_, t)| {
                let mut t = t.clone();
                t.child_tasks = t
                    .child_tasks
                    .iter()
                    .filter_map(|c| map.get(&usize::from(*c)).copied())
                    .collect();
                t
            })
            .collect();
        Plan { tasks }
    }

    /// The plan edited by `msg`, or why not. `issued` are the uids already sent (or
    /// skipped): they must stay the first of the run order, untouched.
    pub fn remove_messages(
        &self,
        msg: &RemoveMessages,
        issued: &BTreeSet<u16>,
        bounds: &Bounds,
    ) -> Result<Plan, Refusal> {
        let t = self.task_named(msg.task_id)?;
        let mut plan = self.clone();
        for (k, uid) in msg.uids.iter().enumerate() {
            let field = format!("uids[{k}]");
            if !self.tasks[t].messages.iter().any(|m| m.uid == *uid) {
                return Err(Refusal::new(
                    field,
                    format!("no message {uid} in task {}", msg.task_id),
                ));
            }
            if issued.contains(uid) {
                return Err(Refusal::new(
                    field,
                    format!("message {uid} was already sent"),
                ));
            }
        }
        plan.tasks[t]
            .messages
            .retain(|m| !msg.uids.contains(&m.uid));
        plan.checked(issued, bounds)
    }

    /// The plan with `msg`'s messages inserted, or why not.
    pub fn insert_messages(
        &self,
        msg: &InsertMessages,
        issued: &BTreeSet<u16>,
        bounds: &Bounds,
    ) -> Result<Plan, Refusal> {
        let t = self.task_named(msg.task_id)?;
        let at = self.tasks[t]
            .messages
            .iter()
            .position(|m| m.uid == msg.uid)
            .ok_or_else(|| {
                Refusal::new(
                    "uid",
                    format!("no message {} in task {}", msg.uid, msg.task_id),
                )
            })?;
        let at = match msg.insert_location {
            MessageInsertPosition::BeforeUid => at,
            _ => at + 1,
        };
        let mut plan = self.clone();
        let list = &mut plan.tasks[t].messages;
        for (k, m) in msg.messages.iter().enumerate() {
            list.insert(at + k, m.clone());
        }
        plan.checked(issued, bounds)
    }

    /// The plan without the task `msg` names (its `promoted_children`, by task id,
    /// moving up to its parent in its place), or why not.
    pub fn remove_task(
        &self,
        msg: &RemoveMissionTask,
        issued: &BTreeSet<u16>,
        bounds: &Bounds,
    ) -> Result<Plan, Refusal> {
        let t = self.task_named(msg.task_id)?;
        let parent = self
            .parent(t)
            .ok_or_else(|| Refusal::new("task_id", "the root task is not removed"))?;
        let mut promoted = Vec::new();
        for (k, id) in msg.promoted_children.iter().enumerate() {
            let c = self
                .task(*id)
                .filter(|c| self.parent(*c) == Some(t))
                .ok_or_else(|| {
                    Refusal::new(
                        format!("promoted_children[{k}]"),
                        format!("task {id} is not a child of task {}", msg.task_id),
                    )
                })?;
            promoted.push(c);
        }
        let mut gone: BTreeSet<usize> = BTreeSet::from([t]);
        for &c in &self.tasks[t].child_tasks {
            let c = usize::from(c);
            if !promoted.contains(&c) {
                gone.extend(self.subtree(c));
            }
        }
        for &g in &gone {
            if let Some(m) = self.tasks[g]
                .messages
                .iter()
                .find(|m| issued.contains(&m.uid))
            {
                return Err(Refusal::new(
                    "task_id",
                    format!(
                        "message {} of task {} was already sent",
                        m.uid, self.tasks[g].task_id
                    ),
                ));
            }
        }
        let mut plan = self.clone();
        let children = &mut plan.tasks[parent].child_tasks;
        let Some(pos) = children.iter().position(|c| usize::from(*c) == t) else {
            return Err(Refusal::new("task_id", "not found under its parent"));
        };
        children.splice(
            pos..=pos,
            promoted.iter().filter_map(|c| u16::try_from(*c).ok()),
        );
        plan.without(&gone).checked(issued, bounds)
    }

    /// The plan with `msg`'s task inserted, or why not. Taken: the new task as a
    /// sibling before or after the task given when `new_parent_task_id` is that task's
    /// parent; the new task in the place of the task given, which becomes its child,
    /// when `new_parent_task_id` is the new task's id and the location Before (its
    /// messages then run first). The new task brings no children of its own.
    pub fn insert_task(
        &self,
        msg: &InsertMissionTask,
        issued: &BTreeSet<u16>,
        bounds: &Bounds,
    ) -> Result<Plan, Refusal> {
        let t = self.task_named(msg.task_id)?;
        if !msg.task.child_tasks.is_empty() {
            return Err(Refusal::new(
                "task.child_tasks",
                "a task inserted brings no children (give them with further inserts)",
            ));
        }
        let mut plan = self.clone();
        let new = plan.tasks.len();
        let new16 = u16::try_from(new).map_err(|_| Refusal::new("task", "too many tasks"))?;
        let t16 = u16::try_from(t).map_err(|_| Refusal::new("task_id", "too many tasks"))?;
        plan.tasks.push(msg.task.clone());
        let parent = self.parent(t);
        let parent_id = parent.map(|p| self.tasks[p].task_id);
        if parent_id == Some(msg.new_parent_task_id) && msg.new_parent_task_id != msg.task.task_id {
            let p = parent.unwrap_or_default();
            let children = &mut plan.tasks[p].child_tasks;
            let pos = children.iter().position(|c| *c == t16).unwrap_or(0);
            let pos = match msg.insert_location {
                TaskInsertPosition::BeforeTask => pos,
                _ => pos + 1,
            };
            children.insert(pos.min(children.len()), new16);
        } else if msg.new_parent_task_id == msg.task.task_id
            && msg.insert_location == TaskInsertPosition::BeforeTask
        {
            plan.tasks[new].child_tasks.push(t16);
            match parent {
                Some(p) => {
                    for c in &mut plan.tasks[p].child_tasks {
                        if *c == t16 {
                            *c = new16;
                        }
                    }
                }
                None => {
                    // The new task becomes the root: swap it to index 0.
                    plan.tasks.swap(0, new);
                    for task in &mut plan.tasks {
                        for c in &mut task.child_tasks {
                            if *c == 0 {
                                *c = new16;
                            } else if *c == new16 {
                                *c = 0;
                            }
                        }
                    }
                }
            }
        } else {
            return Err(Refusal::new(
                "new_parent_task_id",
                format!(
                    "taken: the parent of task {} (a sibling) or the new task's id with \
                     Before (the new task over it)",
                    msg.task_id
                ),
            ));
        }
        plan.checked(issued, bounds)
    }

    /// `self` if it validates and the `issued` uids are still the first of its run
    /// order, each where it was.
    fn checked(self, issued: &BTreeSet<u16>, bounds: &Bounds) -> Result<Plan, Refusal> {
        self.validate(bounds)?;
        let order = self.run_order();
        let head = order
            .iter()
            .take_while(|p| self.message(**p).is_some_and(|m| issued.contains(&m.uid)))
            .count();
        if head != issued.len() {
            return Err(Refusal::new(
                "tasks",
                "the edit would put a message not yet sent before one already sent",
            ));
        }
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::messages::MessageBlocking;

    fn m(uid: u16) -> SpooledMessage {
        SpooledMessage {
            uid,
            destination_id: address_of(As4Id::new(1, 1, 6)),
            jaus_message: vec![4, 0],
            blocking: MessageBlocking::NonBlocking,
        }
    }

    fn t(id: u16, uids: &[u16], children: &[u16]) -> MissionTask {
        MissionTask {
            task_id: id,
            messages: uids.iter().map(|u| m(*u)).collect(),
            child_tasks: children.to_vec(),
        }
    }

    fn bounds() -> Bounds {
        Bounds {
            max_tasks: 16,
            max_messages: 16,
            max_message_bytes: 16,
        }
    }

    fn order(p: &Plan) -> Vec<u16> {
        p.run_order()
            .into_iter()
            .filter_map(|x| p.message(x).map(|m| m.uid))
            .collect()
    }

    /// Root 1 (uid 1) → A 2 (uid 2) → [B 3 (uid 3), C 4 (uid 4)]; D 5 (uid 5) after A.
    fn tree() -> Plan {
        Plan::new(
            vec![
                t(1, &[1], &[1, 4]),
                t(2, &[2], &[2, 3]),
                t(3, &[3], &[]),
                t(4, &[4], &[]),
                t(5, &[5], &[]),
            ],
            &bounds(),
        )
        .unwrap()
    }

    #[test]
    fn a_task_removed_takes_its_children_but_the_promoted_ones() {
        let p = tree();
        assert_eq!(order(&p), vec![1, 2, 3, 4, 5]);
        let rm = RemoveMissionTask {
            mission_id: 1,
            task_id: 2,
            promoted_children: vec![4],
        };
        let q = p.remove_task(&rm, &BTreeSet::new(), &bounds()).unwrap();
        assert_eq!(order(&q), vec![1, 4, 5]);
        // Not once a message of it went; not the root; not a stranger promoted.
        let e = p
            .remove_task(&rm, &BTreeSet::from([1, 2]), &bounds())
            .unwrap_err();
        assert_eq!(e.field, "task_id");
        let root = RemoveMissionTask {
            task_id: 1,
            ..rm.clone()
        };
        assert_eq!(
            p.remove_task(&root, &BTreeSet::new(), &bounds())
                .unwrap_err()
                .field,
            "task_id"
        );
        let stranger = RemoveMissionTask {
            promoted_children: vec![5],
            ..rm
        };
        assert_eq!(
            p.remove_task(&stranger, &BTreeSet::new(), &bounds())
                .unwrap_err()
                .field,
            "promoted_children[0]"
        );
    }

    #[test]
    fn a_task_inserted_beside_or_over_another() {
        let p = tree();
        let issued = BTreeSet::from([1]);
        let beside = InsertMissionTask {
            mission_id: 1,
            task_id: 2,
            insert_location: TaskInsertPosition::AfterTask,
            new_parent_task_id: 1,
            task: t(9, &[9], &[]),
        };
        let q = p.insert_task(&beside, &issued, &bounds()).unwrap();
        assert_eq!(order(&q), vec![1, 2, 3, 4, 9, 5]);
        let over = InsertMissionTask {
            insert_location: TaskInsertPosition::BeforeTask,
            new_parent_task_id: 9,
            ..beside.clone()
        };
        let q = p.insert_task(&over, &issued, &bounds()).unwrap();
        assert_eq!(order(&q), vec![1, 9, 2, 3, 4, 5]);
        // Over the root: the new root.
        let root = InsertMissionTask {
            task_id: 1,
            ..over.clone()
        };
        let q = p.insert_task(&root, &BTreeSet::new(), &bounds()).unwrap();
        assert_eq!(order(&q), vec![9, 1, 2, 3, 4, 5]);
        // Not before what went; not with children; not under another parent.
        assert_eq!(
            p.insert_task(&root, &issued, &bounds()).unwrap_err().field,
            "tasks"
        );
        let kids = InsertMissionTask {
            task: t(9, &[9], &[1]),
            ..beside.clone()
        };
        assert_eq!(
            p.insert_task(&kids, &issued, &bounds()).unwrap_err().field,
            "task.child_tasks"
        );
        let wrong = InsertMissionTask {
            new_parent_task_id: 3,
            ..beside
        };
        assert_eq!(
            p.insert_task(&wrong, &issued, &bounds()).unwrap_err().field,
            "new_parent_task_id"
        );
    }
}
