//! Edge passes' corners without the double-sprayed wedge (issue 22 item 2, decision 0019).
//!
//! An edge pass that sprays through a corner lays two rectangles, one per leg, that overlap
//! on the inner side of the turn, and the footprint sweeps a sector of the disc of radius
//! h = w/2 on the outer side (the preflight's model, `preflight::sprayed`). At a turn of φ
//! toward the core the overlap is h²·tan(φ/2) (6.25 m² at 90° with w = 5 m) and the ground
//! between the sector and the field's corner is missed. A single-section sprayer can instead
//! stop leg 1's spray at e₁ along it from the corner vertex V and start leg 2's at e₂ along
//! it (the flight between is spray-off): with square ends the two strips then tile the
//! corner exactly at 90° (e₁ = e₂ = −h: leg 2's strip starts on leg 1's outer edge).
//!
//! In the corner's frame (x along leg 1, which ends at V = 0; y toward the core; leg 2 along
//! u = (cos φ, sin φ), its normal toward the core n = (−sin φ, cos φ)), with all regions
//! intersections of half-planes:
//!
//!   field F = {y ≥ −h, n·p ≥ −h},   core C = {y ≥ h, n·p ≥ h},   near N = {x ≥ −ℓ₁, u·p ≤ ℓ₂}
//!   R₁(e₁) = {|y| ≤ h, x ≤ e₁},     R₂(e₂) = {|n·p| ≤ h, u·p ≥ e₂}
//!   D = |R₁ ∩ R₂ ∩ F ∩ N|           (sprayed twice; neither strip reaches the core)
//!   M = |F ∩ N| − |C ∩ N| − |R₁ ∩ F ∩ N| − |R₂ ∩ F ∩ N| + D      (band missed)
//!   O = |(R₁ ∪ R₂) ∩ N| − |(R₁ ∪ R₂) ∩ F ∩ N|                   (sprayed outside)
//!
//! (ℓ = the near stretch of each leg). Spraying through is R₁(0), R₂(0) and the sector
//! {|p| ≤ h, x ≥ 0, u·p ≤ 0}. The pair (e₁, e₂) minimising D + λ·M with O ≈ 0 is found by a
//! grid over [−3h, 3h]² refined three times around the best; the corner is cut when that beats
//! spraying through by `LEAST_SAVING_M2`. Measured (decision 0019): it pays for turns of
//! about 75-105° only (90°: D 6.25 → 0 and M 1.34 → 0 m²; 120°: D 10.8 → 4.7 but M 4.3 → 7.5),
//! so only turns in [`LEAST_TURN_DEG`, `MOST_TURN_DEG`] are tried. The model is local: both
//! legs must be at least [`LEAST_LEG_WIDTHS`] swath widths long, and the preflight flies the
//! result against the real field.

use geo::{Contains, Coord, MultiPolygon, Point};

/// Least turn toward the core that is tried, degrees.
pub const LEAST_TURN_DEG: f64 = 70.0;
/// Most turn toward the core that is tried, degrees.
pub const MOST_TURN_DEG: f64 = 110.0;
/// Shortest leg next to a corner that is cut, in swath widths.
pub const LEAST_LEG_WIDTHS: f64 = 3.0;
/// Weight of missed ground against ground sprayed twice at a corner.
const MISSED_WEIGHT: f64 = 4.0;
/// Weight of ground sprayed outside the field: never worth it.
const OUTSIDE_WEIGHT: f64 = 1000.0;
/// Least gain of D + λ·M, m², for which a corner is cut.
const LEAST_SAVING_M2: f64 = 0.5;

/// A convex polygon as the intersection of half-planes {p : normal·p ≥ offset}.
type HalfPlane = (Coord<f64>, f64);

fn dot(a: Coord<f64>, b: Coord<f64>) -> f64 {
    a.x * b.x + a.y * b.y
}

/// Area of the intersection of `planes` (inside a box of half-width `extent` about 0).
fn area(planes: &[HalfPlane], extent: f64) -> f64 {
    let mut polygon = vec![
        Coord {
            x: -extent,
            y: -extent,
        },
        Coord {
            x: extent,
            y: -extent,
        },
        Coord {
            x: extent,
            y: extent,
        },
        Coord {
            x: -extent,
            y: extent,
        },
    ];
    for &(normal, offset) in planes {
        let mut clipped = Vec::with_capacity(polygon.len() + 1);
        for index in 0..polygon.len() {
            let (a, b) = (polygon[index], polygon[(index + 1) % polygon.len()]);
            let (side_a, side_b) = (dot(normal, a) - offset, dot(normal, b) - offset);
            if side_a >= 0.0 {
                clipped.push(a);
            }
            if (side_a >= 0.0) != (side_b >= 0.0) {
                let t = side_a / (side_a - side_b);
                clipped.push(Coord {
                    x: a.x + t * (b.x - a.x),
                    y: a.y + t * (b.y - a.y),
                });
            }
        }
        if clipped.len() < 3 {
            return 0.0;
        }
        polygon = clipped;
    }
    let mut twice = 0.0;
    for index in 0..polygon.len() {
        let (a, b) = (polygon[index], polygon[(index + 1) % polygon.len()]);
        twice += a.x * b.y - b.x * a.y;
    }
    twice.abs() / 2.0
}

/// One corner in its frame: turn `turn` radians toward the core, half-width `half`, near
/// stretches `near` along leg 1 and leg 2.
struct Corner {
    half: f64,
    along: Coord<f64>,
    normal: Coord<f64>,
    near: [f64; 2],
}

/// D, M and O of a corner sprayed as `strips` (each a list of half-planes), plus the area
/// `extra` covers once and no strip does (the sector of a turn sprayed through).
struct Figures {
    double_m2: f64,
    missed_m2: f64,
    outside_m2: f64,
}

impl Figures {
    fn score(&self) -> f64 {
        self.double_m2 + MISSED_WEIGHT * self.missed_m2 + OUTSIDE_WEIGHT * self.outside_m2
    }
}

impl Corner {
    fn new(turn: f64, half: f64, near: [f64; 2]) -> Self {
        Self {
            half,
            along: Coord {
                x: turn.cos(),
                y: turn.sin(),
            },
            normal: Coord {
                x: -turn.sin(),
                y: turn.cos(),
            },
            near,
        }
    }

    fn extent(&self) -> f64 {
        4.0 * (self.near[0] + self.near[1] + self.half)
    }

    fn field_and_near(&self) -> [HalfPlane; 4] {
        let h = self.half;
        [
            (Coord { x: 0.0, y: 1.0 }, -h),
            (self.normal, -h),
            (Coord { x: 1.0, y: 0.0 }, -self.near[0]),
            (-self.along, -self.near[1]),
        ]
    }

    fn leg_one(&self, end: f64) -> [HalfPlane; 3] {
        let h = self.half;
        [
            (Coord { x: 0.0, y: 1.0 }, -h),
            (Coord { x: 0.0, y: -1.0 }, -h),
            (Coord { x: -1.0, y: 0.0 }, -end),
        ]
    }

    fn leg_two(&self, start: f64) -> [HalfPlane; 3] {
        let h = self.half;
        [(self.normal, -h), (-self.normal, -h), (self.along, start)]
    }

    /// The figures with leg 1 sprayed up to `end` and leg 2 from `start`; `sector` adds the
    /// outer sector of a turn sprayed through (x ≥ 0, u·p ≤ 0, |p| ≤ h, as 32 chords).
    fn figures(&self, end: f64, start: f64, sector: bool) -> Figures {
        let parts = self.parts();
        let (one, two) = (self.leg_one(end), self.leg_two(start));
        parts.figures(&one, &two, &parts.strip(&one), &parts.strip(&two), sector)
    }

    /// What every cut of this corner shares: the field, the core and the near stretches.
    fn parts(&self) -> CornerParts {
        let extent = self.extent();
        let field = self.field_and_near();
        let h = self.half;
        let core = [
            (Coord { x: 0.0, y: 1.0 }, h),
            (self.normal, h),
            field[2],
            field[3],
        ];
        CornerParts {
            extent,
            field,
            field_m2: area(&field, extent),
            core_m2: area(&core, extent),
            half: h,
            along: self.along,
        }
    }

    /// The best (e₁, e₂) and its figures: a 25 × 25 grid over [−3h, 3h]², refined three
    /// times (9 × 9 around the best at a quarter of the step); strictly better only, so ties keep
    /// the first in the grid's fixed order. A leg's own areas depend on its cut alone, so they
    /// are computed once per grid line, not once per grid point (the figures are the same to
    /// the bit).
    fn best_cut(&self) -> (f64, f64, Figures) {
        let parts = self.parts();
        let span = 3.0 * self.half;
        let mut step = 2.0 * span / 24.0;
        let mut best = (0.0, 0.0, self.figures(0.0, 0.0, false));
        let mut centre = (0.0, 0.0);
        for (count, first) in [(25, -span), (9, 0.0), (9, 0.0), (9, 0.0)] {
            let origin = if count == 25 {
                (first, first)
            } else {
                (centre.0 - 4.0 * step, centre.1 - 4.0 * step)
            };
            let legs_two: Vec<(f64, [HalfPlane; 3], Strip)> = (0..count)
                .map(|j| {
                    let start = origin.1 + j as f64 * step;
                    let two = self.leg_two(start);
                    (start, two, parts.strip(&two))
                })
                .collect();
            for i in 0..count {
                let end = origin.0 + i as f64 * step;
                let one = self.leg_one(end);
                let strip_one = parts.strip(&one);
                for (start, two, strip_two) in &legs_two {
                    let figures = parts.figures(&one, two, &strip_one, strip_two, false);
                    if figures.score() < best.2.score() - 1e-9 {
                        best = (end, *start, figures);
                    }
                }
            }
            centre = (best.0, best.1);
            step /= 4.0;
        }
        best
    }
}

/// A strip's areas that do not depend on the other leg: |R ∩ F ∩ N| and |R ∩ N|.
struct Strip {
    inside_m2: f64,
    near_m2: f64,
}

/// A corner's regions that every cut shares ([`Corner::parts`]).
struct CornerParts {
    extent: f64,
    field: [HalfPlane; 4],
    field_m2: f64,
    core_m2: f64,
    half: f64,
    along: Coord<f64>,
}

impl CornerParts {
    /// Area of the intersection of the half-planes of `parts`, in that order.
    fn of(&self, parts: &[&[HalfPlane]]) -> f64 {
        let planes: Vec<HalfPlane> = parts.iter().flat_map(|part| part.iter().copied()).collect();
        area(&planes, self.extent)
    }

    fn strip(&self, leg: &[HalfPlane; 3]) -> Strip {
        Strip {
            inside_m2: self.of(&[leg, &self.field]),
            near_m2: self.of(&[leg, &self.field[2..]]),
        }
    }

    /// D, M and O of the strips `one` and `two` (of areas `strip_one` and `strip_two`).
    fn figures(
        &self,
        one: &[HalfPlane; 3],
        two: &[HalfPlane; 3],
        strip_one: &Strip,
        strip_two: &Strip,
        sector: bool,
    ) -> Figures {
        let (field, near) = (&self.field, &self.field[2..]);
        let double_m2 = self.of(&[one, two, field]);
        let mut covered_once = strip_one.inside_m2 + strip_two.inside_m2 - double_m2;
        let sprayed_near = strip_one.near_m2 + strip_two.near_m2 - self.of(&[one, two, near]);
        let outside_m2 = (sprayed_near - covered_once).max(0.0);
        if sector {
            let h = self.half;
            let chords: Vec<HalfPlane> = (0..32)
                .map(|k| {
                    let angle = std::f64::consts::TAU * (k as f64 + 0.5) / 32.0;
                    (
                        Coord {
                            x: -angle.cos(),
                            y: -angle.sin(),
                        },
                        -h,
                    )
                })
                .collect();
            covered_once += self.of(&[
                &chords,
                &[(Coord { x: 1.0, y: 0.0 }, 0.0), (-self.along, 0.0)],
                field,
            ]);
        }
        let missed_m2 = (self.field_m2 - self.core_m2 - covered_once).max(0.0);
        Figures {
            double_m2,
            missed_m2,
            outside_m2,
        }
    }
}

/// Offset lines carry vertices a few centimetres apart (and arcs at concave corners): the
/// corners are found on the ring simplified within this share of a swath width
/// (Ramer–Douglas–Peucker), and cut pieces follow that ring.
const SIMPLIFY_WIDTHS: f64 = 0.01;

/// The ring's corners (not closed): simplified within `tolerance_m`, and without its first
/// point where that lies within `tolerance_m` of its neighbours' chord (the simplification
/// keeps a line's ends).
fn corners_of(ring: &[Coord<f64>], tolerance_m: f64) -> Vec<Coord<f64>> {
    use geo::Simplify;
    let simplified = geo::LineString::new(ring.to_vec()).simplify(tolerance_m);
    let mut vertices = simplified.0;
    if vertices.len() > 1 && vertices.first() == vertices.last() {
        vertices.pop();
    }
    if vertices.len() > 3 {
        let (before, first, after) = (vertices[vertices.len() - 1], vertices[0], vertices[1]);
        if crate::geometry::distance_to_segment(first, before, after) < tolerance_m {
            vertices.remove(0);
        }
    }
    vertices
}

/// What cutting the corners of one ring gave.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CornerCuts {
    /// The paths to fly: the ring itself (closed) when no corner is cut, else open paths
    /// from one cut corner to the next.
    pub paths: Vec<Vec<Coord<f64>>>,
    /// Corners cut.
    pub corners: usize,
    /// Double dose the cut corners save by the local model, m².
    pub double_saved_m2: f64,
}

/// The pass along `ring` (closed) of `region` (the ring's side that is inside `region` is the
/// core's side), `width_m` wide, with each corner cut where that pays (module docs).
pub fn cut_corners(ring: &[Coord<f64>], region: &MultiPolygon<f64>, width_m: f64) -> CornerCuts {
    let whole = CornerCuts {
        paths: vec![ring.to_vec()],
        ..CornerCuts::default()
    };
    let length = |a: Coord<f64>, b: Coord<f64>| (b.x - a.x).hypot(b.y - a.y);
    let vertices = corners_of(ring, SIMPLIFY_WIDTHS * width_m);
    let count = vertices.len();
    if count < 3 {
        return whole;
    }
    let unit = |a: Coord<f64>, b: Coord<f64>| {
        let l = length(a, b);
        Coord {
            x: (b.x - a.x) / l,
            y: (b.y - a.y) / l,
        }
    };
    // Which side of the ring is the core's: a point a little left of the longest leg.
    let longest = (0..count)
        .max_by(|&a, &b| {
            length(vertices[a], vertices[(a + 1) % count])
                .total_cmp(&length(vertices[b], vertices[(b + 1) % count]))
        })
        .expect("three vertices or more");
    let (a, b) = (vertices[longest], vertices[(longest + 1) % count]);
    let direction = unit(a, b);
    let probe = Point::new(
        (a.x + b.x) / 2.0 - direction.y * 0.01 * width_m,
        (a.y + b.y) / 2.0 + direction.x * 0.01 * width_m,
    );
    let core_side = if region.contains(&probe) { 1.0 } else { -1.0 };
    let half = width_m / 2.0;
    let mut cuts: Vec<(usize, f64, f64, f64)> = Vec::new();
    for index in 0..count {
        let (before, at, after) = (
            vertices[(index + count - 1) % count],
            vertices[index],
            vertices[(index + 1) % count],
        );
        let (leg_one, leg_two) = (length(before, at), length(at, after));
        if leg_one < LEAST_LEG_WIDTHS * width_m || leg_two < LEAST_LEG_WIDTHS * width_m {
            continue;
        }
        let (d1, d2) = (unit(before, at), unit(at, after));
        // The frame's y toward the core: d1 turned a quarter toward the core's side.
        let toward_core = Coord {
            x: -d1.y * core_side,
            y: d1.x * core_side,
        };
        let turn = dot(d2, toward_core).atan2(dot(d2, d1));
        if !(LEAST_TURN_DEG.to_radians()..=MOST_TURN_DEG.to_radians()).contains(&turn) {
            continue;
        }
        let corner = Corner::new(turn, half, [leg_one / 2.0, leg_two / 2.0]);
        let through = corner.figures(0.0, 0.0, true);
        let (end, start, cut) = corner.best_cut();
        if cut.outside_m2 < 1e-3 && cut.score() < through.score() - LEAST_SAVING_M2 {
            cuts.push((index, end, start, through.double_m2 - cut.double_m2));
        }
    }
    if cuts.is_empty() {
        return whole;
    }
    // The pieces follow the ring itself, not its simplification (which may stray by the
    // tolerance, outside the field): each corner is one of the ring's own points.
    let mut original: Vec<Coord<f64>> = ring.to_vec();
    if original.len() > 1 && original.first() == original.last() {
        original.pop();
    }
    let total = original.len();
    let index_in_ring = |point: Coord<f64>| {
        original
            .iter()
            .position(|&vertex| vertex == point)
            .expect("the simplification keeps points of the ring")
    };
    let mut paths = Vec::with_capacity(cuts.len());
    for (k, &(from, _, start, _)) in cuts.iter().enumerate() {
        let (to, end, _, _) = cuts[(k + 1) % cuts.len()];
        let leaving = unit(vertices[from], vertices[(from + 1) % count]);
        let arriving = unit(vertices[(to + count - 1) % count], vertices[to]);
        let (first, last) = (vertices[from], vertices[to]);
        let mut path = vec![Coord {
            x: first.x + start * leaving.x,
            y: first.y + start * leaving.y,
        }];
        // The ring's points from the corner `from` to the corner `to` (once round the ring
        // when they are the same corner), less those the cut pieces leave out: the corners
        // themselves where a piece stops short of them, and the points within `start` past
        // the first and within −`end` before the last.
        let (from_index, to_index) = (index_in_ring(first), index_in_ring(last));
        let steps = match (to_index + total - from_index) % total {
            0 => total,
            steps => steps,
        };
        let within = |point: Coord<f64>, corner: Coord<f64>, direction: Coord<f64>, reach: f64| {
            let offset = Coord {
                x: point.x - corner.x,
                y: point.y - corner.y,
            };
            reach > 0.0 && dot(offset, direction) >= 0.0 && offset.x.hypot(offset.y) <= reach
        };
        let backwards = Coord {
            x: -arriving.x,
            y: -arriving.y,
        };
        for step in 0..=steps {
            let point = original[(from_index + step) % total];
            let keep = if step == 0 {
                start < 0.0
            } else if step == steps {
                end > 0.0
            } else {
                !within(point, first, leaving, start) && !within(point, last, backwards, -end)
            };
            if keep {
                path.push(point);
            }
        }
        path.push(Coord {
            x: last.x + end * arriving.x,
            y: last.y + end * arriving.y,
        });
        path.dedup();
        paths.push(path);
    }
    CornerCuts {
        paths,
        corners: cuts.len(),
        double_saved_m2: cuts.iter().map(|cut| cut.3).sum(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::polygon;

    #[test]
    fn a_right_angle_tiles_and_a_shallow_turn_is_sprayed_through() {
        let right = Corner::new(std::f64::consts::FRAC_PI_2, 2.5, [20.0, 20.0]);
        let through = right.figures(0.0, 0.0, true);
        // h²·tan(45°) sprayed twice; the corner square less the quarter disc missed.
        assert!(
            (through.double_m2 - 6.25).abs() < 1e-9,
            "{}",
            through.double_m2
        );
        let quarter_disc = std::f64::consts::PI * 6.25 / 4.0;
        assert!(
            (through.missed_m2 - (6.25 - quarter_disc)).abs() < 0.05,
            "{}",
            through.missed_m2
        );
        let (_, _, cut) = right.best_cut();
        assert!(cut.double_m2 < 1e-6 && cut.missed_m2 < 1e-6 && cut.outside_m2 < 1e-6);
        // Not exactly square: no spray outside, little of either left.
        let (_, _, cut) = Corner::new(89.1f64.to_radians(), 2.5, [24.0, 18.0]).best_cut();
        assert!(cut.outside_m2 < 1e-6 && cut.double_m2 < 0.3 && cut.missed_m2 < 0.3);
        let shallow = Corner::new(40f64.to_radians(), 2.5, [20.0, 20.0]);
        let (_, _, cut) = shallow.best_cut();
        assert!(cut.score() > shallow.figures(0.0, 0.0, true).score() - LEAST_SAVING_M2);
    }

    #[test]
    fn a_square_field_pass_is_cut_at_its_four_corners_and_a_hexagon_is_not() {
        // The pass line of a 60 m square field, w = 5 m: its region is the square inside it.
        let square = polygon![
            (x: 2.5, y: 2.5), (x: 57.5, y: 2.5), (x: 57.5, y: 57.5), (x: 2.5, y: 57.5), (x: 2.5, y: 2.5)
        ];
        let ring: Vec<Coord<f64>> = square.exterior().0.clone();
        let region = MultiPolygon::new(vec![square.clone()]);
        let cuts = cut_corners(&ring, &region, 5.0);
        assert_eq!(cuts.corners, 4);
        assert_eq!(cuts.paths.len(), 4);
        assert!(
            (cuts.double_saved_m2 - 25.0).abs() < 1e-6,
            "{}",
            cuts.double_saved_m2
        );
        // Every piece stays inside the field (the pass line offset by h at most).
        for point in cuts.paths.iter().flatten() {
            assert!((-1e-9..=60.0 + 1e-9).contains(&point.x), "{point:?}");
            assert!((-1e-9..=60.0 + 1e-9).contains(&point.y), "{point:?}");
        }
        // The same ring reversed (a hole's orientation) is cut the same.
        let reversed: Vec<Coord<f64>> = ring.iter().rev().copied().collect();
        assert_eq!(cut_corners(&reversed, &region, 5.0).corners, 4);
        // A regular hexagon turns 60° at each corner: sprayed through, the ring kept whole.
        let hexagon: Vec<Coord<f64>> = (0..=6)
            .map(|k| {
                let angle = std::f64::consts::TAU * (k % 6) as f64 / 6.0;
                Coord {
                    x: 40.0 * angle.cos(),
                    y: 40.0 * angle.sin(),
                }
            })
            .collect();
        let region = MultiPolygon::new(vec![geo::Polygon::new(hexagon.clone().into(), vec![])]);
        let kept = cut_corners(&hexagon, &region, 5.0);
        assert_eq!(kept.corners, 0);
        assert_eq!(kept.paths, vec![hexagon]);
    }
}
