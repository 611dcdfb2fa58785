//! The search for the supply point: screen the coarse candidates by a cheap surrogate,
//! refine the best few by a pattern search, score them by the evaluator itself
//! (docs/decisions/0016-supply-point.md). C is the evaluator's cost, S_A its surrogate around
//! a point A: exact at A and, for the default evaluator, an upper bound of C wherever it is
//! finite, so that the lowest of several is the tightest.
//!
//! 1. **Anchors.** C and S at the references R_i (the spray-weighted centroid, the route's
//!    first and last points) and, on a farm of several fields, at each field's centroid
//!    settled onto a place a vehicle can stand: the screen is then tight near the centre,
//!    the route's ends and every field. C at each R_i settled onto the nearest place a
//!    vehicle can stand too, kept as a finalist (step 5), so that the choice is never dearer
//!    than the place beside the old rule's point (docs/decisions/0031).
//! 2. **Screen.** Every candidate P is scored by S(P) = min over the anchors A of S_A(P), in
//!    O(anchors × sorties). When S is infinite at more than half the candidates (the
//!    anchors' sorties, at the battery's limit, fly from nowhere else as they are), the
//!    settled references and [`FALLBACK_ANCHORS`] candidates spread over the list are
//!    anchors too, scored by C, and the screen is made again. Until 2026-12-06 a 30 L tank on
//!    the Christmas Island fields found no supply point at all (S infinite everywhere), and
//!    the T16's 16 L found one 14 % dearer than a place on the other side of the hole.
//! 3. **Starts.** The references settled onto places a vehicle can stand, the fields'
//!    anchors, each field's best screened candidate among those nearest to it (so that every
//!    field's side is tried), then the best screened candidates; each at least
//!    max(s_g, [`MIN_SEPARATION_M`]) from the starts already taken (s_g: the coarse spacing),
//!    up to max([`STARTS`], N) for `auto:N` (more when the seeds before are more).
//! 4. **Refine.** From each start, a compass pattern search on S within half the separation of
//!    the start (8 directions at step δ, from δ = s_g / 2; a move goes to the best improving
//!    neighbour, each neighbour settled onto a place a vehicle can stand; no improvement
//!    halves δ, down to [`MIN_STEP_M`]), so that the starts stay different places; then C at
//!    the point found.
//! 5. **Polish.** The max([`POLISHED`], N) best by C: a pattern search on the surrogate around
//!    the point, then C at the point found, kept when lower, for at most [`ROUNDS`] rounds.
//! 6. **Rank.** By C (ties by position), points within [`MIN_SEPARATION_M`] of a better one
//!    dropped, so that `auto:N` lists places an operator can tell apart (until 2026-12-06
//!    [`SAME_PLACE_M`], and a newcomer's `auto:3` listed three points 14-21 m apart). Only C
//!    is ever reported, so the result is scored by the evaluator itself.
//!
//! Everything is deterministic: no randomness, total orders on ties. About 15-20
//! evaluations of C per search, up to 11 more when the screen is blind (step 2).

use std::rc::Rc;

use geo::Coord;

use super::standing::StandingRule;
use super::{ScoredPoint, SupplyCost};

/// Starts refined and scored by the evaluator at least.
pub const STARTS: usize = 8;
/// The best scored starts polished at least.
pub const POLISHED: usize = 2;
/// The least distance between two starts, metres.
pub const MIN_SEPARATION_M: f64 = 40.0;
/// The pattern search's finest step, metres.
pub const MIN_STEP_M: f64 = 1.0;
/// Polishing rounds (a surrogate, a pattern search, an evaluation) per point at most.
pub const ROUNDS: usize = 3;
/// Refined points closer than this are one place, metres.
pub const SAME_PLACE_M: f64 = 5.0;
/// Candidates scored by the evaluator itself when the anchors' surrogates are infinite at
/// most candidates (the fallback of step 2).
pub const FALLBACK_ANCHORS: usize = 8;
/// Moves of one pattern search at most (a bound on the work, never reached on real farms).
const MAX_MOVES: usize = 400;

/// The compass directions of the pattern search: the axes and the diagonals.
const DIRECTIONS: [(f64, f64); 8] = [
    (1.0, 0.0),
    (0.0, 1.0),
    (-1.0, 0.0),
    (0.0, -1.0),
    (
        std::f64::consts::FRAC_1_SQRT_2,
        std::f64::consts::FRAC_1_SQRT_2,
    ),
    (
        -std::f64::consts::FRAC_1_SQRT_2,
        std::f64::consts::FRAC_1_SQRT_2,
    ),
    (
        -std::f64::consts::FRAC_1_SQRT_2,
        -std::f64::consts::FRAC_1_SQRT_2,
    ),
    (
        std::f64::consts::FRAC_1_SQRT_2,
        -std::f64::consts::FRAC_1_SQRT_2,
    ),
];

/// The outcome of a search.
#[derive(Debug, Clone, PartialEq)]
pub struct Ranked {
    /// The refined points by the evaluator's cost, best first, each a different place.
    pub points: Vec<ScoredPoint>,
    /// Times the evaluator's cost was computed.
    pub evaluations: usize,
    /// The evaluator's cost at each reference point, in their order.
    pub reference_costs: Vec<f64>,
    /// Each reference point settled onto the nearest place a vehicle can stand, scored by
    /// the evaluator, in their order (`None` where none is found).
    pub settled_references: Vec<Option<ScoredPoint>>,
}

fn distance(a: Coord<f64>, b: Coord<f64>) -> f64 {
    (a.x - b.x).hypot(a.y - b.y)
}

fn by_cost_then_place(a: &ScoredPoint, b: &ScoredPoint) -> std::cmp::Ordering {
    a.cost_s
        .total_cmp(&b.cost_s)
        .then(a.point.x.total_cmp(&b.point.x))
        .then(a.point.y.total_cmp(&b.point.y))
}

/// Points kept in order, each at least `apart` from every earlier one kept.
fn distinct(points: impl IntoIterator<Item = ScoredPoint>, apart: f64) -> Vec<ScoredPoint> {
    let mut kept: Vec<ScoredPoint> = Vec::new();
    for scored in points {
        if kept
            .iter()
            .all(|other| distance(other.point, scored.point) >= apart)
        {
            kept.push(scored);
        }
    }
    kept
}

/// The compass search of `estimate` from `start` (step 4 of the module's documentation).
fn pattern_search(
    start: ScoredPoint,
    estimate: &dyn Fn(Coord<f64>) -> f64,
    standing: &StandingRule,
    first_step_m: f64,
) -> Coord<f64> {
    let (mut at, mut cost) = (start.point, start.cost_s);
    let mut step = first_step_m.max(MIN_STEP_M);
    let mut moves = 0;
    while step >= MIN_STEP_M && moves < MAX_MOVES {
        let mut best: Option<(f64, Coord<f64>)> = None;
        for (dx, dy) in DIRECTIONS {
            let Some(next) = standing.settle(Coord {
                x: at.x + step * dx,
                y: at.y + step * dy,
            }) else {
                continue;
            };
            // Settled back onto the point itself: no move.
            if distance(next, at) < 0.1 * MIN_STEP_M {
                continue;
            }
            let next_cost = estimate(next);
            if next_cost < best.map_or(f64::INFINITY, |(c, _)| c) {
                best = Some((next_cost, next));
            }
        }
        match best {
            Some((next_cost, next)) if next_cost < cost - 1e-9 => {
                (at, cost) = (next, next_cost);
                moves += 1;
            }
            _ => step *= 0.5,
        }
    }
    at
}

/// A surrogate shared between the screen and the polish of its place.
type Shared<'a> = Rc<dyn Fn(Coord<f64>) -> f64 + 'a>;

/// The places the evaluator has scored, with their surrogates.
struct Scored<'a> {
    cost: &'a dyn SupplyCost,
    places: Vec<(ScoredPoint, Shared<'a>)>,
}

impl<'a> Scored<'a> {
    /// C at `point` (computed once per place).
    fn score(&mut self, point: Coord<f64>) -> ScoredPoint {
        if let Some((known, _)) = self.places.iter().find(|(known, _)| known.point == point) {
            return *known;
        }
        let (cost_s, surrogate) = self.cost.cost_and_surrogate(point);
        let scored = ScoredPoint { point, cost_s };
        self.places.push((scored, Rc::from(surrogate)));
        scored
    }

    /// The surrogate around a scored place.
    fn surrogate(&self, point: Coord<f64>) -> Shared<'a> {
        let (_, surrogate) = self
            .places
            .iter()
            .find(|(known, _)| known.point == point)
            .expect("a scored place");
        Rc::clone(surrogate)
    }

    /// The screen: the lowest surrogate of the places scored so far.
    fn screen(&self) -> impl Fn(Coord<f64>) -> f64 + 'a {
        let surrogates: Vec<_> = self.places.iter().map(|(_, s)| Rc::clone(s)).collect();
        move |point| {
            surrogates
                .iter()
                .map(|surrogate| surrogate(point))
                .fold(f64::INFINITY, f64::min)
        }
    }

    /// Polishes the scored place `start` (step 5).
    fn polish(
        &mut self,
        start: ScoredPoint,
        standing: &StandingRule,
        first_step_m: f64,
    ) -> ScoredPoint {
        let mut best = start;
        for _ in 0..ROUNDS {
            if !best.cost_s.is_finite() {
                break;
            }
            let surrogate = self.surrogate(best.point);
            let found = pattern_search(best, &*surrogate, standing, first_step_m);
            if distance(found, best.point) < 0.1 * MIN_STEP_M {
                break;
            }
            let found = self.score(found);
            if found.cost_s < best.cost_s - 1e-9 {
                best = found;
            } else {
                break;
            }
        }
        best
    }
}

/// The search over `candidates` (the module's documentation): `references` are the R_i,
/// `field_anchors` the fields' centroids (settled here), `spacing_m` s_g, `listed` the N of
/// `auto:N` (0 or 1: the best only). `None` when no candidate has a finite cost.
pub fn search(
    candidates: &[Coord<f64>],
    spacing_m: f64,
    references: &[Coord<f64>],
    field_anchors: &[Coord<f64>],
    standing: &StandingRule,
    cost: &dyn SupplyCost,
    listed: usize,
) -> Option<Ranked> {
    let mut scored = Scored {
        cost,
        places: Vec::new(),
    };
    let reference_costs: Vec<f64> = references
        .iter()
        .map(|&reference| scored.score(reference).cost_s)
        .collect();
    // The references where a vehicle can stand, scored by C and finalists too: the choice
    // is never dearer than the place beside the old rule's point (the surrogate's pattern
    // search from it may end dearer by C).
    let settled_references: Vec<Option<ScoredPoint>> = references
        .iter()
        .map(|&reference| standing.settle(reference).map(|point| scored.score(point)))
        .collect();
    let field_scored: Vec<ScoredPoint> = field_anchors
        .iter()
        .filter_map(|&point| standing.settle(point))
        .map(|point| scored.score(point))
        .collect();
    let mut screen = scored.screen();
    let screened_by = |screen: &dyn Fn(Coord<f64>) -> f64| -> Vec<ScoredPoint> {
        candidates
            .iter()
            .map(|&point| ScoredPoint {
                point,
                cost_s: screen(point),
            })
            .filter(|scored| scored.cost_s.is_finite())
            .collect()
    };
    let mut screened = screened_by(&screen);
    if 2 * screened.len() < candidates.len() {
        // The anchors' sorties fly from few candidates as they are (sorties at the battery's
        // limit, anchors inside the fields), so the screen is blind over most of the farm:
        // anchor at places a vehicle can stand too (the settled references are scored
        // already), candidates spread over the list, scored by C itself.
        let stride = candidates.len().div_ceil(FALLBACK_ANCHORS).max(1);
        for place in candidates.iter().step_by(stride) {
            scored.score(*place);
        }
        screen = scored.screen();
        screened = screened_by(&screen);
    }
    let at = |point: Coord<f64>| ScoredPoint {
        point,
        cost_s: screen(point),
    };
    screened.sort_by(by_cost_then_place);
    let mut per_field: Vec<Option<ScoredPoint>> = vec![None; standing.field_count()];
    for candidate in &screened {
        per_field[standing.nearest_field(candidate.point)].get_or_insert(*candidate);
    }
    let seeds: Vec<ScoredPoint> = settled_references
        .iter()
        .flatten()
        .map(|settled| at(settled.point))
        .chain(field_scored.iter().map(|anchor| at(anchor.point)))
        .chain(per_field.into_iter().flatten())
        .filter(|seed| seed.cost_s.is_finite())
        .collect();
    let separation = spacing_m.max(MIN_SEPARATION_M);
    let wanted = STARTS.max(listed).max(seeds.len());
    let mut starts = distinct(seeds.into_iter().chain(screened), separation);
    starts.truncate(wanted);
    let step = 0.5 * spacing_m;
    let refined: Vec<ScoredPoint> = starts
        .iter()
        .map(|&start| {
            let within = |point: Coord<f64>| {
                if distance(point, start.point) <= 0.5 * separation {
                    screen(point)
                } else {
                    f64::INFINITY
                }
            };
            at(pattern_search(start, &within, standing, step))
        })
        .collect();
    let mut finalists: Vec<ScoredPoint> = distinct(refined, SAME_PLACE_M)
        .into_iter()
        .map(|point| scored.score(point.point))
        .chain(settled_references.iter().flatten().copied())
        .filter(|point| point.cost_s.is_finite())
        .collect();
    finalists.sort_by(by_cost_then_place);
    let finalists = distinct(finalists, SAME_PLACE_M);
    let polished = POLISHED.max(listed);
    let mut ranked: Vec<ScoredPoint> = Vec::with_capacity(finalists.len());
    for (index, finalist) in finalists.into_iter().enumerate() {
        ranked.push(if index < polished {
            scored.polish(finalist, standing, step)
        } else {
            finalist
        });
    }
    ranked.sort_by(by_cost_then_place);
    // The best first, then alternatives an operator can tell apart on the ground (another
    // gate, the other side of a field), not the same place polished twice: at least the
    // starts' separation from every point listed before.
    let mut points = distinct(ranked, MIN_SEPARATION_M);
    points.truncate(listed.max(1));
    (!points.is_empty()).then_some(Ranked {
        points,
        evaluations: scored.places.len(),
        reference_costs,
        settled_references,
    })
}
