//! Tensor-product B-spline surfaces: the container, evaluation (seed 000 Algorithm 4, with a
//! tensor fast path for grids), partial derivatives, derivative surfaces, iso-parametric
//! curves, and every structural algorithm in either direction.
//!
//! Structural algorithms are the curve algorithms of [`crate::BSpline`] applied to the lines
//! of the control net (seed 000 §1.4.4: "apply the basic curve algorithms in each
//! direction"): in direction `u` the surface is a curve whose control "points" are the `n_u`
//! rows of the net, so a knot inserted in `u` is inserted once, with one set of weights, for
//! every column (see `structural.rs`). Nothing is implemented twice.

mod basis;
mod container;
mod derivatives;
mod direction;
mod evaluator;
mod structural;

pub use container::Surface;
pub(crate) use container::flatten_net;
pub use direction::Direction;
pub(crate) use evaluator::SMALL_SQUARE;
pub use evaluator::SurfaceEvaluator;
