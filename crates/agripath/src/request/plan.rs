//! A coverage plan as asked for: the layout, the order of the passes, the sorties and the
//! mission files, checked into [`PlanSettings`] for a scenario.

use super::{bad_value, Outcome, ScenarioInputs};
use crate::coverage::heading::HeadingObjective;
use crate::coverage::CoverageSettings;
use crate::mission::flight::{AltitudeReference, MissionSettings, SprayerCommand};
use crate::pipeline::{plan_mission, PlannedMission};
use crate::scenario::Scenario;
use crate::sequence::Sequencer;
use crate::settings::PlanSettings;
use crate::sortie::SortieSettings;
use crate::supply::{SupplyRequest, SupplyValue};
use crate::{Fault, InputError};

/// The options of a coverage plan, as given: names and numbers not yet checked.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanOptions {
    /// Edge passes around each boundary and hole (0: seed 001's layout).
    pub headland_passes: usize,
    /// `auto`, `swaths`, `length`, or degrees from east, counter-clockwise.
    pub heading: String,
    /// Weights ω_N, ω_L of seed 001's E: two numbers.
    pub weights: Vec<f64>,
    /// Refine the best 1° heading to 0.1°.
    pub refine_heading: bool,
    /// `overlap`, `balanced` or `gap`: where swaths' spray on/off points meet the edge band.
    pub edge_cut: String,
    /// Spacing of the terrain samples along swaths, metres.
    pub drape_spacing_m: f64,
    /// Distance kept from field boundaries, metres.
    pub boundary_margin_m: f64,
    /// Distance kept from obstacles, metres.
    pub obstacle_margin_m: f64,
    /// `best`, `greedy` or `aco`.
    pub sequencer: String,
    /// Launch point X, Y in the input's coordinates.
    pub start: Option<Vec<f64>>,
    /// `auto`, `auto:N` or `X,Y` (the supply point; `X,Y` is the same as `start`).
    pub supply: Option<String>,
    /// Seed of the stochastic sequencers and sortie planners.
    pub seed: u64,
    /// Ant colony batches.
    pub batches: usize,
    /// Ants per batch.
    pub ants: usize,
    /// `exact`, `gsa`, `simple`, `unplanned`, or `none` (one flight).
    pub sorties: String,
    /// `relative`, `sea-level` or `terrain`; `None`: the terrain's default.
    pub altitude: Option<String>,
    /// `do-sprayer` or `servo:CHANNEL:ON_PWM:OFF_PWM`.
    pub sprayer: String,
    /// Largest gap between the flown altitude and terrain + spray height, metres.
    pub terrain_tolerance_m: f64,
    /// LON, LAT of a local plan's origin in mission files.
    pub origin: Option<Vec<f64>>,
}

impl PlanOptions {
    /// Checks the options and reads the scenario, in the command line's order: the mission
    /// options, the scenario, the altitude reference, the start, the layout, the sequencer.
    pub fn load(&self, inputs: &ScenarioInputs) -> Result<(Scenario, PlanSettings), InputError> {
        let mut mission = self.mission_settings()?;
        let scenario = inputs.load()?;
        let requested = match self.altitude.as_deref() {
            Some(key) => Some(key.parse::<AltitudeReference>().map_err(|why| {
                InputError::new(
                    "--altitude",
                    Fault::InvalidValue {
                        what: "--altitude".into(),
                        value: key.into(),
                        why,
                    },
                )
            })?),
            None => None,
        };
        mission.altitude =
            AltitudeReference::resolve(requested, &scenario.terrain_spec, scenario.terrain_stated)
                .map_err(|fault| InputError::new("--altitude", fault))?;
        let start = match &self.start {
            Some(values) if values.len() == 2 && values.iter().all(|value| value.is_finite()) => {
                let (x, y) = scenario
                    .farm
                    .coordinate_system
                    .to_plan(values[0], values[1]);
                Some([x, y])
            }
            Some(values) => {
                return Err(InputError::new(
                    "--start",
                    Fault::InvalidValue {
                        what: "--start".into(),
                        value: format!("{values:?}"),
                        why: "expected two finite numbers X,Y".into(),
                    },
                ))
            }
            None => None,
        };
        let (start, supply) = self.supply(start, scenario.farm.coordinate_system)?;
        let settings = PlanSettings {
            coverage: self.coverage_settings()?,
            sequencer: self.sequencer()?,
            start,
            supply,
            sorties: SortieSettings {
                planner: match self.sorties.as_str() {
                    "none" => None,
                    name => Some(
                        name.parse()
                            .map_err(|why: String| bad_value("--sorties", name, why))?,
                    ),
                },
                seed: self.seed,
            },
            mission,
        };
        Ok((scenario, settings))
    }

    /// `--supply` with `--start` (already in planning metres): one supply point at most.
    fn supply(
        &self,
        start: Option<[f64; 2]>,
        frame: crate::model::CoordinateSystem,
    ) -> Result<(Option<[f64; 2]>, SupplyRequest), InputError> {
        let Some(text) = &self.supply else {
            return Ok((start, SupplyRequest::FromInputs));
        };
        let value: SupplyValue = text
            .parse()
            .map_err(|why: String| bad_value("--supply", text, why))?;
        if start.is_some() {
            return Err(bad_value(
                "--supply",
                text,
                "--start already gives the supply point (the drone starts, refills and lands at one place): give one of --start and --supply",
            ));
        }
        Ok(match value {
            SupplyValue::Auto { listed } => (None, SupplyRequest::Auto { listed }),
            SupplyValue::Point([x, y]) => {
                let (x, y) = frame.to_plan(x, y);
                (Some([x, y]), SupplyRequest::FromInputs)
            }
        })
    }

    fn coverage_settings(&self) -> Result<CoverageSettings, InputError> {
        if self.weights.len() != 2 {
            return Err(InputError::new(
                "--weights",
                Fault::Structure("expected two weights ω_N,ω_L".into()),
            ));
        }
        let heading = HeadingObjective::parse(&self.heading, [self.weights[0], self.weights[1]])
            .map_err(|why| {
                InputError::new(
                    "--heading",
                    Fault::InvalidValue {
                        what: "--heading".into(),
                        value: self.heading.clone(),
                        why,
                    },
                )
            })?;
        let edge_cut = self.edge_cut.parse().map_err(|why| {
            InputError::new(
                "--edge-cut",
                Fault::InvalidValue {
                    what: "--edge-cut".into(),
                    value: self.edge_cut.clone(),
                    why,
                },
            )
        })?;
        let settings = CoverageSettings {
            headland_passes: self.headland_passes,
            edge_cut,
            boundary_margin_m: self.boundary_margin_m,
            obstacle_margin_m: self.obstacle_margin_m,
            drape_spacing_m: self.drape_spacing_m,
            heading,
            refine_heading: self.refine_heading,
        };
        settings
            .validate()
            .map_err(|fault| InputError::new("arguments", fault))?;
        Ok(settings)
    }

    fn sequencer(&self) -> Result<Sequencer, InputError> {
        // Checked whichever sequencer runs: a value no run could use is a mistake to report.
        for (flag, value) in [("--ants", self.ants), ("--batches", self.batches)] {
            if !(1..=100_000).contains(&value) {
                return Err(InputError::new(
                    flag,
                    Fault::InvalidValue {
                        what: flag.into(),
                        value: value.to_string(),
                        why: "must be 1..=100000".into(),
                    },
                ));
            }
        }
        Sequencer::from_key(&self.sequencer, self.seed, self.ants, self.batches).ok_or_else(|| {
            bad_value(
                "--sequencer",
                &self.sequencer,
                format!("expected {}", Sequencer::KEYS.join(", ")),
            )
        })
    }

    /// The mission-file options, checked.
    fn mission_settings(&self) -> Result<MissionSettings, InputError> {
        let invalid = |what: &str, value: String, why: &str| bad_value(what, value, why);
        let mut settings = MissionSettings {
            sprayer: self
                .sprayer
                .parse::<SprayerCommand>()
                .map_err(|why| invalid("--sprayer", self.sprayer.clone(), &why))?,
            ..MissionSettings::default()
        };
        if !(self.terrain_tolerance_m.is_finite() && self.terrain_tolerance_m > 0.0) {
            return Err(invalid(
                "--terrain-tolerance",
                self.terrain_tolerance_m.to_string(),
                "must be a finite number above 0",
            ));
        }
        settings.terrain_tolerance_m = self.terrain_tolerance_m;
        if let Some(origin) = &self.origin {
            let valid = origin.len() == 2
                && (-180.0..=180.0).contains(&origin[0])
                && (-80.0..=84.0).contains(&origin[1]);
            if !valid {
                return Err(invalid(
                    "--origin",
                    format!("{origin:?}"),
                    "expected LON,LAT with longitude in -180..180 and latitude in -80..84",
                ));
            }
            settings.local_origin = (origin[0], origin[1]);
        }
        Ok(settings)
    }
}

/// The demo: seed 001's embedded five-field farm planned from the seed's Table 8 start C1
/// (0, 0), a corner of S1, with the default settings.
pub fn plan_demo() -> Result<(Scenario, PlannedMission), InputError> {
    let scenario = crate::demo::scenario()?;
    let mut settings = PlanSettings {
        start: Some([0.0, 0.0]),
        ..PlanSettings::default()
    };
    settings.mission.altitude =
        AltitudeReference::resolve(None, &scenario.terrain_spec, scenario.terrain_stated)
            .map_err(|fault| InputError::new(crate::demo::FARM_LABEL, fault))?;
    let mission = plan_mission(&scenario, &settings)
        .map_err(|fault| InputError::new(crate::demo::FARM_LABEL, fault))?;
    Ok((scenario, mission))
}

/// A rendered plan as a command ends it: the plan's files (all but the mission files when the
/// preflight fails and not `allow_unsafe`), its report, and the verdict; `source` names the
/// input in errors.
pub fn outcome(
    scenario: &Scenario,
    mission: &PlannedMission,
    allow_unsafe: bool,
    source: &std::path::Path,
) -> Result<Outcome, InputError> {
    let mut rendered = crate::pipeline::render(scenario, mission)
        .map_err(|fault| InputError::new(source, fault))?;
    rendered.keep_files_to_write(allow_unsafe);
    let contents = files_summary(&rendered.files);
    let mut outcome = Outcome::with_folder(String::new(), rendered.files, &contents);
    if let Some(folder) = outcome.folder.as_mut() {
        folder.report = rendered.report.to_text();
    }
    if !rendered.verdict.safe {
        if allow_unsafe {
            outcome.warning = Some(
                "warning: the mission files were written although the preflight failed (--allow-unsafe)".into(),
            );
        } else {
            outcome.failures = rendered.verdict.failures;
        }
    }
    Ok(outcome)
}

/// The files written, in one short line: mission files per sortie are counted, not listed.
pub fn files_summary(files: &[(String, Vec<u8>)]) -> String {
    let sorties = files
        .iter()
        .filter(|(name, _)| name.ends_with(".plan"))
        .count();
    let mut names: Vec<&str> = files
        .iter()
        .map(|(name, _)| name.as_str())
        .filter(|name| !name.starts_with("sortie_"))
        .collect();
    let per_sortie = format!("sortie_NN.plan and .waypoints for {sorties} sortie(s)");
    if sorties > 0 {
        names.push(&per_sortie);
    }
    names.join(", ")
}
