//! scipy's `make_smoothing_spline` on many value columns: [`super::smoothing_spline`] for
//! each column (scipy chooses λ per column), the results on their common knots as one
//! [`ColumnSpline`], like the crate's other column-wise fits (`make_interp_spline`,
//! `make_lsq_spline`), with scipy's checks and words.

use super::{SmoothingParameter, smoothing_spline};
use spline_core::{Error, ErrorKind, Result};
use spline_geom::ColumnSpline;

/// The cubic smoothing spline of every column of `y` (row-major, `len(x) × columns`):
/// scipy's `make_smoothing_spline(x, y, w, lam)`. Each column `j` is
/// [`smoothing_spline`]`(x, y[:, j], w, parameter)`: it minimises
/// $\sum_i w_i (y_{ij} - f_j(x_i))^2 + \lambda_j \int f_j''(u)^2 du$ with $\lambda_j$ given
/// ([`SmoothingParameter::Lambda`], the same for every column) or chosen for that column by
/// generalised cross-validation ([`SmoothingParameter::Gcv`], as scipy does for 2-D `y`).
/// The columns share the knots $x_0$ (×4), $x_1, …, x_{n-2}$, $x_{n-1}$ (×4); their
/// coefficients are those of the scalar fits, bit for bit.
///
/// ```
/// use spline_fit::{SmoothingParameter, make_smoothing_spline, smoothing_spline};
/// // Two columns of noisy data on 30 abscissae.
/// let x: Vec<f64> = (0..30).map(|i| f64::from(i) / 29.0).collect();
/// let noise = |i: usize| if i % 2 == 0 { 0.03 } else { -0.03 };
/// let y: Vec<f64> = x.iter().enumerate()
///     .flat_map(|(i, &t)| [(5.0 * t).sin() + noise(i), t * t - noise(i)])
///     .collect();
/// let s = make_smoothing_spline(&x, &y, 2, None, SmoothingParameter::Gcv)?;
/// assert_eq!((s.rows(), s.columns(), s.degree()), (32, 2, 3));
/// // Column 1 is the scalar fit of the second column, with its own λ.
/// let second: Vec<f64> = y.iter().skip(1).step_by(2).copied().collect();
/// let fit = smoothing_spline(&x, &second, None, SmoothingParameter::Gcv)?;
/// let column: Vec<f64> = s.coefficients().iter().skip(1).step_by(2).copied().collect();
/// assert_eq!(column, fit.spline.control_points());
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// With scipy's words: "``x`` should be an ascending array" ([`ErrorKind::UnsortedKnots`]),
/// "``x`` should be 1D and x.shape … == y.shape …" ([`ErrorKind::InvalidLength`], `y` not
/// `len(x)` rows of `columns ≥ 1` values), "Invalid vector of weights"
/// ([`ErrorKind::InvalidWeight`], a weight `≤ 0`), "``x`` and ``y`` length must be at least
/// 5" ([`ErrorKind::TooFewPoints`]), "Regularization parameter should be non-negative"
/// ([`ErrorKind::InvalidArgument`], λ < 0); then the errors of [`smoothing_spline`] for a
/// column (non-finite data, weights or λ, a weight count other than `len(x)`, a system that
/// cannot be solved), with the column named when there are several.
pub fn make_smoothing_spline(
    x: &[f64],
    y: &[f64],
    columns: usize,
    w: Option<&[f64]>,
    parameter: SmoothingParameter<f64>,
) -> Result<ColumnSpline> {
    check_scipy(x, y, columns, w, parameter)?;
    let n = x.len();
    let mut column = vec![0.0; n];
    let mut fitted: Option<(spline_core::KnotVector<f64>, Vec<f64>)> = None;
    for j in 0..columns {
        for (i, v) in column.iter_mut().enumerate() {
            *v = y[i * columns + j];
        }
        let fit = smoothing_spline(x, &column, w, parameter).map_err(|e| {
            if columns > 1 {
                e.context(format_args!("column {j}"))
            } else {
                e
            }
        })?;
        let spline = fit.spline;
        let (_, c) = fitted
            .get_or_insert_with(|| (spline.knots().clone(), vec![0.0; spline.len() * columns]));
        for (i, &v) in spline.control_points().iter().enumerate() {
            c[i * columns + j] = v;
        }
    }
    let (knots, c) = fitted.ok_or_else(|| Error::new(ErrorKind::InvalidArgument, "no column"))?;
    ColumnSpline::from_knot_vector(knots, c, columns)
}

/// scipy's checks of `make_smoothing_spline`, in its order and words.
fn check_scipy(
    x: &[f64],
    y: &[f64],
    columns: usize,
    w: Option<&[f64]>,
    parameter: SmoothingParameter<f64>,
) -> Result<()> {
    let n = x.len();
    if let Some(i) = (1..n).find(|&i| x[i] - x[i - 1] <= 0.0) {
        return Err(Error::new(
            ErrorKind::UnsortedKnots,
            format!(
                "``x`` should be an ascending array (x[{i}] = {} follows {})",
                x[i],
                x[i - 1]
            ),
        ));
    }
    if columns == 0 || Some(y.len()) != n.checked_mul(columns) {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "``x`` should be 1D and x.shape = ({n},) == y.shape: {} values are not {n} rows of {columns} columns",
                y.len()
            ),
        ));
    }
    if let Some((i, v)) = w
        .into_iter()
        .flatten()
        .enumerate()
        .find(|&(_, &v)| v <= 0.0)
    {
        return Err(Error::new(
            ErrorKind::InvalidWeight,
            format!("Invalid vector of weights (w[{i}] = {v})"),
        )
        .with_index(i));
    }
    if n <= 4 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!("``x`` and ``y`` length must be at least 5, got {n}"),
        )
        .with_counts(5, n));
    }
    if let SmoothingParameter::Lambda(lam) = parameter
        && lam < 0.0
    {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("Regularization parameter should be non-negative, got {lam}"),
        )
        .with_value(lam));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 24 abscissae, unevenly spaced, and three columns of wiggly data.
    fn data() -> (Vec<f64>, Vec<f64>) {
        let x: Vec<f64> = (0..24)
            .map(|i| {
                let t = f64::from(i) / 23.0;
                t + 0.01 * (7.0 * t).sin()
            })
            .collect();
        let y = x
            .iter()
            .enumerate()
            .flat_map(|(i, &t)| {
                let e = 0.05 * (f64::from(u8::try_from(i % 5).unwrap()) - 2.0);
                [(6.0 * t).sin() + e, t.powi(3) - e, 2.0 - t + 0.5 * e]
            })
            .collect();
        (x, y)
    }

    /// Each column equals the scalar fit of that column, bit for bit.
    fn assert_per_column(parameter: SmoothingParameter<f64>, w: Option<&[f64]>) {
        let (x, y) = data();
        let m = 3;
        let s = make_smoothing_spline(&x, &y, m, w, parameter).unwrap();
        assert_eq!(s.columns(), m);
        for j in 0..m {
            let column: Vec<f64> = y.iter().skip(j).step_by(m).copied().collect();
            let fit = smoothing_spline(&x, &column, w, parameter).unwrap();
            assert_eq!(s.knots(), fit.spline.knots().knots());
            assert_eq!(s.rows(), fit.spline.len());
            let ours: Vec<f64> = s
                .coefficients()
                .iter()
                .skip(j)
                .step_by(m)
                .copied()
                .collect();
            assert_eq!(ours, fit.spline.control_points(), "column {j}");
        }
    }

    #[test]
    fn columns_are_the_scalar_fits() {
        let w: Vec<f64> = (0..24).map(|i| 0.5 + f64::from(i) / 24.0).collect();
        for parameter in [
            SmoothingParameter::Gcv,
            SmoothingParameter::Lambda(0.0),
            SmoothingParameter::Lambda(1e-3),
        ] {
            assert_per_column(parameter, None);
            assert_per_column(parameter, Some(&w));
        }
    }

    #[test]
    fn gcv_chooses_lambda_per_column() {
        let (x, y) = data();
        let s = make_smoothing_spline(&x, &y, 3, None, SmoothingParameter::Gcv).unwrap();
        let lambdas: Vec<f64> = (0..3)
            .map(|j| {
                let column: Vec<f64> = y.iter().skip(j).step_by(3).copied().collect();
                smoothing_spline(&x, &column, None, SmoothingParameter::Gcv)
                    .unwrap()
                    .lambda
            })
            .collect();
        assert!(lambdas[0] != lambdas[1] || lambdas[1] != lambdas[2]);
        assert_eq!(s.rows(), x.len() + 2);
    }

    #[test]
    fn scipy_checks_and_words() {
        let (x, y) = data();
        let gcv = SmoothingParameter::Gcv;
        let err = |r: Result<ColumnSpline>| r.unwrap_err();
        let mut reversed = x.clone();
        reversed.reverse();
        let e = err(make_smoothing_spline(&reversed, &y, 3, None, gcv));
        assert_eq!(e.kind(), ErrorKind::UnsortedKnots);
        assert!(
            e.message()
                .starts_with("``x`` should be an ascending array")
        );
        let mut repeated = x.clone();
        repeated[1] = repeated[0];
        let e = err(make_smoothing_spline(&repeated, &y, 3, None, gcv));
        assert_eq!(e.kind(), ErrorKind::UnsortedKnots);
        let e = err(make_smoothing_spline(&x, &y[3..], 3, None, gcv));
        assert_eq!(e.kind(), ErrorKind::InvalidLength);
        assert!(
            e.message()
                .starts_with("``x`` should be 1D and x.shape = (24,) == y.shape")
        );
        let e = err(make_smoothing_spline(&x, &[], 0, None, gcv));
        assert_eq!(e.kind(), ErrorKind::InvalidLength);
        let mut w = vec![1.0; 24];
        w[5] = 0.0;
        let e = err(make_smoothing_spline(&x, &y, 3, Some(&w), gcv));
        assert_eq!(e.kind(), ErrorKind::InvalidWeight);
        assert!(e.message().starts_with("Invalid vector of weights"));
        let e = err(make_smoothing_spline(&x[..4], &y[..12], 3, None, gcv));
        assert_eq!(e.kind(), ErrorKind::TooFewPoints);
        assert!(
            e.message()
                .starts_with("``x`` and ``y`` length must be at least 5")
        );
        let e = err(make_smoothing_spline(
            &x,
            &y,
            3,
            None,
            SmoothingParameter::Lambda(-1.0),
        ));
        assert_eq!(e.kind(), ErrorKind::InvalidArgument);
        assert!(
            e.message()
                .starts_with("Regularization parameter should be non-negative")
        );
        // The scalar fit's checks follow, naming the column.
        let mut bad = y.clone();
        bad[3 * 7 + 2] = f64::NAN;
        let e = err(make_smoothing_spline(&x, &bad, 3, None, gcv));
        assert_eq!(e.kind(), ErrorKind::NonFinite);
        assert!(e.message().starts_with("column 2"), "{}", e.message());
        let e = err(make_smoothing_spline(&x, &y, 3, Some(&[1.0; 23]), gcv));
        assert_eq!(e.kind(), ErrorKind::InvalidLength);
    }
}
