//! What a flight sprays, measured row by row: every spray leg lays a strip one swath wide
//! (a rectangle about the leg, square ends where the sprayer goes on and off), and where a
//! spray run turns at a waypoint the footprint of a multirotor, symmetric about it, sweeps
//! the sector of the swath's disc between the two legs' rectangles on the outer side of the
//! turn (with the rectangles, a round join: the flown line buffered by w/2; the opposite
//! sector lies in both rectangles, sprayed twice, as flown). Each
//! horizontal row of the plane is cut exactly into the intervals the strips, the fields and
//! the obstacles cover. The sector belongs to the leg it ends and lies in neither rectangle,
//! so a turn's gap is sprayed once (the whole disc, as until decision 0019, counted half of
//! it twice against the next leg); ground under two different legs is sprayed twice.
//! Areas are Σ length × row spacing (midpoint rule): exact for straight edges up to the rows'
//! discretisation, independent of how the plan was made, and fast (an active-edge sweep).

use geo::Coord;

use super::missed::MissedPieces;

/// The sector a turn sweeps: {p : |p − centre| < radius, (p − centre)·into > 0,
/// (p − centre)·out_of < 0}.
#[derive(Debug, Clone, Copy)]
struct Joint {
    centre: Coord<f64>,
    radius: f64,
    into: Coord<f64>,
    out_of: Coord<f64>,
}

impl Joint {
    /// Where row `y` crosses the sector (convex: one interval at most).
    fn interval(&self, y: f64) -> Option<(f64, f64)> {
        let dy = y - self.centre.y;
        if dy.abs() >= self.radius {
            return None;
        }
        let half = (self.radius * self.radius - dy * dy).sqrt();
        let (mut low, mut high) = (self.centre.x - half, self.centre.x + half);
        // (x − cx)·d.x + dy·d.y has the sign asked for.
        for (direction, sign) in [(self.into, 1.0), (self.out_of, -1.0)] {
            let (a, b) = (sign * direction.x, sign * dy * direction.y);
            if a.abs() < 1e-12 {
                if b <= 0.0 {
                    return None;
                }
            } else if a > 0.0 {
                low = low.max(self.centre.x - b / a);
            } else {
                high = high.min(self.centre.x - b / a);
            }
        }
        (high > low).then_some((low, high))
    }
}

/// A sprayed strip: the convex quadrilateral about one spray leg, and the disc at its end
/// when the run turns there.
#[derive(Debug, Clone, Copy)]
pub struct Strip {
    corners: [Coord<f64>; 4],
    low_y: f64,
    high_y: f64,
    /// Where the run turns at the leg's end: the disc's centre and radius, and the two legs'
    /// directions (the sector swept lies ahead of this leg's end and behind the next leg's
    /// start).
    joint: Option<Joint>,
}

impl Strip {
    /// The strip a leg from `a` to `b` sprays with half width `half_m`; `None` for a leg of no
    /// length.
    pub fn new(a: Coord<f64>, b: Coord<f64>, half_m: f64) -> Option<Self> {
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        let length = dx.hypot(dy);
        if length < 1e-9 {
            return None;
        }
        let (nx, ny) = (-dy / length * half_m, dx / length * half_m);
        let corners = [
            Coord {
                x: a.x + nx,
                y: a.y + ny,
            },
            Coord {
                x: b.x + nx,
                y: b.y + ny,
            },
            Coord {
                x: b.x - nx,
                y: b.y - ny,
            },
            Coord {
                x: a.x - nx,
                y: a.y - ny,
            },
        ];
        let low_y = corners.iter().map(|c| c.y).fold(f64::INFINITY, f64::min);
        let high_y = corners
            .iter()
            .map(|c| c.y)
            .fold(f64::NEG_INFINITY, f64::max);
        Some(Self {
            corners,
            low_y,
            high_y,
            joint: None,
        })
    }

    /// The strip with the sector a multirotor sweeps where the spray run turns at the leg's
    /// end, from direction `into` to `out_of` (need not be unit vectors).
    pub fn turning_at_end(
        mut self,
        end: Coord<f64>,
        half_m: f64,
        into: Coord<f64>,
        out_of: Coord<f64>,
    ) -> Self {
        self.joint = Some(Joint {
            centre: end,
            radius: half_m,
            into,
            out_of,
        });
        self.low_y = self.low_y.min(end.y - half_m);
        self.high_y = self.high_y.max(end.y + half_m);
        self
    }

    /// Where row `y` crosses the strip and its disc (one or two intervals, merged when they
    /// touch), pushed onto `out`.
    fn intervals(&self, y: f64, out: &mut Vec<(f64, f64)>) {
        let mut low = f64::INFINITY;
        let mut high = f64::NEG_INFINITY;
        for k in 0..4 {
            let (a, b) = (self.corners[k], self.corners[(k + 1) % 4]);
            if (a.y <= y && b.y > y) || (b.y <= y && a.y > y) {
                let x = a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x);
                low = low.min(x);
                high = high.max(x);
            }
        }
        let strip = (high > low).then_some((low, high));
        let disc = self.joint.and_then(|joint| joint.interval(y));
        match (strip, disc) {
            (Some(a), Some(b)) if a.0 <= b.1 && b.0 <= a.1 => {
                out.push((a.0.min(b.0), a.1.max(b.1)))
            }
            (a, b) => out.extend(a.into_iter().chain(b)),
        }
    }
}

/// A region under the even-odd rule: closed rings (a polygon's shell and holes, or several
/// polygons' rings that do not overlap).
#[derive(Debug, Clone)]
pub struct Rings {
    /// Edges sorted by their lower y: (lower y, upper y, a, b).
    edges: Vec<(f64, f64, Coord<f64>, Coord<f64>)>,
}

impl Rings {
    /// The region of `rings`, each a list of corners; a ring given open is closed.
    pub fn new<'a>(rings: impl IntoIterator<Item = &'a [Coord<f64>]>) -> Self {
        let mut edges = Vec::new();
        for ring in rings {
            for pair in ring.windows(2) {
                let (a, b) = (pair[0], pair[1]);
                if a.y != b.y {
                    edges.push((a.y.min(b.y), a.y.max(b.y), a, b));
                }
            }
            // Close a ring given open.
            if let (Some(&first), Some(&last)) = (ring.first(), ring.last()) {
                if first != last && first.y != last.y {
                    edges.push((first.y.min(last.y), first.y.max(last.y), last, first));
                }
            }
        }
        edges.sort_by(|a, b| a.0.total_cmp(&b.0));
        Self { edges }
    }

    /// The rings of a polygon with holes.
    pub fn of_polygon(polygon: &geo::Polygon<f64>) -> Self {
        Self::new(crate::geometry::rings(polygon))
    }

    /// The rings of every polygon of `region`, holes included.
    pub fn of_multi_polygon(region: &geo::MultiPolygon<f64>) -> Self {
        Self::new(region.0.iter().flat_map(crate::geometry::rings))
    }
}

/// Walks a [`Rings`] upwards row by row, keeping only the edges the row can cross.
struct Cursor<'a> {
    rings: &'a Rings,
    next: usize,
    active: Vec<usize>,
    crossings: Vec<f64>,
}

impl<'a> Cursor<'a> {
    fn new(rings: &'a Rings) -> Self {
        Self {
            rings,
            next: 0,
            active: Vec::new(),
            crossings: Vec::new(),
        }
    }

    /// The intervals inside the region on row `y` (rows must come in increasing y).
    fn intervals(&mut self, y: f64, out: &mut Vec<(f64, f64)>) {
        let edges = &self.rings.edges;
        while self.next < edges.len() && edges[self.next].0 <= y {
            self.active.push(self.next);
            self.next += 1;
        }
        self.active.retain(|&k| edges[k].1 > y);
        self.crossings.clear();
        for &k in &self.active {
            let (low, high, a, b) = edges[k];
            if low <= y && high > y {
                self.crossings
                    .push(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
            }
        }
        self.crossings.sort_by(f64::total_cmp);
        out.clear();
        for pair in self.crossings.chunks_exact(2) {
            if pair[1] > pair[0] {
                out.push((pair[0], pair[1]));
            }
        }
    }
}

/// Union of sorted intervals → sorted disjoint intervals.
fn union(intervals: &mut [(f64, f64)], out: &mut Vec<(f64, f64)>) {
    intervals.sort_by(|a, b| a.0.total_cmp(&b.0));
    out.clear();
    for &(low, high) in intervals.iter() {
        match out.last_mut() {
            Some(last) if low <= last.1 => last.1 = last.1.max(high),
            _ => out.push((low, high)),
        }
    }
}

/// Where at least two intervals overlap, as sorted disjoint intervals.
fn doubled(intervals: &[(f64, f64)], out: &mut Vec<(f64, f64)>) {
    let mut events: Vec<(f64, i32)> = Vec::with_capacity(2 * intervals.len());
    for &(low, high) in intervals {
        events.push((low, 1));
        events.push((high, -1));
    }
    // Ends before starts at the same x: strips that only touch do not overlap.
    events.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    out.clear();
    let mut depth = 0;
    let mut start = 0.0;
    for (x, change) in events {
        let before = depth;
        depth += change;
        if before < 2 && depth >= 2 {
            start = x;
        } else if before >= 2 && depth < 2 && x > start {
            out.push((start, x));
        }
    }
}

/// Length of the intersection of two sorted disjoint interval lists.
fn overlap_length(a: &[(f64, f64)], b: &[(f64, f64)]) -> f64 {
    let (mut i, mut j, mut total) = (0, 0, 0.0);
    while i < a.len() && j < b.len() {
        let low = a[i].0.max(b[j].0);
        let high = a[i].1.min(b[j].1);
        if high > low {
            total += high - low;
        }
        if a[i].1 < b[j].1 {
            i += 1;
        } else {
            j += 1;
        }
    }
    total
}

/// `a` less `b`, both sorted disjoint.
fn subtract(a: &[(f64, f64)], b: &[(f64, f64)], out: &mut Vec<(f64, f64)>) {
    out.clear();
    let mut j = 0;
    for &(low, high) in a {
        let mut start = low;
        while j < b.len() && b[j].1 <= start {
            j += 1;
        }
        let mut k = j;
        while k < b.len() && b[k].0 < high {
            if b[k].0 > start {
                out.push((start, b[k].0));
            }
            start = start.max(b[k].1);
            k += 1;
        }
        if start < high {
            out.push((start, high));
        }
    }
}

fn length(intervals: &[(f64, f64)]) -> f64 {
    intervals.iter().map(|(low, high)| high - low).sum()
}

/// A field's ground as the measure sees it: its sprayable region and the part of that a
/// swath can reach ([`crate::coverage::region::reachable_region`]).
#[derive(Debug, Clone)]
pub struct FieldGround {
    /// The sprayable region.
    pub sprayable: Rings,
    /// The part of it a swath can reach.
    pub reachable: Rings,
    /// The rest, as polygons for the map.
    pub unreachable: geo::MultiPolygon<f64>,
}

impl FieldGround {
    /// The ground of each field of `farm`, its sprayable region within these margins.
    pub fn of_farm(
        farm: &crate::model::Farm,
        boundary_margin_m: f64,
        obstacle_margin_m: f64,
        width_m: f64,
    ) -> Vec<Self> {
        farm.fields
            .iter()
            .map(|field| {
                let sprayable = crate::coverage::region::sprayable_region(
                    field,
                    &farm.obstacles,
                    boundary_margin_m,
                    obstacle_margin_m,
                );
                Self::of(&sprayable, width_m)
            })
            .collect()
    }

    /// The ground of a field's `sprayable` region for a swath `width_m` wide.
    pub fn of(sprayable: &geo::MultiPolygon<f64>, width_m: f64) -> Self {
        let reachable = crate::coverage::region::reachable_region(sprayable, width_m);
        Self {
            sprayable: Rings::of_multi_polygon(sprayable),
            reachable: Rings::of_multi_polygon(&reachable),
            unreachable: crate::coverage::region::unreachable_part(sprayable, &reachable),
        }
    }
}

/// The figures of one region.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RegionSprayed {
    /// The region's area, m² (measured on the same rows as the rest).
    pub area_m2: f64,
    /// Under at least one strip.
    pub covered_m2: f64,
    /// Under two strips or more.
    pub doubled_m2: f64,
    /// The reachable part's area, m².
    pub reachable_area_m2: f64,
    /// The reachable part under at least one strip, m².
    pub reachable_covered_m2: f64,
}

impl RegionSprayed {
    /// Reachable ground under no strip, m².
    pub fn missed_m2(&self) -> f64 {
        (self.reachable_area_m2 - self.reachable_covered_m2).max(0.0)
    }

    /// Ground no swath can reach that is left unsprayed, m² (unreachable ground a strip
    /// does cover counts as covered).
    pub fn unreachable_m2(&self) -> f64 {
        (self.area_m2 - self.covered_m2 - self.missed_m2()).max(0.0)
    }

    /// The share covered of the ground that is covered or could be: covered / (covered +
    /// missed), 1 for an empty region.
    pub fn covered_fraction(&self) -> f64 {
        let could_be = self.covered_m2 + self.missed_m2();
        if could_be > 0.0 {
            self.covered_m2 / could_be
        } else {
            1.0
        }
    }
}

/// The figures of a flight.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Sprayed {
    /// Per region asked for (each field's sprayable region), in order.
    pub regions: Vec<RegionSprayed>,
    /// Area under at least one strip.
    pub sprayed_m2: f64,
    /// Sprayed area outside the ground that may be sprayed (off the fields, over holes or
    /// obstacles).
    pub outside_m2: f64,
    /// Per region, the reachable ground missed, as polygons.
    pub missed: Vec<geo::MultiPolygon<f64>>,
}

/// The farm's rings the measure reads: every field's own ground (with --allow-overlap a
/// shared part belongs to the earlier field only: the rings are read even-odd, so a part in
/// two fields would count as off), and each obstacle's.
pub fn farm_rings(farm: &crate::model::Farm) -> (Rings, Vec<Rings>) {
    let own_grounds: Vec<geo::MultiPolygon<f64>> =
        farm.fields.iter().map(|field| field.own_ground()).collect();
    let ground = Rings::new(
        own_grounds
            .iter()
            .flat_map(|ground| ground.0.iter().flat_map(crate::geometry::rings)),
    );
    let excluded = farm
        .obstacles
        .iter()
        .map(|obstacle| Rings::of_polygon(&obstacle.polygon))
        .collect();
    (ground, excluded)
}

/// Measures `strips` against `regions`, and their spray outside `ground` (fields with their
/// holes) less `excluded` (obstacles), on rows `row_m` apart.
pub fn measure(
    strips: &[Strip],
    regions: &[FieldGround],
    ground: &Rings,
    excluded: &[Rings],
    row_m: f64,
) -> Sprayed {
    let mut low = f64::INFINITY;
    let mut high = f64::NEG_INFINITY;
    for strip in strips {
        low = low.min(strip.low_y);
        high = high.max(strip.high_y);
    }
    for rings in regions.iter().map(|region| &region.sprayable) {
        if let (Some(first), Some(last)) = (
            rings.edges.first(),
            rings.edges.iter().map(|e| e.1).reduce(f64::max),
        ) {
            low = low.min(first.0);
            high = high.max(last);
        }
    }
    let mut result = Sprayed {
        regions: vec![RegionSprayed::default(); regions.len()],
        ..Sprayed::default()
    };
    if !(low.is_finite() && high.is_finite()) {
        return result;
    }
    let mut order: Vec<usize> = (0..strips.len()).collect();
    order.sort_by(|&a, &b| strips[a].low_y.total_cmp(&strips[b].low_y));
    let mut next_strip = 0;
    let mut active: Vec<usize> = Vec::new();
    let mut region_cursors: Vec<(Cursor, Cursor)> = regions
        .iter()
        .map(|region| {
            (
                Cursor::new(&region.sprayable),
                Cursor::new(&region.reachable),
            )
        })
        .collect();
    let mut ground_cursor = Cursor::new(ground);
    let mut excluded_cursors: Vec<Cursor> = excluded.iter().map(Cursor::new).collect();
    let (mut raw, mut covered, mut twice, mut inside) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let (mut blocked, mut piece, mut allowed, mut merged) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut missed_rows: Vec<MissedPieces> =
        regions.iter().map(|_| MissedPieces::default()).collect();
    let mut missed = Vec::new();
    let rows = ((high - low) / row_m).ceil() as usize;
    for row in 0..rows {
        let y = low + (row as f64 + 0.5) * row_m;
        while next_strip < order.len() && strips[order[next_strip]].low_y <= y {
            active.push(order[next_strip]);
            next_strip += 1;
        }
        active.retain(|&k| strips[k].high_y > y);
        raw.clear();
        for &k in &active {
            strips[k].intervals(y, &mut raw);
        }
        doubled(&raw, &mut twice);
        union(&mut raw, &mut covered);
        for (((sprayable, reachable), figures), pieces) in region_cursors
            .iter_mut()
            .zip(&mut result.regions)
            .zip(&mut missed_rows)
        {
            sprayable.intervals(y, &mut inside);
            figures.area_m2 += length(&inside) * row_m;
            figures.covered_m2 += overlap_length(&inside, &covered) * row_m;
            figures.doubled_m2 += overlap_length(&inside, &twice) * row_m;
            reachable.intervals(y, &mut inside);
            figures.reachable_area_m2 += length(&inside) * row_m;
            figures.reachable_covered_m2 += overlap_length(&inside, &covered) * row_m;
            subtract(&inside, &covered, &mut missed);
            pieces.add_row(y, &missed);
        }
        // The cursors walk every row, sprayed or not (rows come in increasing y).
        ground_cursor.intervals(y, &mut inside);
        blocked.clear();
        for cursor in &mut excluded_cursors {
            cursor.intervals(y, &mut piece);
            blocked.extend_from_slice(&piece);
        }
        if covered.is_empty() {
            continue;
        }
        union(&mut blocked, &mut merged);
        subtract(&inside, &merged, &mut allowed);
        let sprayed = length(&covered);
        result.sprayed_m2 += sprayed * row_m;
        result.outside_m2 += (sprayed - overlap_length(&covered, &allowed)) * row_m;
    }
    result.missed = missed_rows
        .into_iter()
        .map(|pieces| pieces.finish(row_m))
        .collect();
    result
}

/// The footprint of a spray leg from `from` to `to` (`half` the swath on either side), turning
/// at its end when the run goes on spraying through the `next` leg in another direction (not
/// at the waypoints of a straight swath that only follow the terrain).
pub(super) fn leg_strip(
    from: Coord<f64>,
    to: Coord<f64>,
    half: f64,
    next: Option<&super::flown::Leg>,
) -> Option<Strip> {
    let strip = Strip::new(from, to, half)?;
    let direction = Coord {
        x: to.x - from.x,
        y: to.y - from.y,
    };
    let Some(next) = next else {
        return Some(strip);
    };
    let next_direction = Coord {
        x: next.to.x - next.from.x,
        y: next.to.y - next.from.y,
    };
    let cross = direction.x * next_direction.y - direction.y * next_direction.x;
    let dot = direction.x * next_direction.x + direction.y * next_direction.y;
    let turns_on =
        next.spraying && next.horizontal_m() > 0.0 && cross.atan2(dot).abs() > super::MIN_TURN_RAD;
    Some(if turns_on {
        strip.turning_at_end(to, half, direction, next_direction)
    } else {
        strip
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x0: f64, y0: f64, size: f64) -> Vec<Coord<f64>> {
        vec![
            Coord { x: x0, y: y0 },
            Coord {
                x: x0 + size,
                y: y0,
            },
            Coord {
                x: x0 + size,
                y: y0 + size,
            },
            Coord {
                x: x0,
                y: y0 + size,
            },
            Coord { x: x0, y: y0 },
        ]
    }

    #[test]
    fn strips_over_a_square_with_a_hole_are_measured_exactly() {
        let shell = square(0.0, 0.0, 100.0);
        let hole = square(40.0, 40.0, 20.0);
        let field = Rings::new([shell.as_slice(), hole.as_slice()]);
        // Ten diagonal-free strips 10 m wide cover the square; one more overlaps the first.
        let mut strips: Vec<Strip> = (0..10)
            .map(|k| {
                let y = 5.0 + 10.0 * k as f64;
                Strip::new(Coord { x: 0.0, y }, Coord { x: 100.0, y }, 5.0).unwrap()
            })
            .collect();
        strips.push(Strip::new(Coord { x: 0.0, y: 5.0 }, Coord { x: 120.0, y: 5.0 }, 5.0).unwrap());
        let ground = FieldGround {
            sprayable: field.clone(),
            reachable: field.clone(),
            unreachable: geo::MultiPolygon::new(vec![]),
        };
        let measured = measure(&strips, std::slice::from_ref(&ground), &field, &[], 0.05);
        let figures = measured.regions[0];
        assert!((figures.area_m2 - 9600.0).abs() < 1e-6, "{figures:?}");
        assert!((figures.covered_m2 - 9600.0).abs() < 1e-6);
        assert!((figures.doubled_m2 - 1000.0).abs() < 1e-6);
        // Outside: the hole (400 m²) and the 20 m × 10 m overhang.
        assert!((measured.outside_m2 - 600.0).abs() < 1e-6, "{measured:?}");
        assert!((measured.sprayed_m2 - 10_200.0).abs() < 1e-6);
    }

    #[test]
    fn unsprayed_ground_no_swath_reaches_is_unreachable_not_missed() {
        // A 100 × 10 field whose reachable part is x in [0, 90]; one strip sprays x in
        // [0, 50]: 400 m² of reachable ground missed, 100 m² unreachable and unsprayed.
        let field = Rings::new([square(0.0, 0.0, 100.0).as_slice()]);
        let sprayable = Rings::new([[
            Coord { x: 0.0, y: 0.0 },
            Coord { x: 100.0, y: 0.0 },
            Coord { x: 100.0, y: 10.0 },
            Coord { x: 0.0, y: 10.0 },
        ]
        .as_slice()]);
        let reachable = Rings::new([[
            Coord { x: 0.0, y: 0.0 },
            Coord { x: 90.0, y: 0.0 },
            Coord { x: 90.0, y: 10.0 },
            Coord { x: 0.0, y: 10.0 },
        ]
        .as_slice()]);
        let strip = Strip::new(Coord { x: 0.0, y: 5.0 }, Coord { x: 50.0, y: 5.0 }, 5.0).unwrap();
        let ground = FieldGround {
            sprayable,
            reachable,
            unreachable: geo::MultiPolygon::new(vec![]),
        };
        let figures =
            measure(&[strip], std::slice::from_ref(&ground), &field, &[], 0.05).regions[0];
        assert!((figures.missed_m2() - 400.0).abs() < 1e-6, "{figures:?}");
        assert!(
            (figures.unreachable_m2() - 100.0).abs() < 1e-6,
            "{figures:?}"
        );
        assert!((figures.covered_fraction() - 500.0 / 900.0).abs() < 1e-9);
    }

    #[test]
    fn a_tilted_strip_has_its_rectangle_area() {
        let strip = Strip::new(Coord { x: 0.0, y: 0.0 }, Coord { x: 30.0, y: 40.0 }, 2.5).unwrap();
        let everywhere = Rings::new([square(-100.0, -100.0, 300.0).as_slice()]);
        let ground = FieldGround {
            sprayable: everywhere.clone(),
            reachable: everywhere.clone(),
            unreachable: geo::MultiPolygon::new(vec![]),
        };
        let measured = measure(
            &[strip],
            std::slice::from_ref(&ground),
            &everywhere,
            &[],
            0.01,
        );
        assert!(
            (measured.regions[0].covered_m2 - 250.0).abs() < 0.05,
            "{measured:?}"
        );
        assert_eq!(measured.outside_m2, 0.0);
    }
}
