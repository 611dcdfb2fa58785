//! XYZ point clouds (a handheld terrain sampler's output, seed 000 §5.3): one point per line,
//! `x y z` separated by commas, semicolons or spaces; a first line of column names is skipped.
//! Gridded by nearest-neighbour interpolation, as the seed does: each cell centre takes the
//! height of the closest point; cells with no point within three cells have no data.

use std::path::Path;

use super::Grid;
use crate::error::{Fault, InputError};
use crate::files::read_text;
use crate::limits::{MAX_GRIDDED_CELLS, MAX_GRIDDED_CELL_M, MAX_POINT_CLOUD_POINTS};

/// Cells searched around a cell centre for its nearest point.
const SEARCH_RADIUS_CELLS: i64 = 3;

/// Reads an XYZ file and grids it at `cell_m` metres (estimated when `None`); errs on an unreadable file, a bad line (with its number) or a cloud that cannot be gridded.
pub fn read(path: &Path, cell_m: Option<f64>) -> Result<Grid, InputError> {
    let text = read_text(path)?;
    let points = parse_points(&text).map_err(|(line, fault)| {
        let error = InputError::new(path, fault);
        match line {
            Some(line) => error.at(format!("line {line}")),
            None => error,
        }
    })?;
    grid_points(&points, cell_m).map_err(|fault| InputError::new(path, fault))
}

/// The points of an XYZ text, `[x, y, z]` in file order; errs with the 1-based line number (when one is at fault) and the fault.
pub fn parse_points(text: &str) -> Result<Vec<[f64; 3]>, (Option<usize>, Fault)> {
    let mut points = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let line_number = index + 1;
        let trimmed = line.trim();
        if trimmed.is_empty() || trimmed.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = trimmed
            .split(|c: char| c == ',' || c == ';' || c.is_ascii_whitespace())
            .filter(|field| !field.is_empty())
            .collect();
        let numbers: Result<Vec<f64>, _> = fields
            .iter()
            .take(3)
            .map(|field| field.parse::<f64>())
            .collect();
        match numbers {
            Ok(numbers) if numbers.len() == 3 => {
                if numbers.iter().any(|number| !number.is_finite()) {
                    return Err((Some(line_number), Fault::NonFinite));
                }
                points.push([numbers[0], numbers[1], numbers[2]]);
            }
            // A header line of column names is allowed before the first point.
            Err(_)
                if points.is_empty()
                    && fields.iter().any(|f| f.parse::<f64>().is_err())
                    && index == 0 => {}
            _ => {
                return Err((
                    Some(line_number),
                    Fault::Structure(format!("expected 'x y z', found '{trimmed}'")),
                ))
            }
        }
        if points.len() > MAX_POINT_CLOUD_POINTS {
            return Err((
                None,
                Fault::TooLarge(format!("more than {MAX_POINT_CLOUD_POINTS} points")),
            ));
        }
    }
    if points.len() < 3 {
        return Err((
            None,
            Fault::Structure(format!(
                "{} point(s): a terrain needs at least 3",
                points.len()
            )),
        ));
    }
    Ok(points)
}

/// Nearest-neighbour gridding at `cell_m` (default: the mean spacing √(area / points)).
pub fn grid_points(points: &[[f64; 3]], cell_m: Option<f64>) -> Result<Grid, Fault> {
    let (mut min_x, mut min_y, mut max_x, mut max_y) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for &[x, y, _] in points {
        min_x = min_x.min(x);
        min_y = min_y.min(y);
        max_x = max_x.max(x);
        max_y = max_y.max(y);
    }
    let width = max_x - min_x;
    let height = max_y - min_y;
    if width <= 0.0 || height <= 0.0 {
        return Err(Fault::Structure(
            "the points lie on a line: they span no area".into(),
        ));
    }
    let cell = match cell_m {
        Some(cell) if cell.is_finite() && cell > 0.0 => cell,
        Some(cell) => {
            return Err(Fault::InvalidValue {
                what: "cell_m".into(),
                value: cell.to_string(),
                why: "must be above 0".into(),
            })
        }
        None => (width * height / points.len() as f64).sqrt(),
    };
    if cell > MAX_GRIDDED_CELL_M {
        return Err(Fault::InvalidValue {
            what: "the gridding cell".into(),
            value: format!("{cell:.1} m"),
            why: format!(
                "at most {MAX_GRIDDED_CELL_M} m: the points are too sparse for a terrain model \
                 ({} points over {:.0} × {:.0} m)",
                points.len(),
                width,
                height
            ),
        });
    }
    // In floating point first: a cloud kilometres wide at a tiny cell (or coordinates of
    // 1e23, as fuzzing found) must be refused, not wrap around in integer arithmetic.
    let (columns, rows) = ((width / cell).floor() + 1.0, (height / cell).floor() + 1.0);
    let cells = columns * rows;
    if cells.is_nan() || cells > MAX_GRIDDED_CELLS as f64 {
        return Err(Fault::TooLarge(format!(
            "gridding at {cell} m gives {columns:.0} × {rows:.0} cells (limit {MAX_GRIDDED_CELLS} for point clouds)"
        )));
    }
    let (columns, rows) = (columns as usize, rows as usize);
    // Bucket the points by cell (offsets into one index array: 8 bytes per cell, 4 per
    // point) so each centre only looks at its neighbourhood.
    let bucket_of = |x: f64, y: f64| {
        let column = (((x - min_x) / cell).round() as usize).min(columns - 1);
        let row = (((max_y - y) / cell).round() as usize).min(rows - 1);
        row * columns + column
    };
    let mut offsets = vec![0u32; columns * rows + 1];
    for &[x, y, _] in points {
        offsets[bucket_of(x, y) + 1] += 1;
    }
    for k in 1..offsets.len() {
        offsets[k] += offsets[k - 1];
    }
    let mut members = vec![0u32; points.len()];
    let mut filled = offsets.clone();
    for (index, &[x, y, _]) in points.iter().enumerate() {
        let bucket = bucket_of(x, y);
        members[filled[bucket] as usize] = index as u32;
        filled[bucket] += 1;
    }
    drop(filled);
    let bucket = |k: usize| &members[offsets[k] as usize..offsets[k + 1] as usize];
    let mut heights = vec![f32::NAN; columns * rows];
    let limit = (SEARCH_RADIUS_CELLS as f64 * cell).powi(2);
    for row in 0..rows {
        for column in 0..columns {
            let centre_x = min_x + column as f64 * cell;
            let centre_y = max_y - row as f64 * cell;
            let mut best = (limit, f32::NAN);
            for bucket_row in row as i64 - SEARCH_RADIUS_CELLS..=row as i64 + SEARCH_RADIUS_CELLS {
                for bucket_column in
                    column as i64 - SEARCH_RADIUS_CELLS..=column as i64 + SEARCH_RADIUS_CELLS
                {
                    if bucket_row < 0
                        || bucket_column < 0
                        || bucket_row >= rows as i64
                        || bucket_column >= columns as i64
                    {
                        continue;
                    }
                    for &index in bucket(bucket_row as usize * columns + bucket_column as usize) {
                        let [x, y, z] = points[index as usize];
                        let distance = (x - centre_x).powi(2) + (y - centre_y).powi(2);
                        if distance <= best.0 {
                            best = (distance, z as f32);
                        }
                    }
                }
            }
            heights[row * columns + column] = best.1;
        }
    }
    Ok(Grid {
        columns,
        rows,
        first_center_x: min_x,
        first_center_y: max_y,
        cell_x: cell,
        cell_y: cell,
        heights,
        epsg: None,
        source: format!(
            "XYZ point cloud of {} points gridded by nearest neighbour: {columns} × {rows}, cell {cell:.3} m",
            points.len()
        ),
    })
}

#[cfg(test)]
mod tests {

    #[test]
    fn huge_coordinates_are_refused_not_wrapped() {
        // Found by `cargo fuzz run xyz` (docs/fuzzing.md): the column count overflowed u64
        // and wrapped to 0, then indexing panicked.
        let points = [
            [4.444444444440445e23, 100.0, 1.0],
            [0.0, 0.0, 1.0],
            [0.0, 51.0, 3.0],
        ];
        assert!(matches!(
            grid_points(&points, Some(5.0)),
            Err(Fault::TooLarge(_))
        ));
        // The automatic cell (the mean spacing) would be kilometres: too sparse a terrain.
        assert!(matches!(
            grid_points(&points, None),
            Err(Fault::InvalidValue { .. })
        ));
    }

    #[test]
    fn a_cloud_too_sparse_for_terrain_is_refused() {
        let corners = [
            [0.0, 0.0, 1.0],
            [1e6, 0.0, 1.0],
            [0.0, 1e6, 1.0],
            [1e6, 1e6, 1.0],
        ];
        let refused = grid_points(&corners, None).unwrap_err().to_string();
        assert!(refused.contains("at most 100 m"), "{refused}");
        assert!(grid_points(&corners, Some(150.0)).is_err());
    }

    use super::*;
    use crate::terrain::Terrain;

    #[test]
    fn nearest_point_wins_and_header_is_skipped() {
        let text = "x,y,z\n0,0,1\n10,0,2\n0,10,3\n10,10,4\n";
        let points = parse_points(text).unwrap();
        let grid = grid_points(&points, Some(5.0)).unwrap();
        assert_eq!((grid.columns, grid.rows), (3, 3));
        assert_eq!(grid.height_m(0.0, 0.0), Ok(1.0));
        assert_eq!(grid.height_m(10.0, 10.0), Ok(4.0));
        // The middle centre is equidistant; it takes one of the four heights.
        let middle = grid.cell(1, 1);
        assert!([1.0, 2.0, 3.0, 4.0].contains(&middle));
    }

    #[test]
    fn bad_lines_are_located() {
        let error = parse_points("0 0 1\n1 1 nan\n2 2 2\n").unwrap_err();
        assert_eq!(error, (Some(2), Fault::NonFinite));
        let error = parse_points("0 0 1\n1 1\n").unwrap_err();
        assert_eq!(error.0, Some(2));
    }
}
