//! Time series drawn as stacked SVG panels, one per series, sharing the time axis (the
//! soak test's RSS, CPU and latency per second: docs/faults.md). Drawn with the demo
//! plots' helpers (`plot`): text as SVG `<text>`, no font files.

use plotters::prelude::*;

use crate::plot::{self, Area, Drawn};

/// One panel: a named series of (time s, value) points in `unit`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Series {
    /// What is plotted ("RSS").
    pub name: String,
    /// Its unit ("MiB").
    pub unit: String,
    /// (seconds since the start, value); points that are not finite are skipped.
    pub points: Vec<(f64, f64)>,
}

/// Panel height in pixels.
const PANEL: u32 = 200;
/// Width in pixels.
const WIDTH: u32 = 900;
const TITLE: u32 = 36;

/// An SVG of `series`, one panel each under `title`; the error names the plot.
pub fn time_series_svg(title: &str, series: &[Series]) -> std::io::Result<String> {
    let height = TITLE + PANEL * series.len().max(1) as u32;
    let t_end = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.0))
        .filter(|t| t.is_finite())
        .fold(1.0_f64, f64::max);
    plot::render(title, (WIDTH, height), |root| {
        root.draw(&Text::new(
            title.to_string(),
            (16, TITLE as i32 / 2),
            plot::text_left(16.0, &plot::INK),
        ))?;
        let body = root.margin(TITLE, 0, 0, 0);
        let panels = body.split_evenly((series.len().max(1), 1));
        for (s, area) in series.iter().zip(&panels) {
            panel(area, s, t_end)?;
        }
        Ok(())
    })
}

fn panel(area: &Area<'_>, s: &Series, t_end: f64) -> Drawn {
    let finite = || {
        s.points
            .iter()
            .copied()
            .filter(|(t, v)| t.is_finite() && v.is_finite())
    };
    let hi = finite().map(|p| p.1).fold(0.0_f64, f64::max);
    let y = 0.0..plot::padded(0.0, hi, 0.08, 1e-3).end;
    let mut chart = ChartBuilder::on(area)
        .margin(10)
        .y_label_area_size(70)
        .x_label_area_size(30)
        .build_cartesian_2d(0.0..t_end, y)?;
    chart
        .configure_mesh()
        .bold_line_style(plot::GRID)
        .light_line_style(TRANSPARENT)
        .x_desc("time (s)")
        .y_desc(format!("{} ({})", s.name, s.unit))
        .x_label_formatter(&plot::tick)
        .y_label_formatter(&plot::tick)
        .axis_desc_style(plot::text(12.0, &plot::INK))
        .label_style(plot::text(11.0, &plot::INK))
        .draw()?;
    chart.draw_series(LineSeries::new(finite(), BLUE.stroke_width(2)))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_series_is_a_panel_with_its_name_and_a_trace() {
        let series = [
            Series {
                name: "RSS".into(),
                unit: "MiB".into(),
                points: vec![(0.0, 10.0), (1.0, 11.0), (2.0, f64::NAN), (3.0, 11.5)],
            },
            Series {
                name: "latency".into(),
                unit: "ms".into(),
                points: vec![(0.0, 0.2), (3.0, 0.4)],
            },
        ];
        let svg = time_series_svg("soak", &series).unwrap();
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains("RSS (MiB)") && svg.contains("latency (ms)"));
        assert!(
            svg.contains("soak\n</text>") || svg.contains(">soak<"),
            "{svg}"
        );
        assert!(svg.matches("<polyline").count() >= 2);
    }
}
