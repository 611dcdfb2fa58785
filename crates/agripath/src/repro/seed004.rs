//! Seed 004: fewest-turn grid coverage of the six 80 m × 80 m fields with obstacles. For each
//! field: turns, U-turns and non-spray distance of our HPSO, the boustrophedon baseline and our
//! constructive method, beside the paper's HPSO and Reeb-graph counts; the best single-direction
//! boustrophedon (decision 5's reference) and the axis-parallel lower bound; a map per field.

use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

use serde::Serialize;

use crate::error::InputError;
use crate::grid_cover::hybrid_pso::{self, HpsoSettings, Initial, Placement};
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

/// The grid of one field file and the figures the file states (swath, the paper's counts).
fn grid_of(name: &str, text: &str) -> Result<(PointGrid, serde_json::Value), InputError> {
    let label = format!("<embedded>/seed004_{name}.geojson");
    let farm = geojson::parse(Path::new(&label), text, CoordinateChoice::FromFile)?;
    let references: serde_json::Value = serde_json::from_str(text).unwrap_or_default();
    let swath = references["swath_width_m"].as_f64().unwrap_or(5.0);
    let grid = PointGrid::new(&farm, 0, swath).map_err(|fault| InputError::new(&label, fault))?;
    Ok((grid, references))
}

/// Plans one field with every method.
pub fn field_row(name: &str, text: &str, hpso: &HpsoSettings) -> Result<FieldRow, InputError> {
    let (grid, references) = grid_of(name, text)?;
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
            let measure = route.measure(&row.grid);
            (
                crate::grid_cover::route_title(&row.name, label, &measure),
                *route,
            )
        })
        .collect();
    crate::grid_cover::routes_svg(&row.grid, &labelled)
}

/// The readings of HPSO's open choices that the ablation tries (issue 20, decision 0010): the
/// default, then one choice changed at a time, then the seeded start with more iterations.
pub fn ablation_readings() -> Vec<(String, HpsoSettings)> {
    let base = HpsoSettings::default();
    let with = |name: &str, settings: HpsoSettings| (name.to_string(), settings);
    vec![
        with(
            "default: random start, mutation rate 1, placement drawn, 1,000 iterations",
            base,
        ),
        with(
            "mutation rate 0.5",
            HpsoSettings {
                mutation_rate: 0.5,
                ..base
            },
        ),
        with(
            "mutation rate 0.1",
            HpsoSettings {
                mutation_rate: 0.1,
                ..base
            },
        ),
        with(
            "mutation rate 0 (crossovers only)",
            HpsoSettings {
                mutation_rate: 0.0,
                ..base
            },
        ),
        with(
            "placement (1): at the end",
            HpsoSettings {
                placement: Placement::End,
                ..base
            },
        ),
        with(
            "placement (2): where it was in the guide",
            HpsoSettings {
                placement: Placement::InPlace,
                ..base
            },
        ),
        with(
            "placement (3): at a random place",
            HpsoSettings {
                placement: Placement::Anywhere,
                ..base
            },
        ),
        with(
            "5,000 iterations",
            HpsoSettings {
                iterations: 5_000,
                ..base
            },
        ),
        with(
            "start: the baseline's route",
            HpsoSettings {
                initial: Initial::Baseline,
                ..base
            },
        ),
        with(
            "start: the single-direction boustrophedon",
            HpsoSettings {
                initial: Initial::SingleDirection,
                ..base
            },
        ),
        with(
            "start: single-direction, 5,000 iterations",
            HpsoSettings {
                initial: Initial::SingleDirection,
                iterations: 5_000,
                ..base
            },
        ),
        with(
            "start: single-direction, placement (1), 5,000 iterations",
            HpsoSettings {
                initial: Initial::SingleDirection,
                placement: Placement::End,
                iterations: 5_000,
                ..base
            },
        ),
    ]
}

/// One reading's runs: per field, the turns of the route of each seed and whether every route
/// is valid (every point once, no move through an obstacle).
#[derive(Debug, Clone, Serialize)]
pub struct AblationRow {
    /// What the reading changes.
    pub reading: String,
    /// Per field (in [`FIELDS`] order), per seed: the turns of HPSO's route.
    pub turns: Vec<Vec<usize>>,
    /// Whether every route of the reading is valid.
    pub valid: bool,
    /// Planning time of the reading over every field and seed, seconds.
    pub seconds: f64,
}

/// Runs every reading on the six fields with each of `seeds` (the seed of a reading's
/// settings is replaced by each in turn); `tick` is told each reading's name as it starts.
pub fn ablation(
    readings: &[(String, HpsoSettings)],
    seeds: &[u64],
    mut tick: impl FnMut(&str),
) -> Result<(Vec<AblationRow>, Vec<Option<u64>>), InputError> {
    let mut grids = Vec::new();
    let mut paper = Vec::new();
    for (name, text) in FIELDS {
        let (grid, references) = grid_of(name, text)?;
        paper.push(references["reference_turns"]["hybrid_pso"].as_u64());
        grids.push(grid);
    }
    // The two starting routes themselves, before any search: what a seeded swarm keeps or
    // improves on.
    let mut rows: Vec<AblationRow> = [
        (
            "start route: the baseline's, no search",
            boustrophedon::plan as fn(&PointGrid) -> GridRoute,
        ),
        (
            "start route: the single-direction boustrophedon, no search",
            boustrophedon::single_direction,
        ),
    ]
    .into_iter()
    .map(|(reading, plan)| {
        let started = Instant::now();
        let routes: Vec<(GridRoute, &PointGrid)> =
            grids.iter().map(|grid| (plan(grid), grid)).collect();
        AblationRow {
            reading: reading.into(),
            turns: routes
                .iter()
                .map(|(route, grid)| vec![route.measure(grid).turns])
                .collect(),
            valid: routes.iter().all(|(route, grid)| {
                route.visits_every_point_once(grid) && route.measure(grid).crossings == 0
            }),
            seconds: started.elapsed().as_secs_f64(),
        }
    })
    .collect();
    for (reading, settings) in readings {
        tick(reading);
        let started = Instant::now();
        let mut valid = true;
        let turns = grids
            .iter()
            .map(|grid| {
                seeds
                    .iter()
                    .map(|&seed| {
                        let route = hybrid_pso::plan(grid, &HpsoSettings { seed, ..*settings }).0;
                        let measure = route.measure(grid);
                        valid &= route.visits_every_point_once(grid) && measure.crossings == 0;
                        measure.turns
                    })
                    .collect()
            })
            .collect();
        rows.push(AblationRow {
            reading: reading.clone(),
            turns,
            valid,
            seconds: started.elapsed().as_secs_f64(),
        });
    }
    Ok((rows, paper))
}

/// The ablation as a Markdown table: per field the best and the median turns over the seeds,
/// and how many fields come within 1.2 × the paper's count (issue 20's bar).
pub fn ablation_markdown(rows: &[AblationRow], paper: &[Option<u64>], seeds: &[u64]) -> String {
    let mut text = String::new();
    let _ = writeln!(
        text,
        "HPSO turns per field, best / median of {} seeds ({:?}); the paper's count and 1.2 × it in the first row.\n",
        seeds.len(),
        seeds
    );
    let names: Vec<&str> = FIELDS.iter().map(|(name, _)| *name).collect();
    let _ = writeln!(
        text,
        "| reading | {} | fields ≤ 1.2 × paper | valid | s |",
        names.join(" | ")
    );
    let _ = writeln!(text, "|---|{}---|---|---|", "---|".repeat(names.len()));
    let bars: Vec<String> = paper
        .iter()
        .map(|p| p.map_or("-".into(), |p| format!("{p} (≤ {:.1})", 1.2 * p as f64)))
        .collect();
    let _ = writeln!(text, "| the paper's HPSO | {} | | | |", bars.join(" | "));
    for row in rows {
        let mut within = 0;
        let cells: Vec<String> = row
            .turns
            .iter()
            .zip(paper)
            .map(|(runs, paper)| {
                let mut sorted = runs.clone();
                sorted.sort_unstable();
                let (best, median) = (sorted[0], sorted[sorted.len() / 2]);
                if paper.is_some_and(|p| best as f64 <= 1.2 * p as f64) {
                    within += 1;
                }
                format!("{best} / {median}")
            })
            .collect();
        let _ = writeln!(
            text,
            "| {} | {} | {within} of {} | {} | {:.1} |",
            row.reading,
            cells.join(" | "),
            paper.len(),
            if row.valid { "yes" } else { "NO" },
            row.seconds
        );
    }
    text
}
