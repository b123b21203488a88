//! The hardware a vendor connects: four small traits, each a few lines to implement.
//! The stock components are generic over them; the `jaus-sim` crate implements them all
//! with a simulated vehicle.

use std::time::Instant;

use nalgebra::{UnitQuaternion, Vector3};

/// A wrench effort in percent of the platform's available effort (Set Wrench Effort).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Wrench {
    /// Propulsive linear effort x, y, z, −100..=100 %.
    pub linear: Vector3<f64>,
    /// Propulsive rotational effort about x, y, z, −100..=100 %.
    pub rotational: Vector3<f64>,
    /// Resistive (braking) linear effort x, y, z, 0..=100 %.
    pub resistive_linear: Vector3<f64>,
    /// Resistive rotational effort about x, y, z, 0..=100 %.
    pub resistive_rotational: Vector3<f64>,
}

impl Wrench {
    /// No effort at all: the platform coasts to a stop.
    pub const ZERO: Wrench = Wrench {
        linear: Vector3::new(0.0, 0.0, 0.0),
        rotational: Vector3::new(0.0, 0.0, 0.0),
        resistive_linear: Vector3::new(0.0, 0.0, 0.0),
        resistive_rotational: Vector3::new(0.0, 0.0, 0.0),
    };

    /// Full brakes, no propulsion.
    pub fn brake() -> Wrench {
        Wrench {
            resistive_linear: Vector3::new(100.0, 100.0, 100.0),
            resistive_rotational: Vector3::new(100.0, 100.0, 100.0),
            ..Wrench::ZERO
        }
    }

    /// Whether every component is finite and in its range.
    pub fn is_valid(&self) -> bool {
        let prop = |v: &Vector3<f64>| {
            v.iter()
                .all(|x| x.is_finite() && (-100.0..=100.0).contains(x))
        };
        let res = |v: &Vector3<f64>| v.iter().all(|x| x.is_finite() && (0.0..=100.0).contains(x));
        prop(&self.linear)
            && prop(&self.rotational)
            && res(&self.resistive_linear)
            && res(&self.resistive_rotational)
    }
}

/// A position fix in WGS 84 with attitude.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GlobalPose {
    /// Latitude, degrees.
    pub latitude: f64,
    /// Longitude, degrees.
    pub longitude: f64,
    /// Elevation above the ellipsoid, m.
    pub elevation: f64,
    /// Attitude (roll, pitch, yaw about x north, y east, z down).
    pub attitude: UnitQuaternion<f64>,
    /// Position RMS error, m.
    pub position_rms: f64,
}

/// A position in a local frame (x north, y east, z down, m) with attitude.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalPose {
    /// Position, m.
    pub position: Vector3<f64>,
    /// Attitude.
    pub attitude: UnitQuaternion<f64>,
}

impl LocalPose {
    /// Heading (yaw), radians, 0 = +x, growing toward +y.
    pub fn yaw(&self) -> f64 {
        self.attitude.euler_angles().2
    }
}

/// The velocity state of Part 1 §5.3.3, in the vehicle frame.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct VelocityState {
    /// Linear velocity x (forward), y (right), z (down), m/s.
    pub linear: Vector3<f64>,
    /// Angular velocity about x, y, z, rad/s.
    pub angular: Vector3<f64>,
}

/// The platform's operational data (RA 3.3 Report Platform Operational Data), each
/// field `None` where the platform does not measure it. Units are SI or percent; the
/// Primitive Driver converts them to the message's encoding.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct OperationalData {
    /// Engine temperature, °C (the message carries −75..=180 °C).
    pub engine_temperature: Option<f64>,
    /// Distance travelled since the platform's odometer was set, m (never decreasing;
    /// reported in whole metres, rounded down, up to `u32::MAX`).
    pub odometer: Option<f64>,
    /// Battery voltage, % of nominal (the message carries 0..=127 %).
    pub battery_voltage: Option<f64>,
    /// Fuel level, % (0..=100 %).
    pub fuel_level: Option<f64>,
    /// Oil pressure, % of nominal (the message carries 0..=127 %).
    pub oil_pressure: Option<f64>,
}

/// Applies wrench efforts to the actuators (the Primitive Driver's hardware).
pub trait Actuators: Send + 'static {
    /// Applies `effort` from `now` on.
    fn apply(&mut self, now: Instant, effort: &Wrench);

    /// The platform's operational data at `now` (engine temperature, odometer, battery,
    /// fuel, oil pressure), answered to Query Platform Operational Data; `None` (the
    /// default) when the platform measures none of them, and the driver then leaves the
    /// query unanswered.
    fn operational_data(&mut self, now: Instant) -> Option<OperationalData> {
        let _ = now;
        None
    }
}

/// Reads global pose fixes (a GPS/INS).
pub trait GlobalPoseSource: Send + 'static {
    /// The latest fix, or `None` without one.
    fn global_pose(&mut self, now: Instant) -> Option<GlobalPose>;
}

/// Reads the local pose (odometry, a local positioning system).
pub trait LocalPoseSource: Send + 'static {
    /// The latest pose, or `None` without one.
    fn local_pose(&mut self, now: Instant) -> Option<LocalPose>;
}

/// Reads the velocity state.
pub trait VelocitySource: Send + 'static {
    /// The latest velocity state, or `None` without one.
    fn velocity(&mut self, now: Instant) -> Option<VelocityState>;
}
