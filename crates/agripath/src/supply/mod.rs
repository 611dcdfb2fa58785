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
//! start point) is scored by the same evaluator, so the saving is like for like.

pub mod candidates;
pub mod evaluator;
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
        evaluations: ranked.evaluations,
        ranked: ranked.points,
        listed,
        on_access: standing.on_access(),
        margin_m: standing.margin_m,
        reach_m: standing.reach_m.is_finite().then_some(standing.reach_m),
        evaluator: cost.describe(),
    })
}
