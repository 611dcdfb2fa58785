//! GeoTIFF DEMs: one band of float32/64 or 8-64-bit integers, strips or tiles, any compression
//! and predictor the `tiff` crate decodes (none, deflate, LZW; predictors 2 and 3).
//!
//! Georeferencing from the GeoTIFF tags: ModelPixelScale + ModelTiepoint, or a
//! ModelTransformation without rotation (rotated or sheared rasters are refused); GeoKeys
//! 1025 (PixelIsArea/PixelIsPoint), 3072 (projected EPSG) and 2048 (geographic EPSG);
//! GDAL_NODATA (tag 42113) marks cells without data; a GDAL internal mask (an image of
//! NewSubfileType 4 the size of the DEM) is refused, since the crate cannot decode it.
//!
//! Heights are read in metres as GDAL reads them (decision 0037): the band's scale and offset
//! from GDAL_METADATA (tag 42112: height = stored × scale + offset, no data compared before
//! that), then the vertical unit to metres: VerticalUnitsGeoKey (4099), else GDAL's UNITTYPE,
//! else a vertical CRS (VerticalCSTypeGeoKey 4096) of [`FEET_VERTICAL_CRS`] or
//! [`US_FEET_VERTICAL_CRS`]. A unit it does not know is refused, never read as metres.

use std::io::Cursor;
use std::path::Path;

use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::tags::Tag;
use tiff::ColorType;

use super::Grid;
use crate::error::{Fault, InputError};
use crate::files::read_bytes;
use crate::limits::MAX_TERRAIN_CELLS;

const GT_MODEL_TYPE: u16 = 1024;
const GT_RASTER_TYPE: u16 = 1025;
const GEOGRAPHIC_TYPE: u16 = 2048;
const GEODETIC_DATUM: u16 = 2050;
const PROJECTED_CS_TYPE: u16 = 3072;
const PROJECTION: u16 = 3074;
const DATUM_GDA94: u16 = 6283;
const VERTICAL_CS_TYPE: u16 = 4096;
const VERTICAL_UNITS: u16 = 4099;
const RASTER_PIXEL_IS_POINT: u16 = 2;
const USER_DEFINED: u16 = 32767;
/// GDAL's dataset and band metadata (XML).
const GDAL_METADATA: u16 = 42112;
/// NewSubfileType's bit of a transparency mask.
const SUBFILE_MASK: u32 = 4;
/// The international foot, metres.
const FOOT_M: f64 = 0.3048;
/// The US survey foot, metres.
const US_FOOT_M: f64 = 1200.0 / 3937.0;
/// EPSG vertical CRSs whose heights are in international feet: NAVD88 height (ft), MSL height
/// (ft), GCVD54, LCVD61 and CBVD61 heights (ft).
pub const FEET_VERTICAL_CRS: [u16; 5] = [8228, 8050, 6130, 6131, 6132];
/// EPSG vertical CRSs whose heights are in US survey feet: NGVD29 height (ftUS), NAVD88
/// height (ftUS), MSL height (ftUS).
pub const US_FEET_VERTICAL_CRS: [u16; 3] = [5702, 6360, 8052];

/// Reads a GeoTIFF DEM.
pub fn read(path: &Path) -> Result<Grid, InputError> {
    crate::files::check_start(
        path,
        false,
        &[b"II*\0", b"MM\0*", b"II+\0", b"MM\0+"],
        "a readable GeoTIFF",
    )?;
    let bytes = read_bytes(path)?;
    decode(&bytes).map_err(|fault| InputError::new(path, fault))
}

/// Decodes GeoTIFF bytes into a grid.
pub fn decode(bytes: &[u8]) -> Result<Grid, Fault> {
    let tiff_fault = |error: tiff::TiffError| Fault::Tiff(in_words(&error));
    let mut decoder = Decoder::new(Cursor::new(bytes)).map_err(tiff_fault)?;
    let (columns, rows) = decoder.dimensions().map_err(tiff_fault)?;
    let cells = u64::from(columns) * u64::from(rows);
    if columns == 0 || rows == 0 {
        return Err(Fault::Tiff("the image has no pixels".into()));
    }
    if cells > MAX_TERRAIN_CELLS {
        return Err(Fault::TooLarge(format!(
            "{columns} × {rows} cells (limit {MAX_TERRAIN_CELLS}): crop the DEM to the work area"
        )));
    }
    match decoder.colortype().map_err(tiff_fault)? {
        ColorType::Gray(_) => {}
        ColorType::Multiband { num_samples, .. } => {
            return Err(Fault::Tiff(format!(
                "a DEM has one band of heights; this image has {num_samples}: keep the heights' band (gdal_translate -b 1 IN.tif OUT.tif)"
            )))
        }
        other => {
            return Err(Fault::Tiff(format!(
                "a DEM has one band of heights; this image is colour ({other:?}): keep the heights' band (gdal_translate -b 1 IN.tif OUT.tif)"
            )))
        }
    }
    // Room for the whole image, and never less than the crate's own limits: a tiny image
    // may be stored in a tile far larger than itself.
    let mut limits = Limits::default();
    limits.decoding_buffer_size = limits.decoding_buffer_size.max((cells * 8) as usize);
    limits.intermediate_buffer_size = limits.intermediate_buffer_size.max((cells * 8) as usize);
    decoder = decoder.with_limits(limits);

    let keys = decoder
        .find_tag(Tag::GeoKeyDirectoryTag)
        .map_err(tiff_fault)?
        .map(|value| value.into_u16_vec())
        .transpose()
        .map_err(tiff_fault)?
        .map(|directory| geo_keys(&directory))
        .unwrap_or_default();
    let key = |id: u16| {
        keys.iter()
            .find(|(key, _)| *key == id)
            .map(|(_, value)| *value)
    };
    let pixel_is_point = key(GT_RASTER_TYPE) == Some(RASTER_PIXEL_IS_POINT);
    let epsg = match key(GT_MODEL_TYPE) {
        Some(2) => key(GEOGRAPHIC_TYPE),
        _ => key(PROJECTED_CS_TYPE).or(key(GEOGRAPHIC_TYPE)),
    }
    .filter(|&code| code != USER_DEFINED && code != 0)
    .map(u32::from)
    .or_else(|| user_defined_utm(key(PROJECTION), key(GEODETIC_DATUM)));

    let (first_center_x, first_center_y, cell_x, cell_y) =
        georeference(&mut decoder, pixel_is_point)?;
    // A NaN tiepoint is refused before the pixels are decoded (a 20,000² raster is 1.6 GB).
    if ![first_center_x, first_center_y, cell_x, cell_y]
        .iter()
        .all(|value| value.is_finite())
    {
        return Err(Fault::Structure(format!(
            "the raster's placement is not finite: first cell centre ({first_center_x}, {first_center_y}), cell {cell_x} × {cell_y}"
        )));
    }

    let nodata: Option<f64> = decoder
        .find_tag(Tag::GdalNodata)
        .map_err(tiff_fault)?
        .and_then(|value| value.into_string().ok())
        .and_then(|text| text.trim_matches(char::from(0)).trim().parse().ok());

    let metadata = decoder
        .find_tag(Tag::Unknown(GDAL_METADATA))
        .map_err(tiff_fault)?
        .and_then(|value| value.into_string().ok())
        .map(|text| band_metadata(&text))
        .unwrap_or_default();
    let unit = vertical_unit(key(VERTICAL_UNITS), key(VERTICAL_CS_TYPE), &metadata)?;
    let (scale, offset) = (
        metadata.scale.unwrap_or(1.0),
        metadata.offset.unwrap_or(0.0),
    );
    if !(scale.is_finite() && scale != 0.0 && offset.is_finite()) {
        return Err(Fault::Tiff(format!(
            "the band's scale {scale} and offset {offset} (GDAL_METADATA) do not make heights"
        )));
    }

    let image = decoder.read_image().map_err(tiff_fault)?;
    let mut heights = to_f32(image)?;
    if heights.len() as u64 != cells {
        return Err(Fault::Tiff(format!(
            "expected {cells} samples, decoded {}",
            heights.len()
        )));
    }
    if let Some(nodata) = nodata {
        let nodata = nodata as f32;
        for height in &mut heights {
            if *height == nodata {
                *height = f32::NAN;
            }
        }
    }
    refuse_internal_mask(&mut decoder, columns, rows)?;
    let to_metres = unit.map_or(1.0, |(_, metres)| metres);
    let rescaled = scale != 1.0 || offset != 0.0 || to_metres != 1.0;
    for height in &mut heights {
        if rescaled {
            *height = ((f64::from(*height) * scale + offset) * to_metres) as f32;
        }
        if !height.is_finite() {
            *height = f32::NAN;
        }
    }
    let source = format!(
        "GeoTIFF {columns} × {rows}, cell {cell_x} × {cell_y}{}, {}{}",
        if epsg.is_some_and(|code| code == 4326) {
            "°"
        } else {
            " m"
        },
        match epsg {
            Some(code) => format!("EPSG:{code}"),
            None => "no EPSG code".to_string(),
        },
        if pixel_is_point {
            ", pixel-is-point"
        } else {
            ""
        }
    ) + &heights_note(scale, offset, unit);
    Ok(Grid {
        columns: columns as usize,
        rows: rows as usize,
        first_center_x,
        first_center_y,
        cell_x,
        cell_y,
        heights,
        epsg,
        source,
    })
}

/// The decoder's error in an operator's words: a compression it does not decode is named,
/// with the command that rewrites the file in one it does.
fn in_words(error: &tiff::TiffError) -> String {
    use tiff::tags::CompressionMethod;
    if let tiff::TiffError::UnsupportedError(
        tiff::TiffUnsupportedError::UnsupportedCompressionMethod(method),
    ) = error
    {
        let name = match method {
            CompressionMethod::Unknown(34887) => "LERC".to_string(),
            CompressionMethod::Unknown(34925) => "LZMA".to_string(),
            CompressionMethod::Unknown(50001) => "WebP".to_string(),
            CompressionMethod::Unknown(code) => format!("number {code}"),
            other => format!("{other:?}"),
        };
        return format!(
            "its compression ({name}) is not one agripath decodes (none, DEFLATE, LZW, PackBits): rewrite it with gdal_translate -co COMPRESS=DEFLATE IN.tif OUT.tif"
        );
    }
    error.to_string()
}

/// What `source` says of how the stored values became metres.
fn heights_note(scale: f64, offset: f64, unit: Option<(&str, f64)>) -> String {
    let mut note = String::new();
    if scale != 1.0 || offset != 0.0 {
        note += &format!(", heights = stored × {scale} + {offset}");
    }
    if let Some((name, metres)) = unit.filter(|&(_, metres)| metres != 1.0) {
        note += &format!(", heights in {name} (× {metres} to metres)");
    }
    note
}

/// The band-0 items of GDAL_METADATA that change what a stored value means.
#[derive(Debug, Default, PartialEq)]
struct BandMetadata {
    scale: Option<f64>,
    offset: Option<f64>,
    unit_type: Option<String>,
}

/// Reads `<Item name=".." sample="0" role="scale|offset|unittype">value</Item>` (GDAL's form;
/// items of other bands, and dataset items, are not the height band's).
fn band_metadata(xml: &str) -> BandMetadata {
    let attribute = |tag: &str, name: &str| {
        let start = tag.find(&format!("{name}=\""))? + name.len() + 2;
        let length = tag[start..].find('"')?;
        Some(tag[start..start + length].to_string())
    };
    let mut metadata = BandMetadata::default();
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
        match role.map(|role| role.to_ascii_lowercase()).as_deref() {
            Some("scale") => metadata.scale = value.parse().ok().or(Some(f64::NAN)),
            Some("offset") => metadata.offset = value.parse().ok().or(Some(f64::NAN)),
            Some("unittype") if !value.is_empty() => metadata.unit_type = Some(value.to_string()),
            _ => {}
        }
    }
    metadata
}

/// The heights' unit and its length in metres, from the GeoKeys or GDAL's UNITTYPE; `None`
/// when nothing says (metres). A unit it does not know is refused.
fn vertical_unit(
    units_key: Option<u16>,
    vertical_crs: Option<u16>,
    metadata: &BandMetadata,
) -> Result<Option<(&'static str, f64)>, Fault> {
    if let Some(code) = units_key.filter(|&code| code != USER_DEFINED && code != 0) {
        return match code {
            9001 => Ok(Some(("metres", 1.0))),
            9002 => Ok(Some(("feet", FOOT_M))),
            9003 => Ok(Some(("US survey feet", US_FOOT_M))),
            other => Err(Fault::Tiff(format!(
                "the heights' unit is EPSG unit {other} (VerticalUnitsGeoKey), which agripath does not convert: write the DEM in metres (gdal_translate -scale or gdalwarp -t_srs with a metre vertical CRS)"
            ))),
        };
    }
    if let Some(unit) = &metadata.unit_type {
        return match unit.trim().to_ascii_lowercase().as_str() {
            "m" | "metre" | "meter" | "metres" | "meters" => Ok(Some(("metres", 1.0))),
            "ft" | "foot" | "feet" | "international foot" => Ok(Some(("feet", FOOT_M))),
            "us-ft" | "ftus" | "us survey foot" | "us_survey_foot" | "foot_us" => {
                Ok(Some(("US survey feet", US_FOOT_M)))
            }
            other => Err(Fault::Tiff(format!(
                "the heights' unit is '{other}' (GDAL UNITTYPE), which agripath does not convert: write the DEM in metres"
            ))),
        };
    }
    Ok(match vertical_crs {
        Some(code) if FEET_VERTICAL_CRS.contains(&code) => Some(("feet", FOOT_M)),
        Some(code) if US_FEET_VERTICAL_CRS.contains(&code) => Some(("US survey feet", US_FOOT_M)),
        _ => None,
    })
}

/// Refuses a GDAL internal mask (NewSubfileType 4, the DEM's size): its 0 cells are no data,
/// but the `tiff` crate does not decode transparency masks, and read without it they would
/// be taken for ground. Overviews and other images are passed over.
fn refuse_internal_mask(
    decoder: &mut Decoder<Cursor<&[u8]>>,
    columns: u32,
    rows: u32,
) -> Result<(), Fault> {
    let tiff_fault = |error: tiff::TiffError| Fault::Tiff(format!("its images: {error}"));
    while decoder.more_images() {
        decoder.next_image().map_err(tiff_fault)?;
        let subfile = decoder
            .find_tag(Tag::NewSubfileType)
            .map_err(tiff_fault)?
            .and_then(|value| value.into_u32().ok())
            .unwrap_or(0);
        if subfile & SUBFILE_MASK != 0
            && decoder.dimensions().map_err(tiff_fault)? == (columns, rows)
        {
            return Err(Fault::Tiff(
                "it carries a GDAL internal mask of no-data cells, which agripath does not read (read without it, those cells would be taken for ground): write them as a no-data value instead (gdalwarp -dstnodata -9999 IN.tif OUT.tif)".into(),
            ));
        }
    }
    Ok(())
}

/// A user-defined projected CS built from a UTM projection code (EPSG 16001-16060 north,
/// 16101-16160 south), as GDAL writes for national grids: the equivalent EPSG code, GDA94/MGA
/// (283zz) on the GDA94 datum and WGS84 UTM otherwise.
fn user_defined_utm(projection: Option<u16>, datum: Option<u16>) -> Option<u32> {
    let projection = u32::from(projection?);
    let (zone, south) = match projection {
        16001..=16060 => (projection - 16000, false),
        16101..=16160 => (projection - 16100, true),
        _ => return None,
    };
    Some(match (datum, south) {
        (Some(DATUM_GDA94), true) => 28300 + zone,
        (_, true) => 32700 + zone,
        (_, false) => 32600 + zone,
    })
}

/// The GeoKey directory as (key, short value) pairs; keys stored in other tags are skipped
/// (none of the ones read here are).
fn geo_keys(directory: &[u16]) -> Vec<(u16, u16)> {
    if directory.len() < 4 {
        return Vec::new();
    }
    let count = usize::from(directory[3]);
    directory[4..]
        .chunks_exact(4)
        .take(count)
        .filter(|entry| entry[1] == 0)
        .map(|entry| (entry[0], entry[3]))
        .collect()
}

/// Centre of pixel (0, 0) and the cell size, from the model tags.
fn georeference(
    decoder: &mut Decoder<Cursor<&[u8]>>,
    pixel_is_point: bool,
) -> Result<(f64, f64, f64, f64), Fault> {
    let tiff_fault = |error: tiff::TiffError| Fault::Tiff(error.to_string());
    let doubles =
        |decoder: &mut Decoder<Cursor<&[u8]>>, tag: Tag| -> Result<Option<Vec<f64>>, Fault> {
            decoder
                .find_tag(tag)
                .map_err(tiff_fault)?
                .map(|value| value.into_f64_vec().map_err(tiff_fault))
                .transpose()
        };
    // A pixel-is-area raster's tiepoint refers to the pixel's corner, so its centre is half a
    // pixel further; a pixel-is-point raster's tiepoint is the centre itself.
    let centre_offset = if pixel_is_point { 0.0 } else { 0.5 };
    if let Some(matrix) = doubles(decoder, Tag::ModelTransformationTag)? {
        if matrix.len() < 16 {
            return Err(Fault::Tiff(
                "ModelTransformation has fewer than 16 values".into(),
            ));
        }
        if matrix[1] != 0.0 || matrix[4] != 0.0 {
            return Err(Fault::Tiff(
                "the raster is rotated or sheared (ModelTransformation): warp it north-up first (gdalwarp)".into(),
            ));
        }
        let (scale_x, offset_x, scale_y, offset_y) = (matrix[0], matrix[3], matrix[5], matrix[7]);
        if !(scale_x > 0.0 && scale_y < 0.0) {
            return Err(Fault::Tiff(
                "the raster is flipped (ModelTransformation): expected x growing east and rows running south".into(),
            ));
        }
        return Ok((
            offset_x + centre_offset * scale_x,
            offset_y + centre_offset * scale_y,
            scale_x,
            -scale_y,
        ));
    }
    let scale = doubles(decoder, Tag::ModelPixelScaleTag)?;
    let tiepoint = doubles(decoder, Tag::ModelTiepointTag)?;
    match (scale, tiepoint) {
        (Some(scale), Some(tiepoint)) if scale.len() >= 2 && tiepoint.len() >= 6 => {
            if tiepoint.len() > 6 {
                return Err(Fault::Tiff(
                    "the raster has several tiepoints (a warped grid): warp it north-up first (gdalwarp)".into(),
                ));
            }
            let (cell_x, cell_y) = (scale[0], scale[1]);
            if !(cell_x.is_finite() && cell_y.is_finite() && cell_x > 0.0 && cell_y > 0.0) {
                return Err(Fault::Tiff(format!(
                    "ModelPixelScale ({cell_x}, {cell_y}) is not a positive cell size"
                )));
            }
            let [i, j, _, x, y, _] = [
                tiepoint[0], tiepoint[1], tiepoint[2], tiepoint[3], tiepoint[4], tiepoint[5],
            ];
            Ok((
                x + (centre_offset - i) * cell_x,
                y - (centre_offset - j) * cell_y,
                cell_x,
                cell_y,
            ))
        }
        // No georeferencing: pixel units, centre of the first pixel at (0.5, rows - 0.5) so
        // that x is the column and y grows north, as a plain image would be read.
        _ => Err(Fault::Tiff(
            "no georeferencing (ModelPixelScale/ModelTiepoint or ModelTransformation): this is an image, not a DEM".into(),
        )),
    }
}

fn to_f32(image: DecodingResult) -> Result<Vec<f32>, Fault> {
    Ok(match image {
        DecodingResult::F32(values) => values,
        DecodingResult::F64(values) => values.into_iter().map(|v| v as f32).collect(),
        DecodingResult::I16(values) => values.into_iter().map(f32::from).collect(),
        DecodingResult::U16(values) => values.into_iter().map(f32::from).collect(),
        DecodingResult::I8(values) => values.into_iter().map(f32::from).collect(),
        DecodingResult::U8(values) => values.into_iter().map(f32::from).collect(),
        DecodingResult::I32(values) => values.into_iter().map(|v| v as f32).collect(),
        DecodingResult::U32(values) => values.into_iter().map(|v| v as f32).collect(),
        DecodingResult::I64(values) => values.into_iter().map(|v| v as f32).collect(),
        DecodingResult::U64(values) => values.into_iter().map(|v| v as f32).collect(),
        _ => return Err(Fault::Tiff("unsupported sample format".into())),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::Terrain;
    use std::path::PathBuf;

    const ROWS: usize = 24;
    const COLUMNS: usize = 40;

    fn fixture(name: &str) -> PathBuf {
        PathBuf::from(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../data/test/geotiff"
        ))
        .join(name)
    }

    /// The heights `make_fixtures.py` wrote.
    fn expected(row: usize, column: usize, float: bool) -> f64 {
        if float {
            100.0 + 0.5 * row as f64 - 0.25 * column as f64 + ((row * column) % 7) as f64
        } else {
            1000.0 + 3.0 * row as f64 - 2.0 * column as f64
        }
    }

    #[test]
    fn every_encoding_reads_the_stored_values_at_pixel_centres() {
        for (name, float) in [
            ("float32_strips_none.tif", true),
            ("float32_deflate_predictor3.tif", true),
            ("float32_lzw_predictor3_tiled.tif", true),
            ("int16_deflate_predictor2_tiled.tif", false),
            ("int32_lzw_predictor2.tif", false),
        ] {
            let grid = read(&fixture(name)).unwrap_or_else(|error| panic!("{error}"));
            assert_eq!((grid.columns, grid.rows), (COLUMNS, ROWS), "{name}");
            assert_eq!(grid.epsg, Some(32633), "{name}");
            for row in 0..ROWS {
                for column in 0..COLUMNS {
                    // Pixel-is-area: centre of (row, column) is half a cell in from the tiepoint.
                    let x = 500_000.0 + (column as f64 + 0.5) * 2.0;
                    let y = 4_000_000.0 - (row as f64 + 0.5) * 2.0;
                    let height = grid.height_m(x, y).unwrap();
                    assert_eq!(
                        height,
                        expected(row, column, float),
                        "{name} at ({row}, {column})"
                    );
                }
            }
        }
    }

    #[test]
    fn nodata_and_pixel_is_point() {
        let grid = read(&fixture("float32_nodata_pixel_is_point.tif")).unwrap();
        // Pixel-is-point: the tiepoint is the centre of pixel (0, 0).
        assert_eq!(
            grid.height_m(500_000.0, 4_000_000.0),
            Ok(expected(0, 0, true))
        );
        let (x, y) = grid.cell_center(3, 4);
        assert_eq!((x, y), (500_008.0, 3_999_994.0));
        assert!(matches!(
            grid.height_m(x, y),
            Err(crate::error::TerrainError::NoData { .. })
        ));
        assert_eq!(grid.valid_cells(), ROWS * COLUMNS - 1);
    }

    #[test]
    fn refusals_say_why() {
        let rotated = read(&fixture("rotated.tif")).unwrap_err().to_string();
        assert!(rotated.contains("rotated"), "{rotated}");
        let rgb = read(&fixture("rgb.tif")).unwrap_err().to_string();
        assert!(rgb.contains("one band"), "{rgb}");
        let plain = read(&fixture("no_georeference.tif"))
            .unwrap_err()
            .to_string();
        assert!(plain.contains("no georeferencing"), "{plain}");
    }

    /// Heights as GDAL reads them: stored × scale + offset, then the vertical unit in metres
    /// (decision 0037); the fixtures hold `expected`'s values, written by tifffile.
    #[test]
    fn scale_offset_and_feet_become_metres() {
        let centre = |row: usize, column: usize| {
            (
                500_000.0 + (column as f64 + 0.5) * 2.0,
                4_000_000.0 - (row as f64 + 0.5) * 2.0,
            )
        };
        let cases: [(&str, bool, fn(f64) -> f64); 3] = [
            ("int16_scale_offset.tif", false, |stored| {
                stored * 0.1 + 100.0
            }),
            ("float32_navd88_feet.tif", true, |stored| stored * 0.3048),
            ("float32_us_survey_feet.tif", true, |stored| {
                stored * 1200.0 / 3937.0
            }),
        ];
        for (name, float, metres) in cases {
            let grid = read(&fixture(name)).unwrap_or_else(|error| panic!("{error}"));
            for (row, column) in [(0, 0), (7, 13), (23, 39)] {
                let (x, y) = centre(row, column);
                let height = grid.height_m(x, y).unwrap();
                let wanted = metres(expected(row, column, float));
                assert!(
                    (height - wanted).abs() < 1e-4,
                    "{name} at ({row}, {column}): {height} against {wanted}"
                );
            }
            assert!(grid.source.contains("heights"), "{}", grid.source);
        }
    }

    #[test]
    fn a_unit_it_does_not_know_and_an_internal_mask_are_refused() {
        let furlong = read(&fixture("float32_unittype_furlong.tif"))
            .unwrap_err()
            .to_string();
        assert!(furlong.contains("'furlong'"), "{furlong}");
        let masked = read(&fixture("float32_internal_mask.tif"))
            .unwrap_err()
            .to_string();
        assert!(masked.contains("internal mask"), "{masked}");
        assert!(masked.contains("gdalwarp -dstnodata"), "{masked}");
    }

    /// A 1 × 1 raster stored in a 16 × 16 tile (the decoder's buffer is the tile's, not the
    /// image's).
    #[test]
    fn a_raster_smaller_than_its_tile_reads() {
        let grid =
            read(&fixture("float32_1x1_tiled.tif")).unwrap_or_else(|error| panic!("{error}"));
        assert_eq!((grid.columns, grid.rows), (1, 1));
        assert_eq!(grid.height_m(500_001.0, 3_999_999.0), Ok(123.5));
    }

    #[test]
    fn a_compression_it_does_not_decode_is_named_with_the_fix() {
        use tiff::tags::CompressionMethod;
        let unsupported = |method| {
            in_words(&tiff::TiffError::UnsupportedError(
                tiff::TiffUnsupportedError::UnsupportedCompressionMethod(method),
            ))
        };
        let lerc = unsupported(CompressionMethod::Unknown(34887));
        assert!(
            lerc.contains("(LERC)") && lerc.contains("COMPRESS=DEFLATE"),
            "{lerc}"
        );
        assert!(unsupported(CompressionMethod::Unknown(4242)).contains("(number 4242)"));
    }

    #[test]
    fn gdal_metadata_items_of_the_first_band_only() {
        let xml = r#"<GDALMetadata>
  <Item name="STATISTICS_MEAN" sample="0">12</Item>
  <Item name="OFFSET" sample="1" role="offset">7</Item>
  <Item name="OFFSET" sample="0" role="offset">150</Item>
  <Item name="SCALE" sample="0" role="scale">0.10000000000000001</Item>
  <Item name="UNITTYPE" sample="0" role="unittype">ft</Item>
</GDALMetadata>"#;
        let metadata = band_metadata(xml);
        assert_eq!(metadata.offset, Some(150.0));
        assert_eq!(metadata.scale, Some(0.1));
        assert_eq!(metadata.unit_type.as_deref(), Some("ft"));
        assert_eq!(
            vertical_unit(None, None, &metadata).unwrap(),
            Some(("feet", FOOT_M))
        );
        // The GeoKey wins over GDAL's unit type; a vertical CRS says feet only when nothing else does.
        assert_eq!(
            vertical_unit(Some(9001), None, &metadata).unwrap(),
            Some(("metres", 1.0))
        );
        assert_eq!(
            vertical_unit(None, Some(6360), &BandMetadata::default()).unwrap(),
            Some(("US survey feet", US_FOOT_M))
        );
        assert_eq!(
            vertical_unit(None, Some(5703), &BandMetadata::default()).unwrap(),
            None
        );
        assert!(vertical_unit(Some(9036), None, &metadata).is_err());
    }

    /// The SPSO DEM is uncompressed float32 strips: its stored values can be read straight
    /// from the strip bytes, independently of the decoder, and compared at pixel centres.
    #[test]
    fn christmas_island_dem_matches_its_raw_strips() {
        let path = PathBuf::from(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../data/spso/ChrismasTerrain.tif"
        ));
        let bytes = std::fs::read(&path).unwrap();
        let grid = decode(&bytes).unwrap();
        assert_eq!((grid.columns, grid.rows), (1045, 879));
        assert_eq!(grid.epsg, Some(28348), "GDA94 / MGA zone 48");
        // Strip offsets (tag 273) from the first IFD: every strip is one row of 4180 bytes.
        let u16_at = |at: usize| u16::from_le_bytes([bytes[at], bytes[at + 1]]) as usize;
        let u32_at = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
        let ifd = u32_at(4);
        let entries = u16_at(ifd);
        let strip_offsets = (0..entries)
            .map(|index| ifd + 2 + 12 * index)
            .find(|&entry| u16_at(entry) == 273)
            .map(|entry| u32_at(entry + 8))
            .unwrap();
        for (row, column) in [
            (0, 0),
            (0, 1044),
            (878, 0),
            (878, 1044),
            (439, 522),
            (100, 900),
        ] {
            let strip = u32_at(strip_offsets + 4 * row);
            let at = strip + 4 * column;
            let stored = f32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
            let x = 566_710.0 + (column as f64 + 0.5) * 5.0;
            let y = 8_842_640.0 - (row as f64 + 0.5) * 5.0;
            assert_eq!(
                grid.height_m(x, y),
                Ok(f64::from(stored)),
                "({row}, {column})"
            );
        }
    }
}
