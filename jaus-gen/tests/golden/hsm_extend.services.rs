#[allow(unused_imports)]
use super::*;
#[allow(unused_imports)]
use ::jaus::hsm;
/// Counter: trait [`Counter`](counter::Counter), its triggers and state machines (hsm_extend.yaml:7).
#[allow(clippy::module_inception)]
pub mod counter {
    #[allow(unused_imports)]
    use super::*;
    /// The service's URI and version.
    pub const ID: &str = "urn:test:hsm:Counter 1.0";
    /// The service's URI.
    pub const URI: &str = "urn:test:hsm:Counter";
    /// The service's version: major, minor.
    pub const VERSION: (u8, u8) = (1, 0);
    /// The internal events of Counter: triggers of its transitions that are not
    /// received messages.
    pub mod event {
        #[allow(unused_imports)]
        use super::*;
        /// Internal event `Bump` of [`Counter`].
        #[derive(Debug, Clone, PartialEq)]
        pub struct Bump {}
        /// Internal event `Reset` of [`Counter`].
        #[derive(Debug, Clone, PartialEq)]
        pub struct Reset {}
    }
    /// The Counter service (`urn:test:hsm:Counter` version 1.0).
    ///
    /// Implement its guards and actions; [`Machines`] runs its state machines over the
    /// implementation.
    pub trait Counter {
        /// Called as `add()` (hsm_extend.yaml:21).
        fn add(&mut self);
        /// Called as `started()` (hsm_extend.yaml:19).
        fn started(&mut self);
    }
    /// What drives the state machines of Counter: a received message (with the
    /// trigger's other parameters) or an internal event.
    #[derive(Debug, Clone, Copy)]
    pub enum Trigger {
        /// `Bump`.
        Bump {},
    }
    impl Trigger {
        /// The trigger's name in the state tables.
        pub fn key(&self) -> &'static str {
            match self {
                Trigger::Bump { .. } => "Bump",
            }
        }
    }
    /// State machine `CountFSM` of [`Counter`].
    pub static COUNT_FSM: hsm::MachineDef = hsm::MachineDef {
        service: "Counter",
        name: "CountFSM",
        states: &[
            hsm::State {
                name: "Running",
                path: "Running",
                parent: None,
                initial: None,
                entry: &[0],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Bump"),
                        guard: None,
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[1],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
        ],
        start: 0,
        transitions: &[],
        defaults: &[],
    };
    /// The state machines of Counter, in definition order.
    pub static MACHINES: [&hsm::MachineDef; 1] = [&COUNT_FSM];
    /// Runs the guards and actions of the tables on an implementation of the trait.
    struct Run<'s, S: ?Sized>(&'s mut S);
    impl<S: Counter + ?Sized> hsm::Host<Trigger> for Run<'_, S> {
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn guard(&self, n: u16, t: Option<&Trigger>) -> bool {
            match (n, t) {
                _ => false,
            }
        }
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn action(&mut self, n: u16, t: Option<&Trigger>) {
            match (n, t) {
                (0, _) => self.0.started(),
                (1, _) => self.0.add(),
                _ => {}
            }
        }
    }
    /// The running state machines of Counter: feed it triggers with an
    /// implementation of [`Counter`]; it calls the guards and actions.
    #[derive(Debug, Clone)]
    pub struct Machines(pub hsm::Machines);
    impl Default for Machines {
        fn default() -> Self {
            Self::new()
        }
    }
    impl Machines {
        /// The machines, not started.
        pub fn new() -> Self {
            Self(hsm::Machines::new(&MACHINES))
        }
        /// Enters each machine's start state (running the entry actions).
        pub fn start<S: Counter + ?Sized>(&mut self, service: &mut S) {
            self.0.start(&mut Run(service));
        }
        /// Offers `trigger` to every machine (starting them first if needed); whether
        /// one took a transition.
        pub fn handle<S: Counter + ?Sized>(
            &mut self,
            service: &mut S,
            trigger: &Trigger,
        ) -> bool {
            self.0.handle(&mut Run(service), trigger.key(), trigger)
        }
        /// The current state's path in machine `machine`.
        pub fn state(&self, machine: &str) -> Option<&'static str> {
            self.0.state(machine)
        }
    }
}
/// Limited: trait [`Limited`](limited::Limited), its triggers and state machines (hsm_extend.yaml:22).
#[allow(clippy::module_inception)]
pub mod limited {
    #[allow(unused_imports)]
    use super::*;
    /// The service's URI and version.
    pub const ID: &str = "urn:test:hsm:Limited 1.0";
    /// The service's URI.
    pub const URI: &str = "urn:test:hsm:Limited";
    /// The service's version: major, minor.
    pub const VERSION: (u8, u8) = (1, 0);
    /// The internal events of Limited: triggers of its transitions that are not
    /// received messages.
    pub mod event {
        #[allow(unused_imports)]
        use super::*;
        /// Internal event `Full` of [`Limited`].
        #[derive(Debug, Clone, PartialEq)]
        pub struct Full {}
    }
    /// The Limited service (`urn:test:hsm:Limited` version 1.0).
    ///
    /// Implement its guards and actions; [`Machines`] runs its state machines over the
    /// implementation.
    pub trait Limited: super::counter::Counter {
        /// Called as `armed()` (hsm_extend.yaml:37).
        fn armed(&mut self);
        /// Called as `refuse()` (hsm_extend.yaml:44).
        fn refuse(&mut self);
    }
    /// What drives the state machines of Limited: a received message (with the
    /// trigger's other parameters) or an internal event.
    #[derive(Debug, Clone, Copy)]
    pub enum Trigger {
        /// `Bump`.
        Bump {},
        /// `Full`.
        Full {},
        /// `counter.Reset`.
        Reset {},
    }
    impl Trigger {
        /// The trigger's name in the state tables.
        pub fn key(&self) -> &'static str {
            match self {
                Trigger::Bump { .. } => "Bump",
                Trigger::Full { .. } => "Full",
                Trigger::Reset { .. } => "Reset",
            }
        }
    }
    /// State machine `CountFSM` of [`Limited`] (with what it inherits).
    pub static COUNT_FSM: hsm::MachineDef = hsm::MachineDef {
        service: "Limited",
        name: "CountFSM",
        states: &[
            hsm::State {
                name: "Running",
                path: "Running",
                parent: None,
                initial: Some(1),
                entry: &[0, 1],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Bump"),
                        guard: None,
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[2],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
            hsm::State {
                name: "Below",
                path: "Running.Below",
                parent: Some(0),
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Full"),
                        guard: None,
                        kind: hsm::Kind::Simple,
                        target: Some(2),
                        actions: &[],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
            hsm::State {
                name: "AtLimit",
                path: "Running.AtLimit",
                parent: Some(0),
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Bump"),
                        guard: None,
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[3],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
            hsm::State {
                name: "Stopped",
                path: "Stopped",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Reset"),
                        guard: None,
                        kind: hsm::Kind::Simple,
                        target: Some(0),
                        actions: &[],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
        ],
        start: 1,
        transitions: &[],
        defaults: &[],
    };
    /// The state machines of Limited, in definition order.
    pub static MACHINES: [&hsm::MachineDef; 1] = [&COUNT_FSM];
    /// Runs the guards and actions of the tables on an implementation of the trait.
    struct Run<'s, S: ?Sized>(&'s mut S);
    impl<S: Limited + ?Sized> hsm::Host<Trigger> for Run<'_, S> {
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn guard(&self, n: u16, t: Option<&Trigger>) -> bool {
            match (n, t) {
                _ => false,
            }
        }
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn action(&mut self, n: u16, t: Option<&Trigger>) {
            match (n, t) {
                (0, _) => self.0.started(),
                (1, _) => self.0.armed(),
                (2, _) => self.0.add(),
                (3, _) => self.0.refuse(),
                _ => {}
            }
        }
    }
    /// The running state machines of Limited: feed it triggers with an
    /// implementation of [`Limited`]; it calls the guards and actions.
    #[derive(Debug, Clone)]
    pub struct Machines(pub hsm::Machines);
    impl Default for Machines {
        fn default() -> Self {
            Self::new()
        }
    }
    impl Machines {
        /// The machines, not started.
        pub fn new() -> Self {
            Self(hsm::Machines::new(&MACHINES))
        }
        /// Enters each machine's start state (running the entry actions).
        pub fn start<S: Limited + ?Sized>(&mut self, service: &mut S) {
            self.0.start(&mut Run(service));
        }
        /// Offers `trigger` to every machine (starting them first if needed); whether
        /// one took a transition.
        pub fn handle<S: Limited + ?Sized>(
            &mut self,
            service: &mut S,
            trigger: &Trigger,
        ) -> bool {
            self.0.handle(&mut Run(service), trigger.key(), trigger)
        }
        /// The current state's path in machine `machine`.
        pub fn state(&self, machine: &str) -> Option<&'static str> {
            self.0.state(machine)
        }
    }
}
