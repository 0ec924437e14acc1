//! Curvature invariants of planar B-spline curves as B-spline functions of the parameter,
//! with Jacobians and Hessians with respect to the control points (thesis ch. 6), and the
//! inflections and curvature extrema built on them.

use crate::bilinear::SparseBilinear;
use crate::maps::SplineMap;
use crate::product::{bernstein_product, product_knots};
use crate::sparse::{add_scaled, interleave_columns, matmul};
use nalgebra::Vector2;
use nalgebra_sparse::CsrMatrix;
use spline_core::{Error, ErrorKind, KnotVector, Result, Scalar, cast};
use spline_geom::BSpline;

/// The four products of derivatives of a planar curve `c(u)` that make up its curvature
/// $\kappa = h_4 / h_1^{3/2}$ and the derivative
/// $\kappa' = (h_1 h_2 - 3 h_3 h_4) / h_1^{5/2}$ (thesis (6.8)–(6.14)), with
/// $a \wedge b = a_x b_y - a_y b_x$.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Invariant {
    /// $h_1 = c' \cdot c'$ (degree `2d − 2`): the squared speed.
    H1,
    /// $h_2 = c' \wedge c'''$ (degree `2d − 4`; zero for `d = 2`).
    H2,
    /// $h_3 = c' \cdot c''$ (degree `2d − 3`).
    H3,
    /// $h_4 = c' \wedge c''$ (degree `2d − 3`): its zeros with a sign change are the
    /// inflections.
    H4,
}

impl Invariant {
    fn index(self) -> usize {
        match self {
            Self::H1 => 0,
            Self::H2 => 1,
            Self::H3 => 2,
            Self::H4 => 3,
        }
    }
}

/// Which representation of a derived function.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Form {
    /// The B-spline form on the minimal knot vector (products by [`crate::product_knots`]).
    BSpline,
    /// The per-segment Bernstein form of the thesis ([`KnotVector::bernstein`]): one
    /// Bézier piece per non-empty knot span of the curve, `degree + 1` coefficients each.
    Bernstein,
}

/// A spline function whose coefficients depend on variables `x`, with the Jacobian
/// $\partial\\,\text{coefficient}_k / \partial x_j$ (rows: coefficients, columns: variables).
#[derive(Clone, Debug)]
pub struct Differentiated<T> {
    /// The function.
    pub value: BSpline<T, T>,
    /// The Jacobian of its coefficients.
    pub jacobian: CsrMatrix<T>,
}

/// The curvature algebra of planar curves of one knot vector, prepared once (every map is
/// constant and sparse): for control points `P_i = (x_i, y_i)` and the interleaved variables
/// $X = [x_1, y_1, \dots, x_n, y_n]$ it gives
///
/// - the [`Invariant`]s `h1 … h4`, quadratic in `X`: value, Jacobian, constant Hessian;
/// - the curvature-extremum numerator $g = h_1 h_2 - 3 h_3 h_4$ (thesis (6.10), (6.22)),
///   quartic in `X`: value, Jacobian, Hessian (which depends on `X`),
///
/// each in [`Form::Bernstein`] (degree `4d − 6` for `g`, `(4d − 5)` coefficients per segment,
/// `(4d − 5)(n − d)` in all for simple knots) or [`Form::BSpline`] (minimal knots; for simple
/// knots `g` has interior multiplicity `3d − 2`).
///
/// Normalisation: `g` is exactly $h_1 h_2 - 3 h_3 h_4$ with derivatives taken with respect to
/// the curve's own parameter; for the quadratic Bézier curve `(−1,0), (x,y), (1,0)` on
/// `[0, 1]` its Bernstein coefficients are `192 ×` the thesis's (6.30)–(6.32).
///
/// ```
/// use nalgebra::Vector2;
/// use spline_algebra::{Form, PlanarInvariants};
/// use spline_core::KnotVector;
/// let knots = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0])?;
/// let algebra = PlanarInvariants::new(&knots)?;
/// let (x, y) = (0.3, 0.8);
/// let points = [Vector2::new(-1.0, 0.0), Vector2::new(x, y), Vector2::new(1.0, 0.0)];
/// let g = algebra.g(&points, Form::Bernstein)?;
/// let expected = [
///     -y * ((x + 0.5f64).powi(2) + y * y - 0.25),
///     -x * y,
///     y * ((x - 0.5f64).powi(2) + y * y - 0.25),
/// ];
/// for (gi, ei) in g.value.control_points().iter().zip(expected) {
///     assert!((gi - 192.0 * ei).abs() < 1e-12);
/// }
/// assert_eq!(g.jacobian.ncols(), 6); // [x1, y1, x2, y2, x3, y3]
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct PlanarInvariants<T> {
    knots: KnotVector<T>,
    /// `h_k(X) = Q_k(X, X)` in per-segment Bernstein form.
    quadratic: [SparseBilinear<T>; 4],
    /// Per-segment Bernstein form → minimal B-spline form of `h_k`.
    removal: [SplineMap<T>; 4],
    /// Bernstein products for `h1 h2` and `h3 h4`.
    g_products: [SparseBilinear<T>; 2],
    g_removal: SplineMap<T>,
}

impl<T: Scalar> PlanarInvariants<T> {
    /// Prepares the algebra for curves on `knots` (degree `d ≥ 2`).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] for degree below 2 (the curvature of a polyline is zero
    /// wherever it is defined); [`ErrorKind::DegreeTooHigh`] if `4d − 6` exceeds
    /// [`spline_core::MAX_DEGREE`].
    ///
    /// # Panics
    /// Never: the `expect`s only state internal invariants (matching dimensions).
    pub fn new(knots: &KnotVector<T>) -> Result<Self> {
        let d = knots.degree();
        if d < 2 {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "curvature invariants need degree 2 or more, got {d} (a polyline has zero curvature wherever it is defined)"
                ),
            )
            .with_value(d as f64)
            .with_interval(2.0, f64::INFINITY));
        }
        check_extremum_numerator_degree(d)?;
        let n = knots.num_basis();
        let breakpoints = knots.domain_breaks();
        let segments = breakpoints.len() - 1;
        // X → per-segment Bernstein coefficients of x^(k), y^(k), and the derivative spaces.
        let mut cx = Vec::new();
        let mut cy = Vec::new();
        let mut spaces = Vec::new();
        for k in 1..=3.min(d) {
            let der = SplineMap::derivative(knots, k)?;
            let pieces = KnotVector::bernstein(d - k, &breakpoints)?;
            let ext = SplineMap::transfer(der.target(), &pieces)?;
            let m = matmul(ext.matrix(), der.matrix());
            cx.push(interleave_columns(&m, 2, 0));
            cy.push(interleave_columns(&m, 2, 1));
            spaces.push(der.target().clone());
        }
        let nx = 2 * n;
        let form = |p: usize,
                    q: usize,
                    a: &CsrMatrix<T>,
                    b: &CsrMatrix<T>,
                    c: &CsrMatrix<T>,
                    e: &CsrMatrix<T>,
                    sign: T| {
            let prod = bernstein_product::<T>(p, q, segments);
            prod.compose(a, b)
                .expect("dimensions")
                .combine(T::one(), &prod.compose(c, e).expect("dimensions"), sign)
                .expect("shapes")
        };
        let one = T::one();
        let q1 = form(d - 1, d - 1, &cx[0], &cx[0], &cy[0], &cy[0], one);
        let q2 = if d >= 3 {
            form(d - 1, d - 3, &cx[0], &cy[2], &cy[0], &cx[2], -one)
        } else {
            SparseBilinear::zeros(segments, nx, nx)
        };
        let q3 = form(d - 1, d - 2, &cx[0], &cx[1], &cy[0], &cy[1], one);
        let q4 = form(d - 1, d - 2, &cx[0], &cy[1], &cy[0], &cx[1], -one);
        // Minimal B-spline spaces of the invariants.
        let w1 = product_knots(&spaces[0], &spaces[0])?;
        let w2 = if d >= 3 {
            product_knots(&spaces[0], &spaces[2])?
        } else {
            KnotVector::bernstein(0, &breakpoints)?
        };
        let w3 = product_knots(&spaces[0], &spaces[1])?;
        let degrees = [2 * d - 2, 2 * d - 4, 2 * d - 3, 2 * d - 3];
        let ws = [&w1, &w2, &w3, &w3];
        let mut removal = Vec::with_capacity(4);
        for (deg, w) in degrees.iter().zip(ws) {
            removal.push(SplineMap::knot_removal(
                &KnotVector::bernstein(*deg, &breakpoints)?,
                w,
            )?);
        }
        let wg = product_knots(&w1, &w2)?.merged(&product_knots(&w3, &w3)?)?;
        let g_removal =
            SplineMap::knot_removal(&KnotVector::bernstein(4 * d - 6, &breakpoints)?, &wg)?;
        let removal: [SplineMap<T>; 4] = removal.try_into().expect("four maps");
        Ok(Self {
            knots: knots.clone(),
            quadratic: [q1, q2, q3, q4],
            removal,
            g_products: [
                bernstein_product(2 * d - 2, 2 * d - 4, segments),
                bernstein_product(2 * d - 3, 2 * d - 3, segments),
            ],
            g_removal,
        })
    }

    /// The knot vector of the curves.
    #[must_use]
    pub fn knots(&self) -> &KnotVector<T> {
        &self.knots
    }

    /// Number of variables, `2n`.
    #[must_use]
    pub fn num_variables(&self) -> usize {
        2 * self.knots.num_basis()
    }

    /// The space of an invariant in the given form.
    #[must_use]
    pub fn space(&self, which: Invariant, form: Form) -> &KnotVector<T> {
        let map = &self.removal[which.index()];
        match form {
            Form::BSpline => map.target(),
            Form::Bernstein => map.source(),
        }
    }

    /// The space of `g` in the given form.
    #[must_use]
    pub fn g_space(&self, form: Form) -> &KnotVector<T> {
        match form {
            Form::BSpline => self.g_removal.target(),
            Form::Bernstein => self.g_removal.source(),
        }
    }

    /// The map from the per-segment Bernstein form of `g` to its B-spline form.
    #[must_use]
    pub fn g_removal(&self) -> &SplineMap<T> {
        &self.g_removal
    }

    fn variables(&self, points: &[Vector2<T>]) -> Result<Vec<T>> {
        if points.len() != self.knots.num_basis() {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "the knot vector needs {} control points, got {}",
                    self.knots.num_basis(),
                    points.len()
                ),
            ));
        }
        Ok(points.iter().flat_map(|p| [p.x, p.y]).collect())
    }

    fn finish(
        &self,
        map: &SplineMap<T>,
        form: Form,
        pieces: Vec<T>,
        jac: CsrMatrix<T>,
    ) -> Differentiated<T> {
        match form {
            Form::Bernstein => Differentiated {
                value: BSpline::new_unchecked(map.source().clone(), pieces),
                jacobian: jac,
            },
            Form::BSpline => Differentiated {
                value: BSpline::new_unchecked(
                    map.target().clone(),
                    crate::sparse::apply_points(map.matrix(), &pieces),
                ),
                jacobian: matmul(map.matrix(), &jac),
            },
        }
    }

    /// An invariant with its Jacobian with respect to `X`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless there are `n` control points.
    pub fn invariant(
        &self,
        which: Invariant,
        points: &[Vector2<T>],
        form: Form,
    ) -> Result<Differentiated<T>> {
        let x = self.variables(points)?;
        let (value, jac) = self.quadratic[which.index()].quadratic(&x)?;
        Ok(self.finish(&self.removal[which.index()], form, value, jac))
    }

    /// An invariant without derivatives.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless there are `n` control points.
    pub fn invariant_value(
        &self,
        which: Invariant,
        points: &[Vector2<T>],
        form: Form,
    ) -> Result<BSpline<T, T>> {
        let x = self.variables(points)?;
        let pieces = self.quadratic[which.index()].apply_unchecked(&x, &x);
        let map = &self.removal[which.index()];
        Ok(match form {
            Form::Bernstein => BSpline::new_unchecked(map.source().clone(), pieces),
            Form::BSpline => map.apply_to(&BSpline::new_unchecked(map.source().clone(), pieces))?,
        })
    }

    /// The constant Hessian of an invariant: row `k` is the `2n × 2n` Hessian of coefficient
    /// `k` with respect to `X`.
    ///
    /// # Panics
    /// Never: the `expect`s only state internal invariants (matching dimensions).
    #[must_use]
    pub fn invariant_hessian(&self, which: Invariant, form: Form) -> SparseBilinear<T> {
        let h = self.quadratic[which.index()]
            .symmetrized()
            .expect("square quadratic form");
        match form {
            Form::Bernstein => h,
            Form::BSpline => h
                .then(self.removal[which.index()].matrix())
                .expect("dimensions"),
        }
    }

    /// The quadratic form `Q` with `h(X) = Q(X, X)` (per-segment Bernstein form).
    #[must_use]
    pub fn quadratic_form(&self, which: Invariant) -> &SparseBilinear<T> {
        &self.quadratic[which.index()]
    }

    /// $g = h_1 h_2 - 3 h_3 h_4$ with its Jacobian
    /// $\nabla g = h_2 \nabla h_1 + h_1 \nabla h_2 - 3 (h_4 \nabla h_3 + h_3 \nabla h_4)$
    /// (the thesis's (6.22) regrouped), every product taken in Bernstein form.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless there are `n` control points.
    pub fn g(&self, points: &[Vector2<T>], form: Form) -> Result<Differentiated<T>> {
        let x = self.variables(points)?;
        let h: Vec<(Vec<T>, CsrMatrix<T>)> = self
            .quadratic
            .iter()
            .map(|q| q.quadratic(&x))
            .collect::<Result<_>>()?;
        let [p12, p34] = &self.g_products;
        let three = cast::<T>(3.0);
        let v12 = p12.apply_unchecked(&h[0].0, &h[1].0);
        let v34 = p34.apply_unchecked(&h[2].0, &h[3].0);
        let value: Vec<T> = v12.iter().zip(&v34).map(|(&a, &b)| a - three * b).collect();
        let j12 = add_scaled(
            T::one(),
            &matmul(&p12.contract(&h[1].0, true), &h[0].1),
            T::one(),
            &matmul(&p12.contract(&h[0].0, false), &h[1].1),
        );
        let j34 = add_scaled(
            T::one(),
            &matmul(&p34.contract(&h[3].0, true), &h[2].1),
            T::one(),
            &matmul(&p34.contract(&h[2].0, false), &h[3].1),
        );
        let jac = add_scaled(T::one(), &j12, -three, &j34);
        Ok(self.finish(&self.g_removal, form, value, jac))
    }

    /// `g` without derivatives.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless there are `n` control points.
    pub fn g_value(&self, points: &[Vector2<T>], form: Form) -> Result<BSpline<T, T>> {
        let x = self.variables(points)?;
        let h: Vec<Vec<T>> = self
            .quadratic
            .iter()
            .map(|q| q.apply_unchecked(&x, &x))
            .collect();
        let three = cast::<T>(3.0);
        let v12 = self.g_products[0].apply_unchecked(&h[0], &h[1]);
        let v34 = self.g_products[1].apply_unchecked(&h[2], &h[3]);
        let pieces: Vec<T> = v12.iter().zip(&v34).map(|(&a, &b)| a - three * b).collect();
        let spline = BSpline::new_unchecked(self.g_removal.source().clone(), pieces);
        match form {
            Form::Bernstein => Ok(spline),
            Form::BSpline => self.g_removal.apply_to(&spline),
        }
    }

    /// The Hessian of `g` at `X` (it depends on `X`: `g` is quartic): row `k` is the
    /// symmetric `2n × 2n` Hessian of coefficient `k`, by the product rule
    /// $\nabla^2 (h_a h_b) = h_b \nabla^2 h_a + h_a \nabla^2 h_b + \nabla h_a \nabla h_b^{\mathsf T}
    /// + \nabla h_b \nabla h_a^{\mathsf T}$ on every Bernstein product term.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless there are `n` control points.
    pub fn g_hessian(&self, points: &[Vector2<T>], form: Form) -> Result<SparseBilinear<T>> {
        let x = self.variables(points)?;
        let nx = x.len();
        let mut values = Vec::with_capacity(4);
        let mut jacobians = Vec::with_capacity(4);
        let mut hessians = Vec::with_capacity(4);
        for q in &self.quadratic {
            let (v, j) = q.quadratic(&x)?;
            values.push(v);
            jacobians.push(j);
            hessians.push(q.symmetrized()?);
        }
        let three = cast::<T>(3.0);
        let rows = (0..self.g_removal.source().num_basis())
            .map(|r| {
                let mut row = Vec::new();
                for (product, (ia, ib), weight) in [
                    (&self.g_products[0], (0, 1), T::one()),
                    (&self.g_products[1], (2, 3), -three),
                ] {
                    for &(a, b, w) in product.row(r) {
                        let w = w * weight;
                        let (ha, hb) = (values[ia][a], values[ib][b]);
                        for &(j, l, v) in hessians[ia].row(a) {
                            row.push((j, l, w * hb * v));
                        }
                        for &(j, l, v) in hessians[ib].row(b) {
                            row.push((j, l, w * ha * v));
                        }
                        let ga = jacobians[ia].row(a);
                        let gb = jacobians[ib].row(b);
                        for (&j, &va) in ga.col_indices().iter().zip(ga.values()) {
                            for (&l, &vb) in gb.col_indices().iter().zip(gb.values()) {
                                row.push((j, l, w * va * vb));
                                row.push((l, j, w * va * vb));
                            }
                        }
                    }
                }
                row
            })
            .collect();
        let h = SparseBilinear::from_rows_unchecked(nx, nx, rows);
        Ok(match form {
            Form::Bernstein => h,
            Form::BSpline => h.then(self.g_removal.matrix())?,
        })
    }
}

/// [`ErrorKind::DegreeTooHigh`] when the curvature-extremum numerator `g` of a degree-`d`
/// planar curve (degree `4d − 6`) is above [`spline_core::MAX_DEGREE`].
pub(crate) fn check_extremum_numerator_degree(d: usize) -> Result<()> {
    let degree = (4 * d).saturating_sub(6);
    if degree > spline_core::MAX_DEGREE {
        return Err(Error::new(
            ErrorKind::DegreeTooHigh,
            format!(
                "g of a degree-{d} curve has degree {degree}, above the supported maximum {}",
                spline_core::MAX_DEGREE
            ),
        )
        .with_value(degree as f64)
        .with_interval(0.0, spline_core::MAX_DEGREE as f64));
    }
    Ok(())
}
