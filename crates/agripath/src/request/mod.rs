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
pub fn check_folder(inputs: &ScenarioInputs, folder: &Path) -> Result<Verdict, InputError> {
    let scenario = if inputs.given() {
        inputs.load()?
    } else {
        crate::demo::scenario()?
    };
    let world = World {
        farm: &scenario.farm,
        terrain: scenario.terrain.as_ref(),
        vehicle: &scenario.vehicle,
    };
    crate::preflight::check_folder(&world, folder).map_err(|fault| InputError::new(folder, fault))
}

/// `agripath check`: the verdict on `folder` as text, unsafe when the preflight fails.
pub fn check(inputs: &ScenarioInputs, folder: &Path) -> Result<Outcome, InputError> {
    let verdict = check_folder(inputs, folder)?;
    let mut outcome = Outcome::text(verdict.to_text());
    if !verdict.safe {
        outcome.failures = verdict.failures;
        outcome.closing = Some(CHECK_CLOSING);
    }
    Ok(outcome)
}

/// `agripath validate`: what the inputs hold, as text ending in `valid`, or as JSON.
pub fn validate(inputs: &ScenarioInputs, json: bool) -> Result<String, InputError> {
    let scenario = inputs.load()?;
    let summary = crate::summary::ScenarioSummary::of(&scenario);
    Ok(if json {
        serde_json::to_string_pretty(&summary).expect("a summary serialises") + "\n"
    } else {
        let notes: String = scenario
            .farm
            .notes
            .iter()
            .map(|note| format!("note: {note}\n"))
            .collect();
        summary.to_text() + &notes + "valid\n"
    })
}

/// An option's value that is not one it may take: the error names the option.
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
