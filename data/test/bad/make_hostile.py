"""Writes the hostile inputs of the bad-input corpus that are easier generated than typed
(run from this folder: python3 make_hostile.py). Each is one fault; the corpus test
(crates/cli/tests/bad_input.rs) says which message it must get."""
import json
import zipfile


def collection(features, local=True):
    document = {"type": "FeatureCollection", "features": features}
    if local:
        document["crs"] = "local"
    return document


def polygon(name, ring, kind=None):
    properties = {"name": name}
    if kind:
        properties["kind"] = kind
    return {"type": "Feature", "properties": properties,
            "geometry": {"type": "Polygon", "coordinates": [ring]}}


def square(x0, y0, side):
    return [[x0, y0], [x0 + side, y0], [x0 + side, y0 + side], [x0, y0 + side], [x0, y0]]


def write_json(name, document):
    with open(name, "w") as file:
        json.dump(document, file)


write_json("overlap.geojson", collection([
    polygon("north", square(0, 0, 100)), polygon("south", [[0, -80], [100, -80], [100, 20], [0, 20], [0, -80]])]))
write_json("duplicate_field.geojson", collection([
    polygon("A", square(0, 0, 100)), polygon("A again", square(0, 0, 100))]))
write_json("covered_by_obstacle.geojson", collection([
    polygon("wood", square(0, 0, 100)), polygon("trees", square(-5, -5, 110), "obstacle")]))
write_json("speck.geojson", collection([polygon("big", square(0, 0, 100)), polygon("speck", square(200, 0, 1))]))
write_json("huge_area.geojson", collection([polygon("prairie", square(0, 0, 12000))]))
write_json("many_swaths.geojson", collection([polygon("wide", square(0, 0, 5000))]))
write_json("polar.geojson", collection([polygon("ice", [[10, 85], [10.1, 85], [10.1, 85.1], [10, 85]])], local=False))
write_json("wide_polar.geojson", collection([polygon("tundra", [[0, 83], [7, 83], [7, 83.01], [0, 83]])], local=False))
write_json("nan_string_coordinate.geojson", collection([polygon("x", [[0, 0], [10, 0], ["NaN", 10], [0, 0]])]))
write_json("null_geometry.geojson", collection([{"type": "Feature", "properties": {}, "geometry": None}]))
write_json("empty_collection.geojson", {"type": "FeatureCollection", "features": []})
write_json("number_root.geojson", 42)
with open("deep_nesting.geojson", "w") as file:
    file.write("[" * 100000 + "]" * 100000)
write_json("multipolygon_bad_part.geojson", collection([{
    "type": "Feature", "properties": {"name": "two"},
    "geometry": {"type": "MultiPolygon", "coordinates": [[square(0, 0, 10)], [[[20, 0], [30, 10], [30, 0], [20, 10], [20, 0]]]]}}]))
write_json("point_only.geojson", collection([{"type": "Feature", "properties": {"kind": "launch"},
                                               "geometry": {"type": "Point", "coordinates": [0, 0]}}]))
write_json("two_launches.geojson", collection([
    polygon("A", square(0, 0, 100)),
    {"type": "Feature", "properties": {"kind": "launch", "name": "one"}, "geometry": {"type": "Point", "coordinates": [-10, 0]}},
    {"type": "Feature", "properties": {"kind": "launch", "name": "two"}, "geometry": {"type": "Point", "coordinates": [-20, 0]}}]))

KML_HEAD = '<?xml version="1.0" encoding="UTF-8"?>\n'
RING = "8.5,47.3 8.51,47.3 8.51,47.31 8.5,47.3"


def kml(body, namespace="http://www.opengis.net/kml/2.2", head=KML_HEAD):
    return f'{head}<kml xmlns="{namespace}"><Document>{body}</Document></kml>\n'


def placemark(name, coordinates=RING):
    return (f"<Placemark><name>{name}</name><Polygon><outerBoundaryIs><LinearRing>"
            f"<coordinates>{coordinates}</coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark>")


def write_text(name, text):
    with open(name, "w") as file:
        file.write(text)


write_text("wrong_namespace.kml", kml(placemark("A"), namespace="http://example.com/not-kml"))
write_text("entities.kml", kml(placemark("&b;"), head=KML_HEAD + '<!DOCTYPE kml [<!ENTITY a "aaaaaaaaaa">'
                               '<!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">]>\n'))
write_text("unknown_entity.kml", kml(placemark("&nbsp;")))
write_text("deep.kml", kml("<Folder>" * 300 + placemark("A") + "</Folder>" * 300))
write_text("nan_coordinate.kml", kml(placemark("A", "8.5,47.3 nan,47.3 8.51,47.31 8.5,47.3")))
write_text("latitude_out_of_range.kml", kml(placemark("A", "8.5,97.3 8.51,97.3 8.51,97.31 8.5,97.3")))
write_text("empty_coordinates.kml", kml(placemark("A", "")))
write_text("polar.kml", kml(placemark("A", "8.5,86.3 8.51,86.3 8.51,86.31 8.5,86.3")))
write_text("overlap.kml", kml(placemark("A") + placemark("B")))
with zipfile.ZipFile("wrong_namespace.kmz", "w", zipfile.ZIP_DEFLATED) as archive:
    archive.writestr("doc.kml", kml(placemark("A"), namespace="http://example.com/not-kml"))
with zipfile.ZipFile("bomb.kmz", "w", zipfile.ZIP_DEFLATED) as archive:
    # 600 MB of spaces inflate from under a megabyte: past the 512 MB limit for the inner KML.
    with archive.open("doc.kml", "w") as entry:
        chunk = b" " * (1 << 20)
        for _ in range(600):
            entry.write(chunk)

# Vehicles: each one figure out of its plausible range (model/limits.rs).
for name, key, value in [
    ("vehicle_zero_speed.toml", "spray_speed_mps", 0.0),
    ("vehicle_huge_battery.toml", "battery_endurance_s", 1e9),
    ("vehicle_tiny_tank.toml", "tank_l", 0.0001),
    ("vehicle_negative_swap.toml", "battery_swap_s", -1.0),
    ("vehicle_huge_swath.toml", "swath_width_m", 1e308),
    ("vehicle_fast_climb.toml", "climb_speed_mps", 500.0),
    ("vehicle_reserve_95.toml", "battery_reserve_percent", 95.0),
]:
    write_text(name, f'name = "hostile"\nswath_width_m = 5.0\n{key} = {value!r}\n'.replace(
        "swath_width_m = 5.0\nswath_width_m", "swath_width_m"))
write_text("vehicle_huge_rate.toml", 'name = "hostile"\ntank_l = 16.0\napplication_rate_l_per_ha = 1e9\n')

# Scenarios.
write_text("scenario_overlap_type.toml", 'fields = "../../seed001_farm.geojson"\nallow_overlap = "yes"\n')
write_text("scenario_missing_vehicle.toml", 'fields = "../../seed001_farm.geojson"\nvehicle_file = "nowhere.toml"\n')
write_text("scenario_overlapping_fields.toml", 'fields = "overlap.geojson"\n')

# Track scenarios.
seed000 = json.load(open("track_start_in_threat.json"))
same = json.loads(json.dumps(seed000))
same["tasks"][0]["start"] = [300, 300, 250]
same["tasks"][0]["goal"] = [300, 300, 250]
write_json("track_start_is_goal.json", same)
many = json.loads(json.dumps(seed000))
many["tasks"][0]["start"] = [5, 5, 250]
many["tasks"][0]["threat_cylinders_x_y_r"] = [[100 + (i % 40) * 20, 100 + (i // 40) * 20, 1] for i in range(1001)]
write_json("track_too_many_threats.json", many)
nan_goal = json.loads(json.dumps(seed000))
nan_goal["tasks"][0]["start"] = [5, 5, 250]
nan_goal["tasks"][0]["goal"] = [100, 100, 1e400]
with open("track_infinite_goal.json", "w") as file:
    file.write(json.dumps(nan_goal).replace("Infinity", "1e400"))
