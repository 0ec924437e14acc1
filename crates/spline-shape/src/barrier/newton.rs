//! The sparse Newton matrix of the barrier method (above [`DENSE_LIMIT`] unknowns): its
//! pattern — the union of the objective Hessian's, of `Jᵀ D J`'s and of the constraint
//! curvature's, plus the diagonal — is computed once per problem shape; each step rewrites
//! the values in place and refactors with nalgebra-sparse's Cholesky factorisation on the
//! same symbolic analysis.

use nalgebra::DVector;
use nalgebra_sparse::factorization::{CscCholesky, CscSymbolicCholesky};
use nalgebra_sparse::pattern::SparsityPattern;
use nalgebra_sparse::{CooMatrix, CscMatrix};
use spline_core::{Error, ErrorKind, Result};

/// Problems with at most this many unknowns use dense matrices.
pub(super) const DENSE_LIMIT: usize = 400;

/// The Newton matrix on a fixed pattern (CSC, both triangles) and its factorisation.
pub(crate) struct SparseNewton {
    n: usize,
    pattern: SparsityPattern,
    /// The slot of every diagonal entry.
    diagonal: Vec<usize>,
    factor: CscCholesky<f64>,
    /// The values without the constraints' curvature, and the values being factored.
    pub(super) base: Vec<f64>,
    pub(super) work: Vec<f64>,
    /// Whether an entry fell outside the pattern since the last fill.
    pub(super) missed: bool,
}

impl SparseNewton {
    /// The Newton matrix whose pattern holds `entries` and the diagonal.
    pub(super) fn new(n: usize, entries: impl Iterator<Item = (usize, usize)>) -> Self {
        let mut coo = CooMatrix::new(n, n);
        for i in 0..n {
            coo.push(i, i, 1.0);
        }
        for (i, j) in entries {
            coo.push(i, j, 0.0);
        }
        let csc = CscMatrix::from(&coo);
        // A positive definite matrix on the pattern (the identity) for the first numerical
        // factorisation: later ones only rewrite the values.
        let identity: Vec<f64> = csc
            .triplet_iter()
            .map(|(i, j, _)| if i == j { 1.0 } else { 0.0 })
            .collect();
        let pattern = csc.pattern().clone();
        let diagonal = (0..n)
            .map(|j| {
                let rows = &pattern.minor_indices()
                    [pattern.major_offsets()[j]..pattern.major_offsets()[j + 1]];
                pattern.major_offsets()[j] + rows.partition_point(|&r| r < j)
            })
            .collect();
        let symbolic = CscSymbolicCholesky::factor(pattern.clone());
        let factor = CscCholesky::factor_numerical(symbolic, &identity)
            .expect("the identity is positive definite");
        let nnz = pattern.nnz();
        Self {
            n,
            pattern,
            diagonal,
            factor,
            base: vec![0.0; nnz],
            work: vec![0.0; nnz],
            missed: false,
        }
    }

    /// The entries of the pattern.
    pub(super) fn entries(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..self.n).flat_map(move |j| {
            let (a, b) = (
                self.pattern.major_offsets()[j],
                self.pattern.major_offsets()[j + 1],
            );
            self.pattern.minor_indices()[a..b]
                .iter()
                .map(move |&i| (i, j))
        })
    }

    fn slot(&self, i: usize, j: usize) -> Option<usize> {
        let (a, b) = (
            self.pattern.major_offsets()[j],
            self.pattern.major_offsets()[j + 1],
        );
        let rows = &self.pattern.minor_indices()[a..b];
        rows.binary_search(&i).ok().map(|k| a + k)
    }

    /// Clears the base values.
    pub(super) fn clear(&mut self) {
        self.base.iter_mut().for_each(|v| *v = 0.0);
        self.missed = false;
    }

    /// Adds `v` at `(i, j)` of the base values (records a miss outside the pattern).
    pub(super) fn add(&mut self, i: usize, j: usize, v: f64) {
        match self.slot(i, j) {
            Some(s) => self.base[s] += v,
            None => self.missed = true,
        }
    }

    /// Adds `w · a aᵀ` for a sparse vector `a` to the base values.
    pub(super) fn add_outer(&mut self, cols: &[usize], vals: &[f64], w: f64) {
        for (&ca, &va) in cols.iter().zip(vals) {
            let wa = w * va;
            for (&cb, &vb) in cols.iter().zip(vals) {
                self.add(ca, cb, wa * vb);
            }
        }
    }

    /// Sets the working values to the base values.
    pub(super) fn reset_work(&mut self) {
        self.work.copy_from_slice(&self.base);
    }

    /// Adds `v` at `(i, j)` of the working values (records a miss outside the pattern).
    pub(super) fn add_work(&mut self, i: usize, j: usize, v: f64) {
        match self.slot(i, j) {
            Some(s) => self.work[s] += v,
            None => self.missed = true,
        }
    }

    /// Factors the working values and solves `H d = −g` into `d`, if `H` is positive
    /// definite.
    fn solve_work(&mut self, gradient: &DVector<f64>, d: &mut DVector<f64>) -> bool {
        // A failed factorisation leaves partial sums in the factor's work memory; the next
        // one on the same symbolic analysis is still exact: left-looking Cholesky's first
        // touch of a work entry `p` in column `j` is the scatter of column `j` of the matrix
        // (an assignment: the first column whose factor pattern holds `p` has `p` in the
        // matrix's pattern), so nothing of the failed one is read (tested below).
        if self.factor.refactor(&self.work).is_err() {
            return false;
        }
        d.copy_from(gradient);
        d.neg_mut();
        self.factor.solve_mut(&mut *d);
        d.iter().all(|v| v.is_finite())
    }

    /// Solves `H d = −g` with the working values, if they are positive definite.
    pub(super) fn solve_definite(&mut self, gradient: &DVector<f64>, d: &mut DVector<f64>) -> bool {
        self.solve_work(gradient, d)
    }

    /// Solves `H d = −g` with the base values, adding `δ I` with growing `δ` while they are
    /// not positive definite.
    pub(super) fn solve_shifted(
        &mut self,
        gradient: &DVector<f64>,
        d: &mut DVector<f64>,
    ) -> Result<()> {
        let scale = self
            .diagonal
            .iter()
            .map(|&s| self.base[s].abs())
            .fold(0.0, f64::max)
            .max(1e-300);
        let mut shift = 0.0;
        for _ in 0..40 {
            self.reset_work();
            if shift > 0.0 {
                for k in 0..self.n {
                    self.work[self.diagonal[k]] += shift;
                }
            }
            if self.solve_work(gradient, d) {
                return Ok(());
            }
            shift = if shift == 0.0 {
                1e-10 * scale
            } else {
                shift * 10.0
            };
        }
        Err(Error::new(
            ErrorKind::SingularSystem,
            "the Newton matrix could not be made positive definite",
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scattered symmetric pattern whose factor fills in: entries `(i, i + 1)`,
    /// `(i, i + 4)` and `(i, 7i mod n)`.
    fn scattered(n: usize) -> SparseNewton {
        let entries = (0..n).flat_map(|i| {
            [(i + 1) % n, (i + 4) % n, (7 * i) % n]
                .into_iter()
                .flat_map(move |j| [(i, j), (j, i)])
        });
        SparseNewton::new(n, entries)
    }

    fn fill(m: &mut SparseNewton, value: impl Fn(usize, usize) -> f64) {
        m.clear();
        let entries: Vec<_> = m.entries().collect();
        for (i, j) in entries {
            m.add(i, j, value(i, j));
        }
        m.reset_work();
    }

    fn spd(i: usize, j: usize) -> f64 {
        if i == j {
            12.0 + (i % 5) as f64
        } else {
            0.3 + 0.05 * ((i * j) % 7) as f64
        }
    }

    /// After failed (indefinite) factorisations, failing in every column in turn, the next
    /// one on the same symbolic analysis solves bit for bit as a factorisation from scratch
    /// does.
    #[test]
    fn a_failed_factorisation_leaves_no_trace() {
        let n = 23;
        let gradient = DVector::from_fn(n, |i, _| 1.0 + (i as f64).sin());
        let mut fresh = scattered(n);
        fill(&mut fresh, spd);
        let mut expected = DVector::zeros(n);
        assert!(fresh.solve_definite(&gradient, &mut expected));
        let h = nalgebra::DMatrix::from_fn(n, n, |i, j| {
            if fresh.slot(i, j).is_some() {
                spd(i, j)
            } else {
                0.0
            }
        });
        assert!((h * &expected + &gradient).norm() < 1e-12);
        let mut d = DVector::zeros(n);
        let mut reused = scattered(n);
        for k in 1..n {
            // Indefinite in column k (the failure happens after columns 0..k wrote).
            fill(&mut reused, |i, j| {
                if i == k && j == k {
                    -100.0
                } else {
                    3.0 * spd(i, j) + 1.0
                }
            });
            assert!(!reused.solve_definite(&gradient, &mut d));
            fill(&mut reused, spd);
            assert!(reused.solve_definite(&gradient, &mut d));
            assert_eq!(d, expected, "after a failure in column {k}");
        }
    }

    /// The shifted solve after a failed curved one: the same as on a fresh factor.
    #[test]
    fn shifted_solves_reuse_the_symbolic_analysis() {
        let n = 23;
        let semidefinite = |i: usize, j: usize| if i == 0 || j == 0 { 1.0 } else { 0.0 };
        let gradient = DVector::from_element(n, 1.0);
        let mut d = DVector::zeros(n);
        let mut reused = scattered(n);
        fill(&mut reused, |i, j| if i == j { -1.0 } else { 2.0 });
        assert!(!reused.solve_definite(&gradient, &mut d));
        fill(&mut reused, semidefinite);
        reused.solve_shifted(&gradient, &mut d).expect("shifted");
        let mut fresh = scattered(n);
        fill(&mut fresh, semidefinite);
        let mut expected = DVector::zeros(n);
        fresh
            .solve_shifted(&gradient, &mut expected)
            .expect("shifted");
        assert_eq!(d, expected);
        assert!(d.iter().all(|v| v.is_finite()));
    }
}
