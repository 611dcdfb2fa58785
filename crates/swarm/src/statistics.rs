//! The statistics of independent runs' final costs, as every table of the papers reports them
//! (best, worst, mean, sample standard deviation), the median and quartiles CEC reports add,
//! and the Wilcoxon rank-sum test between two algorithms' runs: one implementation for the
//! function benchmarks and the track planners.

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

/// The `q`-quantile (0 ≤ q ≤ 1) of `values` by linear interpolation between order
/// statistics (Hyndman and Fan's type 7, numpy's and R's default); NaN for no values.
pub fn quantile(values: &[f64], q: f64) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let position = q.clamp(0.0, 1.0) * (sorted.len() - 1) as f64;
    let below = position.floor() as usize;
    let above = position.ceil() as usize;
    let fraction = position - below as f64;
    if below == above {
        sorted[below]
    } else {
        sorted[below] + (sorted[above] - sorted[below]) * fraction
    }
}

/// The median of `values` (NaN for none).
pub fn median(values: &[f64]) -> f64 {
    quantile(values, 0.5)
}

/// The Wilcoxon rank-sum (Mann-Whitney U) test of two independent samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RankSum {
    /// W, the sum of the first sample's ranks in the pooled sample (ties get their mean rank).
    pub rank_sum: f64,
    /// z = (W − n1(n1 + n2 + 1)/2) / σ, σ² = n1·n2/12 · (n1 + n2 + 1 − Σ(t³ − t)/((n1 + n2)(n1 + n2 − 1)))
    /// with t the size of each group of ties; negative when the first sample tends lower.
    pub z: f64,
    /// The two-sided p-value 2·(1 − Φ(|z|)) of the normal approximation (1 when every value
    /// is tied, so that σ = 0).
    pub p_value: f64,
}

/// The rank-sum test of `first` against `second` with the normal approximation and the tie
/// correction, without continuity correction: scipy's
/// `mannwhitneyu(first, second, use_continuity=False, method="asymptotic")`, and, without
/// ties, `ranksums(first, second)`. `None` when a sample is empty.
pub fn rank_sum(first: &[f64], second: &[f64]) -> Option<RankSum> {
    if first.is_empty() || second.is_empty() {
        return None;
    }
    let (n1, n2) = (first.len() as f64, second.len() as f64);
    let mut pooled: Vec<(f64, bool)> = first
        .iter()
        .map(|&v| (v, true))
        .chain(second.iter().map(|&v| (v, false)))
        .collect();
    pooled.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (mut rank_sum, mut ties) = (0.0, 0.0);
    let mut start = 0;
    while start < pooled.len() {
        let mut end = start + 1;
        while end < pooled.len() && pooled[end].0 == pooled[start].0 {
            end += 1;
        }
        // Ranks start + 1 ..= end share their mean.
        let mean_rank = (start + 1 + end) as f64 / 2.0;
        let group = (end - start) as f64;
        ties += group * group * group - group;
        rank_sum += mean_rank * pooled[start..end].iter().filter(|(_, f)| *f).count() as f64;
        start = end;
    }
    let total = n1 + n2;
    let expected = n1 * (total + 1.0) / 2.0;
    let variance = if total > 1.0 {
        n1 * n2 / 12.0 * (total + 1.0 - ties / (total * (total - 1.0)))
    } else {
        0.0
    };
    if variance <= 0.0 {
        return Some(RankSum {
            rank_sum,
            z: 0.0,
            p_value: 1.0,
        });
    }
    let z = (rank_sum - expected) / variance.sqrt();
    // 2·(1 − Φ(|z|)) = erfc(|z|/√2), accurate far into the tail.
    let p_value = libm::erfc(z.abs() / std::f64::consts::SQRT_2).min(1.0);
    Some(RankSum {
        rank_sum,
        z,
        p_value,
    })
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

    #[test]
    fn quantiles_interpolate_as_numpy_does() {
        let values = [7.0, 1.0, 3.0, 5.0];
        assert_eq!(median(&values), 4.0);
        // numpy.quantile([1, 3, 5, 7], 0.25) = 2.5, 0.75 → 5.5.
        assert_eq!(quantile(&values, 0.25), 2.5);
        assert_eq!(quantile(&values, 0.75), 5.5);
        assert_eq!(median(&[2.0]), 2.0);
        assert!(median(&[]).is_nan());
    }

    #[test]
    fn the_rank_sum_matches_hand_computed_values() {
        // No ties: x = {1, 2, 3}, y = {4, 5, 6}: W = 6, E = 3·7/2 = 10.5, σ² = 9·7/12 = 5.25,
        // z = −4.5/√5.25; scipy.stats.ranksums gives z = −1.9639610121239315,
        // p = 0.049534613435626706.
        let test = rank_sum(&[1.0, 2.0, 3.0], &[4.0, 5.0, 6.0]).unwrap();
        assert_eq!(test.rank_sum, 6.0);
        assert!((test.z + 4.5 / 5.25f64.sqrt()).abs() < 1e-15);
        assert!((test.z + 1.963_961_012_123_931_5).abs() < 1e-14);
        assert!(
            (test.p_value - 0.049_534_613_435_626_706).abs() < 1e-15,
            "{test:?}"
        );
        // Ties: x = {1, 2, 2}, y = {2, 3, 3}: pooled ranks 1, 3, 3, 3, 5.5, 5.5; W = 7,
        // E = 10.5, Σ(t³ − t) = 24 + 6 = 30, σ² = 9/12·(7 − 30/30) = 4.5, z = −3.5/√4.5.
        let tied = rank_sum(&[1.0, 2.0, 2.0], &[2.0, 3.0, 3.0]).unwrap();
        assert_eq!(tied.rank_sum, 7.0);
        assert!((tied.z + 3.5 / 4.5f64.sqrt()).abs() < 1e-15);
        // scipy.stats.mannwhitneyu(…, use_continuity=False, method="asymptotic").
        assert!(
            (tied.p_value - 0.098_960_154_019_405_74).abs() < 1e-15,
            "{tied:?}"
        );
        // Symmetry: swapping the samples flips z and keeps p.
        let swapped = rank_sum(&[2.0, 3.0, 3.0], &[1.0, 2.0, 2.0]).unwrap();
        assert!((swapped.z + tied.z).abs() < 1e-15);
        assert!((swapped.p_value - tied.p_value).abs() < 1e-15);
        // Everything tied: no evidence at all.
        assert_eq!(rank_sum(&[1.0, 1.0], &[1.0]).unwrap().p_value, 1.0);
        assert!(rank_sum(&[], &[1.0]).is_none());
    }
}
