#[allow(unused_imports)]
use super::*;
#[allow(unused_imports)]
use ::jaus::hsm;
/// Door: trait [`Door`](door::Door), its triggers and state machines (hsm_nested.yaml:5).
#[allow(clippy::module_inception)]
pub mod door {
    #[allow(unused_imports)]
    use super::*;
    /// The service's URI and version.
    pub const ID: &str = "urn:test:hsm:Door 1.0";
    /// The service's URI.
    pub const URI: &str = "urn:test:hsm:Door";
    /// The service's version: major, minor.
    pub const VERSION: (u8, u8) = (1, 0);
    /// The internal events of Door: triggers of its transitions that are not
    /// received messages.
    pub mod event {
        #[allow(unused_imports)]
        use super::*;
        /// Internal event `Push` of [`Door`].
        ///
        /// Someone pushes the door.
        #[derive(Debug, Clone, PartialEq)]
        pub struct Push {}
        /// Internal event `Turn` of [`Door`].
        ///
        /// Someone turns the key.
        #[derive(Debug, Clone, PartialEq)]
        pub struct Turn {}
    }
    /// The Door service (`urn:test:hsm:Door` version 1.0).
    ///
    /// A door that opens, closes and locks.
    ///
    /// Implement its guards and actions; [`Machines`] runs its state machines over the
    /// implementation.
    pub trait Door {
        /// Called as `beep('LOCKED')` (hsm_nested.yaml:27), `beep('UNLOCKED')` (hsm_nested.yaml:28).
        fn beep(&mut self, value0: &str);
        /// Called as `bolt()` (hsm_nested.yaml:24).
        fn bolt(&mut self);
        /// Called as `lightOff()` (hsm_nested.yaml:19).
        fn light_off(&mut self);
        /// Light the way in.
        ///
        /// Called as `lightOn()` (hsm_nested.yaml:20).
        fn light_on(&mut self);
    }
    /// What drives the state machines of Door: a received message (with the
    /// trigger's other parameters) or an internal event.
    #[derive(Debug, Clone, Copy)]
    pub enum Trigger {
        /// `Turn`.
        ///
        /// Someone turns the key.
        Turn {},
        /// `Push`.
        ///
        /// Someone pushes the door.
        Push {},
    }
    impl Trigger {
        /// The trigger's name in the state tables.
        pub fn key(&self) -> &'static str {
            match self {
                Trigger::Turn { .. } => "Turn",
                Trigger::Push { .. } => "Push",
            }
        }
    }
    /// State machine `DoorFSM` of [`Door`].
    pub static DOOR_FSM: hsm::MachineDef = hsm::MachineDef {
        service: "Door",
        name: "DoorFSM",
        states: &[
            hsm::State {
                name: "Closed",
                path: "Closed",
                parent: None,
                initial: Some(1),
                entry: &[0],
                exit: &[1],
                transitions: &[],
                defaults: &[],
            },
            hsm::State {
                name: "Unlocked",
                path: "Closed.Unlocked",
                parent: Some(0),
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Turn"),
                        guard: None,
                        kind: hsm::Kind::Simple,
                        target: Some(2),
                        actions: &[2],
                        raise: None,
                    },
                    hsm::Transition {
                        trigger: Some("Push"),
                        guard: None,
                        kind: hsm::Kind::Simple,
                        target: Some(3),
                        actions: &[],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
            hsm::State {
                name: "Locked",
                path: "Closed.Locked",
                parent: Some(0),
                initial: None,
                entry: &[3],
                exit: &[4],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Turn"),
                        guard: None,
                        kind: hsm::Kind::Simple,
                        target: Some(1),
                        actions: &[],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
            hsm::State {
                name: "Open",
                path: "Open",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Push"),
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
        start: 0,
        transitions: &[],
        defaults: &[],
    };
    /// The state machines of Door, in definition order.
    pub static MACHINES: [&hsm::MachineDef; 1] = [&DOOR_FSM];
    /// Runs the guards and actions of the tables on an implementation of the trait.
    struct Run<'s, S: ?Sized>(&'s mut S);
    impl<S: Door + ?Sized> hsm::Host<Trigger> for Run<'_, S> {
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn guard(&self, n: u16, t: Option<&Trigger>) -> bool {
            match (n, t) {
                _ => false,
            }
        }
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn action(&mut self, n: u16, t: Option<&Trigger>) {
            match (n, t) {
                (0, _) => self.0.light_off(),
                (1, _) => self.0.light_on(),
                (2, _) => self.0.bolt(),
                (3, _) => self.0.beep("LOCKED"),
                (4, _) => self.0.beep("UNLOCKED"),
                _ => {}
            }
        }
    }
    /// The running state machines of Door: feed it triggers with an
    /// implementation of [`Door`]; it calls the guards and actions.
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
        pub fn start<S: Door + ?Sized>(&mut self, service: &mut S) {
            self.0.start(&mut Run(service));
        }
        /// Offers `trigger` to every machine (starting them first if needed); whether
        /// one took a transition.
        pub fn handle<S: Door + ?Sized>(
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
