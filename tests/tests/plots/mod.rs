//! Reading the demo plots (`demo.svg`, `arm.svg`, drawn with plotters' SVG backend) in
//! tests: their text elements, their data traces and the checks the tests share.
#![allow(dead_code)]

/// One `<text>` element: position, `text-anchor` and content (XML entities as written).
#[derive(Debug, Clone, PartialEq)]
pub struct Text {
    pub x: f64,
    pub y: f64,
    pub anchor: String,
    pub content: String,
}

impl Text {
    /// The content as a number (a tick label), if it is one.
    pub fn number(&self) -> Option<f64> {
        self.content.parse().ok()
    }
}

/// The value of attribute `name` in the attributes `attrs` of one element.
fn attr<'a>(attrs: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = attrs.find(&key)? + key.len();
    attrs[start..].split('"').next()
}

/// The `<text>` elements of `svg`, in order.
pub fn texts(svg: &str) -> Vec<Text> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let (attrs, rest) = t.split_once('>')?;
            let attrs = format!(" {attrs}");
            Some(Text {
                x: attr(&attrs, "x")?.parse().ok()?,
                y: attr(&attrs, "y")?.parse().ok()?,
                anchor: attr(&attrs, "text-anchor").unwrap_or("start").to_string(),
                content: rest.split("</text>").next()?.trim().to_string(),
            })
        })
        .collect()
}

/// The `<polyline>`s of `svg`: (stroke colour, points in pixels).
pub fn polylines(svg: &str) -> Vec<(String, Vec<(f64, f64)>)> {
    svg.split("<polyline")
        .skip(1)
        .filter_map(|p| {
            let attrs = format!(" {}", p.split("/>").next()?);
            let stroke = attr(&attrs, "stroke")?.to_string();
            let points = attr(&attrs, "points")?
                .split_whitespace()
                .filter_map(|xy| {
                    let (x, y) = xy.split_once(',')?;
                    Some((x.parse().ok()?, y.parse().ok()?))
                })
                .collect();
            Some((stroke, points))
        })
        .collect()
}

/// The data traces of `svg`: its `<polyline>`s in a colour other than the axes' and
/// ticks' black.
pub fn traces(svg: &str) -> Vec<(String, Vec<(f64, f64)>)> {
    polylines(svg)
        .into_iter()
        .filter(|(stroke, _)| stroke != "#000000")
        .collect()
}

/// The x of the vertical axis lines (black, longer than 100 pixels) of `svg`, left to
/// right.
pub fn y_axes(svg: &str) -> Vec<f64> {
    let mut xs: Vec<f64> = polylines(svg)
        .into_iter()
        .filter(|(stroke, _)| stroke == "#000000")
        .filter_map(|(_, p)| match p[..] {
            [a, b] if a.0 == b.0 && (a.1 - b.1).abs() > 100.0 => Some(a.0),
            _ => None,
        })
        .collect();
    xs.sort_by(f64::total_cmp);
    xs
}

/// Checks that `svg` is a whole SVG document holding every text of `labels`; returns
/// its text elements.
pub fn check_document(svg: &str, labels: &[&str]) -> Vec<Text> {
    assert!(
        svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"),
        "not a whole SVG document: {}…",
        &svg[..svg.len().min(200)]
    );
    let texts = texts(svg);
    for label in labels {
        assert!(
            texts.iter().any(|t| t.content == *label),
            "no text {label:?} in the plot; texts: {:?}",
            texts.iter().map(|t| &t.content).collect::<Vec<_>>()
        );
    }
    texts
}

/// The tick labels under the axis described by the text `axis` (numbers centred on
/// their tick, on the row just above the description), left to right, among those left
/// of `right_of_panel` pixels.
pub fn x_ticks(texts: &[Text], axis: &str, right_of_panel: f64) -> Vec<(f64, f64)> {
    let desc = texts
        .iter()
        .find(|t| t.content == axis)
        .unwrap_or_else(|| panic!("no axis label {axis:?}"));
    let mut ticks: Vec<(f64, f64)> = texts
        .iter()
        .filter(|t| t.anchor == "middle" && t.y < desc.y && t.y > desc.y - 60.0)
        .filter(|t| t.x < right_of_panel)
        .filter_map(|t| Some((t.x, t.number()?)))
        .collect();
    ticks.sort_by(|a, b| a.0.total_cmp(&b.0));
    ticks
}

/// The demo's trajectory plot: axes in metres, the legend, eleven commanded legs and the
/// driven trajectory, and one metre the same length on both axes.
pub fn check_trajectory_plot(svg: &str) {
    let texts = check_document(
        svg,
        &[
            "y, east (m)",
            "x, north (m)",
            "commanded: waypoint legs",
            "commanded: Part 1 path segments",
            "commanded: mission moves (planned)",
            "driven",
            "start",
            "end",
            "W0",
            "P4",
            "obstacle (stored in the world model)",
            "obstacle (found by the range sensor)",
        ],
    );
    let traces = traces(svg);
    assert_eq!(
        traces.len(),
        12,
        "11 commanded legs + the trajectory: {traces:?}"
    );
    assert!(
        traces.iter().any(|(_, p)| p.len() > 50),
        "no trajectory: {traces:?}"
    );
    // Equal aspect: pixels per metre between the outer tick labels of each axis.
    let east = x_ticks(&texts, "y, east (m)", f64::INFINITY);
    let mut north: Vec<(f64, f64)> = texts
        .iter()
        .filter(|t| t.anchor == "end")
        .filter_map(|t| Some((t.y, t.number()?)))
        .collect();
    north.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert!(east.len() >= 5 && north.len() >= 5, "{east:?} {north:?}");
    let scale = |t: &[(f64, f64)]| {
        let (a, b) = (t[0], t[t.len() - 1]);
        ((b.0 - a.0) / (b.1 - a.1)).abs()
    };
    let (sx, sy) = (scale(&east), scale(&north));
    assert!(
        (sx - sy).abs() / sx < 0.01,
        "{sx:.2} px/m east, {sy:.2} px/m north"
    );
}
