//! The `.prj` beside an ESRI ASCII grid: the grid's coordinate system as WKT (decision 0037).
//!
//! National mapping agencies ship `.asc` grids with a `.prj` in ESRI's WKT, which carries no
//! EPSG code (`PROJCS["WGS_1984_UTM_Zone_31N",GEOGCS["GCS_WGS_1984",…]]`), or in OGC's WKT 1 or
//! 2, which may (`AUTHORITY["EPSG","32631"]` or `ID["EPSG",32631]` on the outermost node). The
//! frames agripath places a DEM in are those of the GeoTIFF reader ([`super::frame`]): UTM and
//! lon/lat on WGS84, ETRS89, NAD83, GDA94 and GDA2020. The WKT is parsed as a tree, and:
//!
//! - an EPSG code on the outermost node decides alone (a code of another frame is refused);
//! - else the datum is the DATUM node's own name, matched whole (never a `TOWGS84` inside it,
//!   which ED50 or NAD27 carry), and a projected system is UTM only when its parameters say so:
//!   Transverse Mercator, latitude of origin 0 (or left out), scale 0.9996, false easting 500,000 m, false
//!   northing 0 (north) or 10,000,000 m (south), a central meridian 6·zone − 183, in metres. The
//!   zone and hemisphere come from those parameters, not from the name.
//!
//! Anything else is refused, naming the system: a frame is never guessed at.

/// A WKT node: its keyword, its quoted strings and numbers in order, and its child nodes.
#[derive(Debug, Default)]
struct Node {
    keyword: String,
    texts: Vec<String>,
    numbers: Vec<f64>,
    children: Vec<Node>,
}

impl Node {
    fn name(&self) -> &str {
        self.texts.first().map_or("", String::as_str)
    }

    fn child(&self, keywords: &[&str]) -> Option<&Node> {
        self.children
            .iter()
            .find(|child| keywords.contains(&child.keyword.as_str()))
    }

    /// Every node below this one whose keyword is in `keywords`, not looking inside nodes
    /// whose keyword is in `skip`.
    fn descendants<'a>(&'a self, keywords: &[&str], skip: &[&str], found: &mut Vec<&'a Node>) {
        for child in &self.children {
            if keywords.contains(&child.keyword.as_str()) {
                found.push(child);
            }
            if !skip.contains(&child.keyword.as_str()) {
                child.descendants(keywords, skip, found);
            }
        }
    }

    /// The EPSG code this node names itself by (`AUTHORITY["EPSG","n"]`, `ID["EPSG",n]`).
    fn epsg(&self) -> Option<u32> {
        let authority = self.child(&["AUTHORITY", "ID"])?;
        if !authority.name().eq_ignore_ascii_case("EPSG") {
            return None;
        }
        match (authority.texts.get(1), authority.numbers.first()) {
            (Some(code), _) => code.trim().parse().ok(),
            (None, Some(&code)) if code.fract() == 0.0 && code > 0.0 => Some(code as u32),
            _ => None,
        }
    }
}

/// Parses WKT into its tree (keywords upper-cased); `None` when it is not WKT.
fn parse(text: &str) -> Option<Node> {
    fn node(chars: &[char], at: &mut usize) -> Option<Node> {
        let skip_blank = |at: &mut usize| {
            while *at < chars.len() && chars[*at].is_whitespace() {
                *at += 1;
            }
        };
        skip_blank(at);
        let start = *at;
        while *at < chars.len() && (chars[*at].is_ascii_alphanumeric() || chars[*at] == '_') {
            *at += 1;
        }
        let keyword: String = chars[start..*at]
            .iter()
            .collect::<String>()
            .to_ascii_uppercase();
        skip_blank(at);
        if keyword.is_empty() || !matches!(chars.get(*at), Some('[') | Some('(')) {
            return None;
        }
        *at += 1;
        let mut parsed = Node {
            keyword,
            ..Node::default()
        };
        loop {
            skip_blank(at);
            match chars.get(*at)? {
                ']' | ')' => {
                    *at += 1;
                    return Some(parsed);
                }
                ',' => *at += 1,
                '"' => {
                    let mut text = String::new();
                    *at += 1;
                    loop {
                        match chars.get(*at)? {
                            // WKT doubles a quote inside a string.
                            '"' if chars.get(*at + 1) == Some(&'"') => {
                                text.push('"');
                                *at += 2;
                            }
                            '"' => {
                                *at += 1;
                                break;
                            }
                            &c => {
                                text.push(c);
                                *at += 1;
                            }
                        }
                    }
                    parsed.texts.push(text);
                }
                c if c.is_ascii_digit() || matches!(c, '-' | '+' | '.') => {
                    let start = *at;
                    while *at < chars.len()
                        && (chars[*at].is_ascii_alphanumeric()
                            || matches!(chars[*at], '-' | '+' | '.'))
                    {
                        *at += 1;
                    }
                    let number: String = chars[start..*at].iter().collect();
                    parsed.numbers.push(number.parse().ok()?);
                }
                _ => {
                    // A child node, or a bare enumeration word (an axis's NORTH, EAST).
                    let mut probe = *at;
                    while probe < chars.len()
                        && (chars[probe].is_ascii_alphanumeric() || chars[probe] == '_')
                    {
                        probe += 1;
                    }
                    while probe < chars.len() && chars[probe].is_whitespace() {
                        probe += 1;
                    }
                    if matches!(chars.get(probe), Some('[') | Some('(')) {
                        parsed.children.push(node(chars, at)?);
                    } else if probe > *at {
                        *at = probe;
                    } else {
                        return None;
                    }
                }
            }
        }
    }
    let chars: Vec<char> = text.trim().chars().collect();
    let mut at = 0;
    node(&chars, &mut at)
}

/// Lower case without spaces, underscores or hyphens: how names are compared.
fn squeezed(text: &str) -> String {
    text.chars()
        .filter(|c| !matches!(c, ' ' | '_' | '-'))
        .flat_map(char::to_lowercase)
        .collect()
}

/// (names of the datum, UTM north base, UTM south base, lon/lat code).
type Datum = (&'static [&'static str], Option<u32>, Option<u32>, u32);
const DATUMS: [Datum; 5] = [
    (
        &["dwgs1984", "wgs1984", "wgs84", "worldgeodeticsystem1984"],
        Some(32600),
        Some(32700),
        4326,
    ),
    (
        &[
            "detrs1989",
            "etrs1989",
            "etrs89",
            "europeanterrestrialreferencesystem1989",
        ],
        Some(25800),
        None,
        4258,
    ),
    (
        &[
            "dnorthamerican1983",
            "northamerican1983",
            "nad1983",
            "nad83",
            "northamericandatum1983",
        ],
        Some(26900),
        None,
        4269,
    ),
    (
        &[
            "dgda1994",
            "gda1994",
            "gda94",
            "geocentricdatumofaustralia1994",
        ],
        None,
        Some(28300),
        4283,
    ),
    (
        &["dgda2020", "gda2020", "geocentricdatumofaustralia2020"],
        None,
        Some(7800),
        7844,
    ),
];

/// The EPSG code of the coordinate system `wkt` describes, or why it is not one agripath
/// places a DEM in (the system's name, in words).
pub fn epsg_of(wkt: &str) -> Result<u32, String> {
    let Some(root) = parse(wkt) else {
        return Err("not WKT (expected PROJCS[…] or GEOGCS[…])".into());
    };
    let name = root.name().to_string();
    if let Some(code) = root.epsg() {
        return if readable(code) {
            Ok(code)
        } else {
            Err(not_read(&name))
        };
    }
    let mut datums = Vec::new();
    root.descendants(&["DATUM", "GEODETICDATUM", "TRF"], &[], &mut datums);
    let datum = match datums.as_slice() {
        [datum] => squeezed(datum.name()),
        _ => return Err(not_read(&name)),
    };
    let Some(&(_, north, south, lon_lat)) = DATUMS
        .iter()
        .find(|(names, ..)| names.contains(&datum.as_str()))
    else {
        return Err(not_read(&name));
    };
    let code = match root.keyword.as_str() {
        "PROJCS" | "PROJCRS" | "PROJECTEDCRS" => utm_zone(&root).and_then(|(zone, is_south)| {
            if is_south { south } else { north }.map(|base| base + zone)
        }),
        "GEOGCS" | "GEOGCRS" | "GEOGRAPHICCRS" => Some(lon_lat),
        _ => None,
    };
    code.filter(|&code| readable(code))
        .ok_or_else(|| not_read(&name))
}

/// The UTM zone and whether it is south, when the projected system's parameters are UTM's
/// exactly (see the module's comment); `None` otherwise.
fn utm_zone(root: &Node) -> Option<(u32, bool)> {
    let geographic = ["GEOGCS", "BASEGEOGCRS", "GEOGCRS", "BASEGEODCRS"];
    let mut methods = Vec::new();
    root.descendants(&["PROJECTION", "METHOD"], &geographic, &mut methods);
    if methods.len() != 1 || squeezed(methods[0].name()) != "transversemercator" {
        return None;
    }
    let mut parameters = Vec::new();
    root.descendants(&["PARAMETER"], &geographic, &mut parameters);
    let parameter = |names: &[&str]| {
        parameters
            .iter()
            .find(|node| names.contains(&squeezed(node.name()).as_str()))
            .and_then(|node| node.numbers.first().copied())
    };
    let near = |value: Option<f64>, wanted: f64| value.is_some_and(|v| (v - wanted).abs() < 1e-6);
    let mut units = Vec::new();
    root.descendants(&["UNIT", "LENGTHUNIT"], &geographic, &mut units);
    let in_metres = !units.is_empty()
        && units.iter().all(|unit| {
            unit.numbers
                .first()
                .is_some_and(|&factor| (factor - 1.0).abs() < 1e-12)
        });
    // A latitude of origin left out is 0, as GDAL reads it; every other parameter must be given.
    let origin = parameter(&["latitudeoforigin", "latitudeofnaturalorigin"]).or(Some(0.0));
    let scale = parameter(&["scalefactor", "scalefactoratnaturalorigin"]);
    let easting = parameter(&["falseeasting"]);
    let northing = parameter(&["falsenorthing"])?;
    let meridian = parameter(&["centralmeridian", "longitudeofnaturalorigin"])?;
    let zone = (meridian + 183.0) / 6.0;
    let is_south = match northing {
        n if n.abs() < 1e-6 => false,
        n if (n - 10_000_000.0).abs() < 1e-6 => true,
        _ => return None,
    };
    let utm = in_metres
        && near(origin, 0.0)
        && near(scale, 0.9996)
        && near(easting, 500_000.0)
        && zone.fract().abs() < 1e-9
        && (1.0..=60.0).contains(&zone);
    utm.then_some((zone as u32, is_south))
}

fn not_read(name: &str) -> String {
    format!(
        "'{name}', which agripath does not place a DEM in (it reads UTM and lon/lat on WGS84, ETRS89, NAD83, GDA94 and GDA2020): convert the grid to a GeoTIFF in one of them (gdalwarp -t_srs EPSG:326zz)"
    )
}

fn readable(code: u32) -> bool {
    super::frame::placeable(code)
}

#[cfg(test)]
mod tests {
    use super::*;

    const ESRI_UTM_31N: &str = r#"PROJCS["WGS_1984_UTM_Zone_31N",GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID["WGS_1984",6378137.0,298.257223563]],PRIMEM["Greenwich",0.0],UNIT["Degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],PARAMETER["False_Easting",500000.0],PARAMETER["False_Northing",0.0],PARAMETER["Central_Meridian",3.0],PARAMETER["Scale_Factor",0.9996],PARAMETER["Latitude_Of_Origin",0.0],UNIT["Meter",1.0]]"#;

    #[test]
    fn esri_and_ogc_wkt_name_their_systems() {
        assert_eq!(epsg_of(ESRI_UTM_31N), Ok(32631));
        let ogc_south = r#"PROJCS["WGS 84 / UTM zone 55S",GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563,AUTHORITY["EPSG","7030"]],AUTHORITY["EPSG","6326"]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433],AUTHORITY["EPSG","4326"]],PROJECTION["Transverse_Mercator"],PARAMETER["latitude_of_origin",0],PARAMETER["central_meridian",147],PARAMETER["scale_factor",0.9996],PARAMETER["false_easting",500000],PARAMETER["false_northing",10000000],UNIT["metre",1,AUTHORITY["EPSG","9001"]],AUTHORITY["EPSG","32755"]]"#;
        assert_eq!(epsg_of(ogc_south), Ok(32755));
        // The same without its own authority: read from its parameters (the inner nodes'
        // codes are not the system's).
        let unnamed = ogc_south.replace(r#",AUTHORITY["EPSG","32755"]"#, "");
        assert_eq!(epsg_of(&unnamed), Ok(32755));
        // GDAL's default name for SetUTM, which names the hemisphere in words.
        let gdal_default =
            unnamed.replace("WGS 84 / UTM zone 55S", "UTM Zone 55, Southern Hemisphere");
        assert_eq!(epsg_of(&gdal_default), Ok(32755));
        let mga = ESRI_UTM_31N
            .replace("WGS_1984_UTM_Zone_31N", "GDA_1994_MGA_Zone_48")
            .replace("D_WGS_1984", "D_GDA_1994")
            .replace("\"Central_Meridian\",3.0", "\"Central_Meridian\",105.0")
            .replace("\"False_Northing\",0.0", "\"False_Northing\",10000000.0");
        assert_eq!(epsg_of(&mga), Ok(28348));
        let etrs = ESRI_UTM_31N.replace("D_WGS_1984", "D_ETRS_1989");
        assert_eq!(epsg_of(&etrs), Ok(25831));
        let lonlat = r#"GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID["WGS_1984",6378137.0,298.257223563]],PRIMEM["Greenwich",0.0],UNIT["Degree",0.0174532925199433]]"#;
        assert_eq!(epsg_of(lonlat), Ok(4326));
        let wkt2 = r#"PROJCRS["WGS 84 / UTM zone 31N",BASEGEOGCRS["WGS 84",DATUM["World Geodetic System 1984",ELLIPSOID["WGS 84",6378137,298.257223563,LENGTHUNIT["metre",1]]],PRIMEM["Greenwich",0,ANGLEUNIT["degree",0.0174532925199433]]],CONVERSION["UTM zone 31N",METHOD["Transverse Mercator",ID["EPSG",9807]],PARAMETER["Latitude of natural origin",0,ANGLEUNIT["degree",0.0174532925199433]],PARAMETER["Longitude of natural origin",3,ANGLEUNIT["degree",0.0174532925199433]],PARAMETER["Scale factor at natural origin",0.9996,SCALEUNIT["unity",1]],PARAMETER["False easting",500000,LENGTHUNIT["metre",1]],PARAMETER["False northing",0,LENGTHUNIT["metre",1]]],CS[Cartesian,2],AXIS["(E)",east,ORDER[1],LENGTHUNIT["metre",1]],AXIS["(N)",north,ORDER[2],LENGTHUNIT["metre",1]]]"#;
        assert_eq!(epsg_of(wkt2), Ok(32631));
        let with_id = format!("{},ID[\"EPSG\",32631]]", &wkt2[..wkt2.len() - 1]);
        assert_eq!(epsg_of(&with_id), Ok(32631));
        let other_id = format!("{},ID[\"EPSG\",2154]]", &wkt2[..wkt2.len() - 1]);
        assert!(epsg_of(&other_id).is_err(), "the system's own code decides");
    }

    /// The review's probes: other datums through their TOWGS84, a projected system whose
    /// inner nodes carry codes, feet, false-easting grids, a meridian off the zone.
    #[test]
    fn other_systems_are_named_not_guessed() {
        let lambert = r#"PROJCS["RGF93_Lambert_93",GEOGCS["GCS_RGF_1993",DATUM["D_RGF_1993",SPHEROID["GRS_1980",6378137.0,298.257222101]]],PROJECTION["Lambert_Conformal_Conic"],UNIT["Meter",1.0]]"#;
        let why = epsg_of(lambert).unwrap_err();
        assert!(why.contains("'RGF93_Lambert_93'"), "{why}");
        let ed50 = r#"PROJCS["ED50 / UTM zone 31N",GEOGCS["ED50",DATUM["European_Datum_1950",SPHEROID["International 1924",6378388,297],TOWGS84[-87,-98,-121,0,0,0,0],AUTHORITY["EPSG","6230"]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433],AUTHORITY["EPSG","4230"]],PROJECTION["Transverse_Mercator"],PARAMETER["latitude_of_origin",0],PARAMETER["central_meridian",3],PARAMETER["scale_factor",0.9996],PARAMETER["false_easting",500000],PARAMETER["false_northing",0],UNIT["metre",1],AUTHORITY["EPSG","23031"]]"#;
        assert!(epsg_of(ed50).is_err());
        assert!(epsg_of(&ed50.replace(r#",AUTHORITY["EPSG","23031"]"#, "")).is_err());
        let feet = ESRI_UTM_31N.replace(
            r#"UNIT["Meter",1.0]]"#,
            r#"UNIT["Foot_US",0.3048006096012192]]"#,
        );
        assert!(epsg_of(&feet).is_err());
        let zone_e = ESRI_UTM_31N.replace("500000.0", "32500000.0");
        assert!(epsg_of(&zone_e).is_err());
        let off_zone = ESRI_UTM_31N.replace("\"Central_Meridian\",3.0", "\"Central_Meridian\",4.0");
        assert!(epsg_of(&off_zone).is_err());
        let custom_tm = ESRI_UTM_31N.replace("0.9996", "1.0");
        assert!(epsg_of(&custom_tm).is_err());
        assert!(epsg_of("").is_err());
        assert!(epsg_of("PROJCS[\"x\"").is_err());
    }
}
