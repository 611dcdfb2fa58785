//! GeoTIFF DEMs: one band of float32/64 or 8-64-bit integers, strips or tiles, any compression
//! and predictor the `tiff` crate decodes (none, deflate, LZW; predictors 2 and 3).
//!
//! Georeferencing from the GeoTIFF tags: ModelPixelScale + ModelTiepoint, or a
//! ModelTransformation without rotation (rotated or sheared rasters are refused); GeoKeys
//! 1025 (PixelIsArea/PixelIsPoint), 3072 (projected EPSG) and 2048 (geographic EPSG);
//! GDAL_NODATA (tag 42113) marks cells without data; a GDAL mask (an image of NewSubfileType 4
//! the size of the DEM, or a `DEM.tif.msk` beside it) is refused, since the crate cannot decode
//! it.
//!
//! Heights are read in metres as GDAL reads them (decision 0037): the band's scale and offset
//! (height = stored × scale + offset, no data compared with the stored value), then the
//! vertical unit to metres ([`super::gdal_metadata`]), from the file and from the
//! `DEM.tif.aux.xml` GDAL writes beside it. A `DEM.tif.msk` mask beside it is refused like an
//! internal one.

use std::io::Cursor;
use std::path::Path;

use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::tags::Tag;
use tiff::ColorType;

use super::gdal_metadata::{vertical_unit, BandMetadata};
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

/// Reads a GeoTIFF DEM.
pub fn read(path: &Path) -> Result<Grid, InputError> {
    crate::files::check_start(
        path,
        false,
        &[b"II*\0", b"MM\0*", b"II+\0", b"MM\0+"],
        "a readable GeoTIFF",
    )?;
    let beside = |suffix: &str| {
        let mut name = path.as_os_str().to_owned();
        name.push(suffix);
        std::path::PathBuf::from(name)
    };
    if [".msk", ".MSK"]
        .iter()
        .any(|suffix| beside(suffix).is_file())
    {
        return Err(InputError::new(path, Fault::Tiff(MASK_REFUSED.into())));
    }
    let pam = beside(".aux.xml");
    let sidecar = if pam.is_file() {
        BandMetadata::of_pam(&crate::files::read_text(&pam)?)
    } else {
        BandMetadata::default()
    };
    let bytes = read_bytes(path)?;
    decode_with(&bytes, sidecar).map_err(|fault| InputError::new(path, fault))
}

/// Why a DEM with a GDAL mask (inside the file or beside it) is refused.
const MASK_REFUSED: &str = "it carries a GDAL mask of no-data cells, which agripath does not read (read without it, those cells would be taken for ground): write them as a no-data value instead (gdalwarp -dstnodata -9999 IN.tif OUT.tif)";

/// Decodes GeoTIFF bytes into a grid.
pub fn decode(bytes: &[u8]) -> Result<Grid, Fault> {
    decode_with(bytes, BandMetadata::default())
}

/// Decodes GeoTIFF bytes into a grid, with `sidecar` (a PAM `.aux.xml`'s band 1) over the
/// file's own metadata.
fn decode_with(bytes: &[u8], sidecar: BandMetadata) -> Result<Grid, Fault> {
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

    let file_nodata: Option<f64> = decoder
        .find_tag(Tag::GdalNodata)
        .map_err(tiff_fault)?
        .and_then(|value| value.into_string().ok())
        .and_then(|text| text.trim_matches(char::from(0)).trim().parse().ok());

    let metadata = decoder
        .find_tag(Tag::Unknown(GDAL_METADATA))
        .map_err(tiff_fault)?
        .and_then(|value| value.into_string().ok())
        .map(|text| BandMetadata::of_tiff_tag(&text))
        .unwrap_or_default()
        .overlaid(sidecar);
    let nodata = metadata.nodata.or(file_nodata);
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
        if rescaled && height.is_finite() {
            let stored = *height;
            *height = ((f64::from(stored) * scale + offset) * to_metres) as f32;
            // A finite stored value that scales past f32 is not no data: the range check
            // after reading refuses it, as it does a huge value stored as it is.
            if !height.is_finite() {
                return Err(Fault::Tiff(format!(
                    "a stored value {stored} × {scale} + {offset} is not a height (an undeclared no-data value?)"
                )));
            }
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

/// Refuses a GDAL internal mask (NewSubfileType 4, the DEM's size): its 0 cells are no data,
/// but the `tiff` crate does not decode transparency masks, and read without it they would
/// be taken for ground. Overviews and other images are passed over.
fn refuse_internal_mask(
    decoder: &mut Decoder<Cursor<&[u8]>>,
    columns: u32,
    rows: u32,
) -> Result<(), Fault> {
    let tiff_fault =
        |error: tiff::TiffError| Fault::Tiff(format!("its images: {}", in_words(&error)));
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
            return Err(Fault::Tiff(MASK_REFUSED.into()));
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
        type Case = (&'static str, bool, fn(f64) -> f64);
        let cases: [Case; 3] = [
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
        assert!(masked.contains("GDAL mask"), "{masked}");
        assert!(masked.contains("gdalwarp -dstnodata"), "{masked}");
    }

    /// What GDAL reads beside the file: a PAM `.aux.xml` (its scale and offset win over the
    /// file's), a `.msk` mask (refused); a scale that overflows a height is refused.
    #[test]
    fn sidecars_beside_the_file_are_read_as_gdal_reads_them() {
        let folder = std::env::temp_dir().join(format!("agripath-sidecar-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        let copy = |name: &str| {
            let path = folder.join(name);
            std::fs::copy(fixture("float32_strips_none.tif"), &path).unwrap();
            path
        };
        let pam = copy("pam.tif");
        std::fs::write(
            folder.join("pam.tif.aux.xml"),
            r#"<PAMDataset><PAMRasterBand band="1"><Offset>150</Offset><UnitType>ft</UnitType></PAMRasterBand></PAMDataset>"#,
        )
        .unwrap();
        let grid = read(&pam).unwrap();
        let height = grid.height_m(500_001.0, 3_999_999.0).unwrap();
        assert!(
            (height - (expected(0, 0, true) + 150.0) * 0.3048).abs() < 1e-4,
            "{height}"
        );
        let masked = copy("masked.tif");
        std::fs::write(folder.join("masked.tif.msk"), b"II*\0").unwrap();
        let refused = read(&masked).unwrap_err().to_string();
        assert!(refused.contains("GDAL mask"), "{refused}");
        let huge = copy("huge.tif");
        std::fs::write(
            folder.join("huge.tif.aux.xml"),
            r#"<PAMDataset><PAMRasterBand band="1"><Scale>1e37</Scale></PAMRasterBand></PAMDataset>"#,
        )
        .unwrap();
        let refused = read(&huge).unwrap_err().to_string();
        assert!(refused.contains("is not a height"), "{refused}");
        std::fs::remove_dir_all(&folder).unwrap();
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
