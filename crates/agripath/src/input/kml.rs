//! KML and KMZ field files (Google Earth, ground stations): Placemarks with Polygons or
//! MultiGeometries, inner boundaries as holes. KML positions are always WGS84 lon/lat.
//! A Placemark is an obstacle when its ExtendedData has `kind` = `obstacle` (as a GeoJSON
//! property would be), or when it sits in a Folder named "obstacles"; it is an access road,
//! track (LineString) or yard (Polygon) when its `kind` is `access` or it sits in a Folder named
//! "access". Other LineStrings (drawn paths) are skipped.
//!
//! The reader is a single pass over quick-xml events, not a document model: the `kml` crate
//! loops forever on some truncated documents, and a planner must refuse those cleanly.

use std::path::Path;

use quick_xml::events::Event;
use quick_xml::Reader;

use super::farm::{build, RawFeature, RawGeometry, RawRings};
use super::CoordinateChoice;
use crate::error::{Fault, InputError};
use crate::files::read_text;
use crate::model::Farm;

/// Reads a KML file into a validated farm; errs on an unreadable file, bad KML or an invalid polygon.
pub fn read_kml(path: &Path, choice: CoordinateChoice) -> Result<Farm, InputError> {
    let text = read_text(path)?;
    parse(path, &text, choice)
}

/// Parses KML text; `path` only names the source in errors.
pub fn parse(path: &Path, text: &str, choice: CoordinateChoice) -> Result<Farm, InputError> {
    let (features, skipped) = read_features(text).map_err(|(place, fault)| {
        let error = InputError::new(path, fault);
        match place {
            Some(place) => error.at(place),
            None => error,
        }
    })?;
    let built = build(path, features, choice == CoordinateChoice::FromFile, None);
    // A file of drawn paths only (a walked boundary saved as a track): say what was skipped,
    // not only that no field was found (the eleventh trial).
    let mut farm = match built {
        Err(error) if error.fault == Fault::NoFields && !skipped.is_empty() => {
            return Err(InputError::new(
                path,
                Fault::Structure(format!(
                    "no field polygons found; skipped {} (a boundary walked as a track must be closed into a Polygon to be a field)",
                    skipped.join("; ")
                )),
            ));
        }
        other => other?,
    };
    farm.notes.extend(skipped);
    Ok(farm)
}

type Located = (Option<String>, Fault);

/// KML's namespaces: OGC KML 2.2 and Google's earlier ones (2.0-2.2).
const KML_NAMESPACES: [&str; 2] = [
    "http://www.opengis.net/kml/",
    "http://earth.google.com/kml/",
];

/// The root `kml` element must be in a KML namespace (or in none, as hand-written files
/// are): a document of another vocabulary that happens to use the same names is not a field
/// file.
fn check_namespace(start: &quick_xml::events::BytesStart) -> Result<(), String> {
    let prefix = start
        .name()
        .prefix()
        .map(|prefix| String::from_utf8_lossy(prefix.as_ref()).into_owned());
    let attribute_name = match &prefix {
        Some(prefix) => format!("xmlns:{prefix}"),
        None => "xmlns".to_string(),
    };
    let namespace = start
        .try_get_attribute(attribute_name.as_str())
        .ok()
        .flatten()
        .map(|attribute| String::from_utf8_lossy(&attribute.value).into_owned());
    match namespace {
        None => Ok(()),
        Some(namespace) if KML_NAMESPACES.iter().any(|kml| namespace.starts_with(kml)) => Ok(()),
        Some(namespace) => Err(format!(
            "the root element is in namespace '{namespace}', not KML's (http://www.opengis.net/kml/2.2)"
        )),
    }
}

/// Elements nested deeper than this are refused (no real KML comes near it).
const MAX_DEPTH: usize = 256;

/// The Placemark being read.
#[derive(Default)]
struct PlacemarkState {
    name: Option<String>,
    kind: Option<String>,
    radius_m: Option<String>,
    /// A `name` in ExtendedData (QGIS and ogr2ogr write the attribute table there): the
    /// name when the Placemark has no `<name>`.
    data_name: Option<String>,
    polygons: Vec<RawRings>,
    point: Option<[f64; 2]>,
    lines: Vec<Vec<[f64; 2]>>,
}

/// What the Folders around a Placemark make of it, by their names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum FolderKind {
    /// No kind: the Placemark's own (a field by default).
    Plain,
    /// "obstacles".
    Obstacles,
    /// "access".
    Access,
}

/// Walks the XML events once. Only the elements that make a field are read: Placemark
/// (name, ExtendedData kind), Folder (name), Polygon with outer and inner LinearRings,
/// MultiGeometry (by walking into it), Point, LineString (for access features); everything
/// else is skipped.
/// The features, and one line for each placemark skipped (a drawn path that is not a road).
fn read_features(text: &str) -> Result<(Vec<RawFeature>, Vec<String>), Located> {
    let xml_fault = |message: String| (None, Fault::Kml(message));
    let mut reader = Reader::from_str(text);
    let mut stack: Vec<String> = Vec::new();
    // Per open Folder: the kind its name (or a parent's) gives.
    let mut folders: Vec<FolderKind> = Vec::new();
    let mut placemark: Option<PlacemarkState> = None;
    let mut polygon: Option<RawRings> = None;
    // Outer rings seen in the open Polygon: exactly one makes a polygon. With none, its inner
    // rings would be read as the boundary and the holes flown as a field.
    let mut outer_rings = 0usize;
    let mut data_name: Option<String> = None;
    let mut text_buffer = String::new();
    let mut features = Vec::new();
    let mut skipped = Vec::new();
    let mut saw_kml = false;
    loop {
        let position = reader.buffer_position();
        let event = reader
            .read_event()
            .map_err(|error| xml_fault(format!("{error} (at byte {position})")))?;
        match event {
            Event::Start(start) => {
                let name = local_name(start.local_name().as_ref());
                if name == "kml" && !saw_kml {
                    check_namespace(&start).map_err(xml_fault)?;
                }
                saw_kml |= name == "kml";
                match name.as_str() {
                    "Folder" => folders.push(folders.last().copied().unwrap_or(FolderKind::Plain)),
                    "Placemark" => placemark = Some(PlacemarkState::default()),
                    "Polygon" => {
                        polygon = Some(Vec::new());
                        outer_rings = 0;
                    }
                    "Data" | "SimpleData" => {
                        data_name = start
                            .try_get_attribute("name")
                            .ok()
                            .flatten()
                            .and_then(|attribute| {
                                attribute
                                    .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                                    .ok()
                            })
                            .map(|value| value.into_owned());
                    }
                    _ => {}
                }
                stack.push(name);
                if stack.len() > MAX_DEPTH {
                    return Err(xml_fault(format!(
                        "elements nested deeper than {MAX_DEPTH}"
                    )));
                }
                text_buffer.clear();
            }
            Event::Empty(_) => {}
            Event::Text(content) => {
                let decoded = content
                    .decode()
                    .map_err(|error| xml_fault(format!("{error} (at byte {position})")))?;
                text_buffer.push_str(&decoded);
            }
            Event::CData(content) => {
                text_buffer.push_str(&String::from_utf8_lossy(&content));
            }
            Event::GeneralRef(reference) => {
                let resolved = match reference.resolve_char_ref() {
                    Ok(Some(character)) => Some(character),
                    _ => match &*reference as &[u8] {
                        b"amp" => Some('&'),
                        b"lt" => Some('<'),
                        b"gt" => Some('>'),
                        b"quot" => Some('"'),
                        b"apos" => Some('\''),
                        _ => None,
                    },
                };
                match resolved {
                    Some(character) => text_buffer.push(character),
                    None => {
                        return Err(xml_fault(format!(
                            "unknown entity '&{};' (at byte {position}): KML field files use only XML's five",
                            String::from_utf8_lossy(&reference)
                        )))
                    }
                }
            }
            // Entity declarations are how "billion laughs" documents grow; no ground station
            // writes them.
            Event::DocType(doctype) if String::from_utf8_lossy(&doctype).contains("<!ENTITY") => {
                return Err(xml_fault(
                    "the document declares entities (<!ENTITY> in its DOCTYPE): not accepted in a field file".into(),
                ));
            }
            Event::End(_) => {
                let name = stack.pop().unwrap_or_default();
                let parent = stack.last().map(String::as_str).unwrap_or("");
                let content = std::mem::take(&mut text_buffer);
                let place = || {
                    let index = features.len();
                    match placemark.as_ref().and_then(|state| state.name.as_ref()) {
                        Some(name) => format!("Placemark {} ({name})", index + 1),
                        None => format!("Placemark {}", index + 1),
                    }
                };
                match name.as_str() {
                    "name" if parent == "Placemark" => {
                        if let Some(state) = placemark.as_mut() {
                            state.name = Some(content.trim().to_string());
                        }
                    }
                    "name" if parent == "Folder" => {
                        let kind = folder_kind(&content);
                        if let (Some(kind), Some(last)) = (kind, folders.last_mut()) {
                            *last = kind;
                        } else if folders.last() == Some(&FolderKind::Plain)
                            && sounds_like_keep_out(&content)
                        {
                            skipped.push(format!(
                                "Folder '{}' is read as fields, and its polygons are sprayed: if they are places not to spray, name the folder 'Obstacles' or give each placemark kind = obstacle",
                                content.trim()
                            ));
                        }
                    }
                    // ExtendedData: the kind (or `type`), a name, an obstacle point's radius,
                    // under Data names of any case.
                    "value" | "SimpleData" => {
                        let key = data_name.as_deref().map(str::to_ascii_lowercase);
                        if let (Some(state), Some(key)) = (placemark.as_mut(), key) {
                            let text = content.trim();
                            match key.as_str() {
                                "kind" | "type" => state.kind = Some(text.to_ascii_lowercase()),
                                "name" if !text.is_empty() => {
                                    state.data_name.get_or_insert_with(|| text.to_string());
                                }
                                "radius_m" => state.radius_m = Some(text.to_string()),
                                _ => {}
                            }
                        }
                    }
                    "coordinates" => {
                        let positions =
                            parse_coordinates(&content).map_err(|fault| (Some(place()), fault))?;
                        let in_ring = stack.iter().any(|element| element == "LinearRing");
                        let inner = stack.iter().any(|element| element == "innerBoundaryIs");
                        let outer = stack.iter().any(|element| element == "outerBoundaryIs");
                        match (polygon.as_mut(), in_ring) {
                            (Some(rings), true) if outer => {
                                outer_rings += 1;
                                rings.insert(0, positions)
                            }
                            (Some(rings), true) if inner => rings.push(positions),
                            _ if parent == "Point" => {
                                if let (Some(state), Some(first)) =
                                    (placemark.as_mut(), positions.first())
                                {
                                    state.point.get_or_insert(*first);
                                }
                            }
                            // A LinearRing that is the Placemark's geometry itself (valid
                            // KML): a boundary without holes.
                            (None, true) if parent == "LinearRing" => {
                                if let Some(state) = placemark.as_mut() {
                                    state.polygons.push(vec![positions]);
                                }
                            }
                            _ if parent == "LineString" => {
                                if let Some(state) = placemark.as_mut() {
                                    state.lines.push(positions);
                                }
                            }
                            _ => {}
                        }
                    }
                    "Polygon" => {
                        let rings = polygon.take().unwrap_or_default();
                        if outer_rings == 0 {
                            return Err((
                                Some(place()),
                                Fault::Kml(if rings.is_empty() {
                                    "Polygon has no outerBoundaryIs ring".into()
                                } else {
                                    "Polygon has innerBoundaryIs rings (holes) but no outerBoundaryIs ring: give the field's boundary as its outerBoundaryIs".into()
                                }),
                            ));
                        }
                        if outer_rings > 1 {
                            return Err((
                                Some(place()),
                                Fault::Kml(format!("Polygon has {outer_rings} outerBoundaryIs rings: a Polygon has one (use a MultiGeometry for several fields)")),
                            ));
                        }
                        match placemark.as_mut() {
                            Some(state) => state.polygons.push(rings),
                            None => features.push(RawFeature {
                                place: format!("Polygon {}", features.len()),
                                name: None,
                                kind: None,
                                radius_m: None,
                                geometry: RawGeometry::Polygons(vec![rings]),
                            }),
                        }
                    }
                    "Placemark" => {
                        let mut state = placemark.take().unwrap_or_default();
                        state.name = state.name.take().or(state.data_name.take());
                        let index = features.len();
                        let place = match &state.name {
                            Some(name) => format!("Placemark {} ({name})", index + 1),
                            None => format!("Placemark {}", index + 1),
                        };
                        let kind = state.kind.or(match folders.last() {
                            Some(FolderKind::Obstacles) => Some("obstacle".to_string()),
                            Some(FolderKind::Access) => Some("access".to_string()),
                            _ => None,
                        });
                        let geometry = match (state.polygons.is_empty(), state.point) {
                            (false, _) => Some(RawGeometry::Polygons(state.polygons)),
                            (true, Some(point)) => Some(RawGeometry::Point(point)),
                            (true, None)
                                if !state.lines.is_empty() && kind.as_deref() == Some("access") =>
                            {
                                Some(RawGeometry::Lines(state.lines))
                            }
                            // Any other LineString placemark (a drawn path) is not an area:
                            // skip it, and say so.
                            (true, None) => {
                                if !state.lines.is_empty() {
                                    skipped.push(format!(
                                        "{place}: a LineString is not planned (not a field); give it kind 'access' or put it in a Folder named access to use it as a road"
                                    ));
                                }
                                None
                            }
                        };
                        let radius_m = match state.radius_m {
                            None => None,
                            Some(text) => Some(text.parse::<f64>().map_err(|_| {
                                (
                                    Some(place.clone()),
                                    Fault::Kml(format!(
                                        "radius_m is '{text}', expected a number of metres"
                                    )),
                                )
                            })?),
                        };
                        if let Some(geometry) = geometry {
                            features.push(RawFeature {
                                place,
                                name: state.name,
                                kind,
                                radius_m,
                                geometry,
                            });
                        }
                    }
                    "Folder" => {
                        folders.pop();
                    }
                    "Data" => data_name = None,
                    _ => {}
                }
            }
            Event::Eof => break,
            _ => {}
        }
    }
    if let Some(open) = stack.last() {
        return Err(xml_fault(format!(
            "the document ends inside <{open}> (truncated?)"
        )));
    }
    if !saw_kml {
        return Err(xml_fault(
            "no <kml> element: this is not a KML document".into(),
        ));
    }
    Ok((features, skipped))
}

fn local_name(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// What a Folder's name says its Placemarks are. Operators name such folders in their own
/// words ("Obstacles", "No-spray zones", "Exclusion zone", "Keep-out areas", "Trees",
/// "Do not spray"): the name's words, case and punctuation aside and without a last
/// "zone(s)", "area(s)" or "region(s)", must be one of these whole, so that "Excluded blocks",
/// "Tree farm" or "Obstacle-free fields" stay fields.
fn folder_kind(name: &str) -> Option<FolderKind> {
    let mut words = words_of(name);
    if words.len() > 1
        && matches!(
            words.last().map(String::as_str),
            Some("zone" | "zones" | "area" | "areas" | "region" | "regions")
        )
    {
        words.pop();
    }
    let letters: String = words.concat();
    const OBSTACLE_NAMES: [&str; 22] = [
        "obstacle",
        "obstacles",
        "nospray",
        "donotspray",
        "dontspray",
        "exclusion",
        "exclusions",
        "exclude",
        "keepout",
        "nofly",
        "donotfly",
        "nogo",
        "hazard",
        "hazards",
        "tree",
        "trees",
        "building",
        "buildings",
        "avoid",
        "buffer",
        "buffers",
        "restricted",
    ];
    const ACCESS_NAMES: [&str; 4] = ["access", "accessroads", "accesstracks", "roads"];
    if OBSTACLE_NAMES.contains(&letters.as_str()) {
        Some(FolderKind::Obstacles)
    } else if ACCESS_NAMES.contains(&letters.as_str()) {
        Some(FolderKind::Access)
    } else {
        None
    }
}

/// A folder name's words, lower case, without punctuation.
fn words_of(name: &str) -> Vec<String> {
    name.split(|c: char| !c.is_alphanumeric())
        .filter(|word| !word.is_empty())
        .map(str::to_lowercase)
        .collect()
}

/// Whether a folder read as fields has a name that sounds like a place not to spray (a word
/// of warning in it), for a note: its polygons are planned and sprayed.
fn sounds_like_keep_out(name: &str) -> bool {
    const WARNING_WORDS: [&str; 16] = [
        "no",
        "not",
        "dont",
        "avoid",
        "keep",
        "exclusion",
        "exclude",
        "hazard",
        "danger",
        "restricted",
        "buffer",
        "obstacle",
        "obstacles",
        "tree",
        "trees",
        "protected",
    ];
    words_of(name)
        .iter()
        .any(|word| WARNING_WORDS.contains(&word.as_str()))
}

/// KML `coordinates`: tuples `lon,lat[,alt]` separated by white space.
fn parse_coordinates(text: &str) -> Result<Vec<[f64; 2]>, Fault> {
    text.split_ascii_whitespace()
        .map(|tuple| {
            let mut numbers = tuple.split(',').map(|number| number.trim().parse::<f64>());
            match (numbers.next(), numbers.next()) {
                (Some(Ok(lon)), Some(Ok(lat))) => Ok([lon, lat]),
                _ => Err(Fault::Kml(format!(
                    "coordinate tuple '{tuple}' is not 'lon,lat[,alt]'"
                ))),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::kmz::{parse_kmz, read_kmz};

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
        // 0.01° × 0.01° at 47.3° N is about 754 m × 1112 m, less a triangular hole of
        // 0.002° × 0.002° (about 151 m × 222 m / 2).
        let area = farm.fields[0].area_m2();
        assert!(
            (area - (754.0 * 1112.0 - 151.0 * 222.0 / 2.0)).abs() < 3_000.0,
            "{area}"
        );
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

    /// Trial 9: Finder's resource forks first in the archive, and a second document.
    #[test]
    fn kmz_skips_macos_resource_forks_and_names_documents_it_does_not_read() {
        let mut buffer = std::io::Cursor::new(Vec::new());
        {
            let mut writer = zip::ZipWriter::new(&mut buffer);
            let options = zip::write::SimpleFileOptions::default();
            for (name, text) in [
                ("__MACOSX/._fields.kml", "\0\u{5}\u{16}\u{7}Mac OS X"),
                ("fields.kml", FIELD_KML),
                ("extra/other.kml", FIELD_KML),
            ] {
                writer.start_file(name, options).unwrap();
                std::io::Write::write_all(&mut writer, text.as_bytes()).unwrap();
            }
            writer.finish().unwrap();
        }
        let farm = parse_kmz(
            Path::new("f.kmz"),
            buffer.into_inner(),
            CoordinateChoice::FromFile,
        )
        .unwrap();
        assert_eq!(farm.fields[0].name, "North");
        assert!(
            farm.notes
                .iter()
                .any(|note| note.contains("extra/other.kml")),
            "{:?}",
            farm.notes
        );
    }

    /// Trial 9: a pylon drawn as a point (kind under another case, a radius given), and a
    /// field drawn as a bare LinearRing, both valid KML.
    #[test]
    fn point_obstacles_and_bare_rings_are_read() {
        let text = r#"<?xml version="1.0" encoding="UTF-8"?>
<kml xmlns="http://www.opengis.net/kml/2.2"><Document>
  <Placemark><ExtendedData><SchemaData schemaUrl="fields"><SimpleData name="Name">Ring</SimpleData>
    </SchemaData></ExtendedData><LinearRing><coordinates>
    8.50,47.30 8.51,47.30 8.51,47.31 8.50,47.31 8.50,47.30
  </coordinates></LinearRing></Placemark>
  <Placemark><name>Pylon</name>
    <ExtendedData><Data name="Kind"><value>obstacle</value></Data>
      <Data name="radius_m"><value>3.5</value></Data></ExtendedData>
    <Point><coordinates>8.505,47.305</coordinates></Point></Placemark>
  <Folder><name>No-spray zones</name>
    <Placemark><name>Tree</name><Point><coordinates>8.502,47.302</coordinates></Point></Placemark>
  </Folder>
</Document></kml>"#;
        let farm = parse(Path::new("f.kml"), text, CoordinateChoice::FromFile).unwrap();
        assert_eq!(farm.fields.len(), 1);
        assert_eq!(farm.fields[0].name, "Ring");
        assert_eq!(farm.obstacles.len(), 2);
        assert!(farm.markers.is_empty());
        // The circle's polygon holds the disc: its area is a little above π r².
        let area = |k: usize| geo::Area::unsigned_area(&farm.obstacles[k].polygon);
        let disc = |r: f64| std::f64::consts::PI * r * r;
        assert!(
            area(0) > disc(3.5) && area(0) < 1.03 * disc(3.5),
            "{}",
            area(0)
        );
        assert!(
            area(1) > disc(1.0) && area(1) < 1.03 * disc(1.0),
            "{}",
            area(1)
        );
        assert!(
            farm.notes
                .iter()
                .any(|note| note.contains("'Tree' is a point")),
            "{:?}",
            farm.notes
        );
        let bad = text.replace(">3.5<", ">three<");
        let error = parse(Path::new("f.kml"), &bad, CoordinateChoice::FromFile).unwrap_err();
        assert!(error.to_string().contains("radius_m is 'three'"), "{error}");
    }

    #[test]
    fn access_roads_and_yards_are_read_and_other_paths_skipped() {
        let text = r#"<?xml version="1.0" encoding="UTF-8"?>
<kml xmlns="http://www.opengis.net/kml/2.2"><Document>
  <Placemark><name>North</name><Polygon><outerBoundaryIs><LinearRing><coordinates>
    8.50,47.30 8.51,47.30 8.51,47.31 8.50,47.31 8.50,47.30
  </coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark>
  <Placemark><name>farm road</name>
    <ExtendedData><Data name="kind"><value>access</value></Data></ExtendedData>
    <LineString><coordinates>8.499,47.30 8.499,47.31</coordinates></LineString></Placemark>
  <Folder><name>access</name>
    <Placemark><name>yard</name><Polygon><outerBoundaryIs><LinearRing><coordinates>
      8.511,47.30 8.512,47.30 8.512,47.301 8.511,47.30
    </coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark>
  </Folder>
  <Placemark><name>walk</name><LineString><coordinates>8.50,47.29 8.51,47.29</coordinates></LineString></Placemark>
</Document></kml>"#;
        let farm = parse(Path::new("f.kml"), text, CoordinateChoice::FromFile).unwrap();
        assert_eq!(farm.fields.len(), 1);
        let names: Vec<&str> = farm.access.iter().map(|a| a.name.as_str()).collect();
        assert_eq!(names, ["farm road", "yard"]);
        assert!(matches!(
            farm.access[0].shape,
            crate::model::AccessShape::Line(_)
        ));
        assert!(matches!(
            farm.access[1].shape,
            crate::model::AccessShape::Area(_)
        ));
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

    #[test]
    fn a_polygon_needs_one_outer_boundary() {
        let ring = "<LinearRing><coordinates>8.50,47.30 8.51,47.30 8.51,47.31 8.50,47.30</coordinates></LinearRing>";
        let read = |polygon: String| {
            let text = format!(
                "<kml><Document><Placemark><name>F</name><Polygon>{polygon}</Polygon></Placemark></Document></kml>"
            );
            parse(Path::new("f.kml"), &text, CoordinateChoice::FromFile)
                .unwrap_err()
                .to_string()
        };
        let holes_only = read(format!("<innerBoundaryIs>{ring}</innerBoundaryIs>"));
        assert!(holes_only.contains("no outerBoundaryIs"), "{holes_only}");
        let two_outer = read(format!(
            "<outerBoundaryIs>{ring}</outerBoundaryIs><outerBoundaryIs>{ring}</outerBoundaryIs>"
        ));
        assert!(two_outer.contains("2 outerBoundaryIs rings"), "{two_outer}");
    }

    #[test]
    fn folders_named_in_an_operators_words_give_the_kind() {
        for name in [
            "obstacles",
            "Obstacle",
            "No-spray zones",
            "no spray",
            "Exclusions",
            "KEEP OUT",
            "No fly",
            // The fourth trial's names, read as fields until 2026-12-07.
            "Exclusion zone",
            "Keep-out areas",
            "Hazards",
            "Trees",
            "Do not spray",
            "Buffer zones",
            "Avoid",
        ] {
            assert_eq!(folder_kind(name), Some(FolderKind::Obstacles), "{name}");
        }
        assert_eq!(folder_kind("Access roads"), Some(FolderKind::Access));
        for name in [
            "North farm",
            "Fields 2026",
            "Spray",
            "Excluded blocks",
            "Obstacle-free fields",
            "Tree farm",
            "Zone 3",
        ] {
            assert_eq!(folder_kind(name), None, "{name}");
        }
        // A folder read as fields whose name warns gets a note, and its polygons stay fields.
        let kml = |folder: &str| {
            format!(
                r#"<kml><Document><Folder><name>{folder}</name><Placemark><name>B</name><Polygon><outerBoundaryIs><LinearRing><coordinates>
                8.50,47.30 8.51,47.30 8.51,47.31 8.50,47.30</coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark></Folder></Document></kml>"#
            )
        };
        let (_, notes) = read_features(&kml("Obstacle-free fields")).unwrap();
        assert!(
            notes
                .iter()
                .any(|note| note.contains("'Obstacle-free fields' is read as fields")),
            "{notes:?}"
        );
        let (_, notes) = read_features(&kml("North farm")).unwrap();
        assert!(notes.is_empty(), "{notes:?}");
        // Inside an obstacles folder a folder is an obstacle, whatever its name: no note.
        let nested = kml("Trees by the barn")
            .replace("<Folder>", "<Folder><name>Obstacles</name><Folder>")
            .replace("</Folder>", "</Folder></Folder>");
        let (features, notes) = read_features(&nested).unwrap();
        assert!(notes.is_empty(), "{notes:?}");
        assert_eq!(features.len(), 1);
        // Fields whose folder name has a word of warning get a note.
        assert!(sounds_like_keep_out("Obstacle-free fields"));
        assert!(sounds_like_keep_out("Do not enter"));
        assert!(!sounds_like_keep_out("North farm"));
        assert!(!sounds_like_keep_out("Excluded blocks"));
    }
}
