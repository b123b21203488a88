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
/// The Navigator (component id 220): trait [`Navigator`], interface, dispatch.
///
/// The function of the Navigator is to drive through waypoints.
#[cfg(all(feature = "planning", feature = "sensors"))]
pub mod navigator {
    use super::*;
    /// The Navigator's component id.
    pub const ID: u8 = 220;
    /// The Navigator's row of the component table.
    pub const INFO: ComponentInfo = ComponentInfo {
        name: "Navigator",
        module: "navigator",
        id: ID,
        function: "The function of the Navigator is to drive through waypoints.",
        stock: None,
    };
    /// Navigator (component id 220).
    ///
    /// The function of the Navigator is to drive through waypoints.
    ///
    /// # Messages
    ///
    /// * Commands (from the component in control only): [`SetGlobalWaypoint`]
    /// * Accepted from anyone: [`QueryGlobalWaypoint`], [`ReportGlobalPose`]
    /// * Sent on its own: [`QueryGlobalPose`]
    ///
    /// Defined in `feature_gates.yaml:11`.
    ///
    /// Implement the methods of the messages your component supports; the runtime
    /// ([`Component`]) does everything common to all JAUS components. Run it with
    /// [`component`].
    pub trait Navigator: Send + 'static {
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
        /// Handles [`QueryGlobalWaypoint`] (0x240C): Query Global Waypoint.
        ///
        /// A query from any component: return the [`ReportGlobalWaypoint`] to send back. The same
        /// method answers service connections and events on that report.
        ///
        /// Not implemented: the message is ignored and counted as unsupported.
        fn on_query_global_waypoint(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &QueryGlobalWaypoint,
        ) -> Result<ReportGlobalWaypoint, Refused> {
            let _ = (ctx, msg);
            Err(Refused::Unsupported)
        }
        /// Handles [`ReportGlobalPose`] (0x4402): Report Global Pose.
        ///
        /// Accepted from any component.
        ///
        /// Not implemented: the message is ignored and counted as unsupported.
        fn on_report_global_pose(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &ReportGlobalPose,
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
    /// The interface of the Navigator: its id, messages and modes.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub struct Interface;
    impl ::jaus::component::Interface for Interface {
        const NAME: &'static str = INFO.name;
        const ID: u8 = ID;
        const FUNCTION: &'static str = INFO.function;
        const COMMANDS: &'static [CommandCode] = &[CommandCode(0x040C)];
        const ACCEPTS: &'static [CommandCode] = &[
            CommandCode(0x240C),
            CommandCode(0x4402),
        ];
        const EMITS: &'static [CommandCode] = &[CommandCode(0x2402)];
        const ANY_MESSAGE: bool = false;
        type Modes = NoModes;
        type Messages = Message;
    }
    impl Emits<QueryGlobalPose> for Interface {
        fn wrap(msg: QueryGlobalPose) -> Message {
            msg.into()
        }
    }
    /// The context handed to the methods of [`Navigator`].
    pub type Ctx<'a> = Context<'a, Interface>;
    /// Runs a [`Navigator`] implementation under the component runtime.
    #[derive(Debug, Clone, Default)]
    pub struct Dispatch<T>(pub T);
    impl<T: Navigator> Behaviour for Dispatch<T> {
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
                Message::QueryGlobalWaypoint(m) => {
                    self.0.on_query_global_waypoint(ctx, m).map(|r| Some(r.into()))
                }
                Message::ReportGlobalPose(m) => {
                    self.0.on_report_global_pose(ctx, m).map(|()| None)
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
    /// A Navigator component at `address` running `imp`, starting at `now`.
    pub fn component<T: Navigator>(
        address: Address,
        imp: T,
        config: Config,
        now: std::time::Instant,
    ) -> Component<Dispatch<T>> {
        Component::new(address, Dispatch(imp), config, now)
    }
}
#[cfg(all(feature = "planning", feature = "sensors"))]
#[allow(unused_imports)]
pub use navigator::Navigator;
/// Every component interface: its name, module, id, function and stock implementation
/// (the `INFO` of each module), in definition order.
pub static COMPONENTS: &[ComponentInfo] = &[
    #[cfg(all(feature = "planning", feature = "sensors"))]
    navigator::INFO,
];
