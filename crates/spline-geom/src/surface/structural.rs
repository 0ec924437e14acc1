//! Structural algorithms of surfaces: the curve algorithms of [`BSpline`] run on the lines
//! of the control net. In direction `u` the surface is the curve whose control points are
//! the rows $(P_{i0}, …, P_{i,n_v-1})$ of the net ([`Line`], a vector space of its own), so
//! every algorithm computes its weights once for all columns.

use super::container::Surface;
use super::direction::Direction;
use crate::bezier::bezier_as_bspline;
use crate::bspline::BSpline;
use crate::structural::{checked_removal, relative_scale};
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, VectorSpace};

/// A line of a control net: the points of one row (direction `u`) or one column (direction
/// `v`), added and scaled point by point. The empty line is the zero vector of any length.
#[derive(Clone, Debug, PartialEq)]
struct Line<P>(Vec<P>);

impl<T: Scalar, P: ControlPoint<T>> VectorSpace<T> for Line<P> {
    fn zero_vector() -> Self {
        Self(Vec::new())
    }

    fn combine(&self, a: T, other: &Self, b: T) -> Self {
        match (self.0.is_empty(), other.0.is_empty()) {
            (true, _) => other.scaled(b),
            (_, true) => self.scaled(a),
            _ => Self(
                self.0
                    .iter()
                    .zip(&other.0)
                    .map(|(x, y)| *x * a + *y * b)
                    .collect(),
            ),
        }
    }

    fn scaled(&self, a: T) -> Self {
        Self(self.0.iter().map(|x| *x * a).collect())
    }

    fn add_scaled(&mut self, other: &Self, a: T) {
        if self.0.is_empty() {
            *self = other.scaled(a);
        } else {
            for (x, y) in self.0.iter_mut().zip(&other.0) {
                *x += *y * a;
            }
        }
    }

    fn is_finite_vector(&self) -> bool {
        self.0.iter().all(ControlPoint::all_finite)
    }
}

impl<T: Scalar, P: ControlPoint<T>> Surface<T, P> {
    /// The surface as a curve in `direction` whose control points are the lines of the net
    /// across it.
    fn lines(&self, direction: Direction) -> BSpline<T, Line<P>> {
        let (nu, nv) = self.net_size();
        let points = self.control_points();
        let lines = match direction {
            Direction::U => points
                .chunks_exact(nv)
                .map(|row| Line(row.to_vec()))
                .collect(),
            Direction::V => (0..nv)
                .map(|j| Line((0..nu).map(|i| points[i * nv + j]).collect()))
                .collect(),
        };
        BSpline::new_unchecked(self.knots(direction).clone(), lines)
    }

    /// The surface of [`Surface::lines`] in `direction`, the knots across being `other`.
    fn from_lines(direction: Direction, other: KnotVector<T>, curve: BSpline<T, Line<P>>) -> Self {
        let (knots, lines) = curve.into_parts();
        match direction {
            Direction::U => Self::new_unchecked(
                knots,
                other,
                lines.into_iter().flat_map(|line| line.0).collect(),
            ),
            Direction::V => {
                let (nu, nv) = (other.num_basis(), lines.len());
                let mut points = Vec::with_capacity(nu * nv);
                for i in 0..nu {
                    points.extend(lines.iter().map(|line| line.0[i]));
                }
                Self::new_unchecked(other, knots, points)
            }
        }
    }

    /// Runs a curve algorithm on the lines of the net in `direction`.
    fn with_lines(
        &self,
        direction: Direction,
        f: impl FnOnce(&BSpline<T, Line<P>>) -> Result<BSpline<T, Line<P>>>,
    ) -> Result<Self> {
        let curve = f(&self.lines(direction))
            .map_err(|e| e.context(format_args!("direction {direction}")))?;
        Ok(Self::from_lines(
            direction,
            self.knots(direction.other()).clone(),
            curve,
        ))
    }

    /// The `n_v` curves (direction `U`) formed by the columns $P_{0j}, …, P_{n_u-1,j}$ of
    /// the net with the knots in `u`, or the `n_u` curves (direction `V`) formed by its rows
    /// with the knots in `v`. A surface is a curve of such curves (seed 004 (5.3), (5.6)).
    #[must_use]
    pub fn control_curves(&self, direction: Direction) -> Vec<BSpline<T, P>> {
        // The curves in `direction` are the lines across the other direction.
        self.lines(direction.other())
            .into_parts()
            .1
            .into_iter()
            .map(|line| BSpline::new_unchecked(self.knots(direction).clone(), line.0))
            .collect()
    }

    /// Applies a curve algorithm to every control curve in `direction` (see
    /// [`Surface::control_curves`]) and reassembles the surface. `f` must map curves with
    /// equal knots to curves with equal knots, as every structural algorithm does.
    ///
    /// ```
    /// use spline_geom::{Direction, Surface};
    /// let s = Surface::bezier(vec![vec![0.0, 1.0], vec![2.0, 3.0], vec![4.0, 6.0]])?;
    /// let r = s.map_curves(Direction::U, |c| Ok(c.reversed()))?;
    /// assert_eq!(r.eval(0.25, 0.5)?, s.eval(0.75, 0.5)?);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// The first error of `f`; [`ErrorKind::SpaceMismatch`] if `f` returns curves with
    /// different knot vectors (the index of the first curve unlike the one before it as
    /// [`Error::index`]).
    pub fn map_curves(
        &self,
        direction: Direction,
        mut f: impl FnMut(&BSpline<T, P>) -> Result<BSpline<T, P>>,
    ) -> Result<Self> {
        let curves = self
            .control_curves(direction)
            .iter()
            .map(&mut f)
            .collect::<Result<Vec<_>>>()?;
        if let Some(i) = curves.windows(2).position(|w| w[0].knots() != w[1].knots()) {
            return Err(Error::new(
                ErrorKind::SpaceMismatch,
                "the control curves ended with different knot vectors",
            )
            .with_index(i + 1));
        }
        let knots = curves[0].knots().clone();
        let lines = curves.into_iter().map(|c| Line(c.into_parts().1)).collect();
        // The curves are the lines across the other direction.
        let across = BSpline::new_unchecked(self.knots(direction.other()).clone(), lines);
        Ok(Self::from_lines(direction.other(), knots, across))
    }

    /// The iso-parametric curve `v ↦ S(u, v)` at fixed `u` (seed 004 (5.6)): a B-spline in
    /// `v` with control points $P_j(u) = \sum_i N_i(u) P_{ij}$.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn curve_at_u(&self, u: T) -> Result<BSpline<T, P>> {
        self.iso_curve(Direction::U, u)
    }

    /// The iso-parametric curve `u ↦ S(u, v)` at fixed `v` (seed 004 (5.3)): a B-spline in
    /// `u` with control points $P_i(v) = \sum_j N_j(v) P_{ij}$.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn curve_at_v(&self, v: T) -> Result<BSpline<T, P>> {
        self.iso_curve(Direction::V, v)
    }

    /// The iso-parametric curve with the parameter of direction `fixed` held at `value`:
    /// [`Surface::curve_at_u`] or [`Surface::curve_at_v`].
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn iso_curve(&self, fixed: Direction, value: T) -> Result<BSpline<T, P>> {
        let points = self
            .control_curves(fixed)
            .iter()
            .map(|c| c.eval(value))
            .collect::<Result<Vec<_>>>()?;
        Ok(BSpline::new_unchecked(
            self.knots(fixed.other()).clone(),
            points,
        ))
    }

    /// The partial derivative $\partial^{k+l} S / \partial u^k \partial v^l$ as a B-spline
    /// surface of degrees `(p − k, q − l)` (seed 004 (5.10)–(5.11), applied `k` and `l`
    /// times), built with [`BSpline::derivative`] on the lines of the net.
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] if `k > p` or `l > q` (those derivatives are zero).
    pub fn derivative_surface(&self, k: usize, l: usize) -> Result<Self> {
        let mut s = self.clone();
        if k > 0 {
            s = s.with_lines(Direction::U, |c| c.derivative(k))?;
        }
        if l > 0 {
            s = s.with_lines(Direction::V, |c| c.derivative(l))?;
        }
        Ok(s)
    }

    /// Inserts the knot `t` `times` times in `direction` (seed 000 FIG. 12) without changing
    /// the surface.
    ///
    /// ```
    /// use spline_geom::{Direction, Surface};
    /// let s = Surface::bezier(vec![vec![0.0f64, 1.0, 0.5], vec![2.0, 3.0, 1.0], vec![4.0, 6.0, 2.0]])?;
    /// let t = s.insert_knot(Direction::V, 0.25, 2)?;
    /// assert_eq!(t.net_size(), (3, 5));
    /// assert!((t.eval(0.3, 0.7)? - s.eval(0.3, 0.7)?).abs() < 1e-15);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BSpline::insert_knot`].
    pub fn insert_knot(&self, direction: Direction, t: T, times: usize) -> Result<Self> {
        self.with_lines(direction, |c| c.insert_knot(t, times))
    }

    /// Inserts many knots in `direction` at once (knot refinement).
    ///
    /// # Errors
    /// As [`BSpline::refine`].
    pub fn refine(&self, direction: Direction, knots: &[T]) -> Result<Self> {
        self.with_lines(direction, |c| c.refine(knots))
    }

    /// Removes the interior knot `t` of `direction` `times` times if the surface moves by at
    /// most `tolerance` (absolute). The change is checked exactly as for curves (see
    /// [`BSpline::remove_knot_within`]) on every line of the net; by the partition of unity
    /// in the other direction, the largest change of a control point bounds the change of
    /// the surface.
    ///
    /// # Errors
    /// As [`BSpline::remove_knot_within`].
    pub fn remove_knot_within(&self, dir: Direction, t: T, times: usize, tol: T) -> Result<Self> {
        self.with_lines(dir, |c| {
            checked_removal(c, t, times, tol, |a: &Line<P>, b: &Line<P>| {
                a.0.iter()
                    .zip(&b.0)
                    .fold(T::zero(), |m, (x, y)| m.max((*x - *y).length()))
            })
        })
    }

    /// [`Surface::remove_knot_within`] with a tolerance relative to the size of the control
    /// net (its largest coordinate magnitude, or 1 if that is smaller).
    ///
    /// # Errors
    /// As [`BSpline::remove_knot_within`].
    pub fn remove_knot(&self, dir: Direction, t: T, times: usize, relative: T) -> Result<Self> {
        let scale = relative_scale(self.control_points().iter().map(ControlPoint::max_abs));
        self.remove_knot_within(dir, t, times, relative * scale)
    }

    /// Raises the degree in `direction` by `times` (seed 000 FIG. 13; exact, as
    /// [`BSpline::elevate_degree`]).
    ///
    /// # Errors
    /// As [`BSpline::elevate_degree`].
    pub fn elevate_degree(&self, direction: Direction, times: usize) -> Result<Self> {
        self.with_lines(direction, |c| c.elevate_degree(times))
    }

    /// Splits the surface at `t` in `direction` (seed 000 FIG. 11) into two surfaces, both
    /// clamped at `t`, on the two halves of the domain.
    ///
    /// # Errors
    /// As [`BSpline::split`], naming the direction.
    pub fn split(&self, direction: Direction, t: T) -> Result<(Self, Self)> {
        let (left, right) = self
            .lines(direction)
            .split(t)
            .map_err(|e| e.context(format_args!("direction {direction}")))?;
        let other = self.knots(direction.other()).clone();
        Ok((
            Self::from_lines(direction, other.clone(), left),
            Self::from_lines(direction, other, right),
        ))
    }

    /// The same surface with clamped knots in both directions (it then interpolates the
    /// four corners of its net, seed 004 (5.9)).
    ///
    /// # Panics
    /// Never: clamping cannot fail.
    #[must_use]
    pub fn clamped(&self) -> Self {
        self.with_lines(Direction::U, |c| Ok(c.clamped()))
            .and_then(|s| s.with_lines(Direction::V, |c| Ok(c.clamped())))
            .expect("clamping cannot fail")
    }

    /// The same surface traversed backwards in `direction`.
    ///
    /// # Panics
    /// Never: reversal cannot fail.
    #[must_use]
    pub fn reversed(&self, direction: Direction) -> Self {
        self.with_lines(direction, |c| Ok(c.reversed()))
            .expect("reversal cannot fail")
    }

    /// The same surface with the domain of `direction` mapped affinely onto `[a, b]`.
    ///
    /// # Errors
    /// [`ErrorKind::EmptyDomain`] unless `a < b`; [`ErrorKind::NonFinite`].
    pub fn reparametrized(&self, direction: Direction, a: T, b: T) -> Result<Self> {
        let knots = self.knots(direction).reparametrized(a, b)?;
        let points = self.control_points().to_vec();
        Ok(match direction {
            Direction::U => Self::new_unchecked(knots, self.knots_v().clone(), points),
            Direction::V => Self::new_unchecked(self.knots_u().clone(), knots, points),
        })
    }

    /// The surface with `u` and `v` exchanged: $\tilde S(v, u) = S(u, v)$.
    #[must_use]
    pub fn transposed(&self) -> Self {
        let (knots, lines) = self.lines(Direction::V).into_parts();
        Self::new_unchecked(
            knots,
            self.knots_u().clone(),
            lines.into_iter().flat_map(|line| line.0).collect(),
        )
    }

    /// The strips of the surface between consecutive distinct knots of `direction`, each a
    /// Bézier in that direction on its own interval.
    fn bezier_strips(&self, direction: Direction) -> Vec<Self> {
        let other = self.knots(direction.other()).clone();
        self.lines(direction)
            .bezier_segments()
            .iter()
            .map(|segment| Self::from_lines(direction, other.clone(), bezier_as_bspline(segment)))
            .collect()
    }

    /// The Bézier patches of the surface: `[a][b]` is the patch over the `a`-th non-empty
    /// knot span in `u` and the `b`-th in `v`, a Bézier surface (seed 004 (5.2)) on that
    /// rectangle (knots of multiplicity `p + 1`, `q + 1` at its ends).
    #[must_use]
    pub fn bezier_patches(&self) -> Vec<Vec<Self>> {
        self.bezier_strips(Direction::U)
            .iter()
            .map(|strip| strip.bezier_strips(Direction::V))
            .collect()
    }
}
