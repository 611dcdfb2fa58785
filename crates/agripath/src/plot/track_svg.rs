//! Pictures of point-to-point tracks: a top view (hillshade, threat cylinders with their
//! danger band, start, goal, one track per planner) and an altitude profile of a track
//! against the terrain under it.

use std::fmt::Write;

use super::line_chart::{self, escape, Chart, Series, COLOURS};
use crate::terrain::{hillshade::hillshade, Extent};
use crate::track::scenario::TrackScenario;

/// The top view: `tracks` are (label, points) pairs, points with any z.
pub fn top_view(
    scenario: &TrackScenario,
    title: &str,
    tracks: &[(String, Vec<[f64; 3]>)],
) -> String {
    let (min_x, min_y, max_x, max_y) = scenario.area;
    let (width_px, pad, legend) = (760.0, 30.0, 190.0);
    let scale = (width_px - 2.0 * pad) / (max_x - min_x).max(max_y - min_y);
    let map_w = (max_x - min_x) * scale;
    let map_h = (max_y - min_y) * scale;
    let to_px = |x: f64, y: f64| (pad + (x - min_x) * scale, pad + 24.0 + (max_y - y) * scale);
    let mut svg = String::new();
    let total_w = map_w + 2.0 * pad + legend;
    let total_h = map_h + 2.0 * pad + 24.0;
    let _ = write!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{total_w:.0}" height="{total_h:.0}" viewBox="0 0 {total_w:.0} {total_h:.0}" font-family="DejaVu Sans, sans-serif" font-size="12">"#
    );
    let _ = write!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = write!(
        svg,
        r#"<text x="{pad}" y="20" font-size="15">{}</text>"#,
        escape(title)
    );
    let extent = Extent {
        min_x,
        min_y,
        max_x,
        max_y,
    };
    let shaded = hillshade(&scenario.terrain, extent, 500, 1.0 / scenario.unit_m);
    let (x0, y0) = to_px(min_x, max_y);
    let _ = write!(
        svg,
        r#"<image x="{x0:.1}" y="{y0:.1}" width="{map_w:.1}" height="{map_h:.1}" preserveAspectRatio="none" opacity="0.8" href="data:image/png;base64,{}"/>"#,
        super::plan_html::base64(&shaded.to_png())
    );
    let _ = write!(
        svg,
        r##"<rect x="{x0:.1}" y="{y0:.1}" width="{map_w:.1}" height="{map_h:.1}" fill="none" stroke="#444"/>"##
    );
    let (danger, _) = scenario.cost.danger_band();
    for threat in &scenario.threats {
        let (cx, cy) = to_px(threat.x, threat.y);
        let _ = write!(
            svg,
            r##"<circle cx="{cx:.1}" cy="{cy:.1}" r="{:.1}" fill="#D55E00" fill-opacity="0.35" stroke="#A33" stroke-width="1.2"/>"##,
            threat.radius * scale
        );
        if danger > 0.0 {
            let _ = write!(
                svg,
                r##"<circle cx="{cx:.1}" cy="{cy:.1}" r="{:.1}" fill="none" stroke="#A33" stroke-dasharray="4 3" stroke-width="0.8"/>"##,
                (threat.radius + danger) * scale
            );
        }
    }
    for (index, (_, points)) in tracks.iter().enumerate() {
        let colour = COLOURS[index % COLOURS.len()];
        let path: Vec<String> = points
            .iter()
            .map(|p| {
                let (x, y) = to_px(p[0], p[1]);
                format!("{x:.1},{y:.1}")
            })
            .collect();
        let _ = write!(
            svg,
            r#"<polyline points="{}" fill="none" stroke="{colour}" stroke-width="2.2" stroke-linejoin="round"/>"#,
            path.join(" ")
        );
        if points.len() <= 40 {
            for p in &points[1..points.len().saturating_sub(1)] {
                let (x, y) = to_px(p[0], p[1]);
                let _ = write!(
                    svg,
                    r#"<circle cx="{x:.1}" cy="{y:.1}" r="2.8" fill="{colour}"/>"#
                );
            }
        }
    }
    let (sx, sy) = to_px(scenario.start[0], scenario.start[1]);
    let (gx, gy) = to_px(scenario.goal[0], scenario.goal[1]);
    let _ = write!(
        svg,
        r##"<rect x="{:.1}" y="{:.1}" width="10" height="10" fill="#222"/><circle cx="{gx:.1}" cy="{gy:.1}" r="6" fill="#222"/>"##,
        sx - 5.0,
        sy - 5.0
    );
    let lx = map_w + 2.0 * pad;
    let mut ly = pad + 40.0;
    for (index, (label, _)) in tracks.iter().enumerate() {
        let colour = COLOURS[index % COLOURS.len()];
        let _ = write!(
            svg,
            r#"<line x1="{lx:.0}" y1="{:.0}" x2="{:.0}" y2="{:.0}" stroke="{colour}" stroke-width="3"/><text x="{:.0}" y="{ly:.0}">{}</text>"#,
            ly - 4.0,
            lx + 22.0,
            ly - 4.0,
            lx + 28.0,
            escape(label)
        );
        ly += 20.0;
    }
    let _ = write!(
        svg,
        r##"<rect x="{lx:.0}" y="{:.0}" width="10" height="10" fill="#222"/><text x="{:.0}" y="{:.0}">start</text><circle cx="{:.0}" cy="{:.0}" r="5" fill="#222"/><text x="{:.0}" y="{:.0}">goal</text><circle cx="{:.0}" cy="{:.0}" r="6" fill="#D55E00" fill-opacity="0.35" stroke="#A33"/><text x="{:.0}" y="{:.0}">threat</text>"##,
        ly + 6.0,
        lx + 28.0,
        ly + 15.0,
        lx + 5.0,
        ly + 32.0,
        lx + 28.0,
        ly + 36.0,
        lx + 5.0,
        ly + 54.0,
        lx + 28.0,
        ly + 58.0
    );
    if scenario.unit_m != 1.0 {
        let _ = write!(
            svg,
            r#"<text x="{lx:.0}" y="{:.0}" font-size="11">1 unit = {} m (pixels)</text>"#,
            ly + 84.0,
            scenario.unit_m
        );
    }
    svg.push_str("</svg>\n");
    svg
}

/// The altitude profile of `points` (altitudes above sea level) against the terrain under it,
/// with the height band when the scenario has one.
pub fn profile(scenario: &TrackScenario, title: &str, points: &[[f64; 3]]) -> String {
    let mut along = 0.0;
    let mut track = Vec::new();
    let mut ground = Vec::new();
    let mut floor = Vec::new();
    let mut ceiling = Vec::new();
    for (index, pair) in points.windows(2).enumerate() {
        let (a, b) = (pair[0], pair[1]);
        let length = (b[0] - a[0]).hypot(b[1] - a[1]);
        let steps = ((length / scenario.terrain.cell()).ceil() as usize).clamp(1, 400);
        for step in 0..=steps {
            if step == 0 && index > 0 {
                continue;
            }
            let t = step as f64 / steps as f64;
            let (x, y, z) = (
                a[0] + t * (b[0] - a[0]),
                a[1] + t * (b[1] - a[1]),
                a[2] + t * (b[2] - a[2]),
            );
            let distance = (along + t * length) * scenario.unit_m;
            let height = scenario.terrain.bilinear(x, y);
            track.push((distance, z));
            ground.push((distance, height));
            if let Some((low, high)) = scenario.height_band {
                floor.push((distance, height + low));
                ceiling.push((distance, height + high));
            }
        }
        along += length;
    }
    let mut series = vec![
        Series {
            name: "track".into(),
            points: track,
        },
        Series {
            name: "terrain".into(),
            points: ground,
        },
    ];
    if scenario.height_band.is_some() {
        series.push(Series {
            name: "band floor".into(),
            points: floor,
        });
        series.push(Series {
            name: "band ceiling".into(),
            points: ceiling,
        });
    }
    line_chart::render(
        &Chart {
            title,
            x_label: "distance along the track (m)",
            y_label: "altitude above sea level (m)",
            log_y: false,
        },
        &series,
    )
}
