//! The ROS 2 messages the bridge speaks, as serde structs with the fields in the exact
//! order of their `.msg` definitions: serde serialises a struct's fields in declaration
//! order, and CDR (the DDS wire encoding ROS 2 uses) is that order with natural
//! alignment, no field names and no tags. A field out of order is a different type on
//! the wire, which is why the layouts are pinned by the byte-level tests below and by
//! the integration test against Cyclone DDS.
//!
//! Each type's DDS name follows ROS 2's convention `<package>::msg::dds_::<Type>_`
//! ([`RosMessage::DDS_TYPE`]); topics are prefixed `rt/` ([`crate::config::Topics`]).

use std::fmt;

use serde::de::{self, SeqAccess, Visitor};
use serde::ser::SerializeTuple;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A ROS 2 message: its package and type name (what `ros2 topic info` prints as
/// `package/msg/Type`).
pub trait RosMessage: Serialize + for<'de> Deserialize<'de> + Send + 'static {
    /// The ROS package, e.g. `nav_msgs`.
    const PACKAGE: &'static str;
    /// The type name in its package, e.g. `Odometry`.
    const NAME: &'static str;
    /// The DDS type name ROS 2 middlewares register, e.g.
    /// `nav_msgs::msg::dds_::Odometry_`.
    const DDS_TYPE: &'static str;
}

macro_rules! ros_message {
    ($t:ty, $pkg:literal, $name:literal) => {
        impl RosMessage for $t {
            const PACKAGE: &'static str = $pkg;
            const NAME: &'static str = $name;
            const DDS_TYPE: &'static str = concat!($pkg, "::msg::dds_::", $name, "_");
        }
    };
}

/// `builtin_interfaces/Time`: seconds and nanoseconds since the Unix epoch (or of the
/// simulated clock).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Time {
    /// Seconds (`int32 sec`).
    pub sec: i32,
    /// Nanoseconds, 0..1e9 (`uint32 nanosec`).
    pub nanosec: u32,
}

impl Time {
    /// The time as nanoseconds (negative before the epoch).
    pub fn as_nanos(&self) -> i64 {
        i64::from(self.sec) * 1_000_000_000 + i64::from(self.nanosec)
    }
}

/// `std_msgs/Header`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// Time of the data (`builtin_interfaces/Time stamp`).
    pub stamp: Time,
    /// Frame the data is in (`string frame_id`).
    pub frame_id: String,
}

/// `geometry_msgs/Vector3`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Vector3 {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// z.
    pub z: f64,
}

/// `geometry_msgs/Point`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Point {
    /// x, m.
    pub x: f64,
    /// y, m.
    pub y: f64,
    /// z, m.
    pub z: f64,
}

/// `geometry_msgs/Quaternion` (x, y, z, w: w last, unlike nalgebra's constructor).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Quaternion {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// z.
    pub z: f64,
    /// w.
    pub w: f64,
}

impl Default for Quaternion {
    /// The identity, as ROS 2 defaults it (`float64 w 1`).
    fn default() -> Self {
        Quaternion {
            x: 0.0,
            y: 0.0,
            z: 0.0,
            w: 1.0,
        }
    }
}

/// `geometry_msgs/Pose`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Position.
    pub position: Point,
    /// Orientation.
    pub orientation: Quaternion,
}

/// A 6×6 covariance, row major (`float64[36]`): a fixed array, on the wire as 36
/// doubles with no length (serde derives arrays up to 32 only).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Covariance6(pub [f64; 36]);

impl Default for Covariance6 {
    fn default() -> Self {
        Covariance6([0.0; 36])
    }
}

impl Serialize for Covariance6 {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut t = s.serialize_tuple(36)?;
        for v in &self.0 {
            t.serialize_element(v)?;
        }
        t.end()
    }
}

impl<'de> Deserialize<'de> for Covariance6 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Covariance6;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("36 doubles")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Covariance6, A::Error> {
                let mut out = [0.0; 36];
                for (i, slot) in out.iter_mut().enumerate() {
                    *slot = seq
                        .next_element()?
                        .ok_or_else(|| de::Error::invalid_length(i, &self))?;
                }
                Ok(Covariance6(out))
            }
        }
        d.deserialize_tuple(36, V)
    }
}

/// `geometry_msgs/PoseWithCovariance`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct PoseWithCovariance {
    /// The pose.
    pub pose: Pose,
    /// Its covariance (x, y, z, rotation about x, y, z).
    pub covariance: Covariance6,
}

/// `geometry_msgs/Twist`: what `cmd_vel` carries.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Twist {
    /// Linear velocity, m/s.
    pub linear: Vector3,
    /// Angular velocity, rad/s.
    pub angular: Vector3,
}

impl Twist {
    /// No motion.
    pub const ZERO: Twist = Twist {
        linear: Vector3 {
            x: 0.0,
            y: 0.0,
            z: 0.0,
        },
        angular: Vector3 {
            x: 0.0,
            y: 0.0,
            z: 0.0,
        },
    };

    /// Whether every component is exactly zero.
    pub fn is_zero(&self) -> bool {
        *self == Twist::ZERO
    }
}

/// `geometry_msgs/TwistWithCovariance`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct TwistWithCovariance {
    /// The twist.
    pub twist: Twist,
    /// Its covariance.
    pub covariance: Covariance6,
}

/// `nav_msgs/Odometry`: the pose in `header.frame_id` (the odometry frame), the twist
/// in `child_frame_id` (the robot's base frame).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Odometry {
    /// Stamp and the pose's frame.
    pub header: Header,
    /// The twist's frame.
    pub child_frame_id: String,
    /// Pose.
    pub pose: PoseWithCovariance,
    /// Twist.
    pub twist: TwistWithCovariance,
}

/// `sensor_msgs/NavSatStatus`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct NavSatStatus {
    /// −1 no fix, 0 fix, 1 satellite-based augmentation, 2 ground-based augmentation.
    pub status: i8,
    /// Bit mask of the constellations used (1 GPS, 2 GLONASS, 4 COMPASS, 8 GALILEO).
    pub service: u16,
}

impl NavSatStatus {
    /// `STATUS_NO_FIX`.
    pub const NO_FIX: i8 = -1;
}

/// `sensor_msgs/NavSatFix`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct NavSatFix {
    /// Stamp and the antenna's frame.
    pub header: Header,
    /// Fix status.
    pub status: NavSatStatus,
    /// Latitude, degrees, + north.
    pub latitude: f64,
    /// Longitude, degrees, + east.
    pub longitude: f64,
    /// Altitude above the WGS 84 ellipsoid, m.
    pub altitude: f64,
    /// Position covariance, m², ENU, row major.
    pub position_covariance: [f64; 9],
    /// 0 unknown, 1 approximated, 2 diagonal known, 3 known.
    pub position_covariance_type: u8,
}

impl NavSatFix {
    /// `COVARIANCE_TYPE_UNKNOWN`.
    pub const COVARIANCE_UNKNOWN: u8 = 0;
}

/// `geometry_msgs/PoseStamped`: what `goal_pose` carries (RViz's "2D Goal Pose").
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct PoseStamped {
    /// Stamp and the pose's frame.
    pub header: Header,
    /// The pose.
    pub pose: Pose,
}

/// `std_msgs/String`.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct StdString {
    /// The text (`string data`).
    pub data: String,
}

/// `sensor_msgs/LaserScan`: one sweep of a planar range finder, beam `i` at
/// `angle_min + i · angle_increment` (rad, counter-clockwise, 0 along the laser frame's
/// x axis, REP-103).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct LaserScan {
    /// Stamp (the first beam) and the laser's frame.
    pub header: Header,
    /// Angle of the first beam, rad.
    pub angle_min: f32,
    /// Angle of the last beam, rad.
    pub angle_max: f32,
    /// Angle between beams, rad.
    pub angle_increment: f32,
    /// Time between beams, s.
    pub time_increment: f32,
    /// Time between sweeps, s.
    pub scan_time: f32,
    /// Shortest valid range, m.
    pub range_min: f32,
    /// Longest valid range, m.
    pub range_max: f32,
    /// Ranges, m (outside `[range_min, range_max]`, `inf` or `NaN`: no return).
    pub ranges: Vec<f32>,
    /// Intensities (device units; may be empty).
    pub intensities: Vec<f32>,
}

/// `sensor_msgs/Image`: an uncompressed image, rows top to bottom, `step` bytes a row.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Image {
    /// Stamp and the camera's optical frame.
    pub header: Header,
    /// Rows.
    pub height: u32,
    /// Columns.
    pub width: u32,
    /// Pixel encoding (`rgb8`, `bgr8`, `mono8`, ...: `sensor_image_encodings.h`).
    pub encoding: String,
    /// Whether multi-byte channels are big-endian.
    pub is_bigendian: u8,
    /// Bytes a row (at least `width` × bytes a pixel).
    pub step: u32,
    /// The rows.
    pub data: Vec<u8>,
}

/// `sensor_msgs/CompressedImage`: an image file (`format` names it: `png`, `jpeg`, or
/// image_transport's `rgb8; png compressed bgr8`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct CompressedImage {
    /// Stamp and the camera's optical frame.
    pub header: Header,
    /// The file's format.
    pub format: String,
    /// The file.
    pub data: Vec<u8>,
}

ros_message!(Twist, "geometry_msgs", "Twist");
ros_message!(PoseStamped, "geometry_msgs", "PoseStamped");
ros_message!(StdString, "std_msgs", "String");
ros_message!(Odometry, "nav_msgs", "Odometry");
ros_message!(NavSatFix, "sensor_msgs", "NavSatFix");
ros_message!(LaserScan, "sensor_msgs", "LaserScan");
ros_message!(Image, "sensor_msgs", "Image");
ros_message!(CompressedImage, "sensor_msgs", "CompressedImage");
ros_message!(Header, "std_msgs", "Header");
ros_message!(Time, "builtin_interfaces", "Time");

#[cfg(test)]
mod tests {
    use super::*;
    use ros2_client::rustdds::serialization::{
        deserialize_from_cdr_with_rep_id, to_writer_with_rep_id,
    };
    use ros2_client::rustdds::RepresentationIdentifier;

    fn cdr<T: Serialize>(v: &T) -> Vec<u8> {
        let mut out = Vec::new();
        to_writer_with_rep_id(&mut out, v, RepresentationIdentifier::CDR_LE).unwrap();
        out
    }

    fn back<T: for<'de> Deserialize<'de>>(b: &[u8]) -> T {
        deserialize_from_cdr_with_rep_id(b, RepresentationIdentifier::CDR_LE)
            .unwrap()
            .0
    }

    #[test]
    fn dds_type_names_follow_ros2() {
        assert_eq!(Odometry::DDS_TYPE, "nav_msgs::msg::dds_::Odometry_");
        assert_eq!(Twist::DDS_TYPE, "geometry_msgs::msg::dds_::Twist_");
        assert_eq!(NavSatFix::DDS_TYPE, "sensor_msgs::msg::dds_::NavSatFix_");
        assert_eq!(Header::DDS_TYPE, "std_msgs::msg::dds_::Header_");
    }

    #[test]
    fn twist_is_six_doubles_in_order() {
        let t = Twist {
            linear: Vector3 {
                x: 1.0,
                y: 2.0,
                z: 3.0,
            },
            angular: Vector3 {
                x: 4.0,
                y: 5.0,
                z: 6.0,
            },
        };
        let b = cdr(&t);
        assert_eq!(b.len(), 48);
        for (i, chunk) in b.chunks(8).enumerate() {
            let v = f64::from_le_bytes(chunk.try_into().unwrap());
            assert_eq!(v, (i + 1) as f64);
        }
        assert_eq!(back::<Twist>(&b), t);
    }

    #[test]
    fn odometry_layout_matches_the_idl() {
        let mut o = Odometry {
            header: Header {
                stamp: Time { sec: 7, nanosec: 9 },
                frame_id: "odom".into(),
            },
            child_frame_id: "base_link".into(),
            ..Odometry::default()
        };
        o.pose.pose.position.x = 1.5;
        o.pose.covariance.0[35] = 0.25;
        o.twist.twist.angular.z = -0.5;
        let b = cdr(&o);
        // sec, nanosec; "odom\0" with its length; pad to 4; "base_link\0" with length.
        assert_eq!(&b[0..4], &7i32.to_le_bytes());
        assert_eq!(&b[4..8], &9u32.to_le_bytes());
        assert_eq!(&b[8..12], &5u32.to_le_bytes());
        assert_eq!(&b[12..17], b"odom\0");
        assert_eq!(&b[20..24], &10u32.to_le_bytes());
        assert_eq!(&b[24..34], b"base_link\0");
        // Pose position x at the next multiple of 8 (40): 34 → 40.
        assert_eq!(&b[40..48], &1.5f64.to_le_bytes());
        // 7 doubles of pose, 36 of covariance, 6 of twist, 36 of covariance.
        assert_eq!(b.len(), 40 + 8 * (7 + 36 + 6 + 36));
        let cov_end = 40 + 8 * (7 + 36);
        assert_eq!(&b[cov_end - 8..cov_end], &0.25f64.to_le_bytes());
        assert_eq!(&b[cov_end + 40..cov_end + 48], &(-0.5f64).to_le_bytes());
        assert_eq!(back::<Odometry>(&b), o);
    }

    #[test]
    fn navsatfix_layout_matches_the_idl() {
        let f = NavSatFix {
            header: Header {
                stamp: Time { sec: 1, nanosec: 2 },
                frame_id: "gps".into(),
            },
            status: NavSatStatus {
                status: NavSatStatus::NO_FIX,
                service: 1,
            },
            latitude: 29.5,
            longitude: -82.25,
            altitude: 10.0,
            position_covariance: [1.0; 9],
            position_covariance_type: 2,
        };
        let b = cdr(&f);
        // 8 stamp + 4 length + "gps\0" = 16; status i8 at 16, pad, u16 at 18.
        assert_eq!(b[16], 0xff);
        assert_eq!(&b[18..20], &1u16.to_le_bytes());
        assert_eq!(&b[24..32], &29.5f64.to_le_bytes());
        assert_eq!(b.len(), 24 + 8 * 12 + 1);
        assert_eq!(b[b.len() - 1], 2);
        assert_eq!(back::<NavSatFix>(&b), f);
    }

    #[test]
    fn laserscan_layout_matches_the_idl() {
        let l = LaserScan {
            header: Header {
                stamp: Time { sec: 1, nanosec: 2 },
                frame_id: "laser".into(),
            },
            angle_min: -1.5,
            angle_max: 1.5,
            angle_increment: 0.5,
            range_min: 0.1,
            range_max: 30.0,
            ranges: vec![1.0, f32::INFINITY],
            intensities: vec![],
            ..LaserScan::default()
        };
        let b = cdr(&l);
        // 8 stamp + 4 length + "laser\0" = 18, padded to 20; seven floats; ranges.
        assert_eq!(LaserScan::DDS_TYPE, "sensor_msgs::msg::dds_::LaserScan_");
        assert_eq!(&b[20..24], &(-1.5f32).to_le_bytes());
        assert_eq!(&b[44..48], &30.0f32.to_le_bytes());
        assert_eq!(&b[48..52], &2u32.to_le_bytes());
        assert_eq!(&b[52..56], &1.0f32.to_le_bytes());
        assert_eq!(&b[60..64], &0u32.to_le_bytes());
        assert_eq!(b.len(), 64);
        assert_eq!(back::<LaserScan>(&b), l);
    }

    #[test]
    fn image_layouts_match_the_idl() {
        let i = Image {
            header: Header {
                stamp: Time { sec: 1, nanosec: 2 },
                frame_id: "cam".into(),
            },
            height: 2,
            width: 1,
            encoding: "rgb8".into(),
            is_bigendian: 0,
            step: 3,
            data: vec![1, 2, 3, 4, 5, 6],
        };
        let b = cdr(&i);
        // 8 + 4 + "cam\0" = 16; height, width; "rgb8\0" at 24 (length) 28..33; u8 at 33;
        // step at 36; data length at 40, bytes at 44.
        assert_eq!(&b[16..20], &2u32.to_le_bytes());
        assert_eq!(&b[28..33], b"rgb8\0");
        assert_eq!(&b[36..40], &3u32.to_le_bytes());
        assert_eq!(&b[40..44], &6u32.to_le_bytes());
        assert_eq!(&b[44..], &[1, 2, 3, 4, 5, 6]);
        assert_eq!(back::<Image>(&b), i);
        let c = CompressedImage {
            format: "png".into(),
            data: vec![9; 3],
            ..CompressedImage::default()
        };
        let b = cdr(&c);
        // 8 + 4 + "\0" = 13, pad 16: "png\0" length; data length at 24.
        assert_eq!(&b[20..24], b"png\0");
        assert_eq!(&b[24..28], &3u32.to_le_bytes());
        assert_eq!(back::<CompressedImage>(&b), c);
        assert_eq!(Image::DDS_TYPE, "sensor_msgs::msg::dds_::Image_");
        assert_eq!(
            CompressedImage::DDS_TYPE,
            "sensor_msgs::msg::dds_::CompressedImage_"
        );
    }

    #[test]
    fn truncated_input_is_an_error_not_a_panic() {
        let b = cdr(&Odometry::default());
        for n in [0, 3, 9, 40, b.len() - 1] {
            let r = deserialize_from_cdr_with_rep_id::<Odometry>(
                &b[..n],
                RepresentationIdentifier::CDR_LE,
            );
            assert!(r.is_err(), "{n}");
        }
    }
}
