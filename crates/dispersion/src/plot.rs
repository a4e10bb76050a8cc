//! SVG plots (plotters' SVG backend): the landing scatter with its k-σ ellipses (each body's
//! in its own colour, in a study of several) and a histogram of one output (the apogee).

use crate::error::DispersionError;
use crate::stats::Ellipse;
use plotters::prelude::*;
use std::path::Path;

type PlotResult = Result<(), Box<dyn std::error::Error>>;

fn failed(path: &Path) -> impl FnOnce(Box<dyn std::error::Error>) -> DispersionError + '_ {
    move |e| DispersionError::Plot {
        path: path.to_owned(),
        message: e.to_string(),
    }
}

/// Colours of the 1σ, 2σ, 3σ contours.
const SIGMA_COLOURS: [RGBColor; 3] = [RGBColor(0, 160, 0), RGBColor(255, 140, 0), RED];

/// Colours of the landing points of the bodies of a study, the first body's first.
const BODY_COLOURS: [RGBColor; 4] = [BLUE, MAGENTA, CYAN, RGBColor(128, 0, 128)];

/// One body's landing points and ellipse in the landing plot.
#[derive(Debug, Clone, Copy)]
pub struct Landings<'a> {
    /// Its name; none in a study of one body.
    pub body: Option<&'a str>,
    /// Landing points (x east, y north), m.
    pub points: &'a [[f64; 2]],
    /// Their ellipse.
    pub ellipse: Option<&'a Ellipse>,
}

/// Draws each body's landing points and the 1σ/2σ/3σ rings of its ellipse to `path`.
pub fn landing(path: &Path, title: &str, bodies: &[Landings<'_>]) -> Result<(), DispersionError> {
    let mut svg = String::new();
    draw_landing(&mut svg, title, bodies).map_err(failed(path))?;
    crate::files::write_atomic(path, svg.as_bytes())
}

fn draw_landing(svg: &mut String, title: &str, bodies: &[Landings<'_>]) -> PlotResult {
    let rings: Vec<Vec<Vec<[f64; 2]>>> = bodies
        .iter()
        .map(|b| {
            b.ellipse
                .map(|e| (1..=3).map(|k| e.boundary(f64::from(k), 100)).collect())
                .unwrap_or_default()
        })
        .collect();
    let everything = bodies
        .iter()
        .flat_map(|b| b.points.iter())
        .chain(rings.iter().flatten().flatten())
        .chain([&[0.0, 0.0]]);
    let (mut x0, mut x1, mut y0, mut y1) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for p in everything.filter(|p| p[0].is_finite() && p[1].is_finite()) {
        x0 = x0.min(p[0]);
        x1 = x1.max(p[0]);
        y0 = y0.min(p[1]);
        y1 = y1.max(p[1]);
    }
    // Equal scales on both axes, 5 % margin.
    let half = 0.55 * (x1 - x0).max(y1 - y0).max(1.0);
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let root = SVGBackend::with_string(svg, (800, 800)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((cx - half)..(cx + half), (cy - half)..(cy + half))?;
    chart
        .configure_mesh()
        .x_desc("x, east of the pad (m)")
        .y_desc("y, north of the pad (m)")
        .draw()?;
    for (index, (body, rings)) in bodies.iter().zip(rings).enumerate() {
        let prefix = body
            .body
            .map(|name| format!("{name}: "))
            .unwrap_or_default();
        let colour = BODY_COLOURS[index % BODY_COLOURS.len()];
        chart
            .draw_series(
                body.points
                    .iter()
                    .map(|p| Circle::new((p[0], p[1]), 2, colour.mix(0.35).filled())),
            )?
            .label(format!("{prefix}landing points"))
            .legend(move |(x, y)| Circle::new((x + 10, y), 3, colour.filled()));
        for (level, ring) in rings.into_iter().enumerate() {
            let colour = SIGMA_COLOURS[level % 3];
            let mut closed = ring.clone();
            if let Some(first) = ring.first() {
                closed.push(*first);
            }
            chart
                .draw_series(LineSeries::new(
                    closed.into_iter().map(|p| (p[0], p[1])),
                    colour.stroke_width(2),
                ))?
                .label(format!("{prefix}{} sigma (RocketPy k-sigma)", level + 1))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
        }
    }
    chart
        .draw_series([Cross::new((0.0, 0.0), 6, BLACK.stroke_width(2))])?
        .label("launch pad")
        .legend(|(x, y)| Cross::new((x + 10, y), 4, BLACK));
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

/// Draws a histogram of `sorted` (ascending, finite) values of `name` to `path`.
pub fn histogram(
    path: &Path,
    title: &str,
    name: &str,
    sorted: &[f64],
) -> Result<(), DispersionError> {
    let mut svg = String::new();
    draw_histogram(&mut svg, title, name, sorted).map_err(failed(path))?;
    if svg.is_empty() {
        return Ok(());
    }
    crate::files::write_atomic(path, svg.as_bytes())
}

fn draw_histogram(svg: &mut String, title: &str, name: &str, sorted: &[f64]) -> PlotResult {
    let (Some(&low), Some(&high)) = (sorted.first(), sorted.last()) else {
        return Ok(());
    };
    // Square-root rule for the number of bins, 10 to 60.
    let bins = ((sorted.len() as f64).sqrt().ceil() as usize).clamp(10, 60);
    let width = if high > low {
        (high - low) / bins as f64
    } else {
        1.0
    };
    let mut counts = vec![0u64; bins];
    for v in sorted {
        let bin = (((v - low) / width) as usize).min(bins - 1);
        if let Some(count) = counts.get_mut(bin) {
            *count += 1;
        }
    }
    let top = counts.iter().copied().max().unwrap_or(1) as f64 * 1.1;
    let root = SVGBackend::with_string(svg, (900, 600)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(low..(low + width * bins as f64), 0.0..top)?;
    chart
        .configure_mesh()
        .x_desc(name)
        .y_desc("samples")
        .draw()?;
    chart.draw_series(counts.iter().enumerate().map(|(i, &count)| {
        let left = low + width * i as f64;
        Rectangle::new(
            [(left, 0.0), (left + width, count as f64)],
            BLUE.mix(0.6).filled(),
        )
    }))?;
    root.present()?;
    Ok(())
}

/// Draws the variance shares of one output as horizontal bars, largest first: each input in
/// blue and the unexplained part in red (RocketPy's `SensitivityModel` bar plot colours),
/// each bar labelled with its name and percentage.
pub fn sensitivity_bars(
    path: &Path,
    sensitivity: &crate::sensitivity::OutputSensitivity,
) -> Result<(), DispersionError> {
    let mut svg = String::new();
    draw_sensitivity(&mut svg, sensitivity).map_err(failed(path))?;
    crate::files::write_atomic(path, svg.as_bytes())
}

fn draw_sensitivity(
    svg: &mut String,
    sensitivity: &crate::sensitivity::OutputSensitivity,
) -> PlotResult {
    let mut bars: Vec<(String, f64, RGBColor)> = sensitivity
        .inputs
        .iter()
        .map(|i| (i.input.clone(), 100.0 * i.share, BLUE))
        .collect();
    bars.push((
        "unexplained (linear approximation error)".to_owned(),
        100.0 * sensitivity.unexplained,
        RED,
    ));
    bars.sort_by(|a, b| b.1.total_cmp(&a.1));
    let count = bars.len();
    let height = 120 + 40 * u32::try_from(count).unwrap_or(u32::MAX / 64).min(200);
    let root = SVGBackend::with_string(svg, (900, height)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!(
                "Sensitivity of {} ({} samples)",
                sensitivity.output, sensitivity.samples
            ),
            ("sans-serif", 22),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(10)
        .build_cartesian_2d(0.0..100.0, -0.5..(count as f64 - 0.5))?;
    chart
        .configure_mesh()
        .x_desc("share of the variance (%)")
        .disable_y_mesh()
        .y_labels(0)
        .draw()?;
    // Largest at the top: bar k at y = count − 1 − k.
    let y = |k: usize| (count - 1 - k) as f64;
    chart.draw_series(bars.iter().enumerate().map(|(k, (_, share, colour))| {
        Rectangle::new(
            [(0.0, y(k) - 0.35), (share.clamp(0.0, 100.0), y(k) + 0.35)],
            colour.mix(0.6).filled(),
        )
    }))?;
    chart.draw_series(bars.iter().enumerate().map(|(k, (name, share, _))| {
        Text::new(
            format!("{name}: {share:.2} %"),
            (1.0, y(k) + 0.1),
            ("sans-serif", 15).into_font(),
        )
    }))?;
    root.present()?;
    Ok(())
}
