//! Seeded, independent random streams: one per run.
//!
//! Every stochastic result must be reproducible from one seed, and runs must be independent
//! streams so that running them in parallel gives the same numbers as in series (MISSION.md
//! decision 10). Run `k` of seed `s` is xoshiro256++ seeded from `s` and advanced by `k`
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
