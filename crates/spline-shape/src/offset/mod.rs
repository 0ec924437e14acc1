//! Offsets: the one home that front ends call. A curve's offset is its approximation within a
//! tolerance (`spline_fit::offset_curve`, on `spline_fit::AdaptiveApproximation`) with the
//! cusps of the offset (`spline_algebra::offset_cusps`) as `C⁰` corners, returned with the
//! cusps and the error bound in one record ([`CurveOffset`]).
//!
//! The offset lives here, not in spline-fit or spline-algebra, because it needs both: the
//! cusps come from algebra's root isolation, the curve from fit's adaptive approximation, and
//! spline-fit does not depend on spline-algebra (nor the other way round).

mod curve;
mod curve_offset;
mod options;
mod revolution;
mod surface;

pub use curve_offset::{
    CUSP_ACCURACY, CurveOffset, Cusp, OffsetShape, OffsetSource, offset_planar_curve,
    offset_space_curve,
};
pub use options::OffsetOptions;
pub use surface::{
    ExactOffset, SurfaceOffset, SurfaceOffsetShape, SurfaceOffsetSource, offset_surface,
};
