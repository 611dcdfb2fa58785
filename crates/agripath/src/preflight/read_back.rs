//! Mission files read back as a ground station reads them: a QGroundControl `.plan` (JSON)
//! and its `QGC WPL 110` twin. Nothing here knows how they were written; what the files say
//! is what the preflight flies.

use serde_json::Value;

/// One mission item as a file stores it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FileItem {
    /// MAVLink command number (MAV_CMD), e.g. 16 for NAV_WAYPOINT.
    pub command: u16,
    /// MAVLink frame number (MAV_FRAME): 0 above sea level, 3 above home, 10 above terrain.
    pub frame: u8,
    /// p1…p7; NaN where the file has `null` or `nan`.
    pub params: [f64; 7],
}

impl FileItem {
    /// Latitude, degrees (p5).
    pub fn lat(&self) -> f64 {
        self.params[4]
    }
    /// Longitude, degrees (p6).
    pub fn lon(&self) -> f64 {
        self.params[5]
    }
    /// Altitude in the item's frame, metres (p7).
    pub fn altitude(&self) -> f64 {
        self.params[6]
    }
}

/// A polygon of the geofence, as (lat, lon) corners.
#[derive(Debug, Clone, PartialEq)]
pub struct FencePolygon {
    /// `true`: the flight must stay inside; `false`: outside (an exclusion zone).
    pub inclusion: bool,
    /// The corners, (lat, lon) in degrees, in file order.
    pub corners: Vec<(f64, f64)>,
}

/// What a `.plan` file holds.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanFile {
    /// plannedHomePosition: lat, lon, altitude above sea level.
    pub home: (f64, f64, f64),
    /// The mission items, in file order.
    pub items: Vec<FileItem>,
    /// The geofence's polygons.
    pub fence: Vec<FencePolygon>,
    /// Rally points: lat, lon, altitude.
    pub rally: Vec<(f64, f64, f64)>,
}

fn number(value: &Value) -> f64 {
    value.as_f64().unwrap_or(f64::NAN)
}

/// Reads a `.plan`; the message says what is missing or malformed.
pub fn read_plan(text: &str) -> Result<PlanFile, String> {
    let plan: Value = serde_json::from_str(text).map_err(|error| format!("not JSON: {error}"))?;
    if plan["fileType"] != "Plan" {
        return Err("fileType is not \"Plan\"".into());
    }
    let mission = &plan["mission"];
    let home = mission["plannedHomePosition"]
        .as_array()
        .filter(|home| home.len() == 3)
        .ok_or("mission.plannedHomePosition is not [lat, lon, alt]")?;
    let home = (number(&home[0]), number(&home[1]), number(&home[2]));
    let mut items = Vec::new();
    for (index, item) in mission["items"]
        .as_array()
        .ok_or("mission.items is not a list")?
        .iter()
        .enumerate()
    {
        if item["type"] != "SimpleItem" {
            return Err(format!("item {}: only SimpleItem is flown", index + 1));
        }
        let params = item["params"]
            .as_array()
            .filter(|params| params.len() == 7)
            .ok_or_else(|| format!("item {}: params is not 7 values", index + 1))?;
        let mut values = [f64::NAN; 7];
        for (slot, value) in values.iter_mut().zip(params) {
            *slot = number(value);
        }
        let command = item["command"]
            .as_u64()
            .and_then(|c| u16::try_from(c).ok())
            .ok_or_else(|| format!("item {}: command is not a number", index + 1))?;
        let frame = item["frame"]
            .as_u64()
            .and_then(|f| u8::try_from(f).ok())
            .ok_or_else(|| format!("item {}: frame is not a number", index + 1))?;
        items.push(FileItem {
            command,
            frame,
            params: values,
        });
    }
    let fence = plan["geoFence"]["polygons"]
        .as_array()
        .map(|polygons| {
            polygons
                .iter()
                .map(|polygon| FencePolygon {
                    inclusion: polygon["inclusion"].as_bool().unwrap_or(false),
                    corners: polygon["polygon"]
                        .as_array()
                        .map(|corners| {
                            corners
                                .iter()
                                .map(|corner| (number(&corner[0]), number(&corner[1])))
                                .collect()
                        })
                        .unwrap_or_default(),
                })
                .collect()
        })
        .unwrap_or_default();
    let rally = plan["rallyPoints"]["points"]
        .as_array()
        .map(|points| {
            points
                .iter()
                .map(|p| (number(&p[0]), number(&p[1]), number(&p[2])))
                .collect()
        })
        .unwrap_or_default();
    Ok(PlanFile {
        home,
        items,
        fence,
        rally,
    })
}

/// What a `.waypoints` file holds: home (row 0: lat, lon, altitude) and the items after it.
#[derive(Debug, Clone, PartialEq)]
pub struct WaypointsFile {
    /// Home from row 0: lat, lon (degrees) and altitude (metres).
    pub home: (f64, f64, f64),
    /// The rows after home, in file order.
    pub items: Vec<FileItem>,
}

/// Reads `QGC WPL 110` text.
pub fn read_waypoints(text: &str) -> Result<WaypointsFile, String> {
    let mut lines = text.lines();
    if lines.next().map(str::trim) != Some("QGC WPL 110") {
        return Err("the first line is not \"QGC WPL 110\"".into());
    }
    let mut rows = Vec::new();
    for (number, line) in lines.enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let columns: Vec<&str> = line.split('\t').collect();
        if columns.len() != 12 {
            return Err(format!(
                "line {}: {} columns, expected 12",
                number + 2,
                columns.len()
            ));
        }
        let parse = |k: usize| -> Result<f64, String> {
            let text = columns[k].trim();
            if text.eq_ignore_ascii_case("nan") {
                return Ok(f64::NAN);
            }
            text.parse::<f64>()
                .map_err(|_| format!("line {}: column {} is not a number", number + 2, k + 1))
        };
        let mut params = [f64::NAN; 7];
        for (k, slot) in params.iter_mut().enumerate() {
            *slot = parse(4 + k)?;
        }
        let frame = parse(2)?;
        let command = parse(3)?;
        rows.push(FileItem {
            command: command as u16,
            frame: frame as u8,
            params,
        });
    }
    let Some((home, items)) = rows.split_first() else {
        return Err("no home row".into());
    };
    Ok(WaypointsFile {
        home: (home.lat(), home.lon(), home.altitude()),
        items: items.to_vec(),
    })
}

/// Where a `.waypoints` file says something else than its `.plan`: one line per difference
/// (empty when they agree to the files' rounding).
pub fn differences(plan: &PlanFile, waypoints: &WaypointsFile) -> Vec<String> {
    let mut found = Vec::new();
    if plan.items.len() != waypoints.items.len() {
        found.push(format!(
            "{} items in the .plan, {} in the .waypoints",
            plan.items.len(),
            waypoints.items.len()
        ));
        return found;
    }
    let close =
        |a: f64, b: f64, tolerance: f64| (a.is_nan() && b.is_nan()) || (a - b).abs() <= tolerance;
    if !(close(plan.home.0, waypoints.home.0, 1e-7) && close(plan.home.1, waypoints.home.1, 1e-7)) {
        found.push("home differs between the .plan and the .waypoints".into());
    }
    for (index, (a, b)) in plan.items.iter().zip(&waypoints.items).enumerate() {
        let same = a.command == b.command
            && a.frame == b.frame
            && (0..7).all(|k| {
                let tolerance = if k == 4 || k == 5 { 1e-7 } else { 2e-3 };
                // A null in the .plan is written 0 in some .waypoints columns of DO items.
                close(a.params[k], b.params[k], tolerance)
                    || (a.params[k].is_nan() && b.params[k] == 0.0)
            });
        if !same {
            found.push(format!(
                "item {} differs between the .plan and the .waypoints",
                index + 1
            ));
        }
    }
    found
}

/// The folder's mission files, `sortie_NN.plan`, by sortie number. A file named like one
/// that is not (`sortie_01 copy.plan`, a ground station's second save) fails the read, as
/// does a missing number: flown as one more sortie, or skipped, it would change the verdict
/// of the files the drone will fly.
pub(super) fn sortie_files<'f>(
    files: &'f [(String, Vec<u8>)],
    read: &mut super::verdict::Tally,
) -> Vec<&'f String> {
    let mut numbered: Vec<(usize, &String)> = Vec::new();
    for (name, _) in files {
        let Some(middle) = name
            .strip_prefix("sortie_")
            .and_then(|rest| rest.strip_suffix(".plan"))
        else {
            continue;
        };
        match middle.parse::<usize>() {
            Ok(number) if middle.len() >= 2 && middle.bytes().all(|b| b.is_ascii_digit()) => {
                numbered.push((number, name));
            }
            _ => read.fail(format!(
                "{name} is not a mission file name agripath writes (sortie_NN.plan): move it out of the folder"
            )),
        }
    }
    numbered.sort();
    if numbered.is_empty() {
        read.fail("no mission file (sortie_NN.plan) to fly".into());
    }
    if let Some(pair) = numbered.windows(2).find(|pair| pair[0].0 == pair[1].0) {
        read.fail(format!(
            "{} and {} are both sortie {}: move one out of the folder",
            pair[0].1, pair[1].1, pair[0].0
        ));
    } else if let Some((expected, (_, name))) = (1..)
        .zip(&numbered)
        .find(|(expected, (number, _))| number != expected)
    {
        read.fail(format!(
            "{name}: sortie {expected} is missing (the files number the sorties 1, 2, … with none left out)"
        ));
    }
    numbered.into_iter().map(|(_, name)| name).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn waypoints_and_plan_are_read_and_compared() {
        let plan = r#"{"fileType":"Plan","mission":{"plannedHomePosition":[45.0,126.0,0.0],
            "items":[{"type":"SimpleItem","command":22,"frame":3,"params":[0,0,0,null,45.0,126.0,20.0]}]},
            "geoFence":{"polygons":[{"inclusion":true,"polygon":[[45,126],[45.1,126],[45,126.1]]}]},
            "rallyPoints":{"points":[[45.0,126.0,20.0]]}}"#;
        let plan = read_plan(plan).unwrap();
        assert_eq!(plan.items[0].command, 22);
        assert!(plan.items[0].params[3].is_nan());
        assert_eq!(plan.fence[0].corners.len(), 3);
        let waypoints = read_waypoints(
            "QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t45.0\t126.0\t0.0\t1\n1\t0\t3\t22\t0\t0\t0\tnan\t45.0\t126.0\t20.0\t1\n",
        )
        .unwrap();
        assert!(differences(&plan, &waypoints).is_empty());
        let changed = read_waypoints(
            "QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t45.0\t126.0\t0.0\t1\n1\t0\t0\t22\t0\t0\t0\tnan\t45.0\t126.0\t20.0\t1\n",
        )
        .unwrap();
        assert_eq!(differences(&plan, &changed).len(), 1);
        assert!(read_waypoints("QGC WPL 110\n1\t2\n").is_err());
        assert!(read_plan("{}").is_err());
    }
}
