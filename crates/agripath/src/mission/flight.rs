//! The flight as autopilot commands, one mission per sortie: what every mission exporter
//! writes (QGroundControl `.plan`, `QGC WPL 110`, KML, CSV).
//!
//! A sortie takes off at the supply point to the cruise height (spray height + h), flies to
//! above its first route point, descends to spray height, then follows the route: the
//! sprayer goes on at each swath start and off at its end (`DO_SPRAYER`, or `DO_SET_SERVO`),
//! the speed changes between spraying and transit (`DO_CHANGE_SPEED`), transfers that leave a
//! field climb to the cruise height and back. At its last point the sprayer goes off and the
//! drone climbs, flies back and lands at the supply point.
//!
//! Terrain following: along a swath the terrain is sampled every `sample_spacing_m` and the
//! waypoints kept are those a vertical Douglas-Peucker keeps at `terrain_tolerance_m`: between
//! two waypoints the straight climb or descent stays within the tolerance of terrain + spray
//! height (what QGroundControl's terrain following precomputes), and flat stretches need
//! only their ends.

use serde::Serialize;

use crate::error::Fault;
use crate::geometry::{from_utm, to_utm, UtmZone};
use crate::model::{CoordinateSystem, Scenario};
use crate::pipeline::PlannedMission;
use crate::sortie::route::{RoutePoint, Segment};
use crate::terrain::Terrain;

/// How altitudes are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum AltitudeReference {
    /// Above sea level from our terrain model (MAV_FRAME_GLOBAL, QGC "calculated above terrain").
    SeaLevel,
    /// Above the terrain, as the autopilot measures it (MAV_FRAME_GLOBAL_TERRAIN_ALT, ArduPilot).
    Terrain,
}

/// How the sprayer is switched.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SprayerCommand {
    /// MAV_CMD_DO_SPRAYER (216), ArduPilot's sprayer.
    DoSprayer,
    /// MAV_CMD_DO_SET_SERVO (183) on `channel` with these pulse widths, for any pump on a servo output.
    Servo {
        channel: u16,
        on_pwm: u16,
        off_pwm: u16,
    },
}

/// What the mission files are asked for.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MissionSettings {
    pub altitude: AltitudeReference,
    pub sprayer: SprayerCommand,
    /// Largest gap between the flown altitude and terrain + spray height along a swath, metres.
    pub terrain_tolerance_m: f64,
    /// Terrain samples along swaths, metres.
    pub sample_spacing_m: f64,
    /// Where a plan in local metres lies on Earth (lon, lat of its origin), for mission files.
    pub local_origin: (f64, f64),
}

impl Default for MissionSettings {
    fn default() -> Self {
        Self {
            altitude: AltitudeReference::SeaLevel,
            sprayer: SprayerCommand::DoSprayer,
            terrain_tolerance_m: 1.0,
            sample_spacing_m: 2.0,
            // Harbin, Heilongjiang: the Northeast Agricultural University fields of seed 003.
            local_origin: (126.63, 45.75),
        }
    }
}

/// One autopilot command.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "action", rename_all = "snake_case")]
pub enum Action {
    Takeoff,
    Waypoint,
    Land,
    /// Ground speed, m/s.
    Speed {
        mps: f64,
    },
    Spray {
        on: bool,
    },
}

/// A command with its place: longitude, latitude, terrain height and height above it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Item {
    #[serde(flatten)]
    pub action: Action,
    pub lon: f64,
    pub lat: f64,
    pub ground_m: f64,
    pub above_ground_m: f64,
}

impl Item {
    pub fn sea_level_m(&self) -> f64 {
        self.ground_m + self.above_ground_m
    }

    /// Whether the command flies somewhere (the others act where the drone is).
    pub fn moves(&self) -> bool {
        matches!(
            self.action,
            Action::Takeoff | Action::Waypoint | Action::Land
        )
    }
}

/// The mission of one sortie.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SortieMission {
    pub sortie: usize,
    /// The supply point: home, takeoff and landing.
    pub home: Item,
    pub items: Vec<Item>,
}

/// Plan metres → longitude, latitude.
#[derive(Debug, Clone, Copy)]
pub struct GeoFrame {
    system: CoordinateSystem,
    /// For local plans: the zone and UTM position of the origin.
    local: Option<(UtmZone, f64, f64)>,
}

impl GeoFrame {
    pub fn new(system: CoordinateSystem, local_origin: (f64, f64)) -> Self {
        let local = (system == CoordinateSystem::Local).then(|| {
            let zone = UtmZone::containing(local_origin.0, local_origin.1);
            let (easting, northing) = to_utm(local_origin.0, local_origin.1, zone);
            (zone, easting, northing)
        });
        Self { system, local }
    }

    pub fn lon_lat(&self, x: f64, y: f64) -> (f64, f64) {
        match self.local {
            Some((zone, easting, northing)) => from_utm(easting + x, northing + y, zone),
            None => self.system.to_input(x, y),
        }
    }
}

/// Keeps the samples a vertical Douglas-Peucker keeps: (distance along, height) pairs.
fn simplify(profile: &[(f64, f64)], tolerance: f64, keep: &mut [bool], first: usize, last: usize) {
    if last <= first + 1 {
        return;
    }
    let (x0, z0) = profile[first];
    let (x1, z1) = profile[last];
    let mut worst = (0.0, first);
    for (index, &(x, z)) in profile.iter().enumerate().take(last).skip(first + 1) {
        let along = if x1 > x0 { (x - x0) / (x1 - x0) } else { 0.0 };
        let gap = (z - (z0 + along * (z1 - z0))).abs();
        if gap > worst.0 {
            worst = (gap, index);
        }
    }
    if worst.0 > tolerance {
        keep[worst.1] = true;
        simplify(profile, tolerance, keep, first, worst.1);
        simplify(profile, tolerance, keep, worst.1, last);
    }
}

/// The terrain-following waypoints of a spray run through `points` (plan metres and ground
/// heights): the run's ends, every corner (an edge pass turns at the boundary's vertices),
/// and every sample the terrain needs between them.
fn follow_terrain(
    points: &[RoutePoint],
    terrain: &dyn Terrain,
    settings: &MissionSettings,
) -> Result<Vec<RoutePoint>, Fault> {
    let mut samples = vec![points[0]];
    let mut anchors = vec![0];
    for (index, pair) in points.windows(2).enumerate() {
        let (a, b) = (pair[0], pair[1]);
        let length = (b.x - a.x).hypot(b.y - a.y);
        let steps = (length / settings.sample_spacing_m).ceil().max(1.0) as usize;
        for step in 1..steps {
            let t = step as f64 / steps as f64;
            let (x, y) = (a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
            samples.push(RoutePoint {
                x,
                y,
                ground_m: terrain.height_m(x, y)?,
            });
        }
        samples.push(b);
        let corner = points.get(index + 2).is_some_and(|c| {
            let (incoming, outgoing) = ((b.x - a.x, b.y - a.y), (c.x - b.x, c.y - b.y));
            let cross = incoming.0 * outgoing.1 - incoming.1 * outgoing.0;
            let dot = incoming.0 * outgoing.0 + incoming.1 * outgoing.1;
            cross.atan2(dot).abs() > 0.5_f64.to_radians()
        });
        if corner || index + 2 == points.len() {
            anchors.push(samples.len() - 1);
        }
    }
    let mut along = 0.0;
    let profile: Vec<(f64, f64)> = samples
        .iter()
        .enumerate()
        .map(|(index, point)| {
            if index > 0 {
                let previous = samples[index - 1];
                along += (point.x - previous.x).hypot(point.y - previous.y);
            }
            (along, point.ground_m)
        })
        .collect();
    let mut keep = vec![false; samples.len()];
    for pair in anchors.windows(2) {
        keep[pair[0]] = true;
        keep[pair[1]] = true;
        simplify(
            &profile,
            settings.terrain_tolerance_m,
            &mut keep,
            pair[0],
            pair[1],
        );
    }
    Ok(samples
        .into_iter()
        .zip(keep)
        .filter_map(|(point, kept)| kept.then_some(point))
        .collect())
}

/// The missions of a plan, one per sortie (one in all when the route is not split).
pub fn build_missions(
    scenario: &Scenario,
    mission: &PlannedMission,
    settings: &MissionSettings,
) -> Result<Vec<SortieMission>, Fault> {
    let vehicle = &scenario.vehicle;
    let frame = GeoFrame::new(scenario.farm.coordinate_system, settings.local_origin);
    let speeds = crate::sortie::route::Speeds {
        spray_mps: vehicle.spray_speed_mps,
        turn_mps: vehicle.turn_speed_mps,
        transit_mps: vehicle.transit_speed_mps,
    };
    let (work_route, supply, bounds) = match &mission.sorties {
        Some(split) => {
            let mut bounds: Vec<usize> = vec![0];
            bounds.extend(split.plan.breaks.iter().copied());
            bounds.push(split.work_route.len().saturating_sub(1));
            (split.work_route.clone(), split.supply, bounds)
        }
        None => {
            let route = crate::sortie::route::WorkRoute::from_route(&mission.route, speeds);
            let supply = mission
                .route
                .launch
                .map(|leg| RoutePoint {
                    x: leg.from.x,
                    y: leg.from.y,
                    ground_m: leg.from.ground_m,
                })
                .or_else(|| route.points().first().copied());
            let Some(supply) = supply else {
                return Ok(vec![]);
            };
            let last = route.len().saturating_sub(1);
            (route, supply, vec![0, last])
        }
    };
    if work_route.len() < 2 {
        return Ok(vec![]);
    }
    let spray_height = vehicle.spray_height_m;
    let cruise = spray_height + vehicle.safe_height_m.max(5.0);
    let item = |action: Action, point: &RoutePoint, above: f64| {
        let (lon, lat) = frame.lon_lat(point.x, point.y);
        Item {
            action,
            lon,
            lat,
            ground_m: point.ground_m,
            above_ground_m: above,
        }
    };
    let home = item(Action::Waypoint, &supply, 0.0);
    let points = work_route.points();
    let segments = work_route.segments();
    let mut missions = Vec::new();
    for (sortie, pair) in bounds.windows(2).enumerate() {
        let (first, last) = (pair[0], pair[1]);
        let mut items = vec![
            item(Action::Takeoff, &supply, cruise),
            item(
                Action::Speed {
                    mps: vehicle.transit_speed_mps,
                },
                &supply,
                cruise,
            ),
            item(Action::Waypoint, &points[first], cruise),
            item(Action::Waypoint, &points[first], spray_height),
            item(
                Action::Speed {
                    mps: vehicle.spray_speed_mps,
                },
                &points[first],
                spray_height,
            ),
        ];
        let mut index = first;
        while index < last {
            match segments[index] {
                Segment::Spray => {
                    let mut end = index;
                    while end < last && segments[end] == Segment::Spray {
                        end += 1;
                    }
                    items.push(item(
                        Action::Spray { on: true },
                        &points[index],
                        spray_height,
                    ));
                    let run =
                        follow_terrain(&points[index..=end], scenario.terrain.as_ref(), settings)?;
                    for point in &run[1..] {
                        items.push(item(Action::Waypoint, point, spray_height));
                    }
                    // Off at the swath's end: nothing sprays on turns, transfers or returns.
                    items.push(item(
                        Action::Spray { on: false },
                        &points[end],
                        spray_height,
                    ));
                    index = end;
                }
                Segment::Turn => {
                    items.push(item(Action::Waypoint, &points[index + 1], spray_height));
                    index += 1;
                }
                Segment::Transfer => {
                    let (from, to) = (&points[index], &points[index + 1]);
                    items.push(item(
                        Action::Speed {
                            mps: vehicle.transit_speed_mps,
                        },
                        from,
                        spray_height,
                    ));
                    items.push(item(Action::Waypoint, from, cruise));
                    items.push(item(Action::Waypoint, to, cruise));
                    items.push(item(Action::Waypoint, to, spray_height));
                    items.push(item(
                        Action::Speed {
                            mps: vehicle.spray_speed_mps,
                        },
                        to,
                        spray_height,
                    ));
                    index += 1;
                }
            }
        }
        items.push(item(
            Action::Speed {
                mps: vehicle.transit_speed_mps,
            },
            &points[last],
            spray_height,
        ));
        items.push(item(Action::Waypoint, &points[last], cruise));
        items.push(item(Action::Waypoint, &supply, cruise));
        items.push(item(Action::Land, &supply, 0.0));
        missions.push(SortieMission {
            sortie,
            home,
            items,
        });
    }
    Ok(missions)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn douglas_peucker_keeps_the_bend_and_drops_the_flat() {
        let profile: Vec<(f64, f64)> = (0..=20)
            .map(|i| {
                let x = i as f64;
                (x, if i <= 10 { 0.0 } else { (x - 10.0) * 0.5 })
            })
            .collect();
        let mut keep = vec![false; profile.len()];
        keep[0] = true;
        keep[20] = true;
        simplify(&profile, 0.1, &mut keep, 0, 20);
        let kept: Vec<usize> = (0..=20).filter(|&i| keep[i]).collect();
        assert_eq!(kept, vec![0, 10, 20]);
    }

    struct Waves;

    impl Terrain for Waves {
        fn height_m(&self, x: f64, y: f64) -> Result<f64, crate::TerrainError> {
            Ok(4.0 * (x / 23.0).sin() + 2.0 * (y / 17.0).cos())
        }
        fn extent(&self) -> Option<crate::terrain::Extent> {
            None
        }
        fn describe(&self) -> String {
            "waves".into()
        }
    }

    #[test]
    fn terrain_following_keeps_corners_and_stays_within_the_tolerance() {
        let at = |x: f64, y: f64| RoutePoint {
            x,
            y,
            ground_m: Waves.height_m(x, y).unwrap(),
        };
        // An L-shaped run: along x, then along y.
        let points = [at(0.0, 0.0), at(100.0, 0.0), at(100.0, 80.0)];
        let settings = MissionSettings {
            terrain_tolerance_m: 0.5,
            sample_spacing_m: 1.0,
            ..MissionSettings::default()
        };
        let kept = follow_terrain(&points, &Waves, &settings).unwrap();
        assert!(
            kept.iter().any(|p| p.x == 100.0 && p.y == 0.0),
            "the corner is a waypoint"
        );
        assert!(
            kept.len() > 3 && kept.len() < 60,
            "{} waypoints",
            kept.len()
        );
        for pair in kept.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let length = (b.x - a.x).hypot(b.y - a.y);
            for k in 0..=100 {
                let t = k as f64 / 100.0;
                let (x, y) = (a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
                let flown = a.ground_m + t * (b.ground_m - a.ground_m);
                // Sampled every metre: between samples the gap can grow by the slope × 1 m.
                assert!(
                    (flown - Waves.height_m(x, y).unwrap()).abs() <= 0.5 + 0.2,
                    "{length} m leg at t = {t}"
                );
            }
        }
    }

    #[test]
    fn a_local_frame_is_placed_at_its_origin() {
        let frame = GeoFrame::new(CoordinateSystem::Local, (126.63, 45.75));
        let (lon, lat) = frame.lon_lat(0.0, 0.0);
        assert!((lon - 126.63).abs() < 1e-9 && (lat - 45.75).abs() < 1e-9);
        let (_, north) = frame.lon_lat(0.0, 1000.0);
        assert!((north - 45.75 - 1000.0 / 111_150.0).abs() < 2e-4);
    }
}
