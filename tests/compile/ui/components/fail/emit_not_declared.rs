use jaus::component::Refused;
use jaus::components::global_pose_sensor::{Ctx, GlobalPoseSensor};
use jaus::messages::{QueryGlobalPose, ReportGlobalPose, SetWrenchEffort};
use jaus::Address;

struct Gps;

impl GlobalPoseSensor for Gps {
    fn on_query_global_pose(
        &mut self,
        ctx: &mut Ctx<'_>,
        _q: &QueryGlobalPose,
    ) -> Result<ReportGlobalPose, Refused> {
        // A pose sensor has no business driving the vehicle.
        ctx.send(Address::new(1, 1, 33, 1), SetWrenchEffort::default());
        Ok(ReportGlobalPose::default())
    }
}

fn main() {}
