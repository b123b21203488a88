//! A local tangent plane at a WGS 84 origin: global (latitude, longitude) to local
//! (x north, y east) metres and back. The plane uses the ellipsoid's meridian and
//! prime-vertical radii of curvature at the origin, which keeps the error under a few
//! centimetres within a few kilometres of the origin: the range of a waypoint mission.

use nalgebra::Vector2;

use crate::messages::ReportGlobalPose;

/// WGS 84 semi-major axis, m.
pub const WGS84_A: f64 = 6_378_137.0;
/// WGS 84 flattening.
pub const WGS84_F: f64 = 1.0 / 298.257_223_563;

/// A local frame: x points north, y east, z down; heading 0 is +x (north) and grows
/// toward +y (east), as Part 1 defines headings about a downward z axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalFrame {
    /// Latitude of the origin, degrees.
    pub latitude: f64,
    /// Longitude of the origin, degrees.
    pub longitude: f64,
    /// Elevation of the origin above the ellipsoid, m.
    pub elevation: f64,
    meridian_radius: f64,
    normal_radius: f64,
}

impl LocalFrame {
    /// The frame at `latitude`, `longitude` (degrees) and `elevation` (m).
    pub fn new(latitude: f64, longitude: f64, elevation: f64) -> Self {
        let e2 = WGS84_F * (2.0 - WGS84_F);
        let s = latitude.to_radians().sin();
        let w = (1.0 - e2 * s * s).sqrt();
        Self {
            latitude,
            longitude,
            elevation,
            meridian_radius: WGS84_A * (1.0 - e2) / (w * w * w),
            normal_radius: WGS84_A / w,
        }
    }

    /// Local (north, east) metres of a global position.
    pub fn to_local(&self, latitude: f64, longitude: f64) -> Vector2<f64> {
        let dlat = (latitude - self.latitude).to_radians();
        let mut dlon = longitude - self.longitude;
        if dlon > 180.0 {
            dlon -= 360.0;
        } else if dlon < -180.0 {
            dlon += 360.0;
        }
        Vector2::new(
            dlat * (self.meridian_radius + self.elevation),
            dlon.to_radians()
                * (self.normal_radius + self.elevation)
                * self.latitude.to_radians().cos(),
        )
    }

    /// Global (latitude, longitude) degrees of a local (north, east) position.
    pub fn to_global(&self, p: Vector2<f64>) -> (f64, f64) {
        let lat = self.latitude + (p.x / (self.meridian_radius + self.elevation)).to_degrees();
        let lon = self.longitude
            + (p.y / ((self.normal_radius + self.elevation) * self.latitude.to_radians().cos()))
                .to_degrees();
        (lat, lon)
    }
}

/// `a` wrapped into (-π, π].
pub fn wrap_angle(a: f64) -> f64 {
    let mut a = a % std::f64::consts::TAU;
    if a > std::f64::consts::PI {
        a -= std::f64::consts::TAU;
    } else if a <= -std::f64::consts::PI {
        a += std::f64::consts::TAU;
    }
    a
}

/// A global pose report as a local position and heading in `frame`, which is anchored
/// at this report's position when still `None`. `last_yaw` stands in when the report
/// carries no yaw (0 without one). `None` without a finite latitude and longitude.
pub fn local_pose(
    frame: &mut Option<LocalFrame>,
    r: &ReportGlobalPose,
    last_yaw: Option<f64>,
) -> Option<(Vector2<f64>, f64)> {
    let (Some(lat), Some(lon)) = (r.latitude, r.longitude) else {
        return None;
    };
    if !(lat.is_finite() && lon.is_finite()) {
        return None;
    }
    let frame = *frame.get_or_insert_with(|| LocalFrame::new(lat, lon, r.elevation.unwrap_or(0.0)));
    let yaw = r.yaw.or(last_yaw).unwrap_or(0.0);
    Some((frame.to_local(lat, lon), yaw))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_scale() {
        let f = LocalFrame::new(29.6436, -82.3549, 0.0);
        let p = f.to_local(29.6436 + 0.001, -82.3549 + 0.001);
        // 0.001° of latitude is about 110.9 m here; of longitude about 96.8 m.
        assert!((p.x - 110.86).abs() < 0.1, "{p}");
        assert!((p.y - 96.83).abs() < 0.1, "{p}");
        let (lat, lon) = f.to_global(p);
        assert!((lat - 29.6446).abs() < 1e-12 && (lon + 82.3539).abs() < 1e-12);
        assert!((wrap_angle(3.5) - (3.5 - std::f64::consts::TAU)).abs() < 1e-12);
        assert_eq!(wrap_angle(-std::f64::consts::PI), std::f64::consts::PI);
    }
}
