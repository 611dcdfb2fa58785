//! Command-line grammar (clap derive). Values are checked here only for shape; meaning is
//! checked by the library, once.

use std::path::{Path, PathBuf};

use clap::{Args, Parser, Subcommand};

#[derive(Debug, Parser)]
#[command(
    name = "agripath",
    version,
    about = "Mission planning for agricultural UAVs over real terrain",
    long_about = "Mission planning for agricultural UAVs over real terrain.\n\nExit status: 0 done, 2 bad input (nothing written), 3 not safe to fly (no mission file written), 1 could not write outputs."
)]
pub struct Arguments {
    #[command(subcommand)]
    pub command: Command,
}

// Parsed once per run: the size of the largest variant does not matter.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run the embedded default (seed 001's five-field farm) and write ./agripath-demo/.
    Demo {
        /// Output folder.
        #[arg(long, default_value = "agripath-demo")]
        out: PathBuf,
    },
    /// Plan full coverage of the fields: swaths at the best heading, edge passes, route.
    /// Writes DIR/plan.geojson, DIR/report.json and DIR/plan.svg.
    Plan {
        #[command(flatten)]
        inputs: Inputs,
        #[command(flatten)]
        coverage: CoverageArgs,
        #[command(flatten)]
        order: OrderArgs,
        #[command(flatten)]
        mission: MissionArgs,
        /// Output folder (replaced as a whole when planning succeeds).
        #[arg(long)]
        out: PathBuf,
    },
    /// Fly the mission files of a plan folder (perhaps edited in a ground station) against
    /// the inputs again: the preflight check of `plan`, on the files as they are now. Exit 3
    /// when they are not safe to fly.
    Check {
        /// The plan folder (written by `agripath plan` or `demo`).
        folder: PathBuf,
        /// The inputs it was planned from (the demo's embedded farm when none are given).
        #[command(flatten)]
        inputs: Inputs,
    },
    /// Recompute a table of the papers beside the paper's figures.
    Repro {
        #[arg(value_enum)]
        table: ReproTable,
        /// Independent runs, for the stochastic tables (default: the paper's).
        #[arg(long)]
        runs: Option<u64>,
        /// Seed of the random streams.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Also write the tables (Markdown, CSV) and plots into this folder.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Fewest-turn coverage of one field on a grid of path points (seed 004): `ours`, the
    /// seed's `hpso`, or the `baseline` boustrophedon decomposition. Writes DIR/plan.geojson,
    /// DIR/report.json and DIR/plan.svg.
    Grid {
        #[command(flatten)]
        grid: GridArgs,
        #[arg(long)]
        out: PathBuf,
    },
    /// Plan a safe point-to-point 3D track over terrain and threat cylinders. Writes
    /// DIR/track.geojson, DIR/report.json, DIR/table.md, DIR/top_view.svg (and .png in
    /// builds with the `png` feature, the default), DIR/profile_NAME.svg, DIR/convergence.svg and, per planner whose track is safe,
    /// DIR/NAME.waypoints (QGC WPL 110). Exits 3 and writes no .waypoints when no planner
    /// finds a safe track.
    ///
    /// Scenario formats (detected from the extension and keys): seed 000's orchard JSON
    /// (`tasks`, `terrain.coefficients`/`terrain.hills`, e.g. data/seed000_orchard.json);
    /// seed 002's survey JSON (`ga`, data/seed002_field_survey.json); SPSO's JSON
    /// (`threat_cylinders_x_y_z_r` with a `dem.file`, data/spso/scenario.json); the operator
    /// TOML (a DEM, start/goal/threats in lon/lat or local metres, a height band above the
    /// ground, data/tracks/christmas_island_track.toml). Unknown keys are an error. A start
    /// or goal below the band's floor is reached by a vertical climb or descent.
    Track {
        #[command(flatten)]
        track: TrackArgs,
        /// Write the .waypoints of unsafe tracks too, and exit 0 with a warning.
        #[arg(long)]
        allow_unsafe: bool,
        #[arg(long)]
        out: PathBuf,
    },
    /// Serve a plan folder on 127.0.0.1 and print the address of its plan.html (the page also
    /// works opened straight from disk). Runs until stopped (Ctrl-C).
    View {
        /// A folder written by `plan` or `demo`.
        folder: PathBuf,
        /// Port on 127.0.0.1 (0: any free port).
        #[arg(long, default_value_t = 8765)]
        port: u16,
        /// Also open the page in the desktop's browser (xdg-open / open).
        #[arg(long)]
        open: bool,
    },
    /// Benchmarks: optimizers on the test functions of seed 000 Table 1.
    Bench {
        #[command(subcommand)]
        action: BenchAction,
    },
    /// Read a scenario (or fields, terrain and vehicle) and say what was read or what is wrong.
    Validate {
        #[command(flatten)]
        inputs: Inputs,
        /// Print the summary as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Look at a terrain model: its extent and heights, samples, a hillshade picture.
    Terrain {
        #[command(subcommand)]
        action: TerrainAction,
    },
}

/// Where a scenario comes from: a scenario file, or its parts as flags (flags override it).
#[derive(Debug, Args)]
pub struct Inputs {
    /// Scenario TOML file tying fields, terrain and vehicle together.
    pub scenario: Option<PathBuf>,
    /// Field file: GeoJSON (.geojson/.json), KML or KMZ.
    #[arg(long)]
    pub fields: Option<PathBuf>,
    /// Terrain: a DEM file (.tif, .asc, .xyz/.csv) or flat, flat:HEIGHT, seed000, seed002.
    #[arg(long)]
    pub terrain: Option<String>,
    /// Vehicle TOML file.
    #[arg(long)]
    pub vehicle: Option<PathBuf>,
    /// Read field coordinates as metres in a local frame ("local"), whatever the file says.
    #[arg(long, value_parser = ["local"])]
    pub crs: Option<String>,
    /// Swath width, metres (overrides the vehicle).
    #[arg(long, allow_negative_numbers = true)]
    pub swath_width: Option<f64>,
    /// Spray height above the terrain, metres (overrides the vehicle).
    #[arg(long, allow_negative_numbers = true)]
    pub spray_height: Option<f64>,
    /// Safe transfer height h, metres (overrides the vehicle).
    #[arg(long, allow_negative_numbers = true)]
    pub safe_height: Option<f64>,
    /// Keep fields that overlap and spray each overlap once, with the field that comes first
    /// in the file (without it, overlapping fields are refused).
    #[arg(long)]
    pub allow_overlap: bool,
}

/// What `grid` plans: the field, the method and the cell width.
#[derive(Debug, Args)]
pub struct GridArgs {
    /// Field file (GeoJSON, KML or KMZ); obstacles as in `plan`.
    pub fields: PathBuf,
    /// Which field, by name (default: the first).
    #[arg(long)]
    pub field: Option<String>,
    #[arg(long, default_value = "ours", value_parser = agripath::grid_cover::GRID_METHODS)]
    pub method: String,
    /// Path-point spacing = swath width, metres (default: the file's `swath_width_m`, else 5).
    #[arg(long, allow_negative_numbers = true)]
    pub swath_width: Option<f64>,
    /// Read coordinates as local metres.
    #[arg(long, value_parser = ["local"])]
    pub crs: Option<String>,
    /// Seed of HPSO.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// What `track` plans: the scenario, the planners, their runs and the safety limits.
#[derive(Debug, Args)]
pub struct TrackArgs {
    /// Scenario file: JSON of seed 000, seed 002 or SPSO, or an operator TOML.
    pub scenario: PathBuf,
    /// Seed 000's task (I, II or III, or a task name of the file).
    #[arg(long)]
    pub task: Option<String>,
    /// Planners, comma-separated: lattice (ours), iba-fcs, ba, ilssiwba, pso, spso, ga,
    /// aco-r, gsa, lshade, improved-ga.
    #[arg(long, default_value = "lattice")]
    pub algorithm: String,
    /// Independent runs per planner (default: the scenario's `algorithms.runs`, else 5).
    #[arg(long)]
    pub runs: Option<u64>,
    /// Seed of the random streams.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Encoding for the swarm algorithms: cartesian, cylindrical or spherical (default:
    /// the scenario paper's).
    #[arg(long)]
    pub encoding: Option<String>,
    /// Evaluations per run (default: the scenario paper's population × iterations).
    #[arg(long)]
    pub evaluations: Option<u64>,
    /// Least height above the terrain a safe track keeps along its cruise, metres
    /// (checked every 1 m against the terrain as given).
    #[arg(long, default_value_t = 2.0)]
    pub min_clearance: f64,
    /// The vehicle's radius: least distance from a threat cylinder's wall, metres.
    #[arg(long, default_value_t = 1.0)]
    pub vehicle_radius: f64,
}

/// How coverage is laid out.
#[derive(Debug, Args)]
pub struct CoverageArgs {
    /// Edge passes around each boundary and hole; 0 gives seed 001's layout (interior only).
    #[arg(long, default_value_t = 1)]
    pub headland: usize,
    /// Where swaths' spray on/off points sit against the edge-pass band: `overlap` (on the
    /// pass line), `balanced` (least double dose for little missed) or `gap` (no double dose).
    #[arg(long, default_value = "balanced")]
    pub edge_cut: String,
    /// Swath heading: `auto` (seed 001's E), `swaths` (fewest), `length` (shortest), or
    /// degrees from east, counter-clockwise.
    #[arg(long, default_value = "auto", allow_negative_numbers = true)]
    pub heading: String,
    /// Weights ω_N,ω_L of seed 001's E.
    #[arg(long, value_delimiter = ',', default_values_t = [0.5, 0.5])]
    pub weights: Vec<f64>,
    /// Keep the best 1° heading (the seed's) instead of refining it to 0.1°.
    #[arg(long)]
    pub no_refine: bool,
    /// Seed 001's a: spacing of the terrain samples along swaths, metres.
    #[arg(long, default_value_t = 20.0, allow_negative_numbers = true)]
    pub drape_spacing: f64,
    /// Distance kept from field boundaries, metres.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub boundary_margin: f64,
    /// Distance kept from obstacles, metres.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub obstacle_margin: f64,
}

/// How the passes are ordered.
#[derive(Debug, Args)]
pub struct OrderArgs {
    /// `best` (ours: local search), `greedy` or `aco` (seed 001's ant colony).
    #[arg(long, default_value = "best", value_parser = agripath::sequence::Sequencer::KEYS)]
    pub sequencer: String,
    /// Launch point X,Y in the input's coordinates (lon,lat or local metres): the supply
    /// point, as `--supply X,Y`; default: the field file's `launch`/`supply` marker, else
    /// `--supply auto` (with sorties) or a free start.
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub start: Option<Vec<f64>>,
    /// Supply point (take-off, refills, battery swaps, landing): `auto` (the place a vehicle
    /// can stand, on the file's access features if any, that saves most non-spray time; the
    /// default without a launch marker), `auto:N` (also list the N best in report.json), or
    /// X,Y in the input's coordinates.
    #[arg(long, allow_hyphen_values = true)]
    pub supply: Option<String>,
    /// Seed of the stochastic sequencers (same seed, same plan).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Ant colony batches (seed 001: 100 or 200).
    #[arg(long, default_value_t = 200)]
    pub batches: usize,
    /// Ants per batch (seed 001: 50).
    #[arg(long, default_value_t = 50)]
    pub ants: usize,
    /// Return points for refill and battery swap: `joint` (ours: the order of the passes and
    /// the returns optimised together), `exact` (ours: the optimal returns for the order the
    /// sequencer chose), the seed 003 planners `gsa` (gravitational search), `simple`,
    /// `unplanned`, or `none` (one flight).
    #[arg(long, default_value = "joint", value_parser = ["joint", "exact", "gsa", "simple", "unplanned", "none"])]
    pub sorties: String,
}

/// How mission files are written.
#[derive(Debug, Args)]
pub struct MissionArgs {
    /// Altitudes in mission files: `relative` (above the launch point's ground,
    /// MAV_FRAME_GLOBAL_RELATIVE_ALT; the default without a DEM), `sea-level` (from the DEM,
    /// MAV_FRAME_GLOBAL; the default with one; needs a DEM or `--terrain flat:H`) or `terrain`
    /// (above ground, MAV_FRAME_GLOBAL_TERRAIN_ALT, for ArduPilot).
    #[arg(long, value_parser = ["relative", "sea-level", "terrain"])]
    pub altitude: Option<String>,
    /// Write the mission files even when the preflight check of the files as flown fails
    /// (the verdict stays in report.json; exit status 0).
    #[arg(long)]
    pub allow_unsafe: bool,
    /// Sprayer switching: `do-sprayer` (MAV_CMD_DO_SPRAYER) or `servo:CHANNEL:ON_PWM:OFF_PWM`
    /// (MAV_CMD_DO_SET_SERVO).
    #[arg(long, default_value = "do-sprayer")]
    pub sprayer: String,
    /// Terrain following: the largest gap, metres, between the flown altitude and terrain +
    /// spray height along a swath before another waypoint is added.
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub terrain_tolerance: f64,
    /// For fields in local metres: LON,LAT of their origin in mission files (default 126.63,45.75).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub origin: Option<Vec<f64>>,
}

impl Command {
    /// The folder this command writes, if any: checked before any work is done.
    pub fn output_folder(&self) -> Option<&Path> {
        match self {
            Command::Demo { out }
            | Command::Plan { out, .. }
            | Command::Grid { out, .. }
            | Command::Track { out, .. } => Some(out),
            Command::Repro { out, .. }
            | Command::Bench {
                action: BenchAction::Functions { out, .. },
            } => out.as_deref(),
            Command::Check { .. }
            | Command::View { .. }
            | Command::Validate { .. }
            | Command::Terrain { .. } => None,
        }
    }
}

#[derive(Debug, Subcommand)]
pub enum BenchAction {
    /// Optimizers × test functions × runs: best, worst, mean, std and time as in seed 000
    /// Table 2 (Markdown on stdout; with --out also CSV and convergence plots).
    Functions {
        /// Dimension of every function.
        #[arg(long, default_value_t = 50)]
        dim: usize,
        /// Population (agents per iteration).
        #[arg(long, default_value_t = 500)]
        pop: usize,
        /// Iterations; every algorithm gets pop × (iters + 1) evaluations.
        #[arg(long, default_value_t = 300)]
        iters: usize,
        /// Independent runs per algorithm and function.
        #[arg(long, default_value_t = 50)]
        runs: u64,
        /// Algorithms, comma-separated: pso, ga, ba, ilssiwba, iba-fcs, gsa, aco-r, lshade
        /// (default: the five of seed 000).
        #[arg(long, value_delimiter = ',')]
        algorithms: Vec<String>,
        /// Functions, comma-separated: f1 … f9 (default: all nine).
        #[arg(long, value_delimiter = ',')]
        functions: Vec<String>,
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Folder for table.md, table.csv and convergence_*.svg.
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum ReproTable {
    /// Seed 000 Table 2: PSO, GA, BA, ILSSIWBA, IBA-FCS (and L-SHADE) on nine functions, D = 50.
    #[value(name = "seed000-table2")]
    Seed000Table2,
    /// Seed 003 Tables 4 and 5: return points on the strip, unplanned / simple / GSA / exact.
    #[value(name = "seed003-table4")]
    Seed003Table4,
    /// Seed 004: fewest-turn grid coverage of six fields: HPSO, the baseline and ours.
    #[value(name = "seed004")]
    Seed004,
    /// Seed 001 Table 7: headings, swath counts and lengths of the five-field farm.
    #[value(name = "seed001-table7")]
    Seed001Table7,
    /// Seed 000 Table 4: PSO, BA, ILSSIWBA, IBA-FCS (and ours) on track tasks I-III.
    #[value(name = "seed000-table4")]
    Seed000Table4,
    /// Seed 000 Table 5: IBA-FCS with the cylindrical and the Cartesian encoding.
    #[value(name = "seed000-table5")]
    Seed000Table5,
    /// Seed 002 Table 2: GA, ACO, the improved GA with B-spline smoothing (and ours).
    #[value(name = "seed002")]
    Seed002,
    /// SPSO's public scenario: SPSO, IBA-FCS and ours against SPSO's reference runs.
    #[value(name = "spso")]
    Spso,
    /// Seed 001 Table 8: transfer lengths of greedy, ant colony and ours from its start points.
    #[value(name = "seed001-table8")]
    Seed001Table8,
}

#[derive(Debug, Subcommand)]
pub enum TerrainAction {
    /// Size, cell, coordinate system, extent and height range of a terrain.
    Info {
        /// A DEM file (.tif, .asc, .xyz/.csv) or flat, flat:HEIGHT, seed000, seed002.
        terrain: String,
        /// Cell size for gridding an XYZ point cloud, metres.
        #[arg(long)]
        cell: Option<f64>,
        #[arg(long)]
        json: bool,
    },
    /// Heights at points given in the terrain's own coordinates: X Y [X Y ...].
    Sample {
        terrain: String,
        /// Pairs of coordinates.
        #[arg(required = true, num_args = 2.., allow_negative_numbers = true)]
        coordinates: Vec<f64>,
        #[arg(long)]
        cell: Option<f64>,
    },
    /// A hillshade picture (PNG, north up) of the terrain.
    Hillshade {
        terrain: String,
        /// Output PNG file.
        #[arg(long)]
        out: PathBuf,
        /// Longer side of the picture, pixels.
        #[arg(long, default_value_t = 1024)]
        size: usize,
        /// Vertical exaggeration.
        #[arg(long, default_value_t = 1.0)]
        exaggeration: f64,
        /// Area to draw, for unbounded terrains: MIN_X,MIN_Y,MAX_X,MAX_Y.
        #[arg(
            long,
            value_delimiter = ',',
            num_args = 4,
            allow_negative_numbers = true
        )]
        extent: Option<Vec<f64>>,
        #[arg(long)]
        cell: Option<f64>,
    },
}

impl Inputs {
    /// The library's request for these inputs.
    pub fn request(&self) -> agripath::request::ScenarioInputs {
        agripath::request::ScenarioInputs {
            scenario: self.scenario.clone(),
            fields: self.fields.clone(),
            terrain: self.terrain.clone(),
            vehicle: self.vehicle.clone(),
            local_coordinates: self.crs.is_some(),
            overrides: agripath::scenario::VehicleOverrides {
                swath_width_m: self.swath_width,
                spray_height_m: self.spray_height,
                safe_height_m: self.safe_height,
            },
            allow_overlap: self.allow_overlap,
        }
    }
}

/// The library's options for a coverage plan.
pub fn plan_options(
    coverage: &CoverageArgs,
    order: &OrderArgs,
    mission: &MissionArgs,
) -> agripath::request::plan::PlanOptions {
    agripath::request::plan::PlanOptions {
        headland_passes: coverage.headland,
        heading: coverage.heading.clone(),
        weights: coverage.weights.clone(),
        refine_heading: !coverage.no_refine,
        edge_cut: coverage.edge_cut.clone(),
        drape_spacing_m: coverage.drape_spacing,
        boundary_margin_m: coverage.boundary_margin,
        obstacle_margin_m: coverage.obstacle_margin,
        sequencer: order.sequencer.clone(),
        start: order.start.clone(),
        supply: order.supply.clone(),
        seed: order.seed,
        batches: order.batches,
        ants: order.ants,
        sorties: order.sorties.clone(),
        altitude: mission.altitude.clone(),
        sprayer: mission.sprayer.clone(),
        terrain_tolerance_m: mission.terrain_tolerance,
        origin: mission.origin.clone(),
    }
}

impl GridArgs {
    /// The library's request for this grid.
    pub fn request(&self) -> agripath::request::grid::GridRequest {
        agripath::request::grid::GridRequest {
            fields: self.fields.clone(),
            field: self.field.clone(),
            method: self.method.clone(),
            swath_width_m: self.swath_width,
            local_coordinates: self.crs.is_some(),
            seed: self.seed,
        }
    }
}

impl TrackArgs {
    /// The library's request for this track.
    pub fn request(&self) -> agripath::request::track::TrackRequest {
        agripath::request::track::TrackRequest {
            scenario_path: self.scenario.clone(),
            task: self.task.clone(),
            algorithms: self.algorithm.clone(),
            runs: self.runs,
            seed: self.seed,
            encoding: self.encoding.clone(),
            evaluations: self.evaluations,
            limits: agripath::track::SafetyLimits {
                min_clearance_m: self.min_clearance,
                vehicle_radius_m: self.vehicle_radius,
            },
        }
    }
}
