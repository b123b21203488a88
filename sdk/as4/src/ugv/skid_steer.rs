//! The Skid Steer Driver over an RA 3.3 Primitive Driver: the effort of each side
//! becomes RA 3.3 Set Wrench Effort.
//!
//! RA 3.3's vehicle frame is x forward, y right, z down, so a positive rotation about z
//! turns the vehicle clockwise seen from above (to the right, its heading increasing).
//! A faster left side turns a skid-steered vehicle right, hence, with `l` and `r` the
//! left and right efforts (percent, −100..=100):
//!
//! | RA 3.3 Set Wrench Effort | from Set Skid Steer Effort |
//! |---|---|
//! | propulsive linear effort x | `(l + r) / 2` (equal efforts: straight ahead, or back) |
//! | propulsive rotational effort z | `(l − r) / 2` (left faster: positive, turning right) |
//! | resistive linear effort x (brake) | 0: a skid-steer command is the whole drive command, and an RA 3.3 driver keeps what a Set Wrench Effort leaves out (a brake set before would hold the vehicle) |
//!
//! Both stay within −100..=100 for any two efforts in range, and the two sides come
//! back as `x + z` and `x − z`. The machines (`defs/ugv_services.yaml`) take Set Skid
//! Steer Effort from the controlling client while the component is Ready; leaving
//! Ready stops the vehicle (`stopMotion`: linear and rotational effort 0 when the
//! gateway holds RA 3.3 control of the driver). Query Skid Steer Effort answers any
//! client with the efforts this service last commanded (0 and 0 before any, and after
//! leaving Ready).
//!
//! **Beside the Mobility Primitive Driver.** Both services command the same RA 3.3
//! Primitive Driver through the same path ([`crate::mobility::primitive`]: RA 3.3
//! control asked for, the driver resumed while Ready, the efforts streamed): the latest
//! command of either wins, nothing merges them. Each one's query reports what it
//! commanded itself: after a Set Wrench Effort the RA 3.3 driver applies that one, and
//! the Primitive Driver's Query Wrench Effort (the RA 3.3 driver's report) says so,
//! while Query Skid Steer Effort still reads the last skid-steer command. As with Set
//! Wrench Effort, the RA 3.3 driver's command watchdog (the stock one's 300 ms) brakes
//! when the client stops sending: a client streams its efforts.

use jaus::messages as ra;
use jaus::Address;

use super::ServiceIds;
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::skid_steer_driver as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::{QuerySkidSteerEffort, ReportSkidSteerEffort, SetSkidSteerEffort};
use crate::mobility::primitive::{command_efforts, stop_efforts};

/// RA 3.3 Set Wrench Effort of a skid-steer command: `left` and `right` efforts
/// (percent) as linear effort x (their mean), rotational effort z (half the left one's
/// excess: positive turns right) and the brake released. `None` when either is not
/// finite or outside −100..=100 %.
pub fn wrench_effort(left: f64, right: f64) -> Option<ra::SetWrenchEffort> {
    let side = |e: f64| e.is_finite() && (-100.0..=100.0).contains(&e);
    if !(side(left) && side(right)) {
        return None;
    }
    Some(ra::SetWrenchEffort {
        propulsive_linear_effort_x: Some((left + right) / 2.0),
        propulsive_rotational_effort_z: Some((left - right) / 2.0),
        resistive_linear_effort_x: Some(0.0),
        ..Default::default()
    })
}

/// The Skid Steer Driver over the RA 3.3 Primitive Driver at an address, on its
/// generated machines.
pub type SkidSteerDriver = OnMachines<SkidSteer>;

/// The Skid Steer Driver's data: the RA 3.3 Primitive Driver and the efforts last
/// commanded (left, right; percent).
#[derive(Debug)]
pub struct SkidSteer {
    driver: Address,
    commanded: (f64, f64),
}

impl SkidSteerDriver {
    /// The service over the RA 3.3 Primitive Driver at `driver`.
    pub fn new(driver: Address) -> Self {
        OnMachines::from_impl(SkidSteer {
            driver,
            commanded: (0.0, 0.0),
        })
    }
}

machined!(
    SkidSteer,
    skid_steer_driver,
    ServiceIds::SKID_STEER_DRIVER,
    management
);

impl generated::SkidSteerDriver for On<'_, SkidSteer> {
    fn send_report_skid_steer_effort(&mut self, _msg: &QuerySkidSteerEffort, transport: &Receive) {
        let (left, right) = self.svc.commanded;
        let report = ReportSkidSteerEffort {
            left_side_propulsive_effort: left,
            right_side_propulsive_effort: right,
        };
        self.reply(transport, report);
    }

    fn set_skid_steer_effort(&mut self, msg: &SetSkidSteerEffort) {
        let (left, right) = (
            msg.left_side_propulsive_effort,
            msg.right_side_propulsive_effort,
        );
        let Some(efforts) = wrench_effort(left, right) else {
            return self.refuse(format!(
                "Set Skid Steer Effort: efforts {left}, {right} not finite or outside -100..100 %"
            ));
        };
        self.svc.commanded = (left, right);
        command_efforts(self.env, self.svc.driver, efforts);
    }

    fn stop_motion(&mut self) {
        self.svc.commanded = (0.0, 0.0);
        stop_efforts(self.env, self.svc.driver);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn xz(left: f64, right: f64) -> (f64, f64) {
        let w = wrench_effort(left, right).expect("in range");
        assert_eq!(w.resistive_linear_effort_x, Some(0.0));
        (
            w.propulsive_linear_effort_x.expect("x"),
            w.propulsive_rotational_effort_z.expect("z"),
        )
    }

    #[test]
    fn a_faster_left_side_turns_right_and_equal_sides_go_straight() {
        assert_eq!(xz(60.0, 60.0), (60.0, 0.0));
        assert_eq!(xz(-40.0, -40.0), (-40.0, 0.0));
        // Left faster: positive rotation about z (down), clockwise seen from above.
        assert_eq!(xz(80.0, 20.0), (50.0, 30.0));
        assert_eq!(xz(20.0, 80.0), (50.0, -30.0));
        // Turning in place, at the extremes: still in range.
        assert_eq!(xz(100.0, -100.0), (0.0, 100.0));
        assert_eq!(xz(-100.0, 100.0), (0.0, -100.0));
        // The sides come back as x + z and x - z.
        let (x, z) = xz(37.5, -12.25);
        assert_eq!((x + z, x - z), (37.5, -12.25));
    }

    #[test]
    fn efforts_out_of_range_or_not_finite_are_refused() {
        for (l, r) in [
            (100.5, 0.0),
            (0.0, -101.0),
            (f64::NAN, 0.0),
            (0.0, f64::INFINITY),
        ] {
            assert!(wrench_effort(l, r).is_none(), "{l}, {r}");
        }
    }
}
