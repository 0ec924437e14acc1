//! Parametrisation of data points and knot placement.

use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, check_params, from_count,
    to_f64,
};

/// How parameters are assigned to the data points `Q_0 … Q_m`.
///
/// Named choices are normalised to `[0, 1]` (seed 004 (7.5), seed 003 TD2, The NURBS Book
/// §9.2.1): with $d_j = \lVert Q_j - Q_{j-1} \rVert^e$,
/// $\bar u_0 = 0$ and $\bar u_j = \sum_{i \le j} d_i / \sum_i d_i$, where `e = 0` for
/// [`Parametrization::Uniform`] (équidistante), `e = 1` for [`Parametrization::Chordal`] and
/// `e = ½` for [`Parametrization::Centripetal`].
#[derive(Clone, Debug, PartialEq)]
pub enum Parametrization<T> {
    /// Equally spaced parameters $\bar u_j = j/m$.
    Uniform,
    /// Chord-length parameters (seed 004 (7.5)): spacing proportional to the distances.
    Chordal,
    /// Centripetal parameters (Lee 1989): spacing proportional to the square roots of the
    /// distances.
    Centripetal,
    /// Parameters given by the caller: finite and non-decreasing (strictly increasing for
    /// interpolation), one per point.
    Given(Vec<T>),
}

impl<T> Default for Parametrization<T> {
    /// Chord length, the default of the exchange-format contract.
    fn default() -> Self {
        Self::Chordal
    }
}

impl<T> Parametrization<T> {
    /// The names of the named choices, as every front end spells them (the tool's
    /// `--parametrization`, the studio's field, the Python keyword).
    pub const NAMES: [&'static str; 3] = ["uniform", "chordal", "centripetal"];

    /// The named choice `name` (one of [`Self::NAMES`]; `"chord"` is read as `"chordal"`).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] naming the choices for any other text.
    ///
    /// # Examples
    /// ```
    /// use spline_fit::Parametrization;
    /// assert_eq!(Parametrization::<f64>::from_name("centripetal")?, Parametrization::Centripetal);
    /// assert!(Parametrization::<f64>::from_name("arc").is_err());
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    pub fn from_name(name: &str) -> Result<Self> {
        match name.trim() {
            "uniform" => Ok(Self::Uniform),
            "chordal" | "chord" => Ok(Self::Chordal),
            "centripetal" => Ok(Self::Centripetal),
            other => Err(unknown_name("parametrization", other, &Self::NAMES)),
        }
    }

    /// The name of a named choice; `None` for [`Parametrization::Given`].
    #[must_use]
    pub const fn name(&self) -> Option<&'static str> {
        match self {
            Self::Uniform => Some("uniform"),
            Self::Chordal => Some("chordal"),
            Self::Centripetal => Some("centripetal"),
            Self::Given(_) => None,
        }
    }
}

/// The error for a name that is none of `names`: the text (at most 40 characters) and the
/// choices.
pub(crate) fn unknown_name(what: &str, text: &str, names: &[&str]) -> Error {
    Error::new(
        ErrorKind::InvalidArgument,
        format!(
            "unknown {what} {:?} (one of {})",
            text.chars().take(40).collect::<String>(),
            names.join(", ")
        ),
    )
}

/// How the knot vector of a fit is chosen.
#[derive(Clone, Debug, PartialEq)]
pub enum KnotChoice<T> {
    /// Averaging of the parameters (seed 004 (7.6), (7.8); The NURBS Book (9.8)): clamped on
    /// $[\bar u_0, \bar u_m]$ with $u_{j+p} = \frac1p \sum_{i=j}^{j+p-1} \bar u_i$. For
    /// least squares with fewer control points than data, the same as
    /// [`KnotChoice::NurbsBook`].
    Averaging,
    /// Clamped, uniformly spaced knots on $[\bar u_0, \bar u_m]$.
    Uniform,
    /// The data-driven placement of The NURBS Book (9.68)–(9.69), made for least squares so
    /// that every knot span holds data: see [`nurbs_book_knots`].
    NurbsBook,
    /// A knot vector given by the caller.
    Given(KnotVector<T>),
}

impl<T> Default for KnotChoice<T> {
    /// Averaging, the default of the exchange-format contract.
    fn default() -> Self {
        Self::Averaging
    }
}

impl<T> KnotChoice<T> {
    /// The names of the placements chosen by rule, as every front end spells them.
    pub const NAMES: [&'static str; 3] = ["averaging", "uniform", "nurbs-book"];

    /// The placement named `name` (one of [`Self::NAMES`]).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] naming the choices for any other text.
    pub fn from_name(name: &str) -> Result<Self> {
        match name.trim() {
            "averaging" => Ok(Self::Averaging),
            "uniform" => Ok(Self::Uniform),
            "nurbs-book" => Ok(Self::NurbsBook),
            other => Err(unknown_name("knot placement", other, &Self::NAMES)),
        }
    }
}

/// Checks that the data points are finite and that there are at least `needed`.
pub(crate) fn check_points<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    needed: usize,
    what: &str,
) -> Result<()> {
    if let Some(i) = points.iter().position(|p| !p.all_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("data point {i} is not finite"),
        ));
    }
    if points.len() < needed {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!(
                "{what} needs at least {needed} points, got {}",
                points.len()
            ),
        ));
    }
    Ok(())
}

/// The distances between consecutive points raised to `exponent` (1 or ½), with an error
/// naming the first pair of coincident points.
fn spacings<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    closed: bool,
    centripetal: bool,
    kind: &str,
) -> Result<Vec<T>> {
    let count = points.len();
    let pairs = if closed { count } else { count - 1 };
    let mut out = Vec::with_capacity(pairs);
    // Only ratios of distances matter: they are computed on differences divided by the
    // largest coordinate of any difference, so that coordinates near 1e±300 neither overflow
    // nor underflow when squared.
    let difference = |j: usize| {
        let (a, b) = (points[j], points[(j + 1) % count]);
        // Halves first: b − a of finite points may overflow.
        b * cast::<T>(0.5) - a * cast::<T>(0.5)
    };
    let largest = (0..pairs).fold(T::zero(), |m, j| m.max(difference(j).max_abs()));
    // A power of four: the scaling is exact and commutes with the square roots.
    let largest: T = cast(spline_core::power_of_two_scale(to_f64(largest)));
    for j in 0..pairs {
        let diff = difference(j);
        // Each length on its own scale first, so that a distance 1e-300 times the largest
        // is neither squared to zero nor taken for a coincidence.
        let own = diff.max_abs();
        let d = if own > T::zero() {
            (own / largest) * P::from_coords(|i| diff.coord(i) / own).length()
        } else {
            T::zero()
        };
        if !(d > T::zero()) {
            let next = (j + 1) % count;
            return Err(Error::new(
                ErrorKind::DegenerateGeometry,
                format!(
                    "points {j} and {next} coincide: {kind} parameters need distinct consecutive points"
                ),
            ));
        }
        out.push(if centripetal { d.sqrt() } else { d });
    }
    Ok(out)
}

fn cumulative<T: Scalar>(steps: &[T]) -> Vec<T> {
    let mut out = Vec::with_capacity(steps.len() + 1);
    let mut sum = T::zero();
    out.push(sum);
    for &s in steps {
        sum += s;
        out.push(sum);
    }
    let total = sum;
    for v in &mut out {
        *v /= total;
    }
    // Exact ends despite rounding.
    if let Some(last) = out.last_mut() {
        *last = T::one();
    }
    out
}

/// Parameters for the points of an open curve (seed 004 (7.5)): `m + 1` values, normalised to
/// `[0, 1]` for named choices, checked (finite, non-decreasing, one per point) when given.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_fit::{Parametrization, parametrize};
/// let points = [Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.0), Vector2::new(1.0, 3.0)];
/// let u: Vec<f64> = parametrize(&points, &Parametrization::Chordal)?;
/// assert_eq!(u, vec![0.0, 0.25, 1.0]);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] with fewer than two points (one point is accepted for
/// [`Parametrization::Given`]); [`ErrorKind::NonFinite`] for NaN coordinates or parameters;
/// [`ErrorKind::DegenerateGeometry`] when two consecutive points coincide under chordal or
/// centripetal parameters; [`ErrorKind::InvalidLength`] when the number of given parameters
/// differs from the number of points; [`ErrorKind::UnsortedKnots`] when given parameters
/// decrease.
pub fn parametrize<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    parametrization: &Parametrization<T>,
) -> Result<Vec<T>> {
    match parametrization {
        Parametrization::Given(params) => {
            check_points(points, 1, "a parametrisation")?;
            check_given(params, points.len())?;
            Ok(params.clone())
        }
        Parametrization::Uniform => {
            check_points(points, 2, "a parametrisation")?;
            let m = points.len() - 1;
            Ok(uniform_params(m))
        }
        Parametrization::Chordal => {
            check_points(points, 2, "a parametrisation")?;
            Ok(cumulative(&spacings(points, false, false, "chordal")?))
        }
        Parametrization::Centripetal => {
            check_points(points, 2, "a parametrisation")?;
            Ok(cumulative(&spacings(points, false, true, "centripetal")?))
        }
    }
}

fn uniform_params<T: Scalar>(m: usize) -> Vec<T> {
    (0..=m)
        .map(|j| {
            if j == m {
                T::one()
            } else {
                from_count::<T>(j) / from_count::<T>(m)
            }
        })
        .collect()
}

/// Parameters for the points `Q_0 … Q_{N−1}` of a closed curve: `N + 1` values, the last one
/// for the return to `Q_0` (the closing chord counts in chordal and centripetal parameters).
/// Named choices are normalised to `[0, 1]`; given parameters must be `N + 1` strictly
/// increasing values.
///
/// # Errors
/// As [`parametrize`]; a closed curve needs at least two distinct points.
pub fn parametrize_closed<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    parametrization: &Parametrization<T>,
) -> Result<Vec<T>> {
    check_points(points, 2, "a closed curve")?;
    match parametrization {
        Parametrization::Given(params) => {
            check_given(params, points.len() + 1)?;
            check_strict(params)?;
            Ok(params.clone())
        }
        Parametrization::Uniform => Ok(uniform_params(points.len())),
        Parametrization::Chordal => Ok(cumulative(&spacings(points, true, false, "chordal")?)),
        Parametrization::Centripetal => {
            Ok(cumulative(&spacings(points, true, true, "centripetal")?))
        }
    }
}

/// Checks the weights of `m` data: one per datum, each positive and finite.
pub(crate) fn check_weights<T: Scalar>(weights: &[T], m: usize) -> Result<()> {
    if weights.len() != m {
        return Err(Error::invalid_length(
            "one weight per datum",
            m,
            weights.len(),
        ));
    }
    if let Some(k) = weights
        .iter()
        .position(|&v| !(v > T::zero() && v.is_finite()))
    {
        return Err(Error::new(
            ErrorKind::InvalidWeight,
            format!(
                "weight {k} is {}: weights must be positive and finite",
                to_f64(weights[k])
            ),
        )
        .with_index(k));
    }
    Ok(())
}

/// [`ErrorKind::InvalidArgument`] unless `value` (a smoothing weight, a residual target) is
/// finite and non-negative: `{what} must be finite and non-negative, got {value}`.
pub(crate) fn check_non_negative<T: Scalar>(value: T, what: &str) -> Result<()> {
    if value >= T::zero() && value.is_finite() {
        return Ok(());
    }
    Err(Error::new(
        ErrorKind::InvalidArgument,
        format!(
            "{what} must be finite and non-negative, got {}",
            to_f64(value)
        ),
    )
    .with_value(to_f64(value))
    .with_interval(0.0, f64::INFINITY))
}

/// Checks given parameters: the right number, finite, non-decreasing.
pub(crate) fn check_given<T: Scalar>(params: &[T], expected: usize) -> Result<()> {
    if params.len() != expected {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("{} parameters given for {expected} points", params.len()),
        ));
    }
    check_params(params)
}

/// Checks that parameters increase strictly (interpolation: two conditions at one parameter
/// would contradict each other or repeat).
pub(crate) fn check_strict<T: Scalar>(params: &[T]) -> Result<()> {
    check_params(params)?;
    if let Some(j) = (1..params.len()).find(|&j| !(params[j] > params[j - 1])) {
        return Err(Error::new(
            ErrorKind::UnsortedKnots,
            format!(
                "interpolation parameters must increase strictly: parameters {} and {j} are both {}",
                j - 1,
                to_f64(params[j])
            ),
        ));
    }
    Ok(())
}

/// The knots of The NURBS Book (9.68)–(9.69) for a least-squares fit with `num_control`
/// control points of degree `p` to `m + 1` data with parameters $\bar u_0 \le … \le \bar u_m$:
/// clamped on $[\bar u_0, \bar u_m]$ with, for `d = (m + 1)/(n − p + 1)` (`n + 1` control
/// points), `j = ⌊i d⌋`, `α = i d − j`,
///
/// $$ u_{p+i} = (1 - \alpha)\\, \bar u_{j-1} + \alpha\\, \bar u_j, \qquad i = 1, …, n - p. $$
///
/// Every knot span then contains at least one parameter, so the Schoenberg–Whitney
/// conditions hold when the parameters are distinct.
///
/// ```
/// let u: Vec<f64> = (0..=10).map(|j| j as f64 / 10.0).collect();
/// let k = spline_fit::nurbs_book_knots(2, 4, &u)?;
/// assert_eq!(k.num_basis(), 4);
/// assert_eq!(k.knots().len(), 7);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] unless `p + 1 ≤ num_control ≤ m + 1`;
/// [`ErrorKind::DegreeTooHigh`]; [`ErrorKind::NonFinite`] or [`ErrorKind::UnsortedKnots`]
/// for bad parameters; [`ErrorKind::EmptyDomain`] when all parameters are equal.
pub fn nurbs_book_knots<T: Scalar>(
    degree: usize,
    num_control: usize,
    params: &[T],
) -> Result<KnotVector<T>> {
    check_params(params)?;
    check_degree(degree)?;
    check_control_count(degree, num_control, params.len())?;
    let count = params.len(); // m + 1
    let n = num_control - 1;
    let (a, b) = (params[0], params[count - 1]);
    let d = from_count::<T>(count) / from_count::<T>(n - degree + 1);
    let interior: Vec<T> = (1..=n - degree)
        .map(|i| {
            let id = from_count::<T>(i) * d;
            let j = to_f64(id).floor();
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let ji = j as usize;
            let alpha = id - cast::<T>(j);
            let ji = ji.clamp(1, count - 1);
            params[ji - 1] * (T::one() - alpha) + params[ji] * alpha
        })
        .collect();
    let mut knots = Vec::with_capacity(num_control + degree + 1);
    knots.extend(std::iter::repeat_n(a, degree + 1));
    knots.extend(interior);
    knots.extend(std::iter::repeat_n(b, degree + 1));
    KnotVector::new(degree, knots)
}

/// Checks that `num_control` control points of degree `p` can be fitted to `num_data` data:
/// `p < num_control ≤ num_data`.
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] otherwise.
pub(crate) fn check_control_count(
    degree: usize,
    num_control: usize,
    num_data: usize,
) -> Result<()> {
    if num_control <= degree {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!(
                "a degree-{degree} curve needs at least {} control points, got {num_control}",
                degree + 1
            ),
        ));
    }
    if num_data < num_control {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!(
                "{num_control} control points need at least {num_control} data points, got {num_data}"
            ),
        ));
    }
    Ok(())
}

/// The knot vector that `choice` describes for `num_control` control points and the data
/// parameters `params` (least squares when `num_control` is below the number of data).
pub(crate) fn knots_for<T: Scalar>(
    choice: &KnotChoice<T>,
    degree: usize,
    num_control: usize,
    params: &[T],
) -> Result<KnotVector<T>> {
    let (a, b) = match (params.first(), params.last()) {
        (Some(&a), Some(&b)) => (a, b),
        _ => return Err(Error::new(ErrorKind::TooFewPoints, "no data points")),
    };
    match choice {
        KnotChoice::Given(k) => Ok(k.clone()),
        KnotChoice::Uniform => KnotVector::clamped_uniform(degree, num_control, a, b),
        KnotChoice::Averaging if num_control == params.len() => {
            KnotVector::averaging(degree, params)
        }
        KnotChoice::Averaging | KnotChoice::NurbsBook => {
            nurbs_book_knots(degree, num_control, params)
        }
    }
}

/// [`ErrorKind::DegreeTooHigh`] above [`spline_core::MAX_DEGREE`].
pub(crate) fn check_degree(degree: usize) -> Result<()> {
    if degree > spline_core::MAX_DEGREE {
        return Err(Error::new(
            ErrorKind::DegreeTooHigh,
            format!(
                "degree {degree} is above the supported maximum {}",
                spline_core::MAX_DEGREE
            ),
        ));
    }
    Ok(())
}

/// Maps parameters normalised to `[u_0, u_m]` affinely onto `[a, b]`.
pub(crate) fn map_to_domain<T: Scalar>(params: &mut [T], (a, b): (T, T)) {
    let (Some(&lo), Some(&hi)) = (params.first(), params.last()) else {
        return;
    };
    if lo == a && hi == b {
        return;
    }
    let scale = (b - a) / (hi - lo);
    let last = params.len() - 1;
    for (j, u) in params.iter_mut().enumerate() {
        *u = if j == last { b } else { a + (*u - lo) * scale };
    }
}

/// Parameters for `points` on the domain `[a, b]` of a knot vector: the named choices of
/// [`parametrize`] (on `[0, 1]`) mapped affinely onto `[a, b]` (the last one exactly `b`);
/// given parameters are returned as they are.
///
/// ```
/// use spline_fit::{Parametrization, parametrize_in};
/// let points = [0.0, 1.0, 3.0];
/// assert_eq!(parametrize_in(&points, &Parametrization::Chordal, (2.0, 5.0))?, vec![2.0, 3.0, 5.0]);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// The errors of [`parametrize`].
pub fn parametrize_in<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    parametrization: &Parametrization<T>,
    domain: (T, T),
) -> Result<Vec<T>> {
    let mut params = parametrize(points, parametrization)?;
    if !matches!(parametrization, Parametrization::Given(_)) {
        map_to_domain(&mut params, domain);
    }
    Ok(params)
}
