//! The demo's report for people: a table of the legs and an SVG of the commanded paths
//! against the driven trajectory.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use jaus::stock::nalgebra::Vector2;
use jaus_sim::demo::{Report, OBSTACLE, SEGMENTS, UNKNOWN_OBSTACLE, WAYPOINTS};

/// Writes `demo.svg` of `report` into `dir` (created if missing) and returns its path.
pub fn write_svg(report: &Report, dir: &Path) -> std::io::Result<PathBuf> {
    std::fs::create_dir_all(dir)?;
    let path = dir.join("demo.svg");
    std::fs::write(&path, svg(report))?;
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

/// An SVG of the commanded paths (blue, waypoints and control points marked) and the
/// driven trajectory (red). x (north) is drawn up, y (east) to the right.
pub fn svg(r: &Report) -> String {
    let controls: Vec<Vector2<f64>> = SEGMENTS
        .iter()
        .flat_map(|(p1, p2, _)| [Vector2::new(p1.0, p1.1), Vector2::new(p2.0, p2.1)])
        .collect();
    let all = r
        .commanded
        .iter()
        .flatten()
        .chain(&r.trail)
        .chain(&controls);
    let (mut lo, mut hi) = (
        Vector2::repeat(f64::INFINITY),
        Vector2::repeat(f64::NEG_INFINITY),
    );
    for p in all {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    let margin = 1.0;
    let scale = 40.0;
    let (w, h) = (
        ((hi.y - lo.y + 2.0 * margin) * scale).max(480.0),
        (hi.x - lo.x + 2.0 * margin) * scale,
    );
    let px = |p: &Vector2<f64>| ((p.y - lo.y + margin) * scale, (hi.x - p.x + margin) * scale);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{:.0}" viewBox="0 0 {w:.0} {:.0}" font-family="sans-serif" font-size="13">"#,
        h + 60.0,
        h + 60.0
    );
    let _ = writeln!(s, r##"<rect width="100%" height="100%" fill="#fff"/>"##);
    // 1 m grid.
    let mut x = lo.x.floor();
    while x <= hi.x.ceil() {
        let (_, yy) = px(&Vector2::new(x, lo.y));
        let _ = writeln!(
            s,
            r##"<line x1="0" y1="{yy:.1}" x2="{w:.0}" y2="{yy:.1}" stroke="#eee"/>"##
        );
        x += 1.0;
    }
    let mut y = lo.y.floor();
    while y <= hi.y.ceil() {
        let (xx, _) = px(&Vector2::new(lo.x, y));
        let _ = writeln!(
            s,
            r##"<line x1="{xx:.1}" y1="0" x2="{xx:.1}" y2="{h:.0}" stroke="#eee"/>"##
        );
        y += 1.0;
    }
    let poly = |pts: &[Vector2<f64>]| {
        pts.iter()
            .map(|p| {
                let (a, b) = px(p);
                format!("{a:.1},{b:.1}")
            })
            .collect::<Vec<_>>()
            .join(" ")
    };
    for c in &r.commanded {
        let _ = writeln!(
            s,
            r##"<polyline points="{}" fill="none" stroke="#1f5fbf" stroke-width="3" stroke-opacity="0.5"/>"##,
            poly(c)
        );
    }
    let _ = writeln!(
        s,
        r##"<polyline points="{}" fill="none" stroke="#d62728" stroke-width="1.5"/>"##,
        poly(&r.trail)
    );
    for (((ox, oy), r), label) in [
        (OBSTACLE, "obstacle (stored in the world model)"),
        (UNKNOWN_OBSTACLE, "obstacle (found by the range sensor)"),
    ] {
        let (a, b) = px(&Vector2::new(ox, oy));
        let _ = writeln!(
            s,
            r##"<circle cx="{a:.1}" cy="{b:.1}" r="{:.1}" fill="#999" fill-opacity="0.35" stroke="#555"/><text x="{:.1}" y="{:.1}" fill="#555">{label}</text>"##,
            r * scale,
            a + r * scale + 4.0,
            b + 4.0
        );
    }
    for (i, (x, y)) in WAYPOINTS.iter().enumerate() {
        let (a, b) = px(&Vector2::new(*x, *y));
        let _ = writeln!(
            s,
            r##"<circle cx="{a:.1}" cy="{b:.1}" r="5" fill="#1f5fbf"/><text x="{:.1}" y="{:.1}">W{i}</text>"##,
            a + 7.0,
            b - 7.0
        );
    }
    for (i, (p1, p2, _)) in SEGMENTS.iter().enumerate() {
        let (a, b) = px(&Vector2::new(p1.0, p1.1));
        let _ = writeln!(
            s,
            r##"<rect x="{:.1}" y="{:.1}" width="8" height="8" fill="none" stroke="#555"/><text x="{:.1}" y="{:.1}" fill="#555">P{}</text>"##,
            a - 4.0,
            b - 4.0,
            a + 7.0,
            b - 7.0,
            2 * i + 1
        );
        let (a, b) = px(&Vector2::new(p2.0, p2.1));
        let _ = writeln!(
            s,
            r##"<circle cx="{a:.1}" cy="{b:.1}" r="4" fill="#555"/><text x="{:.1}" y="{:.1}" fill="#555">P{}</text>"##,
            a + 7.0,
            b + 14.0,
            2 * i + 2
        );
    }
    let _ = writeln!(
        s,
        r##"<text x="10" y="{:.0}"><tspan fill="#1f5fbf">━ commanded: waypoint legs, Part 1 path segments</tspan></text><text x="10" y="{:.0}"><tspan fill="#d62728">━ driven</tspan> (1 m grid; x north up, y east right)</text>"##,
        h + 22.0,
        h + 44.0
    );
    s.push_str("</svg>\n");
    s
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
