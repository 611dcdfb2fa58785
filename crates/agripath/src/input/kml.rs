//! KML and KMZ field files (Google Earth, ground stations): Placemarks with Polygons or
//! MultiGeometries, inner boundaries as holes. KML positions are always WGS84 lon/lat.
//! A Placemark is an obstacle when its ExtendedData has `kind` = `obstacle` (as a GeoJSON
//! property would be), or when it sits in a Folder named "obstacles".

use std::io::Read;
use std::path::Path;

use kml::types::{Geometry, Placemark, Polygon};
use kml::Kml;

use super::farm::{build, RawFeature, RawGeometry, RawRings};
use super::{read_bytes, read_text, CoordinateChoice};
use crate::error::{Fault, InputError};
use crate::model::Farm;

/// Biggest KML document inflated from a KMZ, bytes (a zip bomb stops here).
const MAX_INFLATED_KML_BYTES: u64 = 512 * 1024 * 1024;

pub fn read_kml(path: &Path, choice: CoordinateChoice) -> Result<Farm, InputError> {
    let text = read_text(path)?;
    parse(path, &text, choice)
}

/// A KMZ is a zip holding `doc.kml` (or another `.kml` at its root).
pub fn read_kmz(path: &Path, choice: CoordinateChoice) -> Result<Farm, InputError> {
    let bytes = read_bytes(path)?;
    let fail = |message: String| InputError::new(path, Fault::Kml(message));
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes))
        .map_err(|error| fail(format!("not a KMZ (zip) archive: {error}")))?;
    let names: Vec<String> = archive
        .file_names()
        .map(|name| name.map(|name| name.into_owned()))
        .collect::<Result<_, _>>()
        .map_err(|error| fail(format!("unreadable entry name in the archive: {error}")))?;
    let entry = names
        .iter()
        .find(|name| name.eq_ignore_ascii_case("doc.kml"))
        .or_else(|| {
            names
                .iter()
                .find(|name| name.to_ascii_lowercase().ends_with(".kml"))
        })
        .ok_or_else(|| fail("the KMZ archive holds no .kml document".into()))?
        .clone();
    let file = archive
        .by_name(&entry)
        .map_err(|error| fail(format!("cannot open {entry} in the archive: {error}")))?;
    let mut text = String::new();
    file.take(MAX_INFLATED_KML_BYTES + 1)
        .read_to_string(&mut text)
        .map_err(|error| fail(format!("cannot inflate {entry}: {error}")))?;
    if text.len() as u64 > MAX_INFLATED_KML_BYTES {
        return Err(InputError::new(
            path,
            Fault::TooLarge(format!(
                "{entry} inflates past {MAX_INFLATED_KML_BYTES} bytes"
            )),
        ));
    }
    parse(path, &text, choice).map_err(|error| error.at_inner(&entry))
}

impl InputError {
    fn at_inner(self, entry: &str) -> Self {
        if self.place.is_some() {
            let place = self.place.clone().unwrap_or_default();
            Self {
                place: Some(format!("{entry}: {place}")),
                ..self
            }
        } else {
            self
        }
    }
}

/// Parses KML text; `path` only names the source in errors.
pub fn parse(path: &Path, text: &str, choice: CoordinateChoice) -> Result<Farm, InputError> {
    let document: Kml<f64> = text
        .parse()
        .map_err(|error: kml::Error| InputError::new(path, Fault::Kml(error.to_string())))?;
    let mut features = Vec::new();
    collect(&document, false, &mut features)
        .map_err(|(place, fault)| InputError::new(path, fault).at(place))?;
    build(path, features, choice == CoordinateChoice::FromFile, None)
}

type Located = (String, Fault);

fn collect(
    node: &Kml<f64>,
    in_obstacle_folder: bool,
    out: &mut Vec<RawFeature>,
) -> Result<(), Located> {
    match node {
        Kml::KmlDocument(document) => {
            for element in &document.elements {
                collect(element, in_obstacle_folder, out)?;
            }
        }
        Kml::Document { elements, .. } => {
            for element in elements {
                collect(element, in_obstacle_folder, out)?;
            }
        }
        Kml::Folder(folder) => {
            let obstacles = in_obstacle_folder
                || folder
                    .name
                    .as_deref()
                    .is_some_and(|name| name.trim().eq_ignore_ascii_case("obstacles"));
            for element in &folder.elements {
                collect(element, obstacles, out)?;
            }
        }
        Kml::Placemark(placemark) => {
            if let Some(feature) = read_placemark(placemark, out.len(), in_obstacle_folder)? {
                out.push(feature);
            }
        }
        Kml::Polygon(polygon) => {
            let place = format!("Polygon {}", out.len());
            let rings = read_polygon(polygon).map_err(|fault| (place.clone(), fault))?;
            out.push(RawFeature {
                place,
                name: None,
                kind: None,
                geometry: RawGeometry::Polygons(vec![rings]),
            });
        }
        _ => {}
    }
    Ok(())
}

fn read_placemark(
    placemark: &Placemark<f64>,
    index: usize,
    in_obstacle_folder: bool,
) -> Result<Option<RawFeature>, Located> {
    let place = match &placemark.name {
        Some(name) => format!("Placemark {index} ({name})"),
        None => format!("Placemark {index}"),
    };
    let Some(geometry) = &placemark.geometry else {
        return Ok(None);
    };
    let mut polygons = Vec::new();
    let mut point = None;
    gather(geometry, &mut polygons, &mut point).map_err(|fault| (place.clone(), fault))?;
    let geometry = match (polygons.is_empty(), point) {
        (false, _) => RawGeometry::Polygons(polygons),
        (true, Some(position)) => RawGeometry::Point(position),
        // A LineString placemark (a drawn path) is not an area to spray: skip it.
        (true, None) => return Ok(None),
    };
    let kind = extended_kind(placemark).or(in_obstacle_folder.then(|| "obstacle".to_string()));
    Ok(Some(RawFeature {
        place,
        name: placemark.name.clone(),
        kind,
        geometry,
    }))
}

fn gather(
    geometry: &Geometry<f64>,
    polygons: &mut Vec<RawRings>,
    point: &mut Option<[f64; 2]>,
) -> Result<(), Fault> {
    match geometry {
        Geometry::Polygon(polygon) => polygons.push(read_polygon(polygon)?),
        Geometry::MultiGeometry(multi) => {
            for part in &multi.geometries {
                gather(part, polygons, point)?;
            }
        }
        Geometry::Point(found) => {
            point.get_or_insert([found.coord.x, found.coord.y]);
        }
        _ => {}
    }
    Ok(())
}

fn read_polygon(polygon: &Polygon<f64>) -> Result<RawRings, Fault> {
    let ring = |coords: &[kml::types::Coord<f64>]| -> Vec<[f64; 2]> {
        coords.iter().map(|coord| [coord.x, coord.y]).collect()
    };
    let mut rings = vec![ring(&polygon.outer.coords)];
    rings.extend(polygon.inner.iter().map(|inner| ring(&inner.coords)));
    Ok(rings)
}

/// `<ExtendedData><Data name="kind"><value>obstacle</value></Data></ExtendedData>`
fn extended_kind(placemark: &Placemark<f64>) -> Option<String> {
    placemark
        .children
        .iter()
        .filter(|element| element.name == "ExtendedData")
        .flat_map(|extended| &extended.children)
        .filter(|data| data.attrs.get("name").is_some_and(|name| name == "kind"))
        .flat_map(|data| &data.children)
        .find(|value| value.name == "value")
        .and_then(|value| value.content.as_ref())
        .map(|kind| kind.trim().to_ascii_lowercase())
}

#[cfg(test)]
mod tests {
    use super::*;

    const FIELD_KML: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<kml xmlns="http://www.opengis.net/kml/2.2"><Document>
  <Placemark><name>North</name><Polygon><outerBoundaryIs><LinearRing><coordinates>
    8.50,47.30,0 8.51,47.30,0 8.51,47.31,0 8.50,47.31,0 8.50,47.30,0
  </coordinates></LinearRing></outerBoundaryIs>
  <innerBoundaryIs><LinearRing><coordinates>
    8.503,47.303 8.505,47.303 8.505,47.305 8.503,47.303
  </coordinates></LinearRing></innerBoundaryIs></Polygon></Placemark>
  <Placemark><name>pylon</name>
    <ExtendedData><Data name="kind"><value>obstacle</value></Data></ExtendedData>
    <Polygon><outerBoundaryIs><LinearRing><coordinates>
    8.507,47.307 8.508,47.307 8.508,47.308 8.507,47.307
  </coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark>
</Document></kml>"#;

    #[test]
    fn reads_placemarks_holes_and_obstacles() {
        let farm = parse(Path::new("f.kml"), FIELD_KML, CoordinateChoice::FromFile).unwrap();
        assert_eq!(farm.fields.len(), 1);
        assert_eq!(farm.fields[0].name, "North");
        assert_eq!(farm.fields[0].holes(), 1);
        assert_eq!(farm.obstacles.len(), 1);
        assert_eq!(farm.obstacles[0].name, "pylon");
        // 0.01° × 0.01° at 47.3° N is about 754 m × 1112 m.
        let area = farm.fields[0].area_m2();
        assert!((area - 837_000.0).abs() < 10_000.0, "{area}");
    }

    #[test]
    fn kmz_holds_the_same_farm() {
        let mut buffer = std::io::Cursor::new(Vec::new());
        {
            let mut writer = zip::ZipWriter::new(&mut buffer);
            let options = zip::write::SimpleFileOptions::default()
                .compression_method(zip::CompressionMethod::Deflated);
            writer.start_file("doc.kml", options).unwrap();
            std::io::Write::write_all(&mut writer, FIELD_KML.as_bytes()).unwrap();
            writer.finish().unwrap();
        }
        let folder = std::env::temp_dir().join(format!("agripath-kmz-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        let path = folder.join("fields.kmz");
        std::fs::write(&path, buffer.into_inner()).unwrap();
        let farm = read_kmz(&path, CoordinateChoice::FromFile).unwrap();
        std::fs::remove_dir_all(&folder).unwrap();
        assert_eq!(farm.fields.len(), 1);
        assert_eq!(farm.obstacles.len(), 1);
    }

    #[test]
    fn broken_xml_is_a_kml_fault() {
        let error = parse(
            Path::new("f.kml"),
            "<kml><Document><Placemark>",
            CoordinateChoice::FromFile,
        )
        .unwrap_err();
        assert!(
            matches!(error.fault, Fault::Kml(_) | Fault::NoFields),
            "{error}"
        );
    }
}
