use jaus::component::Refused;
use jaus::components::global_pose_sensor::{Ctx, GlobalPoseSensor};
use jaus::messages::{QueryLocalPose, ReportGlobalPose};

struct Gps;

impl GlobalPoseSensor for Gps {
    fn on_query_global_pose(
        &mut self,
        _ctx: &mut Ctx<'_>,
        _q: &QueryLocalPose,
    ) -> Result<ReportGlobalPose, Refused> {
        Ok(ReportGlobalPose::default())
    }
}

fn main() {}
