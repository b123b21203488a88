use jaus::component::Refused;
use jaus::components::global_pose_sensor::{Ctx, GlobalPoseSensor};
use jaus::messages::{QueryGlobalPose, ReportLocalPose};

struct Gps;

impl GlobalPoseSensor for Gps {
    fn on_query_global_pose(
        &mut self,
        _ctx: &mut Ctx<'_>,
        _q: &QueryGlobalPose,
    ) -> Result<ReportLocalPose, Refused> {
        Ok(ReportLocalPose::default())
    }
}

fn main() {}
