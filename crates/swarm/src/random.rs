//! Seeded, independent random streams: one per run.
//!
//! Every stochastic result must be reproducible from one seed, and runs must be independent
//! streams so that running them in parallel gives the same numbers as in series (contract
//! decision 10, docs/contract.md). Run `k` of seed `s` is xoshiro256++ seeded from `s` and advanced by `k`
//! jumps of 2^128 steps: the streams never overlap in any realistic use, and run `k` does
//! not depend on whether runs `0..k` were ever drawn.

use rand_xoshiro::rand_core::SeedableRng;
pub use rand_xoshiro::Xoshiro256PlusPlus as RunStream;

/// The random stream of run `run` under `seed`.
pub fn run_stream(seed: u64, run: u64) -> RunStream {
    let mut stream = RunStream::seed_from_u64(seed);
    for _ in 0..run {
        stream.jump();
    }
    stream
}

/// Draws from a stream (the trait that gives `next_u64`).
pub use rand_xoshiro::rand_core::Rng;

/// A uniform draw in [0, 1) with 53 random bits.
pub fn uniform(stream: &mut RunStream) -> f64 {
    (stream.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

/// A uniform draw in [low, high).
pub fn uniform_in(stream: &mut RunStream, low: f64, high: f64) -> f64 {
    low + (high - low) * uniform(stream)
}

/// A standard normal draw (Box-Muller; one of the pair is used so that every draw costs the
/// same two uniforms and a stream's position never depends on an earlier call's parity).
pub fn normal(stream: &mut RunStream) -> f64 {
    // 1 - u lies in (0, 1]: the logarithm is finite.
    let radius = (-2.0 * (1.0 - uniform(stream)).ln()).sqrt();
    radius * (std::f64::consts::TAU * uniform(stream)).cos()
}

/// A standard Cauchy draw (L-SHADE's scale factor).
pub fn cauchy(stream: &mut RunStream) -> f64 {
    (std::f64::consts::PI * (uniform(stream) - 0.5)).tan()
}

/// A uniform draw in 0..n (n > 0), by Lemire's multiply-shift (bias below 2⁻⁶⁴·n).
pub fn below(stream: &mut RunStream, n: usize) -> usize {
    ((u128::from(stream.next_u64()) * n as u128) >> 64) as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    fn first_draws(mut stream: RunStream) -> Vec<u64> {
        (0..8).map(|_| stream.next_u64()).collect()
    }

    #[test]
    fn normal_draws_have_unit_spread() {
        let mut stream = run_stream(3, 0);
        let draws: Vec<f64> = (0..20_000).map(|_| normal(&mut stream)).collect();
        let mean = draws.iter().sum::<f64>() / draws.len() as f64;
        let variance = draws.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / draws.len() as f64;
        assert!(mean.abs() < 0.03, "mean {mean}");
        assert!((variance - 1.0).abs() < 0.05, "variance {variance}");
    }

    #[test]
    fn same_seed_and_run_give_the_same_stream() {
        assert_eq!(first_draws(run_stream(7, 3)), first_draws(run_stream(7, 3)));
    }

    #[test]
    fn runs_and_seeds_differ() {
        let base = first_draws(run_stream(7, 0));
        assert_ne!(base, first_draws(run_stream(7, 1)));
        assert_ne!(base, first_draws(run_stream(8, 0)));
    }

    #[test]
    fn a_run_does_not_depend_on_the_runs_before_it() {
        // Drawing from run 0 first must not change run 2 (parallel = serial).
        let mut earlier = run_stream(11, 0);
        for _ in 0..1000 {
            earlier.next_u64();
        }
        assert_eq!(
            first_draws(run_stream(11, 2)),
            first_draws(run_stream(11, 2))
        );
        let mut jumped = RunStream::seed_from_u64(11);
        jumped.jump();
        jumped.jump();
        assert_eq!(first_draws(run_stream(11, 2)), first_draws(jumped));
    }
}
