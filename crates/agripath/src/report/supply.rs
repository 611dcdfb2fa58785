//! The `supply` object of `report.json`: where the supply point is, which rule chose it, and
//! for `auto` what it saves against the old rule (the first point of the route planned
//! without a start point), both scored by the same evaluator (docs/decisions/0016).

use serde::Serialize;

use crate::model::CoordinateSystem;
use crate::numbers::round;
use crate::supply::{ScoredPoint, SupplyChoice};

/// A point in planning metres, and in lon/lat when the farm is geographic.
#[derive(Debug, Clone, Serialize)]
pub struct ReportedPoint {
    /// [x, y] in planning metres (the UTM zone's for lon/lat input).
    pub point_m: [f64; 2],
    /// [lon, lat] when the field file was in lon/lat, else `null`.
    pub lon_lat: Option<[f64; 2]>,
}

impl ReportedPoint {
    fn new(x: f64, y: f64, frame: CoordinateSystem) -> Self {
        Self {
            point_m: [round(x, 1e-6), round(y, 1e-6)],
            lon_lat: match frame {
                CoordinateSystem::Local => None,
                CoordinateSystem::Utm(_) => {
                    let (lon, lat) = frame.to_input(x, y);
                    Some([round(lon, 1e-9), round(lat, 1e-9)])
                }
            },
        }
    }
}

/// A candidate of `auto:N` with its cost.
#[derive(Debug, Clone, Serialize)]
pub struct CandidateReport {
    /// Where it stands.
    #[serde(flatten)]
    pub at: ReportedPoint,
    /// Non-spray seconds by the evaluator; `null` where the plan cannot be flown from it (a
    /// sortie out of the battery's reach).
    pub cost_s: Option<f64>,
}

impl CandidateReport {
    fn new(scored: &ScoredPoint, frame: CoordinateSystem) -> Self {
        Self {
            at: ReportedPoint::new(scored.point.x, scored.point.y, frame),
            cost_s: scored
                .cost_s
                .is_finite()
                .then(|| round(scored.cost_s, 1e-3)),
        }
    }
}

/// The old rule's point moved to the nearest place a vehicle can stand, and the saving
/// against it.
#[derive(Debug, Clone, Serialize)]
pub struct MovedReport {
    /// Where it stands, and its cost.
    #[serde(flatten)]
    pub scored: CandidateReport,
    /// Its cost less the chosen point's, seconds: ≥ 0, as the search weighs the place,
    /// unless it is steeper than `auto` stands on (decision 0029), where it is scored on any
    /// ground and may be cheaper than the level place chosen; `null` where the plan cannot be
    /// flown from it.
    pub saving_s: Option<f64>,
    /// The saving as a share of its cost, percent (`null` with `saving_s`).
    pub saving_percent: Option<f64>,
    /// Why no vehicle stands level there (its slope above what `auto` stands on, decision
    /// 0029), when the chosen point is level and it is not; `null` otherwise. The summary
    /// then calls it the nearest place outside the fields, not the nearest place one can.
    pub unlevel: Option<String>,
}

/// `old - best` in seconds and as a share of `old`, percent, rounded for the report; `None`
/// where `old` is not a cost (the plan cannot be flown from that point).
fn saving(old: f64, best: f64) -> Option<(f64, f64)> {
    (old.is_finite() && best.is_finite() && old > 0.0).then(|| {
        let saving = old - best;
        (round(saving, 1e-3), round(100.0 * saving / old, 1e-3))
    })
}

/// The `auto` rule's figures.
#[derive(Debug, Clone, Serialize)]
pub struct AutoReport {
    /// What the evaluator measures.
    pub evaluator: String,
    /// The old rule's point: the first point of the route planned without a start point.
    pub first_point: CandidateReport,
    /// Whether a vehicle could stand there (a pass end lies on or in a field, as a rule).
    pub first_point_stands: bool,
    /// The old rule's cost less the chosen point's, seconds (≥ 0 when auto wins); `null`
    /// where the plan cannot be flown from the old rule's point.
    pub saving_s: Option<f64>,
    /// The saving as a share of the old rule's cost, percent (`null` with `saving_s`).
    pub saving_percent: Option<f64>,
    /// Where no vehicle can stand at the old rule's point: the nearest place one can, its
    /// cost and the saving against it (the old rule as an operator could follow it;
    /// docs/decisions/0031); `null` when the point stands, or when no place a vehicle can
    /// stand was found near it.
    pub first_point_moved: Option<MovedReport>,
    /// Whether the candidates stood on the file's access features.
    pub on_access: bool,
    /// Distance kept from fields, holes and obstacles, metres (0 on access features).
    pub margin_m: f64,
    /// Farthest from the nearest field, metres (`null` on access features: no limit).
    pub reach_m: Option<f64>,
    /// Times the evaluator's cost was computed.
    pub evaluations: usize,
    /// With `auto:N`: the N best places found, best first, with their costs (empty otherwise).
    pub candidates: Vec<CandidateReport>,
}

/// The `supply` object.
#[derive(Debug, Clone, Serialize)]
pub struct SupplyReport {
    /// `marker`, `given` or `auto`.
    pub rule: &'static str,
    /// The supply point.
    #[serde(flatten)]
    pub at: ReportedPoint,
    /// Its ground height, metres.
    pub ground_m: f64,
    /// For `auto`: its cost by the evaluator (on the route planned without a start point),
    /// seconds; `null` for a point marked or given (not searched).
    pub cost_s: Option<f64>,
    /// The same measure on the route as planned from the point (re-ordered from it), seconds.
    pub planned_cost_s: f64,
    /// For `auto`: the search's figures.
    pub auto: Option<AutoReport>,
    /// For a point marked or given where `auto` would not stand (in or near a field, hole or
    /// obstacle, or beyond its reach of the fields): why, in words; `null` otherwise.
    pub warning: Option<String>,
}

impl SupplyReport {
    /// The report of `choice` in `frame`; `planned_cost_s` is the measure on the route as
    /// planned from it.
    pub fn new(choice: &SupplyChoice, frame: CoordinateSystem, planned_cost_s: f64) -> Self {
        let auto = choice.auto.as_ref().map(|auto| {
            let best = auto.best().cost_s;
            let first_saving = saving(auto.first_point.cost_s, best);
            AutoReport {
                evaluator: auto.evaluator.to_string(),
                first_point: CandidateReport::new(&auto.first_point, frame),
                first_point_stands: auto.first_point_stands,
                saving_s: first_saving.map(|(seconds, _)| seconds),
                saving_percent: first_saving.map(|(_, percent)| percent),
                first_point_moved: auto.first_point_moved.map(|moved| {
                    let moved_saving = saving(moved.cost_s, best);
                    MovedReport {
                        unlevel: auto.first_point_moved_unlevel.clone(),
                        scored: CandidateReport::new(&moved, frame),
                        saving_s: moved_saving.map(|(seconds, _)| seconds),
                        saving_percent: moved_saving.map(|(_, percent)| percent),
                    }
                }),
                on_access: auto.on_access,
                margin_m: auto.margin_m,
                reach_m: auto.reach_m,
                evaluations: auto.evaluations,
                candidates: if auto.listed > 0 {
                    auto.ranked
                        .iter()
                        .map(|scored| CandidateReport::new(scored, frame))
                        .collect()
                } else {
                    Vec::new()
                },
            }
        });
        Self {
            rule: choice.source.key(),
            at: ReportedPoint::new(choice.point.x, choice.point.y, frame),
            ground_m: round(choice.point.ground_m, 1e-4),
            cost_s: choice
                .auto
                .as_ref()
                .map(|auto| round(auto.best().cost_s, 1e-3)),
            planned_cost_s: round(planned_cost_s, 1e-3),
            auto,
            warning: choice
                .standing_warning
                .as_ref()
                .map(|why| format!("a vehicle cannot stand at the supply point: {why}")),
        }
    }

    /// The summary's line; `working` is "spraying" or "surveying" ([`crate::model::Vehicle::work_words`]).
    /// For `auto`: the point and what chose it, the two estimates and the saving; the plan's
    /// own time not working is the summary's `total` line (the estimates are made on the
    /// route planned without a start point, so they differ from it: `planned_cost_s`).
    pub fn to_text(&self, working: &str) -> String {
        let place = match self.at.lon_lat {
            Some([lon, lat]) => format!("{lon:.6}, {lat:.6}"),
            None => format!("{:.1}, {:.1} m", self.at.point_m[0], self.at.point_m[1]),
        };
        let warning = self
            .warning
            .as_ref()
            .map(|warning| format!("warning: {warning}\n"))
            .unwrap_or_default();
        match &self.auto {
            Some(auto) => format!(
                "supply point (auto{}): {place}, where the least time is spent not {working}: estimated {:.0} s, against {}{}{}\n{}",
                if auto.on_access { ", on access features" } else { "" },
                self.cost_s.unwrap_or(f64::NAN),
                against(
                    "the route's first point",
                    &format!(
                        "the old rule{}",
                        if auto.first_point_stands {
                            ""
                        } else {
                            ", where no vehicle can stand"
                        }
                    ),
                    &auto.first_point,
                    auto.saving_s.zip(auto.saving_percent)
                ),
                auto.first_point_moved
                    .as_ref()
                    .map(|moved| format!(
                        "; {}",
                        against(
                            if moved.unlevel.is_some() {
                                "the nearest place outside the fields"
                            } else {
                                "the nearest place one can"
                            },
                            moved.unlevel.as_deref().unwrap_or(""),
                            &moved.scored,
                            moved.saving_s.zip(moved.saving_percent)
                        )
                    ))
                    .unwrap_or_default(),
                match auto.candidates.len() {
                    0 => String::new(),
                    1 => "; 1 candidate in report.json".to_string(),
                    2 => "; 2 candidates in report.json, the other on the map as option 2"
                        .to_string(),
                    count => format!(
                        "; {count} candidates in report.json, the others on the map as options 2-{count}"
                    ),
                },
                warning
            ),
            None => format!("supply point ({}): {place}\n{warning}", self.rule),
        }
    }
}

/// "N s from `what` (`why`), S s (P%) saved", or, where the plan cannot be flown from
/// that point, "`what` (`why`), from which a sortie is out of the battery's reach".
fn against(
    what: &str,
    why: &str,
    reference: &CandidateReport,
    saving: Option<(f64, f64)>,
) -> String {
    let why = if why.is_empty() {
        String::new()
    } else {
        format!(" ({why})")
    };
    match (reference.cost_s, saving) {
        (Some(cost_s), Some((saving_s, saving_percent))) => format!(
            "{cost_s:.0} s from {what}{why}, {}",
            saved_or_more(saving_s, saving_percent)
        ),
        _ => format!("{what}{why}, from which a sortie is out of the battery's reach"),
    }
}

/// "N s (P%) saved", or "N s (P%) more" when the saving is negative: under half a second
/// either way reads as a tie, not as "-0 s saved".
fn saved_or_more(saving_s: f64, saving_percent: f64) -> String {
    if saving_s > -0.5 {
        format!(
            "{:.0} s ({:.1}%) saved",
            saving_s.max(0.0),
            saving_percent.max(0.0)
        )
    } else {
        format!("{:.0} s ({:.1}%) more", -saving_s, -saving_percent)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A reference point from which the plan cannot be flown (a sortie out of the battery's
    /// reach, cost +inf) reads as such, with no saving: not "inf s" and "0.0 % saved".
    #[test]
    fn a_point_out_of_reach_has_no_cost_and_no_saving() {
        assert_eq!(saving(f64::INFINITY, 1_000.0), None);
        assert_eq!(saving(1_200.0, 1_000.0), Some((200.0, 16.667)));
        let scored = ScoredPoint {
            point: geo::Coord { x: 1.0, y: 2.0 },
            cost_s: f64::INFINITY,
        };
        let reference = CandidateReport::new(&scored, CoordinateSystem::Local);
        assert_eq!(reference.cost_s, None);
        let text = against("the route's first point", "the old rule", &reference, None);
        assert_eq!(
            text,
            "the route's first point (the old rule), from which a sortie is out of the battery's reach"
        );
        assert!(!text.contains("inf"));
        let reachable = CandidateReport::new(
            &ScoredPoint {
                cost_s: 1_200.0,
                ..scored
            },
            CoordinateSystem::Local,
        );
        assert_eq!(
            against(
                "the nearest place one can",
                "",
                &reachable,
                saving(1_200.0, 1_000.0)
            ),
            "1200 s from the nearest place one can, 200 s (16.7%) saved"
        );
    }
}
