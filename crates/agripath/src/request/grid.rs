//! Fewest-turn grid coverage of one field as asked for (seed 004): the field file, which
//! field, the method, the cell width; planned, checked and rendered.

use std::path::{Path, PathBuf};

use super::{Failure, Outcome};
use crate::grid_cover::{cell_width_m, grid_method, render, PointGrid, GRID_METHODS};
use crate::input::CoordinateChoice;
use crate::{Fault, InputError};

/// What `agripath grid` is asked, as given.
/// With the `cli` feature, also the command line's grammar of `grid`.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct GridRequest {
    /// Field file (GeoJSON, KML or KMZ); obstacles as in `plan`.
    pub fields: PathBuf,
    /// Which field, by name (default: the first).
    #[cfg_attr(feature = "cli", arg(long))]
    pub field: Option<String>,
    /// Method: `ours`, the seed's `hpso`, or the `baseline` boustrophedon decomposition.
    #[cfg_attr(
        feature = "cli",
        arg(long, default_value = "ours", value_parser = GRID_METHODS)
    )]
    pub method: String,
    /// Path-point spacing = swath width, metres (default: the file's `swath_width_m`, else 5).
    #[cfg_attr(
        feature = "cli",
        arg(
            long = "swath-width",
            value_name = "SWATH_WIDTH",
            allow_negative_numbers = true
        )
    )]
    pub swath_width_m: Option<f64>,
    /// Read coordinates as local metres ("local"), whatever the file says.
    #[cfg_attr(feature = "cli", arg(long = "crs", value_name = "CRS", value_parser = super::cli::local_coordinates(), default_value_t = false, hide_default_value = true, action = clap::ArgAction::Set))]
    pub local_coordinates: bool,
    /// Seed of HPSO.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 1))]
    pub seed: u64,
}

impl GridRequest {
    /// Plans the field's route and renders its folder; unsafe, with nothing to write, when
    /// a move of the route crosses an obstacle.
    pub fn plan(&self) -> Result<Outcome, Failure> {
        let fields = self.fields.as_path();
        let choice = if self.local_coordinates {
            CoordinateChoice::Local
        } else {
            CoordinateChoice::FromFile
        };
        let farm = crate::input::read_farm(fields, choice)?;
        let index = match &self.field {
            None => 0,
            Some(name) => farm
                .fields
                .iter()
                .position(|field| &field.name == name)
                .ok_or_else(|| {
                    InputError::new(fields, Fault::Structure(format!("no field named '{name}'")))
                })?,
        };
        let width = cell_width_m(self.swath_width_m, &farm).map_err(|fault| {
            // A width given on the command line is the option's fault, not the file's.
            let named = if self.swath_width_m.is_some() {
                Path::new("--swath-width")
            } else {
                fields
            };
            InputError::new(named, fault)
        })?;
        let grid =
            PointGrid::new(&farm, index, width).map_err(|fault| InputError::new(fields, fault))?;
        let method = self.method.as_str();
        let started = std::time::Instant::now();
        let planner = grid_method(method, self.seed).ok_or_else(|| {
            InputError::new(
                "--method",
                Fault::InvalidValue {
                    what: "--method".into(),
                    value: method.into(),
                    why: format!("expected {}", GRID_METHODS.join(", ")),
                },
            )
        })?;
        let route = planner.plan(&grid);
        let runtime_s = started.elapsed().as_secs_f64();
        // The grid route's preflight: a move that crosses an obstacle is not flown.
        let crossings = route.measure(&grid).crossings;
        if crossings > 0 {
            return Err(Failure::Unsafe(super::UnsafeFlight {
                lines: vec![format!(
                    "{crossings} move(s) of the {method} route cross an obstacle and no clear way round was found"
                )],
                closing: "not safe to fly as planned: nothing was written",
            }));
        }
        let (files, title) = render(&farm, index, &grid, &route, method, runtime_s);
        let files = files
            .into_iter()
            .map(|(name, bytes)| (name.to_string(), bytes))
            .collect();
        let mut outcome =
            Outcome::with_folder(String::new(), files, "plan.geojson, report.json, plan.svg");
        if let Some(folder) = outcome.folder.as_mut() {
            folder.report = format!(
                "{title} ({} points, planned in {:.3} s)\n",
                grid.points.len(),
                runtime_s
            );
        }
        Ok(outcome)
    }
}
