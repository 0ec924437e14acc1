//! Smoothing splines: the penalised least-squares spline with its weight chosen by
//! generalised cross-validation (scipy's `make_smoothing_spline`; on many value columns
//! [`make_smoothing_spline`], in `columns.rs`), and the spline that reaches a residual
//! target with knots placed automatically (FITPACK's `curfit`, scipy's `splrep(s=…)`,
//! `make_splrep` and `make_splprep`).

mod band_inverse;
mod brent;
mod columns;
mod fitpack_steps;
mod penalised;
mod periodic;
mod profile;
mod residual;
mod splrep;
mod splrep_options;

pub use columns::make_smoothing_spline;
pub use fitpack_steps::MAX_RESIDUAL_ITERATIONS;
pub use penalised::{SmoothingFit, SmoothingParameter, smoothing_curve, smoothing_spline};
pub use residual::{ResidualFit, smoothing_curve_to_residual, smoothing_to_residual};
pub use splrep::{
    SplrepOptions, chord_length_parameters, generate_knots, make_splprep, make_splrep,
};
