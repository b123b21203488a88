use jaus::component::Refused;
use jaus::components::global_waypoint_driver::{Ctx, GlobalWaypointDriver};
use jaus::components::mission_spooler::Transition;
use jaus::messages::SetTravelSpeed;

struct Driver;

impl GlobalWaypointDriver for Driver {
    fn on_set_travel_speed(&mut self, ctx: &mut Ctx<'_>, _m: &SetTravelSpeed) -> Result<(), Refused> {
        // The spooler's transitions are not the waypoint driver's.
        let _ = ctx.transition(Transition::Run);
        Ok(())
    }
    fn stop(&mut self, _ctx: &mut Ctx<'_>, _reason: jaus::component::StopReason) {}
}

fn main() {}
