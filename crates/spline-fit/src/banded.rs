//! Banded linear solvers, generic over the scalar and solving for control points directly.
//!
//! Written here rather than taken from a crate because they must work for every
//! [`Scalar`] (`f32`, `f64`, dual numbers) and solve with right-hand sides of any
//! [`ControlPoint`] type in one pass; the Rust crates that offer banded factorisations are
//! `f64`-only LAPACK bindings or large frameworks.
//!
//! - [`Staircase`]: Gaussian elimination without pivoting on a collocation matrix whose
//!   rows hold `p + 1` consecutive entries starting at non-decreasing columns. Totally
//!   positive matrices (B-spline collocation at increasing parameters, Schoenberg–Whitney
//!   satisfied) need no pivoting (de Boor and Pinkus 1977) and produce no fill-in outside the
//!   rows' own `p + 1` columns: `O(n p²)` time, `n (p + 1)` memory.
//! - [`BandLu`]: LU with partial pivoting of a band matrix with an optional dense right
//!   border (the periodic and end-condition systems), the scheme of LAPACK `gbtrf`.
//! - [`BandCholesky`]: Cholesky factorisation of a symmetric positive definite band matrix
//!   (least-squares normal equations).
//! - [`BandQr`]: row-by-row Givens QR of a banded design matrix (least squares without
//!   squaring the condition number).

// Index loops mirror the textbook formulas of the factorisations.
#![allow(clippy::needless_range_loop)]

use spline_core::{ControlPoint, Error, ErrorKind, MAX_ORDER, Result, Scalar, from_count};

fn singular(message: String) -> Error {
    Error::new(ErrorKind::SingularSystem, message)
}

/// Gaussian elimination without pivoting on a collocation matrix whose row `i` holds
/// `w` consecutive entries starting at column `first[i]`, `first` non-decreasing and
/// `first[i] ≤ i < first[i] + w`, built one row at a time: each new row is reduced against
/// the previous ones at once (the right-hand side too) and scaled to a unit pivot, so only
/// the unit upper factor is kept.
#[derive(Clone, Debug)]
pub(crate) struct Staircase<T, P> {
    width: usize,
    first: Vec<u32>,
    upper: Vec<T>,
    rhs: Vec<P>,
    tiny: T,
}

impl<T: Scalar, P: ControlPoint<T>> Staircase<T, P> {
    /// An empty system for `n` rows of width `width`.
    pub(crate) fn with_capacity(n: usize, width: usize) -> Self {
        Self {
            width,
            first: Vec::with_capacity(n),
            upper: Vec::with_capacity(n * width),
            rhs: Vec::with_capacity(n),
            tiny: T::default_epsilon() * from_count::<T>(4 * width),
        }
    }

    /// Appends the next row (`row.len() == width`, at columns `first ..`) with right-hand
    /// side `b`, and eliminates it.
    ///
    /// # Errors
    /// [`ErrorKind::SingularSystem`] on a pivot below `eps · 4w` relative to the row.
    ///
    /// # Panics
    /// If there are more than `u32::MAX` rows.
    #[inline]
    pub(crate) fn push_row(&mut self, first: usize, row: &[T], b: P) -> Result<()> {
        let w = self.width;
        let i = self.rhs.len();
        debug_assert!(first <= i && i < first + w && row.len() == w);
        let scale = row.iter().fold(T::zero(), |m, v| m.max(v.abs()));
        self.upper.extend_from_slice(row);
        let (done, current) = self.upper.split_at_mut(i * w);
        let mut acc = b;
        for k in first..i {
            let l = current[k - first];
            if l == T::zero() {
                continue;
            }
            let fk = self.first[k] as usize;
            // Row k of U (unit diagonal) covers columns k .. fk + w, inside this row's window.
            let urow = &done[k * w + (k + 1 - fk)..(k + 1) * w];
            let dst = &mut current[k + 1 - first..fk + w - first];
            for (d, &u) in dst.iter_mut().zip(urow) {
                *d -= l * u;
            }
            acc -= self.rhs[k] * l;
        }
        let pivot = current[i - first];
        if !(pivot.abs() > self.tiny * scale) || !pivot.is_finite() {
            return Err(singular(format!(
                "the conditions do not determine the spline: condition {i} nearly repeats the ones before it (the system is singular or too ill-conditioned)"
            )));
        }
        let inverse = T::one() / pivot;
        for v in &mut current[i + 1 - first..] {
            *v *= inverse;
        }
        self.first
            .push(u32::try_from(first).expect("fewer than 2³² rows"));
        self.rhs.push(acc * inverse);
        Ok(())
    }

    /// Back substitution: the solution.
    pub(crate) fn solve(mut self) -> Vec<P> {
        let n = self.rhs.len();
        let w = self.width;
        for i in (0..n).rev() {
            let fi = self.first[i] as usize;
            let end = (fi + w).min(n);
            let row = &self.upper[i * w..(i + 1) * w];
            let mut acc = self.rhs[i];
            for j in i + 1..end {
                acc -= self.rhs[j] * row[j - fi];
            }
            self.rhs[i] = acc;
        }
        self.rhs
    }
}

/// LU factorisation with partial pivoting of an `n × n` matrix whose entries `(i, j)` lie in
/// the band `i − kl ≤ j ≤ i + ku` or in the last `border` columns (dense).
#[derive(Clone, Debug)]
pub(crate) struct BandLu<T> {
    n: usize,
    kl: usize,
    ku: usize,
    border: usize,
    width: usize,
    band: Vec<T>,
    right: Vec<T>,
    pivots: Vec<usize>,
}

impl<T: Scalar> BandLu<T> {
    /// A zero matrix with the given structure.
    pub(crate) fn zeros(n: usize, kl: usize, ku: usize, border: usize) -> Self {
        let border = border.min(n);
        let width = 2 * kl + ku + 1;
        Self {
            n,
            kl,
            ku,
            border,
            width,
            band: vec![T::zero(); n * width],
            right: vec![T::zero(); n * border],
            pivots: Vec::new(),
        }
    }

    #[inline]
    fn first_border(&self) -> usize {
        self.n - self.border
    }

    #[inline]
    fn index(&self, i: usize, j: usize) -> (bool, usize) {
        let fb = self.first_border();
        if j >= fb {
            (true, i * self.border + (j - fb))
        } else {
            debug_assert!(
                j + self.kl >= i && j <= i + self.ku + self.kl,
                "({i}, {j}) outside the band"
            );
            (false, i * self.width + (j + self.kl - i))
        }
    }

    #[inline]
    fn get(&self, i: usize, j: usize) -> T {
        match self.index(i, j) {
            (true, k) => self.right[k],
            (false, k) => self.band[k],
        }
    }

    #[inline]
    fn get_mut(&mut self, i: usize, j: usize) -> &mut T {
        match self.index(i, j) {
            (true, k) => &mut self.right[k],
            (false, k) => &mut self.band[k],
        }
    }

    /// Adds `value` to entry `(i, j)`.
    ///
    /// # Panics
    /// In debug builds, if `(i, j)` lies outside the structure.
    pub(crate) fn add(&mut self, i: usize, j: usize, value: T) {
        *self.get_mut(i, j) += value;
    }

    fn last_row(&self, k: usize) -> usize {
        if k >= self.first_border() {
            self.n - 1
        } else {
            (k + self.kl).min(self.n - 1)
        }
    }

    fn last_band_col(&self, k: usize) -> usize {
        // Band columns of row k after fill-in: up to k + ku + kl, never into the border.
        (k + self.ku + self.kl).min(self.first_border().max(1) - 1)
    }

    /// Factorises in place.
    ///
    /// # Errors
    /// [`ErrorKind::SingularSystem`] with the column at which no usable pivot was found.
    pub(crate) fn factor(&mut self) -> Result<()> {
        let n = self.n;
        let fb = self.first_border();
        let scale = self
            .band
            .iter()
            .chain(&self.right)
            .fold(T::zero(), |m, v| m.max(v.abs()));
        let tiny = scale * T::default_epsilon() * from_count::<T>(4 * (self.width + self.border));
        self.pivots = Vec::with_capacity(n);
        for k in 0..n {
            let last = self.last_row(k);
            let mut best = k;
            let mut best_abs = self.get(k, k).abs();
            for i in k + 1..=last {
                let v = self.get(i, k).abs();
                if v > best_abs {
                    best = i;
                    best_abs = v;
                }
            }
            if !(best_abs > tiny) || !best_abs.is_finite() {
                return Err(singular(format!(
                    "the conditions do not determine the spline: coefficient {k} of {n} is free or nearly so (the system is singular or too ill-conditioned)"
                )));
            }
            self.pivots.push(best);
            let band_end = if k < fb { self.last_band_col(k) } else { 0 };
            if best != k {
                if k < fb {
                    for j in k..=band_end {
                        let a = self.get(k, j);
                        let b = self.get(best, j);
                        *self.get_mut(k, j) = b;
                        *self.get_mut(best, j) = a;
                    }
                }
                let start = k.max(fb) - fb;
                for c in start..self.border {
                    self.right.swap(k * self.border + c, best * self.border + c);
                }
            }
            let pivot = self.get(k, k);
            for i in k + 1..=last {
                let v = self.get(i, k);
                if v == T::zero() {
                    continue;
                }
                let l = v / pivot;
                *self.get_mut(i, k) = l;
                if k < fb {
                    for j in k + 1..=band_end {
                        let u = self.get(k, j);
                        *self.get_mut(i, j) -= l * u;
                    }
                }
                let start = (k + 1).max(fb) - fb;
                for c in start..self.border {
                    let u = self.right[k * self.border + c];
                    self.right[i * self.border + c] -= l * u;
                }
            }
        }
        Ok(())
    }

    /// Solves `A x = rhs` in place after [`BandLu::factor`].
    pub(crate) fn solve<P: ControlPoint<T>>(&self, rhs: &mut [P]) {
        let n = self.n;
        let fb = self.first_border();
        for k in 0..n {
            let p = self.pivots[k];
            if p != k {
                rhs.swap(k, p);
            }
            let bk = rhs[k];
            for i in k + 1..=self.last_row(k) {
                let l = self.get(i, k);
                if l != T::zero() {
                    rhs[i] -= bk * l;
                }
            }
        }
        for k in (0..n).rev() {
            let mut acc = rhs[k];
            if k < fb {
                for j in k + 1..=self.last_band_col(k) {
                    acc -= rhs[j] * self.get(k, j);
                }
            }
            for j in (k + 1).max(fb)..n {
                acc -= rhs[j] * self.right[k * self.border + (j - fb)];
            }
            rhs[k] = acc * (T::one() / self.get(k, k));
        }
    }
}

/// Cholesky factorisation `A = L Lᵀ` of a symmetric positive definite band matrix with
/// half-bandwidth `bw`, stored by rows of the lower band: `data[i (bw + 1) + d]` $= A_{i, i-d}$.
#[derive(Clone, Debug)]
pub(crate) struct BandCholesky<T> {
    n: usize,
    bw: usize,
    data: Vec<T>,
}

impl<T: Scalar> BandCholesky<T> {
    /// A zero matrix.
    pub(crate) fn zeros(n: usize, bw: usize) -> Self {
        Self {
            n,
            bw,
            data: vec![T::zero(); n * (bw + 1)],
        }
    }

    /// Sets every entry to zero (the storage is kept).
    pub(crate) fn clear(&mut self) {
        self.data.iter_mut().for_each(|v| *v = T::zero());
    }

    /// The size `n`.
    pub(crate) fn len(&self) -> usize {
        self.n
    }

    /// The lower band, `data[i (bw + 1) + d]` $= A_{i, i-d}$.
    pub(crate) fn data_mut(&mut self) -> &mut [T] {
        &mut self.data
    }

    /// The half-bandwidth.
    pub(crate) fn bandwidth(&self) -> usize {
        self.bw
    }

    /// The entry $A_{ij}$ for `j ≤ i` within the band (before factoring).
    #[inline]
    pub(crate) fn lower(&self, i: usize, j: usize) -> T {
        debug_assert!(j <= i && i - j <= self.bw);
        self.data[i * (self.bw + 1) + (i - j)]
    }

    /// Adds `value` to $A_{ij}$ for `j ≤ i` (the lower triangle).
    #[inline]
    pub(crate) fn add_lower(&mut self, i: usize, j: usize, value: T) {
        debug_assert!(j <= i && i - j <= self.bw);
        self.data[i * (self.bw + 1) + (i - j)] += value;
    }

    /// Adds `scale · v vᵀ` for a row `v` whose entries sit at columns `first ..`.
    #[inline]
    pub(crate) fn add_outer(&mut self, first: usize, v: &[T], scale: T) {
        let w = self.bw + 1;
        for (a, &va) in v.iter().enumerate() {
            let sa = va * scale;
            if sa == T::zero() {
                continue;
            }
            let row = &mut self.data[(first + a) * w..(first + a) * w + a + 1];
            // row[d] = A[first + a][first + a − d], d = a − c.
            for (c, &vc) in v[..=a].iter().enumerate() {
                row[a - c] += sa * vc;
            }
        }
    }

    /// Factorises in place. `what(i)` names unknown `i` in the error message.
    ///
    /// # Errors
    /// [`ErrorKind::SingularSystem`] when a pivot is not positive (relative to the diagonal),
    /// naming the unknown the data do not determine.
    pub(crate) fn factor(&mut self, what: &dyn Fn(usize) -> String) -> Result<()> {
        let (n, bw) = (self.n, self.bw);
        let w = bw + 1;
        let diag_max = (0..n).fold(T::zero(), |m, i| m.max(self.data[i * w].abs()));
        let tiny = T::default_epsilon() * from_count::<T>(8 * w);
        for j in 0..n {
            // L_jj.
            let lo = j.saturating_sub(bw);
            let mut s = self.data[j * w];
            let orig = s;
            for k in lo..j {
                let l = self.data[j * w + (j - k)];
                s -= l * l;
            }
            if !(s > tiny * orig.max(diag_max * T::default_epsilon())) || !s.is_finite() {
                return Err(singular(format!(
                    "the least-squares system is singular: {} is not determined by the data",
                    what(j)
                )));
            }
            let d = s.sqrt();
            self.data[j * w] = d;
            let inv = T::one() / d;
            for i in j + 1..(j + w).min(n) {
                let lo_i = i.saturating_sub(bw).max(lo);
                let mut s = self.data[i * w + (i - j)];
                for k in lo_i..j {
                    s -= self.data[i * w + (i - k)] * self.data[j * w + (j - k)];
                }
                self.data[i * w + (i - j)] = s * inv;
            }
        }
        Ok(())
    }

    /// Solves `L Lᵀ x = rhs` in place after [`BandCholesky::factor`].
    pub(crate) fn solve<P: ControlPoint<T>>(&self, rhs: &mut [P]) {
        let (n, bw) = (self.n, self.bw);
        let w = bw + 1;
        for i in 0..n {
            let mut acc = rhs[i];
            for k in i.saturating_sub(bw)..i {
                acc -= rhs[k] * self.data[i * w + (i - k)];
            }
            rhs[i] = acc * (T::one() / self.data[i * w]);
        }
        for i in (0..n).rev() {
            let mut acc = rhs[i];
            for k in i + 1..(i + w).min(n) {
                acc -= rhs[k] * self.data[k * w + (k - i)];
            }
            rhs[i] = acc * (T::one() / self.data[i * w]);
        }
    }
}

/// Upper-triangular band factor `R` (half-bandwidth `bw`) of a least-squares problem,
/// built one design row at a time by Givens rotations, with `Qᵀ b` alongside.
#[derive(Clone, Debug)]
pub(crate) struct BandQr<T, P> {
    n: usize,
    bw: usize,
    /// `r[i (bw + 1) + d]` = $R_{i, i+d}$.
    r: Vec<T>,
    qtb: Vec<P>,
}

impl<T: Scalar, P: ControlPoint<T>> BandQr<T, P> {
    /// An empty factor for `n` unknowns.
    pub(crate) fn new(n: usize, bw: usize) -> Self {
        Self {
            n,
            bw,
            r: vec![T::zero(); n * (bw + 1)],
            qtb: vec![P::origin(); n],
        }
    }

    /// Rotates the row `v` (entries at columns `first ..`, at most `bw + 1` of them) with
    /// right-hand side `b` into the factor. The row is carried in a window of `bw + 1`
    /// columns that slides right as its leading entry is annihilated (fill-in from the rows
    /// of `R` stays inside the window).
    ///
    /// # Panics
    /// If `v` has more than `bw + 1` entries or the bandwidth exceeds `MAX_ORDER − 1`.
    pub(crate) fn add_row(&mut self, first: usize, v: &[T], mut b: P) {
        let w = self.bw + 1;
        assert!(v.len() <= w && w <= MAX_ORDER, "row wider than the band");
        let mut work = [T::zero(); MAX_ORDER];
        work[..v.len()].copy_from_slice(v);
        let mut c = first;
        let mut live = v.len(); // entries past `live` are zero
        while c < self.n && live > 0 {
            let va = work[0];
            if va != T::zero() {
                let row = &mut self.r[c * w..c * w + w];
                let rc = row[0];
                if rc == T::zero() {
                    // Empty row of R: the remaining design row becomes it.
                    row.copy_from_slice(&work[..w]);
                    self.qtb[c] = b;
                    return;
                }
                let h = (rc * rc + va * va).sqrt();
                let (cs, sn) = (rc / h, va / h);
                row[0] = h;
                for k in 1..w {
                    let rj = row[k];
                    let x = work[k];
                    row[k] = cs * rj + sn * x;
                    work[k] = cs * x - sn * rj;
                }
                let z = self.qtb[c];
                self.qtb[c] = z * cs + b * sn;
                b = b * cs - z * sn;
                live = w;
            }
            // Slide the window one column to the right.
            work.copy_within(1..w, 0);
            work[w - 1] = T::zero();
            live -= 1;
            c += 1;
        }
    }

    /// Back substitution.
    ///
    /// # Errors
    /// [`ErrorKind::SingularSystem`] when a diagonal entry of `R` is negligible, naming the
    /// unknown with `what`.
    pub(crate) fn solve(mut self, what: &dyn Fn(usize) -> String) -> Result<Vec<P>> {
        let (n, w) = (self.n, self.bw + 1);
        let rmax = (0..n).fold(T::zero(), |m, i| m.max(self.r[i * w].abs()));
        let tiny = rmax * T::default_epsilon() * from_count::<T>(8 * w);
        for i in (0..n).rev() {
            let d = self.r[i * w];
            if !(d.abs() > tiny) || !d.is_finite() {
                return Err(singular(format!(
                    "the least-squares system is singular: {} is not determined by the data",
                    what(i)
                )));
            }
            let mut acc = self.qtb[i];
            for k in 1..w.min(n - i) {
                acc -= self.qtb[i + k] * self.r[i * w + k];
            }
            self.qtb[i] = acc * (T::one() / d);
        }
        Ok(self.qtb)
    }
}

#[cfg(test)]
mod tests;
