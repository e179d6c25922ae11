//! Scatter plots as inline SVG text (plotters' SVG backend, no fonts needed).

use plotters::coord::combinators::IntoLogRange;
use plotters::prelude::*;

/// One labelled point.
#[derive(Clone, Debug)]
pub struct Point {
    /// Horizontal value.
    pub x: f64,
    /// Vertical value.
    pub y: f64,
    /// Text next to the marker (empty: none).
    pub label: String,
}

/// Points drawn in one colour, named in the legend.
#[derive(Clone, Debug, Default)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// The points.
    pub points: Vec<Point>,
}

/// What to draw.
#[derive(Clone, Debug)]
pub struct Scatter<'a> {
    /// Caption above the plot.
    pub title: &'a str,
    /// Horizontal axis label.
    pub x_label: &'a str,
    /// Vertical axis label.
    pub y_label: &'a str,
    /// Size in pixels.
    pub size: (u32, u32),
    /// Draw the lower-left Pareto front (no point both faster and more accurate) over all series.
    pub pareto: bool,
    /// Connect each series' points in order.
    pub lines: bool,
}

/// The points of `pts` on the lower-left Pareto front (minimal y for increasing x), by x.
#[must_use]
pub fn pareto_front(pts: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut v: Vec<(f64, f64)> = pts.iter().copied().filter(|(x, y)| x.is_finite() && y.is_finite()).collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut front: Vec<(f64, f64)> = Vec::new();
    for p in v {
        if front.last().is_none_or(|l| p.1 < l.1) {
            front.push(p);
        }
    }
    front
}

fn log_bounds(vals: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in vals.filter(|v| v.is_finite() && *v > 0.0) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (0.1, 10.0);
    }
    // A little room on both sides, at least a factor of 10 overall.
    let (lo, hi) = (lo / 1.6, hi * 1.6);
    if hi / lo < 10.0 {
        let mid = (lo * hi).sqrt();
        (mid / 3.2, mid * 3.2)
    } else {
        (lo, hi)
    }
}

/// A log–log scatter plot as an SVG document (values ≤ 0 or non-finite are left out).
#[must_use]
pub fn scatter_svg(spec: &Scatter<'_>, series: &[Series]) -> String {
    let mut svg = String::new();
    if let Err(e) = draw(&mut svg, spec, series) {
        return format!("<p>plot failed: {e}</p>");
    }
    svg
}

fn draw<'a>(svg: &'a mut String, spec: &Scatter<'_>, series: &[Series]) -> Result<(), Box<dyn std::error::Error + 'a>> {
    let all = || series.iter().flat_map(|s| s.points.iter()).filter(|p| p.x > 0.0 && p.y > 0.0);
    let (x0, x1) = log_bounds(all().map(|p| p.x));
    let (y0, y1) = log_bounds(all().map(|p| p.y));
    let root = SVGBackend::with_string(svg, spec.size).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(spec.title, ("sans-serif", 15))
        .margin(8)
        .x_label_area_size(34)
        .y_label_area_size(58)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc(spec.x_label)
        .y_desc(spec.y_label)
        .x_labels(6)
        .y_labels(6)
        .x_label_formatter(&|v| format!("{v:.2e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style(("sans-serif", 10))
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    if spec.pareto {
        let pts: Vec<(f64, f64)> = all().map(|p| (p.x, p.y)).collect();
        let front = pareto_front(&pts);
        // Staircase: from each front point right to the next one's time, then down.
        let mut stairs = Vec::new();
        for (k, p) in front.iter().enumerate() {
            stairs.push(*p);
            if let Some(n) = front.get(k + 1) {
                stairs.push((n.0, p.1));
            }
        }
        chart
            .draw_series(LineSeries::new(stairs, ShapeStyle::from(&BLACK.mix(0.35)).stroke_width(2)))?
            .label("Pareto front")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 14, y)], BLACK.mix(0.35)));
    }
    for (k, s) in series.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        let pts: Vec<&Point> = s.points.iter().filter(|p| p.x > 0.0 && p.y > 0.0).collect();
        if spec.lines && pts.len() > 1 {
            chart.draw_series(LineSeries::new(pts.iter().map(|p| (p.x, p.y)), color.mix(0.6)))?;
        }
        chart
            .draw_series(pts.iter().map(|p| {
                EmptyElement::at((p.x, p.y))
                    + Circle::new((0, 0), 4, color.filled())
                    + Text::new(p.label.clone(), (6, -4), ("sans-serif", 10).into_font())
            }))?
            .label(s.name.clone())
            .legend(move |(x, y)| Circle::new((x + 7, y), 4, color.filled()));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.3))
        .label_font(("sans-serif", 10))
        .draw()?;
    root.present()?;
    Ok(())
}
