//! Small sparse-matrix helpers on [`CsrMatrix`]: building from rows, products, sums,
//! Kronecker products and applying a matrix to control points of any type.

use nalgebra_sparse::CsrMatrix;
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar};

/// Builds a CSR matrix from rows of `(column, value)` pairs in any order; duplicates are summed.
pub(crate) fn csr_from_rows<T: Scalar>(ncols: usize, rows: Vec<Vec<(usize, T)>>) -> CsrMatrix<T> {
    let nrows = rows.len();
    let mut offsets = Vec::with_capacity(nrows + 1);
    let mut cols = Vec::new();
    let mut values = Vec::new();
    offsets.push(0);
    for mut row in rows {
        row.sort_by_key(|&(c, _)| c);
        let start = cols.len();
        for (c, v) in row {
            debug_assert!(c < ncols, "column {c} out of range {ncols}");
            if cols.len() > start && *cols.last().expect("non-empty") == c {
                let last = values.len() - 1;
                values[last] += v;
            } else {
                cols.push(c);
                values.push(v);
            }
        }
        offsets.push(cols.len());
    }
    CsrMatrix::try_from_csr_data(nrows, ncols, offsets, cols, values)
        .expect("rows are sorted and deduplicated")
}

/// Accumulates sparse rows with a dense scatter array (the classic SPA).
pub(crate) struct RowAccumulator<T> {
    values: Vec<T>,
    marks: Vec<bool>,
    touched: Vec<usize>,
}

impl<T: Scalar> RowAccumulator<T> {
    pub(crate) fn new(ncols: usize) -> Self {
        Self {
            values: vec![T::zero(); ncols],
            marks: vec![false; ncols],
            touched: Vec::new(),
        }
    }

    #[inline]
    pub(crate) fn add(&mut self, col: usize, value: T) {
        if self.marks[col] {
            self.values[col] += value;
        } else {
            self.marks[col] = true;
            self.values[col] = value;
            self.touched.push(col);
        }
    }

    /// Appends the accumulated row (sorted) to CSR arrays and resets.
    pub(crate) fn flush(&mut self, cols: &mut Vec<usize>, values: &mut Vec<T>) {
        self.touched.sort_unstable();
        for &c in &self.touched {
            cols.push(c);
            values.push(self.values[c]);
            self.marks[c] = false;
        }
        self.touched.clear();
    }
}

/// The product `a · b`.
///
/// # Panics
/// If the inner dimensions differ (an internal invariant).
pub(crate) fn matmul<T: Scalar>(a: &CsrMatrix<T>, b: &CsrMatrix<T>) -> CsrMatrix<T> {
    assert_eq!(a.ncols(), b.nrows(), "inner dimensions of a sparse product");
    let mut acc = RowAccumulator::new(b.ncols());
    let mut offsets = Vec::with_capacity(a.nrows() + 1);
    let mut cols = Vec::new();
    let mut values = Vec::new();
    offsets.push(0);
    for row in a.row_iter() {
        for (&k, &v) in row.col_indices().iter().zip(row.values()) {
            let brow = b.row(k);
            for (&j, &w) in brow.col_indices().iter().zip(brow.values()) {
                acc.add(j, v * w);
            }
        }
        acc.flush(&mut cols, &mut values);
        offsets.push(cols.len());
    }
    CsrMatrix::try_from_csr_data(a.nrows(), b.ncols(), offsets, cols, values)
        .expect("valid CSR product")
}

/// `alpha · a + beta · b`.
///
/// # Panics
/// If the shapes differ (an internal invariant).
pub(crate) fn add_scaled<T: Scalar>(
    alpha: T,
    a: &CsrMatrix<T>,
    beta: T,
    b: &CsrMatrix<T>,
) -> CsrMatrix<T> {
    assert_eq!(
        (a.nrows(), a.ncols()),
        (b.nrows(), b.ncols()),
        "shapes of a sparse sum"
    );
    let mut acc = RowAccumulator::new(a.ncols());
    let mut offsets = Vec::with_capacity(a.nrows() + 1);
    let mut cols = Vec::new();
    let mut values = Vec::new();
    offsets.push(0);
    for (ra, rb) in a.row_iter().zip(b.row_iter()) {
        for (&j, &v) in ra.col_indices().iter().zip(ra.values()) {
            acc.add(j, alpha * v);
        }
        for (&j, &v) in rb.col_indices().iter().zip(rb.values()) {
            acc.add(j, beta * v);
        }
        acc.flush(&mut cols, &mut values);
        offsets.push(cols.len());
    }
    CsrMatrix::try_from_csr_data(a.nrows(), a.ncols(), offsets, cols, values)
        .expect("valid CSR sum")
}

/// The Kronecker product `a ⊗ b`: entry `(i·rb + k, j·cb + l) = a_ij b_kl` — the matrix of a
/// tensor-product map on row-major grids (`x[i · n_b + k]`).
///
/// # Panics
///
/// Never for valid inputs: the product's CSR structure is valid by construction.
///
/// ```
/// use spline_algebra::{CsrMatrix, kron};
/// let a = CsrMatrix::identity(2);
/// let b = CsrMatrix::try_from_csr_data(1, 2, vec![0, 2], vec![0, 1], vec![1.0, 2.0]).unwrap();
/// let k = kron(&a, &b);
/// assert_eq!((k.nrows(), k.ncols(), k.nnz()), (2, 4, 4));
/// ```
#[must_use]
pub fn kron<T: Scalar>(a: &CsrMatrix<T>, b: &CsrMatrix<T>) -> CsrMatrix<T> {
    let mut offsets = Vec::with_capacity(a.nrows() * b.nrows() + 1);
    let mut cols = Vec::with_capacity(a.nnz() * b.nnz());
    let mut values = Vec::with_capacity(a.nnz() * b.nnz());
    offsets.push(0);
    for ra in a.row_iter() {
        for rb in b.row_iter() {
            for (&j, &v) in ra.col_indices().iter().zip(ra.values()) {
                for (&l, &w) in rb.col_indices().iter().zip(rb.values()) {
                    cols.push(j * b.ncols() + l);
                    values.push(v * w);
                }
            }
            offsets.push(cols.len());
        }
    }
    CsrMatrix::try_from_csr_data(
        a.nrows() * b.nrows(),
        a.ncols() * b.ncols(),
        offsets,
        cols,
        values,
    )
    .expect("valid Kronecker product")
}

/// Spreads the columns of `a` (`n` columns) over an interleaved vector of `dim · n` variables:
/// column `j` becomes `dim · j + coord`.
pub(crate) fn interleave_columns<T: Scalar>(
    a: &CsrMatrix<T>,
    dim: usize,
    coord: usize,
) -> CsrMatrix<T> {
    let (offsets, cols, values) = a.csr_data();
    CsrMatrix::try_from_csr_data(
        a.nrows(),
        a.ncols() * dim,
        offsets.to_vec(),
        cols.iter().map(|&j| dim * j + coord).collect(),
        values.to_vec(),
    )
    .expect("valid interleaved matrix")
}

/// `y = A x` for control points of any type.
pub(crate) fn apply_points<T: Scalar, P: ControlPoint<T>>(a: &CsrMatrix<T>, x: &[P]) -> Vec<P> {
    debug_assert_eq!(a.ncols(), x.len());
    a.row_iter()
        .map(|row| {
            let mut acc = P::origin();
            for (&j, &v) in row.col_indices().iter().zip(row.values()) {
                acc += x[j] * v;
            }
            acc
        })
        .collect()
}

/// The `n × n` identity.
pub(crate) fn identity<T: Scalar>(n: usize) -> CsrMatrix<T> {
    CsrMatrix::try_from_csr_data(n, n, (0..=n).collect(), (0..n).collect(), vec![T::one(); n])
        .expect("valid identity")
}

pub(crate) fn check_len(what: &str, expected: usize, got: usize) -> Result<()> {
    if expected == got {
        Ok(())
    } else {
        Err(Error::new(
            ErrorKind::InvalidLength,
            format!("{what}: expected {expected} coefficients, got {got}"),
        ))
    }
}
