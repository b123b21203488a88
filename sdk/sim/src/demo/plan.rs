//! The obstacle round's plan: objects found by the range sensor merged, and a route
//! that passes them with the demo's clearance.

use nalgebra::Vector2;

use super::*;

/// An object the world model returned.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Found {
    pub(super) centre: Vector2<f64>,
    pub(super) buffer: f64,
    /// Stored by the operator (else detected by the range sensor).
    pub(super) operator: bool,
}

/// One object for each group of overlapping ones (the range sensor also detects the
/// obstacle the operator stored): the one with the largest buffer, the operator's
/// flag if either was the operator's.
pub(super) fn merge_overlapping(objects: Vec<Found>) -> Vec<Found> {
    let mut out: Vec<Found> = Vec::new();
    for o in objects {
        match out
            .iter_mut()
            .find(|k| (k.centre - o.centre).norm() < k.buffer.max(o.buffer))
        {
            Some(k) => {
                let operator = k.operator || o.operator;
                if o.buffer > k.buffer {
                    *k = o;
                }
                k.operator = operator;
            }
            None => out.push(o),
        }
    }
    out
}

/// The moves of `route` (its first point is where the vehicle is) with a detour
/// waypoint before each leg's end for every object within its buffer plus
/// [`CLEARANCE`] of that leg, in the order the leg meets them.
pub(super) fn plan_round(route: &[Vector2<f64>], objects: &[Found]) -> Vec<(f64, f64)> {
    let mut plan = Vec::new();
    for leg in route.windows(2) {
        let (from, to) = (leg[0], leg[1]);
        let Some(dir) = (to - from).try_normalize(1e-9) else {
            plan.push((to.x, to.y));
            continue;
        };
        let mut on_leg: Vec<(f64, (f64, f64))> = objects
            .iter()
            .filter_map(|o| {
                let along = (o.centre - from).dot(&dir).clamp(0.0, (to - from).norm());
                let off = (o.centre - (from + dir * along)).norm();
                (off < o.buffer + CLEARANCE).then(|| (along, detour(from, to, o.centre, o.buffer)))
            })
            .collect();
        on_leg.sort_by(|a, b| a.0.total_cmp(&b.0));
        plan.extend(on_leg.into_iter().map(|(_, p)| p));
        plan.push((to.x, to.y));
    }
    plan
}

/// A waypoint that takes the leg `from` → `to` round an obstacle at `c` with buffer `r`:
/// beside the obstacle's projection on the leg, `r` + [`CLEARANCE`] + a margin for the
/// corner the vehicle cuts, on the side the obstacle leaves free.
pub(super) fn detour(from: Vector2<f64>, to: Vector2<f64>, c: Vector2<f64>, r: f64) -> (f64, f64) {
    let d = (to - from)
        .try_normalize(1e-9)
        .unwrap_or(Vector2::new(1.0, 0.0));
    let along = (c - from).dot(&d).clamp(0.0, (to - from).norm());
    let foot = from + d * along;
    let mut n = Vector2::new(-d.y, d.x);
    if (c - foot).dot(&n) > 0.0 {
        n = -n;
    }
    let p = c + n * (r + CLEARANCE + 0.3) - (c - foot);
    (p.x, p.y)
}
