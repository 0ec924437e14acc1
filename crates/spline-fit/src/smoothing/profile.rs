//! Cholesky factorisation of a symmetric positive definite matrix stored by its profile
//! (envelope): row `i` keeps the entries from its first non-zero column `first[i]` to the
//! diagonal, and the factor $L$ has the same profile (a row's fill-in never starts left of
//! its first non-zero). The periodic least-squares systems of FITPACK's `fpperi` are cyclic
//! bands — entries at cyclic distance at most `b` from the diagonal — whose profile is a band
//! for the first `N − b` rows and full for the last `b` (the wrap-around): factored in
//! natural order, as FITPACK's Givens rotations triangularise them, in `O(N b²)`.

use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, from_count};

/// A symmetric matrix by the profile of its lower triangle, factored in place.
#[derive(Clone, Debug)]
pub(super) struct ProfileCholesky<T> {
    /// The first stored column of each row.
    first: Vec<usize>,
    /// Where each row starts in `data`.
    start: Vec<usize>,
    /// Row `i`: $A_{i, \text{first}[i]} … A_{ii}$ (after [`Self::factor`], $L$'s).
    data: Vec<T>,
}

impl<T: Scalar> ProfileCholesky<T> {
    /// The zero `n × n` cyclic band of half-bandwidth `b`: $A_{ij}$ may be non-zero where
    /// $\min(|i - j|, n - |i - j|) \le b$.
    pub(super) fn cyclic(n: usize, b: usize) -> Self {
        let first: Vec<usize> = (0..n)
            .map(|i| if i + b >= n { 0 } else { i.saturating_sub(b) })
            .collect();
        let mut start = Vec::with_capacity(n);
        let mut len = 0;
        for (i, &f) in first.iter().enumerate() {
            start.push(len);
            len += i + 1 - f;
        }
        Self {
            first,
            start,
            data: vec![T::zero(); len],
        }
    }

    /// The size `n`.
    pub(super) fn len(&self) -> usize {
        self.first.len()
    }

    fn index(&self, i: usize, j: usize) -> usize {
        debug_assert!(
            j <= i && j >= self.first[i],
            "({i}, {j}) outside the profile"
        );
        self.start[i] + (j - self.first[i])
    }

    /// Adds `value` to $A_{ij}$ and (implicitly) to $A_{ji}$; `i == j` adds it once.
    ///
    /// # Panics
    /// In debug builds, for an entry outside the profile.
    pub(super) fn add(&mut self, i: usize, j: usize, value: T) {
        let (i, j) = if j <= i { (i, j) } else { (j, i) };
        let at = self.index(i, j);
        self.data[at] += value;
    }

    /// The diagonal entry `i` (after [`Self::factor`]: $L_{ii}$).
    pub(super) fn diagonal(&self, i: usize) -> T {
        self.data[self.index(i, i)]
    }

    /// Factorises $A = L L^T$ in place, row by row. `what(i)` names unknown `i` in the
    /// error.
    ///
    /// # Errors
    /// [`ErrorKind::SingularSystem`] when a pivot is not positive relative to the diagonal
    /// (the data do not determine unknown `i`).
    pub(super) fn factor(&mut self, what: &dyn Fn(usize) -> String) -> Result<()> {
        let n = self.len();
        let diag_max = (0..n).fold(T::zero(), |m, i| m.max(self.diagonal(i).abs()));
        let width = self.first.iter().enumerate().map(|(i, &f)| i + 1 - f).max();
        let tiny = T::default_epsilon() * from_count::<T>(8 * width.unwrap_or(1));
        for i in 0..n {
            let fi = self.first[i];
            let row = self.start[i];
            for j in fi..=i {
                let fj = self.first[j];
                let lo = fi.max(fj);
                let other = self.start[j];
                let mut s = self.data[row + (j - fi)];
                for l in lo..j {
                    s -= self.data[row + (l - fi)] * self.data[other + (l - fj)];
                }
                if j < i {
                    self.data[row + (j - fi)] = s / self.data[other + (j - fj)];
                } else {
                    let orig = self.data[row + (i - fi)];
                    if !(s > tiny * orig.max(diag_max * T::default_epsilon())) || !s.is_finite() {
                        return Err(Error::new(
                            ErrorKind::SingularSystem,
                            format!(
                                "the periodic least-squares system is singular: {} is not determined by the data",
                                what(i)
                            ),
                        ));
                    }
                    self.data[row + (i - fi)] = s.sqrt();
                }
            }
        }
        Ok(())
    }

    /// Solves $L L^T x = $ `rhs` in place after [`Self::factor`].
    pub(super) fn solve<P: ControlPoint<T>>(&self, rhs: &mut [P]) {
        let n = self.len();
        for i in 0..n {
            let fi = self.first[i];
            let row = &self.data[self.start[i]..=self.index(i, i)];
            let mut acc = rhs[i];
            for (l, &v) in row[..i - fi].iter().enumerate() {
                acc -= rhs[fi + l] * v;
            }
            rhs[i] = acc * (T::one() / row[i - fi]);
        }
        for i in (0..n).rev() {
            let fi = self.first[i];
            let row = &self.data[self.start[i]..=self.index(i, i)];
            let xi = rhs[i] * (T::one() / row[i - fi]);
            rhs[i] = xi;
            for (l, &v) in row[..i - fi].iter().enumerate() {
                rhs[fi + l] -= xi * v;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    /// A cyclic band with a dominant diagonal, against nalgebra's dense Cholesky.
    #[test]
    fn cyclic_band_matches_dense_cholesky() {
        for (n, b) in [(12, 3), (7, 3), (5, 4), (3, 2), (1, 2), (20, 1)] {
            let mut profile = ProfileCholesky::cyclic(n, b);
            let mut dense = DMatrix::<f64>::zeros(n, n);
            for i in 0..n {
                for d in 0..=b.min(n - 1) {
                    let j = (i + d) % n;
                    let v = if d == 0 {
                        10.0 + i as f64
                    } else {
                        1.0 / (1.0 + (i * 7 + d) as f64)
                    };
                    profile.add(i, j, v);
                    dense[(i, j)] += v;
                    if i != j {
                        dense[(j, i)] += v;
                    }
                }
            }
            let rhs: Vec<f64> = (0..n).map(|i| (i as f64).sin() + 1.0).collect();
            let mut x = rhs.clone();
            let chol = dense.clone().cholesky().unwrap();
            profile.factor(&|i| format!("unknown {i}")).unwrap();
            profile.solve(&mut x);
            let want = chol.solve(&DMatrix::from_column_slice(n, 1, &rhs));
            for i in 0..n {
                assert!(
                    (x[i] - want[(i, 0)]).abs() < 1e-14,
                    "n = {n}, b = {b}, i = {i}"
                );
                assert!((profile.diagonal(i) - chol.l()[(i, i)]).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn singular_matrix_is_an_error() {
        let mut profile = ProfileCholesky::<f64>::cyclic(4, 1);
        profile.add(0, 0, 1.0);
        profile.add(1, 1, 1.0);
        profile.add(2, 2, 1.0);
        let err = profile.factor(&|i| format!("coefficient {i}")).unwrap_err();
        assert_eq!(err.kind(), ErrorKind::SingularSystem);
        assert!(err.to_string().contains("coefficient 3"), "{err}");
    }
}
