//! The eraser's problem in the interior-point method's terms: objective, constraints and
//! their derivatives as [`BarrierProblem`] asks for them.

use super::{EraserProblem, Scratch};
use crate::barrier::BarrierProblem;
use crate::eraser::Objective;
use nalgebra::{DMatrix, DVector, Vector2};
use nalgebra_sparse::{CooMatrix, CsrMatrix};

impl BarrierProblem for EraserProblem {
    fn dimension(&self) -> usize {
        2 * self.n + usize::from(self.minimax()) + usize::from(self.relaxed)
    }

    fn num_constraints(&self) -> usize {
        self.num_distance_constraints()
            + self.excursions.len()
            + self.num_conditions()
            + usize::from(self.relaxed)
    }

    fn objective(&self, x: &DVector<f64>) -> f64 {
        let d2 = self.squared_distances(x);
        let mean = d2.iter().sum::<f64>() / (d2.len() as f64 * self.unit);
        let fit = match self.objective {
            Objective::MaxDeviation => x[2 * self.n] + self.mean_weight * mean,
            Objective::LeastSquares => mean,
        };
        if self.relaxed {
            x[self.tau_index()] + self.pull * fit
        } else {
            fit
        }
    }

    fn objective_gradient(&self, x: &DVector<f64>) -> DVector<f64> {
        let feet = self.feet(x, true);
        let m = self.distances.points.len();
        let weight = match self.objective {
            Objective::MaxDeviation => self.mean_weight,
            Objective::LeastSquares => 1.0,
        } / (m as f64 * self.unit);
        let mut g = DVector::zeros(self.dimension());
        for foot in &feet.feet {
            for (a, v) in foot.gradient.iter().enumerate() {
                g[self.column(2 * foot.first + a)] += weight * v;
            }
        }
        if self.minimax() {
            g[2 * self.n] = 1.0;
        }
        if self.relaxed {
            g *= self.pull;
            g[self.tau_index()] = 1.0;
        }
        g
    }

    fn objective_hessian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        let mut dense = DMatrix::zeros(self.dimension(), self.dimension());
        let weight = if self.relaxed { self.pull } else { 1.0 };
        self.add_distance_hessians(x, weight, None, &mut dense);
        let mut coo = CooMatrix::new(self.dimension(), self.dimension());
        for j in 0..dense.ncols() {
            for i in 0..dense.nrows() {
                if dense[(i, j)] != 0.0 {
                    coo.push(i, j, dense[(i, j)]);
                }
            }
        }
        CsrMatrix::from(&coo)
    }

    fn constraints(&self, x: &DVector<f64>) -> DVector<f64> {
        let mut out = Vec::with_capacity(self.num_constraints());
        if self.minimax() {
            let z = x[2 * self.n];
            out.extend(
                self.squared_distances(x)
                    .iter()
                    .map(|d2| d2 / self.unit - z),
            );
        }
        {
            let mut scratch = self.scratch.borrow_mut();
            self.fill_control(x, &mut scratch.control);
            for e in &self.excursions {
                let c = self.curve_point(&scratch.control, e.param);
                out.push((c - e.centre).norm_squared() / e.radius2 - 1.0);
            }
        }
        let tau = self.tau_at(x);
        let q1 = self.kernel.coefficients_per_segment();
        self.with_signed_coefficients(x, |coefficients| {
            for (piece, c) in self.pieces.iter().zip(coefficients.chunks(q1)) {
                for ((v, s), shift) in c.iter().zip(&piece.scale).zip(&piece.shift) {
                    out.push(-v / s - tau * shift);
                }
            }
        });
        if self.relaxed {
            out.push(-tau - 1.0);
        }
        DVector::from_vec(out)
    }

    fn constraint_jacobian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        let q1 = self.kernel.coefficients_per_segment();
        let nl = self.kernel.local_variables();
        let mut scratch = self.scratch.borrow_mut();
        let Scratch {
            workspace,
            values,
            jacobian,
            control,
            segment_jacobians,
            ..
        } = &mut *scratch;
        self.fill_control(x, control);
        let rows = self.num_constraints();
        let mut offsets = Vec::with_capacity(rows + 1);
        let mut cols = Vec::with_capacity(rows * (nl + 1));
        let mut vals = Vec::with_capacity(rows * (nl + 1));
        offsets.push(0);
        if self.minimax() {
            let feet = self.feet(x, true);
            for foot in &feet.feet {
                for (a, v) in foot.gradient.iter().enumerate() {
                    cols.push(self.column(2 * foot.first + a));
                    vals.push(v / self.unit);
                }
                cols.push(2 * self.n);
                vals.push(-1.0);
                offsets.push(cols.len());
            }
        }
        let p = self.distances.knots.degree();
        let mut basis = [0.0; spline_core::MAX_ORDER];
        for e in &self.excursions {
            let span = self.distances.knots.span_in_domain(e.param);
            self.distances
                .knots
                .basis_values(span, e.param, &mut basis[..=p]);
            let c: Vector2<f64> = (0..=p).map(|k| control[span - p + k] * basis[k]).sum();
            let r = (c - e.centre) * (2.0 / e.radius2);
            for (k, b) in basis[..=p].iter().enumerate() {
                cols.push(self.column(2 * (span - p + k)));
                vals.push(b * r.x);
                cols.push(self.column(2 * (span - p + k) + 1));
                vals.push(b * r.y);
            }
            offsets.push(cols.len());
        }
        segment_jacobians.clear();
        for s in 0..self.kernel.num_segments() {
            self.kernel
                .segment(s, control, workspace, values, Some(jacobian), None);
            segment_jacobians.extend_from_slice(jacobian);
        }
        let block = q1 * nl;
        for piece in &self.pieces {
            let first = 2 * self.kernel.first_point(piece.segment);
            let jac = &segment_jacobians[piece.segment * block..(piece.segment + 1) * block];
            for r in 0..q1 {
                let sub = &piece.subdivision[r * q1..(r + 1) * q1];
                let factor = -piece.sign / piece.scale[r];
                for c in 0..nl {
                    let mut acc = 0.0;
                    for (k, &s) in sub.iter().enumerate() {
                        acc += s * jac[k * nl + c];
                    }
                    cols.push(self.column(first + c));
                    vals.push(factor * acc);
                }
                if self.relaxed {
                    cols.push(self.tau_index());
                    vals.push(-piece.shift[r]);
                }
                offsets.push(cols.len());
            }
        }
        if self.relaxed {
            cols.push(self.tau_index());
            vals.push(-1.0);
            offsets.push(cols.len());
        }
        if self.closed {
            // Wrapped control points fold onto the first ones: restore the column order.
            sort_rows(&offsets, &mut cols, &mut vals);
        }
        CsrMatrix::try_from_csr_data(rows, self.dimension(), offsets, cols, vals)
            .expect("rows of increasing columns")
    }

    fn weighted_constraint_hessian(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
    ) -> Option<CsrMatrix<f64>> {
        let mut dense = DMatrix::zeros(self.dimension(), self.dimension());
        self.add_weighted_constraint_hessian(x, weights, &mut dense);
        let mut coo = CooMatrix::new(self.dimension(), self.dimension());
        for j in 0..dense.ncols() {
            for i in 0..dense.nrows() {
                if dense[(i, j)] != 0.0 {
                    coo.push(i, j, dense[(i, j)]);
                }
            }
        }
        Some(CsrMatrix::from(&coo))
    }

    fn add_weighted_constraint_hessian(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
        out: &mut DMatrix<f64>,
    ) -> bool {
        let md = self.num_distance_constraints();
        if md > 0 {
            let w = weights.rows(0, md).into_owned();
            self.add_distance_hessians(x, 0.0, Some(&w), out);
        }
        let p = self.distances.knots.degree();
        let mut basis = [0.0; spline_core::MAX_ORDER];
        for (k, e) in self.excursions.iter().enumerate() {
            let w = weights[md + k] * 2.0 / e.radius2;
            let span = self.distances.knots.span_in_domain(e.param);
            self.distances
                .knots
                .basis_values(span, e.param, &mut basis[..=p]);
            for a in 0..=p {
                for b in 0..=p {
                    let v = w * basis[a] * basis[b];
                    let (i, j) = (2 * (span - p + a), 2 * (span - p + b));
                    out[(self.column(i), self.column(j))] += v;
                    out[(self.column(i + 1), self.column(j + 1))] += v;
                }
            }
        }
        let md = md + self.excursions.len();
        let q1 = self.kernel.coefficients_per_segment();
        let nl = self.kernel.local_variables();
        let mut scratch = self.scratch.borrow_mut();
        let Scratch {
            workspace,
            values,
            control,
            omega,
            block,
            ..
        } = &mut *scratch;
        omega.clear();
        omega.resize(q1 * self.kernel.num_segments(), 0.0);
        for (p, piece) in self.pieces.iter().enumerate() {
            for r in 0..q1 {
                let w = weights[md + p * q1 + r] * (-piece.sign / piece.scale[r]);
                if w == 0.0 {
                    continue;
                }
                let o = &mut omega[piece.segment * q1..(piece.segment + 1) * q1];
                for (k, o) in o.iter_mut().enumerate() {
                    *o += w * piece.subdivision[r * q1 + k];
                }
            }
        }
        self.fill_control(x, control);
        block.resize(nl * nl, 0.0);
        for (s, w) in omega.chunks(q1).enumerate() {
            block.iter_mut().for_each(|b| *b = 0.0);
            self.kernel
                .segment(s, control, workspace, values, None, Some((w, block)));
            let first = 2 * self.kernel.first_point(s);
            for a in 0..nl {
                for b in 0..nl {
                    out[(self.column(first + a), self.column(first + b))] += block[a * nl + b];
                }
            }
        }
        true
    }
}

/// Sorts the entries of every CSR row by column (the rows of a closed curve's conditions
/// wrap around the control polygon).
fn sort_rows(offsets: &[usize], cols: &mut [usize], vals: &mut [f64]) {
    let mut row: Vec<(usize, f64)> = Vec::new();
    for w in offsets.windows(2) {
        row.clear();
        row.extend(
            cols[w[0]..w[1]]
                .iter()
                .copied()
                .zip(vals[w[0]..w[1]].iter().copied()),
        );
        row.sort_by_key(|&(c, _)| c);
        for (k, (c, v)) in row.iter().enumerate() {
            cols[w[0] + k] = *c;
            vals[w[0] + k] = *v;
        }
    }
}
