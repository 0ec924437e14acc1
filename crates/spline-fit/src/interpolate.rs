//! Interpolation of points by B-spline curves and functions (seed 004 §7).

use crate::banded::{BandLu, Staircase};
use crate::periodic::solve_periodic_collocation;

// `check_degree` moved to `params` (no import cycle); the old path stays for its users.
#[allow(unused_imports)]
pub(crate) use crate::params::check_degree;
use crate::params::{
    KnotChoice, Parametrization, check_points, check_strict, knots_for, map_to_domain, parametrize,
    parametrize_closed,
};
use crate::report::CurveFit;
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, MAX_ORDER, Result, Scalar, SpanBasis, cast,
    from_count, to_f64,
};
use spline_geom::BSpline;

/// Options of [`interpolate`].
#[derive(Clone, Debug, PartialEq)]
pub struct InterpolationOptions<T, P> {
    /// Parameters of the points (default chordal, normalised to `[0, 1]`).
    pub parametrization: Parametrization<T>,
    /// Knot vector (default averaging, seed 004 (7.6)).
    pub knots: KnotChoice<T>,
    /// First derivative $C'(\bar u_0)$ to impose at the start (one more control point).
    pub start_derivative: Option<P>,
    /// First derivative $C'(\bar u_m)$ to impose at the end (one more control point).
    pub end_derivative: Option<P>,
}

impl<T, P> Default for InterpolationOptions<T, P> {
    fn default() -> Self {
        Self {
            parametrization: Parametrization::Chordal,
            knots: KnotChoice::Averaging,
            start_derivative: None,
            end_derivative: None,
        }
    }
}

/// Interpolates the points `Q_0 … Q_m` by a B-spline curve of degree `p` (seed 004 §7, The
/// NURBS Book §9.2.1–9.2.2): $C(\bar u_j) = Q_j$, optionally with $C'(\bar u_0) = D_0$ and
/// $C'(\bar u_m) = D_m$.
///
/// The parameters follow `options.parametrization` (named choices on `[0, 1]`), the knots
/// `options.knots`. With end derivatives, averaging knots are taken over the parameter
/// sequence with the end parameters doubled (The NURBS Book (9.22) when both are given).
/// The collocation matrix is banded; without end derivatives it is totally positive and is
/// solved without pivoting in `O(m p²)`, otherwise by banded LU with partial pivoting.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_fit::{InterpolationOptions, interpolate};
/// let points = [
///     Vector2::new(0.0, 0.0), Vector2::new(1.0, 2.0), Vector2::new(3.0, 2.5),
///     Vector2::new(4.0, 0.0), Vector2::new(6.0, 1.0),
/// ];
/// let fit = interpolate(&points, 3, &InterpolationOptions::default())?;
/// for (u, q) in fit.params.iter().zip(&points) {
///     assert!((fit.curve.eval(*u)? - q).norm() < 1e-12);
/// }
/// assert!(fit.deviation.max < 1e-12);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] with fewer than `p + 1` conditions (points plus end
/// derivatives) or fewer than two points; [`ErrorKind::NonFinite`] for NaN input;
/// [`ErrorKind::DegenerateGeometry`] for coincident consecutive points under chordal or
/// centripetal parameters; [`ErrorKind::UnsortedKnots`] for given parameters that do not
/// increase strictly; [`ErrorKind::InvalidLength`] when a given knot vector does not have one
/// basis function per condition; [`ErrorKind::SchoenbergWhitney`] when a basis function
/// vanishes at its parameter (the message names the basis function and an empty knot span);
/// [`ErrorKind::SingularSystem`] for numerically singular systems.
pub fn interpolate<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    degree: usize,
    options: &InterpolationOptions<T, P>,
) -> Result<CurveFit<T, P>> {
    check_degree(degree)?;
    check_points(points, 2, "interpolation")?;
    for (what, d) in [
        ("start", &options.start_derivative),
        ("end", &options.end_derivative),
    ] {
        if d.is_some_and(|d| !d.all_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!("the {what} derivative is not finite"),
            ));
        }
    }
    let extra = usize::from(options.start_derivative.is_some())
        + usize::from(options.end_derivative.is_some());
    let n = points.len() + extra;
    if n <= degree {
        return Err(too_few(degree, points.len(), extra));
    }
    let mut params = parametrize(points, &options.parametrization)?;
    check_strict(&params)?;
    let knots = match &options.knots {
        KnotChoice::Given(k) => {
            if !matches!(options.parametrization, Parametrization::Given(_)) {
                map_to_domain(&mut params, k.domain());
            }
            k.clone()
        }
        choice => {
            let mut augmented = Vec::with_capacity(n);
            if options.start_derivative.is_some() {
                augmented.push(params[0]);
            }
            augmented.extend_from_slice(&params);
            if options.end_derivative.is_some() {
                augmented.push(params[params.len() - 1]);
            }
            knots_for(choice, degree, n, &augmented)?
        }
    };
    if knots.degree() != degree {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the knot vector is of degree {}, the interpolant of degree {degree}",
                knots.degree()
            ),
        )
        .with_counts(degree, knots.degree()));
    }
    let curve = if extra == 0 {
        interpolate_with_knots(&knots, &params, points)?
    } else {
        let mut conditions = Vec::with_capacity(n);
        let mut targets = Vec::with_capacity(n);
        let last = params.len() - 1;
        for (j, (&u, &q)) in params.iter().zip(points).enumerate() {
            // At the end the derivative comes before the value: the matrix stays banded.
            if j == last {
                if let Some(d) = options.end_derivative {
                    conditions.push(Condition { param: u, order: 1 });
                    targets.push(d);
                }
            }
            conditions.push(Condition { param: u, order: 0 });
            targets.push(q);
            if j == 0 {
                if let Some(d) = options.start_derivative {
                    conditions.push(Condition { param: u, order: 1 });
                    targets.push(d);
                }
            }
        }
        hermite(&knots, &conditions, targets)?
    };
    CurveFit::new(curve, params, points)
}

fn too_few(degree: usize, points: usize, extra: usize) -> Error {
    Error::new(
        ErrorKind::TooFewPoints,
        format!(
            "a degree-{degree} interpolant needs at least {} conditions, got {points} points{}",
            degree + 1,
            if extra > 0 {
                format!(" and {extra} end derivative(s)")
            } else {
                String::new()
            }
        ),
    )
}

/// Interpolation on a given knot vector: the control points with $C(\bar u_j) = Q_j$ for
/// the `n` parameters of the `n` points (seed 004 (7.1)–(7.3)). Proposition 7.1 of seed 004
/// (Schoenberg–Whitney) is checked: $N_i(\bar u_i) \ne 0$ for every `i`. The system is
/// solved by banded elimination without pivoting (totally positive matrix), `O(n p²)`.
///
/// ```
/// use spline_core::KnotVector;
/// use spline_fit::interpolate_with_knots;
/// let u = [0.0, 0.25, 0.5, 0.75, 1.0];
/// let knots = KnotVector::averaging(3, &u)?;
/// let y: Vec<f64> = u.iter().map(|x| x * x * x).collect();
/// let f = interpolate_with_knots(&knots, &u, &y)?;
/// assert!((f.eval(0.6)? - 0.216).abs() < 1e-12); // cubics are reproduced
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidLength`] unless there are as many parameters and points as basis
/// functions; [`ErrorKind::NonFinite`]; [`ErrorKind::UnsortedKnots`] for parameters that do
/// not increase strictly; [`ErrorKind::OutOfDomain`]; [`ErrorKind::SchoenbergWhitney`];
/// [`ErrorKind::SingularSystem`].
pub fn interpolate_with_knots<T: Scalar, P: ControlPoint<T>>(
    knots: &KnotVector<T>,
    params: &[T],
    points: &[P],
) -> Result<BSpline<T, P>> {
    let n = knots.num_basis();
    if params.len() != n || points.len() != n {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "the knot vector defines {n} basis functions: interpolation needs {n} parameters and {n} points, got {} and {}",
                params.len(),
                points.len()
            ),
        ));
    }
    // Finite, strictly increasing parameters inside the domain, finite points: checked in
    // the loop below, reported by the usual checks.
    let (a, b) = knots.domain();
    let bad = |j: usize| -> Error {
        if let Err(e) = check_points(points, 1, "interpolation").and_then(|()| check_strict(params))
        {
            return e;
        }
        match knots.check_param(params[j]) {
            Err(e) => e.context(format_args!("parameter {j}")),
            Ok(()) => Error::new(
                ErrorKind::NonFinite,
                format!("data point {j} is not finite"),
            ),
        }
    };
    let p = knots.degree();
    let fast = match p {
        0 => collocation_kernel::<T, P, 1>(knots, params, points),
        1 => collocation_kernel::<T, P, 2>(knots, params, points),
        2 => collocation_kernel::<T, P, 3>(knots, params, points),
        3 => collocation_kernel::<T, P, 4>(knots, params, points),
        4 => collocation_kernel::<T, P, 5>(knots, params, points),
        5 => collocation_kernel::<T, P, 6>(knots, params, points),
        _ => None,
    };
    if let Some(result) = fast {
        return match result {
            Ok(control) => Ok(BSpline::new_unchecked(knots.clone(), control)),
            Err(KernelError::Invalid(i)) => Err(bad(i)),
            Err(KernelError::Schoenberg(i)) => {
                Err(schoenberg_whitney_interpolation(knots, params, i))
            }
            Err(KernelError::Singular(i, pivot)) => Err(Error::new(
                ErrorKind::SingularSystem,
                format!(
                    "the data do not determine the interpolating spline: condition {i} nearly repeats the ones before it (the system is singular or too ill-conditioned; pivot {})",
                    spline_core::Short(pivot)
                ),
            )),
        };
    }
    let width = p + 1;
    let mut system = Staircase::with_capacity(n, width);
    let mut row = [T::zero(); MAX_ORDER];
    let mut span = p;
    let mut basis = SpanBasis::new();
    let mut previous = a;
    for (i, (&u, &q)) in params.iter().zip(points).enumerate() {
        if !(u >= a && u <= b && (u > previous || i == 0) && q.all_finite()) {
            return Err(bad(i));
        }
        previous = u;
        span = knots.span_in_domain_from(u, span);
        let f = span - p;
        basis.eval(knots, span, u, &mut row[..width]);
        if i < f || i > span || row[i - f] == T::zero() {
            return Err(schoenberg_whitney_interpolation(knots, params, i));
        }
        system.push_row(f, &row[..width], q)?;
    }
    let rhs = system.solve();
    Ok(BSpline::new_unchecked(knots.clone(), rhs))
}

enum KernelError {
    /// Parameter or point `i` is invalid (not finite, unsorted, outside the domain).
    Invalid(usize),
    /// $N_i(\bar u_i) = 0$.
    Schoenberg(usize),
    /// A negligible pivot at row `i`.
    Singular(usize, f64),
}

/// The collocation solve of [`interpolate_with_knots`] for degree `W − 1` known at compile
/// time (loops unrolled, rows in fixed-size arrays): validation, Cox–de Boor basis
/// functions, elimination without pivoting against the previous rows as each row is built
/// (unit pivots), back substitution. `None` never happens; the `Option` lets the caller
/// fall back for other degrees.
#[allow(clippy::unnecessary_wraps)]
fn collocation_kernel<T: Scalar, P: ControlPoint<T>, const W: usize>(
    knots: &KnotVector<T>,
    params: &[T],
    points: &[P],
) -> Option<std::result::Result<Vec<P>, KernelError>> {
    Some(collocation_kernel_inner::<T, P, W>(knots, params, points))
}

fn collocation_kernel_inner<T: Scalar, P: ControlPoint<T>, const W: usize>(
    knots: &KnotVector<T>,
    params: &[T],
    points: &[P],
) -> std::result::Result<Vec<P>, KernelError> {
    let p = W - 1;
    let n = params.len();
    let (a, b) = knots.domain();
    let tiny = T::default_epsilon() * from_count::<T>(4 * W);
    let mut first: Vec<u32> = Vec::with_capacity(n);
    let mut upper: Vec<[T; W]> = Vec::with_capacity(n);
    let mut rhs: Vec<P> = Vec::with_capacity(n);
    let mut span = p;
    let mut previous = a;
    for (i, (&u, &q)) in params.iter().zip(points).enumerate() {
        if !(u >= a && u <= b && (u > previous || i == 0) && q.all_finite()) {
            return Err(KernelError::Invalid(i));
        }
        previous = u;
        span = knots.span_in_domain_from(u, span);
        let mut row = knots.basis_values_fixed::<W>(span, u);
        let f = span - p;
        if i < f || i > span || row[i - f] == T::zero() {
            return Err(KernelError::Schoenberg(i));
        }
        let scale = row.iter().fold(T::zero(), |m, v| m.max(v.abs()));
        let mut acc = q;
        for kk in f..i {
            let l = row[kk - f];
            if l == T::zero() {
                continue;
            }
            let fk = first[kk] as usize;
            let urow = &upper[kk];
            for c in kk + 1..fk + W {
                row[c - f] -= l * urow[c - fk];
            }
            acc -= rhs[kk] * l;
        }
        let pivot = row[i - f];
        if !(pivot.abs() > tiny * scale) || !pivot.is_finite() {
            return Err(KernelError::Singular(i, spline_core::to_f64(pivot)));
        }
        let inverse = T::one() / pivot;
        for v in &mut row[i + 1 - f..] {
            *v *= inverse;
        }
        #[allow(clippy::cast_possible_truncation)]
        first.push(f as u32);
        upper.push(row);
        rhs.push(acc * inverse);
    }
    if u32::try_from(n).is_err() {
        return Err(KernelError::Singular(n, f64::NAN));
    }
    for i in (0..n).rev() {
        let fi = first[i] as usize;
        let end = (fi + W).min(n);
        let row = &upper[i];
        let mut acc = rhs[i];
        for j in i + 1..end {
            acc -= rhs[j] * row[j - fi];
        }
        rhs[i] = acc;
    }
    Ok(rhs)
}

/// The error for $N_i(\bar u_i) = 0$, naming a knot span without data when there is one.
pub(crate) fn schoenberg_whitney_interpolation<T: Scalar>(
    knots: &KnotVector<T>,
    params: &[T],
    i: usize,
) -> Error {
    let k = knots.knots();
    let p = knots.degree();
    let mut message = format!(
        "the knots do not suit the data (Schoenberg–Whitney conditions fail): data parameter {i} ({}) lies outside the support [{}, {}] of basis function N_{i}",
        to_f64(params[i]),
        to_f64(k[i]),
        to_f64(k[i + p + 1])
    );
    if let Some((a, b)) = empty_span(knots, params) {
        message.push_str(&format!(
            "; knot span [{}, {}] holds no data parameter",
            to_f64(a),
            to_f64(b)
        ));
    }
    Error::new(ErrorKind::SchoenbergWhitney, message)
}

/// The first non-empty knot span of the domain that contains no parameter (the last span
/// is closed on the right).
pub(crate) fn empty_span<T: Scalar>(knots: &KnotVector<T>, params: &[T]) -> Option<(T, T)> {
    let k = knots.knots();
    let p = knots.degree();
    let n = knots.num_basis();
    let (_, end) = knots.domain();
    (p..n).filter(|&s| k[s] < k[s + 1]).find_map(|s| {
        let (a, b) = (k[s], k[s + 1]);
        let inside = params
            .iter()
            .any(|&u| u >= a && (u < b || (b == end && u <= b)));
        (!inside).then_some((a, b))
    })
}

/// One interpolation condition: the derivative of order `order` at `param`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Condition<T> {
    pub(crate) param: T,
    pub(crate) order: usize,
}

/// Solves the Hermite–Birkhoff conditions `C^{(order)}(param) = target` (as many as basis
/// functions, sorted by parameter) by banded LU with partial pivoting.
pub(crate) fn hermite<T: Scalar, P: ControlPoint<T>>(
    knots: &KnotVector<T>,
    conditions: &[Condition<T>],
    targets: Vec<P>,
) -> Result<BSpline<T, P>> {
    let n = knots.num_basis();
    debug_assert_eq!(conditions.len(), n);
    debug_assert_eq!(targets.len(), n);
    let p = knots.degree();
    let width = p + 1;
    let mut rows: Vec<(usize, Vec<T>)> = Vec::with_capacity(n);
    let (mut kl, mut ku) = (0usize, 0usize);
    let mut table = vec![T::zero(); (MAX_ORDER + 1) * width];
    for (r, c) in conditions.iter().enumerate() {
        knots
            .check_param(c.param)
            .map_err(|e| e.context(format_args!("condition {r}")))?;
        let span = knots.span_in_domain(c.param);
        let f = span - p;
        let order = c.order.min(MAX_ORDER);
        knots.basis_derivatives(span, c.param, order, &mut table[..(order + 1) * width]);
        let vals = table[order * width..(order + 1) * width].to_vec();
        for (a, v) in vals.iter().enumerate() {
            if *v != T::zero() {
                let col = f + a;
                kl = kl.max(r.saturating_sub(col));
                ku = ku.max(col.saturating_sub(r));
            }
        }
        rows.push((f, vals));
    }
    let mut lu = BandLu::zeros(n, kl, ku, 0);
    for (r, (f, vals)) in rows.iter().enumerate() {
        for (a, &v) in vals.iter().enumerate() {
            if v != T::zero() {
                lu.add(r, f + a, v);
            }
        }
    }
    lu.factor()?;
    let mut rhs = targets;
    lu.solve(&mut rhs);
    BSpline::new(knots.clone(), rhs)
}

/// Interpolation of a function (seed 004 (7.7)–(7.8)): the B-spline function $\sigma$ of
/// degree `p` with $\sigma(x_j) = y_j$, on the knots (7.8) clamped on $[x_0, x_n]$ with
/// interior knots averaging the abscissae. `P = T` gives a scalar function; vector `y`
/// values give the curve $x \mapsto (\sigma_1(x), …)$.
///
/// ```
/// let x = [0.0, 1.0, 2.0, 3.0, 4.0];
/// let y: Vec<f64> = x.iter().map(|t: &f64| t.sin()).collect();
/// let f = spline_fit::interpolate_function(&x, &y, 3)?;
/// assert!((f.eval(2.0)? - 2f64.sin()).abs() < 1e-12);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidLength`] if `x` and `y` differ in length; [`ErrorKind::TooFewPoints`]
/// with `p + 1` points or fewer than two; [`ErrorKind::UnsortedKnots`] unless `x` increases
/// strictly; [`ErrorKind::NonFinite`].
pub fn interpolate_function<T: Scalar, P: ControlPoint<T>>(
    x: &[T],
    y: &[P],
    degree: usize,
) -> Result<BSpline<T, P>> {
    check_degree(degree)?;
    if x.len() != y.len() {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("{} abscissae for {} ordinates", x.len(), y.len()),
        ));
    }
    check_points(y, 2, "interpolation")?;
    if x.len() <= degree {
        return Err(too_few(degree, x.len(), 0));
    }
    check_strict(x)?;
    let knots = KnotVector::averaging(degree, x)?;
    interpolate_with_knots(&knots, x, y)
}

/// Interpolation of the points `Q_0 … Q_{N−1}` by a closed (periodic) curve of degree `p`:
/// $C(\bar u_j) = Q_j$ and $C$ is $C^{p-1}$ across the closing point, where it returns to
/// `Q_0` at $\bar u_N$.
///
/// The result is an unclamped B-spline with `N + p` control points whose last `p` repeat
/// the first `p` ("wrapped" control points). The breakpoints are the parameters for odd
/// degrees and the midpoints between consecutive parameters for even degrees (the choices
/// for which periodic interpolation is always uniquely solvable); the domain is
/// $[\bar u_0, \bar u_N]$ for odd degrees and the period starting at the first midpoint
/// for even ones (it contains every $\bar u_j$). The cyclic system is solved as a band
/// with a dense right border by LU with partial pivoting, `O(N p²)`.
///
/// The points must not repeat the first point at the end (drop it; the closing chord is
/// implicit). `params` in the result has `N` entries, one per point.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_fit::{Parametrization, interpolate_closed};
/// let square = [
///     Vector2::new(1.0, 0.0), Vector2::new(0.0, 1.0),
///     Vector2::new(-1.0, 0.0), Vector2::new(0.0, -1.0),
/// ];
/// let fit = interpolate_closed(&square, 3, &Parametrization::Chordal)?;
/// let (a, b) = fit.curve.domain();
/// let (start, end) = (fit.curve.derivatives(a, 2)?, fit.curve.derivatives(b, 2)?);
/// for k in 0..3 {
///     assert!((start[k] - end[k]).norm() < 1e-12); // C² closure
/// }
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] with fewer than `max(2, p + 1)` points; the parametrisation
/// errors of [`crate::parametrize_closed`]; [`ErrorKind::SingularSystem`].
pub fn interpolate_closed<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    degree: usize,
    parametrization: &Parametrization<T>,
) -> Result<CurveFit<T, P>> {
    check_degree(degree)?;
    let count = points.len();
    check_points(points, 2.max(degree + 1), "closed interpolation")?;
    let t = parametrize_closed(points, parametrization)?;
    let p = degree;
    let period = t[count] - t[0];
    // Breakpoints τ_0 < … < τ_N = τ_0 + period.
    let tau: Vec<T> = if p % 2 == 1 {
        t.clone()
    } else {
        let half: T = cast(0.5);
        let mut v = Vec::with_capacity(count + 1);
        v.push((t[count - 1] - period + t[0]) * half);
        for j in 1..count {
            v.push((t[j - 1] + t[j]) * half);
        }
        v.push(v[0] + period);
        v
    };
    // Knots u_k = τ_{k−p} extended periodically, k = 0 … N + 2p.
    // τ_{j} for j = k − p, k = 0 … N + 2p: τ_{j ± N} = τ_j ± period.
    let knots_vec: Vec<T> = (0..count + 2 * p + 1)
        .map(|k| {
            if k < p {
                let d = p - k;
                let r = (count - d % count) % count;
                tau[r] - period * from_count::<T>((d + r) / count)
            } else {
                let j = k - p;
                tau[j % count] + period * from_count::<T>(j / count)
            }
        })
        .collect();
    let knots = KnotVector::new(p, knots_vec)?;
    let params = t[..count].to_vec();
    let control = solve_periodic_collocation(&knots, &params, points)?;
    let curve = BSpline::new(knots, control)?;
    CurveFit::new(curve, params, points)
}
