//! The verdict of the preflight: each check's worst figure against its limit, the failure
//! lines (a few per check, then a count), and the figures per field and sortie as flown.

use serde::Serialize;

use crate::mission::flight::AltitudeReference;

/// Lines reported per failed check (the count of the rest follows).
const LINES_PER_CHECK: usize = 3;

/// One check and its figure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckResult {
    pub name: &'static str,
    pub passed: bool,
    /// The worst figure found, in `unit`.
    pub figure: f64,
    /// The bound it is held to (≥ or ≤ as `rule` says).
    pub limit: f64,
    pub rule: &'static str,
    pub unit: &'static str,
}

/// A field's coverage as flown.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FieldFlown {
    pub name: String,
    pub sprayable_area_m2: f64,
    pub covered_fraction: f64,
    pub required_fraction: f64,
    pub missed_m2: f64,
    pub double_sprayed_m2: f64,
}

/// A sortie as flown.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SortieFlown {
    pub sortie: usize,
    pub file: String,
    pub items: usize,
    pub spray_m: f64,
    pub tank_fraction: Option<f64>,
    pub flight_time_s: f64,
    pub battery_fraction: f64,
    /// Largest gap between the height above ground on spray legs and the spray height, m.
    pub worst_spray_height_error_m: f64,
    /// Least margin above h over the highest ground under a transit leg, m (none: no transit).
    pub least_transit_margin_m: Option<f64>,
}

/// The verdict of the preflight, as `report.json` carries it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verdict {
    pub safe: bool,
    pub altitude_reference: AltitudeReference,
    pub checks: Vec<CheckResult>,
    /// One line per failure: sortie, item, place and what is wrong.
    pub failures: Vec<String>,
    pub fields: Vec<FieldFlown>,
    pub sprayed_area_m2: f64,
    pub sprayed_outside_m2: f64,
    pub sprayed_outside_fraction: f64,
    pub sorties: Vec<SortieFlown>,
    /// Least height above the ground of any airborne sample (takeoff and landing aside), m.
    pub lowest_clearance_m: f64,
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

    /// The one line of the printed summary.
    pub fn summary(&self) -> String {
        let coverage = self
            .fields
            .iter()
            .map(|field| field.covered_fraction)
            .fold(f64::INFINITY, f64::min);
        format!(
            "preflight ({} altitudes, read back from {} mission file(s)): {}; least coverage {:.2}%, sprayed outside {:.3}%, lowest clearance {:.2} m",
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
        }
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

    pub(super) fn fail(&mut self, line: String) {
        self.failed += 1;
        if self.lines.len() < LINES_PER_CHECK {
            self.lines.push(line);
        }
    }

    pub(super) fn finish(self, checks: &mut Vec<CheckResult>, failures: &mut Vec<String>) {
        checks.push(CheckResult {
            name: self.name,
            passed: self.failed == 0,
            figure: self.worst.unwrap_or(self.limit),
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
