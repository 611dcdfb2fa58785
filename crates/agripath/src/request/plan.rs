//! A coverage plan as asked for: the layout, the order of the passes, the sorties and the
//! mission files, checked into [`PlanSettings`] for a scenario.

pub use super::plan_faults::planning_error;
use super::plan_faults::typed_point;
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

/// The options of a coverage plan, as given: names and numbers not yet checked. With the
/// `cli` feature this is also the command line's grammar for them, and its defaults are
/// [`PlanOptions::default`]'s (a test in the program checks that they agree).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct PlanOptions {
    /// Edge passes around each boundary and hole; 0 gives seed 001's layout (interior only).
    #[cfg_attr(
        feature = "cli",
        arg(long = "headland", value_name = "HEADLAND", default_value_t = 1)
    )]
    pub headland_passes: usize,
    /// Swath heading: `dose` (the default: seed 001's E, then the least double dose among
    /// near-best headings), `auto` (seed 001's E), `swaths` (fewest), `length` (shortest), or
    /// degrees from east, counter-clockwise.
    #[cfg_attr(
        feature = "cli",
        arg(long, default_value = "dose", allow_negative_numbers = true)
    )]
    pub heading: String,
    /// Weights ω_N,ω_L of seed 001's E.
    #[cfg_attr(
        feature = "cli",
        arg(long, value_delimiter = ',', default_value = "0.5,0.5")
    )]
    pub weights: Vec<f64>,
    /// Refine the best 1° heading to 0.1° (`--no-refine` keeps the seed's 1° heading).
    #[cfg_attr(feature = "cli", arg(long = "no-refine", action = clap::ArgAction::SetFalse, help = "Keep the best 1° heading (the seed's) instead of refining it to 0.1°"))]
    pub refine_heading: bool,
    /// Where swaths' spray on/off points sit against the edge-pass band: `overlap` (on the
    /// pass line), `balanced` (the default: least double dose with at most 0.3 % of each
    /// field missed) or `gap` (no double dose).
    #[cfg_attr(
        feature = "cli",
        arg(long = "edge-cut", default_value = "balanced", value_parser = ["overlap", "balanced", "gap"])
    )]
    pub edge_cut: String,
    /// Seed 001's a: spacing of the terrain samples along swaths, metres.
    #[cfg_attr(
        feature = "cli",
        arg(
            long = "drape-spacing",
            value_name = "DRAPE_SPACING",
            default_value_t = 20.0,
            allow_negative_numbers = true
        )
    )]
    pub drape_spacing_m: f64,
    /// Distance kept from field boundaries, metres.
    #[cfg_attr(
        feature = "cli",
        arg(
            long = "boundary-margin",
            value_name = "BOUNDARY_MARGIN",
            default_value_t = 0.0,
            allow_negative_numbers = true
        )
    )]
    pub boundary_margin_m: f64,
    /// Distance kept from obstacles, metres.
    #[cfg_attr(
        feature = "cli",
        arg(
            long = "obstacle-margin",
            value_name = "OBSTACLE_MARGIN",
            default_value_t = 0.0,
            allow_negative_numbers = true
        )
    )]
    pub obstacle_margin_m: f64,
    /// `best` (ours: local search), `greedy` or `aco` (seed 001's ant colony). Each
    /// optimises the flight as flown: from and back to the supply point when there is one,
    /// else an open path (free first and last pass).
    #[cfg_attr(
        feature = "cli",
        arg(long, default_value = "best", value_parser = Sequencer::KEYS)
    )]
    pub sequencer: String,
    /// Launch point X,Y in the input's coordinates (lon,lat or local metres): the supply
    /// point, as `--supply X,Y`; default: the field file's `launch`/`supply` marker, else
    /// `--supply auto` (with sorties), else none: the flight is an open path.
    #[cfg_attr(
        feature = "cli",
        arg(long, value_delimiter = ',', allow_hyphen_values = true)
    )]
    pub start: Option<Vec<f64>>,
    /// Supply point (take-off, refills, battery swaps, landing): `auto` (the place a vehicle
    /// can stand, on the file's access features if any, that saves most non-spray time; the
    /// default without a launch marker), `auto:N` (also list the N best in report.json), or
    /// X,Y in the input's coordinates.
    #[cfg_attr(feature = "cli", arg(long, allow_hyphen_values = true))]
    pub supply: Option<String>,
    /// Seed of the stochastic sequencers and sortie planners (same seed, same plan).
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 1))]
    pub seed: u64,
    /// Ant colony batches (seed 001: 100 or 200).
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 200))]
    pub batches: usize,
    /// Ants per batch (seed 001: 50).
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 50))]
    pub ants: usize,
    /// Return points for refill and battery swap: `joint` (ours: the order of the passes and
    /// the returns optimised together), `exact` (ours: the optimal returns for the order the
    /// sequencer chose), the seed 003 planners `gsa` (gravitational search), `simple`,
    /// `unplanned`, or `none` (one flight).
    #[cfg_attr(
        feature = "cli",
        arg(long, default_value = "joint", value_parser = SORTIE_KEYS)
    )]
    pub sorties: String,
    /// Altitudes in mission files: `relative` (above the launch point's ground,
    /// MAV_FRAME_GLOBAL_RELATIVE_ALT; the default without a DEM), `sea-level` (from the DEM,
    /// MAV_FRAME_GLOBAL; the default with one; needs a DEM or `--terrain flat:H`) or `terrain`
    /// (above ground, MAV_FRAME_GLOBAL_TERRAIN_ALT, for ArduPilot).
    #[cfg_attr(
        feature = "cli",
        arg(long, value_parser = ["relative", "sea-level", "terrain"])
    )]
    pub altitude: Option<String>,
    /// Sprayer switching: `do-sprayer` (MAV_CMD_DO_SPRAYER, the default) or
    /// `servo:CHANNEL:ON_PWM:OFF_PWM` (MAV_CMD_DO_SET_SERVO); refused for a survey vehicle.
    #[cfg_attr(feature = "cli", arg(long))]
    pub sprayer: Option<String>,
    /// Terrain following: the largest gap, metres, between the flown altitude and terrain +
    /// spray height along a swath before another waypoint is added.
    #[cfg_attr(
        feature = "cli",
        arg(
            long = "terrain-tolerance",
            value_name = "TERRAIN_TOLERANCE",
            default_value_t = 1.0,
            allow_negative_numbers = true
        )
    )]
    pub terrain_tolerance_m: f64,
    /// For fields in local metres: LON,LAT of their origin in mission files (default 126.63,45.75).
    #[cfg_attr(
        feature = "cli",
        arg(long, value_delimiter = ',', allow_hyphen_values = true)
    )]
    pub origin: Option<Vec<f64>>,
}

impl Default for PlanOptions {
    /// The command line's defaults: seed 001's layout with one edge pass, E's heading refined
    /// to 0.1°, our sequencer and joint sorties, the supply point and altitudes as the inputs
    /// give them.
    fn default() -> Self {
        PlanOptions {
            headland_passes: 1,
            heading: "dose".into(),
            weights: vec![0.5, 0.5],
            refine_heading: true,
            edge_cut: "balanced".into(),
            drape_spacing_m: 20.0,
            boundary_margin_m: 0.0,
            obstacle_margin_m: 0.0,
            sequencer: "best".into(),
            start: None,
            supply: None,
            seed: 1,
            batches: 200,
            ants: 50,
            sorties: "joint".into(),
            altitude: None,
            sprayer: None,
            terrain_tolerance_m: 1.0,
            origin: None,
        }
    }
}

/// The names `--sorties` takes: the sortie planners, and `none` for one flight.
pub const SORTIE_KEYS: [&str; 6] = ["joint", "exact", "gsa", "simple", "unplanned", "none"];

impl PlanOptions {
    /// Checks the options and reads the scenario, in the command line's order: the mission
    /// options, the scenario, the altitude reference, the start, the layout, the sequencer.
    pub fn load(&self, inputs: &ScenarioInputs) -> Result<(Scenario, PlanSettings), InputError> {
        let mut mission = self.mission_settings()?;
        let mut scenario = inputs.load()?;
        if self.origin.is_some()
            && scenario.farm.coordinate_system != crate::model::CoordinateSystem::Local
        {
            scenario.farm.notes.push(
                "--origin is not used: the fields are in lon/lat, and the mission files place them where they lie".into(),
            );
        }
        if let (Some(_), Some(sprayer)) = (&scenario.vehicle.camera, &self.sprayer) {
            return Err(bad_value(
                "--sprayer",
                sprayer,
                format!(
                    "vehicle '{}' is a survey vehicle (it has a [camera]): it has no sprayer to switch",
                    scenario.vehicle.name
                ),
            ));
        }
        if let Some(why) = crate::limits::terrain_tolerance_fault(
            mission.terrain_tolerance_m,
            scenario.vehicle.spray_height_m,
        ) {
            return Err(bad_value(
                "--terrain-tolerance",
                mission.terrain_tolerance_m.to_string(),
                why,
            ));
        }
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
                let text = format!("{},{}", values[0], values[1]);
                Some(typed_point(
                    "--start",
                    &text,
                    [values[0], values[1]],
                    &scenario.farm,
                )?)
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
        let (start, supply) = self.supply(start, &scenario.farm)?;
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
                ..SortieSettings::default()
            },
            mission,
        };
        Ok((scenario, settings))
    }

    /// `--supply` with `--start` (already in planning metres): one supply point at most.
    fn supply(
        &self,
        start: Option<[f64; 2]>,
        farm: &crate::model::Farm,
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
            SupplyValue::Point(typed) => (
                Some(typed_point("--supply", text, typed, farm)?),
                SupplyRequest::FromInputs,
            ),
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
            sprayer: {
                let sprayer = self.sprayer.as_deref().unwrap_or("do-sprayer");
                sprayer
                    .parse::<SprayerCommand>()
                    .map_err(|why| invalid("--sprayer", sprayer.to_string(), &why))?
            },
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
    files: FolderChoice,
    source: &std::path::Path,
) -> Result<Outcome, InputError> {
    let mut rendered = crate::pipeline::render_flyable(scenario, mission).map_err(|fault| {
        super::plan_faults::rendering_error(scenario, source, mission.settings.start, fault)
    })?;
    rendered.keep_files_to_write(files.allow_unsafe);
    let pdf_warning = if files.pdf {
        print_sheet(&mut rendered.files)
    } else {
        None
    };
    let contents = files_summary(&rendered.files);
    let notes: String = scenario
        .farm
        .notes
        .iter()
        .map(|note| format!("note: {}: {note}\n", scenario.farm.source.display()))
        .collect();
    let mut outcome = Outcome::with_folder(notes, rendered.files, &contents);
    if let Some(folder) = outcome.folder.as_mut() {
        folder.report = rendered.report.to_text();
    }
    outcome.warning = pdf_warning;
    if !rendered.verdict.safe {
        if files.allow_unsafe {
            // Both warnings when both apply: the unsafe one first, it matters more.
            let unsafe_warning = "warning: the mission files were written although the preflight failed (--allow-unsafe)";
            outcome.warning = Some(match outcome.warning.take() {
                Some(pdf) => format!("{unsafe_warning}\n{pdf}"),
                None => unsafe_warning.to_string(),
            });
        } else {
            outcome.failures = rendered.verdict.failures;
        }
    }
    Ok(outcome)
}

/// What goes into a plan's folder besides what is always there.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FolderChoice {
    /// Write the mission files even when the preflight fails (`--allow-unsafe`).
    pub allow_unsafe: bool,
    /// Print `sheet.html` to `sheet.pdf` with a headless Chromium (`--pdf`).
    pub pdf: bool,
}

/// Adds `sheet.pdf`, printed from `sheet.html`; without a browser, or when printing fails,
/// the warning that says so (the folder is written without it).
fn print_sheet(files: &mut Vec<(String, Vec<u8>)>) -> Option<String> {
    let Some(browser) = crate::sheet::find_browser() else {
        return Some(format!(
            "warning: sheet.pdf not written: no Chromium found (install chromium, or set {} to a browser); print sheet.html from any browser instead",
            crate::sheet::BROWSER_VARIABLE
        ));
    };
    let html = files
        .iter()
        .find(|(name, _)| name == "sheet.html")
        .map(|(_, bytes)| String::from_utf8_lossy(bytes).into_owned())?;
    match crate::sheet::pdf(&browser, &html) {
        Ok(bytes) => {
            files.push(("sheet.pdf".to_string(), bytes));
            None
        }
        Err(why) => Some(format!("warning: sheet.pdf not written: {why}")),
    }
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
