//! The simulated world the hardware simulators share: where the vehicle starts (the
//! origin of the local frame), what the range scanner and camera see, and the arm's
//! control period. A node hosting stock components over the simulators builds them
//! over one `World` (`jaus_node::host::Host::with_world`); the demo has its own
//! ([`crate::demo::world`]).

use std::time::Duration;

use jaus::stock::geo::LocalFrame;

use crate::scanner::Scene;
use crate::vehicle::VehicleParams;

/// The simulated world the components are built over.
#[derive(Debug, Clone, PartialEq)]
pub struct World {
    /// The WGS 84 origin of the local frame: where the simulated vehicle starts, and
    /// the frame of the drivers' local coordinates. Default: the origin of
    /// [`VehicleParams::default`].
    pub origin: LocalFrame,
    /// What the range sensor, the reflexive driver and the camera see (local metres).
    /// Default: nothing.
    pub scene: Scene,
    /// Tick of the manipulator components: the control period of the simulated arm.
    /// Default 10 ms (the period the stock manipulator drivers' servo is tuned for).
    pub arm_control_period: Duration,
}

impl Default for World {
    fn default() -> Self {
        Self {
            origin: VehicleParams::default().origin,
            scene: Scene::default(),
            arm_control_period: Duration::from_millis(10),
        }
    }
}
