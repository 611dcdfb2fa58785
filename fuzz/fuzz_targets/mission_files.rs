#![no_main]
//! Any text as the mission files the preflight check reads back: a QGroundControl `.plan`
//! and a `QGC WPL 110` `.waypoints` (each parsed, then compared when both parse).
use agripath::preflight::read_back::{differences, read_plan, read_waypoints};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let plan = read_plan(text);
    let waypoints = read_waypoints(text);
    if let (Ok(plan), Ok(waypoints)) = (plan, waypoints) {
        let _ = differences(&plan, &waypoints);
    }
});
