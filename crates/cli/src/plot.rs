//! SVG line charts for the CLI's `--plot` and `--out` outputs (plotters' SVG backend: no
//! system library, no font files).

use std::path::Path;

use anyhow::{Result, anyhow};
use karman_mission::dispersion::files::write_atomic;
use plotters::prelude::*;

/// One named curve of a chart.
pub struct Series<'a> {
    /// Legend label.
    pub label: &'a str,
    /// Points `(x, y)`.
    pub points: Vec<(f64, f64)>,
}

const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(23, 190, 207),
];

/// The chart's canvas, pixels.
const CANVAS: (u32, u32) = (900, 600);
/// Margin around the chart, pixels.
const MARGIN: u32 = 15;
/// Height of the x-axis label area, pixels.
const X_LABEL_AREA: u32 = 45;
/// Width of the y-axis label area, pixels.
const Y_LABEL_AREA: u32 = 75;
/// Height the 22-pixel caption takes with its spacing, pixels (plotters: the font size plus
/// its margin).
const CAPTION_HEIGHT: u32 = 32;

/// A padded `[lo, hi]` range covering `values` (a unit range around a constant).
fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = if hi > lo {
        0.05 * (hi - lo)
    } else {
        0.5 * lo.abs().max(1.0)
    };
    (lo - pad, hi + pad)
}

/// Writes a line chart of `series` to the SVG file `path`, atomically
/// ([`write_atomic`]: the whole chart or, on an error naming `path`, no new file).
pub fn line_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
) -> Result<()> {
    chart(path, title, x_label, y_label, series, false)
}

/// [`line_chart`] with one scale on both axes (a metre east is as long as a metre north): a
/// ground track or landing map, whose shape a stretched chart would falsify.
pub fn map_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
) -> Result<()> {
    chart(path, title, x_label, y_label, series, true)
}

fn chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
    equal: bool,
) -> Result<()> {
    let mut svg = String::new();
    draw(&mut svg, title, x_label, y_label, series, equal)
        .map_err(|e| anyhow!("{}: cannot draw the chart: {e}", path.display()))?;
    write_atomic(path, svg.as_bytes())?;
    Ok(())
}

/// The plotting area, pixels: the canvas less margins, label areas and caption.
const AREA: (u32, u32) = (
    CANVAS.0 - 2 * MARGIN - Y_LABEL_AREA,
    CANVAS.1 - 2 * MARGIN - X_LABEL_AREA - CAPTION_HEIGHT,
);

/// The ranges `x`, `y` with the narrower widened about its centre until a unit spans as many
/// pixels of [`AREA`] on both axes.
fn equal_scale(x: (f64, f64), y: (f64, f64)) -> ((f64, f64), (f64, f64)) {
    let (width, height) = (f64::from(AREA.0), f64::from(AREA.1));
    let scale = ((x.1 - x.0) / width).max((y.1 - y.0) / height);
    let (cx, cy) = (0.5 * (x.0 + x.1), 0.5 * (y.0 + y.1));
    (
        (cx - 0.5 * scale * width, cx + 0.5 * scale * width),
        (cy - 0.5 * scale * height, cy + 0.5 * scale * height),
    )
}

/// Draws the chart into `svg`.
fn draw(
    svg: &mut String,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
    equal: bool,
) -> Result<()> {
    let err = |e: &dyn std::fmt::Display| anyhow!("{e}");
    let (mut x0, mut x1) = range(series.iter().flat_map(|s| s.points.iter().map(|p| p.0)));
    let (mut y0, mut y1) = range(series.iter().flat_map(|s| s.points.iter().map(|p| p.1)));
    if equal {
        ((x0, x1), (y0, y1)) = equal_scale((x0, x1), (y0, y1));
    }
    let root = SVGBackend::with_string(svg, CANVAS).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(MARGIN)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .draw()
        .map_err(|e| err(&e))?;
    for (i, s) in series.iter().enumerate() {
        let color = COLORS[i % COLORS.len()];
        chart
            .draw_series(LineSeries::new(
                s.points.iter().copied(),
                color.stroke_width(2),
            ))
            .map_err(|e| err(&e))?
            .label(s.label)
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2)));
    }
    if series.len() > 1 {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(&e))?;
    }
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_map_has_one_scale_on_both_axes() {
        // A track 100 m east and 2 km north: the east range widens, the north one stays.
        let ((x0, x1), (y0, y1)) = equal_scale((0.0, 100.0), (0.0, 2000.0));
        let per_pixel = |lo: f64, hi: f64, px: u32| (hi - lo) / f64::from(px);
        let (sx, sy) = (per_pixel(x0, x1, AREA.0), per_pixel(y0, y1, AREA.1));
        assert!((sx - sy).abs() < 1e-12 * sy, "{sx} {sy}");
        assert!(x0 <= 0.0 && x1 >= 100.0 && (y0, y1) == (0.0, 2000.0));
        assert!((0.5 * (x0 + x1) - 50.0).abs() < 1e-9);
        // A wide track: the north range widens.
        let (x, (y0, y1)) = equal_scale((-5000.0, 5000.0), (0.0, 10.0));
        assert_eq!(x, (-5000.0, 5000.0));
        assert!(y0 < 0.0 && y1 > 10.0);
    }

    #[test]
    fn writes_an_svg_with_the_labels() {
        let dir = std::env::temp_dir().join(format!("karman-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let path = dir.join("chart.svg");
        let series = [
            Series {
                label: "up",
                points: vec![(0.0, 0.0), (1.0, 2.0)],
            },
            Series {
                label: "flat",
                points: vec![(0.0, 1.0), (1.0, 1.0)],
            },
        ];
        line_chart(&path, "Title here", "x (s)", "y (m)", &series).expect("chart");
        let svg = std::fs::read_to_string(&path).expect("svg");
        assert!(svg.starts_with("<svg") || svg.contains("<svg"));
        for text in ["Title here", "x (s)", "y (m)", "up", "flat"] {
            assert!(svg.contains(text), "missing {text}");
        }
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn constant_and_empty_ranges_are_usable() {
        assert_eq!(range([2.0, 2.0].into_iter()), (1.0, 3.0));
        assert_eq!(range(std::iter::empty()), (0.0, 1.0));
    }
}
