//! The eraser's problem in the interior-point method's terms: objective, constraints and
//! their derivatives as [`BarrierProblem`] asks for them.

use super::{EraserProblem, Scratch};
use crate::barrier::{BarrierProblem, SparseRows};
use crate::eraser::Objective;
use nalgebra::{DMatrix, DVector, Vector2};
use nalgebra_sparse::{CooMatrix, CsrMatrix};

/// The most local variables of a segment: `2(p + 1)` for the highest degree a knot vector
/// allows.
const MAX_LOCAL: usize = 2 * spline_core::MAX_ORDER;

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
        let feet = self.feet(x, false);
        let sum = feet.feet.iter().map(|f| f.squared).sum::<f64>();
        let mean = sum / (feet.feet.len() as f64 * self.unit);
        drop(feet);
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
        let mut g = DVector::zeros(self.dimension());
        self.objective_gradient_into(x, &mut g);
        g
    }

    fn objective_gradient_into(&self, x: &DVector<f64>, g: &mut DVector<f64>) {
        let feet = self.feet(x, true);
        let m = self.distances.points.len();
        let weight = match self.objective {
            Objective::MaxDeviation => self.mean_weight,
            Objective::LeastSquares => 1.0,
        } / (m as f64 * self.unit);
        g.fill(0.0);
        for foot in &feet.feet {
            for (a, v) in foot.gradient.iter().enumerate() {
                g[self.column(2 * foot.first + a)] += weight * v;
            }
        }
        if self.minimax() {
            g[2 * self.n] = 1.0;
        }
        if self.relaxed {
            *g *= self.pull;
            g[self.tau_index()] = 1.0;
        }
    }

    fn objective_hessian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        let mut dense = DMatrix::zeros(self.dimension(), self.dimension());
        let weight = if self.relaxed { self.pull } else { 1.0 };
        self.add_distance_hessians(x, weight, None, &mut dense);
        sparse_of(&dense)
    }

    fn add_objective_hessian(&self, x: &DVector<f64>, scale: f64, out: &mut DMatrix<f64>) {
        // The Hessian as its own matrix first, then scaled entry by entry: the sums of the
        // owned form.
        let n = self.dimension();
        let mut scratch = self.scratch.borrow_mut();
        let dense = &mut scratch.dense;
        if dense.nrows() != n {
            *dense = DMatrix::zeros(n, n);
        }
        dense.fill(0.0);
        let weight = if self.relaxed { self.pull } else { 1.0 };
        self.add_distance_hessians(x, weight, None, dense);
        debug_assert_eq!(out.shape(), dense.shape());
        for (o, &v) in out.as_mut_slice().iter_mut().zip(dense.as_slice()) {
            if v != 0.0 {
                *o += scale * v;
            }
        }
    }

    fn constraints(&self, x: &DVector<f64>) -> DVector<f64> {
        let mut out = DVector::zeros(self.num_constraints());
        self.constraints_into(x, &mut out);
        out
    }

    fn constraints_into(&self, x: &DVector<f64>, out: &mut DVector<f64>) {
        let mut k = 0;
        if self.minimax() {
            let z = x[2 * self.n];
            for foot in &self.feet(x, false).feet {
                out[k] = foot.squared / self.unit - z;
                k += 1;
            }
        }
        {
            let mut scratch = self.scratch.borrow_mut();
            self.fill_control(x, &mut scratch.control);
            for e in &self.excursions {
                let c = self.curve_point(&scratch.control, e.param);
                out[k] = (c - e.centre).norm_squared() / e.radius2 - 1.0;
                k += 1;
            }
        }
        let tau = self.tau_at(x);
        let q1 = self.kernel.coefficients_per_segment();
        self.with_signed_coefficients(x, |coefficients| {
            for (piece, c) in self.pieces.iter().zip(coefficients.chunks(q1)) {
                for ((v, s), shift) in c.iter().zip(&piece.scale).zip(&piece.shift) {
                    out[k] = -v / s - tau * shift;
                    k += 1;
                }
            }
        });
        if self.relaxed {
            out[k] = -tau - 1.0;
        }
    }

    fn constraint_jacobian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        let mut rows = SparseRows::new(self.dimension());
        self.constraint_jacobian_into(x, &mut rows);
        rows.to_csr()
    }

    fn constraint_jacobian_into(&self, x: &DVector<f64>, out: &mut SparseRows) {
        let q1 = self.kernel.coefficients_per_segment();
        let nl = self.kernel.local_variables();
        out.clear(self.dimension());
        // Rows are appended whole (`push_row`): one length update per row, not per entry.
        let mut row_columns = [0; MAX_LOCAL + 1];
        if self.minimax() {
            let feet = self.feet(x, true);
            for foot in &feet.feet {
                let k = foot.gradient.len();
                self.local_columns(2 * foot.first, &mut row_columns[..k]);
                row_columns[k] = 2 * self.n;
                let values = out.push_row(&row_columns[..=k]);
                for (value, v) in values.iter_mut().zip(&foot.gradient) {
                    *value = v / self.unit;
                }
                values[k] = -1.0;
            }
        }
        let mut scratch = self.scratch.borrow_mut();
        let Scratch {
            values,
            jacobian,
            control,
            segment_jacobians,
            sorted_row,
            forms,
            forms_control,
            ..
        } = &mut *scratch;
        self.fill_control(x, control);
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
                out.push(self.column(2 * (span - p + k)), b * r.x);
                out.push(self.column(2 * (span - p + k) + 1), b * r.y);
            }
            out.end_row();
        }
        segment_jacobians.clear();
        for (s, forms) in forms.iter_mut().enumerate() {
            self.kernel
                .segment(s, control, forms, values, Some(jacobian), None);
            segment_jacobians.extend_from_slice(jacobian);
        }
        forms_control.clone_from(control);
        let block = q1 * nl;
        let mut row = [0.0; MAX_LOCAL];
        let row = &mut row[..nl];
        // A piece's rows: its segment's local variables, then τ in phase I.
        let width = nl + usize::from(self.relaxed);
        row_columns[nl] = self.tau_index();
        for piece in &self.pieces {
            let first = 2 * self.kernel.first_point(piece.segment);
            self.local_columns(first, &mut row_columns[..nl]);
            let jac = &segment_jacobians[piece.segment * block..(piece.segment + 1) * block];
            for r in 0..q1 {
                let sub = &piece.subdivision[r * q1..(r + 1) * q1];
                let factor = -piece.sign / piece.scale[r];
                // Row r of sub · jac, the rows of jac added in turn (each entry the same sum,
                // in the same order, as a dot product down a column of jac).
                row.fill(0.0);
                for (&s, jac_row) in sub.iter().zip(jac.chunks_exact(nl)) {
                    for (acc, &j) in row.iter_mut().zip(jac_row) {
                        *acc += s * j;
                    }
                }
                let values = out.push_row(&row_columns[..width]);
                for (value, &acc) in values.iter_mut().zip(row.iter()) {
                    *value = factor * acc;
                }
                if self.relaxed {
                    values[nl] = -piece.shift[r];
                }
            }
        }
        if self.relaxed {
            out.push(self.tau_index(), -1.0);
            out.end_row();
        }
        if self.closed {
            // Wrapped control points fold onto the first ones: restore the column order.
            sort_rows(out, sorted_row);
        }
    }

    fn weighted_constraint_hessian(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
    ) -> Option<CsrMatrix<f64>> {
        let mut dense = DMatrix::zeros(self.dimension(), self.dimension());
        self.add_weighted_constraint_hessian(x, weights, &mut dense);
        Some(sparse_of(&dense))
    }

    fn add_weighted_constraint_hessian(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
        out: &mut DMatrix<f64>,
    ) -> bool {
        let md = self.num_distance_constraints();
        if md > 0 {
            // The first `md` weights are those of the distance constraints.
            self.add_distance_hessians(x, 0.0, Some(weights), out);
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
            forms,
            forms_control,
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
        // The forms of the Jacobian's pass, if it was at these control points.
        let built = forms_control == control;
        block.resize(nl * nl, 0.0);
        let mut columns = [0; MAX_LOCAL];
        let columns = &mut columns[..nl];
        for (s, w) in omega.chunks(q1).enumerate() {
            block.iter_mut().for_each(|b| *b = 0.0);
            if built {
                self.kernel
                    .add_segment_hessian(s, &mut forms[s], (w, block));
            } else {
                self.kernel
                    .segment(s, control, workspace, values, None, Some((w, block)));
            }
            let first = 2 * self.kernel.first_point(s);
            self.local_columns(first, columns);
            for (a, &i) in columns.iter().enumerate() {
                for (&j, &v) in columns.iter().zip(&block[a * nl..(a + 1) * nl]) {
                    out[(i, j)] += v;
                }
            }
        }
        true
    }
}

/// The non-zero entries of a dense matrix as a sparse one.
fn sparse_of(dense: &DMatrix<f64>) -> CsrMatrix<f64> {
    let mut coo = CooMatrix::new(dense.nrows(), dense.ncols());
    for j in 0..dense.ncols() {
        for i in 0..dense.nrows() {
            if dense[(i, j)] != 0.0 {
                coo.push(i, j, dense[(i, j)]);
            }
        }
    }
    CsrMatrix::from(&coo)
}

/// Sorts the entries of every row by column (the rows of a closed curve's conditions wrap
/// around the control polygon), through the reused buffer `row`.
fn sort_rows(rows: &mut SparseRows, row: &mut Vec<(usize, f64)>) {
    let (offsets, cols, vals) = rows.parts_mut();
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
