//! QGroundControl `.plan` (JSON), one per sortie, following QGC's loader rules
//! (`../shared/reference/ecosystem.md` §8.1): `fileType` "Plan", version 1; mission version 2
//! with `plannedHomePosition` [lat, lon, AMSL], `firmwareType` 3 (ArduPilot), `vehicleType` 2;
//! every item a `SimpleItem` with exactly seven params (`null` for NaN), `autoContinue`,
//! `doJumpId` from 1, and `AltitudeMode`, `Altitude`, `AMSLAltAboveTerrain` together.
//! Obstacles become exclusion polygons of the geofence.

use serde_json::{json, Value};

use super::flight::{AltitudeReference, GeoFrame, MissionSettings, SortieMission};
use super::mavlink::Command;
use crate::model::Farm;

/// QGC's altitude modes: 3 = calculated above terrain (frame 0, AMSL), 4 = terrain frame.
fn altitude_mode(reference: AltitudeReference) -> u8 {
    match reference {
        AltitudeReference::SeaLevel => 3,
        AltitudeReference::Terrain => 4,
    }
}

fn rounded(value: f64, decimals: i32) -> Value {
    let scale = 10f64.powi(decimals);
    json!((value * scale).round() / scale)
}

/// The `.plan` of one sortie.
pub fn plan_file(
    mission: &SortieMission,
    farm: &Farm,
    settings: &MissionSettings,
    cruise_mps: f64,
    hover_mps: f64,
) -> String {
    let frame = GeoFrame::new(farm.coordinate_system, settings.local_origin);
    let items: Vec<Value> = mission
        .items
        .iter()
        .enumerate()
        .map(|(index, item)| {
            let command = Command::of(item, settings.altitude, settings.sprayer);
            let params: Vec<Value> = command
                .params
                .iter()
                .enumerate()
                .map(|(k, p)| match p {
                    Some(value) if k == 4 || k == 5 => rounded(*value, 9),
                    Some(value) => rounded(*value, 3),
                    None => Value::Null,
                })
                .collect();
            let mut object = json!({
                "type": "SimpleItem",
                "autoContinue": true,
                "command": command.command,
                "doJumpId": index + 1,
                "frame": command.frame,
                "params": params,
            });
            if item.moves() {
                object["AltitudeMode"] = json!(altitude_mode(settings.altitude));
                object["Altitude"] = rounded(item.above_ground_m, 3);
                object["AMSLAltAboveTerrain"] = rounded(item.sea_level_m(), 3);
            }
            object
        })
        .collect();
    let polygons: Vec<Value> = farm
        .obstacles
        .iter()
        .map(|obstacle| {
            let ring: Vec<Value> = obstacle.polygon.exterior().0
                [..obstacle.polygon.exterior().0.len() - 1]
                .iter()
                .map(|point| {
                    let (lon, lat) = frame.lon_lat(point.x, point.y);
                    json!([rounded(lat, 9), rounded(lon, 9)])
                })
                .collect();
            json!({"inclusion": false, "polygon": ring, "version": 1})
        })
        .collect();
    let home = &mission.home;
    let plan = json!({
        "fileType": "Plan",
        "version": 1,
        "groundStation": "QGroundControl",
        "geoFence": {"circles": [], "polygons": polygons, "version": 2},
        "mission": {
            "version": 2,
            "firmwareType": 3,
            "vehicleType": 2,
            "cruiseSpeed": cruise_mps,
            "hoverSpeed": hover_mps,
            "globalPlanAltitudeMode": altitude_mode(settings.altitude),
            "plannedHomePosition": [rounded(home.lat, 9), rounded(home.lon, 9), rounded(home.sea_level_m(), 3)],
            "items": items,
        },
        "rallyPoints": {"points": [], "version": 2},
    });
    serde_json::to_string_pretty(&plan).expect("JSON value") + "\n"
}

/// What QGC's loader would refuse in a `.plan` (empty when it loads): the rules above.
pub fn check_plan(text: &str) -> Vec<String> {
    let mut faults = Vec::new();
    let Ok(plan) = serde_json::from_str::<Value>(text) else {
        return vec!["not JSON".into()];
    };
    let mut require = |ok: bool, what: &str| {
        if !ok {
            faults.push(what.to_string());
        }
    };
    require(plan["fileType"] == "Plan", "fileType must be \"Plan\"");
    require(plan["version"] == 1, "version must be 1");
    require(
        plan["groundStation"].is_string(),
        "groundStation must be a string",
    );
    let mission = &plan["mission"];
    require(mission["version"] == 2, "mission.version must be 2");
    require(
        mission["firmwareType"].is_number(),
        "mission.firmwareType must be a number",
    );
    let home = mission["plannedHomePosition"].as_array();
    require(
        home.is_some_and(|h| h.len() == 3 && h.iter().all(Value::is_number)),
        "plannedHomePosition must be [lat, lon, alt]",
    );
    let items = mission["items"].as_array().cloned().unwrap_or_default();
    require(!items.is_empty(), "mission.items must not be empty");
    for (index, item) in items.iter().enumerate() {
        let at = |what: &str| format!("item {index}: {what}");
        require(item["type"] == "SimpleItem", &at("type must be SimpleItem"));
        require(item["command"].is_u64(), &at("command must be a number"));
        require(item["frame"].is_u64(), &at("frame must be a number"));
        require(
            item["autoContinue"].is_boolean(),
            &at("autoContinue must be a boolean"),
        );
        let params = item["params"].as_array();
        require(
            params.is_some_and(|p| p.len() == 7 && p.iter().all(|v| v.is_number() || v.is_null())),
            &at("params must be exactly 7 numbers or null"),
        );
        let altitude_keys = ["AltitudeMode", "Altitude", "AMSLAltAboveTerrain"];
        let present = altitude_keys
            .iter()
            .filter(|key| item.get(**key).is_some())
            .count();
        require(
            present == 0 || present == 3,
            &at("AltitudeMode, Altitude and AMSLAltAboveTerrain go together"),
        );
        if let Some(params) = params {
            if item["frame"] != 0
                || item["command"] == 16
                || item["command"] == 21
                || item["command"] == 22
            {
                let lat = params.get(4).and_then(Value::as_f64).unwrap_or(0.0);
                let lon = params.get(5).and_then(Value::as_f64).unwrap_or(0.0);
                require(
                    (-90.0..=90.0).contains(&lat) && (-180.0..=180.0).contains(&lon),
                    &at("lat/lon out of range"),
                );
            }
        }
    }
    faults
}
