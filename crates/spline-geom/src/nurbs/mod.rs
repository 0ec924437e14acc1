//! NURBS curves and surfaces: rational views over B-spline containers of homogeneous points.
//!
//! A NURBS curve is the central projection of a B-spline curve in $\mathbb{R}^{D+1}$ whose
//! control points are $(w_i P_i, w_i)$ (seed 004 (6.4)–(6.5)). Evaluation is evaluation in
//! homogeneous space followed by the projection; rational derivatives follow from Leibniz's
//! rule (The NURBS Book A4.2 and A4.4); every structural algorithm (insertion, refinement,
//! removal, elevation, splitting) runs unchanged on the homogeneous container.

mod curve;
mod derivatives;
mod mobius;
mod rational;
mod removal;
mod surface;
mod surface_evaluator;
mod weighted;

pub use curve::{NurbsCurve, NurbsCurve2, NurbsCurve3};
pub(crate) use derivatives::rational_curve_derivatives;
pub use rational::{HomogeneousContainer, Rational};
pub use surface::{NurbsSurface, NurbsSurface3};
pub use surface_evaluator::NurbsSurfaceEvaluator;
