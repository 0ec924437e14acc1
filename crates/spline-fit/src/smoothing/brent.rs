//! Brent's minimisation on a bounded interval, step for step as scipy's
//! `minimize_scalar(method="Bounded")` (`_minimize_scalar_bounded`: golden sections and
//! parabolic steps, `xatol = 1e-5`, at most 500 evaluations), so that a smoothing weight
//! chosen by cross-validation is the one scipy chooses.

use spline_core::{Error, ErrorKind, Result, Scalar, cast};

/// The absolute tolerance of scipy's bounded search.
const XATOL: f64 = 1e-5;
/// The evaluation limit of scipy's bounded search.
const MAX_EVALUATIONS: usize = 500;

/// The minimiser of `f` on `[a, b]` found by scipy's bounded Brent search.
///
/// # Errors
/// The first error of `f`; [`ErrorKind::NoConvergence`] after 500 evaluations or when the
/// scores are NaN.
pub(super) fn fminbound<T: Scalar>(mut f: impl FnMut(T) -> Result<T>, a: T, b: T) -> Result<T> {
    let sqrt_eps: T = cast(2.2e-16f64.sqrt());
    let golden_mean: T = cast(0.5 * (3.0 - 5f64.sqrt()));
    let xatol: T = cast(XATOL);
    let half: T = cast(0.5);
    let two: T = cast(2.0);
    let third = xatol / cast(3.0);
    let (mut a, mut b) = (a, b);
    let mut fulc = a + golden_mean * (b - a);
    let (mut nfc, mut xf) = (fulc, fulc);
    let (mut rat, mut e) = (T::zero(), T::zero());
    let mut fx = f(xf)?;
    let mut evaluations = 1;
    let (mut ffulc, mut fnfc) = (fx, fx);
    let mut fu = T::zero();
    let mut xm = half * (a + b);
    let mut tol1 = sqrt_eps * xf.abs() + third;
    let mut tol2 = two * tol1;
    while (xf - xm).abs() > tol2 - half * (b - a) {
        let mut golden = true;
        if e.abs() > tol1 {
            golden = false;
            let mut r = (xf - nfc) * (fx - ffulc);
            let mut q = (xf - fulc) * (fx - fnfc);
            let mut p = (xf - fulc) * q - (xf - nfc) * r;
            q = two * (q - r);
            if q > T::zero() {
                p = -p;
            }
            q = q.abs();
            r = e;
            e = rat;
            if p.abs() < (half * q * r).abs() && p > q * (a - xf) && p < q * (b - xf) {
                rat = p / q;
                let x = xf + rat;
                if (x - a) < tol2 || (b - x) < tol2 {
                    rat = tol1 * sign_or_one(xm - xf);
                }
            } else {
                golden = true;
            }
        }
        if golden {
            e = if xf >= xm { a - xf } else { b - xf };
            rat = golden_mean * e;
        }
        let x = xf + sign_or_one(rat) * rat.abs().max(tol1);
        fu = f(x)?;
        evaluations += 1;
        if fu <= fx {
            if x >= xf {
                a = xf;
            } else {
                b = xf;
            }
            (fulc, ffulc) = (nfc, fnfc);
            (nfc, fnfc) = (xf, fx);
            (xf, fx) = (x, fu);
        } else {
            if x < xf {
                a = x;
            } else {
                b = x;
            }
            if fu <= fnfc || nfc == xf {
                (fulc, ffulc) = (nfc, fnfc);
                (nfc, fnfc) = (x, fu);
            } else if fu <= ffulc || fulc == xf || fulc == nfc {
                (fulc, ffulc) = (x, fu);
            }
        }
        xm = half * (a + b);
        tol1 = sqrt_eps * xf.abs() + third;
        tol2 = two * tol1;
        if evaluations >= MAX_EVALUATIONS {
            return Err(Error::new(
                ErrorKind::NoConvergence,
                format!("the bounded search did not converge in {MAX_EVALUATIONS} evaluations"),
            ));
        }
    }
    if [xf, fx, fu].iter().any(|v| v.partial_cmp(v).is_none()) {
        return Err(Error::new(
            ErrorKind::NoConvergence,
            "the score is NaN: no minimum can be located",
        ));
    }
    Ok(xf)
}

/// `sign(x)`, with `+1` for zero (numpy's `sign(x) + (x == 0)`).
fn sign_or_one<T: Scalar>(x: T) -> T {
    if x < T::zero() { -T::one() } else { T::one() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_minimum_of_a_parabola_to_the_tolerance() {
        let x = fminbound(|x: f64| Ok((x - 1.234).powi(2) + 0.5), 0.0, 10.0).unwrap();
        assert!((x - 1.234).abs() < 1e-5);
    }

    #[test]
    fn bounded_minimum_at_an_end() {
        let x = fminbound(|x: f64| Ok(x), 0.0, 3.0).unwrap();
        assert!(x < 1e-4, "{x}");
    }
}
