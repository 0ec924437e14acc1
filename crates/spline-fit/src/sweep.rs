//! Sweeps: a profile carried along a path by rotation-minimising frames, skinned through its
//! copies.

use crate::skin::{Skinned, skin};
use nalgebra::Vector3;
use spline_core::{Error, ErrorKind, Result, Scalar, from_count};
use spline_geom::{BSpline, ParamCurve, rotation_minimizing_frames};

/// The largest number of sections of a sweep.
pub const MAX_SWEEP_SECTIONS: usize = 10_000;

/// The sweep of `profile` along `path` (any kind of space curve, [`ParamCurve`]): the
/// profile, placed where it is in space, is attached to the rotation-minimising frame of the
/// path at its start ([`rotation_minimizing_frames`], with the initial normal
/// `normal` or a default) and carried by the frames to `sections` stations equally spaced in
/// parameter along the path (the start and the end included); the surface is skinned
/// ([`skin`], degree `min(3, sections − 1)` across) through the carried copies, so it
/// contains each copy exactly: $S(u, v_k) = x_k + R_k R_0^{\mathsf T} (C(u) - x_0)$ with the
/// frame rotations $R_k$ and path points $x_k$. Between stations it follows the frames as
/// closely as the skinning interpolant follows them (more sections, closer).
///
/// ```
/// use nalgebra::Vector3;
/// use spline_fit::sweep;
/// use spline_geom::BSpline;
/// // A segment swept along a straight path: a flat strip.
/// let profile = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
///     vec![Vector3::new(0.0, -1.0, 0.0), Vector3::new(0.0, 1.0, 0.0)])?;
/// let path = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
///     vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.0, 0.0, 5.0)])?;
/// let s = sweep(&profile, &path, 4, None)?;
/// assert!((s.surface.eval(1.0, 1.0)? - Vector3::new(0.0, 1.0, 5.0)).norm() < 1e-12);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] for fewer than two sections; [`ErrorKind::InvalidArgument`]
/// above [`MAX_SWEEP_SECTIONS`]; the errors of [`rotation_minimizing_frames`] (a path with
/// zero velocity) and of [`skin`].
pub fn sweep<T: Scalar, C: ParamCurve<T, Point = Vector3<T>>>(
    profile: &BSpline<T, Vector3<T>>,
    path: &C,
    sections: usize,
    normal: Option<Vector3<T>>,
) -> Result<Skinned<T, Vector3<T>>> {
    if sections < 2 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!("a sweep needs at least two sections, got {sections}"),
        ));
    }
    if sections > MAX_SWEEP_SECTIONS {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("{sections} sections: at most {MAX_SWEEP_SECTIONS}"),
        )
        .with_counts(MAX_SWEEP_SECTIONS, sections));
    }
    let (a, b) = path.domain();
    let params: Vec<T> = (0..sections)
        .map(|k| {
            if k + 1 == sections {
                b
            } else {
                a + (b - a) * from_count::<T>(k) / from_count::<T>(sections - 1)
            }
        })
        .collect();
    let frames = rotation_minimizing_frames(path, &params, normal)?;
    let start = frames[0];
    let copies: Vec<BSpline<T, Vector3<T>>> = frames
        .iter()
        .map(|f| {
            let rotation = f.rotation() * start.rotation().transpose();
            profile.map_control_points(|p| f.origin + rotation * (p - start.origin))
        })
        .collect();
    let mut skinned = skin(&copies, 3, Some(&params))?;
    skinned.params = params;
    Ok(skinned)
}
