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
/// The Track Driver (component id 210): trait [`TrackDriver`], interface, dispatch.
///
/// The function of the Track Driver is to turn effort commands into track speeds.
pub mod track_driver {
    use super::*;
    /// The Track Driver's component id.
    pub const ID: u8 = 210;
    /// The Track Driver's row of the component table.
    pub const INFO: ComponentInfo = ComponentInfo {
        name: "TrackDriver",
        module: "track_driver",
        id: ID,
        function: "The function of the Track Driver is to turn effort commands into track speeds.",
        stock: Some(StockInfo {
            name: "track_driver",
            needs: Hardware::Vehicle,
        }),
    };
    /// Track Driver (component id 210).
    ///
    /// The function of the Track Driver is to turn effort commands into track speeds.
    ///
    /// It reads the platform's pose to limit its speed on slopes.
    ///
    /// # Rules (Part 1)
    ///
    /// * The effort is set to zero on every transition from Standby to Ready.
    /// * Efforts outside -100 % to 100 % are refused.
    ///
    /// # Messages
    ///
    /// * Commands (from the component in control only): [`SetWrenchEffort`], [`SetTravelSpeed`]
    /// * Accepted from anyone: [`QueryWrenchEffort`], [`ReportGlobalPose`]
    /// * Sent on its own: [`QueryGlobalPose`]
    ///
    /// Defined in `component_messages.yaml:16`.
    ///
    /// Implement the methods of the messages your component supports; the runtime
    /// ([`Component`]) does everything common to all JAUS components. Run it with
    /// [`component`].
    pub trait TrackDriver: Send + 'static {
        /// Stops all motion now (required: this component commands motion). The runtime
        /// calls it on entering Emergency (from any state), on leaving Ready for Standby,
        /// Shutdown or Failure, and when the component in control releases it, is
        /// preempted or disappears; `reason` says which. Commands are refused until the
        /// component is Ready again and controlled.
        fn stop(&mut self, ctx: &mut Ctx<'_>, reason: StopReason);
        /// Handles [`SetWrenchEffort`] (0x0405): Set Wrench Effort.
        ///
        /// A command: the runtime calls this only when the sender is the component in control and
        /// the component is in Ready or Standby. Return `Err(Refused::Invalid(..))` for values that
        /// cannot be executed (the sender gets a NAK if it asked for an acknowledgement).
        ///
        /// Not implemented: the message is ignored and counted as unsupported.
        fn on_set_wrench_effort(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &SetWrenchEffort,
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
        /// Not implemented: the message is ignored and counted as unsupported.
        fn on_set_travel_speed(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &SetTravelSpeed,
        ) -> Result<(), Refused> {
            let _ = (ctx, msg);
            Err(Refused::Unsupported)
        }
        /// Handles [`QueryWrenchEffort`] (0x2405): Query Wrench Effort.
        ///
        /// A query from any component: return the [`ReportWrenchEffort`] to send back. The same
        /// method answers service connections and events on that report.
        ///
        /// Not implemented: the message is ignored and counted as unsupported.
        fn on_query_wrench_effort(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &QueryWrenchEffort,
        ) -> Result<ReportWrenchEffort, Refused> {
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
    /// The interface of the Track Driver: its id, messages and modes.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub struct Interface;
    impl ::jaus::component::Interface for Interface {
        const NAME: &'static str = INFO.name;
        const ID: u8 = ID;
        const FUNCTION: &'static str = INFO.function;
        const COMMANDS: &'static [CommandCode] = &[
            CommandCode(0x0405),
            CommandCode(0x040A),
        ];
        const ACCEPTS: &'static [CommandCode] = &[
            CommandCode(0x2405),
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
    /// The context handed to the methods of [`TrackDriver`].
    pub type Ctx<'a> = Context<'a, Interface>;
    /// Runs a [`TrackDriver`] implementation under the component runtime.
    #[derive(Debug, Clone, Default)]
    pub struct Dispatch<T>(pub T);
    impl<T: TrackDriver> Behaviour for Dispatch<T> {
        type Interface = Interface;
        #[allow(clippy::match_single_binding)]
        fn handle(
            &mut self,
            ctx: &mut Ctx<'_>,
            msg: &Message,
        ) -> Result<Option<Message>, Refused> {
            match msg {
                Message::SetWrenchEffort(m) => {
                    self.0.on_set_wrench_effort(ctx, m).map(|()| None)
                }
                Message::SetTravelSpeed(m) => {
                    self.0.on_set_travel_speed(ctx, m).map(|()| None)
                }
                Message::QueryWrenchEffort(m) => {
                    self.0.on_query_wrench_effort(ctx, m).map(|r| Some(r.into()))
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
        fn stop(&mut self, ctx: &mut Ctx<'_>, reason: StopReason) {
            self.0.stop(ctx, reason)
        }
    }
    /// A Track Driver component at `address` running `imp`, starting at `now`.
    pub fn component<T: TrackDriver>(
        address: Address,
        imp: T,
        config: Config,
        now: std::time::Instant,
    ) -> Component<Dispatch<T>> {
        Component::new(address, Dispatch(imp), config, now)
    }
}
#[allow(unused_imports)]
pub use track_driver::TrackDriver;
/// Every component interface: its name, module, id, function and stock implementation
/// (the `INFO` of each module), in definition order.
pub static COMPONENTS: &[ComponentInfo] = &[track_driver::INFO];
