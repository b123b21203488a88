#[allow(unused_imports)]
use super::*;
#[allow(unused_imports)]
use ::jaus::hsm;
/// Throttle: trait [`Throttle`](throttle::Throttle), its triggers and state machines (hsm_guards.yaml:10).
#[allow(clippy::module_inception)]
pub mod throttle {
    #[allow(unused_imports)]
    use super::*;
    /// The service's URI and version.
    pub const ID: &str = "urn:test:hsm:Throttle 1.0";
    /// The service's URI.
    pub const URI: &str = "urn:test:hsm:Throttle";
    /// The service's version: major, minor.
    pub const VERSION: (u8, u8) = (1, 0);
    /// The internal events of Throttle: triggers of its transitions that are not
    /// received messages.
    pub mod event {
        #[allow(unused_imports)]
        use super::*;
        /// Internal event `Received` of [`Throttle`].
        #[derive(Debug, Clone, PartialEq)]
        pub struct Received {
            pub source: u32,
        }
    }
    /// The Throttle service (`urn:test:hsm:Throttle` version 1.0).
    ///
    /// Implement its guards and actions; [`Machines`] runs its state machines over the
    /// implementation.
    pub trait Throttle {
        /// A trusted sender within the limit, or an override.
        ///
        /// Called as `isOverride(from)` (hsm_guards.yaml:28).
        fn is_override(&self, from: &super::throttle::event::Received) -> bool;
        /// A trusted sender within the limit, or an override.
        ///
        /// Called as `isTooFast(msg)` (hsm_guards.yaml:28).
        fn is_too_fast(&self, msg: &SetSpeed) -> bool;
        /// A trusted sender within the limit, or an override.
        ///
        /// Called as `isTrusted(from)` (hsm_guards.yaml:28).
        fn is_trusted(&self, from: &super::throttle::event::Received) -> bool;
        /// Called as `apply(msg)` (hsm_guards.yaml:31).
        fn apply(&mut self, msg: &SetSpeed);
        /// Called as `refuse(from, 'UNTRUSTED')` (hsm_guards.yaml:38).
        fn refuse(&mut self, from: &super::throttle::event::Received, value1: &str);
    }
    /// What drives the state machines of Throttle: a received message (with the
    /// trigger's other parameters) or an internal event.
    #[derive(Debug, Clone, Copy)]
    pub enum Trigger<'a> {
        /// `Received` carrying [`SetSpeed`].
        SetSpeed {
            /// Parameter `msg`.
            msg: &'a SetSpeed,
            /// Parameter `from`.
            from: &'a super::throttle::event::Received,
        },
    }
    impl Trigger<'_> {
        /// The trigger's name in the state tables.
        pub fn key(&self) -> &'static str {
            match self {
                Trigger::SetSpeed { .. } => "SetSpeed",
            }
        }
    }
    impl<'a> Trigger<'a> {
        /// The trigger a received `message` raises in the machines of Throttle, with
        /// the trigger's other parameters; `None` for a message none of them takes.
        pub fn received(
            message: &'a Message,
            from: &'a super::throttle::event::Received,
        ) -> Option<Self> {
            Some(
                match message {
                    Message::SetSpeed(msg) => Trigger::SetSpeed { msg, from },
                    _ => return None,
                },
            )
        }
    }
    /// The messages the machines of Throttle take, by command code (ascending).
    pub const RECEIVES: &[::jaus::CommandCode] = &[
        <SetSpeed as ::jaus::JausMessage>::CODE,
    ];
    /// State machine `Main` of [`Throttle`].
    pub static MAIN: hsm::MachineDef = hsm::MachineDef {
        service: "Throttle",
        name: "Main",
        states: &[
            hsm::State {
                name: "Idle",
                path: "Idle",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("SetSpeed"),
                        guard: Some(
                            &hsm::Expr::Or(
                                &[
                                    hsm::Expr::And(
                                        &[hsm::Expr::Call(0), hsm::Expr::Not(&hsm::Expr::Call(1))],
                                    ),
                                    hsm::Expr::Call(2),
                                ],
                            ),
                        ),
                        kind: hsm::Kind::Simple,
                        target: Some(1),
                        actions: &[0],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
            hsm::State {
                name: "Moving",
                path: "Moving",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("SetSpeed"),
                        guard: Some(
                            &hsm::Expr::Not(
                                &hsm::Expr::Or(&[hsm::Expr::Call(3), hsm::Expr::Call(4)]),
                            ),
                        ),
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
    /// The state machines of Throttle, in definition order.
    pub static MACHINES: [&hsm::MachineDef; 1] = [&MAIN];
    /// Runs the guards and actions of the tables on an implementation of the trait.
    struct Run<'s, S: ?Sized>(&'s mut S);
    impl<S: Throttle + ?Sized> hsm::Host<Trigger<'_>> for Run<'_, S> {
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn guard(&self, n: u16, t: Option<&Trigger<'_>>) -> bool {
            match (n, t) {
                (0, Some(Trigger::SetSpeed { from, .. })) => self.0.is_trusted(from),
                (1, Some(Trigger::SetSpeed { msg, .. })) => self.0.is_too_fast(msg),
                (2, Some(Trigger::SetSpeed { from, .. })) => self.0.is_override(from),
                (3, Some(Trigger::SetSpeed { from, .. })) => self.0.is_trusted(from),
                (4, Some(Trigger::SetSpeed { from, .. })) => self.0.is_override(from),
                _ => false,
            }
        }
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn action(&mut self, n: u16, t: Option<&Trigger<'_>>) {
            match (n, t) {
                (0, Some(Trigger::SetSpeed { msg, .. })) => self.0.apply(msg),
                (1, Some(Trigger::SetSpeed { from, .. })) => {
                    self.0.refuse(from, "UNTRUSTED")
                }
                _ => {}
            }
        }
    }
    /// The running state machines of Throttle: feed it triggers with an
    /// implementation of [`Throttle`]; it calls the guards and actions.
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
        pub fn start<S: Throttle + ?Sized>(&mut self, service: &mut S) {
            self.0.start(&mut Run(service));
        }
        /// Offers `trigger` to every machine (starting them first if needed); whether
        /// one took a transition.
        pub fn handle<S: Throttle + ?Sized>(
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
        pub fn receive<S: Throttle + ?Sized>(
            &mut self,
            service: &mut S,
            message: &Message,
            from: &super::throttle::event::Received,
        ) -> Option<bool> {
            let trigger = Trigger::received(message, from)?;
            Some(self.handle(service, &trigger))
        }
    }
}
