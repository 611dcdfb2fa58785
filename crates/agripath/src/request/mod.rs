//! What a user asks for, as a command line gives it (paths, names and numbers), checked once
//! into the library's own values: a scenario, plan settings, a track job, a function bench.
//! Every bad value is an [`InputError`] naming the option and why, so that a program built
//! on the library refuses the same input with the same words as `agripath` does.
//!
//! The checks run in the order the command line's options are read, so that of two faults
//! the same one is reported first whichever program asks.

pub mod bench;
pub mod grid;
mod outcome;
pub mod plan;
mod plan_faults;
pub mod repro;
pub mod terrain;
pub mod track;

pub use outcome::{
    output_failure, write_folder, Failure, FolderFiles, Outcome, UnsafeFlight, CHECK_CLOSING,
    UNSAFE_CLOSING,
};

use std::path::{Path, PathBuf};

use crate::input::CoordinateChoice;
use crate::preflight::{Verdict, World};
use crate::scenario::{Scenario, ScenarioParts, VehicleOverrides};
use crate::terrain::TerrainSpec;
use crate::{Fault, InputError};

/// Where a scenario comes from: a scenario file, or its parts (fields, terrain, vehicle);
/// the vehicle figures given here override the vehicle's. With the `cli` feature this is
/// also the command line's grammar for it (flags override the scenario file).
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct ScenarioInputs {
    /// Scenario TOML file tying fields, terrain and vehicle together.
    pub scenario: Option<PathBuf>,
    /// Field file: GeoJSON (.geojson/.json), KML or KMZ.
    #[cfg_attr(feature = "cli", arg(long))]
    pub fields: Option<PathBuf>,
    /// Terrain: a DEM file (.tif, .asc, .xyz/.csv) or flat, flat:HEIGHT, seed000, seed002.
    #[cfg_attr(feature = "cli", arg(long))]
    pub terrain: Option<String>,
    /// Vehicle TOML file.
    #[cfg_attr(feature = "cli", arg(long))]
    pub vehicle: Option<PathBuf>,
    /// Read field coordinates as metres in a local frame ("local"), whatever the file says.
    #[cfg_attr(feature = "cli", arg(long = "crs", value_name = "CRS", value_parser = cli::local_coordinates(), default_value_t = false, hide_default_value = true, action = clap::ArgAction::Set))]
    pub local_coordinates: bool,
    /// Swath width, spray height and safe height that override the vehicle's.
    #[cfg_attr(feature = "cli", command(flatten))]
    pub overrides: VehicleOverrides,
    /// Keep fields that overlap and spray each overlap once, with the field that comes first
    /// in the file (without it, overlapping fields are refused).
    #[cfg_attr(feature = "cli", arg(long))]
    pub allow_overlap: bool,
}

/// Value parsers the command-line grammar shares.
#[cfg(feature = "cli")]
pub(crate) mod cli {
    use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};

    /// `--crs local`, the one coordinate choice a flag can make: true when given. The hidden
    /// value `false` is the default's (clap parses defaults too); it is not in the help.
    pub fn local_coordinates() -> impl TypedValueParser<Value = bool> {
        PossibleValuesParser::new([
            PossibleValue::new("local"),
            PossibleValue::new("false").hide(true),
        ])
        .map(|value| value == "local")
    }
}

impl ScenarioInputs {
    /// The files these inputs name (the terrain's name taken as a path; a keyword such as
    /// `flat` names none that exists).
    pub fn files(&self) -> Vec<PathBuf> {
        let mut files: Vec<PathBuf> = [&self.scenario, &self.fields, &self.vehicle]
            .into_iter()
            .flatten()
            .cloned()
            .collect();
        files.extend(self.terrain.as_ref().map(PathBuf::from));
        files
    }

    /// Whether a scenario file or a field file is given at all.
    pub fn given(&self) -> bool {
        self.scenario.is_some() || self.fields.is_some()
    }

    /// Reads and checks the scenario: a scenario file (whose terrain, vehicle and coordinates
    /// are its own), or the parts.
    pub fn load(&self) -> Result<Scenario, InputError> {
        let terrain = self
            .terrain
            .as_deref()
            .map(TerrainSpec::from_argument)
            .transpose()?;
        let coordinates = if self.local_coordinates {
            CoordinateChoice::Local
        } else {
            CoordinateChoice::FromFile
        };
        match (&self.scenario, &self.fields) {
            (Some(path), None) => {
                if self.terrain.is_some() || self.vehicle.is_some() || self.local_coordinates {
                    return Err(InputError::new(
                        path,
                        Fault::Structure(
                            "with a scenario file, set terrain, vehicle and crs in the file (only --swath-width, --spray-height and --safe-height override it)".into(),
                        ),
                    ));
                }
                Scenario::from_file(path, self.overrides, self.allow_overlap)
            }
            (None, Some(fields)) => Scenario::load(ScenarioParts {
                name: None,
                fields: fields.clone(),
                coordinates,
                terrain,
                terrain_base: PathBuf::new(),
                vehicle_file: self.vehicle.clone(),
                vehicle_table: None,
                overrides: self.overrides,
                allow_overlap: self.allow_overlap,
            }),
            (Some(path), Some(_)) => Err(InputError::new(
                path,
                Fault::Structure("give a scenario file or --fields, not both".into()),
            )),
            (None, None) => Err(InputError::new(
                "arguments",
                Fault::Structure("give a scenario file or --fields FILE".into()),
            )),
        }
    }
}

/// The preflight of `agripath check`: the mission files of `folder` as they are now, flown
/// against the scenario `inputs` give (the demo's embedded farm when they give none).
///
/// The vehicle is the one the inputs give (a scenario file's, `--vehicle`, else the default,
/// with the command line's overrides). `report.json` records the vehicle the plan was made
/// for (`vehicle_settings`), but `check` does not fly with it, since it can be edited along
/// with the missions; it compares: when the inputs name no vehicle and the recorded one
/// differs, the check is refused (a plan for a small battery is not passed against the
/// default one); when a named vehicle differs, it flies with a warning. Returns the verdict
/// and a line saying which vehicle flew.
pub fn check_folder(
    inputs: &ScenarioInputs,
    folder: &Path,
) -> Result<(Verdict, String), InputError> {
    let mut scenario = if inputs.given() {
        inputs.load()?
    } else {
        crate::demo::scenario()?
    };
    let overridden = inputs.overrides != crate::scenario::VehicleOverrides::default();
    if !inputs.given() && (inputs.vehicle.is_some() || overridden) {
        scenario.vehicle = crate::scenario::load_vehicle(&crate::scenario::ScenarioParts {
            vehicle_file: inputs.vehicle.clone(),
            overrides: inputs.overrides,
            ..Default::default()
        })?;
    }
    let report_path = folder.join("report.json");
    let vehicle_named = inputs.vehicle.is_some() || inputs.scenario.is_some();
    let line = match recorded_vehicle(&report_path)? {
        Some(recorded) if recorded != scenario.vehicle && !vehicle_named => {
            return Err(InputError::new(
                "--vehicle",
                Fault::Structure(format!(
                    "{} was planned for vehicle '{}' ({}), not '{}': give its file with --vehicle (and the plan's --swath-width, --spray-height or --safe-height, if it had them); check does not take the vehicle from report.json, which can be edited with the missions",
                    folder.display(),
                    recorded.name,
                    report_path.display(),
                    scenario.vehicle.name
                )),
            ));
        }
        Some(recorded) if recorded != scenario.vehicle => format!(
            "warning: the plan was made for vehicle '{}' ({}); checked with '{}' as given\n",
            recorded.name,
            report_path.display(),
            scenario.vehicle.name
        ),
        _ => format!("vehicle: {}\n", scenario.vehicle.name),
    };
    let world = World {
        farm: &scenario.farm,
        terrain: scenario.terrain.as_ref(),
        vehicle: &scenario.vehicle,
    };
    let verdict = crate::preflight::check_folder(&world, folder)
        .map_err(|fault| InputError::new(folder, fault))?;
    Ok((verdict, line))
}

/// The vehicle `report.json` records the plan was made for; `None` for a report written
/// before it was recorded, or one that cannot be read (the folder check names that fault).
fn recorded_vehicle(report_path: &Path) -> Result<Option<crate::model::Vehicle>, InputError> {
    let Ok(text) = crate::files::read_text(report_path) else {
        return Ok(None);
    };
    let Ok(report) = serde_json::from_str::<serde_json::Value>(&text) else {
        return Ok(None);
    };
    let Some(settings) = report.get("vehicle_settings") else {
        return Ok(None);
    };
    serde_json::from_value(settings.clone())
        .map(Some)
        .map_err(|error| {
            InputError::new(
                report_path,
                Fault::Structure(format!("vehicle_settings: {error}")),
            )
        })
}

/// `agripath check`: the verdict on `folder` as text, unsafe when the preflight fails.
pub fn check(inputs: &ScenarioInputs, folder: &Path) -> Result<Outcome, InputError> {
    let (verdict, vehicle_line) = check_folder(inputs, folder)?;
    let mut outcome = Outcome::text(vehicle_line + &verdict.to_text());
    if !verdict.safe {
        outcome.failures = verdict.failures;
        outcome.closing = Some(CHECK_CLOSING);
    }
    Ok(outcome)
}

/// `agripath validate`: what the inputs hold, as text ending in `valid`, or as JSON.
pub fn validate(inputs: &ScenarioInputs, json: bool) -> Result<String, InputError> {
    let scenario = inputs.load()?;
    crate::coverage::check_fields_can_be_laid_out(&scenario.farm, &scenario.vehicle)
        .map_err(|fault| InputError::new(&scenario.farm.source, fault))?;
    let mut summary = crate::summary::ScenarioSummary::of(&scenario);
    // `plan` refuses two launch markers unless --start or --supply chooses (trial 9: validate
    // said `valid` with no word of it).
    summary
        .notes
        .extend(crate::pipeline::several_launch_points(&scenario.farm));
    Ok(if json {
        serde_json::to_string_pretty(&summary).expect("a summary serialises") + "\n"
    } else {
        let notes: String = summary
            .notes
            .iter()
            .map(|note| format!("note: {note}\n"))
            .collect();
        summary.to_text() + &notes + "valid\n"
    })
}

/// The names of a comma-separated list given to `option`, each parsed by `parse`: an empty
/// name (a comma too many) and a thing named twice (by one name or by two aliases) are
/// refused, naming the option, not passed on as an unknown name or a repeated column.
pub(crate) fn named_list<T: PartialEq, E: std::fmt::Display>(
    option: &str,
    names: &[&str],
    parse: impl Fn(&str) -> Result<T, E>,
) -> Result<Vec<T>, InputError> {
    let mut parsed: Vec<(T, &str)> = Vec::with_capacity(names.len());
    for name in names.iter().map(|name| name.trim()) {
        if name.is_empty() {
            return Err(bad_value(
                option,
                names.join(","),
                "an empty name in the list (a comma too many?)",
            ));
        }
        let thing = parse(name).map_err(|why| bad_value(option, name, why.to_string()))?;
        if let Some((_, before)) = parsed.iter().find(|(other, _)| *other == thing) {
            let why = if before.eq_ignore_ascii_case(name) {
                "named twice".to_string()
            } else {
                format!("the same as '{before}' before it: named twice")
            };
            return Err(bad_value(option, name, why));
        }
        parsed.push((thing, name));
    }
    Ok(parsed.into_iter().map(|(thing, _)| thing).collect())
}

pub(crate) fn bad_value(
    option: &str,
    value: impl Into<String>,
    why: impl Into<String>,
) -> InputError {
    InputError::new(
        "arguments",
        Fault::InvalidValue {
            what: option.into(),
            value: value.into(),
            why: why.into(),
        },
    )
}
