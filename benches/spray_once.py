"""Spray once (issue 22's acceptance): random irregular lon/lat fields with 0-2 holes, planned
with default settings (or `--edge-cut MODE`), flown from their mission files by the preflight
read-back; per field and in mean: covered %, missed m², double-sprayed m² and % of the
sprayable area, and the preflight's verdict.

Fields: star-shaped (simple), concave (at least one reflex corner; never a rectangle), 4-12
vertices at evenly spaced angles with jitter, 120-280 m across; 0-2 star-shaped holes of
4-7 vertices well inside (only in fields of 6 or more vertices, whose chords stay clear of
them); three fields a farm, 400 m apart, at random latitudes between -50 and 60 degrees; no DEM.

  python3 benches/spray_once.py target/release/agripath [FIELDS] [SEED] [--edge-cut MODE] [--scale K]
"""
import json
import math
import os
import random
import subprocess
import sys
import tempfile

args = [a for a in sys.argv[1:]]
extra = []
if "--edge-cut" in args:
    at = args.index("--edge-cut")
    extra = ["--edge-cut", args[at + 1]]
    del args[at:at + 2]
# --scale K: fields K times as wide (and farms K times as far apart), to see how the double
# dose falls with the size of the field (it goes as the swath width over the field's width).
scale = 1.0
if "--scale" in args:
    at = args.index("--scale")
    scale = float(args[at + 1])
    del args[at:at + 2]
AGRIPATH = args[0]
FIELDS = int(args[1]) if len(args) > 1 else 24
rng = random.Random(int(args[2]) if len(args) > 2 else 11)


def star(cx, cy, r_low, r_high, count, concave=True):
    while True:
        points = []
        # One notch (a reflex corner): deep in fields of few corners, whose chords run close
        # to the centre.
        notch = rng.randrange(count) if concave else -1
        for k in range(count):
            angle = (k + rng.uniform(-0.3, 0.3)) * 2 * math.pi / count
            r = rng.uniform(r_low, r_high)
            if k == notch:
                r = r_high * (rng.uniform(0.03, 0.08) if count <= 5 else rng.uniform(0.3, 0.45))
            points.append((cx + r * math.cos(angle), cy + r * math.sin(angle)))
        turns = [(points[(k + 1) % count][0] - points[k][0]) * (points[(k + 2) % count][1] - points[(k + 1) % count][1])
                 - (points[(k + 1) % count][1] - points[k][1]) * (points[(k + 2) % count][0] - points[(k + 1) % count][0])
                 for k in range(count)]
        if not concave or any(t < 0 for t in turns):
            return points + [points[0]]


def field(cx, cy):
    size = scale * rng.uniform(60, 140)
    vertices = rng.randint(4, 12)
    rings = [star(cx, cy, 0.55 * size, size, vertices)]
    holes = rng.randint(0, 2) if vertices >= 6 else 0
    for h in range(holes):
        angle = rng.uniform(0, 2 * math.pi) if holes == 1 else math.pi * h + rng.uniform(-0.3, 0.3)
        hx, hy = cx + 0.15 * size * math.cos(angle), cy + 0.15 * size * math.sin(angle)
        hole = star(hx, hy, 0.04 * size, 0.1 * size, rng.randint(4, 7), concave=False)
        rings.append(list(reversed(hole)))
    return rings


rows = []
flight = {"non_spray_time_s": 0.0, "total_time_s": 0.0, "turns": 0}
# KEEP=DIR keeps the farms and plan folders there to look at.
with (tempfile.TemporaryDirectory() if not os.environ.get("KEEP") else open(os.devnull)) as _scratch:
    scratch = os.environ.get("KEEP") or _scratch
    os.makedirs(scratch, exist_ok=True)
    farm_index = 0
    while len(rows) < FIELDS:
        lon0, lat0 = rng.uniform(-170, 170), rng.uniform(-50, 60)
        metres_lon = 111_320.0 * math.cos(math.radians(lat0))
        to_lonlat = lambda p: [lon0 + p[0] / metres_lon, lat0 + p[1] / 111_320.0]
        features = []
        for k in range(3):
            rings = field(scale * 400.0 * k, 0.0)
            features.append({"type": "Feature", "properties": {"name": f"F{k + 1}"},
                             "geometry": {"type": "Polygon",
                                          "coordinates": [[to_lonlat(p) for p in ring] for ring in rings]}})
        path = os.path.join(scratch, f"farm{farm_index}.geojson")
        with open(path, "w") as handle:
            json.dump({"type": "FeatureCollection", "features": features}, handle)
        out = os.path.join(scratch, f"out{farm_index}")
        run = subprocess.run([AGRIPATH, "plan", "--fields", path, "--out", out, "--allow-unsafe"] + extra,
                             capture_output=True, text=True)
        farm_index += 1
        if run.returncode != 0:
            print(f"farm {farm_index - 1}: exit {run.returncode}: {run.stderr.strip()}")
            continue
        report = json.load(open(os.path.join(out, "report.json")))
        verdict = report["preflight"]
        for key in flight:
            flight[key] += report[key]
        for figures in verdict["fields"]:
            area = figures["sprayable_area_m2"]
            rows.append((farm_index - 1, figures["name"], area, figures["covered_fraction"],
                         figures["missed_m2"], figures["double_sprayed_m2"], verdict["safe"],
                         verdict["sprayed_outside_fraction"]))

print(f"{'farm':>4} {'field':>5} {'area m2':>9} {'covered %':>9} {'missed m2':>9} {'double m2':>9} {'double %':>8}  verdict")
for farm, name, area, covered, missed, double, safe, outside in rows[:FIELDS]:
    print(f"{farm:4d} {name:>5} {area:9.1f} {100 * covered:9.2f} {missed:9.1f} {double:9.1f} "
          f"{100 * double / area:8.2f}  {'safe' if safe else 'UNSAFE'}")
rows = rows[:FIELDS]
double_shares = [r[5] / r[2] for r in rows]
print(f"{len(rows)} fields{' with ' + ' '.join(extra) if extra else ' (default settings)'}: "
      f"double-sprayed mean {100 * sum(double_shares) / len(rows):.2f}% (worst {100 * max(double_shares):.2f}%), "
      f"of the total area {100 * sum(r[5] for r in rows) / sum(r[2] for r in rows):.2f}%; "
      f"coverage mean {100 * sum(r[3] for r in rows) / len(rows):.2f}% (least {100 * min(r[3] for r in rows):.2f}%); "
      f"most spray outside {100 * max(r[7] for r in rows):.3f}%; "
      f"unsafe farms {len({r[0] for r in rows if not r[6]})}")
print(f"{farm_index} farms flown: non-spray time {flight['non_spray_time_s']:.0f} s, "
      f"total time {flight['total_time_s']:.0f} s, turns {flight['turns']}")
