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
    /// A parameter of type [`link::event::Delivered`].
    LinkDelivered(&'a link::event::Delivered),
}
/// Access: trait [`Access`](access::Access), its triggers and state machines (access.yaml:5).
#[allow(clippy::module_inception)]
pub mod access {
    #[allow(unused_imports)]
    use super::*;
    /// The service's URI and version.
    pub const ID: &str = "urn:test:access:Access 1.0";
    /// The service's URI.
    pub const URI: &str = "urn:test:access:Access";
    /// The service's version: major, minor.
    pub const VERSION: (u8, u8) = (1, 0);
    /// The internal events of Access: triggers of its transitions that are not
    /// received messages.
    pub mod event {
        #[allow(unused_imports)]
        use super::*;
        /// Internal event `Lapsed` of [`Access`].
        ///
        /// The controller did not renew its request in time.
        #[derive(Debug, Clone, PartialEq)]
        pub struct Lapsed {}
    }
    /// The Access service (`urn:test:access:Access` version 1.0).
    ///
    /// Grants exclusive control to one client at a time, by rank.
    ///
    /// Clients renew their request before it lapses.
    ///
    /// Implement its guards and actions; [`Machines`] runs its state machines over the
    /// implementation.
    pub trait Access: super::link::Link {
        /// the controller renews
        ///
        /// Called as `isController(from)` (access.yaml:102).
        fn is_controller(&self, from: &super::link::event::Delivered) -> bool;
        /// a higher rank takes over
        ///
        /// Called as `outranks(msg)` (access.yaml:123).
        fn outranks(&self, msg: &AskForControl) -> bool;
        /// below the service's own rank
        ///
        /// Called as `rankTooLow(msg)` (access.yaml:53).
        fn rank_too_low(&self, msg: &AskForControl) -> bool;
        /// Called as `forgetController()` (access.yaml:44).
        fn forget_controller(&mut self);
        /// Called as `rememberController(from)` (access.yaml:76).
        fn remember_controller(&mut self, from: &super::link::event::Delivered);
        /// Called as `restartClock()` (access.yaml:82).
        fn restart_clock(&mut self);
        /// Called as `stopClock()` (access.yaml:93).
        fn stop_clock(&mut self);
        /// Called as `takeRank(msg)` (access.yaml:79).
        fn take_rank(&mut self, msg: &AskForControl);
    }
    /// What drives the state machines of Access: a received message (with the
    /// trigger's other parameters) or an internal event.
    #[derive(Debug, Clone, Copy)]
    pub enum Trigger<'a> {
        /// `Delivered`.
        Delivered {},
        /// `link.Delivered` carrying [`AskForControl`].
        AskForControl {
            /// Parameter `msg`.
            msg: &'a AskForControl,
            /// Parameter `from`.
            from: &'a super::link::event::Delivered,
        },
        /// `link.Delivered` carrying [`GiveUpControl`].
        GiveUpControl {
            /// Parameter `msg`.
            msg: &'a GiveUpControl,
            /// Parameter `from`.
            from: &'a super::link::event::Delivered,
        },
        /// `Lapsed`.
        ///
        /// The controller did not renew its request in time.
        Lapsed {},
    }
    impl Trigger<'_> {
        /// The trigger's name in the state tables.
        pub fn key(&self) -> &'static str {
            match self {
                Trigger::Delivered { .. } => "Delivered",
                Trigger::AskForControl { .. } => "AskForControl",
                Trigger::GiveUpControl { .. } => "GiveUpControl",
                Trigger::Lapsed { .. } => "Lapsed",
            }
        }
    }
    impl<'a> Trigger<'a> {
        /// The trigger a received `message` raises in the machines of Access, with
        /// the trigger's other parameters; `None` for a message none of them takes.
        pub fn received(
            message: &'a Message,
            from: &'a super::link::event::Delivered,
        ) -> Option<Self> {
            Some(
                match message {
                    Message::AskForControl(msg) => {
                        Trigger::AskForControl {
                            msg,
                            from,
                        }
                    }
                    Message::GiveUpControl(msg) => {
                        Trigger::GiveUpControl {
                            msg,
                            from,
                        }
                    }
                    _ => return None,
                },
            )
        }
    }
    /// The messages the machines of Access take, by command code (ascending).
    pub const RECEIVES: &[::jaus::CommandCode] = &[
        <AskForControl as ::jaus::JausMessage>::CODE,
        <GiveUpControl as ::jaus::JausMessage>::CODE,
    ];
    /// State machine `InFSM` of [`Access`] (with what it inherits).
    ///
    /// extending InFSM of link: adds control
    pub static IN_FSM: hsm::MachineDef = hsm::MachineDef {
        service: "Access",
        name: "InFSM",
        states: &[
            hsm::State {
                name: "Listening",
                path: "Listening",
                parent: None,
                initial: Some(1),
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Delivered"),
                        guard: None,
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
            hsm::State {
                name: "Serving",
                path: "Listening.Serving",
                parent: Some(0),
                initial: Some(2),
                entry: &[],
                exit: &[],
                transitions: &[],
                defaults: &[],
            },
            hsm::State {
                name: "Free",
                path: "Listening.Serving.Free",
                parent: Some(1),
                initial: None,
                entry: &[0],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("AskForControl"),
                        guard: Some(&hsm::Expr::Call(0)),
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[1],
                        raise: None,
                    },
                    hsm::Transition {
                        trigger: Some("AskForControl"),
                        guard: Some(&hsm::Expr::Not(&hsm::Expr::Call(1))),
                        kind: hsm::Kind::Simple,
                        target: Some(3),
                        actions: &[2, 3, 4, 5],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
            hsm::State {
                name: "Held",
                path: "Listening.Serving.Held",
                parent: Some(1),
                initial: None,
                entry: &[],
                exit: &[6],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("AskForControl"),
                        guard: Some(&hsm::Expr::Call(2)),
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[7, 8, 9],
                        raise: None,
                    },
                    hsm::Transition {
                        trigger: Some("AskForControl"),
                        guard: Some(
                            &hsm::Expr::And(
                                &[hsm::Expr::Call(3), hsm::Expr::Not(&hsm::Expr::Call(4))],
                            ),
                        ),
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[10, 11, 12, 13, 14],
                        raise: None,
                    },
                    hsm::Transition {
                        trigger: Some("AskForControl"),
                        guard: Some(
                            &hsm::Expr::Not(
                                &hsm::Expr::Or(&[hsm::Expr::Call(5), hsm::Expr::Call(6)]),
                            ),
                        ),
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[15],
                        raise: None,
                    },
                    hsm::Transition {
                        trigger: Some("GiveUpControl"),
                        guard: Some(&hsm::Expr::Call(7)),
                        kind: hsm::Kind::Simple,
                        target: Some(2),
                        actions: &[16],
                        raise: None,
                    },
                    hsm::Transition {
                        trigger: Some("Lapsed"),
                        guard: None,
                        kind: hsm::Kind::Simple,
                        target: Some(2),
                        actions: &[17],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
        ],
        start: 2,
        transitions: &[],
        defaults: &[],
    };
    /// The state machines of Access, in definition order.
    pub static MACHINES: [&hsm::MachineDef; 1] = [&IN_FSM];
    /// Runs the guards and actions of the tables on an implementation of the trait.
    struct Run<'s, S: ?Sized>(&'s mut S);
    impl<S: Access + ?Sized> hsm::Host<Trigger<'_>> for Run<'_, S> {
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn guard(&self, n: u16, t: Option<&Trigger<'_>>) -> bool {
            match (n, t) {
                (0, Some(Trigger::AskForControl { msg, .. })) => self.0.rank_too_low(msg),
                (1, Some(Trigger::AskForControl { msg, .. })) => self.0.rank_too_low(msg),
                (2, Some(Trigger::AskForControl { from, .. })) => {
                    self.0.is_controller(from)
                }
                (3, Some(Trigger::AskForControl { msg, .. })) => self.0.outranks(msg),
                (4, Some(Trigger::AskForControl { from, .. })) => {
                    self.0.is_controller(from)
                }
                (5, Some(Trigger::AskForControl { msg, .. })) => self.0.outranks(msg),
                (6, Some(Trigger::AskForControl { from, .. })) => {
                    self.0.is_controller(from)
                }
                (7, Some(Trigger::GiveUpControl { from, .. })) => {
                    self.0.is_controller(from)
                }
                _ => false,
            }
        }
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn action(&mut self, n: u16, t: Option<&Trigger<'_>>) {
            match (n, t) {
                (0, _) => self.0.forget_controller(),
                (1, Some(Trigger::AskForControl { from, .. })) => {
                    self.0
                        .reply(
                            &[
                                super::Arg::Const("AnswerControl"),
                                super::Arg::Const("RANK_TOO_LOW"),
                                super::Arg::LinkDelivered(from),
                            ],
                        )
                }
                (2, Some(Trigger::AskForControl { from, .. })) => {
                    self.0.remember_controller(from)
                }
                (3, Some(Trigger::AskForControl { msg, .. })) => self.0.take_rank(msg),
                (4, _) => self.0.restart_clock(),
                (5, Some(Trigger::AskForControl { from, .. })) => {
                    self.0
                        .reply(
                            &[
                                super::Arg::Const("AnswerControl"),
                                super::Arg::Const("GRANTED"),
                                super::Arg::LinkDelivered(from),
                            ],
                        )
                }
                (6, _) => self.0.stop_clock(),
                (7, Some(Trigger::AskForControl { msg, .. })) => self.0.take_rank(msg),
                (8, _) => self.0.restart_clock(),
                (9, Some(Trigger::AskForControl { from, .. })) => {
                    self.0
                        .reply(
                            &[
                                super::Arg::Const("AnswerControl"),
                                super::Arg::Const("GRANTED"),
                                super::Arg::LinkDelivered(from),
                            ],
                        )
                }
                (10, _) => self.0.reply(&[super::Arg::Const("EndControl")]),
                (11, Some(Trigger::AskForControl { from, .. })) => {
                    self.0.remember_controller(from)
                }
                (12, Some(Trigger::AskForControl { msg, .. })) => self.0.take_rank(msg),
                (13, _) => self.0.restart_clock(),
                (14, Some(Trigger::AskForControl { from, .. })) => {
                    self.0
                        .reply(
                            &[
                                super::Arg::Const("AnswerControl"),
                                super::Arg::Const("GRANTED"),
                                super::Arg::LinkDelivered(from),
                            ],
                        )
                }
                (15, Some(Trigger::AskForControl { from, .. })) => {
                    self.0
                        .reply(
                            &[
                                super::Arg::Const("AnswerControl"),
                                super::Arg::Const("RANK_TOO_LOW"),
                                super::Arg::LinkDelivered(from),
                            ],
                        )
                }
                (16, Some(Trigger::GiveUpControl { from, .. })) => {
                    self.0
                        .reply(
                            &[
                                super::Arg::Const("EndControl"),
                                super::Arg::LinkDelivered(from),
                            ],
                        )
                }
                (17, _) => self.0.reply(&[super::Arg::Const("EndControl")]),
                _ => {}
            }
        }
    }
    /// The running state machines of Access: feed it triggers with an
    /// implementation of [`Access`]; it calls the guards and actions.
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
        pub fn start<S: Access + ?Sized>(&mut self, service: &mut S) {
            self.0.start(&mut Run(service));
        }
        /// Offers `trigger` to every machine (starting them first if needed); whether
        /// one took a transition.
        pub fn handle<S: Access + ?Sized>(
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
        pub fn receive<S: Access + ?Sized>(
            &mut self,
            service: &mut S,
            message: &Message,
            from: &super::link::event::Delivered,
        ) -> Option<bool> {
            let trigger = Trigger::received(message, from)?;
            Some(self.handle(service, &trigger))
        }
    }
}
/// Link: trait [`Link`](link::Link), its triggers and state machines (link.yaml:5).
#[allow(clippy::module_inception)]
pub mod link {
    #[allow(unused_imports)]
    use super::*;
    /// The service's URI and version.
    pub const ID: &str = "urn:test:access:Link 1.0";
    /// The service's URI.
    pub const URI: &str = "urn:test:access:Link";
    /// The service's version: major, minor.
    pub const VERSION: (u8, u8) = (1, 0);
    /// The internal events of Link: triggers of its transitions that are not
    /// received messages.
    pub mod event {
        #[allow(unused_imports)]
        use super::*;
        /// Internal event `Delivered` of [`Link`].
        ///
        /// A message came in.
        #[derive(Debug, Clone, PartialEq)]
        pub struct Delivered {
            pub from: u32,
        }
    }
    /// The Link service (`urn:test:access:Link` version 1.0).
    ///
    /// Delivers messages to the services built on it and sends theirs.
    ///
    /// Delivery is best effort.
    ///
    /// Implement its guards and actions; [`Machines`] runs its state machines over the
    /// implementation.
    pub trait Link {
        /// refuse
        ///
        /// Called as `link.Reply('AnswerControl', 'RANK_TOO_LOW', from)` (access.yaml:57), `link.Reply('AnswerControl', 'GRANTED', from)` (access.yaml:83), `link.Reply('EndControl')` (access.yaml:127) and 1 more.
        ///
        /// Its call sites pass different arguments: each call's are in `args`, in order.
        fn reply(&mut self, args: &[super::Arg<'_>]);
    }
    /// What drives the state machines of Link: a received message (with the
    /// trigger's other parameters) or an internal event.
    #[derive(Debug, Clone, Copy)]
    pub enum Trigger {
        /// `Delivered`.
        ///
        /// A message came in.
        Delivered {},
    }
    impl Trigger {
        /// The trigger's name in the state tables.
        pub fn key(&self) -> &'static str {
            match self {
                Trigger::Delivered { .. } => "Delivered",
            }
        }
    }
    /// State machine `InFSM` of [`Link`].
    pub static IN_FSM: hsm::MachineDef = hsm::MachineDef {
        service: "Link",
        name: "InFSM",
        states: &[
            hsm::State {
                name: "Listening",
                path: "Listening",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Delivered"),
                        guard: None,
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[],
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
    /// The state machines of Link, in definition order.
    pub static MACHINES: [&hsm::MachineDef; 1] = [&IN_FSM];
    /// Runs the guards and actions of the tables on an implementation of the trait.
    struct Run<'s, S: ?Sized>(&'s mut S);
    impl<S: Link + ?Sized> hsm::Host<Trigger> for Run<'_, S> {
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn guard(&self, n: u16, t: Option<&Trigger>) -> bool {
            match (n, t) {
                _ => false,
            }
        }
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn action(&mut self, n: u16, t: Option<&Trigger>) {
            match (n, t) {
                _ => {}
            }
        }
    }
    /// The running state machines of Link: feed it triggers with an
    /// implementation of [`Link`]; it calls the guards and actions.
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
        pub fn start<S: Link + ?Sized>(&mut self, service: &mut S) {
            self.0.start(&mut Run(service));
        }
        /// Offers `trigger` to every machine (starting them first if needed); whether
        /// one took a transition.
        pub fn handle<S: Link + ?Sized>(
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
