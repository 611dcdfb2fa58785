//! Command-line grammar (clap derive). Values are checked here only for shape; meaning is
//! checked by the library, once.

use std::path::{Path, PathBuf};

use clap::{Parser, Subcommand};

use agripath::request::bench::FunctionBenchOptions;
use agripath::request::grid::GridRequest;
use agripath::request::plan::PlanOptions;
use agripath::request::track::TrackRequest;
use agripath::request::ScenarioInputs;

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
        /// Also print the mission sheet to sheet.pdf with a headless Chromium.
        #[arg(long)]
        pdf: bool,
    },
    /// Plan full coverage of the fields: swaths at the best heading, edge passes, the order,
    /// sorties with returns to the supply point, mission files checked as flown.
    ///
    /// Writes into DIR: plan.geojson, report.json, plan.svg (and plan.png), plan.html (the
    /// offline viewer), sheet.html (the mission sheet to print; sheet.pdf with --pdf),
    /// mission.kml, waypoints.csv, terrain.png (the terrain map: fields, legend, scale), and
    /// per sortie NN sortie_NN.plan (QGroundControl) and sortie_NN.waypoints (QGC WPL 110).
    /// Inputs: a scenario TOML, or --fields (GeoJSON, KML, KMZ) with --terrain (GeoTIFF, ESRI
    /// ASCII grid, XYZ, flat) and --vehicle (TOML; a [camera] section makes it a survey).
    Plan {
        #[command(flatten)]
        inputs: ScenarioInputs,
        #[command(flatten)]
        options: PlanOptions,
        /// Write the mission files even when the preflight check of the files as flown fails
        /// (the verdict stays in report.json; exit status 0).
        #[arg(long)]
        allow_unsafe: bool,
        /// Also print the mission sheet (sheet.html) to sheet.pdf with a headless Chromium
        /// (`chromium` on PATH, or the browser named by AGRIPATH_BROWSER).
        #[arg(long)]
        pdf: bool,
        /// Output folder, replaced as a whole (without mission files when the preflight
        /// refuses them, exit 3; left untouched on bad input, exit 2).
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
        inputs: ScenarioInputs,
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
        /// seed000-table2: the reading of the text's open choices (paper, engine, or one of
        /// those --ablation lists; join changes with '+'; with --ablation, a comma-separated
        /// list of readings to compare with paper; docs/decisions/0020).
        #[arg(long, default_value = "paper")]
        variant: String,
        /// seed000-table2: run every named reading and print the ablation table.
        #[arg(long)]
        ablation: bool,
        /// Also write the tables (Markdown, CSV) and plots into this folder.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Fewest-turn coverage of one field on a grid of path points (seed 004): `ours`, the
    /// seed's `hpso`, or the `baseline` boustrophedon decomposition. Writes DIR/plan.geojson,
    /// DIR/report.json and DIR/plan.svg.
    Grid {
        #[command(flatten)]
        grid: GridRequest,
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
        track: TrackRequest,
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
        inputs: ScenarioInputs,
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

impl Command {
    /// The folder this command writes, if any: checked before any work is done.
    /// The files the command reads, where they are paths: a run must not replace the folder
    /// that holds one of them.
    pub fn input_files(&self) -> Vec<PathBuf> {
        match self {
            Command::Plan { inputs, .. } => inputs.files(),
            Command::Grid { grid, .. } => vec![grid.fields.clone()],
            Command::Track { track, .. } => vec![track.scenario_path.clone()],
            _ => Vec::new(),
        }
    }

    pub fn output_folder(&self) -> Option<&Path> {
        match self {
            Command::Demo { out, .. }
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
        #[command(flatten)]
        options: FunctionBenchOptions,
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
        /// Print the figures as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Heights at points given in the terrain's own coordinates: X Y [X Y ...] (with
    /// --lonlat: LON LAT [LON LAT ...]).
    Sample {
        terrain: String,
        /// Pairs of coordinates.
        #[arg(required = true, num_args = 2.., allow_negative_numbers = true)]
        coordinates: Vec<f64>,
        /// The pairs are longitude and latitude (degrees), for a DEM in UTM or lon/lat.
        #[arg(long)]
        lonlat: bool,
        /// Cell size for gridding an XYZ point cloud, metres.
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
        #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
        extent: Option<Vec<f64>>,
        /// Cell size for gridding an XYZ point cloud, metres.
        #[arg(long)]
        cell: Option<f64>,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The library's defaults are the command line's: a program built on the library plans
    /// what `agripath plan` plans.
    #[test]
    fn the_plan_defaults_are_the_librarys() {
        let arguments = Arguments::try_parse_from(["agripath", "plan", "--out", "x"]).unwrap();
        let Command::Plan {
            inputs,
            options,
            allow_unsafe,
            ..
        } = arguments.command
        else {
            panic!("not a plan command");
        };
        assert_eq!(options, PlanOptions::default());
        assert_eq!(inputs, ScenarioInputs::default());
        assert!(!allow_unsafe);
    }

    #[test]
    fn flags_reach_the_request() {
        let arguments = Arguments::try_parse_from([
            "agripath",
            "plan",
            "--fields",
            "f.geojson",
            "--crs",
            "local",
            "--no-refine",
            "--swath-width",
            "7",
            "--weights",
            "0.2,0.8",
            "--out",
            "x",
        ])
        .unwrap();
        let Command::Plan {
            inputs, options, ..
        } = arguments.command
        else {
            panic!("not a plan command");
        };
        assert!(inputs.local_coordinates);
        assert_eq!(inputs.overrides.swath_width_m, Some(7.0));
        assert!(!options.refine_heading);
        assert_eq!(options.weights, vec![0.2, 0.8]);
        assert!(
            Arguments::try_parse_from(["agripath", "plan", "--crs", "utm", "--out", "x"]).is_err()
        );
    }
}
