//! A generic, table-driven hierarchical state machine engine: the runtime of the
//! services that `jaus-gen` generates from SAE AS-4 (JSIDL) protocol behaviour.
//!
//! Sans-IO like the component runtime: no threads, sockets or clocks. The machine is
//! static data ([`MachineDef`]: states with their parent, initial sub-state, entry and
//! exit actions, transitions with a trigger, a guard [`Expr`], a [`Kind`], a target and
//! actions); the guards and actions are numbered call sites that a [`Host`] runs (the
//! generated code maps each to a method of the service's trait). Time, where a service
//! needs it, is the owner's: a timeout is an internal event it raises like any other
//! trigger.
//!
//! # Semantics
//!
//! * **Run to completion**: [`Machine::handle`] takes one trigger and returns when it and
//!   every trigger a `pop` raised on the way are done.
//! * **Which transition**: the transitions for the trigger of the current (leaf) state,
//!   then of each ancestor up to the top, then those of the machine's default state; the
//!   first whose guard holds is taken. Only if none is, the default transitions (any
//!   trigger) in the same order: leaf, ancestors, machine.
//! * **Order of actions** (UML, SMC): the exit actions from the current leaf up to (not
//!   including) the least common ancestor of the transition's source and target, then
//!   the transition's actions, then the entry actions from below that ancestor down to the
//!   target and on through the initial sub-states to a leaf. A transition whose target
//!   is its source or one of the source's ancestors or descendants leaves and re-enters
//!   the outer of the two (an external transition).
//! * **Kinds**: `internal` runs its actions only; `simple` moves to its target (without
//!   one, it leaves and re-enters the state that owns it, or the current leaf for a
//!   machine-level transition); `push` does the same and remembers the state it left;
//!   `pop` returns to the state remembered by the last `push` (staying put, with its
//!   actions run, when nothing was pushed) and then raises its trigger, if it names one.
//!
//! Every transition taken is traced (`tracing::trace!` with the service, machine, state
//! left, trigger and state reached), so `-vvv` of the command-line tools shows it.

#[cfg(test)]
mod tests;

use std::collections::VecDeque;

/// The index of a state in [`MachineDef::states`].
pub type StateId = u16;

/// A guard expression, parsed by the generator and kept as data.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Expr {
    /// Guard call site `n` (a [`Host::guard`] call).
    Call(u16),
    /// A constant.
    Const(bool),
    /// Negation.
    Not(&'static Expr),
    /// All hold (evaluated left to right, stopping at the first that does not).
    And(&'static [Expr]),
    /// Any holds (evaluated left to right, stopping at the first that does).
    Or(&'static [Expr]),
}

impl Expr {
    /// Evaluates the expression, calling the host for each guard it needs.
    pub fn eval<T: ?Sized, H: Host<T> + ?Sized>(&self, host: &H, trigger: Option<&T>) -> bool {
        match self {
            Expr::Call(n) => host.guard(*n, trigger),
            Expr::Const(b) => *b,
            Expr::Not(e) => !e.eval(host, trigger),
            Expr::And(es) => es.iter().all(|e| e.eval(host, trigger)),
            Expr::Or(es) => es.iter().any(|e| e.eval(host, trigger)),
        }
    }
}

/// What a transition does to the state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Runs its actions and stays: no exit or entry actions run.
    Internal,
    /// Moves to its target.
    Simple,
    /// Moves to its target, remembering the state it left.
    Push,
    /// Returns to the state the last push left.
    Pop,
}

/// A transition.
#[derive(Debug, Clone, Copy)]
pub struct Transition {
    /// The trigger it answers; `None` for a default transition (any trigger).
    pub trigger: Option<&'static str>,
    /// The condition under which it is taken (`None`: always).
    pub guard: Option<&'static Expr>,
    /// What it does to the state.
    pub kind: Kind,
    /// The state it leads to (`Simple`, `Push`).
    pub target: Option<StateId>,
    /// Its action call sites, in order.
    pub actions: &'static [u16],
    /// For `Pop`: the trigger raised after returning.
    pub raise: Option<&'static str>,
}

/// A state.
#[derive(Debug, Clone, Copy)]
pub struct State {
    /// Its name.
    pub name: &'static str,
    /// Its path from the machine's top (`Receiving.Ready.Controlled`).
    pub path: &'static str,
    /// The state it is a sub-state of.
    pub parent: Option<StateId>,
    /// The sub-state entered with it.
    pub initial: Option<StateId>,
    /// Action call sites on entering it.
    pub entry: &'static [u16],
    /// Action call sites on leaving it.
    pub exit: &'static [u16],
    /// Its transitions by trigger (its own, then those of its default state).
    pub transitions: &'static [Transition],
    /// Its default transitions (any trigger).
    pub defaults: &'static [Transition],
}

/// A state machine as data.
#[derive(Debug, Clone, Copy)]
pub struct MachineDef {
    /// The service it belongs to (for traces and errors).
    pub service: &'static str,
    /// Its name.
    pub name: &'static str,
    /// Its states; a parent comes before its sub-states.
    pub states: &'static [State],
    /// Where it starts (entered with its ancestors and initial sub-states).
    pub start: StateId,
    /// The transitions of its default state, by trigger.
    pub transitions: &'static [Transition],
    /// The default transitions of its default state (any trigger).
    pub defaults: &'static [Transition],
}

/// Runs the guards and actions of a machine: the generated code implements it over the
/// service's trait. `trigger` is `None` for the entry actions run by [`Machine::start`].
pub trait Host<T: ?Sized> {
    /// Evaluates guard call site `n`.
    fn guard(&self, n: u16, trigger: Option<&T>) -> bool;
    /// Runs action call site `n`.
    fn action(&mut self, n: u16, trigger: Option<&T>);
}

/// What [`Machine::handle`] did with a trigger.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Step {
    /// A transition was taken: from the state (path) it was in to the one it is in.
    Taken {
        /// The path of the state before.
        from: &'static str,
        /// The path of the state after.
        to: &'static str,
    },
    /// No transition answers the trigger in the current state (or no guard held).
    Ignored,
}

/// At most this many triggers raised by `pop` transitions run in one
/// [`Machine::handle`] (a cycle of pops raising each other ends here).
pub const MAX_RAISED: usize = 64;

/// Most nested pushes remembered (the oldest is forgotten beyond it).
pub const MAX_PUSHED: usize = 64;

/// What [`Machine::state`] returns for an id outside the table.
static NO_STATE: State = State {
    name: "",
    path: "",
    parent: None,
    initial: None,
    entry: &[],
    exit: &[],
    transitions: &[],
    defaults: &[],
};

/// A running state machine.
#[derive(Debug, Clone)]
pub struct Machine {
    def: &'static MachineDef,
    current: StateId,
    pushed: Vec<StateId>,
    started: bool,
}

impl Machine {
    /// A machine of `def`, not started: [`start`](Self::start) enters its start state.
    pub fn new(def: &'static MachineDef) -> Self {
        Self {
            def,
            current: def.start,
            pushed: Vec::new(),
            started: false,
        }
    }

    /// A machine of `def` already in state `state` (a leaf), started, without running
    /// any entry action: to go on from a state kept elsewhere.
    pub fn resume_at(def: &'static MachineDef, state: StateId) -> Self {
        Self {
            def,
            current: state,
            pushed: Vec::new(),
            started: true,
        }
    }

    /// Its definition.
    pub fn def(&self) -> &'static MachineDef {
        self.def
    }

    /// Enters the start state: the entry actions of its ancestors, of it, and of its
    /// initial sub-states, top down. Does nothing once started.
    pub fn start<T: ?Sized, H: Host<T> + ?Sized>(&mut self, host: &mut H) {
        if self.started {
            return;
        }
        self.started = true;
        let start = self.def.start;
        self.current = start;
        let mut path = self.ancestors(start);
        path.reverse();
        for s in path {
            self.run(host, self.state(s).entry, None);
        }
        self.current = self.descend(host, start, None);
        tracing::trace!(
            service = self.def.service,
            machine = self.def.name,
            to = self.path(),
            "started"
        );
    }

    /// Whether [`start`](Self::start) ran.
    pub fn is_started(&self) -> bool {
        self.started
    }

    /// The state `id` (a placeholder without transitions for an id outside the table).
    pub fn state(&self, id: StateId) -> &'static State {
        self.def.states.get(usize::from(id)).unwrap_or(&NO_STATE)
    }

    /// The current state's id.
    pub fn current(&self) -> StateId {
        self.current
    }

    /// The current state's path (`Receiving.Ready.Controlled.Available`).
    pub fn path(&self) -> &'static str {
        self.state(self.current).path
    }

    /// Whether the current state is the state at `path` or inside it
    /// (`is_in("Receiving.Ready.Controlled")`).
    pub fn is_in(&self, path: &str) -> bool {
        self.ancestors(self.current)
            .into_iter()
            .any(|s| self.state(s).path == path)
    }

    /// Follows a machine this one extends, whose current state is at `path`, without
    /// running any action ([`follow_with`](Self::follow_with) over [`NoHost`]).
    pub fn follow(&mut self, path: &str) -> bool {
        self.follow_with::<(), _>(path, &mut NoHost)
    }

    /// Follows a machine this one extends, whose current state is at `path` (a state
    /// path of the parent's machine, such as `Receiving.Ready.Controlled.Available`):
    /// the machine goes to the deepest of its states whose path is `path` or a prefix
    /// of it, on through their initial sub-states, unless it already is inside that
    /// state. On the way it runs the exit actions of the states it leaves (from the
    /// current leaf up to, not including, the least common ancestor) and the entry
    /// actions of those it enters, top down, on `host` with no trigger: a host that
    /// runs only the extending service's own actions runs what the service added to
    /// the shared states (an exit action of `Ready`), the parent's having run in the
    /// parent. A machine not started is taken to be in its start state, entered
    /// without actions. Returns whether the state changed. A `path` that shares no
    /// state with this machine changes nothing.
    pub fn follow_with<T: ?Sized, H: Host<T> + ?Sized>(
        &mut self,
        path: &str,
        host: &mut H,
    ) -> bool {
        // Already there, or inside it (the common case: the parent did not move since
        // the last message): one comparison, no search.
        let here = self.state(self.current).path;
        if self.started
            && here
                .strip_prefix(path)
                .is_some_and(|rest| rest.is_empty() || rest.starts_with('.'))
        {
            return false;
        }
        let mut at = path;
        let target = loop {
            if let Some(id) = state_id(self.def, at) {
                break id;
            }
            match at.rfind('.') {
                Some(i) => at = &at[..i],
                None => return false,
            }
        };
        self.started = true;
        let left = self.ancestors(self.current);
        if left.contains(&target) {
            return false;
        }
        self.pushed.clear();
        let down = self.ancestors(target);
        let lca = left.iter().copied().find(|s| down.contains(s));
        for s in left {
            if Some(s) == lca {
                break;
            }
            self.run(host, self.state(s).exit, None);
        }
        let entered: Vec<StateId> = down.into_iter().take_while(|s| Some(*s) != lca).collect();
        for s in entered.into_iter().rev() {
            self.run(host, self.state(s).entry, None);
        }
        self.current = self.descend(host, target, None);
        tracing::trace!(
            service = self.def.service,
            machine = self.def.name,
            follows = path,
            to = self.path(),
            "followed"
        );
        true
    }

    /// Handles one trigger to completion (starting the machine first if needed). The
    /// trigger's name is `key`; `payload` is passed to the guards and actions.
    pub fn handle<T: ?Sized, H: Host<T> + ?Sized>(
        &mut self,
        host: &mut H,
        key: &'static str,
        payload: &T,
    ) -> Step {
        self.start(host);
        let from = self.path();
        let mut queue: VecDeque<&'static str> = VecDeque::from([key]);
        let mut taken = false;
        let mut raised = 0;
        while let Some(k) = queue.pop_front() {
            let Some(raise) = self.fire(host, k, payload) else {
                continue;
            };
            taken = true;
            let Some(next) = raise else { continue };
            if raised < MAX_RAISED {
                raised += 1;
                queue.push_back(next);
            } else {
                tracing::warn!(
                    service = self.def.service,
                    machine = self.def.name,
                    trigger = next,
                    "more than {MAX_RAISED} triggers raised by pop transitions: dropped"
                );
            }
        }
        if taken {
            Step::Taken {
                from,
                to: self.path(),
            }
        } else {
            Step::Ignored
        }
    }

    /// Takes the transition for `key` in the current state, if any: `None` when none
    /// answers, `Some(raised)` with the trigger a pop raises.
    fn fire<T: ?Sized, H: Host<T> + ?Sized>(
        &mut self,
        host: &mut H,
        key: &'static str,
        payload: &T,
    ) -> Option<Option<&'static str>> {
        let (owner, t) = self.select(host, key, payload)?;
        let from = self.path();
        match t.kind {
            Kind::Internal => self.run(host, t.actions, Some(payload)),
            Kind::Simple | Kind::Push => {
                let source = owner.unwrap_or(self.current);
                let target = t.target.unwrap_or(source);
                if t.kind == Kind::Push {
                    if self.pushed.len() >= MAX_PUSHED {
                        self.pushed.remove(0);
                    }
                    self.pushed.push(self.current);
                }
                self.go(host, source, target, t.actions, payload, true);
            }
            Kind::Pop => match self.pushed.pop() {
                Some(back) => self.go(host, self.current, back, t.actions, payload, false),
                None => self.run(host, t.actions, Some(payload)),
            },
        }
        tracing::trace!(
            service = self.def.service,
            machine = self.def.name,
            from,
            trigger = key,
            to = self.path(),
            "transition"
        );
        Some(t.raise)
    }

    /// The transition answering `key`, with the state owning it (`None`: the machine's
    /// default state).
    fn select<T: ?Sized, H: Host<T> + ?Sized>(
        &self,
        host: &H,
        key: &str,
        payload: &T,
    ) -> Option<(Option<StateId>, &'static Transition)> {
        let chain = self.ancestors(self.current);
        let holds = |t: &&'static Transition| t.guard.is_none_or(|g| g.eval(host, Some(payload)));
        let by_trigger =
            |ts: &'static [Transition]| ts.iter().filter(|t| t.trigger == Some(key)).find(holds);
        let any = |ts: &'static [Transition]| ts.iter().find(holds);
        for s in &chain {
            if let Some(t) = by_trigger(self.state(*s).transitions) {
                return Some((Some(*s), t));
            }
        }
        if let Some(t) = by_trigger(self.def.transitions) {
            return Some((None, t));
        }
        for s in &chain {
            if let Some(t) = any(self.state(*s).defaults) {
                return Some((Some(*s), t));
            }
        }
        any(self.def.defaults).map(|t| (None, t))
    }

    /// Moves from the current leaf to `target` for a transition owned by `source`:
    /// exits, the transition's actions, entries (and, with `descend`, the initial
    /// sub-states below `target`).
    fn go<T: ?Sized, H: Host<T> + ?Sized>(
        &mut self,
        host: &mut H,
        source: StateId,
        target: StateId,
        actions: &'static [u16],
        payload: &T,
        descend: bool,
    ) {
        let up = self.ancestors(source);
        let down = self.ancestors(target);
        // The least common ancestor; an external transition between a state and its
        // ancestor (or itself) leaves and re-enters the outer one.
        let mut lca = up.iter().copied().find(|s| down.contains(s));
        if lca == Some(source) || lca == Some(target) {
            lca = lca.and_then(|s| self.state(s).parent);
        }
        for s in self.ancestors(self.current) {
            if Some(s) == lca {
                break;
            }
            self.run(host, self.state(s).exit, Some(payload));
        }
        self.run(host, actions, Some(payload));
        let entered: Vec<StateId> = down.into_iter().take_while(|s| Some(*s) != lca).collect();
        for s in entered.into_iter().rev() {
            self.run(host, self.state(s).entry, Some(payload));
        }
        self.current = if descend {
            self.descend(host, target, Some(payload))
        } else {
            target
        };
    }

    /// Enters the initial sub-states below `s`, down to a leaf; returns the leaf.
    fn descend<T: ?Sized, H: Host<T> + ?Sized>(
        &self,
        host: &mut H,
        mut s: StateId,
        payload: Option<&T>,
    ) -> StateId {
        // A parent comes before its sub-states, so this ends; the bound guards against a
        // malformed table.
        for _ in 0..self.def.states.len() {
            match self.state(s).initial {
                Some(child) if child != s => {
                    self.run(host, self.state(child).entry, payload);
                    s = child;
                }
                _ => break,
            }
        }
        s
    }

    /// `s` and its ancestors, innermost first.
    fn ancestors(&self, s: StateId) -> Vec<StateId> {
        let mut out = vec![s];
        let mut at = s;
        while let Some(p) = self.state(at).parent {
            if out.contains(&p) || out.len() > self.def.states.len() {
                break;
            }
            out.push(p);
            at = p;
        }
        out
    }

    fn run<T: ?Sized, H: Host<T> + ?Sized>(
        &self,
        host: &mut H,
        actions: &'static [u16],
        payload: Option<&T>,
    ) {
        for a in actions {
            host.action(*a, payload);
        }
    }
}

/// A [`Host`] for tables without guards or actions (RA 3.3 core states, a component's
/// modes): every guard fails, no action runs.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoHost;

impl<T: ?Sized> Host<T> for NoHost {
    fn guard(&self, _: u16, _: Option<&T>) -> bool {
        false
    }
    fn action(&mut self, _: u16, _: Option<&T>) {}
}

/// The state a machine of `def` without guards or actions reaches from state `from` on
/// trigger `key`: `None` when no transition answers `key` there. The state's id in
/// `def.states`.
pub fn next_state(def: &'static MachineDef, from: StateId, key: &'static str) -> Option<StateId> {
    let mut m = Machine::resume_at(def, from);
    match m.handle(&mut NoHost, key, &()) {
        Step::Taken { .. } => Some(m.current()),
        Step::Ignored => None,
    }
}

/// The id of the state at `path` in `def` (`Live.Ready`).
pub fn state_id(def: &MachineDef, path: &str) -> Option<StateId> {
    def.states
        .iter()
        .position(|s| s.path == path)
        .and_then(|i| StateId::try_from(i).ok())
}

/// The state machines of one service: every trigger is offered to each of them.
#[derive(Debug, Clone)]
pub struct Machines {
    machines: Vec<Machine>,
}

impl Machines {
    /// The machines of `defs`, not started.
    pub fn new(defs: &'static [&'static MachineDef]) -> Self {
        Self {
            machines: defs.iter().map(|d| Machine::new(d)).collect(),
        }
    }

    /// Starts every machine ([`Machine::start`]).
    pub fn start<T: ?Sized, H: Host<T> + ?Sized>(&mut self, host: &mut H) {
        for m in &mut self.machines {
            m.start(host);
        }
    }

    /// Offers the trigger to every machine; whether one took a transition.
    pub fn handle<T: ?Sized, H: Host<T> + ?Sized>(
        &mut self,
        host: &mut H,
        key: &'static str,
        payload: &T,
    ) -> bool {
        let mut taken = false;
        for m in &mut self.machines {
            taken |= m.handle(host, key, payload) != Step::Ignored;
        }
        taken
    }

    /// Makes the machine named `machine` follow the machine it extends, now at `path`
    /// ([`Machine::follow`]); whether its state changed (false for an unknown machine).
    pub fn follow(&mut self, machine: &str, path: &str) -> bool {
        self.machines
            .iter_mut()
            .find(|m| m.def().name == machine)
            .is_some_and(|m| m.follow(path))
    }

    /// Makes every machine follow the machine it extends, now at `path`
    /// ([`Machine::follow`]); whether one's state changed.
    pub fn follow_all(&mut self, path: &str) -> bool {
        self.follow_all_with::<(), _>(path, &mut NoHost)
    }

    /// Makes every machine follow the machine it extends, now at `path`, running the
    /// exit and entry actions on the way on `host` ([`Machine::follow_with`]); whether
    /// one's state changed.
    pub fn follow_all_with<T: ?Sized, H: Host<T> + ?Sized>(
        &mut self,
        path: &str,
        host: &mut H,
    ) -> bool {
        let mut changed = false;
        for m in &mut self.machines {
            changed |= m.follow_with(path, host);
        }
        changed
    }

    /// The current state's path in the machine named `machine`.
    pub fn state(&self, machine: &str) -> Option<&'static str> {
        self.get(machine).map(Machine::path)
    }

    /// The machine named `machine`.
    pub fn get(&self, machine: &str) -> Option<&Machine> {
        self.machines.iter().find(|m| m.def().name == machine)
    }

    /// Every machine, in definition order.
    pub fn iter(&self) -> impl Iterator<Item = &Machine> {
        self.machines.iter()
    }
}
