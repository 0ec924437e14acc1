//! Structural algorithms: knot insertion, refinement, removal, degree elevation, splitting,
//! clamping, Bézier decomposition, reversal and reparametrisation. Each leaves the curve
//! unchanged on its domain (up to rounding) and changes only its representation.

use crate::bezier::Bezier;
use crate::bspline::BSpline;
use nalgebra::RealField;
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, MAX_ORDER, Result, Scalar, binomial, to_f64,
};

/// The default relative tolerance of [`BSpline::remove_knot`]: `1e-9` times the size of the
/// control polygon.
pub const DEFAULT_REMOVAL_TOLERANCE: f64 = 1e-9;

/// The scale that turns a relative removal tolerance into an absolute one: the largest of
/// the control points' coordinate magnitudes, or 1 if that is smaller.
pub(crate) fn relative_scale<T: Scalar>(magnitudes: impl IntoIterator<Item = T>) -> T {
    magnitudes.into_iter().fold(T::one(), RealField::max)
}

impl<T: Scalar, P: ControlPoint<T>> BSpline<T, P> {
    /// Inserts the knot `u` once (Boehm; seed 000 Algorithm 3, seed 004 (8.4)–(8.5)):
    /// $\bar P_i = \alpha_i P_i + (1 - \alpha_i) P_{i-1}$ with
    /// $\alpha_i = \frac{u - u_i}{u_{i+p} - u_i}$ for $k - p + 1 \le i \le k$.
    fn insert_once(&self, u: T) -> Self {
        let p = self.degree();
        let knots = self.knots().knots();
        let k = self.knots().span_in_domain(u);
        let old = self.control_points();
        let mut points = Vec::with_capacity(old.len() + 1);
        points.extend_from_slice(&old[..=k - p]);
        for i in k - p + 1..=k {
            let alpha = (u - knots[i]) / (knots[i + p] - knots[i]);
            points.push(old[i] * alpha + old[i - 1] * (T::one() - alpha));
        }
        points.extend_from_slice(&old[k..]);
        let at = knots.partition_point(|&x| x <= u);
        let mut new_knots = Vec::with_capacity(knots.len() + 1);
        new_knots.extend_from_slice(&knots[..at]);
        new_knots.push(u);
        new_knots.extend_from_slice(&knots[at..]);
        Self::new_unchecked(KnotVector::new_unchecked(p, new_knots), points)
    }

    /// Inserts the knot `u` `times` times without changing the curve.
    ///
    /// ```
    /// use spline_geom::BSpline;
    /// let f = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 1.0, 0.0])?;
    /// let g = f.insert_knot(0.5, 1)?;
    /// assert_eq!(g.control_points(), &[0.0, 0.5, 0.5, 0.0]);
    /// let (a, b): (f64, f64) = (g.eval(0.3)?, f.eval(0.3)?);
    /// assert!((a - b).abs() < 1e-15);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]/[`ErrorKind::OutOfDomain`] for `u`;
    /// [`ErrorKind::KnotMultiplicity`] if `u` would appear more than `p + 1` times.
    pub fn insert_knot(&self, u: T, times: usize) -> Result<Self> {
        // Validates u and the final multiplicity.
        self.knots().with_inserted(u, times)?;
        let mut curve = self.clone();
        for _ in 0..times {
            curve = curve.insert_once(u);
        }
        Ok(curve)
    }

    /// Inserts many knots at once (knot refinement, The NURBS Book A5.4), in `O(n + r p)`.
    /// The knots may come in any order and repeat.
    ///
    /// # Errors
    /// As [`BSpline::insert_knot`] for each knot, checked before anything is computed.
    pub fn refine(&self, new_knots: &[T]) -> Result<Self> {
        if new_knots.is_empty() {
            return Ok(self.clone());
        }
        for (j, &u) in new_knots.iter().enumerate() {
            self.knots()
                .check_param(u)
                .map_err(|e| e.context(format_args!("knot {j}")))?;
        }
        let mut x = new_knots.to_vec();
        x.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        let p = self.degree();
        let old_knots = self.knots().knots();
        let mut merged = Vec::with_capacity(old_knots.len() + x.len());
        merged.extend_from_slice(old_knots);
        merged.extend_from_slice(&x);
        merged.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        let target = KnotVector::new(p, merged)?;

        let old = self.control_points();
        let n = old.len() - 1; // index of the last control point
        let m = n + p + 1; // index of the last knot
        let r = x.len() - 1;
        let a = self.knots().span_in_domain(x[0]);
        let b = self.knots().span_in_domain(x[r]) + 1;
        let mut q = vec![P::origin(); n + r + 2];
        let mut ubar = vec![T::zero(); m + r + 2];
        q[..=a - p].copy_from_slice(&old[..=a - p]);
        for j in b - 1..=n {
            q[j + r + 1] = old[j];
        }
        ubar[..=a].copy_from_slice(&old_knots[..=a]);
        for j in b + p..=m {
            ubar[j + r + 1] = old_knots[j];
        }
        let mut i = b + p - 1;
        let mut k = b + p + r;
        for j in (0..=r).rev() {
            while x[j] <= old_knots[i] && i > a {
                q[k - p - 1] = old[i - p - 1];
                ubar[k] = old_knots[i];
                k -= 1;
                i -= 1;
            }
            q[k - p - 1] = q[k - p];
            for l in 1..=p {
                let ind = k - p + l;
                let alpha = ubar[k + l] - x[j];
                if alpha == T::zero() {
                    q[ind - 1] = q[ind];
                } else {
                    let alpha = alpha / (ubar[k + l] - old_knots[i + l - p]);
                    q[ind - 1] = q[ind - 1] * alpha + q[ind] * (T::one() - alpha);
                }
            }
            ubar[k] = x[j];
            k -= 1;
        }
        debug_assert!(ubar.iter().zip(target.knots()).all(|(a, b)| a == b));
        Ok(Self::new_unchecked(target, q))
    }

    /// Removes the interior knot `u` `times` times if the curve moves by at most
    /// `tolerance` (absolute; see [`BSpline::remove_knot`] for the relative default).
    ///
    /// Each removal solves the local equations of The NURBS Book A5.8; the result is then
    /// checked exactly: re-inserting the knots gives control points whose largest distance
    /// to the original ones bounds the change of the curve (partition of unity).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] if `u` is not an interior knot, is repeated fewer than
    /// `times` times, or `tolerance` is negative or NaN; [`ErrorKind::ToleranceExceeded`]
    /// (the message gives the deviation) if the curve would move more than `tolerance`.
    pub fn remove_knot_within(&self, u: T, times: usize, tolerance: T) -> Result<Self> {
        if !(tolerance >= T::zero()) {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!("tolerance must be non-negative, got {}", to_f64(tolerance)),
            ));
        }
        let (a, b) = self.domain();
        let mult = self.knots().multiplicity(u);
        if !(u > a && u < b) || mult == 0 {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!("{} is not an interior knot of the curve", to_f64(u)),
            ));
        }
        if times > mult {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "knot {} appears {mult} times and cannot be removed {times} times",
                    to_f64(u)
                ),
            ));
        }
        let mut curve = self.clone();
        for _ in 0..times {
            curve = curve.remove_once(u);
        }
        let back = curve.insert_knot(u, times)?;
        let deviation = back
            .control_points()
            .iter()
            .zip(self.control_points())
            .fold(T::zero(), |m, (x, y)| m.max((*x - *y).length()));
        if !(deviation <= tolerance) {
            return Err(Error::new(
                ErrorKind::ToleranceExceeded,
                format!(
                    "removing knot {} {times} time(s) would move the curve by up to {:.3e}, more than the tolerance {:.3e}",
                    to_f64(u),
                    to_f64(deviation),
                    to_f64(tolerance)
                ),
            ));
        }
        Ok(curve)
    }

    /// Removes the interior knot `u` `times` times if the curve moves by at most
    /// `relative_tolerance` times the size of the control polygon (its largest coordinate
    /// magnitude, or 1 if that is smaller). [`DEFAULT_REMOVAL_TOLERANCE`] is the usual choice.
    ///
    /// ```
    /// use spline_geom::BSpline;
    /// let f = BSpline::from_knots(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
    ///     vec![0.0, 2.0, -1.0, 1.0])?;
    /// let g = f.insert_knot(0.25, 2)?;
    /// let back = g.remove_knot(0.25, 2, 1e-9)?;
    /// assert!(back.control_points().iter().zip(f.control_points()).all(|(a, b): (&f64, &f64)| (a - b).abs() < 1e-12));
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BSpline::remove_knot_within`].
    pub fn remove_knot(&self, u: T, times: usize, relative_tolerance: T) -> Result<Self> {
        let scale = relative_scale(self.control_points().iter().map(ControlPoint::max_abs));
        self.remove_knot_within(u, times, relative_tolerance * scale)
    }

    /// One removal of the interior knot `u` (The NURBS Book A5.8 with `num = 1`), without
    /// any tolerance check.
    fn remove_once(&self, u: T) -> Self {
        let p = self.degree();
        let knots = self.knots().knots();
        let old = self.control_points();
        let s = self.knots().multiplicity(u);
        let r = knots.partition_point(|&k| k <= u) - 1; // last occurrence of u
        let first = r - p;
        let last = r - s;
        let off = first - 1;
        let mut temp = vec![P::origin(); last + 2 - off];
        temp[0] = old[off];
        temp[last + 1 - off] = old[last + 1];
        let (mut i, mut j) = (first, last);
        let (mut ii, mut jj) = (1, last - off);
        while j > i {
            let alpha_i = (u - knots[i]) / (knots[i + p + 1] - knots[i]);
            let alpha_j = (u - knots[j]) / (knots[j + p + 1] - knots[j]);
            temp[ii] = (old[i] - temp[ii - 1] * (T::one() - alpha_i)) * (T::one() / alpha_i);
            temp[jj] = (old[j] - temp[jj + 1] * alpha_j) * (T::one() / (T::one() - alpha_j));
            i += 1;
            ii += 1;
            j -= 1;
            jj -= 1;
        }
        let mut points = old.to_vec();
        let (mut i, mut j) = (first, last);
        while j > i {
            points[i] = temp[i - off];
            points[j] = temp[j - off];
            i += 1;
            j -= 1;
        }
        let fout = (2 * r - s - p) / 2;
        points.remove(fout);
        let mut new_knots = knots.to_vec();
        new_knots.remove(r);
        Self::new_unchecked(KnotVector::new_unchecked(p, new_knots), points)
    }

    /// Raises the degree by `times` (Cohen–Lyche–Schumaker; The NURBS Book A5.9): every
    /// distinct knot's multiplicity rises by exactly `times`, the curve is unchanged.
    /// An unclamped curve is first clamped at its domain ends.
    ///
    /// # Errors
    /// [`ErrorKind::DegreeTooHigh`] if `p + times` exceeds [`spline_core::MAX_DEGREE`].
    ///
    /// # Panics
    /// Never: the internal `expect`s guard invariants of the algorithm.
    // The loops mirror the indices of A5.9 so that the code can be checked against the book.
    #[allow(clippy::needless_range_loop, clippy::explicit_counter_loop)]
    pub fn elevate_degree(&self, times: usize) -> Result<Self> {
        if times == 0 {
            return Ok(self.clone());
        }
        let p = self.degree();
        let ph = spline_core::check_elevated_degree(p, times)?;
        if p == 0 {
            // Piecewise constants: every knot gains `times` copies, every coefficient too.
            let knots = self.knots().elevated(times)?;
            let points = self
                .control_points()
                .iter()
                .flat_map(|&c| std::iter::repeat_n(c, times + 1))
                .collect();
            return Ok(Self::new_unchecked(knots, points));
        }
        let clamped = self.clamped();
        // A5.9 assumes continuity at interior knots: elevate the pieces between
        // discontinuities (multiplicity p + 1) separately and join them.
        if let Some(&(cut_at, _)) = clamped
            .knots()
            .interior_breakpoints()
            .iter()
            .find(|(_, m)| *m == p + 1)
        {
            let (left, right) = clamped.cut(cut_at);
            let (left, right) = (
                left.expect("interior").elevate_degree(times)?,
                right.expect("interior").elevate_degree(times)?,
            );
            let mut knots = left.knots().knots().to_vec();
            knots.extend_from_slice(&right.knots().knots()[ph + 1..]);
            let mut points = left.control_points().to_vec();
            points.extend_from_slice(right.control_points());
            return Ok(Self::new_unchecked(
                KnotVector::new_unchecked(ph, knots),
                points,
            ));
        }
        let u = clamped.knots().knots();
        let pw = clamped.control_points();
        let t = times;
        let m = u.len() - 1;
        let ph2 = ph / 2;
        // Bézier degree-elevation coefficients.
        let mut bezalfs = vec![vec![T::zero(); p + 1]; ph + 1];
        bezalfs[0][0] = T::one();
        bezalfs[ph][p] = T::one();
        for i in 1..=ph2 {
            let inv = T::one() / binomial::<T>(ph, i);
            for j in i.saturating_sub(t)..=p.min(i) {
                bezalfs[i][j] = inv * binomial::<T>(p, j) * binomial::<T>(t, i - j);
            }
        }
        for i in ph2 + 1..ph {
            for j in i.saturating_sub(t)..=p.min(i) {
                bezalfs[i][j] = bezalfs[ph - i][p - j];
            }
        }
        let target = clamped.knots().elevated(t)?;
        let mut qw = vec![P::origin(); target.num_basis()];
        let mut uh = vec![T::zero(); target.len()];
        let mut bpts = [P::origin(); MAX_ORDER];
        let mut next_bpts = [P::origin(); MAX_ORDER];
        let mut ebpts = [P::origin(); MAX_ORDER];
        let mut alfs = [T::zero(); MAX_ORDER];
        let mut kind = ph + 1;
        let mut r: isize = -1;
        let mut a = p;
        let mut b = p + 1;
        let mut cind = 1;
        let mut ua = u[0];
        qw[0] = pw[0];
        for x in uh.iter_mut().take(ph + 1) {
            *x = ua;
        }
        bpts[..=p].copy_from_slice(&pw[..=p]);
        while b < m {
            let i0 = b;
            while b < m && u[b] == u[b + 1] {
                b += 1;
            }
            let mul = b - i0 + 1;
            let ub = u[b];
            let oldr = r;
            r = p as isize - mul as isize;
            let lbz = if oldr > 0 { (oldr as usize + 2) / 2 } else { 1 };
            let rbz = if r > 0 {
                ph - (r as usize).div_ceil(2)
            } else {
                ph
            };
            if r > 0 {
                // Insert u_b r times into the current Bézier segment.
                let numer = ub - ua;
                for k in (mul + 1..=p).rev() {
                    alfs[k - mul - 1] = numer / (u[a + k] - ua);
                }
                for j in 1..=r as usize {
                    let save = r as usize - j;
                    let s = mul + j;
                    for k in (s..=p).rev() {
                        bpts[k] = bpts[k] * alfs[k - s] + bpts[k - 1] * (T::one() - alfs[k - s]);
                    }
                    next_bpts[save] = bpts[p];
                }
            }
            // Elevate the Bézier segment.
            for i in lbz..=ph {
                let mut acc = P::origin();
                for j in i.saturating_sub(t)..=p.min(i) {
                    acc += bpts[j] * bezalfs[i][j];
                }
                ebpts[i] = acc;
            }
            if oldr > 1 {
                // Remove knot u_a oldr − 1 times.
                let oldr = oldr as usize;
                let mut first = kind - 2;
                let mut last = kind;
                let den = ub - ua;
                let bet = (ub - uh[kind - 1]) / den;
                for tr in 1..oldr {
                    let mut i = first;
                    let mut j = last;
                    let mut kj = j - kind + 1;
                    while j - i > tr {
                        if i < cind {
                            let alf = (ub - uh[i]) / (ua - uh[i]);
                            qw[i] = qw[i] * alf + qw[i - 1] * (T::one() - alf);
                        }
                        if j >= lbz {
                            if j - tr <= kind - ph + oldr {
                                let gam = (ub - uh[j - tr]) / den;
                                ebpts[kj] = ebpts[kj] * gam + ebpts[kj + 1] * (T::one() - gam);
                            } else {
                                ebpts[kj] = ebpts[kj] * bet + ebpts[kj + 1] * (T::one() - bet);
                            }
                        }
                        i += 1;
                        j -= 1;
                        kj = kj.wrapping_sub(1);
                    }
                    first -= 1;
                    last += 1;
                }
            }
            if a != p {
                let count = (ph as isize - oldr) as usize;
                for _ in 0..count {
                    uh[kind] = ua;
                    kind += 1;
                }
            }
            for j in lbz..=rbz {
                qw[cind] = ebpts[j];
                cind += 1;
            }
            if b < m {
                let rr = r.max(0) as usize;
                bpts[..rr].copy_from_slice(&next_bpts[..rr]);
                for j in rr..=p {
                    bpts[j] = pw[b - p + j];
                }
                a = b;
                b += 1;
                ua = ub;
            } else {
                for i in 0..=ph {
                    uh[kind + i] = ub;
                }
            }
        }
        debug_assert!(uh.iter().zip(target.knots()).all(|(x, y)| x == y));
        debug_assert_eq!(cind, qw.len());
        Ok(Self::new_unchecked(target, qw))
    }

    /// The curve on the same domain with clamped knots (`p + 1` copies of each domain end),
    /// so that it interpolates its first and last control points. Clamped curves are
    /// returned unchanged.
    ///
    /// # Panics
    /// Never (the domain of a valid knot vector is not empty).
    #[must_use]
    pub fn clamped(&self) -> Self {
        let (a, b) = self.domain();
        let p = self.degree();
        let mut curve = self.clone();
        let knots = curve.knots().knots();
        if knots[0] != a || curve.knots().multiplicity(a) < p + 1 {
            curve = curve.cut(a).1.expect("a < b");
        }
        let knots = curve.knots().knots();
        if knots[knots.len() - 1] != b || curve.knots().multiplicity(b) < p + 1 {
            curve = curve.cut(b).0.expect("a < b");
        }
        curve
    }

    /// Inserts `u` (in the domain) up to multiplicity `p + 1` and cuts there. The part left
    /// of `u` exists unless `u = a`, the part right of it unless `u = b`.
    fn cut(&self, u: T) -> (Option<Self>, Option<Self>) {
        let p = self.degree();
        let mut full = self.clone();
        for _ in self.knots().multiplicity(u)..=p {
            full = full.insert_once(u);
        }
        let knots = full.knots().knots();
        let points = full.control_points();
        let at = knots.partition_point(|&k| k < u);
        let (a, b) = self.domain();
        let left = (u > a).then(|| {
            Self::new_unchecked(
                KnotVector::new_unchecked(p, knots[..at + p + 1].to_vec()),
                points[..at].to_vec(),
            )
        });
        let right = (u < b).then(|| {
            Self::new_unchecked(
                KnotVector::new_unchecked(p, knots[at..].to_vec()),
                points[at..].to_vec(),
            )
        });
        (left, right)
    }

    /// Splits the curve at `u` (seed 000 FIG. 5; seed 004 (8.6)–(8.7)) into two curves, both
    /// clamped at `u` (`p + 1` copies of `u`), whose domains are `[a, u]` and `[u, b]`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::OutOfDomain`] unless `a < u < b`.
    ///
    /// # Panics
    /// Never: both parts exist once `a < u < b` is checked.
    pub fn split(&self, u: T) -> Result<(Self, Self)> {
        self.knots().check_param(u)?;
        let (a, b) = self.domain();
        if !(u > a && u < b) {
            return Err(Error::new(
                ErrorKind::OutOfDomain,
                format!(
                    "split parameter {} must lie strictly inside the domain [{}, {}]",
                    to_f64(u),
                    to_f64(a),
                    to_f64(b)
                ),
            ));
        }
        let (left, right) = self.cut(u);
        Ok((left.expect("u > a"), right.expect("u < b")))
    }

    /// The Bézier segments of the curve, one per non-empty knot span of the domain, each on
    /// its own parameter interval (interior knots raised to multiplicity `p` by refinement).
    ///
    /// # Panics
    /// Never: the refinement only inserts interior knots up to multiplicity `p`.
    #[must_use]
    pub fn bezier_segments(&self) -> Vec<Bezier<T, P>> {
        let clamped = self.clamped();
        let p = self.degree();
        let mut extra = Vec::new();
        for (k, m) in clamped.knots().interior_breakpoints() {
            extra.extend(std::iter::repeat_n(k, p.saturating_sub(m)));
        }
        let full = clamped
            .refine(&extra)
            .expect("interior knots up to multiplicity p");
        let knots = full.knots().knots();
        let n = full.control_points().len();
        (p..n)
            .filter(|&k| knots[k] < knots[k + 1])
            .map(|k| {
                Bezier::new_unchecked(
                    full.control_points()[k - p..=k].to_vec(),
                    knots[k],
                    knots[k + 1],
                )
            })
            .collect()
    }

    /// The same curve traversed backwards on the same domain: $\tilde C(u) = C(a + b - u)$.
    #[must_use]
    pub fn reversed(&self) -> Self {
        let mut points = self.control_points().to_vec();
        points.reverse();
        Self::new_unchecked(self.knots().reversed(), points)
    }

    /// The same curve on the domain `[a, b]` (affine change of parameter).
    ///
    /// # Errors
    /// [`ErrorKind::EmptyDomain`] unless `a < b`; [`ErrorKind::NonFinite`].
    pub fn reparametrized(&self, a: T, b: T) -> Result<Self> {
        Ok(Self::new_unchecked(
            self.knots().reparametrized(a, b)?,
            self.control_points().to_vec(),
        ))
    }
}
