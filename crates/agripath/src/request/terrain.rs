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
    // The flag before the file: a bad value is the command line's fault whatever the file.
    if let Some(cell) = cell.filter(|cell| !(cell.is_finite() && *cell > 0.0)) {
        return Err(super::bad_value(
            "--cell",
            cell.to_string(),
            "must be a positive number of metres",
        ));
    }
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
    let epsg = model.epsg();
    let lon_lat_box = extent
        .zip(epsg)
        .and_then(|(extent, epsg)| crate::terrain::frame::lon_lat_box(epsg, extent));
    let geographic = epsg.is_some_and(crate::terrain::frame::is_lon_lat);
    // Width and height in metres: as given for a projected DEM; for one in degrees, along the
    // parallel through its middle and along a meridian (1° of latitude is 111.13 km).
    let size_m = extent.map(|e| {
        if geographic {
            let middle = (0.5 * (e.min_y + e.max_y)).to_radians();
            (e.width() * 111_320.0 * middle.cos(), e.height() * 111_132.0)
        } else {
            (e.width(), e.height())
        }
    });
    if json {
        let value = serde_json::json!({
            "terrain": argument,
            "description": model.describe(),
            "epsg": epsg,
            "extent": extent.map(|e| [e.min_x, e.min_y, e.max_x, e.max_y]),
            "lon_lat_box": lon_lat_box,
            "size_m": size_m.map(|(width, height)| [width, height]),
            "height_range_m": range.map(|(low, high)| [low, high]),
        });
        return Ok(serde_json::to_string_pretty(&value).expect("JSON value") + "\n");
    }
    let mut text = model.describe() + "\n";
    text += &match (extent, size_m) {
        (Some(e), Some((width, height))) if geographic => format!(
            "extent lon {:.6}..{:.6}, lat {:.6}..{:.6} (about {width:.1} × {height:.1} m)\n",
            e.min_x, e.max_x, e.min_y, e.max_y
        ),
        (Some(e), Some((width, height))) => format!(
            "extent x {:.3}..{:.3}, y {:.3}..{:.3} ({width:.1} × {height:.1} m)\n",
            e.min_x, e.max_x, e.min_y, e.max_y
        ),
        _ => "extent unbounded\n".into(),
    };
    if let (Some([west, south, east, north]), false) = (lon_lat_box, geographic) {
        text += &format!("lon/lat lon {west:.6}..{east:.6}, lat {south:.6}..{north:.6}\n");
    }
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
    lon_lat: bool,
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
        // With --lonlat the pairs are LON LAT, taken to the DEM's own coordinates.
        let (x, y) = if lon_lat {
            model
                .epsg()
                .and_then(|epsg| crate::terrain::frame::from_lon_lat(epsg, pair[0], pair[1]))
                .ok_or_else(|| {
                    InputError::new(
                        argument,
                        Fault::Structure(
                            "--lonlat needs a DEM whose file states a lon/lat or UTM coordinate system".into(),
                        ),
                    )
                })?
        } else {
            (pair[0], pair[1])
        };
        // A lon/lat DEM across the antimeridian (179.99..180.01) holds −179.999° as 180.001°.
        let x = match (lon_lat, model.epsg(), model.extent()) {
            (true, Some(epsg), Some(extent)) if crate::terrain::frame::is_lon_lat(epsg) => {
                crate::terrain::frame::wrap_into(x, extent)
            }
            _ => x,
        };
        let height = model.height_m(x, y).map_err(|error| {
            // The point as the caller typed it, then as the DEM's frame holds it.
            let fault = if lon_lat {
                Fault::Structure(format!(
                    "lon/lat ({}, {}) in the DEM's frame: {error}",
                    pair[0], pair[1]
                ))
            } else {
                Fault::Terrain(error)
            };
            InputError::new(argument, fault)
        })?;
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
