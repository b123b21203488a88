//! What the demo plots share (`report` and `arm_report`): an SVG drawn with plotters'
//! SVG backend into a string, text styles, tick labels, equal-aspect ranges and a legend
//! drawn outside the data.
//!
//! Text is emitted as SVG `<text>` elements (no font files: plotters' `ttf` feature is
//! off and only estimates text sizes for the layout). Legend swatches of lines are thin
//! filled rectangles, so every `<polyline>` of a colour other than the axes' black is a
//! data trace.

use std::error::Error;
use std::ops::Range;

use plotters::coord::{CoordTranslate, Shift};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// A drawing area of the SVG being drawn.
pub(crate) type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// What drawing returns (plotters' errors, boxed).
pub(crate) type Drawn = Result<(), Box<dyn Error>>;

/// The font family of every text.
const FONT: &str = "sans-serif";

/// Text of `px` pixels (the SVG backend writes plotters' font size divided by 1.24).
pub(crate) fn text(px: f64, colour: &RGBColor) -> TextStyle<'static> {
    TextStyle {
        font: (FONT, px * 1.24).into_font(),
        color: colour.to_backend_color(),
        pos: Pos::default(),
    }
}

/// Text of `px` pixels anchored at its left end, vertically centred.
pub(crate) fn text_left(px: f64, colour: &RGBColor) -> TextStyle<'static> {
    text(px, colour).pos(Pos::new(HPos::Left, VPos::Center))
}

/// Axis labels, tick labels and titles.
pub(crate) const INK: RGBColor = RGBColor(0x33, 0x33, 0x33);
/// Grid lines.
pub(crate) const GRID: RGBColor = RGBColor(0xe4, 0xe4, 0xe4);

/// Draws an SVG of `size` pixels on a white background with `draw` and returns it;
/// errors name `what`.
pub(crate) fn render(
    what: &str,
    size: (u32, u32),
    draw: impl FnOnce(&Area<'_>) -> Drawn,
) -> std::io::Result<String> {
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, size).into_drawing_area();
        root.fill(&WHITE)
            .map_err(Box::<dyn Error>::from)
            .and_then(|()| draw(&root))
            .and_then(|()| root.present().map_err(Box::<dyn Error>::from))
            .map_err(|e| std::io::Error::other(format!("drawing {what}: {e}")))?;
    }
    Ok(out)
}

/// A tick label: the value with at most two decimals, trailing zeros dropped, and no
/// "-0".
pub(crate) fn tick(v: &f64) -> String {
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" || s.is_empty() {
        "0".into()
    } else {
        s.into()
    }
}

/// The smallest box holding a set of points; (0, 0)–(1, 1) when the set is empty.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Bounds {
    /// Smallest x, y.
    pub lo: (f64, f64),
    /// Largest x, y.
    pub hi: (f64, f64),
}

impl Bounds {
    /// The box of the finite points of `points`.
    pub fn of(points: impl IntoIterator<Item = (f64, f64)>) -> Self {
        let mut b = Bounds {
            lo: (f64::INFINITY, f64::INFINITY),
            hi: (f64::NEG_INFINITY, f64::NEG_INFINITY),
        };
        for (x, y) in points {
            if x.is_finite() && y.is_finite() {
                b.lo = (b.lo.0.min(x), b.lo.1.min(y));
                b.hi = (b.hi.0.max(x), b.hi.1.max(y));
            }
        }
        if b.lo.0 > b.hi.0 {
            b = Bounds {
                lo: (0.0, 0.0),
                hi: (1.0, 1.0),
            };
        }
        b
    }

    /// The box grown by `m` on every side.
    pub fn grown(self, m: f64) -> Self {
        Bounds {
            lo: (self.lo.0 - m, self.lo.1 - m),
            hi: (self.hi.0 + m, self.hi.1 + m),
        }
    }
}

/// `lo..hi` grown by `fraction` of its span on each side (at least `min` in all).
pub(crate) fn padded(lo: f64, hi: f64, fraction: f64, min: f64) -> Range<f64> {
    let m = ((hi - lo) * fraction).max(min / 2.0);
    lo - m..hi + m
}

/// Ranges holding `b` (padded by `pad` of the larger span) for a plotting area of `px`
/// pixels with one unit the same length on both axes: the axis with room to spare is
/// widened about its centre.
pub(crate) fn equal_aspect(b: Bounds, pad: f64, px: (u32, u32)) -> (Range<f64>, Range<f64>) {
    let (w, h) = (f64::from(px.0.max(1)), f64::from(px.1.max(1)));
    let span = (b.hi.0 - b.lo.0).max(b.hi.1 - b.lo.1).max(1e-3);
    let b = b.grown(span * pad);
    let (sx, sy) = ((b.hi.0 - b.lo.0).max(1e-3), (b.hi.1 - b.lo.1).max(1e-3));
    // Pixels per unit: the tighter of the two axes.
    let scale = (w / sx).min(h / sy);
    let (cx, cy) = ((b.lo.0 + b.hi.0) / 2.0, (b.lo.1 + b.hi.1) / 2.0);
    let (hx, hy) = (w / scale / 2.0, h / scale / 2.0);
    (cx - hx..cx + hx, cy - hy..cy + hy)
}

/// A marker: how a legend entry, and the same mark in the data, is drawn.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Swatch {
    /// A line of this colour and width (a thin filled bar).
    Line(RGBAColor, u32),
    /// A filled dot.
    Dot(RGBColor),
    /// An open square.
    Square(RGBColor),
    /// An open circle.
    Ring(RGBColor),
    /// A filled disc with an outline.
    Disc(RGBAColor, RGBColor),
    /// A filled triangle.
    Triangle(RGBColor),
    /// A cross.
    Cross(RGBColor),
}

impl Swatch {
    /// Draws the marker centred at `at` on `area` (pixels or data coordinates): legend
    /// and data draw the same shapes.
    pub fn draw<DB, CT>(self, area: &DrawingArea<DB, CT>, at: CT::From) -> Drawn
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
        CT: CoordTranslate,
        CT::From: Clone,
    {
        let at = EmptyElement::at(at);
        match self {
            Swatch::Line(c, w) => {
                let w = (w as i32).max(2);
                area.draw(&(at + Rectangle::new([(-12, -w / 2), (12, w - w / 2)], c.filled())))?
            }
            Swatch::Dot(c) => area.draw(&(at + Circle::new((0, 0), 5, c.filled())))?,
            Swatch::Square(c) => {
                area.draw(&(at + Rectangle::new([(-4, -4), (4, 4)], c.stroke_width(1))))?
            }
            Swatch::Ring(c) => area.draw(&(at + Circle::new((0, 0), 5, c.stroke_width(1))))?,
            Swatch::Disc(fill, stroke) => area.draw(
                &(at + Circle::new((0, 0), 7, fill.filled())
                    + Circle::new((0, 0), 7, stroke.stroke_width(1))),
            )?,
            Swatch::Triangle(c) => area.draw(&(at + TriangleMarker::new((0, 0), 9, c.filled())))?,
            Swatch::Cross(c) => area.draw(&(at + Cross::new((0, 0), 5, c.stroke_width(2))))?,
        }
        Ok(())
    }
}

/// Draws a legend on `area`: `entries` in `columns` columns of `column_width` pixels,
/// `row_height` apart, from `(x, y)` (the first row's centre line).
pub(crate) fn legend(
    area: &Area<'_>,
    (x, y): (i32, i32),
    columns: usize,
    (column_width, row_height): (i32, i32),
    entries: &[(Swatch, &str)],
) -> Drawn {
    let style = text_left(13.0, &INK);
    for (i, (swatch, label)) in entries.iter().enumerate() {
        let (col, row) = (i % columns.max(1), i / columns.max(1));
        let (cx, cy) = (x + col as i32 * column_width, y + row as i32 * row_height);
        swatch.draw(area, (cx + 12, cy))?;
        area.draw(&Text::new(label.to_string(), (cx + 32, cy), style.clone()))?;
    }
    Ok(())
}

/// The plotting area's size in pixels of a chart built on `area` with `margin` on every
/// side, `left` pixels of y labels and `bottom` pixels of x labels.
pub(crate) fn plot_size(area: &Area<'_>, margin: u32, left: u32, bottom: u32) -> (u32, u32) {
    let (w, h) = area.dim_in_pixel();
    (
        w.saturating_sub(2 * margin + left),
        h.saturating_sub(2 * margin + bottom),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_drop_trailing_zeros_and_negative_zero() {
        let labels: Vec<String> = [0.0, -0.0, 2.5, 10.0, -0.25, 1e-4, -1e-4, 0.126]
            .iter()
            .map(tick)
            .collect();
        assert_eq!(labels, ["0", "0", "2.5", "10", "-0.25", "0", "0", "0.13"]);
    }

    #[test]
    fn bounds_skip_what_is_not_finite_and_default_when_empty() {
        let b = Bounds::of([
            (1.0, f64::NAN),
            (2.0, -1.0),
            (f64::INFINITY, 0.0),
            (-1.0, 3.0),
        ]);
        assert_eq!((b.lo, b.hi), ((-1.0, -1.0), (2.0, 3.0)));
        let e = Bounds::of(std::iter::empty());
        assert_eq!((e.lo, e.hi), ((0.0, 0.0), (1.0, 1.0)));
    }

    #[test]
    fn equal_aspect_ranges_give_one_unit_the_same_pixels_on_both_axes() {
        let b = Bounds {
            lo: (0.0, 0.0),
            hi: (2.0, 1.0),
        };
        for px in [(400, 100), (100, 400), (300, 150)] {
            let (x, y) = equal_aspect(b, 0.05, px);
            let (sx, sy) = (
                f64::from(px.0) / (x.end - x.start),
                f64::from(px.1) / (y.end - y.start),
            );
            assert!((sx - sy).abs() < 1e-9 * sx, "{px:?}: {sx} {sy}");
            // The data stays inside, with its padding.
            assert!(x.start <= -0.1 + 1e-9 && x.end >= 2.1 - 1e-9, "{x:?}");
            assert!(y.start <= -0.1 + 1e-9 && y.end >= 1.1 - 1e-9, "{y:?}");
        }
    }

    #[test]
    fn a_render_is_a_whole_svg_and_its_errors_name_the_plot() {
        let svg = render("test.svg", (200, 100), |root| {
            legend(root, (0, 20), 1, (0, 20), &[(Swatch::Dot(INK), "a dot")])
        })
        .unwrap();
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains("a dot"));
        let e = render("test.svg", (200, 100), |_| Err("broken".into())).unwrap_err();
        assert_eq!(e.to_string(), "drawing test.svg: broken");
    }
}
