//! The composite terrain of seeds 000 and 002 as a scenario file describes it, and the
//! planners' raster of it.

use serde_json::Value;

use super::json::{lookup, number, numbers, only_keys, text};
use super::ORCHARD_CELL_M;
use crate::error::Fault;
use crate::terrain::composite::Hill;
use crate::terrain::{Composite, Extent};
use crate::track::height_map::HeightMap;

/// The composite terrain a file describes: its `coefficients` a..g and `hills` when given,
/// else `default`'s, over `extent`.
pub(super) fn composite(
    terrain: &Value,
    default: Composite,
    extent: Extent,
) -> Result<Composite, Fault> {
    let kind = match terrain.get("kind") {
        Some(_) => text(terrain, "kind")?,
        None => "composite".into(),
    };
    if kind != "composite" {
        return Err(Fault::InvalidValue {
            what: "terrain.kind".into(),
            value: kind,
            why: "track scenarios in JSON have the composite terrain of seeds 000/002".into(),
        });
    }
    let mut model = Composite { extent, ..default };
    if let Some(coefficients) = terrain.get("coefficients") {
        const NAMES: [&str; 7] = ["a", "b", "c", "d", "e", "f", "g"];
        only_keys(coefficients, "terrain.coefficients", &NAMES)?;
        for (slot, name) in model.coefficients.iter_mut().zip(NAMES) {
            *slot = number(coefficients, name).map_err(|_| {
                Fault::Structure(format!(
                    "'terrain.coefficients.{name}' must be a finite number"
                ))
            })?;
        }
    }
    if let Some(hills) = terrain.get("hills") {
        const NAMES: [&str; 5] = ["h", "x", "y", "xs", "ys"];
        only_keys(hills, "terrain.hills", &NAMES)?;
        let columns = NAMES
            .iter()
            .map(|name| {
                numbers(hills, name).map_err(|_| {
                    Fault::Structure(format!(
                        "'terrain.hills.{name}' must be an array of finite numbers"
                    ))
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let length = columns[0].len();
        if columns.iter().any(|column| column.len() != length) || length > 1000 {
            return Err(Fault::Structure(
                "'terrain.hills' needs h, x, y, xs and ys of one length (at most 1000 hills)"
                    .into(),
            ));
        }
        model.hills = (0..length)
            .map(|index| Hill {
                height_m: columns[0][index],
                x_m: columns[1][index],
                y_m: columns[2][index],
                spread_x_m: columns[3][index],
                spread_y_m: columns[4][index],
            })
            .collect();
        if let Some(index) = model.hills.iter().position(|hill| {
            hill.spread_x_m <= 0.0 || hill.spread_y_m <= 0.0 || hill.height_m.abs() > 1.0e4
        }) {
            return Err(Fault::InvalidValue {
                what: format!("terrain.hills[{index}]"),
                value: format!("{:?}", model.hills[index]),
                why: "spreads must be positive and heights within ±10 km".into(),
            });
        }
    }
    if let Some(scale) = terrain.get("height_scale") {
        let scale = scale
            .as_f64()
            .filter(|scale| scale.is_finite() && *scale > 0.0)
            .ok_or_else(|| {
                Fault::Structure("'terrain.height_scale' must be a positive number".into())
            })?;
        model.height_scale = scale;
    }
    Ok(model)
}

/// The file's composite terrain over [0, x] × [0, y] of `extent`, and the planners' raster of
/// it.
pub(super) fn composite_over(
    value: &Value,
    default: Composite,
    extent: &[f64],
) -> Result<(Composite, HeightMap), Fault> {
    let area = Extent {
        min_x: 0.0,
        min_y: 0.0,
        max_x: extent[0],
        max_y: extent[1],
    };
    let terrain = composite(lookup(value, "terrain")?, default, area)?;
    let map = HeightMap::sample(&terrain, (0.0, 0.0, extent[0], extent[1]), ORCHARD_CELL_M)?;
    Ok((terrain, map))
}
