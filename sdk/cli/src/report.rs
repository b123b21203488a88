//! The demo's report for people: a table of the legs and an SVG plot (plotters) of the
//! commanded paths against the driven trajectory.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use jaus::stock::nalgebra::Vector2;
use jaus_sim::demo::{Report, OBSTACLE, SEGMENTS, UNKNOWN_OBSTACLE, WAYPOINTS};
use plotters::prelude::*;

use crate::plot::{self, Bounds, Swatch};

/// Writes `demo.svg` of `report` into `dir` (created if missing) and returns its path.
pub fn write_svg(report: &Report, dir: &Path) -> std::io::Result<PathBuf> {
    std::fs::create_dir_all(dir)?;
    let path = dir.join("demo.svg");
    std::fs::write(&path, svg(report)?)?;
    Ok(path)
}

/// Writes the image the operator received from the Visual Sensor into `dir` as
/// `camera.png` (or `.ppm`, by its format), with a line saying what it is; `None`
/// when there is none.
pub fn write_image(report: &Report, dir: &Path) -> std::io::Result<Option<(PathBuf, String)>> {
    let Some(img) = &report.image else {
        return Ok(None);
    };
    let ext = match img.video_format {
        jaus::messages::ImageFormat::Png => "png",
        jaus::messages::ImageFormat::Ppm => "ppm",
        _ => "bin",
    };
    std::fs::create_dir_all(dir)?;
    let path = dir.join(format!("camera.{ext}"));
    std::fs::write(&path, &img.data)?;
    let what = format!(
        "{:?}, {} bytes, camera {} of the Visual Sensor 1.1.37.1",
        img.video_format,
        img.data.len(),
        img.camera_id
    );
    Ok(Some((path, what)))
}

/// Pixels per metre of the trajectory plot, the same on both axes (less when the data
/// would not fit in [`MAX_PLOT`]).
const SCALE: f64 = 40.0;
/// The largest side of the plotting area, pixels.
const MAX_PLOT: f64 = 1600.0;
/// Room for the title, the y tick labels and axis label, the x ones, the margins and
/// the legend (pixels).
const TITLE: u32 = 40;
const LEFT: u32 = 60;
const BOTTOM: u32 = 50;
const PAD: u32 = 12;
const LEGEND: u32 = 390;

const WAYPOINT_LEG: RGBColor = RGBColor(0x1f, 0x5f, 0xbf);
const PATH_LEG: RGBColor = RGBColor(0x8e, 0x44, 0xad);
const MISSION_LEG: RGBColor = RGBColor(0x16, 0x9c, 0x8c);
const DRIVEN: RGBColor = RGBColor(0xd6, 0x27, 0x28);
const CONTROL: RGBColor = RGBColor(0x55, 0x55, 0x55);
const START: RGBColor = RGBColor(0x2c, 0xa0, 0x2c);
const STORED: RGBColor = RGBColor(0x99, 0x99, 0x99);
const SENSED: RGBColor = RGBColor(0xe8, 0x9a, 0x2e);

/// The SVG plot: the commanded paths (waypoint legs, Part 1 path segments and the
/// mission's planned moves, each kind in its colour, waypoints and control points
/// marked) and the driven trajectory, with the obstacles, start and end, on a 1 m grid
/// (coarser if the data spans more than 40 m) in the demo's local frame: x (north) up, y (east) to the right, one metre the same
/// length on both axes; the legend is beside the plot.
pub fn svg(r: &Report) -> std::io::Result<String> {
    // Plotted as (east, north): the chart's horizontal axis is the frame's y.
    let en = |p: &Vector2<f64>| (p.y, p.x);
    let controls: Vec<((f64, f64), bool)> = SEGMENTS
        .iter()
        .flat_map(|((x1, y1), (x2, y2), _)| [((*y1, *x1), true), ((*y2, *x2), false)])
        .collect();
    let obstacles = [
        (OBSTACLE, STORED, "obstacle (stored in the world model)"),
        (
            UNKNOWN_OBSTACLE,
            SENSED,
            "obstacle (found by the range sensor)",
        ),
    ];
    let b = Bounds::of(
        r.commanded
            .iter()
            .flatten()
            .chain(&r.trail)
            .map(en)
            .chain(controls.iter().map(|(p, _)| *p))
            .chain(WAYPOINTS.iter().map(|(x, y)| (*y, *x)))
            .chain(
                obstacles
                    .iter()
                    .flat_map(|(((x, y), rad), _, _)| [(y - rad, x - rad), (y + rad, x + rad)]),
            ),
    );
    // Whole metres, at least half a metre clear of the data.
    let (e0, e1) = ((b.lo.0 - 0.5).floor(), (b.hi.0 + 0.5).ceil());
    let (n0, n1) = ((b.lo.1 - 0.5).floor(), (b.hi.1 + 0.5).ceil());
    let scale = SCALE.min(MAX_PLOT / (e1 - e0).max(n1 - n0));
    let plot = (
        ((e1 - e0) * scale).round() as u32,
        ((n1 - n0) * scale).round() as u32,
    );
    // A tick and a grid line every metre at the usual scale; fewer on a larger map.
    let ticks = |span: f64| (span * scale / (SCALE - 1.0)) as usize + 1;
    let size = (
        PAD + LEFT + plot.0 + PAD + LEGEND,
        TITLE + plot.1 + BOTTOM + PAD,
    );
    plot::render("demo.svg", size, |root| {
        let (left, right) = root.split_horizontally(PAD + LEFT + plot.0 + PAD);
        let (title, area) = left.split_vertically(TITLE);
        title.draw(&Text::new(
            "demo: commanded paths and the driven trajectory",
            (PAD as i32, (TITLE / 2) as i32),
            plot::text_left(16.0, &plot::INK),
        ))?;
        let mut chart = ChartBuilder::on(&area)
            .margin_left(PAD)
            .margin_right(PAD)
            .margin_bottom(PAD)
            .y_label_area_size(LEFT)
            .x_label_area_size(BOTTOM)
            .build_cartesian_2d(e0..e1, n0..n1)?;
        chart
            .configure_mesh()
            .x_labels(ticks(e1 - e0))
            .y_labels(ticks(n1 - n0))
            .bold_line_style(plot::GRID)
            .light_line_style(TRANSPARENT)
            .x_desc("y, east (m)")
            .y_desc("x, north (m)")
            .x_label_formatter(&plot::tick)
            .y_label_formatter(&plot::tick)
            .label_style(plot::text(12.0, &plot::INK))
            .axis_desc_style(plot::text(13.0, &plot::INK))
            .draw()?;
        for (((x, y), rad), colour, _) in obstacles {
            let px = (rad * scale).round() as i32;
            chart.draw_series([
                Circle::new((y, x), px, colour.mix(0.35).filled()),
                Circle::new((y, x), px, CONTROL.stroke_width(1)),
            ])?;
        }
        let (wp, ps) = (WAYPOINTS.len(), WAYPOINTS.len() + SEGMENTS.len());
        for (i, leg) in r.commanded.iter().enumerate() {
            let colour = match i {
                i if i < wp => WAYPOINT_LEG,
                i if i < ps => PATH_LEG,
                _ => MISSION_LEG,
            };
            chart.draw_series(LineSeries::new(
                leg.iter().map(en),
                colour.mix(0.55).stroke_width(4),
            ))?;
        }
        chart.draw_series(LineSeries::new(
            r.trail.iter().map(en),
            DRIVEN.stroke_width(2),
        ))?;
        let label = |s: String, dx: i32, dy: i32, colour: &RGBColor| {
            Text::new(s, (dx, dy), plot::text_left(12.0, colour))
        };
        for (i, (x, y)) in WAYPOINTS.iter().enumerate() {
            chart.draw_series([EmptyElement::at((*y, *x))
                + Circle::new((0, 0), 5, WAYPOINT_LEG.filled())
                + label(format!("W{i}"), 7, -9, &plot::INK)])?;
        }
        for (i, (p, control)) in controls.iter().enumerate() {
            let (swatch, dy) = if *control {
                (Swatch::Square(CONTROL), -9)
            } else {
                (Swatch::Dot(CONTROL), 9)
            };
            swatch.draw(chart.plotting_area(), *p)?;
            chart.draw_series([
                EmptyElement::at(*p) + label(format!("P{}", i + 1), 7, dy, &CONTROL)
            ])?;
        }
        if let (Some(first), Some(last)) = (r.trail.first(), r.trail.last()) {
            Swatch::Triangle(START).draw(chart.plotting_area(), en(first))?;
            Swatch::Cross(BLACK).draw(chart.plotting_area(), en(last))?;
        }
        let entries = [
            (
                Swatch::Line(WAYPOINT_LEG.mix(0.55), 4),
                "commanded: waypoint legs",
            ),
            (
                Swatch::Line(PATH_LEG.mix(0.55), 4),
                "commanded: Part 1 path segments",
            ),
            (
                Swatch::Line(MISSION_LEG.mix(0.55), 4),
                "commanded: mission moves (planned)",
            ),
            (Swatch::Line(DRIVEN.to_rgba(), 2), "driven"),
            (Swatch::Dot(WAYPOINT_LEG), "waypoints W0–W4"),
            (Swatch::Square(CONTROL), "path segment control points"),
            (Swatch::Dot(CONTROL), "path segment ends"),
            (Swatch::Triangle(START), "start"),
            (Swatch::Cross(BLACK), "end"),
            (Swatch::Disc(STORED.mix(0.35), CONTROL), obstacles[0].2),
            (Swatch::Disc(SENSED.mix(0.35), CONTROL), obstacles[1].2),
        ];
        let top = (TITLE + 24) as i32;
        plot::legend(&right, (0, top), 1, (0, 26), &entries)?;
        right.draw(&Text::new(
            if scale == SCALE {
                "1 m grid, the same scale on both axes"
            } else {
                "the same scale on both axes"
            },
            (0, top + 26 * entries.len() as i32 + 8),
            plot::text_left(12.0, &plot::INK),
        ))?;
        Ok(())
    })
}

/// The report as text.
pub fn summary(r: &Report) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<16} {:>10} {:>12} {:>12}",
        "leg", "arrival", "xte RMS", "xte max"
    );
    for l in &r.legs {
        let _ = writeln!(
            s,
            "{:<16} {:>10} {:>10.3} m {:>10.3} m",
            l.name,
            l.arrival.map_or("—".to_string(), |t| format!("{t:.1} s")),
            l.xte_rms,
            l.xte_max
        );
    }
    let _ = writeln!(
        s,
        "waypoints: Standby at {}, {:.3} m from the final waypoint",
        r.waypoints_done.map_or("—".into(), |t| format!("{t:.1} s")),
        r.final_errors[0]
    );
    let _ = writeln!(
        s,
        "path segments: Standby at {}, {:.3} m from P4",
        r.path_done.map_or("—".into(), |t| format!("{t:.1} s")),
        r.final_errors[1]
    );
    let _ = writeln!(
        s,
        "spooled mission: finished at {} (payload action seen at {}), {:.3} m from home",
        r.mission_done.map_or("—".into(), |t| format!("{t:.1} s")),
        r.horn_at.map_or("—".into(), |t| format!("{t:.1} s")),
        r.final_errors[2]
    );
    let _ = writeln!(
        s,
        "world model: {} object(s) along the mission stored by the operator, {} detected by the range sensor (1.1.50.1) and stored by it; planned moves {}",
        r.objects_found.0,
        r.objects_found.1,
        r.planned
            .iter()
            .map(|(x, y)| format!("({x:.2}, {y:.2})"))
            .collect::<Vec<_>>()
            .join(" ")
    );
    let _ = writeln!(
        s,
        "  stored obstacle r = {:.1} m at ({:.1}, {:.1}): closest approach {:.2} m from its centre",
        OBSTACLE.1, OBSTACLE.0 .0, OBSTACLE.0 .1, r.obstacle_clearance
    );
    let _ = writeln!(
        s,
        "  obstacle not in the world model beforehand, r = {:.1} m at ({:.1}, {:.1}): closest approach {:.2} m from its centre",
        UNKNOWN_OBSTACLE.1,
        UNKNOWN_OBSTACLE.0 .0,
        UNKNOWN_OBSTACLE.0 .1,
        r.unknown_clearance
    );
    let _ = write!(
        s,
        "{:.1} s simulated, {} messages on the bus",
        r.duration, r.messages
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report(trail: Vec<Vector2<f64>>) -> Report {
        Report {
            legs: Vec::new(),
            waypoints_done: None,
            path_done: None,
            mission_done: None,
            horn_at: None,
            obstacle_clearance: 0.0,
            unknown_clearance: 0.0,
            objects_found: (0, 0),
            planned: Vec::new(),
            image: None,
            final_errors: Vec::new(),
            duration: 0.0,
            messages: 0,
            commanded: Vec::new(),
            trail,
        }
    }

    #[test]
    fn a_run_without_positions_still_draws_its_axes_and_legend() {
        let svg = svg(&report(Vec::new())).unwrap();
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        for label in ["y, east (m)", "x, north (m)", "driven", "W4", "P4"] {
            assert!(svg.contains(label), "{label}");
        }
        // No trajectory, no start or end marker.
        assert!(!svg.contains("stroke=\"#D62728\""), "{svg}");
        assert_eq!(
            svg.matches("<polygon").count(),
            1,
            "the legend's start only: {svg}"
        );
    }

    #[test]
    fn positions_far_away_shrink_the_scale_not_grow_the_plot() {
        let far = vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1e9, -1e9),
            Vector2::new(f64::NAN, 1.0),
        ];
        let svg = svg(&report(far)).unwrap();
        let width: u32 = svg
            .split("width=\"")
            .nth(1)
            .and_then(|w| w.split('"').next())
            .and_then(|w| w.parse().ok())
            .unwrap();
        assert!(width <= 2100, "{width} px wide");
        assert!(svg.contains("the same scale on both axes"));
        assert!(!svg.contains("1 m grid"));
    }
}
