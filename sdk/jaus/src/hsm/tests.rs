//! The engine on a hand-written machine: the order of exits, actions and entries, guard
//! precedence, defaults, push and pop.

use super::*;

// Top (initial A)
//   A        entry 10, exit 11
//   B        entry 20, exit 21, initial B1
//     B1     entry 30, exit 31
//     B2     entry 40, exit 41
// Call sites: guards 0 (`ok`), 1 (`no`); actions 1.. as numbered.
static TOP_T: [Transition; 1] = [Transition {
    trigger: Some("reset"),
    guard: None,
    kind: Kind::Simple,
    target: Some(1),
    actions: &[90],
    raise: None,
}];
static NOT_NO: Expr = Expr::Not(&Expr::Call(1));
static GUARD_AND: Expr = Expr::And(&[Expr::Call(0), Expr::Not(&Expr::Call(1))]);
static GUARD_OR: Expr = Expr::Or(&[Expr::Call(1), Expr::Call(0)]);
static GUARD_NO: Expr = Expr::Call(1);
static A_T: [Transition; 3] = [
    Transition {
        trigger: Some("go"),
        guard: Some(&GUARD_NO),
        kind: Kind::Simple,
        target: Some(4),
        actions: &[99],
        raise: None,
    },
    Transition {
        trigger: Some("go"),
        guard: Some(&GUARD_AND),
        kind: Kind::Simple,
        target: Some(3),
        actions: &[1, 2],
        raise: None,
    },
    Transition {
        trigger: Some("push"),
        guard: Some(&GUARD_OR),
        kind: Kind::Push,
        target: Some(4),
        actions: &[3],
        raise: None,
    },
];
static B_T: [Transition; 2] = [
    Transition {
        trigger: Some("tick"),
        guard: Some(&NOT_NO),
        kind: Kind::Internal,
        target: None,
        actions: &[5],
        raise: None,
    },
    Transition {
        trigger: Some("pop"),
        guard: None,
        kind: Kind::Pop,
        target: None,
        actions: &[6],
        raise: Some("popped"),
    },
];
static B1_T: [Transition; 1] = [Transition {
    trigger: Some("tick"),
    guard: None,
    kind: Kind::Internal,
    target: None,
    actions: &[4],
    raise: None,
}];
static A_POPPED: [Transition; 2] = [
    A_T[2],
    Transition {
        trigger: Some("popped"),
        guard: None,
        kind: Kind::Internal,
        target: None,
        actions: &[7],
        raise: None,
    },
];
static B2_DEFAULT: [Transition; 1] = [Transition {
    trigger: None,
    guard: None,
    kind: Kind::Simple,
    target: None,
    actions: &[8],
    raise: None,
}];
static MACHINE_DEFAULT: [Transition; 1] = [Transition {
    trigger: None,
    guard: None,
    kind: Kind::Internal,
    target: None,
    actions: &[9],
    raise: None,
}];
static STATES: [State; 5] = [
    State {
        name: "Top",
        path: "Top",
        parent: None,
        initial: Some(1),
        entry: &[100],
        exit: &[101],
        transitions: &TOP_T,
        defaults: &[],
    },
    State {
        name: "A",
        path: "Top.A",
        parent: Some(0),
        initial: None,
        entry: &[10],
        exit: &[11],
        transitions: &A_T,
        defaults: &[],
    },
    State {
        name: "B",
        path: "Top.B",
        parent: Some(0),
        initial: Some(3),
        entry: &[20],
        exit: &[21],
        transitions: &B_T,
        defaults: &[],
    },
    State {
        name: "B1",
        path: "Top.B.B1",
        parent: Some(2),
        initial: None,
        entry: &[30],
        exit: &[31],
        transitions: &B1_T,
        defaults: &[],
    },
    State {
        name: "B2",
        path: "Top.B.B2",
        parent: Some(2),
        initial: None,
        entry: &[40],
        exit: &[41],
        transitions: &[],
        defaults: &B2_DEFAULT,
    },
];
static A_WITH_POPPED: [State; 5] = {
    let mut s = STATES;
    s[1].transitions = &A_POPPED;
    s
};
static DEF: MachineDef = MachineDef {
    service: "Test",
    name: "FSM",
    states: &STATES,
    start: 0,
    transitions: &[],
    defaults: &MACHINE_DEFAULT,
};
static DEF_POPPED: MachineDef = MachineDef {
    service: "Test",
    name: "FSM",
    states: &A_WITH_POPPED,
    start: 0,
    transitions: &[],
    defaults: &[],
};

#[derive(Default)]
struct Log {
    calls: Vec<u16>,
    guards: std::cell::RefCell<Vec<u16>>,
}

impl Host<()> for Log {
    fn guard(&self, n: u16, _: Option<&()>) -> bool {
        self.guards.borrow_mut().push(n);
        n == 0
    }
    fn action(&mut self, n: u16, _: Option<&()>) {
        self.calls.push(n);
    }
}

fn take(log: &mut Log) -> Vec<u16> {
    std::mem::take(&mut log.calls)
}

#[test]
fn start_enters_the_start_state_and_its_initial_sub_states() {
    let mut m = Machine::new(&DEF);
    let mut log = Log::default();
    m.start(&mut log);
    assert_eq!(m.path(), "Top.A");
    assert_eq!(take(&mut log), [100, 10]);
    m.start(&mut log);
    assert!(take(&mut log).is_empty(), "start runs once");
}

#[test]
fn exits_then_actions_then_entries_down_through_initial_states() {
    let mut m = Machine::new(&DEF);
    let mut log = Log::default();
    m.start(&mut log);
    take(&mut log);
    // The first `go` has a false guard; the second (ok && !no) holds.
    let step = m.handle(&mut log, "go", &());
    assert_eq!(
        step,
        Step::Taken {
            from: "Top.A",
            to: "Top.B.B1"
        }
    );
    assert_eq!(take(&mut log), [11, 1, 2, 20, 30]);
    assert_eq!(*log.guards.borrow(), [1, 0, 1]);
    assert!(m.is_in("Top.B") && m.is_in("Top") && !m.is_in("Top.A"));
}

#[test]
fn the_innermost_state_answers_first_then_ancestors() {
    let mut m = Machine::new(&DEF);
    let mut log = Log::default();
    m.handle(&mut log, "go", &());
    take(&mut log);
    // B1 answers `tick` itself (action 4), not B (action 5).
    assert_eq!(
        m.handle(&mut log, "tick", &()),
        Step::Taken {
            from: "Top.B.B1",
            to: "Top.B.B1"
        }
    );
    assert_eq!(take(&mut log), [4]);
    // Top's transition to its own sub-state A is external: B1, B and Top are left,
    // Top and A entered.
    m.handle(&mut log, "reset", &());
    assert_eq!(take(&mut log), [31, 21, 101, 90, 100, 10]);
    assert_eq!(m.path(), "Top.A");
}

#[test]
fn push_remembers_and_pop_returns_then_raises() {
    let mut m = Machine::new(&DEF_POPPED);
    let mut log = Log::default();
    m.start(&mut log);
    take(&mut log);
    // no || ok holds: push to B2 (no initial descent below a leaf).
    m.handle(&mut log, "push", &());
    assert_eq!(m.path(), "Top.B.B2");
    assert_eq!(take(&mut log), [11, 3, 20, 40]);
    // B answers `pop`: back to A, then A answers the raised `popped`.
    let step = m.handle(&mut log, "pop", &());
    assert_eq!(
        step,
        Step::Taken {
            from: "Top.B.B2",
            to: "Top.A"
        }
    );
    assert_eq!(take(&mut log), [41, 21, 6, 10, 7]);
    // Nothing pushed: pop runs its actions and stays; here only the machine's default
    // answers the raised trigger.
    let mut m = Machine::new(&DEF);
    m.handle(&mut log, "go", &());
    take(&mut log);
    m.handle(&mut log, "pop", &());
    assert_eq!(m.path(), "Top.B.B1");
    assert_eq!(take(&mut log), [6, 9]);
}

#[test]
fn default_transitions_come_after_every_triggered_one() {
    let mut m = Machine::new(&DEF);
    let mut log = Log::default();
    m.start(&mut log);
    take(&mut log);
    // A has no `unknown` and no default transition: the machine's default (internal).
    assert_eq!(
        m.handle(&mut log, "unknown", &()),
        Step::Taken {
            from: "Top.A",
            to: "Top.A"
        }
    );
    assert_eq!(take(&mut log), [9]);
    m.handle(&mut log, "push", &());
    take(&mut log);
    // B2's default (simple, no target) leaves and re-enters B2, before the machine's.
    m.handle(&mut log, "unknown", &());
    assert_eq!(take(&mut log), [41, 8, 40]);
    // `tick` is B's (a triggered transition of an ancestor beats B2's default).
    m.handle(&mut log, "tick", &());
    assert_eq!(take(&mut log), [5]);
}

#[test]
fn an_unanswered_trigger_is_ignored() {
    let mut m = Machine::new(&DEF_POPPED);
    let mut log = Log::default();
    m.start(&mut log);
    take(&mut log);
    assert_eq!(m.handle(&mut log, "tick", &()), Step::Ignored);
    assert!(take(&mut log).is_empty());
    assert_eq!(m.path(), "Top.A");
}

#[test]
fn follow_goes_to_the_deepest_shared_state_without_actions() {
    let mut m = Machine::new(&DEF);
    let mut log = Log::default();
    m.start(&mut log);
    take(&mut log);
    // The parent is in `Top.B.X.Y`, states this machine lacks: the deepest shared state
    // is `Top.B`, entered through its initial sub-state, without any action.
    assert!(m.follow("Top.B.X.Y"));
    assert_eq!(m.path(), "Top.B.B1");
    assert!(take(&mut log).is_empty(), "following runs no action");
    // Already inside `Top.B` (in B2): kept there.
    m.follow("Top.B.B2");
    assert_eq!(m.path(), "Top.B.B2");
    assert!(!m.follow("Top.B"), "already inside Top.B");
    assert_eq!(m.path(), "Top.B.B2");
    // Nothing shared: nothing changes.
    assert!(!m.follow("Elsewhere.C"));
    assert_eq!(m.path(), "Top.B.B2");
    // Back to A; then the machine goes on from there.
    assert!(m.follow("Top.A"));
    assert_eq!(m.path(), "Top.A");
    assert!(matches!(m.handle(&mut log, "go", &()), Step::Taken { .. }));
}

#[test]
fn follow_with_runs_the_exits_and_entries_on_the_way() {
    let mut m = Machine::new(&DEF);
    let mut log = Log::default();
    m.start(&mut log);
    take(&mut log);
    // A → B (through its initial B1): A's exit, then B's and B1's entries; Top is
    // shared and neither left nor entered.
    assert!(m.follow_with("Top.B.X", &mut log));
    assert_eq!(m.path(), "Top.B.B1");
    assert_eq!(take(&mut log), [11, 20, 30]);
    // B1 → B2 inside B: B1's exit, B2's entry.
    assert!(m.follow_with("Top.B.B2", &mut log));
    assert_eq!(take(&mut log), [31, 40]);
    // Already there: nothing runs.
    assert!(!m.follow_with("Top.B", &mut log));
    assert!(take(&mut log).is_empty());
    // Back to A: B2's and B's exits, A's entry.
    assert!(m.follow_with("Top.A", &mut log));
    assert_eq!(take(&mut log), [41, 21, 10]);
}

#[test]
fn follow_with_before_start_leaves_the_start_state_without_entering_it() {
    // Not started: taken to be in its start state (Top, whose initial is A), entered
    // without actions; following to B runs only B's and B1's entries.
    let mut m = Machine::new(&DEF);
    let mut log = Log::default();
    assert!(m.follow_with("Top.B", &mut log));
    assert_eq!(m.path(), "Top.B.B1");
    assert_eq!(take(&mut log), [20, 30]);
    assert!(m.is_started());
}
