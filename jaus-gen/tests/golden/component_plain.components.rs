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
/// The Beacon (component id 200): trait [`Beacon`], interface, dispatch.
///
/// The function of the Beacon is to be seen on the network: it answers what every JAUS
/// component answers and nothing else.
pub mod beacon {
    use super::*;
    /// The Beacon's component id.
    pub const ID: u8 = 200;
    /// The Beacon's row of the component table.
    pub const INFO: ComponentInfo = ComponentInfo {
        name: "Beacon",
        module: "beacon",
        id: ID,
        function: "The function of the Beacon is to be seen on the network: it answers what every JAUS component answers and nothing else.",
        stock: None,
    };
    /// Beacon (component id 200).
    ///
    /// The function of the Beacon is to be seen on the network: it answers what every JAUS
    /// component answers and nothing else.
    ///
    /// # Messages
    ///
    /// * Commands (from the component in control only): none
    /// * Accepted from anyone: none
    /// * Sent on its own: none
    ///
    /// Defined in `component_plain.yaml:6`.
    ///
    /// Implement the methods of the messages your component supports; the runtime
    /// ([`Component`]) does everything common to all JAUS components. Run it with
    /// [`component`].
    pub trait Beacon: Send + 'static {
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
    /// The interface of the Beacon: its id, messages and modes.
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
    /// The context handed to the methods of [`Beacon`].
    pub type Ctx<'a> = Context<'a, Interface>;
    /// Runs a [`Beacon`] implementation under the component runtime.
    #[derive(Debug, Clone, Default)]
    pub struct Dispatch<T>(pub T);
    impl<T: Beacon> Behaviour for Dispatch<T> {
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
    /// A Beacon component at `address` running `imp`, starting at `now`.
    pub fn component<T: Beacon>(
        address: Address,
        imp: T,
        config: Config,
        now: std::time::Instant,
    ) -> Component<Dispatch<T>> {
        Component::new(address, Dispatch(imp), config, now)
    }
}
#[allow(unused_imports)]
pub use beacon::Beacon;
/// Every component interface: its name, module, id, function and stock implementation
/// (the `INFO` of each module), in definition order.
pub static COMPONENTS: &[ComponentInfo] = &[beacon::INFO];
