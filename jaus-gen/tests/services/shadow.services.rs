#[allow(unused_imports)]
use super::*;
#[allow(unused_imports)]
use ::jaus::hsm;
/// Switch: trait [`Switch`](switch::Switch), its triggers and state machines (shadow.yaml:21).
#[allow(clippy::module_inception)]
pub mod switch {
    #[allow(unused_imports)]
    use super::*;
    /// The service's URI and version.
    pub const ID: &str = "urn:test:shadow:Switch 1.0";
    /// The service's URI.
    pub const URI: &str = "urn:test:shadow:Switch";
    /// The service's version: major, minor.
    pub const VERSION: (u8, u8) = (1, 0);
    /// The internal events of Switch: triggers of its transitions that are not
    /// received messages.
    pub mod event {
        #[allow(unused_imports)]
        use super::*;
        /// Internal event `Receive` of [`Switch`].
        ///
        /// A message arrived.
        #[derive(Debug, Clone, PartialEq)]
        pub struct Receive {
            pub source: u32,
        }
    }
    /// The Switch service (`urn:test:shadow:Switch` version 1.0).
    ///
    /// Switches a light on.
    ///
    /// Implement its guards and actions; [`Machines`] runs its state machines over the
    /// implementation.
    pub trait Switch {
        /// Called as `isAllowed(msg)` (shadow.yaml:42).
        fn is_allowed(&self, msg: &SwitchOn) -> bool;
        /// Called as `switchOn(msg)` (shadow.yaml:44).
        fn switch_on(&mut self, msg: &SwitchOn);
    }
    /// What drives the state machines of Switch: a received message (with the
    /// trigger's other parameters) or an internal event.
    #[derive(Debug, Clone, Copy)]
    pub enum Trigger<'a> {
        /// `Receive` carrying [`SwitchOn`].
        SwitchOn {
            /// Parameter `msg`.
            msg: &'a SwitchOn,
            /// Parameter `data`.
            data: &'a super::switch::event::Receive,
        },
    }
    impl Trigger<'_> {
        /// The trigger's name in the state tables.
        pub fn key(&self) -> &'static str {
            match self {
                Trigger::SwitchOn { .. } => "SwitchOn",
            }
        }
    }
    impl<'a> Trigger<'a> {
        /// The trigger a received `message` raises in the machines of Switch, with
        /// the trigger's other parameters; `None` for a message none of them takes.
        pub fn received(
            message: &'a Message,
            data: &'a super::switch::event::Receive,
        ) -> Option<Self> {
            Some(
                match message {
                    Message::SwitchOn(msg) => Trigger::SwitchOn { msg, data },
                    _ => return None,
                },
            )
        }
    }
    /// The messages the machines of Switch take, by command code (ascending).
    pub const RECEIVES: &[::jaus::CommandCode] = &[
        <SwitchOn as ::jaus::JausMessage>::CODE,
    ];
    /// State machine `SwitchFSM` of [`Switch`].
    pub static SWITCH_FSM: hsm::MachineDef = hsm::MachineDef {
        service: "Switch",
        name: "SwitchFSM",
        states: &[
            hsm::State {
                name: "Receiving",
                path: "Receiving",
                parent: None,
                initial: Some(1),
                entry: &[],
                exit: &[],
                transitions: &[],
                defaults: &[],
            },
            hsm::State {
                name: "Off",
                path: "Receiving.Off",
                parent: Some(0),
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("SwitchOn"),
                        guard: Some(&hsm::Expr::Call(0)),
                        kind: hsm::Kind::Simple,
                        target: Some(2),
                        actions: &[0],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
            hsm::State {
                name: "On",
                path: "Receiving.On",
                parent: Some(0),
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[],
                defaults: &[],
            },
        ],
        start: 1,
        transitions: &[],
        defaults: &[],
    };
    /// The state machines of Switch, in definition order.
    pub static MACHINES: [&hsm::MachineDef; 1] = [&SWITCH_FSM];
    /// Runs the guards and actions of the tables on an implementation of the trait.
    struct Run<'s, S: ?Sized>(&'s mut S);
    impl<S: Switch + ?Sized> hsm::Host<Trigger<'_>> for Run<'_, S> {
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn guard(&self, n: u16, t: Option<&Trigger<'_>>) -> bool {
            match (n, t) {
                (0, Some(Trigger::SwitchOn { msg, .. })) => self.0.is_allowed(msg),
                _ => false,
            }
        }
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn action(&mut self, n: u16, t: Option<&Trigger<'_>>) {
            match (n, t) {
                (0, Some(Trigger::SwitchOn { msg, .. })) => self.0.switch_on(msg),
                _ => {}
            }
        }
    }
    /// The running state machines of Switch: feed it triggers with an
    /// implementation of [`Switch`]; it calls the guards and actions.
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
        pub fn start<S: Switch + ?Sized>(&mut self, service: &mut S) {
            self.0.start(&mut Run(service));
        }
        /// Offers `trigger` to every machine (starting them first if needed); whether
        /// one took a transition.
        pub fn handle<S: Switch + ?Sized>(
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
        /// Offers a received `message` to every machine as its trigger
        /// ([`Trigger::received`]): `None` when none of them takes the message, else
        /// whether one took a transition.
        pub fn receive<S: Switch + ?Sized>(
            &mut self,
            service: &mut S,
            message: &Message,
            data: &super::switch::event::Receive,
        ) -> Option<bool> {
            let trigger = Trigger::received(message, data)?;
            Some(self.handle(service, &trigger))
        }
    }
}
/// Dimmer: trait [`Dimmer`](dimmer::Dimmer), its triggers and state machines (shadow.yaml:46).
#[allow(clippy::module_inception)]
pub mod dimmer {
    #[allow(unused_imports)]
    use super::*;
    /// The service's URI and version.
    pub const ID: &str = "urn:test:shadow:Dimmer 1.0";
    /// The service's URI.
    pub const URI: &str = "urn:test:shadow:Dimmer";
    /// The service's version: major, minor.
    pub const VERSION: (u8, u8) = (1, 0);
    /// The Dimmer service (`urn:test:shadow:Dimmer` version 1.0).
    ///
    /// Dims the light a Switch switched on.
    ///
    /// Implement its guards and actions; [`Machines`] runs its state machines over the
    /// implementation.
    pub trait Dimmer: super::switch::Switch {
        /// Called as `isAllowed(msg)` (shadow.yaml:66).
        fn is_allowed(&self, msg: &SetLevel) -> bool;
        /// Called as `applyLevel(msg)` (shadow.yaml:68).
        fn apply_level(&mut self, msg: &SetLevel);
        /// Called as `applyStart(msg)` (shadow.yaml:73).
        fn apply_start(&mut self, msg: &SwitchOn);
    }
    /// What drives the state machines of Dimmer: a received message (with the
    /// trigger's other parameters) or an internal event.
    #[derive(Debug, Clone, Copy)]
    pub enum Trigger<'a> {
        /// `Receive` carrying [`SwitchOn`].
        SwitchOn {
            /// Parameter `msg`.
            msg: &'a SwitchOn,
            /// Parameter `data`.
            data: &'a super::switch::event::Receive,
        },
        /// `switch.Receive` carrying [`SetLevel`].
        SetLevel {
            /// Parameter `msg`.
            msg: &'a SetLevel,
            /// Parameter `data`.
            data: &'a super::switch::event::Receive,
        },
    }
    impl Trigger<'_> {
        /// The trigger's name in the state tables.
        pub fn key(&self) -> &'static str {
            match self {
                Trigger::SwitchOn { .. } => "SwitchOn",
                Trigger::SetLevel { .. } => "SetLevel",
            }
        }
    }
    impl<'a> Trigger<'a> {
        /// The trigger a received `message` raises in the machines of Dimmer, with
        /// the trigger's other parameters; `None` for a message none of them takes.
        pub fn received(
            message: &'a Message,
            data: &'a super::switch::event::Receive,
        ) -> Option<Self> {
            Some(
                match message {
                    Message::SetLevel(msg) => Trigger::SetLevel { msg, data },
                    Message::SwitchOn(msg) => Trigger::SwitchOn { msg, data },
                    _ => return None,
                },
            )
        }
    }
    /// The messages the machines of Dimmer take, by command code (ascending).
    pub const RECEIVES: &[::jaus::CommandCode] = &[
        <SetLevel as ::jaus::JausMessage>::CODE,
        <SwitchOn as ::jaus::JausMessage>::CODE,
    ];
    /// State machine `SwitchFSM` of [`Dimmer`] (with what it inherits).
    pub static SWITCH_FSM: hsm::MachineDef = hsm::MachineDef {
        service: "Dimmer",
        name: "SwitchFSM",
        states: &[
            hsm::State {
                name: "Receiving",
                path: "Receiving",
                parent: None,
                initial: Some(1),
                entry: &[],
                exit: &[],
                transitions: &[],
                defaults: &[],
            },
            hsm::State {
                name: "Off",
                path: "Receiving.Off",
                parent: Some(0),
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("SwitchOn"),
                        guard: Some(&hsm::Expr::Call(0)),
                        kind: hsm::Kind::Simple,
                        target: Some(2),
                        actions: &[0],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
            hsm::State {
                name: "On",
                path: "Receiving.On",
                parent: Some(0),
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("SetLevel"),
                        guard: Some(&hsm::Expr::Call(1)),
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[1],
                        raise: None,
                    },
                    hsm::Transition {
                        trigger: Some("SwitchOn"),
                        guard: Some(&hsm::Expr::Call(2)),
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[2],
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
    /// The state machines of Dimmer, in definition order.
    pub static MACHINES: [&hsm::MachineDef; 1] = [&SWITCH_FSM];
    /// Runs the guards and actions of the tables on an implementation of the trait.
    struct Run<'s, S: ?Sized>(&'s mut S);
    impl<S: Dimmer + ?Sized> hsm::Host<Trigger<'_>> for Run<'_, S> {
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn guard(&self, n: u16, t: Option<&Trigger<'_>>) -> bool {
            match (n, t) {
                (0, Some(Trigger::SwitchOn { msg, .. })) => {
                    super::switch::Switch::is_allowed(&*self.0, msg)
                }
                (1, Some(Trigger::SetLevel { msg, .. })) => {
                    super::dimmer::Dimmer::is_allowed(&*self.0, msg)
                }
                (2, Some(Trigger::SwitchOn { msg, .. })) => {
                    super::switch::Switch::is_allowed(&*self.0, msg)
                }
                _ => false,
            }
        }
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn action(&mut self, n: u16, t: Option<&Trigger<'_>>) {
            match (n, t) {
                (0, Some(Trigger::SwitchOn { msg, .. })) => self.0.switch_on(msg),
                (1, Some(Trigger::SetLevel { msg, .. })) => self.0.apply_level(msg),
                (2, Some(Trigger::SwitchOn { msg, .. })) => self.0.apply_start(msg),
                _ => {}
            }
        }
    }
    /// The running state machines of Dimmer: feed it triggers with an
    /// implementation of [`Dimmer`]; it calls the guards and actions.
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
        pub fn start<S: Dimmer + ?Sized>(&mut self, service: &mut S) {
            self.0.start(&mut Run(service));
        }
        /// Offers `trigger` to every machine (starting them first if needed); whether
        /// one took a transition.
        pub fn handle<S: Dimmer + ?Sized>(
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
        /// Offers a received `message` to every machine as its trigger
        /// ([`Trigger::received`]): `None` when none of them takes the message, else
        /// whether one took a transition.
        pub fn receive<S: Dimmer + ?Sized>(
            &mut self,
            service: &mut S,
            message: &Message,
            data: &super::switch::event::Receive,
        ) -> Option<bool> {
            let trigger = Trigger::received(message, data)?;
            Some(self.handle(service, &trigger))
        }
    }
}
