//! From format-neutral features to a validated [`Farm`]: frame choice, projection, ring
//! cleaning, polygon validity, size limits. Shared by every field format.

use std::path::Path;

use geo::{Coord, LineString, Polygon};

use crate::error::{Fault, InputError};
use crate::geometry::validate::{clean_ring, validate_polygon};
use crate::geometry::{mean_longitude, to_utm, wrap_longitude, UtmZone};
use crate::limits::{
    MAX_FARM_EXTENT_M, MAX_FARM_LONGITUDE_SPAN_DEG, MAX_LOCAL_COORDINATE_M, MAX_POLYGONS,
    MAX_VERTICES,
};
use crate::model::{Access, AccessShape, CoordinateSystem, Farm, Field, Marker, Obstacle};
use crate::terrain::TerrainSpec;

/// Rings as read: the first is the outer boundary, the rest are holes; positions are
/// `[x, y]` or `[lon, lat]` as the file has them.
pub type RawRings = Vec<Vec<[f64; 2]>>;

/// The geometry of a raw feature.
#[derive(Debug, Clone, PartialEq)]
pub enum RawGeometry {
    /// One or more polygons (a MultiPolygon has several), each as [`RawRings`].
    Polygons(Vec<RawRings>),
    /// A single position, `[x, y]` or `[lon, lat]`: it becomes a [`Marker`].
    Point([f64; 2]),
    /// One or more lines (a MultiLineString has several), positions as read: only an
    /// `access` feature (a road or track) may be a line.
    Lines(Vec<Vec<[f64; 2]>>),
}

/// Radius of an obstacle drawn as a point with no `radius_m`, metres: a pole or a pylon's leg
/// (decision 0037). The planner keeps its swaths and the preflight its checks off the circle.
pub const POINT_OBSTACLE_RADIUS_M: f64 = 1.0;
/// Smallest radius of an obstacle point, metres: a thin pole; below a few centimetres the
/// files' rounding is as large as the obstacle.
pub const MIN_POINT_OBSTACLE_RADIUS_M: f64 = 0.1;
/// Corners of the polygon an obstacle point becomes (drawn round its circle).
const POINT_OBSTACLE_CORNERS: usize = 16;

/// One feature of a field file, before any checking.
#[derive(Debug, Clone, PartialEq)]
pub struct RawFeature {
    /// "feature 3" or "Placemark 'North'": how an error message names it.
    pub place: String,
    /// The feature's name, when the file gives one.
    pub name: Option<String>,
    /// `properties.kind`: `field` when absent, `obstacle` for no-spray zones, `access` for
    /// roads, tracks and yards.
    pub kind: Option<String>,
    /// `properties.radius_m`: the size of an obstacle drawn as a point (a pole, a pylon, a
    /// tree), [`POINT_OBSTACLE_RADIUS_M`] when absent.
    pub radius_m: Option<f64>,
    /// The feature's geometry.
    pub geometry: RawGeometry,
}

/// Builds the farm. `lon_lat` says whether positions are WGS84 degrees (then they are
/// projected to the UTM zone of the farm's centre) or local metres.
pub fn build(
    path: &Path,
    features: Vec<RawFeature>,
    lon_lat: bool,
    embedded_terrain: Option<TerrainSpec>,
) -> Result<Farm, InputError> {
    let polygon_count: usize = features
        .iter()
        .map(|feature| match &feature.geometry {
            RawGeometry::Polygons(polygons) => polygons.len(),
            RawGeometry::Point(_) | RawGeometry::Lines(_) => 0,
        })
        .sum();
    if polygon_count > MAX_POLYGONS {
        return Err(InputError::new(
            path,
            Fault::TooLarge(format!(
                "{polygon_count} polygons (limit {MAX_POLYGONS} per file)"
            )),
        ));
    }
    let vertex_count: usize = features
        .iter()
        .map(|feature| match &feature.geometry {
            RawGeometry::Polygons(polygons) => polygons.iter().flatten().map(Vec::len).sum(),
            RawGeometry::Point(_) => 1,
            RawGeometry::Lines(lines) => lines.iter().map(Vec::len).sum(),
        })
        .sum();
    if vertex_count > MAX_VERTICES {
        return Err(InputError::new(
            path,
            Fault::TooLarge(format!(
                "{vertex_count} vertices (limit {MAX_VERTICES} per file)"
            )),
        ));
    }

    let coordinate_system = if lon_lat {
        CoordinateSystem::Utm(zone_of(path, &features)?)
    } else {
        CoordinateSystem::Local
    };
    let project = |position: [f64; 2]| -> Result<Coord<f64>, Fault> {
        let [x, y] = position;
        if !x.is_finite() || !y.is_finite() {
            return Err(Fault::NonFinite);
        }
        match coordinate_system {
            CoordinateSystem::Local => {
                if x.abs() > MAX_LOCAL_COORDINATE_M || y.abs() > MAX_LOCAL_COORDINATE_M {
                    return Err(Fault::InvalidValue {
                        what: "coordinate".into(),
                        value: format!("({x}, {y})"),
                        why: format!(
                            "local coordinates are metres from the frame's origin and must lie within ±{} km of it, where the plane laid on the Earth at --origin keeps its scale (is this lon/lat? then drop \"crs\": \"local\"; a projected grid such as UTM? then give the fields in lon/lat)",
                            MAX_LOCAL_COORDINATE_M / 1000.0
                        ),
                    });
                }
                Ok(Coord { x, y })
            }
            CoordinateSystem::Utm(zone) => {
                let (easting, northing) = to_utm(x, y, zone);
                Ok(Coord {
                    x: easting,
                    y: northing,
                })
            }
        }
    };

    let mut fields = Vec::new();
    let mut notes = Vec::new();
    let mut obstacles = Vec::new();
    let mut markers = Vec::new();
    let mut access = Vec::new();
    for feature in features {
        let kind = feature.kind.clone().unwrap_or_else(|| "field".to_string());
        let fault_here = |fault: Fault| InputError::new(path, fault).at(feature.place.clone());
        match &feature.geometry {
            RawGeometry::Point(position) if kind == "obstacle" => {
                let radius_m = feature.radius_m.unwrap_or(POINT_OBSTACLE_RADIUS_M);
                if !(radius_m.is_finite()
                    && (MIN_POINT_OBSTACLE_RADIUS_M..=1000.0).contains(&radius_m))
                {
                    return Err(fault_here(Fault::InvalidValue {
                        what: "radius_m".into(),
                        value: radius_m.to_string(),
                        why: format!("an obstacle point's radius is metres, {MIN_POINT_OBSTACLE_RADIUS_M} to 1000"),
                    }));
                }
                let centre = project(*position).map_err(fault_here)?;
                let number = obstacles.len() + 1;
                let name = feature
                    .name
                    .clone()
                    .unwrap_or_else(|| format!("obstacle {number}"));
                if feature.radius_m.is_none() {
                    notes.push(format!(
                        "obstacle '{name}' is a point: kept clear as a circle of radius {radius_m} m (give it radius_m for its real size)"
                    ));
                }
                obstacles.push(Obstacle {
                    name,
                    polygon: circle_around(centre, radius_m),
                });
            }
            RawGeometry::Point(position) => markers.push(Marker {
                kind: kind.clone(),
                name: feature.name.clone().unwrap_or_else(|| kind.clone()),
                position: project(*position).map_err(fault_here)?,
            }),
            RawGeometry::Lines(lines) => {
                if kind == "field" {
                    return Err(fault_here(Fault::Structure(
                        "geometry type 'LineString' cannot be a field: use Polygon or MultiPolygon (Point for markers; a line is a road or track of kind 'access')".into(),
                    )));
                }
                if kind != "access" {
                    return Err(fault_here(Fault::Structure(format!(
                        "properties.kind is '{kind}': a line (LineString) can only be a road or track of kind 'access'"
                    ))));
                }
                for (part, line) in lines.iter().enumerate() {
                    let shape = build_line(line, &project).map_err(|fault| {
                        let error = fault_here(fault);
                        if lines.len() > 1 {
                            error.at(format!("line {}", part + 1))
                        } else {
                            error
                        }
                    })?;
                    let number = access.len() + 1;
                    access.push(Access {
                        name: feature
                            .name
                            .clone()
                            .unwrap_or_else(|| format!("access {number}")),
                        shape: AccessShape::Line(shape),
                    });
                }
            }
            RawGeometry::Polygons(polygons) => {
                let several = polygons.len() > 1;
                for (part, rings) in polygons.iter().enumerate() {
                    let part_place = |error: InputError| {
                        if several {
                            error.at(format!("polygon {}", part + 1))
                        } else {
                            error
                        }
                    };
                    for (ring_index, ring) in rings.iter().enumerate() {
                        if ring.len() > 2 && ring.first() != ring.last() {
                            notes.push(format!(
                                "{}{}: {} was not closed (its last position is not its first); closed it",
                                feature.place,
                                if several { format!(", polygon {}", part + 1) } else { String::new() },
                                if ring_index == 0 { "the boundary".to_string() } else { format!("hole {ring_index}") }
                            ));
                        }
                    }
                    let polygon = build_polygon(rings, &project).map_err(|fault| {
                        part_place(fault_here(in_input_terms(fault, coordinate_system)))
                    })?;
                    let base_name = feature.name.clone();
                    match kind.as_str() {
                        "field" => {
                            let number = fields.len() + 1;
                            let name = match (&base_name, several) {
                                (Some(name), false) => name.clone(),
                                (Some(name), true) => format!("{name}.{}", part + 1),
                                (None, _) => format!("field {number}"),
                            };
                            fields.push(Field::new(name, polygon));
                        }
                        "obstacle" => {
                            let number = obstacles.len() + 1;
                            obstacles.push(Obstacle {
                                name: base_name.unwrap_or_else(|| format!("obstacle {number}")),
                                polygon,
                            });
                        }
                        "access" => {
                            let number = access.len() + 1;
                            access.push(Access {
                                name: base_name.unwrap_or_else(|| format!("access {number}")),
                                shape: AccessShape::Area(polygon),
                            });
                        }
                        other => {
                            return Err(fault_here(Fault::Structure(format!(
                                "properties.kind is '{other}': a polygon must be a 'field', an 'obstacle' or an 'access' yard"
                            ))))
                        }
                    }
                }
            }
        }
    }
    if fields.is_empty() {
        return Err(InputError::new(path, Fault::NoFields));
    }
    notes.extend(name_fields_apart(&mut fields));
    notes.extend(access_inside_fields(&access, &fields));
    let farm = Farm {
        source: path.to_path_buf(),
        coordinate_system,
        fields,
        obstacles,
        markers,
        access,
        embedded_terrain,
        stated_swath_width_m: None,
        notes,
    };
    let bounds = farm.bounds();
    let extent = bounds.width().max(bounds.height());
    if extent > MAX_FARM_EXTENT_M {
        return Err(InputError::new(
            path,
            Fault::TooLarge(format!(
                "the fields span {:.0} km (limit {:.0} km): split the farm into work areas",
                extent / 1000.0,
                MAX_FARM_EXTENT_M / 1000.0
            )),
        ));
    }
    if coordinate_system == CoordinateSystem::Local && looks_like_degrees(&bounds) {
        return Err(InputError::new(
            path,
            Fault::Structure(format!(
                "the fields lie within x {:.4} … {:.4}, y {:.4} … {:.4}, under 1 m across if these are metres as \"crs\": \"local\" (or --crs local) says: they look like longitude and latitude, so drop the local frame",
                bounds.min().x,
                bounds.max().x,
                bounds.min().y,
                bounds.max().y
            )),
        ));
    }
    Ok(farm)
}

/// The polygon round the circle of `radius_m` about `centre` (its sides touch the circle, so
/// the circle is inside it).
fn circle_around(centre: Coord<f64>, radius_m: f64) -> geo::Polygon<f64> {
    let step = std::f64::consts::TAU / POINT_OBSTACLE_CORNERS as f64;
    let corner_m = radius_m / (step / 2.0).cos();
    let corners: Vec<Coord<f64>> = (0..=POINT_OBSTACLE_CORNERS)
        .map(|k| {
            let angle = step * (k % POINT_OBSTACLE_CORNERS) as f64;
            Coord {
                x: centre.x + corner_m * angle.cos(),
                y: centre.y + corner_m * angle.sin(),
            }
        })
        .collect();
    geo::Polygon::new(geo::LineString(corners), vec![])
}

/// Whether a farm read in local metres is one in degrees read wrongly: under 1 m across (no
/// field so small can be sprayed) and where a longitude and a latitude can be.
fn looks_like_degrees(bounds: &geo::Rect<f64>) -> bool {
    bounds.width().max(bounds.height()) < 1.0
        && bounds.min().x >= -180.0
        && bounds.max().x <= 180.0
        && bounds.min().y >= -90.0
        && bounds.max().y <= 90.0
}

/// A note for each access feature (a road, a track, a yard) that runs into a field: the
/// supply point stands only on its parts outside fields, holes and obstacles, so a road
/// across a field is two roads, and a yard over one is smaller than drawn (a fifth trial's
/// road across a field gave no word of it).
fn access_inside_fields(access: &[Access], fields: &[Field]) -> Vec<String> {
    use geo::algorithm::relate::Relate;
    use geo::coordinate_position::CoordPos;
    use geo::dimensions::Dimensions;
    let mut notes = Vec::new();
    for road in access {
        for field in fields {
            let matrix = match &road.shape {
                AccessShape::Line(line) => field.polygon.relate(line),
                AccessShape::Area(area) => field.polygon.relate(area),
            };
            if matrix.get(CoordPos::Inside, CoordPos::Inside) != Dimensions::Empty {
                let (kind, what) = match road.shape {
                    AccessShape::Line(_) => {
                        ("crosses", "only its stretches outside fields hold it")
                    }
                    AccessShape::Area(_) => ("overlaps", "only its part outside fields holds it"),
                };
                notes.push(format!(
                    "access '{}' {kind} field '{}': it is sprayed there, and the supply point stands off the crop: {what}",
                    road.name, field.name
                ));
            }
        }
    }
    notes
}

/// Gives fields that share a name (two polygons both called "Untitled Polygon" in a KML, say) names
/// of their own, `NAME (2)`, `NAME (3)`, …, in the file's order, so the summary, the sheet, the
/// map and `report.json` tell them apart; returns a note for each name changed.
fn name_fields_apart(fields: &mut [Field]) -> Vec<String> {
    let mut taken: std::collections::HashSet<String> =
        fields.iter().map(|field| field.name.clone()).collect();
    let mut seen: std::collections::HashSet<String> = std::collections::HashSet::new();
    let mut notes = Vec::new();
    for field in fields.iter_mut() {
        if seen.insert(field.name.clone()) {
            continue;
        }
        let mut copy = 2;
        let renamed = loop {
            let candidate = format!("{} ({copy})", field.name);
            if !taken.contains(&candidate) {
                break candidate;
            }
            copy += 1;
        };
        notes.push(format!(
            "two fields are named '{}': the later one is '{renamed}' in the plan",
            field.name
        ));
        taken.insert(renamed.clone());
        seen.insert(renamed.clone());
        field.name = renamed;
    }
    notes
}

/// A road or track in planning metres: repeated points dropped, at least two left.
fn build_line(
    positions: &[[f64; 2]],
    project: &dyn Fn([f64; 2]) -> Result<Coord<f64>, Fault>,
) -> Result<LineString<f64>, Fault> {
    let mut points: Vec<Coord<f64>> = Vec::with_capacity(positions.len());
    for &position in positions {
        let point = project(position)?;
        if points.last() != Some(&point) {
            points.push(point);
        }
    }
    if points.len() < 2 {
        return Err(Fault::Structure(
            "an access line needs at least two distinct positions".into(),
        ));
    }
    Ok(LineString::new(points))
}

/// A geometry fault with its place in the input's coordinates: lon/lat (6 decimals, about
/// 0.1 m) for a lon/lat file, whose users never saw the UTM metres it was checked in.
fn in_input_terms(fault: Fault, frame: CoordinateSystem) -> Fault {
    let CoordinateSystem::Utm(_) = frame else {
        return fault;
    };
    let lon_lat = |x: f64, y: f64| {
        let (lon, lat) = frame.to_input(x, y);
        format!("near lon {lon:.6}, lat {lat:.6}")
    };
    match fault {
        Fault::SelfIntersection { x, y } => {
            Fault::Structure(format!("boundary intersects itself {}", lon_lat(x, y)))
        }
        Fault::HoleCrossesShell { hole, x, y } => Fault::Structure(format!(
            "hole {hole} touches or crosses the outer boundary {} (a hole must lie inside it: redraw the boundary round the gap if the hole opens onto the edge)",
            lon_lat(x, y)
        )),
        Fault::HolesTouch {
            first,
            second,
            x,
            y,
        } => Fault::Structure(format!(
            "holes {first} and {second} touch along their edges {} without overlapping: draw them as one hole, or leave a gap between them",
            lon_lat(x, y)
        )),
        other => other,
    }
}

fn build_polygon(
    rings: &RawRings,
    project: &dyn Fn([f64; 2]) -> Result<Coord<f64>, Fault>,
) -> Result<Polygon<f64>, Fault> {
    let mut cleaned: Vec<LineString<f64>> = Vec::with_capacity(rings.len());
    for (index, ring) in rings.iter().enumerate() {
        let label = |fault: Fault| {
            if index == 0 {
                fault
            } else {
                Fault::Structure(format!("hole {index}: {fault}"))
            }
        };
        let positions: Vec<Coord<f64>> = ring
            .iter()
            .map(|&position| project(position))
            .collect::<Result<_, _>>()?;
        cleaned.push(clean_ring(&positions).map_err(label)?);
    }
    let mut rings = cleaned.into_iter();
    let exterior = rings.next().ok_or(Fault::DegenerateRing)?;
    let polygon = Polygon::new(exterior, rings.collect());
    validate_polygon(&polygon)?;
    Ok(polygon)
}

/// The UTM zone of the farm's centre (the mean longitude taken on the circle, so a farm on
/// the antimeridian is in zone 60 or 1, not zone 30); every position must be a real
/// longitude/latitude inside UTM's latitudes, and the farm no wider than
/// [`MAX_FARM_LONGITUDE_SPAN_DEG`].
fn zone_of(path: &Path, features: &[RawFeature]) -> Result<UtmZone, InputError> {
    let mut positions = Vec::new();
    for feature in features {
        let feature_positions: Box<dyn Iterator<Item = &[f64; 2]>> = match &feature.geometry {
            RawGeometry::Polygons(polygons) => Box::new(polygons.iter().flatten().flatten()),
            RawGeometry::Point(position) => Box::new(std::iter::once(position)),
            RawGeometry::Lines(lines) => Box::new(lines.iter().flatten()),
        };
        for &[lon, lat] in feature_positions {
            if !lon.is_finite() || !lat.is_finite() {
                return Err(InputError::new(path, Fault::NonFinite).at(feature.place.clone()));
            }
            if !(-180.0..=180.0).contains(&lon) || !(-90.0..=90.0).contains(&lat) {
                // Swapped, the pair would be a place: say so (the eleventh trial's file).
                let hint = if (-90.0..=90.0).contains(&lon) && (-180.0..=180.0).contains(&lat) {
                    "; are longitude and latitude swapped? GeoJSON and KML give longitude first"
                } else {
                    ""
                };
                return Err(
                    InputError::new(path, Fault::OutOfRange { lon, lat }).at(format!(
                        "{} (coordinates are read as WGS84 lon/lat; for metres in a local frame use \"crs\": \"local\" or --crs local{hint})",
                        feature.place
                    )),
                );
            }
            if !(-80.0..=84.0).contains(&lat) {
                return Err(InputError::new(
                    path,
                    Fault::Structure(format!(
                        "latitude {lat} is in a polar region (beyond 80°S..84°N, where UPS replaces UTM): agripath plans in UTM only"
                    )),
                )
                .at(feature.place.clone()));
            }
            positions.push((lon, lat));
        }
    }
    if positions.is_empty() {
        return Err(InputError::new(path, Fault::NoFields));
    }
    let centre_lon = mean_longitude(positions.iter().map(|&(lon, _)| lon));
    let centre_lat = positions.iter().map(|&(_, lat)| lat).sum::<f64>() / positions.len() as f64;
    let (west, east) = positions
        .iter()
        .fold((0.0f64, 0.0f64), |(west, east), &(lon, _)| {
            let offset = wrap_longitude(lon - centre_lon);
            (west.min(offset), east.max(offset))
        });
    if east - west > MAX_FARM_LONGITUDE_SPAN_DEG {
        return Err(InputError::new(
            path,
            Fault::TooLarge(format!(
                "the farm spans {:.2}° of longitude (limit {MAX_FARM_LONGITUDE_SPAN_DEG}°, one UTM zone's width): plan it in parts",
                east - west
            )),
        ));
    }
    Ok(UtmZone::containing(centre_lon, centre_lat))
}
