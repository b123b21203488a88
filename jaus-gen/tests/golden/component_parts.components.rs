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
/// Parts that several component interfaces share: one trait each, generic over the
/// interface of the component it serves. A component trait reaches its parts through
/// one method per part and passes the shared messages to them.
pub mod parts {
    use super::*;
    /// Follower: a part that several component interfaces share.
    ///
    /// What the two followers share, a travel speed and their output.
    ///
    /// # Rules
    ///
    /// * The travel speed is set to zero on every transition from Standby to Ready.
    ///
    /// # Messages
    ///
    /// * Commands (from the component in control only): [`SetTravelSpeed`]
    /// * Accepted from anyone: [`QueryTravelSpeed`], [`ReportVelocityState`]
    /// * Handled only by the components that list them: [`ReportVelocityState`]
    /// * Sent on its own: [`SetWrenchEffort`]
    ///
    /// # Use
    ///
    /// Shared by [`GlobalFollower`], [`LocalFollower`]. `I` is the interface of the component
    /// the part serves (its `Interface`), so a handler gets that component's context. Implement
    /// the part once, generic over `I` (bounded by what it needs, such as `Emits<M>` to send
    /// `M`), or for one interface; then return it from each component trait's `follower` method
    /// (`Some(self)`, or `Some(&mut self.field)`). The component trait's default methods of
    /// these messages, and its `initialize`, `state_changed` and `tick`, pass to it.
    ///
    /// Defined in `component_parts.yaml:18`.
    pub trait Follower<I: ::jaus::component::Interface> {
        /// Handles [`SetTravelSpeed`] (0x040A): Set Travel Speed.
        ///
        /// A command: the runtime calls this only when the sender is the component in control and
        /// the component is in Ready or Standby. Return `Err(Refused::Invalid(..))` for values that
        /// cannot be executed (the sender gets a NAK if it asked for an acknowledgement).
        ///
        /// Not implemented: the message is ignored and counted as unsupported.
        fn on_set_travel_speed(
            &mut self,
            ctx: &mut Context<'_, I>,
            msg: &SetTravelSpeed,
        ) -> Result<(), Refused> {
            let _ = (ctx, msg);
            Err(Refused::Unsupported)
        }
        /// Handles [`QueryTravelSpeed`] (0x240A): Query Travel Speed.
        ///
        /// A query from any component: return the [`ReportTravelSpeed`] to send back. The same
        /// method answers service connections and events on that report.
        ///
        /// Not implemented: the message is ignored and counted as unsupported.
        fn on_query_travel_speed(
            &mut self,
            ctx: &mut Context<'_, I>,
            msg: &QueryTravelSpeed,
        ) -> Result<ReportTravelSpeed, Refused> {
            let _ = (ctx, msg);
            Err(Refused::Unsupported)
        }
        /// Handles [`ReportVelocityState`] (0x4404): Report Velocity State.
        ///
        /// Accepted from any component.
        ///
        /// Not implemented: the message is ignored and counted as unsupported.
        fn on_report_velocity_state(
            &mut self,
            ctx: &mut Context<'_, I>,
            msg: &ReportVelocityState,
        ) -> Result<(), Refused> {
            let _ = (ctx, msg);
            Err(Refused::Unsupported)
        }
        /// Called in Initialize by the component's default `initialize`; return an error
        /// to enter Failure instead of Standby.
        fn initialize(&mut self, ctx: &mut Context<'_, I>) -> Result<(), InitError> {
            let _ = ctx;
            Ok(())
        }
        /// Called after every core state change by the component's default
        /// `state_changed`.
        fn state_changed(
            &mut self,
            ctx: &mut Context<'_, I>,
            from: CoreState,
            to: CoreState,
        ) {
            let _ = (ctx, from, to);
        }
        /// Called every `Config::tick` by the component's default `tick`.
        fn tick(&mut self, ctx: &mut Context<'_, I>) {
            let _ = ctx;
        }
    }
}
/// The Global Follower (component id 213): trait [`GlobalFollower`], interface, dispatch.
///
/// The function of the Global Follower is to follow global waypoints.
pub mod global_follower {
    use super::*;
    /// The Global Follower's component id.
    pub const ID: u8 = 213;
    /// The Global Follower's row of the component table.
    pub const INFO: ComponentInfo = ComponentInfo {
        name: "GlobalFollower",
        module: "global_follower",
        id: ID,
        function: "The function of the Global Follower is to follow global waypoints.",
        stock: None,
    };
    /// Global Follower (component id 213).
    ///
    /// The function of the Global Follower is to follow global waypoints.
    ///
    /// # Messages
    ///
    /// * Commands (from the component in control only): [`SetGlobalWaypoint`], [`SetTravelSpeed`]
    /// * Accepted from anyone: [`QueryTravelSpeed`], [`ReportVelocityState`]
    /// * Sent on its own: [`SetWrenchEffort`]
    /// * Shares the [`Follower`](super::parts::Follower) part with other components: its messages go to [`follower`](Self::follower)
    ///
    /// Defined in `component_parts.yaml:27`.
    ///
    /// Implement the methods of the messages your component supports; the runtime
    /// ([`Component`]) does everything common to all JAUS components. Run it with
    /// [`component`].
    pub trait GlobalFollower: Send + 'static {
        /// Stops all motion now (required: this component commands motion). The runtime
        /// calls it on entering Emergency (from any state), on leaving Ready for Standby,
        /// Shutdown or Failure, and when the component in control releases it, is
        /// preempted or disappears; `reason` says which. Commands are refused until the
        /// component is Ready again and controlled.
        fn stop(&mut self, ctx: &mut Ctx<'_>, reason: StopReason);
        /// The [`Follower`](super::parts::Follower) part of this component: return it
        /// (`Some(self)` when `Self` implements it, or a field that does) and the default
        /// methods of the part's messages, `initialize`, `state_changed` and `tick` pass
        /// to it. `None` (the default): those messages are unsupported.
        fn follower(&mut self) -> Option<&mut dyn super::parts::Follower<Interface>> {
            None
        }
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
        /// Handles [`SetTravelSpeed`] (0x040A): Set Travel Speed.
        ///
        /// A command: the runtime calls this only when the sender is the component in control and
        /// the component is in Ready or Standby. Return `Err(Refused::Invalid(..))` for values that
        /// cannot be executed (the sender gets a NAK if it asked for an acknowledgement).
        ///
        /// Not implemented here: passed to the `Follower` part that [`follower`](Self::follower)
        /// returns, if any; otherwise the message is ignored and counted as unsupported.
        fn on_set_travel_speed(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &SetTravelSpeed,
        ) -> Result<(), Refused> {
            match self.follower() {
                Some(part) => part.on_set_travel_speed(ctx, msg),
                None => Err(Refused::Unsupported),
            }
        }
        /// Handles [`QueryTravelSpeed`] (0x240A): Query Travel Speed.
        ///
        /// A query from any component: return the [`ReportTravelSpeed`] to send back. The same
        /// method answers service connections and events on that report.
        ///
        /// Not implemented here: passed to the `Follower` part that [`follower`](Self::follower)
        /// returns, if any; otherwise the message is ignored and counted as unsupported.
        fn on_query_travel_speed(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &QueryTravelSpeed,
        ) -> Result<ReportTravelSpeed, Refused> {
            match self.follower() {
                Some(part) => part.on_query_travel_speed(ctx, msg),
                None => Err(Refused::Unsupported),
            }
        }
        /// Handles [`ReportVelocityState`] (0x4404): Report Velocity State.
        ///
        /// Accepted from any component.
        ///
        /// Not implemented here: passed to the `Follower` part that [`follower`](Self::follower)
        /// returns, if any; otherwise the message is ignored and counted as unsupported.
        fn on_report_velocity_state(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &ReportVelocityState,
        ) -> Result<(), Refused> {
            match self.follower() {
                Some(part) => part.on_report_velocity_state(ctx, msg),
                None => Err(Refused::Unsupported),
            }
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
        /// to check). The default calls `initialize` of each part; an override
        /// calls them itself.
        fn initialize(&mut self, ctx: &mut Ctx<'_>) -> Result<(), InitError> {
            if let Some(part) = self.follower() {
                part.initialize(ctx)?;
            }
            Ok(())
        }
        /// Called after every core state change (into Emergency: stop all motion). The
        /// default calls `state_changed` of each part.
        fn state_changed(&mut self, ctx: &mut Ctx<'_>, from: CoreState, to: CoreState) {
            if let Some(part) = self.follower() {
                part.state_changed(ctx, from, to);
            }
        }
        /// Called every `Config::tick`, in every state but Shutdown. The
        /// default calls `tick` of each part.
        fn tick(&mut self, ctx: &mut Ctx<'_>) {
            if let Some(part) = self.follower() {
                part.tick(ctx);
            }
        }
    }
    /// The interface of the Global Follower: its id, messages and modes.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub struct Interface;
    impl ::jaus::component::Interface for Interface {
        const NAME: &'static str = INFO.name;
        const ID: u8 = ID;
        const FUNCTION: &'static str = INFO.function;
        const COMMANDS: &'static [CommandCode] = &[
            CommandCode(0x040C),
            CommandCode(0x040A),
        ];
        const ACCEPTS: &'static [CommandCode] = &[
            CommandCode(0x240A),
            CommandCode(0x4404),
        ];
        const EMITS: &'static [CommandCode] = &[CommandCode(0x0405)];
        const ANY_MESSAGE: bool = false;
        type Modes = NoModes;
        type Messages = Message;
    }
    impl Emits<SetWrenchEffort> for Interface {
        fn wrap(msg: SetWrenchEffort) -> Message {
            msg.into()
        }
    }
    /// The context handed to the methods of [`GlobalFollower`].
    pub type Ctx<'a> = Context<'a, Interface>;
    /// Runs a [`GlobalFollower`] implementation under the component runtime.
    #[derive(Debug, Clone, Default)]
    pub struct Dispatch<T>(pub T);
    impl<T: GlobalFollower> Behaviour for Dispatch<T> {
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
                Message::SetTravelSpeed(m) => {
                    self.0.on_set_travel_speed(ctx, m).map(|()| None)
                }
                Message::QueryTravelSpeed(m) => {
                    self.0.on_query_travel_speed(ctx, m).map(|r| Some(r.into()))
                }
                Message::ReportVelocityState(m) => {
                    self.0.on_report_velocity_state(ctx, m).map(|()| None)
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
        fn stop(&mut self, ctx: &mut Ctx<'_>, reason: StopReason) {
            self.0.stop(ctx, reason)
        }
    }
    /// A Global Follower component at `address` running `imp`, starting at `now`.
    pub fn component<T: GlobalFollower>(
        address: Address,
        imp: T,
        config: Config,
        now: std::time::Instant,
    ) -> Component<Dispatch<T>> {
        Component::new(address, Dispatch(imp), config, now)
    }
}
#[allow(unused_imports)]
pub use global_follower::GlobalFollower;
/// The Local Follower (component id 214): trait [`LocalFollower`], interface, dispatch.
///
/// The function of the Local Follower is to follow local waypoints.
pub mod local_follower {
    use super::*;
    /// The Local Follower's component id.
    pub const ID: u8 = 214;
    /// The Local Follower's row of the component table.
    pub const INFO: ComponentInfo = ComponentInfo {
        name: "LocalFollower",
        module: "local_follower",
        id: ID,
        function: "The function of the Local Follower is to follow local waypoints.",
        stock: None,
    };
    /// Local Follower (component id 214).
    ///
    /// The function of the Local Follower is to follow local waypoints.
    ///
    /// # Messages
    ///
    /// * Commands (from the component in control only): [`SetLocalWaypoint`], [`SetTravelSpeed`]
    /// * Accepted from anyone: [`QueryTravelSpeed`]
    /// * Sent on its own: [`SetWrenchEffort`]
    /// * Shares the [`Follower`](super::parts::Follower) part with other components: its messages go to [`follower`](Self::follower)
    ///
    /// Defined in `component_parts.yaml:35`.
    ///
    /// Implement the methods of the messages your component supports; the runtime
    /// ([`Component`]) does everything common to all JAUS components. Run it with
    /// [`component`].
    pub trait LocalFollower: Send + 'static {
        /// Stops all motion now (required: this component commands motion). The runtime
        /// calls it on entering Emergency (from any state), on leaving Ready for Standby,
        /// Shutdown or Failure, and when the component in control releases it, is
        /// preempted or disappears; `reason` says which. Commands are refused until the
        /// component is Ready again and controlled.
        fn stop(&mut self, ctx: &mut Ctx<'_>, reason: StopReason);
        /// The [`Follower`](super::parts::Follower) part of this component: return it
        /// (`Some(self)` when `Self` implements it, or a field that does) and the default
        /// methods of the part's messages, `initialize`, `state_changed` and `tick` pass
        /// to it. `None` (the default): those messages are unsupported.
        fn follower(&mut self) -> Option<&mut dyn super::parts::Follower<Interface>> {
            None
        }
        /// Handles [`SetLocalWaypoint`] (0x040D): Set Local Waypoint.
        ///
        /// A command: the runtime calls this only when the sender is the component in control and
        /// the component is in Ready or Standby. Return `Err(Refused::Invalid(..))` for values that
        /// cannot be executed (the sender gets a NAK if it asked for an acknowledgement).
        ///
        /// Not implemented: the message is ignored and counted as unsupported.
        fn on_set_local_waypoint(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &SetLocalWaypoint,
        ) -> Result<(), Refused> {
            let _ = (ctx, msg);
            Err(Refused::Unsupported)
        }
        /// Handles [`SetTravelSpeed`] (0x040A): Set Travel Speed.
        ///
        /// A command: the runtime calls this only when the sender is the component in control and
        /// the component is in Ready or Standby. Return `Err(Refused::Invalid(..))` for values that
        /// cannot be executed (the sender gets a NAK if it asked for an acknowledgement).
        ///
        /// Not implemented here: passed to the `Follower` part that [`follower`](Self::follower)
        /// returns, if any; otherwise the message is ignored and counted as unsupported.
        fn on_set_travel_speed(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &SetTravelSpeed,
        ) -> Result<(), Refused> {
            match self.follower() {
                Some(part) => part.on_set_travel_speed(ctx, msg),
                None => Err(Refused::Unsupported),
            }
        }
        /// Handles [`QueryTravelSpeed`] (0x240A): Query Travel Speed.
        ///
        /// A query from any component: return the [`ReportTravelSpeed`] to send back. The same
        /// method answers service connections and events on that report.
        ///
        /// Not implemented here: passed to the `Follower` part that [`follower`](Self::follower)
        /// returns, if any; otherwise the message is ignored and counted as unsupported.
        fn on_query_travel_speed(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &QueryTravelSpeed,
        ) -> Result<ReportTravelSpeed, Refused> {
            match self.follower() {
                Some(part) => part.on_query_travel_speed(ctx, msg),
                None => Err(Refused::Unsupported),
            }
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
        /// to check). The default calls `initialize` of each part; an override
        /// calls them itself.
        fn initialize(&mut self, ctx: &mut Ctx<'_>) -> Result<(), InitError> {
            if let Some(part) = self.follower() {
                part.initialize(ctx)?;
            }
            Ok(())
        }
        /// Called after every core state change (into Emergency: stop all motion). The
        /// default calls `state_changed` of each part.
        fn state_changed(&mut self, ctx: &mut Ctx<'_>, from: CoreState, to: CoreState) {
            if let Some(part) = self.follower() {
                part.state_changed(ctx, from, to);
            }
        }
        /// Called every `Config::tick`, in every state but Shutdown. The
        /// default calls `tick` of each part.
        fn tick(&mut self, ctx: &mut Ctx<'_>) {
            if let Some(part) = self.follower() {
                part.tick(ctx);
            }
        }
    }
    /// The interface of the Local Follower: its id, messages and modes.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub struct Interface;
    impl ::jaus::component::Interface for Interface {
        const NAME: &'static str = INFO.name;
        const ID: u8 = ID;
        const FUNCTION: &'static str = INFO.function;
        const COMMANDS: &'static [CommandCode] = &[
            CommandCode(0x040D),
            CommandCode(0x040A),
        ];
        const ACCEPTS: &'static [CommandCode] = &[CommandCode(0x240A)];
        const EMITS: &'static [CommandCode] = &[CommandCode(0x0405)];
        const ANY_MESSAGE: bool = false;
        type Modes = NoModes;
        type Messages = Message;
    }
    impl Emits<SetWrenchEffort> for Interface {
        fn wrap(msg: SetWrenchEffort) -> Message {
            msg.into()
        }
    }
    /// The context handed to the methods of [`LocalFollower`].
    pub type Ctx<'a> = Context<'a, Interface>;
    /// Runs a [`LocalFollower`] implementation under the component runtime.
    #[derive(Debug, Clone, Default)]
    pub struct Dispatch<T>(pub T);
    impl<T: LocalFollower> Behaviour for Dispatch<T> {
        type Interface = Interface;
        #[allow(clippy::match_single_binding)]
        fn handle(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &Message,
        ) -> Result<Option<Message>, Refused> {
            match msg {
                Message::SetLocalWaypoint(m) => {
                    self.0.on_set_local_waypoint(ctx, m).map(|()| None)
                }
                Message::SetTravelSpeed(m) => {
                    self.0.on_set_travel_speed(ctx, m).map(|()| None)
                }
                Message::QueryTravelSpeed(m) => {
                    self.0.on_query_travel_speed(ctx, m).map(|r| Some(r.into()))
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
        fn stop(&mut self, ctx: &mut Ctx<'_>, reason: StopReason) {
            self.0.stop(ctx, reason)
        }
    }
    /// A Local Follower component at `address` running `imp`, starting at `now`.
    pub fn component<T: LocalFollower>(
        address: Address,
        imp: T,
        config: Config,
        now: std::time::Instant,
    ) -> Component<Dispatch<T>> {
        Component::new(address, Dispatch(imp), config, now)
    }
}
#[allow(unused_imports)]
pub use local_follower::LocalFollower;
/// Every component interface: its name, module, id, function and stock implementation
/// (the `INFO` of each module), in definition order.
pub static COMPONENTS: &[ComponentInfo] = &[global_follower::INFO, local_follower::INFO];
