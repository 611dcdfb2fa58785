//! Coverage of the default layout (one edge pass) against the seed's layout on 200 random
//! star-shaped fields with up to three holes (w = 5 m, flat ground). Run:
//!
//! ```sh
//! cargo run --release -p agripath --example coverage_random_fields
//! ```

use agripath::coverage::{cover_field, CoverageSettings};
use agripath::terrain::Flat;
use geo::{Coord, LineString, MultiPolygon, Polygon};
use swarm::random::{below, run_stream};

fn uniform(stream: &mut swarm::RunStream, low: f64, high: f64) -> f64 {
    low + (high - low) * swarm::uniform(stream)
}

fn star(
    stream: &mut swarm::RunStream,
    centre: (f64, f64),
    low: f64,
    high: f64,
    count: usize,
) -> LineString<f64> {
    let mut points: Vec<Coord<f64>> = (0..count)
        .map(|index| {
            let angle = index as f64 / count as f64 * std::f64::consts::TAU;
            let radius = uniform(stream, low, high);
            Coord {
                x: centre.0 + radius * angle.cos(),
                y: centre.1 + radius * angle.sin(),
            }
        })
        .collect();
    points.push(points[0]);
    LineString::new(points)
}

fn main() {
    let (mut ours_min, mut seed_min, mut ours_sum, mut seed_sum, mut overlap_sum, mut outside_max) =
        (1.0f64, 1.0f64, 0.0, 0.0, 0.0, 0.0f64);
    let fields = 200;
    for index in 0..fields {
        let mut stream = run_stream(2026, index);
        let count = 5 + below(&mut stream, 9);
        let shell = star(&mut stream, (0.0, 0.0), 80.0, 150.0, count);
        let holes = (0..below(&mut stream, 4))
            .map(|hole| {
                let angle = hole as f64 * std::f64::consts::TAU / 3.0;
                let count = 3 + below(&mut stream, 4);
                star(
                    &mut stream,
                    (40.0 * angle.cos(), 40.0 * angle.sin()),
                    4.0,
                    12.0,
                    count,
                )
            })
            .collect();
        let sprayable = MultiPolygon::new(vec![Polygon::new(shell, holes)]);
        let ours = cover_field(
            0,
            "f",
            &sprayable,
            &Flat::new(0.0),
            5.0,
            &CoverageSettings::default(),
        )
        .unwrap();
        let seed_settings = CoverageSettings {
            headland_passes: 0,
            ..CoverageSettings::default()
        };
        let seed = cover_field(0, "f", &sprayable, &Flat::new(0.0), 5.0, &seed_settings).unwrap();
        ours_min = ours_min.min(ours.measure.covered_fraction);
        seed_min = seed_min.min(seed.measure.covered_fraction);
        ours_sum += ours.measure.covered_fraction;
        seed_sum += seed.measure.covered_fraction;
        overlap_sum += ours.measure.overlap_m2 / ours.measure.sprayable_area_m2;
        outside_max = outside_max.max(ours.measure.outside_m2 / ours.measure.sprayable_area_m2);
    }
    let n = fields as f64;
    println!("{fields} random fields with holes, w = 5 m:");
    println!("  ours (1 edge pass): covered mean {:.3} %, min {:.3} %; overlap mean {:.2} % of the area; outside max {:.5} %",
        100.0 * ours_sum / n, 100.0 * ours_min, 100.0 * overlap_sum / n, 100.0 * outside_max);
    println!(
        "  seed layout:        covered mean {:.3} %, min {:.3} %",
        100.0 * seed_sum / n,
        100.0 * seed_min
    );
}
