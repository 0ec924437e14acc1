//! Operations of scipy's `BSpline` on [`ColumnSpline`]: derivative and antiderivative
//! splines (FITPACK's `splder`/`splantider`), definite integrals, knot insertion (FITPACK's
//! `insert`, periodic rules included) and the basis element.

use super::{ColumnSpline, Extrapolate, invalid};
use spline_core::{Error, ErrorKind, Result, check_derivative_order};

impl ColumnSpline {
    /// The coefficient rows padded with zero rows (or cut) to `len(t)` rows: FITPACK's
    /// convention, which `splder` and `splantider` work in.
    fn padded_coefficients(&self) -> Vec<f64> {
        let m = self.columns;
        let len = self.knots().len();
        let mut c = self.coefficients[..self.rows.min(len) * m].to_vec();
        c.resize(len * m, 0.0);
        c
    }

    /// The derivative of order `nu` as a spline (scipy's `BSpline.derivative`, FITPACK's
    /// `splder`): each order removes the first and the last knot and lowers the degree by
    /// one; the new coefficients
    /// $c'_i = k\,(c_{i+1} - c_i)/(t_{i+k+1} - t_{i+1})$ are padded with `k` zero rows to
    /// `len(t)` rows (FITPACK's convention, as scipy returns them).
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] for `nu > k` ("Order of derivative (n = …) must be <=
    /// order of spline (k = …)"); [`ErrorKind::KnotMultiplicity`] when `k + 1` knots away
    /// from the first and last coincide ("The spline has internal repeated knots and is not
    /// differentiable").
    pub fn derivative(&self, nu: usize) -> Result<Self> {
        let k0 = self.degree();
        if nu > k0 {
            return Err(Error::new(
                ErrorKind::OrderTooHigh,
                format!("Order of derivative (n = {nu}) must be <= order of spline (k = {k0})"),
            )
            .with_counts(k0, nu));
        }
        let m = self.columns;
        let mut t = self.knots().to_vec();
        let mut c = self.padded_coefficients();
        let mut k = k0;
        for _ in 0..nu {
            let len = t.len();
            let kf = k as f64;
            let mut next = Vec::with_capacity((len - 2) * m);
            for i in 0..len - k - 2 {
                let dt = t[i + k + 1] - t[i + 1];
                if dt == 0.0 {
                    return Err(Error::new(
                        ErrorKind::KnotMultiplicity,
                        format!(
                            "The spline has internal repeated knots and is not differentiable {nu} times (knots {} to {} equal {})",
                            i + 1,
                            i + k + 1,
                            t[i + 1]
                        ),
                    ));
                }
                let scale = kf / dt;
                next.extend((0..m).map(|j| (c[(i + 1) * m + j] - c[i * m + j]) * scale));
            }
            next.resize((len - 2) * m, 0.0);
            c = next;
            t = t[1..len - 1].to_vec();
            k -= 1;
        }
        Self::new(t, c, k, m)
    }

    /// The antiderivative of order `nu` (scipy's `BSpline.antiderivative`, FITPACK's
    /// `splantider`): each order repeats the first and the last knot once more, raises the
    /// degree by one and sets
    /// $C_0 = 0$, $C_{i+1} = C_i + c_i (t_{i+k+1} - t_i)/(k + 1)$, followed by `k + 2`
    /// copies of the last value, so `len(t) + 2` rows (FITPACK's convention). It vanishes at
    /// $t_0$ and at every point left of $t_{k+1}$ of a clamped spline; its
    /// [`ColumnSpline::derivative`] is the spline itself.
    ///
    /// # Errors
    /// [`ErrorKind::DegreeTooHigh`] when `k + nu` is above [`spline_core::MAX_DEGREE`];
    /// [`ErrorKind::OrderTooHigh`] above [`spline_core::MAX_DERIVATIVE_ORDER`].
    pub fn antiderivative(&self, nu: usize) -> Result<Self> {
        check_derivative_order(nu)?;
        let m = self.columns;
        let mut t = self.knots().to_vec();
        let mut c = self.padded_coefficients();
        let mut k = self.degree();
        if k + nu > spline_core::MAX_DEGREE {
            return Err(Error::new(
                ErrorKind::DegreeTooHigh,
                format!(
                    "the antiderivative of order {nu} has degree {} above the supported maximum {}",
                    k + nu,
                    spline_core::MAX_DEGREE
                ),
            ));
        }
        for _ in 0..nu {
            let len = t.len();
            let kp1 = (k + 1) as f64;
            let mut next = Vec::with_capacity((len + 2) * m);
            next.extend(std::iter::repeat_n(0.0, m));
            let mut acc = vec![0.0; m];
            for i in 0..len - k - 1 {
                let dt = t[i + k + 1] - t[i];
                for (a, &ci) in acc.iter_mut().zip(&c[i * m..(i + 1) * m]) {
                    *a += ci * dt;
                }
                next.extend(acc.iter().map(|a| a / kp1));
            }
            let last = next[next.len() - m..].to_vec();
            for _ in 0..k + 2 {
                next.extend_from_slice(&last);
            }
            c = next;
            let mut tn = Vec::with_capacity(len + 2);
            tn.push(t[0]);
            tn.extend_from_slice(&t);
            tn.push(t[len - 1]);
            t = tn;
            k += 1;
        }
        Self::new(t, c, k, m)
    }

    /// The definite integral $\int_a^b s_j(x)\,dx$ of every column (scipy's
    /// `BSpline.integrate`), `a > b` giving the negative of the integral over `[b, a]`.
    ///
    /// [`Extrapolate::On`] integrates the end pieces' polynomials outside $[t_k, t_n]$;
    /// [`Extrapolate::Off`] takes the spline as zero there (so an interval outside the base
    /// interval gives zeros, as scipy's one-column path does; scipy's several-column path
    /// returns NaN there); [`Extrapolate::Periodic`] integrates the periodic extension: whole
    /// periods times the integral over $[t_k, t_n]$ plus the rest, wrapped.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] for NaN or infinite limits.
    pub fn integrate(&self, a: f64, b: f64, mode: Extrapolate) -> Result<Vec<f64>> {
        if !a.is_finite() || !b.is_finite() {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!("the integration limits must be finite, got [{a}, {b}]"),
            ));
        }
        let m = self.columns;
        let (mut a, mut b) = (a, b);
        let mut sign = 1.0;
        if b < a {
            std::mem::swap(&mut a, &mut b);
            sign = -1.0;
        }
        let (ts, te) = self.domain();
        let anti = self.antiderivative(1)?;
        let mut integral = vec![0.0; m];
        // Adds F(hi) − F(lo) to the integral, with F evaluated by extrapolation.
        let add = |lo: f64, hi: f64, times: f64, integral: &mut [f64]| -> Result<()> {
            let mut out = vec![0.0; 2 * m];
            anti.eval_into(&[lo, hi], 0, Extrapolate::On, &mut out)?;
            for (j, v) in integral.iter_mut().enumerate() {
                *v += times * (out[m + j] - out[j]);
            }
            Ok(())
        };
        match mode {
            Extrapolate::On => add(a, b, 1.0, &mut integral)?,
            Extrapolate::Off => {
                let (lo, hi) = (a.max(ts), b.min(te));
                if lo < hi {
                    add(lo, hi, 1.0, &mut integral)?;
                }
            }
            Extrapolate::Periodic => {
                let period = te - ts;
                let interval = b - a;
                // Python's divmod for non-negative floats.
                let left = interval % period;
                let div = (interval - left) / period;
                let mut periods = div.floor();
                if div - periods > 0.5 {
                    periods += 1.0;
                }
                if periods > 0.0 {
                    add(ts, te, periods, &mut integral)?;
                }
                let a = ts + (a - ts).rem_euclid(period);
                let b = a + left;
                if b <= te {
                    add(a, b, 1.0, &mut integral)?;
                } else {
                    add(a, te, 1.0, &mut integral)?;
                    add(ts, ts + b - te, 1.0, &mut integral)?;
                }
            }
        }
        for v in &mut integral {
            *v *= sign;
        }
        Ok(integral)
    }

    /// The spline with the knot `x` inserted `times` times (scipy's `BSpline.insert_knot`,
    /// FITPACK's `insert` applied `times` times; Boehm's algorithm on all columns at once).
    ///
    /// With `periodic` (a spline used with [`Extrapolate::Periodic`]) FITPACK's periodic
    /// rules apply: there must be at least `k` interior knots $t_j$ with $t_{k+1} < t_j \le x$
    /// or at least `k` with $x \le t_j < t_{n-k}$, and the first and last `k` knots and
    /// coefficients are updated so that the spline stays periodic.
    ///
    /// # Errors
    /// [`ErrorKind::OutOfDomain`] for `x` outside $[t_k, t_n]$ or NaN ("Cannot insert a
    /// knot at …"); [`ErrorKind::InvalidArgument`] for `times == 0` ("`m` must be
    /// positive") or too few interior knots of a periodic spline ("Not enough internal
    /// knots"). A knot may be inserted more than `k + 1` times, as scipy allows (the spline
    /// keeps its values; see [`ColumnSpline`] on repeated knots).
    pub fn insert_knot(&self, x: f64, times: usize, periodic: bool) -> Result<Self> {
        let (a, b) = self.domain();
        if !(x >= a && x <= b) {
            return Err(Error::new(
                ErrorKind::OutOfDomain,
                format!("Cannot insert a knot at {x}: it is outside the base interval [{a}, {b}]"),
            )
            .with_value(x)
            .with_interval(a, b));
        }
        if times == 0 {
            return Err(invalid("`m` must be positive, got m = 0").with_counts(1, 0));
        }
        let k = self.degree();
        let m = self.columns;
        let mut t = self.knots().to_vec();
        let mut c = self.coefficients.clone();
        for _ in 0..times {
            insert_once(x, &mut t, &mut c, k, m, periodic)?;
        }
        Self::new(t, c, k, m)
    }

    /// The B-spline basis element $B(x \mid t_0, …, t_{k+1})$ of degree `k = len(t) − 2`
    /// (scipy's `BSpline.basis_element`): the knots are extended by `k` copies of
    /// $t_0 - 1$ in front and `k` copies of $t_{k+1} + 1$ behind, and the coefficients are
    /// zero except $c_k = 1$ (`len(t) + 2k` rows, FITPACK's padding, one column). With
    /// extrapolation it is zero outside $[t_0, t_{k+1}]$ up to the added knots.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] for fewer than 2 knots; the errors of
    /// [`ColumnSpline::new`] (unsorted knots, more than `k + 1` equal, …).
    pub fn basis_element(t: &[f64]) -> Result<Self> {
        if t.len() < 2 {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!("a basis element needs at least 2 knots, got {}", t.len()),
            ));
        }
        let k = t.len() - 2;
        let mut knots = Vec::with_capacity(t.len() + 2 * k);
        knots.extend(std::iter::repeat_n(t[0] - 1.0, k));
        knots.extend_from_slice(t);
        knots.extend(std::iter::repeat_n(t[t.len() - 1] + 1.0, k));
        let mut c = vec![0.0; knots.len()];
        c[k] = 1.0;
        Self::new(knots, c, k, 1)
    }
}

/// One knot inserted at `x` (FITPACK's `insert`, as scipy's `_insert` ports it), into knots
/// `t` and row-major coefficients `c` of `m` columns (all rows kept, one row added).
fn insert_once(
    x: f64,
    t: &mut Vec<f64>,
    c: &mut Vec<f64>,
    k: usize,
    m: usize,
    periodic: bool,
) -> Result<()> {
    let len = t.len();
    let n = len - k - 1;
    // scipy's find_interval without extrapolation: t[l] ≤ x < t[l+1], or n − 1 at t_n.
    let mut interval = k + t[k + 1..n].partition_point(|&v| v <= x);
    if t[interval] == t[interval + k + 1] && interval > k {
        interval -= 1;
    }
    if periodic && interval < 2 * k && interval + 1 + 2 * k >= len {
        return Err(invalid(format!(
            "Not enough internal knots to insert {x} into a periodic spline of degree {k}"
        ))
        .with_value(x));
    }
    t.insert(interval + 1, x);
    let rows = c.len() / m;
    let mut cc = vec![0.0; (rows + 1) * m];
    cc[(interval + 1) * m..].copy_from_slice(&c[interval * m..]);
    for i in (interval + 1 - k..=interval).rev() {
        let den = t[i + k + 1] - t[i];
        if den == 0.0 {
            return Err(Error::new(
                ErrorKind::KnotMultiplicity,
                format!("Cannot insert the knot at {x}: the knots around it coincide"),
            ));
        }
        let fac = (x - t[i]) / den;
        for j in 0..m {
            cc[i * m + j] = fac * c[i * m + j] + (1.0 - fac) * c[(i - 1) * m + j];
        }
    }
    cc[..(interval + 1 - k) * m].copy_from_slice(&c[..(interval + 1 - k) * m]);
    if periodic {
        let len = t.len();
        let nk = len - k - 1;
        let n2k = len - 2 * k - 1;
        let period = t[nk] - t[k];
        if interval >= nk - k {
            for i in 0..k {
                t[i] = t[nk - k + i] - period;
            }
            cc.copy_within(n2k * m..(n2k + k) * m, 0);
        }
        if interval < 2 * k {
            for i in 0..k {
                t[len - k + i] = t[k + 1 + i] + period;
            }
            cc.copy_within(0..k * m, n2k * m);
        }
    }
    *c = cc;
    Ok(())
}
