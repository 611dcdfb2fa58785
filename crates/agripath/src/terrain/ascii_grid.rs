//! ESRI ASCII grids (`.asc`): six header lines — `ncols`, `nrows`, `xllcorner` or
//! `xllcenter`, `yllcorner` or `yllcenter`, `cellsize` (or `dx` and `dy`), optional
//! `NODATA_value` — then `nrows` rows of `ncols` heights, northern row first. A `.prj` beside
//! the grid (same name) gives its coordinate system ([`super::prj`]); without one the grid has
//! none, and only local fields drawn in its frame can use it.

use std::path::Path;

use super::Grid;
use crate::error::{Fault, InputError};
use crate::files::read_text;
use crate::limits::MAX_TERRAIN_CELLS;

/// Reads an ESRI ASCII grid file; errs on an unreadable file or a bad header or body, with its place.
pub fn read(path: &Path) -> Result<Grid, InputError> {
    let text = read_text(path)?;
    let mut grid = parse(&text).map_err(|(place, fault)| {
        let error = InputError::new(path, fault);
        match place {
            Some(place) => error.at(place),
            None => error,
        }
    })?;
    let beside = ["prj", "PRJ"]
        .iter()
        .map(|extension| path.with_extension(extension))
        .find(|candidate| candidate.is_file());
    if let Some(prj) = beside {
        let wkt = read_text(&prj)?;
        let code = super::prj::epsg_of(&wkt).map_err(|why| {
            InputError::new(
                &prj,
                Fault::Structure(format!(
                    "the coordinate system of the grid {} is {why}",
                    path.display()
                )),
            )
        })?;
        grid.epsg = Some(code);
        grid.source += &format!(", EPSG:{code} (from its .prj)");
    }
    Ok(grid)
}

type Located = (Option<String>, Fault);

/// Parses an ESRI ASCII grid's text; errs with the place (when known) and the fault.
pub fn parse(text: &str) -> Result<Grid, Located> {
    let structure = |message: String| (None, Fault::Structure(message));
    let mut tokens = text.split_ascii_whitespace().peekable();
    let mut header: Vec<(String, f64)> = Vec::new();
    while let Some(&token) = tokens.peek() {
        if token.parse::<f64>().is_ok() {
            break;
        }
        let key = token.to_ascii_lowercase();
        tokens.next();
        let value = tokens
            .next()
            .ok_or_else(|| structure(format!("header key '{key}' has no value")))?;
        let value: f64 = value
            .parse()
            .map_err(|_| structure(format!("header '{key}' has value '{value}', not a number")))?;
        if !value.is_finite() {
            return Err((Some(format!("header '{key}'")), Fault::NonFinite));
        }
        header.push((key, value));
    }
    let get = |key: &str| {
        header
            .iter()
            .find(|(name, _)| name == key)
            .map(|(_, value)| *value)
    };
    let count = |key: &str| -> Result<usize, Located> {
        let value = get(key).ok_or_else(|| structure(format!("header has no '{key}'")))?;
        if value < 1.0 || value.fract() != 0.0 {
            return Err(structure(format!(
                "'{key}' is {value}, expected a whole number ≥ 1"
            )));
        }
        Ok(value as usize)
    };
    let columns = count("ncols")?;
    let rows = count("nrows")?;
    if (columns as u64) * (rows as u64) > MAX_TERRAIN_CELLS {
        return Err((
            None,
            Fault::TooLarge(format!(
                "{columns} × {rows} cells (limit {MAX_TERRAIN_CELLS})"
            )),
        ));
    }
    let (cell_x, cell_y) = match (get("cellsize"), get("dx"), get("dy")) {
        (Some(size), _, _) => (size, size),
        (None, Some(dx), Some(dy)) => (dx, dy),
        _ => {
            return Err(structure(
                "header has no 'cellsize' (or 'dx' and 'dy')".into(),
            ))
        }
    };
    if !(cell_x > 0.0 && cell_y > 0.0) {
        return Err(structure(format!(
            "cell size {cell_x} × {cell_y} must be above 0"
        )));
    }
    let (left_center, bottom_center) = match (
        get("xllcorner"),
        get("xllcenter"),
        get("yllcorner"),
        get("yllcenter"),
    ) {
        (Some(x), None, Some(y), None) => (x + cell_x / 2.0, y + cell_y / 2.0),
        (None, Some(x), None, Some(y)) => (x, y),
        _ => {
            return Err(structure(
                "header needs xllcorner and yllcorner, or xllcenter and yllcenter".into(),
            ))
        }
    };
    let nodata = get("nodata_value");
    let mut heights = Vec::with_capacity(columns * rows);
    for token in tokens {
        let index = heights.len();
        let place = || {
            Some(format!(
                "row {}, column {}",
                index / columns + 1,
                index % columns + 1
            ))
        };
        if index >= columns * rows {
            return Err((
                None,
                Fault::Structure(format!(
                    "more than ncols × nrows = {} values",
                    columns * rows
                )),
            ));
        }
        let value: f64 = token.parse().map_err(|_| {
            (
                place(),
                Fault::Structure(format!("'{token}' is not a number")),
            )
        })?;
        if nodata == Some(value) {
            heights.push(f32::NAN);
        } else if value.is_finite() {
            heights.push(value as f32);
        } else {
            // A height, not a coordinate: say so, and how to mark a gap.
            return Err((
                place(),
                Fault::Structure(format!(
                    "height '{token}' is not a finite number (mark a cell with no height by the header's NODATA_value)"
                )),
            ));
        }
    }
    if heights.len() != columns * rows {
        return Err(structure(format!(
            "expected ncols × nrows = {} values, found {} (truncated?)",
            columns * rows,
            heights.len()
        )));
    }
    Ok(Grid {
        columns,
        rows,
        first_center_x: left_center,
        first_center_y: bottom_center + (rows as f64 - 1.0) * cell_y,
        cell_x,
        cell_y,
        heights,
        epsg: None,
        // Square cells by one figure, others (`dx`/`dy` headers) by both (trial 8).
        source: if cell_x == cell_y {
            format!("ESRI ASCII grid {columns} × {rows}, cell {cell_x} m")
        } else {
            format!("ESRI ASCII grid {columns} × {rows}, cell {cell_x} × {cell_y} m")
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::Terrain;

    /// Trial 9: an agency's grid with its `.prj` beside it is placed; a `.prj` naming a frame
    /// agripath does not read is an error naming the `.prj`.
    #[test]
    fn a_prj_beside_the_grid_gives_its_frame() {
        let folder = std::env::temp_dir().join(format!("agripath-prj-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        let grid = folder.join("dem.asc");
        std::fs::write(
            &grid,
            "ncols 2\nnrows 2\nxllcorner 449000\nyllcorner 5229000\ncellsize 5\n1 2\n3 4\n",
        )
        .unwrap();
        assert_eq!(read(&grid).unwrap().epsg, None);
        let prj = folder.join("dem.prj");
        std::fs::write(&prj, r#"PROJCS["WGS_1984_UTM_Zone_31N",GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID["WGS_1984",6378137.0,298.257223563]],PRIMEM["Greenwich",0.0],UNIT["Degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],PARAMETER["False_Easting",500000.0],PARAMETER["False_Northing",0.0],PARAMETER["Central_Meridian",3.0],PARAMETER["Scale_Factor",0.9996],PARAMETER["Latitude_Of_Origin",0.0],UNIT["Meter",1.0]]"#).unwrap();
        let placed = read(&grid).unwrap();
        assert_eq!(placed.epsg, Some(32631));
        assert!(
            placed.source.ends_with("EPSG:32631 (from its .prj)"),
            "{}",
            placed.source
        );
        std::fs::write(&prj, r#"PROJCS["RGF93_Lambert_93",GEOGCS["GCS_RGF_1993"]]"#).unwrap();
        let error = read(&grid).unwrap_err().to_string();
        assert!(
            error.contains("dem.prj") && error.contains("'RGF93_Lambert_93'"),
            "{error}"
        );
        std::fs::remove_dir_all(&folder).unwrap();
    }

    #[test]
    fn corner_header_puts_centres_half_a_cell_in() {
        let grid = parse(
            "ncols 3\nnrows 2\nxllcorner 100\nyllcorner 200\ncellsize 10\nNODATA_value -9999\n1 2 3\n4 5 -9999\n",
        )
        .unwrap();
        // Northern row first: (105, 215) holds 1, (105, 205) holds 4.
        assert_eq!(grid.height_m(105.0, 215.0), Ok(1.0));
        assert_eq!(grid.height_m(105.0, 205.0), Ok(4.0));
        assert!(grid.height_m(125.0, 205.0).is_err());
    }

    #[test]
    fn truncated_and_garbage_are_refused() {
        let truncated = parse("ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4\n");
        assert!(truncated.unwrap_err().1.to_string().contains("truncated"));
        let garbage = parse("ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 x\n");
        assert!(garbage.is_err());
    }
}
