//! The squared distances of data points to a curve at their foot points, with their gradients
//! and Hessians with respect to the control points (variable projection).

use nalgebra::Vector2;
use spline_core::KnotVector;
use std::cell::RefCell;

/// Parameter steps of the foot-point iteration at or below this (the parameters are on
/// `[0, 1]`) end it: a few units in the last place of the parameter.
const FOOT_PARAMETER_RESOLUTION: f64 = 1e-14;

/// A Newton step of the foot-point iteration at or below this (on `[0, 1]`) ends it: once
/// accepted, the next step of the quadratically converging iteration is below
/// [`FOOT_PARAMETER_RESOLUTION`]; when it does not decrease the distance, the distance's
/// rounding decides, and halving it only asks the rounding again. On 100 UIUC airfoils,
/// 38 % of the iteration's evaluations were such halvings of steps below 1e-9.
const FOOT_CONVERGED_STEP: f64 = 1e-9;

/// One data point's squared distance at the current curve (buffers reused from one
/// evaluation to the next).
#[derive(Clone, Debug, Default)]
pub(super) struct Foot {
    /// `d² = ‖C(u) − Q‖²`.
    pub(super) squared: f64,
    /// First control point acting at `u`.
    pub(super) first: usize,
    /// `∂d²/∂x` on the `2(p+1)` local variables.
    pub(super) gradient: Vec<f64>,
    /// `∂²d²/∂x²` on the local variables, row-major.
    pub(super) hessian: Vec<f64>,
    /// The foot-point parameter.
    pub(super) param: f64,
}

/// The squared distances of the data to curves of one knot vector. Foot points are found
/// from anchor parameters that change only when the driver commits a new curve, so that the
/// distances are a deterministic function of the control points during a Newton iteration.
pub(super) struct Distances {
    pub(super) knots: KnotVector<f64>,
    pub(super) points: Vec<Vector2<f64>>,
    pub(super) params: RefCell<Vec<f64>>,
    /// Whether foot points follow the curve (variable projection) or stay at the anchors
    /// (the fixed parameters of classic least squares).
    pub(super) project: bool,
    /// A closed curve of period 1 on `[0, 1]`: no foot point is pinned and foot points cross
    /// the closing point.
    pub(super) closed: bool,
    /// The curve of the last control points as one polynomial per knot span.
    pub(super) form: RefCell<TaylorForm>,
}

/// The curve of one set of control points as one polynomial per knot span — its Taylor
/// coefficients about the span's left knot — so that each step of the foot-point iteration
/// evaluates `C`, `C′` and `C″` by Horner's scheme, `O(p)`, instead of the basis functions'
/// triangular scheme and three sums over the control points, `O(p²)`. Built once per set of
/// control points (one basis evaluation per span), used by every data point's iteration.
#[derive(Clone, Debug, Default)]
pub(super) struct TaylorForm {
    /// `p + 1` coefficients per span, spans from the first (`span − p`); empty spans zero.
    coefficients: Vec<Vector2<f64>>,
    /// The basis functions' right derivatives at every span's left knot (`(p + 1)²` a span,
    /// as `basis_derivatives` writes them) for the knots `table_knots`: they depend on the
    /// knots only, and the form is filled for every new set of control points.
    table: Vec<f64>,
    table_knots: Vec<f64>,
}

impl TaylorForm {
    /// The form of the curve with `knots` and `control`.
    pub(super) fn fill(&mut self, knots: &KnotVector<f64>, control: &[Vector2<f64>]) {
        let p = knots.degree();
        let width = p + 1;
        let n = knots.num_basis();
        let k = knots.knots();
        let square = width * width;
        if self.table_knots.as_slice() != k {
            self.table_knots.clear();
            self.table_knots.extend_from_slice(k);
            self.table.clear();
            self.table.resize((n - p) * square, 0.0);
            for span in p..n {
                if k[span] < k[span + 1] {
                    // Right derivatives at the span's left knot: this span's polynomial.
                    let block = &mut self.table[(span - p) * square..(span - p + 1) * square];
                    knots.basis_derivatives(span, k[span], p, block);
                }
            }
        }
        self.coefficients.clear();
        self.coefficients.resize((n - p) * width, Vector2::zeros());
        for span in p..n {
            if !(k[span] < k[span + 1]) {
                continue;
            }
            let basis = &self.table[(span - p) * square..(span - p + 1) * square];
            let mut factorial = 1.0;
            for order in 0..=p {
                if order > 1 {
                    factorial *= order as f64;
                }
                let mut c = Vector2::zeros();
                for (a, point) in control[span - p..=span].iter().enumerate() {
                    c += point * basis[order * width + a];
                }
                self.coefficients[(span - p) * width + order] = c / factorial;
            }
        }
    }

    /// `C(u)`, `C′(u)` and `C″(u)` on `span` (of the knots the form was filled with).
    fn eval(&self, knots: &KnotVector<f64>, span: usize, u: f64) -> [Vector2<f64>; 3] {
        let width = knots.degree() + 1;
        let first = (span - knots.degree()) * width;
        let t = u - knots.knots()[span];
        let (mut value, mut slope, mut half_curvature) =
            (Vector2::zeros(), Vector2::zeros(), Vector2::zeros());
        for c in self.coefficients[first..first + width].iter().rev() {
            half_curvature = half_curvature * t + slope;
            slope = slope * t + value;
            value = value * t + c;
        }
        [value, slope, half_curvature * 2.0]
    }
}

/// Data points at least this many have their foot points found on every core (each foot
/// is independent of the others, so the result is the same bit for bit); fewer (an
/// airfoil's few hundred) stay on the calling thread, where spawning would cost more than it
/// gains and a batch already runs one file per core.
const PARALLEL_POINTS: usize = 8192;

impl Distances {
    /// The foot points of every data point at the curve of `control`, into `feet` (one per
    /// data point), with the derivatives of the squared distances when `derivatives`; with
    /// `found`, each foot is already known to be at its `param` (as
    /// [`FootSolver::foot_into`]). Many points are shared out among the cores.
    pub(super) fn feet_into(
        &self,
        control: &[Vector2<f64>],
        derivatives: bool,
        found: bool,
        feet: &mut [Foot],
    ) {
        let anchors = self.params.borrow();
        let anchors: &[f64] = &anchors;
        let mut form = self.form.borrow_mut();
        form.fill(&self.knots, control);
        let solver = FootSolver {
            knots: &self.knots,
            points: &self.points,
            project: self.project,
            closed: self.closed,
            form: &form,
        };
        let threads = if feet.len() < PARALLEL_POINTS {
            1
        } else {
            std::thread::available_parallelism().map_or(1, std::num::NonZero::get)
        };
        if threads <= 1 {
            for (j, foot) in feet.iter_mut().enumerate() {
                solver.foot_into(j, anchors[j], (derivatives, found), foot);
            }
            return;
        }
        let chunk = feet.len().div_ceil(threads);
        std::thread::scope(|scope| {
            for (c, part) in feet.chunks_mut(chunk).enumerate() {
                let solver = &solver;
                scope.spawn(move || {
                    for (k, foot) in part.iter_mut().enumerate() {
                        let j = c * chunk + k;
                        solver.foot_into(j, anchors[j], (derivatives, found), foot);
                    }
                });
            }
        });
    }
}

/// What finding one foot point needs, shareable between threads.
pub(super) struct FootSolver<'a> {
    knots: &'a KnotVector<f64>,
    points: &'a [Vector2<f64>],
    project: bool,
    closed: bool,
    /// The curve of the control points passed to [`FootSolver::foot_into`].
    form: &'a TaylorForm,
}

impl FootSolver<'_> {
    /// The foot point of data point `j` (on the curve of the solver's form) near its cached
    /// parameter `anchor`, with the
    /// derivatives of its squared distance when `derivatives`, written into `out` (its
    /// buffers reused: no allocation once they have their size). With `found`, the foot
    /// point is already known to be at `out.param` (found by an earlier call for the same
    /// control points): only the derivatives are computed there.
    fn foot_into(&self, j: usize, anchor: f64, (derivatives, found): (bool, bool), out: &mut Foot) {
        let p = self.knots.degree();
        let width = p + 1;
        let q = self.points[j];
        let last = self.points.len() - 1;
        let pinned = !self.closed && (j == 0 || j == last);
        let fixed = pinned || !self.project;
        let mut u = if pinned {
            if j == 0 { 0.0 } else { 1.0 }
        } else if found {
            out.param
        } else {
            anchor
        };
        // The span of a step's parameter is most often the current one (a check, not a
        // search: `span_in_domain_from`).
        let eval = |u: f64, hint: usize| -> (usize, [Vector2<f64>; 3]) {
            let span = self.knots.span_in_domain_from(u, hint);
            (span, self.form.eval(self.knots, span, u))
        };
        // The first from this data point's last foot (`out` is its own from call to call).
        let (mut span, mut d) = eval(u, out.first + p);
        if !fixed && !found {
            let mut dist2 = (d[0] - q).norm_squared();
            for _ in 0..30 {
                let r = d[0] - q;
                let psi = r.dot(&d[1]);
                let dpsi = d[1].norm_squared() + r.dot(&d[2]);
                let mut step = if dpsi > 0.0 {
                    -psi / dpsi
                } else {
                    -psi.signum() * 0.01
                };
                let mut moved = false;
                let mut converged = false;
                for _ in 0..30 {
                    let candidate = if self.closed {
                        (u + step).rem_euclid(1.0)
                    } else {
                        (u + step).clamp(0.0, 1.0)
                    };
                    // A step below the rounding of the parameter (on [0, 1]) changes nothing
                    // the distance can see: the foot point is found.
                    if (candidate - u).abs() <= FOOT_PARAMETER_RESOLUTION {
                        break;
                    }
                    let (s2, d2) = eval(candidate, span);
                    let c2 = (d2[0] - q).norm_squared();
                    if c2 <= dist2 {
                        moved = true;
                        u = candidate;
                        span = s2;
                        d = d2;
                        dist2 = c2;
                        // Newton's iterates converge quadratically: after a step this
                        // small the next one is below the resolution.
                        converged = step.abs() <= FOOT_CONVERGED_STEP;
                        break;
                    }
                    // A Newton step this small that does not decrease the distance is
                    // rounding: halving it only finds rounding again.
                    if step.abs() <= FOOT_CONVERGED_STEP {
                        break;
                    }
                    step *= 0.5;
                }
                if !moved || converged {
                    break;
                }
            }
        }
        let r = d[0] - q;
        let squared = r.norm_squared();
        let first = span - p;
        let n = 2 * width;
        let Foot {
            gradient, hessian, ..
        } = out;
        gradient.clear();
        hessian.clear();
        if derivatives {
            // The basis functions and their slopes at u.
            let mut basis = [0.0; 2 * spline_core::MAX_ORDER];
            self.knots
                .basis_derivatives(span, u, 1, &mut basis[..2 * width]);
            let value = &basis[..width];
            let slope = &basis[width..2 * width];
            gradient.resize(n, 0.0);
            hessian.resize(n * n, 0.0);
            for a in 0..width {
                gradient[2 * a] = 2.0 * value[a] * r.x;
                gradient[2 * a + 1] = 2.0 * value[a] * r.y;
                for b in 0..width {
                    let v = 2.0 * value[a] * value[b];
                    hessian[(2 * a) * n + 2 * b] = v;
                    hessian[(2 * a + 1) * n + 2 * b + 1] = v;
                }
            }
            let interior = !fixed && (self.closed || (u > 0.0 && u < 1.0));
            let phi_uu = 2.0 * (d[1].norm_squared() + r.dot(&d[2]));
            if interior && phi_uu > 0.0 {
                // φ_xu = 2 (N′ r + N c′) per local variable.
                let mut cross = [0.0; 2 * spline_core::MAX_ORDER];
                for a in 0..width {
                    cross[2 * a] = 2.0 * (slope[a] * r.x + value[a] * d[1].x);
                    cross[2 * a + 1] = 2.0 * (slope[a] * r.y + value[a] * d[1].y);
                }
                for i in 0..n {
                    for k in 0..n {
                        hessian[i * n + k] -= cross[i] * cross[k] / phi_uu;
                    }
                }
            }
        }
        out.squared = squared;
        out.first = first;
        out.param = u;
    }
}

#[cfg(test)]
mod tests {
    use super::{Distances, Foot, FootSolver, PARALLEL_POINTS, TaylorForm};
    use nalgebra::Vector2;
    use spline_core::KnotVector;
    use std::cell::RefCell;

    /// The feet found on every core are those of the one-by-one loop, bit for bit, with
    /// and without derivatives, open and closed.
    #[test]
    fn feet_on_every_core_equal_the_sequential_ones() {
        let knots = KnotVector::uniform(3, 9, 0.0, 1.0).unwrap();
        let control: Vec<Vector2<f64>> = (0..9)
            .map(|i| {
                let t = f64::from(i) / 8.0;
                Vector2::new(t, (5.0 * t).sin() * 0.3)
            })
            .collect();
        let m = PARALLEL_POINTS + 1234;
        let points: Vec<Vector2<f64>> = (0..m)
            .map(|j| {
                let t = j as f64 / (m - 1) as f64;
                Vector2::new(t, (5.0 * t).sin() * 0.3 + 0.01 * (37.0 * t).cos())
            })
            .collect();
        let anchors: Vec<f64> = (0..m).map(|j| j as f64 / (m - 1) as f64).collect();
        for closed in [false, true] {
            let distances = Distances {
                knots: knots.clone(),
                points: points.clone(),
                params: RefCell::new(anchors.clone()),
                project: true,
                closed,
                form: RefCell::default(),
            };
            for derivatives in [false, true] {
                let mut together = vec![Foot::default(); m];
                distances.feet_into(&control, derivatives, false, &mut together);
                let mut form = TaylorForm::default();
                form.fill(&knots, &control);
                let solver = FootSolver {
                    knots: &knots,
                    points: &points,
                    project: true,
                    closed,
                    form: &form,
                };
                for (j, foot) in together.iter().enumerate() {
                    let mut alone = Foot::default();
                    solver.foot_into(j, anchors[j], (derivatives, false), &mut alone);
                    assert_eq!(foot.squared.to_bits(), alone.squared.to_bits(), "{j}");
                    assert_eq!(foot.param.to_bits(), alone.param.to_bits(), "{j}");
                    assert_eq!(
                        (foot.first, &foot.gradient, &foot.hessian),
                        (alone.first, &alone.gradient, &alone.hessian)
                    );
                }
            }
        }
    }

    /// The Taylor form's `C`, `C′`, `C″` agree with the curve's derivatives (de Boor's
    /// triangular scheme) at parameters across every span, on knots with a double knot.
    #[test]
    fn taylor_form_is_the_curve() {
        use spline_geom::BSpline;
        for degree in 3..=5 {
            let mut knots = vec![0.0; degree + 1];
            knots.extend([0.1, 0.25, 0.25, 0.5, 0.7, 0.9]);
            knots.extend(vec![1.0; degree + 1]);
            let knots = KnotVector::new(degree, knots).unwrap();
            let control: Vec<Vector2<f64>> = (0..knots.num_basis())
                .map(|i| {
                    let t = i as f64;
                    Vector2::new(t * 0.3 + (t * 1.7).sin(), (t * 2.3).cos())
                })
                .collect();
            let curve = BSpline::new(knots.clone(), control.clone()).unwrap();
            let mut form = TaylorForm::default();
            form.fill(&knots, &control);
            for step in 0..=400 {
                let u = f64::from(step) / 400.0;
                let span = knots.span_in_domain(u);
                let ours = form.eval(&knots, span, u);
                let mut theirs = [Vector2::zeros(); 3];
                curve.derivatives_into(u, &mut theirs).unwrap();
                for (order, (a, b)) in ours.iter().zip(&theirs).enumerate() {
                    let scale = 1.0 + b.norm();
                    assert!(
                        (a - b).norm() <= 1e-12 * scale * 10f64.powi(order as i32),
                        "degree {degree}, u = {u}, order {order}: {a} vs {b}"
                    );
                }
            }
        }
    }
}
