//! The rank-sum test against scipy's: `tests/data/rank_sum_scipy.json` holds samples and the
//! p-values `scipy.stats.mannwhitneyu(first, second, use_continuity=False,
//! method="asymptotic")` gave for them (the script beside it wrote it).

use swarm::statistics::rank_sum;

#[test]
fn p_values_agree_with_scipy() {
    let text = include_str!("data/rank_sum_scipy.json");
    let data: serde_json::Value = serde_json::from_str(text).unwrap();
    let cases = data["cases"].as_array().unwrap();
    assert!(cases.len() >= 7);
    let numbers = |value: &serde_json::Value| -> Vec<f64> {
        value
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    for case in cases {
        let (first, second) = (numbers(&case["first"]), numbers(&case["second"]));
        let expected = case["p_value"].as_f64().unwrap();
        let ours = rank_sum(&first, &second).unwrap().p_value;
        let error = (ours - expected).abs() / expected;
        assert!(error < 1e-9, "ours {ours}, scipy {expected}");
    }
}
