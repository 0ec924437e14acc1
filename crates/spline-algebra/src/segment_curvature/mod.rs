//! The curvature-extremum numerator `g` of a planar curve segment by segment, in dense form:
//! the fast kernel behind the selective eraser's constraints.
//!
//! [`crate::PlanarInvariants`] builds `g` as sparse bilinear maps over the whole curve, which
//! suits any knot vector and any use of the Jacobians. An interior-point method evaluates
//! `g`, its Jacobian and a weighted sum of its Hessians thousands of times for one curve;
//! each Bernstein coefficient of `g` on a segment depends only on the `p + 1` control points
//! active there, so dense blocks of size `2(p + 1)` hold everything. This module computes
//! them directly: the derivative coefficients of the segment are linear forms in its local
//! control points, `h1 … h4` quadratic forms (Bernstein products), and `g = h1 h2 − 3 h3 h4`
//! a quartic form whose gradient and Hessian follow from the product rule.

mod forms;

use crate::curves::check_extremum_numerator_degree;
use crate::maps::SplineMap;
use forms::{
    Pairing, ProductSums, Quadratic, add_pair, product_hessians, product_weights, quartic_products,
};
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, KnotVector, Result, Scalar, from_count};

/// The Bernstein coefficients of `g = h1 h2 − 3 h3 h4` (thesis (6.10)) on every non-empty knot
/// span of a planar curve of a fixed knot vector, with their gradients and Hessians with
/// respect to the control points, as dense blocks per segment.
///
/// Segment `s` (the `s`-th non-empty span) has `q + 1 = 4p − 5` coefficients, which depend on
/// the `p + 1` control points [`first_point(s)`](SegmentCurvature::first_point)` … + p`; its
/// local variables are their interleaved coordinates `[x_0, y_0, …, x_p, y_p]`
/// (`2(p + 1)` of them). The coefficients agree with [`crate::PlanarInvariants::g`] in
/// [`crate::Form::Bernstein`].
///
/// ```
/// use nalgebra::Vector2;
/// use spline_algebra::{Form, PlanarInvariants, SegmentCurvature};
/// use spline_core::KnotVector;
/// let knots = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0])?;
/// let points: Vec<Vector2<f64>> = [(0.0, 0.0), (1.0, 2.0), (2.0, -1.0), (3.0, 1.0), (4.0, 0.5)]
///     .iter().map(|&(x, y)| Vector2::new(x, y)).collect();
/// let fast = SegmentCurvature::new(&knots)?;
/// let mut values = vec![0.0; fast.num_coefficients()];
/// fast.values(&points, &mut values);
/// let reference = PlanarInvariants::new(&knots)?.g_value(&points, Form::Bernstein)?;
/// for (a, b) in values.iter().zip(reference.control_points()) {
///     assert!((a - b).abs() < 1e-10 * (1.0 + b.abs()));
/// }
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct SegmentCurvature<T> {
    degree: usize,
    segments: Vec<Segment<T>>,
    /// Bernstein product weights `C(m,i) C(n,j) / C(m+n,i+j)` for the four products.
    weights: ProductWeights<T>,
}

#[derive(Clone, Debug)]
struct Segment<T> {
    /// Index of the first control point acting on the segment.
    first: usize,
    /// Parameter interval of the segment.
    interval: (T, T),
    /// Coefficient vectors of the first three derivatives' Bernstein coefficients over the
    /// local control points: `d1[i]` has `p + 1` entries, `d1[i] · X` is the `x` coordinate of
    /// the `i`-th coefficient of `c′` (the same vector acts on `Y`).
    d1: Vec<Vec<T>>,
    d2: Vec<Vec<T>>,
    d3: Vec<Vec<T>>,
    /// The constant Hessians of the quadratic forms `h1 … h4` (row-major `N × N` each, in
    /// the order `h1`, `h2`, `h3`, `h4`): they depend on the knots only, so they are built
    /// once here and each weighted Hessian only combines them.
    hessians: Vec<T>,
}

#[derive(Clone, Debug)]
struct ProductWeights<T> {
    /// `h1 = c′·c′`, `h3 = c′·c″`, `h4 = c′ ∧ c″`, `h2 = c′ ∧ c‴`: Bernstein products of degree
    /// `(p−1)×(p−1)`, `(p−1)×(p−2)` and `(p−1)×(p−3)`.
    d1d1: Vec<Vec<T>>,
    d1d2: Vec<Vec<T>>,
    d1d3: Vec<Vec<T>>,
    /// `h1 h2` (degrees `2p−2`, `2p−4`) and `h3 h4` (`2p−3`, `2p−3`).
    h1h2: Vec<Vec<T>>,
    h3h4: Vec<Vec<T>>,
}

/// Scratch memory of one segment evaluation.
#[derive(Clone, Debug)]
pub struct SegmentWorkspace<T> {
    h1: Vec<Quadratic<T>>,
    h2: Vec<Quadratic<T>>,
    h3: Vec<Quadratic<T>>,
    h4: Vec<Quadratic<T>>,
    d1: Vec<(T, T)>,
    d2: Vec<(T, T)>,
    d3: Vec<(T, T)>,
    /// The weighted Hessian's sums: `Σ_i s_ij a_i` per right factor, `Σ_j s_ij b_j` per
    /// left factor, and `Σ_j s_ij ∇b_j` per left factor (`N` entries each).
    right_sums: Vec<T>,
    left_sums: Vec<T>,
    gradient_sums: Vec<T>,
}

impl<T: Scalar> SegmentCurvature<T> {
    /// Prepares the kernel for planar curves on `knots` (degree `p ≥ 3`).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] for degree below 3 (then `c‴ = 0` and `g` has no
    /// Bernstein form of degree `4p − 6`; use [`crate::PlanarInvariants`]);
    /// [`ErrorKind::DegreeTooHigh`] if `4p − 6` exceeds [`spline_core::MAX_DEGREE`].
    ///
    /// # Panics
    /// Never: the `expect` only states that every segment of a valid knot vector's domain
    /// lies in a knot span.
    pub fn new(knots: &KnotVector<T>) -> Result<Self> {
        let p = knots.degree();
        if p < 3 {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!("the segment kernel of g needs degree 3 or more, got {p}"),
            )
            .with_value(p as f64)
            .with_interval(3.0, f64::INFINITY));
        }
        check_extremum_numerator_degree(p)?;
        let weights = ProductWeights {
            d1d1: product_weights(p - 1, p - 1),
            d1d2: product_weights(p - 1, p - 2),
            d1d3: product_weights(p - 1, p - 3),
            h1h2: product_weights(2 * p - 2, 2 * p - 4),
            h3h4: product_weights(2 * p - 3, 2 * p - 3),
        };
        let nl = 2 * (p + 1);
        let extraction = SplineMap::bezier_extraction(knots);
        let matrix = extraction.matrix();
        let breaks = knots.domain_breaks();
        let k = knots.knots();
        let n = knots.num_basis();
        let mut segments = Vec::with_capacity(breaks.len() - 1);
        for (s, w) in breaks.windows(2).enumerate() {
            let (a, b) = (w[0], w[1]);
            // The span of the segment: the last index with k[span] ≤ a < k[span + 1].
            let span = (p..n)
                .rev()
                .find(|&i| k[i] <= a && a < k[i + 1])
                .expect("every domain segment lies in a knot span");
            let first = span - p;
            // Local extraction block: Bézier point r = Σ_j E[r][j] P[first + j].
            let mut local = vec![vec![T::zero(); p + 1]; p + 1];
            for (r, row) in local.iter_mut().enumerate() {
                let global = matrix.row(s * (p + 1) + r);
                for (&c, &v) in global.col_indices().iter().zip(global.values()) {
                    debug_assert!(c >= first && c <= span, "extraction outside the span");
                    row[c - first] = v;
                }
            }
            let h = b - a;
            let diff = |rows: &[Vec<T>], degree: usize| -> Vec<Vec<T>> {
                let f = from_count::<T>(degree) / h;
                rows.windows(2)
                    .map(|w| w[1].iter().zip(&w[0]).map(|(x, y)| (*x - *y) * f).collect())
                    .collect()
            };
            let d1 = diff(&local, p);
            let d2 = diff(&d1, p - 1);
            let d3 = diff(&d2, p - 2);
            // h1 … h4 have 2p − 1, 2p − 3, 2p − 2 and 2p − 2 coefficients.
            let mut hessians = Vec::with_capacity((8 * p - 8) * nl * nl);
            product_hessians(&mut hessians, nl, &d1, &d1, &weights.d1d1, Pairing::Dot);
            product_hessians(&mut hessians, nl, &d1, &d3, &weights.d1d3, Pairing::Wedge);
            product_hessians(&mut hessians, nl, &d1, &d2, &weights.d1d2, Pairing::Dot);
            product_hessians(&mut hessians, nl, &d1, &d2, &weights.d1d2, Pairing::Wedge);
            segments.push(Segment {
                first,
                interval: (a, b),
                d1,
                d2,
                d3,
                hessians,
            });
        }
        Ok(Self {
            degree: p,
            segments,
            weights,
        })
    }

    /// The degree `p` of the curves.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The number of segments (non-empty knot spans in the domain).
    #[must_use]
    pub fn num_segments(&self) -> usize {
        self.segments.len()
    }

    /// Coefficients of `g` per segment: `4p − 5`.
    #[must_use]
    pub fn coefficients_per_segment(&self) -> usize {
        4 * self.degree - 5
    }

    /// All coefficients: segments × coefficients per segment.
    #[must_use]
    pub fn num_coefficients(&self) -> usize {
        self.segments.len() * self.coefficients_per_segment()
    }

    /// Local variables per segment: `2(p + 1)`.
    #[must_use]
    pub fn local_variables(&self) -> usize {
        2 * (self.degree + 1)
    }

    /// The index of the first control point acting on segment `s`.
    ///
    /// # Panics
    /// If `s` is not a segment index.
    #[must_use]
    pub fn first_point(&self, s: usize) -> usize {
        self.segments[s].first
    }

    /// The parameter interval of segment `s`.
    ///
    /// # Panics
    /// If `s` is not a segment index.
    #[must_use]
    pub fn interval(&self, s: usize) -> (T, T) {
        self.segments[s].interval
    }

    /// Scratch memory for [`Self::segment`].
    #[must_use]
    pub fn workspace(&self) -> SegmentWorkspace<T> {
        let p = self.degree;
        let n = self.local_variables();
        SegmentWorkspace {
            h1: vec![Quadratic::zeros(n); 2 * p - 1],
            h2: vec![Quadratic::zeros(n); 2 * p - 3],
            h3: vec![Quadratic::zeros(n); 2 * p - 2],
            h4: vec![Quadratic::zeros(n); 2 * p - 2],
            d1: vec![(T::zero(), T::zero()); p],
            d2: vec![(T::zero(), T::zero()); p - 1],
            d3: vec![(T::zero(), T::zero()); p - 2],
            right_sums: vec![T::zero(); 2 * p - 1],
            left_sums: vec![T::zero(); 2 * p - 1],
            gradient_sums: vec![T::zero(); (2 * p - 1) * n],
        }
    }

    /// The coefficients of `g` of every segment, segment after segment, into `out`
    /// ([`Self::num_coefficients`] entries).
    ///
    /// # Panics
    /// If `points` does not have one point per basis function of the knot vector, or `out`
    /// has the wrong length.
    pub fn values(&self, points: &[Vector2<T>], out: &mut [T]) {
        let q1 = self.coefficients_per_segment();
        assert_eq!(out.len(), self.num_coefficients(), "output length");
        let mut ws = self.workspace();
        for (s, chunk) in out.chunks_exact_mut(q1).enumerate() {
            self.segment(s, points, &mut ws, chunk, None, None);
        }
    }

    /// Segment `s`: its `g` coefficients into `values` (`4p − 5` entries); with `jacobian`
    /// (`(4p − 5) × 2(p + 1)`, row-major) their gradients with respect to the local
    /// variables; with `hessian = (weights, out)` the weighted sum of their Hessians
    /// $\sum_k w_k \nabla^2 g_k$ (`2(p + 1) × 2(p + 1)`, row-major), *added* to `out`.
    ///
    /// # Panics
    /// If the slices have the wrong lengths or `points` is too short.
    pub fn segment(
        &self,
        s: usize,
        points: &[Vector2<T>],
        ws: &mut SegmentWorkspace<T>,
        values: &mut [T],
        jacobian: Option<&mut [T]>,
        hessian: Option<(&[T], &mut [T])>,
    ) {
        let p = self.degree;
        let n = self.local_variables();
        let seg = &self.segments[s];
        let local = &points[seg.first..=seg.first + p];
        let coords = |rows: &[Vec<T>], out: &mut [(T, T)]| {
            for (o, r) in out.iter_mut().zip(rows) {
                let mut x = T::zero();
                let mut y = T::zero();
                for (c, q) in r.iter().zip(local) {
                    x += *c * q.x;
                    y += *c * q.y;
                }
                *o = (x, y);
            }
        };
        coords(&seg.d1, &mut ws.d1);
        coords(&seg.d2, &mut ws.d2);
        coords(&seg.d3, &mut ws.d3);
        let need_grad = jacobian.is_some() || hessian.is_some();
        // h1 = c′·c′, h3 = c′·c″, h4 = c′ ∧ c″, h2 = c′ ∧ c‴ (Bernstein products).
        let w = &self.weights;
        let build = |out: &mut [Quadratic<T>],
                     right: &[Vec<T>],
                     rc: &[(T, T)],
                     weights: &[Vec<T>],
                     pairing: Pairing| {
            out.iter_mut().for_each(Quadratic::clear);
            for (i, (a, ac)) in seg.d1.iter().zip(&ws.d1).enumerate() {
                for (j, (b, bc)) in right.iter().zip(rc).enumerate() {
                    add_pair(
                        &mut out[i + j],
                        weights[i][j],
                        (a, b),
                        *ac,
                        *bc,
                        (pairing, need_grad),
                    );
                }
            }
        };
        {
            let (mut h1, mut h2, mut h3, mut h4) = (
                std::mem::take(&mut ws.h1),
                std::mem::take(&mut ws.h2),
                std::mem::take(&mut ws.h3),
                std::mem::take(&mut ws.h4),
            );
            build(&mut h1, &seg.d1, &ws.d1, &w.d1d1, Pairing::Dot);
            build(&mut h2, &seg.d3, &ws.d3, &w.d1d3, Pairing::Wedge);
            build(&mut h3, &seg.d2, &ws.d2, &w.d1d2, Pairing::Dot);
            build(&mut h4, &seg.d2, &ws.d2, &w.d1d2, Pairing::Wedge);
            ws.h1 = h1;
            ws.h2 = h2;
            ws.h3 = h3;
            ws.h4 = h4;
        }
        values.iter_mut().for_each(|v| *v = T::zero());
        let mut jacobian = jacobian;
        if let Some(jac) = jacobian.as_deref_mut() {
            jac.iter_mut().for_each(|v| *v = T::zero());
        }
        let three: T = from_count(3);
        // g = h1 h2 − 3 h3 h4: products of quadratic forms.
        for (left, right, weights, factor) in [
            (&ws.h1, &ws.h2, &w.h1h2, T::one()),
            (&ws.h3, &ws.h4, &w.h3h4, -three),
        ] {
            quartic_products(
                left,
                right,
                weights,
                factor,
                n,
                values,
                jacobian.as_deref_mut(),
            );
        }
        if let Some(hessian) = hessian {
            self.add_segment_hessian(s, ws, hessian);
        }
    }

    /// The weighted sum of the Hessians of segment `s`'s coefficients,
    /// $\sum_k w_k \nabla^2 g_k$ with `(weights, out)` as in [`Self::segment`], *added* to
    /// `out`, from the quadratic forms `ws` holds: those of the last [`Self::segment`] call
    /// on `ws`, which must have been for segment `s` at the control points wanted and with
    /// a Jacobian or a Hessian asked (a call for values only keeps no gradients). A caller
    /// that keeps one workspace per segment gets the Jacobians and, once the weights are
    /// known, the Hessians with the forms built once — the same numbers, bit for bit, as
    /// [`Self::segment`] with both.
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use spline_algebra::SegmentCurvature;
    /// use spline_core::KnotVector;
    /// let knots = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0])?;
    /// let points: Vec<Vector2<f64>> = [(0.0, 0.0), (1.0, 2.0), (2.0, -1.0), (3.0, 1.0), (4.0, 0.5)]
    ///     .iter().map(|&(x, y)| Vector2::new(x, y)).collect();
    /// let kernel = SegmentCurvature::new(&knots)?;
    /// let (q1, n) = (kernel.coefficients_per_segment(), kernel.local_variables());
    /// let weights: Vec<f64> = (0..q1).map(|k| 1.0 + k as f64).collect();
    /// let (mut values, mut jacobian) = (vec![0.0; q1], vec![0.0; q1 * n]);
    /// let mut at_once = vec![0.0; n * n];
    /// let mut ws = kernel.workspace();
    /// kernel.segment(1, &points, &mut ws, &mut values, None, Some((&weights, &mut at_once)));
    /// let mut later = vec![0.0; n * n];
    /// kernel.segment(1, &points, &mut ws, &mut values, Some(&mut jacobian), None);
    /// kernel.add_segment_hessian(1, &mut ws, (&weights, &mut later));
    /// assert_eq!(at_once, later);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Panics
    /// If `s` is not a segment index or the slices have the wrong lengths.
    pub fn add_segment_hessian(
        &self,
        s: usize,
        ws: &mut SegmentWorkspace<T>,
        (hw, out): (&[T], &mut [T]),
    ) {
        let p = self.degree;
        let n = self.local_variables();
        let w = &self.weights;
        let three: T = from_count(3);
        let nn = n * n;
        let (q1, q2, q3) = (2 * p - 1, 2 * p - 3, 2 * p - 2);
        let (h1, rest) = self.segments[s].hessians.split_at(q1 * nn);
        let (h2, rest) = rest.split_at(q2 * nn);
        let (h3, h4) = rest.split_at(q3 * nn);
        let SegmentWorkspace {
            h1: a1,
            h2: a2,
            h3: a3,
            h4: a4,
            right_sums,
            left_sums,
            gradient_sums,
            ..
        } = ws;
        let mut sums = ProductSums {
            right: right_sums,
            left: left_sums,
            gradients: gradient_sums,
        };
        sums.add_weighted_hessian((a1, h1), (a2, h2), &w.h1h2, T::one(), hw, out);
        sums.add_weighted_hessian((a3, h3), (a4, h4), &w.h3h4, -three, hw, out);
    }
}
