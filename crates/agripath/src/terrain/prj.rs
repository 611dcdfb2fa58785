//! The `.prj` beside an ESRI ASCII grid: the grid's coordinate system as WKT (decision 0037).
//!
//! National mapping agencies ship `.asc` grids with a `.prj` in ESRI's WKT, which carries no
//! EPSG code (`PROJCS["WGS_1984_UTM_Zone_31N",GEOGCS["GCS_WGS_1984",…]]`), or in OGC's, which
//! does (`AUTHORITY["EPSG","32631"]` as the last element). The frames agripath places a DEM in
//! are those of the GeoTIFF reader ([`super::frame`]): UTM on WGS84, ETRS89, NAD83, GDA94 or
//! GDA2020 (MGA), and lon/lat on those datums. A `.prj` that names another is not guessed at:
//! the reader says so.

/// The EPSG code of the coordinate system `wkt` describes, or why it is not one agripath
/// places a DEM in (the system's name, in words).
pub fn epsg_of(wkt: &str) -> Result<u32, String> {
    let text = wkt.trim();
    let kind = text
        .split('[')
        .next()
        .unwrap_or_default()
        .trim()
        .to_ascii_uppercase();
    let name = first_quoted(text).unwrap_or_default();
    // OGC WKT names the whole system's code last.
    if let Some(code) = last_epsg_authority(text) {
        if readable(code) {
            return Ok(code);
        }
    }
    let words = name.to_ascii_lowercase().replace(['_', '/'], " ");
    let words: Vec<&str> = words.split_whitespace().collect();
    let datum = text.to_ascii_lowercase().replace([' ', '_', '-'], "");
    let has = |names: &[&str]| names.iter().any(|name| datum.contains(name));
    // (UTM north base, UTM south base, lon/lat code) per datum, the first named wins.
    let datums: [(&[&str], Option<u32>, Option<u32>, u32); 5] = [
        (&["gda2020"], None, Some(7800), 7844),
        (&["gda1994", "gda94"], None, Some(28300), 4283),
        (&["etrs1989", "etrs89"], Some(25800), None, 4258),
        (&["nad1983", "nad83"], Some(26900), None, 4269),
        (&["wgs1984", "wgs84"], Some(32600), Some(32700), 4326),
    ];
    let Some(&(_, north, south, lon_lat)) = datums.iter().find(|(names, ..)| has(names)) else {
        return Err(not_read(name));
    };
    let code = match kind.as_str() {
        "PROJCS" | "PROJCRS" => zone_after(&words, &["utm", "zone"])
            .or_else(|| zone_after(&words, &["mga", "zone"]))
            .and_then(|(number, is_south)| {
                if is_south { south } else { north }.map(|base| base + number)
            }),
        "GEOGCS" | "GEOGCRS" => Some(lon_lat),
        _ => None,
    };
    code.filter(|&code| readable(code))
        .ok_or_else(|| not_read(name))
}

fn not_read(name: &str) -> String {
    format!(
        "'{name}', which agripath does not place a DEM in (it reads UTM and lon/lat on WGS84, ETRS89, NAD83, GDA94 and GDA2020): convert the grid to a GeoTIFF in one of them (gdalwarp -t_srs EPSG:326zz)"
    )
}

fn readable(code: u32) -> bool {
    super::frame::placeable(code)
}

fn first_quoted(text: &str) -> Option<&str> {
    let start = text.find('"')? + 1;
    let length = text[start..].find('"')?;
    Some(&text[start..start + length])
}

/// The code of the last `AUTHORITY["EPSG","n"]` (or `ID["EPSG",n]`) in `text`.
fn last_epsg_authority(text: &str) -> Option<u32> {
    let upper = text.to_ascii_uppercase();
    let at = upper
        .rfind("AUTHORITY[\"EPSG\"")
        .or_else(|| upper.rfind("ID[\"EPSG\""))?;
    let rest = &text[at..];
    let comma = rest.find(',')?;
    let digits: String = rest[comma + 1..]
        .chars()
        .skip_while(|c| *c == '"' || c.is_whitespace())
        .take_while(char::is_ascii_digit)
        .collect();
    digits.parse().ok()
}

/// The zone number and whether it is south, from the word after `keys` in order (`… utm zone
/// 31n`): 1..=60, with `n`/`s` or a separate `north`/`south` word.
fn zone_after(words: &[&str], keys: &[&str]) -> Option<(u32, bool)> {
    let at = words
        .windows(keys.len())
        .position(|window| window == keys)?
        + keys.len();
    let word = words.get(at)?;
    let digits: String = word.chars().take_while(char::is_ascii_digit).collect();
    let number: u32 = digits.parse().ok().filter(|zone| (1..=60).contains(zone))?;
    let letter = &word[digits.len()..];
    let south = match letter {
        "s" => true,
        "n" => false,
        "" => words.get(at + 1) == Some(&"south") || keys[0] == "mga",
        // MGRS latitude bands: C-M south, N-X north.
        band if band.len() == 1 => band < "n",
        _ => return None,
    };
    Some((number, south))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn esri_and_ogc_wkt_name_their_systems() {
        let esri_utm = r#"PROJCS["WGS_1984_UTM_Zone_31N",GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID["WGS_1984",6378137.0,298.257223563]],PRIMEM["Greenwich",0.0],UNIT["Degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],PARAMETER["False_Easting",500000.0],PARAMETER["False_Northing",0.0],PARAMETER["Central_Meridian",3.0],PARAMETER["Scale_Factor",0.9996],PARAMETER["Latitude_Of_Origin",0.0],UNIT["Meter",1.0]]"#;
        assert_eq!(epsg_of(esri_utm), Ok(32631));
        let ogc_south = r#"PROJCS["WGS 84 / UTM zone 55S",GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563,AUTHORITY["EPSG","7030"]],AUTHORITY["EPSG","6326"]],AUTHORITY["EPSG","4326"]],PROJECTION["Transverse_Mercator"],UNIT["metre",1,AUTHORITY["EPSG","9001"]],AUTHORITY["EPSG","32755"]]"#;
        assert_eq!(epsg_of(ogc_south), Ok(32755));
        // The same without its authority: read from the name.
        let unnamed = ogc_south.replace(r#",AUTHORITY["EPSG","32755"]"#, "");
        assert_eq!(epsg_of(&unnamed), Ok(32755));
        let mga = r#"PROJCS["GDA_1994_MGA_Zone_48",GEOGCS["GCS_GDA_1994",DATUM["D_GDA_1994",SPHEROID["GRS_1980",6378137.0,298.257222101]]]]"#;
        assert_eq!(epsg_of(mga), Ok(28348));
        let lonlat = r#"GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID["WGS_1984",6378137.0,298.257223563]]]"#;
        assert_eq!(epsg_of(lonlat), Ok(4326));
    }

    #[test]
    fn other_systems_are_named_not_guessed() {
        let lambert = r#"PROJCS["RGF93_Lambert_93",GEOGCS["GCS_RGF_1993",DATUM["D_RGF_1993",SPHEROID["GRS_1980",6378137.0,298.257222101]]],PROJECTION["Lambert_Conformal_Conic"]]"#;
        let why = epsg_of(lambert).unwrap_err();
        assert!(why.contains("'RGF93_Lambert_93'"), "{why}");
        // UTM on ETRS89 is its own code; on a datum not listed, refused.
        let etrs = r#"PROJCS["ETRS_1989_UTM_Zone_31N",GEOGCS["GCS_ETRS_1989",DATUM["D_ETRS_1989",SPHEROID["GRS_1980",6378137.0,298.257222101]]]]"#;
        assert_eq!(epsg_of(etrs), Ok(25831));
        let pulkovo = etrs.replace("ETRS_1989", "Pulkovo_1942");
        assert!(epsg_of(&pulkovo).is_err());
        assert!(epsg_of("").is_err());
        assert!(epsg_of("PROJCS[\"WGS_1984_UTM_Zone_99N\",DATUM[\"D_WGS_1984\"]]").is_err());
    }
}
