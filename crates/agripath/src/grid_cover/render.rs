//! What `agripath grid` writes: the route as GeoJSON, the report and the SVG map of one or
//! several routes over the field's path points.

use geo::Polygon;

use super::{axis_lower_bound, single_direction_turns, GridRoute, PointGrid};
use crate::model::Farm;

/// The files of `agripath grid`: `plan.geojson` (field, obstacles, the route as a `grid_route`
/// LineString with its figures, every path point as a `waypoint` with its `seq`),
/// `report.json` and `plan.svg`; and the map's title.
pub fn render(
    farm: &Farm,
    field: usize,
    grid: &PointGrid,
    route: &GridRoute,
    method: &str,
    runtime_s: f64,
) -> (Vec<(&'static str, Vec<u8>)>, String) {
    use serde_json::json;
    let measure = route.measure(grid);
    let system = farm.coordinate_system;
    let position = |x: f64, y: f64| {
        let (a, b) = system.to_input(x, y);
        json!([a, b])
    };
    let ring = |polygon: &Polygon<f64>| -> Vec<serde_json::Value> {
        polygon
            .exterior()
            .0
            .iter()
            .map(|c| position(c.x, c.y))
            .collect()
    };
    let name = &farm.fields[field].name;
    let mut features = vec![
        json!({"type": "Feature", "properties": {"kind": "field", "name": name},
        "geometry": {"type": "Polygon", "coordinates": [ring(&farm.fields[field].polygon)]}}),
    ];
    for obstacle in &farm.obstacles {
        features.push(
            json!({"type": "Feature", "properties": {"kind": "obstacle", "name": obstacle.name},
            "geometry": {"type": "Polygon", "coordinates": [ring(&obstacle.polygon)]}}),
        );
    }
    let line: Vec<serde_json::Value> = route
        .polyline(grid)
        .iter()
        .map(|c| position(c.x, c.y))
        .collect();
    features.push(json!({"type": "Feature",
        "properties": {"kind": "grid_route", "method": method, "seq": 0, "sortie": 0, "turns": measure.turns,
                       "u_turns": measure.u_turns, "non_spray_m": crate::numbers::round(measure.non_spray_m, 1e-4),
                       "length_m": crate::numbers::round(measure.length_m, 1e-4)},
        "geometry": {"type": "LineString", "coordinates": line}}));
    for (seq, &visit) in route.visits.iter().enumerate() {
        let c = grid.centre(visit);
        features.push(
            json!({"type": "Feature", "properties": {"kind": "waypoint", "seq": seq},
            "geometry": {"type": "Point", "coordinates": position(c.x, c.y)}}),
        );
    }
    let mut collection = json!({"type": "FeatureCollection", "features": features});
    if system == crate::model::CoordinateSystem::Local {
        collection["crs"] = json!("local");
    }
    let report = json!({
        "field": name, "method": method, "swath_width_m": grid.cell_m,
        "points": grid.points.len(), "turns": measure.turns, "u_turns": measure.u_turns,
        "non_spray_m": crate::numbers::round(measure.non_spray_m, 1e-4),
        "length_m": crate::numbers::round(measure.length_m, 1e-4),
        "single_direction_turns": single_direction_turns(grid),
        "axis_lower_bound_turns": axis_lower_bound(grid),
        "runtime_s": crate::numbers::round(runtime_s, 1e-4),
    });
    let title = route_title(name, method, &measure);
    let files = vec![
        (
            "plan.geojson",
            (serde_json::to_string_pretty(&collection).expect("JSON") + "\n").into_bytes(),
        ),
        (
            "report.json",
            (serde_json::to_string_pretty(&report).expect("JSON") + "\n").into_bytes(),
        ),
        (
            "plan.svg",
            routes_svg(grid, &[(title.clone(), route)]).into_bytes(),
        ),
    ];
    (files, title)
}

/// A route's panel title: "NAME METHOD: T turns, U U-turns, M m non-spray".
pub fn route_title(name: &str, method: &str, measure: &super::RouteMeasure) -> String {
    format!(
        "{name} {method}: {} turns, {} U-turn{}, {:.0} m non-spray",
        measure.turns,
        measure.u_turns,
        if measure.u_turns == 1 { "" } else { "s" },
        measure.non_spray_m
    )
}

/// Routes over a grid side by side, one titled panel each (SVG): the field's box, the points
/// no route may visit (red), the flown polyline, its start (orange).
pub fn routes_svg(grid: &PointGrid, routes: &[(String, &GridRoute)]) -> String {
    use std::fmt::Write;
    let panel = 320.0;
    let scale = (panel - 40.0) / (grid.columns.max(grid.rows) as f64 * grid.cell_m);
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" font-family="sans-serif" font-size="11"><rect width="100%" height="100%" fill="white"/>"##,
        routes.len() as f64 * panel,
        grid.rows as f64 * grid.cell_m * scale + 64.0
    );
    for (k, (title, route)) in routes.iter().enumerate() {
        let left = k as f64 * panel + 20.0;
        let top = 44.0;
        let x = |v: f64| left + (v - grid.origin.x) * scale;
        let y = |v: f64| top + (grid.rows as f64 * grid.cell_m - (v - grid.origin.y)) * scale;
        let escaped = title.replace('&', "&amp;").replace('<', "&lt;");
        // "NAME: figures" on two lines, so neighbouring panels' titles do not run together.
        let (head, figures) = escaped.split_once(": ").unwrap_or((escaped.as_str(), ""));
        let _ = writeln!(
            svg,
            r##"<text x="{left}" y="16" font-weight="bold">{head}</text><text x="{left}" y="31">{figures}</text>"##
        );
        let _ = writeln!(
            svg,
            r##"<rect x="{left}" y="{top}" width="{:.1}" height="{:.1}" fill="#eef5e6" stroke="#4a7a2a"/>"##,
            grid.columns as f64 * grid.cell_m * scale,
            grid.rows as f64 * grid.cell_m * scale
        );
        for index in (0..grid.valid.len()).filter(|&i| !grid.valid[i]) {
            let c = grid.centre(index);
            let _ = writeln!(
                svg,
                r##"<circle cx="{:.1}" cy="{:.1}" r="2.5" fill="#c62828"/>"##,
                x(c.x),
                y(c.y)
            );
        }
        let line = route.polyline(grid);
        let points: Vec<String> = line
            .iter()
            .map(|c| format!("{:.1},{:.1}", x(c.x), y(c.y)))
            .collect();
        let _ = writeln!(
            svg,
            r##"<polyline points="{}" fill="none" stroke="#0072B2" stroke-width="1.5" stroke-linejoin="round"/>"##,
            points.join(" ")
        );
        if let Some(first) = line.first() {
            let _ = writeln!(
                svg,
                r##"<circle cx="{:.1}" cy="{:.1}" r="4" fill="#E69F00"/>"##,
                x(first.x),
                y(first.y)
            );
        }
    }
    svg.push_str("</svg>\n");
    svg
}
