//! Prints random track scenario SEED (seed 000's JSON format, task "R") for `agripath track`:
//! `cargo run --release -p agripath --example random_track_scenario -- 7 > random_7.json`
fn main() {
    let seed: u64 = std::env::args()
        .nth(1)
        .map_or(0, |text| text.parse().expect("a seed"));
    let value = agripath::track::random_scenario::json(seed);
    println!(
        "{}",
        serde_json::to_string_pretty(&value).expect("JSON values serialise")
    );
}
