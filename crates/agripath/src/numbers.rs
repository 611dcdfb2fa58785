//! Numbers as the outputs carry them.

/// Rounds to a step so that reports are stable and readable (no 17-digit noise).
pub fn round(value: f64, step: f64) -> f64 {
    let rounded = (value / step).round() * step;
    // Strip the binary noise the multiplication leaves by printing through a short decimal.
    let decimals = (-step.log10()).ceil().max(0.0) as usize;
    // Adding 0 turns a negative zero (a length of −0.00001 m rounded) into 0: "-0.0 m" in a
    // summary reads as a fault.
    format!("{rounded:.decimals$}").parse().unwrap_or(rounded) + 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_gives_short_decimals_and_no_negative_zero() {
        assert_eq!(round(0.1 + 0.2, 1e-4), 0.3);
        assert_eq!(round(2.46, 0.1), 2.5);
        let zero = round(-0.00001, 1e-4);
        assert_eq!(zero, 0.0);
        assert!(zero.is_sign_positive(), "{zero}");
        assert_eq!(format!("{:.1}", zero), "0.0");
    }
}
