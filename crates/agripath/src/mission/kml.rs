//! KML for Google Earth: the fields and obstacles on the ground, and per sortie a folder with
//! its sprayed stretches, its transit legs (climbs and returns) and its waypoints, at their
//! altitudes: above sea level (`altitudeMode` absolute) when the mission's altitudes are
//! above sea level, else above the ground under each point (`relativeToGround`, which Google
//! Earth draws over its own terrain).

use std::fmt::Write;

use super::flight::{Action, GeoFrame, Item, MissionSettings, SortieMission};
use crate::model::Farm;

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Longitude, latitude, altitude above sea level.
type Position = (f64, f64, f64);

fn coordinates(points: &[Position]) -> String {
    points
        .iter()
        .map(|(lon, lat, alt)| format!("{lon:.9},{lat:.9},{alt:.3}"))
        .collect::<Vec<_>>()
        .join(" ")
}

fn ring(frame: &GeoFrame, ring: &geo::LineString<f64>) -> String {
    let points: Vec<Position> = ring
        .0
        .iter()
        .map(|point| {
            let (lon, lat) = frame.lon_lat(point.x, point.y);
            (lon, lat, 0.0)
        })
        .collect();
    coordinates(&points)
}

/// Sortie colours (KML aabbggrr), repeating.
const SORTIE_COLOURS: [&str; 6] = [
    "ff2a9df4", "ffb4772c", "ff2ca02c", "ff9467bd", "ff4b56d6", "ff17becf",
];

/// The KML document of a plan.
pub fn mission_kml(
    name: &str,
    farm: &Farm,
    missions: &[SortieMission],
    settings: &MissionSettings,
) -> String {
    let frame = GeoFrame::new(farm.coordinate_system, settings.local_origin);
    let absolute = settings.altitude == super::flight::AltitudeReference::SeaLevel;
    let mode = if absolute {
        "absolute"
    } else {
        "relativeToGround"
    };
    let height = |item: &Item| {
        if absolute {
            item.sea_level_m()
        } else {
            item.above_ground_m
        }
    };
    let mut kml = String::new();
    let _ = writeln!(kml, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        kml,
        r#"<kml xmlns="http://www.opengis.net/kml/2.2"><Document><name>{}</name>"#,
        escape(name)
    );
    let _ = writeln!(
        kml,
        r#"<Style id="field"><LineStyle><color>ff3c8c3c</color><width>2</width></LineStyle><PolyStyle><color>4d3cb43c</color></PolyStyle></Style>"#
    );
    let _ = writeln!(
        kml,
        r#"<Style id="obstacle"><LineStyle><color>ff2020c0</color><width>2</width></LineStyle><PolyStyle><color>802020c0</color></PolyStyle></Style>"#
    );
    let _ = writeln!(
        kml,
        r#"<Style id="transit"><LineStyle><color>ff909090</color><width>1.5</width></LineStyle></Style>"#
    );
    for (index, colour) in SORTIE_COLOURS.iter().enumerate() {
        let _ = writeln!(
            kml,
            r#"<Style id="sortie{index}"><LineStyle><color>{colour}</color><width>3</width></LineStyle><IconStyle><scale>0.5</scale></IconStyle></Style>"#
        );
    }
    let _ = writeln!(kml, "<Folder><name>fields</name>");
    let areas = farm
        .fields
        .iter()
        .map(|field| (field.name.as_str(), &field.polygon, "field"))
        .chain(
            farm.obstacles
                .iter()
                .map(|o| (o.name.as_str(), &o.polygon, "obstacle")),
        );
    for (name, polygon, style) in areas {
        let _ = write!(
            kml,
            "<Placemark><name>{}</name><styleUrl>#{style}</styleUrl><Polygon><outerBoundaryIs><LinearRing><coordinates>{}</coordinates></LinearRing></outerBoundaryIs>",
            escape(name),
            ring(&frame, polygon.exterior())
        );
        for hole in polygon.interiors() {
            let _ = write!(
                kml,
                "<innerBoundaryIs><LinearRing><coordinates>{}</coordinates></LinearRing></innerBoundaryIs>",
                ring(&frame, hole)
            );
        }
        let _ = writeln!(kml, "</Polygon></Placemark>");
    }
    let _ = writeln!(kml, "</Folder>");
    for mission in missions {
        let style = format!("sortie{}", mission.sortie % SORTIE_COLOURS.len());
        let _ = writeln!(kml, "<Folder><name>sortie {}</name>", mission.sortie + 1);
        // Split the flown path into sprayed stretches and transit stretches.
        let mut pieces: Vec<(bool, Vec<Position>)> = Vec::new();
        let mut spraying = false;
        let mut last: Option<&Item> = None;
        for item in &mission.items {
            match item.action {
                Action::Spray { .. } | Action::CameraTrigger { .. } => {
                    spraying = item.action.work_state() == Some(true);
                }
                _ if item.moves() => {
                    let point = (item.lon, item.lat, height(item));
                    if pieces.last().is_none_or(|(kind, _)| *kind != spraying) {
                        let start = last
                            .map(|l| vec![(l.lon, l.lat, height(l))])
                            .unwrap_or_default();
                        pieces.push((spraying, start));
                    }
                    pieces.last_mut().expect("just pushed").1.push(point);
                    last = Some(item);
                }
                _ => {}
            }
        }
        // A survey's camera stretches are named for what they are.
        let work = if mission
            .items
            .iter()
            .any(|item| matches!(item.action, Action::CameraTrigger { .. }))
        {
            "survey"
        } else {
            "spray"
        };
        for (sprayed, points) in pieces.iter().filter(|(_, points)| points.len() >= 2) {
            let _ = writeln!(
                kml,
                "<Placemark><name>{}</name><styleUrl>#{}</styleUrl><LineString><altitudeMode>{mode}</altitudeMode><coordinates>{}</coordinates></LineString></Placemark>",
                if *sprayed { work } else { "transit" },
                if *sprayed { style.as_str() } else { "transit" },
                coordinates(points)
            );
        }
        let _ = writeln!(kml, "<Folder><name>waypoints</name>");
        for (index, item) in mission
            .items
            .iter()
            .enumerate()
            .filter(|(_, item)| item.moves())
        {
            let _ = writeln!(
                kml,
                "<Placemark><name>{}</name><styleUrl>#{style}</styleUrl><Point><altitudeMode>{mode}</altitudeMode><coordinates>{}</coordinates></Point></Placemark>",
                index + 1,
                coordinates(&[(item.lon, item.lat, height(item))])
            );
        }
        let _ = writeln!(kml, "</Folder></Folder>");
    }
    let _ = writeln!(kml, "</Document></kml>");
    kml
}
