//! Umbilics on singular parameter lines: a boundary line of the parameter domain that the
//! surface collapses to one point (a pole, as on a sphere's or an ellipsoid's axis), where
//! the curvature numerators vanish identically and say nothing.

use nalgebra::Vector3;
use spline_core::Result;
use spline_geom::NurbsSurface;

/// Probes along a boundary line (the line collapses if the surface is constant there).
const PROBES: usize = 17;
/// A pole is umbilic when its principal curvatures agree to this fraction of their size.
///
/// The second fundamental form at the pole is read off the exact first and second derivatives
/// of the surface across the line (rounding about `1e-15` relative, amplified by the least
/// squares fit over directions that span the tangent plane by a factor of at most `10³` when
/// the directions are well spread): `1e-9` is far above rounding and far below any geometric
/// difference a user would mean (a spheroid whose equatorial semi-axes differ by `10⁻⁸`
/// of their size is reported as such).
pub(crate) const POLE_UMBILIC: f64 = 1e-9;

/// The points `[u, v]` (the middle of the collapsed line) of the poles of `surface` that
/// are umbilics.
///
/// At a pole `P` reached along the line `u = u₀` (likewise for the other three), with
/// `T(v) = S_u(u₀, v)` sweeping the tangent plane and `n` its normal,
/// `S(u₀ + h, v) = P + h T + ½ h² S_uu + O(h³)`: the height above the tangent plane is
/// `½ h² S_uu · n` at the tangent position `h T`, so the second fundamental form `II` of the
/// surface at `P` satisfies `II(T(v)) = S_uu(u₀, v) · n` for every `v`. `II` is fitted in an
/// orthonormal basis of the plane by least squares over the probes (it must fit to rounding,
/// else the pole is not a regular point of the surface and is skipped) and the pole is umbilic
/// when its eigenvalues agree to [`POLE_UMBILIC`] (a flat pole, `II = 0`, counts).
pub(crate) fn pole_umbilics(surface: &NurbsSurface<f64, 3>) -> Result<Vec<[f64; 2]>> {
    let ((u0, u1), (v0, v1)) = surface.domain();
    let size = surface
        .control_points()
        .iter()
        .fold(0.0f64, |m, x| m.max(x.amax()))
        .max(f64::MIN_POSITIVE);
    let mut out = Vec::new();
    // (whether u is the fixed parameter, its value, the range of the other)
    let lines = [
        (true, u0, (v0, v1)),
        (true, u1, (v0, v1)),
        (false, v0, (u0, u1)),
        (false, v1, (u0, u1)),
    ];
    for (fixed_u, value, (a, b)) in lines {
        let mut points = Vec::with_capacity(PROBES);
        let mut first = Vec::with_capacity(PROBES);
        let mut second = Vec::with_capacity(PROBES);
        for k in 0..PROBES {
            // Probes off the knots (a line's derivatives jump there only one-sidedly).
            let t = a + (b - a) * (k as f64 + 0.37) / PROBES as f64;
            let (u, v) = if fixed_u { (value, t) } else { (t, value) };
            let d = surface.derivatives(u, v, 2)?;
            points.push(d[0][0]);
            if fixed_u {
                first.push(d[1][0]);
                second.push(d[2][0]);
            } else {
                first.push(d[0][1]);
                second.push(d[0][2]);
            }
        }
        if points.iter().any(|p| (p - points[0]).amax() > 1e-12 * size) {
            continue;
        }
        if let Some(true) = umbilic_pole(&first, &second) {
            let t = 0.5 * (a + b);
            out.push(if fixed_u { [value, t] } else { [t, value] });
        }
    }
    Ok(out)
}

/// Whether the pole with first derivatives `first` (the tangent directions, across the
/// line) and second derivatives `second` is umbilic; `None` if the directions do not span a
/// plane or `II` does not fit.
fn umbilic_pole(first: &[Vector3<f64>], second: &[Vector3<f64>]) -> Option<bool> {
    // The normal from the best-conditioned pair of directions.
    let mut normal = Vector3::zeros();
    for a in first {
        for b in first {
            let c = a.cross(b);
            if c.norm() > normal.norm() {
                normal = c;
            }
        }
    }
    let scale = first.iter().fold(0.0f64, |m, t| m.max(t.norm()));
    if !(normal.norm() > 1e-6 * scale * scale) {
        return None;
    }
    let n = normal.normalize();
    let e1 = first
        .iter()
        .max_by(|x, y| x.norm().total_cmp(&y.norm()))?
        .normalize();
    let e2 = n.cross(&e1);
    // II(T) = α a² + 2β a b + γ b² with T = a e1 + b e2: least squares for (α, β, γ).
    let mut ata = nalgebra::Matrix3::<f64>::zeros();
    let mut atb = Vector3::<f64>::zeros();
    let rows: Vec<(Vector3<f64>, f64)> = first
        .iter()
        .zip(second)
        .map(|(t, s)| {
            let (a, b) = (t.dot(&e1), t.dot(&e2));
            (Vector3::new(a * a, 2.0 * a * b, b * b), s.dot(&n))
        })
        .collect();
    for (r, y) in &rows {
        ata += r * r.transpose();
        atb += r * *y;
    }
    let x = ata.lu().solve(&atb)?;
    let size = rows
        .iter()
        .fold(0.0f64, |m, (r, y)| m.max(y.abs()).max(r.amax() * x.amax()));
    let residual = rows
        .iter()
        .fold(0.0f64, |m, (r, y)| m.max((r.dot(&x) - y).abs()));
    if residual > 1e-8 * size.max(f64::MIN_POSITIVE) {
        return None;
    }
    let (alpha, beta, gamma) = (x[0], x[1], x[2]);
    let gap = ((alpha - gamma).powi(2) + 4.0 * beta * beta).sqrt();
    let magnitude = alpha.abs() + gamma.abs() + 2.0 * beta.abs();
    Some(gap <= POLE_UMBILIC * magnitude)
}
