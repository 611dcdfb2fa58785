//! A scenario ties fields, terrain, vehicle and settings together. It comes from a scenario
//! TOML file (`data/scenarios/*.toml`) or from command-line parts; either way the result is
//! validated once, and every stage after it can rely on it.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::error::{Fault, InputError, TerrainError};
use crate::files::read_text;
use crate::geometry::validate::point_in_ring;
use crate::input::{read_farm, CoordinateChoice};
use crate::model::vehicle::one_line;
use crate::model::{Farm, Vehicle};
use crate::terrain::{Terrain, TerrainSpec};

/// Command-line figures that override the vehicle file.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct VehicleOverrides {
    /// Swath width, metres (overrides the vehicle).
    #[cfg_attr(
        feature = "cli",
        arg(
            long = "swath-width",
            value_name = "SWATH_WIDTH",
            allow_negative_numbers = true
        )
    )]
    pub swath_width_m: Option<f64>,
    /// Spray height above the terrain, metres (overrides the vehicle).
    #[cfg_attr(
        feature = "cli",
        arg(
            long = "spray-height",
            value_name = "SPRAY_HEIGHT",
            allow_negative_numbers = true
        )
    )]
    pub spray_height_m: Option<f64>,
    /// Safe transfer height h, metres (overrides the vehicle).
    #[cfg_attr(
        feature = "cli",
        arg(
            long = "safe-height",
            value_name = "SAFE_HEIGHT",
            allow_negative_numbers = true
        )
    )]
    pub safe_height_m: Option<f64>,
}

/// The parts of a scenario before loading.
#[derive(Debug, Clone, Default)]
pub struct ScenarioParts {
    /// The scenario's name; the field file's stem when absent.
    pub name: Option<String>,
    /// The field file (GeoJSON, KML or KMZ).
    pub fields: PathBuf,
    /// How the field file's coordinates are read.
    pub coordinates: CoordinateChoice,
    /// The terrain; when absent, the field file's own terrain, else flat ground at 0 m.
    pub terrain: Option<TerrainSpec>,
    /// Folder relative terrain paths are taken from.
    pub terrain_base: PathBuf,
    /// The vehicle file (TOML); the default vehicle when absent.
    pub vehicle_file: Option<PathBuf>,
    /// Vehicle keys given inline (a scenario's `[vehicle]` table), over the vehicle file.
    pub vehicle_table: Option<toml::Table>,
    /// Figures from the command line, over the vehicle file and table.
    pub overrides: VehicleOverrides,
    /// Keep overlapping fields and spray each overlap once (`--allow-overlap`), instead of
    /// refusing them.
    pub allow_overlap: bool,
}

/// Everything a plan needs, validated.
pub struct Scenario {
    /// The scenario's name.
    pub name: String,
    /// The farm, validated (overlaps resolved or refused).
    pub farm: Farm,
    /// The terrain the plan uses, as described.
    pub terrain_spec: TerrainSpec,
    /// Whether the terrain was given (a scenario's `[terrain]` or `--terrain`), not taken
    /// from the field file or assumed flat: a stated `flat:H` gives sea-level heights.
    pub terrain_stated: bool,
    /// The terrain model the spec loaded, covering every field.
    pub terrain: Box<dyn Terrain>,
    /// The vehicle, validated, with its overrides applied.
    pub vehicle: Vehicle,
    /// The vehicle file it was read from (`None`: the default vehicle or a scenario's
    /// inline table), so that a fault of the vehicle names its file.
    pub vehicle_file: Option<PathBuf>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ScenarioFile {
    name: Option<String>,
    fields: PathBuf,
    crs: Option<String>,
    vehicle_file: Option<PathBuf>,
    vehicle: Option<toml::Table>,
    terrain: Option<TerrainSpec>,
    #[serde(default)]
    allow_overlap: bool,
}

/// The scenario file's `[vehicle]` table read as a vehicle straight from the text, so that a
/// wrong type or an unknown key in it is reported at its line and column (the table merged
/// later has no places). The other keys are [`ScenarioFile`]'s to check.
#[derive(Deserialize)]
struct InlineVehicle {
    #[serde(rename = "vehicle")]
    _vehicle: Vehicle,
}

impl Scenario {
    /// Reads a scenario TOML file; paths in it are relative to its folder. `allow_overlap`
    /// (`--allow-overlap`) adds to the file's own `allow_overlap`.
    pub fn from_file(
        path: &Path,
        overrides: VehicleOverrides,
        allow_overlap: bool,
    ) -> Result<Self, InputError> {
        let text = read_text(path)?;
        let file: ScenarioFile =
            toml::from_str(&text).map_err(|error| InputError::toml(path, &error, &text))?;
        if file.vehicle.is_some() {
            toml::from_str::<InlineVehicle>(&text)
                .map_err(|error| InputError::toml(path, &error, &text))?;
        }
        let base = path.parent().unwrap_or(Path::new("")).to_path_buf();
        let coordinates = match file.crs.as_deref() {
            None => CoordinateChoice::FromFile,
            Some("local") => CoordinateChoice::Local,
            Some(other) => {
                return Err(InputError::new(
                    path,
                    Fault::InvalidValue {
                        what: "crs".into(),
                        value: other.into(),
                        why: "the only setting is \"local\" (leave it out for lon/lat)".into(),
                    },
                ))
            }
        };
        Self::load(ScenarioParts {
            name: file.name,
            fields: base.join(&file.fields),
            coordinates,
            terrain: file.terrain,
            terrain_base: base.clone(),
            vehicle_file: file.vehicle_file.map(|vehicle| base.join(vehicle)),
            vehicle_table: file.vehicle,
            overrides,
            allow_overlap: allow_overlap || file.allow_overlap,
        })
        .map_err(|error| {
            if error.file.as_os_str().is_empty() {
                InputError {
                    file: path.to_path_buf(),
                    ..error
                }
            } else {
                error
            }
        })
    }

    /// Loads and checks every part.
    pub fn load(parts: ScenarioParts) -> Result<Self, InputError> {
        let farm = read_farm(&parts.fields, parts.coordinates)?;
        Self::with_farm(farm, parts)
    }

    /// Completes a scenario around a farm already read (the embedded demo farm, for one).
    pub fn with_farm(mut farm: Farm, parts: ScenarioParts) -> Result<Self, InputError> {
        farm.resolve_overlaps(parts.allow_overlap)
            .map_err(|fault| InputError::new(&farm.source, fault))?;
        let vehicle = load_vehicle(&parts)?;
        farm.notes.extend(vehicle.short_battery_note());
        let (terrain_spec, terrain_base) = match (&parts.terrain, &farm.embedded_terrain) {
            (Some(spec), _) => (spec.clone(), parts.terrain_base.clone()),
            (None, Some(spec)) => (
                spec.clone(),
                farm.source.parent().unwrap_or(Path::new("")).to_path_buf(),
            ),
            (None, None) => (
                TerrainSpec::Flat { height_m: 0.0 },
                parts.terrain_base.clone(),
            ),
        };
        let terrain = terrain_spec.load(&terrain_base, farm.coordinate_system)?;
        check_terrain_covers(&farm, terrain.as_ref()).map_err(|(field, fault)| {
            let file = match &terrain_spec {
                TerrainSpec::File { path, .. } => terrain_base.join(path),
                _ => farm.source.clone(),
            };
            InputError::new(file, fault).at(format!("field '{field}'"))
        })?;
        let name = parts.name.clone().unwrap_or_else(|| {
            farm.source
                .file_stem()
                .map(|stem| stem.to_string_lossy().into_owned())
                .unwrap_or_else(|| "plan".into())
        });
        Ok(Self {
            name,
            farm,
            terrain_stated: parts.terrain.is_some(),
            terrain_spec,
            terrain,
            vehicle,
            vehicle_file: parts.vehicle_file.clone(),
        })
    }
}

/// The vehicle the parts give (its file, else the default), with the overrides applied and
/// every figure checked.
pub(crate) fn load_vehicle(parts: &ScenarioParts) -> Result<Vehicle, InputError> {
    let (mut table, source) = match &parts.vehicle_file {
        Some(path) => {
            let text = read_text(path)?;
            let table: toml::Table =
                toml::from_str(&text).map_err(|error| InputError::toml(path, &error, &text))?;
            // Read as a vehicle straight from the text too, so that a wrong type or an unknown
            // key is reported at its line and column (the merged table below has no places).
            toml::from_str::<Vehicle>(&text)
                .map_err(|error| InputError::toml(path, &error, &text))?;
            (table, path.clone())
        }
        None => (toml::Table::new(), PathBuf::new()),
    };
    if let Some(inline) = &parts.vehicle_table {
        for (key, value) in inline {
            table.insert(key.clone(), value.clone());
        }
    }
    let overrides = [
        (
            "swath_width_m",
            parts.overrides.swath_width_m,
            "--swath-width",
        ),
        (
            "spray_height_m",
            parts.overrides.spray_height_m,
            "--spray-height",
        ),
        (
            "safe_height_m",
            parts.overrides.safe_height_m,
            "--safe-height",
        ),
    ];
    let mut vehicle: Vehicle =
        toml::Value::Table(table.clone())
            .try_into()
            .map_err(|error: toml::de::Error| {
                InputError::new(
                    &source,
                    Fault::Toml {
                        message: one_line(&error, ""),
                        line_column: None,
                    },
                )
            })?;
    vehicle
        .apply_stated(&table)
        .map_err(|fault| InputError::new(&source, fault))?;
    for (key, value, flag) in overrides {
        if let Some(value) = value {
            match key {
                "swath_width_m" => vehicle.swath_width_m = value,
                "spray_height_m" => vehicle.spray_height_m = value,
                _ => vehicle.safe_height_m = value,
            }
            // Check the flag on its own, so the message names the flag and not the file.
            let mut probe = Vehicle::default();
            match key {
                "swath_width_m" => probe.swath_width_m = value,
                "spray_height_m" => probe.spray_height_m = value,
                _ => probe.safe_height_m = value,
            }
            probe
                .validate()
                .map_err(|fault| InputError::new(flag, fault))?;
        }
    }
    vehicle
        .validate()
        .map_err(|fault| InputError::new(&source, fault))?;
    Ok(vehicle)
}

/// Every field must lie on the terrain model: its boundary vertices and a lattice of points
/// inside it are sampled.
fn check_terrain_covers(farm: &Farm, terrain: &dyn Terrain) -> Result<(), (String, Fault)> {
    for field in &farm.fields {
        let fail = |error: TerrainError| {
            let (x, y) = match error {
                TerrainError::Outside { x, y } | TerrainError::NoData { x, y } => (x, y),
            };
            let (input_x, input_y) = farm.coordinate_system.to_input(x, y);
            (
                field.name.clone(),
                Fault::Structure(format!(
                    "the terrain model does not cover the field: {error} (input coordinates {input_x:.6}, {input_y:.6})"
                )),
            )
        };
        for ring in std::iter::once(field.polygon.exterior()).chain(field.polygon.interiors()) {
            for point in &ring.0 {
                terrain.height_m(point.x, point.y).map_err(fail)?;
            }
        }
        let exterior = &field.polygon.exterior().0;
        let (mut min_x, mut min_y, mut max_x, mut max_y) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
        for point in exterior {
            min_x = min_x.min(point.x);
            min_y = min_y.min(point.y);
            max_x = max_x.max(point.x);
            max_y = max_y.max(point.y);
        }
        let steps = 32;
        for row in 0..=steps {
            for column in 0..=steps {
                let x = min_x + (max_x - min_x) * column as f64 / steps as f64;
                let y = min_y + (max_y - min_y) * row as f64 / steps as f64;
                if point_in_ring(geo::Coord { x, y }, exterior) {
                    terrain.height_m(x, y).map_err(fail)?;
                }
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::from_utm;
    use crate::model::CoordinateSystem;

    fn data(relative: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../data")
            .join(relative)
    }

    #[test]
    fn a_bad_inline_vehicle_is_placed_at_its_line_and_column() {
        let folder =
            std::env::temp_dir().join(format!("agripath-inline-vehicle-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        let scenario = folder.join("scenario.toml");
        std::fs::write(
            &scenario,
            "fields = \"fields.geojson\"\n\n[vehicle]\nname = \"x\"\nswath_width_m = \"wide\"\n",
        )
        .unwrap();
        let Err(error) = Scenario::from_file(&scenario, VehicleOverrides::default(), false) else {
            panic!("a string swath width was accepted");
        };
        let error = error.to_string();
        let place = format!("{}:5:17:", scenario.display());
        assert!(error.starts_with(&place), "{error}");
        assert!(
            error.contains("swath_width_m") || error.contains("wide"),
            "{error}"
        );
        assert!(!error.contains('\n'), "{error}");
        std::fs::remove_dir_all(&folder).unwrap();
    }

    /// Lon/lat fields planned in UTM 32N over a DEM in EPSG:4326: each query goes back to
    /// lon/lat, and the DEM's linear heights come back exactly.
    #[test]
    fn lon_lat_dem_is_sampled_where_the_fields_are() {
        let folder = std::env::temp_dir().join(format!("agripath-lonlat-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        let fields = folder.join("fields.geojson");
        std::fs::write(
            &fields,
            r#"{"type":"Polygon","coordinates":[[[8.505,47.305],[8.52,47.305],[8.52,47.315],[8.505,47.305]]]}"#,
        )
        .unwrap();
        let scenario = Scenario::load(ScenarioParts {
            fields: fields.clone(),
            terrain: Some(TerrainSpec::File {
                path: data("test/geotiff/lonlat_4326_float64.tif"),
                cell_m: None,
            }),
            ..ScenarioParts::default()
        })
        .unwrap();
        std::fs::remove_dir_all(&folder).unwrap();
        let CoordinateSystem::Utm(zone) = scenario.farm.coordinate_system else {
            panic!("lon/lat fields are planned in UTM")
        };
        for point in &scenario.farm.fields[0].polygon.exterior().0 {
            let (lon, lat) = from_utm(point.x, point.y, zone);
            let expected = 1000.0 * (lon - 8.5) + 2000.0 * (lat - 47.3);
            let height = scenario.terrain.height_m(point.x, point.y).unwrap();
            assert!((height - expected).abs() < 1e-6, "{height} vs {expected}");
        }
    }

    #[test]
    fn every_example_scenario_loads() {
        let mut loaded = 0;
        for entry in std::fs::read_dir(data("scenarios")).unwrap() {
            let path = entry.unwrap().path();
            if path
                .extension()
                .is_some_and(|extension| extension == "toml")
            {
                Scenario::from_file(&path, VehicleOverrides::default(), false)
                    .unwrap_or_else(|error| panic!("{error}"));
                loaded += 1;
            }
        }
        // An empty or missing folder must not pass.
        assert!(loaded >= 10, "{loaded} scenarios loaded");
    }

    #[test]
    fn flags_override_the_vehicle_file() {
        let scenario = Scenario::from_file(
            &data("scenarios/seed001_farm.toml"),
            VehicleOverrides {
                swath_width_m: Some(6.5),
                ..VehicleOverrides::default()
            },
            false,
        )
        .unwrap();
        assert_eq!(scenario.vehicle.swath_width_m, 6.5);
        assert_eq!(scenario.vehicle.safe_height_m, 18.0);
    }
}
