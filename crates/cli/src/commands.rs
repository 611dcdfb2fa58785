//! One function per command: build the request, call the library, print, write.

use std::path::{Path, PathBuf};

use agripath::input::CoordinateChoice;
use agripath::model::scenario::{ScenarioParts, VehicleOverrides};
use agripath::model::Scenario;
use agripath::output::{write_file_atomically, StagedFolder};
use agripath::summary::ScenarioSummary;
use agripath::terrain::hillshade::hillshade;
use agripath::terrain::{Extent, Terrain, TerrainSpec};
use agripath::{Fault, InputError};

use crate::args::{Arguments, Command, Inputs, TerrainAction};
use crate::Failure;

pub fn run(arguments: Arguments) -> Result<(), Failure> {
    match arguments.command {
        Command::Demo { out } => demo(&out),
        Command::Validate { inputs, json } => validate(&inputs, json),
        Command::Terrain { action } => terrain(action),
    }
}

fn output_failure(path: &Path, error: std::io::Error) -> Failure {
    Failure::Output(format!("{}: cannot write: {error}", path.display()))
}

fn demo(out: &Path) -> Result<(), Failure> {
    let scenario = agripath::demo::scenario()?;
    let summary = ScenarioSummary::of(&scenario);
    let text = summary.to_text();
    let bounds = scenario.farm.bounds();
    let margin = 20.0;
    let extent = Extent {
        min_x: bounds.min().x - margin,
        min_y: bounds.min().y - margin,
        max_x: bounds.max().x + margin,
        max_y: bounds.max().y + margin,
    };
    let shaded = hillshade(scenario.terrain.as_ref(), extent, 1024, 5.0);
    let staged = StagedFolder::new(out).map_err(|error| output_failure(out, error))?;
    let json = serde_json::to_string_pretty(&summary).expect("a summary serialises");
    staged
        .write("summary.json", json.as_bytes())
        .and_then(|()| staged.write("summary.txt", text.as_bytes()))
        .and_then(|()| staged.write("terrain.png", &shaded.to_png()))
        .map_err(|error| output_failure(out, error))?;
    let written = staged
        .commit()
        .map_err(|error| output_failure(out, error))?;
    print!("{text}");
    println!(
        "wrote {}/summary.json, summary.txt, terrain.png (hillshade, heights × 5)",
        written.display()
    );
    Ok(())
}

fn load_scenario(inputs: &Inputs) -> Result<Scenario, InputError> {
    let overrides = VehicleOverrides {
        swath_width_m: inputs.swath_width,
        spray_height_m: inputs.spray_height,
        safe_height_m: inputs.safe_height,
    };
    let terrain = inputs
        .terrain
        .as_deref()
        .map(TerrainSpec::from_argument)
        .transpose()?;
    let coordinates = match inputs.crs.as_deref() {
        Some("local") => CoordinateChoice::Local,
        _ => CoordinateChoice::FromFile,
    };
    match (&inputs.scenario, &inputs.fields) {
        (Some(path), None) => {
            if inputs.terrain.is_some() || inputs.vehicle.is_some() || inputs.crs.is_some() {
                return Err(InputError::new(
                    path,
                    Fault::Structure(
                        "with a scenario file, set terrain, vehicle and crs in the file (only --swath-width, --spray-height and --safe-height override it)".into(),
                    ),
                ));
            }
            Scenario::from_file(path, overrides)
        }
        (None, Some(fields)) => Scenario::load(ScenarioParts {
            name: None,
            fields: fields.clone(),
            coordinates,
            terrain,
            terrain_base: PathBuf::new(),
            vehicle_file: inputs.vehicle.clone(),
            vehicle_table: None,
            overrides,
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

fn validate(inputs: &Inputs, json: bool) -> Result<(), Failure> {
    let scenario = load_scenario(inputs)?;
    let summary = ScenarioSummary::of(&scenario);
    if json {
        println!(
            "{}",
            serde_json::to_string_pretty(&summary).expect("a summary serialises")
        );
    } else {
        print!("{}", summary.to_text());
        println!("valid");
    }
    Ok(())
}

fn load_terrain(argument: &str, cell: Option<f64>) -> Result<Box<dyn Terrain>, InputError> {
    let mut spec = TerrainSpec::from_argument(argument)?;
    if let TerrainSpec::File { cell_m, .. } = &mut spec {
        *cell_m = cell;
    }
    spec.load(Path::new(""), agripath::model::CoordinateSystem::Local)
}

fn terrain(action: TerrainAction) -> Result<(), Failure> {
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
                println!(
                    "{}",
                    serde_json::to_string_pretty(&value).expect("JSON value")
                );
            } else {
                println!("{}", model.describe());
                match extent {
                    Some(e) => println!(
                        "extent x {:.3}..{:.3}, y {:.3}..{:.3} ({:.1} × {:.1})",
                        e.min_x,
                        e.max_x,
                        e.min_y,
                        e.max_y,
                        e.width(),
                        e.height()
                    ),
                    None => println!("extent unbounded"),
                }
                if let Some((low, high)) = range {
                    println!("heights {low:.3}..{high:.3} m");
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
            println!("{}", lines.join("\n"));
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
            println!(
                "wrote {} ({} × {} pixels)",
                out.display(),
                shaded.width,
                shaded.height
            );
            Ok(())
        }
    }
}
