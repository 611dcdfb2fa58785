//! Open paths against an outside solver (issue 19, decision 0018's seventh and eighth steps):
//! on the farms of `benches/ordering_vs_lkh.py` where `best` was trapped 2-5 % above LKH-3
//! (irregular farms 04 and 08 before each field's stretch was ordered again, 12 and the seed
//! 001 farm before the chain of whole field blocks), its open path stays within 1 % of
//! LKH-3's. The references are LKH-3's open paths on the same eq. (8) matrices (elkai, 10 runs
//! in each of two integer encodings, the cheaper kept; the pass pairs forced adjacent and a
//! dummy node for the free ends), recorded from the script's run of 2026-12-05: LKH is not a
//! dependency of the tests, and its result on a fixed matrix does not change.
//!
//! It holds one trajectory of the search, the default seed's, not a property of every seed
//! (irregular_08 with seed 2 is 1.053 × LKH, before this step and after it): a change to the
//! search's random stream may move these two farms either way, and should then be measured
//! on the whole benchmark (`benches/ordering_vs_lkh.py`) before these figures are touched.

use agripath::coverage::{plan_coverage, CoveragePlan, CoverageSettings};
use agripath::model::Vehicle;
use agripath::sequence::tour::Start;
use agripath::sequence::{route, Sequencer, TransferModel};
use agripath::terrain::Flat;

/// Our open path on `irregular_farm(seed, target, 5.0)` as `bench_sequence --lkh-only` lays it
/// out (no edge passes, flat ground, the default vehicle, h = 18 m), in metres of eq. (8).
fn open_path_m(seed: u64, target: usize) -> (usize, f64) {
    let farm = agripath::bench::farms::irregular_farm(seed, target, 5.0);
    let settings = CoverageSettings {
        headland_passes: 0,
        ..CoverageSettings::default()
    };
    let plan = plan_coverage(&farm, &Flat::new(0.0), &Vehicle::default(), &settings).unwrap();
    let model = TransferModel::new(&farm, 18.0);
    flown_open(&plan, &model)
}

/// The passes of `plan` and the cost of our open path over them.
fn flown_open(plan: &CoveragePlan, model: &TransferModel) -> (usize, f64) {
    let passes = plan
        .fields
        .iter()
        .map(|field| field.swaths.len() + field.edges.len())
        .sum();
    let flown = route(plan, model, Start::Open, &Sequencer::default());
    (passes, flown.tour_cost_m)
}

#[test]
fn open_paths_on_trapped_farms_are_within_one_per_cent_of_lkh() {
    // (seed, swath target, passes, LKH-3's open path in metres)
    for (seed, target, passes, lkh_m) in [
        (4, 230, 238, 3038.4),
        (8, 230, 200, 2353.2),
        (12, 230, 249, 3049.6),
    ] {
        let (counted, ours) = open_path_m(seed, target);
        assert_eq!(
            counted, passes,
            "irregular_{seed:02}'s layout moved: re-run LKH"
        );
        assert!(
            ours <= 1.01 * lkh_m,
            "irregular_{seed:02}: {ours:.1} m against LKH-3's {lkh_m:.1} m"
        );
    }
}

#[test]
fn the_seed_001_farms_open_path_is_within_one_per_cent_of_lkh() {
    // The embedded seed 001 farm planned by default (headland passes, the layout's own
    // headings), as `bench_sequence`'s "seed001_farm": LKH-3's open path is 1,377.7 m; the
    // whole path's chain alone flies 1,448.2 m (1.051 ×).
    let scenario = agripath::demo::scenario().unwrap();
    let plan = plan_coverage(
        &scenario.farm,
        scenario.terrain.as_ref(),
        &scenario.vehicle,
        &CoverageSettings::default(),
    )
    .unwrap();
    let model = TransferModel::new(&scenario.farm, scenario.vehicle.safe_height_m);
    let (passes, ours) = flown_open(&plan, &model);
    assert_eq!(passes, 147, "the seed 001 farm's layout moved: re-run LKH");
    assert!(
        ours <= 1.01 * 1377.7,
        "seed 001 farm: {ours:.1} m against LKH-3's 1377.7 m"
    );
}
