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
/// The Operator Unit (component id 213): trait [`OperatorUnit`], interface, dispatch.
///
/// The function of the Operator Unit is to let an operator command any component.
pub mod operator_unit {
    use super::*;
    /// The Operator Unit's component id.
    pub const ID: u8 = 213;
    /// The Operator Unit's row of the component table.
    pub const INFO: ComponentInfo = ComponentInfo {
        name: "OperatorUnit",
        module: "operator_unit",
        id: ID,
        function: "The function of the Operator Unit is to let an operator command any component.",
        stock: None,
    };
    /// Operator Unit (component id 213).
    ///
    /// The function of the Operator Unit is to let an operator command any component.
    ///
    /// # Messages
    ///
    /// A command and control component: it may send any message to any component and receive any message (all arrive in `on_other_message`).
    ///
    /// Defined in `component_any_message.yaml:6`.
    ///
    /// Implement the methods of the messages your component supports; the runtime
    /// ([`Component`]) does everything common to all JAUS components. Run it with
    /// [`component`].
    pub trait OperatorUnit: Send + 'static {
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
    /// The interface of the Operator Unit: its id, messages and modes.
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
            msg.into()
        }
    }
    /// The context handed to the methods of [`OperatorUnit`].
    pub type Ctx<'a> = Context<'a, Interface>;
    /// Runs a [`OperatorUnit`] implementation under the component runtime.
    #[derive(Debug, Clone, Default)]
    pub struct Dispatch<T>(pub T);
    impl<T: OperatorUnit> Behaviour for Dispatch<T> {
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
    /// A Operator Unit component at `address` running `imp`, starting at `now`.
    pub fn component<T: OperatorUnit>(
        address: Address,
        imp: T,
        config: Config,
        now: std::time::Instant,
    ) -> Component<Dispatch<T>> {
        Component::new(address, Dispatch(imp), config, now)
    }
}
#[allow(unused_imports)]
pub use operator_unit::OperatorUnit;
/// Every component interface: its name, module, id, function and stock implementation
/// (the `INFO` of each module), in definition order.
pub static COMPONENTS: &[ComponentInfo] = &[operator_unit::INFO];
