#[allow(unused_imports)]
use ::jaus::component::{
    Behaviour, Component, Config, Context, CoreState, CoreTransition, Emits, InitError,
    Modes, NoModes, Refused, StopReason,
};
/// The row type of [`COMPONENTS`] (the `INFO` of each module) and what it holds.
pub use ::jaus::component::{ComponentInfo, Hardware, StockInfo};
#[allow(unused_imports)]
use ::jaus::messages::*;
#[allow(unused_imports)]
use ::jaus::{Address, CommandCode, JausMessage};
/// The Waypoint Follower (component id 211): trait [`WaypointFollower`], interface, modes, dispatch.
///
/// The function of the Waypoint Follower is to drive to one waypoint at a time.
pub mod waypoint_follower {
    use super::*;
    /// The Waypoint Follower's component id.
    pub const ID: u8 = 211;
    /// The Waypoint Follower's row of the component table.
    pub const INFO: ComponentInfo = ComponentInfo {
        name: "WaypointFollower",
        module: "waypoint_follower",
        id: ID,
        function: "The function of the Waypoint Follower is to drive to one waypoint at a time.",
        stock: None,
    };
    /// Waypoint Follower (component id 211).
    ///
    /// The function of the Waypoint Follower is to drive to one waypoint at a time.
    ///
    /// # Messages
    ///
    /// * Commands (from the component in control only): [`SetGlobalWaypoint`]
    /// * Accepted from anyone: none
    /// * Sent on its own: none
    ///
    /// Defined in `component_modes.yaml:9`.
    ///
    /// Implement the methods of the messages your component supports; the runtime
    /// ([`Component`]) does everything common to all JAUS components. Run it with
    /// [`component`].
    pub trait WaypointFollower: Send + 'static {
        /// Handles [`SetGlobalWaypoint`] (0x040C): Set Global Waypoint.
        ///
        /// A command: the runtime calls this only when the sender is the component in control and
        /// the component is in Ready or Standby. Return `Err(Refused::Invalid(..))` for values that
        /// cannot be executed (the sender gets a NAK if it asked for an acknowledgement).
        ///
        /// Not implemented: the message is ignored and counted as unsupported.
        fn on_set_global_waypoint(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &SetGlobalWaypoint,
        ) -> Result<(), Refused> {
            let _ = (ctx, msg);
            Err(Refused::Unsupported)
        }
        /// Any other message outside this interface (for example
        /// Confirm Component Control answering a request this component sent, or reports
        /// of the sensors it queries). Return a reply to send it back to the sender.
        fn on_other_message(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &Message,
        ) -> Result<Option<Message>, Refused> {
            let _ = (ctx, msg);
            Err(Refused::Unsupported)
        }
        /// Called in Initialize; return an error to enter Failure instead of Standby (the
        /// runtime logs it with the component's name and address: say what failed and what
        /// to check).
        fn initialize(&mut self, ctx: &mut Ctx<'_>) -> Result<(), InitError> {
            let _ = ctx;
            Ok(())
        }
        /// Called after every core state change (into Emergency: stop all motion).
        fn state_changed(&mut self, ctx: &mut Ctx<'_>, from: CoreState, to: CoreState) {
            let _ = (ctx, from, to);
        }
        /// Called every `Config::tick`, in every state but Shutdown.
        fn tick(&mut self, ctx: &mut Ctx<'_>) {
            let _ = ctx;
        }
    }
    /// The interface of the Waypoint Follower: its id, messages and modes.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub struct Interface;
    impl ::jaus::component::Interface for Interface {
        const NAME: &'static str = INFO.name;
        const ID: u8 = ID;
        const FUNCTION: &'static str = INFO.function;
        const COMMANDS: &'static [CommandCode] = &[CommandCode(0x040C)];
        const ACCEPTS: &'static [CommandCode] = &[];
        const EMITS: &'static [CommandCode] = &[];
        const ANY_MESSAGE: bool = false;
        type Modes = Mode;
        type Messages = Message;
    }
    /// The context handed to the methods of [`WaypointFollower`].
    pub type Ctx<'a> = Context<'a, Interface>;
    /// Modes of the Waypoint Follower within Ready.
    ///
    /// What the follower is doing.
    ///
    /// The runtime returns to the initial mode whenever the component leaves Ready.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum Mode {
        /// No waypoint to drive to.
        Idle,
        /// Mode Driving.
        Driving,
        /// Stopped short of the waypoint.
        Holding,
    }
    /// The legal changes of [`Mode`] (pass them to `Ctx::transition`).
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum Transition {
        /// `Idle`, `Holding` → `Driving`.
        ///
        /// A waypoint arrived.
        Start,
        /// `Driving` → `Holding`.
        Hold,
        /// `Driving` → `Idle`.
        /// The component also enters Standby.
        ///
        /// The waypoint is reached.
        Arrive,
        /// `Driving`, `Holding` → `Idle`.
        /// The component also enters Failure.
        LosePose,
    }
    /// Every [`Mode`], in the order of [`MODES`]' states.
    const MODE_LIST: [Mode; 3] = [Mode::Idle, Mode::Driving, Mode::Holding];
    /// The modes as a state machine, run by `::jaus::hsm` ([`Modes::next`]): a state per
    /// mode, a transition per mode it may be taken from.
    pub static MODES: ::jaus::hsm::MachineDef = ::jaus::hsm::MachineDef {
        service: "WaypointFollower",
        name: "modes",
        states: &[
            ::jaus::hsm::State {
                name: "Idle",
                path: "Idle",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    ::jaus::hsm::Transition {
                        trigger: Some("start"),
                        guard: None,
                        kind: ::jaus::hsm::Kind::Simple,
                        target: Some(1),
                        actions: &[],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
            ::jaus::hsm::State {
                name: "Driving",
                path: "Driving",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    ::jaus::hsm::Transition {
                        trigger: Some("hold"),
                        guard: None,
                        kind: ::jaus::hsm::Kind::Simple,
                        target: Some(2),
                        actions: &[],
                        raise: None,
                    },
                    ::jaus::hsm::Transition {
                        trigger: Some("arrive"),
                        guard: None,
                        kind: ::jaus::hsm::Kind::Simple,
                        target: Some(0),
                        actions: &[],
                        raise: None,
                    },
                    ::jaus::hsm::Transition {
                        trigger: Some("lose_pose"),
                        guard: None,
                        kind: ::jaus::hsm::Kind::Simple,
                        target: Some(0),
                        actions: &[],
                        raise: None,
                    },
                ],
                defaults: &[],
            },
            ::jaus::hsm::State {
                name: "Holding",
                path: "Holding",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[
                    ::jaus::hsm::Transition {
                        trigger: Some("start"),
                        guard: None,
                        kind: ::jaus::hsm::Kind::Simple,
                        target: Some(1),
                        actions: &[],
                        raise: None,
                    },
                    ::jaus::hsm::Transition {
                        trigger: Some("lose_pose"),
                        guard: None,
                        kind: ::jaus::hsm::Kind::Simple,
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
    impl Modes for Mode {
        type Transition = Transition;
        const INITIAL: Self = Mode::Idle;
        const MACHINE: &'static str = "WaypointFollower";
        fn name(self) -> &'static str {
            match self {
                Mode::Idle => "Idle",
                Mode::Driving => "Driving",
                Mode::Holding => "Holding",
            }
        }
        fn next(self, t: Transition) -> Option<Self> {
            let to = ::jaus::hsm::next_state(
                &MODES,
                self as u16,
                Self::transition_name(t),
            )?;
            MODE_LIST.get(usize::from(to)).copied()
        }
        fn transition_name(t: Transition) -> &'static str {
            match t {
                Transition::Start => "start",
                Transition::Hold => "hold",
                Transition::Arrive => "arrive",
                Transition::LosePose => "lose_pose",
            }
        }
        fn core_effect(t: Transition) -> Option<CoreTransition> {
            match t {
                Transition::Start => None,
                Transition::Hold => None,
                Transition::Arrive => Some(CoreTransition::Standby),
                Transition::LosePose => Some(CoreTransition::Fail),
            }
        }
    }
    /// Runs a [`WaypointFollower`] implementation under the component runtime.
    #[derive(Debug, Clone, Default)]
    pub struct Dispatch<T>(pub T);
    impl<T: WaypointFollower> Behaviour for Dispatch<T> {
        type Interface = Interface;
        #[allow(clippy::match_single_binding)]
        fn handle(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &Message,
        ) -> Result<Option<Message>, Refused> {
            match msg {
                Message::SetGlobalWaypoint(m) => {
                    self.0.on_set_global_waypoint(ctx, m).map(|()| None)
                }
                #[allow(unreachable_patterns)]
                other => self.0.on_other_message(ctx, other),
            }
        }
        fn initialize(&mut self, ctx: &mut Ctx<'_>) -> Result<(), InitError> {
            self.0.initialize(ctx)
        }
        fn state_changed(&mut self, ctx: &mut Ctx<'_>, from: CoreState, to: CoreState) {
            self.0.state_changed(ctx, from, to)
        }
        fn tick(&mut self, ctx: &mut Ctx<'_>) {
            self.0.tick(ctx)
        }
    }
    /// A Waypoint Follower component at `address` running `imp`, starting at `now`.
    pub fn component<T: WaypointFollower>(
        address: Address,
        imp: T,
        config: Config,
        now: std::time::Instant,
    ) -> Component<Dispatch<T>> {
        Component::new(address, Dispatch(imp), config, now)
    }
}
#[allow(unused_imports)]
pub use waypoint_follower::WaypointFollower;
/// The Recorder (component id 212): trait [`Recorder`], interface, modes, dispatch.
///
/// The function of the Recorder is to record.
pub mod recorder {
    use super::*;
    /// The Recorder's component id.
    pub const ID: u8 = 212;
    /// The Recorder's row of the component table.
    pub const INFO: ComponentInfo = ComponentInfo {
        name: "Recorder",
        module: "recorder",
        id: ID,
        function: "The function of the Recorder is to record.",
        stock: None,
    };
    /// Recorder (component id 212).
    ///
    /// The function of the Recorder is to record.
    ///
    /// # Messages
    ///
    /// * Commands (from the component in control only): none
    /// * Accepted from anyone: none
    /// * Sent on its own: none
    ///
    /// Defined in `component_modes.yaml:25`.
    ///
    /// Implement the methods of the messages your component supports; the runtime
    /// ([`Component`]) does everything common to all JAUS components. Run it with
    /// [`component`].
    pub trait Recorder: Send + 'static {
        /// Any other message outside this interface (for example
        /// Confirm Component Control answering a request this component sent, or reports
        /// of the sensors it queries). Return a reply to send it back to the sender.
        fn on_other_message(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &Message,
        ) -> Result<Option<Message>, Refused> {
            let _ = (ctx, msg);
            Err(Refused::Unsupported)
        }
        /// Called in Initialize; return an error to enter Failure instead of Standby (the
        /// runtime logs it with the component's name and address: say what failed and what
        /// to check).
        fn initialize(&mut self, ctx: &mut Ctx<'_>) -> Result<(), InitError> {
            let _ = ctx;
            Ok(())
        }
        /// Called after every core state change (into Emergency: stop all motion).
        fn state_changed(&mut self, ctx: &mut Ctx<'_>, from: CoreState, to: CoreState) {
            let _ = (ctx, from, to);
        }
        /// Called every `Config::tick`, in every state but Shutdown.
        fn tick(&mut self, ctx: &mut Ctx<'_>) {
            let _ = ctx;
        }
    }
    /// The interface of the Recorder: its id, messages and modes.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub struct Interface;
    impl ::jaus::component::Interface for Interface {
        const NAME: &'static str = INFO.name;
        const ID: u8 = ID;
        const FUNCTION: &'static str = INFO.function;
        const COMMANDS: &'static [CommandCode] = &[];
        const ACCEPTS: &'static [CommandCode] = &[];
        const EMITS: &'static [CommandCode] = &[];
        const ANY_MESSAGE: bool = false;
        type Modes = Mode;
        type Messages = Message;
    }
    /// The context handed to the methods of [`Recorder`].
    pub type Ctx<'a> = Context<'a, Interface>;
    /// Modes of the Recorder within Ready.
    ///
    /// The runtime returns to the initial mode whenever the component leaves Ready.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum Mode {
        /// Mode Recording.
        Recording,
    }
    /// The legal changes of [`Mode`] (pass them to `Ctx::transition`).
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum Transition {}
    /// The modes as a state machine, run by `::jaus::hsm` ([`Modes::next`]): a state per
    /// mode, a transition per mode it may be taken from.
    pub static MODES: ::jaus::hsm::MachineDef = ::jaus::hsm::MachineDef {
        service: "Recorder",
        name: "modes",
        states: &[
            ::jaus::hsm::State {
                name: "Recording",
                path: "Recording",
                parent: None,
                initial: None,
                entry: &[],
                exit: &[],
                transitions: &[],
                defaults: &[],
            },
        ],
        start: 0,
        transitions: &[],
        defaults: &[],
    };
    impl Modes for Mode {
        type Transition = Transition;
        const INITIAL: Self = Mode::Recording;
        const MACHINE: &'static str = "Recorder";
        fn name(self) -> &'static str {
            match self {
                Mode::Recording => "Recording",
            }
        }
        fn next(self, t: Transition) -> Option<Self> {
            let _ = self;
            match t {}
        }
        fn transition_name(t: Transition) -> &'static str {
            match t {}
        }
        fn core_effect(t: Transition) -> Option<CoreTransition> {
            match t {}
        }
    }
    /// Runs a [`Recorder`] implementation under the component runtime.
    #[derive(Debug, Clone, Default)]
    pub struct Dispatch<T>(pub T);
    impl<T: Recorder> Behaviour for Dispatch<T> {
        type Interface = Interface;
        #[allow(clippy::match_single_binding)]
        fn handle(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &Message,
        ) -> Result<Option<Message>, Refused> {
            match msg {
                #[allow(unreachable_patterns)]
                other => self.0.on_other_message(ctx, other),
            }
        }
        fn initialize(&mut self, ctx: &mut Ctx<'_>) -> Result<(), InitError> {
            self.0.initialize(ctx)
        }
        fn state_changed(&mut self, ctx: &mut Ctx<'_>, from: CoreState, to: CoreState) {
            self.0.state_changed(ctx, from, to)
        }
        fn tick(&mut self, ctx: &mut Ctx<'_>) {
            self.0.tick(ctx)
        }
    }
    /// A Recorder component at `address` running `imp`, starting at `now`.
    pub fn component<T: Recorder>(
        address: Address,
        imp: T,
        config: Config,
        now: std::time::Instant,
    ) -> Component<Dispatch<T>> {
        Component::new(address, Dispatch(imp), config, now)
    }
}
#[allow(unused_imports)]
pub use recorder::Recorder;
/// Every component interface: its name, module, id, function and stock implementation
/// (the `INFO` of each module), in definition order.
pub static COMPONENTS: &[ComponentInfo] = &[waypoint_follower::INFO, recorder::INFO];
