//! Line charts as SVG: convergence curves (best cost against evaluations) for the bench
//! and repro commands. Hand-written SVG, like the maps: no plotting dependency.

use std::fmt::Write;

const WIDTH: f64 = 770.0;
const HEIGHT: f64 = 440.0;
const LEFT: f64 = 78.0;
const RIGHT: f64 = 200.0;
const TOP: f64 = 40.0;
const BOTTOM: f64 = 56.0;

/// Colour-blind-safe series colours (Okabe and Ito).
pub(crate) const COLOURS: [&str; 8] = [
    "#0072B2", "#E69F00", "#009E73", "#CC79A7", "#D55E00", "#56B4E9", "#000000", "#F0E442",
];

/// One line of a chart.
pub struct Series {
    /// The series' name, as the legend shows it.
    pub name: String,
    /// The points, (x, y) in data units, in drawing order.
    pub points: Vec<(f64, f64)>,
}

/// A chart's titles and axes. With `log_y`, y values must be positive (others are dropped).
pub struct Chart<'a> {
    /// Title above the chart.
    pub title: &'a str,
    /// Label of the x axis.
    pub x_label: &'a str,
    /// Label of the y axis.
    pub y_label: &'a str,
    /// Whether the y axis is logarithmic.
    pub log_y: bool,
}

pub(crate) fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// "Nice" tick values covering [low, high].
pub(crate) fn ticks(low: f64, high: f64, wanted: usize) -> Vec<f64> {
    let span = (high - low).max(f64::MIN_POSITIVE);
    let raw = span / wanted as f64;
    let magnitude = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * magnitude)
        .find(|&s| s >= raw)
        .unwrap_or(10.0 * magnitude);
    let first = (low / step).ceil() as i64;
    let last = (high / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

pub(crate) fn tick_label(value: f64) -> String {
    if value != 0.0 && (value.abs() >= 1e5 || value.abs() < 1e-3) {
        format!("{value:e}")
    } else {
        // k · step in floating point is 0.30000000000000004 for 3 × 0.1: round it away.
        let rounded = (value * 1e9).round() / 1e9;
        format!("{rounded}")
    }
}

/// The chart as an SVG document, series in the palette's order.
pub fn render(chart: &Chart, series: &[Series]) -> String {
    render_coloured(chart, series, &[])
}

/// The chart with series `i` drawn in `colours[i]` (the palette's order beyond them).
pub fn render_coloured(chart: &Chart, series: &[Series], colours: &[&str]) -> String {
    render_banded(chart, series, &[], colours)
}

/// Points kept on the chart's y scale (finite; positive and as log10 with `log_y`).
fn on_scale(chart: &Chart, points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    points
        .iter()
        .filter(|(x, y)| x.is_finite() && y.is_finite() && (!chart.log_y || *y > 0.0))
        .map(|&(x, y)| (x, if chart.log_y { y.log10() } else { y }))
        .collect()
}

/// An SVG path through `points` (chart units), mapped to pixels by `px` and `py`.
fn path_data<'p>(
    points: impl Iterator<Item = &'p (f64, f64)>,
    px: &impl Fn(f64) -> f64,
    py: &impl Fn(f64) -> f64,
) -> String {
    let mut data = String::new();
    for (k, &(x, y)) in points.enumerate() {
        let _ = write!(
            data,
            "{}{:.1},{:.1}",
            if k == 0 { "M" } else { " L" },
            px(x),
            py(y)
        );
    }
    data
}

/// The chart with a shaded band behind series `i`: `bands[i]` holds (x, low, high), e.g.
/// the inter-quartile range of the runs around their median.
pub fn render_banded(
    chart: &Chart,
    series: &[Series],
    bands: &[Vec<(f64, f64, f64)>],
    colours: &[&str],
) -> String {
    let transformed: Vec<Vec<(f64, f64)>> =
        series.iter().map(|s| on_scale(chart, &s.points)).collect();
    type Edges = (Vec<(f64, f64)>, Vec<(f64, f64)>);
    let band_edges: Vec<Edges> = bands
        .iter()
        .map(|band| {
            let low: Vec<(f64, f64)> = band.iter().map(|&(x, low, _)| (x, low)).collect();
            let high: Vec<(f64, f64)> = band.iter().map(|&(x, _, high)| (x, high)).collect();
            (on_scale(chart, &low), on_scale(chart, &high))
        })
        .collect();
    let all = transformed.iter().flatten().chain(
        band_edges
            .iter()
            .flat_map(|(low, high)| low.iter().chain(high)),
    );
    let (mut min_x, mut max_x, mut min_y, mut max_y) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in all {
        min_x = min_x.min(x);
        max_x = max_x.max(x);
        min_y = min_y.min(y);
        max_y = max_y.max(y);
    }
    if min_x > max_x {
        (min_x, max_x, min_y, max_y) = (0.0, 1.0, 0.0, 1.0);
    }
    if max_x - min_x < 1e-12 {
        max_x = min_x + 1.0;
    }
    if max_y - min_y < 1e-12 {
        (min_y, max_y) = (min_y - 0.5, max_y + 0.5);
    }
    if chart.log_y {
        (min_y, max_y) = (min_y.floor(), max_y.ceil());
    }
    let plot_width = WIDTH - LEFT - RIGHT;
    let plot_height = HEIGHT - TOP - BOTTOM;
    let colour_of = |index: usize| {
        colours
            .get(index)
            .copied()
            .unwrap_or(COLOURS[index % COLOURS.len()])
    };
    let px = |x: f64| LEFT + (x - min_x) / (max_x - min_x) * plot_width;
    let py = |y: f64| TOP + (max_y - y) / (max_y - min_y) * plot_height;

    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" viewBox="0 0 {WIDTH} {HEIGHT}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        svg,
        r#"<text x="{}" y="22" font-size="15" text-anchor="middle">{}</text>"#,
        LEFT + plot_width / 2.0,
        escape(chart.title)
    );
    let y_ticks = if chart.log_y {
        let step = ((max_y - min_y) / 8.0).ceil().max(1.0);
        let mut values = vec![];
        let mut value = min_y;
        while value <= max_y + 1e-9 {
            values.push(value);
            value += step;
        }
        values
    } else {
        ticks(min_y, max_y, 6)
    };
    for value in y_ticks {
        let y = py(value);
        let label = if chart.log_y {
            format!("1e{value:.0}")
        } else {
            tick_label(value)
        };
        let _ = writeln!(
            svg,
            r##"<line x1="{LEFT}" x2="{:.1}" y1="{y:.1}" y2="{y:.1}" stroke="#e4e4e4"/><text x="{:.1}" y="{:.1}" text-anchor="end">{label}</text>"##,
            LEFT + plot_width,
            LEFT - 6.0,
            y + 4.0
        );
    }
    for value in ticks(min_x, max_x, 6) {
        let x = px(value);
        let _ = writeln!(
            svg,
            r##"<line x1="{x:.1}" x2="{x:.1}" y1="{TOP}" y2="{:.1}" stroke="#e4e4e4"/><text x="{x:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
            TOP + plot_height,
            TOP + plot_height + 18.0,
            tick_label(value)
        );
    }
    let _ = writeln!(
        svg,
        r##"<rect x="{LEFT}" y="{TOP}" width="{plot_width}" height="{plot_height}" fill="none" stroke="#444"/>"##
    );
    let _ = writeln!(
        svg,
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
        LEFT + plot_width / 2.0,
        HEIGHT - 14.0,
        escape(chart.x_label)
    );
    let _ = writeln!(
        svg,
        r#"<text transform="translate(18 {:.1}) rotate(-90)" text-anchor="middle">{}</text>"#,
        TOP + plot_height / 2.0,
        escape(chart.y_label)
    );
    for (index, (low, high)) in band_edges.iter().enumerate() {
        if low.is_empty() || high.is_empty() {
            continue;
        }
        let colour = colour_of(index);
        let data = path_data(low.iter().chain(high.iter().rev()), &px, &py);
        let _ = writeln!(
            svg,
            r#"<path d="{data} Z" fill="{colour}" fill-opacity="0.18" stroke="none"/>"#
        );
    }
    for (index, (line, points)) in series.iter().zip(&transformed).enumerate() {
        let colour = colour_of(index);
        if !points.is_empty() {
            let data = path_data(points.iter(), &px, &py);
            let _ = writeln!(
                svg,
                r#"<path d="{data}" fill="none" stroke="{colour}" stroke-width="2"/>"#
            );
        }
        let legend_y = TOP + 10.0 + index as f64 * 20.0;
        let legend_x = LEFT + plot_width + 14.0;
        let _ = writeln!(
            svg,
            r#"<line x1="{legend_x}" x2="{:.1}" y1="{legend_y}" y2="{legend_y}" stroke="{colour}" stroke-width="3"/><text x="{:.1}" y="{:.1}">{}</text>"#,
            legend_x + 22.0,
            legend_x + 28.0,
            legend_y + 4.0,
            escape(&line.name)
        );
    }
    svg.push_str("</svg>\n");
    svg
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_read_as_written() {
        assert_eq!(tick_label(3.0 * 0.1), "0.3");
        assert_eq!(tick_label(1200.0), "1200");
        assert_eq!(tick_label(0.25), "0.25");
        assert_eq!(tick_label(2e-4), "2e-4");
    }

    #[test]
    fn ticks_are_round_and_inside() {
        assert_eq!(ticks(0.0, 10.0, 5), vec![0.0, 2.0, 4.0, 6.0, 8.0, 10.0]);
        assert!(ticks(0.13, 0.87, 4)
            .iter()
            .all(|t| (0.13..=0.87).contains(t)));
    }

    #[test]
    fn a_chart_draws_every_series_with_a_legend() {
        let chart = Chart {
            title: "f1 <test>",
            x_label: "evaluations",
            y_label: "best",
            log_y: true,
        };
        let series = [
            Series {
                name: "A".into(),
                points: vec![(0.0, 100.0), (10.0, 1e-3)],
            },
            Series {
                name: "B".into(),
                points: vec![(0.0, 50.0), (10.0, -1.0)],
            },
        ];
        let svg = render(&chart, &series);
        assert_eq!(svg.matches("<path").count(), 2);
        assert!(svg.contains("f1 &lt;test&gt;"));
        assert!(svg.contains(">A</text>") && svg.contains(">B</text>"));
        let band = vec![(0.0, 60.0, 200.0), (10.0, 1e-4, 1e-2)];
        let banded = render_banded(&chart, &series, &[band], &[]);
        assert_eq!(banded.matches("<path").count(), 3);
        assert_eq!(banded.matches("fill-opacity").count(), 1);
    }
}
