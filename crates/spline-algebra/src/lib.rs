//! B-spline algebra: every structural operation as a sparse linear map, products with
//! their Jacobians and (constant) second derivatives, curvature invariants of planar curves
//! with Jacobians and Hessians, bivariate differential quantities, and root isolation.
//!
//! The idea (Demers 2017, §5.3): every derived quantity — a derivative, a product, a
//! knot-inserted or degree-elevated form — is itself a B-spline whose coefficients are
//! functions of the input coefficients `x`. Linear operations are sparse matrices
//! ([`SplineMap`], [`TensorMap`]) that are their own Jacobians and compose by the chain rule;
//! products are sparse bilinear maps ([`SparseBilinear`], [`ProductMap`]) whose partial
//! contractions are the Jacobians and which are themselves the constant second derivative.
//! Sign conditions on the resulting coefficients are then sufficient conditions on the shape
//! (variation diminishing), ready for an interior-point solver.
//!
//! - Maps: [`SplineMap::derivative`], [`SplineMap::insertion`], [`SplineMap::refinement`],
//!   [`SplineMap::elevation`], [`SplineMap::bezier_extraction`], [`SplineMap::restriction`],
//!   exact [`SplineMap::knot_removal`]; applying one to control points of any type gives
//!   exactly what spline-geom computes. Tensor-product versions act as `A_u ⊗ A_v`.
//! - Products: [`product_knots`] (minimal multiplicities), [`ProductMap`] (per-segment
//!   Bernstein product (5.38), exact conversion to the minimal space by blossoming),
//!   [`dot_product`], [`wedge_product`], [`square`], [`sum`], [`difference`], [`linear_combination`].
//! - Planar curves: [`PlanarInvariants`] for `h1 … h4` and `g = h1 h2 − 3 h3 h4` in B-spline
//!   or per-segment Bernstein [`Form`]; [`planar_features`] (inflections, curvature extrema).
//! - Bivariate functions ([`spline_geom::Surface`]s with scalar control points; maps act on
//!   their row-major nets as `A_u ⊗ A_v`): [`partials`], [`tensor_product`],
//!   [`hessian_determinant`] (`s_uu s_vv − s_uv²` with gradient and constant Hessian),
//!   [`ridge_polynomials`].
//! - Curves of every kind: [`CurveFeatures`] (planar: inflections, curvature extrema,
//!   constant curvature), [`SpaceCurveFeatures`] (curvature extrema, torsion zeros),
//!   [`rational_planar_numerators`] / [`space_numerators`] with Jacobians w.r.t. the weighted
//!   control points, [`rational_planar_hessians`] / [`space_numerator_hessians`].
//! - Surfaces: [`curvature_numerators`] (`K`, `H`, umbilic conditions as bivariate splines),
//!   [`zero_set`] and [`common_zeros`] of bivariate splines, [`parabolic_lines`],
//!   [`umbilics`] (with those at poles), [`ridges`] of functions, [`surface_ridges`] of
//!   parametric surfaces, all of them in space by [`surface_feature_lines`] (drawn by
//!   `spline-io`).
//! - Roots: [`zeros`] and [`sign_change_params`] of any B-spline function.
//! - Intersections of planar curves of any kind: [`intersect_curves`] and
//!   [`self_intersections`] (subdivision of the Bézier pieces, Newton's method, tangential
//!   intersections flagged).
//! - Bounds: [`tight_box`], the exact extremes of every coordinate of a curve.
//! - Offsets: [`offset_cusps`], where the curvature times the distance is one (zeros of
//!   $d^2 h_4^2 - h_1^3$).
//!
//! Everything is generic over [`spline_core::Scalar`], so the same code runs on dual numbers
//! (the tests check every Jacobian and Hessian that way).
//!
//! ```
//! use spline_algebra::{ProductMap, SplineMap};
//! use spline_core::KnotVector;
//! use spline_geom::BSpline;
//! // s(u) and its derivative s'(u); the square s'(u)² with its Jacobian w.r.t. s's coefficients.
//! let knots = KnotVector::new(3, vec![0.0f64, 0., 0., 0., 0.5, 1., 1., 1., 1.])?;
//! let s = BSpline::new(knots.clone(), vec![0.0, 1.0, -1.0, 2.0, 0.5])?;
//! let d = SplineMap::derivative(&knots, 1)?;
//! let ds = d.apply_to(&s)?;
//! let square = ProductMap::new(d.target(), d.target())?;
//! let value = square.product(&ds, &ds)?;
//! assert!((value.eval(0.3)? - s.derivatives(0.3, 1)?[1].powi(2)).abs() < 1e-12);
//! // Chain rule: ∂(s'²)/∂x = (B(·, s') + B(s', ·)) · D.
//! let bilinear = square.bilinear();
//! let (_, inner) = bilinear.quadratic(ds.control_points())?;
//! let jacobian = &inner * d.matrix();
//! assert_eq!(jacobian.ncols(), 5);
//! # Ok::<(), spline_core::Error>(())
//! ```
//!
//! # Feature flags
//! None.

mod bezier_patch;
mod bilinear;
mod bounds;
mod curve_intersection;
mod curves;
mod features;
mod maps;
mod numerator;
mod offset;
mod parametric_ridges;
mod pole_umbilics;
mod polylines;
mod product;
mod revolution;
mod ridge_function;
mod ridges;
mod roots;
mod segment_curvature;
mod space;
mod sparse;
mod surface_features;
mod surface_numerators;
mod tensor;
mod threads;
mod umbilics;
mod zero_set;

pub use bilinear::SparseBilinear;
pub use bounds::tight_box;
pub use curve_intersection::{
    CurveEvent, CurveIntersection, CurveIntersections, CurveOverlap, DEFAULT_RELATIVE_CONTACT,
    MAX_INTERSECTION_PAIRS, TANGENTIAL_SINE, intersect_curves, intersect_curves_relative,
    planar_extent, self_intersections, self_intersections_relative,
};
pub use curves::{Differentiated, Form, Invariant, PlanarInvariants};
pub use features::{
    CurveFeatures, PlanarFeatures, RELATIVE_FEATURE_ACCURACY, RationalNumerators,
    curvature_extrema, default_feature_accuracy, inflections, planar_features,
    rational_planar_hessians, rational_planar_numerators,
};
pub use maps::SplineMap;
pub use nalgebra_sparse::CsrMatrix;
pub use offset::{OffsetCusp, offset_cusps};
pub use parametric_ridges::{SurfaceRidges, surface_ridges, surface_ridges_with_umbilics};
pub use polylines::UvPolyline;
pub use product::{
    ProductJacobians, ProductMap, Square, bernstein_product, common_space, difference, dot_product,
    linear_combination, product, product_knots, product_with_jacobians, scale, square, sum,
    wedge_product,
};
pub use revolution::{
    RevolutionFeatures, RevolutionNumerators, RidgeCircle, revolution_features,
    revolution_numerators,
};
pub use ridges::{Ridges, ridges};
pub use roots::{Zero, sign_change_params, zeros};
pub use segment_curvature::{SegmentCurvature, SegmentWorkspace};
pub use space::{
    SpaceCurveFeatures, SpaceFeatures, SpaceNumerators, space_numerator_hessians, space_numerators,
    torsion,
};
pub use sparse::kron;
pub use surface_features::{
    FunctionFeatures, LiftedPolyline, SurfaceFeatureLines, SurfaceFeatures, function_features,
    on_graph, on_surface, surface_feature_lines, surface_features,
};
pub use surface_numerators::{
    CurvatureNumerators, NumeratorJacobians, curvature_numerators,
    curvature_numerators_with_jacobians, parabolic_lines,
};
pub use tensor::{
    Partial, QuadraticFunction, TensorMap, TensorProductMap, hessian_determinant, partial,
    partials, ridge_polynomials, tensor_linear_combination, tensor_product,
};
pub use umbilics::{CommonZeros, common_zeros, umbilics};
pub use zero_set::{ZeroSet, zero_set};
