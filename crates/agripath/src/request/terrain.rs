//! A terrain looked at (`agripath terrain`): its description, extent and height range,
//! heights at points, a hillshade picture, from a terrain argument as given.

use std::path::Path;

use crate::model::CoordinateSystem;
use crate::terrain::hillshade::{hillshade, Shaded};
use crate::terrain::{Extent, Terrain, TerrainSpec};
use crate::{Fault, InputError};

/// The terrain an argument names (a DEM file, flat, flat:HEIGHT, seed000, seed002), an XYZ
/// point cloud gridded at `cell` metres when given.
pub fn load_terrain(argument: &str, cell: Option<f64>) -> Result<Box<dyn Terrain>, InputError> {
    let mut spec = TerrainSpec::from_argument(argument)?;
    if let TerrainSpec::File { cell_m, .. } = &mut spec {
        *cell_m = cell;
    }
    spec.load(Path::new(""), CoordinateSystem::Local)
}

/// What a terrain is: its description, extent and height range, as text lines or as JSON.
pub fn info(argument: &str, cell: Option<f64>, json: bool) -> Result<String, InputError> {
    let model = load_terrain(argument, cell)?;
    let extent = model.extent();
    let range = extent.and_then(|extent| model.height_range_m(extent));
    if json {
        let value = serde_json::json!({
            "terrain": argument,
            "description": model.describe(),
            "extent": extent.map(|e| [e.min_x, e.min_y, e.max_x, e.max_y]),
            "height_range_m": range.map(|(low, high)| [low, high]),
        });
        return Ok(serde_json::to_string_pretty(&value).expect("JSON value") + "\n");
    }
    let mut text = model.describe() + "\n";
    text += &match extent {
        Some(e) => format!(
            "extent x {:.3}..{:.3}, y {:.3}..{:.3} ({:.1} × {:.1})\n",
            e.min_x,
            e.max_x,
            e.min_y,
            e.max_y,
            e.width(),
            e.height()
        ),
        None => "extent unbounded\n".into(),
    };
    if let Some((low, high)) = range {
        text += &format!("heights {low:.3}..{high:.3} m\n");
    }
    Ok(text)
}

/// The heights at X Y pairs, one `X Y HEIGHT` line each.
pub fn sample(
    argument: &str,
    cell: Option<f64>,
    coordinates: &[f64],
) -> Result<String, InputError> {
    if !coordinates.len().is_multiple_of(2) {
        return Err(InputError::new(
            "arguments",
            Fault::Structure("coordinates come in X Y pairs".into()),
        ));
    }
    let model = load_terrain(argument, cell)?;
    let mut lines = Vec::new();
    for pair in coordinates.chunks(2) {
        let height = model
            .height_m(pair[0], pair[1])
            .map_err(|error| InputError::new(argument, Fault::Terrain(error)))?;
        lines.push(format!("{} {} {}", pair[0], pair[1], height));
    }
    Ok(lines.join("\n") + "\n")
}

/// A hillshade picture `size` pixels on its longer side, of the terrain's extent or of
/// `extent` (MIN_X, MIN_Y, MAX_X, MAX_Y), which an unbounded terrain needs.
pub fn shade(
    argument: &str,
    cell: Option<f64>,
    size: usize,
    exaggeration: f64,
    extent: Option<&[f64]>,
) -> Result<Shaded, InputError> {
    if !(2..=16384).contains(&size) {
        return Err(InputError::new(
            "--size",
            Fault::InvalidValue {
                what: "--size".into(),
                value: size.to_string(),
                why: "must be 2..16384 pixels".into(),
            },
        ));
    }
    if !(exaggeration.is_finite() && exaggeration > 0.0) {
        return Err(InputError::new(
            "--exaggeration",
            Fault::InvalidValue {
                what: "--exaggeration".into(),
                value: exaggeration.to_string(),
                why: "must be a number above 0".into(),
            },
        ));
    }
    let model = load_terrain(argument, cell)?;
    let area = match (extent, model.extent()) {
        (Some(values), _) if values.len() != 4 => {
            return Err(InputError::new(
                "--extent",
                Fault::Structure("expected MIN_X,MIN_Y,MAX_X,MAX_Y".into()),
            ))
        }
        (Some(values), _) => {
            let [min_x, min_y, max_x, max_y] = [values[0], values[1], values[2], values[3]];
            if !(values.iter().all(|v| v.is_finite()) && max_x > min_x && max_y > min_y) {
                return Err(InputError::new(
                    "--extent",
                    Fault::Structure("expected MIN_X,MIN_Y,MAX_X,MAX_Y with MAX above MIN".into()),
                ));
            }
            Extent {
                min_x,
                min_y,
                max_x,
                max_y,
            }
        }
        (None, Some(extent)) => extent,
        (None, None) => {
            return Err(InputError::new(
                argument,
                Fault::Structure(
                    "this terrain is unbounded: give --extent MIN_X,MIN_Y,MAX_X,MAX_Y".into(),
                ),
            ))
        }
    };
    Ok(hillshade(model.as_ref(), area, size, exaggeration))
}

/// `agripath terrain hillshade`: the picture of [`shade`] written as a PNG to `out`, and the
/// line saying so.
pub fn write_hillshade(
    argument: &str,
    cell: Option<f64>,
    size: usize,
    exaggeration: f64,
    extent: Option<&[f64]>,
    out: &std::path::Path,
) -> Result<String, super::Failure> {
    let shaded = shade(argument, cell, size, exaggeration, extent)?;
    crate::output::write_file_atomically(out, &shaded.to_png())
        .map_err(|error| super::output_failure(out, error))?;
    Ok(format!(
        "wrote {} ({} × {} pixels)\n",
        out.display(),
        shaded.width,
        shaded.height
    ))
}
