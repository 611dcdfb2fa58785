//! The preflight run again on a plan folder as it is now (`agripath check`): its mission
//! files, perhaps edited in a ground station, held to the settings its `report.json` records.

use super::{check, PreflightSettings, Promise, Verdict, World};
use crate::mission::flight::MissionSettings;

/// Checks a plan folder written earlier (and perhaps edited by hand in a ground station)
/// against `world`: its mission files as they are now, held to the settings its
/// `report.json` records.
pub fn check_folder(world: &World, folder: &std::path::Path) -> Result<Verdict, crate::Fault> {
    use crate::Fault;
    let report_path = folder.join("report.json");
    let text = crate::files::read_text(&report_path).map_err(|error| {
        Fault::Structure(format!(
            "{}: cannot read: {}",
            report_path.display(),
            error.fault
        ))
    })?;
    let report: serde_json::Value = serde_json::from_str(&text).map_err(|error| {
        Fault::Structure(format!("{}: not JSON: {error}", report_path.display()))
    })?;
    let missing = |what: &str| {
        Fault::Structure(format!(
            "{}: no {what} (written by agripath plan?)",
            report_path.display()
        ))
    };
    let mission: MissionSettings = serde_json::from_value(report["mission"].clone())
        .map_err(|error| missing(&format!("valid mission settings ({error})")))?;
    // The tolerance is read from a file that may have been edited with the missions: it is
    // held to the same bound as `--terrain-tolerance` (and the preflight's floor holds anyway).
    if let Some(why) = crate::limits::terrain_tolerance_fault(
        mission.terrain_tolerance_m,
        world.vehicle.spray_height_m,
    ) {
        return Err(Fault::Structure(format!(
            "{}: mission.terrain_tolerance_m = {}: {why}",
            report_path.display(),
            mission.terrain_tolerance_m
        )));
    }
    let number =
        |value: &serde_json::Value, what: &str| value.as_f64().ok_or_else(|| missing(what));
    let fields = report["fields"].as_array().cloned().unwrap_or_default();
    let promise = Promise {
        headland_passes: report["settings"]["headland_passes"].as_u64().unwrap_or(1) as usize,
        edge_gaps: report["settings"]["edge_cut"] == "gap",
        covered_fraction: world
            .farm
            .fields
            .iter()
            .enumerate()
            .map(|(index, _)| {
                fields
                    .get(index)
                    .and_then(|field| field["covered_fraction"].as_f64())
                    .unwrap_or(1.0)
            })
            .collect(),
        outside_m2: fields
            .iter()
            .map(|field| field["outside_m2"].as_f64().unwrap_or(0.0))
            .sum(),
        sprayed_m2: (number(&report["spray_length_m"], "spray_length_m")?
            + number(&report["edge_length_m"], "edge_length_m")?)
            * world.vehicle.swath_width_m,
    };
    let settings = PreflightSettings::new(
        &mission,
        number(
            &report["settings"]["boundary_margin_m"],
            "settings.boundary_margin_m",
        )?,
        number(
            &report["settings"]["obstacle_margin_m"],
            "settings.obstacle_margin_m",
        )?,
        &promise,
    );
    let mut files = Vec::new();
    let entries = std::fs::read_dir(folder)
        .map_err(|error| Fault::Structure(format!("{}: cannot read: {error}", folder.display())))?;
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.starts_with("sortie_") && (name.ends_with(".plan") || name.ends_with(".waypoints"))
        {
            let bytes = crate::files::read_bytes(&entry.path())
                .map_err(|error| Fault::Structure(error.to_string()))?;
            files.push((name, bytes));
        }
    }
    Ok(check(world, &settings, &files))
}
