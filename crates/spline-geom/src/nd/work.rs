//! The working memory of [`super::NdSpline`]'s evaluations: the knot vectors of the
//! dimensions with their batch tables, and the basis rows and odometer of one batch.

use spline_core::{BatchBasis, Error, ErrorKind, KnotVector, Result};

/// The knot vectors of the dimensions with their batch tables and the row strides of the
/// coefficient array.
#[derive(Clone, Debug)]
pub(super) struct Dims {
    pub(super) knots: Vec<KnotVector<f64>>,
    pub(super) batches: Vec<BatchBasis<f64>>,
    /// `n_e`, the number of basis functions of each dimension.
    pub(super) shape: Vec<usize>,
    /// Row-major strides of the coefficient array in rows (the last is 1).
    pub(super) strides: Vec<usize>,
    /// The product of the shape (the number of coefficient rows).
    pub(super) rows: usize,
}

impl Dims {
    pub(super) fn new(knots: Vec<KnotVector<f64>>) -> Result<Self> {
        if knots.is_empty() {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "a tensor-product spline needs at least one dimension",
            )
            .with_counts(1, 0));
        }
        let shape: Vec<usize> = knots.iter().map(KnotVector::num_basis).collect();
        let mut strides = vec![1usize; shape.len()];
        let mut rows = 1usize;
        for e in (0..shape.len()).rev() {
            strides[e] = rows;
            rows = rows.checked_mul(shape[e]).ok_or_else(|| {
                Error::new(
                    ErrorKind::InvalidLength,
                    "the coefficient array of the tensor product has too many entries",
                )
            })?;
        }
        let batches = knots.iter().map(BatchBasis::new).collect();
        Ok(Self {
            knots,
            batches,
            shape,
            strides,
            rows,
        })
    }

    pub(super) fn ndim(&self) -> usize {
        self.knots.len()
    }

    pub(super) fn widths(&self) -> impl Iterator<Item = usize> + '_ {
        self.knots.iter().map(|k| k.degree() + 1)
    }

    /// The number of products per point, $\prod_e (k_e + 1)$, checked.
    pub(super) fn terms(&self) -> Result<usize> {
        self.widths()
            .try_fold(1usize, usize::checked_mul)
            .ok_or_else(|| {
                Error::new(
                    ErrorKind::InvalidLength,
                    "the tensor product has too many basis functions per point",
                )
            })
    }

    /// Checks `xi` (points × d) and returns the number of points.
    pub(super) fn points(&self, xi: &[f64]) -> Result<usize> {
        let d = self.ndim();
        if xi.len() % d != 0 {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "{} coordinates do not make points of {d} coordinates (ndim = {d})",
                    xi.len()
                ),
            ));
        }
        Ok(xi.len() / d)
    }
}

/// The working memory of one batch of evaluations (allocated once per call).
pub(super) struct Work {
    /// The basis rows of every dimension, concatenated (`k_e + 1` each).
    pub(super) basis: Vec<f64>,
    /// Where each dimension's row starts in `basis`.
    pub(super) offsets: Vec<usize>,
    pub(super) widths: Vec<usize>,
    /// Room for one table of basis derivatives.
    pub(super) scratch: Vec<f64>,
    pub(super) hints: Vec<usize>,
    /// The odometer over the multi-index of the tensor sum, the partial products of the
    /// basis values and the partial row offsets of the levels above the innermost.
    pub(super) index: Vec<usize>,
    pub(super) partial: Vec<f64>,
    pub(super) base: Vec<usize>,
}

impl Work {
    pub(super) fn new(dims: &Dims, nu: &[usize]) -> Self {
        let widths: Vec<usize> = dims.widths().collect();
        let mut offsets = Vec::with_capacity(widths.len());
        let mut total = 0;
        for &w in &widths {
            offsets.push(total);
            total += w;
        }
        let scratch = widths
            .iter()
            .zip(nu)
            .map(|(&w, &n)| (n + 1) * w)
            .max()
            .unwrap_or(0);
        let d = widths.len();
        Self {
            basis: vec![0.0; total],
            offsets,
            widths,
            scratch: vec![0.0; scratch],
            hints: vec![usize::MAX; d],
            index: vec![0; d],
            partial: vec![0.0; d],
            base: vec![0; d],
        }
    }

    /// Basis values (`nu == 0`) or derivatives of order `nu ≤ k` of dimension `e` at `u`
    /// into `out[..k + 1]`, with the span, or `None` where the point gives NaN (`u` not
    /// finite, or outside the base interval without extrapolation). `scratch` holds at least
    /// `(nu + 1)(k + 1)` values. Writes the row into `self.basis`.
    #[inline(always)]
    pub(super) fn basis(
        &mut self,
        dims: &Dims,
        e: usize,
        u: f64,
        nu: usize,
        extrapolate: bool,
    ) -> Option<usize> {
        let hint = self.hints[e];
        let o = self.offsets[e];
        let out = &mut self.basis[o..o + self.widths[e]];
        let scratch = &mut self.scratch;
        let kv = &dims.knots[e];
        let (a, b) = kv.domain();
        let inside = u >= a && u <= b;
        if !u.is_finite() || (!extrapolate && !inside) {
            return None;
        }
        let k = kv.degree();
        let w = k + 1;
        if nu > 0 {
            let span = if inside {
                dims.batches[e].span_from(kv, u, hint)
            } else {
                kv.span_in_domain(u)
            };
            kv.basis_derivatives(span, u, nu, scratch);
            out[..w].copy_from_slice(&scratch[nu * w..(nu + 1) * w]);
            return Some(span);
        }
        if !inside {
            let span = kv.span_in_domain(u);
            kv.basis_values(span, u, out);
            return Some(span);
        }
        let batch = &dims.batches[e];
        macro_rules! fixed {
            ($n:literal) => {{
                let (span, v) = batch.eval_fixed_from::<$n>(kv, u, hint);
                out[..$n].copy_from_slice(&v);
                span
            }};
        }
        Some(match k {
            1 => fixed!(2),
            2 => fixed!(3),
            3 => fixed!(4),
            4 => fixed!(5),
            5 => fixed!(6),
            _ => {
                let span = batch.span_from(kv, u, hint);
                kv.basis_values(span, u, out);
                span
            }
        })
    }

    /// Fills the basis rows for point `x`; returns the first coefficient row of the
    /// tensor sum, or `None` for a NaN row.
    #[inline(always)]
    pub(super) fn prepare(
        &mut self,
        dims: &Dims,
        x: &[f64],
        nu: &[usize],
        extrapolate: bool,
    ) -> Option<usize> {
        let mut first = 0;
        for (e, &u) in x.iter().enumerate() {
            let w = self.widths[e];
            let span = self.basis(dims, e, u, nu[e], extrapolate)?;
            self.hints[e] = span;
            first += (span + 1 - w) * dims.strides[e];
        }
        Some(first)
    }

    /// Calls `f(row, weight, inner)` for every line of the tensor sum at the prepared point
    /// along the last dimension: the coefficient rows `row ..` (as many as `inner`, the
    /// last dimension's basis row) enter with the weights `weight · inner[i]`, `weight`
    /// the product of the other dimensions' basis values (rows in increasing order).
    #[inline(always)]
    pub(super) fn for_each_line(
        &mut self,
        dims: &Dims,
        first: usize,
        mut f: impl FnMut(usize, f64, &[f64]),
    ) {
        let d = self.widths.len();
        // One, two and three dimensions as plain loops (the same products in the same
        // order as the odometer below).
        match d {
            1 => {
                f(first, 1.0, &self.basis[..self.widths[0]]);
                return;
            }
            2 => {
                let (b0, b1) = self.basis.split_at(self.widths[0]);
                let s0 = dims.strides[0];
                for (i0, &v0) in b0.iter().enumerate() {
                    f(first + i0 * s0, v0, b1);
                }
                return;
            }
            3 => {
                let (b0, rest) = self.basis.split_at(self.widths[0]);
                let (b1, b2) = rest.split_at(self.widths[1]);
                let (s0, s1) = (dims.strides[0], dims.strides[1]);
                for (i0, &v0) in b0.iter().enumerate() {
                    let r0 = first + i0 * s0;
                    for (i1, &v1) in b1.iter().enumerate() {
                        f(r0 + i1 * s1, v0 * v1, b2);
                    }
                }
                return;
            }
            _ => {}
        }
        let last = d - 1;
        for l in 0..last {
            self.index[l] = 0;
            let (p, b) = if l == 0 {
                (1.0, first)
            } else {
                (self.partial[l - 1], self.base[l - 1])
            };
            self.partial[l] = p * self.basis[self.offsets[l]];
            self.base[l] = b;
        }
        let inner = &self.basis[self.offsets[last]..self.offsets[last] + self.widths[last]];
        loop {
            let (p, b) = if last == 0 {
                (1.0, first)
            } else {
                (self.partial[last - 1], self.base[last - 1])
            };
            f(b, p, inner);
            // Advance the odometer over the outer levels.
            let mut l = last;
            loop {
                if l == 0 {
                    return;
                }
                l -= 1;
                self.index[l] += 1;
                if self.index[l] < self.widths[l] {
                    break;
                }
                self.index[l] = 0;
            }
            for j in l..last {
                let (p, b) = if j == 0 {
                    (1.0, first)
                } else {
                    (self.partial[j - 1], self.base[j - 1])
                };
                let i = self.index[j];
                self.partial[j] = p * self.basis[self.offsets[j] + i];
                self.base[j] = b + i * dims.strides[j];
            }
        }
    }
}
