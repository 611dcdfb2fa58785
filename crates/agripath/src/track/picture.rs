//! Pictures of point-to-point tracks that show whether they are safe.
//!
//! - The top view: the terrain tinted by height and hill-shaded, with a height legend, axes in
//!   the scenario's units and a scale bar in metres; threat cylinders with their danger band;
//!   start, goal, and one track per planner in the planner's own colour (the same in every
//!   picture), dashed when the track is unsafe.
//! - The altitude profile of a track: the terrain under it as given (the verdict's ground),
//!   the height band, the minimum-clearance line, the lowest clearance marked, and "unsafe"
//!   wherever the track comes closer to the terrain than the minimum.

use std::fmt::Write;

use super::scenario::TrackScenario;
use crate::plot::line_chart::{escape, tick_label, ticks};
use crate::plot::terrain_map::height_tint;
use crate::terrain::{hillshade::hillshade, Extent};

/// One track to draw.
pub struct DrawnTrack<'a> {
    /// The legend's label.
    pub label: &'a str,
    /// Stroke colour, as CSS (e.g. `#0072B2`).
    pub colour: &'a str,
    /// Points with altitudes above sea level.
    pub points: &'a [[f64; 3]],
    /// Whether the track passed the safety check (drawn dashed when not).
    pub safe: bool,
    /// The safety check's lowest clearance in any direction (`report.json`'s
    /// `lowest_clearance_m`), metres: the profile's label gives it where it is less than the
    /// height above the ground the section shows.
    pub lowest_clearance_m: Option<f64>,
}

fn rgb_png(width: usize, height: usize, pixels: &[u8]) -> Vec<u8> {
    crate::terrain::hillshade::encode_png(width, height, png::ColorType::Rgb, pixels)
}

/// The terrain over `extent`, tinted by height and hill-shaded, as a PNG; with the lowest and
/// highest heights drawn.
fn relief(scenario: &TrackScenario, extent: Extent) -> (Vec<u8>, f64, f64) {
    let shaded = hillshade(&scenario.terrain, extent, 500, 1.0 / scenario.unit_m);
    let (width, height) = (shaded.width, shaded.height);
    let pixel_x = extent.width() / width as f64;
    let pixel_y = extent.height() / height as f64;
    let heights: Vec<f64> = (0..width * height)
        .map(|index| {
            let (row, column) = (index / width, index % width);
            scenario.terrain.bilinear(
                extent.min_x + (column as f64 + 0.5) * pixel_x,
                extent.max_y - (row as f64 + 0.5) * pixel_y,
            )
        })
        .collect();
    let (low, high) = heights
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), &h| {
            (low.min(h), high.max(h))
        });
    let span = (high - low).max(1e-9);
    let mut pixels = Vec::with_capacity(width * height * 3);
    for (index, &value) in heights.iter().enumerate() {
        let colour = height_tint((value - low) / span);
        let light = 0.55 + 0.45 * f64::from(shaded.pixels[2 * index]) / 255.0;
        pixels.extend(colour.map(|channel| (channel * light).round().clamp(0.0, 255.0) as u8));
    }
    (rgb_png(width, height, &pixels), low, high)
}

/// A round length for a scale bar of about `wanted` metres.
fn round_length(wanted: f64) -> f64 {
    let magnitude = 10f64.powf(wanted.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * magnitude)
        .rfind(|&length| length <= wanted)
        .unwrap_or(magnitude)
}

/// The top view.
pub fn top_view(scenario: &TrackScenario, title: &str, tracks: &[DrawnTrack]) -> String {
    let (min_x, min_y, max_x, max_y) = scenario.area;
    let (width_px, left, top, bottom, legend) = (700.0, 70.0, 40.0, 50.0, 230.0);
    let scale = (width_px - left) / (max_x - min_x).max(max_y - min_y);
    let map_w = (max_x - min_x) * scale;
    let map_h = (max_y - min_y) * scale;
    let to_px = |x: f64, y: f64| (left + (x - min_x) * scale, top + (max_y - y) * scale);
    let total_w = left + map_w + legend;
    let total_h = top + map_h + bottom;
    let mut svg = String::new();
    let _ = write!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{total_w:.0}" height="{total_h:.0}" viewBox="0 0 {total_w:.0} {total_h:.0}" font-family="DejaVu Sans, sans-serif" font-size="12">"#
    );
    let _ = write!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = write!(
        svg,
        r#"<text x="{left}" y="22" font-size="15">{}</text>"#,
        escape(title)
    );
    let extent = Extent {
        min_x,
        min_y,
        max_x,
        max_y,
    };
    let (png, low, high) = relief(scenario, extent);
    let (x0, y0) = to_px(min_x, max_y);
    let _ = write!(
        svg,
        r#"<image x="{x0:.1}" y="{y0:.1}" width="{map_w:.1}" height="{map_h:.1}" preserveAspectRatio="none" href="data:image/png;base64,{}"/>"#,
        crate::plot::plan_html::base64(&png)
    );
    // Axes in the scenario's units.
    let unit = if scenario.unit_m == 1.0 {
        "m".to_string()
    } else {
        format!("units of {} m", scenario.unit_m)
    };
    for value in ticks(min_x, max_x, 6) {
        let (x, _) = to_px(value, min_y);
        let _ = write!(
            svg,
            r##"<line x1="{x:.1}" x2="{x:.1}" y1="{:.1}" y2="{:.1}" stroke="#444"/><text x="{x:.1}" y="{:.1}" text-anchor="middle" font-size="11">{}</text>"##,
            top + map_h,
            top + map_h + 5.0,
            top + map_h + 18.0,
            coordinate_label(value)
        );
    }
    for value in ticks(min_y, max_y, 6) {
        let (_, y) = to_px(min_x, value);
        let _ = write!(
            svg,
            r##"<line x1="{:.1}" x2="{left:.1}" y1="{y:.1}" y2="{y:.1}" stroke="#444"/><text x="{:.1}" y="{:.1}" text-anchor="end" font-size="11">{}</text>"##,
            left - 5.0,
            left - 8.0,
            y + 4.0,
            coordinate_label(value)
        );
    }
    let _ = write!(
        svg,
        r##"<text x="{:.1}" y="{:.1}" text-anchor="middle">x ({unit})</text><text transform="translate(16 {:.1}) rotate(-90)" text-anchor="middle">y ({unit})</text>"##,
        left + map_w / 2.0,
        top + map_h + 36.0,
        top + map_h / 2.0
    );
    let _ = write!(
        svg,
        r##"<rect x="{x0:.1}" y="{y0:.1}" width="{map_w:.1}" height="{map_h:.1}" fill="none" stroke="#444"/>"##
    );
    // Threats: the cylinder (no entry) and the cost model's danger band around it.
    let (danger, _) = scenario.cost.danger_band();
    for threat in &scenario.threats {
        let (cx, cy) = to_px(threat.x, threat.y);
        if danger > 0.0 {
            let _ = write!(
                svg,
                r##"<circle cx="{cx:.1}" cy="{cy:.1}" r="{:.1}" fill="#C00000" fill-opacity="0.12" stroke="#C00000" stroke-dasharray="4 3" stroke-width="0.9"/>"##,
                (threat.radius + danger) * scale
            );
        }
        let _ = write!(
            svg,
            r##"<circle cx="{cx:.1}" cy="{cy:.1}" r="{:.1}" fill="#C00000" fill-opacity="0.35" stroke="#C00000" stroke-width="1.4"/>"##,
            threat.radius * scale
        );
    }
    for track in tracks {
        let path: Vec<String> = track
            .points
            .iter()
            .map(|p| {
                let (x, y) = to_px(p[0], p[1]);
                format!("{x:.1},{y:.1}")
            })
            .collect();
        let dash = if track.safe {
            ""
        } else {
            r#" stroke-dasharray="7 4""#
        };
        let _ = write!(
            svg,
            r#"<polyline points="{}" fill="none" stroke="white" stroke-width="4.2" stroke-linejoin="round" opacity="0.7"/><polyline points="{}" fill="none" stroke="{}" stroke-width="2.2" stroke-linejoin="round"{dash}/>"#,
            path.join(" "),
            path.join(" "),
            track.colour
        );
        if track.points.len() <= 40 {
            for p in &track.points[1..track.points.len().saturating_sub(1)] {
                let (x, y) = to_px(p[0], p[1]);
                let _ = write!(
                    svg,
                    r#"<circle cx="{x:.1}" cy="{y:.1}" r="2.8" fill="{}"/>"#,
                    track.colour
                );
            }
        }
    }
    let (sx, sy) = to_px(scenario.start[0], scenario.start[1]);
    let (gx, gy) = to_px(scenario.goal[0], scenario.goal[1]);
    let _ = write!(
        svg,
        r##"<rect x="{:.1}" y="{:.1}" width="10" height="10" fill="#222" stroke="white"/><circle cx="{gx:.1}" cy="{gy:.1}" r="6" fill="#222" stroke="white"/>"##,
        sx - 5.0,
        sy - 5.0
    );
    // Scale bar in metres, bottom left inside the map.
    let metres_per_px = scenario.unit_m / scale;
    let bar_m = round_length(0.25 * map_w * metres_per_px);
    let bar_px = bar_m / metres_per_px;
    let (bx, by) = (left + 12.0, top + map_h - 14.0);
    let _ = write!(
        svg,
        r##"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="22" fill="white" opacity="0.8"/><line x1="{bx:.1}" x2="{:.1}" y1="{by:.1}" y2="{by:.1}" stroke="#222" stroke-width="3"/><text x="{:.1}" y="{:.1}" font-size="11">{} m</text>"##,
        bx - 6.0,
        by - 16.0,
        bar_px + 60.0,
        bx + bar_px,
        bx + bar_px + 6.0,
        by + 4.0,
        tick_label(bar_m)
    );
    // Legend: planners, markers, threats, the height ramp.
    let lx = left + map_w + 24.0;
    let mut ly = top + 12.0;
    for track in tracks {
        let dash = if track.safe {
            ""
        } else {
            r#" stroke-dasharray="7 4""#
        };
        let _ = write!(
            svg,
            r#"<line x1="{lx:.0}" y1="{:.0}" x2="{:.0}" y2="{:.0}" stroke="{}" stroke-width="3"{dash}/><text x="{:.0}" y="{ly:.0}">{}{}</text>"#,
            ly - 4.0,
            lx + 22.0,
            ly - 4.0,
            track.colour,
            lx + 28.0,
            escape(track.label),
            if track.safe { "" } else { " (unsafe)" }
        );
        ly += 20.0;
    }
    let _ = write!(
        svg,
        r##"<rect x="{lx:.0}" y="{:.0}" width="10" height="10" fill="#222"/><text x="{:.0}" y="{:.0}">start</text><circle cx="{:.0}" cy="{:.0}" r="5" fill="#222"/><text x="{:.0}" y="{:.0}">goal</text><circle cx="{:.0}" cy="{:.0}" r="6" fill="#C00000" fill-opacity="0.35" stroke="#C00000"/><text x="{:.0}" y="{:.0}">threat cylinder</text>"##,
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
    ly += 76.0;
    if danger > 0.0 {
        let _ = write!(
            svg,
            r##"<circle cx="{:.0}" cy="{:.0}" r="6" fill="#C00000" fill-opacity="0.12" stroke="#C00000" stroke-dasharray="3 2"/><text x="{:.0}" y="{:.0}">danger band ({} {})</text>"##,
            lx + 5.0,
            ly - 4.0,
            lx + 28.0,
            ly,
            tick_label(danger),
            if scenario.unit_m == 1.0 { "m" } else { "units" }
        );
        ly += 24.0;
    }
    let _ = write!(
        svg,
        r#"<text x="{lx:.0}" y="{ly:.0}">terrain height (m)</text>"#
    );
    let (bar_top, bar_height) = (ly + 8.0, 120.0);
    for step in 0..24 {
        let fraction = 1.0 - step as f64 / 23.0;
        let [r, g, b] = height_tint(fraction).map(|c| c.round() as u8);
        let _ = write!(
            svg,
            r#"<rect x="{lx:.0}" y="{:.1}" width="16" height="{:.1}" fill="rgb({r},{g},{b})"/>"#,
            bar_top + step as f64 * bar_height / 24.0,
            bar_height / 24.0 + 0.5
        );
    }
    let _ = write!(
        svg,
        r##"<rect x="{lx:.0}" y="{bar_top:.0}" width="16" height="{bar_height:.0}" fill="none" stroke="#444"/><text x="{:.0}" y="{:.0}">{high:.0}</text><text x="{:.0}" y="{:.0}">{low:.0}</text>"##,
        lx + 22.0,
        bar_top + 10.0,
        lx + 22.0,
        bar_top + bar_height
    );
    svg.push_str("</svg>\n");
    svg
}

/// The profile's label at its lowest point: the height above the ground the section shows,
/// and, where the check found the terrain nearer in another direction (a slope beside the
/// track), that distance too, as `report.json` gives it.
fn lowest_words(height_m: f64, any_direction_m: Option<f64>) -> String {
    match any_direction_m {
        Some(distance) if distance < height_m - 0.05 => format!(
            "lowest {height_m:.1} m above the ground; clearance {distance:.1} m in any direction"
        ),
        _ => format!("lowest clearance {height_m:.1} m"),
    }
}

/// A map coordinate as people read one: UTM eastings and northings in whole metres
/// (8842000, not 8.842e6), small ones as the chart's ticks.
fn coordinate_label(value: f64) -> String {
    if value.abs() >= 1e5 {
        format!("{value:.0}")
    } else {
        tick_label(value)
    }
}

/// The altitude profile of a whole track (altitudes above sea level) against the terrain as
/// given, with the band, the minimum clearance and where the track breaks it.
pub fn profile(scenario: &TrackScenario, title: &str, track: &DrawnTrack) -> String {
    let minimum = scenario.limits.min_clearance_m;
    // Samples at most 1 m apart (and at most 4000): distance, track, ground.
    let total: f64 = track
        .points
        .windows(2)
        .map(|pair| (pair[1][0] - pair[0][0]).hypot(pair[1][1] - pair[0][1]) * scenario.unit_m)
        .sum();
    let spacing = (total / 4000.0).max(1.0);
    let mut samples: Vec<(f64, f64, f64)> = Vec::new();
    let mut along = 0.0;
    for pair in track.points.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let length = (b[0] - a[0]).hypot(b[1] - a[1]) * scenario.unit_m;
        let steps = ((length / spacing).ceil() as usize).max(1);
        for step in 0..=steps {
            let t = step as f64 / steps as f64;
            let (x, y, z) = (
                a[0] + t * (b[0] - a[0]),
                a[1] + t * (b[1] - a[1]),
                a[2] + t * (b[2] - a[2]),
            );
            let ground = scenario
                .true_ground(x, y)
                .unwrap_or_else(|| scenario.terrain.bilinear(x, y));
            samples.push((along + t * length, z, ground));
        }
        along += length;
    }
    let band = scenario.height_band;
    let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
    // The track, the ground and the band's floor in view (the ceiling may be cut).
    for &(_, z, ground) in &samples {
        low = low.min(z).min(ground);
        high = high
            .max(z)
            .max(ground + band.map_or(minimum, |(floor, _)| floor.max(minimum)));
    }
    let margin = 0.06 * (high - low).max(1.0);
    let (low, high) = (low - margin, high + margin);
    let (width, height, left, right, top, bottom) = (860.0, 420.0, 70.0, 230.0, 40.0, 50.0);
    let plot_w = width - left - right;
    let plot_h = height - top - bottom;
    let length = along.max(1e-9);
    let px = |d: f64| left + d / length * plot_w;
    let py = |z: f64| top + (high - z) / (high - low) * plot_h;
    let line = |values: &mut dyn Iterator<Item = (f64, f64)>| -> String {
        let mut data = String::new();
        for (k, (d, z)) in values.enumerate() {
            let _ = write!(
                data,
                "{}{:.1},{:.1}",
                if k == 0 { "M" } else { " L" },
                px(d),
                py(z)
            );
        }
        data
    };
    let mut svg = String::new();
    let _ = write!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="DejaVu Sans, sans-serif" font-size="12"><rect width="100%" height="100%" fill="white"/><text x="{left}" y="22" font-size="14">{}</text>"#,
        escape(title)
    );
    let _ = write!(
        svg,
        r#"<clipPath id="plot"><rect x="{left}" y="{top}" width="{plot_w}" height="{plot_h}"/></clipPath><g clip-path="url(#plot)">"#
    );
    // The band as a shaded strip, the terrain filled, the minimum clearance dashed.
    if let Some((floor, ceiling)) = band {
        let upper = line(&mut samples.iter().map(|&(d, _, g)| (d, g + ceiling)));
        let lower: Vec<String> = samples
            .iter()
            .rev()
            .map(|&(d, _, g)| format!("L{:.1},{:.1}", px(d), py(g + floor)))
            .collect();
        let _ = write!(
            svg,
            r##"<path d="{upper} {} Z" fill="#56B4E9" fill-opacity="0.18" stroke="none"/>"##,
            lower.join(" ")
        );
    }
    let ground = line(&mut samples.iter().map(|&(d, _, g)| (d, g)));
    let _ = write!(
        svg,
        r##"<path d="{ground} L{:.1},{:.1} L{:.1},{:.1} Z" fill="#8B6B4A" fill-opacity="0.55" stroke="#5A4030" stroke-width="1.2"/>"##,
        px(length),
        py(low),
        px(0.0),
        py(low)
    );
    let clearance_line = line(&mut samples.iter().map(|&(d, _, g)| (d, g + minimum)));
    let _ = write!(
        svg,
        r##"<path d="{clearance_line}" fill="none" stroke="#A33" stroke-width="1" stroke-dasharray="5 3"/>"##
    );
    let flown = line(&mut samples.iter().map(|&(d, z, _)| (d, z)));
    let _ = write!(
        svg,
        r#"<path d="{flown}" fill="none" stroke="{}" stroke-width="2.2"/>"#,
        track.colour
    );
    // Where the track is closer to the terrain than the minimum (the vertical legs at the
    // start and the goal excepted).
    let exempt =
        |d: f64| (scenario.takes_off() && d < 1e-6) || (scenario.lands() && d > length - 1e-6);
    let mut unsafe_at = None;
    for &(d, z, g) in &samples {
        if z - g < minimum && !exempt(d) {
            unsafe_at.get_or_insert(d);
            let _ = write!(
                svg,
                r##"<circle cx="{:.1}" cy="{:.1}" r="2.5" fill="#D00"/>"##,
                px(d),
                py(z)
            );
        }
    }
    svg.push_str("</g>");
    if let Some(d) = unsafe_at {
        let _ = write!(
            svg,
            r##"<text x="{:.1}" y="{:.1}" fill="#D00" font-weight="bold">unsafe</text>"##,
            px(d) + 4.0,
            top + 16.0
        );
    }
    let lowest = samples
        .iter()
        .filter(|(d, _, _)| !exempt(*d))
        .min_by(|a, b| (a.1 - a.2).total_cmp(&(b.1 - b.2)));
    if let Some(&(d, z, g)) = lowest {
        let x = px(d);
        let _ = write!(
            svg,
            r##"<line x1="{x:.1}" x2="{x:.1}" y1="{:.1}" y2="{:.1}" stroke="#222" stroke-width="1.2"/><circle cx="{x:.1}" cy="{:.1}" r="3.5" fill="none" stroke="#222"/><text x="{:.1}" y="{:.1}" font-size="11">{}</text>"##,
            py(z),
            py(g),
            py(z),
            x + 6.0,
            py(z) - 8.0,
            lowest_words(z - g, track.lowest_clearance_m),
        );
    }
    for value in ticks(low, high, 6) {
        let y = py(value);
        let _ = write!(
            svg,
            r##"<line x1="{:.1}" x2="{left}" y1="{y:.1}" y2="{y:.1}" stroke="#444"/><text x="{:.1}" y="{:.1}" text-anchor="end" font-size="11">{}</text>"##,
            left - 5.0,
            left - 8.0,
            y + 4.0,
            tick_label(value)
        );
    }
    for value in ticks(0.0, length, 6) {
        let x = px(value);
        let _ = write!(
            svg,
            r##"<line x1="{x:.1}" x2="{x:.1}" y1="{:.1}" y2="{:.1}" stroke="#444"/><text x="{x:.1}" y="{:.1}" text-anchor="middle" font-size="11">{}</text>"##,
            top + plot_h,
            top + plot_h + 5.0,
            top + plot_h + 18.0,
            tick_label(value)
        );
    }
    let _ = write!(
        svg,
        r##"<rect x="{left}" y="{top}" width="{plot_w}" height="{plot_h}" fill="none" stroke="#444"/><text x="{:.1}" y="{:.1}" text-anchor="middle">distance along the track (m)</text><text transform="translate(16 {:.1}) rotate(-90)" text-anchor="middle">altitude above sea level (m)</text>"##,
        left + plot_w / 2.0,
        height - 12.0,
        top + plot_h / 2.0
    );
    let lx = left + plot_w + 16.0;
    let mut entries = vec![
        format!(
            r#"<line x1="{lx}" x2="{}" y1="{{y}}" y2="{{y}}" stroke="{}" stroke-width="3"/><text x="{}" y="{{t}}">{}</text>"#,
            lx + 22.0,
            track.colour,
            lx + 28.0,
            escape(track.label)
        ),
        format!(
            r##"<rect x="{lx}" y="{{r}}" width="22" height="10" fill="#8B6B4A" fill-opacity="0.55"/><text x="{}" y="{{t}}">terrain</text>"##,
            lx + 28.0
        ),
        format!(
            r##"<line x1="{lx}" x2="{}" y1="{{y}}" y2="{{y}}" stroke="#A33" stroke-dasharray="5 3"/><text x="{}" y="{{t}}">minimum clearance {} m</text>"##,
            lx + 22.0,
            lx + 28.0,
            tick_label(minimum)
        ),
    ];
    if let Some((floor, ceiling)) = band {
        entries.push(format!(
            r##"<rect x="{lx}" y="{{r}}" width="22" height="10" fill="#56B4E9" fill-opacity="0.3"/><text x="{}" y="{{t}}">band {}-{} m</text>"##,
            lx + 28.0,
            tick_label(floor),
            tick_label(ceiling)
        ));
    }
    for (index, entry) in entries.iter().enumerate() {
        let y = top + 12.0 + index as f64 * 22.0;
        let _ = write!(
            svg,
            "{}",
            entry
                .replace("{y}", &format!("{:.0}", y - 4.0))
                .replace("{r}", &format!("{:.0}", y - 9.0))
                .replace("{t}", &format!("{y:.0}"))
        );
    }
    svg.push_str("</svg>\n");
    svg
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pictures_mark_an_unsafe_track_and_show_the_legend() {
        let mut scenario = TrackScenario::seed000("I").unwrap();
        scenario.start = scenario.cruise_start;
        scenario.goal = scenario.cruise_goal;
        let ground = |x: f64, y: f64| scenario.true_ground(x, y).unwrap();
        let points = [
            [100.0, 100.0, ground(100.0, 100.0) + 120.0],
            [500.0, 500.0, ground(500.0, 500.0) + 1.0],
            [900.0, 900.0, ground(900.0, 900.0) + 120.0],
        ];
        let track = DrawnTrack {
            label: "test",
            colour: "#0072B2",
            points: &points,
            safe: false,
            lowest_clearance_m: None,
        };
        let profile = profile(&scenario, "profile", &track);
        assert!(profile.contains(">unsafe</text>"));
        assert!(profile.contains("lowest clearance 1.0 m"));
        assert_eq!(lowest_words(3.4, Some(3.38)), "lowest clearance 3.4 m");
        assert_eq!(
            lowest_words(3.4, Some(2.7)),
            "lowest 3.4 m above the ground; clearance 2.7 m in any direction"
        );
        assert!(profile.contains("minimum clearance 2 m"));
        let top = top_view(&scenario, "top", &[track]);
        assert!(top.contains("terrain height (m)") && top.contains("test (unsafe)"));
        assert!(top.contains(" m</text>"), "a scale bar");
    }
}
