//! Cubic B-spline smoothing of a track (seed 002 §1.3, eqs. 3-10).
//!
//! The planned points P_0..P_m (start, waypoints, goal) are the curve's type points: the
//! uniform cubic B-spline through them has control points V_0..V_{m+2} with
//! - (7) P_i = (V_i + 4 V_{i+1} + V_{i+2}) / 6 for i = 0..m (every type point is on the curve),
//! - (8) V_0 = V_1 and V_{m+2} = V_{m+1} (the end conditions),
//!
//! a tridiagonal system solved per coordinate. Segment i (control points V_i..V_{i+3}) is
//! (9) P_i(u) = [(1 − u)³ V_i + (3u³ − 6u² + 4) V_{i+1} + (−3u³ + 3u² + 3u + 1) V_{i+2}
//! + u³ V_{i+3}] / 6, sampled at u = 0, 0.01, …, 1 (eq. 10); repeated joints are dropped.
//!
//! Eq. (9) as printed gives V_{i+1} the weight (−3x³ + 3x² − 3x + 1)/6, whose four weights do
//! not sum to 1; the standard basis above is what eq. (6)'s matrix gives. Eq. (7)'s indices
//! are shifted to make m + 1 equations for m + 3 unknowns with the two conditions of eq. (8).

/// The smoothed curve through `points`, 100 samples per span (the first point and the last
/// are the track's ends).
pub fn smooth(points: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let m = points.len().saturating_sub(1);
    if m < 2 {
        return points.to_vec();
    }
    let controls = control_points(points);
    let mut curve = Vec::with_capacity(100 * m + 1);
    for span in 0..m {
        let v = &controls[span..span + 4];
        for step in 0..100 {
            curve.push(evaluate(v, step as f64 / 100.0));
        }
    }
    curve.push(evaluate(&controls[m - 1..m + 3], 1.0));
    curve.dedup();
    curve
}

fn evaluate(v: &[[f64; 3]], u: f64) -> [f64; 3] {
    let weights = [
        (1.0 - u).powi(3) / 6.0,
        (3.0 * u.powi(3) - 6.0 * u * u + 4.0) / 6.0,
        (-3.0 * u.powi(3) + 3.0 * u * u + 3.0 * u + 1.0) / 6.0,
        u.powi(3) / 6.0,
    ];
    let mut point = [0.0; 3];
    for (control, weight) in v.iter().zip(weights) {
        for axis in 0..3 {
            point[axis] += weight * control[axis];
        }
    }
    point
}

/// Solves eqs. (7)-(8) for V_0..V_{m+2}. With V_0 = V_1 the first equation reads
/// 5 V_1 + V_2 = 6 P_0, and with V_{m+2} = V_{m+1} the last V_m + 5 V_{m+1} = 6 P_m: a
/// tridiagonal system in V_1..V_{m+1} (Thomas algorithm; diagonally dominant).
fn control_points(points: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let size = points.len(); // unknowns V_1..V_{m+1}
    let mut diagonal = vec![4.0; size];
    diagonal[0] = 5.0;
    diagonal[size - 1] = 5.0;
    let mut solution = vec![[0.0; 3]; size];
    for axis in 0..3 {
        let mut upper = vec![0.0; size];
        let mut right: Vec<f64> = points.iter().map(|p| 6.0 * p[axis]).collect();
        let mut pivot = diagonal.clone();
        upper[0] = 1.0 / pivot[0];
        right[0] /= pivot[0];
        for row in 1..size {
            pivot[row] = diagonal[row] - upper[row - 1];
            upper[row] = 1.0 / pivot[row];
            right[row] = (right[row] - right[row - 1]) / pivot[row];
        }
        solution[size - 1][axis] = right[size - 1];
        for row in (0..size - 1).rev() {
            solution[row][axis] = right[row] - upper[row] * solution[row + 1][axis];
        }
    }
    let mut controls = Vec::with_capacity(size + 2);
    controls.push(solution[0]);
    controls.extend_from_slice(&solution);
    controls.push(solution[size - 1]);
    controls
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_curve_passes_through_every_planned_point() {
        let points = [
            [0.0, 0.0, 20.0],
            [100.0, 50.0, 30.0],
            [200.0, -20.0, 25.0],
            [260.0, 80.0, 40.0],
            [400.0, 100.0, 35.0],
        ];
        let curve = smooth(&points);
        assert_eq!(curve.len(), 401);
        for (span, point) in points.iter().enumerate() {
            let on_curve = curve[(100 * span).min(curve.len() - 1)];
            for axis in 0..3 {
                assert!((on_curve[axis] - point[axis]).abs() < 1e-9, "span {span}");
            }
        }
    }

    #[test]
    fn a_straight_line_stays_straight() {
        let points = [
            [0.0, 0.0, 0.0],
            [1.0, 2.0, 3.0],
            [2.0, 4.0, 6.0],
            [3.0, 6.0, 9.0],
        ];
        for point in smooth(&points) {
            assert!(
                (point[1] - 2.0 * point[0]).abs() < 1e-9
                    && (point[2] - 3.0 * point[0]).abs() < 1e-9
            );
        }
    }
}
