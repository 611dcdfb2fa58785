//! The verdict of the preflight: each check's worst figure against its limit, the failure
//! lines (a few per check, then a count), and the figures per field and sortie as flown.

use serde::Serialize;

use crate::mission::flight::AltitudeReference;

/// Lines reported per failed check (the count of the rest follows).
const LINES_PER_CHECK: usize = 3;
/// Places of failures one check keeps for the map.
const PLACES_PER_CHECK: usize = 200;

/// One check and its figure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckResult {
    /// The check's name, e.g. "spray height".
    pub name: &'static str,
    /// Whether nothing failed the check.
    pub passed: bool,
    /// The worst figure found, in `unit`.
    pub figure: f64,
    /// The bound it is held to (≥ or ≤ as `rule` says).
    pub limit: f64,
    /// "≥" or "≤": how the figures must compare with `limit`.
    pub rule: &'static str,
    /// The unit of `figure` and `limit`, in words (e.g. "m above the ground", "items").
    pub unit: &'static str,
}

/// Share of a field's ground sprayed twice from which the summary names it.
pub const DOUBLE_DOSE_NOTED: f64 = 0.2;

/// A field's coverage as flown.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FieldFlown {
    /// The field's name.
    pub name: String,
    /// Area of the field's sprayable region (within the margins), m².
    pub sprayable_area_m2: f64,
    /// Share covered as flown of the ground that is covered or could be (covered + missed),
    /// 0..1 (1 when it is empty).
    pub covered_fraction: f64,
    /// The share the field must reach, 0..1.
    pub required_fraction: f64,
    /// Ground a swath can reach under no strip, m².
    pub missed_m2: f64,
    /// Ground narrower than a swath (sharp tips, necks between holes) under no strip, m²:
    /// it could only be sprayed by spraying outside too.
    pub unreachable_m2: f64,
    /// Sprayable area under two strips or more, m².
    pub double_sprayed_m2: f64,
    /// Litres put on the double-sprayed area beyond one dose (the vehicle's application rate
    /// × `double_sprayed_m2`; ground under three strips counts once), `null` without a rate.
    pub over_applied_litres: Option<f64>,
}

/// A sortie as flown.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SortieFlown {
    /// The sortie's number, from 1, in the order of the `sortie_NN.plan` names.
    pub sortie: usize,
    /// The `.plan` file flown.
    pub file: String,
    /// Number of mission items in the file.
    pub items: usize,
    /// Horizontal distance flown with the sprayer on, metres.
    pub spray_m: f64,
    /// Spray distance as a share of one tank's (none: the vehicle gives no tank figure).
    pub tank_fraction: Option<f64>,
    /// Flight time as written, seconds: each leg at its speed, or at the climb speed when longer.
    pub flight_time_s: f64,
    /// Flight time as a share of the battery's endurance.
    pub battery_fraction: f64,
    /// Largest gap between the height above ground on spray legs and the spray height, m.
    pub worst_spray_height_error_m: f64,
    /// Least margin above h over the highest ground under a transit leg, m (none: no transit).
    pub least_transit_margin_m: Option<f64>,
    /// Horizontal metres of spray legs where ArduPilot's sprayer stops its pump: ground so
    /// steep that the climb holds the vehicle under `SPRAY_SPEED_MIN` (1 m/s) for longer than
    /// its shut-off delay (1 s). Not sprayed; the coverage as flown counts them missed.
    pub pump_stopped_m: f64,
}

/// The verdict of the preflight, as `report.json` carries it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verdict {
    /// Whether every check passed.
    pub safe: bool,
    /// The altitude reference the files were checked against.
    pub altitude_reference: AltitudeReference,
    /// Every check, in a fixed order.
    pub checks: Vec<CheckResult>,
    /// One line per failure: sortie, item, place and what is wrong.
    pub failures: Vec<String>,
    /// Coverage as flown, one entry per field in the farm's order.
    pub fields: Vec<FieldFlown>,
    /// Area under at least one strip, m².
    pub sprayed_area_m2: f64,
    /// Sprayed area outside the ground that may be sprayed (off the fields, over holes or
    /// obstacles), m².
    pub sprayed_outside_m2: f64,
    /// `sprayed_outside_m2` as a share of `sprayed_area_m2`, 0..1 (0 when nothing is sprayed).
    pub sprayed_outside_fraction: f64,
    /// The figures of each sortie whose file could be flown, by sortie number.
    pub sorties: Vec<SortieFlown>,
    /// Least height above the ground of any airborne sample (takeoff and landing aside), m.
    pub lowest_clearance_m: f64,
    /// Per field, the ground no swath reaches and the reachable ground missed as flown, for
    /// the map and `plan.geojson` (not in `report.json`: `unreachable_m2` and `missed_m2`
    /// give their areas).
    #[serde(skip)]
    pub ground: crate::coverage::region::GroundPatches,
}

impl Verdict {
    /// The summary line and one line per check, as `agripath check` prints them.
    pub fn to_text(&self) -> String {
        let mut text = self.summary() + "\n";
        for check in &self.checks {
            text += &format!(
                "  {:<20} {:>5}  {} {} (limit {} {})\n",
                check.name,
                if check.passed { "ok" } else { "FAIL" },
                check.figure,
                check.unit,
                check.rule,
                check.limit
            );
        }
        text
    }

    /// Share of all fields' ground covered as flown, of what is covered or could be
    /// (covered + missed: ground narrower than a swath left unsprayed is not counted), 0..1.
    pub fn covered_fraction(&self) -> f64 {
        let (mut covered, mut could_be) = (0.0, 0.0);
        for field in &self.fields {
            let reachable = (field.sprayable_area_m2 - field.unreachable_m2).max(0.0);
            covered += field.covered_fraction * reachable;
            could_be += reachable;
        }
        if could_be > 0.0 {
            covered / could_be
        } else {
            1.0
        }
    }

    /// The fields of which at least [`DOUBLE_DOSE_NOTED`] of the ground is sprayed twice as
    /// flown, most first (at most three named): a strip under two swaths wide is crossed by the
    /// passes along both its sides, and `report.json` alone said so (the eleventh trial's
    /// 5.5-7 m strips, 42-80 % double-sprayed, while the table's planned overlap read 0).
    fn double_dose_note(&self) -> String {
        double_dose_note(&self.fields)
    }

    /// The one line of the printed summary.
    pub fn summary(&self) -> String {
        let coverage = self
            .fields
            .iter()
            .map(|field| field.covered_fraction)
            .fold(f64::INFINITY, f64::min);
        // Two different areas, both named: the reachable ground the files miss as flown (what
        // the coverage figure counts) and the ground no swath could reach (left out of it).
        let missed: f64 = self.fields.iter().map(|field| field.missed_m2).sum();
        let unreachable: f64 = self.fields.iter().map(|field| field.unreachable_m2).sum();
        let missed = if missed >= 0.05 {
            format!(", {missed:.1} m² missed as flown")
        } else {
            String::new()
        };
        let sprayable: f64 = self
            .fields
            .iter()
            .map(|field| field.sprayable_area_m2)
            .sum();
        // The share too: on small fields it is not small (60 squares of 10 m read "100.00%"
        // with 7.7 % of their ground left out, the fourth trial).
        let unreachable = if unreachable >= 0.05 {
            format!(
                " ({unreachable:.1} m², {:.1}% of the fields, of tips, corners and necks no swath reaches left out of that figure)",
                100.0 * unreachable / sprayable.max(f64::MIN_POSITIVE)
            )
        } else {
            String::new()
        };
        let doubled = self.double_dose_note();
        let stopped: f64 = self
            .sorties
            .iter()
            .map(|sortie| sortie.pump_stopped_m)
            .sum();
        let stopped = if stopped >= 0.05 {
            format!(" (with {stopped:.1} m of spray legs where ArduPilot stops the pump: too steep to cross at its SPRAY_SPEED_MIN)")
        } else {
            String::new()
        };
        format!(
            "preflight ({} altitudes, read back from {} mission file(s)): {}; coverage as flown {:.2}% in the least covered field{missed}{stopped}{unreachable}{doubled}, sprayed outside {:.3}%, lowest clearance {:.2} m (spray legs included; beside a slope where nearer than 0.5 m)",
            self.altitude_reference.key(),
            self.sorties.len(),
            if self.safe {
                "SAFE".to_string()
            } else {
                format!(
                    "UNSAFE ({} failed)",
                    self.checks.iter().filter(|c| !c.passed).count()
                )
            },
            100.0 * if coverage.is_finite() { coverage } else { 0.0 },
            100.0 * self.sprayed_outside_fraction,
            self.lowest_clearance_m
        )
    }
}

/// Collects the figures and failure lines of one check.
pub(super) struct Tally {
    name: &'static str,
    rule: &'static str,
    unit: &'static str,
    pub(super) limit: f64,
    worst: Option<f64>,
    lines: Vec<String>,
    failed: usize,
    /// Where the failures recorded with a place lie (plan metres), at most
    /// [`PLACES_PER_CHECK`]: the map marks them.
    places: Vec<[f64; 2]>,
    /// Whether the check's figure is the count of failures (samples inside, outside), not
    /// the worst figure recorded.
    counts: bool,
}

/// The mission size check, when the vehicle states its autopilot's limit
/// (`mission_items_max`).
pub(super) fn mission_size(limit: Option<u32>) -> Option<Tally> {
    limit.map(|items| {
        Tally::new(
            "mission size",
            "≤",
            f64::from(items),
            "items, home included",
        )
    })
}

/// Records sortie `sortie`'s mission, file `file`, of `items` items (its home included, as
/// the autopilot stores it) against the autopilot's limit, when there is one.
pub(super) fn record_mission(size: &mut Option<Tally>, sortie: usize, file: &str, items: usize) {
    if let Some(size) = size {
        let limit = size.limit;
        size.record(items as f64, items as f64 > limit, || {
            format!(
                "sortie {sortie}: {file} has {items} mission items, home included, and the autopilot holds {limit:.0} (mission_items_max): the upload fails, or older ArduPilot drops the last items; a larger --terrain-tolerance writes fewer waypoints over the ground"
            )
        });
    }
}

impl Tally {
    pub(super) fn new(
        name: &'static str,
        rule: &'static str,
        limit: f64,
        unit: &'static str,
    ) -> Self {
        Self {
            name,
            rule,
            unit,
            limit,
            worst: None,
            lines: Vec::new(),
            failed: 0,
            places: Vec::new(),
            counts: false,
        }
    }

    /// The same check, whose figure is how many samples failed (until 2026-12-07 the table
    /// read "FAIL 1 samples inside" over 211 failures listed).
    pub(super) fn counting(mut self) -> Self {
        self.counts = true;
        self
    }

    /// Records a figure; `bad` says whether it breaks the rule, `line` what to print then.
    pub(super) fn record(&mut self, figure: f64, bad: bool, line: impl FnOnce() -> String) {
        let better = |old: f64| match self.rule {
            "≥" => figure < old,
            _ => figure > old,
        };
        if self.worst.is_none_or(better) {
            self.worst = Some(figure);
        }
        if bad {
            self.failed += 1;
            if self.lines.len() < LINES_PER_CHECK {
                self.lines.push(line());
            }
        }
    }

    /// As [`Self::record`], at the plan's place `(x, y)`, which the map marks when it fails.
    pub(super) fn record_at(
        &mut self,
        (x, y): (f64, f64),
        figure: f64,
        bad: bool,
        line: impl FnOnce() -> String,
    ) {
        if bad && self.places.len() < PLACES_PER_CHECK {
            self.places.push([x, y]);
        }
        self.record(figure, bad, line);
    }

    /// A failure with no figure of its own (a file that cannot be read, a frame): the figure
    /// is then the count of failures, so the check never reads "FAIL 0 faults".
    pub(super) fn fail(&mut self, line: String) {
        self.failed += 1;
        self.worst = Some(self.worst.unwrap_or(0.0).max(self.failed as f64));
        if self.lines.len() < LINES_PER_CHECK {
            self.lines.push(line);
        }
    }

    /// Adds the check's figure to `checks`, its failure lines to `failures` and the places
    /// of its failures to `places`.
    pub(super) fn finish(
        self,
        checks: &mut Vec<CheckResult>,
        failures: &mut Vec<String>,
        places: &mut Vec<[f64; 2]>,
    ) {
        places.extend(self.places);
        checks.push(CheckResult {
            name: self.name,
            passed: self.failed == 0,
            figure: if self.counts {
                self.failed as f64
            } else {
                self.worst.unwrap_or(self.limit)
            },
            limit: self.limit,
            rule: self.rule,
            unit: self.unit,
        });
        failures.extend(self.lines);
        if self.failed > LINES_PER_CHECK {
            failures.push(format!(
                "{}: {} more failure(s) like these",
                self.name,
                self.failed - LINES_PER_CHECK
            ));
        }
    }
}

/// [`Verdict::double_dose_note`] of `fields`.
fn double_dose_note(fields: &[FieldFlown]) -> String {
    let mut doubled: Vec<(&str, f64)> = fields
        .iter()
        .filter(|field| field.sprayable_area_m2 > 0.0)
        .map(|field| {
            let share = field.double_sprayed_m2 / field.sprayable_area_m2;
            (field.name.as_str(), share)
        })
        .filter(|(_, share)| *share >= DOUBLE_DOSE_NOTED)
        .collect();
    if doubled.is_empty() {
        return String::new();
    }
    doubled.sort_by(|a, b| b.1.total_cmp(&a.1));
    let named: Vec<String> = doubled
        .iter()
        .take(3)
        .map(|(name, share)| format!("{:.0}% of '{name}'", 100.0 * share))
        .collect();
    let more = match doubled.len() {
        0..=3 => String::new(),
        4 => " and of 1 more field".to_string(),
        count => format!(" and of {} more fields", count - 3),
    };
    format!(", sprayed twice as flown: {}{more}", named.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field(name: &str, double_sprayed_m2: f64) -> FieldFlown {
        FieldFlown {
            name: name.into(),
            sprayable_area_m2: 1000.0,
            covered_fraction: 1.0,
            required_fraction: 0.99,
            missed_m2: 0.0,
            unreachable_m2: 0.0,
            double_sprayed_m2,
            over_applied_litres: None,
        }
    }

    #[test]
    fn fields_sprayed_twice_over_a_fifth_are_named_most_first() {
        assert_eq!(double_dose_note(&[field("a", 199.0), field("b", 0.0)]), "");
        let fields = [
            field("a", 300.0),
            field("b", 800.0),
            field("c", 100.0),
            field("d", 650.0),
            field("e", 420.0),
            field("f", 200.0),
        ];
        assert_eq!(
            double_dose_note(&fields),
            ", sprayed twice as flown: 80% of 'b', 65% of 'd', 42% of 'e' and of 2 more fields"
        );
    }
}
