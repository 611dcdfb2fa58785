"""Outside oracles for what agripath reads: pyproj (UTM projection) and shapely (polygon
validity and area), checked through the `agripath validate --json` command users run.

Run by scripts/test (inside the .peers venv that has pyproj and shapely). Prints
'oracles: N passed, N failed' and exits non-zero on any failure.
"""
import json
import math
import os
import random
import subprocess
import sys
import tempfile

from pyproj import Transformer
from shapely.geometry import Polygon

BINARY = sys.argv[1] if len(sys.argv) > 1 else "target/debug/agripath"
passed = 0
failed = []


def check(ok, message):
    global passed
    if ok:
        passed += 1
    else:
        failed.append(message)


def validate(feature_collection, folder, name):
    path = os.path.join(folder, name)
    with open(path, "w") as handle:
        json.dump(feature_collection, handle)
    result = subprocess.run([BINARY, "validate", "--fields", path, "--json"], capture_output=True, text=True)
    return result, path


def star(random_source, centre, radius, count):
    """A star-shaped (so simple) ring: vertices at increasing angles, one radius each."""
    angles = sorted(random_source.uniform(0, 2 * math.pi) for _ in range(count))
    radii = [radius * random_source.uniform(0.3, 1.0) for _ in angles]
    return [
        (centre[0] + r * math.cos(a), centre[1] + r * math.sin(a))
        for a, r in zip(angles, radii)
    ]


def closed(ring):
    return [list(p) for p in ring] + [list(ring[0])]


def projection_cases(folder, random_source):
    """Random farms around the world: agripath's UTM bounds against PROJ's, to 1 mm."""
    for case in range(40):
        lon = random_source.uniform(-179.0, 179.0)
        lat = random_source.uniform(-79.0, 83.0)
        # A 2 km field in degrees (longer in longitude at high latitude).
        radius_lat = 1000.0 / 111_000.0
        radius_lon = radius_lat / max(math.cos(math.radians(lat)), 0.05)
        ring = [
            (lon + radius_lon * x, lat + radius_lat * y)
            for x, y in star(random_source, (0.0, 0.0), 1.0, 12)
        ]
        collection = {"type": "FeatureCollection", "features": [
            {"type": "Feature", "properties": {"name": f"f{case}"},
             "geometry": {"type": "Polygon", "coordinates": [closed(ring)]}}]}
        result, path = validate(collection, folder, f"lonlat_{case}.geojson")
        if result.returncode != 0:
            check(False, f"{path}: {result.stderr.strip()}")
            continue
        summary = json.loads(result.stdout)
        epsg = summary["coordinate_system"].split("EPSG:")[1].rstrip(")")
        to_utm = Transformer.from_crs("EPSG:4326", f"EPSG:{epsg}", always_xy=True)
        xs, ys = zip(*[to_utm.transform(x, y) for x, y in ring])
        expected = [min(xs), min(ys), max(xs), max(ys)]
        worst = max(abs(a - b) for a, b in zip(summary["farm_bounds_m"], expected))
        check(worst < 1e-3, f"{path}: UTM bounds differ from PROJ by {worst:.6f} m")
        area = Polygon(list(zip(xs, ys))).area
        check(abs(summary["total_area_m2"] - area) < 1e-3 * max(1.0, area) * 1e-3,
              f"{path}: area {summary['total_area_m2']} vs shapely on PROJ coordinates {area}")


def validity_cases(folder, random_source):
    """Random polygons with holes, some shuffled into self-intersection, some with holes
    pushed out: agripath's verdict and area against shapely's."""
    verdicts = {True: 0, False: 0}
    for case in range(150):
        shell = star(random_source, (0.0, 0.0), 100.0, random_source.randint(3, 14))
        holes = []
        for _ in range(random_source.randint(0, 3)):
            centre = (random_source.uniform(-60, 60), random_source.uniform(-60, 60))
            holes.append(star(random_source, centre, random_source.uniform(3, 25), random_source.randint(3, 7)))
        if random_source.random() < 0.35 and len(shell) > 3:
            random_source.shuffle(shell)
        polygon = Polygon(shell, holes)
        collection = {"type": "FeatureCollection", "crs": "local", "features": [
            {"type": "Feature", "properties": {"name": f"p{case}"},
             "geometry": {"type": "Polygon", "coordinates": [closed(shell)] + [closed(h) for h in holes]}}]}
        result, path = validate(collection, folder, f"local_{case}.geojson")
        ours = result.returncode == 0
        verdicts[polygon.is_valid] += 1
        check(result.returncode in (0, 2) and "panicked" not in result.stderr,
              f"{path}: exit {result.returncode}: {result.stderr.strip()}")
        check(ours == polygon.is_valid,
              f"{path}: agripath says {'valid' if ours else result.stderr.strip()}, shapely says valid={polygon.is_valid}")
        if ours and polygon.is_valid:
            area = json.loads(result.stdout)["total_area_m2"]
            check(abs(area - polygon.area) < 1e-6 * polygon.area, f"{path}: area {area} vs shapely {polygon.area}")
    print(f"validity: {verdicts[True]} valid and {verdicts[False]} invalid polygons compared with shapely")
    check(min(verdicts.values()) >= 30, f"too few cases of one kind: {verdicts}")


def orientation_cases(folder):
    """plan.geojson's polygons as RFC 7946 §3.1.6 orders their rings (exterior
    counterclockwise, holes clockwise), whatever way the input's rings turn: a field drawn
    clockwise with a counterclockwise hole, in lon/lat, planned; every Polygon of the plan
    (fields, obstacles, missed patches) checked with shapely."""
    shell = [[9.95, 49.8], [9.95, 49.8015], [9.9535, 49.8015], [9.9535, 49.8], [9.95, 49.8]]  # clockwise
    hole = [[9.9515, 49.8005], [9.952, 49.8005], [9.952, 49.8009], [9.9515, 49.8009], [9.9515, 49.8005]]
    collection = {"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"name": "clockwise"},
         "geometry": {"type": "Polygon", "coordinates": [shell, hole]}}]}
    path = os.path.join(folder, "clockwise.geojson")
    with open(path, "w") as handle:
        json.dump(collection, handle)
    out = os.path.join(folder, "clockwise_plan")
    result = subprocess.run([BINARY, "plan", "--fields", path, "--out", out], capture_output=True, text=True)
    check(result.returncode == 0, f"{path}: plan exit {result.returncode}: {result.stderr.strip()}")
    if result.returncode != 0:
        return
    with open(os.path.join(out, "plan.geojson")) as handle:
        features = json.load(handle)["features"]
    polygons = 0
    for feature in features:
        geometry = feature["geometry"]
        if geometry["type"] != "Polygon":
            continue
        polygons += 1
        rings = geometry["coordinates"]
        shape = Polygon(rings[0], rings[1:])
        kind = feature["properties"].get("kind")
        # The input's polygons are valid; a missed patch may be a wedge whose tip lies on its
        # own far side within the file's 1e-9° (decision 0036), and has no orientation then.
        if kind in ("field", "obstacle", "access"):
            check(shape.is_valid, f"plan.geojson: a {kind} polygon is not valid ({len(rings[0])} points)")
        elif not shape.is_valid:
            continue
        check(shape.exterior.is_ccw, f"plan.geojson: a {kind} polygon's exterior runs clockwise")
        for interior in shape.interiors:
            check(not interior.is_ccw, f"plan.geojson: a {kind} polygon's hole runs counterclockwise")
    check(polygons > 0, "plan.geojson: no polygon to check")
    print(f"orientation: {polygons} polygons of plan.geojson checked against RFC 7946")


def main():
    random_source = random.Random(20261123)
    with tempfile.TemporaryDirectory() as folder:
        projection_cases(folder, random_source)
        validity_cases(folder, random_source)
        orientation_cases(folder)
    for message in failed:
        print("FAILED:", message)
    print(f"oracles: {passed} passed, {len(failed)} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
