//! The flight as autopilot commands, one mission per sortie: what every mission exporter
//! writes (QGroundControl `.plan`, `QGC WPL 110`, KML, CSV).
//!
//! A sortie takes off at the supply point to the cruise height (spray height + h), flies to
//! above its first route point, descends to spray height, then follows the route: the
//! sprayer goes on at each swath start and off at its end (`DO_SPRAYER`, or `DO_SET_SERVO`;
//! a survey vehicle's camera instead: `DO_SET_CAM_TRIGG_DIST` with its distance, then 0),
//! the speed changes between spraying and transit (`DO_CHANGE_SPEED`), transfers that leave a
//! field climb to the cruise height and back. At its last point the sprayer goes off and the
//! drone climbs, flies back and lands at the supply point.
//!
//! The parts: `settings` (what the files are asked for: altitude reference, sprayer,
//! terrain tolerance), `geo_frame` (plan metres ↔ longitude, latitude),
//! `terrain_following` (the waypoints a spray run keeps over the terrain) and `battery` (the
//! sortie model the split plans with, charged for the legs as these missions fly them).

pub mod battery;
mod geo_frame;
mod settings;
mod terrain_following;

use serde::Serialize;

use crate::error::Fault;
use crate::scenario::Scenario;
use crate::sequence::Route;
use crate::sortie::route::{RoutePoint, Segment};
use crate::sortie::PlannedSorties;
use crate::terrain::Terrain;
use terrain_following::follow_terrain;

pub use geo_frame::GeoFrame;
pub use settings::{
    sea_level_known, AltitudeReference, MissionSettings, SprayerCommand, DEFAULT_LOCAL_ORIGIN,
    SERVO_CHANNELS, SERVO_PWM_US,
};

/// One autopilot command.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "action", rename_all = "snake_case")]
pub enum Action {
    /// Take off, climbing to the item's altitude.
    Takeoff,
    /// Fly to the item's place and altitude.
    Waypoint,
    /// Land at the item's place.
    Land,
    /// Ground speed, m/s.
    Speed {
        /// The speed, m/s.
        mps: f64,
    },
    /// Turn the sprayer on or off.
    Spray {
        /// `true`: on; `false`: off.
        on: bool,
    },
    /// A survey camera: a photo every `distance_m` along the track from here on (one at
    /// once), or none after this with 0.
    CameraTrigger {
        /// Ground distance between photos, metres; 0 stops triggering.
        distance_m: f64,
    },
}

impl Action {
    /// The work switched on (`true`) or off at a swath's ends: the sprayer, or for a survey
    /// vehicle (`trigger_distance_m`) the camera's distance trigger.
    pub fn work(on: bool, trigger_distance_m: Option<f64>) -> Self {
        match trigger_distance_m {
            Some(distance_m) => Self::CameraTrigger {
                distance_m: if on { distance_m } else { 0.0 },
            },
            None => Self::Spray { on },
        }
    }

    /// Whether the action switches the work on or off: `Some(true)` for on.
    pub fn work_state(&self) -> Option<bool> {
        match *self {
            Self::Spray { on } => Some(on),
            Self::CameraTrigger { distance_m } => Some(distance_m > 0.0),
            _ => None,
        }
    }
}

/// A command with its place: longitude, latitude, terrain height and height above it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Item {
    /// What the command does.
    #[serde(flatten)]
    pub action: Action,
    /// Longitude, degrees.
    pub lon: f64,
    /// Latitude, degrees.
    pub lat: f64,
    /// Terrain height under the item, metres, in the terrain model's datum (sea level for a DEM).
    pub ground_m: f64,
    /// Height of the item above that terrain, metres.
    pub above_ground_m: f64,
}

impl Item {
    /// The item's altitude, metres: ground plus height above it, in the terrain model's datum.
    pub fn sea_level_m(&self) -> f64 {
        self.ground_m + self.above_ground_m
    }

    /// The altitude written for this item in `reference`, with the launch point's ground at
    /// `home_ground_m`.
    pub fn altitude_m(&self, reference: AltitudeReference, home_ground_m: f64) -> f64 {
        match reference {
            AltitudeReference::Relative => self.sea_level_m() - home_ground_m,
            AltitudeReference::SeaLevel => self.sea_level_m(),
            AltitudeReference::Terrain => self.above_ground_m,
        }
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
    /// The sortie's index in the plan, from 0.
    pub sortie: usize,
    /// The supply point: home, takeoff and landing.
    pub home: Item,
    /// The commands in flying order, from takeoff to landing.
    pub items: Vec<Item>,
}

/// Terrain samples along a transit, metres: at most this far apart (the preflight samples
/// legs at the same spacing).
pub const TRANSIT_SAMPLE_M: f64 = 1.0;

/// The highest ground under the straight leg a → b, sampled every [`TRANSIT_SAMPLE_M`] and
/// at the terrain's bends and peaks between ([`crate::terrain::profile_places`]).
pub fn highest_ground(terrain: &dyn Terrain, a: (f64, f64), b: (f64, f64)) -> Result<f64, Fault> {
    let length = (b.0 - a.0).hypot(b.1 - a.1);
    let place = |t: f64| (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
    let places = crate::terrain::profile_places(terrain, a, b, length, TRANSIT_SAMPLE_M, |t| {
        let (x, y) = place(t);
        terrain.height_m(x, y).ok().map(|ground| vec![ground])
    });
    let mut highest = f64::NEG_INFINITY;
    for t in places {
        let (x, y) = place(t);
        highest = highest.max(terrain.height_m(x, y)?);
    }
    Ok(highest)
}

/// Half the width of the corridor whose ground a transit clears by its height, metres: the
/// distance it keeps from obstacles. Ground beside a leg (a mast, a bank) is as much in its
/// way as ground beneath it: a transit held only to the ground under it passed 0.49 m beside
/// a mast one DEM cell wide (trial 8, decision 0036).
pub const TRANSIT_CORRIDOR_M: f64 = OBSTACLE_CLEARANCE_M;

/// Most spacing of the lines across the corridor the ground is read along, metres; on a
/// raster it is also at most half a cell, so that a feature one cell wide (whose bilinear
/// surface is two cells wide) is met by a line (a review: a 0.25 m DEM's pole sat between
/// lines 0.5 m apart).
pub const CORRIDOR_LINE_SPACING_M: f64 = 0.5;

/// The highest ground within `half_width_m` of the straight leg a → b: along the leg
/// ([`highest_ground`], which fails where the terrain has no height) and along lines beside
/// it, [`CORRIDOR_LINE_SPACING_M`] or half a raster cell apart and as far beyond its ends as
/// `half_width_m` (where those leave the terrain's extent, they are not read).
pub fn highest_ground_near(
    terrain: &dyn Terrain,
    a: (f64, f64),
    b: (f64, f64),
    half_width_m: f64,
) -> Result<f64, Fault> {
    let mut highest = highest_ground(terrain, a, b)?;
    let length = (b.0 - a.0).hypot(b.1 - a.1);
    let (along_x, along_y) = if length > 1e-9 {
        ((b.0 - a.0) / length, (b.1 - a.1) / length)
    } else {
        (1.0, 0.0)
    };
    let spacing = terrain
        .lattice()
        .map_or(CORRIDOR_LINE_SPACING_M, |(_, (cell_x, cell_y))| {
            CORRIDOR_LINE_SPACING_M.min(cell_x.abs().min(cell_y.abs()) / 2.0)
        });
    let lines = (half_width_m / spacing).ceil() as i32;
    let (beyond_x, beyond_y) = (along_x * half_width_m, along_y * half_width_m);
    let span = length + 2.0 * half_width_m;
    // Line 0 is the leg's own, read again from `half_width_m` before its start to as far
    // past its end.
    for line in -lines..=lines {
        let offset =
            (half_width_m * f64::from(line) / f64::from(lines)).clamp(-half_width_m, half_width_m);
        let (across_x, across_y) = (-along_y * offset, along_x * offset);
        let from = (a.0 + across_x - beyond_x, a.1 + across_y - beyond_y);
        let to = (b.0 + across_x + beyond_x, b.1 + across_y + beyond_y);
        let place = |t: f64| (from.0 + t * (to.0 - from.0), from.1 + t * (to.1 - from.1));
        let places =
            crate::terrain::profile_places(terrain, from, to, span, TRANSIT_SAMPLE_M, |t| {
                let (x, y) = place(t);
                terrain.height_m(x, y).ok().map(|ground| vec![ground])
            });
        for t in places {
            let (x, y) = place(t);
            if let Ok(ground) = terrain.height_m(x, y) {
                highest = highest.max(ground);
            }
        }
    }
    Ok(highest)
}

/// A transit between two places at a level altitude: the corners it turns at to keep out of
/// the obstacles (the geofence's exclusion zones) and the altitude above sea level that
/// clears the highest ground under and beside every leg ([`TRANSIT_CORRIDOR_M`]) by
/// `clearance_m`.
struct Transit {
    corners: Vec<RoutePoint>,
    altitude_m: f64,
}

/// How far transits keep from obstacles, metres.
pub const OBSTACLE_CLEARANCE_M: f64 = 2.0;

fn transit(
    from: &RoutePoint,
    to: &RoutePoint,
    scenario: &Scenario,
    obstacles: &[geo::Polygon<f64>],
    clearance_m: f64,
) -> Result<Transit, Fault> {
    let corners = crate::geometry::detour::detour(
        geo::Coord {
            x: from.x,
            y: from.y,
        },
        geo::Coord { x: to.x, y: to.y },
        obstacles,
        OBSTACLE_CLEARANCE_M,
    )
    .ok_or(Fault::NoTransit {
        from: (from.x, from.y),
        to: (to.x, to.y),
    })?;
    let corners: Vec<RoutePoint> = corners
        .into_iter()
        .map(|corner| {
            Ok(RoutePoint {
                x: corner.x,
                y: corner.y,
                ground_m: scenario.terrain.height_m(corner.x, corner.y)?,
            })
        })
        .collect::<Result<_, Fault>>()?;
    let mut path = vec![(from.x, from.y)];
    path.extend(corners.iter().map(|corner| (corner.x, corner.y)));
    path.push((to.x, to.y));
    let mut highest = f64::NEG_INFINITY;
    for pair in path.windows(2) {
        highest = highest.max(highest_ground_near(
            scenario.terrain.as_ref(),
            pair[0],
            pair[1],
            TRANSIT_CORRIDOR_M,
        )?);
    }
    Ok(Transit {
        corners,
        altitude_m: highest + clearance_m,
    })
}

/// The missions of a plan, one per sortie (one in all when the route is not split).
///
/// Every transit (out from the supply point, transfers that leave a field, back home) flies
/// level at the cruise height (spray height + h, h ≥ 5 m) above the highest ground under it,
/// and round the obstacles, which the geofence excludes at every altitude.
pub fn build_missions(
    scenario: &Scenario,
    route: &Route,
    sorties: Option<&PlannedSorties>,
    settings: &MissionSettings,
) -> Result<Vec<SortieMission>, Fault> {
    let vehicle = &scenario.vehicle;
    let frame = GeoFrame::new(scenario.farm.coordinate_system, settings.local_origin);
    let speeds = crate::sortie::route::Speeds::of(vehicle);
    // Each sortie's first and last route point: a sortie may resume at the point after the
    // last one's return, skipping the turn or transfer between them.
    let (work_route, supply, spans) = match sorties {
        Some(split) => {
            let spans: Vec<(usize, usize)> = split
                .plan
                .sorties
                .iter()
                .map(|sortie| (sortie.first, sortie.last))
                .collect();
            (split.work_route.clone(), split.supply, spans)
        }
        None => {
            let launch = route.launch;
            let route = crate::sortie::route::WorkRoute::from_route(route, speeds);
            let supply = launch
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
            (route, supply, vec![(0, last)])
        }
    };
    if work_route.len() < 2 {
        return Ok(vec![]);
    }
    let spray_height = vehicle.spray_height_m;
    let cruise = vehicle.cruise_height_m();
    // An item at `point`, `above` metres over its ground.
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
    // An item at `point` at `altitude_m` above sea level.
    let level = |action: Action, point: &RoutePoint, altitude_m: f64| {
        item(action, point, altitude_m - point.ground_m)
    };
    let home = item(Action::Waypoint, &supply, 0.0);
    // The geofence's exclusions, which every transit keeps out of.
    let obstacles: Vec<geo::Polygon<f64>> = scenario
        .farm
        .obstacles
        .iter()
        .map(|obstacle| obstacle.polygon.clone())
        .collect();
    let points = work_route.points();
    let segments = work_route.segments();
    let mut missions = Vec::new();
    for (sortie, &(first, last)) in spans.iter().enumerate() {
        let out = transit(&supply, &points[first], scenario, &obstacles, cruise)?;
        let mut items = vec![
            level(Action::Takeoff, &supply, out.altitude_m),
            level(
                Action::Speed {
                    mps: vehicle.transit_speed_mps,
                },
                &supply,
                out.altitude_m,
            ),
        ];
        for corner in &out.corners {
            items.push(level(Action::Waypoint, corner, out.altitude_m));
        }
        items.extend([
            level(Action::Waypoint, &points[first], out.altitude_m),
            item(Action::Waypoint, &points[first], spray_height),
            item(
                Action::Speed {
                    mps: vehicle.spray_speed_mps,
                },
                &points[first],
                spray_height,
            ),
        ]);
        let mut index = first;
        while index < last {
            match segments[index] {
                Segment::Spray => {
                    let mut end = index;
                    while end < last && segments[end] == Segment::Spray {
                        end += 1;
                    }
                    items.push(item(
                        Action::work(true, vehicle.trigger_distance_m()),
                        &points[index],
                        spray_height,
                    ));
                    let run = follow_terrain(
                        &points[index..=end],
                        scenario.terrain.as_ref(),
                        settings,
                        vehicle.spray_height_m,
                    )?;
                    for point in &run[1..] {
                        items.push(item(Action::Waypoint, point, spray_height));
                    }
                    // Off at the swath's end: nothing sprays on turns, transfers or returns.
                    items.push(item(
                        Action::work(false, vehicle.trigger_distance_m()),
                        &points[end],
                        spray_height,
                    ));
                    index = end;
                }
                Segment::Turn => {
                    // Turns stay low inside the field, so they follow the terrain as swaths do.
                    let run = follow_terrain(
                        &points[index..=index + 1],
                        scenario.terrain.as_ref(),
                        settings,
                        vehicle.spray_height_m,
                    )?;
                    for point in &run[1..] {
                        items.push(item(Action::Waypoint, point, spray_height));
                    }
                    index += 1;
                }
                Segment::Transfer => {
                    let (from, to) = (&points[index], &points[index + 1]);
                    let hop = transit(from, to, scenario, &obstacles, cruise)?;
                    items.push(item(
                        Action::Speed {
                            mps: vehicle.transit_speed_mps,
                        },
                        from,
                        spray_height,
                    ));
                    items.push(level(Action::Waypoint, from, hop.altitude_m));
                    for corner in &hop.corners {
                        items.push(level(Action::Waypoint, corner, hop.altitude_m));
                    }
                    items.push(level(Action::Waypoint, to, hop.altitude_m));
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
        let back = transit(&points[last], &supply, scenario, &obstacles, cruise)?;
        items.push(item(
            Action::Speed {
                mps: vehicle.transit_speed_mps,
            },
            &points[last],
            spray_height,
        ));
        items.push(level(Action::Waypoint, &points[last], back.altitude_m));
        for corner in &back.corners {
            items.push(level(Action::Waypoint, corner, back.altitude_m));
        }
        items.push(level(Action::Waypoint, &supply, back.altitude_m));
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
    use super::terrain_following::simplify;
    use super::*;
    use crate::model::CoordinateSystem;

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
        let kept = follow_terrain(&points, &Waves, &settings, 2.5).unwrap();
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

    /// A transit clears the ground beside it: a mast one 1 m cell wide, its centre 1.5 m
    /// beside the leg, is not under the leg but within the corridor (trial 8).
    #[test]
    fn the_corridor_sees_a_mast_beside_the_leg() {
        let (columns, rows) = (20, 10);
        let grid = crate::terrain::Grid {
            columns,
            rows,
            first_center_x: 0.5,
            first_center_y: 9.5,
            cell_x: 1.0,
            cell_y: 1.0,
            heights: (0..rows * columns)
                .map(|index| {
                    if index == 3 * columns + 10 {
                        140.0
                    } else {
                        100.0
                    }
                })
                .collect(),
            epsg: None,
            source: "mast".into(),
        };
        // The mast's centre is (10.5, 6.5); the leg runs along y = 5.
        let (a, b) = ((2.0, 5.0), (18.0, 5.0));
        assert_eq!(highest_ground(&grid, a, b).unwrap(), 100.0);
        let near = highest_ground_near(&grid, a, b, TRANSIT_CORRIDOR_M).unwrap();
        assert!(near >= 139.0, "{near}");
        // Beyond the corridor it is not in the way.
        let far = highest_ground_near(&grid, (2.0, 2.0), (18.0, 2.0), TRANSIT_CORRIDOR_M);
        assert_eq!(far.unwrap(), 100.0);
    }
}
