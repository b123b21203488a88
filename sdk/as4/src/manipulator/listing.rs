//! What the two manipulator list drivers share ([`super::list`], joint positions over
//! the RA 3.3 Joint Move Driver; [`super::pose_list`], end-effector poses over the RA
//! 3.3 End-Effector Pose Driver): the component's one List Manager and its elements,
//! the list being driven (the elements' UIDs and targets, the active one), the command
//! waiting for RA 3.3 control, the Manipulator List Driver's guards and its Report
//! Manipulator Active Element ([`list_driver!`]), which driver answers which message
//! ([`Listing::claims`]), Execute List's command event kept running until the list is
//! done ([`Listing::in_progress`]), and the end of a list: done, the component out of
//! Ready, control ended, or another command given to the arm.

use std::time::Instant;

use jaus::messages as ra;
use jaus::{Address, CommandCode, JausMessage};

use super::drivers::{deliver, flush};
use super::{Arm, LIST_ELEMENTS};
use crate::core::lists::Lists;
use crate::machined::On;
use crate::messages::services::transport::event::Receive;
use crate::messages::{ManipulatorExecuteList, ReportManipulatorActiveElement};
use crate::ra33::Ra33Side;
use crate::service::ServiceId;
use crate::Message;

/// A list being driven: its elements' UIDs and targets (from Execute List's element
/// on), the one being driven to.
#[derive(Debug)]
pub(super) struct Run<T> {
    /// The elements' UIDs, in order.
    pub uids: Vec<u16>,
    /// Their targets.
    pub targets: Vec<T>,
    /// The index of the element being driven to (`uids.len()` once all are reached).
    pub active: usize,
    /// When Execute List started it.
    pub started: Instant,
    /// [`Ra33Side::activations`] after the list's own last command.
    epoch: u64,
}

impl<T> Run<T> {
    /// The active element is reached: the next one becomes active.
    pub fn reach(&mut self, id: ServiceId) {
        if let Some(uid) = self.uids.get(self.active) {
            tracing::info!(service = %id, uid, "element reached");
            self.active += 1;
        }
    }

    /// Whether every element is reached.
    pub fn all_reached(&self) -> bool {
        self.active >= self.uids.len()
    }
}

/// A manipulator list driver's state: its service, the kind of element it drives, its
/// RA 3.3 driver, the arm, the list being driven and the command waiting for RA 3.3
/// control.
#[derive(Debug)]
pub(super) struct Listing<T> {
    id: ServiceId,
    kind: CommandCode,
    /// The RA 3.3 driver.
    pub driver: Address,
    /// The arm.
    pub arm: Arm,
    /// The list being driven.
    pub run: Option<Run<T>>,
    pending: Option<ra::Message>,
}

impl<T> Listing<T> {
    /// A driver of service `id` of the elements holding `kind`, over the RA 3.3 `driver`.
    pub fn new(id: ServiceId, kind: CommandCode, driver: Address, arm: Arm) -> Self {
        Self {
            id,
            kind,
            driver,
            arm,
            run: None,
            pending: None,
        }
    }

    /// The element being driven to (the last once all are reached, until the list is
    /// done): its UID and target.
    pub fn target(&self) -> Option<(u16, &T)> {
        let run = self.run.as_ref()?;
        let i = run.active.min(run.uids.len().checked_sub(1)?);
        Some((run.uids[i], &run.targets[i]))
    }

    /// Starts driving `list` (UIDs and targets) at `now`: `command` goes to the RA 3.3
    /// driver (now, or once control of it is granted), which becomes the arm's.
    pub fn start(
        &mut self,
        env: &mut Ra33Side,
        now: Instant,
        list: Vec<(u16, T)>,
        command: ra::Message,
    ) {
        let (uids, targets) = list.into_iter().unzip();
        self.run = Some(Run {
            uids,
            targets,
            active: 0,
            started: now,
            epoch: 0,
        });
        self.command(env, command);
    }

    /// Gives the RA 3.3 driver the next command of the list being driven.
    pub fn command(&mut self, env: &mut Ra33Side, command: ra::Message) {
        deliver(env, self.driver, command, &mut self.pending);
        if let Some(run) = self.run.as_mut() {
            run.epoch = env.activations(self.driver);
        }
    }

    /// Sends the command waiting for RA 3.3 control, and the list being driven, unless
    /// it ended: another command went to the arm (another driver's, or this RA 3.3
    /// driver's through another service), the component left Ready (its drivers went to
    /// standby, holding the arm) or control ended.
    pub fn follow(&mut self, env: &mut Ra33Side) -> Option<&mut Run<T>> {
        flush(env, self.driver, &mut self.pending);
        let run = self.run.as_ref()?;
        let why = if !env.controlled() {
            Some("control ended")
        } else if !env.is_active(self.driver) || env.activations(self.driver) != run.epoch {
            Some("the arm was given another command")
        } else {
            None
        };
        if let Some(why) = why {
            tracing::info!(service = %self.id, driver = %self.driver, "list ended: {why}");
            self.run = None;
            self.pending = None;
        }
        self.run.as_mut()
    }

    /// The list is done: no element is active any more.
    pub fn finish(&mut self) {
        if self.run.take().is_some() {
            tracing::info!(service = %self.id, "list finished");
        }
    }

    /// The component left Ready: the RA 3.3 driver is put in standby, which holds the
    /// arm where it is, and the list ends.
    pub fn stop(&mut self) {
        if self.run.take().is_some() {
            tracing::info!(service = %self.id, "list ended: the component left Ready");
        }
        self.pending = None;
    }

    /// Whether this driver answers `message`: Manipulator Execute List when the element
    /// it starts from (or the head) is not the other list driver's kind; Query
    /// Manipulator Active Element while it drives a list, or else when the list's head
    /// is not the other's kind; `commanded` (its Query Commanded ...) only while it
    /// drives a list; anything else.
    pub fn claims(&self, lists: &Lists, message: &Message, commanded: CommandCode) -> bool {
        let other = |uid: u16| {
            let code = lists
                .get(uid)
                .and_then(|el| el.message())
                .and_then(Result::ok)
                .map(|m| m.code());
            code.is_some_and(|c| c != self.kind && LIST_ELEMENTS.iter().any(|(_, k)| *k == c))
        };
        match message {
            Message::ManipulatorExecuteList(e) => start_of(lists, e).is_none_or(|s| !other(s)),
            Message::QueryManipulatorActiveElement(_) => {
                self.run.is_some() || lists.head().is_none_or(|h| !other(h))
            }
            m if m.code() == commanded => self.run.is_some(),
            _ => true,
        }
    }

    /// Whether the command `code` is still being carried out: Execute List until the
    /// list is done.
    pub fn in_progress(&self, code: CommandCode) -> bool {
        code == ManipulatorExecuteList::CODE && self.run.is_some()
    }
}

/// The UID a Manipulator Execute List starts from: the one it names, else the list's
/// head; `None` when the list holds no such element.
pub(super) fn start_of(lists: &Lists, e: &ManipulatorExecuteList) -> Option<u16> {
    match e.element_uid {
        Some(uid) => lists.get(uid).map(|_| uid),
        None => lists.head(),
    }
}

/// The elements of the list from `start`, each holding a message of `kind` (`name`)
/// made a target by `target`, or why one is not (naming its UID).
pub(super) fn elements<T>(
    lists: &Lists,
    start: u16,
    kind: CommandCode,
    name: &str,
    mut target: impl FnMut(&Message) -> Result<T, String>,
) -> Result<Vec<(u16, T)>, String> {
    let mut out = Vec::new();
    for el in lists.iter_from(start) {
        let uid = el.uid;
        let m = match el.message() {
            Some(Ok(m)) if m.code() == kind => m,
            Some(Ok(m)) => {
                return Err(format!("element {uid}: a {}, not a {name}", m.name()));
            }
            Some(Err(e)) => return Err(format!("element {uid}: {name} not decoded: {e}")),
            None => return Err(format!("element {uid}: user-defined, not a {name}")),
        };
        let t = target(&m).map_err(|why| format!("element {uid}: {why}"))?;
        out.push((uid, t));
    }
    Ok(out)
}

/// A manipulator list driver's data: its [`Listing`], and the check of the list.
pub(super) trait ListDriving {
    /// What an element is driven to.
    type Target;
    /// Its service.
    const ID: ServiceId;
    /// Its list.
    fn listing(&self) -> &Listing<Self::Target>;
    /// The elements of the list from `start`, checked (the kind of message, the target
    /// reachable), or why one is not.
    fn check(
        &self,
        env: &Ra33Side,
        lists: &Lists,
        start: u16,
    ) -> Result<Vec<(u16, Self::Target)>, String>;
}

/// The `elementExists` guard: Execute List names an element of the list, or none and
/// the list has a head.
pub(super) fn element_exists<T: ListDriving>(on: &On<'_, T>, msg: &ManipulatorExecuteList) -> bool {
    start_of(on.lists, msg).is_some()
}

/// The `isListValid` guard: every element from the head is a target this driver can
/// reach (logged with the element and why when not).
pub(super) fn is_list_valid<T: ListDriving>(on: &On<'_, T>) -> bool {
    let Some(head) = on.lists.head() else {
        tracing::info!(service = %T::ID, "Manipulator Execute List: the list is empty");
        return false;
    };
    match on.svc.check(on.env, on.lists, head) {
        Ok(_) => true,
        Err(why) => {
            tracing::info!(service = %T::ID, "Manipulator Execute List: list not valid: {why}");
            false
        }
    }
}

/// Report Manipulator Active Element: the element being driven to, 0 when none.
pub(super) fn report_active_element<T: ListDriving>(on: &mut On<'_, T>, transport: &Receive) {
    let element_uid = on.svc.listing().target().map_or(0, |(uid, _)| uid);
    on.reply(transport, ReportManipulatorActiveElement { element_uid });
}

/// Implements the Manipulator List Driver (the parent of both list drivers) for
/// `On<'_, $data>` over [`ListDriving`].
macro_rules! list_driver {
    ($data:ty) => {
        impl $crate::messages::services::manipulator_list_driver::ManipulatorListDriver
            for $crate::machined::On<'_, $data>
        {
            fn element_exists(&self, msg: &$crate::messages::ManipulatorExecuteList) -> bool {
                $crate::manipulator::listing::element_exists(self, msg)
            }

            fn is_list_valid(&self) -> bool {
                $crate::manipulator::listing::is_list_valid(self)
            }

            fn send_report_manipulator_active_element(
                &mut self,
                transport: &$crate::messages::services::transport::event::Receive,
            ) {
                $crate::manipulator::listing::report_active_element(self, transport)
            }
        }
    };
}
pub(super) use list_driver;
