//! The Environment Sensing services (AS6060, `urn:jaus:jss:environmentSensing`): the
//! Still Image and Digital Video over RA 3.3 components, as the [`crate::mobility`] and
//! [`crate::manipulator`] services are (their machines `defs/environment_services.yaml`,
//! run by [`crate::machined`]), and the Range Sensor hosted natively over a scanning
//! range finder (a [`GeneratedService`](crate::service::GeneratedService) over
//! `jaus::stock::environment::range::RangeScanner`, the trait the RA 3.3 stock Range
//! Sensor reads too).
//!
//! | AS-4 service | over | messages |
//! |---|---|---|
//! | Still Image (with the Visual Sensor it extends) | RA 3.3 Visual Sensor (37) | Query Still Image Data → an RA 3.3 Query Image, its Report Image (PNG) the answer, as sensor 1, in its native coordinate system; the still image and visual sensor capabilities and configuration (PNG, the sensor's name and state); Set ... Configuration answered with Confirm Sensor Configuration, accepting what the RA 3.3 sensor does (PNG, no frame size, Active) and refusing the rest, sensor by sensor |
//! | Digital Video ([`video`], with the Visual Sensor it extends) | RA 3.3 Visual Sensor (37), on a node with a [`VideoHub`] (`as4: { video: … }` of a node file) | while the controlling client has the stream playing (Control Digital Video Sensor Stream), an RA 3.3 Query Image at the configured frame rate, each Report Image made a JPEG frame and published to the hub, from which the node serves MJPEG over HTTP; capabilities (MJPEG, 1 to the highest rate) and configuration; Set Digital Video Sensor Configuration from the controlling client: the frame rate, the rest refused sensor by sensor |
//! | Range Sensor ([`range`]) | a `RangeScanner` (the simulated vehicle's: the one its RA 3.3 Range Sensor reads) | Query Range Sensor Data → a fresh sweep as sensor 1's points (range, bearing, inclination 0; native, or the vehicle's coordinate system when the mount is known), a beam without a return at the farthest range, invalid; capabilities, configuration and placement from the scanner's spec; compressed data with no compression only; Set Range Sensor Configuration from the controlling client, accepting what the scanner does and refusing the rest |
//!
//! The RA 3.3 Visual Sensor has cameras but one image at a time, and a scanner is one
//! sensor: each is AS-4 sensor [`SENSOR_ID`] of its service. Not served: Analog Video (its
//! messages and machines are defined and generated; no simulated analog output); the RA 3.3
//! Range Sensor itself (it reports one object per query, not a scan) is not gatewayed:
//! the AS-4 Range Sensor reads its scanner.

use crate::core::generated_id;
use crate::service::ServiceId;

pub mod range;
pub mod still_image;
pub mod video;
mod visual;

pub use range::RangeSensorService;
pub use still_image::StillImage;
pub use video::{DigitalVideo, VideoHub, VideoLimits};

/// The AS-4 sensor id of the one sensor a service presents.
pub const SENSOR_ID: u16 = 1;

/// The URIs and versions of the Environment Sensing services served, as
/// `defs/environment_services.yaml` gives them.
#[derive(Debug)]
pub struct ServiceIds;

impl ServiceIds {
    /// `urn:jaus:jss:environmentSensing:StillImage`.
    pub const STILL_IMAGE: ServiceId = generated_id!(still_image);
    /// `urn:jaus:jss:environmentSensing:DigitalVideo`.
    pub const DIGITAL_VIDEO: ServiceId = generated_id!(digital_video);
    /// `urn:jaus:jss:environmentSensing:RangeSensor`.
    pub const RANGE_SENSOR: ServiceId = generated_id!(range_sensor);
}
