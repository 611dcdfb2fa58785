//! `terrain info|sample|hillshade`.

use super::*;

pub(super) fn load_terrain(
    argument: &str,
    cell: Option<f64>,
) -> Result<Box<dyn Terrain>, InputError> {
    let mut spec = TerrainSpec::from_argument(argument)?;
    if let TerrainSpec::File { cell_m, .. } = &mut spec {
        *cell_m = cell;
    }
    spec.load(Path::new(""), agripath::model::CoordinateSystem::Local)
}

pub(super) fn terrain(action: TerrainAction) -> Result<(), Failure> {
    match action {
        TerrainAction::Info {
            terrain,
            cell,
            json,
        } => {
            let model = load_terrain(&terrain, cell)?;
            let extent = model.extent();
            let range = extent.and_then(|extent| model.height_range_m(extent));
            if json {
                let value = serde_json::json!({
                    "terrain": terrain,
                    "description": model.describe(),
                    "extent": extent.map(|e| [e.min_x, e.min_y, e.max_x, e.max_y]),
                    "height_range_m": range.map(|(low, high)| [low, high]),
                });
                emitln!(
                    "{}",
                    serde_json::to_string_pretty(&value).expect("JSON value")
                );
            } else {
                emitln!("{}", model.describe());
                match extent {
                    Some(e) => emitln!(
                        "extent x {:.3}..{:.3}, y {:.3}..{:.3} ({:.1} × {:.1})",
                        e.min_x,
                        e.max_x,
                        e.min_y,
                        e.max_y,
                        e.width(),
                        e.height()
                    ),
                    None => emitln!("extent unbounded"),
                }
                if let Some((low, high)) = range {
                    emitln!("heights {low:.3}..{high:.3} m");
                }
            }
            Ok(())
        }
        TerrainAction::Sample {
            terrain,
            coordinates,
            cell,
        } => {
            if coordinates.len() % 2 != 0 {
                return Err(InputError::new(
                    "arguments",
                    Fault::Structure("coordinates come in X Y pairs".into()),
                )
                .into());
            }
            let model = load_terrain(&terrain, cell)?;
            let mut lines = Vec::new();
            for pair in coordinates.chunks(2) {
                let height = model
                    .height_m(pair[0], pair[1])
                    .map_err(|error| InputError::new(&terrain, Fault::Terrain(error)))?;
                lines.push(format!("{} {} {}", pair[0], pair[1], height));
            }
            emitln!("{}", lines.join("\n"));
            Ok(())
        }
        TerrainAction::Hillshade {
            terrain,
            out,
            size,
            exaggeration,
            extent,
            cell,
        } => {
            if !(2..=16384).contains(&size) {
                return Err(InputError::new(
                    "--size",
                    Fault::InvalidValue {
                        what: "--size".into(),
                        value: size.to_string(),
                        why: "must be 2..16384 pixels".into(),
                    },
                )
                .into());
            }
            if !(exaggeration.is_finite() && exaggeration > 0.0) {
                return Err(InputError::new(
                    "--exaggeration",
                    Fault::InvalidValue {
                        what: "--exaggeration".into(),
                        value: exaggeration.to_string(),
                        why: "must be a number above 0".into(),
                    },
                )
                .into());
            }
            let model = load_terrain(&terrain, cell)?;
            let area = match (extent, model.extent()) {
                (Some(values), _) if values.len() != 4 => {
                    return Err(InputError::new(
                        "--extent",
                        Fault::Structure("expected MIN_X,MIN_Y,MAX_X,MAX_Y".into()),
                    )
                    .into())
                }
                (Some(values), _) => {
                    let [min_x, min_y, max_x, max_y] = [values[0], values[1], values[2], values[3]];
                    if !(values.iter().all(|v| v.is_finite()) && max_x > min_x && max_y > min_y) {
                        return Err(InputError::new(
                            "--extent",
                            Fault::Structure(
                                "expected MIN_X,MIN_Y,MAX_X,MAX_Y with MAX above MIN".into(),
                            ),
                        )
                        .into());
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
                        &terrain,
                        Fault::Structure(
                            "this terrain is unbounded: give --extent MIN_X,MIN_Y,MAX_X,MAX_Y"
                                .into(),
                        ),
                    )
                    .into())
                }
            };
            let shaded = hillshade(model.as_ref(), area, size, exaggeration);
            write_file_atomically(&out, &shaded.to_png())
                .map_err(|error| output_failure(&out, error))?;
            emitln!(
                "wrote {} ({} × {} pixels)",
                out.display(),
                shaded.width,
                shaded.height
            );
            Ok(())
        }
    }
}
