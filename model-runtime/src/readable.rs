//! Numbers in messages, written for a reader: `1e-8` rather than `0.00000001`, `0` rather than
//! `0e0`, `1e-9` rather than `0.0000000009999999999999986`.
//!
//! Messages (errors, stop details, the command line's help) are read, not parsed back: twelve
//! significant digits are more than any tolerance in the program resolves, and cutting there
//! hides the round-off tail of a computed value. Files and JSON keep full precision; only
//! text meant for people goes through [`Readable`].

use std::fmt;

/// Significant digits a readable number keeps.
const DIGITS: usize = 12;

/// An `f64` displayed for a reader: plain decimals from 1e-4 up to below 1e6, scientific
/// notation outside, at most twelve significant digits, no trailing zeros.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Readable(pub f64);

impl fmt::Display for Readable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if x == 0.0 {
            return f.write_str("0");
        }
        if !x.is_finite() {
            return write!(f, "{x}");
        }
        let scientific = format!("{:.*e}", DIGITS - 1, x);
        let (mantissa, exponent) = scientific
            .split_once('e')
            .expect("`{:e}` always writes an exponent");
        let exponent: i32 = exponent.parse().expect("`{:e}` writes an integer exponent");
        if (-4..6).contains(&exponent) {
            let decimals = usize::try_from(DIGITS as i32 - 1 - exponent).unwrap_or(0);
            f.write_str(trim_zeros(&format!("{x:.decimals$}")))
        } else {
            write!(f, "{}e{exponent}", trim_zeros(mantissa))
        }
    }
}

/// `1.2500` -> `1.25`, `3.000` -> `3`; text without a decimal point is kept.
fn trim_zeros(text: &str) -> &str {
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.')
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::Readable;

    fn show(x: f64) -> String {
        Readable(x).to_string()
    }

    #[test]
    fn the_numbers_people_met_in_messages() {
        assert_eq!(show(0.0), "0");
        assert_eq!(show(-0.0), "0");
        assert_eq!(show(1e-8), "1e-8");
        assert_eq!(show(1e-10), "1e-10");
        assert_eq!(show(0.000_000_000_999_999_999_999_998_6), "1e-9");
        assert_eq!(show(100.0), "100");
        assert_eq!(show(99.000_75), "99.00075");
        assert_eq!(show(-2.5e7), "-2.5e7");
        assert_eq!(show(0.1 + 0.2), "0.3");
        assert_eq!(show(1.0e-4), "0.0001");
        assert_eq!(show(9.5e-5), "9.5e-5");
        assert_eq!(show(999_999.999_999_9), "1e6");
        assert_eq!(show(f64::NAN), "NaN");
        assert_eq!(show(f64::NEG_INFINITY), "-inf");
    }

    #[test]
    fn twelve_digits_read_back_within_their_rounding() {
        let mut x = 1.234_567_891_234_567e-300;
        while x < 1e300 {
            let back: f64 = show(x).parse().unwrap();
            assert!((back - x).abs() <= 5e-12 * x.abs(), "{x} -> {}", show(x));
            x *= 7.3;
        }
    }
}
