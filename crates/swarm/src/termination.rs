//! When a run stops: the budgets of the one loop ([`crate::runner`]).

use std::time::Duration;

use thiserror::Error;

/// When a run stops: at whichever configured limit comes first. At least one budget
/// (iterations, evaluations or time) is required; a target alone might never be reached.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Termination {
    /// Stop after this many steps (iterations, generations).
    pub max_iterations: Option<usize>,
    /// Stop once this many costs have been computed.
    pub max_evaluations: Option<u64>,
    /// Stop as soon as the best cost is at or below this value.
    pub target_cost: Option<f64>,
    /// Wall-clock limit. Results then depend on the machine: not reproducible from the seed.
    pub time_limit: Option<Duration>,
}

/// Why a termination was refused.
#[derive(Debug, Error, PartialEq)]
pub enum TerminationError {
    /// No iteration, evaluation or time limit is set.
    #[error("a run needs a budget: iterations, evaluations or a time limit")]
    NoBudget,
    /// A budget of zero.
    #[error("a budget of zero iterations or evaluations runs nothing")]
    ZeroBudget,
}

impl Termination {
    /// Stop after `iterations` steps.
    pub fn iterations(iterations: usize) -> Self {
        Self {
            max_iterations: Some(iterations),
            ..Self::default()
        }
    }

    /// Stop once `evaluations` costs have been computed.
    pub fn evaluations(evaluations: u64) -> Self {
        Self {
            max_evaluations: Some(evaluations),
            ..Self::default()
        }
    }

    /// Also stop at `evaluations` (whichever limit comes first).
    pub fn and_evaluations(mut self, evaluations: u64) -> Self {
        self.max_evaluations = Some(evaluations);
        self
    }

    /// Also stop when the best cost reaches `target`.
    pub fn and_target(mut self, target: f64) -> Self {
        self.target_cost = Some(target);
        self
    }

    /// Also stop after `limit` of wall time (results then depend on the machine).
    pub fn and_time_limit(mut self, limit: Duration) -> Self {
        self.time_limit = Some(limit);
        self
    }

    /// Refuses a termination without a budget, or with a zero budget.
    pub fn validate(&self) -> Result<(), TerminationError> {
        if self.max_iterations.is_none()
            && self.max_evaluations.is_none()
            && self.time_limit.is_none()
        {
            return Err(TerminationError::NoBudget);
        }
        if self.max_iterations == Some(0) || self.max_evaluations == Some(0) {
            return Err(TerminationError::ZeroBudget);
        }
        Ok(())
    }
}
