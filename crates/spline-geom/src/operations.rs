//! Structural operations as values, and the traits that apply them to every kind of curve
//! and surface: what a front end (the `spline` tool, a script) parses is an [`Operation`];
//! the library applies it to a B-spline or NURBS curve ([`StructuralCurve`]) or surface
//! ([`StructuralSurface`]) and returns an [`Outcome`] to print.

use crate::bspline::BSpline;
use crate::surface::{Direction, Surface};
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar};

/// A structural operation with its arguments.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Operation<T> {
    /// Insert `knot` `times` times.
    Insert {
        /// The knot.
        knot: T,
        /// How many times.
        times: usize,
    },
    /// Insert all `knots` (refinement).
    Refine {
        /// The knots, any order.
        knots: Vec<T>,
    },
    /// Remove `knot` `times` times if the shape moves by at most `tolerance` times the size
    /// of the control polygon.
    Remove {
        /// The interior knot.
        knot: T,
        /// How many times.
        times: usize,
        /// The relative tolerance.
        tolerance: T,
    },
    /// Raise the degree by `times`.
    Elevate {
        /// By how many degrees.
        times: usize,
    },
    /// Split at `at` into two pieces clamped there.
    Split {
        /// The parameter, strictly inside the domain.
        at: T,
    },
    /// The Bézier segments (curves) or patches (surfaces).
    Bezier,
    /// The derivative curve of order `order` (surfaces: the partial derivatives of order
    /// `order` in `u` and in `v`).
    Derivative {
        /// The order.
        order: usize,
    },
}

/// What an operation returns.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome<S> {
    /// One object (insertion, refinement, removal, elevation, derivative of a curve).
    One(S),
    /// Two objects: the halves of a split, or the partial derivatives in `u` and in `v`.
    Pair(S, S),
    /// A list: the Bézier segments of a curve.
    List(Vec<S>),
    /// A grid: the Bézier patches of a surface, `[a][b]` over the `a`-th span in `u` and the
    /// `b`-th in `v`.
    Grid(Vec<Vec<S>>),
}

/// The structural operations of a kind of curve.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::{BSpline, Operation, Outcome, StructuralCurve};
/// let c = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 2.0), Vector2::new(2.0, 0.0)])?;
/// match c.apply(&Operation::Split { at: 0.25 })? {
///     Outcome::Pair(left, right) => assert_eq!((left.domain(), right.domain()), ((0.0, 0.25), (0.25, 1.0))),
///     _ => unreachable!(),
/// }
/// # Ok::<(), spline_core::Error>(())
/// ```
pub trait StructuralCurve<T: Scalar>: Sized {
    /// Inserts the knot `u` `times` times.
    ///
    /// # Errors
    /// As [`BSpline::insert_knot`].
    fn insert_knot(&self, u: T, times: usize) -> Result<Self>;
    /// Inserts all the knots.
    ///
    /// # Errors
    /// As [`BSpline::refine`].
    fn refine(&self, knots: &[T]) -> Result<Self>;
    /// Removes the knot `u` `times` times within a relative tolerance.
    ///
    /// # Errors
    /// As [`BSpline::remove_knot`].
    fn remove_knot(&self, u: T, times: usize, relative_tolerance: T) -> Result<Self>;
    /// Raises the degree by `times`.
    ///
    /// # Errors
    /// As [`BSpline::elevate_degree`].
    fn elevate_degree(&self, times: usize) -> Result<Self>;
    /// Splits at `u` into two curves clamped there.
    ///
    /// # Errors
    /// As [`BSpline::split`].
    fn split(&self, u: T) -> Result<(Self, Self)>;
    /// The Bézier segments, each a clamped curve of the same kind on its span.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidWeight`] for rational segments whose weights leave the range of
    /// floating point.
    fn bezier_curves(&self) -> Result<Vec<Self>>;
    /// The derivative curve of order `order`.
    ///
    /// # Errors
    /// As [`BSpline::derivative`]; [`ErrorKind::Unsupported`] for rational curves (their
    /// derivatives are not curves of the same kind on the same knots).
    fn derivative_curve(&self, order: usize) -> Result<Self>;

    /// Applies an operation.
    ///
    /// # Errors
    /// The errors of the operation.
    fn apply(&self, operation: &Operation<T>) -> Result<Outcome<Self>> {
        Ok(match operation {
            Operation::Insert { knot, times } => Outcome::One(self.insert_knot(*knot, *times)?),
            Operation::Refine { knots } => Outcome::One(self.refine(knots)?),
            Operation::Remove {
                knot,
                times,
                tolerance,
            } => Outcome::One(self.remove_knot(*knot, *times, *tolerance)?),
            Operation::Elevate { times } => Outcome::One(self.elevate_degree(*times)?),
            Operation::Split { at } => {
                let (a, b) = self.split(*at)?;
                Outcome::Pair(a, b)
            }
            Operation::Bezier => Outcome::List(self.bezier_curves()?),
            Operation::Derivative { order } => Outcome::One(self.derivative_curve(*order)?),
        })
    }
}

impl<T: Scalar, P: ControlPoint<T>> StructuralCurve<T> for BSpline<T, P> {
    fn insert_knot(&self, u: T, times: usize) -> Result<Self> {
        BSpline::insert_knot(self, u, times)
    }

    fn refine(&self, knots: &[T]) -> Result<Self> {
        BSpline::refine(self, knots)
    }

    fn remove_knot(&self, u: T, times: usize, relative_tolerance: T) -> Result<Self> {
        BSpline::remove_knot(self, u, times, relative_tolerance)
    }

    fn elevate_degree(&self, times: usize) -> Result<Self> {
        BSpline::elevate_degree(self, times)
    }

    fn split(&self, u: T) -> Result<(Self, Self)> {
        BSpline::split(self, u)
    }

    fn bezier_curves(&self) -> Result<Vec<Self>> {
        Ok(self
            .bezier_segments()
            .iter()
            .map(crate::bezier::bezier_as_bspline)
            .collect())
    }

    fn derivative_curve(&self, order: usize) -> Result<Self> {
        self.derivative(order)
    }
}

/// The structural operations of a kind of tensor-product surface, in one direction.
pub trait StructuralSurface<T: Scalar>: Sized {
    /// Inserts the knot `t` `times` times in `direction`.
    ///
    /// # Errors
    /// As [`Surface::insert_knot`].
    fn insert_knot(&self, direction: Direction, t: T, times: usize) -> Result<Self>;
    /// Inserts all the knots in `direction`.
    ///
    /// # Errors
    /// As [`Surface::refine`].
    fn refine(&self, direction: Direction, knots: &[T]) -> Result<Self>;
    /// Removes the knot `t` of `direction` `times` times if the surface moves by at most
    /// `tolerance` (absolute).
    ///
    /// # Errors
    /// As [`Surface::remove_knot_within`].
    fn remove_knot_within(&self, dir: Direction, t: T, times: usize, tol: T) -> Result<Self>;
    /// Removes the knot `t` of `dir` `times` times within a relative tolerance.
    ///
    /// # Errors
    /// As [`Surface::remove_knot`].
    fn remove_knot(&self, dir: Direction, t: T, times: usize, relative: T) -> Result<Self>;
    /// Raises the degree in `direction` by `times`.
    ///
    /// # Errors
    /// As [`Surface::elevate_degree`].
    fn elevate_degree(&self, direction: Direction, times: usize) -> Result<Self>;
    /// Splits at `t` in `direction`.
    ///
    /// # Errors
    /// As [`Surface::split`].
    fn split(&self, direction: Direction, t: T) -> Result<(Self, Self)>;
    /// The Bézier patches.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidWeight`] for rational patches whose weights leave the range of
    /// floating point.
    fn bezier_patches(&self) -> Result<Vec<Vec<Self>>>;
    /// The partial derivatives of order `order` in `u` and in `v`, as surfaces.
    ///
    /// # Errors
    /// As [`Surface::derivative_surface`]; [`ErrorKind::Unsupported`] for rational
    /// surfaces.
    fn derivative_surfaces(&self, order: usize) -> Result<(Self, Self)>;

    /// Applies an operation in `direction` (`None`: `u`, and the operations without a
    /// direction).
    ///
    /// # Errors
    /// The errors of the operation; [`ErrorKind::InvalidArgument`] for a direction given to
    /// an operation without one (Bézier patches, derivatives).
    fn apply(
        &self,
        operation: &Operation<T>,
        direction: Option<Direction>,
    ) -> Result<Outcome<Self>> {
        if direction.is_some()
            && matches!(operation, Operation::Bezier | Operation::Derivative { .. })
        {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "--direction is not used by this operation",
            ));
        }
        let d = direction.unwrap_or(Direction::U);
        Ok(match operation {
            Operation::Insert { knot, times } => Outcome::One(self.insert_knot(d, *knot, *times)?),
            Operation::Refine { knots } => Outcome::One(self.refine(d, knots)?),
            Operation::Remove {
                knot,
                times,
                tolerance,
            } => Outcome::One(self.remove_knot(d, *knot, *times, *tolerance)?),
            Operation::Elevate { times } => Outcome::One(self.elevate_degree(d, *times)?),
            Operation::Split { at } => {
                let (a, b) = self.split(d, *at)?;
                Outcome::Pair(a, b)
            }
            Operation::Bezier => Outcome::Grid(self.bezier_patches()?),
            Operation::Derivative { order } => {
                let (du, dv) = self.derivative_surfaces(*order)?;
                Outcome::Pair(du, dv)
            }
        })
    }
}

impl<T: Scalar, P: ControlPoint<T>> StructuralSurface<T> for Surface<T, P> {
    fn insert_knot(&self, direction: Direction, t: T, times: usize) -> Result<Self> {
        Surface::insert_knot(self, direction, t, times)
    }

    fn refine(&self, direction: Direction, knots: &[T]) -> Result<Self> {
        Surface::refine(self, direction, knots)
    }

    fn remove_knot_within(&self, direction: Direction, t: T, times: usize, tol: T) -> Result<Self> {
        Surface::remove_knot_within(self, direction, t, times, tol)
    }

    fn remove_knot(&self, direction: Direction, t: T, times: usize, tol: T) -> Result<Self> {
        Surface::remove_knot(self, direction, t, times, tol)
    }

    fn elevate_degree(&self, direction: Direction, times: usize) -> Result<Self> {
        Surface::elevate_degree(self, direction, times)
    }

    fn split(&self, direction: Direction, t: T) -> Result<(Self, Self)> {
        Surface::split(self, direction, t)
    }

    fn bezier_patches(&self) -> Result<Vec<Vec<Self>>> {
        Ok(Surface::bezier_patches(self))
    }

    fn derivative_surfaces(&self, order: usize) -> Result<(Self, Self)> {
        Ok((
            self.derivative_surface(order, 0)?,
            self.derivative_surface(0, order)?,
        ))
    }
}
