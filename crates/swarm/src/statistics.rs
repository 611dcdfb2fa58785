//! The statistics of independent runs' final costs, as every table of the papers reports them
//! (best, worst, mean, sample standard deviation): one implementation for the function
//! benchmarks and the track planners.

/// Best, worst, mean and sample standard deviation of a set of values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spread {
    /// The lowest value (+∞ for none).
    pub best: f64,
    /// The highest value (−∞ for none).
    pub worst: f64,
    /// The mean (0 for none).
    pub mean: f64,
    /// The sample standard deviation, with n − 1 (0 for fewer than two values).
    pub standard_deviation: f64,
}

impl Spread {
    /// The spread of `values`.
    pub fn of(values: &[f64]) -> Self {
        let count = values.len().max(1) as f64;
        let mean = values.iter().sum::<f64>() / count;
        let variance = if values.len() > 1 {
            values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (count - 1.0)
        } else {
            0.0
        };
        Self {
            best: values.iter().copied().fold(f64::INFINITY, f64::min),
            worst: values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            mean,
            standard_deviation: variance.sqrt(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spread_of_a_few_values_is_the_textbook_one() {
        let spread = Spread::of(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]);
        assert_eq!((spread.best, spread.worst, spread.mean), (2.0, 9.0, 5.0));
        // Σ(v − 5)² = 32; 32 / 7.
        assert!((spread.standard_deviation - (32.0f64 / 7.0).sqrt()).abs() < 1e-15);
        let one = Spread::of(&[3.0]);
        assert_eq!((one.mean, one.standard_deviation), (3.0, 0.0));
        assert_eq!(Spread::of(&[]).mean, 0.0);
    }
}
