//! What an optimizer minimises: a cost over a declared solution type.
//!
//! [`Problem`] is the general form: a problem names its `Solution` (a real vector, a
//! permutation with flips, a grid route, …), costs one, and can draw one at random. Every
//! optimizer is written against it (generic over the solution, like the random-search
//! baseline) or against one kind of solution: the continuous algorithms of
//! [`crate::algorithms`] take a [`BoxProblem`], a box of real vectors, which is a `Problem`
//! whose solution is `[f64]` (the blanket implementation below).

use std::borrow::Borrow;

use thiserror::Error;

use crate::random::{self, RunStream};

/// A minimisation problem over solutions of type `Solution`.
///
/// `Sync` because independent runs evaluate the same problem from several threads.
pub trait Problem: Sync {
    /// What is searched over, as the optimizer proposes it (`[f64]`, `[Step]`, …); the Runner
    /// keeps the best one as its owned form (`Vec<f64>`, …).
    type Solution: ?Sized + ToOwned<Owned: Clone + Send + Sync + std::fmt::Debug> + Sync;

    /// The cost of `solution` (lower is better; NaN counts as worst).
    fn evaluate(&self, solution: &Self::Solution) -> f64;

    /// A valid solution to report before anything is evaluated (the lower corner of a box,
    /// the identity order of a tour).
    fn first_solution(&self) -> SolutionOf<Self>;

    /// A solution drawn uniformly from the whole space, from the run's stream.
    fn random_solution(&self, stream: &mut RunStream) -> SolutionOf<Self>;
}

/// The owned form of a problem's solution (what an [`crate::Outcome`] holds).
pub type SolutionOf<P> = <<P as Problem>::Solution as ToOwned>::Owned;

/// A continuous problem: a cost over the box `bounds` of real vectors.
pub trait BoxProblem: Sync {
    /// The search box; its length is the dimension.
    fn bounds(&self) -> &Bounds;
    /// The cost of `x` (lower is better). `x` always lies inside `bounds()`.
    fn evaluate(&self, x: &[f64]) -> f64;
}

impl<B: BoxProblem + ?Sized> Problem for B {
    type Solution = [f64];

    fn evaluate(&self, solution: &[f64]) -> f64 {
        BoxProblem::evaluate(self, solution)
    }

    fn first_solution(&self) -> Vec<f64> {
        self.bounds().lower().to_vec()
    }

    fn random_solution(&self, stream: &mut RunStream) -> Vec<f64> {
        let bounds = self.bounds();
        (0..bounds.dimension())
            .map(|d| random::uniform_in(stream, bounds.lower()[d], bounds.upper()[d]))
            .collect()
    }
}

/// Borrows an owned solution as the problem's solution type.
pub fn as_solution<P: Problem + ?Sized>(owned: &SolutionOf<P>) -> &P::Solution {
    owned.borrow()
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
    /// No dimension at all.
    #[error("a search box needs at least one dimension")]
    Empty,
    /// `lower` and `upper` differ in length.
    #[error("lower and upper bounds have different lengths ({lower} and {upper})")]
    LengthMismatch {
        /// Length of the lower bounds.
        lower: usize,
        /// Length of the upper bounds.
        upper: usize,
    },
    /// A dimension whose bounds are not finite with lower < upper.
    #[error("dimension {dimension}: bounds [{lower}, {upper}] are not finite with lower < upper")]
    Invalid {
        /// The dimension, from 0.
        dimension: usize,
        /// Its lower bound.
        lower: f64,
        /// Its upper bound.
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

    /// The number of coordinates.
    pub fn dimension(&self) -> usize {
        self.lower.len()
    }

    /// The lower bound of every coordinate.
    pub fn lower(&self) -> &[f64] {
        &self.lower
    }

    /// The upper bound of every coordinate.
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
    /// The problem of minimising `cost` over `bounds`.
    pub fn new(bounds: Bounds, cost: F) -> Self {
        Self { bounds, cost }
    }
}

impl<F: Fn(&[f64]) -> f64 + Sync> BoxProblem for FnProblem<F> {
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
