#[allow(unused_imports)]
use super::*;
#[allow(unused_imports)]
use ::jaus::hsm;
/// Player: trait [`Player`](player::Player), its triggers and state machines (hsm_kinds.yaml:6).
#[allow(clippy::module_inception)]
pub mod player {
    #[allow(unused_imports)]
    use super::*;
    /// The service's URI and version.
    pub const ID: &str = "urn:test:hsm:Player 1.0";
    /// The service's URI.
    pub const URI: &str = "urn:test:hsm:Player";
    /// The service's version: major, minor.
    pub const VERSION: (u8, u8) = (1, 0);
    /// The internal events of Player: triggers of its transitions that are not
    /// received messages.
    pub mod event {
        #[allow(unused_imports)]
        use super::*;
        /// Internal event `Play` of [`Player`].
        #[derive(Debug, Clone, PartialEq)]
        pub struct Play {}
        /// Internal event `Pause` of [`Player`].
        #[derive(Debug, Clone, PartialEq)]
        pub struct Pause {}
        /// Internal event `Resume` of [`Player`].
        #[derive(Debug, Clone, PartialEq)]
        pub struct Resume {}
        /// Internal event `Resumed` of [`Player`].
        #[derive(Debug, Clone, PartialEq)]
        pub struct Resumed {}
        /// Internal event `Volume` of [`Player`].
        #[derive(Debug, Clone, PartialEq)]
        pub struct Volume {}
        /// Internal event `Eject` of [`Player`].
        #[derive(Debug, Clone, PartialEq)]
        pub struct Eject {}
    }
    /// The Player service (`urn:test:hsm:Player` version 1.0).
    ///
    /// Implement its guards and actions; [`Machines`] runs its state machines over the
    /// implementation.
    pub trait Player {
        /// Called as `eject()` (hsm_kinds.yaml:38).
        fn eject(&mut self);
        /// Called as `ignore()` (hsm_kinds.yaml:29).
        fn ignore(&mut self);
        /// Called as `remember()` (hsm_kinds.yaml:35).
        fn remember(&mut self);
        /// Called as `setVolume()` (hsm_kinds.yaml:26).
        fn set_volume(&mut self);
        /// Called as `spinUp()` (hsm_kinds.yaml:23).
        fn spin_up(&mut self);
        /// Called as `unexpected()` (hsm_kinds.yaml:40).
        fn unexpected(&mut self);
    }
    /// What drives the state machines of Player: a received message (with the
    /// trigger's other parameters) or an internal event.
    #[derive(Debug, Clone, Copy)]
    pub enum Trigger {
        /// `Eject`.
        Eject {},
        /// `Play`.
        Play {},
        /// `Volume`.
        Volume {},
        /// `Pause`.
        Pause {},
        /// `Resume`.
        Resume {},
    }
    impl Trigger {
        /// The trigger's name in the state tables.
        pub fn key(&self) -> &'static str {
            match self {
                Trigger::Eject { .. } => "Eject",
                Trigger::Play { .. } => "Play",
                Trigger::Volume { .. } => "Volume",
                Trigger::Pause { .. } => "Pause",
                Trigger::Resume { .. } => "Resume",
            }
        }
    }
    /// State machine `PlayerFSM` of [`Player`].
    pub static PLAYER_FSM: hsm::MachineDef = hsm::MachineDef {
        service: "Player",
        name: "PlayerFSM",
        states: &[
            hsm::State {
                name: "Stopped",
                path: "Stopped",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Play"),
                        guard: None,
                        kind: hsm::Kind::Simple,
                        target: Some(1),
                        actions: &[0],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
            hsm::State {
                name: "Playing",
                path: "Playing",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Volume"),
                        guard: None,
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[1],
                        raise: None,
                    },
                    hsm::Transition {
                        trigger: Some("Pause"),
                        guard: None,
                        kind: hsm::Kind::Push,
                        target: Some(2),
                        actions: &[],
                        raise: None,
                    },
                ],
                defaults: &[
                    hsm::Transition {
                        trigger: None,
                        guard: None,
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[2],
                        raise: None,
                    },
                ],
            },
            hsm::State {
                name: "Paused",
                path: "Paused",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    hsm::Transition {
                        trigger: Some("Resume"),
                        guard: None,
                        kind: hsm::Kind::Pop,
                        target: None,
                        actions: &[],
                        raise: Some("Resumed"),
                    },
                    hsm::Transition {
                        trigger: Some("Volume"),
                        guard: None,
                        kind: hsm::Kind::Internal,
                        target: None,
                        actions: &[3],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
        ],
        start: 0,
        transitions: &[
            hsm::Transition {
                trigger: Some("Eject"),
                guard: None,
                kind: hsm::Kind::Simple,
                target: Some(0),
                actions: &[4],
                raise: None,
            },
        ],
        defaults: &[
            hsm::Transition {
                trigger: None,
                guard: None,
                kind: hsm::Kind::Internal,
                target: None,
                actions: &[5],
                raise: None,
            },
        ],
    };
    /// The state machines of Player, in definition order.
    pub static MACHINES: [&hsm::MachineDef; 1] = [&PLAYER_FSM];
    /// Runs the guards and actions of the tables on an implementation of the trait.
    struct Run<'s, S: ?Sized>(&'s mut S);
    impl<S: Player + ?Sized> hsm::Host<Trigger> for Run<'_, S> {
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn guard(&self, n: u16, t: Option<&Trigger>) -> bool {
            match (n, t) {
                _ => false,
            }
        }
        #[allow(unused_variables, clippy::match_single_binding, clippy::single_match)]
        fn action(&mut self, n: u16, t: Option<&Trigger>) {
            match (n, t) {
                (0, _) => self.0.spin_up(),
                (1, _) => self.0.set_volume(),
                (2, _) => self.0.ignore(),
                (3, _) => self.0.remember(),
                (4, _) => self.0.eject(),
                (5, _) => self.0.unexpected(),
                _ => {}
            }
        }
    }
    /// The running state machines of Player: feed it triggers with an
    /// implementation of [`Player`]; it calls the guards and actions.
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
        pub fn start<S: Player + ?Sized>(&mut self, service: &mut S) {
            self.0.start(&mut Run(service));
        }
        /// Offers `trigger` to every machine (starting them first if needed); whether
        /// one took a transition.
        pub fn handle<S: Player + ?Sized>(
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
