//! The Environment Sensing services (AS6060, `urn:jaus:jss:environmentSensing`) over RA
//! 3.3 components, as the [`crate::mobility`] and [`crate::manipulator`] services are:
//! their machines are `defs/environment_services.yaml`, run by [`crate::machined`].
//!
//! | AS-4 service | RA 3.3 component | messages |
//! |---|---|---|
//! | Still Image (with the Visual Sensor it extends) | Visual Sensor (37) | Query Still Image Data → an RA 3.3 Query Image, its Report Image (PNG) the answer, as sensor 1, in its native coordinate system; the still image and visual sensor capabilities and configuration (PNG, the sensor's name and state); Set ... Configuration answered with Confirm Sensor Configuration, accepting what the RA 3.3 sensor does (PNG, no frame size, Active) and refusing the rest, sensor by sensor |
//!
//! The RA 3.3 Visual Sensor has cameras but one image at a time; it is AS-4 sensor
//! [`SENSOR_ID`]. Not served yet: the Range Sensor (an RA 3.3 range sensor reports one
//! object per query, not a scan), Digital and Analog Video (their messages and machines
//! are defined and generated).

use crate::core::generated_id;
use crate::service::ServiceId;

pub mod still_image;

pub use still_image::StillImage;

/// The AS-4 sensor id of the one sensor a service presents.
pub const SENSOR_ID: u16 = 1;

/// The URIs and versions of the Environment Sensing services served, as
/// `defs/environment_services.yaml` gives them.
#[derive(Debug)]
pub struct ServiceIds;

impl ServiceIds {
    /// `urn:jaus:jss:environmentSensing:StillImage`.
    pub const STILL_IMAGE: ServiceId = generated_id!(still_image);
}
