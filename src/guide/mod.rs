//! Six chapters between the README and the API reference, each a short text with
//! examples that run as doc tests (`cargo test -p spline --doc guide`).
//!
//! Read them in order, or jump to the one that matches where you come from:
//!
//! 1. [From scipy](crate::guide::from_scipy): `make_interp_spline`, `BSpline`, `make_splrep`
//!    and `NdBSpline` in Rust, and the Python package `spline` as a drop-in for scipy.
//! 2. [Curves](crate::guide::curves): knot vectors, B-spline and NURBS curves, the classic
//!    structural algorithms (insertion, removal, elevation, splitting) and constructions
//!    (circles, conics, surfaces of revolution, spheres, tori).
//! 3. [Fitting](crate::guide::fitting): interpolation and least squares with
//!    parametrisations and parameter correction, then the selective eraser of curvature
//!    extrema on an airfoil, as `spline smooth` runs it.
//! 4. [Jacobians](crate::guide::jacobians): every structural operation as a sparse matrix,
//!    products and curvature numerators with their Jacobians, for gradient-based
//!    optimisation.
//! 5. [Surfaces](crate::guide::surfaces): tensor-product surfaces, closest points,
//!    intersections, curvature features, and approximation under shape constraints.
//! 6. [CAD exchange](crate::guide::cad_exchange): STEP and IGES files, and the JSON exchange
//!    format.
//!
//! Every example uses the facade only (`spline::…`); each layer is also a crate of its own
//! (`spline-core`, `spline-geom`, `spline-fit`, `spline-algebra`, `spline-shape`,
//! `spline-io`) for projects that want fewer dependencies. Pictures of most objects in the
//! guide are drawn into `docs/` by `cargo xtask docs`; the chapters name the files.

#[doc = include_str!("from_scipy.md")]
pub mod from_scipy {}

#[doc = include_str!("curves.md")]
pub mod curves {}

#[doc = include_str!("fitting.md")]
pub mod fitting {}

#[doc = include_str!("jacobians.md")]
pub mod jacobians {}

#[doc = include_str!("surfaces.md")]
pub mod surfaces {}

#[doc = include_str!("cad_exchange.md")]
pub mod cad_exchange {}
