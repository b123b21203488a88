//! What the arm demo measures of each move on the arm's true joint angles, sampled every
//! control period: how far the joints left where they were held while the arm passed
//! from one driver to the next, and how far they went past where a move left them.

/// A joint that moves less than this over a move's last leg (rad, 0.05°) has no
/// direction of travel to overshoot in.
const STILL: f64 = 0.05 * std::f64::consts::PI / 180.0;

/// The joint angles of `trace` ((s, joints) in time order) sampled nearest to `t`.
pub fn sample_at(trace: &[(f64, Vec<f64>)], t: f64) -> Option<Vec<f64>> {
    trace
        .iter()
        .min_by(|a, b| (a.0 - t).abs().total_cmp(&(b.0 - t).abs()))
        .map(|s| s.1.clone())
}

fn within(trace: &[(f64, Vec<f64>)], from: f64, to: f64) -> impl Iterator<Item = &[f64]> {
    trace
        .iter()
        .filter(move |(t, _)| *t >= from && *t <= to)
        .map(|(_, q)| q.as_slice())
}

/// The largest distance of any joint from `held` over the samples of `trace` from `from`
/// to `to` (inclusive), degrees.
pub fn excursion_deg(trace: &[(f64, Vec<f64>)], from: f64, to: f64, held: &[f64]) -> f64 {
    within(trace, from, to)
        .flat_map(|q| q.iter().zip(held).map(|(a, b)| (a - b).abs()))
        .fold(0.0, f64::max)
        .to_degrees()
}

/// The overshoot of a move's last leg, from `from` (where the joints were at `start`)
/// until `to` (where they were at `end`, the move's final position), degrees: per joint,
/// the largest distance past `end` in the direction the joint travelled over the leg
/// (from `start` toward `end`); the largest over the joints. Over a leg each joint moves
/// one way (a rest-to-rest profile, or a straight tool line that passes no joint
/// extremum), so anything past `end` is overshoot.
pub fn overshoot_deg(
    trace: &[(f64, Vec<f64>)],
    from: f64,
    to: f64,
    start: &[f64],
    end: &[f64],
) -> f64 {
    let mut worst: f64 = 0.0;
    for (j, (&origin, &goal)) in start.iter().zip(end).enumerate() {
        if (goal - origin).abs() < STILL {
            continue;
        }
        let direction = (goal - origin).signum();
        let past = within(trace, from, to)
            .filter_map(|q| q.get(j))
            .map(|v| (v - goal) * direction)
            .fold(0.0, f64::max);
        worst = worst.max(past);
    }
    worst.to_degrees()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn what_passes_the_end_of_a_leg_is_overshoot() {
        // Joint 0 from 0 to 10°, 2° past it and back; joint 1 still.
        let deg = |d: f64| d.to_radians();
        let path = [0.0, 5.0, 9.5, 12.0, 10.5, 10.0];
        let trace: Vec<(f64, Vec<f64>)> = path
            .iter()
            .enumerate()
            .map(|(i, d)| (i as f64 * 0.1, vec![deg(*d), 0.3]))
            .collect();
        let (start, end) = (vec![0.0, 0.3], vec![deg(10.0), 0.3]);
        let o = overshoot_deg(&trace, 0.0, 0.5, &start, &end);
        assert!((o - 2.0).abs() < 1e-9, "{o}");
        // Before 0.3 s it had not passed.
        assert_eq!(overshoot_deg(&trace, 0.0, 0.2, &start, &end), 0.0);
        // The other way round: from 12° down to 10°, nothing passes 10°.
        let back = vec![deg(12.0), 0.3];
        assert_eq!(overshoot_deg(&trace, 0.3, 0.5, &back, &end), 0.0);
        let e = excursion_deg(&trace, 0.0, 0.2, &start);
        assert!((e - 9.5).abs() < 1e-9, "{e}");
        assert_eq!(sample_at(&trace, 0.26).map(|q| q[0]), Some(deg(12.0)));
    }
}
