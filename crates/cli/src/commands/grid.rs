//! `grid`: fewest-turn grid coverage of one field (seed 004).

use super::*;
use agripath::input::CoordinateChoice;

pub(super) fn grid(
    fields: &Path,
    field: Option<&str>,
    method: &str,
    swath_width: Option<f64>,
    local: bool,
    seed: u64,
    out: &Path,
) -> Result<(), Failure> {
    use agripath::grid_cover::PointGrid;
    let choice = if local {
        CoordinateChoice::Local
    } else {
        CoordinateChoice::FromFile
    };
    let farm = agripath::input::read_farm(fields, choice)?;
    let index = match field {
        None => 0,
        Some(name) => farm
            .fields
            .iter()
            .position(|f| f.name == name)
            .ok_or_else(|| {
                InputError::new(fields, Fault::Structure(format!("no field named '{name}'")))
            })?,
    };
    let width = agripath::grid_cover::cell_width_m(swath_width, &farm).map_err(|fault| {
        let named = if swath_width.is_some() {
            Path::new("--swath-width")
        } else {
            fields
        };
        InputError::new(named, fault)
    })?;
    let grid =
        PointGrid::new(&farm, index, width).map_err(|fault| InputError::new(fields, fault))?;
    let started = std::time::Instant::now();
    let planner = agripath::grid_cover::grid_method(method, seed).ok_or_else(|| {
        InputError::new(
            "--method",
            Fault::InvalidValue {
                what: "--method".into(),
                value: method.into(),
                why: format!("expected {}", agripath::grid_cover::GRID_METHODS.join(", ")),
            },
        )
    })?;
    let route = planner.plan(&grid);
    let runtime_s = started.elapsed().as_secs_f64();
    // The grid route's preflight: a move that crosses an obstacle is not flown.
    let crossings = route.measure(&grid).crossings;
    if crossings > 0 {
        return Err(Failure::Unsafe(vec![format!(
            "{crossings} move(s) of the {method} route cross an obstacle and no clear way round was found"
        )]));
    }
    let (files, title) =
        agripath::grid_cover::render(&farm, index, &grid, &route, method, runtime_s);
    let written = write_folder(out, &files)?;
    emitln!(
        "{title} ({} points, planned in {:.3} s)",
        grid.points.len(),
        runtime_s
    );
    emitln!(
        "wrote {}/: plan.geojson, report.json, plan.svg",
        written.display()
    );
    Ok(())
}
