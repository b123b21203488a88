//! The arm demo's report for people (`jaus demo --arm`): a table of the moves and an SVG
//! plot (plotters) of the joint angles over time and the tool path seen from above and
//! from the side.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use jaus::stock::nalgebra::Vector3;
use jaus_sim::arm_demo::ArmReport;
use plotters::prelude::*;

use crate::plot::{self, Swatch};

/// The table: per move, the driver, when it started, the time from command to settled,
/// the final error of the true tool pose against the commanded one, then how far the
/// joints left their held positions while the arm passed to the move's driver
/// (`hand-over`, none when the same driver carried on) and how far they went past where
/// the move left them (`overshoot`), in degrees.
pub fn summary(r: &ArmReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<40} {:>11} {:>8} {:>8} {:>10} {:>8}",
        "move", "driver", "start s", "time s", "error mm", "error °"
    );
    for m in &r.moves {
        let handover = m
            .handover_deg
            .map_or_else(|| "—, same driver".to_string(), |d| format!("{d:.2}°"));
        let _ = writeln!(
            s,
            "{:<40} {:>11} {:>8.2} {:>8.2} {:>10.3} {:>8.3}   hand-over {handover}, overshoot {:.2}°",
            m.name,
            m.driver.to_string(),
            m.start,
            m.seconds,
            m.position_error_mm,
            m.angle_error_deg,
            m.overshoot_deg
        );
    }
    if let Some((rms, max)) = r.jog_tracking {
        let _ = writeln!(
            s,
            "jog velocity tracking (tool point, steady part): RMS error {:.1} mm/s, largest {:.1} mm/s of {:.0} mm/s commanded",
            rms * 1000.0,
            max * 1000.0,
            jaus_sim::arm_demo::JOG.0.iter().map(|v| v * v).sum::<f64>().sqrt() * 1000.0
        );
    }
    let _ = write!(
        s,
        "{} moves in {:.1} s of simulated time, {} messages on the bus (the jog is open loop on its end point: its error is against the commanded displacement)",
        r.moves.len(),
        r.duration,
        r.messages
    );
    s
}

/// Writes `arm.svg` of `report` into `dir` (created if missing) and returns its path.
pub fn write_svg(report: &ArmReport, dir: &Path) -> std::io::Result<PathBuf> {
    std::fs::create_dir_all(dir)?;
    let path = dir.join("arm.svg");
    std::fs::write(&path, svg(report)?)?;
    Ok(path)
}

/// Canvas, column and panel sizes of the arm plot (pixels).
const WIDTH: u32 = 1240;
const HEIGHT: u32 = 760;
const JOINT_COLUMN: u32 = 720;
const TITLE: u32 = 30;
const LEFT: u32 = 62;
const BOTTOM: u32 = 48;
const MARGIN: u32 = 10;
const LEGEND: u32 = 110;

/// One colour per joint.
const JOINT_COLOURS: [RGBColor; 6] = [
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0xff, 0x7f, 0x0e),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0x8c, 0x56, 0x4b),
];
const TOOL_PATH: RGBColor = RGBColor(0x11, 0x7a, 0x8b);
/// The marks where moves start.
const MOVE_MARK: RGBColor = RGBColor(0xa0, 0xa0, 0xa0);

/// The joint names of the legend.
const JOINT_NAMES: [&str; 6] = [
    "joint 1", "joint 2", "joint 3", "joint 4", "joint 5", "joint 6",
];

/// The SVG plot: on the left the six joint angles (degrees) over time from 0 s, one
/// trace per joint, a thin grey line numbered 1, 2, … where each move starts (is
/// commanded); on the right the tool path from above (y right, x up: the vehicle's
/// forward up the page) and from the side (x right, height = −z up), one metre the same
/// length on both axes, the commanded targets circled. Legends are below the panels.
///
/// The joint traces are the simulated arm's true angles every 50 ms, one polyline per
/// joint over the whole run (the angles are not wrapped: the joints stay within ±3 rad).
/// Between moves the traces are flat: when a driver goes to Standby the Primitive
/// Manipulator's holding controller keeps the arm where the move left it (gravity
/// compensated) until the next driver, which starts from the efforts it finds, takes
/// over (default seed, sampled every 10 ms: no joint moves more than 0.03° at a
/// hand-over, where it used to sag 7 to 11° for 0.13 s). Each move ends by slowing into
/// its target on a jerk-limited profile: no joint passes where the move leaves it by
/// more than 0.4° (the pose driver's constant-rate ramp used to overshoot by 3.4 to
/// 4.1°).
pub fn svg(r: &ArmReport) -> std::io::Result<String> {
    let deg: Vec<(f64, Vec<f64>)> = r
        .joints
        .iter()
        .map(|(t, q)| (*t, q.iter().map(|v| v.to_degrees()).collect()))
        .collect();
    let n = deg.iter().map(|(_, q)| q.len()).max().unwrap_or(0);
    let t_end = deg
        .last()
        .map_or(r.duration, |(t, _)| t.max(r.duration))
        .max(1e-3);
    let angles = plot::Bounds::of(deg.iter().flat_map(|(t, q)| q.iter().map(|v| (*t, *v))));
    let above = |p: &Vector3<f64>| (p.y, p.x);
    let side = |p: &Vector3<f64>| (p.x, -p.z);
    plot::render("arm.svg", (WIDTH, HEIGHT), |root| {
        let (left, right) = root.split_horizontally(JOINT_COLUMN);
        let (panel, legend) = left.split_vertically(HEIGHT - LEGEND);
        let panel = titled(&panel, "joint angles (the arm's true angles, every 50 ms)")?;
        let mut chart = ChartBuilder::on(&panel)
            .margin(MARGIN)
            .y_label_area_size(LEFT)
            .x_label_area_size(BOTTOM)
            .build_cartesian_2d(
                0.0..t_end,
                plot::padded(angles.lo.1, angles.hi.1, 0.05, 1.0),
            )?;
        chart
            .configure_mesh()
            .x_labels(12)
            .y_labels(12)
            .bold_line_style(plot::GRID)
            .light_line_style(TRANSPARENT)
            .x_desc("time (s)")
            .y_desc("joint angle (°)")
            .x_label_formatter(&plot::tick)
            .y_label_formatter(&plot::tick)
            .label_style(plot::text(12.0, &plot::INK))
            .axis_desc_style(plot::text(13.0, &plot::INK))
            .draw()?;
        // Where each move starts: thin rectangles (not lines, so the traces stay the
        // joints'), numbered at the top.
        let y_top = chart.y_range().end;
        let y_bottom = chart.y_range().start;
        let width = t_end * 0.0015;
        chart.draw_series(r.moves.iter().map(|m| {
            Rectangle::new(
                [(m.start, y_bottom), (m.start + width, y_top)],
                MOVE_MARK.filled(),
            )
        }))?;
        chart.draw_series(r.moves.iter().enumerate().map(|(i, m)| {
            Text::new(
                format!("{}", i + 1),
                (m.start + width * 2.0, y_top),
                plot::text_left(11.0, &plot::INK),
            )
        }))?;
        for j in 0..n {
            chart.draw_series(LineSeries::new(
                deg.iter().filter_map(|(t, q)| q.get(j).map(|v| (*t, *v))),
                JOINT_COLOURS[j % JOINT_COLOURS.len()].stroke_width(2),
            ))?;
        }
        let entries: Vec<(Swatch, &str)> = (0..n)
            .map(|j| {
                (
                    Swatch::Line(JOINT_COLOURS[j % JOINT_COLOURS.len()].to_rgba(), 3),
                    JOINT_NAMES.get(j).copied().unwrap_or("joint"),
                )
            })
            .collect();
        plot::legend(
            &legend,
            ((MARGIN + LEFT) as i32, 14),
            6,
            (104, 24),
            &entries,
        )?;
        for (i, line) in [
            "Grey lines: where moves 1, 2, … of the table start. Between drivers the Primitive",
            "Manipulator holds the arm still; every move slows into its target.",
        ]
        .iter()
        .enumerate()
        {
            legend.draw(&Text::new(
                *line,
                ((MARGIN + LEFT) as i32, 50 + 18 * i as i32),
                plot::text_left(12.0, &plot::INK),
            ))?;
        }

        let (views, legend) = right.split_vertically(HEIGHT - LEGEND);
        let (top, bottom) = views.split_vertically((HEIGHT - LEGEND) * 11 / 20);
        let views = [
            (
                top,
                "tool path from above",
                "y, right (m)",
                "x, forward (m)",
                &above as &dyn Fn(&Vector3<f64>) -> (f64, f64),
            ),
            (
                bottom,
                "tool path from the side",
                "x, forward (m)",
                "height, −z (m)",
                &side,
            ),
        ];
        for (area, title, x_desc, y_desc, project) in views {
            let area = titled(&area, title)?;
            let b = plot::Bounds::of(
                r.tool
                    .iter()
                    .map(|(_, p)| project(p))
                    .chain(r.targets.iter().map(project)),
            );
            let (xs, ys) =
                plot::equal_aspect(b, 0.06, plot::plot_size(&area, MARGIN, LEFT, BOTTOM));
            let mut chart = ChartBuilder::on(&area)
                .margin(MARGIN)
                .y_label_area_size(LEFT)
                .x_label_area_size(BOTTOM)
                .build_cartesian_2d(xs, ys)?;
            chart
                .configure_mesh()
                .x_labels(8)
                .y_labels(8)
                .bold_line_style(plot::GRID)
                .light_line_style(TRANSPARENT)
                .x_desc(x_desc)
                .y_desc(y_desc)
                .x_label_formatter(&plot::tick)
                .y_label_formatter(&plot::tick)
                .label_style(plot::text(12.0, &plot::INK))
                .axis_desc_style(plot::text(13.0, &plot::INK))
                .draw()?;
            chart.draw_series(LineSeries::new(
                r.tool.iter().map(|(_, p)| project(p)),
                TOOL_PATH.stroke_width(2),
            ))?;
            for p in &r.targets {
                Swatch::Ring(BLACK).draw(chart.plotting_area(), project(p))?;
            }
        }
        plot::legend(
            &legend,
            ((MARGIN + LEFT) as i32, 14),
            2,
            (200, 24),
            &[
                (Swatch::Line(TOOL_PATH.to_rgba(), 3), "tool point (true)"),
                (Swatch::Ring(BLACK), "commanded target"),
            ],
        )?;
        legend.draw(&Text::new(
            "1 m is the same length on both axes of a view",
            ((MARGIN + LEFT) as i32, 50),
            plot::text_left(12.0, &plot::INK),
        ))?;
        Ok(())
    })
}

/// `area` below a title line, the area left for the chart.
fn titled<'a>(
    area: &plot::Area<'a>,
    title: &str,
) -> Result<plot::Area<'a>, Box<dyn std::error::Error>> {
    let (head, rest) = area.split_vertically(TITLE);
    head.draw(&Text::new(
        title.to_string(),
        ((MARGIN + LEFT) as i32, (TITLE / 2 + 4) as i32),
        plot::text_left(15.0, &plot::INK),
    ))?;
    Ok(rest)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_empty_run_still_draws_its_axes() {
        let svg = svg(&ArmReport::default()).unwrap();
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        for label in ["time (s)", "joint angle (°)", "tool path from above"] {
            assert!(svg.contains(label), "{label}");
        }
    }
}
