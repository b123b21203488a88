//! Motion profiles of the manipulator drivers (Part 1 §5.4.6, §5.4.7, §5.4.10, §5.4.11):
//! trapezoidal joint profiles that reach each joint set at its time (Joint Move Driver),
//! synchronised rest-to-rest trapezoidal moves to a joint target (Joint Positions and
//! End-Effector Pose Drivers: every joint decelerates into the target and all arrive
//! together), and end-effector poses interpolated between timed poses, linearly in position and by
//! spherical interpolation in orientation (End-Effector Discrete Pose Driver).

use nalgebra::{Isometry3, Translation3, UnitQuaternion};

/// Why a timed move cannot be executed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProfileError {
    /// The limits are not positive finite numbers.
    #[error("joint {joint}: {what} = {value} must be a positive finite number")]
    BadLimit {
        /// Joint index, 0 = first joint.
        joint: usize,
        /// Which limit.
        what: &'static str,
        /// The value received.
        value: f64,
    },
    /// The joint cannot cover the distance in the time with its limits.
    #[error(
        "joint {joint}: {distance:.4} in {duration:.3} s needs a cruise speed of {needed:.4}/s, above the limit {max_velocity:.4}/s (or more acceleration)"
    )]
    TooFast {
        /// Joint index, 0 = first joint.
        joint: usize,
        /// Distance to cover (rad or m).
        distance: f64,
        /// Time available, s.
        duration: f64,
        /// The cruise speed the move would need (infinite when no speed suffices with the
        /// given acceleration and deceleration).
        needed: f64,
        /// The joint's speed limit for the move.
        max_velocity: f64,
    },
    /// Times must grow strictly from one pose to the next (the first after 0).
    #[error("pose {pose}: time {time} s does not come after the previous pose's {previous} s")]
    TimeNotIncreasing {
        /// Pose index, 0 = first pose.
        pose: usize,
        /// Its time, s.
        time: f64,
        /// The previous pose's time (0 for the first pose), s.
        previous: f64,
    },
}

/// One joint's trapezoidal velocity profile from `from` to `to` taking exactly
/// `duration`: accelerate at `a`, cruise, decelerate at `d`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trapezoid {
    from: f64,
    to: f64,
    duration: f64,
    cruise: f64,
    accel: f64,
    decel: f64,
}

impl Trapezoid {
    /// The profile covering `to - from` in exactly `duration` seconds with at most
    /// `max_velocity`, `max_acceleration` and `max_deceleration` (their signs are
    /// ignored). The cruise speed is the lowest that arrives on time with the full
    /// acceleration and deceleration: `v = (T − √(T² − 4kD)) / 2k`, `k = 1/2a + 1/2d`.
    pub fn timed(
        joint: usize,
        from: f64,
        to: f64,
        duration: f64,
        max_velocity: f64,
        max_acceleration: f64,
        max_deceleration: f64,
    ) -> Result<Trapezoid, ProfileError> {
        let (vmax, a, d) = (
            max_velocity.abs(),
            max_acceleration.abs(),
            max_deceleration.abs(),
        );
        for (what, value) in [
            ("max_velocity", vmax),
            ("max_acceleration", a),
            ("max_deceleration", d),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(ProfileError::BadLimit { joint, what, value });
            }
        }
        let distance = (to - from).abs();
        if distance == 0.0 {
            return Ok(Trapezoid {
                from,
                to,
                duration,
                cruise: 0.0,
                accel: a,
                decel: d,
            });
        }
        let k = 1.0 / (2.0 * a) + 1.0 / (2.0 * d);
        let disc = duration * duration - 4.0 * k * distance;
        let cruise = if disc >= 0.0 {
            (duration - disc.sqrt()) / (2.0 * k)
        } else {
            f64::INFINITY
        };
        // Relative slack for the rounding of the wire's scaled integers.
        if cruise > vmax * (1.0 + 1e-9) {
            return Err(ProfileError::TooFast {
                joint,
                distance,
                duration,
                needed: cruise,
                max_velocity: vmax,
            });
        }
        Ok(Trapezoid {
            from,
            to,
            duration,
            cruise: cruise.min(vmax),
            accel: a,
            decel: d,
        })
    }

    /// Duration of the profile, s.
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// The cruise speed (unsigned), rad/s or m/s.
    pub fn cruise(&self) -> f64 {
        self.cruise
    }

    /// Position and velocity `t` seconds after the start (held at the ends outside
    /// `[0, duration]`).
    pub fn sample(&self, t: f64) -> (f64, f64) {
        if self.cruise == 0.0 || t >= self.duration {
            return (self.to, 0.0);
        }
        if t <= 0.0 {
            return (self.from, 0.0);
        }
        let s = (self.to - self.from).signum();
        let v = self.cruise;
        let ta = v / self.accel;
        let td = v / self.decel;
        let (dist, vel) = if t < ta {
            (0.5 * self.accel * t * t, self.accel * t)
        } else if t <= self.duration - td {
            (0.5 * v * ta + v * (t - ta), v)
        } else {
            let r = self.duration - t;
            let total = (self.to - self.from).abs();
            (total - 0.5 * self.decel * r * r, self.decel * r)
        };
        (self.from + s * dist, s * vel)
    }

    /// The integral of the position from 0 to `t` (the position is `from` before the
    /// start and `to` after the end), for the smoothed profiles of [`SynchronisedMove`].
    pub fn integral(&self, t: f64) -> f64 {
        if self.cruise == 0.0 || t <= 0.0 {
            let held = if self.cruise == 0.0 {
                self.to
            } else {
                self.from
            };
            return held * t;
        }
        let s = (self.to - self.from).signum();
        let total = (self.to - self.from).abs();
        let v = self.cruise;
        let (ta, td) = (v / self.accel, v / self.decel);
        let t2 = self.duration - td;
        // Distance covered (unsigned) integrated over each phase, up to `t`.
        let up = |t: f64| self.accel * t * t * t / 6.0;
        let cruise = |t: f64| 0.5 * v * ta * (t - ta) + 0.5 * v * (t - ta) * (t - ta);
        let down = |t: f64| {
            let (r2, r) = (td, self.duration - t);
            total * (t - t2) - 0.5 * self.decel * (r2 * r2 * r2 - r * r * r) / 3.0
        };
        let distance = if t < ta {
            up(t)
        } else if t <= t2 {
            up(ta) + cruise(t)
        } else if t < self.duration {
            up(ta) + cruise(t2) + down(t)
        } else {
            up(ta) + cruise(t2) + down(self.duration) + total * (t - self.duration)
        };
        self.from * t + s * distance
    }
}

/// The shortest time in which a joint covers `distance` from rest to rest with at most
/// `max_velocity` and `max_acceleration` (both as deceleration): a triangle when the
/// distance is too short to reach the speed, a trapezoid otherwise. Infinite unless both
/// limits are positive.
///
/// ```
/// use jaus::stock::manipulator::profile::shortest_time;
/// // 1 rad at 1 rad/s and 2 rad/s²: 0.5 s up, 0.5 s cruise, 0.5 s down.
/// assert!((shortest_time(1.0, 1.0, 2.0) - 1.5).abs() < 1e-12);
/// // 0.1 rad: a triangle of 2·√(0.1/2) s.
/// assert!((shortest_time(0.1, 1.0, 2.0) - 2.0 * 0.05f64.sqrt()).abs() < 1e-12);
/// ```
pub fn shortest_time(distance: f64, max_velocity: f64, max_acceleration: f64) -> f64 {
    let (d, v, a) = (distance.abs(), max_velocity.abs(), max_acceleration.abs());
    if !(v > 0.0 && a > 0.0 && v.is_finite() && a.is_finite() && d.is_finite()) {
        return f64::INFINITY;
    }
    if d * a >= v * v {
        d / v + v / a
    } else {
        2.0 * (d / a).sqrt()
    }
}

/// One joint set of a joint move: when it is to be reached (s after the start of the
/// move) and, per joint, its position and limits.
#[derive(Debug, Clone, PartialEq)]
pub struct JointSet {
    /// Time relative to the start of the move, s.
    pub time: f64,
    /// Per joint: (position, max velocity, max acceleration, max deceleration).
    pub joints: Vec<(f64, f64, f64, f64)>,
}

/// A joint move: per segment between successive joint sets, one [`Trapezoid`] per joint,
/// optionally smoothed ([`smoothed`](Self::smoothed)).
#[derive(Debug, Clone, PartialEq)]
pub struct JointMove {
    /// Segments: (start time, end time, profile per joint).
    segments: Vec<(f64, f64, Vec<Trapezoid>)>,
    start: Vec<f64>,
    smoothing: f64,
}

impl JointMove {
    /// Plans the move from joint positions `start` through `sets` (their times relative
    /// to the start of the move, strictly increasing, every set with `start.len()`
    /// joints: the caller checks the count).
    pub fn plan(start: &[f64], sets: &[JointSet]) -> Result<JointMove, ProfileError> {
        let mut from = start.to_vec();
        let mut previous = 0.0;
        let mut segments = Vec::with_capacity(sets.len());
        for (pose, set) in sets.iter().enumerate() {
            if !(set.time.is_finite() && set.time > previous) {
                return Err(ProfileError::TimeNotIncreasing {
                    pose,
                    time: set.time,
                    previous,
                });
            }
            let duration = set.time - previous;
            let profiles = set
                .joints
                .iter()
                .zip(&from)
                .enumerate()
                .map(|(j, (&(to, v, a, d), &f))| Trapezoid::timed(j, f, to, duration, v, a, d))
                .collect::<Result<Vec<_>, _>>()?;
            segments.push((previous, set.time, profiles));
            from = set.joints.iter().map(|j| j.0).collect();
            previous = set.time;
        }
        Ok(JointMove {
            segments,
            start: start.to_vec(),
            smoothing: 0.0,
        })
    }

    /// The move with its positions averaged over a window of `window` seconds centred on
    /// each instant (narrower in the first `window / 2` seconds, so the move still starts
    /// from rest where it starts): each joint's acceleration builds up and dies away
    /// instead of stepping (its jerk is limited), each set is still passed at its time
    /// (within `a·window²/24` where a joint turns back), the reference never goes past
    /// the last set, and the move ends `window / 2` after the last set's time.
    pub fn smoothed(mut self, window: f64) -> JointMove {
        self.smoothing = if window.is_finite() {
            window.max(0.0)
        } else {
            0.0
        };
        self
    }

    /// The integral of joint `j`'s unsmoothed position from 0 to `t`.
    fn integral(&self, j: usize, t: f64) -> f64 {
        let first = self.start.get(j).copied().unwrap_or(0.0);
        if t <= 0.0 {
            return first * t;
        }
        let mut sum = 0.0;
        let mut end = (0.0, first);
        for (t0, t1, profiles) in &self.segments {
            let Some(p) = profiles.get(j) else {
                return sum;
            };
            if t <= *t0 {
                return sum;
            }
            sum += p.integral(t.min(*t1) - t0);
            end = (*t1, p.to);
        }
        if t > end.0 {
            sum += end.1 * (t - end.0);
        }
        sum
    }

    fn sample_raw(&self, t: f64, q: &mut [f64], qd: &mut [f64]) {
        let seg = self
            .segments
            .iter()
            .find(|s| t < s.1)
            .or(self.segments.last());
        match seg {
            Some((t0, _, profiles)) => {
                for (j, p) in profiles.iter().enumerate() {
                    let (x, v) = p.sample(t - t0);
                    q[j] = x;
                    qd[j] = v;
                }
            }
            None => {
                q.copy_from_slice(&self.start);
                qd.iter_mut().for_each(|v| *v = 0.0);
            }
        }
    }

    /// Total duration (with the smoothing's half window), s.
    pub fn duration(&self) -> f64 {
        self.segments.last().map_or(0.0, |s| s.1) + self.smoothing / 2.0
    }

    /// Desired positions and velocities `t` s after the start, into `q` and `qd`.
    pub fn sample(&self, t: f64, q: &mut [f64], qd: &mut [f64]) {
        let half = (self.smoothing / 2.0).min(t);
        if half <= 0.0 || t >= self.duration() {
            self.sample_raw(t, q, qd);
            return;
        }
        let n = q.len().min(qd.len());
        let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
        let mut v = vec![0.0; n];
        self.sample_raw(t - half, &mut a, &mut v);
        self.sample_raw(t + half, &mut b, &mut v);
        for j in 0..n {
            q[j] = (self.integral(j, t + half) - self.integral(j, t - half)) / (2.0 * half);
            qd[j] = (b[j] - a[j]) / (2.0 * half);
        }
    }
}

/// A rest-to-rest, jerk-limited move from joint positions to a target on which every
/// joint arrives at the same time (the Joint Positions and End-Effector Pose Drivers'
/// profile). Each joint runs a [`Trapezoid`] over the time the slowest joint needs
/// within its limits (at the lowest cruise speed that arrives on time), and its position
/// is averaged over a sliding window of `smoothing` seconds: the acceleration then builds
/// up and dies away over that time instead of stepping (the jerk is limited), the speed
/// and acceleration stay within the trapezoid's, the reference never passes the target,
/// and the move lasts `smoothing` longer. A servo without acceleration feed-forward
/// (which needs the arm's inertia) lags a step of deceleration by a position error that
/// it carries past the target; a deceleration that dies away leaves it none.
#[derive(Debug, Clone, PartialEq)]
pub struct SynchronisedMove {
    profiles: Vec<Trapezoid>,
    smoothing: f64,
}

impl SynchronisedMove {
    /// From `start` to `target` (one entry per joint), `limits(j)` giving joint `j`'s
    /// (max velocity, max acceleration), the acceleration also its deceleration; the
    /// position smoothed over `smoothing` seconds (0: a plain trapezoid).
    pub fn plan(
        start: &[f64],
        target: &[f64],
        limits: impl Fn(usize) -> (f64, f64),
        smoothing: f64,
    ) -> Result<SynchronisedMove, ProfileError> {
        let mut duration: f64 = 1e-3;
        for (j, (a, b)) in start.iter().zip(target).enumerate() {
            let (v, acc) = limits(j);
            for (what, value) in [("max_velocity", v), ("max_acceleration", acc)] {
                if !(value.is_finite() && value > 0.0) {
                    return Err(ProfileError::BadLimit {
                        joint: j,
                        what,
                        value,
                    });
                }
            }
            duration = duration.max(shortest_time(b - a, v, acc));
        }
        // A hair longer than the slowest joint needs, so rounding never makes it too fast.
        let time = duration * (1.0 + 1e-6);
        let profiles = start
            .iter()
            .zip(target)
            .enumerate()
            .map(|(j, (&from, &to))| {
                let (v, a) = limits(j);
                Trapezoid::timed(j, from, to, time, v, a, a)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(SynchronisedMove {
            profiles,
            smoothing: if smoothing.is_finite() {
                smoothing.max(0.0)
            } else {
                0.0
            },
        })
    }

    /// Total duration (the trapezoids' and the smoothing), s.
    pub fn duration(&self) -> f64 {
        self.profiles.first().map_or(0.0, Trapezoid::duration) + self.smoothing
    }

    /// Desired positions and velocities `t` s after the start, into `q` and `qd`.
    pub fn sample(&self, t: f64, q: &mut [f64], qd: &mut [f64]) {
        let w = self.smoothing;
        for (j, p) in self.profiles.iter().enumerate() {
            if w > 0.0 {
                q[j] = (p.integral(t) - p.integral(t - w)) / w;
                qd[j] = (p.sample(t).0 - p.sample(t - w).0) / w;
            } else {
                (q[j], qd[j]) = p.sample(t);
            }
            if t >= self.duration() {
                (q[j], qd[j]) = (p.to, 0.0);
            }
        }
    }
}

/// A timed end-effector pose path starting at the pose the arm is in.
#[derive(Debug, Clone, PartialEq)]
pub struct PosePath {
    /// (time s, pose), the first at time 0.
    poses: Vec<(f64, Isometry3<f64>)>,
}

impl PosePath {
    /// From `start` (at time 0) through `poses` (times strictly increasing, after 0).
    pub fn new(
        start: Isometry3<f64>,
        poses: impl IntoIterator<Item = (f64, Isometry3<f64>)>,
    ) -> Result<PosePath, ProfileError> {
        let mut all = vec![(0.0, start)];
        for (i, (t, p)) in poses.into_iter().enumerate() {
            let previous = all.last().map_or(0.0, |x| x.0);
            if !(t.is_finite() && t > previous) {
                return Err(ProfileError::TimeNotIncreasing {
                    pose: i,
                    time: t,
                    previous,
                });
            }
            all.push((t, p));
        }
        Ok(PosePath { poses: all })
    }

    /// The poses after the start, with their times.
    pub fn targets(&self) -> &[(f64, Isometry3<f64>)] {
        &self.poses[1..]
    }

    /// Total duration, s.
    pub fn duration(&self) -> f64 {
        self.poses.last().map_or(0.0, |p| p.0)
    }

    /// The pose at `t` s: linear in position, slerp in orientation (the shorter way),
    /// held at the ends.
    pub fn sample(&self, t: f64) -> Isometry3<f64> {
        let last = self.poses[self.poses.len() - 1];
        if t >= last.0 {
            return last.1;
        }
        if t <= 0.0 {
            return self.poses[0].1;
        }
        let i = self.poses.iter().position(|p| p.0 > t).unwrap_or(1).max(1);
        let (t0, a) = self.poses[i - 1];
        let (t1, b) = self.poses[i];
        let s = (t - t0) / (t1 - t0);
        let p = a.translation.vector.lerp(&b.translation.vector, s);
        let r: UnitQuaternion<f64> = a
            .rotation
            .try_slerp(&b.rotation, s, 1e-9)
            .unwrap_or(if s < 0.5 { a.rotation } else { b.rotation });
        Isometry3::from_parts(Translation3::from(p), r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn a_trapezoid_arrives_on_time_within_its_limits() {
        let p = Trapezoid::timed(0, 0.2, 1.2, 2.0, 1.0, 2.0, 4.0).unwrap();
        // D = 1, T = 2, k = 1/4 + 1/8 = 0.375: v = (2 - sqrt(4 - 1.5)) / 0.75.
        let v = (2.0 - 2.5f64.sqrt()) / 0.75;
        assert!((p.cruise() - v).abs() < 1e-12);
        assert_eq!(p.sample(0.0), (0.2, 0.0));
        assert_eq!(p.sample(2.0), (1.2, 0.0));
        let mut last = 0.2;
        for i in 1..=2000 {
            let (x, vel) = p.sample(i as f64 * 0.001);
            assert!(vel >= -1e-12 && vel <= v + 1e-12, "speed {vel}");
            let acc = (x - last) / 0.001;
            assert!(acc <= v + 1e-3, "discrete speed {acc} at step {i}");
            assert!(x + 1e-12 >= last, "monotonic");
            last = x;
        }
        assert!((last - 1.2).abs() < 1e-12);
        // The profile is continuous at the phase boundaries.
        let (ta, td) = (v / 2.0, v / 4.0);
        for t in [ta, 2.0 - td] {
            let (a, _) = p.sample(t - 1e-9);
            let (b, _) = p.sample(t + 1e-9);
            assert!((a - b).abs() < 1e-6);
        }
    }

    #[test]
    fn a_trapezoid_that_cannot_arrive_in_time_is_refused_with_the_speed_it_needs() {
        let e = Trapezoid::timed(3, 0.0, -2.0, 1.0, 1.0, 10.0, 10.0).unwrap_err();
        assert!(matches!(e, ProfileError::TooFast { joint: 3, .. }), "{e}");
        assert!(e.to_string().contains("joint 3"));
        // Too little acceleration for any speed.
        let e = Trapezoid::timed(0, 0.0, 1.0, 1.0, 100.0, 1.0, 1.0).unwrap_err();
        assert!(matches!(e, ProfileError::TooFast { needed, .. } if needed.is_infinite()));
        let e = Trapezoid::timed(1, 0.0, 1.0, 1.0, f64::NAN, 1.0, 1.0).unwrap_err();
        assert!(matches!(
            e,
            ProfileError::BadLimit {
                joint: 1,
                what: "max_velocity",
                ..
            }
        ));
        let e = Trapezoid::timed(1, 0.0, 1.0, 1.0, 1.0, 0.0, 1.0).unwrap_err();
        assert!(matches!(
            e,
            ProfileError::BadLimit {
                what: "max_acceleration",
                ..
            }
        ));
    }

    #[test]
    fn a_joint_move_passes_each_set_at_its_time() {
        let sets = vec![
            JointSet {
                time: 2.0,
                joints: vec![(1.0, 2.0, 3.0, 3.0), (-0.5, 2.0, 3.0, 3.0)],
            },
            JointSet {
                time: 3.5,
                joints: vec![(0.0, 2.0, 3.0, 3.0), (-0.5, 2.0, 3.0, 3.0)],
            },
        ];
        let m = JointMove::plan(&[0.0, 0.0], &sets).unwrap();
        assert_eq!(m.duration(), 3.5);
        let (mut q, mut qd) = (vec![0.0; 2], vec![0.0; 2]);
        m.sample(2.0, &mut q, &mut qd);
        assert!((q[0] - 1.0).abs() < 1e-9 && (q[1] + 0.5).abs() < 1e-9);
        assert!(qd.iter().all(|v| v.abs() < 1e-9));
        m.sample(1.0, &mut q, &mut qd);
        assert!(q[0] > 0.0 && q[0] < 1.0 && qd[0] > 0.0);
        m.sample(10.0, &mut q, &mut qd);
        assert_eq!(q, vec![0.0, -0.5]);
        let bad = JointMove::plan(
            &[0.0],
            &[
                JointSet {
                    time: 1.0,
                    joints: vec![(0.1, 1.0, 1.0, 1.0)],
                },
                JointSet {
                    time: 1.0,
                    joints: vec![(0.2, 1.0, 1.0, 1.0)],
                },
            ],
        );
        assert!(matches!(
            bad,
            Err(ProfileError::TimeNotIncreasing { pose: 1, .. })
        ));
    }

    #[test]
    fn a_trapezoid_integrates_its_positions() {
        let p = Trapezoid::timed(0, 0.2, 1.2, 2.0, 1.0, 2.0, 4.0).unwrap();
        let mut sum = 0.0;
        let dt = 1e-4;
        for i in 0..30_000 {
            let t = (i as f64 + 0.5) * dt;
            sum += p.sample(t).0 * dt;
            if i % 1000 == 999 {
                let exact = p.integral((i + 1) as f64 * dt);
                assert!(
                    (sum - exact).abs() < 1e-6,
                    "at {} s: {sum} vs {exact}",
                    (i + 1) as f64 * dt
                );
            }
        }
        assert!((p.integral(-1.0) + 0.2).abs() < 1e-12);
    }

    #[test]
    fn a_synchronised_move_brings_every_joint_to_rest_on_the_target_together() {
        for smoothing in [0.0, 0.2] {
            synchronised(smoothing);
        }
    }

    fn synchronised(smoothing: f64) {
        let start = [0.0, 1.0, -0.5];
        let target = [1.0, 0.9, 0.5];
        let limits = |j: usize| [(1.0, 2.0), (1.0, 2.0), (0.5, 1.0)][j];
        let m = SynchronisedMove::plan(&start, &target, limits, smoothing).unwrap();
        // Joint 2 is the slowest: 1 rad at 0.5 rad/s and 1 rad/s² takes 2.5 s.
        assert!(
            (m.duration() - 2.5 - smoothing).abs() < 1e-5,
            "{}",
            m.duration()
        );
        let (mut q, mut qd) = (vec![0.0; 3], vec![0.0; 3]);
        let dt = 0.001;
        let mut previous = start.to_vec();
        let mut speed = [0.0f64; 3];
        let steps = (m.duration() / dt).ceil() as usize + 10;
        for i in 1..=steps {
            m.sample(i as f64 * dt, &mut q, &mut qd);
            for j in 0..3 {
                let (v, a) = limits(j);
                let s = (q[j] - previous[j]) / dt;
                assert!(s.abs() <= v + 1e-6, "joint {j} speed {s}");
                assert!(
                    (s - speed[j]).abs() / dt <= a + 1e-3,
                    "joint {j} acceleration"
                );
                // Never past the target (no overshoot in the reference).
                let overshoot = (q[j] - target[j]) * (target[j] - start[j]).signum();
                assert!(
                    overshoot <= 1e-12,
                    "joint {j} passes its target by {overshoot}"
                );
                speed[j] = s;
            }
            previous.copy_from_slice(&q);
        }
        assert_eq!(q, target.to_vec());
        assert!(qd.iter().all(|v| *v == 0.0));
        // Half way, every joint is half way (the same profile shape, scaled).
        m.sample(m.duration() / 2.0, &mut q, &mut qd);
        for j in 0..3 {
            let half = (start[j] + target[j]) / 2.0;
            assert!((q[j] - half).abs() < 1e-6, "joint {j}: {} vs {half}", q[j]);
        }
        assert!(SynchronisedMove::plan(&[0.0], &[1.0], |_| (0.0, 1.0), smoothing).is_err());
        // Nothing to do: a short move that stays put.
        let still = SynchronisedMove::plan(&[0.3], &[0.3], |_| (1.0, 1.0), smoothing).unwrap();
        still.sample(0.0, &mut q[..1], &mut qd[..1]);
        assert_eq!(q[0], 0.3);
    }

    #[test]
    fn a_smoothed_joint_move_starts_at_rest_and_passes_its_sets_on_time() {
        let sets = vec![
            JointSet {
                time: 2.0,
                joints: vec![(1.0, 2.0, 3.0, 3.0)],
            },
            JointSet {
                time: 3.5,
                joints: vec![(0.0, 2.0, 3.0, 3.0)],
            },
        ];
        let m = JointMove::plan(&[0.0], &sets).unwrap().smoothed(0.3);
        assert!((m.duration() - 3.65).abs() < 1e-12);
        let (mut q, mut qd) = ([0.0], [0.0]);
        m.sample(0.0, &mut q, &mut qd);
        assert_eq!((q[0], qd[0]), (0.0, 0.0));
        m.sample(2.0, &mut q, &mut qd);
        // Turning back at the set: within a·w²/24 = 3·0.09/24.
        assert!((q[0] - 1.0).abs() <= 3.0 * 0.09 / 24.0 + 1e-9, "{q:?}");
        let mut last = 0.0;
        for i in 1..4000 {
            m.sample(i as f64 * 0.001, &mut q, &mut qd);
            assert!(q[0] <= 1.0 + 1e-12 && q[0] >= -1e-12, "{q:?} at {i} ms");
            let speed = (q[0] - last) / 0.001;
            assert!(speed.abs() <= 2.0 + 1e-6, "{speed} at {i} ms");
            last = q[0];
        }
        assert_eq!(q[0], 0.0);
    }

    #[test]
    fn a_pose_path_interpolates_position_and_orientation() {
        let a = Isometry3::identity();
        let b = Isometry3::from_parts(
            Translation3::new(1.0, 2.0, 0.0),
            UnitQuaternion::from_euler_angles(0.0, 0.0, 1.0),
        );
        let path = PosePath::new(a, [(2.0, b)]).unwrap();
        let mid = path.sample(1.0);
        assert!((mid.translation.vector - Vector3::new(0.5, 1.0, 0.0)).norm() < 1e-12);
        assert!((mid.rotation.euler_angles().2 - 0.5).abs() < 1e-12);
        assert_eq!(path.sample(5.0), b);
        assert_eq!(path.sample(-1.0), a);
        assert!(PosePath::new(a, [(0.0, b)]).is_err());
        assert!(PosePath::new(a, [(1.0, b), (f64::NAN, b)]).is_err());
    }
}
