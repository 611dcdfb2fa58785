//! The classical functions of seed 000 Table 1 (definitions in
//! `../shared/reference/track-anchors.md` §4.2, with their sources).

use std::f64::consts::PI;

/// Schwefel 2.22: Σ|x_i| + Π|x_i|; 0 at the origin.
pub fn schwefel_2_22(x: &[f64]) -> f64 {
    let sum: f64 = x.iter().map(|v| v.abs()).sum();
    let product: f64 = x.iter().map(|v| v.abs()).product();
    sum + product
}

/// Ackley N.4 (Jamil and Yang 2013, no. 4):
/// Σ_{i<D} [e^{−0.2}·√(x_i² + x_{i+1}²) + 3·(cos 2x_i + sin 2x_{i+1})].
/// No closed-form optimum at D = 50; at D = 2 about −4.590101 near (−1.51, −0.755).
pub fn ackley_4(x: &[f64]) -> f64 {
    let decay = (-0.2_f64).exp();
    x.windows(2)
        .map(|pair| {
            let (a, b) = (pair[0], pair[1]);
            decay * (a * a + b * b).sqrt() + 3.0 * ((2.0 * a).cos() + (2.0 * b).sin())
        })
        .sum()
}

/// Levy (Surjanovic and Bingham form), w_i = 1 + (x_i − 1)/4:
/// sin²(πw_1) + Σ_{i<D} (w_i − 1)²[1 + 10 sin²(πw_i + 1)] + (w_D − 1)²[1 + sin²(2πw_D)]; 0 at x = 1.
pub fn levy(x: &[f64]) -> f64 {
    let w: Vec<f64> = x.iter().map(|v| 1.0 + (v - 1.0) / 4.0).collect();
    let last = w[w.len() - 1];
    let middle: f64 = w[..w.len() - 1]
        .iter()
        .map(|wi| (wi - 1.0).powi(2) * (1.0 + 10.0 * (PI * wi + 1.0).sin().powi(2)))
        .sum();
    (PI * w[0]).sin().powi(2)
        + middle
        + (last - 1.0).powi(2) * (1.0 + (2.0 * PI * last).sin().powi(2))
}

/// u(x, a, k, m) of the penalized functions.
fn penalty(x: f64, a: f64, k: f64, m: i32) -> f64 {
    if x > a {
        k * (x - a).powi(m)
    } else if x < -a {
        k * (-x - a).powi(m)
    } else {
        0.0
    }
}

/// Generalized penalized 1 (Yao, Liu and Lin 1999, F12), y_i = 1 + (x_i + 1)/4:
/// (π/D){10 sin²(πy_1) + Σ_{i<D} (y_i − 1)²[1 + 10 sin²(πy_{i+1})] + (y_D − 1)²} + Σ u(x_i, 10, 100, 4);
/// 0 at x = −1.
pub fn penalized_1(x: &[f64]) -> f64 {
    let y: Vec<f64> = x.iter().map(|v| 1.0 + (v + 1.0) / 4.0).collect();
    let dimension = x.len() as f64;
    let middle: f64 = y
        .windows(2)
        .map(|pair| (pair[0] - 1.0).powi(2) * (1.0 + 10.0 * (PI * pair[1]).sin().powi(2)))
        .sum();
    let last = y[y.len() - 1];
    PI / dimension * (10.0 * (PI * y[0]).sin().powi(2) + middle + (last - 1.0).powi(2))
        + x.iter().map(|&v| penalty(v, 10.0, 100.0, 4)).sum::<f64>()
}

/// Generalized penalized 2 (Yao, Liu and Lin 1999, F13):
/// 0.1{sin²(3πx_1) + Σ_{i<D} (x_i − 1)²[1 + sin²(3πx_{i+1})] + (x_D − 1)²[1 + sin²(2πx_D)]}
/// + Σ u(x_i, 5, 100, 4); 0 at x = 1.
pub fn penalized_2(x: &[f64]) -> f64 {
    let middle: f64 = x
        .windows(2)
        .map(|pair| (pair[0] - 1.0).powi(2) * (1.0 + (3.0 * PI * pair[1]).sin().powi(2)))
        .sum();
    let last = x[x.len() - 1];
    0.1 * ((3.0 * PI * x[0]).sin().powi(2)
        + middle
        + (last - 1.0).powi(2) * (1.0 + (2.0 * PI * last).sin().powi(2)))
        + x.iter().map(|&v| penalty(v, 5.0, 100.0, 4)).sum::<f64>()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn optima_are_zero_where_the_definitions_put_them() {
        assert_eq!(schwefel_2_22(&[0.0; 50]), 0.0);
        assert!(levy(&[1.0; 50]).abs() < 1e-28);
        assert!(penalized_1(&[-1.0; 50]).abs() < 1e-28);
        assert!(penalized_2(&[1.0; 50]).abs() < 1e-28);
    }

    #[test]
    fn ackley_4_at_two_dimensions_matches_the_published_minimum() {
        let value = ackley_4(&[-1.51, -0.755]);
        assert!((value + 4.5901).abs() < 1e-3, "{value}");
    }

    #[test]
    fn penalties_start_outside_their_band() {
        assert_eq!(penalty(10.0, 10.0, 100.0, 4), 0.0);
        assert_eq!(penalty(12.0, 10.0, 100.0, 4), 1600.0);
        assert_eq!(penalty(-12.0, 10.0, 100.0, 4), 1600.0);
    }
}
