//! The path segment of Part 1 §5.3.10: a rational quadratic curve
//!
//! p(u) = ((1-u)² P0 + 2u(1-u) w1 P1 + u² P2) / ((1-u)² + 2u(1-u) w1 + u²),  u ∈ [0, 1],
//!
//! which starts at P0 tangent to P0→P1 and ends at P2 tangent to P1→P2; a larger w1
//! draws the curve toward P1. A [`Path`] chains segments (each starting where the
//! previous one ended) into a dense polyline for tracking and cross-track error.

use nalgebra::{Vector2, Vector3};

/// One path segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathSegment {
    /// Start point.
    pub p0: Vector3<f64>,
    /// Control point (not on the curve in general).
    pub p1: Vector3<f64>,
    /// End point.
    pub p2: Vector3<f64>,
    /// Weighting factor w1 (≥ 0).
    pub w1: f64,
}

impl PathSegment {
    /// The point at parameter `u` (clamped to [0, 1]).
    pub fn point(&self, u: f64) -> Vector3<f64> {
        let u = u.clamp(0.0, 1.0);
        let (a, b, c) = ((1.0 - u) * (1.0 - u), 2.0 * u * (1.0 - u) * self.w1, u * u);
        (self.p0 * a + self.p1 * b + self.p2 * c) / (a + b + c)
    }

    /// The derivative dp/du at `u` (quotient rule on numerator N and denominator D).
    pub fn derivative(&self, u: f64) -> Vector3<f64> {
        let u = u.clamp(0.0, 1.0);
        let (a, b, c) = ((1.0 - u) * (1.0 - u), 2.0 * u * (1.0 - u) * self.w1, u * u);
        let (da, db, dc) = (-2.0 * (1.0 - u), 2.0 * self.w1 * (1.0 - 2.0 * u), 2.0 * u);
        let n = self.p0 * a + self.p1 * b + self.p2 * c;
        let dn = self.p0 * da + self.p1 * db + self.p2 * dc;
        let (d, dd) = (a + b + c, da + db + dc);
        (dn * d - n * dd) / (d * d)
    }

    /// `n + 1` points at equal steps of u.
    pub fn sample(&self, n: usize) -> Vec<Vector3<f64>> {
        let n = n.max(1);
        (0..=n).map(|i| self.point(i as f64 / n as f64)).collect()
    }

    /// Length of the curve, by summing a fine polyline.
    pub fn length(&self) -> f64 {
        self.sample(256)
            .windows(2)
            .map(|w| (w[1] - w[0]).norm())
            .sum()
    }
}

/// A polyline in the plane (x, y) with cumulative arc length, for tracking.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Path {
    points: Vec<Vector2<f64>>,
    arc: Vec<f64>,
}

/// Where a position projects onto a [`Path`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// Arc length from the start to the nearest point.
    pub s: f64,
    /// Distance from the path (the cross-track error), m.
    pub distance: f64,
    /// The nearest point.
    pub point: Vector2<f64>,
}

impl Path {
    /// A path through `points`; consecutive duplicates are dropped.
    pub fn new(points: impl IntoIterator<Item = Vector2<f64>>) -> Self {
        let mut p = Path::default();
        for q in points {
            p.push(q);
        }
        p
    }

    /// Appends a point.
    pub fn push(&mut self, q: Vector2<f64>) {
        match self.points.last() {
            Some(last) if (q - last).norm() < 1e-9 => {}
            Some(last) => {
                let s = self.arc.last().copied().unwrap_or(0.0) + (q - last).norm();
                self.points.push(q);
                self.arc.push(s);
            }
            None => {
                self.points.push(q);
                self.arc.push(0.0);
            }
        }
    }

    /// Appends a path segment, sampled densely (its P0 should be the current end).
    pub fn push_segment(&mut self, seg: &PathSegment) {
        let n = ((seg.length() / 0.05).ceil() as usize).clamp(16, 4096);
        for q in seg.sample(n) {
            self.push(Vector2::new(q.x, q.y));
        }
    }

    /// The points.
    pub fn points(&self) -> &[Vector2<f64>] {
        &self.points
    }

    /// Total length.
    pub fn length(&self) -> f64 {
        self.arc.last().copied().unwrap_or(0.0)
    }

    /// Whether the path has no length.
    pub fn is_empty(&self) -> bool {
        self.points.len() < 2
    }

    /// The point at arc length `s` (clamped to the path).
    pub fn at(&self, s: f64) -> Vector2<f64> {
        match self.points.len() {
            0 => Vector2::zeros(),
            1 => self.points[0],
            _ => {
                let s = s.clamp(0.0, self.length());
                let i = self
                    .arc
                    .partition_point(|a| *a < s)
                    .clamp(1, self.points.len() - 1);
                let (a, b) = (self.points[i - 1], self.points[i]);
                let seg = self.arc[i] - self.arc[i - 1];
                let t = if seg > 0.0 {
                    (s - self.arc[i - 1]) / seg
                } else {
                    0.0
                };
                a + (b - a) * t
            }
        }
    }

    /// The fastest speed at arc length `s` from which the vehicle can still slow down,
    /// at `deceleration`, to take every turn ahead within `tolerance` of the path,
    /// turning at `yaw_rate` (rad/s); at most `limit`. A turn is the change of
    /// direction across a vertex, measured over `window` m either side (so a sampled
    /// curve counts as the turn it makes, not as many tiny ones). Taking a turn of angle
    /// θ on an arc of radius r strays r (1/cos(θ/2) − 1) from the corner, so the speed
    /// through it is `yaw_rate` · r for the r that strays `tolerance`. A turn less than
    /// `window` behind `s` still limits the speed (the vehicle is still in it).
    pub fn turn_speed(
        &self,
        s: f64,
        limit: f64,
        (deceleration, tolerance, yaw_rate, window): (f64, f64, f64, f64),
    ) -> f64 {
        // NaN limits and decelerations are no limits.
        if self.points.len() < 3
            || limit.is_nan()
            || limit <= 0.0
            || deceleration.is_nan()
            || deceleration <= 0.0
        {
            return limit;
        }
        // Only the turns within braking distance of `limit` matter.
        let horizon = s + limit * limit / (2.0 * deceleration) + window;
        // A turn just passed (within the window) still holds: the vehicle is in it.
        let first = self.arc.partition_point(|a| *a <= s - window).max(1);
        let mut v = limit;
        for i in first..self.points.len() - 1 {
            let at = self.arc[i];
            if at > horizon {
                break;
            }
            let before = self.at(at) - self.at(at - window);
            let after = self.at(at + window) - self.at(at);
            if before.norm() < 1e-9 || after.norm() < 1e-9 {
                continue;
            }
            let cos = (before.dot(&after) / (before.norm() * after.norm())).clamp(-1.0, 1.0);
            let angle = cos.acos();
            let stray = 1.0 / (angle / 2.0).cos().max(1e-6) - 1.0;
            if stray < 1e-9 {
                continue;
            }
            let through = yaw_rate * tolerance / stray;
            let d = (at - s).max(0.0);
            v = v.min((through * through + 2.0 * deceleration * d).sqrt());
        }
        v
    }

    /// The nearest point of the path to `p`, searched among segments whose arc length
    /// lies in `[from, to]` (pass the whole range for a global search).
    pub fn project(&self, p: Vector2<f64>, from: f64, to: f64) -> Option<Projection> {
        let mut best: Option<Projection> = None;
        for i in 1..self.points.len() {
            if self.arc[i] < from || self.arc[i - 1] > to {
                continue;
            }
            let (a, b) = (self.points[i - 1], self.points[i]);
            let ab = b - a;
            let t = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
            let q = a + ab * t;
            let d = (p - q).norm();
            if best.is_none_or(|x| d < x.distance) {
                best = Some(Projection {
                    s: self.arc[i - 1] + ab.norm() * t,
                    distance: d,
                    point: q,
                });
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fig_5_12() -> PathSegment {
        PathSegment {
            p0: Vector3::new(1.0, 2.0, 0.0),
            p1: Vector3::new(3.0, 5.0, 0.0),
            p2: Vector3::new(5.0, 1.0, 0.0),
            w1: 1.5,
        }
    }

    #[test]
    fn turns_limit_the_speed_before_them_and_in_them() {
        let corner = Path::new([
            Vector2::new(0.0, 0.0),
            Vector2::new(10.0, 0.0),
            Vector2::new(10.0, 10.0),
        ]);
        let params = (0.8, 0.05, 0.75, 0.3);
        // A right angle strays r (√2 − 1): 0.05 m at r = 0.05 / 0.414.
        let through = 0.75 * 0.05 / (2f64.sqrt() - 1.0);
        assert!((corner.turn_speed(10.0, 2.0, params) - through).abs() < 1e-9);
        // Within the window after it, still in the turn.
        assert!((corner.turn_speed(10.2, 2.0, params) - through).abs() < 1e-9);
        // One metre before: what braking at 0.8 m/s² leaves.
        let v = corner.turn_speed(9.0, 2.0, params);
        assert!((v - (through * through + 1.6).sqrt()).abs() < 1e-9, "{v}");
        // Far before, and past it: the limit.
        assert_eq!(corner.turn_speed(0.0, 2.0, params), 2.0);
        assert_eq!(corner.turn_speed(12.0, 2.0, params), 2.0);
        // A straight line never slows.
        let straight = Path::new([
            Vector2::new(0.0, 0.0),
            Vector2::new(5.0, 0.0),
            Vector2::new(9.0, 0.0),
        ]);
        assert_eq!(straight.turn_speed(4.9, 1.0, params), 1.0);
        // A gentle bend slows less than a sharp one.
        let gentle = Path::new([
            Vector2::new(0.0, 0.0),
            Vector2::new(10.0, 0.0),
            Vector2::new(20.0, 2.0),
        ]);
        assert!(gentle.turn_speed(10.0, 2.0, params) > 5.0 * through);
    }

    #[test]
    fn ends_are_p0_and_p2() {
        let s = fig_5_12();
        assert!((s.point(0.0) - s.p0).norm() < 1e-12);
        assert!((s.point(1.0) - s.p2).norm() < 1e-12);
    }

    #[test]
    fn midpoint_by_hand() {
        // u = 1/2: weights 1/4, w1/2, 1/4 → (P0 + 2 w1 P1 + P2) / (2 + 2 w1).
        // With w1 = 1.5: ([1,2] + 3·[3,5] + [5,1]) / 5 = [15, 18] / 5 = [3, 3.6].
        let m = fig_5_12().point(0.5);
        assert!((m - Vector3::new(3.0, 3.6, 0.0)).norm() < 1e-12, "{m}");
        // w1 = 1 is the ordinary quadratic Bézier: (P0 + 2 P1 + P2) / 4 = [3, 3.25].
        let b = PathSegment {
            w1: 1.0,
            ..fig_5_12()
        }
        .point(0.5);
        assert!((b - Vector3::new(3.0, 3.25, 0.0)).norm() < 1e-12, "{b}");
    }

    #[test]
    fn tangent_at_the_ends_points_along_the_control_polygon() {
        let s = fig_5_12();
        let d0 = s.derivative(0.0).normalize();
        let d1 = s.derivative(1.0).normalize();
        // dp/du(0) = 2 w1 (P1 - P0), dp/du(1) = 2 w1 (P2 - P1).
        assert!((s.derivative(0.0) - (s.p1 - s.p0) * (2.0 * s.w1)).norm() < 1e-9);
        assert!((s.derivative(1.0) - (s.p2 - s.p1) * (2.0 * s.w1)).norm() < 1e-9);
        assert!((d0 - (s.p1 - s.p0).normalize()).norm() < 1e-12);
        assert!((d1 - (s.p2 - s.p1).normalize()).norm() < 1e-12);
        // Numerical derivative agrees in the middle.
        let h = 1e-6;
        let num = (s.point(0.3 + h) - s.point(0.3 - h)) / (2.0 * h);
        assert!((num - s.derivative(0.3)).norm() < 1e-5);
    }

    #[test]
    fn larger_w1_draws_the_curve_toward_p1() {
        let dist = |w1: f64| (PathSegment { w1, ..fig_5_12() }.point(0.5) - fig_5_12().p1).norm();
        assert!(dist(0.5) > dist(1.0) && dist(1.0) > dist(1.5) && dist(1.5) > dist(5.0));
        // w1 = 0 degenerates to the chord from P0 to P2.
        let chord = PathSegment {
            w1: 0.0,
            ..fig_5_12()
        }
        .point(0.5);
        assert!((chord - Vector3::new(3.0, 1.5, 0.0)).norm() < 1e-12);
    }

    #[test]
    fn figure_5_14_joins_with_slope_continuity() {
        let a = fig_5_12();
        let b = PathSegment {
            p0: a.p2,
            p1: Vector3::new(6.0, -1.0, 0.0),
            p2: Vector3::new(8.0, -1.0, 0.0),
            w1: 2.0,
        };
        let ta = a.derivative(1.0).normalize();
        let tb = b.derivative(0.0).normalize();
        assert!(
            (ta - tb).norm() < 1e-12,
            "P1-P2 and P2-P3 are collinear: {ta} {tb}"
        );
        let mut path = Path::default();
        path.push_segment(&a);
        path.push_segment(&b);
        let p = path
            .project(Vector2::new(3.0, 3.6), 0.0, f64::INFINITY)
            .unwrap();
        assert!(p.distance < 1e-3);
        assert!((path.at(path.length()) - Vector2::new(8.0, -1.0)).norm() < 1e-9);
    }
}
