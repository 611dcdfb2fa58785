//! `terrain info|sample|hillshade`.

use super::*;
use agripath::request::terrain;

pub(super) fn terrain(action: TerrainAction) -> Result<(), Failure> {
    match action {
        TerrainAction::Info {
            terrain,
            cell,
            json,
        } => emit!("{}", terrain::info(&terrain, cell, json)?),
        TerrainAction::Sample {
            terrain,
            coordinates,
            cell,
        } => emit!("{}", terrain::sample(&terrain, cell, &coordinates)?),
        TerrainAction::Hillshade {
            terrain,
            out,
            size,
            exaggeration,
            extent,
            cell,
        } => {
            let shaded = terrain::shade(&terrain, cell, size, exaggeration, extent.as_deref())?;
            write_file_atomically(&out, &shaded.to_png())
                .map_err(|error| output_failure(&out, error))?;
            emitln!(
                "wrote {} ({} × {} pixels)",
                out.display(),
                shaded.width,
                shaded.height
            );
        }
    }
    Ok(())
}
