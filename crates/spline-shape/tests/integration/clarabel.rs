//! A second opinion on the interior-point method: the convex problems of thesis ch. 5
//! (least squares under linear sign conditions on derivatives — quadratic programs) solved
//! by Clarabel, a well-kept interior-point solver written independently, from matrices built
//! here (collocation by spline-core's basis functions, derivatives by spline-algebra's maps).
//! Costs and solutions agree to 1e-8.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
};
use nalgebra::{DMatrix, DVector};
use spline_algebra::SplineMap;
use spline_core::KnotVector;
use spline_shape::{BarrierOptions, FunctionApproximation, Sign, SurfaceApproximation};
use std::f64::consts::PI;

/// The collocation matrix `A_{ji} = N_i(u_j)`.
fn collocation(knots: &KnotVector<f64>, params: &[f64]) -> DMatrix<f64> {
    let n = knots.num_basis();
    let p = knots.degree();
    let mut a = DMatrix::zeros(params.len(), n);
    let mut basis = vec![0.0; p + 1];
    for (j, &u) in params.iter().enumerate() {
        let span = knots.find_span(u).unwrap();
        knots.basis_values(span, u, &mut basis);
        for (k, v) in basis.iter().enumerate() {
            a[(j, span - p + k)] = *v;
        }
    }
    a
}

fn dense(map: &SplineMap<f64>) -> DMatrix<f64> {
    let m = map.matrix();
    let mut out = DMatrix::zeros(m.nrows(), m.ncols());
    for (i, j, v) in m.triplet_iter() {
        out[(i, j)] = *v;
    }
    out
}

fn csc(m: &DMatrix<f64>, upper_only: bool) -> CscMatrix<f64> {
    let (mut rows, mut cols, mut vals) = (Vec::new(), Vec::new(), Vec::new());
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            if m[(i, j)] != 0.0 && (!upper_only || i <= j) {
                rows.push(i);
                cols.push(j);
                vals.push(m[(i, j)]);
            }
        }
    }
    CscMatrix::new_from_triplets(m.nrows(), m.ncols(), rows, cols, vals)
}

/// Clarabel's solution of `min ½‖A x − b‖²` s.t. `D x ≥ 0`, and its cost.
fn clarabel(a: &DMatrix<f64>, b: &DVector<f64>, d: &DMatrix<f64>) -> (DVector<f64>, f64) {
    let p = a.transpose() * a;
    let q = -(a.transpose() * b);
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .tol_gap_abs(1e-11)
        .tol_gap_rel(1e-11)
        .tol_feas(1e-11)
        .max_iter(400)
        .build()
        .unwrap();
    let cones = [NonnegativeConeT(d.nrows())];
    let mut solver = DefaultSolver::new(
        &csc(&p, true),
        q.as_slice(),
        &csc(&(-d), false),
        &vec![0.0; d.nrows()],
        &cones,
        settings,
    )
    .unwrap();
    solver.solve();
    assert!(
        matches!(
            solver.solution.status,
            SolverStatus::Solved | SolverStatus::AlmostSolved
        ),
        "{:?}",
        solver.solution.status
    );
    let x = DVector::from_vec(solver.solution.x.clone());
    let cost = 0.5 * (a * &x - b).norm_squared();
    (x, cost)
}

fn tight() -> BarrierOptions {
    BarrierOptions {
        gap_tolerance: 1e-12,
        newton_tolerance: 1e-15,
        ..BarrierOptions::default()
    }
}

fn assert_agree(what: &str, ours: (&DVector<f64>, f64), theirs: (&DVector<f64>, f64)) {
    let (x, cost) = ours;
    let (y, reference) = theirs;
    assert!(
        (cost - reference).abs() <= 1e-8 * reference.abs().max(1.0),
        "{what}: cost {cost} vs Clarabel {reference}"
    );
    let scale = y.amax().max(1.0);
    let worst = (x - y).amax();
    assert!(
        worst <= 1e-8 * scale,
        "{what}: solutions differ by {worst:e} (scale {scale})"
    );
}

#[test]
fn functions_of_section_5_1_agree_with_clarabel() {
    let params: Vec<f64> = (0..=1256).map(|j| 0.01 * f64::from(j)).collect();
    type Target = fn(f64) -> f64;
    let cases: [(&str, usize, usize, Target); 4] = [
        ("5.1.3", 3, 0, f64::cos),
        ("5.1.4", 3, 1, |u| u.sin() + 0.5 * u),
        ("5.1.4 bis", 4, 2, |u| {
            (2.0 * u).cos() + 0.2 * (u - 2.0 * PI).powi(2)
        }),
        ("5.1.5", 5, 3, |u| {
            (2.0 * u).sin() + 0.05 * (u - 2.0 * PI).powi(3)
        }),
    ];
    for (what, degree, order, f) in cases {
        for n in [11, 40] {
            let values: Vec<f64> = params.iter().map(|&u| f(u)).collect();
            let approx = FunctionApproximation::uniform(degree, n, 0.0, 4.0 * PI)
                .unwrap()
                .sign(order, Sign::NonNegative)
                .options(tight());
            let ours = approx.fit(&params, &values).unwrap();
            let knots = approx.knots().clone();
            let a = collocation(&knots, &params);
            let b = DVector::from_vec(values);
            let d = dense(&SplineMap::derivative(&knots, order).unwrap());
            let (y, reference) = clarabel(&a, &b, &d);
            let x = DVector::from_column_slice(ours.spline.control_points());
            assert_agree(
                &format!("{what}, {n} coefficients"),
                (&x, ours.objective),
                (&y, reference),
            );
        }
    }
}

#[test]
fn a_nonnegative_surface_of_section_5_5_agrees_with_clarabel() {
    // s ≥ 0 for sin u sin v on [0, 4π]² (thesis §5.5.2), 10 × 10 coefficients.
    let grid: Vec<f64> = (0..=40).map(|k| 4.0 * PI * f64::from(k) / 40.0).collect();
    let mut values = Vec::with_capacity(grid.len() * grid.len());
    for &u in &grid {
        for &v in &grid {
            values.push(u.sin() * v.sin());
        }
    }
    let approx = SurfaceApproximation::uniform((3, 3), (10, 10), (0.0, 4.0 * PI), (0.0, 4.0 * PI))
        .unwrap()
        .sign(0, 0, Sign::NonNegative)
        .options(tight());
    let ours = approx.fit_grid(&grid, &grid, &values).unwrap();
    let (ku, kv) = approx.knots();
    // Row-major net (i along u): A = A_u ⊗ A_v, samples ordered (u outer, v inner).
    let a = collocation(ku, &grid).kronecker(&collocation(kv, &grid));
    let b = DVector::from_vec(values);
    let identity = DMatrix::identity(a.ncols(), a.ncols());
    let (y, reference) = clarabel(&a, &b, &identity);
    let x = DVector::from_iterator(a.ncols(), ours.surface.control_points().iter().copied());
    assert_agree("§5.5.2, 10 × 10", (&x, ours.objective), (&y, reference));
}
