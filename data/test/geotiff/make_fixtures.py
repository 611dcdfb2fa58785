"""Writes the GeoTIFF fixtures of the DEM reader's tests with tifffile (an outside writer).

Run: python make_fixtures.py (needs tifffile, numpy, imagecodecs). The heights follow
h(row, col) below, so the tests know every stored value without reading it back the same way.
"""
import numpy as np
import tifffile

ROWS, COLS = 24, 40
ORIGIN_X, ORIGIN_Y, CELL = 500000.0, 4000000.0, 2.0


def heights(dtype):
    r, c = np.mgrid[0:ROWS, 0:COLS]
    if np.issubdtype(dtype, np.floating):
        return (100.0 + 0.5 * r - 0.25 * c + (r * c % 7)).astype(dtype)
    return (1000 + 3 * r - 2 * c).astype(dtype)


def geo_tags(epsg=32633, pixel_is_point=False, nodata=None, transform=None):
    keys = [1, 1, 0, 3, 1024, 0, 1, 1, 1025, 0, 1, 2 if pixel_is_point else 1, 3072, 0, 1, epsg]
    tags = [(34735, "H", len(keys), keys, False)]
    if transform is None:
        tags += [
            (33550, "d", 3, (CELL, CELL, 0.0), False),
            (33922, "d", 6, (0.0, 0.0, 0.0, ORIGIN_X, ORIGIN_Y, 0.0), False),
        ]
    else:
        tags += [(34264, "d", 16, transform, False)]
    if nodata is not None:
        tags += [(42113, "s", 0, str(nodata), False)]
    return tags


def write(name, data, **options):
    tags = options.pop("tags", geo_tags())
    tifffile.imwrite(name, data, extratags=tags, photometric="minisblack", **options)


write("float32_strips_none.tif", heights(np.float32), rowsperstrip=5)
write("float32_deflate_predictor3.tif", heights(np.float32), compression="zlib", predictor=3, rowsperstrip=7)
write("float32_lzw_predictor3_tiled.tif", heights(np.float32), compression="lzw", predictor=3, tile=(16, 16))
write("int16_deflate_predictor2_tiled.tif", heights(np.int16), compression="zlib", predictor=2, tile=(16, 16))
write("int32_lzw_predictor2.tif", heights(np.int32), compression="lzw", predictor=2, rowsperstrip=4)
with_nodata = heights(np.float32)
with_nodata[3, 4] = -9999.0
write("float32_nodata_pixel_is_point.tif", with_nodata, tags=geo_tags(pixel_is_point=True, nodata=-9999))
angle = np.radians(10)
rotated = (CELL * np.cos(angle), -CELL * np.sin(angle), 0, ORIGIN_X,
           CELL * np.sin(angle), -CELL * np.cos(angle), 0, ORIGIN_Y,
           0, 0, 0, 0, 0, 0, 0, 1)
write("rotated.tif", heights(np.float32), tags=geo_tags(transform=rotated))
tifffile.imwrite("rgb.tif", np.zeros((8, 8, 3), np.uint8), photometric="rgb", extratags=geo_tags())
tifffile.imwrite("no_georeference.tif", heights(np.float32), photometric="minisblack")

# A geographic DEM (EPSG:4326, 0.001° cells from 8.5°E, 47.324°N): heights are linear in
# lon/lat, h = 1000·(lon − 8.5) + 2000·(lat − 47.3), so bilinear sampling is exact anywhere.
r, c = np.mgrid[0:24, 0:40]
lon = 8.5 + (c + 0.5) * 0.001
lat = 47.324 - (r + 0.5) * 0.001
linear = (1000 * (lon - 8.5) + 2000 * (lat - 47.3)).astype(np.float64)
keys = [1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326]
tifffile.imwrite(
    "lonlat_4326_float64.tif", linear, photometric="minisblack",
    extratags=[(34735, "H", len(keys), keys, False),
               (33550, "d", 3, (0.001, 0.001, 0.0), False),
               (33922, "d", 6, (0.0, 0.0, 0.0, 8.5, 47.324, 0.0), False)])

# Hostile rasters for the bad-input corpus (written beside it, in ../bad/): a NaN tiepoint,
# every cell no-data, and an undeclared no-data value of 3.4e38 (float32's largest).
write("../bad/nan_tiepoint.tif", heights(np.float32),
      tags=[t for t in geo_tags() if t[0] != 33922] + [(33922, "d", 6, (0.0, 0.0, 0.0, float("nan"), ORIGIN_Y, 0.0), False)])
write("../bad/all_nodata.tif", np.full((ROWS, COLS), -9999.0, np.float32), tags=geo_tags(nodata=-9999))
huge = heights(np.float32)
huge[5, 6] = np.finfo(np.float32).max
write("../bad/huge_height.tif", huge)

# Heights in other units, tiny rasters and an internal mask (decision 0037). The stored values
# are heights(np.int16) or heights(np.float32); the tests know what they mean in metres.
def gdal_metadata(items):
    body = "".join(f'<Item name="{name}" sample="0" role="{role}">{value}</Item>' for name, role, value in items)
    return (42112, "s", 0, f"<GDALMetadata>{body}</GDALMetadata>", False)


def vertical_tags(key, value):
    keys = [1, 1, 0, 4, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, 32633, key, 0, 1, value]
    return [t for t in geo_tags() if t[0] != 34735] + [(34735, "H", len(keys), keys, False)]


def units_and_masks():
    write("int16_scale_offset.tif", heights(np.int16),
          tags=geo_tags(nodata=-32768) + [gdal_metadata([("OFFSET", "offset", 100), ("SCALE", "scale", 0.1)])])
    write("float32_navd88_feet.tif", heights(np.float32), tags=vertical_tags(4096, 8228))
    write("float32_us_survey_feet.tif", heights(np.float32), tags=vertical_tags(4099, 9003))
    write("float32_unittype_furlong.tif", heights(np.float32),
          tags=geo_tags() + [gdal_metadata([("UNITTYPE", "unittype", "furlong")])])
    write("float32_1x1_tiled.tif", np.full((1, 1), 123.5, np.float32), tile=(16, 16))
    with tifffile.TiffWriter("float32_internal_mask.tif") as tif:
        tif.write(heights(np.float32), photometric="minisblack", extratags=geo_tags())
        mask = np.ones((ROWS, COLS), bool)
        mask[2:5, 3:9] = False
        tif.write(mask, photometric=4, subfiletype=4, compression="zlib")


if __name__ == "__main__":
    units_and_masks()
