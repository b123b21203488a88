//! [`Frame`]: the AS-4 local frame relative to the RA 3.3 one.

/// A rigid 2-D transform: AS-4 local = rotate(yaw) · RA 3.3 local + (x, y).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Frame {
    /// Translation along X, metres.
    pub x: f64,
    /// Translation along Y, metres.
    pub y: f64,
    /// Rotation, radians.
    pub yaw: f64,
}

impl Frame {
    /// A point of the RA 3.3 local frame in the AS-4 one.
    pub fn to_as4(&self, x: f64, y: f64) -> (f64, f64) {
        let (s, c) = self.yaw.sin_cos();
        (c * x - s * y + self.x, s * x + c * y + self.y)
    }

    /// A point of the AS-4 local frame in the RA 3.3 one.
    pub fn to_ra33(&self, x: f64, y: f64) -> (f64, f64) {
        let (s, c) = self.yaw.sin_cos();
        let (dx, dy) = (x - self.x, y - self.y);
        (c * dx + s * dy, -s * dx + c * dy)
    }

    /// A heading of the RA 3.3 local frame in the AS-4 one, in (-π, π].
    pub fn yaw_to_as4(&self, yaw: f64) -> f64 {
        wrap(yaw + self.yaw)
    }

    /// A heading of the AS-4 local frame in the RA 3.3 one.
    pub fn yaw_to_ra33(&self, yaw: f64) -> f64 {
        wrap(yaw - self.yaw)
    }

    /// The frame in which the RA 3.3 pose (`x`, `y`, `yaw`) reads as the AS-4 pose
    /// (`ax`, `ay`, `ayaw`).
    pub fn placing(x: f64, y: f64, yaw: f64, ax: f64, ay: f64, ayaw: f64) -> Frame {
        let r = wrap(ayaw - yaw);
        let (s, c) = r.sin_cos();
        Frame {
            x: ax - (c * x - s * y),
            y: ay - (s * x + c * y),
            yaw: r,
        }
    }
}

fn wrap(a: f64) -> f64 {
    let t = std::f64::consts::TAU;
    let w = a.rem_euclid(t);
    if w > std::f64::consts::PI {
        w - t
    } else {
        w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_round_trip_and_placing() {
        let f = Frame::placing(3.0, 4.0, 0.5, -1.0, 2.0, 2.0);
        let (ax, ay) = f.to_as4(3.0, 4.0);
        assert!((ax + 1.0).abs() < 1e-9 && (ay - 2.0).abs() < 1e-9);
        assert!((f.yaw_to_as4(0.5) - 2.0).abs() < 1e-9);
        let (x, y) = f.to_ra33(10.0, -7.0);
        let (bx, by) = f.to_as4(x, y);
        assert!((bx - 10.0).abs() < 1e-9 && (by + 7.0).abs() < 1e-9);
        assert!((f.yaw_to_ra33(f.yaw_to_as4(3.0)) - 3.0).abs() < 1e-9);
    }
}
