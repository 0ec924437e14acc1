//! The argument checks of the constructions and their errors.

use nalgebra::SVector;
use spline_core::{Error, ErrorKind, Result, Scalar, to_f64};

pub(super) fn degenerate(message: impl Into<String>) -> Error {
    Error::new(ErrorKind::DegenerateGeometry, message)
}

pub(super) fn check_vector<T: Scalar, const D: usize>(v: &SVector<T, D>, what: &str) -> Result<()> {
    if v.iter().all(nalgebra::ComplexField::is_finite) {
        Ok(())
    } else {
        Err(Error::new(
            ErrorKind::NonFinite,
            format!("{what} is not finite"),
        ))
    }
}

pub(super) fn check_positive<T: Scalar>(value: T, what: &str) -> Result<()> {
    if !value.is_finite() {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("{what} is not finite"),
        ));
    }
    if !(value > T::zero()) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("{what} must be positive, got {}", to_f64(value)),
        )
        .with_value(to_f64(value))
        .with_interval(0.0, f64::INFINITY));
    }
    Ok(())
}
