//! The demo's figures: the commanded legs and what the vehicle did on each (cross-track
//! error, arrival), from the operator's trail.

use std::time::Instant;

use nalgebra::{Vector2, Vector3};

use jaus::stock::path::{Path, PathSegment};

use super::*;

/// Legs of the commanded paths: waypoint legs are straight lines from the previous
/// point; path segments are the curves of Part 1.
pub(super) fn commanded_legs(mission: &[(f64, f64)]) -> (Legs, Legs, Legs) {
    let mut wp = Vec::new();
    let mut from = Vector2::new(0.0, 0.0);
    for (i, (x, y)) in WAYPOINTS.iter().enumerate() {
        let to = Vector2::new(*x, *y);
        wp.push((format!("waypoint {i}"), Path::new([from, to])));
        from = to;
    }
    let mut ps = Vec::new();
    let mut p0 = from;
    for (i, (p1, p2, w1)) in SEGMENTS.iter().enumerate() {
        let seg = PathSegment {
            p0: Vector3::new(p0.x, p0.y, 0.0),
            p1: Vector3::new(p1.0, p1.1, 0.0),
            p2: Vector3::new(p2.0, p2.1, 0.0),
            w1: *w1,
        };
        let mut path = Path::default();
        path.push_segment(&seg);
        ps.push((format!("path segment {i}"), path));
        p0 = Vector2::new(p2.0, p2.1);
    }
    let mut ms = Vec::new();
    for (i, (x, y)) in mission.iter().enumerate() {
        let to = Vector2::new(*x, *y);
        ms.push((format!("mission move {i}"), Path::new([p0, to])));
        p0 = to;
    }
    (wp, ps, ms)
}

/// What the run measured, from a trajectory `trail` (seconds since `t0`, local
/// metres): the simulated vehicle's true one in the in-process demo, the positions the
/// operator received in `--ocu-only`.
pub(super) fn measure(
    t0: Instant,
    trail: &[(f64, Vector2<f64>)],
    done_at: [Option<Instant>; 3],
    horn_at: Option<Instant>,
    (planned, objects_found): (&[(f64, f64)], (usize, usize)),
    (duration, messages): (f64, u64),
) -> Report {
    let [wp_done, path_done, mission_done] = done_at;
    let secs = |t: Option<Instant>| t.map(|t| (t - t0).as_secs_f64());
    let (wp_legs, path_legs, mission_legs) = commanded_legs(planned);
    let wp_end = secs(wp_done).unwrap_or(f64::INFINITY);
    let path_end = secs(path_done).unwrap_or(f64::INFINITY);
    let mission_end = secs(mission_done).unwrap_or(f64::INFINITY);
    let mut legs = Vec::new();
    let phases = [
        (&wp_legs, 0.0, wp_end),
        (&path_legs, wp_end, path_end),
        (&mission_legs, path_end, mission_end),
    ];
    for (phase_legs, start, end) in phases {
        // Points of this phase, assigned to the leg they are nearest to, moving forward
        // only (a point near a corner belongs to the leg being driven).
        let pts: Vec<&(f64, Vector2<f64>)> = trail
            .iter()
            .filter(|(t, _)| *t >= start && *t <= end)
            .collect();
        let mut leg = 0usize;
        let mut errs: Vec<Vec<f64>> = vec![Vec::new(); phase_legs.len()];
        let mut arrivals: Vec<Option<f64>> = vec![None; phase_legs.len()];
        for (t, p) in pts {
            while leg + 1 < phase_legs.len() {
                let here = phase_legs[leg].1.project(*p, 0.0, f64::INFINITY);
                let next = phase_legs[leg + 1].1.project(*p, 0.0, f64::INFINITY);
                let end_reached = here.is_some_and(|h| h.s >= phase_legs[leg].1.length() - 0.3);
                match (here, next) {
                    (Some(h), Some(n)) if end_reached && n.distance <= h.distance => {
                        arrivals[leg] = Some(*t);
                        leg += 1;
                    }
                    _ => break,
                }
            }
            if let Some(h) = phase_legs[leg].1.project(*p, 0.0, f64::INFINITY) {
                errs[leg].push(h.distance);
            }
        }
        if end.is_finite() {
            arrivals[phase_legs.len() - 1] = Some(end);
        }
        for (i, (name, _)) in phase_legs.iter().enumerate() {
            let e = &errs[i];
            let rms = if e.is_empty() {
                0.0
            } else {
                (e.iter().map(|x| x * x).sum::<f64>() / e.len() as f64).sqrt()
            };
            legs.push(Leg {
                name: name.clone(),
                arrival: arrivals[i],
                xte_rms: rms,
                xte_max: e.iter().copied().fold(0.0, f64::max),
            });
        }
    }
    let at = |t: f64| {
        trail
            .iter()
            .find(|(s, _)| *s >= t)
            .or(trail.last())
            .map(|(_, p)| *p)
            .unwrap_or_default()
    };
    let clearance = |((ox, oy), _): ((f64, f64), f64)| {
        trail
            .iter()
            .filter(|(t, _)| *t >= path_end && *t <= mission_end)
            .map(|(_, p)| (p - Vector2::new(ox, oy)).norm())
            .fold(f64::INFINITY, f64::min)
    };
    let obstacle_clearance = clearance(OBSTACLE);
    let unknown_clearance = clearance(UNKNOWN_OBSTACLE);
    let final_errors = vec![
        (at(wp_end) - Vector2::new(WAYPOINTS[4].0, WAYPOINTS[4].1)).norm(),
        (at(path_end) - Vector2::new(SEGMENTS[1].1 .0, SEGMENTS[1].1 .1)).norm(),
        (at(mission_end) - Vector2::new(MISSION[1].0, MISSION[1].1)).norm(),
    ];
    let commanded: Vec<Vec<Vector2<f64>>> = wp_legs
        .iter()
        .chain(&path_legs)
        .chain(&mission_legs)
        .map(|(_, p)| p.points().to_vec())
        .collect();
    let trail_points: Vec<Vector2<f64>> = trail.iter().map(|(_, p)| *p).collect();
    Report {
        legs,
        waypoints_done: secs(wp_done),
        path_done: secs(path_done),
        mission_done: secs(mission_done),
        horn_at: secs(horn_at),
        obstacle_clearance,
        unknown_clearance,
        objects_found,
        planned: planned.to_vec(),
        image: None,
        final_errors,
        duration,
        messages,
        commanded,
        trail: trail_points,
    }
}

/// The report of an operator that drove the vehicle over a network (`jaus demo
/// --ocu-only`): measured on the positions it received from the Local Pose Sensor (a
/// 10 Hz service connection), so the errors include the sensor's noise and the link's
/// delay. `None` until the operator is done.
pub fn operator_report(t0: Instant, ocu: &Ocu) -> Option<Report> {
    let o = &ocu.behaviour().0;
    if o.step != Step::Done {
        return None;
    }
    let trail: Vec<(f64, Vector2<f64>)> = o
        .trail
        .iter()
        .map(|(t, p)| ((*t - t0).as_secs_f64(), *p))
        .collect();
    let end = o.trail.last().map_or(0.0, |(t, _)| (*t - t0).as_secs_f64());
    Some(Report {
        image: o.image.clone(),
        ..measure(
            t0,
            &trail,
            [o.waypoints_done, o.path_done, o.mission_done],
            o.horn_at,
            (&o.planned, o.objects_found),
            (end, ocu.stats().received),
        )
    })
}
