//! `repro`: the papers' tables recomputed beside their figures.

use super::*;
use agripath::repro::printed;

pub(super) fn repro(
    table: ReproTable,
    runs: Option<u64>,
    seed: u64,
    out: Option<&Path>,
) -> Result<(), Failure> {
    match table {
        ReproTable::Seed000Table2 => {
            let settings = agripath::repro::seed000_table2::settings(runs.unwrap_or(50), seed);
            let table = run_function_bench(&settings)?;
            let comparison = agripath::repro::seed000_table2::comparison(&table);
            emit!("{comparison}");
            if let Some(out) = out {
                let mut files = table.files();
                files.push(("comparison.md".into(), comparison.into_bytes()));
                let named: Vec<(&str, Vec<u8>)> = files
                    .iter()
                    .map(|(name, bytes)| (name.as_str(), bytes.clone()))
                    .collect();
                let written = write_folder(out, &named)?;
                emitln!(
                    "wrote {}/: comparison.md, table.md, table.csv, convergence_*.svg",
                    written.display()
                );
            }
            Ok(())
        }
        ReproTable::Seed000Table4
        | ReproTable::Seed000Table5
        | ReproTable::Seed002
        | ReproTable::Spso => repro_tracks(table, runs, seed, out),
        ReproTable::Seed003Table4 => {
            emit!("{}", printed::seed003_table4(seed)?);
            Ok(())
        }
        ReproTable::Seed004 => {
            let settings = agripath::grid_cover::hybrid_pso::HpsoSettings {
                seed,
                ..Default::default()
            };
            let (rows, table, text) = printed::seed004(&settings)?;
            emit!("{text}");
            if let Some(out) = out {
                let mut files: Vec<(String, Vec<u8>)> =
                    vec![("seed004.txt".into(), table.into_bytes())];
                for row in &rows {
                    let map = agripath::repro::seed004::map_svg(row);
                    files.push((format!("{}.svg", row.name), map.into_bytes()));
                }
                let written = write_folder(out, &files)?;
                emitln!(
                    "wrote {}/: seed004.txt and a map per field",
                    written.display()
                );
            }
            Ok(())
        }
        ReproTable::Seed001Table8 => {
            emit!("{}", printed::seed001_table8(seed)?);
            Ok(())
        }
        ReproTable::Seed001Table7 => {
            emit!("{}", printed::seed001_table7()?);
            Ok(())
        }
    }
}
