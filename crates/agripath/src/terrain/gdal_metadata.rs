//! What GDAL says a GeoTIFF's stored values mean (decision 0037): the band's scale, offset,
//! unit and no-data value, from the file's GDAL_METADATA tag (42112) and from the
//! `DEM.tif.aux.xml` sidecar GDAL writes beside a file it may not change (its PAM, which wins,
//! as in GDAL), and the unit of the heights from those and the GeoKeys.
//!
//! The unit is decided as GDAL's `GetUnitType` does, and whatever is not known is refused,
//! never read as metres: `UNITTYPE` first (a GeoKey that says otherwise is refused as a
//! contradiction), else VerticalUnitsGeoKey (4099: 9001 metre, 9002 foot, 9003 US survey foot;
//! any other, user-defined 32767 included, refused), else the vertical CRS (4096): in feet
//! ([`FEET_VERTICAL_CRS`], [`US_FEET_VERTICAL_CRS`]) converted; a depth (positive down) or one
//! in another unit ([`REFUSED_VERTICAL_CRS`]) refused; any other read as metres, the unit of
//! every other vertical CRS in EPSG's register we know of.

use crate::error::Fault;

const USER_DEFINED: u16 = 32767;
/// The international foot, metres.
pub const FOOT_M: f64 = 0.3048;
/// The US survey foot, metres.
pub const US_FOOT_M: f64 = 1200.0 / 3937.0;
/// EPSG vertical CRSs whose heights are in international feet: NAVD88 height (ft), MSL height
/// (ft), GCVD54, LCVD61 and CBVD61 heights (ft).
pub const FEET_VERTICAL_CRS: [u16; 5] = [8228, 8050, 6130, 6131, 6132];
/// EPSG vertical CRSs whose heights are in US survey feet: NGVD29 height (ftUS), NAVD88
/// height (ftUS), MSL height (ftUS).
pub const US_FEET_VERTICAL_CRS: [u16; 3] = [5702, 6360, 8052];
/// EPSG vertical CRSs refused: depths (MSL depth, NAVD88 depth in m and ftUS, NGVD29 depth
/// (ftUS), MSL depth in ft and ftUS), and Poolbeg height in British feet (1936).
pub const REFUSED_VERTICAL_CRS: [u16; 7] = [5715, 6357, 6358, 6359, 8051, 8053, 5754];

/// The band-1 values that change what a stored value means.
#[derive(Debug, Default, Clone, PartialEq)]
pub struct BandMetadata {
    /// What a stored value is multiplied by (NaN when the text is not a number).
    pub scale: Option<f64>,
    /// What is added after the scale.
    pub offset: Option<f64>,
    /// The unit of the heights, in GDAL's word (`m`, `ft`, `US survey foot`, …).
    pub unit_type: Option<String>,
    /// The stored value that marks no data (the sidecar's `NoDataValue`).
    pub nodata: Option<f64>,
}

impl BandMetadata {
    /// `self` with whatever `over` gives put over it (the PAM sidecar over the file's tag).
    pub fn overlaid(self, over: BandMetadata) -> Self {
        Self {
            scale: over.scale.or(self.scale),
            offset: over.offset.or(self.offset),
            unit_type: over.unit_type.or(self.unit_type),
            nodata: over.nodata.or(self.nodata),
        }
    }

    /// Reads GDAL_METADATA's `<Item name=".." sample="0" role="scale|offset|unittype">value
    /// </Item>` (items of other bands, and dataset items, are not the height band's).
    pub fn of_tiff_tag(xml: &str) -> Self {
        let mut metadata = Self::default();
        for item in xml.split("<Item").skip(1) {
            let Some(close) = item.find('>') else {
                continue;
            };
            let (tag, rest) = (&item[..close], &item[close + 1..]);
            let value = rest.split("</Item>").next().unwrap_or("").trim();
            if attribute(tag, "sample").as_deref() != Some("0") {
                continue;
            }
            let role = attribute(tag, "role").or_else(|| attribute(tag, "name"));
            metadata.set(role.as_deref().unwrap_or_default(), value);
        }
        metadata
    }

    /// Reads a PAM sidecar's `<PAMRasterBand band="1">` `Scale`, `Offset`, `UnitType` and
    /// `NoDataValue`.
    pub fn of_pam(xml: &str) -> Self {
        let mut metadata = Self::default();
        for band in xml.split("<PAMRasterBand").skip(1) {
            let Some(close) = band.find('>') else {
                continue;
            };
            if attribute(&band[..close], "band").as_deref() != Some("1") {
                continue;
            }
            let body = band[close + 1..]
                .split("</PAMRasterBand>")
                .next()
                .unwrap_or_default();
            for element in ["Scale", "Offset", "UnitType", "NoDataValue"] {
                let open = format!("<{element}>");
                if let Some(start) = body.find(&open) {
                    let rest = &body[start + open.len()..];
                    let value = rest.split(&format!("</{element}>")).next().unwrap_or("");
                    metadata.set(element, value.trim());
                }
            }
        }
        metadata
    }

    fn set(&mut self, role: &str, value: &str) {
        let number = || value.parse().ok().or(Some(f64::NAN));
        match role.to_ascii_lowercase().as_str() {
            "scale" => self.scale = number(),
            "offset" => self.offset = number(),
            "unittype" if !value.is_empty() => self.unit_type = Some(value.to_string()),
            "nodatavalue" => self.nodata = number(),
            _ => {}
        }
    }
}

/// The value of attribute `name` in an element's opening tag.
fn attribute(tag: &str, name: &str) -> Option<String> {
    let start = tag.find(&format!("{name}=\""))? + name.len() + 2;
    let length = tag[start..].find('"')?;
    Some(tag[start..start + length].to_string())
}

/// A unit's name and its length in metres, from the word GDAL's UNITTYPE holds.
fn unit_named(word: &str) -> Option<(&'static str, f64)> {
    match word.trim().to_ascii_lowercase().as_str() {
        "m" | "metre" | "meter" | "metres" | "meters" => Some(("metres", 1.0)),
        "ft" | "foot" | "feet" | "international foot" => Some(("feet", FOOT_M)),
        "us-ft" | "ftus" | "us survey foot" | "us_survey_foot" | "foot_us" => {
            Some(("US survey feet", US_FOOT_M))
        }
        _ => None,
    }
}

/// The heights' unit and its length in metres (see the module's comment); `None` when
/// nothing says (metres). A unit it does not know, or a contradiction, is refused.
pub fn vertical_unit(
    units_key: Option<u16>,
    vertical_crs: Option<u16>,
    metadata: &BandMetadata,
) -> Result<Option<(&'static str, f64)>, Fault> {
    let from_key = match units_key.filter(|&code| code != 0) {
        None => None,
        Some(9001) => Some(("metres", 1.0)),
        Some(9002) => Some(("feet", FOOT_M)),
        Some(9003) => Some(("US survey feet", US_FOOT_M)),
        Some(other) => {
            return Err(Fault::Tiff(format!(
                "the heights' unit is {} (VerticalUnitsGeoKey), which agripath does not convert: write the DEM in metres (gdal_translate -scale, or gdalwarp -t_srs with a metre vertical CRS)",
                if other == USER_DEFINED { "user-defined".to_string() } else { format!("EPSG unit {other}") }
            )))
        }
    };
    if let Some(word) = &metadata.unit_type {
        let Some(unit) = unit_named(word) else {
            return Err(Fault::Tiff(format!(
                "the heights' unit is '{}' (GDAL UNITTYPE), which agripath does not convert: write the DEM in metres",
                word.trim()
            )));
        };
        if from_key.is_some_and(|key| key.1 != unit.1) {
            return Err(Fault::Tiff(format!(
                "its heights are in {} by GDAL's UNITTYPE but in {} by its VerticalUnitsGeoKey: say one unit (gdal_edit.py -units)",
                unit.0,
                from_key.map_or("", |key| key.0)
            )));
        }
        return Ok(Some(unit));
    }
    if from_key.is_some() {
        return Ok(from_key);
    }
    match vertical_crs {
        Some(code) if FEET_VERTICAL_CRS.contains(&code) => Ok(Some(("feet", FOOT_M))),
        Some(code) if US_FEET_VERTICAL_CRS.contains(&code) => {
            Ok(Some(("US survey feet", US_FOOT_M)))
        }
        Some(code) if REFUSED_VERTICAL_CRS.contains(&code) => Err(Fault::Tiff(format!(
            "its vertical CRS is EPSG:{code}, depths or a unit agripath does not convert: write heights above the datum in metres"
        ))),
        _ => Ok(None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gdal_metadata_items_of_the_first_band_only() {
        let xml = r#"<GDALMetadata>
  <Item name="STATISTICS_MEAN" sample="0">12</Item>
  <Item name="OFFSET" sample="1" role="offset">7</Item>
  <Item name="OFFSET" sample="0" role="offset">150</Item>
  <Item name="SCALE" sample="0" role="scale">0.10000000000000001</Item>
  <Item name="UNITTYPE" sample="0" role="unittype">ft</Item>
</GDALMetadata>"#;
        let metadata = BandMetadata::of_tiff_tag(xml);
        assert_eq!(metadata.offset, Some(150.0));
        assert_eq!(metadata.scale, Some(0.1));
        assert_eq!(metadata.unit_type.as_deref(), Some("ft"));
        assert_eq!(
            vertical_unit(None, None, &metadata).unwrap(),
            Some(("feet", FOOT_M))
        );
        // GDAL's unit type decides; a GeoKey saying the same is fine, one saying otherwise is
        // a contradiction.
        assert_eq!(
            vertical_unit(Some(9002), None, &metadata).unwrap(),
            Some(("feet", FOOT_M))
        );
        assert!(vertical_unit(Some(9001), None, &metadata).is_err());
        let none = BandMetadata::default();
        assert_eq!(
            vertical_unit(None, Some(6360), &none).unwrap(),
            Some(("US survey feet", US_FOOT_M))
        );
        assert_eq!(vertical_unit(None, Some(5703), &none).unwrap(), None);
        for refused in [Some(9036), Some(USER_DEFINED)] {
            assert!(vertical_unit(refused, None, &none).is_err(), "{refused:?}");
        }
        for depth_or_other in [5715, 6357, 8051, 5754] {
            assert!(vertical_unit(None, Some(depth_or_other), &none).is_err());
        }
    }

    #[test]
    fn the_pam_sidecar_overrides_the_files_tag() {
        let pam = r#"<PAMDataset>
  <PAMRasterBand band="2"><Offset>7</Offset></PAMRasterBand>
  <PAMRasterBand band="1">
    <NoDataValue>-9999</NoDataValue>
    <Offset>150</Offset>
    <UnitType>m</UnitType>
  </PAMRasterBand>
</PAMDataset>"#;
        let sidecar = BandMetadata::of_pam(pam);
        assert_eq!(sidecar.offset, Some(150.0));
        assert_eq!(sidecar.nodata, Some(-9999.0));
        assert_eq!(sidecar.scale, None);
        let file = BandMetadata {
            scale: Some(0.5),
            offset: Some(3.0),
            ..BandMetadata::default()
        };
        let merged = file.overlaid(sidecar);
        assert_eq!((merged.scale, merged.offset), (Some(0.5), Some(150.0)));
        assert_eq!(merged.unit_type.as_deref(), Some("m"));
    }
}
