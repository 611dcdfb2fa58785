//! Random irregular farms for the routing benchmarks (issue 19): inputs the planners were not
//! designed around. A farm has 2-5 fields; each field is a star-shaped ring of 4-12 vertices
//! (simple, and concave: one vertex is pulled in towards the centre), with 0-2 convex holes
//! well inside and apart; fields lie on a row with gaps between them. Sizes are drawn so that
//! the farm has about the asked number of swaths of the asked width.

use geo::{Contains, Coord, Intersects, LineString, Polygon};
use swarm::random::{below, run_stream, uniform};
use swarm::RunStream;

use crate::model::{Farm, Field};

fn between(stream: &mut RunStream, low: f64, high: f64) -> f64 {
    low + (high - low) * uniform(stream)
}

/// A star-shaped closed ring about `centre`: `count` vertices at sorted random angles, radii in
/// `low..high`.
fn star(
    stream: &mut RunStream,
    centre: Coord<f64>,
    low: f64,
    high: f64,
    count: usize,
) -> Vec<Coord<f64>> {
    // Angles jittered inside equal sectors, so that no two vertices come close in angle.
    (0..count)
        .map(|index| {
            let sector = std::f64::consts::TAU / count as f64;
            let angle = sector * (index as f64 + between(stream, 0.15, 0.85));
            let radius = between(stream, low, high);
            Coord {
                x: centre.x + radius * angle.cos(),
                y: centre.y + radius * angle.sin(),
            }
        })
        .collect()
}

fn closed(mut ring: Vec<Coord<f64>>) -> LineString<f64> {
    ring.push(ring[0]);
    LineString::new(ring)
}

/// One irregular field of mean radius `radius` about `centre`, with 0-2 holes.
fn irregular_field(stream: &mut RunStream, name: String, centre: Coord<f64>, radius: f64) -> Field {
    let count = 4 + below(stream, 9);
    let mut ring = star(stream, centre, 0.8 * radius, 1.2 * radius, count);
    // Concave: the vertex whose neighbours are nearest in angle (under 180° apart, as the
    // gaps of all such pairs sum to 720°) moves to halfway between their chord's midpoint and
    // the centre, which is on the far side of the chord: the vertex becomes reflex.
    let angle = |point: Coord<f64>| (point.y - centre.y).atan2(point.x - centre.x);
    let gap = |index: usize| {
        let before = ring[(index + count - 1) % count];
        let after = ring[(index + 1) % count];
        (angle(after) - angle(before)).rem_euclid(std::f64::consts::TAU)
    };
    let dent = (0..count)
        .min_by(|&a, &b| gap(a).total_cmp(&gap(b)))
        .expect("four or more vertices");
    let (before, after) = (ring[(dent + count - 1) % count], ring[(dent + 1) % count]);
    let middle = Coord {
        x: 0.5 * (before.x + after.x),
        y: 0.5 * (before.y + after.y),
    };
    let pulled = between(stream, 0.3, 0.7);
    ring[dent] = Coord {
        x: middle.x + pulled * (centre.x - middle.x),
        y: middle.y + pulled * (centre.y - middle.y),
    };
    let boundary = Polygon::new(closed(ring), vec![]);
    let wanted = below(stream, 3);
    let mut holes: Vec<Polygon<f64>> = Vec::new();
    for _attempt in 0..40 {
        if holes.len() == wanted {
            break;
        }
        let size = between(stream, 0.06, 0.14) * radius;
        let offset = between(stream, 0.0, 0.3) * radius;
        let angle = between(stream, 0.0, std::f64::consts::TAU);
        let hole_centre = Coord {
            x: centre.x + offset * angle.cos(),
            y: centre.y + offset * angle.sin(),
        };
        let hole = Polygon::new(closed(star(stream, hole_centre, size, size, 6)), vec![]);
        // Well inside the boundary (a swath's worth of margin) and apart from the others.
        let grown = Polygon::new(
            closed(star(stream, hole_centre, 1.6 * size, 1.6 * size, 12)),
            vec![],
        );
        if boundary.contains(&grown) && holes.iter().all(|other| !other.intersects(&grown)) {
            holes.push(hole);
        }
    }
    let interiors = holes.into_iter().map(|hole| hole.exterior().clone());
    Field::new(
        name,
        Polygon::new(boundary.exterior().clone(), interiors.collect()),
    )
}

/// A random farm of 2-5 irregular fields (local metres, flat), seeded by `seed`, sized for
/// about `swaths` swaths of `swath_width_m`.
pub fn irregular_farm(seed: u64, swaths: usize, swath_width_m: f64) -> Farm {
    let mut stream = run_stream(seed, 0);
    let count = 2 + below(&mut stream, 4);
    // Field i's share of the swaths, each field about 2 · radius / w swaths across.
    let shares: Vec<f64> = (0..count).map(|_| between(&mut stream, 0.5, 1.5)).collect();
    let total: f64 = shares.iter().sum();
    let mut fields = Vec::with_capacity(count);
    let mut x = 0.0;
    for (index, share) in shares.iter().enumerate() {
        let radius = 0.5 * swaths as f64 * swath_width_m * share / total;
        let gap = between(&mut stream, 30.0, 200.0);
        x += 1.2 * radius;
        let centre = Coord {
            x,
            y: between(&mut stream, -0.5, 0.5) * radius,
        };
        x += 1.2 * radius + gap;
        fields.push(irregular_field(
            &mut stream,
            format!("F{}", index + 1),
            centre,
            radius,
        ));
    }
    Farm::local(format!("random irregular farm {seed}"), fields)
}

/// Swath counts asked of [`irregular_farm`] in turn by the routing benchmarks (`bench_joint`,
/// `joint_budget_curve`): farm `seed` asks for `ROUTING_SWATH_TARGETS[(seed - 1) % 5]`.
pub const ROUTING_SWATH_TARGETS: [usize; 5] = [120, 150, 180, 210, 240];

/// How far south of a random farm's bounding box its supply point stands in the routing
/// benchmarks, metres.
pub const SUPPLY_SOUTH_M: f64 = 30.0;

/// A random farm's supply point in the routing benchmarks: [`SUPPLY_SOUTH_M`] south of the
/// middle of its bounding box's south side (outside every field, where a truck could stand
/// by the farm's edge).
pub fn supply_south_of(farm: &Farm) -> [f64; 2] {
    let bounds = farm.bounds();
    [
        0.5 * (bounds.min().x + bounds.max().x),
        bounds.min().y - SUPPLY_SOUTH_M,
    ]
}

/// About `swaths` swaths of width `swath_width_m` as one compact farm, for the large-farm time
/// goal: [`irregular_farm`]s of about `per_tile` swaths each (seeds `seed`, `seed + 1`, …) laid
/// out in rows about as wide as the whole is tall, [`TILE_GAP_M`] apart, so that every pass
/// is short and the farm's far corners are a few kilometres from its middle (one
/// [`irregular_farm`] of 5,000 swaths is 25 km long and has passes no battery flies). Also
/// returns a supply point in the middle of the gap between the two middle rows, where no
/// field lies.
pub fn tiled_irregular_farm(
    seed: u64,
    swaths: usize,
    per_tile: usize,
    swath_width_m: f64,
) -> (Farm, Coord<f64>) {
    use geo::{BoundingRect, Translate};
    let tiles: Vec<Farm> = (0..swaths.div_ceil(per_tile.max(1)).max(1) as u64)
        .map(|index| irregular_farm(seed + index, per_tile, swath_width_m))
        .collect();
    let bounds: Vec<geo::Rect<f64>> = tiles
        .iter()
        .map(|tile| {
            let rects = tile
                .fields
                .iter()
                .filter_map(|field| field.polygon.bounding_rect());
            rects
                .reduce(|a, b| {
                    geo::Rect::new(
                        Coord {
                            x: a.min().x.min(b.min().x),
                            y: a.min().y.min(b.min().y),
                        },
                        Coord {
                            x: a.max().x.max(b.max().x),
                            y: a.max().y.max(b.max().y),
                        },
                    )
                })
                .expect("a random farm has fields")
        })
        .collect();
    let area: f64 = bounds
        .iter()
        .map(|rect| (rect.width() + TILE_GAP_M) * (rect.height() + TILE_GAP_M))
        .sum();
    let row_width = area.sqrt();
    let mut fields = Vec::new();
    // Rows run downwards from y = 0; `row_bottoms` is where each row's tallest tile ends.
    let (mut x, mut top, mut bottom) = (0.0, 0.0_f64, 0.0_f64);
    let mut row_bottoms = Vec::new();
    for (index, (tile, rect)) in tiles.iter().zip(&bounds).enumerate() {
        if x > 0.0 && x + rect.width() > row_width {
            row_bottoms.push(bottom);
            top = bottom - TILE_GAP_M;
            x = 0.0;
        }
        let (dx, dy) = (x - rect.min().x, top - rect.max().y);
        for field in &tile.fields {
            fields.push(Field {
                name: format!("T{}.{}", index + 1, field.name),
                polygon: field.polygon.translate(dx, dy),
                sprayed_with_others: Vec::new(),
            });
        }
        bottom = if x == 0.0 {
            top - rect.height()
        } else {
            bottom.min(top - rect.height())
        };
        x += rect.width() + TILE_GAP_M;
    }
    row_bottoms.push(bottom);
    // Between the two middle rows (below the farm when it is one row).
    let middle = (row_bottoms.len() / 2).saturating_sub(usize::from(row_bottoms.len() > 1));
    let supply = Coord {
        x: 0.5 * row_width,
        y: row_bottoms[middle] - 0.5 * TILE_GAP_M,
    };
    let first = tiles.into_iter().next().expect("at least one tile");
    let farm = Farm {
        source: format!("tiled random irregular farm {seed}, {swaths} swaths").into(),
        fields,
        ..first
    };
    (farm, supply)
}

/// Metres between the tiles of [`tiled_irregular_farm`]: the gap a supply vehicle stands in.
pub const TILE_GAP_M: f64 = 60.0;

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{Area, Validation};

    #[test]
    fn random_farms_are_valid_irregular_and_repeatable() {
        let mut holes = 0;
        for seed in 0..30 {
            let farm = irregular_farm(seed, 200, 5.0);
            assert!((2..=5).contains(&farm.fields.len()));
            for field in &farm.fields {
                assert!(field.polygon.is_valid(), "seed {seed}: {}", field.name);
                let vertices = field.polygon.exterior().0.len() - 1;
                assert!((4..=12).contains(&vertices));
                assert!(field.polygon.interiors().len() <= 2);
                holes += field.polygon.interiors().len();
                // Not convex: the hull is larger than the field.
                use geo::ConvexHull;
                let outline = Polygon::new(field.polygon.exterior().clone(), vec![]);
                assert!(
                    outline.convex_hull().unsigned_area() > 1.005 * outline.unsigned_area(),
                    "seed {seed} {} {vertices} {:?}",
                    field.name,
                    outline.exterior().0
                );
            }
            // Fields do not touch.
            for (i, a) in farm.fields.iter().enumerate() {
                for b in &farm.fields[i + 1..] {
                    assert!(!a.polygon.intersects(&b.polygon));
                }
            }
            assert_eq!(farm.fields, irregular_farm(seed, 200, 5.0).fields);
        }
        assert!(holes > 10, "holes are drawn: {holes}");
    }

    #[test]
    fn a_tiled_farm_is_compact_its_fields_apart_and_its_supply_point_off_them() {
        let (farm, supply) = tiled_irregular_farm(1, 2000, 100, 5.0);
        assert!(farm.fields.len() >= 40, "{} fields", farm.fields.len());
        let point = geo::Point::from(supply);
        for (i, a) in farm.fields.iter().enumerate() {
            assert!(a.polygon.is_valid());
            assert!(
                !a.polygon.contains(&point),
                "{} holds the supply point",
                a.name
            );
            for b in &farm.fields[i + 1..] {
                assert!(
                    !a.polygon.intersects(&b.polygon),
                    "{} meets {}",
                    a.name,
                    b.name
                );
            }
        }
        use geo::BoundingRect;
        let bounds = geo::MultiPolygon::new(
            farm.fields
                .iter()
                .map(|field| field.polygon.clone())
                .collect(),
        )
        .bounding_rect()
        .unwrap();
        // About square: neither side more than three times the other.
        let (width, height) = (bounds.width(), bounds.height());
        assert!(
            width < 3.0 * height && height < 3.0 * width,
            "{width} × {height}"
        );
        assert!(bounds.contains(&point) || supply.y < bounds.min().y);
    }
}
