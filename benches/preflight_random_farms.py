"""Default plans of random lon/lat farms with holes, flown from their mission files by the
preflight read-back (issue 15's acceptance): per field the coverage as flown, the spray
outside the fields, and the legs through holes or obstacles.

Farms: 2-4 irregular fields each (star-shaped, so simple and concave, 6-12 vertices, 60-220 m
across), 0-2 holes each (small polygons well inside), a few hundred metres apart, placed at
random latitudes between -50 and 60 degrees; no DEM (relative altitudes).

  python3 benches/preflight_random_farms.py target/release/agripath [FARMS] [SEED]
"""
import json
import math
import os
import random
import subprocess
import sys
import tempfile

AGRIPATH = sys.argv[1]
EXTRA = sys.argv[4:]
FARMS = int(sys.argv[2]) if len(sys.argv) > 2 else 20
rng = random.Random(int(sys.argv[3]) if len(sys.argv) > 3 else 7)


def star(cx, cy, r_low, r_high, count):
    angles = sorted(rng.uniform(0, 2 * math.pi) for _ in range(count))
    points = []
    for angle in angles:
        r = rng.uniform(r_low, r_high)
        points.append((cx + r * math.cos(angle), cy + r * math.sin(angle)))
    return points + [points[0]]


def farm(lon0, lat0):
    metres_lon = 111_320.0 * math.cos(math.radians(lat0))
    to_lonlat = lambda p: [lon0 + p[0] / metres_lon, lat0 + p[1] / 111_320.0]
    features = []
    for k in range(rng.randint(2, 4)):
        cx, cy = 320.0 * k, rng.uniform(-80, 80)
        size = rng.uniform(30, 110)
        shell = star(cx, cy, 0.55 * size, size, rng.randint(6, 12))
        rings = [shell]
        holes = rng.randint(0, 2)
        for h in range(holes):
            angle = rng.uniform(0, 2 * math.pi) if holes == 1 else math.pi * h + rng.uniform(-0.3, 0.3)
            hx = cx + 0.25 * size * math.cos(angle)
            hy = cy + 0.25 * size * math.sin(angle)
            hole = star(hx, hy, 0.05 * size, 0.12 * size, rng.randint(4, 7))
            rings.append(list(reversed(hole)))
        features.append({"type": "Feature", "properties": {"name": f"F{k + 1}"},
                         "geometry": {"type": "Polygon", "coordinates": [[to_lonlat(p) for p in ring] for ring in rings]}})
    return {"type": "FeatureCollection", "features": features}


worst_coverage, worst_outside, through, fields, unsafe = 1.0, 0.0, 0, 0, []
worst_raw, unreachable, sprayable = 1.0, 0.0, 0.0
# KEEP=DIR keeps the farms and plan folders there to look at.
with (tempfile.TemporaryDirectory() if not os.environ.get("KEEP") else open(os.devnull)) as _scratch:
    scratch = os.environ.get("KEEP") or _scratch
    os.makedirs(scratch, exist_ok=True)
    for index in range(FARMS):
        lon0, lat0 = rng.uniform(-170, 170), rng.uniform(-50, 60)
        path = os.path.join(scratch, f"farm{index}.geojson")
        with open(path, "w") as handle:
            json.dump(farm(lon0, lat0), handle)
        out = os.path.join(scratch, f"out{index}")
        run = subprocess.run([AGRIPATH, "plan", "--fields", path, "--out", out] + EXTRA, capture_output=True, text=True)
        if run.returncode not in (0, 3):
            print(f"farm {index}: exit {run.returncode}: {run.stderr.strip()}")
            continue
        report = json.load(open(os.path.join(out, "report.json")))
        verdict = report["preflight"]
        if not verdict["safe"]:
            unsafe.append((index, verdict["failures"]))
        coverage = min(f["covered_fraction"] for f in verdict["fields"])
        # Of the whole sprayable area, the ground narrower than a swath included.
        raw = min(1 - (f["missed_m2"] + f["unreachable_m2"]) / f["sprayable_area_m2"] for f in verdict["fields"])
        worst_raw = min(worst_raw, raw)
        unreachable += sum(f["unreachable_m2"] for f in verdict["fields"])
        sprayable += sum(f["sprayable_area_m2"] for f in verdict["fields"])
        holes_check = next(c for c in verdict["checks"] if c["name"] == "holes and obstacles")
        through += int(holes_check["figure"])
        fields += len(verdict["fields"])
        worst_coverage = min(worst_coverage, coverage)
        worst_outside = max(worst_outside, verdict["sprayed_outside_fraction"])
        print(f"farm {index:2d} ({lon0:8.3f}, {lat0:7.3f}): {len(verdict['fields'])} fields, "
              f"{report['sorties']} sorties, least coverage as flown {100 * coverage:.2f}% "
              f"({100 * raw:.2f}% of the sprayable area), "
              f"outside {100 * verdict['sprayed_outside_fraction']:.3f}%, "
              f"{'safe' if verdict['safe'] else 'UNSAFE'}")
print(f"{FARMS} farms, {fields} fields: least coverage as flown {100 * worst_coverage:.2f}% of the ground a swath "
      f"reaches ({100 * worst_raw:.2f}% of the sprayable area; unreachable {unreachable:.0f} m², "
      f"{100 * unreachable / max(sprayable, 1):.2f}% of {sprayable:.0f} m²), "
      f"most spray outside {100 * worst_outside:.3f}%, samples in holes or obstacles {through}, "
      f"unsafe {len(unsafe)}")
for index, failures in unsafe:
    print(f"  farm {index}: {failures[:3]}")
