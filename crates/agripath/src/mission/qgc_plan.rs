//! QGroundControl `.plan` (JSON), one per sortie, following QGC's loader rules
//! (`../shared/reference/ecosystem.md` §8.1): `fileType` "Plan", version 1; mission version 2
//! with `plannedHomePosition` [lat, lon, AMSL], `firmwareType` 3 (ArduPilot), `vehicleType` 2;
//! every item a `SimpleItem` with exactly seven params (`null` for NaN), `autoContinue`,
//! `doJumpId` from 1, and `AltitudeMode`, `Altitude`, `AMSLAltAboveTerrain` together.
//! The geofence (decision 0012): one inclusion polygon, the convex hull of every place the
//! sortie flies grown by `fence_margin_m` (one, because firmware that meets several inclusion
//! polygons asks to be inside all of them), and the obstacles as exclusion polygons; the
//! supply point is the rally point.

use serde_json::{json, Value};

use super::flight::{AltitudeReference, GeoFrame, MissionSettings, SortieMission};
use super::mavlink::Command;
use crate::model::Farm;

/// QGC's altitude modes (`QGroundControlQmlGlobal::AltMode`): 1 relative to home (frame 3),
/// 2 absolute (frame 0, AMSL), 4 terrain frame (frame 10).
fn altitude_mode(reference: AltitudeReference) -> u8 {
    match reference {
        AltitudeReference::Relative => 1,
        AltitudeReference::SeaLevel => 2,
        AltitudeReference::Terrain => 4,
    }
}

/// The geofence of a sortie in plan metres: the inclusion ring (closed) and the exclusion
/// rings (the obstacles). The preflight checks flights against what the file says, which is
/// this.
pub fn fence_rings(
    mission: &SortieMission,
    farm: &Farm,
    settings: &MissionSettings,
) -> (Vec<geo::Coord<f64>>, Vec<Vec<geo::Coord<f64>>>) {
    let frame = GeoFrame::new(farm.coordinate_system, settings.local_origin);
    let mut places: Vec<geo::Coord<f64>> = mission
        .items
        .iter()
        .chain(std::iter::once(&mission.home))
        .filter(|item| item.moves())
        .map(|item| {
            let (x, y) = frame.plan_xy(item.lon, item.lat);
            geo::Coord { x, y }
        })
        .collect();
    places.dedup();
    let inclusion = crate::geometry::detour::grown_convex_hull(&places, settings.fence_margin_m);
    let exclusions = farm
        .obstacles
        .iter()
        .map(|obstacle| obstacle.polygon.exterior().0.clone())
        .collect();
    (inclusion, exclusions)
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
            let command = Command::of(
                item,
                settings.altitude,
                mission.home.ground_m,
                settings.sprayer,
            );
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
                object["Altitude"] =
                    rounded(item.altitude_m(settings.altitude, mission.home.ground_m), 3);
                object["AMSLAltAboveTerrain"] = rounded(item.sea_level_m(), 3);
            }
            object
        })
        .collect();
    let (inclusion, exclusions) = fence_rings(mission, farm, settings);
    let ring_json = |ring: &[geo::Coord<f64>]| -> Vec<Value> {
        ring[..ring.len().saturating_sub(1)]
            .iter()
            .map(|point| {
                let (lon, lat) = frame.lon_lat(point.x, point.y);
                json!([rounded(lat, 9), rounded(lon, 9)])
            })
            .collect()
    };
    let mut polygons =
        vec![json!({"inclusion": true, "polygon": ring_json(&inclusion), "version": 1})];
    for ring in &exclusions {
        polygons.push(json!({"inclusion": false, "polygon": ring_json(ring), "version": 1}));
    }
    let home = &mission.home;
    // The rally point: the supply point, at the altitude the sortie leaves it (relative to home).
    let rally_altitude = mission
        .items
        .first()
        .map_or(0.0, |item| item.sea_level_m() - home.ground_m);
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
        "rallyPoints": {"points": [[rounded(home.lat, 9), rounded(home.lon, 9), rounded(rally_altitude, 3)]], "version": 2},
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
