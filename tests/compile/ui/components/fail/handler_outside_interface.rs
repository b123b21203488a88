use jaus::component::Refused;
use jaus::components::global_pose_sensor::{Ctx, GlobalPoseSensor};
use jaus::messages::SetWrenchEffort;

struct Gps;

impl GlobalPoseSensor for Gps {
    fn on_set_wrench_effort(&mut self, _ctx: &mut Ctx<'_>, _m: &SetWrenchEffort) -> Result<(), Refused> {
        Ok(())
    }
}

fn main() {}
