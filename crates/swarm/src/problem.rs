//! What an optimizer minimises: a cost over a box of real vectors.

use thiserror::Error;

/// A minimisation problem over the box `bounds`.
///
/// `Sync` because independent runs evaluate the same problem from several threads.
pub trait Problem: Sync {
    /// The search box; its length is the dimension.
    fn bounds(&self) -> &Bounds;
    /// The cost of `x` (lower is better). `x` always lies inside `bounds()`.
    fn evaluate(&self, x: &[f64]) -> f64;
}

/// A box `lower[d] ≤ x[d] ≤ upper[d]`, valid by construction (finite, lower < upper).
#[derive(Debug, Clone, PartialEq)]
pub struct Bounds {
    lower: Vec<f64>,
    upper: Vec<f64>,
}

/// Why a box was refused.
#[derive(Debug, Error, PartialEq)]
pub enum BoundsError {
    #[error("a search box needs at least one dimension")]
    Empty,
    #[error("lower and upper bounds have different lengths ({lower} and {upper})")]
    LengthMismatch { lower: usize, upper: usize },
    #[error("dimension {dimension}: bounds [{lower}, {upper}] are not finite with lower < upper")]
    Invalid {
        dimension: usize,
        lower: f64,
        upper: f64,
    },
}

impl Bounds {
    /// A box from per-dimension bounds.
    pub fn new(lower: Vec<f64>, upper: Vec<f64>) -> Result<Self, BoundsError> {
        if lower.len() != upper.len() {
            return Err(BoundsError::LengthMismatch {
                lower: lower.len(),
                upper: upper.len(),
            });
        }
        if lower.is_empty() {
            return Err(BoundsError::Empty);
        }
        for (dimension, (&low, &high)) in lower.iter().zip(&upper).enumerate() {
            if !(low.is_finite() && high.is_finite() && low < high) {
                return Err(BoundsError::Invalid {
                    dimension,
                    lower: low,
                    upper: high,
                });
            }
        }
        Ok(Self { lower, upper })
    }

    /// The cube `[low, high]^dimension`.
    pub fn cube(dimension: usize, low: f64, high: f64) -> Result<Self, BoundsError> {
        Self::new(vec![low; dimension], vec![high; dimension])
    }

    pub fn dimension(&self) -> usize {
        self.lower.len()
    }

    pub fn lower(&self) -> &[f64] {
        &self.lower
    }

    pub fn upper(&self) -> &[f64] {
        &self.upper
    }

    /// `upper − lower` in dimension `d`.
    pub fn width(&self, d: usize) -> f64 {
        self.upper[d] - self.lower[d]
    }

    /// Moves every coordinate of `x` to the nearest point of the box.
    pub fn clamp(&self, x: &mut [f64]) {
        for ((value, &low), &high) in x.iter_mut().zip(&self.lower).zip(&self.upper) {
            *value = value.clamp(low, high);
        }
    }

    /// Whether `x` lies in the box.
    pub fn contains(&self, x: &[f64]) -> bool {
        x.len() == self.dimension()
            && x.iter()
                .zip(&self.lower)
                .zip(&self.upper)
                .all(|((value, &low), &high)| (low..=high).contains(value))
    }
}

/// Any closure over a box is a problem: `FnProblem::new(bounds, |x| ...)`.
pub struct FnProblem<F> {
    bounds: Bounds,
    cost: F,
}

impl<F: Fn(&[f64]) -> f64 + Sync> FnProblem<F> {
    pub fn new(bounds: Bounds, cost: F) -> Self {
        Self { bounds, cost }
    }
}

impl<F: Fn(&[f64]) -> f64 + Sync> Problem for FnProblem<F> {
    fn bounds(&self) -> &Bounds {
        &self.bounds
    }

    fn evaluate(&self, x: &[f64]) -> f64 {
        (self.cost)(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_boxes_are_refused() {
        assert_eq!(Bounds::cube(0, 0.0, 1.0), Err(BoundsError::Empty));
        assert!(matches!(
            Bounds::new(vec![0.0], vec![1.0, 2.0]),
            Err(BoundsError::LengthMismatch { .. })
        ));
        assert!(Bounds::cube(2, 1.0, 1.0).is_err());
        assert!(Bounds::cube(2, f64::NAN, 1.0).is_err());
        assert!(Bounds::cube(2, 0.0, f64::INFINITY).is_err());
    }

    #[test]
    fn clamp_moves_into_the_box() {
        let bounds = Bounds::cube(3, -1.0, 1.0).unwrap();
        let mut x = [-5.0, 0.5, 7.0];
        bounds.clamp(&mut x);
        assert_eq!(x, [-1.0, 0.5, 1.0]);
        assert!(bounds.contains(&x));
    }
}
