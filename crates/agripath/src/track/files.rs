//! What `agripath track` writes: the best track of each planner as GeoJSON and as mission
//! waypoints, the runs' statistics, a top view, an altitude profile and convergence curves.

use std::fmt::Write;

use serde_json::{json, Value};

use super::picture as track_svg;
use super::planner::{statistics, Planner, TrackRun};
use super::scenario::TrackScenario;
use crate::mission::flight::{Action, Item, MissionSettings, SortieMission};
use crate::mission::wpl;
use crate::plot::line_chart::{self, Chart, Series};

/// The runs of one planner.
pub struct PlannerRuns {
    /// The planner.
    pub planner: Planner,
    /// The encoding its vectors used.
    pub encoding: super::Encoding,
    /// Its runs, in run order.
    pub runs: Vec<TrackRun>,
}

impl PlannerRuns {
    /// The result's name in file names: the planner's key, with the encoding's where another
    /// result of `results` has the same planner (`repro spso` runs IBA-FCS on two encodings,
    /// whose files would otherwise overwrite each other).
    pub fn file_key(&self, results: &[PlannerRuns]) -> String {
        let shared = results
            .iter()
            .filter(|other| other.planner == self.planner)
            .count()
            > 1;
        if shared {
            format!("{}-{}", self.planner.key(), self.encoding.key())
        } else {
            self.planner.key().to_string()
        }
    }

    /// The result's name in legends: the planner's label, with the encoding's where another
    /// result of `results` has the same planner.
    pub fn legend_label(&self, results: &[PlannerRuns]) -> String {
        if results.iter().filter(|o| o.planner == self.planner).count() > 1 {
            format!("{} ({})", self.planner.label(), self.encoding.key())
        } else {
            self.planner.label().to_string()
        }
    }

    /// The track handed over: the safe run with the lowest final cost, or the lowest-cost
    /// run when none is safe (the first of equals).
    pub fn best(&self) -> &TrackRun {
        fn lowest<'r>(runs: impl Iterator<Item = &'r TrackRun>) -> Option<&'r TrackRun> {
            runs.min_by(|a, b| a.final_cost().total_cmp(&b.final_cost()))
        }
        lowest(self.runs.iter().filter(|run| run.is_safe()))
            .or_else(|| lowest(self.runs.iter()))
            .expect("at least one run")
    }

    /// The verdict of the track handed over.
    pub fn verdict(&self) -> &super::safety::Verdict {
        let best = self.best();
        match &best.smoothed {
            Some(smoothed) if smoothed.verdict.is_safe() => &smoothed.verdict,
            _ => &best.verdict,
        }
    }

    /// Why the planner found no safe track: its best track's worst violation.
    pub fn unsafe_reason(&self) -> Option<String> {
        let verdict = self.verdict();
        (!verdict.is_safe()).then(|| {
            format!(
                "{}: no safe track in {} run{}; the best: {}",
                self.planner.label(),
                self.runs.len(),
                if self.runs.len() == 1 { "" } else { "s" },
                verdict.worst().unwrap_or("unsafe")
            )
        })
    }
}

/// Mission waypoints of a whole track: takeoff at the start, climbing to the cruise's first
/// altitude (vertically above the start), the cruise's waypoints as
/// [`super::flown::mission_cruise`] keeps them, the last above the goal, and land at the goal
/// (a vertical descent: ArduPilot flies a NAV_LAND's place at the altitude it has, so the
/// point above the goal is always a waypoint of its own); altitudes above sea level.
pub fn mission(scenario: &TrackScenario, track: &[[f64; 3]]) -> String {
    let item = |action: Action, p: [f64; 3]| {
        let (lon, lat) = scenario.lon_lat(p[0], p[1]);
        let ground = scenario.terrain.height(p[0], p[1]);
        Item {
            action,
            lon,
            lat,
            ground_m: ground,
            above_ground_m: p[2] - ground,
        }
    };
    let cruise = super::flown::mission_cruise(scenario, track);
    // A takeoff item climbs above its own position to its altitude.
    let mut items = vec![item(Action::Takeoff, cruise[0])];
    for &point in &cruise[1..] {
        items.push(item(Action::Waypoint, point));
    }
    let last = cruise[cruise.len() - 1];
    // The landing's row gives where it ends: the goal, or the ground beneath the last point
    // when the goal is in the air (ArduPilot ignores a NAV_LAND's altitude).
    items.push(item(
        Action::Land,
        if scenario.lands() {
            track[track.len() - 1]
        } else {
            [last[0], last[1], scenario.terrain.height(last[0], last[1])]
        },
    ));
    let mission = SortieMission {
        sortie: 1,
        // Home is the ground under the start (the start itself when the track takes off
        // from the ground).
        home: Item {
            above_ground_m: 0.0,
            ..item(Action::Takeoff, track[0])
        },
        items,
    };
    let settings = MissionSettings {
        altitude: crate::mission::flight::AltitudeReference::SeaLevel,
        ..MissionSettings::default()
    };
    wpl::waypoints_file(&mission, &settings)
}

fn circle(x: f64, y: f64, radius: f64) -> Vec<[f64; 2]> {
    (0..=48)
        .map(|k| {
            let angle = std::f64::consts::TAU * k as f64 / 48.0;
            [x + radius * angle.cos(), y + radius * angle.sin()]
        })
        .collect()
}

/// The GeoJSON, in the scenario's input coordinates (longitude/latitude for a scenario given
/// in lon/lat, else its local frame with `"crs": "local"`), z above sea level: threats, start,
/// goal, and each planner's best track with its waypoints.
pub fn geojson(scenario: &TrackScenario, results: &[PlannerRuns]) -> String {
    let position = |p: [f64; 3]| {
        let (a, b) = scenario.to_input(p[0], p[1]);
        [a, b, p[2]]
    };
    let mut features: Vec<Value> = scenario
        .threats
        .iter()
        .enumerate()
        .map(|(index, threat)| {
            let ring: Vec<[f64; 2]> = circle(threat.x, threat.y, threat.radius)
                .into_iter()
                .map(|[x, y]| {
                    let (a, b) = scenario.to_input(x, y);
                    [a, b]
                })
                .collect();
            json!({"type": "Feature", "properties": {"kind": "threat", "index": index, "radius": threat.radius},
                   "geometry": {"type": "Polygon", "coordinates": [ring]}})
        })
        .collect();
    for (kind, point) in [("start", scenario.start), ("goal", scenario.goal)] {
        let p = position(scenario.sea_level(point));
        features.push(json!({"type": "Feature", "properties": {"kind": kind},
            "geometry": {"type": "Point", "coordinates": p}}));
    }
    for result in results {
        let best = result.best();
        let verdict = result.verdict();
        let points: Vec<[f64; 3]> = best.final_points().iter().map(|&p| position(p)).collect();
        features.push(json!({"type": "Feature",
            "properties": {"kind": "track", "planner": result.planner.label(),
                           "encoding": result.encoding.key(), "run": best.run,
                           "cost": best.final_cost(), "safe": verdict.is_safe(),
                           "lowest_clearance_m": verdict.lowest_clearance_m,
                           "threat_margin_m": verdict.threat_margin_m,
                           "outside_band_m": verdict.outside_band_m,
                           "violations": verdict.violations},
            "geometry": {"type": "LineString", "coordinates": points}}));
        let inner = best.points.len().saturating_sub(2);
        for (seq, &p) in best.points.iter().enumerate().skip(1).take(inner) {
            features.push(json!({"type": "Feature",
                "properties": {"kind": "waypoint", "planner": result.planner.label(),
                               "encoding": result.encoding.key(), "seq": seq},
                "geometry": {"type": "Point", "coordinates": position(p)}}));
        }
    }
    let mut collection =
        json!({"type": "FeatureCollection", "name": scenario.name, "features": features});
    if scenario.is_local() {
        collection["crs"] = json!("local");
    }
    serde_json::to_string_pretty(&collection).expect("JSON values serialise") + "\n"
}

/// The runs' statistics per planner, with each best track's cost terms and safety.
pub fn report(scenario: &TrackScenario, results: &[PlannerRuns], seed: u64) -> String {
    let names = scenario.cost.term_names();
    let planners: Vec<Value> = results
        .iter()
        .map(|result| {
            let stats = statistics(&result.runs);
            let best = result.best();
            let verdict = result.verdict();
            let terms: serde_json::Map<String, Value> = names
                .iter()
                .zip(best.cost.terms)
                .map(|(name, value)| ((*name).to_string(), json!(value)))
                .collect();
            json!({
                "planner": result.planner.label(),
                "encoding": result.encoding.key(),
                "runs": stats.runs,
                "safe_runs": stats.safe_runs,
                "best": stats.best, "worst": stats.worst, "mean": stats.mean,
                "standard_deviation": stats.standard_deviation,
                "mean_runtime_s": stats.mean_seconds,
                "evaluations_per_run": best.evaluations,
                "best_run": {"run": best.run, "cost": best.final_cost(), "terms": terms,
                             "safe": verdict.is_safe(),
                             "lowest_clearance_m": verdict.lowest_clearance_m,
                             "lowest_clearance_at": scenario.to_input(verdict.lowest_clearance_at[0], verdict.lowest_clearance_at[1]),
                             "threat_margin_m": verdict.threat_margin_m,
                             "outside_band_m": verdict.outside_band_m,
                             "smoothed": best.smoothed.as_ref().map(|s| json!({"cost": s.cost.total, "safe": s.verdict.is_safe(), "violations": s.verdict.violations})),
                             "violations": verdict.violations},
                "costs": result.runs.iter().map(TrackRun::final_cost).collect::<Vec<_>>(),
            })
        })
        .collect();
    let report = json!({
        "scenario": scenario.name,
        "cost_model": scenario.cost.label(),
        "free_waypoints": scenario.free_waypoints,
        "scenario_evaluation_budget": scenario.evaluation_budget(),
        "seed": seed,
        "safety": {"min_clearance_m": scenario.limits.min_clearance_m,
                   "vehicle_radius_m": scenario.limits.vehicle_radius_m,
                   "sample_spacing_m": super::safety::SAMPLE_SPACING_M,
                   "takeoff_climb_m": scenario.takes_off().then(|| scenario.sea_level(scenario.cruise_start)[2] - scenario.sea_level(scenario.start)[2]),
                   "landing_descent_m": scenario.lands().then(|| scenario.sea_level(scenario.cruise_goal)[2] - scenario.sea_level(scenario.goal)[2])},
        "safe": results.iter().any(|result| result.verdict().is_safe()),
        "planners": planners,
    });
    serde_json::to_string_pretty(&report).expect("JSON values serialise") + "\n"
}

/// Mean best cost against evaluations, one curve per planner (100 points each).
pub fn convergence(scenario: &TrackScenario, results: &[PlannerRuns]) -> String {
    let series: Vec<Series> = results
        .iter()
        .map(|result| {
            let budget = result.runs.iter().map(|r| r.evaluations).max().unwrap_or(1) as f64;
            let points = (1..=100)
                .map(|k| {
                    let at = budget * k as f64 / 100.0;
                    let mean = result
                        .runs
                        .iter()
                        .map(|run| {
                            run.history
                                .iter()
                                .take_while(|record| record.evaluations as f64 <= at)
                                .last()
                                .map_or(f64::NAN, |record| record.best_cost)
                        })
                        .sum::<f64>()
                        / result.runs.len() as f64;
                    (at, mean)
                })
                .filter(|(_, mean)| mean.is_finite())
                .collect();
            Series {
                name: result.legend_label(results),
                points,
            }
        })
        .collect();
    let colours: Vec<&str> = results
        .iter()
        .map(|result| result.planner.colour())
        .collect();
    line_chart::render_coloured(
        &Chart {
            title: &format!("{}: mean best cost", scenario.name),
            x_label: "evaluations",
            y_label: "cost",
            log_y: true,
        },
        &series,
        &colours,
    )
}

/// The table `agripath track` prints.
pub fn table(scenario: &TrackScenario, results: &[PlannerRuns]) -> String {
    let mut text = format!(
        "{} — {} ({} free waypoints, {} evaluations per run)\n\n| planner | encoding | best | worst | mean | std | safe runs | s/run |\n|---|---|---:|---:|---:|---:|---:|---:|\n",
        scenario.name,
        scenario.cost.label(),
        scenario.free_waypoints,
        results
            .iter()
            .flat_map(|result| result.runs.iter().map(|run| run.evaluations))
            .max()
            .unwrap_or(0)
    );
    for result in results {
        let s = statistics(&result.runs);
        let _ = writeln!(
            text,
            "| {} | {} | {} |",
            result.planner.label(),
            result.encoding.key(),
            s.cells(2)
        );
    }
    // A safe track whose cost holds a penalty: the cost model's ground is the planners'
    // conservative raster (grown by the clearance sideways, decision 0032), the verdict the
    // exact check; such runs lift the mean and the spread.
    let penalised = results
        .iter()
        .flat_map(|result| &result.runs)
        .filter(|run| run.verdict.is_safe() && super::cost::legs_too_low(scenario, &run.points) > 0)
        .count();
    if penalised > 0 {
        let _ = writeln!(
            text,
            "\n{penalised} safe run(s) carry the cost model's penalty of {:.0} per leg that its conservative ground (the terrain raised by the clearance sideways, decision 0032) finds too low, where the exact check finds the track safe; they lift the mean and std.",
            super::cost::PENALTY
        );
    }
    text
}

/// Every file of `agripath track`, by name. A planner's `.waypoints` are written only when
/// its track is safe, unless `allow_unsafe`.
pub fn files(
    scenario: &TrackScenario,
    results: &[PlannerRuns],
    seed: u64,
    allow_unsafe: bool,
) -> Result<Vec<(String, Vec<u8>)>, String> {
    let mut files = vec![
        (
            "track.geojson".to_string(),
            geojson(scenario, results).into_bytes(),
        ),
        (
            "report.json".to_string(),
            report(scenario, results, seed).into_bytes(),
        ),
        (
            "table.md".to_string(),
            table(scenario, results).into_bytes(),
        ),
        (
            "convergence.svg".to_string(),
            convergence(scenario, results).into_bytes(),
        ),
    ];
    let labels: Vec<String> = results
        .iter()
        .map(|result| result.legend_label(results))
        .collect();
    let drawn: Vec<track_svg::DrawnTrack> = results
        .iter()
        .zip(&labels)
        .map(|(result, label)| track_svg::DrawnTrack {
            label,
            colour: result.planner.colour(),
            points: result.best().final_points(),
            safe: result.verdict().is_safe(),
            lowest_clearance_m: Some(result.verdict().lowest_clearance_m)
                .filter(|metres| metres.is_finite()),
        })
        .collect();
    let top = track_svg::top_view(scenario, &scenario.name, &drawn);
    #[cfg(feature = "png")]
    files.push((
        "top_view.png".to_string(),
        crate::plot::raster::svg_to_png(&top, 1200)?,
    ));
    files.push(("top_view.svg".to_string(), top.into_bytes()));
    for (result, track) in results.iter().zip(&drawn) {
        let key = result.file_key(results);
        if track.safe || allow_unsafe {
            files.push((
                format!("{key}.waypoints"),
                mission(scenario, track.points).into_bytes(),
            ));
        }
        let title = format!(
            "{}: altitude profile of the best track ({}){}",
            scenario.name,
            track.label,
            if track.safe { "" } else { ", UNSAFE" }
        );
        files.push((
            format!("profile_{key}.svg"),
            track_svg::profile(scenario, &title, track).into_bytes(),
        ));
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::Encoding;

    fn result(planner: Planner, encoding: Encoding) -> PlannerRuns {
        PlannerRuns {
            planner,
            encoding,
            runs: Vec::new(),
        }
    }

    #[test]
    fn one_planner_on_two_encodings_gets_two_file_names() {
        let iba = Planner::parse("iba-fcs").unwrap();
        let results = [
            result(iba, Encoding::Cartesian),
            result(iba, Encoding::Spherical),
            result(Planner::Lattice, Encoding::Cartesian),
        ];
        let keys: Vec<String> = results.iter().map(|r| r.file_key(&results)).collect();
        assert_eq!(
            keys,
            [
                format!("{}-cartesian", iba.key()),
                format!("{}-spherical", iba.key()),
                "lattice".to_string()
            ]
        );
        assert_ne!(
            results[0].legend_label(&results),
            results[1].legend_label(&results)
        );
        assert_eq!(results[2].legend_label(&results), Planner::Lattice.label());
    }
}
