//! The preflight check: the mission files just written, read back and flown against the
//! inputs (decision 0012). It does not look at the plan in memory. For every sortie it reads
//! `sortie_NN.plan` and `sortie_NN.waypoints` (which must agree item by item), flies the
//! items as the autopilot would ([`flown`]), samples every leg at most
//! [`SAMPLE_M`] apart, and checks:
//!
//! - **frame**: every position item is in the frame of the altitude reference asked for;
//! - **spray height**: on spray legs the height above the ground stays within the terrain
//!   tolerance of the spray height;
//! - **transit clearance**: a leg off spray that leaves the fields (or crosses a hole or an
//!   obstacle) stays ≥ h above the highest ground under it; one inside a field (a headland
//!   turn) stays within the tolerance of spray height or above;
//! - **holes and obstacles**: no leg at spray height enters a hole or an obstacle (grown by
//!   the obstacle margin), and no leg at any height enters an obstacle of the inputs, whatever
//!   the file's fence says (obstacles tested against their edges, not only at the samples);
//! - **fence**: every sample inside the file's inclusion polygon and outside its exclusions;
//! - **coverage** as flown (strips one swath wide along the spray legs, [`sprayed`]) of each
//!   field's sprayable area: covered / (covered + missed), where missed is ground a swath
//!   can reach ([`crate::coverage::region::reachable_region`]) left unsprayed; ground narrower than a swath (sharp
//!   tips, necks) left unsprayed is reported apart as unreachable; and the **spray outside** the fields, holes and obstacles
//!   excluded, as a share of all that is sprayed;
//! - **tank** and **battery** per sortie, recomputed from the files and the vehicle; the **mission size** (home included) when the vehicle gives `mission_items_max`.
//!
//! The parts: [`settings`] (what a plan is held to), [`verdict`] (the checks' figures and failure lines, as
//! `report.json` carries them) and [`folder`] (the check run again on a plan folder as it is now); the flight
//! itself in [`flown`], the measure of what it sprays in [`sprayed`].

mod dose;
pub mod flown;
pub mod folder;
mod heights;
mod missed;
pub mod read_back;
pub mod settings;
pub mod sprayed;
pub mod verdict;
mod zones;

use geo::Coord;

use crate::coverage::region::GroundPatches;
use crate::limits::MIN_GROUND_CLEARANCE_M;
use crate::mission::flight::GeoFrame;
use crate::mission::flight::{highest_ground_near, TRANSIT_CORRIDOR_M};
use crate::mission::mavlink::Command;
use crate::terrain::nearness::GroundNearness;
use flown::Motion;
use verdict::Tally;

pub use dose::MAX_SPRAY_SPEED_SHARE;
pub use folder::check_folder;
pub use settings::{PreflightSettings, Promise, World};
pub use verdict::{CheckResult, FieldFlown, SortieFlown, Verdict};

/// Largest distance between two samples of a leg, metres.
pub const SAMPLE_M: f64 = 1.0;
/// Rows of the sprayed-area measure, metres apart.
const ROW_M: f64 = 0.1;
/// What rounding in the files (1e-9° ≈ 0.1 mm, altitudes to 1 mm) and the lon/lat round trip
/// may move a place or a height, metres.
const SLACK_M: f64 = 0.02;
/// Most sprayed area outside the fields, as a share of the sprayed area (the default layout).
pub const MAX_OUTSIDE_FRACTION: f64 = 0.005;
/// Smallest change of direction between two spray legs that sweeps a turn's disc, radians.
const MIN_TURN_RAD: f64 = 0.5 * std::f64::consts::PI / 180.0;

/// Runs the check on the mission files among `files` (name, bytes).
pub fn check(world: &World, settings: &PreflightSettings, files: &[(String, Vec<u8>)]) -> Verdict {
    let frame = GeoFrame::new(world.farm.coordinate_system, settings.local_origin);
    let to_plan = |lon: f64, lat: f64| frame.plan_xy(lon, lat);
    let vehicle = world.vehicle;
    let terrain = world.terrain;
    let expected_frame = Command::frame_of(settings.altitude);
    let mut checks = Vec::new();
    let mut failures = Vec::new();
    let mut read = Tally::new("files read back", "≤", 0.0, "faults");
    let mut frames = Tally::new("altitude frame", "≤", 0.0, "items");
    let mut spray_height = Tally::new(
        "spray height",
        "≤",
        settings.terrain_tolerance_m,
        "m from spray height",
    );
    let mut spray_speed = dose::tally();
    let mut transit = Tally::new(
        "transit clearance",
        "≥",
        vehicle.safe_height_m,
        "m above the highest ground under the leg",
    );
    let mut low_legs = Tally::new(
        "ground clearance",
        "≥",
        (vehicle.spray_height_m - settings.terrain_tolerance_m).max(MIN_GROUND_CLEARANCE_M),
        "m above the ground on legs that do not spray",
    );
    let mut heights = heights::HeightBounds::new(vehicle);
    let mut nearness = GroundNearness::new(
        terrain,
        |x, y| terrain.height_m(x, y).ok(),
        1.0,
        MIN_GROUND_CLEARANCE_M,
    );
    let mut no_go = Tally::new("holes and obstacles", "≤", 0.0, "samples inside").counting();
    // Samples outside, and a fence missing or unusable counted as one failure each.
    let mut fence = Tally::new("fence", "≤", 0.0, "failures").counting();
    let mut tank = Tally::new("tank", "≤", 1.0, "tanks");
    // A sortie may not fly into the share of the battery the operator lands with.
    let usable_battery = vehicle.usable_battery_s() / vehicle.battery_endurance_s;
    let mut battery = Tally::new("battery", "≤", usable_battery, "batteries");
    let mut mission_size = verdict::mission_size(vehicle.mission_items_max);
    let place = |x: f64, y: f64| frame.describe(x, y);
    let low_limit = low_legs.limit;

    // Field, hole and obstacle rings in plan metres.
    let zones = zones::Zones::new(world.farm, settings.obstacle_margin_m);

    let mut strips = Vec::new();
    let mut sorties = Vec::new();
    let names = read_back::sortie_files(files, &mut read);
    let flown_sorties = crate::progress::Counter::new("flying the mission files", names.len());
    for (number, name) in names.iter().enumerate() {
        flown_sorties.one_done();
        let sortie = number + 1;
        let bytes = |file: &str| {
            files
                .iter()
                .find(|(n, _)| n == file)
                .map(|(_, bytes)| String::from_utf8_lossy(bytes).into_owned())
        };
        let plan = match bytes(name).map(|text| read_back::read_plan(&text)) {
            Some(Ok(plan)) => plan,
            Some(Err(why)) => {
                read.fail(format!("sortie {sortie}: {name}: {why}"));
                continue;
            }
            None => continue,
        };
        let twin = name.replace(".plan", ".waypoints");
        match bytes(&twin).map(|text| read_back::read_waypoints(&text)) {
            Some(Ok(waypoints)) => {
                for difference in read_back::differences(&plan, &waypoints) {
                    read.fail(format!("sortie {sortie}: {twin}: {difference}"));
                }
            }
            Some(Err(why)) => read.fail(format!("sortie {sortie}: {twin}: {why}")),
            None => read.fail(format!("sortie {sortie}: {twin} is missing")),
        }
        let home_xy = to_plan(plan.home.1, plan.home.0);
        let home_ground = match terrain.height_m(home_xy.0, home_xy.1) {
            Ok(height) => height,
            Err(error) => {
                read.fail(format!(
                    "sortie {sortie}: home {}: {error}",
                    place(home_xy.0, home_xy.1)
                ));
                continue;
            }
        };
        for (index, item) in plan.items.iter().enumerate() {
            let positional = matches!(item.command, 16 | 21 | 22);
            if positional && item.frame != expected_frame {
                frames.fail(format!(
                    "sortie {sortie}, item {}: frame {} where {} altitudes need frame {expected_frame}",
                    index + 1,
                    item.frame,
                    settings.altitude.key()
                ));
            } else if positional {
                frames.record(0.0, false, String::new);
            }
        }
        let legs = match flown::fly(
            &plan.items,
            home_xy,
            home_ground,
            settings.sprayer,
            flown::StartSpeeds::of(vehicle),
            &to_plan,
        ) {
            Ok(legs) => legs,
            Err(unflyable) => {
                read.fail(format!(
                    "sortie {sortie}, item {}: {}",
                    unflyable.item, unflyable.why
                ));
                continue;
            }
        };
        // The fence as the file gives it.
        let fences: Vec<zones::Fence> = plan
            .fence
            .iter()
            .map(|polygon| {
                let mut ring: Vec<Coord<f64>> = polygon
                    .corners
                    .iter()
                    .map(|&(lat, lon)| {
                        let (x, y) = to_plan(lon, lat);
                        Coord { x, y }
                    })
                    .collect();
                if let Some(&first) = ring.first() {
                    ring.push(first);
                }
                (polygon.inclusion, ring)
            })
            .filter(|(_, ring): &(bool, Vec<Coord<f64>>)| {
                // A closed ring of fewer than three corners fences nothing.
                let usable = ring.len() >= 4;
                if !usable {
                    fence.fail(format!(
                        "sortie {sortie}: {name} has a geofence polygon of fewer than 3 corners"
                    ));
                }
                usable
            })
            .map(|(inclusion, ring)| zones::Fence::new(inclusion, &ring))
            .collect();
        if !fences.iter().any(|fence| fence.inclusion) {
            fence.fail(format!("sortie {sortie}: {name} has no inclusion geofence"));
        }
        verdict::record_mission(&mut mission_size, sortie, name, plan.items.len() + 1);
        let mut figures = SortieFlown {
            sortie,
            file: name.to_string(),
            items: plan.items.len(),
            spray_m: 0.0,
            tank_fraction: None,
            flight_time_s: 0.0,
            battery_fraction: 0.0,
            worst_spray_height_error_m: 0.0,
            least_transit_margin_m: None,
            pump_stopped_m: 0.0,
        };
        // ArduPilot's pump through each spray run (decision 0030).
        let mut pump = dose::Pump::default();
        for (leg_index, leg) in legs.iter().enumerate() {
            if !leg.spraying {
                pump = dose::Pump::default();
            }
            let horizontal = leg.horizontal_m();
            let rise = leg.rise_m(terrain).unwrap_or(0.0);
            figures.flight_time_s += leg.flight_s(vehicle, rise);
            // Where the terrain has no answer (a waypoint off the DEM), the leg cannot be
            // checked: that is a failure, and the leg's other checks are skipped.
            let sampled: Result<Vec<(f64, f64, f64, f64)>, crate::TerrainError> = leg
                .sample_places(terrain)
                .into_iter()
                .map(|t| {
                    let (x, y, altitude) = leg.at(t, terrain)?;
                    Ok((x, y, altitude, terrain.height_m(x, y)?))
                })
                .collect();
            let points = match sampled {
                Ok(points) => points,
                Err(error) => {
                    read.fail(format!("sortie {sortie}, item {}: {error}", leg.item));
                    continue;
                }
            };
            for &(x, y, _, _) in &points {
                let p = Coord { x, y };
                let outside = fences.iter().any(|polygon| polygon.breached_at(p));
                fence.record_at((x, y), f64::from(u8::from(outside)), outside, || {
                    format!(
                        "sortie {sortie}, item {} at {}: outside the geofence",
                        leg.item,
                        place(x, y)
                    )
                });
                // Spray legs are asked below, against obstacles grown by the margin.
                let in_obstacle = !(leg.spraying && horizontal > 0.0) && zones.in_obstacle(p);
                no_go.record_at(
                    (x, y),
                    f64::from(u8::from(in_obstacle)),
                    in_obstacle,
                    || {
                        format!(
                            "sortie {sortie}, item {} at {}: flying through an obstacle",
                            leg.item,
                            place(x, y)
                        )
                    },
                );
            }
            // And against the obstacles' edges: a pole thinner than the step is met (0037).
            let ends = [leg.from, leg.to].map(|end| Coord { x: end.x, y: end.y });
            let spraying = leg.spraying && horizontal > 0.0;
            if let Some((p, what)) = zones.leg_through_obstacle(ends, spraying) {
                let line = format!(
                    "sortie {sortie}, item {} at {}: {what}",
                    leg.item,
                    place(p.x, p.y)
                );
                no_go.record_at((p.x, p.y), 1.0, true, || line);
            }
            if leg.motion != Motion::Flight {
                // Takeoff, landing: held to the floor beside them once up (decision 0036).
                heights.record_column((sortie, leg.item), &points, &mut nearness, &place);
                continue;
            }
            let shape = if horizontal < SLACK_M {
                heights::LegShape::InPlace
            } else if leg.follows_terrain() {
                heights::LegShape::FollowingTerrain
            } else {
                heights::LegShape::Along
            };
            let within_field = points
                .iter()
                .all(|&(x, y, _, _)| zones.over_field(Coord { x, y }));
            // A transit (off spray, leaving the fields or crossing a hole or obstacle) clears
            // the ground beside it as written: the ceiling is held over it (decision 0036).
            let off_spray = !leg.spraying;
            let is_transit = off_spray && shape != heights::LegShape::InPlace && !within_field;
            let ends = ((leg.from.x, leg.from.y), (leg.to.x, leg.to.y));
            let beside = is_transit.then(|| {
                highest_ground_near(terrain, ends.0, ends.1, TRANSIT_CORRIDOR_M)
                    .unwrap_or(f64::NEG_INFINITY)
            });
            heights.record(
                (sortie, leg.item),
                &points,
                shape,
                beside,
                off_spray,
                &place,
            );
            heights.record_sideways((sortie, leg.item), &points, &mut nearness, &place);
            if leg.spraying && horizontal > 0.0 {
                figures.spray_m += horizontal;
                let pump_stops = dose::record(
                    &mut spray_speed,
                    leg,
                    (horizontal, rise),
                    vehicle,
                    settings.sprayer,
                    sortie,
                    &mut pump,
                );
                if pump_stops {
                    figures.pump_stopped_m += horizontal;
                }
                let (a, b) = (points[0], points[points.len() - 1]);
                let half = vehicle.swath_width_m / 2.0;
                // Where ArduPilot's pump stops, nothing is sprayed: the coverage as flown
                // counts the gap.
                if !pump_stops {
                    let (from, to) = (Coord { x: a.0, y: a.1 }, Coord { x: b.0, y: b.1 });
                    strips.extend(sprayed::leg_strip(from, to, half, legs.get(leg_index + 1)));
                }
                for &(x, y, altitude, ground) in &points {
                    let error = (altitude - ground - vehicle.spray_height_m).abs();
                    figures.worst_spray_height_error_m =
                        figures.worst_spray_height_error_m.max(error);
                    spray_height.record_at(
                        (x, y),
                        error,
                        error > settings.terrain_tolerance_m + SLACK_M,
                        || {
                            format!(
                                "sortie {sortie}, item {} at {}: spraying {:.2} m above the ground (spray height {} m ± {} m)",
                                leg.item,
                                place(x, y),
                                altitude - ground,
                                vehicle.spray_height_m,
                                settings.terrain_tolerance_m
                            )
                        },
                    );
                    let inside = zones.no_go(Coord { x, y });
                    no_go.record_at((x, y), f64::from(u8::from(inside)), inside, || {
                        format!(
                            "sortie {sortie}, item {} at {}: spraying inside a hole or an obstacle",
                            leg.item,
                            place(x, y)
                        )
                    });
                }
                continue;
            }
            if horizontal < SLACK_M {
                // A climb or descent in place: its lower end keeps the low-leg clearance.
                let lowest = points
                    .iter()
                    .map(|&(_, _, altitude, ground)| altitude - ground)
                    .fold(f64::INFINITY, f64::min);
                let (x, y, _, _) = points[0];
                low_legs.record_at((x, y), lowest, lowest < low_limit - SLACK_M, || {
                    format!(
                        "sortie {sortie}, item {} at {}: {:.2} m above the ground (needs ≥ {:.2} m)",
                        leg.item,
                        place(x, y),
                        lowest,
                        low_limit
                    )
                });
                continue;
            }
            if within_field {
                for &(x, y, altitude, ground) in &points {
                    let clearance = altitude - ground;
                    low_legs.record_at((x, y), clearance, clearance < low_limit - SLACK_M, || {
                        format!(
                            "sortie {sortie}, item {} at {}: turn {:.2} m above the ground (needs ≥ {:.2} m)",
                            leg.item,
                            place(x, y),
                            clearance,
                            low_limit
                        )
                    });
                }
            } else {
                let (x, y, margin) = leg.transit_margin(&points);
                figures.least_transit_margin_m = Some(
                    figures
                        .least_transit_margin_m
                        .map_or(margin - vehicle.safe_height_m, |m: f64| {
                            m.min(margin - vehicle.safe_height_m)
                        }),
                );
                transit.record_at((x, y), margin, margin < vehicle.safe_height_m - SLACK_M, || {
                    format!(
                        "sortie {sortie}, item {} at {}: transit {:.2} m above the highest ground under the leg (needs ≥ h = {} m)",
                        leg.item,
                        place(x, y),
                        margin,
                        vehicle.safe_height_m
                    )
                });
            }
        }
        heights.end_sortie(&place);
        if let Some(per_tank) = vehicle.spray_length_per_tank_m() {
            let fraction = figures.spray_m / per_tank;
            figures.tank_fraction = Some(fraction);
            tank.record(fraction, figures.spray_m > per_tank * 1.001 + 1.0, || {
                format!(
                    "sortie {sortie}: sprays {:.0} m, {:.1}% of a tank ({per_tank:.0} m)",
                    figures.spray_m,
                    100.0 * fraction
                )
            });
        }
        figures.battery_fraction = figures.flight_time_s / vehicle.battery_endurance_s;
        battery.record(
            figures.battery_fraction,
            figures.flight_time_s > vehicle.usable_battery_s() * 1.001,
            || {
                format!(
                    "sortie {sortie}: flies {:.0} s as written, {:.1}% of the battery ({} s, {:.0} s usable)",
                    figures.flight_time_s,
                    100.0 * figures.battery_fraction,
                    vehicle.battery_endurance_s,
                    vehicle.usable_battery_s()
                )
            },
        );
        sorties.push(figures);
    }

    // Coverage and spray outside, as flown.
    let regions = sprayed::FieldGround::of_farm(
        world.farm,
        settings.boundary_margin_m,
        settings.obstacle_margin_m,
        world.vehicle.swath_width_m,
    );
    let (ground, excluded) = sprayed::farm_rings(world.farm);
    let mut measured = sprayed::measure(&strips, &regions, &ground, &excluded, ROW_M);
    let mut coverage = Tally::new("coverage", "≥", 0.0, "share of the ground a swath reaches");
    let mut field_figures = Vec::new();
    for (index, (field, figures)) in world.farm.fields.iter().zip(&measured.regions).enumerate() {
        let required = settings
            .required_coverage
            .get(index)
            .copied()
            .unwrap_or(0.99);
        let covered = figures.covered_fraction();
        coverage.limit = coverage.limit.max(required);
        coverage.record(covered, covered + 1e-9 < required, || {
            format!(
                "field '{}': {:.2}% of the ground a swath can reach covered as flown (needs ≥ {:.2}%): {:.1} m² missed",
                field.name,
                100.0 * covered,
                100.0 * required,
                figures.missed_m2()
            )
        });
        field_figures.push(FieldFlown {
            name: field.name.clone(),
            sprayable_area_m2: figures.area_m2,
            covered_fraction: covered,
            required_fraction: required,
            missed_m2: figures.missed_m2(),
            unreachable_m2: figures.unreachable_m2(),
            double_sprayed_m2: figures.doubled_m2,
            over_applied_litres: world
                .vehicle
                .application_rate_l_per_ha
                .map(|rate| crate::numbers::round(rate * figures.doubled_m2 / 1e4, 1e-3)),
        });
    }
    let outside_fraction = if measured.sprayed_m2 > 0.0 {
        measured.outside_m2 / measured.sprayed_m2
    } else {
        0.0
    };
    let limit = settings.max_outside_fraction;
    let mut outside = Tally::new("spray outside", "≤", limit, "share of the sprayed area");
    outside.record(outside_fraction, outside_fraction > limit, || {
        format!(
            "{:.0} m² sprayed outside the fields (or over holes and obstacles): {:.2}% of the {:.0} m² sprayed (at most {:.1}%)",
            measured.outside_m2,
            100.0 * outside_fraction,
            measured.sprayed_m2,
            100.0 * limit
        )
    });
    let lowest_clearance = heights.lowest_clearance_m;
    let bounds = heights.tallies();
    let mut failure_places = Vec::new();
    for tally in [read, frames, spray_height, spray_speed, transit, low_legs]
        .into_iter()
        .chain(bounds)
        .chain([no_go, fence, coverage, outside, tank, battery])
        .chain(mission_size)
    {
        tally.finish(&mut checks, &mut failures, &mut failure_places);
    }
    let round = |value: f64| crate::numbers::round(value, 1e-4);
    for check in &mut checks {
        check.figure = round(check.figure);
    }
    Verdict {
        safe: checks.iter().all(|check| check.passed),
        altitude_reference: settings.altitude,
        checks,
        failures,
        fields: field_figures
            .into_iter()
            .map(|field| FieldFlown {
                sprayable_area_m2: round(field.sprayable_area_m2),
                covered_fraction: crate::numbers::round(field.covered_fraction, 1e-6),
                missed_m2: round(field.missed_m2),
                unreachable_m2: round(field.unreachable_m2),
                double_sprayed_m2: round(field.double_sprayed_m2),
                ..field
            })
            .collect(),
        sprayed_area_m2: round(measured.sprayed_m2),
        sprayed_outside_m2: round(measured.outside_m2),
        sprayed_outside_fraction: crate::numbers::round(outside_fraction, 1e-6),
        sorties: sorties
            .into_iter()
            .map(|sortie| SortieFlown {
                spray_m: round(sortie.spray_m),
                tank_fraction: sortie.tank_fraction.map(|f| crate::numbers::round(f, 1e-6)),
                flight_time_s: round(sortie.flight_time_s),
                battery_fraction: crate::numbers::round(sortie.battery_fraction, 1e-6),
                worst_spray_height_error_m: round(sortie.worst_spray_height_error_m),
                least_transit_margin_m: sortie.least_transit_margin_m.map(round),
                ..sortie
            })
            .collect(),
        lowest_clearance_m: round(if lowest_clearance.is_finite() {
            lowest_clearance
        } else {
            0.0
        }),
        ground: GroundPatches {
            unreachable: regions
                .into_iter()
                .map(|region| region.unreachable)
                .collect(),
            missed: std::mem::take(&mut measured.missed),
            failures: failure_places,
        },
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use serde_json::Value;

    use super::*;
    use crate::input::{geojson, CoordinateChoice};
    use crate::mission::flight::{AltitudeReference, SprayerCommand};
    use crate::model::Vehicle;
    use crate::pipeline::{plan_mission, preflight_settings, render};
    use crate::scenario::Scenario;
    use crate::scenario::ScenarioParts;
    use crate::settings::PlanSettings;

    /// A 120 m × 60 m field with a 20 m square hole, lon/lat near Harbin, flat ground.
    const FARM: &str = r#"{"type":"FeatureCollection","features":[
        {"type":"Feature","properties":{"name":"holed"},"geometry":{"type":"Polygon","coordinates":[
          [[126.6300,45.7500],[126.6315,45.7500],[126.6315,45.75054],[126.6300,45.75054],[126.6300,45.7500]],
          [[126.6307,45.75018],[126.63096,45.75018],[126.63096,45.75036],[126.6307,45.75036],[126.6307,45.75018]]]}},
        {"type":"Feature","properties":{"name":"Launch"},"geometry":{"type":"Point","coordinates":[126.6298,45.7499]}}]}"#;

    fn planned() -> (Scenario, PreflightSettings, Vec<(String, Vec<u8>)>) {
        let farm =
            geojson::parse(Path::new("holed.geojson"), FARM, CoordinateChoice::FromFile).unwrap();
        let scenario = Scenario::with_farm(farm, ScenarioParts::default()).unwrap();
        let mission = plan_mission(&scenario, &PlanSettings::default()).unwrap();
        let rendered = render(&scenario, &mission).unwrap();
        assert!(rendered.verdict.safe, "{:?}", rendered.verdict.failures);
        let settings = preflight_settings(&mission);
        (scenario, settings, rendered.files)
    }

    fn verdict(
        scenario: &Scenario,
        settings: &PreflightSettings,
        files: &[(String, Vec<u8>)],
    ) -> Verdict {
        let world = World {
            farm: &scenario.farm,
            terrain: scenario.terrain.as_ref(),
            vehicle: &scenario.vehicle,
        };
        check(&world, settings, files)
    }

    /// Edits item `index` (0-based) of `sortie_01.plan` and writes its `.waypoints` twin
    /// from the edited plan, so that only the edit differs.
    fn edit(files: &mut [(String, Vec<u8>)], change: impl FnOnce(&mut Vec<Value>)) {
        let plan_at = files
            .iter()
            .position(|(n, _)| n == "sortie_01.plan")
            .unwrap();
        let mut plan: Value = serde_json::from_slice(&files[plan_at].1).unwrap();
        let mut items = plan["mission"]["items"].as_array().unwrap().clone();
        change(&mut items);
        plan["mission"]["items"] = Value::Array(items.clone());
        files[plan_at].1 = serde_json::to_vec(&plan).unwrap();
        let home = plan["mission"]["plannedHomePosition"]
            .as_array()
            .unwrap()
            .clone();
        let mut text = format!(
            "QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t{}\t{}\t{}\t1\n",
            home[0], home[1], home[2]
        );
        for (k, item) in items.iter().enumerate() {
            let p: Vec<String> = item["params"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().map_or("nan".to_string(), |v| v.to_string()))
                .collect();
            text.push_str(&format!(
                "{}\t0\t{}\t{}\t{}\t1\n",
                k + 1,
                item["frame"],
                item["command"],
                p.join("\t")
            ));
        }
        let twin = files
            .iter()
            .position(|(n, _)| n == "sortie_01.waypoints")
            .unwrap();
        files[twin].1 = text.into_bytes();
    }

    fn failed(verdict: &Verdict) -> Vec<&'static str> {
        verdict
            .checks
            .iter()
            .filter(|c| !c.passed)
            .map(|c| c.name)
            .collect()
    }

    #[test]
    fn the_plan_as_written_flies_safely_and_covers_the_field() {
        let (scenario, settings, files) = planned();
        let verdict = verdict(&scenario, &settings, &files);
        assert!(verdict.safe, "{:?}", verdict.failures);
        assert!(verdict.fields[0].covered_fraction >= 0.99);
        assert!(verdict.sprayed_outside_fraction <= MAX_OUTSIDE_FRACTION);
        // No rate, no litres; at 80 L/ha the double dose in litres.
        assert_eq!(verdict.fields[0].over_applied_litres, None);
        let vehicle = Vehicle {
            application_rate_l_per_ha: Some(80.0),
            ..scenario.vehicle.clone()
        };
        let world = World {
            farm: &scenario.farm,
            terrain: scenario.terrain.as_ref(),
            vehicle: &vehicle,
        };
        let field = &check(&world, &settings, &files).fields[0];
        assert!(field.double_sprayed_m2 > 0.0);
        assert_eq!(
            field.over_applied_litres,
            Some(crate::numbers::round(
                80.0 * field.double_sprayed_m2 / 1e4,
                1e-3
            ))
        );
        // Planned from the launch marker, relative altitudes (no DEM).
        assert_eq!(verdict.altitude_reference, AltitudeReference::Relative);
    }

    fn position_items(items: &[Value]) -> Vec<usize> {
        (0..items.len())
            .filter(|&k| items[k]["command"] == 16)
            .collect()
    }

    #[test]
    fn a_frame_that_is_not_the_reference_fails() {
        let (scenario, settings, mut files) = planned();
        edit(&mut files, |items| {
            let k = position_items(items)[3];
            items[k]["frame"] = 0.into();
        });
        assert_eq!(
            failed(&verdict(&scenario, &settings, &files)),
            vec!["altitude frame"]
        );
    }

    #[test]
    fn a_waypoint_under_the_ground_fails() {
        let (scenario, settings, mut files) = planned();
        edit(&mut files, |items| {
            // The first waypoint after takeoff: the transit out, now 3 m below the ground.
            let k = position_items(items)[0];
            items[k]["params"][6] = (-3.0).into();
        });
        let verdict = verdict(&scenario, &settings, &files);
        assert!(
            failed(&verdict).contains(&"transit clearance"),
            "{:?}",
            verdict.failures
        );
        assert!(verdict.lowest_clearance_m < 0.0);
    }

    #[test]
    fn no_tolerance_lets_a_file_fly_into_the_ground() {
        // Every waypoint of sortie 1 lowered 2.5 m below spray height (2 m), and the file
        // held to a tolerance of 30 m, as an edited report.json could say: the checks drawn
        // from the tolerance pass it, the clearance floor does not.
        let (scenario, mut settings, mut files) = planned();
        settings.terrain_tolerance_m = 30.0;
        edit(&mut files, |items| {
            for k in position_items(items) {
                let altitude = items[k]["params"][6].as_f64().unwrap();
                items[k]["params"][6] = (altitude - 2.5).into();
            }
        });
        let verdict = verdict(&scenario, &settings, &files);
        assert!(verdict.lowest_clearance_m < 0.0);
        assert!(
            failed(&verdict).contains(&"clearance floor"),
            "{:?}",
            verdict.failures
        );
        assert!(
            verdict
                .failures
                .iter()
                .any(|line| line.contains("never below 0.5 m")),
            "{:?}",
            verdict.failures
        );
    }

    #[test]
    fn a_climb_far_above_the_cruise_height_fails_and_the_plans_own_climbs_pass() {
        // The plan as written passes the ceiling (its own climbs for transits included).
        let (scenario, settings, mut files) = planned();
        assert!(!failed(&verdict(&scenario, &settings, &files)).contains(&"height ceiling"));
        // A climb to 250 m over a waypoint and down again, inserted in a ground station.
        edit(&mut files, |items| {
            let k = position_items(items)[4];
            let mut climb = items[k].clone();
            let altitude = climb["params"][6].as_f64().unwrap();
            climb["params"][6] = (altitude + 250.0).into();
            let back = items[k].clone();
            items.splice(k + 1..k + 1, [climb, back]);
        });
        let verdict = verdict(&scenario, &settings, &files);
        assert!(
            failed(&verdict).contains(&"height ceiling"),
            "{:?}",
            verdict.failures
        );
    }

    #[test]
    fn a_spray_leg_through_the_hole_fails() {
        let (scenario, settings, mut files) = planned();
        edit(&mut files, |items| {
            // A spray waypoint moved into the middle of the hole.
            let mut spraying = false;
            let mut target = None;
            for (k, item) in items.iter().enumerate() {
                if item["command"] == 216 {
                    spraying = item["params"][0] == 1.0;
                } else if spraying && item["command"] == 16 && target.is_none() {
                    target = Some(k);
                }
            }
            let k = target.unwrap();
            items[k]["params"][4] = 45.75027.into();
            items[k]["params"][5] = 126.63083.into();
        });
        let verdict = verdict(&scenario, &settings, &files);
        assert!(
            failed(&verdict).contains(&"holes and obstacles"),
            "{:?}",
            verdict.failures
        );
        assert!(
            verdict.failures.iter().any(|line| line.contains("(126.63")),
            "places in lon/lat"
        );
    }

    #[test]
    fn a_flight_through_an_obstacle_fails_whatever_the_files_fence_says() {
        // The files as planned, checked against the farm with a strip of obstacle between the
        // launch point and the field: the files' fence does not exclude it (as after a fence
        // edited away in a ground station), yet every way out crosses it at transit height.
        let (scenario, settings, files) = planned();
        let strip = r#"{"type":"Feature","properties":{"name":"hedge","kind":"obstacle"},"geometry":{"type":"Polygon","coordinates":[
          [[126.62988,45.7490],[126.62994,45.7490],[126.62994,45.7510],[126.62988,45.7510],[126.62988,45.7490]]]}},"#;
        let text = FARM.replacen(r#""features":["#, &format!(r#""features":[{strip}"#), 1);
        let farm = geojson::parse(
            Path::new("hedged.geojson"),
            &text,
            CoordinateChoice::FromFile,
        )
        .unwrap();
        let hedged = Scenario::with_farm(farm, ScenarioParts::default()).unwrap();
        let verdict = verdict(&hedged, &settings, &files);
        let failed = failed(&verdict);
        assert!(
            failed.contains(&"holes and obstacles"),
            "{:?}",
            verdict.failures
        );
        assert!(!failed.contains(&"fence"), "{:?}", verdict.failures);
        assert!(
            verdict
                .failures
                .iter()
                .any(|line| line.contains("flying through an obstacle")),
            "{:?}",
            verdict.failures
        );
        // Without the hedge the same files pass.
        assert!(self::verdict(&scenario, &settings, &files).safe);
    }

    #[test]
    fn a_spray_speed_edited_fails_and_the_plans_own_passes() {
        let (scenario, settings, mut files) = planned();
        let as_planned = verdict(&scenario, &settings, &files);
        let check = |verdict: &Verdict| {
            verdict
                .checks
                .iter()
                .find(|check| check.name == "spray speed")
                .cloned()
                .unwrap()
        };
        assert!(check(&as_planned).passed);
        assert!(
            check(&as_planned).figure < 1e-9,
            "the plan sprays at the spray speed"
        );
        // Every speed item of sortie 1 set to four times the spray speed.
        let fast = 4.0 * scenario.vehicle.spray_speed_mps;
        edit(&mut files, |items| {
            for item in items.iter_mut().filter(|item| item["command"] == 178) {
                item["params"][1] = fast.into();
            }
        });
        let edited = verdict(&scenario, &settings, &files);
        assert!(!check(&edited).passed, "{:?}", edited.failures);
        assert!(
            edited
                .failures
                .iter()
                .any(|line| line.contains("the dose would be 25% of the rate")),
            "{:?}",
            edited.failures
        );
    }

    /// Trial 7's edit of a written mission: the speed item before each swath (type 1, the
    /// spray speed) turned to type 2, a climb speed. ArduCopter then flies the swaths at the
    /// transit speed set before them, and the check must see it.
    #[test]
    fn a_speed_item_turned_into_a_climb_speed_fails() {
        let (scenario, settings, mut files) = planned();
        let spray = scenario.vehicle.spray_speed_mps;
        edit(&mut files, |items| {
            for item in items
                .iter_mut()
                .filter(|item| item["command"] == 178 && item["params"][1].as_f64() == Some(spray))
            {
                item["params"][0] = 2.0.into();
            }
        });
        let edited = verdict(&scenario, &settings, &files);
        assert!(!edited.safe);
        assert!(
            edited
                .failures
                .iter()
                .any(|line| line.contains("sets the climb speed")),
            "{:?}",
            edited.failures
        );
    }

    /// Decision 0028: over a plateau's ramp (6 m over 2 m) the climb holds the vehicle back
    /// along its spray legs. A pump on a servo output runs at one flow and overdoses there;
    /// ArduPilot's sprayer pumps in proportion to ground speed and does not.
    #[test]
    fn a_constant_flow_pump_slowed_by_its_climbs_overdoses() {
        use geo::BoundingRect;
        let farm =
            geojson::parse(Path::new("holed.geojson"), FARM, CoordinateChoice::FromFile).unwrap();
        let mut scenario = Scenario::with_farm(farm, ScenarioParts::default()).unwrap();
        let bounds = scenario.farm.fields[0].polygon.bounding_rect().unwrap();
        let plateau = crate::terrain::Plateau {
            center: [
                bounds.min().x + 25.0,
                (bounds.min().y + bounds.max().y) / 2.0,
            ],
            radius_m: 12.0,
            height_m: 6.0,
            edge_ramp_m: 2.0,
        };
        scenario.terrain = Box::new(crate::terrain::Plateaus::new(0.0, vec![plateau]).unwrap());
        let servo = SprayerCommand::Servo {
            channel: 9,
            on_pwm: 1900,
            off_pwm: 1100,
        };
        for (sprayer, overdoses) in [(SprayerCommand::DoSprayer, false), (servo, true)] {
            let mut plan_settings = PlanSettings::default();
            plan_settings.mission.sprayer = sprayer;
            let mission = plan_mission(&scenario, &plan_settings).unwrap();
            let rendered = render(&scenario, &mission).unwrap();
            let map = rendered
                .files
                .iter()
                .find(|(name, _)| name == "plan.svg")
                .map(|(_, bytes)| String::from_utf8_lossy(bytes).into_owned())
                .unwrap();
            let verdict = rendered.verdict;
            // The map rings where the check failed, and only then.
            assert_eq!(!verdict.ground.failures.is_empty(), overdoses);
            assert_eq!(map.contains(r#"<g id="failures""#), overdoses);
            assert_eq!(map.contains("a check failed here"), overdoses);
            let spray_speed = verdict
                .checks
                .iter()
                .find(|check| check.name == "spray speed")
                .unwrap();
            assert_eq!(
                spray_speed.passed, !overdoses,
                "{sprayer:?}: {:?}",
                verdict.failures
            );
            let steep = verdict
                .failures
                .iter()
                .any(|line| line.contains("terrain too steep to spray along"));
            assert_eq!(steep, overdoses, "{sprayer:?}: {:?}", verdict.failures);
        }
    }

    #[test]
    fn a_sortie_over_its_battery_fails() {
        let (mut scenario, settings, files) = planned();
        scenario.vehicle.battery_endurance_s = 60.0;
        assert!(failed(&verdict(&scenario, &settings, &files)).contains(&"battery"));
    }

    #[test]
    fn a_sortie_into_the_share_to_land_with_fails() {
        let (mut scenario, settings, files) = planned();
        let flown = verdict(&scenario, &settings, &files);
        assert!(!failed(&flown).contains(&"battery"));
        let worst = flown
            .sorties
            .iter()
            .map(|sortie| sortie.battery_fraction)
            .fold(0.0, f64::max);
        // The whole battery covers the worst sortie; the battery less the share does not.
        scenario.vehicle.battery_reserve_percent = 100.0 * (1.0 - worst) + 1.0;
        let careful = verdict(&scenario, &settings, &files);
        assert!(
            failed(&careful).contains(&"battery"),
            "{:?}",
            careful.failures
        );
        assert!(careful
            .failures
            .iter()
            .any(|line| line.contains("s usable")));
    }

    #[test]
    fn a_stray_copy_or_a_missing_sortie_fails_the_read() {
        let (scenario, settings, files) = planned();
        let first = files
            .iter()
            .find(|(name, _)| name == "sortie_01.plan")
            .unwrap()
            .1
            .clone();
        let mut copied = files.clone();
        copied.push(("sortie_01 copy.plan".to_string(), first.clone()));
        let with_copy = verdict(&scenario, &settings, &copied);
        assert_eq!(failed(&with_copy), vec!["files read back"]);
        assert!(with_copy.failures[0].contains("sortie_01 copy.plan is not"));
        // The same sortie under two numberings: named, not taken for a missing sortie 2.
        let mut twice = files.clone();
        twice.push(("sortie_001.plan".to_string(), first));
        let doubled = verdict(&scenario, &settings, &twice);
        assert!(
            doubled
                .failures
                .iter()
                .any(|line| line.contains("are both sortie 1")),
            "{:?}",
            doubled.failures
        );
        // The sortie's files numbered 2: sortie 1 is missing.
        let missing: Vec<(String, Vec<u8>)> = files
            .into_iter()
            .map(|(name, bytes)| (name.replace("sortie_01.", "sortie_02."), bytes))
            .collect();
        let verdict = verdict(&scenario, &settings, &missing);
        assert!(failed(&verdict).contains(&"files read back"));
        assert!(
            verdict
                .failures
                .iter()
                .any(|line| line.contains("sortie 1 is missing")),
            "{:?}",
            verdict.failures
        );
    }

    #[test]
    fn a_waypoints_file_that_disagrees_with_its_plan_fails() {
        let (scenario, settings, mut files) = planned();
        let twin = files
            .iter()
            .position(|(n, _)| n == "sortie_01.waypoints")
            .unwrap();
        let text = String::from_utf8(files[twin].1.clone()).unwrap();
        let mut lines: Vec<&str> = text.lines().collect();
        lines.pop();
        files[twin].1 = (lines.join("\n") + "\n").into_bytes();
        assert_eq!(
            failed(&verdict(&scenario, &settings, &files)),
            vec!["files read back"]
        );
    }
}
