//! The interior-point solver on problems with known solutions.

use nalgebra::DVector;
use nalgebra_sparse::{CooMatrix, CsrMatrix};
use spline_core::ErrorKind;
use spline_shape::{BarrierOptions, BarrierProblem, find_feasible, minimize};

/// `min ½‖x − a‖²` subject to `x_i ≤ upper_i` (and `x_i ≥ lower_i`).
struct BoxProjection {
    a: Vec<f64>,
    upper: Vec<f64>,
    lower: Vec<f64>,
}

impl BarrierProblem for BoxProjection {
    fn dimension(&self) -> usize {
        self.a.len()
    }
    fn num_constraints(&self) -> usize {
        2 * self.a.len()
    }
    fn objective(&self, x: &DVector<f64>) -> f64 {
        0.5 * x
            .iter()
            .zip(&self.a)
            .map(|(x, a)| (x - a).powi(2))
            .sum::<f64>()
    }
    fn objective_gradient(&self, x: &DVector<f64>) -> DVector<f64> {
        DVector::from_iterator(x.len(), x.iter().zip(&self.a).map(|(x, a)| x - a))
    }
    fn objective_hessian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        CsrMatrix::identity(x.len())
    }
    fn constraints(&self, x: &DVector<f64>) -> DVector<f64> {
        let n = x.len();
        DVector::from_iterator(
            2 * n,
            (0..n)
                .map(|i| x[i] - self.upper[i])
                .chain((0..n).map(|i| self.lower[i] - x[i])),
        )
    }
    fn constraint_jacobian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        let n = x.len();
        let mut coo = CooMatrix::new(2 * n, n);
        for i in 0..n {
            coo.push(i, i, 1.0);
            coo.push(n + i, i, -1.0);
        }
        CsrMatrix::from(&coo)
    }
    fn weighted_constraint_hessian(
        &self,
        _: &DVector<f64>,
        _: &DVector<f64>,
    ) -> Option<CsrMatrix<f64>> {
        None
    }
}

/// `min c·x` subject to `‖x‖² < 1`: the solution is `−c/‖c‖`.
struct LinearOverDisc {
    c: [f64; 2],
}

impl BarrierProblem for LinearOverDisc {
    fn dimension(&self) -> usize {
        2
    }
    fn num_constraints(&self) -> usize {
        1
    }
    fn objective(&self, x: &DVector<f64>) -> f64 {
        self.c[0] * x[0] + self.c[1] * x[1]
    }
    fn objective_gradient(&self, _: &DVector<f64>) -> DVector<f64> {
        DVector::from_row_slice(&self.c)
    }
    fn objective_hessian(&self, _: &DVector<f64>) -> CsrMatrix<f64> {
        CsrMatrix::zeros(2, 2)
    }
    fn constraints(&self, x: &DVector<f64>) -> DVector<f64> {
        DVector::from_element(1, x.norm_squared() - 1.0)
    }
    fn constraint_jacobian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        let mut coo = CooMatrix::new(1, 2);
        coo.push(0, 0, 2.0 * x[0]);
        coo.push(0, 1, 2.0 * x[1]);
        CsrMatrix::from(&coo)
    }
    fn weighted_constraint_hessian(
        &self,
        _: &DVector<f64>,
        w: &DVector<f64>,
    ) -> Option<CsrMatrix<f64>> {
        Some(CsrMatrix::identity(2) * (2.0 * w[0]))
    }
}

/// Non-convex: `min x² − y²` subject to `y² < 1` and `x² < 1`; minimum −1 at `(0, ±1)`.
struct Saddle;

impl BarrierProblem for Saddle {
    fn dimension(&self) -> usize {
        2
    }
    fn num_constraints(&self) -> usize {
        2
    }
    fn objective(&self, x: &DVector<f64>) -> f64 {
        x[0] * x[0] - x[1] * x[1]
    }
    fn objective_gradient(&self, x: &DVector<f64>) -> DVector<f64> {
        DVector::from_row_slice(&[2.0 * x[0], -2.0 * x[1]])
    }
    fn objective_hessian(&self, _: &DVector<f64>) -> CsrMatrix<f64> {
        let mut coo = CooMatrix::new(2, 2);
        coo.push(0, 0, 2.0);
        coo.push(1, 1, -2.0);
        CsrMatrix::from(&coo)
    }
    fn constraints(&self, x: &DVector<f64>) -> DVector<f64> {
        DVector::from_row_slice(&[x[1] * x[1] - 1.0, x[0] * x[0] - 1.0])
    }
    fn constraint_jacobian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        let mut coo = CooMatrix::new(2, 2);
        coo.push(0, 1, 2.0 * x[1]);
        coo.push(1, 0, 2.0 * x[0]);
        CsrMatrix::from(&coo)
    }
    fn weighted_constraint_hessian(
        &self,
        _: &DVector<f64>,
        w: &DVector<f64>,
    ) -> Option<CsrMatrix<f64>> {
        let mut coo = CooMatrix::new(2, 2);
        coo.push(0, 0, 2.0 * w[1]);
        coo.push(1, 1, 2.0 * w[0]);
        Some(CsrMatrix::from(&coo))
    }
}

#[test]
fn projection_onto_a_box_is_clipping() {
    let problem = BoxProjection {
        a: vec![2.0, 0.5, -3.0, 0.99],
        upper: vec![1.0; 4],
        lower: vec![-1.0; 4],
    };
    let report = minimize(&problem, DVector::zeros(4), &BarrierOptions::default()).unwrap();
    let expected = [1.0, 0.5, -1.0, 0.99];
    for (x, e) in report.x.iter().zip(expected) {
        assert!((x - e).abs() < 1e-7, "{x} vs {e}");
    }
    assert!(report.max_constraint < 0.0);
    assert!(report.duality_gap < 1e-8);
}

#[test]
fn linear_objective_over_a_disc() {
    let problem = LinearOverDisc { c: [1.0, 2.0] };
    let report = minimize(
        &problem,
        DVector::from_row_slice(&[0.1, -0.2]),
        &BarrierOptions::default(),
    )
    .unwrap();
    let norm = 5f64.sqrt();
    assert!(
        (report.x[0] + 1.0 / norm).abs() < 1e-7 && (report.x[1] + 2.0 / norm).abs() < 1e-7,
        "{}",
        report.x
    );
    assert!((report.objective + norm).abs() < 1e-7);
}

#[test]
fn non_convex_problems_use_the_shifted_newton_matrix() {
    let report = minimize(
        &Saddle,
        DVector::from_row_slice(&[0.5, 0.1]),
        &BarrierOptions::default(),
    )
    .unwrap();
    assert!(
        (report.objective + 1.0).abs() < 1e-6,
        "{}",
        report.objective
    );
    assert!(report.x[0].abs() < 1e-4 && (report.x[1] - 1.0).abs() < 1e-6);
}

#[test]
fn phase_one_finds_a_strictly_feasible_start() {
    let problem = BoxProjection {
        a: vec![0.3, -0.2],
        upper: vec![1.0, 0.0],
        lower: vec![0.5, -1.0],
    };
    let options = BarrierOptions::default();
    let start = find_feasible(
        &problem,
        DVector::from_row_slice(&[5.0, 5.0]),
        1e-6,
        &options,
    )
    .unwrap();
    assert!(problem.constraints(&start).iter().all(|&c| c < -1e-6));
    let report = minimize(&problem, start, &options).unwrap();
    assert!(
        (report.x[0] - 0.5).abs() < 1e-7 && (report.x[1] + 0.2).abs() < 1e-7,
        "{}",
        report.x
    );
}

#[test]
fn errors() {
    let problem = BoxProjection {
        a: vec![0.0],
        upper: vec![1.0],
        lower: vec![-1.0],
    };
    let options = BarrierOptions::default();
    let e = minimize(&problem, DVector::from_row_slice(&[2.0]), &options).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert!(e.message().contains("not strictly feasible"), "{e}");
    // Issue 26: the constraint and its value.
    assert_eq!((e.index(), e.value()), (Some(0), Some(1.0)), "{e}");
    assert_eq!(e.interval(), Some((f64::NEG_INFINITY, 0.0)));
    let e = minimize(&problem, DVector::zeros(2), &options).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    assert_eq!(e.counts(), Some((1, 2)));
    assert_eq!(
        e.message(),
        "starting point has 2 entries, the problem 1 unknowns"
    );
    // x ≤ −1 and x ≥ 1 at once: no feasible point.
    let inconsistent = BoxProjection {
        a: vec![0.0],
        upper: vec![-1.0],
        lower: vec![1.0],
    };
    let e = find_feasible(
        &inconsistent,
        DVector::zeros(1),
        1e-6,
        &BarrierOptions {
            max_outer_iterations: 20,
            ..options
        },
    )
    .unwrap_err();
    assert!(
        matches!(
            e.kind(),
            ErrorKind::NoConvergence | ErrorKind::SingularSystem
        ),
        "{e}"
    );
}

/// `min ½‖x − a‖²` subject to `x_i > 0`: an unbounded feasible set.
struct Positive {
    a: Vec<f64>,
}

impl BarrierProblem for Positive {
    fn dimension(&self) -> usize {
        self.a.len()
    }
    fn num_constraints(&self) -> usize {
        self.a.len()
    }
    fn objective(&self, x: &DVector<f64>) -> f64 {
        0.5 * x
            .iter()
            .zip(&self.a)
            .map(|(x, a)| (x - a).powi(2))
            .sum::<f64>()
    }
    fn objective_gradient(&self, x: &DVector<f64>) -> DVector<f64> {
        DVector::from_iterator(x.len(), x.iter().zip(&self.a).map(|(x, a)| x - a))
    }
    fn objective_hessian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        CsrMatrix::identity(x.len())
    }
    fn constraints(&self, x: &DVector<f64>) -> DVector<f64> {
        -x
    }
    fn constraint_jacobian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        CsrMatrix::identity(x.len()) * -1.0
    }
    fn weighted_constraint_hessian(
        &self,
        _: &DVector<f64>,
        _: &DVector<f64>,
    ) -> Option<CsrMatrix<f64>> {
        None
    }
}

#[test]
fn phase_one_is_bounded_when_the_feasible_set_is_not() {
    let problem = Positive {
        a: vec![2.0, -1.0, 0.5],
    };
    let options = BarrierOptions::default();
    let start = find_feasible(
        &problem,
        DVector::from_row_slice(&[-1.0, -3.0, 2.0]),
        1e-6,
        &options,
    )
    .unwrap();
    assert!(start.iter().all(|&x| x > 1e-6), "{start}");
    let report = minimize(&problem, start, &options).unwrap();
    let expected = [2.0, 0.0, 0.5];
    for (x, e) in report.x.iter().zip(expected) {
        assert!((x - e).abs() < 1e-7, "{x} vs {e}");
    }
}
