//! A driver sends what its interface emits and moves through its modes.
use jaus::component::Refused;
use jaus::components::global_waypoint_driver::{Ctx, GlobalWaypointDriver, Transition};
use jaus::messages::{SetTravelSpeed, SetWrenchEffort};
use jaus::Address;

struct Driver {
    primitive_driver: Address,
}

impl GlobalWaypointDriver for Driver {
    fn on_set_travel_speed(&mut self, ctx: &mut Ctx<'_>, msg: &SetTravelSpeed) -> Result<(), Refused> {
        if !msg.speed.is_finite() {
            return Err(Refused::Invalid("speed is not finite".into()));
        }
        ctx.transition(Transition::Start).map_err(|e| Refused::Invalid(e.to_string()))?;
        ctx.send(self.primitive_driver, SetWrenchEffort::default());
        Ok(())
    }

    fn stop(&mut self, ctx: &mut Ctx<'_>, _reason: jaus::component::StopReason) {
        // Zero effort: the platform stops.
        ctx.send(self.primitive_driver, SetWrenchEffort::default());
    }
}

fn main() {
    let _ = Driver { primitive_driver: Address::new(1, 1, 33, 1) };
}
