"""Mission files checked by the tools autopilots use.

Every `.waypoints` file of the plans (the embedded demo; the Christmas Island plantation in
lon/lat over the real DEM, with sea-level altitudes, with terrain-frame altitudes, and surveyed
by a camera drone; the seed 001 farm with a pump on a servo output) is loaded with
pymavlink's `mavwp.MAVWPLoader` (what MAVProxy and Mission Planner-compatible tools use),
each item packed as an ArduPilot MISSION_ITEM (which refuses out-of-range fields), and the
matching `.plan` must hold the same commands, frames and parameters. A field over a cliff one
cell wide, in a grid this script writes, is flown leg by leg against the script's own
interpolation of that grid (`cliff_flown`). A point-to-point track
over SPSO's DEM is loaded the same way, and its start and goal must sit where PROJ puts the
DEM's pixels (EPSG:28348 → GDA94 longitude/latitude); a track to a goal above a cliff's top,
over a grid written here, is flown item by item as ArduCopter flies it (`track_landing_flown`).
A sprayer's sorties over a hill, in a grid written here, are timed as ArduCopter flies them,
its landing included, against the battery they must land with (`battery_flown`).

Run: python tests/oracles/mission_oracle.py target/debug/agripath
"""
import csv
import glob
import json
import math
import os
import subprocess
import sys
import tempfile

from pymavlink import mavwp
from pymavlink.dialects.v20 import ardupilotmega as mavlink

AGRIPATH = sys.argv[1]
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
KNOWN_COMMANDS = {16, 21, 22, 178, 183, 206, 216}

passed = failed = 0


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print("FAILED:", what)


def same(a, b):
    if a is None:
        return b is None or (isinstance(b, float) and math.isnan(b))
    return abs(float(a) - float(b)) <= 1e-6 * max(1.0, abs(float(a)))


def check_folder(folder, frames, with_plan=True):
    mav = mavlink.MAVLink(None)
    waypoint_files = sorted(glob.glob(os.path.join(folder, "*.waypoints")))
    check(len(waypoint_files) >= 1, f"{folder}: no .waypoints written")
    for path in waypoint_files:
        name = os.path.basename(path)
        with open(path) as handle:
            lines = [line for line in handle.read().splitlines() if line.strip()]
        loader = mavwp.MAVWPLoader()
        count = loader.load(path)
        check(count == len(lines) - 1, f"{name}: pymavlink read {count} of {len(lines) - 1} items")
        for index in range(count):
            item = loader.wp(index)
            try:
                item.pack(mav)
                packed = True
            except Exception as error:  # noqa: BLE001 - any refusal is the finding
                packed = False
                print("  ", name, index, error)
            check(packed, f"{name}: item {index} packs as MISSION_ITEM")
            check(item.command in KNOWN_COMMANDS, f"{name}: item {index} command {item.command}")
            if item.command in (16, 21, 22) and index > 0:  # row 0 is home, always AMSL
                check(item.frame in frames, f"{name}: item {index} frame {item.frame}")
                check(-90 <= item.x <= 90 and -180 <= item.y <= 180 and item.x != 0, f"{name}: item {index} position")
        check(loader.wp(1).command == 22 and loader.wp(count - 1).command == 21, f"{name}: takeoff first, land last")
        # waypoints.csv's `index` is the mission item's number (the .waypoints row): each row
        # of this sortie names its item's place (trial 7 found it one less).
        csv_path = os.path.join(folder, "waypoints.csv")
        sortie = name[len("sortie_"):-len(".waypoints")]
        if os.path.exists(csv_path) and sortie.isdigit():
            with open(csv_path) as handle:
                rows = [row for row in csv.DictReader(handle) if row["sortie"] == str(int(sortie))]
            check(len(rows) == count - 1, f"waypoints.csv: {len(rows)} rows for {name}'s {count - 1} items")
            for row in rows:
                item = loader.wp(int(row["index"]))
                if item.command in (16, 21, 22):
                    check(abs(float(row["lat"]) - item.x) < 1e-7 and abs(float(row["lon"]) - item.y) < 1e-7,
                          f"waypoints.csv: sortie {sortie} index {row['index']} is not that item's place")
        if not with_plan:
            continue
        plan_path = path[: -len(".waypoints")] + ".plan"
        with open(plan_path) as handle:
            plan = json.load(handle)
        items = plan["mission"]["items"]
        check(len(items) == count - 1, f"{os.path.basename(plan_path)}: {len(items)} items, .waypoints has {count - 1}")
        for index, plan_item in enumerate(items[: count - 1]):
            item = loader.wp(index + 1)
            params = [item.param1, item.param2, item.param3, item.param4, item.x, item.y, item.z]
            check(plan_item["command"] == item.command and plan_item["frame"] == item.frame,
                  f"{name}: item {index + 1} command/frame differ from the .plan")
            check(all(same(p, q) for p, q in zip(plan_item["params"], params)),
                  f"{name}: item {index + 1} params {plan_item['params']} vs {params}")


def write_grid(path, heights, x0, y0, cell):
    """Writes `heights` (row 0 the southernmost) as an ESRI ASCII grid whose lower-left corner
    is (x0, y0), and returns this script's own bilinear reading of it."""
    with open(path, "w") as handle:
        rows, columns = heights.shape
        handle.write(f"ncols {columns}\nnrows {rows}\nxllcorner {x0}\nyllcorner {y0}\ncellsize {cell}\nNODATA_value -9999\n")
        for row in heights[::-1]:
            handle.write(" ".join(f"{value:.3f}" for value in row) + "\n")
    return bilinear(heights, x0 + 0.5 * cell, y0 + 0.5 * cell, cell)


def bilinear(heights, first_x, first_y, cell):
    """The bilinear surface through a grid's cell centres (row 0 the southernmost, the first
    centre at (first_x, first_y)), held flat beyond the outer centres: this script's own reading
    of the grids it writes."""
    import numpy

    rows, columns = heights.shape

    def ground(x, y):
        u = numpy.clip((x - first_x) / cell, 0, columns - 1)
        v = numpy.clip((y - first_y) / cell, 0, rows - 1)
        i = numpy.minimum(numpy.floor(u).astype(int), columns - 2)
        j = numpy.minimum(numpy.floor(v).astype(int), rows - 2)
        fu, fv = u - i, v - j
        return (heights[j, i] * (1 - fu) * (1 - fv) + heights[j, i + 1] * fu * (1 - fv)
                + heights[j + 1, i] * (1 - fu) * fv + heights[j + 1, i + 1] * fu * fv)

    return ground


def cliff_flown(scratch):
    """Plans a field over a 12 m step one 4 m cell wide, in local metres over an ESRI grid
    written here, and flies every spray leg of the `.waypoints` against numpy's bilinear
    interpolation of that grid (cell centres, held flat beyond the outer ones), every 2 cm:
    within 1 m (the default tolerance) of the 2 m spray height, never under 0.5 m."""
    import numpy
    from pyproj import Transformer

    columns, rows, cell, x0, y0 = 60, 60, 4.0, -20.0, -20.0
    centres_x = x0 + (numpy.arange(columns) + 0.5) * cell
    centres_y = y0 + (numpy.arange(rows) + 0.5) * cell  # south to north
    heights = 100.0 + 0.05 * centres_x[None, :] + 12.0 * (centres_y[:, None] > 100.0)
    folder = os.path.join(scratch, "cliff")
    os.makedirs(folder)
    ground = write_grid(os.path.join(folder, "cliff.asc"), heights, x0, y0, cell)
    field = {"type": "FeatureCollection", "crs": "local", "features": [{"type": "Feature", "properties": {"name": "slope"},
             "geometry": {"type": "Polygon", "coordinates": [[[20, 30], [180, 38], [172, 190], [28, 182], [20, 30]]]}}]}
    with open(os.path.join(folder, "field.geojson"), "w") as handle:
        json.dump(field, handle)
    # A vehicle that climbs 4 m/s: the default's 2 m/s crosses the step at 0.67 m/s, under
    # ArduPilot's SPRAY_SPEED_MIN, the pump stops there, and the plan is refused for its
    # coverage (decision 0030); this test is about the heights flown.
    with open(os.path.join(folder, "vehicle.toml"), "w") as handle:
        handle.write('name = "climbs 4 m/s"\nclimb_speed_mps = 4.0\n')
    out = os.path.join(folder, "out")
    subprocess.run([AGRIPATH, "plan", "--fields", os.path.join(folder, "field.geojson"), "--terrain",
                    os.path.join(folder, "cliff.asc"), "--vehicle", os.path.join(folder, "vehicle.toml"),
                    "--heading", "85", "--out", out],
                   check=True, stdout=subprocess.DEVNULL)


    to_utm = Transformer.from_crs("EPSG:4326", "EPSG:32652", always_xy=True)
    east0, north0 = to_utm.transform(126.63, 45.75)
    worst_error, lowest, legs = 0.0, math.inf, 0
    for path in sorted(glob.glob(os.path.join(out, "sortie_*.waypoints"))):
        loader = mavwp.MAVWPLoader()
        loader.load(path)
        spraying, previous = False, None
        for index in range(1, loader.count()):
            item = loader.wp(index)
            if item.command == 216:
                spraying = item.param1 >= 0.5
                continue
            if item.command != 16:
                previous = None
                continue
            check(item.frame == 0, f"cliff {os.path.basename(path)}: item {index} in frame {item.frame}, not sea level")
            east, north = to_utm.transform(item.y, item.x)
            here = (east - east0, north - north0, item.z)
            if previous is not None:
                length = math.hypot(here[0] - previous[0], here[1] - previous[1])
                t = numpy.linspace(0.0, 1.0, max(2, int(length / 0.02) + 1))
                x = previous[0] + t * (here[0] - previous[0])
                y = previous[1] + t * (here[1] - previous[1])
                above = previous[2] + t * (here[2] - previous[2]) - ground(x, y)
                lowest = min(lowest, float(above.min()))
                if spraying:
                    legs += 1
                    worst_error = max(worst_error, float(numpy.abs(above - 2.0).max()))
            previous = here
    check(legs > 50, f"cliff: {legs} spray legs flown")
    check(worst_error <= 1.0 + 0.02, f"cliff: a spray leg flies {worst_error:.3f} m off the 2 m spray height")
    check(lowest >= 0.5 - 0.02, f"cliff: a leg flies {lowest:.3f} m above the ground")
    print(f"cliff: {legs} spray legs, worst {worst_error:.3f} m off spray height, lowest {lowest:.3f} m above the ground")


def track_landing_flown(scratch):
    """A track from below a 60 m cliff to a goal 50 m above its top (above the band's floor,
    so no vertical leg is planned there), over an ESRI grid written here in local metres. Each
    written `.waypoints` is flown as ArduCopter flies it: NAV_TAKEOFF climbs at home, a
    NAV_WAYPOINT is flown straight, a NAV_LAND flies to its place at the altitude it has and
    then descends (`ModeAuto::do_land`). Every airborne leg, sampled every 0.5 m against this
    script's bilinear interpolation of the grid, keeps the 2 m minimum clearance above the
    ground (decision 0033: the file used to end on a NAV_LAND from the last cruise waypoint,
    flown level into the cliff)."""
    import numpy
    from pyproj import Transformer

    columns, rows, cell = 240, 160, 5.0
    centres_x = (numpy.arange(columns) + 0.5) * cell
    heights = numpy.tile(20.0 + 60.0 * (centres_x > 600.0), (rows, 1))
    folder = os.path.join(scratch, "track-cliff")
    os.makedirs(folder)
    ground = write_grid(os.path.join(folder, "cliff.asc"), heights, 0.0, 0.0, cell)
    with open(os.path.join(folder, "track.toml"), "w") as handle:
        handle.write('name = "to the cliff top"\ncrs = "local"\nterrain = { kind = "file", path = "cliff.asc" }\n'
                     'origin = [173.2, -41.3]\nstart = [250, 200, 20]\ngoal = [900, 600, 50]\n'
                     'height_band_m = [20, 120]\nfree_waypoints = 8\nmargin_m = 50\npopulation = 60\n'
                     'iterations = 60\nthreats = []\n')
    out = os.path.join(folder, "out")
    subprocess.run([AGRIPATH, "track", os.path.join(folder, "track.toml"), "--algorithm", "pso,ga,lattice",
                    "--runs", "1", "--out", out], check=True, stdout=subprocess.DEVNULL)


    zone = int((173.2 + 180) // 6) + 1
    to_utm = Transformer.from_crs("EPSG:4326", f"EPSG:{32700 + zone}", always_xy=True)
    east0, north0 = to_utm.transform(173.2, -41.3)
    files = sorted(glob.glob(os.path.join(out, "*.waypoints")))
    check(len(files) >= 2, f"track to the cliff top: {len(files)} tracks written")
    for path in files:
        loader = mavwp.MAVWPLoader()
        loader.load(path)
        items = [loader.wp(index) for index in range(loader.count())]

        def place(item):
            east, north = to_utm.transform(item.y, item.x)
            return east - east0, north - north0

        home = items[0]
        here = (*place(home), home.z)
        lowest = math.inf
        for item in items[1:]:
            x, y = place(item)
            if item.command == 22:
                here = (here[0], here[1], item.z)
                continue
            to = (x, y, here[2]) if item.command == 21 else (x, y, item.z)
            length = math.hypot(to[0] - here[0], to[1] - here[1])
            t = numpy.linspace(0.0, 1.0, max(2, int(length / 0.5) + 1))
            above = here[2] + t * (to[2] - here[2]) - ground(here[0] + t * (to[0] - here[0]), here[1] + t * (to[1] - here[1]))
            lowest = min(lowest, float(above.min()))
            here = to
        check(items[-1].command == 21, f"{os.path.basename(path)}: ends on NAV_LAND")
        check(lowest >= 2.0 - 0.01, f"track to the cliff top {os.path.basename(path)}: flown {lowest:.2f} m above the ground")
        print(f"track to the cliff top {os.path.basename(path)}: lowest {lowest:.2f} m above the ground as ArduCopter flies it")


def battery_flown(scratch):
    """A DJI T16-class sprayer (data/vehicles/dji_t16.toml: climbs 3 m/s, descends 1.5 m/s,
    lands its last 10 m at 0.5 m/s as ArduCopter does by default, lands with 20 % of a 600 s
    battery) sprays a field 500 m beyond a 40 m hill from its supply point, over an ESRI grid
    written here. Each sortie's `.waypoints` is timed as ArduCopter flies it: NAV_TAKEOFF
    climbs at the climb speed, each leg takes the longer of its horizontal distance at the
    last DO_CHANGE_SPEED and its climb or descent at the vehicle's vertical speeds, NAV_LAND
    flies to its place at the altitude it has and descends at 1.5 m/s to 10 m above the
    ground, then at 0.5 m/s (`LAND_ALT_LOW`, `LAND_SPEED`). Every sortie lands with its 20 %
    (decision 0034: a fifth trial found a landing charged at the climb speed eating into it),
    and the preflight's own figure per sortie agrees with this one."""
    import numpy
    from pyproj import Transformer

    columns, rows, cell = 120, 200, 5.0
    centres_x = (numpy.arange(columns) + 0.5) * cell
    centres_y = (numpy.arange(rows) + 0.5) * cell
    hill = 40.0 * numpy.exp(-(((centres_y[:, None] - 300.0) / 60.0) ** 2)) + 0.0 * centres_x[None, :]
    heights = 50.0 + hill
    folder = os.path.join(scratch, "battery")
    os.makedirs(folder)
    ground = write_grid(os.path.join(folder, "hill.asc"), heights, 0.0, 0.0, cell)
    field = {"type": "FeatureCollection", "crs": "local", "features": [{"type": "Feature", "properties": {"name": "far"},
             "geometry": {"type": "Polygon", "coordinates": [[[100, 600], [500, 600], [500, 950], [100, 950], [100, 600]]]}}]}
    with open(os.path.join(folder, "field.geojson"), "w") as handle:
        json.dump(field, handle)
    out = os.path.join(folder, "out")
    subprocess.run([AGRIPATH, "plan", "--fields", os.path.join(folder, "field.geojson"), "--terrain",
                    os.path.join(folder, "hill.asc"), "--vehicle", os.path.join(ROOT, "data/vehicles/dji_t16.toml"),
                    "--supply", "300,50", "--out", out], check=True, stdout=subprocess.DEVNULL)
    climb_mps, descent_mps, land_mps, usable_s = 3.0, 1.5, 0.5, 600.0 * 0.8
    to_utm = Transformer.from_crs("EPSG:4326", "EPSG:32652", always_xy=True)
    east0, north0 = to_utm.transform(126.63, 45.75)
    with open(os.path.join(out, "report.json")) as handle:
        ours = [sortie["flight_time_s"] for sortie in json.load(handle)["preflight"]["sorties"]]
    files = sorted(glob.glob(os.path.join(out, "sortie_*.waypoints")))
    check(len(files) == len(ours) and len(files) >= 3, f"battery: {len(files)} sorties written, {len(ours)} in the report")
    most = 0.0
    for path, reported in zip(files, ours):
        loader = mavwp.MAVWPLoader()
        loader.load(path)
        items = [loader.wp(index) for index in range(loader.count())]

        def place(item):
            east, north = to_utm.transform(item.y, item.x)
            return east - east0, north - north0

        def vertical_s(rise):
            return rise / climb_mps if rise >= 0 else -rise / descent_mps

        here = (*place(items[0]), items[0].z)
        speed, seconds = 8.0, 0.0
        for item in items[1:]:
            if item.command == 178:
                speed = item.param2
                continue
            if item.command not in (16, 21, 22):
                continue
            x, y = place(item)
            if item.command == 22:
                seconds += vertical_s(item.z - here[2])
                here = (here[0], here[1], item.z)
                continue
            altitude = here[2] if item.command == 21 else item.z
            seconds += max(math.hypot(x - here[0], y - here[1]) / speed, vertical_s(altitude - here[2]))
            here = (x, y, altitude)
            if item.command == 21:
                height = here[2] - float(ground(numpy.array([x]), numpy.array([y]))[0])
                slow = min(height, 10.0)
                seconds += (height - slow) / descent_mps + slow / land_mps
        most = max(most, seconds)
        name = os.path.basename(path)
        check(seconds <= usable_s + 0.5, f"battery {name}: flies {seconds:.1f} s of the usable {usable_s:.0f} s")
        check(abs(seconds - reported) <= 1.0 + 0.005 * seconds,
              f"battery {name}: {seconds:.1f} s as ArduCopter flies it, the preflight says {reported:.1f} s")
    # Not vacuous: the battery is what ends the sorties.
    check(most >= 0.85 * usable_s, f"battery: the longest sortie flies {most:.1f} s, the battery does not bind")
    print(f"battery: {len(files)} sorties, the longest {most:.1f} s of the usable {usable_s:.0f} s as ArduCopter flies it")


with tempfile.TemporaryDirectory() as scratch:
    demo = os.path.join(scratch, "demo")
    subprocess.run([AGRIPATH, "demo", "--out", demo], check=True, stdout=subprocess.DEVNULL)
    # No DEM: altitudes relative to the launch point (frame 3), never sea level over 0 m.
    check_folder(demo, {3})
    island_sea_level = os.path.join(scratch, "island-sea-level")
    subprocess.run([AGRIPATH, "plan", os.path.join(ROOT, "data/scenarios/christmas_island.toml"),
                    "--out", island_sea_level], check=True, stdout=subprocess.DEVNULL)
    check_folder(island_sea_level, {0})
    island = os.path.join(scratch, "island")
    subprocess.run([AGRIPATH, "plan", os.path.join(ROOT, "data/scenarios/christmas_island.toml"), "--altitude", "terrain",
                    "--out", island], check=True, stdout=subprocess.DEVNULL)
    check_folder(island, {10})
    # A pump on a servo output (DO_SET_SERVO, 183). Not on the island: a constant-flow pump
    # slowed by its climbs over the island's terraces overdoses, and that plan exits 3
    # (decision 0028). The seed 001 farm's one plateau rises 3 m over a 5 m ramp: 1.8 m/s of
    # climb at the 3 m/s spray speed, within the vehicle's 2 m/s.
    servo = os.path.join(scratch, "servo")
    subprocess.run([AGRIPATH, "plan", os.path.join(ROOT, "data/scenarios/seed001_farm.toml"),
                    "--sprayer", "servo:9:1900:1100", "--out", servo], check=True, stdout=subprocess.DEVNULL)
    check_folder(servo, {3})
    servo_items = [json.load(open(path))["mission"]["items"] for path in glob.glob(os.path.join(servo, "*.plan"))]
    check(all(any(item.get("command") == 183 for item in items) for items in servo_items) and servo_items,
          "servo: every sortie switches the pump with DO_SET_SERVO")
    # A survey vehicle: camera triggers (MAV_CMD_DO_SET_CAM_TRIGG_DIST, 206), no sprayer item.
    survey = os.path.join(scratch, "survey")
    subprocess.run([AGRIPATH, "plan", os.path.join(ROOT, "data/scenarios/christmas_island_survey.toml"),
                    "--out", survey], check=True, stdout=subprocess.DEVNULL)
    check_folder(survey, {0})
    for path in sorted(glob.glob(os.path.join(survey, "*.waypoints"))):
        loader = mavwp.MAVWPLoader()
        loader.load(path)
        commands = [loader.wp(index).command for index in range(loader.count())]
        check(mavlink.MAV_CMD_DO_SET_CAM_TRIGG_DIST == 206 and 206 in commands,
              f"{os.path.basename(path)}: camera trigger items")
        check(not {183, 216} & set(commands), f"{os.path.basename(path)}: no sprayer item in a survey")

    # A track over SPSO's real DEM: its pixel frame placed on Earth through the DEM's
    # georeferencing (GDA94 / MGA zone 48), checked against PROJ.
    track = os.path.join(scratch, "track")
    subprocess.run([AGRIPATH, "track", os.path.join(ROOT, "data/spso/scenario.json"), "--algorithm", "lattice,spso",
                    "--runs", "1", "--evaluations", "5000", "--out", track], check=True, stdout=subprocess.DEVNULL)
    check_folder(track, {0}, with_plan=False)
    from pyproj import Transformer
    to_geographic = Transformer.from_crs("EPSG:28348", "EPSG:4283", always_xy=True)
    scenario = json.load(open(os.path.join(ROOT, "data/spso/scenario.json")))
    loader = mavwp.MAVWPLoader()
    loader.load(os.path.join(track, "lattice.waypoints"))
    for index, (x, y) in [(0, scenario["start_xyz_agl"][:2]), (loader.count() - 1, scenario["goal_xyz_agl"][:2])]:
        # Pixel (x, y) from 1 at the top-left pixel; the raster's corner is (566710, 8842640).
        easting, northing = 566710 + (x - 0.5) * 5, 8842640 - (y - 0.5) * 5
        lon, lat = to_geographic.transform(easting, northing)
        item = loader.wp(index)
        check(abs(item.x - lat) < 1e-7 and abs(item.y - lon) < 1e-7,
              f"track item {index}: ({item.y}, {item.x}) vs PROJ ({lon}, {lat})")
    with open(os.path.join(track, "report.json")) as handle:
        report = json.load(handle)
    check(all(p["safe_runs"] == p["runs"] for p in report["planners"]), "every track run over the DEM is safe")

    # A cliff one cell wide, in a grid written here and flown here: every spray leg of the
    # written files, between its waypoints as the autopilot flies them, sampled every 2 cm
    # against this script's own bilinear interpolation of the grid (decision 0028: 1 m samples
    # had passed a leg 1.08 m off spray height, beyond the 1 m tolerance).
    cliff_flown(scratch)
    track_landing_flown(scratch)
    battery_flown(scratch)

print(f"missions: {passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
