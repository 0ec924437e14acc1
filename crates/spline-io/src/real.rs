//! The one number formatter of the CAD writers (STEP and IGES): reals with a decimal point
//! and the shortest digits that read back to the same `f64`.

/// A real with the digits that read back to the same `f64` (Rust's shortest round-trip
/// form), always with a decimal point and, outside `1e-5 ≤ |x| < 1e16`, an exponent `E`:
/// `2.0`, `0.1`, `-0.0`, `1.5E-7`, `1.0E16`. Both STEP (ISO 10303-21 §6.3.2) and IGES
/// (§2.2.2.4) read this form; the caller has checked that `x` is finite.
pub(crate) fn real(x: f64) -> String {
    let magnitude = x.abs();
    if x == 0.0 || (1e-5..1e16).contains(&magnitude) {
        let s = format!("{x}");
        if s.contains('.') { s } else { s + ".0" }
    } else {
        let s = format!("{x:e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        if mantissa.contains('.') {
            format!("{mantissa}E{exponent}")
        } else {
            format!("{mantissa}.0E{exponent}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::real;

    #[test]
    fn reals_have_a_point_and_read_back_exactly() {
        for x in [
            0.0,
            -0.0,
            1.0,
            0.1,
            1.0 / 3.0,
            1.5e-7,
            -2.5e300,
            1e16,
            1e16 - 2.0,
            1e-5,
            9.999_999_999_999_999e-6,
            123_456_789.125,
            -123_456.789,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
        ] {
            let s = real(x);
            assert!(s.contains('.') && !s.contains('e'), "{s}");
            assert!(s.len() <= 24, "{s}");
            let y: f64 = s.parse().unwrap();
            assert_eq!(y.to_bits(), x.to_bits(), "{s}");
        }
        // The forms, written out.
        for (x, s) in [
            (2.0, "2.0"),
            (-0.0, "-0.0"),
            (0.1, "0.1"),
            (1.5e-7, "1.5E-7"),
            (1e16, "1.0E16"),
            (-2.5e300, "-2.5E300"),
            (1e-5, "0.00001"),
            (5e-324, "5.0E-324"),
            (123_456_789.125, "123456789.125"),
        ] {
            assert_eq!(real(x), s);
        }
    }
}
