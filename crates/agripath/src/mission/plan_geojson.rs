//! `plan.geojson`: the plan as a FeatureCollection (contract in `docs/contract.md` and `docs/cli.md`).
//!
//! Features carry `properties.kind`: `field`, `unreachable` (ground of a field narrower than
//! a swath, with `field` and `area_m2`), `missed` (reachable ground the flight left
//! unsprayed, as the preflight measured it; the same properties), `obstacle`, `access`, `edge`, `swath`,
//! `transfer`, `return` (a return point, `role: point`, and its leg to the supply point and
//! back, `role: leg`), `supply`, `supply_option` (with `--supply auto:N`, the other places
//! listed, `rank` from 2 and `cost_s`). Passes and legs carry `seq` (their place in the flight, from 0)
//! and `sortie` (from 0); a pass's coordinates
//! run in the direction flown; positions are `[x, y, z]` in the input's coordinate system
//! (lon/lat or local metres) with z the altitude above sea level (terrain + spray height).

use serde_json::{json, Map, Value};

use crate::coverage::drape::GroundPoint;
use crate::coverage::CoveragePlan;
use crate::model::{CoordinateSystem, Farm};
use crate::sequence::{Pass, Route};
use crate::sortie::PlannedSorties;

/// Decimal places kept: 1e-9° (0.1 mm) for lon/lat, 0.1 mm for metres, 1 mm in height.
fn position(system: CoordinateSystem, x: f64, y: f64, z: Option<f64>) -> Value {
    let (a, b) = system.to_input(x, y);
    let decimals = match system {
        CoordinateSystem::Local => 4,
        CoordinateSystem::Utm(_) => 9,
    };
    let fixed = |value: f64, places: usize| -> Value {
        let text = format!("{value:.places$}");
        serde_json::from_str(&text).unwrap_or(Value::Null)
    };
    match z {
        Some(z) => Value::Array(vec![fixed(a, decimals), fixed(b, decimals), fixed(z, 3)]),
        None => Value::Array(vec![fixed(a, decimals), fixed(b, decimals)]),
    }
}

/// A polygon's rings as RFC 7946 §3.1.6 orders them: the exterior counterclockwise, holes
/// clockwise (strict readers such as d3-geo otherwise fill the outside; trial 7). Turned in
/// plan metres, whose orientation is the lon/lat one (UTM does not mirror).
fn polygon_coordinates(system: CoordinateSystem, polygon: &geo::Polygon<f64>) -> Value {
    let ring_positions = |ring: &geo::LineString<f64>, counterclockwise: bool| {
        let ring = &without_spikes(ring);
        let doubled_area: f64 = ring
            .0
            .windows(2)
            .map(|pair| pair[0].x * pair[1].y - pair[1].x * pair[0].y)
            .sum();
        let mut points: Vec<Value> = ring
            .0
            .iter()
            .map(|point| position(system, point.x, point.y, None))
            .collect();
        if (doubled_area > 0.0) != counterclockwise {
            points.reverse();
        }
        Value::Array(points)
    };
    Value::Array(
        std::iter::once(ring_positions(polygon.exterior(), true))
            .chain(
                polygon
                    .interiors()
                    .iter()
                    .map(|ring| ring_positions(ring, false)),
            )
            .collect(),
    )
}

/// `ring` without its spikes (a vertex the ring goes out to and straight back from, as the
/// polygon operations leave on missed patches: a zero-width antenna that makes the ring cross
/// itself, invalid to RFC 7946 readers) and repeated points (within 1 mm: the file writes
/// positions to 1e-9°, 0.1 mm), closed.
fn without_spikes(ring: &geo::LineString<f64>) -> geo::LineString<f64> {
    const SAME_M: f64 = 1e-3;
    let same = |a: geo::Coord<f64>, b: geo::Coord<f64>| (a.x - b.x).hypot(a.y - b.y) < SAME_M;
    let mut points: Vec<geo::Coord<f64>> = ring.0.clone();
    if points.len() > 1 && same(points[0], points[points.len() - 1]) {
        points.pop();
    }
    loop {
        let count = points.len();
        if count < 3 {
            return ring.clone();
        }
        let removed = (0..count).find_map(|index| {
            let next = (index + 1) % count;
            if same(points[index], points[next]) {
                return Some(vec![next]);
            }
            let after = (index + 2) % count;
            same(points[index], points[after]).then(|| vec![next, after])
        });
        match removed {
            Some(mut indices) => {
                indices.sort_unstable_by(|a, b| b.cmp(a));
                for index in indices {
                    points.remove(index);
                }
            }
            None => break,
        }
    }
    points.push(points[0]);
    geo::LineString(points)
}

/// Mean width (2 · area / perimeter) under which a missed or unreachable piece is left out
/// of the file, metres: slivers millimetres wide between strips, arithmetic of the polygon
/// operations, which no sprayer could fill and whose rings cross once written to 1e-9° (trial
/// 7 found them as invalid, clockwise polygons). Their area stays in `report.json`'s figures.
pub const SLIVER_WIDTH_M: f64 = 0.01;

fn is_sliver(piece: &geo::Polygon<f64>) -> bool {
    let ring_length = |ring: &geo::LineString<f64>| -> f64 {
        ring.0
            .windows(2)
            .map(|pair| (pair[1].x - pair[0].x).hypot(pair[1].y - pair[0].y))
            .sum()
    };
    let perimeter =
        ring_length(piece.exterior()) + piece.interiors().iter().map(ring_length).sum::<f64>();
    perimeter <= 0.0 || 2.0 * geo::Area::unsigned_area(piece) / perimeter < SLIVER_WIDTH_M
}

fn feature(properties: Map<String, Value>, geometry: Value) -> Value {
    json!({"type": "Feature", "properties": properties, "geometry": geometry})
}

fn line(system: CoordinateSystem, points: &[GroundPoint], lift_m: f64) -> Value {
    json!({
        "type": "LineString",
        "coordinates": points.iter().map(|p| position(system, p.x, p.y, Some(p.ground_m + lift_m))).collect::<Vec<_>>(),
    })
}

/// Builds the FeatureCollection.
pub fn plan_geojson(
    farm: &Farm,
    plan: &CoveragePlan,
    route: &Route,
    sorties: Option<&PlannedSorties>,
    spray_height_m: f64,
    safe_height_m: f64,
    ground: &crate::coverage::region::GroundPatches,
) -> Value {
    let system = farm.coordinate_system;
    let mut features = Vec::new();
    for (index, field) in farm.fields.iter().enumerate() {
        let mut properties = Map::new();
        properties.insert("kind".into(), json!("field"));
        properties.insert("name".into(), json!(field.name));
        properties.insert("field".into(), json!(index));
        if let Some(coverage) = plan.fields.get(index) {
            properties.insert(
                "heading_deg".into(),
                json!(crate::numbers::round(coverage.heading.heading_deg, 1e-9)),
            );
        }
        features.push(feature(
            properties,
            json!({"type": "Polygon", "coordinates": polygon_coordinates(system, &field.polygon)}),
        ));
    }
    // Ground narrower than a swath (sharp tips, necks between holes), which no pass reaches
    // without spraying outside too, and reachable ground the flight missed, as the preflight
    // found them (decision 0023, issue 22).
    let patches = ground
        .unreachable
        .iter()
        .enumerate()
        .map(|(index, ground)| ("unreachable", index, ground))
        .chain(
            ground
                .missed
                .iter()
                .enumerate()
                .map(|(index, ground)| ("missed", index, ground)),
        );
    for (kind, index, ground) in patches {
        for piece in ground.0.iter().filter(|piece| !is_sliver(piece)) {
            let mut properties = Map::new();
            properties.insert("kind".into(), json!(kind));
            properties.insert("field".into(), json!(index));
            properties.insert(
                "area_m2".into(),
                json!(crate::numbers::round(geo::Area::unsigned_area(piece), 1e-3)),
            );
            features.push(feature(
                properties,
                json!({"type": "Polygon", "coordinates": polygon_coordinates(system, piece)}),
            ));
        }
    }
    for obstacle in &farm.obstacles {
        let mut properties = Map::new();
        properties.insert("kind".into(), json!("obstacle"));
        properties.insert("name".into(), json!(obstacle.name));
        features.push(feature(properties, json!({"type": "Polygon", "coordinates": polygon_coordinates(system, &obstacle.polygon)})));
    }
    for access in &farm.access {
        let mut properties = Map::new();
        properties.insert("kind".into(), json!("access"));
        properties.insert("name".into(), json!(access.name));
        let geometry = match &access.shape {
            crate::model::AccessShape::Line(line) => {
                json!({"type": "LineString", "coordinates": line
                .0
                .iter()
                .map(|point| position(system, point.x, point.y, None))
                .collect::<Vec<_>>()})
            }
            crate::model::AccessShape::Area(polygon) => {
                json!({"type": "Polygon", "coordinates": polygon_coordinates(system, polygon)})
            }
        };
        features.push(feature(properties, geometry));
    }
    // The sortie flying a work-route point; everything is sortie 0 when the route is not split.
    let sortie_at = |index: usize| sorties.map_or(0, |split| split.sortie_at(index));
    let last_sortie = sorties.map_or(0, |split| split.plan.sorties.len().saturating_sub(1));
    if let Some(split) = sorties {
        let mut properties = Map::new();
        properties.insert("kind".into(), json!("supply"));
        features.push(feature(
            properties,
            json!({"type": "Point", "coordinates": position(system, split.supply.x, split.supply.y, Some(split.supply.ground_m))}),
        ));
    }
    let leg_feature =
        |transfer: &crate::sequence::Transfer, leg: &str, seq: usize, sortie: usize| {
            let mut properties = Map::new();
            properties.insert("kind".into(), json!("transfer"));
            properties.insert("leg".into(), json!(leg));
            properties.insert("seq".into(), json!(seq));
            properties.insert("sortie".into(), json!(sortie));
            properties.insert("climbs".into(), json!(transfer.climbs));
            properties.insert(
                "length_m".into(),
                json!(crate::numbers::round(transfer.cost_m, 1e-4)),
            );
            let lift = |point: GroundPoint, extra: f64| GroundPoint {
                ground_m: point.ground_m + extra,
                ..point
            };
            let points = if transfer.climbs {
                vec![
                    transfer.from,
                    lift(transfer.from, safe_height_m),
                    lift(transfer.to, safe_height_m),
                    transfer.to,
                ]
            } else {
                vec![transfer.from, transfer.to]
            };
            feature(properties, line(system, &points, spray_height_m))
        };
    let mut seq = 0;
    if let Some(launch) = &route.launch {
        features.push(leg_feature(launch, "launch", seq, 0));
        seq += 1;
    }
    for (index, visit) in route.visits.iter().enumerate() {
        let mut properties = Map::new();
        match visit.pass {
            Pass::Swath { field, swath } => {
                let swath = &plan.fields[field].swaths[swath];
                properties.insert("kind".into(), json!("swath"));
                properties.insert("field".into(), json!(plan.fields[field].name));
                properties.insert("line".into(), json!(swath.line));
                properties.insert(
                    "length_m".into(),
                    json!(crate::numbers::round(swath.length_m, 1e-4)),
                );
            }
            Pass::Edge { field, edge } => {
                let edge = &plan.fields[field].edges[edge];
                properties.insert("kind".into(), json!("edge"));
                properties.insert("field".into(), json!(plan.fields[field].name));
                properties.insert("pass".into(), json!(edge.pass));
                properties.insert(
                    "length_m".into(),
                    json!(crate::numbers::round(edge.length_m, 1e-4)),
                );
            }
        }
        let offset = sorties.map_or(0, |split| split.visit_offsets[index]);
        let last_point = offset + visit.points.len().saturating_sub(1);
        properties.insert("seq".into(), json!(seq));
        properties.insert("sortie".into(), json!(sortie_at(offset)));
        features.push(feature(
            properties,
            line(system, &visit.points, spray_height_m),
        ));
        seq += 1;
        if let Some(split) = sorties {
            for (&at, &resume) in split
                .plan
                .breaks
                .iter()
                .zip(&split.plan.resumes)
                .filter(|(&b, _)| b >= offset && b <= last_point)
            {
                let point = split.work_route.points()[at];
                let again = split.work_route.points()[resume];
                let sortie = split.sortie_at(at);
                let mut properties = Map::new();
                properties.insert("kind".into(), json!("return"));
                properties.insert("role".into(), json!("point"));
                properties.insert("sortie".into(), json!(sortie));
                features.push(feature(
                    properties,
                    json!({"type": "Point", "coordinates": position(system, point.x, point.y, Some(point.ground_m + spray_height_m))}),
                ));
                let mut properties = Map::new();
                properties.insert("kind".into(), json!("return"));
                properties.insert("role".into(), json!("leg"));
                properties.insert("seq".into(), json!(seq));
                properties.insert("sortie".into(), json!(sortie));
                // Out and back: to the supply point, and out again to where the next sortie
                // starts (the same point, or the next pass when the return skips a transfer).
                let round_trip = split.model.leg_m(&point) + split.model.leg_m(&again);
                properties.insert(
                    "length_m".into(),
                    json!(crate::numbers::round(round_trip, 1e-4)),
                );
                let at_height = |x: f64, y: f64, z: f64| position(system, x, y, Some(z));
                let cruise =
                    point.ground_m.max(split.supply.ground_m) + spray_height_m + safe_height_m;
                let mut coordinates = vec![
                    at_height(point.x, point.y, point.ground_m + spray_height_m),
                    at_height(point.x, point.y, cruise),
                    at_height(split.supply.x, split.supply.y, cruise),
                    at_height(split.supply.x, split.supply.y, split.supply.ground_m),
                ];
                if resume != at {
                    let cruise =
                        again.ground_m.max(split.supply.ground_m) + spray_height_m + safe_height_m;
                    coordinates.extend([
                        at_height(split.supply.x, split.supply.y, cruise),
                        at_height(again.x, again.y, cruise),
                        at_height(again.x, again.y, again.ground_m + spray_height_m),
                    ]);
                }
                features.push(feature(
                    properties,
                    json!({"type": "LineString", "coordinates": coordinates}),
                ));
                seq += 1;
            }
        }
        let skipped = sorties.is_some_and(|split| {
            split
                .plan
                .breaks
                .iter()
                .zip(&split.plan.resumes)
                .any(|(&at, &resume)| at == last_point && resume == last_point + 1)
        });
        if let Some(transfer) = route.transfers.get(index).filter(|_| !skipped) {
            features.push(leg_feature(transfer, "between", seq, sortie_at(last_point)));
            seq += 1;
        }
    }
    if let Some(home) = &route.home {
        features.push(leg_feature(home, "home", seq, last_sortie));
    }
    let mut collection = Map::new();
    collection.insert("type".into(), json!("FeatureCollection"));
    if system == CoordinateSystem::Local {
        collection.insert("crs".into(), json!("local"));
    }
    collection.insert("features".into(), Value::Array(features));
    Value::Object(collection)
}

/// Adds the other places `--supply auto:N` listed to `geojson` (a [`plan_geojson`]): a Point
/// of kind `supply_option` each, with its `rank` (from 2: the supply point is the first) and
/// its `cost_s` (`null` where the plan cannot be flown from it), as `[x, y]`: a place to
/// stand, whose height the report does not carry.
pub fn add_supply_options(
    geojson: &mut Value,
    system: CoordinateSystem,
    options: &[(geo::Coord<f64>, Option<f64>)],
) {
    let Some(features) = geojson.get_mut("features").and_then(Value::as_array_mut) else {
        return;
    };
    for (index, (point, cost_s)) in options.iter().enumerate() {
        let mut properties = Map::new();
        properties.insert("kind".into(), json!("supply_option"));
        properties.insert("rank".into(), json!(index + 2));
        properties.insert("cost_s".into(), json!(cost_s));
        features.push(feature(
            properties,
            json!({"type": "Point", "coordinates": position(system, point.x, point.y, None)}),
        ));
    }
}
