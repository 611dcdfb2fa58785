//! The supply point: where the drone takes off, refills its tank, swaps its battery and lands
//! (seed 003's P0), and how it is chosen (issue 19; docs/decisions/0016-supply-point.md).
//!
//! Three rules ([`SupplySource`]): a point given on the command line (`--supply X,Y` or
//! `--start X,Y`), else the field file's launch marker, else `auto` (the default when the plan
//! has sorties; `--supply auto` asks for it whatever the file marks): among the places a
//! vehicle can stand ([`standing`]), the one that minimises the plan's non-spray time as an
//! evaluator scores it. The evaluator is a value passed in ([`SupplyCost`]: any
//! `Fn(Coord) -> seconds` is one); the default, [`evaluator::FixedRouteSplit`], keeps the
//! route planned without a start point and splits it exactly into sorties from each point
//! scored. The search ([`search`]) screens a coarse candidate set ([`candidates`]) by the
//! evaluator's cheap surrogate, refines the best few by a pattern search, and keeps the best
//! by the evaluator itself. The old rule (the first point of the route planned without a
//! start point) is scored by the same evaluator, so the saving is like for like; where no
//! vehicle can stand there (a pass end inside a field), so is the nearest place one can, the
//! old rule as an operator could follow it, which the search always weighs.

pub mod candidates;
pub mod evaluator;
pub mod level;
pub mod search;
pub mod standing;

use std::str::FromStr;

use geo::Coord;
use serde::Serialize;

use crate::coverage::drape::GroundPoint;
use crate::error::Fault;
use crate::model::Farm;
use crate::sortie::route::WorkRoute;
use standing::StandingRule;

/// The most candidates `auto:N` lists.
pub const MAX_LISTED: usize = 20;

/// How the supply point is asked for (`--supply`; a point given is the plan's `start`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(tag = "rule", rename_all = "snake_case")]
pub enum SupplyRequest {
    /// From the inputs: the point given, else the field file's launch marker, else `auto`
    /// when the plan has sorties, else none (a free start).
    #[default]
    FromInputs,
    /// Chosen automatically whatever the file marks, listing the `listed` best candidates in
    /// the report (0: the chosen one only).
    Auto {
        /// How many candidates the report lists, 0..=[`MAX_LISTED`].
        listed: usize,
    },
}

/// A `--supply` value: `auto`, `auto:N` or a point `X,Y` (in the input's coordinates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SupplyValue {
    /// `auto` or `auto:N`.
    Auto {
        /// N (0 for plain `auto`).
        listed: usize,
    },
    /// `X,Y`.
    Point([f64; 2]),
}

impl FromStr for SupplyValue {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let text = text.trim();
        let expected = format!(
            "expected auto, auto:N (N = 1..={MAX_LISTED} candidates listed) or X,Y (two numbers in the fields' coordinates)"
        );
        if text.eq_ignore_ascii_case("auto") {
            return Ok(Self::Auto { listed: 0 });
        }
        if let Some(count) = text
            .get(..5)
            .filter(|head| head.eq_ignore_ascii_case("auto:"))
            .map(|_| &text[5..])
        {
            return match count.trim().parse::<usize>() {
                Ok(listed) if (1..=MAX_LISTED).contains(&listed) => Ok(Self::Auto { listed }),
                _ => Err(format!(
                    "'{count}' is not a count of 1..={MAX_LISTED}: {expected}"
                )),
            };
        }
        let numbers: Vec<&str> = text.split(',').map(str::trim).collect();
        match numbers.as_slice() {
            [x, y] => match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(x), Ok(y)) if x.is_finite() && y.is_finite() => Ok(Self::Point([x, y])),
                _ => Err(format!("'{text}' is not two finite numbers: {expected}")),
            },
            _ => Err(expected),
        }
    }
}

/// Which rule chose the supply point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SupplySource {
    /// The field file's launch marker.
    Marker,
    /// Given on the command line (`--supply X,Y`, `--start X,Y`) or by a library caller.
    Given,
    /// Chosen by the search.
    Auto,
}

impl SupplySource {
    /// The rule's name in `report.json` and the summary.
    pub fn key(self) -> &'static str {
        match self {
            Self::Marker => "marker",
            Self::Given => "given",
            Self::Auto => "auto",
        }
    }
}

/// A point with what the evaluator says a plan from it costs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScoredPoint {
    /// The point in planning metres.
    pub point: Coord<f64>,
    /// Non-spray seconds of the plan from it (infinite where none flies).
    pub cost_s: f64,
}

/// A cheap stand-in for an evaluator's cost near one point (see [`SupplyCost`]).
pub type Surrogate<'a> = Box<dyn Fn(Coord<f64>) -> f64 + 'a>;

/// What a supply point costs: the seam the search is written against. Any
/// `Fn(Coord<f64>) -> f64` (seconds) is one; [`evaluator::FixedRouteSplit`] is the default.
pub trait SupplyCost {
    /// Non-spray seconds of the plan flown from `point` (planning metres); infinite where no
    /// plan flies from it.
    fn cost_s(&self, point: Coord<f64>) -> f64;

    /// The cost at `around` and a cheap estimate of the cost near it, equal to it at `around`
    /// (the plan found for `around`, re-costed from other points). The default: the cost
    /// itself, which is exact but spends an evaluation on every step of the search.
    fn cost_and_surrogate(&self, around: Coord<f64>) -> (f64, Surrogate<'_>) {
        (
            self.cost_s(around),
            Box::new(move |point| self.cost_s(point)),
        )
    }

    /// What the cost measures, in a sentence for the report.
    fn describe(&self) -> &'static str {
        "a cost given by the caller"
    }
}

impl<F: Fn(Coord<f64>) -> f64> SupplyCost for F {
    fn cost_s(&self, point: Coord<f64>) -> f64 {
        self(point)
    }
}

/// What the `auto` rule found.
#[derive(Debug, Clone, PartialEq)]
pub struct AutoChoice {
    /// The best candidates by the evaluator, best first (at least the chosen one, at most
    /// `listed`).
    pub ranked: Vec<ScoredPoint>,
    /// The N of `auto:N` (0 for plain `auto`).
    pub listed: usize,
    /// The old rule: the first point of the route planned without a start point, scored by
    /// the same evaluator.
    pub first_point: ScoredPoint,
    /// Whether a vehicle could stand at the old rule's point (it is a pass end: on or in a
    /// field, as a rule).
    pub first_point_stands: bool,
    /// Where no vehicle can stand at the old rule's point: the nearest place one can
    /// ([`standing::StandingRule::settle`]), scored by the same evaluator: the old rule as an
    /// operator could follow it (docs/decisions/0031). `None` when the point stands, or when
    /// no place is found.
    pub first_point_moved: Option<ScoredPoint>,
    /// Why a vehicle cannot stand level at `first_point_moved` (its slope, decision 0029),
    /// when the search kept to level ground and it is not level: then it is only the nearest
    /// place outside the fields, and the summary says so (the eleventh trial read "the
    /// nearest place one can" of a point on a slope `auto` refuses). Set by the pipeline.
    pub first_point_moved_unlevel: Option<String>,
    /// Times the evaluator's cost was computed.
    pub evaluations: usize,
    /// Whether the candidates stood on access features.
    pub on_access: bool,
    /// The margin kept from fields and obstacles, metres (0 on access features).
    pub margin_m: f64,
    /// The farthest from the fields, metres (`None` on access features: no limit).
    pub reach_m: Option<f64>,
    /// What the evaluator measures.
    pub evaluator: &'static str,
}

impl AutoChoice {
    /// The chosen point.
    pub fn best(&self) -> ScoredPoint {
        self.ranked[0]
    }
}

/// The supply point of a plan and how it was chosen.
#[derive(Debug, Clone, PartialEq)]
pub struct SupplyChoice {
    /// The rule that chose it.
    pub source: SupplySource,
    /// The point, with its ground height.
    pub point: GroundPoint,
    /// What the search found, for `auto`.
    pub auto: Option<AutoChoice>,
    /// For a point marked or given: why a vehicle cannot stand there by the rule `auto`
    /// keeps to ([`standing::StandingRule::why_not`]); `None` when it can, and for `auto`.
    pub standing_warning: Option<String>,
}

/// The `auto` rule on `farm` for `route` (the route planned without a start point) scored by
/// `cost`, listing the `listed` best. Errs when no place to stand is found, or none from
/// which the plan flies.
pub fn choose_auto(
    farm: &Farm,
    route: &WorkRoute,
    cost: &dyn SupplyCost,
    listed: usize,
) -> Result<AutoChoice, Fault> {
    let first = route
        .points()
        .first()
        .map(|point| Coord {
            x: point.x,
            y: point.y,
        })
        .ok_or_else(|| Fault::Structure("no route to choose a supply point for".into()))?;
    let standing = StandingRule::new(farm);
    let where_to_stand = if standing.on_access() {
        "on the access features, outside fields and obstacles".to_string()
    } else {
        format!(
            "outside fields, holes and obstacles by {} m and within {} m of a field",
            standing.margin_m, standing.reach_m
        )
    };
    let coarse = candidates::coarse(farm, route, &standing);
    if coarse.points.is_empty() {
        return Err(Fault::Structure(format!(
            "no place for the supply point {where_to_stand}: give one with --supply X,Y"
        )));
    }
    let last = route.points().last().map_or(first, |point| Coord {
        x: point.x,
        y: point.y,
    });
    // The first point second: its cost is the old rule's.
    let mut references = vec![candidates::spray_centroid(route).unwrap_or(first), first];
    if (last.x - first.x).hypot(last.y - first.y) > search::MIN_SEPARATION_M {
        references.push(last);
    }

    let field_anchors: Vec<Coord<f64>> = if farm.fields.len() > 1 {
        farm.fields
            .iter()
            .filter_map(|field| geo::Centroid::centroid(&field.polygon))
            .map(|centre| centre.0)
            .collect()
    } else {
        Vec::new()
    };
    let ranked = search::search(
        &coarse.points,
        coarse.spacing_m,
        &references,
        &field_anchors,
        &standing,
        cost,
        listed,
    )
    .ok_or_else(|| {
        Fault::Structure(format!(
            "no place for the supply point {where_to_stand} from which one tank and one battery fly every sortie (or the terrain has no heights there): give one with --supply X,Y"
        ))
    })?;
    Ok(AutoChoice {
        first_point: ScoredPoint {
            point: first,
            cost_s: ranked.reference_costs[1],
        },
        first_point_stands: standing.allows(first),
        first_point_moved: if standing.allows(first) {
            None
        } else {
            ranked.settled_references[1]
        },
        first_point_moved_unlevel: None,
        evaluations: ranked.evaluations,
        ranked: ranked.points,
        listed,
        on_access: standing.on_access(),
        margin_m: standing.margin_m,
        reach_m: standing.reach_m.is_finite().then_some(standing.reach_m),
        evaluator: cost.describe(),
    })
}

#[cfg(test)]
mod tests {
    use super::evaluator::FixedRouteSplit;
    use super::*;
    use crate::coverage::{plan_coverage, CoverageSettings};
    use crate::model::{Access, AccessShape, Field, Obstacle, Vehicle};
    use crate::sequence::{route, Sequencer, TransferModel};
    use crate::sortie::route::Speeds;
    use crate::sortie::SortieModel;
    use crate::terrain::Flat;
    use geo::{LineString, Polygon};

    fn rectangle(x0: f64, y0: f64, width: f64, height: f64) -> LineString<f64> {
        LineString::from(vec![
            (x0, y0),
            (x0 + width, y0),
            (x0 + width, y0 + height),
            (x0, y0 + height),
            (x0, y0),
        ])
    }

    fn farm_of(fields: Vec<Field>) -> Farm {
        Farm::local("test", fields)
    }

    /// The route planned without a start point (greedy: quick in a debug build).
    fn free_route(farm: &Farm) -> WorkRoute {
        route_from(farm, None)
    }

    /// The route planned from `start`, or without a start point.
    fn route_from(farm: &Farm, start: Option<GroundPoint>) -> WorkRoute {
        let vehicle = Vehicle::default();
        let settings = CoverageSettings {
            headland_passes: 0,
            ..CoverageSettings::default()
        };
        let coverage = plan_coverage(farm, &Flat::new(0.0), &vehicle, &settings).unwrap();
        let transfers = TransferModel::new(farm, vehicle.safe_height_m);
        let start = start.map_or(
            crate::sequence::tour::Start::Closed,
            crate::sequence::tour::Start::Fixed,
        );
        let flight = route(&coverage, &transfers, start, &Sequencer::Greedy);
        let speeds = Speeds::of(&vehicle);
        WorkRoute::from_route(&flight, speeds)
    }

    fn flat(_x: f64, _y: f64) -> Option<f64> {
        Some(0.0)
    }

    fn auto_on(farm: &Farm, listed: usize) -> (WorkRoute, AutoChoice) {
        auto_along(farm, free_route(farm), listed)
    }

    fn auto_along(farm: &Farm, work_route: WorkRoute, listed: usize) -> (WorkRoute, AutoChoice) {
        let vehicle = Vehicle::default();
        let model = SortieModel::new(&vehicle, work_route.points()[0], 36.0);
        let evaluator = FixedRouteSplit::new(&work_route, model, true, &flat);
        let choice = choose_auto(farm, &work_route, &evaluator, listed).unwrap();
        (work_route, choice)
    }

    #[test]
    fn supply_values_parse_and_faults_are_named() {
        assert_eq!("auto".parse(), Ok(SupplyValue::Auto { listed: 0 }));
        assert_eq!(" Auto:3 ".parse(), Ok(SupplyValue::Auto { listed: 3 }));
        assert_eq!("12.5,-3".parse(), Ok(SupplyValue::Point([12.5, -3.0])));
        for (text, fault) in [
            ("auto:0", "'0' is not a count"),
            ("auto:x", "'x' is not a count"),
            ("1,2,3", "expected auto"),
            ("north", "expected auto"),
            ("1,nan", "not two finite numbers"),
        ] {
            let message = text.parse::<SupplyValue>().unwrap_err();
            assert!(message.contains(fault), "{text}: {message}");
        }
    }

    #[test]
    fn candidates_stand_outside_fields_holes_and_obstacles_on_random_farms() {
        for seed in 1..=6 {
            let mut farm = crate::bench::farms::irregular_farm(seed, 40, 5.0);
            let bounds = farm.bounds();
            // A shed between the first two fields' boxes, outside every field.
            farm.obstacles.push(Obstacle {
                name: "shed".into(),
                polygon: Polygon::new(
                    rectangle(bounds.min().x - 60.0, bounds.min().y - 60.0, 30.0, 30.0),
                    vec![],
                ),
            });
            let work_route = free_route(&farm);
            let standing = standing::StandingRule::new(&farm);
            let coarse = candidates::coarse(&farm, &work_route, &standing);
            assert!(coarse.points.len() > 50, "seed {seed}");
            for point in &coarse.points {
                let at = geo::Point::from(*point);
                for field in &farm.fields {
                    let exterior = Polygon::new(field.polygon.exterior().clone(), vec![]);
                    assert!(
                        !geo::Intersects::intersects(&exterior, &at),
                        "seed {seed}: {point:?} in field {} or a hole",
                        field.name
                    );
                    let gap = geo::Distance::distance(&geo::Euclidean, &exterior, &at);
                    assert!(gap >= standing::MARGIN_M - 1e-6, "seed {seed}: {gap}");
                }
                assert!(
                    !geo::Intersects::intersects(&farm.obstacles[0].polygon, &at),
                    "seed {seed}: {point:?} in the shed"
                );
                assert!(standing.distance_to_fields_m(*point) <= standing::REACH_M + 1e-6);
            }
        }
    }

    #[test]
    fn with_access_features_every_candidate_and_the_choice_stand_on_them() {
        let mut farm = farm_of(vec![Field::new(
            "F",
            Polygon::new(rectangle(0.0, 0.0, 150.0, 100.0), vec![]),
        )]);
        farm.access = vec![
            Access {
                name: "track".into(),
                shape: AccessShape::Line(LineString::from(vec![(-30.0, -20.0), (-30.0, 300.0)])),
            },
            Access {
                name: "yard".into(),
                shape: AccessShape::Area(Polygon::new(rectangle(160.0, 40.0, 20.0, 20.0), vec![])),
            },
        ];
        let (work_route, choice) = auto_on(&farm, 3);
        let standing = standing::StandingRule::new(&farm);
        let coarse = candidates::coarse(&farm, &work_route, &standing);
        let on = |point: Coord<f64>| {
            (point.x + 30.0).abs() < standing::ON_LINE_M
                || ((160.0..=180.0).contains(&point.x) && (40.0..=60.0).contains(&point.y))
        };
        assert!(coarse.points.iter().all(|&point| on(point)));
        assert!(choice.on_access);
        for scored in &choice.ranked {
            assert!(on(scored.point), "{:?}", scored.point);
        }
        // The yard, beside the field's middle, beats a track 30 m off its short side.
        let best = choice.best().point;
        assert!((160.0..=180.0).contains(&best.x), "{best:?}");
    }

    /// Decision 0029: where the cheapest place is on a slope, `auto` on level ground stands
    /// on level ground, at a cost a little above it.
    #[test]
    fn on_level_ground_the_choice_avoids_a_slope() {
        let farm = farm_of(vec![Field::new(
            "F",
            Polygon::new(rectangle(0.0, 0.0, 150.0, 100.0), vec![]),
        )]);
        let work_route = free_route(&farm);
        let vehicle = Vehicle::default();
        let model = SortieModel::new(&vehicle, work_route.points()[0], 36.0);
        let evaluator = FixedRouteSplit::new(&work_route, model, true, &flat);
        let free = choose_auto(&farm, &work_route, &evaluator, 0).unwrap();
        let best = free.best().point;
        // A bank rising 30 % within 40 m of that point, level beyond.
        let bank = move |x: f64, y: f64| {
            let distance = (x - best.x).hypot(y - best.y);
            Some(if distance < 40.0 {
                0.3 * (x - best.x)
            } else {
                0.0
            })
        };
        let level = level::OnLevelGround {
            inner: &evaluator,
            ground: &bank,
        };
        let chosen = choose_auto(&farm, &work_route, &level, 0).unwrap().best();
        let slope = level::slope_at(&bank, chosen.point).unwrap();
        assert!(slope <= level::MAX_SLOPE, "{chosen:?} on {slope}");
        assert!(chosen.cost_s >= free.best().cost_s - 1e-9);
        assert!(chosen.cost_s.is_finite());
    }

    #[test]
    fn a_tiny_far_field_does_not_draw_the_point_from_the_large_one() {
        let farm = farm_of(vec![
            Field::new(
                "tiny",
                Polygon::new(rectangle(0.0, 0.0, 20.0, 20.0), vec![]),
            ),
            Field::new(
                "large",
                Polygon::new(rectangle(1100.0, 0.0, 300.0, 250.0), vec![]),
            ),
        ]);
        // The farm: the route begins at the tiny field, so the old rule put the supply
        // point there, a kilometre from most of the work.
        let at_tiny = GroundPoint {
            x: -10.0,
            y: -10.0,
            ground_m: 0.0,
        };
        let (work_route, choice) = auto_along(&farm, route_from(&farm, Some(at_tiny)), 0);
        assert!(work_route.points()[0].x < 20.0 + 1e-9);
        let best = choice.best();
        let standing = standing::StandingRule::new(&farm);
        assert_eq!(standing.nearest_field(best.point), 1, "{:?}", best.point);
        assert!(standing.distance_to_fields_m(best.point) < 20.0);
        // Every return saved flies over 2 km less: the old rule costs far more.
        assert!(
            choice.first_point.cost_s > best.cost_s + 1000.0,
            "{choice:?}"
        );
    }

    #[test]
    fn the_choice_is_deterministic_and_lists_distinct_candidates_best_first() {
        let farm = crate::bench::farms::irregular_farm(3, 60, 5.0);
        let (_, first) = auto_on(&farm, 4);
        let (_, again) = auto_on(&farm, 4);
        assert_eq!(first, again);
        assert!(first.ranked.len() >= 2 && first.ranked.len() <= 4);
        for pair in first.ranked.windows(2) {
            assert!(pair[0].cost_s <= pair[1].cost_s);
            assert!(
                (pair[0].point.x - pair[1].point.x).hypot(pair[0].point.y - pair[1].point.y)
                    >= search::SAME_PLACE_M
            );
        }
    }

    #[test]
    fn the_surrogate_is_exact_at_its_point_and_never_below_the_split_elsewhere() {
        let farm = crate::bench::farms::irregular_farm(2, 60, 5.0);
        let work_route = free_route(&farm);
        let vehicle = Vehicle::default();
        let model = SortieModel::new(&vehicle, work_route.points()[0], 36.0);
        let evaluator = FixedRouteSplit::new(&work_route, model, true, &flat);
        let around = candidates::spray_centroid(&work_route).unwrap();
        let (cost, surrogate) = evaluator.cost_and_surrogate(around);
        assert!((surrogate(around) - cost).abs() < 1e-6, "{cost}");
        for (dx, dy) in [(-80.0, 0.0), (0.0, 60.0), (150.0, -40.0), (30.0, 30.0)] {
            let point = Coord {
                x: around.x + dx,
                y: around.y + dy,
            };
            let estimate = surrogate(point);
            if estimate.is_finite() {
                assert!(estimate >= evaluator.cost_s(point) - 1e-6, "{point:?}");
            }
        }
    }

    /// A cost whose surrogate is blind beyond a metre of its point, as the split's is where
    /// every sortie is at the battery's limit.
    struct Blind(Coord<f64>);

    impl SupplyCost for Blind {
        fn cost_s(&self, point: Coord<f64>) -> f64 {
            (point.x - self.0.x).hypot(point.y - self.0.y)
        }

        fn cost_and_surrogate(&self, around: Coord<f64>) -> (f64, Surrogate<'_>) {
            let cost = self.cost_s(around);
            let near = move |point: Coord<f64>| {
                if (point.x - around.x).hypot(point.y - around.y) <= 1.0 {
                    cost
                } else {
                    f64::INFINITY
                }
            };
            (cost, Box::new(near))
        }
    }

    #[test]
    fn a_blind_surrogate_still_finds_a_place_on_the_far_side() {
        // The best place is west of the field, far from every reference; the anchors'
        // surrogates see nothing beyond a metre, so only the spread anchors can find it
        // (a 30 L tank on the Christmas Island fields found no place before them).
        let farm = farm_of(vec![Field::new(
            "F",
            Polygon::new(rectangle(0.0, 0.0, 100.0, 100.0), vec![]),
        )]);
        let work_route = free_route(&farm);
        let target = Coord { x: -40.0, y: 50.0 };
        let choice = choose_auto(&farm, &work_route, &Blind(target), 0).unwrap();
        let best = choice.best();
        assert!(best.point.x < 0.0, "{best:?}");
        assert!(best.cost_s < 60.0, "{best:?}");
    }

    /// A cost whose surrogate misleads: it claims every point away from its own is cheaper,
    /// so a pattern search on it always ends dearer by the cost itself.
    struct Misleading(Coord<f64>);

    impl SupplyCost for Misleading {
        fn cost_s(&self, point: Coord<f64>) -> f64 {
            (point.x - self.0.x).hypot(point.y - self.0.y)
        }

        fn cost_and_surrogate(&self, around: Coord<f64>) -> (f64, Surrogate<'_>) {
            let cost = self.cost_s(around);
            let away = move |point: Coord<f64>| {
                cost - 0.5 * (point.x - around.x).hypot(point.y - around.y)
            };
            (cost, Box::new(away))
        }
    }

    #[test]
    fn the_choice_is_never_dearer_than_the_place_beside_the_old_rules_point() {
        // The route's first point lies on the crop, where no vehicle stands; the old rule as
        // an operator could follow it is the nearest place one can. A cost that only wants
        // the first point, with a surrogate that leads every pattern search astray, still
        // chooses that place: the search weighs it by the cost itself.
        let farm = farm_of(vec![Field::new(
            "F",
            Polygon::new(rectangle(0.0, 0.0, 100.0, 100.0), vec![]),
        )]);
        let work_route = free_route(&farm);
        let first = work_route.points()[0];
        let first = Coord {
            x: first.x,
            y: first.y,
        };
        let choice = choose_auto(&farm, &work_route, &Misleading(first), 0).unwrap();
        assert!(!choice.first_point_stands);
        let moved = choice
            .first_point_moved
            .expect("a place beside the first point");
        let standing = StandingRule::new(&farm);
        assert!(standing.allows(moved.point), "{moved:?}");
        assert!(choice.best().cost_s <= moved.cost_s, "{choice:?}");
        // And on random farms with the default evaluator.
        for seed in 1..=4 {
            let farm = crate::bench::farms::irregular_farm(seed, 40, 5.0);
            let (_, choice) = auto_on(&farm, 0);
            assert_eq!(
                choice.first_point_moved.is_some(),
                !choice.first_point_stands,
                "seed {seed}"
            );
            if let Some(moved) = choice.first_point_moved {
                assert!(
                    choice.best().cost_s <= moved.cost_s,
                    "seed {seed}: {choice:?}"
                );
            }
        }
    }

    #[test]
    fn any_function_of_the_point_is_an_evaluator() {
        // A cost that only wants to be near (20, 50), inside the field: the nearest place a
        // vehicle can stand is 5 m out from the field's west edge.
        let farm = farm_of(vec![Field::new(
            "F",
            Polygon::new(rectangle(0.0, 0.0, 100.0, 100.0), vec![]),
        )]);
        let work_route = free_route(&farm);
        let target = |point: Coord<f64>| (point.x - 20.0).hypot(point.y - 50.0);
        let choice = choose_auto(&farm, &work_route, &target, 0).unwrap();
        let best = choice.best().point;
        assert!(
            (best.x + standing::MARGIN_M).abs() < 0.5 && (best.y - 50.0).abs() < 2.0,
            "{best:?}"
        );
        assert_eq!(choice.evaluator, "a cost given by the caller");
    }
}
