//! `report.json`: the plan's figures per field and in total (contract in `docs/cli.md`).

mod notes;
mod sortie_report;
pub mod supply;

use serde::Serialize;

use crate::coverage::heading::HeadingObjective;
use crate::coverage::{CoveragePlan, CoverageSettings};
use crate::model::Vehicle;
use crate::numbers::round;
use crate::scenario::Scenario;
use crate::sequence::ant_colony::AntColonySettings;
use crate::sequence::{Route, Sequencer};
use crate::settings::PlanSettings;
use crate::sortie::PlannedSorties;
use crate::sortie::SortiePlanner;
use notes::{far_fields_note, small_tank_note, terrain_warning};
pub use sortie_report::SortieReport;

/// One field's figures in `report.json`.
#[derive(Debug, Clone, Serialize)]
pub struct FieldReport {
    /// The field's name.
    pub name: String,
    /// Chosen heading, degrees from east, counter-clockwise, 0..180 (the seed's angle).
    pub heading_deg: f64,
    /// The same heading as a true bearing of the swaths, 0..180 (0 = true north, clockwise):
    /// the grid bearing plus the grid convergence at the field's middle.
    pub heading_bearing_deg: f64,
    /// The best heading of the 1° scan (seed 001's answer).
    pub heading_integer_deg: f64,
    /// Objective at the chosen and at the integer heading (eq. 1 for the seed objective).
    pub objective: f64,
    /// Objective at the integer heading.
    pub objective_integer: f64,
    /// Interior swaths (seed 001's N) and their draped length (its L), metres.
    pub swaths: usize,
    /// Draped length of the interior swaths, metres.
    pub spray_length_m: f64,
    /// Number of edge passes (a ring whose corners are cut counts once per piece).
    pub edge_passes: usize,
    /// Corners of edge passes flown spray-off across rather than sprayed twice (decision
    /// 0019), and the double dose that saves by the corner model, m².
    pub edge_corners_cut: usize,
    /// Double dose the cut corners save, m² (the corner model's figure; the preflight's
    /// read-back measures the whole field as flown).
    pub edge_corners_saved_m2: f64,
    /// Draped length of the edge passes, metres.
    pub edge_length_m: f64,
    /// Sprayable area (the field less holes, obstacles and margins), m².
    pub sprayable_area_m2: f64,
    /// Share of the sprayable area under at least one strip, 0..1.
    pub covered_fraction: f64,
    /// Area sprayed more than once, m² (counted once per extra pass).
    pub overlap_m2: f64,
    /// Strip area outside the sprayable region, m².
    pub outside_m2: f64,
}

/// The whole `report.json`: the plan's settings and figures per field and in total.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// The scenario's name.
    pub scenario: String,
    /// The coordinate system, as [`crate::model::CoordinateSystem::describe`] words it.
    pub coordinate_system: String,
    /// The vehicle's name.
    pub vehicle: String,
    /// The vehicle planned for, every figure (its file's keys, the command line's overrides
    /// applied): what `agripath check` holds the vehicle it flies with against.
    pub vehicle_settings: Vehicle,
    /// Swath width, metres.
    pub swath_width_m: f64,
    /// Height above the terrain while spraying, metres.
    pub spray_height_m: f64,
    /// Seed 001's h: the climb above spray height for a transfer that leaves the work area, metres.
    pub safe_height_m: f64,
    /// How coverage was laid out.
    pub settings: CoverageSettings,
    /// How the passes were ordered.
    pub sequencer: Sequencer,
    /// Launch point in the input's coordinates, when the flight has one.
    pub start: Option<[f64; 2]>,
    /// The supply point, the rule that chose it and what it saves (`null`: a free start).
    pub supply: Option<supply::SupplyReport>,
    /// Each field's figures, in the farm's order.
    pub fields: Vec<FieldReport>,
    /// Interior swaths, metres.
    pub spray_length_m: f64,
    /// Edge passes, metres.
    pub edge_length_m: f64,
    /// Every leg flown (from the launch point, between passes, home) with their 2h climbs
    /// (seed 001 eq. 8), metres; a transfer that a return to the supply point replaces is not
    /// flown and not counted.
    pub transfer_length_m: f64,
    /// What the sequencer minimised, over the order before it is split into sorties: from
    /// the launch point through every pass and home, or the open path's transfers with no
    /// launch point (decision 0018), metres. The transfers a return replaces are in it but not
    /// flown, so with sorties it exceeds `transfer_length_m`.
    pub tour_cost_m: f64,
    /// Number of legs flown: from the launch point, between passes, home.
    pub transfers: usize,
    /// Legs among them that climb by h.
    pub climbing_transfers: usize,
    /// Changes of direction along the flight (every angle counts) and U-turns among them.
    pub turns: usize,
    /// U-turns among the turns.
    pub u_turns: usize,
    /// Flights from the supply point and back (1 when the route is not split).
    pub sorties: usize,
    /// How the returns were chosen (`null`: not split).
    pub sortie_planner: Option<SortiePlanner>,
    /// Σ over the returns of the legs to the supply point and back out (2 (‖P_n, P0‖ + H_n)
    /// when the sortie resumes where it returned), metres.
    pub return_length_m: f64,
    /// What the operator pays in distance: `transfer_length_m + return_length_m`, metres.
    pub non_spray_length_m: f64,
    /// Return round trips plus max(battery swap, refill) at each return (seed 003 Table 4's
    /// non-spraying time), seconds.
    pub return_time_s: f64,
    /// Battery time each sortie keeps back, seconds (`null`: not split): the landing share
    /// (the vehicle's `battery_reserve_percent`), the climbs to spray and safe height and the
    /// descents eq. 2 does not charge, the worst climb over the terrain between the supply
    /// point and any pass, and `battery_replan_s`.
    pub battery_reserve_s: Option<f64>,
    /// Battery seconds held back because the plan as first written flew a sortie over the
    /// usable battery and was made again (`pipeline::render_flyable`); 0 when the first plan
    /// flew.
    pub battery_replan_s: f64,
    /// Per sortie: spray metres, litres, flight time, tank and battery used (seed 003 Table 5).
    pub sortie_details: Vec<SortieReport>,
    /// Sprayable area of all fields, m².
    pub sprayable_area_m2: f64,
    /// Share of the sprayable area under at least one strip, 0..1 (area-weighted over the fields).
    pub covered_fraction: f64,
    /// Area sprayed more than once over all fields, m².
    pub overlap_m2: f64,
    /// Spraying time: interior swaths and edge passes at spray speed, seconds.
    pub spray_time_s: f64,
    /// Litres for the whole plan: the application rate over the swath-wide strips of every
    /// spray metre (`null` when the vehicle gives no rate). The sorties' litres add up to it.
    pub litres: Option<f64>,
    /// A survey vehicle's camera work (absent for a sprayer, whose report it leaves as it was).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub survey: Option<SurveyReport>,
    /// Transfers and returns to the supply point, seconds.
    pub non_spray_time_s: f64,
    /// Spraying and non-spraying time, seconds.
    pub total_time_s: f64,
    /// Wall time of planning; the one figure that differs between identical runs.
    pub runtime_s: f64,
    /// How the mission files give altitudes (`relative`, `sea-level`, `terrain`)…
    pub altitude_reference: crate::mission::flight::AltitudeReference,
    /// …and what that assumes about the ground.
    pub altitude_assumption: String,
    /// Why the plan's terrain may not be the ground it will fly over (`null` when it is a DEM,
    /// or a farm in local metres, the papers' flat ground): printed as a `warning:` line.
    /// Always present (a reader's key does not come and go with the terrain; trial 7).
    pub terrain_warning: Option<String>,
    /// What the mission files were asked for (altitude reference, sprayer, terrain tolerance,
    /// origin of a local frame, fence margin): what `agripath check` holds them to.
    pub mission: crate::mission::flight::MissionSettings,
    /// The preflight check of the mission files as written (`null` before it has run).
    pub preflight: Option<crate::preflight::Verdict>,
}

/// What a survey flies with its camera on (decision 0022).
#[derive(Debug, Clone, Serialize)]
pub struct SurveyReport {
    /// Ground distance between photos along a swath, metres.
    pub trigger_distance_m: f64,
    /// Swaths and edge passes flown with the camera triggering, metres.
    pub survey_length_m: f64,
    /// Photos to expect: survey length / trigger distance (each swath adds its first
    /// photo, so the camera takes a few more).
    pub photos_estimate: u64,
}

/// Flight time of the transfers: legs inside a field at turn speed; climbing legs at transit
/// speed plus the 2h climb and descent at climb and descent speed.
pub fn transfer_time_s(route: &Route, sorties: Option<&PlannedSorties>, vehicle: &Vehicle) -> f64 {
    flown_legs(route, sorties)
        .into_iter()
        .map(|transfer| {
            if transfer.climbs {
                (transfer.cost_m - 2.0 * vehicle.safe_height_m) / vehicle.transit_speed_mps
                    + vehicle.vertical_s(vehicle.safe_height_m)
                    + vehicle.vertical_s(-vehicle.safe_height_m)
            } else {
                transfer.cost_m / vehicle.turn_speed_mps
            }
        })
        .sum()
}

/// The legs flown between passes: every leg of the route, less the transfers a return to the
/// supply point skipped.
pub fn flown_legs<'r>(
    route: &'r Route,
    sorties: Option<&PlannedSorties>,
) -> Vec<&'r crate::sequence::Transfer> {
    match sorties {
        Some(split) => split.flown_legs(route).collect(),
        None => route.legs().collect(),
    }
}

impl Report {
    /// The report of a planned mission; `preflight` is left `None` for the check to fill in.
    pub fn new(
        scenario: &Scenario,
        plan: &CoveragePlan,
        route: &Route,
        sorties: Option<&PlannedSorties>,
        settings: &PlanSettings,
        runtime_s: f64,
    ) -> Self {
        let vehicle = &scenario.vehicle;
        let fields: Vec<FieldReport> = plan
            .fields
            .iter()
            .map(|field| FieldReport {
                name: field.name.clone(),
                heading_deg: round(field.heading.heading_deg, 1e-9),
                heading_bearing_deg: round(field.swath_bearing_deg(), 1e-9),
                heading_integer_deg: field.heading.integer_heading_deg,
                objective: round(field.heading.objective, 1e-9),
                objective_integer: round(field.heading.integer_objective, 1e-9),
                swaths: field.swaths.len(),
                spray_length_m: round(field.spray_length_m(), 1e-4),
                edge_passes: field.edges.len(),
                edge_corners_cut: field.edge_corners_cut,
                edge_corners_saved_m2: round(field.edge_corners_saved_m2, 1e-4),
                edge_length_m: round(field.edge_length_m(), 1e-4),
                sprayable_area_m2: round(field.measure.sprayable_area_m2, 1e-4),
                covered_fraction: round(field.measure.covered_fraction, 1e-6),
                overlap_m2: round(field.measure.overlap_m2, 1e-4),
                outside_m2: round(field.measure.outside_m2, 1e-4),
            })
            .collect();
        let spray_length_m: f64 = plan.fields.iter().map(|field| field.spray_length_m()).sum();
        let edge_length_m: f64 = plan.fields.iter().map(|field| field.edge_length_m()).sum();
        let sprayable: f64 = plan
            .fields
            .iter()
            .map(|field| field.measure.sprayable_area_m2)
            .sum();
        let covered: f64 = plan
            .fields
            .iter()
            .map(|field| field.measure.covered_fraction * field.measure.sprayable_area_m2)
            .sum();
        let (turns, u_turns) = route.turns();
        let spray_time_s = (spray_length_m + edge_length_m) / vehicle.spray_speed_mps;
        let return_time_s = sorties.map_or(0.0, |split| split.plan.return_time_s);
        let non_spray_time_s = transfer_time_s(route, sorties, vehicle) + return_time_s;
        let sortie_details = sorties.map_or_else(Vec::new, |split| {
            split
                .plan
                .sorties
                .iter()
                .enumerate()
                .map(|(index, sortie)| {
                    let return_point = (index + 1 < split.plan.sorties.len()).then(|| {
                        let point = split.work_route.points()[sortie.last];
                        let (x, y) = scenario.farm.coordinate_system.to_input(point.x, point.y);
                        [
                            round(x, 1e-9),
                            round(y, 1e-9),
                            round(point.ground_m + vehicle.spray_height_m, 1e-4),
                        ]
                    });
                    SortieReport::new(
                        index,
                        sortie.spray_m,
                        sortie.tank_fraction,
                        (sortie.flight_s, sortie.battery_fraction),
                        return_point,
                        vehicle,
                    )
                })
                .collect()
        });
        Self {
            altitude_reference: settings.mission.altitude,
            altitude_assumption: settings.mission.altitude.assumption(&scenario.terrain_spec),
            terrain_warning: terrain_warning(scenario),
            preflight: None,
            mission: settings.mission,
            scenario: scenario.name.clone(),
            coordinate_system: scenario.farm.coordinate_system.describe(),
            vehicle: vehicle.name.clone(),
            vehicle_settings: vehicle.clone(),
            swath_width_m: vehicle.swath_width_m,
            spray_height_m: vehicle.spray_height_m,
            safe_height_m: vehicle.safe_height_m,
            settings: plan.settings,
            sequencer: settings.sequencer,
            start: route.launch.map(|leg| {
                let (x, y) = scenario
                    .farm
                    .coordinate_system
                    .to_input(leg.from.x, leg.from.y);
                [round(x, 1e-9), round(y, 1e-9)]
            }),
            supply: None,
            fields,
            spray_length_m: round(spray_length_m, 1e-4),
            edge_length_m: round(edge_length_m, 1e-4),
            transfer_length_m: round(
                flown_legs(route, sorties)
                    .iter()
                    .map(|leg| leg.cost_m)
                    .sum(),
                1e-4,
            ),
            tour_cost_m: round(route.tour_cost_m, 1e-4),
            transfers: flown_legs(route, sorties).len(),
            climbing_transfers: flown_legs(route, sorties)
                .iter()
                .filter(|transfer| transfer.climbs)
                .count(),
            turns,
            u_turns,
            sorties: sorties.map_or(1, |split| split.plan.sorties.len()),
            sortie_planner: sorties.map(|split| split.plan.planner),
            return_length_m: round(sorties.map_or(0.0, |split| split.plan.round_trip_m), 1e-4),
            non_spray_length_m: round(
                flown_legs(route, sorties)
                    .iter()
                    .map(|leg| leg.cost_m)
                    .sum::<f64>()
                    + sorties.map_or(0.0, |split| split.plan.round_trip_m),
                1e-4,
            ),
            return_time_s: round(return_time_s, 1e-3),
            battery_reserve_s: sorties.map(|split| round(split.model.battery_reserve_s, 1e-3)),
            battery_replan_s: round(settings.sorties.battery_margin_s, 1e-3),
            sortie_details,
            sprayable_area_m2: round(sprayable, 1e-4),
            covered_fraction: round(
                if sprayable > 0.0 {
                    covered / sprayable
                } else {
                    0.0
                },
                1e-6,
            ),
            overlap_m2: round(
                plan.fields
                    .iter()
                    .map(|field| field.measure.overlap_m2)
                    .sum(),
                1e-4,
            ),
            spray_time_s: round(spray_time_s, 1e-3),
            litres: vehicle
                .litres_per_spray_m()
                .map(|per_m| round(per_m * (spray_length_m + edge_length_m), 1e-3)),
            survey: vehicle
                .trigger_distance_m()
                .map(|trigger_distance_m| SurveyReport {
                    trigger_distance_m,
                    survey_length_m: round(spray_length_m + edge_length_m, 1e-4),
                    photos_estimate: ((spray_length_m + edge_length_m) / trigger_distance_m).round()
                        as u64,
                }),
            non_spray_time_s: round(non_spray_time_s, 1e-3),
            total_time_s: round(spray_time_s + non_spray_time_s, 1e-3),
            runtime_s,
        }
    }

    /// Each sortie's share of the battery: as its file flies, when the preflight has read the
    /// files back (what the operator will see on the remote), else as planned; then the
    /// usable share, when the vehicle lands with some left.
    fn battery_words(&self) -> String {
        let flown = self
            .preflight
            .as_ref()
            .filter(|verdict| verdict.sorties.len() == self.sortie_details.len());
        let percents: Vec<f64> = match flown {
            Some(verdict) => verdict
                .sorties
                .iter()
                .map(|sortie| 100.0 * sortie.battery_fraction)
                .collect(),
            None => self
                .sortie_details
                .iter()
                .map(|sortie| sortie.battery_percent)
                .collect(),
        };
        let usable = flown
            .and_then(|verdict| verdict.checks.iter().find(|check| check.name == "battery"))
            .filter(|check| check.limit < 1.0)
            .map_or(String::new(), |check| {
                format!(" (usable {:.0}%)", 100.0 * check.limit)
            });
        let measure = if flown.is_some() {
            "as flown"
        } else {
            "as planned"
        };
        format!("{measure} {}{usable}", battery_shares(&percents))
    }

    /// How the heading objective reads in the CLI's table.
    pub fn heading_label(settings: &CoverageSettings) -> String {
        match settings.heading {
            HeadingObjective::Seed {
                count_weight,
                length_weight,
            } => {
                format!("E (ω_N = {count_weight}, ω_L = {length_weight})")
            }
            HeadingObjective::LeastDose {
                count_weight,
                length_weight,
            } => {
                format!("E (ω_N = {count_weight}, ω_L = {length_weight}), then least double dose")
            }
            HeadingObjective::Swaths => "fewest swaths".into(),
            HeadingObjective::Length => "shortest length".into(),
            HeadingObjective::Fixed { heading_deg } => format!("fixed {heading_deg}°"),
            HeadingObjective::Bearing { bearing_deg } => format!("bearing {bearing_deg}°"),
        }
    }

    /// How the sequencer reads in the CLI's table.
    pub fn sequencer_label(sequencer: &Sequencer) -> String {
        match sequencer {
            Sequencer::Greedy => "greedy".into(),
            Sequencer::AntColony(AntColonySettings {
                ants,
                batches,
                seed,
                ..
            }) => {
                format!("ant colony ({ants} ants × {batches} batches, seed {seed})")
            }
            Sequencer::Best(settings) => format!(
                "best (local search, {} kicks, seed {})",
                settings.kicks, settings.seed
            ),
        }
    }

    /// The short table the CLI prints.
    pub fn to_text(&self) -> String {
        // A survey flies its swaths with the camera on: the same columns, its own words.
        let [work, working, _] = crate::model::Vehicle::work_words(self.survey.is_some());
        let mut text = format!(
            "{}: {} field(s), swath {} m, heading by {}, {} edge pass(es), order by {}\n",
            self.scenario,
            self.fields.len(),
            self.swath_width_m,
            Self::heading_label(&self.settings),
            self.settings.headland_passes,
            Self::sequencer_label(&self.sequencer)
        );
        // The name column as wide as the longest name: the figures stay in their columns.
        let name_width = self
            .fields
            .iter()
            .map(|field| field.name.chars().count())
            .fold(10, usize::max);
        text.push_str(&format!(
            "{:<name_width$} {:>9} {:>9} {:>7} {:>7} {:>11} {:>10} {:>9} {:>10}\n",
            "field",
            "bearing°",
            "heading°",
            "1° scan",
            "swaths",
            format!("{work} m"),
            "edge m",
            "covered",
            "overlap m²"
        ));
        for field in &self.fields {
            text.push_str(&format!(
                "{:<name_width$} {:>9.1} {:>9.1} {:>7.0} {:>7} {:>11.1} {:>10.1} {:>8.2}% {:>10.1}\n",
                field.name,
                field.heading_bearing_deg,
                field.heading_deg,
                field.heading_integer_deg,
                field.swaths,
                field.spray_length_m,
                field.edge_length_m,
                100.0 * field.covered_fraction,
                field.overlap_m2
            ));
        }
        if let Some(supply) = &self.supply {
            text.push_str(&supply.to_text(working));
        }
        if let Some(planner) = self.sortie_planner {
            text.push_str(&format!(
                "sorties ({}): {}, returns {:.1} m round trip, {:.1} min at the supply point and flying to it; battery used per sortie {}\n",
                planner,
                self.sorties,
                self.return_length_m,
                self.return_time_s / 60.0,
                self.battery_words()
            ));
            let vehicle = &self.vehicle_settings;
            // What the plan held back, not only the vehicle's reserve: over hills it also
            // keeps the climbs of the worst leg home (a tenth trial's T40: 281 s of 720 s
            // against the file's 20 %, and the note never came).
            let held_back_s = self
                .battery_reserve_s
                .unwrap_or(vehicle.battery_endurance_s - vehicle.usable_battery_s());
            let usable_percent = 100.0 * (1.0 - held_back_s / vehicle.battery_endurance_s).max(0.0);
            if let Some(note) = far_fields_note(&self.sortie_details, usable_percent) {
                text.push_str(&note);
            }
            if let Some(note) = small_tank_note(vehicle, self.sortie_details.len()) {
                text.push_str(&note);
            }
        }
        text.push_str(&format!(
            "total: {work} {:.1} m + edges {:.1} m, transfers {:.1} m ({} climbing), {} turns ({} U-turns), covered {:.2}% as planned, {:.1} min ({:.1} min not {working}), planned in {:.3} s\n",
            self.spray_length_m,
            self.edge_length_m,
            self.transfer_length_m,
            self.climbing_transfers,
            self.turns,
            self.u_turns,
            100.0 * self.covered_fraction,
            self.total_time_s / 60.0,
            self.non_spray_time_s / 60.0,
            self.runtime_s
        ));
        if let Some(survey) = &self.survey {
            text.push_str(&format!(
                "survey: camera every {} m over {:.1} m, about {} photos; no tank, sorties end for the battery\n",
                survey.trigger_distance_m, survey.survey_length_m, survey.photos_estimate
            ));
        }
        text.push_str(&format!("altitudes: {}\n", self.altitude_assumption));
        // Local metres have no place on Earth: say where the mission files put them, which
        // only the sheet said (a trial's finding, decision 0028).
        if self.coordinate_system == crate::model::CoordinateSystem::Local.describe() {
            let (lon, lat) = self.mission.local_origin;
            let default = crate::mission::flight::DEFAULT_LOCAL_ORIGIN;
            text.push_str(&format!(
                "placed: local (0, 0) at lon {lon:.6}, lat {lat:.6} in the mission files ({}; --origin LON,LAT places them)\n",
                if (lon, lat) == default {
                    "the default origin, near Harbin, China"
                } else {
                    "as given"
                }
            ));
        }
        if let Some(warning) = &self.terrain_warning {
            text.push_str(&format!("warning: {warning}\n"));
        }
        if let Some(verdict) = &self.preflight {
            text.push_str(&verdict.summary());
            text.push('\n');
            let limit = self.vehicle_settings.mission_items_max;
            if let Some(warning) = notes::mission_size_warning(&verdict.sorties, limit) {
                text.push_str(&warning);
            }
        }
        text
    }
}

/// Sorties whose battery shares the summary lists one by one; above, their range and median
/// (a tenth trial's 251 sorties made a line of 1,139 characters; each is in the sheet and
/// `report.json`).
const LISTED_SORTIES: usize = 12;

/// The sorties' battery shares (percent) for the summary: each, or for many their range.
fn battery_shares(percents: &[f64]) -> String {
    if percents.len() <= LISTED_SORTIES {
        return percents
            .iter()
            .map(|percent| format!("{percent:.0}%"))
            .collect::<Vec<_>>()
            .join(" ");
    }
    let mut sorted = percents.to_vec();
    sorted.sort_by(f64::total_cmp);
    format!(
        "{:.0}-{:.0}% (median {:.0}%, each sortie's in the sheet)",
        sorted[0],
        sorted[sorted.len() - 1],
        sorted[sorted.len() / 2]
    )
}

#[cfg(test)]
mod tests {
    use super::battery_shares;

    #[test]
    fn a_few_sorties_are_listed_and_many_given_as_a_range() {
        assert_eq!(battery_shares(&[50.2, 61.0, 71.6]), "50% 61% 72%");
        let many: Vec<f64> = (0..201).map(|k| 36.0 + (k % 37) as f64).collect();
        assert_eq!(
            battery_shares(&many),
            "36-72% (median 52%, each sortie's in the sheet)"
        );
    }
}
