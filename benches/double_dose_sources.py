"""Where the double dose of a plan comes from: for each plan folder under ROOT (as
`KEEP=ROOT python3 benches/spray_once.py …` leaves them), the footprints of the swaths and
of the edge passes in `plan.geojson` (lines buffered by half a swath, flat caps, round
joins, by shapely) split the preflight's double-sprayed area into swath∩edge, swath∩swath
and the rest (edge passes overlapping themselves or each other).

  KEEP=/tmp/so python3 benches/spray_once.py target/release/agripath 24 11 --edge-cut balanced
  .peers/oracles/bin/python benches/double_dose_sources.py /tmp/so
"""
import json, math, os, sys
from shapely.geometry import LineString, shape
from shapely.ops import unary_union
root = sys.argv[1]
tot = {"se": 0, "ss": 0, "ee": 0, "D": 0, "A": 0}
for name in sorted(os.listdir(root)):
    if not name.startswith("out"): continue
    g = json.load(open(os.path.join(root, name, "plan.geojson")))
    rep = json.load(open(os.path.join(root, name, "report.json")))
    w = rep["swath_width_m"]
    feats = g["features"]
    pts = [c for f in feats if f["properties"]["kind"] == "field" for c in f["geometry"]["coordinates"][0]]
    lon0 = sum(p[0] for p in pts)/len(pts); lat0 = sum(p[1] for p in pts)/len(pts)
    k = 111320*math.cos(math.radians(lat0))
    P = lambda c: ((c[0]-lon0)*k, (c[1]-lat0)*111320)
    def fp(f):
        return LineString([P(c) for c in f["geometry"]["coordinates"]]).buffer(w/2, cap_style="flat", join_style="round")
    sw = [fp(f) for f in feats if f["properties"]["kind"] == "swath"]
    ed = [fp(f) for f in feats if f["properties"]["kind"] == "edge"]
    Us, Ue = unary_union(sw), unary_union(ed)
    se = Us.intersection(Ue).area
    ss = sum(s.area for s in sw) - Us.area
    D = sum(f["double_sprayed_m2"] for f in rep["preflight"]["fields"])
    A = sum(f["sprayable_area_m2"] for f in rep["preflight"]["fields"])
    ee = D - se - ss
    for key, v in (("se", se), ("ss", ss), ("ee", ee), ("D", D), ("A", A)): tot[key] += v
    print(f"{name}: double {D:.0f} m² = swath/edge {se:.0f} + swath/swath {ss:.0f} + edge/edge {ee:.0f}; of {A:.0f} m²")
print({k: round(v) for k, v in tot.items()}, f"se {100*tot['se']/tot['A']:.2f}% ss {100*tot['ss']/tot['A']:.2f}% ee {100*tot['ee']/tot['A']:.2f}%")
