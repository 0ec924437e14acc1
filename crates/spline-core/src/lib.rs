//! The foundation of the `spline` library: the [`Scalar`] trait, the [`ControlPoint`] trait,
//! validated [`KnotVector`]s, and B-spline basis functions with their derivatives.
//!
//! Everything here is generic over the scalar type, so `f32`, `f64` and dual numbers all
//! work; with dual numbers a spline evaluation yields exact derivatives with respect to
//! knots, parameters or control points.
//!
//! ```
//! use spline_core::KnotVector;
//! // The basis of FIG. 1 of Celikbas (2003): degree 3, knots [0,0,0,0,1,2,3,3,3,3].
//! let knots = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0])?;
//! let basis = knots.eval_basis(1.5)?;
//! let sum: f64 = basis.values().iter().sum();
//! assert!((sum - 1.0).abs() < 1e-15); // partition of unity
//! # Ok::<(), spline_core::Error>(())
//! ```
//!
//! # Feature flags
//! - `proptest-support`: exports proptest strategies for knot vectors in the `strategies`
//!   module.

mod basis;
mod batch;
mod error;
mod golden;
mod knots;
mod march;
mod point;
mod quadrature;
mod scalar;
#[cfg(feature = "proptest-support")]
pub mod strategies;

pub use basis::{BasisValues, SpanBasis, bernstein, bernstein_all, binomial};
pub use batch::{BatchBasis, SpanTable};
pub use error::{Error, ErrorKind, Result, Short, overflow};
pub use golden::golden_section_max;
pub use knots::{
    KnotVector, MAX_DEGREE, MAX_DERIVATIVE_ORDER, MAX_ORDER, check_derivative_order,
    check_elevated_degree, check_params,
};
pub use march::march_to_boundary;
pub use point::{ControlPoint, SymbolicPoint, VectorSpace, lerp};
pub use quadrature::gauss_legendre;
pub use scalar::{Scalar, cast, from_count, power_of_two_scale, to_f64};
