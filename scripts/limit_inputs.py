"""Writes the generated inputs of docs/limits.md into a folder (default /tmp/limits):
fields_10000.geojson (100 × 100 squares of 40 m, local metres), circle_50000.geojson (one
1 km circle of 50,000 vertices), dem_20000.asc and dem_20001.asc (headers only).

Run: python3 scripts/limit_inputs.py [FOLDER]
"""
import json
import math
import os
import sys

folder = sys.argv[1] if len(sys.argv) > 1 else "/tmp/limits"
os.makedirs(folder, exist_ok=True)


def square(x, y, side):
    return [[[x, y], [x + side, y], [x + side, y + side], [x, y + side], [x, y]]]


features = [
    {"type": "Feature", "properties": {"name": f"f{row}_{column}"},
     "geometry": {"type": "Polygon", "coordinates": square(column * 50.0, row * 50.0, 40.0)}}
    for row in range(100) for column in range(100)
]
with open(os.path.join(folder, "fields_10000.geojson"), "w") as handle:
    json.dump({"type": "FeatureCollection", "crs": "local", "features": features}, handle)

ring = [[1000.0 * math.cos(2 * math.pi * k / 50000), 1000.0 * math.sin(2 * math.pi * k / 50000)] for k in range(50000)]
ring.append(ring[0])
with open(os.path.join(folder, "circle_50000.geojson"), "w") as handle:
    json.dump({"type": "FeatureCollection", "crs": "local", "features": [
        {"type": "Feature", "properties": {"name": "circle"}, "geometry": {"type": "Polygon", "coordinates": [ring]}}]}, handle)

for size in (20000, 20001):
    with open(os.path.join(folder, f"dem_{size}.asc"), "w") as handle:
        handle.write(f"ncols {size}\nnrows {size}\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n")
print("wrote", folder)
