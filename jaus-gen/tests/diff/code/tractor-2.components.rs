#[allow(unused_imports)]
use ::jaus::component::{
    Behaviour, Component, Config, Context, CoreState, CoreTransition, Emits, InitError,
    Modes, NoModes, Refused, StopReason,
};
#[allow(unused_imports)]
use ::jaus::component::{ComponentInfo, Hardware, StockInfo};
#[allow(unused_imports)]
use ::jaus::messages::*;
#[allow(unused_imports)]
use ::jaus::{Address, CommandCode, JausMessage};
#[allow(unused_imports)]
use super::*;
#[allow(unused_imports)]
use super::Message;
/// The Implement Controller (component id 220): trait [`ImplementController`], interface, dispatch.
///
/// Raises, lowers and reports the implement.
pub mod implement_controller {
    use super::*;
    /// The Implement Controller's component id.
    pub const ID: u8 = 220;
    /// The Implement Controller's row of the component table.
    pub const INFO: ComponentInfo = ComponentInfo {
        name: "ImplementController",
        module: "implement_controller",
        id: ID,
        function: "Raises, lowers and reports the implement.",
        stock: None,
    };
    /// Implement Controller (component id 220).
    ///
    /// Raises, lowers and reports the implement.
    ///
    /// # Messages
    ///
    /// * Commands (from the component in control only): [`SetImplementDepth`], [`ClearImplementFault`]
    /// * Accepted from anyone: [`SetImplementMode`], [`QueryImplementState`]
    /// * Sent on its own: [`ReportImplementState`], [`ReportImplementFault`]
    ///
    /// Defined in `my_tractor.yaml:76`.
    ///
    /// Implement the methods of the messages your component supports; the runtime
    /// ([`Component`]) does everything common to all JAUS components. Run it with
    /// [`component`].
    pub trait ImplementController: Send + 'static {
        /// Handles [`SetImplementDepth`] (0xD200): Set Implement Depth.
        ///
        /// A command: the runtime calls this only when the sender is the component in control and
        /// the component is in Ready or Standby. Return `Err(Refused::Invalid(..))` for values that
        /// cannot be executed (the sender gets a NAK if it asked for an acknowledgement).
        ///
        /// Not implemented: the message is ignored and counted as unsupported.
        fn on_set_implement_depth(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &SetImplementDepth,
        ) -> Result<(), Refused> {
            let _ = (ctx, msg);
            Err(Refused::Unsupported)
        }
        /// Handles [`ClearImplementFault`] (0xD205): Clear Implement Fault.
        ///
        /// A command: the runtime calls this only when the sender is the component in control and
        /// the component is in Ready or Standby. Return `Err(Refused::Invalid(..))` for values that
        /// cannot be executed (the sender gets a NAK if it asked for an acknowledgement).
        ///
        /// Not implemented: the message is ignored and counted as unsupported.
        fn on_clear_implement_fault(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &ClearImplementFault,
        ) -> Result<(), Refused> {
            let _ = (ctx, msg);
            Err(Refused::Unsupported)
        }
        /// Handles [`SetImplementMode`] (0xD202): Set Implement Mode.
        ///
        /// Accepted from any component.
        ///
        /// Not implemented: the message is ignored and counted as unsupported.
        fn on_set_implement_mode(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &SetImplementMode,
        ) -> Result<(), Refused> {
            let _ = (ctx, msg);
            Err(Refused::Unsupported)
        }
        /// Handles [`QueryImplementState`] (0xD203): Query Implement State.
        ///
        /// A query from any component: return the [`ReportImplementState`] to send back. The same
        /// method answers service connections and events on that report.
        ///
        /// Not implemented: the message is ignored and counted as unsupported.
        fn on_query_implement_state(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &QueryImplementState,
        ) -> Result<ReportImplementState, Refused> {
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
    /// The interface of the Implement Controller: its id, messages and modes.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub struct Interface;
    impl ::jaus::component::Interface for Interface {
        const NAME: &'static str = INFO.name;
        const ID: u8 = ID;
        const FUNCTION: &'static str = INFO.function;
        const COMMANDS: &'static [CommandCode] = &[
            CommandCode(0xD200),
            CommandCode(0xD205),
        ];
        const ACCEPTS: &'static [CommandCode] = &[
            CommandCode(0xD202),
            CommandCode(0xD203),
        ];
        const EMITS: &'static [CommandCode] = &[
            CommandCode(0xD201),
            CommandCode(0xD204),
        ];
        const ANY_MESSAGE: bool = false;
        type Modes = NoModes;
        type Messages = Message;
    }
    impl Emits<ReportImplementState> for Interface {
        fn wrap(msg: ReportImplementState) -> Message {
            msg.into()
        }
    }
    impl Emits<ReportImplementFault> for Interface {
        fn wrap(msg: ReportImplementFault) -> Message {
            msg.into()
        }
    }
    /// The context handed to the methods of [`ImplementController`].
    pub type Ctx<'a> = Context<'a, Interface>;
    /// Runs a [`ImplementController`] implementation under the component runtime.
    #[derive(Debug, Clone, Default)]
    pub struct Dispatch<T>(pub T);
    impl<T: ImplementController> Behaviour for Dispatch<T> {
        type Interface = Interface;
        #[allow(clippy::match_single_binding)]
        fn handle(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &Message,
        ) -> Result<Option<Message>, Refused> {
            match msg {
                Message::SetImplementDepth(m) => {
                    self.0.on_set_implement_depth(ctx, m).map(|()| None)
                }
                Message::ClearImplementFault(m) => {
                    self.0.on_clear_implement_fault(ctx, m).map(|()| None)
                }
                Message::SetImplementMode(m) => {
                    self.0.on_set_implement_mode(ctx, m).map(|()| None)
                }
                Message::QueryImplementState(m) => {
                    self.0.on_query_implement_state(ctx, m).map(|r| Some(r.into()))
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
    /// A Implement Controller component at `address` running `imp`, starting at `now`.
    pub fn component<T: ImplementController>(
        address: Address,
        imp: T,
        config: Config,
        now: std::time::Instant,
    ) -> Component<Dispatch<T>> {
        Component::new(address, Dispatch(imp), config, now)
    }
}
#[allow(unused_imports)]
pub use implement_controller::ImplementController;
/// The Implement Logger (component id 221): trait [`ImplementLogger`], interface, dispatch.
///
/// Logs what it is sent.
pub mod implement_logger {
    use super::*;
    /// The Implement Logger's component id.
    pub const ID: u8 = 221;
    /// The Implement Logger's row of the component table.
    pub const INFO: ComponentInfo = ComponentInfo {
        name: "ImplementLogger",
        module: "implement_logger",
        id: ID,
        function: "Logs what it is sent.",
        stock: None,
    };
    /// Implement Logger (component id 221).
    ///
    /// Logs what it is sent.
    ///
    /// # Messages
    ///
    /// A command and control component: it may send any message to any component and receive any message (all arrive in `on_other_message`).
    ///
    /// Defined in `my_tractor.yaml:83`.
    ///
    /// Implement the methods of the messages your component supports; the runtime
    /// ([`Component`]) does everything common to all JAUS components. Run it with
    /// [`component`].
    pub trait ImplementLogger: Send + 'static {
        /// Any other message. Return a reply to send it back to the sender.
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
    /// The interface of the Implement Logger: its id, messages and modes.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub struct Interface;
    impl ::jaus::component::Interface for Interface {
        const NAME: &'static str = INFO.name;
        const ID: u8 = ID;
        const FUNCTION: &'static str = INFO.function;
        const COMMANDS: &'static [CommandCode] = &[];
        const ACCEPTS: &'static [CommandCode] = &[];
        const EMITS: &'static [CommandCode] = &[];
        const ANY_MESSAGE: bool = true;
        type Modes = NoModes;
        type Messages = Message;
    }
    impl<M: ::jaus::StandardMessage> Emits<M> for Interface {
        fn wrap(msg: M) -> Message {
            Message::Jaus(msg.into())
        }
    }
    impl Emits<SetImplementDepth> for Interface {
        fn wrap(msg: SetImplementDepth) -> Message {
            msg.into()
        }
    }
    impl Emits<ReportImplementState> for Interface {
        fn wrap(msg: ReportImplementState) -> Message {
            msg.into()
        }
    }
    impl Emits<SetImplementMode> for Interface {
        fn wrap(msg: SetImplementMode) -> Message {
            msg.into()
        }
    }
    impl Emits<QueryImplementState> for Interface {
        fn wrap(msg: QueryImplementState) -> Message {
            msg.into()
        }
    }
    impl Emits<ReportImplementFault> for Interface {
        fn wrap(msg: ReportImplementFault) -> Message {
            msg.into()
        }
    }
    impl Emits<ClearImplementFault> for Interface {
        fn wrap(msg: ClearImplementFault) -> Message {
            msg.into()
        }
    }
    /// The context handed to the methods of [`ImplementLogger`].
    pub type Ctx<'a> = Context<'a, Interface>;
    /// Runs a [`ImplementLogger`] implementation under the component runtime.
    #[derive(Debug, Clone, Default)]
    pub struct Dispatch<T>(pub T);
    impl<T: ImplementLogger> Behaviour for Dispatch<T> {
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
    /// A Implement Logger component at `address` running `imp`, starting at `now`.
    pub fn component<T: ImplementLogger>(
        address: Address,
        imp: T,
        config: Config,
        now: std::time::Instant,
    ) -> Component<Dispatch<T>> {
        Component::new(address, Dispatch(imp), config, now)
    }
}
#[allow(unused_imports)]
pub use implement_logger::ImplementLogger;
/// The Hitch Camera (component id 222): trait [`HitchCamera`], interface, dispatch.
///
/// Watches the hitch.
pub mod hitch_camera {
    use super::*;
    /// The Hitch Camera's component id.
    pub const ID: u8 = 222;
    /// The Hitch Camera's row of the component table.
    pub const INFO: ComponentInfo = ComponentInfo {
        name: "HitchCamera",
        module: "hitch_camera",
        id: ID,
        function: "Watches the hitch.",
        stock: None,
    };
    /// Hitch Camera (component id 222).
    ///
    /// Watches the hitch.
    ///
    /// # Messages
    ///
    /// * Commands (from the component in control only): none
    /// * Accepted from anyone: none
    /// * Sent on its own: none
    ///
    /// Defined in `my_tractor.yaml:88`.
    ///
    /// Implement the methods of the messages your component supports; the runtime
    /// ([`Component`]) does everything common to all JAUS components. Run it with
    /// [`component`].
    pub trait HitchCamera: Send + 'static {
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
    /// The interface of the Hitch Camera: its id, messages and modes.
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
        type Modes = NoModes;
        type Messages = Message;
    }
    /// The context handed to the methods of [`HitchCamera`].
    pub type Ctx<'a> = Context<'a, Interface>;
    /// Runs a [`HitchCamera`] implementation under the component runtime.
    #[derive(Debug, Clone, Default)]
    pub struct Dispatch<T>(pub T);
    impl<T: HitchCamera> Behaviour for Dispatch<T> {
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
    /// A Hitch Camera component at `address` running `imp`, starting at `now`.
    pub fn component<T: HitchCamera>(
        address: Address,
        imp: T,
        config: Config,
        now: std::time::Instant,
    ) -> Component<Dispatch<T>> {
        Component::new(address, Dispatch(imp), config, now)
    }
}
#[allow(unused_imports)]
pub use hitch_camera::HitchCamera;
/// Every component interface: its name, module, id, function and stock implementation
/// (the `INFO` of each module), in definition order.
pub static COMPONENTS: &[ComponentInfo] = &[
    implement_controller::INFO,
    implement_logger::INFO,
    hitch_camera::INFO,
];
