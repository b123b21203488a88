//! The arm demo's report for people (`jaus demo --arm`): a table of the moves and an SVG
//! of the joint angles over time and the tool path seen from above and from the side.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use jaus_sim::arm_demo::ArmReport;

/// The table: per move, the driver, the time from command to settled and the final
/// error of the true tool pose against the commanded one.
pub fn summary(r: &ArmReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<40} {:>11} {:>8} {:>10} {:>8}",
        "move", "driver", "time s", "error mm", "error °"
    );
    for m in &r.moves {
        let _ = writeln!(
            s,
            "{:<40} {:>11} {:>8.2} {:>10.3} {:>8.3}",
            m.name,
            m.driver.to_string(),
            m.seconds,
            m.position_error_mm,
            m.angle_error_deg
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
    std::fs::write(&path, svg(report))?;
    Ok(path)
}

const COLOURS: [&str; 6] = [
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b",
];

/// A panel at (`x0`, `y0`) of `w` × `h` pixels mapping data bounds to pixels.
struct Panel {
    x0: f64,
    y0: f64,
    w: f64,
    h: f64,
    lo: (f64, f64),
    hi: (f64, f64),
}

impl Panel {
    fn new(x0: f64, y0: f64, w: f64, h: f64, points: impl Iterator<Item = (f64, f64)>) -> Self {
        let (mut lo, mut hi) = (
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        for (a, b) in points {
            lo = (lo.0.min(a), lo.1.min(b));
            hi = (hi.0.max(a), hi.1.max(b));
        }
        if !lo.0.is_finite() {
            (lo, hi) = ((0.0, 0.0), (1.0, 1.0));
        }
        // A little room, and never a zero span.
        let pad = |l: f64, h: f64| {
            let m = ((h - l) * 0.05).max(1e-3);
            (l - m, h + m)
        };
        let (l0, h0) = pad(lo.0, hi.0);
        let (l1, h1) = pad(lo.1, hi.1);
        Self {
            x0,
            y0,
            w,
            h,
            lo: (l0, l1),
            hi: (h0, h1),
        }
    }

    fn px(&self, a: f64, b: f64) -> (f64, f64) {
        (
            self.x0 + (a - self.lo.0) / (self.hi.0 - self.lo.0) * self.w,
            self.y0 + self.h - (b - self.lo.1) / (self.hi.1 - self.lo.1) * self.h,
        )
    }

    fn frame(&self, s: &mut String, title: &str, x_label: &str, y_label: &str) {
        let _ = writeln!(
            s,
            r##"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="none" stroke="#999"/>"##,
            self.x0, self.y0, self.w, self.h
        );
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}">{title}</text>"#,
            self.x0,
            self.y0 - 8.0
        );
        let _ = writeln!(
            s,
            r##"<text x="{:.1}" y="{:.1}" fill="#555">{x_label}: {:.2} … {:.2}</text>"##,
            self.x0,
            self.y0 + self.h + 16.0,
            self.lo.0,
            self.hi.0
        );
        let _ = writeln!(
            s,
            r##"<text x="{:.1}" y="{:.1}" fill="#555">{y_label}: {:.2} … {:.2}</text>"##,
            self.x0,
            self.y0 + self.h + 32.0,
            self.lo.1,
            self.hi.1
        );
    }

    fn line(&self, s: &mut String, pts: impl Iterator<Item = (f64, f64)>, colour: &str) {
        let points: Vec<String> = pts
            .map(|(a, b)| {
                let (x, y) = self.px(a, b);
                format!("{x:.1},{y:.1}")
            })
            .collect();
        let _ = writeln!(
            s,
            r##"<polyline points="{}" fill="none" stroke="{colour}" stroke-width="1.5"/>"##,
            points.join(" ")
        );
    }

    fn marks(&self, s: &mut String, pts: impl Iterator<Item = (f64, f64)>) {
        for (a, b) in pts {
            let (x, y) = self.px(a, b);
            let _ = writeln!(
                s,
                r##"<circle cx="{x:.1}" cy="{y:.1}" r="4" fill="none" stroke="#000"/>"##
            );
        }
    }
}

/// The SVG: joint angles (degrees) over time on the left; on the right the tool path
/// from above (y right, x up: the vehicle's forward up the page) and from the side (x
/// right, height up: −z), commanded targets circled.
pub fn svg(r: &ArmReport) -> String {
    let mut s = String::new();
    let (w, h) = (1100.0, 560.0);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="13">"#
    );
    let _ = writeln!(s, r##"<rect width="100%" height="100%" fill="#fff"/>"##);
    let joints = Panel::new(
        40.0,
        40.0,
        560.0,
        440.0,
        r.joints
            .iter()
            .flat_map(|(t, q)| q.iter().map(move |v| (*t, v.to_degrees()))),
    );
    joints.frame(&mut s, "joint angles", "time s", "angle °");
    let n = r.joints.first().map_or(0, |j| j.1.len());
    for j in 0..n {
        joints.line(
            &mut s,
            r.joints.iter().map(|(t, q)| (*t, q[j].to_degrees())),
            COLOURS[j % COLOURS.len()],
        );
        let _ = writeln!(
            s,
            r##"<text x="{:.1}" y="{:.1}" fill="{}">joint {}</text>"##,
            40.0 + 70.0 * j as f64,
            h - 12.0,
            COLOURS[j % COLOURS.len()],
            j + 1
        );
    }
    let top = Panel::new(
        660.0,
        40.0,
        400.0,
        200.0,
        r.tool
            .iter()
            .map(|(_, p)| (p.y, p.x))
            .chain(r.targets.iter().map(|p| (p.y, p.x))),
    );
    top.frame(&mut s, "tool path from above", "y m", "x m");
    top.line(&mut s, r.tool.iter().map(|(_, p)| (p.y, p.x)), "#d62728");
    top.marks(&mut s, r.targets.iter().map(|p| (p.y, p.x)));
    let side = Panel::new(
        660.0,
        300.0,
        400.0,
        180.0,
        r.tool
            .iter()
            .map(|(_, p)| (p.x, -p.z))
            .chain(r.targets.iter().map(|p| (p.x, -p.z))),
    );
    side.frame(&mut s, "tool path from the side", "x m", "height m");
    side.line(&mut s, r.tool.iter().map(|(_, p)| (p.x, -p.z)), "#d62728");
    side.marks(&mut s, r.targets.iter().map(|p| (p.x, -p.z)));
    let _ = writeln!(s, "</svg>");
    s
}
