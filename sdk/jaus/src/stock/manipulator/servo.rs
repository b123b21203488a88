//! The joint servo every closed-loop manipulator driver ends in: per joint, a PID on the
//! position error with velocity feedback and feed-forward, giving the effort (percent of
//! the joint's maximum) sent with Set Joint Efforts.

/// Gains of the joint servo, the same for every joint (efforts are in percent, so the
/// gains are per unit of joint motion: %/rad or %/m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ServoGains {
    /// Effort per unit of position error, %/rad.
    pub kp: f64,
    /// Effort per unit of integrated position error, %/(rad·s).
    pub ki: f64,
    /// Effort per unit of velocity error, %/(rad/s).
    pub kd: f64,
    /// Effort per unit of desired velocity (feed-forward against friction), %/(rad/s).
    pub kv: f64,
    /// Largest effort the integral term may hold, % (anti-windup).
    pub integral_limit: f64,
}

/// The defaults, tuned on the simulated 6-axis arm (`jaus_sim::arm`): kp 400 %/rad,
/// ki 1000 %/(rad·s), kd 30 %/(rad/s), kv 2.5 %/(rad/s) (about the simulated joints'
/// viscous friction: a larger feed-forward is carried by the integral term while moving
/// and pushes the arm back once it stops), integral up to 70 %.
///
/// ```
/// let g = jaus::stock::manipulator::servo::ServoGains::default();
/// assert_eq!((g.kp, g.ki, g.kd, g.kv, g.integral_limit), (400.0, 1000.0, 30.0, 2.5, 70.0));
/// ```
impl Default for ServoGains {
    fn default() -> Self {
        Self {
            kp: 400.0,
            ki: 1000.0,
            kd: 30.0,
            kv: 2.5,
            integral_limit: 70.0,
        }
    }
}

/// Per-joint PID state.
#[derive(Debug, Clone, Default)]
pub struct JointServo {
    integral: Vec<f64>,
}

impl JointServo {
    /// Forgets the integral terms (on a new command, a stop, a change of arm).
    pub fn reset(&mut self) {
        self.integral.clear();
    }

    /// Starts the integral terms so that, with no position or velocity error, the servo
    /// gives `efforts` (percent, one per joint; each within the integral limit): the
    /// bumpless start of a servo that takes over an arm someone else was holding.
    pub fn preload(&mut self, gains: &ServoGains, efforts: &[f64]) {
        self.integral = efforts
            .iter()
            .map(|e| {
                if gains.ki > 0.0 && e.is_finite() {
                    e.clamp(-gains.integral_limit, gains.integral_limit) / gains.ki
                } else {
                    0.0
                }
            })
            .collect();
    }

    /// Efforts (percent, clamped to ±100) into `out` that drive the joints from `q`,
    /// `qd` toward `q_ref`, `qd_ref`, over a control period of `dt` seconds. All slices
    /// have one entry per joint.
    #[allow(clippy::too_many_arguments)]
    pub fn efforts(
        &mut self,
        gains: &ServoGains,
        dt: f64,
        q: &[f64],
        qd: &[f64],
        q_ref: &[f64],
        qd_ref: &[f64],
        out: &mut Vec<f64>,
    ) {
        let n = q.len();
        if self.integral.len() != n {
            self.integral = vec![0.0; n];
        }
        out.clear();
        for j in 0..n {
            let e = q_ref[j] - q[j];
            if !(e.is_finite() && qd[j].is_finite() && qd_ref[j].is_finite()) {
                out.push(0.0);
                continue;
            }
            let ie = &mut self.integral[j];
            if gains.ki > 0.0 {
                let limit = gains.integral_limit / gains.ki;
                *ie = (*ie + e * dt).clamp(-limit, limit);
            }
            let u = gains.kp * e
                + gains.ki * *ie
                + gains.kd * (qd_ref[j] - qd[j])
                + gains.kv * qd_ref[j];
            out.push(if u.is_finite() {
                u.clamp(-100.0, 100.0)
            } else {
                0.0
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn efforts_push_toward_the_reference_and_saturate() {
        let mut s = JointServo::default();
        let g = ServoGains::default();
        let mut out = Vec::new();
        s.efforts(
            &g,
            0.01,
            &[0.0, 0.0],
            &[0.0, 0.0],
            &[0.01, -1.0],
            &[0.0, 0.0],
            &mut out,
        );
        assert!(out[0] > 0.0 && out[0] < 100.0);
        assert_eq!(out[1], -100.0);
        // The integral grows while the error persists, within its limit.
        let first = out[0];
        for _ in 0..1000 {
            s.efforts(
                &g,
                0.01,
                &[0.0, 0.0],
                &[0.0, 0.0],
                &[0.01, -1.0],
                &[0.0, 0.0],
                &mut out,
            );
        }
        assert!(out[0] > first);
        assert!(out[0] <= g.kp * 0.01 + g.integral_limit + 1e-9);
        s.efforts(
            &g,
            0.01,
            &[f64::NAN, 0.0],
            &[0.0, 0.0],
            &[0.0, 0.0],
            &[0.0, 0.0],
            &mut out,
        );
        assert_eq!(out[0], 0.0);
        // A bad reading does not poison the integral.
        s.efforts(
            &g,
            0.01,
            &[0.0, 0.0],
            &[0.0, 0.0],
            &[0.01, -1.0],
            &[0.0, 0.0],
            &mut out,
        );
        assert!(out[0] > 0.0);
    }

    #[test]
    fn a_preloaded_servo_starts_from_the_given_efforts() {
        let mut s = JointServo::default();
        let g = ServoGains::default();
        s.preload(&g, &[-30.0, 500.0]);
        let mut out = Vec::new();
        s.efforts(
            &g, 0.01, &[0.0; 2], &[0.0; 2], &[0.0; 2], &[0.0; 2], &mut out,
        );
        assert!((out[0] + 30.0).abs() < 1e-9, "{out:?}");
        // Within the integral limit.
        assert!((out[1] - g.integral_limit).abs() < 1e-9, "{out:?}");
    }
}
