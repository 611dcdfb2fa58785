//! What was read, for people (`agripath validate`) and programs (`--json`).

use serde::Serialize;

use crate::scenario::Scenario;
use crate::terrain::Extent;

/// One field as read.
#[derive(Debug, Clone, Serialize)]
pub struct FieldSummary {
    /// The field's name.
    pub name: String,
    /// Area inside the boundary less the holes, m².
    pub area_m2: f64,
    /// Number of holes.
    pub holes: usize,
    /// Number of distinct vertices over all rings.
    pub vertices: usize,
    /// Lowest and highest terrain under the field's bounding box, metres.
    pub terrain_range_m: Option<[f64; 2]>,
}

/// What a scenario holds, as `agripath validate` shows it.
#[derive(Debug, Clone, Serialize)]
pub struct ScenarioSummary {
    /// The scenario's name.
    pub name: String,
    /// The field file, as given.
    pub fields_file: String,
    /// The coordinate system, as [`crate::model::CoordinateSystem::describe`] words it.
    pub coordinate_system: String,
    /// Each field, in file order.
    pub fields: Vec<FieldSummary>,
    /// Number of obstacles (no-spray zones).
    pub obstacles: usize,
    /// Number of access features (roads, tracks, yards where the supply point may stand).
    pub access: usize,
    /// Each marker as "name (kind)".
    pub markers: Vec<String>,
    /// Total area of the fields less their holes, m².
    pub total_area_m2: f64,
    /// [min_x, min_y, max_x, max_y] of the farm in planning metres.
    pub farm_bounds_m: [f64; 4],
    /// The terrain model, as it describes itself.
    pub terrain: String,
    /// [min_x, min_y, max_x, max_y] of the terrain model, when it is bounded.
    pub terrain_extent: Option<[f64; 4]>,
    /// Lowest and highest terrain over the terrain's extent (the farm's box when unbounded), metres.
    pub terrain_range_m: Option<[f64; 2]>,
    /// The vehicle's name.
    pub vehicle: String,
    /// Swath width, metres.
    pub swath_width_m: f64,
    /// Height above the terrain while spraying (a survey: while photographing), metres.
    pub spray_height_m: f64,
    /// Whether the vehicle surveys with a camera (`[camera]`) rather than sprays.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub surveys: bool,
    /// Seed 001's h: the climb above spray height for a transfer that leaves the work area, metres.
    pub safe_height_m: f64,
    /// What the field file's reading noted but did not refuse (two fields of one name, an
    /// access road that runs into a field, …), as the text form prints after `note:`.
    pub notes: Vec<String>,
}

impl ScenarioSummary {
    /// The summary of a loaded scenario.
    pub fn of(scenario: &Scenario) -> Self {
        let farm = &scenario.farm;
        let terrain = scenario.terrain.as_ref();
        let fields = farm
            .fields
            .iter()
            .map(|field| {
                let bounds = geo::BoundingRect::bounding_rect(&field.polygon)
                    .expect("a valid field has a bounding box");
                FieldSummary {
                    name: field.name.clone(),
                    area_m2: field.area_m2(),
                    holes: field.holes(),
                    vertices: field.vertices(),
                    terrain_range_m: terrain
                        .height_range_m(Extent {
                            min_x: bounds.min().x,
                            min_y: bounds.min().y,
                            max_x: bounds.max().x,
                            max_y: bounds.max().y,
                        })
                        .map(|(low, high)| [low, high]),
                }
            })
            .collect();
        let bounds = farm.bounds();
        let farm_extent = Extent {
            min_x: bounds.min().x,
            min_y: bounds.min().y,
            max_x: bounds.max().x,
            max_y: bounds.max().y,
        };
        let terrain_extent = terrain.extent();
        Self {
            name: scenario.name.clone(),
            fields_file: farm.source.display().to_string(),
            coordinate_system: farm.coordinate_system.describe(),
            fields,
            obstacles: farm.obstacles.len(),
            access: farm.access.len(),
            markers: farm
                .markers
                .iter()
                // What the plan makes of the point: a launch point, or its kind; a point
                // with no kind reads "marker", not the features' default "field".
                .map(|marker| {
                    let role = if marker.is_launch() {
                        "launch point"
                    } else if marker.kind == "field" {
                        "marker"
                    } else {
                        marker.kind.as_str()
                    };
                    format!("{} ({role})", marker.name)
                })
                .collect(),
            total_area_m2: farm.total_area_m2(),
            farm_bounds_m: [
                farm_extent.min_x,
                farm_extent.min_y,
                farm_extent.max_x,
                farm_extent.max_y,
            ],
            terrain: terrain.describe(),
            terrain_extent: terrain_extent.map(|e| [e.min_x, e.min_y, e.max_x, e.max_y]),
            terrain_range_m: terrain
                .height_range_m(terrain_extent.unwrap_or(farm_extent))
                .map(|(low, high)| [low, high]),
            vehicle: scenario.vehicle.name.clone(),
            swath_width_m: scenario.vehicle.swath_width_m,
            spray_height_m: scenario.vehicle.spray_height_m,
            surveys: scenario.vehicle.is_survey(),
            safe_height_m: scenario.vehicle.safe_height_m,
            notes: farm.notes.clone(),
        }
    }

    /// A short text for the terminal.
    pub fn to_text(&self) -> String {
        let mut text = String::new();
        let range = |range: Option<[f64; 2]>| match range {
            Some([low, high]) => format!("{low:.1}..{high:.1} m"),
            None => "no data".to_string(),
        };
        text.push_str(&format!("scenario  {}\n", self.name));
        text.push_str(&format!(
            "fields    {} ({})\n",
            self.fields_file, self.coordinate_system
        ));
        let name_width = self
            .fields
            .iter()
            .map(|field| field.name.chars().count())
            .fold(14, usize::max);
        text.push_str(&format!(
            "          {:<name_width$} {:>10} {:>6} {:>9}  {}\n",
            "name", "area ha", "holes", "vertices", "terrain"
        ));
        for field in &self.fields {
            text.push_str(&format!(
                "          {:<name_width$} {:>10.3} {:>6} {:>9}  {}\n",
                field.name,
                field.area_m2 / 10_000.0,
                field.holes,
                field.vertices,
                range(field.terrain_range_m)
            ));
        }
        text.push_str(&format!(
            "          {} field(s), {:.3} ha, {} obstacle(s){}{}\n",
            self.fields.len(),
            self.total_area_m2 / 10_000.0,
            self.obstacles,
            if self.access == 0 {
                String::new()
            } else {
                format!(", {} access feature(s)", self.access)
            },
            if self.markers.is_empty() {
                String::new()
            } else {
                format!(", markers: {}", self.markers.join(", "))
            }
        ));
        let [x0, y0, x1, y1] = self.farm_bounds_m;
        text.push_str(&format!(
            "          bounds x {x0:.1}..{x1:.1}, y {y0:.1}..{y1:.1} m ({:.0} × {:.0} m)\n",
            x1 - x0,
            y1 - y0
        ));
        text.push_str(&format!("terrain   {}\n", self.terrain));
        if let Some([x0, y0, x1, y1]) = self.terrain_extent {
            text.push_str(&format!(
                "          extent x {x0:.1}..{x1:.1}, y {y0:.1}..{y1:.1}\n"
            ));
        }
        text.push_str(&format!(
            "          heights {}\n",
            range(self.terrain_range_m)
        ));
        text.push_str(&format!(
            "vehicle   {}: swath {} m, {} height {} m, safe height h {} m\n",
            self.vehicle,
            self.swath_width_m,
            crate::model::Vehicle::work_words(self.surveys)[0],
            self.spray_height_m,
            self.safe_height_m
        ));
        text
    }
}
