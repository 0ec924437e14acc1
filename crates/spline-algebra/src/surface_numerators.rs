//! The numerators of the Gaussian and mean curvature of a surface (polynomial or rational)
//! as bivariate splines in per-patch Bernstein form, built with the tensor-product algebra.

use crate::features::Normalisation;
use crate::maps::SplineMap;
use crate::numerator::{Tracked, cross3, dot3};
use crate::sparse::{csr_from_rows, matmul};
use crate::tensor::{TensorMap, partial};
use crate::zero_set::{ZeroSet, zero_set};
use nalgebra_sparse::CsrMatrix;
use spline_core::{KnotVector, Result, Scalar};
use spline_geom::{NurbsSurface, Surface};

/// Bivariate numerators of the curvatures of a surface `S(u, v)`, each a scalar
/// [`Surface`] in per-patch Bernstein form (knots of full multiplicity at every break of
/// the surface, so that every patch's coefficients are its Bernstein coefficients), equal
/// to the true quantity times a positive function:
///
/// - `first = [E, F, G]` and `second = [L, M, N]`: the fundamental forms, scaled: for a
///   rational surface `P = (X̄, W)`, $\hat E = N_u \cdot N_u$ with $N_u = \bar X_u W - \bar X
///   W_u = W^2 S_u$, and $\hat L = -\det(P, P_u, P_v, P_{uu}) = W^4\\, S_{uu} \cdot (S_u
///   \times S_v)$ (for polynomial surfaces $E = S_u \cdot S_u$, $L = S_{uu} \cdot (S_u
///   \times S_v)$);
/// - `gaussian` $= \hat L \hat N - \hat M^2$, whose sign is that of `K` (zero set: the
///   parabolic lines);
/// - `mean` $= \hat E \hat N - 2 \hat F \hat M + \hat G \hat L$, whose sign is that of the
///   mean curvature `H` for the normal $S_u \times S_v$.
///
/// The coordinates are first translated and scaled exactly by powers of two (the signs do
/// not change), and coefficients that are rounding left by cancellation are set to zero:
/// a torus's `gaussian` vanishes exactly on the patch edges along its top and bottom
/// circles.
#[derive(Clone, Debug)]
pub struct CurvatureNumerators<T> {
    /// `[E, F, G]`, scaled.
    pub first: [Surface<T, T>; 3],
    /// `[L, M, N]`, scaled.
    pub second: [Surface<T, T>; 3],
    /// The numerator of the Gaussian curvature.
    pub gaussian: Surface<T, T>,
    /// The numerator of the mean curvature.
    pub mean: Surface<T, T>,
    /// $\hat E \hat G - \hat F^2$, a positive multiple of $|S_u \times S_v|^2$: zero where
    /// the parametrisation is singular (the poles of a sphere).
    pub area: Surface<T, T>,
    /// $[\hat E \hat M - \hat F \hat L,\ \hat E \hat N - \hat G \hat L]$: both vanish
    /// where the second fundamental form is proportional to the first (where `E ≠ 0`): the
    /// umbilics are their common zeros.
    pub umbilic: [Surface<T, T>; 2],
}

type Bivariate<T> = Tracked<T, Surface<T, T>>;

/// The [`CurvatureNumerators`] of a surface with 3-D points, polynomial or rational
/// ([`NurbsSurface::from_surface`] for polynomial ones: equal weights use the lower-degree
/// polynomial formulas).
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::NurbsSurface;
/// use spline_geom::SpatialSurface;
/// // A torus about z with radii 2 and 1: the sign of the numerator is the sign of K.
/// let torus = NurbsSurface::torus(Vector3::zeros(), Vector3::z(), 2.0, 1.0)?;
/// let n = spline_algebra::curvature_numerators(&torus)?;
/// for (u, v) in [(0.1f64, 0.1f64), (0.1, 0.4), (0.6, 0.7), (0.9, 0.95)] {
///     let k: f64 = torus.local_properties(u, v)?.gaussian_curvature;
///     assert_eq!(n.gaussian.eval(u, v)?.signum(), k.signum());
/// }
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`spline_core::ErrorKind::DegreeTooHigh`] if a numerator's degree exceeds
/// [`spline_core::MAX_DEGREE`] in a direction (rational bi-quartics and above);
/// [`spline_core::ErrorKind::InvalidArgument`] below degree 2 in a direction is fine (the
/// second derivatives vanish), never for valid surfaces otherwise.
pub fn curvature_numerators<T: Scalar>(
    surface: &NurbsSurface<T, 3>,
) -> Result<CurvatureNumerators<T>> {
    Ok(numerators(surface, false)?.0)
}

/// The Jacobians of [`CurvatureNumerators`] with respect to the homogeneous control points
/// $[w_i x_i, w_i y_i, w_i z_i, w_i]$ (interleaved, row-major over the net): rows are the
/// numerators' coefficients. A polynomial surface (equal weights) has the polynomial
/// numerators, and its weight columns are zero: the Jacobian is with respect to the
/// Cartesian control points.
#[derive(Clone, Debug)]
pub struct NumeratorJacobians<T> {
    /// Of `[E, F, G]`.
    pub first: [CsrMatrix<T>; 3],
    /// Of `[L, M, N]`.
    pub second: [CsrMatrix<T>; 3],
    /// Of the numerator of the Gaussian curvature.
    pub gaussian: CsrMatrix<T>,
    /// Of the numerator of the mean curvature.
    pub mean: CsrMatrix<T>,
}

/// [`curvature_numerators`] of the surface as given (no translation or scaling first, so
/// that the numerators are functions of the control points alone) with their Jacobians
/// carried along by the product rule through the tensor-product algebra
/// ([`NumeratorJacobians`]): the derivatives that constraints on the curvature of a
/// parametric patch (such as `K ≥ 0` on its Bernstein coefficients) need.
///
/// # Errors
/// As [`curvature_numerators`].
pub fn curvature_numerators_with_jacobians<T: Scalar>(
    surface: &NurbsSurface<T, 3>,
) -> Result<(CurvatureNumerators<T>, NumeratorJacobians<T>)> {
    let (values, jacobians) = numerators(surface, true)?;
    let jacobians = jacobians.ok_or_else(|| {
        spline_core::Error::new(
            spline_core::ErrorKind::InvalidArgument,
            "the Jacobians of the curvature numerators were not computed",
        )
    })?;
    Ok((values, jacobians))
}

/// The numerators, normalised (`with_jacobians = false`) or as given with their Jacobians.
fn numerators<T: Scalar>(
    surface: &NurbsSurface<T, 3>,
    with_jacobians: bool,
) -> Result<(CurvatureNumerators<T>, Option<NumeratorJacobians<T>>)> {
    let polynomial = surface.weights().iter().all(|&w| w == surface.weights()[0]);
    let frame = if with_jacobians {
        Normalisation::identity()
    } else {
        Normalisation::of(surface.control_points(), surface.weights())
    };
    let variables = 4 * surface.control_points().len();
    let h = surface.homogeneous();
    let (p, q) = surface.degrees();
    let sw = frame.scale * frame.wscale;
    let coordinate = |k: usize| -> Surface<T, T> {
        h.map_control_points(|c| {
            if k < 3 {
                (c.point[k] - c.weight * frame.middle[k]) / sw
            } else {
                c.weight / frame.wscale
            }
        })
    };
    // ∂(coordinate k of control point i)/∂(homogeneous variable 4i + j).
    let selection = |k: usize| -> CsrMatrix<T> {
        let count = surface.control_points().len();
        let rows = (0..count)
            .map(|i| {
                if k < 3 {
                    let mut row = vec![(4 * i + k, T::one() / sw)];
                    if frame.middle[k] != T::zero() {
                        row.push((4 * i + 3, -frame.middle[k] / sw));
                    }
                    row
                } else {
                    vec![(4 * i + 3, T::one() / frame.wscale)]
                }
            })
            .collect();
        csr_from_rows(variables, rows)
    };
    let breaks_u = h.knots_u().domain_breaks();
    let breaks_v = h.knots_v().domain_breaks();
    // ∂^{k+l} of a coordinate, in per-patch Bernstein form (zero above the degree).
    let derivative =
        |f: &Surface<T, T>, coordinate: usize, k: usize, l: usize| -> Result<Bivariate<T>> {
            let (k, l) = (k.min(p + 1), l.min(q + 1));
            let d = if k > p || l > q {
                // Identically zero: a constant on the Bernstein space of degree 0.
                let ku = KnotVector::bernstein(0, &breaks_u)?;
                let kv = KnotVector::bernstein(0, &breaks_v)?;
                let n = ku.num_basis() * kv.num_basis();
                Surface::new_unchecked(ku, kv, vec![T::zero(); n])
            } else {
                partial(f, k, l)?
            };
            let to_bernstein = |knots: &KnotVector<T>, breaks: &[T]| {
                SplineMap::transfer(knots, &KnotVector::bernstein(knots.degree(), breaks)?)
            };
            let map = TensorMap::new(
                to_bernstein(d.knots_u(), &breaks_u)?,
                to_bernstein(d.knots_v(), &breaks_v)?,
            );
            let value = map.apply(&d)?;
            let jacobian = if !with_jacobians {
                None
            } else if k > p || l > q {
                Some(CsrMatrix::zeros(value.control_points().len(), variables))
            } else {
                let partial_map = TensorMap::partial_derivative(f.knots_u(), f.knots_v(), k, l)?;
                Some(matmul(
                    &matmul(&map.matrix(), &partial_map.matrix()),
                    &selection(coordinate),
                ))
            };
            Ok(Tracked::leaf(value, jacobian))
        };
    let point = |k: usize, l: usize| -> Result<[Bivariate<T>; 3]> {
        Ok([
            derivative(&coordinate(0), 0, k, l)?,
            derivative(&coordinate(1), 1, k, l)?,
            derivative(&coordinate(2), 2, k, l)?,
        ])
    };
    let (x, xu, xv) = (point(0, 0)?, point(1, 0)?, point(0, 1)?);
    let (xuu, xuv, xvv) = (point(2, 0)?, point(1, 1)?, point(0, 2)?);
    let (first, second) = if polynomial {
        let m = cross3(&xu, &xv)?;
        (
            [dot3(&xu, &xu)?, dot3(&xu, &xv)?, dot3(&xv, &xv)?],
            [dot3(&xuu, &m)?, dot3(&xuv, &m)?, dot3(&xvv, &m)?],
        )
    } else {
        let w = coordinate(3);
        let (w0, wu, wv) = (
            derivative(&w, 3, 0, 0)?,
            derivative(&w, 3, 1, 0)?,
            derivative(&w, 3, 0, 1)?,
        );
        let (wuu, wuv, wvv) = (
            derivative(&w, 3, 2, 0)?,
            derivative(&w, 3, 1, 1)?,
            derivative(&w, 3, 0, 2)?,
        );
        let times = |a: &[Bivariate<T>; 3], s: &Bivariate<T>| -> Result<[Bivariate<T>; 3]> {
            Ok([a[0].times(s)?, a[1].times(s)?, a[2].times(s)?])
        };
        let combine =
            |a: [Bivariate<T>; 3], b: [Bivariate<T>; 3], sign: T| -> Result<[Bivariate<T>; 3]> {
                let [a0, a1, a2] = a;
                let [b0, b1, b2] = b;
                Ok([
                    Tracked::combination(T::one(), &a0, sign, &b0)?,
                    Tracked::combination(T::one(), &a1, sign, &b1)?,
                    Tracked::combination(T::one(), &a2, sign, &b2)?,
                ])
            };
        let one = T::one();
        // m̂ = W X̄u × X̄v + Wu X̄v × X̄ + Wv X̄ × X̄u = W³ Su × Sv; t = X̄ · (X̄u × X̄v).
        let cuv = cross3(&xu, &xv)?;
        let m = combine(
            combine(times(&cuv, &w0)?, times(&cross3(&xv, &x)?, &wu)?, one)?,
            times(&cross3(&x, &xu)?, &wv)?,
            one,
        )?;
        let t = dot3(&x, &cuv)?;
        // L̂ = X̄uu · m̂ − Wuu t, and likewise; N_u = X̄u W − X̄ Wu = W² Su.
        let form = |a: &[Bivariate<T>; 3], wa: &Bivariate<T>| dot3(a, &m)?.minus(&wa.times(&t)?);
        let nu = combine(times(&xu, &w0)?, times(&x, &wu)?, -one)?;
        let nv = combine(times(&xv, &w0)?, times(&x, &wv)?, -one)?;
        (
            [dot3(&nu, &nu)?, dot3(&nu, &nv)?, dot3(&nv, &nv)?],
            [form(&xuu, &wuu)?, form(&xuv, &wuv)?, form(&xvv, &wvv)?],
        )
    };
    let [e, f, g] = first;
    let [l, m, n] = second.map(Tracked::cleaned);
    let gaussian = l.times(&n)?.minus(&m.times(&m)?)?.cleaned();
    let two: T = T::one() + T::one();
    let mean = e
        .times(&n)?
        .minus(&f.times(&m)?.scaled(two))?
        .plus(&g.times(&l)?)?
        .cleaned();
    let area = e.times(&g)?.minus(&f.times(&f)?)?.cleaned();
    let umbilic_m = e.times(&m)?.minus(&f.times(&l)?)?.cleaned();
    let umbilic_n = e.times(&n)?.minus(&g.times(&l)?)?.cleaned();
    let jacobian = |t: &Bivariate<T>| {
        t.jacobian
            .clone()
            .unwrap_or_else(|| CsrMatrix::zeros(t.value.control_points().len(), 0))
    };
    let jacobians = with_jacobians.then(|| NumeratorJacobians {
        first: [jacobian(&e), jacobian(&f), jacobian(&g)],
        second: [jacobian(&l), jacobian(&m), jacobian(&n)],
        gaussian: jacobian(&gaussian),
        mean: jacobian(&mean),
    });
    Ok((
        CurvatureNumerators {
            area: area.value,
            umbilic: [umbilic_m.value, umbilic_n.value],
            first: [e.value, f.value, g.value],
            second: [l.value, m.value, n.value],
            gaussian: gaussian.value,
            mean: mean.value,
        },
        jacobians,
    ))
}

/// The parabolic lines (`K = 0`) of a surface: the [`crate::zero_set`] of the numerator of
/// its Gaussian curvature ([`curvature_numerators`]), as polylines in `(u, v)` with
/// `samples` points per patch width; regions where `K ≡ 0` (developable pieces) are
/// reported as regions. Where the parametrisation is singular (`S_u × S_v = 0`, as on the
/// lines of a sphere's net that map to its poles) the numerator vanishes too; those pieces
/// are not parabolic lines and are left out.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::NurbsSurface;
/// let torus = NurbsSurface::torus(Vector3::zeros(), Vector3::z(), 2.0, 1.0)?;
/// let lines = spline_algebra::parabolic_lines(&torus, 8)?;
/// assert_eq!(lines.curves.len(), 2); // the top and bottom circles
/// for (u, v) in lines.curves.iter().flatten().map(|p| (p[0], p[1])) {
///     assert!((torus.eval(u, v)?.z.abs() - 1.0).abs() < 1e-12);
/// }
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`curvature_numerators`] and [`crate::zero_set`].
pub fn parabolic_lines(surface: &NurbsSurface<f64, 3>, samples: usize) -> Result<ZeroSet> {
    parabolic_lines_from(&curvature_numerators(surface)?, samples)
}

/// [`parabolic_lines`] from the surface's curvature numerators, already computed.
pub(crate) fn parabolic_lines_from(
    numerators: &CurvatureNumerators<f64>,
    samples: usize,
) -> Result<ZeroSet> {
    let mut set = zero_set(&numerators.gaussian, samples)?;
    let regular = |p: &[f64; 2]| numerators.area.eval(p[0], p[1]).map(|a| a != 0.0);
    let mut curves = Vec::new();
    for curve in set.curves {
        let flags = curve.iter().map(regular).collect::<Result<Vec<_>>>()?;
        // Keep the segments with a regular end; split where both ends are singular.
        let mut run: Vec<([f64; 2], bool)> = Vec::new();
        let mut flush = |run: &mut Vec<([f64; 2], bool)>| {
            if run.len() >= 2 && run.iter().any(|x| x.1) {
                curves.push(run.iter().map(|x| x.0).collect());
            }
            run.clear();
        };
        for (p, f) in curve.iter().zip(flags) {
            if run.last().is_some_and(|last| !last.1 && !f) {
                flush(&mut run);
            }
            run.push((*p, f));
        }
        flush(&mut run);
    }
    set.curves = curves;
    Ok(set)
}
