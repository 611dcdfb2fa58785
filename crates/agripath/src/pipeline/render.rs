//! A planned mission's files: the mission files checked by the preflight as written, the
//! contract files and the maps; and the re-plan when the files fly over the battery.

use crate::error::Fault;
use crate::mission::csv::waypoints_csv;
use crate::mission::flight::build_missions;
use crate::mission::kml::mission_kml;
use crate::mission::plan_geojson::{add_supply_options, plan_geojson};
use crate::mission::{qgc_plan, wpl};
use crate::model::CoordinateSystem;
use crate::plot::map_svg::{plan_svg, PlanMap, Underlay};
use crate::plot::plan_html::{plan_html, Overlay};
#[cfg(feature = "png")]
use crate::plot::raster::svg_to_png;
use crate::plot::terrain_map::{terrain_map_png, TerrainPicture};
use crate::report::Report;
use crate::scenario::Scenario;
use crate::terrain::hillshade::{hillshade, Shaded};
use crate::terrain::Extent;

use super::{plan_mission, PlannedMission};

/// The hillshade under the plan: the farm's box, and the supply point where it stands off
/// the fields, with a margin; heights exaggerated so that low relief still shows ((50 m /
/// relief) clamped to 1..10).
pub fn terrain_overlay(scenario: &Scenario, supply: Option<geo::Coord<f64>>) -> Shaded {
    let farm_box = scenario.farm.bounds();
    let (mut low, mut high) = (farm_box.min(), farm_box.max());
    if let Some(supply) = supply {
        low = geo::Coord {
            x: low.x.min(supply.x),
            y: low.y.min(supply.y),
        };
        high = geo::Coord {
            x: high.x.max(supply.x),
            y: high.y.max(supply.y),
        };
    }
    let margin = 0.05 * (high.x - low.x).max(high.y - low.y) + 10.0;
    let extent = Extent {
        min_x: low.x - margin,
        min_y: low.y - margin,
        max_x: high.x + margin,
        max_y: high.y + margin,
    };
    let relief = scenario
        .terrain
        .height_range_m(extent)
        .map_or(0.0, |(low, high)| high - low);
    let exaggeration = (50.0 / relief.max(1e-9)).clamp(1.0, 10.0);
    hillshade(scenario.terrain.as_ref(), extent, 1024, exaggeration)
}

/// Whether a file of a plan folder is one a ground station or autopilot flies (left out when
/// the preflight fails, unless the operator insists).
pub fn is_mission_file(name: &str) -> bool {
    name.ends_with(".plan")
        || name.ends_with(".waypoints")
        || name == "mission.kml"
        || name == "waypoints.csv"
}

/// A plan folder's files with the preflight verdict on its mission files, and the report
/// that carries it (as `report.json` holds it).
pub struct Rendered {
    /// Every file of the plan folder: its name and its bytes.
    pub files: Vec<(String, Vec<u8>)>,
    /// The preflight verdict on the mission files.
    pub verdict: crate::preflight::Verdict,
    /// The report, carrying the verdict.
    pub report: Report,
}

impl Rendered {
    /// Keeps the files to write: all of them when the flight is safe or `allow_unsafe`, else
    /// all but the mission files.
    pub fn keep_files_to_write(&mut self, allow_unsafe: bool) {
        if !(self.verdict.safe || allow_unsafe) {
            self.files.retain(|(name, _)| !is_mission_file(name));
        }
    }
}

/// What the preflight holds a plan to: its mission settings and margins, and the limits
/// drawn from what its own measure promised ([`crate::preflight::PreflightSettings::new`]).
pub fn preflight_settings(mission: &PlannedMission) -> crate::preflight::PreflightSettings {
    let settings = &mission.settings;
    let promise = crate::preflight::Promise {
        headland_passes: settings.coverage.headland_passes,
        edge_gaps: settings.coverage.edge_cut == crate::coverage::EdgeCut::Gap,
        covered_fraction: mission
            .coverage
            .fields
            .iter()
            .map(|field| field.measure.covered_fraction)
            .collect(),
        outside_m2: mission
            .coverage
            .fields
            .iter()
            .map(|field| field.measure.outside_m2)
            .sum(),
        sprayed_m2: (mission.report.spray_length_m + mission.report.edge_length_m)
            * mission.coverage.swath_width_m,
    };
    crate::preflight::PreflightSettings::new(
        &settings.mission,
        settings.coverage.boundary_margin_m,
        settings.coverage.obstacle_margin_m,
        &promise,
    )
}

/// Re-plans at most this many times when sorties fly over the battery as written.
const MOST_BATTERY_REPLANS: usize = 3;

/// The places `--supply auto:N` listed after the one chosen, in planning metres, with their
/// costs (none without `auto:N`).
fn supply_options(report: &crate::report::Report) -> Vec<(geo::Coord<f64>, Option<f64>)> {
    report
        .supply
        .as_ref()
        .and_then(|supply| supply.auto.as_ref())
        .map(|auto| {
            auto.candidates
                .iter()
                .skip(1)
                .map(|candidate| {
                    let [x, y] = candidate.at.point_m;
                    (geo::Coord { x, y }, candidate.cost_s)
                })
                .collect()
        })
        .unwrap_or_default()
}

/// [`render`], and when the preflight finds sorties that fly over the battery as written,
/// the render of the plan made again with the largest overrun (and a second) held back from
/// every sortie's battery ([`crate::sortie::SortieSettings::battery_margin_s`]), at most
/// `MOST_BATTERY_REPLANS` (3) times.
///
/// The sortie model charges eq. 2's legs and a reserve for their climbs (decision 0012), but
/// not everything the files fly: transfers inside a sortie that climb over a hill between
/// fields, spray legs that follow bumps steeper than the drape's 20 m segments show, turns
/// on slopes. The files are the truth the preflight flies; this closes the loop on it rather
/// than modelling each of those in the split. On the flat (every benchmark farm and the demo)
/// the first render is safe and nothing is re-planned. A re-plan that fails (no battery left
/// to hold back) keeps the last render, which the preflight refuses.
pub fn render_flyable(scenario: &Scenario, mission: &PlannedMission) -> Result<Rendered, Fault> {
    let endurance_s = scenario.vehicle.usable_battery_s();
    let mut rendered = render(scenario, mission)?;
    let mut settings = mission.settings;
    for _ in 0..MOST_BATTERY_REPLANS {
        let overrun_s = rendered
            .verdict
            .sorties
            .iter()
            .map(|sortie| sortie.flight_time_s - endurance_s)
            .fold(0.0, f64::max);
        if overrun_s <= 0.0 || settings.sorties.planner.is_none() {
            break;
        }
        settings.sorties.battery_margin_s += overrun_s + 1.0;
        let Ok(replanned) = plan_mission(scenario, &settings) else {
            break;
        };
        rendered = render(scenario, &replanned)?;
    }
    Ok(rendered)
}

/// The files of a plan folder, by name: the mission files (per sortie `sortie_NN.plan` and
/// `sortie_NN.waypoints`, `mission.kml`, `waypoints.csv`), checked by the preflight as written,
/// then the contract files (`plan.geojson`, `report.json` with the verdict) and the maps
/// (`plan.svg`, `plan.png` with the `png` feature, `plan.html`, `terrain.png`).
pub fn render(scenario: &Scenario, mission: &PlannedMission) -> Result<Rendered, Fault> {
    let vehicle = &scenario.vehicle;
    let settings = &mission.settings.mission;
    crate::progress::stage(|| "writing the mission files".into());
    let missions = build_missions(scenario, &mission.route, mission.sorties.as_ref(), settings)?;
    let mut mission_files = Vec::new();
    for sortie in &missions {
        let name = crate::mission::sortie_file_stem(sortie.sortie);
        mission_files.push((
            format!("{name}.plan"),
            qgc_plan::plan_file(
                sortie,
                &scenario.farm,
                settings,
                vehicle.transit_speed_mps,
                vehicle.spray_speed_mps,
            )
            .into_bytes(),
        ));
        mission_files.push((
            format!("{name}.waypoints"),
            wpl::waypoints_file(sortie, settings).into_bytes(),
        ));
    }
    mission_files.push((
        "mission.kml".to_string(),
        mission_kml(&scenario.name, &scenario.farm, &missions, settings).into_bytes(),
    ));
    mission_files.push((
        "waypoints.csv".to_string(),
        waypoints_csv(
            &missions,
            crate::mission::flight::sea_level_known(
                &scenario.terrain_spec,
                scenario.terrain_stated,
            ),
        )
        .into_bytes(),
    ));
    let world = crate::preflight::World {
        farm: &scenario.farm,
        terrain: scenario.terrain.as_ref(),
        vehicle,
    };
    let verdict = crate::preflight::check(&world, &preflight_settings(mission), &mission_files);
    crate::progress::stage(|| "drawing the maps and the sheet".into());
    let mut report = mission.report.clone();
    report.preflight = Some(verdict.clone());
    if mission.sorties.is_none() {
        report.sortie_details = verdict
            .sorties
            .iter()
            .map(|flown| crate::report::SortieReport::as_flown(flown, vehicle))
            .collect();
    }
    let supply_options = supply_options(&report);
    let geojson_of = |farm: &crate::model::Farm| {
        let mut geojson = plan_geojson(
            farm,
            &mission.coverage,
            &mission.route,
            mission.sorties.as_ref(),
            vehicle.spray_height_m,
            vehicle.safe_height_m,
            &verdict.ground,
        );
        add_supply_options(&mut geojson, farm.coordinate_system, &supply_options);
        geojson
    };
    let geojson = geojson_of(&scenario.farm);
    let title = format!(
        "{}{} — {} field{}, swath {} m, {:.0} m {}, {:.2}% covered as flown",
        if verdict.safe { "" } else { "UNSAFE: " },
        scenario.name,
        scenario.farm.fields.len(),
        if scenario.farm.fields.len() == 1 {
            ""
        } else {
            "s"
        },
        vehicle.swath_width_m,
        mission.report.spray_length_m + mission.report.edge_length_m,
        crate::model::Vehicle::work_words(vehicle.is_survey())[2],
        100.0 * verdict.covered_fraction()
    );
    let json = |value: &serde_json::Value| {
        (serde_json::to_string_pretty(value).expect("JSON value") + "\n").into_bytes()
    };
    let mut files = vec![
        ("plan.geojson".to_string(), json(&geojson)),
        (
            "report.json".to_string(),
            (serde_json::to_string_pretty(&report).expect("report serialises") + "\n").into_bytes(),
        ),
    ];
    // The viewer draws in plan metres: the same features in the local frame.
    let mut local_farm = scenario.farm.clone();
    local_farm.coordinate_system = CoordinateSystem::Local;
    let local = geojson_of(&local_farm);
    let supply = mission
        .route
        .launch
        .map(|leg| geo::Coord {
            x: leg.from.x,
            y: leg.from.y,
        })
        .or_else(|| {
            mission.sorties.as_ref().map(|split| geo::Coord {
                x: split.supply.x,
                y: split.supply.y,
            })
        });
    let shaded = terrain_overlay(scenario, supply);
    let (extent, png) = (shaded.extent, shaded.to_png());
    // The operator's terrain map: tinted, with the fields, the supply point and a legend (the
    // maps above draw their own fields over the plain hillshade).
    let terrain_map = terrain_map_png(&TerrainPicture {
        terrain: scenario.terrain.as_ref(),
        shaded: &shaded,
        farm: &scenario.farm,
        supply,
    });
    let underlay = Underlay {
        png: &png,
        min_x: extent.min_x,
        min_y: extent.min_y,
        max_x: extent.max_x,
        max_y: extent.max_y,
    };
    let other_supply_points: Vec<geo::Coord<f64>> =
        supply_options.iter().map(|(point, _)| *point).collect();
    let map = plan_svg(&PlanMap {
        farm: &scenario.farm,
        plan: &mission.coverage,
        route: &mission.route,
        sorties: mission.sorties.as_ref(),
        underlay: Some(&underlay),
        title: &title,
        ground: &verdict.ground,
        other_supply_points: &other_supply_points,
    });
    let rows = crate::sheet::sortie_rows(
        &scenario.farm,
        &mission.route,
        mission.sorties.as_ref(),
        &report,
        &missions,
    );
    let sheet = crate::sheet::sheet_html(&crate::sheet::SheetParts {
        report: &report,
        rows: &rows,
        map_svg: &map,
        lon_lat: scenario.farm.coordinate_system != CoordinateSystem::Local,
        home_lon_lat: missions
            .first()
            .map(|first| [first.home.lon, first.home.lat]),
    });
    #[cfg(feature = "png")]
    files.push((
        "plan.png".to_string(),
        svg_to_png(&map, 1600).map_err(Fault::Structure)?,
    ));
    files.push(("plan.svg".to_string(), map.into_bytes()));
    let overlay = Overlay {
        png: &png,
        min_x: extent.min_x,
        min_y: extent.min_y,
        max_x: extent.max_x,
        max_y: extent.max_y,
    };
    files.push((
        "plan.html".to_string(),
        plan_html(&title, &local, Some(&overlay)).into_bytes(),
    ));
    files.push(("sheet.html".to_string(), sheet.into_bytes()));
    files.extend(mission_files);
    files.push(("terrain.png".to_string(), terrain_map));
    Ok(Rendered {
        files,
        verdict,
        report,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::TerrainError;
    use crate::model::{Farm, Field};
    use crate::settings::PlanSettings;
    use crate::terrain::Terrain;
    use geo::{LineString, Polygon};

    /// A 150 m ridge across x = 310 between two fields (x 0-160 and 460-620).
    struct Ridge;

    impl Terrain for Ridge {
        fn height_m(&self, x: f64, _y: f64) -> Result<f64, TerrainError> {
            Ok(150.0 * (1.0 - ((x - 310.0) / 60.0).abs()).max(0.0))
        }

        fn extent(&self) -> Option<Extent> {
            None
        }

        fn describe(&self) -> String {
            "a ridge between the fields".into()
        }
    }

    fn rectangle(x0: f64, width: f64) -> Polygon<f64> {
        let (x1, y1) = (x0 + width, 150.0);
        Polygon::new(
            LineString::from(vec![(x0, 0.0), (x1, 0.0), (x1, y1), (x0, y1), (x0, 0.0)]),
            vec![],
        )
    }

    /// The supply point stands on the ridge's crest, 250 m south of the gap between the
    /// fields. A sortie that flies from one field to the other climbs over the ridge as
    /// written, which the split's model does not charge (a transfer inside a sortie costs its
    /// flat climb, and the reserve covers only the legs out and home): the first render has
    /// sorties over the battery; the re-plan holds the overrun back and the plan it renders
    /// passes the preflight.
    #[test]
    fn sorties_over_the_battery_as_written_are_planned_again_until_they_fly() {
        let farm = Farm::local(
            "ridge test",
            vec![
                Field::new("west", rectangle(0.0, 160.0)),
                Field::new("east", rectangle(460.0, 160.0)),
            ],
        );
        let mut scenario =
            Scenario::with_farm(farm, crate::scenario::ScenarioParts::default()).unwrap();
        scenario.terrain = Box::new(Ridge);
        scenario.vehicle.tank_spray_time_s = None;
        scenario.vehicle.tank_l = None;
        scenario.vehicle.battery_endurance_s = 690.0;
        let settings = PlanSettings {
            start: Some([310.0, -250.0]),
            ..PlanSettings::default()
        };
        let mission = plan_mission(&scenario, &settings).unwrap();
        let first = render(&scenario, &mission).unwrap();
        let endurance = scenario.vehicle.battery_endurance_s;
        let worst = |rendered: &Rendered| {
            rendered
                .verdict
                .sorties
                .iter()
                .map(|sortie| sortie.flight_time_s)
                .fold(0.0, f64::max)
        };
        assert!(worst(&first) > endurance, "{}", worst(&first));
        let flyable = render_flyable(&scenario, &mission).unwrap();
        assert!(worst(&flyable) <= endurance, "{}", worst(&flyable));
        assert!(flyable.verdict.safe, "{:?}", flyable.verdict.failures);
    }
}
