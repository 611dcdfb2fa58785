//! The tables as `agripath repro` prints them: each table with its heading and the notes
//! that say how to read it beside the paper's figures, so that every program built on the
//! library prints the same words.

use crate::grid_cover::hybrid_pso::HpsoSettings;
use crate::InputError;

/// Seed 001's Table 7 at the paper's 5 m swath and at 6.5 m, with the notes on S4's plateau.
pub fn seed001_table7() -> Result<String, InputError> {
    let scenario = crate::demo::scenario()?;
    let references: serde_json::Value =
        serde_json::from_str(crate::demo::FARM_GEOJSON).expect("the embedded farm is JSON");
    let mut text = String::from("Seed 001, Table 7: paper beside agripath\n");
    for (width, paper) in [(5.0, &references), (6.5, &serde_json::Value::Null)] {
        let table = super::seed001_table7::table7(&scenario, paper, width)
            .map_err(|fault| InputError::new(crate::demo::FARM_LABEL, fault))?;
        text += "\n";
        text += &table.to_text();
    }
    text += "\n";
    text += "The paper gives figures for w = 5 m only. 'ΔL' is ours against the paper's length; '0.1°'\n";
    text += "is our refinement of E; coverage is of the sprayable area (seed layout vs one edge pass).\n";
    text += "S4 holds the 3 m plateau: at the paper's 87° we find its 47 swaths and its length to 0.03 %,\n";
    text += "but our analytic plateau (5 m rim) drapes 1° to 45 swaths and 7118 m, a lower E (0.064 vs 0.079);\n";
    text += "the paper's 20 m DEM is not published, and L varies by ±1 % between neighbouring headings there.\n";
    Ok(text)
}

/// Seed 001's Table 8: transfer lengths from the paper's start points, `seed` ant colony runs.
pub fn seed001_table8(runs: u64, seed: u64) -> Result<String, InputError> {
    let scenario = crate::demo::scenario()?;
    let table = super::seed001_table8::table8(&scenario, runs as usize, seed)
        .map_err(|fault| InputError::new(crate::demo::FARM_LABEL, fault))?;
    Ok(format!(
        "Seed 001, Table 8: transfer path length (m), paper beside agripath\n{}",
        table.to_text()
    ))
}

/// Seed 003's Tables 4 and 5 on the sloped strip and on flat ground, with the note on what
/// the non-spray time counts.
pub fn seed003_table4(seed: u64) -> Result<String, InputError> {
    use super::seed003_table4::{case, to_text, StripSlope};
    let mut text = String::from(
        "Seed 003, Tables 4 and 5: sorties on the 700 m × 100 m strip, ours (paper)\n",
    );
    let sloped = case(&StripSlope, seed)?;
    text += "\n";
    text += &to_text(&sloped);
    let flat = case(&crate::terrain::Flat::new(0.0), seed)?;
    text += "\nThe same on flat ground (the paper's 2D case):\n";
    text += &to_text(&flat);
    text += "\n";
    text += "Non-spray time = round trips + max(battery swap, refill) per return (the turns, equal for every\n";
    text += "plan, are left out as in the paper's Table 4). 'exact' is ours: the optimal returns for this route.\n";
    Ok(text)
}

/// Seed 004's six fields: the rows, the table as written to `seed004.txt`, and the table as
/// printed (with its heading and the notes on the columns).
pub fn seed004(
    settings: &HpsoSettings,
) -> Result<(Vec<super::seed004::FieldRow>, String, String), InputError> {
    let rows = super::seed004::table(settings)?;
    let table = super::seed004::to_text(&rows, settings);
    let mut text = String::from(
        "Seed 004: turns on the six fields with obstacles (grid of 5 m path points)\n",
    );
    text += &table;
    text += "\n";
    text += "'1-direction': the best single-direction boustrophedon, 2 × (runs − 1); 'lower bd': no route of\n";
    text += "axis-parallel legs can turn fewer times (König cover of the points by row and column runs, − 1).\n";
    text += "'!' marks a route that misses a point or crosses an obstacle.\n";
    text += "'HPSO (ours)' is the seed's HPSO as its text survives: steps 3-5 are missing and no iteration\n";
    text += "count is given, so from random permutations it stays far above the paper's 27-46 turns; the\n";
    text += "paper's column cannot be reproduced from the text (decision 0010). 'ours' is our method.\n";
    Ok((rows, table, text))
}
