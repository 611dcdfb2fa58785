//! The bad-input corpus (`data/test/bad/`): every case exits with status 2, prints exactly one
//! line naming the file (or flag) and the fault, never panics, and writes nothing.

use std::path::{Path, PathBuf};
use std::process::Command;

fn data(relative: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(relative)
        .display()
        .to_string()
}

fn bad(name: &str) -> String {
    data(&format!("test/bad/{name}"))
}

/// (arguments, the file or flag the message must name, a fragment of the fault). `special`
/// holds what git cannot: a FIFO, links to `/dev/zero`, a folder named like a file, a file
/// where a folder is wanted.
fn corpus(special: &Path) -> Vec<(Vec<String>, String, &'static str)> {
    let special_file = |name: &str| special.join(name).display().to_string();
    let fields = |name: &str| vec!["validate".to_string(), "--fields".into(), bad(name)];
    let local_fields = |name: &str| {
        vec![
            "validate".to_string(),
            "--fields".into(),
            bad(name),
            "--crs".into(),
            "local".into(),
        ]
    };
    let terrain_info = |name: &str| vec!["terrain".to_string(), "info".into(), bad(name)];
    let vehicle = |name: &str| {
        vec![
            "validate".to_string(),
            "--fields".into(),
            data("seed001_farm.geojson"),
            "--vehicle".into(),
            bad(name),
        ]
    };
    let scenario = |name: &str| vec!["validate".to_string(), bad(name)];
    let farm_with = |flags: &[&str]| {
        let mut arguments = vec![
            "validate".to_string(),
            "--fields".into(),
            data("seed001_farm.geojson"),
        ];
        arguments.extend(flags.iter().map(|flag| flag.to_string()));
        arguments
    };
    let plan = |fields_file: &str, flags: &[&str]| {
        let mut arguments = vec![
            "plan".to_string(),
            "--fields".into(),
            fields_file.to_string(),
            "--out".into(),
            "out".into(),
        ];
        arguments.extend(flags.iter().map(|flag| flag.to_string()));
        arguments
    };
    let plan_farm = |flags: &[&str]| plan(&data("seed001_farm.geojson"), flags);
    let plan_into = |out: &str| {
        vec![
            "plan".to_string(),
            "--fields".into(),
            data("seed001_farm.geojson"),
            "--out".into(),
            out.to_string(),
        ]
    };
    let terrain_of = |file: String| vec!["terrain".to_string(), "info".into(), file];
    let track_file = |name: &str| track_with(&bad(name), &[]);
    let track_special = |name: &str| track_with(&special_file(name), &[]);
    let on = |name: &str, fragment: &'static str| (fields(name), bad(name), fragment);
    let on_terrain = |name: &str, fragment: &'static str| (terrain_info(name), bad(name), fragment);
    let on_vehicle = |name: &str, fragment: &'static str| (vehicle(name), bad(name), fragment);
    let flag = |flags: &[&str], named: &str, fragment: &'static str| {
        (plan_farm(flags), named.to_string(), fragment)
    };
    let mut cases: Vec<(Vec<String>, String, &'static str)> = vec![
        // Special files: refused before they are opened or read past the budget.
        (fields("nowhere.kml"), bad("nowhere.kml"), "no such file"),
        (
            vec![
                "validate".into(),
                "--fields".into(),
                special_file("fifo.geojson"),
            ],
            special_file("fifo.geojson"),
            "FIFO",
        ),
        (
            vec![
                "validate".into(),
                "--fields".into(),
                special_file("zero.geojson"),
            ],
            special_file("zero.geojson"),
            "a device, not a regular file",
        ),
        (
            vec![
                "validate".into(),
                "--fields".into(),
                special_file("zero.kml"),
            ],
            special_file("zero.kml"),
            "a device",
        ),
        (
            vec![
                "validate".into(),
                "--fields".into(),
                special_file("zero.kmz"),
            ],
            special_file("zero.kmz"),
            "a device",
        ),
        (
            vec![
                "validate".into(),
                "--fields".into(),
                special_file("folder.geojson"),
            ],
            special_file("folder.geojson"),
            "a folder, not a file",
        ),
        (
            terrain_of(special_file("zero.asc")),
            special_file("zero.asc"),
            "a device",
        ),
        (
            terrain_of(special_file("zero.tif")),
            special_file("zero.tif"),
            "a device",
        ),
        (
            terrain_of(special_file("fifo.xyz")),
            special_file("fifo.xyz"),
            "FIFO",
        ),
        (
            vec![
                "validate".into(),
                "--fields".into(),
                data("seed001_farm.geojson"),
                "--vehicle".into(),
                special_file("zero.toml"),
            ],
            special_file("zero.toml"),
            "a device",
        ),
        (
            vec!["validate".into(), special_file("fifo.toml")],
            special_file("fifo.toml"),
            "FIFO",
        ),
        (
            track_special("zero.json"),
            special_file("zero.json"),
            "a device",
        ),
        (
            track_special("fifo.json"),
            special_file("fifo.json"),
            "FIFO",
        ),
        // --out that cannot be a plan folder: refused before any work or move.
        (
            plan_into(&special_file("notes.txt")),
            "--out".into(),
            "notes.txt is a file, not a folder",
        ),
        (
            plan_into(&format!("{}/plan", special_file("notes.txt"))),
            "--out".into(),
            "notes.txt is a file, not a folder",
        ),
        (
            vec!["demo".into(), "--out".into(), special_file("notes.txt")],
            "--out".into(),
            "is a file, not a folder",
        ),
        (
            vec![
                "track".into(),
                data("seed000_orchard.json"),
                "--out".into(),
                special_file("notes.txt"),
            ],
            "--out".into(),
            "is a file, not a folder",
        ),
        (
            plan_into(&special_file("folder_link")),
            "--out".into(),
            "is a symbolic link: give --out the folder itself",
        ),
        (
            plan_into("."),
            "--out".into(),
            "does not name a folder of its own",
        ),
        (
            plan(&bad("thin.geojson"), &[]),
            bad("thin.geojson"),
            "field 'thin' is narrower than one swath (5 m)",
        ),
        (
            // `validate` refuses what `plan` would (it said `valid`: the eleventh trial).
            vec!["validate".to_string(), "--fields".into(), bad("thin.geojson")],
            bad("thin.geojson"),
            "field 'thin' is narrower than one swath (5 m)",
        ),
        flag(
            &["--terrain", "flat:9001"],
            "--terrain",
            "the height must lie within -500..=9000 m",
        ),
        // Terrain: placement, no data, undeclared no-data values, sparse clouds.
        on_terrain("nan_tiepoint.tif", "placement is not finite"),
        on_terrain("all_nodata.tif", "every cell of the raster is no-data"),
        on_terrain("huge_height.tif", "3.4028234663852886e38 m is invalid"),
        on_terrain(
            "undeclared_nodata.asc",
            "-32767 m is invalid: terrain lies within -500..=9000 m",
        ),
        on_terrain("all_nodata.asc", "every cell of the raster is no-data"),
        on_terrain("sparse.xyz", "too sparse for a terrain model"),
        // Heights that would be misread (decision 0037): a mask, a unit not known; a `.prj`
        // naming a frame not read, named as the faulty file.
        (
            vec![
                "terrain".into(),
                "info".into(),
                data("test/geotiff/float32_internal_mask.tif"),
            ],
            data("test/geotiff/float32_internal_mask.tif"),
            "it carries a GDAL mask of no-data cells",
        ),
        (
            vec![
                "terrain".into(),
                "info".into(),
                data("test/geotiff/float32_unittype_furlong.tif"),
            ],
            data("test/geotiff/float32_unittype_furlong.tif"),
            "the heights' unit is 'furlong'",
        ),
        (
            terrain_info("lambert.asc"),
            bad("lambert.prj"),
            "lambert.asc is 'RGF93_Lambert_93'",
        ),
        (
            vec![
                "terrain".into(),
                "info".into(),
                data("test/bad/short_line.xyz"),
                "--cell".into(),
                "-1".into(),
            ],
            "arguments".into(),
            "--cell = -1 is invalid",
        ),
        (
            plan_farm(&["--terrain", &bad("huge_height.tif")]),
            bad("huge_height.tif"),
            "an undeclared no-data value?",
        ),
        // Where fields are on Earth, and how they relate.
        on("polar.geojson", "polar region"),
        on("wide_polar.geojson", "spans 7.00° of longitude"),
        on(
            "overlap.geojson",
            "fields 'north' and 'south' overlap by 2000.0 m²",
        ),
        on(
            "duplicate_field.geojson",
            "fields 'A' and 'A again' overlap by 10000.0 m²",
        ),
        on("overlap.kml", "overlap by"),
        on("holes_only.kml", "holes) but no outerBoundaryIs ring"),
        on("polar.kml", "polar region"),
        (
            plan(&bad("covered_by_obstacle.geojson"), &[]),
            bad("covered_by_obstacle.geojson"),
            "field 'wood' has 0.00 m² left to spray",
        ),
        // Decision 0028: a DEM with no data between two fields names the DEM, not the fields.
        (
            plan(
                &data("seed001_farm.geojson"),
                &["--terrain", &bad("gap_between_fields.asc")],
            ),
            bad("gap_between_fields.asc"),
            "which the flight crosses (a transfer, a return to the supply point or a transit between fields)",
        ),
        // A supply point off the DEM names the flag, not a file.
        (
            plan(
                &data("seed001_farm.geojson"),
                &[
                    "--terrain",
                    &bad("gap_between_fields.asc"),
                    "--supply",
                    "750,200",
                ],
            ),
            "--supply/--start".into(),
            "the terrain has no height there (the terrain model covers (-100.0, -350.0) to (700.0, 250.0))",
        ),
        (
            plan(&bad("speck.geojson"), &[]),
            bad("speck.geojson"),
            "field 'speck' is 1.00 m², smaller than one swath square",
        ),
        (
            plan(&bad("huge_area.geojson"), &[]),
            bad("huge_area.geojson"),
            "the fields cover 14400 ha (limit 10000 ha",
        ),
        (
            plan(&bad("many_swaths.geojson"), &["--swath-width", "0.5"]),
            bad("many_swaths.geojson"),
            "about 14142 swaths of 0.5 m (limit 10000",
        ),
        (
            vec!["validate".into(), bad("scenario_overlapping_fields.toml")],
            bad("overlap.geojson"),
            "overlap by",
        ),
        // GeoJSON structure.
        on("nan_string_coordinate.geojson", "not a number"),
        on("null_geometry.geojson", "no field polygons found"),
        on("empty_collection.geojson", "no field polygons"),
        on("number_root.geojson", "the top level is not a JSON object"),
        on("deep_nesting.geojson", "recursion limit"),
        on(
            "multipolygon_bad_part.geojson",
            "boundary intersects itself",
        ),
        on("point_only.geojson", "no field polygons"),
        (
            plan(&bad("two_launches.geojson"), &[]),
            bad("two_launches.geojson"),
            "2 launch points ('one', 'two')",
        ),
        // KML and KMZ.
        on(
            "wrong_namespace.kml",
            "namespace 'http://example.com/not-kml'",
        ),
        on("entities.kml", "declares entities"),
        on("unknown_entity.kml", "unknown entity '&nbsp;'"),
        on("deep.kml", "nested deeper than 256"),
        on(
            "nan_coordinate.kml",
            "Placemark 1 (A): coordinate is not a finite number",
        ),
        on("latitude_out_of_range.kml", "out of range"),
        on("empty_coordinates.kml", "no field polygons found"),
        on(
            "wrong_namespace.kmz",
            "namespace 'http://example.com/not-kml'",
        ),
        on("bomb.kmz", "inflates to 629145600 bytes"),
        // Vehicles.
        on_vehicle("vehicle_zero_speed.toml", "spray_speed_mps = 0 is invalid"),
        on_vehicle(
            "vehicle_huge_battery.toml",
            "battery_endurance_s = 1e9 is invalid",
        ),
        on_vehicle("vehicle_tiny_tank.toml", "tank_l = 1e-4 is invalid"),
        on_vehicle(
            "vehicle_negative_swap.toml",
            "battery_swap_s = -1 is invalid",
        ),
        on_vehicle(
            "vehicle_huge_swath.toml",
            "swath_width_m = 1e308 is invalid",
        ),
        on_vehicle(
            "vehicle_fast_climb.toml",
            "climb_speed_mps = 500 is invalid",
        ),
        on_vehicle("vehicle_huge_rate.toml", "application_rate_l_per_ha"),
        on_vehicle(
            "vehicle_reserve_95.toml",
            "battery_reserve_percent = 95 is invalid",
        ),
        // Scenario files.
        (
            vec!["validate".into(), bad("scenario_overlap_type.toml")],
            bad("scenario_overlap_type.toml"),
            "scenario_overlap_type.toml:2:17: not valid TOML: invalid type: string \"yes\", expected a boolean",
        ),
        (
            vec!["validate".into(), bad("scenario_missing_vehicle.toml")],
            data("test/bad/nowhere.toml"),
            "no such file",
        ),
        // Planning flags.
        flag(&["--ants", "0"], "--ants", "must be 1..=100000"),
        flag(&["--batches", "0"], "--batches", "must be 1..=100000"),
        flag(
            &["--sprayer", "servo:99:1500:1000"],
            "--sprayer",
            "servo channel 99",
        ),
        flag(
            &["--sprayer", "servo:9:1:1"],
            "--sprayer",
            "pulse width 1 µs",
        ),
        flag(
            &["--sprayer", "servo:9:1500:1500"],
            "--sprayer",
            "would never switch",
        ),
        flag(
            &["--sprayer", "pump"],
            "--sprayer",
            "expected do-sprayer or servo",
        ),
        flag(
            &["--start", "1e9,1e9"],
            "--start",
            "km from the fields",
        ),
        flag(
            &["--start", "1,2,3"],
            "--start",
            "expected two finite numbers",
        ),
        flag(
            &["--start", "nan,1"],
            "--start",
            "expected two finite numbers",
        ),
        flag(
            &["--heading", "north"],
            "--heading",
            "expected dose, auto, swaths, length",
        ),
        flag(
            &["--heading", "inf"],
            "--heading",
            "expected dose, auto, swaths, length",
        ),
        flag(&["--weights", "1"], "--weights", "expected two weights"),
        flag(&["--weights", "a,b"], "arguments", "invalid value 'a'"),
        flag(&["--weights", "0,0"], "arguments", "not both 0"),
        flag(
            &["--headland", "100000"],
            "arguments",
            "at most 20 edge passes",
        ),
        flag(&["--headland", "-1"], "arguments", "-1"),
        flag(
            &["--drape-spacing", "0"],
            "arguments",
            "must be a number above 0",
        ),
        flag(
            &["--drape-spacing", "nan"],
            "arguments",
            "must be a number above 0",
        ),
        flag(
            &["--drape-spacing", "0.001"],
            "arguments",
            "drape spacing (a) = 0.001 is invalid: lies in 0.5..=1000 m",
        ),
        flag(
            &["--drape-spacing", "5000"],
            "arguments",
            "lies in 0.5..=1000 m",
        ),
        flag(
            &["--boundary-margin", "-1"],
            "arguments",
            "must be 0 or more",
        ),
        flag(
            &["--obstacle-margin", "nan"],
            "arguments",
            "must be 0 or more",
        ),
        flag(
            &["--boundary-margin", "1e9"],
            &data("seed001_farm.geojson"),
            "left to spray",
        ),
        flag(
            &["--sequencer", "nope"],
            "arguments",
            "possible values: best, greedy, aco",
        ),
        flag(
            &["--sorties", "bogus"],
            "arguments",
            "possible values: joint, exact, gsa",
        ),
        flag(
            &["--altitude", "sea-level"],
            "--altitude",
            "need a terrain model",
        ),
        flag(&["--altitude", "moon"], "arguments", "moon"),
        flag(
            &["--terrain-tolerance", "-1"],
            "arguments",
            "must be a finite number above 0",
        ),
        flag(&["--origin", "1"], "arguments", "expected LON,LAT"),
        flag(
            &["--seed", "abc"],
            "arguments",
            "invalid value 'abc' for '--seed",
        ),
        flag(&["--seed", "-1"], "arguments", "-1"),
        flag(
            &["--swath-width", "201"],
            "--swath-width",
            "lies in 0.5..=200",
        ),
        flag(
            &["--swath-width", "inf"],
            "--swath-width",
            "must be a finite number above 0",
        ),
        flag(
            &["--spray-height", "-1"],
            "--spray-height",
            "must be a finite number, 0 or more",
        ),
        flag(
            &["--safe-height", "nan"],
            "--safe-height",
            "must be a finite number, 0 or more",
        ),
        flag(
            &["--spray-height", "501"],
            "--spray-height",
            "lies in 1..=500",
        ),
        // A sprayer at 0 m is in the crop (the red team's case: it flew below the ground).
        flag(&["--spray-height", "0"], "--spray-height", "lies in 1..=500"),
        // A tolerance that would let the spray legs sink into the ground.
        flag(
            &["--terrain-tolerance", "5"],
            "arguments",
            "sink to -3.00 m above the ground; at most 1.5 m keeps 0.5 m of clearance",
        ),
        flag(&["--crs", "utm"], "arguments", "utm"),
        flag(
            &["--frobnicate"],
            "arguments",
            "unexpected argument '--frobnicate'",
        ),
        // Track scenarios.
        (
            track_file("track_start_is_goal.json"),
            bad("track_start_is_goal.json"),
            "start and goal",
        ),
        (
            track_file("track_too_many_threats.json"),
            bad("track_too_many_threats.json"),
            "threat cylinders = 1001 is invalid: at most 1000",
        ),
        (
            track_file("track_infinite_goal.json"),
            bad("track_infinite_goal.json"),
            "number out of range",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--evaluations", "0"]),
            "--evaluations".into(),
            "--evaluations = 0 is invalid: must be at least 1",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--vehicle-radius", "nan"]),
            "--vehicle-radius".into(),
            "--vehicle-radius = NaN is invalid: must be 0..=1000 metres",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--min-clearance=-1"]),
            "--min-clearance".into(),
            "--min-clearance = -1 is invalid: must be 0.5..=1000 metres",
        ),
        // `plan`'s floor holds for tracks too: at 0 a track flew 0.29 m above the ground
        // (decision 0030).
        (
            track_with(&data("seed000_orchard.json"), &["--min-clearance", "0"]),
            "--min-clearance".into(),
            "--min-clearance = 0 is invalid: must be 0.5..=1000 metres",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--seed", "x"]),
            "arguments".into(),
            "invalid value 'x' for '--seed",
        ),
        // Commands and their own arguments.
        (
            vec!["fly".into()],
            "arguments".into(),
            "unrecognized subcommand 'fly'",
        ),
        (vec!["plan".into()], "arguments".into(), "--out"),
        (
            vec!["view".into(), bad("empty.geojson")],
            bad("empty.geojson"),
            "no plan.html here",
        ),
        (
            vec!["view".into(), data("test"), "--port".into(), "70000".into()],
            "arguments".into(),
            "70000",
        ),
        (
            vec!["check".into(), data("test/bad")],
            data("test/bad"),
            "report.json: cannot read",
        ),
        (
            vec![
                "terrain".into(),
                "sample".into(),
                data("test/grid_small.asc"),
                "1".into(),
            ],
            "arguments".into(),
            "2 values required",
        ),
        (
            vec![
                "terrain".into(),
                "hillshade".into(),
                "flat".into(),
                "--out".into(),
                "out.png".into(),
                "--size".into(),
                "0".into(),
            ],
            "--size".into(),
            "must be 2..16384 pixels",
        ),
        (
            vec![
                "terrain".into(),
                "hillshade".into(),
                "flat".into(),
                "--out".into(),
                "out.png".into(),
                "--size".into(),
                "100000000".into(),
            ],
            "--size".into(),
            "must be 2..16384 pixels",
        ),
        (
            vec![
                "grid".into(),
                data("seed001_farm.geojson"),
                "--field".into(),
                "nope".into(),
                "--out".into(),
                "out".into(),
            ],
            data("seed001_farm.geojson"),
            "no field named 'nope'",
        ),
        (
            vec![
                "grid".into(),
                data("seed001_farm.geojson"),
                "--field".into(),
                "S1".into(),
                "--swath-width".into(),
                "0.001".into(),
                "--out".into(),
                "out".into(),
            ],
            "--swath-width".into(),
            "swath width = 0.001 is invalid: a grid cell (the swath width) lies in 0.5..=200 m",
        ),
        (
            vec![
                "grid".into(),
                data("seed001_farm.geojson"),
                "--field".into(),
                "S1".into(),
                "--swath-width".into(),
                "0.5".into(),
                "--out".into(),
                "out".into(),
            ],
            data("seed001_farm.geojson"),
            "path points (grid coverage is for fields up to 40,000 points)",
        ),
        (
            vec!["repro".into(), "seed000-table9".into()],
            "arguments".into(),
            "seed000-table9",
        ),
        (
            vec![
                "repro".into(),
                "seed001-table7".into(),
                "--runs".into(),
                "5".into(),
            ],
            "--runs".into(),
            "no runs to count",
        ),
    ];
    cases.extend(vec![
        (fields("empty.geojson"), bad("empty.geojson"), "empty"),
        (
            fields("whitespace.geojson"),
            bad("whitespace.geojson"),
            "empty",
        ),
        (
            fields("truncated.geojson"),
            bad("truncated.geojson"),
            "not valid JSON",
        ),
        (fields("binary.geojson"), bad("binary.geojson"), "not UTF-8"),
        (
            fields("wrong_type.geojson"),
            bad("wrong_type.geojson"),
            "not an array",
        ),
        (
            fields("string_number.geojson"),
            bad("string_number.geojson"),
            "not a number",
        ),
        (
            fields("self_intersecting.geojson"),
            bad("self_intersecting.geojson"),
            "feature 1 (bowtie): boundary intersects itself near (5.000, 5.000)",
        ),
        (
            // Lon/lat input: the place is given in lon/lat, not in the UTM metres checked.
            fields("self_intersecting_lonlat.geojson"),
            bad("self_intersecting_lonlat.geojson"),
            "feature 1 (bowtie): boundary intersects itself near lon 105.625000, lat -10.485000",
        ),
        (
            fields("hole_outside.geojson"),
            bad("hole_outside.geojson"),
            "hole 1 lies outside",
        ),
        (
            fields("hole_crossing.geojson"),
            bad("hole_crossing.geojson"),
            "hole 1 touches or crosses the outer boundary",
        ),
        (
            // Lon/lat input: the place where holes touch in lon/lat too (the eleventh trial
            // was given UTM metres here, lon/lat everywhere else).
            fields("holes_touch_lonlat.geojson"),
            bad("holes_touch_lonlat.geojson"),
            "holes 1 and 2 touch along their edges near lon 105.6",
        ),
        (
            // Latitude first: the pair swapped is a place, and the message says so.
            fields("latlon_swapped.geojson"),
            bad("latlon_swapped.geojson"),
            "are longitude and latitude swapped?",
        ),
        (
            // A boundary walked as a track: what was skipped is named, not only "no field".
            fields("walked_track.kml"),
            bad("walked_track.kml"),
            "no field polygons found; skipped Placemark 1 (Boundary walk): a LineString is not planned",
        ),
        (
            fields("holes_overlap.geojson"),
            bad("holes_overlap.geojson"),
            "overlap",
        ),
        (
            fields("lonlat_out_of_range.geojson"),
            bad("lonlat_out_of_range.geojson"),
            "out of range",
        ),
        (
            fields("linestring.geojson"),
            bad("linestring.geojson"),
            "'LineString' cannot be a field",
        ),
        (
            fields("unclosed.geojson"),
            bad("unclosed.geojson"),
            "unclosed.geojson: feature 1 (North): ring is not closed",
        ),
        (
            fields("degenerate.geojson"),
            bad("degenerate.geojson"),
            "fewer than 3 distinct points",
        ),
        (
            fields("collinear.geojson"),
            bad("collinear.geojson"),
            "zero area",
        ),
        (
            fields("infinite.geojson"),
            bad("infinite.geojson"),
            "number out of range",
        ),
        (
            fields("unknown_kind.geojson"),
            bad("unknown_kind.geojson"),
            "kind is 'pond'",
        ),
        (
            fields("no_fields.geojson"),
            bad("no_fields.geojson"),
            "no field polygons",
        ),
        (
            fields("too_wide.geojson"),
            bad("too_wide.geojson"),
            "span 300 km",
        ),
        // Local metres 300 km from their origin: a projected grid read as local (trial 7).
        (
            fields("local_far.geojson"),
            bad("local_far.geojson"),
            "within ±100 km",
        ),
        (
            fields("farm_too_spread.geojson"),
            bad("farm_too_spread.geojson"),
            "limit 200 km",
        ),
        (
            fields("bad_crs.geojson"),
            bad("bad_crs.geojson"),
            "EPSG:3857",
        ),
        (
            fields("fields.shp"),
            bad("fields.shp"),
            "unsupported file type 'shp' for fields (expected .geojson",
        ),
        (
            fields("does_not_exist.geojson"),
            bad("does_not_exist.geojson"),
            "no such file",
        ),
        (fields("truncated.kml"), bad("truncated.kml"), "truncated"),
        (
            fields("not_kml.kml"),
            bad("not_kml.kml"),
            "not a KML document",
        ),
        (
            fields("bad_coordinates.kml"),
            bad("bad_coordinates.kml"),
            "'a,b' is not 'lon,lat[,alt]'",
        ),
        (
            fields("mismatched.kml"),
            bad("mismatched.kml"),
            "not valid KML",
        ),
        (
            fields("not_zip.kmz"),
            bad("not_zip.kmz"),
            "not a KMZ (zip) archive",
        ),
        (
            fields("no_kml_inside.kmz"),
            bad("no_kml_inside.kmz"),
            "holds no .kml",
        ),
        (
            local_fields("local_too_big.geojson"),
            bad("local_too_big.geojson"),
            "is this lon/lat?",
        ),
        (
            local_fields("degrees_as_local.geojson"),
            bad("degrees_as_local.geojson"),
            "look like longitude and latitude",
        ),
        (
            terrain_info("truncated.asc"),
            bad("truncated.asc"),
            "truncated",
        ),
        (
            terrain_info("nan.asc"),
            bad("nan.asc"),
            "row 1, column 2: height 'nan' is not a finite number",
        ),
        (
            terrain_info("no_cellsize.asc"),
            bad("no_cellsize.asc"),
            "no 'cellsize'",
        ),
        (
            terrain_info("text.tif"),
            bad("text.tif"),
            "not a readable GeoTIFF",
        ),
        (
            terrain_info("truncated.tif"),
            bad("truncated.tif"),
            "not a readable GeoTIFF",
        ),
        (
            terrain_info("short_line.xyz"),
            bad("short_line.xyz"),
            "line 3: expected 'x y z'",
        ),
        (
            terrain_info("collinear.xyz"),
            bad("collinear.xyz"),
            "span no area",
        ),
        (
            vec![
                "terrain".into(),
                "info".into(),
                data("test/geotiff/rotated.tif"),
            ],
            data("test/geotiff/rotated.tif"),
            "rotated",
        ),
        (
            vehicle("vehicle_negative_swath.toml"),
            bad("vehicle_negative_swath.toml"),
            "swath_width_m = -5 is invalid",
        ),
        (
            vehicle("vehicle_unknown_key.toml"),
            bad("vehicle_unknown_key.toml"),
            "vehicle_unknown_key.toml:1:1: unknown key `swath_widht_m` (did you mean `swath_width_m`?); the keys are name, swath_width_m,",
        ),
        (
            vehicle("vehicle_nan.toml"),
            bad("vehicle_nan.toml"),
            "spray_speed_mps = NaN",
        ),
        (
            vehicle("vehicle_wrong_type.toml"),
            bad("vehicle_wrong_type.toml"),
            "vehicle_wrong_type.toml:1:17: not valid TOML: invalid type",
        ),
        (
            vehicle("vehicle_tank_without_rate.toml"),
            bad("vehicle_tank_without_rate.toml"),
            "go together",
        ),
        (
            // The automatic supply point finds no place; the fault is the battery's.
            plan_farm(&["--vehicle", &bad("vehicle_tiny_battery.toml")]),
            bad("vehicle_tiny_battery.toml"),
            "battery_endurance_s = 30, too little for this farm",
        ),
        (
            vehicle("vehicle_two_tanks.toml"),
            bad("vehicle_two_tanks.toml"),
            "tank_l and tank_spray_time_s both give the tank",
        ),
        (
            scenario("scenario_syntax.toml"),
            bad("scenario_syntax.toml"),
            "not valid TOML",
        ),
        (
            scenario("scenario_missing_fields.toml"),
            data("test/bad/does_not_exist.geojson"),
            "no such file",
        ),
        (
            scenario("scenario_unknown_key.toml"),
            bad("scenario_unknown_key.toml"),
            "unknown key `speed`",
        ),
        (
            scenario("scenario_bad_terrain.toml"),
            bad("scenario_bad_terrain.toml"),
            "unknown variant `volcano`",
        ),
        (
            scenario("scenario_dem_not_covering.toml"),
            data("test/bad/../geotiff/float32_strips_none.tif"),
            "field 'S1': the terrain model does not cover the field",
        ),
        (
            scenario("scenario_lonlat_fields_dem_without_crs.toml"),
            data("test/bad/../grid_small.asc"),
            "does not cover the field",
        ),
        (
            farm_with(&["--swath-width", "0"]),
            "--swath-width".into(),
            "swath_width_m = 0 is invalid",
        ),
        (
            farm_with(&["--safe-height", "1e308"]),
            "--safe-height".into(),
            "safe_height_m = 1e308 is invalid: a vehicle's safe_height_m lies in 0..=500",
        ),
        (
            farm_with(&["--spray-height", "1e308"]),
            "--spray-height".into(),
            "spray_height_m = 1e308 is invalid",
        ),
        (
            farm_with(&["--swath-width", "0.001"]),
            "--swath-width".into(),
            "lies in 0.5..=200",
        ),
        (
            farm_with(&["--swath-width", "-5"]),
            "--swath-width".into(),
            "must be a finite number above 0",
        ),
        (
            farm_with(&["--swath-width", "NaN"]),
            "--swath-width".into(),
            "NaN",
        ),
        (
            farm_with(&["--spray-height", "inf"]),
            "--spray-height".into(),
            "inf",
        ),
        (
            farm_with(&["--terrain", "flat:abc"]),
            "--terrain".into(),
            "flat:HEIGHT needs a number",
        ),
        (
            farm_with(&["--terrain", "seed000"]),
            "seed001_farm.geojson".into(),
            "outside the terrain model",
        ),
        (
            vec![
                "terrain".into(),
                "sample".into(),
                data("test/grid_small.asc"),
                "0".into(),
                "0".into(),
            ],
            data("test/grid_small.asc"),
            "outside the terrain model",
        ),
        (
            vec![
                "terrain".into(),
                "hillshade".into(),
                "flat".into(),
                "--out".into(),
                "never.png".into(),
            ],
            "flat".into(),
            "unbounded",
        ),
        (
            bench_with(&["--runs", "1", "--dim", "5", "--algorithms", "pso,nope"]),
            "--algorithms".into(),
            "unknown algorithm 'nope'",
        ),
        (
            bench_with(&["--runs", "1", "--functions", "f3", "--dim", "20"]),
            "--dim".into(),
            "10, 30, 50 (the dimensions with a published rotation matrix)",
        ),
        (
            bench_with(&["--runs", "1", "--functions", "f7", "--dim", "1"]),
            "--dim".into(),
            "2 or more",
        ),
        (
            bench_with(&["--runs", "0", "--dim", "5"]),
            "--runs".into(),
            "needs at least 1",
        ),
        (
            bench_with(&["--runs", "1", "--dim", "5", "--functions", "f10"]),
            "--functions".into(),
            "unknown function",
        ),
        (
            track_with(
                &data("seed000_orchard.json"),
                &["--algorithm", "lattice,nope"],
            ),
            "--algorithm".into(),
            "unknown planner 'nope'",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--task", "IV"]),
            data("seed000_orchard.json"),
            "the scenario has tasks I, II, III",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--encoding", "polar"]),
            "--encoding".into(),
            "cartesian, cylindrical or spherical",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--runs", "0"]),
            "--runs".into(),
            "1..=1000",
        ),
        (
            bench_with(&["--runs", "1", "--dim", "5", "--functions", "f1,"]),
            "--functions".into(),
            "an empty name in the list",
        ),
        (
            bench_with(&["--runs", "1", "--dim", "5", "--algorithms", "pso,PSO"]),
            "--algorithms".into(),
            "named twice",
        ),
        (
            vec![
                "bench".into(),
                "functions".into(),
                "--runs".into(),
                "1".into(),
                "--pop".into(),
                "1000000000".into(),
                "--iters".into(),
                "2".into(),
            ],
            "--pop × --dim".into(),
            "numbers in a population",
        ),
        (
            vec![
                "bench".into(),
                "functions".into(),
                "--iters".into(),
                "-5".into(),
            ],
            "--iters".into(),
            "invalid value '-5'",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--algorithm", "lattice,ours"]),
            "--algorithm".into(),
            "the same as 'lattice' before it",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--min-clearance", "0.2"]),
            "--min-clearance".into(),
            "0.5..=1000",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--encoding", "spherical"]),
            "--encoding".into(),
            "takes an encoding",
        ),
        (
            track_with(&data("tracks/christmas_island_track.toml"), &["--task", "II"]),
            "--task".into(),
            "no tasks",
        ),
        (
            track_with(&data("seed001_farm.geojson"), &[]),
            data("seed001_farm.geojson"),
            "not a track scenario",
        ),
        (
            track_with(&bad("track_negative_radius.json"), &[]),
            bad("track_negative_radius.json"),
            "positive radius",
        ),
        (
            track_with(&bad("track_start_outside.json"), &[]),
            bad("track_start_outside.json"),
            "outside the planning area",
        ),
        (
            track_with(&bad("track_start_in_threat.json"), &[]),
            bad("track_start_in_threat.json"),
            "start = (505, 500) is invalid: inside threat cylinder 1",
        ),
        (
            track_with(&bad("track_goal_under_terrain.json"), &[]),
            bad("track_goal_under_terrain.json"),
            "m under the terrain",
        ),
        (
            track_with(&bad("track_unknown_key.json"), &[]),
            bad("track_unknown_key.json"),
            "unknown key 'terrain.hils'",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--min-clearance", "5000"]),
            "--min-clearance".into(),
            "0.5..=1000",
        ),
        (
            track_with(&bad("track_spso_missing_dem.json"), &[]),
            bad("missing.tif"),
            "cannot read",
        ),
        (
            track_with(&bad("track_outside_dem.toml"), &[]),
            bad("track_outside_dem.toml"),
            "does not cover",
        ),
        (
            track_with(&bad("track_bad_band.toml"), &[]),
            bad("track_bad_band.toml"),
            "lower < upper",
        ),
        (
            track_with(&bad("empty.geojson"), &[]),
            bad("empty.geojson"),
            "empty",
        ),
    ]);
    cases
}

/// `track` with a tiny budget, writing to `out` (which must never appear).
fn track_with(scenario: &str, extra: &[&str]) -> Vec<String> {
    let mut arguments: Vec<String> = vec!["track".into(), scenario.into()];
    if !extra.contains(&"--runs") {
        arguments.extend(["--runs".to_string(), "1".into()]);
    }
    if !extra.contains(&"--evaluations") {
        arguments.extend(["--evaluations".to_string(), "200".into()]);
    }
    arguments.extend(["--out".to_string(), "out".into()]);
    arguments.extend(extra.iter().map(|s| s.to_string()));
    arguments
}

/// `bench functions` with a tiny budget and extra arguments.
fn bench_with(extra: &[&str]) -> Vec<String> {
    let mut arguments: Vec<String> = ["bench", "functions", "--pop", "4", "--iters", "2"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    arguments.extend(extra.iter().map(|s| s.to_string()));
    arguments
}

/// Makes what the corpus needs and git cannot hold (Unix only: FIFOs and device links).
fn special_files(folder: &Path) {
    std::fs::create_dir_all(folder.join("folder.geojson")).unwrap();
    std::fs::write(folder.join("notes.txt"), "the operator's notes").unwrap();
    // A link to a folder holding a file that must survive `--out LINK`.
    std::fs::create_dir_all(folder.join("precious")).unwrap();
    std::fs::write(folder.join("precious/keep.txt"), "keep").unwrap();
    std::os::unix::fs::symlink(folder.join("precious"), folder.join("folder_link")).unwrap();
    for name in [
        "zero.geojson",
        "zero.kml",
        "zero.kmz",
        "zero.asc",
        "zero.tif",
        "zero.toml",
        "zero.json",
    ] {
        std::os::unix::fs::symlink("/dev/zero", folder.join(name)).unwrap();
    }
    for name in ["fifo.geojson", "fifo.xyz", "fifo.toml", "fifo.json"] {
        let made = Command::new("mkfifo")
            .arg(folder.join(name))
            .status()
            .unwrap();
        assert!(made.success(), "mkfifo {name}");
    }
}

/// Largest resident set of any child process waited for so far, bytes.
#[allow(unsafe_code)]
fn children_peak_rss_bytes() -> u64 {
    // SAFETY: getrusage only writes the struct it is given.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let result = unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut usage) };
    assert_eq!(result, 0);
    u64::try_from(usage.ru_maxrss).unwrap_or(0) * 1024
}

/// Each case's budget: a hostile input is refused at once, not after work proportional to
/// its claims. Time is checked loosely here (debug builds on loaded machines); the figures
/// the issue asks for (≤ 2 s, ≤ 200 MB) come from the release run recorded in
/// docs/benchmarks.md.
const CASE_MEMORY_BYTES: u64 = 200 * 1024 * 1024;
const CASE_SECONDS_LOOSE: f64 = 20.0;

#[test]
fn every_bad_input_exits_2_with_one_line_naming_the_file_and_writes_nothing() {
    let workdir = std::env::temp_dir().join(format!("agripath-bad-input-{}", std::process::id()));
    let special = std::env::temp_dir().join(format!("agripath-bad-special-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&special);
    std::fs::create_dir_all(&workdir).unwrap();
    std::fs::create_dir_all(&special).unwrap();
    special_files(&special);
    let cases = corpus(&special);
    assert!(cases.len() >= 150, "the corpus has {} cases", cases.len());
    let mut failures = Vec::new();
    let (mut slowest, mut slowest_case) = (0.0f64, String::new());
    let mut peak_before = children_peak_rss_bytes();
    let mut heaviest_case = String::new();
    for (arguments, file, fragment) in &cases {
        let started = std::time::Instant::now();
        let output = Command::new(env!("CARGO_BIN_EXE_agripath"))
            .args(arguments)
            .current_dir(&workdir)
            .stdin(std::process::Stdio::null())
            .output()
            .unwrap();
        let seconds = started.elapsed().as_secs_f64();
        let peak = children_peak_rss_bytes();
        if peak > peak_before {
            heaviest_case = format!("{arguments:?}");
            peak_before = peak;
        }
        if seconds > slowest {
            slowest = seconds;
            slowest_case = format!("{arguments:?}");
        }
        let stderr = String::from_utf8_lossy(&output.stderr);
        let ok = output.status.code() == Some(2)
            && stderr.lines().count() == 1
            && stderr.starts_with("agripath: error: ")
            && stderr.contains(file.as_str())
            && stderr.contains(fragment)
            && !stderr.contains("panicked")
            && seconds <= CASE_SECONDS_LOOSE;
        if !ok {
            failures.push(format!(
                "{arguments:?}\n  status {:?} after {seconds:.1} s, expected to name {file} and say '{fragment}'\n  stderr: {stderr}",
                output.status.code()
            ));
        }
    }
    println!(
        "{} cases; slowest {slowest:.2} s ({slowest_case}); peak RSS {:.0} MB ({heaviest_case})",
        cases.len(),
        peak_before as f64 / 1e6
    );
    let left: Vec<PathBuf> = std::fs::read_dir(&workdir)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .collect();
    let special_left: Vec<String> = std::fs::read_dir(&special)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    let kept = special.join("precious/keep.txt").is_file();
    std::fs::remove_dir_all(&workdir).unwrap();
    std::fs::remove_dir_all(&special).unwrap();
    assert!(kept, "--out through a link emptied the folder it points to");
    assert!(
        failures.is_empty(),
        "{} of {} cases failed:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
    assert!(left.is_empty(), "bad input left files behind: {left:?}");
    assert_eq!(
        special_left.len(),
        15,
        "the special files were changed: {special_left:?}"
    );
    assert!(
        peak_before <= CASE_MEMORY_BYTES,
        "a case took {:.0} MB: {heaviest_case}",
        peak_before as f64 / 1e6
    );
}
