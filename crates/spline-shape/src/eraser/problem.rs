//! The eraser's optimisation problem on the true point-to-curve distances.
//!
//! Variables: the interleaved control-point coordinates `x = [x_1, y_1, …, x_n, y_n]` and,
//! for the minimax objective, a bound `z` on the squared distances (in units of its start
//! value). The squared distance of data point `Q_j` to the curve is
//! $d_j^2(x) = \min_u \lVert C(u; x) - Q_j \rVert^2$, evaluated at the foot point `u_j(x)`
//! found by a safeguarded Newton iteration from the previous one (variable projection: the
//! parameters are not unknowns of the problem, they follow `x`). Its gradient is that of
//! $\varphi(x, u) = \lVert C(u; x) - Q_j \rVert^2$ at `u_j` (envelope theorem) and its
//! Hessian the Schur complement $\varphi_{xx} - \varphi_{xu}\varphi_{ux}/\varphi_{uu}$.
//! The first and last data points keep the parameters of the curve's ends.
//!
//! Constraints: `d_j² < z` (minimax), and the sign conditions on the Bernstein coefficients
//! of `g` on the pieces of every segment (refined where active), shifted by `τ σ_i` during
//! the homotopy that starts from the least-squares fit (at `τ = 1` it is strictly feasible)
//! and ends at `τ = 0`.

use super::distances::{Distances, Foot};
use super::pieces::{Piece, subdivision_matrix};
use crate::barrier::BarrierProblem;
use crate::eraser::Objective;
use nalgebra::{DMatrix, DVector, Vector2};
use spline_algebra::{SegmentCurvature, SegmentWorkspace};
use spline_core::{KnotVector, Result};
use std::cell::RefCell;

mod barrier_form;
mod excursions;

/// Scratch memory of the segment kernel.
/// Scratch memory of the segment kernel and of the conditions, reused by every evaluation
/// (no allocation inside the solver's iterations once the buffers have their sizes).
struct Scratch {
    workspace: SegmentWorkspace<f64>,
    values: Vec<f64>,
    jacobian: Vec<f64>,
    /// The control points of the current `x`.
    control: Vec<Vector2<f64>>,
    /// The Bernstein coefficients of `g` of every segment, `q + 1` each.
    per_segment: Vec<f64>,
    /// Their Jacobians, `(q + 1) × local variables` each.
    segment_jacobians: Vec<f64>,
    /// `sign · (S g)` of every piece, `q + 1` each.
    signed: Vec<f64>,
    /// Hessian weights per segment coefficient, and one segment's weighted Hessian block.
    omega: Vec<f64>,
    block: Vec<f64>,
    /// A dense Hessian before it is scaled into the solver's matrix.
    dense: DMatrix<f64>,
    /// One row of the Jacobian while its entries are sorted by column.
    sorted_row: Vec<(usize, f64)>,
    /// One workspace per segment, holding its quadratic forms from the Jacobian's pass, and
    /// the control points they are of: the weighted Hessian at the same point (the next
    /// call of a Newton step) combines them without building them again.
    forms: Vec<SegmentWorkspace<f64>>,
    forms_control: Vec<Vector2<f64>>,
}

/// `‖C(u) − centre‖² < radius²` (the bounds of `excursions.rs`).
#[derive(Clone, Debug)]
struct Excursion {
    param: f64,
    centre: Vector2<f64>,
    radius2: f64,
}

/// `min z` (or `min Σ d_j²`) over the control points subject to the distance bounds and the
/// sign conditions on `g`.
pub(crate) struct EraserProblem {
    kernel: SegmentCurvature<f64>,
    pieces: Vec<Piece>,
    distances: Distances,
    objective: Objective,
    /// Number of free control points (the variables): all of them for an open curve; for a
    /// closed one, the first `N` of the wrapped container, whose last `p` repeat them.
    n: usize,
    /// Whether the curve is closed (periodic; the knots are the wrapped container's).
    closed: bool,
    /// Squared distances are divided by this (the largest at the start).
    unit: f64,
    /// Weight of the mean squared distance added to `z` in the minimax objective.
    mean_weight: f64,
    /// Homotopy parameter: the sign conditions are relaxed by `τ σ_i`.
    tau: f64,
    /// Phase I: `τ` is the last variable, the objective `τ + pull · F`, and `τ > −1`.
    relaxed: bool,
    pull: f64,
    first_sign: f64,
    extrema: Vec<f64>,
    /// The feet of the last control points evaluated (with derivatives or not).
    feet: RefCell<FeetCache>,
    /// Curve points between the foot points of consecutive data points, each kept in a
    /// disk around the middle of their chord: no loop or excursion between the data.
    excursions: Vec<Excursion>,
    scratch: RefCell<Scratch>,
}

/// The foot points of one set of control points.
#[derive(Default)]
struct FeetCache {
    control: Vec<f64>,
    derivatives: bool,
    feet: Vec<Foot>,
    /// The control points of `control` (of the wrapped container for a closed curve).
    points: Vec<Vector2<f64>>,
}

impl EraserProblem {
    /// The problem for `points` (at their foot-point parameters `params`) on `knots`, with
    /// the allowed extrema at the knots `extrema` and the curvature increasing on the first
    /// piece when `first_sign > 0`. For a `closed` curve, `knots` are those of the wrapped
    /// container of a periodic B-spline of period 1 on `[0, 1]` (`N + p` control points, the
    /// last `p` repeating the first), the variables its `N` free control points, and every
    /// foot point is free to cross the closing point.
    pub(crate) fn new(
        knots: &KnotVector<f64>,
        closed: bool,
        points: &[Vector2<f64>],
        params: &[f64],
        objective: Objective,
        extrema: Vec<f64>,
        first_sign: f64,
    ) -> Result<Self> {
        let kernel = SegmentCurvature::new(knots)?;
        let q1 = kernel.coefficients_per_segment();
        let scratch = Scratch {
            workspace: kernel.workspace(),
            values: vec![0.0; q1],
            jacobian: vec![0.0; q1 * kernel.local_variables()],
            control: Vec::new(),
            per_segment: Vec::new(),
            segment_jacobians: Vec::new(),
            signed: Vec::new(),
            omega: Vec::new(),
            block: Vec::new(),
            dense: DMatrix::zeros(0, 0),
            sorted_row: Vec::new(),
            forms: (0..kernel.num_segments())
                .map(|_| kernel.workspace())
                .collect(),
            forms_control: Vec::new(),
        };
        let mut problem = Self {
            pieces: Vec::new(),
            kernel,
            distances: Distances {
                knots: knots.clone(),
                points: points.to_vec(),
                params: RefCell::new(params.to_vec()),
                project: true,
                closed,
                form: RefCell::default(),
            },
            objective,
            // A closed curve's last p control points repeat its first p.
            n: knots.num_basis() - if closed { knots.degree() } else { 0 },
            closed,
            unit: 1.0,
            mean_weight: 1e-2,
            tau: 0.0,
            relaxed: false,
            pull: 1.0,
            first_sign,
            extrema,
            excursions: Vec::new(),
            feet: RefCell::new(FeetCache::default()),
            scratch: RefCell::new(scratch),
        };
        problem.pieces = (0..problem.kernel.num_segments())
            .map(|s| problem.piece(s, 0.0, 1.0))
            .collect();
        Ok(problem)
    }

    /// The variable of local coordinate `k = 2·i + c` (coordinate `c` of control point `i` of
    /// the container): itself for an open curve; a wrapped control point's is that of the
    /// control point it repeats.
    pub(super) fn column(&self, k: usize) -> usize {
        let point = k / 2;
        // The division only for a wrapped point (it costs tens of cycles in the assembly's
        // inner loops; an open curve has none).
        let point = if point < self.n {
            point
        } else {
            point % self.n
        };
        2 * point + k % 2
    }

    /// The variables of the local coordinates `first, first + 1, …` into `out` (one per
    /// entry): [`EraserProblem::column`] of each, looked up once for a whole block.
    pub(super) fn local_columns(&self, first: usize, out: &mut [usize]) {
        for (a, column) in out.iter_mut().enumerate() {
            *column = self.column(first + a);
        }
    }

    fn piece(&self, segment: usize, lo: f64, hi: f64) -> Piece {
        let (a, b) = self.kernel.interval(segment);
        let mid = a + (b - a) * 0.5 * (lo + hi);
        let crossed = self.extrema.iter().filter(|&&e| e <= mid).count();
        let sign = if crossed % 2 == 0 {
            self.first_sign
        } else {
            -self.first_sign
        };
        let q = self.kernel.coefficients_per_segment() - 1;
        Piece {
            segment,
            lo,
            hi,
            sign,
            subdivision: subdivision_matrix(q, lo, hi),
            scale: vec![1.0; q + 1],
            shift: vec![0.0; q + 1],
        }
    }

    /// Phase I on or off: with `relaxed`, `τ` becomes the last variable and the objective
    /// `τ + pull · F` (the fit `F` keeps the curve near the data while `τ` goes down).
    pub(crate) fn set_relaxed(&mut self, relaxed: bool, pull: f64) {
        self.relaxed = relaxed;
        self.pull = pull;
    }

    /// The weight of the fit in phase I.
    pub(crate) fn pull(&self) -> f64 {
        self.pull
    }

    /// The index of `τ` among the variables (phase I).
    pub(crate) fn tau_index(&self) -> usize {
        2 * self.n + usize::from(self.minimax())
    }

    /// The current `τ`: the variable in phase I, the parameter otherwise.
    fn tau_at(&self, x: &DVector<f64>) -> f64 {
        if self.relaxed {
            x[self.tau_index()]
        } else {
            self.tau
        }
    }

    /// Whether the problem has the variable `z`.
    fn minimax(&self) -> bool {
        self.objective == Objective::MaxDeviation
    }

    /// Number of distance constraints.
    fn num_distance_constraints(&self) -> usize {
        if self.minimax() {
            self.distances.points.len()
        } else {
            0
        }
    }

    /// The variables for control points `control` and the bound `z` (ignored for least
    /// squares).
    pub(crate) fn variables(&self, control: &[Vector2<f64>], z: f64) -> DVector<f64> {
        let mut x = DVector::zeros(self.dimension());
        for (i, c) in control.iter().take(self.n).enumerate() {
            x[2 * i] = c.x;
            x[2 * i + 1] = c.y;
        }
        if self.minimax() {
            x[2 * self.n] = z;
        }
        if self.relaxed {
            x[self.tau_index()] = self.tau;
        }
        x
    }

    /// The control points of `x` (of the wrapped container for a closed curve).
    pub(crate) fn control_points(&self, x: &DVector<f64>) -> Vec<Vector2<f64>> {
        let mut points = Vec::new();
        self.fill_control(x, &mut points);
        points
    }

    /// [`EraserProblem::control_points`] into `points` (its buffer reused).
    fn fill_control(&self, x: &DVector<f64>, points: &mut Vec<Vector2<f64>>) {
        points.clear();
        points.extend((0..self.distances.knots.num_basis()).map(|i| {
            let k = i % self.n;
            Vector2::new(x[2 * k], x[2 * k + 1])
        }));
    }

    /// Foot points follow the curve (`true`) or stay at their anchors (`false`).
    pub(crate) fn set_projection(&mut self, project: bool) {
        self.distances.project = project;
        *self.feet.borrow_mut() = FeetCache::default();
    }

    /// The anchors of the foot points.
    pub(crate) fn anchors(&self) -> Vec<f64> {
        self.distances.params.borrow().clone()
    }

    /// The curve point at `u`.
    fn curve_point(&self, control: &[Vector2<f64>], u: f64) -> Vector2<f64> {
        let knots = &self.distances.knots;
        let p = knots.degree();
        let mut basis = [0.0; spline_core::MAX_ORDER];
        let span = knots.span_in_domain(u);
        knots.basis_values(span, u, &mut basis[..=p]);
        (0..=p).map(|k| control[span - p + k] * basis[k]).sum()
    }

    /// Moves the anchors of the foot points to the foot points of the curve of `x`.
    pub(crate) fn commit(&self, x: &DVector<f64>) {
        {
            let feet = self.feet(x, false);
            let mut params = self.distances.params.borrow_mut();
            params.clear();
            params.extend(feet.feet.iter().map(|f| f.param));
        }
        // The anchors moved: evaluations start afresh (an empty key never matches; the
        // cache keeps its buffers, which every evaluation overwrites).
        self.feet.borrow_mut().control.clear();
    }

    /// The feet of the data on the curve of `x`, computed once per set of control points
    /// (into the cache's buffers: no allocation once they have their sizes).
    fn feet(&self, x: &DVector<f64>, derivatives: bool) -> std::cell::Ref<'_, FeetCache> {
        let key = &x.as_slice()[..2 * self.n];
        let (same, fresh) = {
            let cache = self.feet.borrow();
            let same = cache.control.as_slice() == key;
            (same, same && (cache.derivatives || !derivatives))
        };
        if same && !fresh {
            // The feet of these control points are known: only their derivatives are new.
            let mut cache = self.feet.borrow_mut();
            let FeetCache {
                derivatives: with_derivatives,
                feet,
                points,
                ..
            } = &mut *cache;
            *with_derivatives = true;
            self.distances.feet_into(points, true, true, feet);
        } else if !fresh {
            let mut cache = self.feet.borrow_mut();
            let FeetCache {
                control,
                derivatives: with_derivatives,
                feet,
                points,
            } = &mut *cache;
            control.clear();
            control.extend_from_slice(key);
            *with_derivatives = derivatives;
            self.fill_control(x, points);
            feet.resize_with(self.distances.points.len(), Foot::default);
            self.distances.feet_into(points, derivatives, false, feet);
        }
        self.feet.borrow()
    }

    /// The squared distances of the data at `x`.
    pub(crate) fn squared_distances(&self, x: &DVector<f64>) -> Vec<f64> {
        self.feet(x, false).feet.iter().map(|f| f.squared).collect()
    }

    /// Sets the unit of squared distances (the objective is then about 1 at the start).
    pub(crate) fn set_unit(&mut self, unit: f64) {
        self.unit = unit.max(f64::MIN_POSITIVE);
    }

    /// The number of sign conditions on `g`.
    pub(crate) fn num_conditions(&self) -> usize {
        self.pieces.len() * self.kernel.coefficients_per_segment()
    }

    /// `sign · (S g)` of every piece at `x` (positive when satisfied), unscaled, `q + 1`
    /// per piece, handed to `f` (computed in the scratch buffers).
    fn with_signed_coefficients<R>(&self, x: &DVector<f64>, f: impl FnOnce(&[f64]) -> R) -> R {
        let q1 = self.kernel.coefficients_per_segment();
        let mut scratch = self.scratch.borrow_mut();
        let Scratch {
            workspace,
            values,
            control,
            per_segment,
            signed,
            ..
        } = &mut *scratch;
        self.fill_control(x, control);
        per_segment.clear();
        for s in 0..self.kernel.num_segments() {
            self.kernel
                .segment(s, control, workspace, values, None, None);
            per_segment.extend_from_slice(values);
        }
        signed.clear();
        for piece in &self.pieces {
            let g = &per_segment[piece.segment * q1..(piece.segment + 1) * q1];
            signed.extend((0..q1).map(|r| {
                let row = &piece.subdivision[r * q1..(r + 1) * q1];
                piece.sign * row.iter().zip(g).map(|(a, b)| a * b).sum::<f64>()
            }));
        }
        f(signed)
    }

    /// [`EraserProblem::with_signed_coefficients`], one vector per piece.
    fn signed_coefficients(&self, x: &DVector<f64>) -> Vec<Vec<f64>> {
        let q1 = self.kernel.coefficients_per_segment();
        self.with_signed_coefficients(x, |c| c.chunks(q1).map(<[f64]>::to_vec).collect())
    }

    /// Scales every condition by its magnitude at `x` (floored at `1e-3` of the largest):
    /// a positive factor per condition leaves the feasible set alone, and puts the nose of an
    /// airfoil and its flat parts on one footing.
    pub(crate) fn rescale(&mut self, x: &DVector<f64>) {
        let coefficients = self.signed_coefficients(x);
        let largest = coefficients
            .iter()
            .flatten()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let floor = (1e-3 * largest).max(f64::MIN_POSITIVE);
        for (piece, c) in self.pieces.iter_mut().zip(&coefficients) {
            for (s, v) in piece.scale.iter_mut().zip(c) {
                *s = v.abs().max(floor);
            }
        }
    }

    /// Starts the homotopy at `x`: shifts `σ_i = max(0, −v_i(x)) + margin` so that `x` is
    /// strictly feasible at `τ = 1` (`v_i` the scaled signed coefficients). Returns whether
    /// any condition was violated.
    pub(crate) fn start_homotopy(&mut self, x: &DVector<f64>, margin: f64) -> bool {
        let coefficients = self.signed_coefficients(x);
        let mut violated = false;
        for (piece, c) in self.pieces.iter_mut().zip(&coefficients) {
            for ((shift, v), s) in piece.shift.iter_mut().zip(c).zip(&piece.scale) {
                let scaled = v / s;
                violated |= scaled <= 0.0;
                *shift = (-scaled).max(0.0) + margin;
            }
        }
        self.tau = 1.0;
        violated
    }

    /// Sets the homotopy parameter (outside phase I).
    pub(crate) fn set_tau(&mut self, tau: f64) {
        self.tau = tau.max(0.0);
    }

    /// Splits every piece whose smallest signed coefficient at `x` is below `relative` times
    /// its largest (an active condition, more conservative there than `g ≥ 0`) in two, unless
    /// it is shorter than `min_length` of its segment. Returns how many were split.
    /// Feasibility is kept: subdivision takes convex combinations of the coefficients. Only
    /// at `τ = 0`.
    pub(crate) fn refine_active(
        &mut self,
        x: &DVector<f64>,
        relative: f64,
        min_length: f64,
    ) -> usize {
        debug_assert!(self.tau == 0.0, "refinement after the homotopy");
        let coefficients = self.signed_coefficients(x);
        let largest_all = coefficients
            .iter()
            .flatten()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let mut next = Vec::with_capacity(self.pieces.len());
        let mut split = 0;
        for (piece, c) in self.pieces.iter().zip(&coefficients) {
            let largest = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let smallest = c.iter().copied().fold(f64::INFINITY, f64::min);
            if smallest < relative * largest
                && largest > 1e-12 * largest_all
                && piece.hi - piece.lo > 2.0 * min_length
            {
                let mid = 0.5 * (piece.lo + piece.hi);
                for (lo, hi) in [(piece.lo, mid), (mid, piece.hi)] {
                    let mut child = self.piece(piece.segment, lo, hi);
                    child.scale = piece.scale.clone();
                    next.push(child);
                }
                split += 1;
            } else {
                next.push(piece.clone());
            }
        }
        self.pieces = next;
        split
    }

    /// Adds the Hessian blocks of the objective and the distance constraints, weighted, into
    /// `out` (dense, variables in order).
    fn add_distance_hessians(
        &self,
        x: &DVector<f64>,
        objective_weight: f64,
        constraint_weights: Option<&DVector<f64>>,
        out: &mut DMatrix<f64>,
    ) {
        let feet = self.feet(x, true);
        let m = self.distances.points.len();
        let per_point_objective = match self.objective {
            Objective::MaxDeviation => self.mean_weight / (m as f64 * self.unit),
            Objective::LeastSquares => 1.0 / (m as f64 * self.unit),
        };
        for j in 0..m {
            let mut w = objective_weight * per_point_objective;
            if let Some(cw) = constraint_weights {
                w += cw[j] / self.unit;
            }
            if w == 0.0 {
                continue;
            }
            let foot = &feet.feet[j];
            let nl = foot.gradient.len();
            let base = 2 * foot.first;
            if !self.closed {
                // The local variables are consecutive columns: add the (symmetric) block
                // column by column.
                let rows = out.nrows();
                let matrix = out.as_mut_slice();
                for (b, block) in foot.hessian.chunks_exact(nl).enumerate() {
                    let start = (base + b) * rows + base;
                    for (o, h) in matrix[start..start + nl].iter_mut().zip(block) {
                        *o += w * h;
                    }
                }
                continue;
            }
            let mut columns = [0; 2 * spline_core::MAX_ORDER];
            let columns = &mut columns[..nl];
            self.local_columns(base, columns);
            for (&i, row) in columns.iter().zip(foot.hessian.chunks_exact(nl)) {
                for (&j, &h) in columns.iter().zip(row) {
                    out[(i, j)] += w * h;
                }
            }
        }
    }
}
