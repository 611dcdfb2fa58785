//! Numbers as the outputs carry them.

/// Rounds to a step so that reports are stable and readable (no 17-digit noise).
pub fn round(value: f64, step: f64) -> f64 {
    let rounded = (value / step).round() * step;
    // Strip the binary noise the multiplication leaves by printing through a short decimal.
    let decimals = (-step.log10()).ceil().max(0.0) as usize;
    format!("{rounded:.decimals$}").parse().unwrap_or(rounded)
}
