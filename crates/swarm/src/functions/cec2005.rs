//! CEC 2005 functions F1, F2, F3, F6 from the official data (Suganthan et al., "Problem
//! definitions and evaluation criteria for the CEC 2005 special session on real-parameter
//! optimization", KanGAL report 2005005; Suganthan et al. 2005, docs/references.md), z = x − o with o the published shift vector:
//!
//! - F1 shifted sphere:                      Σ z_i² − 450
//! - F2 shifted Schwefel 1.2:                Σ_i (Σ_{j≤i} z_j)² − 450 (the full sum, unlike opfunu)
//! - F3 shifted rotated high-conditioned elliptic, z = (x − o)·M (row vector times M):
//!   Σ_i (10⁶)^{(i−1)/(D−1)} z_i² − 450
//! - F6 shifted Rosenbrock, z = x − o + 1:   Σ_{i<D} [100 (z_i² − z_{i+1})² + (z_i − 1)²] + 390
//!
//! The data files are compiled in (`data/cec2005/`, ≤ 100 values per shift, M for D = 10, 30
//! and 50: the only dimensions at which F3 is defined).

use std::sync::OnceLock;

const SPHERE_SHIFT: &str = include_str!("../../../../data/cec2005/data_sphere.txt");
const SCHWEFEL_SHIFT: &str = include_str!("../../../../data/cec2005/data_schwefel_102.txt");
const ELLIPTIC_SHIFT: &str =
    include_str!("../../../../data/cec2005/data_high_cond_elliptic_rot.txt");
const ELLIPTIC_ROTATION_D10: &str = include_str!("../../../../data/cec2005/elliptic_M_D10.txt");
const ELLIPTIC_ROTATION_D30: &str = include_str!("../../../../data/cec2005/elliptic_M_D30.txt");
const ELLIPTIC_ROTATION_D50: &str = include_str!("../../../../data/cec2005/elliptic_M_D50.txt");
const ROSENBROCK_SHIFT: &str = include_str!("../../../../data/cec2005/data_rosenbrock.txt");

/// The largest dimension the published shift vectors allow.
pub const MAX_DIMENSION: usize = 100;
/// The dimensions whose rotation matrix for F3 is in the data.
pub const ROTATED_DIMENSIONS: [usize; 3] = [10, 30, 50];
/// The largest of them (the size of the evaluation's buffers).
const LARGEST_ROTATED: usize = 50;

struct Data {
    sphere: Vec<f64>,
    schwefel: Vec<f64>,
    elliptic: Vec<f64>,
    rosenbrock: Vec<f64>,
    /// Row-major D × D for each D of `ROTATED_DIMENSIONS`, in that order.
    rotations: [Vec<f64>; 3],
}

fn parse(text: &str) -> Vec<f64> {
    text.split_whitespace()
        .map(|word| word.parse().expect("compiled-in CEC 2005 data are numbers"))
        .collect()
}

fn data() -> &'static Data {
    static DATA: OnceLock<Data> = OnceLock::new();
    DATA.get_or_init(|| Data {
        sphere: parse(SPHERE_SHIFT),
        schwefel: parse(SCHWEFEL_SHIFT),
        elliptic: parse(ELLIPTIC_SHIFT),
        rosenbrock: parse(ROSENBROCK_SHIFT),
        rotations: [
            parse(ELLIPTIC_ROTATION_D10),
            parse(ELLIPTIC_ROTATION_D30),
            parse(ELLIPTIC_ROTATION_D50),
        ],
    })
}

/// The F1 shift vector o (its first D values are used at dimension D).
pub fn sphere_shift() -> &'static [f64] {
    &data().sphere
}

/// F1, shifted sphere.
pub fn shifted_sphere(x: &[f64]) -> f64 {
    let o = &data().sphere;
    x.iter().zip(o).map(|(x, o)| (x - o) * (x - o)).sum::<f64>() - 450.0
}

/// F2, shifted Schwefel 1.2.
pub fn shifted_schwefel_1_2(x: &[f64]) -> f64 {
    let o = &data().schwefel;
    let mut prefix = 0.0;
    let mut total = 0.0;
    for (x, o) in x.iter().zip(o) {
        prefix += x - o;
        total += prefix * prefix;
    }
    total - 450.0
}

/// F3, shifted rotated high-conditioned elliptic (D = 10, 30 or 50 only: elsewhere NaN,
/// which the engine counts as +∞; `TestFunction::check_dimension` refuses them first).
pub fn shifted_rotated_elliptic(x: &[f64]) -> f64 {
    let data = data();
    let dimension = x.len();
    let Some(which) = ROTATED_DIMENSIONS.iter().position(|&d| d == dimension) else {
        return f64::NAN;
    };
    let rotation = &data.rotations[which];
    let mut shifted = [0.0; LARGEST_ROTATED];
    for (i, value) in shifted.iter_mut().enumerate().take(dimension) {
        *value = x[i] - data.elliptic[i];
    }
    let mut rotated = [0.0; LARGEST_ROTATED];
    for (i, &s) in shifted.iter().enumerate().take(dimension) {
        let row = &rotation[i * dimension..(i + 1) * dimension];
        for (z, m) in rotated.iter_mut().zip(row) {
            *z += s * m;
        }
    }
    let denominator = (dimension - 1) as f64;
    rotated
        .iter()
        .take(dimension)
        .enumerate()
        .map(|(i, z)| 1e6_f64.powf(i as f64 / denominator) * z * z)
        .sum::<f64>()
        - 450.0
}

/// F6, shifted Rosenbrock.
pub fn shifted_rosenbrock(x: &[f64]) -> f64 {
    let o = &data().rosenbrock;
    let z: Vec<f64> = x.iter().zip(o).map(|(x, o)| x - o + 1.0).collect();
    z.windows(2)
        .map(|pair| 100.0 * (pair[0] * pair[0] - pair[1]).powi(2) + (pair[0] - 1.0).powi(2))
        .sum::<f64>()
        + 390.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_data_have_the_published_sizes() {
        let data = data();
        for shift in [
            &data.sphere,
            &data.schwefel,
            &data.elliptic,
            &data.rosenbrock,
        ] {
            assert_eq!(shift.len(), MAX_DIMENSION);
        }
        for (rotation, d) in data.rotations.iter().zip(ROTATED_DIMENSIONS) {
            assert_eq!(rotation.len(), d * d);
        }
    }

    #[test]
    fn the_rotation_matrices_are_orthogonal() {
        for (rotation, d) in data().rotations.iter().zip(ROTATED_DIMENSIONS) {
            for i in 0..d {
                for j in 0..d {
                    let dot: f64 = (0..d)
                        .map(|k| rotation[i * d + k] * rotation[j * d + k])
                        .sum();
                    let expected = if i == j { 1.0 } else { 0.0 };
                    assert!((dot - expected).abs() < 1e-9, "D = {d}, ({i}, {j}): {dot}");
                }
            }
        }
        assert!(shifted_rotated_elliptic(&[0.0; 20]).is_nan());
    }

    #[test]
    fn optima_are_at_the_shift_vectors() {
        let data = data();
        assert_eq!(shifted_sphere(&data.sphere[..50]), -450.0);
        assert_eq!(shifted_schwefel_1_2(&data.schwefel[..50]), -450.0);
        for d in ROTATED_DIMENSIONS {
            assert!((shifted_rotated_elliptic(&data.elliptic[..d]) + 450.0).abs() < 1e-9);
        }
        assert_eq!(shifted_rosenbrock(&data.rosenbrock[..50]), 390.0);
    }
}
