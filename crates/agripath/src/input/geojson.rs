//! GeoJSON field files (RFC 7946): FeatureCollection, Feature, or a bare Polygon/MultiPolygon.
//!
//! Positions are WGS84 lon/lat unless the top-level object carries the member
//! `"crs": "local"` (the data files of this project) or the caller forces local metres.
//! A `properties.kind` of `obstacle` marks a no-spray zone, `access` a road, track
//! (LineString, MultiLineString) or yard (Polygon) where a vehicle can stand; Points become
//! markers.

use std::path::Path;

use serde_json::{Map, Value};

use super::farm::{build, RawFeature, RawGeometry, RawRings};
use super::CoordinateChoice;
use crate::error::{Fault, InputError};
use crate::files::read_text;
use crate::model::Farm;
use crate::terrain::TerrainSpec;

/// Reads and validates a GeoJSON field file.
pub fn read(path: &Path, choice: CoordinateChoice) -> Result<Farm, InputError> {
    let text = read_text(path)?;
    parse(path, &text, choice)
}

/// Parses GeoJSON text; `path` only names the source in errors.
pub fn parse(path: &Path, text: &str, choice: CoordinateChoice) -> Result<Farm, InputError> {
    let fail = |fault: Fault| InputError::new(path, fault);
    let root: Value =
        serde_json::from_str(text).map_err(|error| fail(Fault::Json(error.to_string())))?;
    let object = root.as_object().ok_or_else(|| {
        fail(Fault::Structure(
            "the top level is not a JSON object".into(),
        ))
    })?;
    let local = match choice {
        CoordinateChoice::Local => true,
        CoordinateChoice::FromFile => crs_is_local(object).map_err(fail)?,
    };
    let embedded_terrain = match object.get("terrain") {
        Some(value) => {
            TerrainSpec::from_embedded(value).map_err(|fault| fail(fault).at("member 'terrain'"))?
        }
        None => None,
    };
    let features = match type_of(object).map_err(fail)? {
        "FeatureCollection" => {
            let list = object
                .get("features")
                .and_then(Value::as_array)
                .ok_or_else(|| {
                    fail(Fault::Structure(
                        "FeatureCollection has no 'features' array".into(),
                    ))
                })?;
            let mut features = Vec::with_capacity(list.len());
            for (index, feature) in list.iter().enumerate() {
                // Counted from 1, as people count (the mission files' sorties and rows too).
                let place = format!("feature {}", index + 1);
                if let Some(feature) = read_feature(feature, &place)
                    .map_err(|fault| fail(fault).at(named(feature, &place)))?
                {
                    features.push(feature);
                }
            }
            features
        }
        "Feature" => read_feature(&root, "feature 1")
            .map_err(|fault| fail(fault).at(named(&root, "feature 1")))?
            .into_iter()
            .collect(),
        _ => vec![RawFeature {
            place: "geometry".into(),
            name: None,
            kind: None,
            radius_m: None,
            geometry: read_geometry(object).map_err(|fault| fail(fault).at("geometry"))?,
        }],
    };
    let mut farm = build(path, features, !local, embedded_terrain)?;
    farm.stated_swath_width_m = object.get("swath_width_m").and_then(Value::as_f64);
    Ok(farm)
}

/// `"crs": "local"` (this project's convention) or an old-style named CRS that is WGS84.
fn crs_is_local(object: &Map<String, Value>) -> Result<bool, Fault> {
    match object.get("crs") {
        None | Some(Value::Null) => Ok(false),
        Some(Value::String(name)) if name.eq_ignore_ascii_case("local") => Ok(true),
        Some(Value::Object(crs)) => {
            let name = crs
                .get("properties")
                .and_then(|properties| properties.get("name"))
                .and_then(Value::as_str)
                .unwrap_or("");
            let wgs84 = ["CRS84", "EPSG:4326", "EPSG::4326"];
            if wgs84.iter().any(|known| name.to_ascii_uppercase().ends_with(known)) {
                Ok(false)
            } else {
                Err(Fault::Structure(format!(
                    "crs '{name}' is not supported: give WGS84 lon/lat (RFC 7946) or \"crs\": \"local\" for metres"
                )))
            }
        }
        Some(other) => Err(Fault::Structure(format!(
            "crs {other} is not understood: use \"crs\": \"local\" for metres or leave it out for WGS84 lon/lat"
        ))),
    }
}

fn type_of(object: &Map<String, Value>) -> Result<&str, Fault> {
    object
        .get("type")
        .and_then(Value::as_str)
        .ok_or_else(|| Fault::Structure("object has no 'type' string".into()))
}

/// A Feature; `None` for a feature without geometry (allowed by the RFC, nothing to plan).
fn read_feature(value: &Value, place: &str) -> Result<Option<RawFeature>, Fault> {
    let object = value
        .as_object()
        .ok_or_else(|| Fault::Structure("is not a JSON object".into()))?;
    let kind = type_of(object)?;
    if kind != "Feature" {
        return Err(Fault::Structure(format!(
            "type is '{kind}', expected 'Feature'"
        )));
    }
    let properties = match object.get("properties") {
        None | Some(Value::Null) => None,
        Some(Value::Object(properties)) => Some(properties),
        Some(_) => return Err(Fault::Structure("'properties' is not an object".into())),
    };
    let text_property = |key: &str| -> Result<Option<String>, Fault> {
        match properties.and_then(|properties| properties.get(key)) {
            None | Some(Value::Null) => Ok(None),
            Some(Value::String(text)) => Ok(Some(text.clone())),
            Some(Value::Number(number)) if key == "name" => Ok(Some(number.to_string())),
            Some(other) => Err(Fault::Structure(format!(
                "properties.{key} is {other}, expected a string"
            ))),
        }
    };
    let name = text_property("name")?;
    // `kind` is ours; `type` is what other tools write for the same (a launch point's "type": "home").
    let kind = match text_property("kind")? {
        Some(kind) => Some(kind),
        None => text_property("type")?,
    }
    .map(|kind| kind.to_ascii_lowercase());
    let geometry = match object.get("geometry") {
        None => return Err(Fault::Structure("has no 'geometry' member".into())),
        Some(Value::Null) => return Ok(None),
        Some(Value::Object(geometry)) => read_geometry(geometry)?,
        Some(_) => return Err(Fault::Structure("'geometry' is not an object".into())),
    };
    let place = match &name {
        Some(name) => format!("{place} ({name})"),
        None => place.to_string(),
    };
    let radius_m = match properties.and_then(|properties| properties.get("radius_m")) {
        None | Some(Value::Null) => None,
        Some(Value::Number(number)) => number.as_f64(),
        Some(other) => {
            return Err(Fault::Structure(format!(
                "properties.radius_m is {other}, expected a number of metres"
            )))
        }
    };
    Ok(Some(RawFeature {
        place,
        name,
        kind,
        radius_m,
        geometry,
    }))
}

/// `place` with the feature's name when it has one ("feature 25 (North)"): the
/// faults found while reading a feature name it as those found later do (a tenth trial's
/// unclosed ring was refused as "feature 25" alone, a self-intersection as "feature 19 (F17)").
fn named(feature: &Value, place: &str) -> String {
    match feature
        .get("properties")
        .and_then(|properties| properties.get("name"))
    {
        Some(Value::String(name)) => format!("{place} ({name})"),
        // A number is a name too, as `read_feature` takes it.
        Some(Value::Number(number)) => format!("{place} ({number})"),
        _ => place.to_string(),
    }
}

fn read_geometry(object: &Map<String, Value>) -> Result<RawGeometry, Fault> {
    let kind = type_of(object)?;
    let coordinates = || {
        object
            .get("coordinates")
            .ok_or_else(|| Fault::Structure(format!("{kind} has no 'coordinates'")))
    };
    match kind {
        "Polygon" => Ok(RawGeometry::Polygons(vec![read_polygon(coordinates()?)?])),
        "MultiPolygon" => {
            let parts = array(coordinates()?, "MultiPolygon coordinates")?;
            if parts.is_empty() {
                return Err(Fault::Structure("MultiPolygon has no polygons".into()));
            }
            Ok(RawGeometry::Polygons(
                parts.iter().map(read_polygon).collect::<Result<_, _>>()?,
            ))
        }
        "Point" => Ok(RawGeometry::Point(read_position(coordinates()?)?)),
        "LineString" => Ok(RawGeometry::Lines(vec![read_line(coordinates()?)?])),
        "MultiLineString" => {
            let parts = array(coordinates()?, "MultiLineString coordinates")?;
            if parts.is_empty() {
                return Err(Fault::Structure("MultiLineString has no lines".into()));
            }
            Ok(RawGeometry::Lines(
                parts.iter().map(read_line).collect::<Result<_, _>>()?,
            ))
        }
        other => Err(Fault::Structure(format!(
            "geometry type '{other}' cannot be a field: use Polygon or MultiPolygon (Point for markers, LineString for access roads)"
        ))),
    }
}

fn array<'a>(value: &'a Value, what: &str) -> Result<&'a Vec<Value>, Fault> {
    value
        .as_array()
        .ok_or_else(|| Fault::Structure(format!("{what} is not an array")))
}

fn read_polygon(value: &Value) -> Result<RawRings, Fault> {
    let rings = array(value, "Polygon coordinates")?;
    if rings.is_empty() {
        return Err(Fault::Structure("Polygon has no rings".into()));
    }
    let mut result = Vec::with_capacity(rings.len());
    for (index, ring) in rings.iter().enumerate() {
        let positions = array(ring, "a ring")?
            .iter()
            .map(read_position)
            .collect::<Result<Vec<_>, _>>()?;
        if positions.len() >= 2 && positions.first() != positions.last() {
            return Err(if index == 0 {
                Fault::UnclosedRing
            } else {
                Fault::Structure(format!("hole {index}: {}", Fault::UnclosedRing))
            });
        }
        result.push(positions);
    }
    Ok(result)
}

fn read_line(value: &Value) -> Result<Vec<[f64; 2]>, Fault> {
    array(value, "LineString coordinates")?
        .iter()
        .map(read_position)
        .collect()
}

fn read_position(value: &Value) -> Result<[f64; 2], Fault> {
    let numbers = array(value, "a position")?;
    if numbers.len() < 2 {
        return Err(Fault::Structure(format!(
            "position {value} has fewer than 2 numbers"
        )));
    }
    let number = |value: &Value| {
        value
            .as_f64()
            .ok_or_else(|| Fault::Structure(format!("position holds {value}, not a number")))
    };
    Ok([number(&numbers[0])?, number(&numbers[1])?])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::CoordinateSystem;

    fn farm(text: &str) -> Result<Farm, InputError> {
        parse(Path::new("test.geojson"), text, CoordinateChoice::FromFile)
    }

    #[test]
    fn reads_holes_obstacles_and_markers() {
        let text = r#"{"type":"FeatureCollection","crs":"local","features":[
          {"type":"Feature","properties":{"name":"A"},"geometry":{"type":"Polygon","coordinates":[
            [[0,0],[100,0],[100,100],[0,100],[0,0]],[[10,10],[20,10],[20,20],[10,10]]]}},
          {"type":"Feature","properties":{"kind":"obstacle"},"geometry":{"type":"Polygon","coordinates":[
            [[50,50],[60,50],[60,60],[50,50]]]}},
          {"type":"Feature","properties":{"kind":"launch"},"geometry":{"type":"Point","coordinates":[-5,-5]}}]}"#;
        let farm = farm(text).unwrap();
        assert_eq!(farm.coordinate_system, CoordinateSystem::Local);
        assert_eq!(farm.fields.len(), 1);
        assert_eq!(farm.fields[0].holes(), 1);
        assert!((farm.fields[0].area_m2() - (10_000.0 - 50.0)).abs() < 1e-9);
        assert_eq!(farm.obstacles.len(), 1);
        assert_eq!(farm.markers[0].kind, "launch");
    }

    #[test]
    fn an_obstacle_point_is_a_circle_of_its_radius() {
        let text = r#"{"type":"FeatureCollection","crs":"local","features":[
          {"type":"Feature","properties":{"name":"A"},"geometry":{"type":"Polygon","coordinates":[
            [[0,0],[100,0],[100,100],[0,100],[0,0]]]}},
          {"type":"Feature","properties":{"kind":"obstacle","name":"pole","radius_m":2},"geometry":{"type":"Point","coordinates":[50,50]}}]}"#;
        let read = farm(text).unwrap();
        assert_eq!(read.obstacles.len(), 1);
        let pole = &read.obstacles[0].polygon;
        use geo::Contains;
        assert!(pole.contains(&geo::Point::new(51.99, 50.0)));
        assert!(pole.contains(&geo::Point::new(50.0, 48.01)));
        assert!(!pole.contains(&geo::Point::new(52.2, 50.0)));
        assert!(read.markers.is_empty());
        for bad in ["0", "-1", "\"2\""] {
            let text = text.replace("\"radius_m\":2", &format!("\"radius_m\":{bad}"));
            assert!(farm(&text).is_err(), "{bad}");
        }
    }

    #[test]
    fn an_access_road_across_a_field_gets_a_note_and_one_along_its_edge_none() {
        let with_road = |coordinates: &str| {
            let text = format!(
                r#"{{"type":"FeatureCollection","crs":"local","features":[
                  {{"type":"Feature","properties":{{"name":"A"}},"geometry":{{"type":"Polygon","coordinates":[[[0,0],[100,0],[100,100],[0,100],[0,0]]]}}}},
                  {{"type":"Feature","properties":{{"kind":"access","name":"road"}},"geometry":{{"type":"LineString","coordinates":{coordinates}}}}}]}}"#
            );
            farm(&text).unwrap().notes
        };
        let across = with_road("[[-20,50],[120,50]]");
        assert!(
            across
                .iter()
                .any(|note| note.contains("access 'road' crosses field 'A'")),
            "{across:?}"
        );
        assert!(with_road("[[-20,0],[120,0]]")
            .iter()
            .all(|note| !note.contains("road")));
        assert!(with_road("[[-20,-10],[120,-10]]").is_empty());
    }

    #[test]
    fn degrees_read_as_local_metres_are_refused_with_the_reason() {
        let square = |x: f64, y: f64, size: f64| {
            format!(
                r#"{{"type":"FeatureCollection","crs":"local","features":[{{"type":"Feature","properties":{{}},"geometry":{{"type":"Polygon","coordinates":[[[{x},{y}],[{},{y}],[{},{}],[{x},{}],[{x},{y}]]]}}}}]}}"#,
                x + size,
                x + size,
                y + size,
                y + size
            )
        };
        let message = farm(&square(126.64, 45.75, 0.002)).unwrap_err().to_string();
        assert!(
            message.contains("look like longitude and latitude"),
            "{message}"
        );
        // Metres: a field 1 m across or more, or outside where degrees can be, is read.
        assert!(farm(&square(126.0, 45.0, 50.0)).is_ok());
        assert!(farm(&square(500.0, 45.0, 0.5)).is_ok());
    }

    #[test]
    fn fields_that_share_a_name_get_names_of_their_own() {
        let square = |x: i32, name: &str| {
            format!(
                r#"{{"type":"Feature","properties":{{"name":"{name}"}},"geometry":{{"type":"Polygon","coordinates":[[[{x},0],[{},0],[{},50],[{x},50],[{x},0]]]}}}}"#,
                x + 50,
                x + 50
            )
        };
        let text = format!(
            r#"{{"type":"FeatureCollection","crs":"local","features":[{},{},{},{}]}}"#,
            square(0, "A"),
            square(100, "A (2)"),
            square(200, "A"),
            square(300, "A")
        );
        let read = farm(&text).unwrap();
        let names: Vec<&str> = read.fields.iter().map(|f| f.name.as_str()).collect();
        assert_eq!(names, ["A", "A (2)", "A (3)", "A (4)"]);
        assert_eq!(read.notes.len(), 2, "{:?}", read.notes);
        assert!(read.notes[0].contains("'A (3)'"), "{:?}", read.notes);
    }

    #[test]
    fn access_lines_and_yards_are_read_and_a_plain_line_is_refused() {
        let text = r#"{"type":"FeatureCollection","crs":"local","features":[
          {"type":"Feature","properties":{"name":"A"},"geometry":{"type":"Polygon","coordinates":[
            [[0,0],[100,0],[100,100],[0,100],[0,0]]]}},
          {"type":"Feature","properties":{"kind":"access","name":"track"},"geometry":{"type":"LineString","coordinates":[[-10,0],[-10,0],[-10,100]]}},
          {"type":"Feature","properties":{"kind":"access"},"geometry":{"type":"MultiLineString","coordinates":[[[0,-10],[100,-10]],[[0,110],[100,110]]]}},
          {"type":"Feature","properties":{"kind":"Access","name":"yard"},"geometry":{"type":"Polygon","coordinates":[
            [[110,0],[130,0],[130,20],[110,0]]]}}]}"#;
        let read = farm(text).unwrap();
        let names: Vec<&str> = read.access.iter().map(|a| a.name.as_str()).collect();
        assert_eq!(names, ["track", "access 2", "access 3", "yard"]);
        let crate::model::AccessShape::Line(track) = &read.access[0].shape else {
            panic!("a line")
        };
        assert_eq!(track.0.len(), 2, "the repeated point is dropped");
        let plain = r#"{"type":"FeatureCollection","crs":"local","features":[
          {"type":"Feature","properties":{"name":"A"},"geometry":{"type":"Polygon","coordinates":[
            [[0,0],[100,0],[100,100],[0,100],[0,0]]]}},
          {"type":"Feature","properties":{"name":"path"},"geometry":{"type":"LineString","coordinates":[[-10,0],[-10,100]]}}]}"#;
        let message = farm(plain).unwrap_err().to_string();
        assert!(
            message.contains("feature 2 (path)") && message.contains("'access'"),
            "{message}"
        );
        let single = r#"{"type":"FeatureCollection","crs":"local","features":[
          {"type":"Feature","properties":{"name":"A"},"geometry":{"type":"Polygon","coordinates":[
            [[0,0],[100,0],[100,100],[0,100],[0,0]]]}},
          {"type":"Feature","properties":{"kind":"access"},"geometry":{"type":"LineString","coordinates":[[-10,0],[-10,0]]}}]}"#;
        let message = farm(single).unwrap_err().to_string();
        assert!(message.contains("two distinct positions"), "{message}");
    }

    #[test]
    fn lon_lat_is_projected_to_utm() {
        let text = r#"{"type":"Polygon","coordinates":[[[8.5,47.3],[8.51,47.3],[8.51,47.31],[8.5,47.3]]]}"#;
        let farm = farm(text).unwrap();
        let CoordinateSystem::Utm(zone) = farm.coordinate_system else {
            panic!("expected UTM")
        };
        assert_eq!(zone.epsg(), 32632);
        let corner = farm.fields[0].polygon.exterior().0[0];
        let (lon, lat) = farm.coordinate_system.to_input(corner.x, corner.y);
        assert!((lon - 8.5).abs() < 1e-9 && (lat - 47.3).abs() < 1e-9);
    }

    #[test]
    fn a_field_on_the_antimeridian_keeps_its_true_size() {
        // 0.002° of longitude at 16°S is 214.07 m on the ellipsoid (pyproj's geodesic); UTM's
        // scale 3° off the central meridian (k = 1.0009) adds 0.08 %. The zone of the raw mean longitude
        // (0°, zone 31) stretched it by 17 %.
        let text = r#"{"type":"Polygon","coordinates":[[[179.999,-16.0],[-179.999,-16.0],[-179.999,-15.998],[179.999,-15.998],[179.999,-16.0]]]}"#;
        let farm = farm(text).unwrap();
        let CoordinateSystem::Utm(zone) = farm.coordinate_system else {
            panic!("expected UTM")
        };
        assert!(
            zone.number == 60 || zone.number == 1,
            "zone {}",
            zone.number
        );
        let ring = &farm.fields[0].polygon.exterior().0;
        let width = (ring[1].x - ring[0].x).abs();
        assert!((width / 214.07 - 1.0).abs() < 0.001, "width {width}");
        for point in ring {
            let (lon, _) = farm.coordinate_system.to_input(point.x, point.y);
            assert!((-180.0..=180.0).contains(&lon), "{lon}");
        }
    }

    #[test]
    fn polar_and_too_wide_farms_are_refused() {
        let polar = r#"{"type":"Polygon","coordinates":[[[10,85],[10.1,85],[10.1,85.1],[10,85]]]}"#;
        let message = farm(polar).unwrap_err().to_string();
        assert!(message.contains("polar region"), "{message}");
        let wide = r#"{"type":"Polygon","coordinates":[[[0,83],[7,83],[7,83.01],[0,83]]]}"#;
        let message = farm(wide).unwrap_err().to_string();
        assert!(message.contains("spans 7.00° of longitude"), "{message}");
    }

    #[test]
    fn faults_name_the_feature() {
        let bow_tie = r#"{"type":"FeatureCollection","crs":"local","features":[
          {"type":"Feature","properties":{"name":"ok"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}},
          {"type":"Feature","properties":{"name":"bad"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[10,10],[10,0],[0,10],[0,0]]]}}]}"#;
        let message = farm(bow_tie).unwrap_err().to_string();
        assert!(
            message.starts_with("test.geojson: feature 2 (bad): boundary intersects itself"),
            "{message}"
        );
        let lon_lat_out_of_range =
            r#"{"type":"Polygon","coordinates":[[[0,0],[500,0],[500,500],[0,0]]]}"#;
        let message = farm(lon_lat_out_of_range).unwrap_err().to_string();
        assert!(message.contains("out of range"), "{message}");
        let line = r#"{"type":"LineString","coordinates":[[0,0],[1,1]]}"#;
        assert!(farm(line).unwrap_err().to_string().contains("LineString"));
    }
}
