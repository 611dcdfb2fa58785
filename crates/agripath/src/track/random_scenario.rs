//! Track scenarios nobody here drew, for tests and benchmarks: seed 000's composite formula
//! with other hills, 6-14 threat cylinders across the start-goal corridor, start and goal on
//! the ground, a height band of 30-150 m above the ground.
//!
//! Each scenario is written in seed 000's JSON format (one task, "R"), so that it goes
//! through the same reader as a user's file, and is a pure function of its seed (SplitMix64
//! and xoshiro-free: one small generator here, so the scenarios never change with a crate).

use serde_json::{json, Value};

use crate::terrain::composite::Hill;
use crate::terrain::{Composite, Extent, Terrain};

/// SplitMix64: enough for drawing scenarios, and stable for ever.
struct Draw(u64);

impl Draw {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [low, high).
    fn uniform(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The side of the square area, metres.
pub const SIDE_M: f64 = 1000.0;

/// Scenario `seed` as seed 000 JSON.
pub fn json(seed: u64) -> Value {
    let mut draw = Draw(seed ^ 0x5EED_0016);
    let hill_count = 5 + (draw.next() % 5) as usize;
    let hills: Vec<Hill> = (0..hill_count)
        .map(|_| Hill {
            height_m: draw.uniform(30.0, 140.0),
            x_m: draw.uniform(0.0, SIDE_M),
            y_m: draw.uniform(0.0, SIDE_M),
            spread_x_m: draw.uniform(70.0, 260.0),
            spread_y_m: draw.uniform(70.0, 260.0),
        })
        .collect();
    let coefficients = [
        draw.uniform(0.0, 20.0),
        draw.uniform(0.1, 0.3),
        draw.uniform(0.05, 0.15),
        draw.uniform(0.3, 0.9),
        draw.uniform(0.5, 1.5),
        draw.uniform(0.05, 0.15),
        draw.uniform(0.05, 0.15),
    ];
    let terrain = Composite {
        coefficients,
        hills: hills.clone(),
        height_scale: 1.0,
        extent: Extent {
            min_x: 0.0,
            min_y: 0.0,
            max_x: SIDE_M,
            max_y: SIDE_M,
        },
    };
    // Start and goal near opposite corners, on the ground.
    let corner = draw.next() % 4;
    let (mut sx, mut sy) = (draw.uniform(50.0, 200.0), draw.uniform(50.0, 200.0));
    let (mut gx, mut gy) = (
        SIDE_M - draw.uniform(50.0, 200.0),
        SIDE_M - draw.uniform(50.0, 200.0),
    );
    if corner % 2 == 1 {
        (sx, gx) = (SIDE_M - sx, SIDE_M - gx);
    }
    if corner >= 2 {
        (sx, sy, gx, gy) = (gx, gy, sx, sy);
    }
    let ground = |x: f64, y: f64| terrain.height_m(x, y).expect("inside the area");
    // Threats across the corridor, clear of the start and the goal.
    let threat_count = 6 + (draw.next() % 9) as usize;
    let mut threats: Vec<[f64; 3]> = Vec::new();
    while threats.len() < threat_count {
        let along = draw.uniform(0.15, 0.85);
        let across = draw.uniform(-220.0, 220.0);
        let radius = draw.uniform(30.0, 80.0);
        let (dx, dy) = (gx - sx, gy - sy);
        let length = dx.hypot(dy);
        let x = sx + along * dx - across * dy / length;
        let y = sy + along * dy + across * dx / length;
        let clear_of = |px: f64, py: f64| (x - px).hypot(y - py) > radius + 40.0;
        if (0.0..SIDE_M).contains(&x)
            && (0.0..SIDE_M).contains(&y)
            && clear_of(sx, sy)
            && clear_of(gx, gy)
        {
            threats.push([round(x), round(y), round(radius)]);
        }
    }
    json!({
        "name": format!("random scenario {seed}"),
        "source": "agripath's generator of track scenarios (track/random_scenario.rs)",
        "terrain": {
            "kind": "composite",
            "coefficients": {"a": coefficients[0], "b": coefficients[1], "c": coefficients[2],
                             "d": coefficients[3], "e": coefficients[4], "f": coefficients[5],
                             "g": coefficients[6]},
            "hills": {
                "h": hills.iter().map(|hill| hill.height_m).collect::<Vec<_>>(),
                "x": hills.iter().map(|hill| hill.x_m).collect::<Vec<_>>(),
                "y": hills.iter().map(|hill| hill.y_m).collect::<Vec<_>>(),
                "xs": hills.iter().map(|hill| hill.spread_x_m).collect::<Vec<_>>(),
                "ys": hills.iter().map(|hill| hill.spread_y_m).collect::<Vec<_>>(),
            },
            "extent_m": [SIDE_M, SIDE_M, 600.0],
        },
        "height_band_agl_m": [30.0, 150.0],
        "free_waypoints": 12,
        "algorithms": {"population": 500, "iterations": 300},
        "tasks": [{
            "name": "R",
            "start": [sx, sy, ground(sx, sy)],
            "goal": [gx, gy, ground(gx, gy)],
            "threat_cylinders_x_y_r": threats,
        }],
    })
}

fn round(value: f64) -> f64 {
    (value * 10.0).round() / 10.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::TrackScenario;

    #[test]
    fn random_scenarios_read_back_with_their_own_hills_and_the_ends_on_the_ground() {
        for seed in 0..5 {
            let value = json(seed);
            let text = serde_json::to_string(&value).unwrap();
            let directory =
                std::env::temp_dir().join(format!("agripath-random-{seed}-{}", std::process::id()));
            std::fs::create_dir_all(&directory).unwrap();
            let path = directory.join("scenario.json");
            std::fs::write(&path, text).unwrap();
            let scenario = TrackScenario::read(&path, Some("R")).unwrap();
            std::fs::remove_dir_all(&directory).unwrap();
            assert!((6..=14).contains(&scenario.threats.len()));
            assert!(scenario.takes_off() && scenario.lands());
            // The planners' ground is this file's formula, not seed 000's hills.
            let hills = &value["terrain"]["hills"];
            let (x, y) = (
                hills["x"][0].as_f64().unwrap(),
                hills["y"][0].as_f64().unwrap(),
            );
            let truth = scenario.true_ground(x, y).unwrap();
            assert!((scenario.terrain.height(x, y) - truth).abs() < 0.6);
            assert!(truth >= hills["h"][0].as_f64().unwrap() - 1.0);
            assert_eq!(json(seed), value, "a pure function of its seed");
        }
    }
}
