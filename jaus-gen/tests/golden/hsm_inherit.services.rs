#[allow(unused_imports)]
use super::*;
#[allow(unused_imports)]
use ::jaus::hsm;
/// An argument of a guard or action whose call sites pass different arguments: a
/// trigger parameter, or a constant as the definition writes it.
#[derive(Debug, Clone, Copy)]
pub enum Arg<'a> {
    /// A constant (`'CONTROL_ACCEPTED'` is `Const("CONTROL_ACCEPTED")`).
    Const(&'static str),
    /// A parameter of type [`base::event::Receive`].
    BaseReceive(&'a base::event::Receive),
}
/// Base: trait [`Base`](base::Base), its triggers and state machines (hsm_inherit.yaml:7).
#[allow(clippy::module_inception)]
pub mod base {
    #[allow(unused_imports)]
    use super::*;
    /// The service's URI and version.
    pub const ID: &str = "urn:test:hsm:Base 1.0";
    /// The service's URI.
    pub const URI: &str = "urn:test:hsm:Base";
    /// The service's version: major, minor.
    pub const VERSION: (u8, u8) = (1, 0);
    /// The internal events of Base: triggers of its transitions that are not
    /// received messages.
    pub mod event {
        #[allow(unused_imports)]
        use super::*;
        /// Internal event `Receive` of [`Base`].
        #[derive(Debug, Clone, PartialEq)]
        pub struct Receive {
            pub source: u32,
        }
    }
    /// The Base service (`urn:test:hsm:Base` version 1.0).
    ///
    /// Implement its guards and actions; [`Machines`] runs its state machines over the
    /// implementation.
    pub trait Base {
        /// Called as `Send(data)` (hsm_inherit.yaml:19), `lower.base.Send('TICK')` (hsm_inherit.yaml:37).
        ///
        /// Its call sites pass different arguments: each call's are in `args`, in order.
        fn send(&mut self, args: &[super::Arg<'_>]);
    }
    /// What drives the state machines of Base: a received message (with the
    /// trigger's other parameters) or an internal event.
    #[derive(Debug, Clone, Copy)]
    pub enum Trigger<'a> {
        /// `Receive`.
        Receive {
            /// Parameter `data`.
            data: &'a super::base::event::Receive,
        },
    }
    impl Trigger<'_> {
        /// The trigger's name in the state tables.
        pub fn key(&self) -> &'static str {
            match self {
                Trigger::Receive { .. } => "Receive",
            }
        }
    }
    /// State machine `ReceiveFSM` of [`Base`].
    pub static RECEIVE_FSM: hsm::MachineDef = hsm::MachineDef {
        service: "Base",
        name: "ReceiveFSM",
        states: &[
            hsm::State {
                name: "Receiving",
                path: "Receiving",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Receive"),
                        guard: None,
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[0],
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
    /// The state machines of Base, in definition order.
    pub static MACHINES: [&hsm::MachineDef; 1] = [&RECEIVE_FSM];
    /// Runs the guards and actions of the tables on an implementation of the trait.
    struct Run<'s, S: ?Sized>(&'s mut S);
    impl<S: Base + ?Sized> hsm::Host<Trigger<'_>> for Run<'_, S> {
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn guard(&self, n: u16, t: Option<&Trigger<'_>>) -> bool {
            match (n, t) {
                _ => false,
            }
        }
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn action(&mut self, n: u16, t: Option<&Trigger<'_>>) {
            match (n, t) {
                (0, Some(Trigger::Receive { data, .. })) => {
                    self.0.send(&[super::Arg::BaseReceive(data)])
                }
                _ => {}
            }
        }
    }
    /// The running state machines of Base: feed it triggers with an
    /// implementation of [`Base`]; it calls the guards and actions.
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
        pub fn start<S: Base + ?Sized>(&mut self, service: &mut S) {
            self.0.start(&mut Run(service));
        }
        /// Offers `trigger` to every machine (starting them first if needed); whether
        /// one took a transition.
        pub fn handle<S: Base + ?Sized>(
            &mut self,
            service: &mut S,
            trigger: &Trigger<'_>,
        ) -> bool {
            self.0.handle(&mut Run(service), trigger.key(), trigger)
        }
        /// The current state's path in machine `machine`.
        pub fn state(&self, machine: &str) -> Option<&'static str> {
            self.0.state(machine)
        }
    }
}
/// Lower: trait [`Lower`](lower::Lower), its triggers and state machines (hsm_inherit.yaml:20).
#[allow(clippy::module_inception)]
pub mod lower {
    #[allow(unused_imports)]
    use super::*;
    /// The service's URI and version.
    pub const ID: &str = "urn:test:hsm:Lower 1.0";
    /// The service's URI.
    pub const URI: &str = "urn:test:hsm:Lower";
    /// The service's version: major, minor.
    pub const VERSION: (u8, u8) = (1, 0);
    /// The Lower service (`urn:test:hsm:Lower` version 1.0).
    ///
    /// Implement its guards and actions; [`Machines`] runs its state machines over the
    /// implementation.
    pub trait Lower: super::base::Base {}
    /// What drives the state machines of Lower: a received message (with the
    /// trigger's other parameters) or an internal event.
    #[derive(Debug, Clone, Copy)]
    pub enum Trigger<'a> {
        /// `Receive`.
        Receive {
            /// Parameter `data`.
            data: &'a super::base::event::Receive,
        },
    }
    impl Trigger<'_> {
        /// The trigger's name in the state tables.
        pub fn key(&self) -> &'static str {
            match self {
                Trigger::Receive { .. } => "Receive",
            }
        }
    }
    /// State machine `ReceiveFSM` of [`Lower`] (with what it inherits).
    pub static RECEIVE_FSM: hsm::MachineDef = hsm::MachineDef {
        service: "Lower",
        name: "ReceiveFSM",
        states: &[
            hsm::State {
                name: "Receiving",
                path: "Receiving",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Receive"),
                        guard: None,
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[0],
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
    /// The state machines of Lower, in definition order.
    pub static MACHINES: [&hsm::MachineDef; 1] = [&RECEIVE_FSM];
    /// Runs the guards and actions of the tables on an implementation of the trait.
    struct Run<'s, S: ?Sized>(&'s mut S);
    impl<S: Lower + ?Sized> hsm::Host<Trigger<'_>> for Run<'_, S> {
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn guard(&self, n: u16, t: Option<&Trigger<'_>>) -> bool {
            match (n, t) {
                _ => false,
            }
        }
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn action(&mut self, n: u16, t: Option<&Trigger<'_>>) {
            match (n, t) {
                (0, Some(Trigger::Receive { data, .. })) => {
                    self.0.send(&[super::Arg::BaseReceive(data)])
                }
                _ => {}
            }
        }
    }
    /// The running state machines of Lower: feed it triggers with an
    /// implementation of [`Lower`]; it calls the guards and actions.
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
        pub fn start<S: Lower + ?Sized>(&mut self, service: &mut S) {
            self.0.start(&mut Run(service));
        }
        /// Offers `trigger` to every machine (starting them first if needed); whether
        /// one took a transition.
        pub fn handle<S: Lower + ?Sized>(
            &mut self,
            service: &mut S,
            trigger: &Trigger<'_>,
        ) -> bool {
            self.0.handle(&mut Run(service), trigger.key(), trigger)
        }
        /// The current state's path in machine `machine`.
        pub fn state(&self, machine: &str) -> Option<&'static str> {
            self.0.state(machine)
        }
    }
}
/// Upper: trait [`Upper`](upper::Upper), its triggers and state machines (hsm_inherit.yaml:24).
#[allow(clippy::module_inception)]
pub mod upper {
    #[allow(unused_imports)]
    use super::*;
    /// The service's URI and version.
    pub const ID: &str = "urn:test:hsm:Upper 1.0";
    /// The service's URI.
    pub const URI: &str = "urn:test:hsm:Upper";
    /// The service's version: major, minor.
    pub const VERSION: (u8, u8) = (1, 0);
    /// The internal events of Upper: triggers of its transitions that are not
    /// received messages.
    pub mod event {
        #[allow(unused_imports)]
        use super::*;
        /// Internal event `Tick` of [`Upper`].
        #[derive(Debug, Clone, PartialEq)]
        pub struct Tick {}
    }
    /// The Upper service (`urn:test:hsm:Upper` version 1.0).
    ///
    /// Implement its guards and actions; [`Machines`] runs its state machines over the
    /// implementation.
    pub trait Upper: super::lower::Lower {
        /// Called as `count()` (hsm_inherit.yaml:37).
        fn count(&mut self);
    }
    /// What drives the state machines of Upper: a received message (with the
    /// trigger's other parameters) or an internal event.
    #[derive(Debug, Clone, Copy)]
    pub enum Trigger<'a> {
        /// `Receive`.
        Receive {
            /// Parameter `data`.
            data: &'a super::base::event::Receive,
        },
        /// `Tick`.
        Tick {},
    }
    impl Trigger<'_> {
        /// The trigger's name in the state tables.
        pub fn key(&self) -> &'static str {
            match self {
                Trigger::Receive { .. } => "Receive",
                Trigger::Tick { .. } => "Tick",
            }
        }
    }
    /// State machine `ReceiveFSM` of [`Upper`] (with what it inherits).
    pub static RECEIVE_FSM: hsm::MachineDef = hsm::MachineDef {
        service: "Upper",
        name: "ReceiveFSM",
        states: &[
            hsm::State {
                name: "Receiving",
                path: "Receiving",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Receive"),
                        guard: None,
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[0],
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
    /// State machine `TickFSM` of [`Upper`] (with what it inherits).
    pub static TICK_FSM: hsm::MachineDef = hsm::MachineDef {
        service: "Upper",
        name: "TickFSM",
        states: &[
            hsm::State {
                name: "Counting",
                path: "Counting",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Tick"),
                        guard: None,
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[1, 2],
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
    /// The state machines of Upper, in definition order.
    pub static MACHINES: [&hsm::MachineDef; 2] = [&RECEIVE_FSM, &TICK_FSM];
    /// Runs the guards and actions of the tables on an implementation of the trait.
    struct Run<'s, S: ?Sized>(&'s mut S);
    impl<S: Upper + ?Sized> hsm::Host<Trigger<'_>> for Run<'_, S> {
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn guard(&self, n: u16, t: Option<&Trigger<'_>>) -> bool {
            match (n, t) {
                _ => false,
            }
        }
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn action(&mut self, n: u16, t: Option<&Trigger<'_>>) {
            match (n, t) {
                (0, Some(Trigger::Receive { data, .. })) => {
                    self.0.send(&[super::Arg::BaseReceive(data)])
                }
                (1, _) => self.0.count(),
                (2, _) => self.0.send(&[super::Arg::Const("TICK")]),
                _ => {}
            }
        }
    }
    /// The running state machines of Upper: feed it triggers with an
    /// implementation of [`Upper`]; it calls the guards and actions.
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
        pub fn start<S: Upper + ?Sized>(&mut self, service: &mut S) {
            self.0.start(&mut Run(service));
        }
        /// Offers `trigger` to every machine (starting them first if needed); whether
        /// one took a transition.
        pub fn handle<S: Upper + ?Sized>(
            &mut self,
            service: &mut S,
            trigger: &Trigger<'_>,
        ) -> bool {
            self.0.handle(&mut Run(service), trigger.key(), trigger)
        }
        /// The current state's path in machine `machine`.
        pub fn state(&self, machine: &str) -> Option<&'static str> {
            self.0.state(machine)
        }
    }
}
/// Top: trait [`Top`](top::Top), its triggers and state machines (hsm_inherit.yaml:38).
#[allow(clippy::module_inception)]
pub mod top {
    #[allow(unused_imports)]
    use super::*;
    /// The service's URI and version.
    pub const ID: &str = "urn:test:hsm:Top 1.0";
    /// The service's URI.
    pub const URI: &str = "urn:test:hsm:Top";
    /// The service's version: major, minor.
    pub const VERSION: (u8, u8) = (1, 0);
    /// The Top service (`urn:test:hsm:Top` version 1.0).
    ///
    /// Implement its guards and actions; [`Machines`] runs its state machines over the
    /// implementation.
    pub trait Top: super::upper::Upper {}
    /// What drives the state machines of Top: a received message (with the
    /// trigger's other parameters) or an internal event.
    #[derive(Debug, Clone, Copy)]
    pub enum Trigger<'a> {
        /// `Receive`.
        Receive {
            /// Parameter `data`.
            data: &'a super::base::event::Receive,
        },
        /// `Tick`.
        Tick {},
    }
    impl Trigger<'_> {
        /// The trigger's name in the state tables.
        pub fn key(&self) -> &'static str {
            match self {
                Trigger::Receive { .. } => "Receive",
                Trigger::Tick { .. } => "Tick",
            }
        }
    }
    /// State machine `ReceiveFSM` of [`Top`] (with what it inherits).
    pub static RECEIVE_FSM: hsm::MachineDef = hsm::MachineDef {
        service: "Top",
        name: "ReceiveFSM",
        states: &[
            hsm::State {
                name: "Receiving",
                path: "Receiving",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Receive"),
                        guard: None,
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[0],
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
    /// State machine `TickFSM` of [`Top`] (with what it inherits).
    pub static TICK_FSM: hsm::MachineDef = hsm::MachineDef {
        service: "Top",
        name: "TickFSM",
        states: &[
            hsm::State {
                name: "Counting",
                path: "Counting",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Tick"),
                        guard: None,
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[1, 2],
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
    /// The state machines of Top, in definition order.
    pub static MACHINES: [&hsm::MachineDef; 2] = [&RECEIVE_FSM, &TICK_FSM];
    /// Runs the guards and actions of the tables on an implementation of the trait.
    struct Run<'s, S: ?Sized>(&'s mut S);
    impl<S: Top + ?Sized> hsm::Host<Trigger<'_>> for Run<'_, S> {
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn guard(&self, n: u16, t: Option<&Trigger<'_>>) -> bool {
            match (n, t) {
                _ => false,
            }
        }
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn action(&mut self, n: u16, t: Option<&Trigger<'_>>) {
            match (n, t) {
                (0, Some(Trigger::Receive { data, .. })) => {
                    self.0.send(&[super::Arg::BaseReceive(data)])
                }
                (1, _) => self.0.count(),
                (2, _) => self.0.send(&[super::Arg::Const("TICK")]),
                _ => {}
            }
        }
    }
    /// The running state machines of Top: feed it triggers with an
    /// implementation of [`Top`]; it calls the guards and actions.
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
        pub fn start<S: Top + ?Sized>(&mut self, service: &mut S) {
            self.0.start(&mut Run(service));
        }
        /// Offers `trigger` to every machine (starting them first if needed); whether
        /// one took a transition.
        pub fn handle<S: Top + ?Sized>(
            &mut self,
            service: &mut S,
            trigger: &Trigger<'_>,
        ) -> bool {
            self.0.handle(&mut Run(service), trigger.key(), trigger)
        }
        /// The current state's path in machine `machine`.
        pub fn state(&self, machine: &str) -> Option<&'static str> {
            self.0.state(machine)
        }
    }
}
