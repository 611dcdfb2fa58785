//! Sizes past which planning would not finish in bounded time or memory; inputs beyond them
//! are refused up front with a clear message (see `docs/limits.md`).

/// Fields (and obstacles) in one file.
pub const MAX_POLYGONS: usize = 20_000;
/// Vertices over all rings of one file.
pub const MAX_VERTICES: usize = 2_000_000;
/// Largest side of a farm's bounding box, metres: a work area, not a country.
pub const MAX_FARM_EXTENT_M: f64 = 200_000.0;
/// Widest farm in longitude, degrees: one UTM zone's width, so a farm touches at most two
/// zones. (Below 72° of latitude [`MAX_FARM_EXTENT_M`] is the tighter bound.)
pub const MAX_FARM_LONGITUDE_SPAN_DEG: f64 = 6.0;
/// Largest coordinate magnitude accepted in a local frame, metres. A local frame is a plane
/// laid on the Earth at `--origin` (its x and y added to the origin's UTM easting and
/// northing); 100 km from its (0, 0) the map's scale there differs from the origin's by at
/// most 0.15 % (UTM's scale factor, k = 0.9996 · (1 + e²/2R²), over 100 km more of
/// easting). Coordinates far beyond a farm's size are a projected grid's (UTM, a national
/// grid) read as local metres, which lay the fields thousands of km off, bent (trial 7: a
/// field at (2,000 km, 0) sprayed 0.96 of its length, one at (10,000 km, 10,000 km) 0.41).
pub const MAX_LOCAL_COORDINATE_M: f64 = 100_000.0;
/// Raster cells a terrain model may hold in memory (4 bytes each: 1.6 GB).
pub const MAX_TERRAIN_CELLS: u64 = 400_000_000;
/// Points of an XYZ point cloud.
pub const MAX_POINT_CLOUD_POINTS: usize = 50_000_000;
/// Cells a point cloud may be gridded into: 12 bytes each while gridding (heights, bucket
/// offsets twice), so at most 1.2 GB.
pub const MAX_GRIDDED_CELLS: u64 = 100_000_000;
/// Largest cell a point cloud is gridded at, metres: coarser than the coarsest public DEMs
/// (SRTM3, 90 m) is not a terrain model a low-flying sprayer can trust.
pub const MAX_GRIDDED_CELL_M: f64 = 100.0;
/// Lowest and highest terrain height accepted, metres above sea level (the Dead Sea shore is
/// −430 m, Everest 8,849 m): anything beyond is an undeclared no-data value or a broken file.
pub const TERRAIN_HEIGHT_RANGE_M: (f64, f64) = (-500.0, 9_000.0);
/// Input file size, bytes, for text formats read whole.
pub const MAX_TEXT_FILE_BYTES: u64 = 2_000_000_000;
/// Sprayable area in one plan, m² (10,000 ha: weeks of work for a spraying drone, which
/// does 10-20 ha an hour). Coverage checks hold rasters of the area in memory.
pub const MAX_PLAN_AREA_M2: f64 = 1.0e8;
/// Swaths in one plan, estimated from each field's diagonal before any layout. 4,000 swaths
/// plan in about 40 s on this project's 2-core machine; routing grows faster than linearly.
pub const MAX_PLAN_SWATHS: usize = 10_000;
/// Terrain samples along swaths (seed 001's a), metres: finer than half a metre is finer than
/// the DEMs a sprayer plans on, and the work grows as 1/a (0.5 m: 2.4 s on the seed 001
/// farm, 0.01 m: over a minute); the terrain tolerance adds waypoints where the ground bends.
pub const DRAPE_SPACING_RANGE_M: (f64, f64) = (0.5, 1000.0);
/// Path points of one field's grid coverage (seed 004): its turn-minimising searches are
/// for fields of a few hundred to a few thousand points.
pub const MAX_GRID_COVER_POINTS: usize = 40_000;
/// Cells of seed 003's grid model of a field (`sortie/grid.rs`, for its repro).
pub const MAX_SORTIE_GRID_CELLS: usize = 4_000_000;
/// Pairs of overlapping fields kept with `--allow-overlap`.
pub const MAX_OVERLAP_PAIRS: usize = 1_000;
/// Pairs of fields whose bounding boxes overlap, intersected one by one in the overlap check.
/// A farm of 10,000 square fields in a grid has some 40,000 (its neighbours' boxes touch).
pub const MAX_OVERLAP_CANDIDATES: usize = 200_000;

/// Scan lines across one field (its diagonal over the swath width).
pub const MAX_SCAN_LINES: usize = 200_000;

/// A swath width, metres: a vehicle's, or a grid cell taken as one (seed 004).
pub const SWATH_WIDTH_RANGE_M: (f64, f64) = (0.5, 200.0);

/// The least height above the ground, metres, that any airborne part of a mission may fly
/// at, whatever the spray height and terrain tolerance say: lower, a sprayer is in the crop.
/// The preflight holds every file to it, and a terrain tolerance that would let the spray
/// legs sink below it is refused (`--terrain-tolerance`, a checked folder's `report.json`).
pub const MIN_GROUND_CLEARANCE_M: f64 = 0.5;

/// Why a terrain tolerance cannot be flown at a spray height: not a finite number above 0,
/// or so large that spray legs within it may sink below [`MIN_GROUND_CLEARANCE_M`].
pub fn terrain_tolerance_fault(tolerance_m: f64, spray_height_m: f64) -> Option<String> {
    if !(tolerance_m.is_finite() && tolerance_m > 0.0) {
        return Some("must be a finite number above 0".into());
    }
    let most = spray_height_m - MIN_GROUND_CLEARANCE_M;
    (tolerance_m > most + 1e-9).then(|| {
        format!(
            "at spray height {spray_height_m} m it would let the spray legs sink to {:.2} m above the ground; at most {most} m keeps {MIN_GROUND_CLEARANCE_M} m of clearance",
            spray_height_m - tolerance_m
        )
    })
}

/// Plausible ranges of a vehicle's figures (`Vehicle::validate`): beyond them a value is a
/// typo or an attack (`1e308`), not an aircraft, and planning with it would overflow or run
/// without end.
pub const VEHICLE_RANGES: [(&str, f64, f64); 16] = [
    (
        "swath_width_m",
        SWATH_WIDTH_RANGE_M.0,
        SWATH_WIDTH_RANGE_M.1,
    ),
    // A spray height must leave room for a terrain tolerance above the clearance floor.
    ("spray_height_m", 1.0, 500.0),
    ("safe_height_m", 0.0, 500.0),
    ("spray_speed_mps", 0.1, 100.0),
    ("turn_speed_mps", 0.1, 100.0),
    ("transit_speed_mps", 0.1, 100.0),
    ("climb_speed_mps", 0.1, 50.0),
    ("descent_speed_mps", 0.1, 50.0),
    ("land_speed_mps", 0.1, 50.0),
    ("battery_endurance_s", 1.0, 86_400.0),
    // Above 90 % held back a battery flies almost nothing: a typo for 9 or 0.9.
    ("battery_reserve_percent", 0.0, 90.0),
    ("battery_swap_s", 0.0, 86_400.0),
    ("refill_base_s", 0.0, 86_400.0),
    ("refill_max_s", 0.0, 86_400.0),
    ("tank_spray_time_s", 1.0, 86_400.0),
    ("tank_l", 0.01, 100_000.0),
];

/// Largest application rate, litres per hectare (ultra-low-volume spraying is 1-10, ground
/// rigs 100-400).
pub const MAX_APPLICATION_RATE_L_PER_HA: f64 = 10_000.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tolerance_that_sinks_the_spray_legs_below_the_floor_is_refused() {
        assert_eq!(terrain_tolerance_fault(1.0, 2.0), None);
        assert_eq!(terrain_tolerance_fault(1.5, 2.0), None);
        let fault = terrain_tolerance_fault(5.0, 2.5).unwrap();
        assert!(
            fault.contains("sink to -2.50 m") && fault.contains("at most 2 m"),
            "{fault}"
        );
        assert!(terrain_tolerance_fault(0.0, 2.0).is_some());
        assert!(terrain_tolerance_fault(f64::NAN, 2.0).is_some());
    }
}
