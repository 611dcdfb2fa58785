"""Coverage as flown, measured from the mission files by shapely, against agripath's own
preflight figures.

For each plan folder, every `sortie_NN.plan` is flown item by item: DO_SPRAYER 1 / 0 (216)
switches the spray, NAV_WAYPOINT (16) moves. Each stretch flown with the spray on is a line,
buffered by half the swath with flat caps and round joins (a multirotor's footprint). The
union of those footprints, against the field polygons of the input file (projected with
PROJ; obstacles subtracted), gives each field's coverage and the spray outside the fields.
They must agree with `report.json` → `preflight` (agripath's row-exact measure) to 0.1 point
of coverage and 0.1 point of spray outside, and every field must be covered ≥ 99 %. Coverage
is of the ground a swath can reach (the field opened by a disc one swath across, computed
here by GEOS): unsprayed ground narrower than a swath is `unreachable_m2`, which must agree
too (to 0.5 m² or 2 %).

Inputs tried: the embedded demo (local metres placed at its origin), the Christmas Island
plantation (lon/lat, a hole and an obstacle, over the DEM), and farms of irregular concave
fields with close holes drawn here, which the planner was not written around.

Run: python tests/oracles/coverage_oracle.py target/debug/agripath
"""
import json
import math
import os
import subprocess
import sys
import tempfile

from pyproj import Transformer
from shapely.geometry import LineString, Polygon, shape
from shapely.ops import unary_union

AGRIPATH = sys.argv[1]
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
passed = failed = 0


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print("FAILED:", what)


def utm_epsg(lon, lat):
    zone = int((lon + 180) // 6) + 1
    return (32700 if lat < 0 else 32600) + zone


def sprayed_lines(folder, to_plan):
    lines = []
    for name in sorted(os.listdir(folder)):
        if not (name.startswith("sortie_") and name.endswith(".plan")):
            continue
        items = json.load(open(os.path.join(folder, name)))["mission"]["items"]
        spraying, here, run = False, None, []
        for item in items:
            command, params = item["command"], item["params"]
            if command == 216:
                if params[0] == 1 and not spraying:
                    run = [here]
                elif params[0] != 1 and spraying and len(run) >= 2:
                    lines.append(LineString(run))
                spraying = params[0] == 1
            elif command in (16, 21, 22):
                here = to_plan(params[5], params[4])
                if spraying:
                    run.append(here)
    return lines


def footprint_of(line, half):
    """A run's footprint: flat caps where the spray goes on and off, round joins where the run
    turns. A run that closes on its start (an edge pass round a boundary) stops spraying there,
    so it gets no join at that vertex: GEOS would treat a closed line as a ring and round it."""
    points = list(line.coords)
    style = dict(cap_style="flat", join_style="round", quad_segs=32)
    if len(points) >= 3 and points[0] == points[-1]:
        return unary_union([LineString(points[:-1]).buffer(half, **style),
                            LineString(points[-2:]).buffer(half, **style)])
    return line.buffer(half, **style)


def compare(label, folder, fields, obstacles, to_plan):
    report = json.load(open(os.path.join(folder, "report.json")))
    half = report["swath_width_m"] / 2
    footprint = unary_union([footprint_of(line, half) for line in sprayed_lines(folder, to_plan)])
    blocked = unary_union(obstacles) if obstacles else None
    ground = unary_union(fields)
    if blocked is not None:
        ground = ground.difference(blocked)
    verdict = report["preflight"]
    least = 1.0
    for field, figures in zip(fields, verdict["fields"]):
        region = field.difference(blocked) if blocked is not None else field
        ours = figures["covered_fraction"]
        # The ground a swath can reach: the opening by a disc one swath across. Coverage is
        # covered / (covered + reachable ground missed); unsprayed ground outside the
        # opening is unreachable, reported apart.
        style = dict(join_style="round", quad_segs=64)
        reachable = region.buffer(-half, **style).buffer(half, **style).intersection(region)
        covered = footprint.intersection(region).area
        missed = reachable.difference(footprint).area
        theirs = covered / (covered + missed)
        unreachable = max(region.area - covered - missed, 0.0)
        least = min(least, theirs)
        check(abs(ours - theirs) <= 1e-3,
              f"{label} {figures['name']}: covered {100 * ours:.3f}% (agripath) vs {100 * theirs:.3f}% (shapely)")
        check(abs(figures["unreachable_m2"] - unreachable) <= max(0.5, 0.02 * unreachable),
              f"{label} {figures['name']}: unreachable {figures['unreachable_m2']:.2f} m² (agripath) vs {unreachable:.2f} m² (shapely)")
        check(theirs >= 0.99, f"{label} {figures['name']}: {100 * theirs:.2f}% covered as flown (shapely)")
        print(f"coverage: {label} {figures['name']}: unreachable {figures['unreachable_m2']:.2f} m² (shapely {unreachable:.2f} m²)")
    outside = footprint.difference(ground).area / footprint.area
    check(abs(outside - verdict["sprayed_outside_fraction"]) <= 1e-3,
          f"{label}: outside {verdict['sprayed_outside_fraction']} (agripath) vs {outside:.6f} (shapely)")
    print(f"coverage: {label}: {len(fields)} field(s), least covered {100 * min(f['covered_fraction'] for f in verdict['fields']):.3f}% "
          f"(shapely {100 * least:.3f}%), outside {100 * outside:.4f}%")


def lonlat_frame(lon, lat):
    forward = Transformer.from_crs("EPSG:4326", f"EPSG:{utm_epsg(lon, lat)}", always_xy=True)
    return lambda lo, la: forward.transform(lo, la)


def read_fields(path, project):
    fields, obstacles = [], []
    for feature in json.load(open(path))["features"]:
        if feature["geometry"]["type"] != "Polygon":
            continue
        rings = [[project(*p[:2]) for p in ring] for ring in feature["geometry"]["coordinates"]]
        polygon = Polygon(rings[0], rings[1:])
        (obstacles if feature["properties"].get("kind") == "obstacle" else fields).append(polygon)
    return fields, obstacles


def irregular_farm(rng_seed):
    """Two concave fields, one with two holes a little more than a swath apart."""
    import random
    rng = random.Random(rng_seed)
    lon0, lat0 = rng.uniform(-120, 120), rng.uniform(-40, 50)
    metres_lon = 111_320.0 * math.cos(math.radians(lat0))
    to_lonlat = lambda x, y: [lon0 + x / metres_lon, lat0 + y / 111_320.0]
    def ring(points, jitter=4.0):
        moved = [(x + rng.uniform(-jitter, jitter), y + rng.uniform(-jitter, jitter)) for x, y in points]
        return [to_lonlat(*p) for p in moved + [moved[0]]]
    l_shape = [(0, 0), (140, 0), (140, 50), (60, 70), (55, 120), (0, 110)]
    holes = [[(20, 20), (32, 20), (32, 32), (20, 32)], [(39, 22), (50, 24), (46, 35)]]
    wedge = [(200, 0), (320, 10), (300, 90), (260, 40), (215, 85)]
    features = [
        {"type": "Feature", "properties": {"name": "L"},
         "geometry": {"type": "Polygon", "coordinates": [ring(l_shape)] + [ring(h[::-1], 1.0) for h in holes]}},
        {"type": "Feature", "properties": {"name": "W"},
         "geometry": {"type": "Polygon", "coordinates": [ring(wedge)]}},
    ]
    return {"type": "FeatureCollection", "features": features}, lon0, lat0


with tempfile.TemporaryDirectory() as scratch:
    run = lambda *arguments: subprocess.run([AGRIPATH, *arguments], check=True, stdout=subprocess.DEVNULL)

    island = os.path.join(scratch, "island")
    run("plan", os.path.join(ROOT, "data/scenarios/christmas_island.toml"), "--out", island)
    fields_path = os.path.join(ROOT, "data/christmas_island_fields.geojson")
    first = json.load(open(fields_path))["features"][0]["geometry"]["coordinates"][0][0]
    project = lonlat_frame(*first)
    compare("island", island, *read_fields(fields_path, project), project)

    demo = os.path.join(scratch, "demo")
    run("demo", "--out", demo)
    origin = json.load(open(os.path.join(demo, "report.json")))["mission"]["local_origin"]
    to_utm = lonlat_frame(*origin)
    east, north = to_utm(*origin)
    compare("demo", demo, *read_fields(os.path.join(ROOT, "data/seed001_farm.geojson"), lambda x, y: (x, y)),
            lambda lo, la: tuple(a - b for a, b in zip(to_utm(lo, la), (east, north))))

    for seed in (1, 2, 3):
        farm, lon0, lat0 = irregular_farm(seed)
        path = os.path.join(scratch, f"irregular{seed}.geojson")
        json.dump(farm, open(path, "w"))
        out = os.path.join(scratch, f"irregular{seed}")
        result = subprocess.run([AGRIPATH, "plan", "--fields", path, "--allow-unsafe", "--out", out],
                                capture_output=True, text=True)
        check(result.returncode == 0, f"irregular farm {seed}: exit {result.returncode}: {result.stderr}")
        project = lonlat_frame(lon0, lat0)
        compare(f"irregular farm {seed}", out, *read_fields(path, project), project)

print(f"coverage: {passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
