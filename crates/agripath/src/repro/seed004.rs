//! Seed 004: fewest-turn grid coverage of the six 80 m × 80 m fields with obstacles. For each
//! field: turns, U-turns and non-spray distance of our HPSO, the boustrophedon baseline and our
//! constructive method, beside the paper's HPSO and Reeb-graph counts; the best single-direction
//! boustrophedon (decision 5's reference) and the axis-parallel lower bound; a map per field.

use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

use serde::Serialize;

use crate::error::InputError;
use crate::grid_cover::hybrid_pso::{self, HpsoSettings};
use crate::grid_cover::{
    axis_lower_bound, boustrophedon, fewest_turns, single_direction_turns, GridRoute, PointGrid,
    RouteMeasure,
};
use crate::input::{geojson, CoordinateChoice};

/// The six fields, compiled in: (name, GeoJSON).
pub const FIELDS: [(&str, &str); 6] = [
    (
        "single_1",
        include_str!("../../../../data/seed004_single_1.geojson"),
    ),
    (
        "single_2",
        include_str!("../../../../data/seed004_single_2.geojson"),
    ),
    (
        "single_3",
        include_str!("../../../../data/seed004_single_3.geojson"),
    ),
    (
        "double_1",
        include_str!("../../../../data/seed004_double_1.geojson"),
    ),
    (
        "double_2",
        include_str!("../../../../data/seed004_double_2.geojson"),
    ),
    (
        "triple",
        include_str!("../../../../data/seed004_triple.geojson"),
    ),
];

/// One method on one field.
#[derive(Debug, Clone, Serialize)]
pub struct MethodResult {
    /// Turns, U-turns, lengths and crossings of the route.
    pub measure: RouteMeasure,
    /// Whether the route visits every valid point exactly once.
    pub valid: bool,
    /// Planning time, milliseconds.
    pub milliseconds: f64,
    /// The route planned.
    #[serde(skip)]
    pub route: GridRoute,
}

/// One field's row.
#[derive(Debug, Clone, Serialize)]
pub struct FieldRow {
    /// The field's name, e.g. `single_1`.
    pub name: String,
    /// Number of grid points to visit.
    pub points: usize,
    /// The paper's HPSO turn count, when the field file gives it.
    pub paper_hpso: Option<u64>,
    /// The paper's Reeb-graph turn count, when the field file gives it.
    pub paper_reeb: Option<u64>,
    /// Turns of the best single-direction boustrophedon.
    pub single_direction: usize,
    /// Lower bound on the turns of any axis-parallel route.
    pub axis_lower_bound: usize,
    /// Our HPSO.
    pub hpso: MethodResult,
    /// The boustrophedon baseline.
    pub baseline: MethodResult,
    /// Our constructive fewest-turn method.
    pub ours: MethodResult,
    /// The grid of points the methods cover.
    #[serde(skip)]
    pub grid: PointGrid,
}

fn timed(grid: &PointGrid, plan: impl FnOnce() -> GridRoute) -> MethodResult {
    let started = Instant::now();
    let route = plan();
    let milliseconds = started.elapsed().as_secs_f64() * 1e3;
    MethodResult {
        measure: route.measure(grid),
        valid: route.visits_every_point_once(grid),
        milliseconds,
        route,
    }
}

/// Plans one field with every method.
pub fn field_row(name: &str, text: &str, hpso: &HpsoSettings) -> Result<FieldRow, InputError> {
    let label = format!("<embedded>/seed004_{name}.geojson");
    let farm = geojson::parse(Path::new(&label), text, CoordinateChoice::FromFile)?;
    let references: serde_json::Value = serde_json::from_str(text).unwrap_or_default();
    let swath = references["swath_width_m"].as_f64().unwrap_or(5.0);
    let grid = PointGrid::new(&farm, 0, swath).map_err(|fault| InputError::new(&label, fault))?;
    Ok(FieldRow {
        name: name.into(),
        points: grid.points.len(),
        paper_hpso: references["reference_turns"]["hybrid_pso"].as_u64(),
        paper_reeb: references["reference_turns"]["reeb_graph_euler_tour"].as_u64(),
        single_direction: single_direction_turns(&grid),
        axis_lower_bound: axis_lower_bound(&grid),
        hpso: timed(&grid, || hybrid_pso::plan(&grid, hpso).0),
        baseline: timed(&grid, || boustrophedon::plan(&grid)),
        ours: timed(&grid, || fewest_turns::plan(&grid)),
        grid,
    })
}

/// All six fields.
pub fn table(hpso: &HpsoSettings) -> Result<Vec<FieldRow>, InputError> {
    FIELDS
        .iter()
        .map(|(name, text)| field_row(name, text, hpso))
        .collect()
}

/// The table as text.
pub fn to_text(rows: &[FieldRow], hpso: &HpsoSettings) -> String {
    let mut text = String::new();
    let _ = writeln!(
        text,
        "Turns (every change of direction), U-turns in brackets, non-spray metres; HPSO {} particles × {} iterations, seed {}.\n",
        hpso.particles, hpso.iterations, hpso.seed
    );
    let _ = writeln!(
        text,
        "{:<9} {:>6} {:>11} {:>10} {:>12} {:>9} {:>16} {:>16} {:>16} {:>9} {:>9}",
        "field",
        "points",
        "paper HPSO",
        "paper Reeb",
        "1-direction",
        "lower bd",
        "HPSO (ours)",
        "baseline",
        "ours",
        "HPSO ms",
        "ours ms"
    );
    for row in rows {
        let show = |m: &MethodResult| {
            let mark = if m.valid && m.measure.crossings == 0 {
                ""
            } else {
                "!"
            };
            format!(
                "{}{} ({}) {:.0}",
                mark, m.measure.turns, m.measure.u_turns, m.measure.non_spray_m
            )
        };
        let _ = writeln!(
            text,
            "{:<9} {:>6} {:>11} {:>10} {:>12} {:>9} {:>16} {:>16} {:>16} {:>9.0} {:>9.1}",
            row.name,
            row.points,
            row.paper_hpso.map_or("-".into(), |v| v.to_string()),
            row.paper_reeb.map_or("-".into(), |v| v.to_string()),
            row.single_direction,
            row.axis_lower_bound,
            show(&row.hpso),
            show(&row.baseline),
            show(&row.ours),
            row.hpso.milliseconds,
            row.ours.milliseconds
        );
    }
    text
}

/// A map of one field with the three routes side by side (SVG).
pub fn map_svg(row: &FieldRow) -> String {
    let panels = [
        ("HPSO", &row.hpso.route),
        ("baseline", &row.baseline.route),
        ("ours", &row.ours.route),
    ];
    let labelled: Vec<(String, &GridRoute)> = panels
        .iter()
        .map(|(label, route)| {
            let m = route.measure(&row.grid);
            (
                format!(
                    "{} {label}: {} turns, {} U-turns, {:.0} m non-spray",
                    row.name, m.turns, m.u_turns, m.non_spray_m
                ),
                *route,
            )
        })
        .collect();
    crate::grid_cover::routes_svg(&row.grid, &labelled)
}
