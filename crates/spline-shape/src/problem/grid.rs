//! Pieces the constrained surface problems share: the normalised quadratic constraints and
//! the check of samples on a parameter grid.

use nalgebra_sparse::{CooMatrix, CsrMatrix};
use spline_algebra::SparseBilinear;
use spline_core::{Error, ErrorKind, Result};

/// The quadratic constraints `−½ xᵀ H_k x / c_k < 0` from forms `H_k` (row `k`), with
/// `c_k` the largest entry of `H_k` in absolute value; identically zero rows are dropped.
pub(crate) fn normalized_forms(forms: &SparseBilinear<f64>) -> Result<SparseBilinear<f64>> {
    let kept: Vec<(usize, f64)> = (0..forms.nrows())
        .filter_map(|k| {
            let c = forms.row(k).iter().fold(0.0f64, |m, e| m.max(e.2.abs()));
            (c > 0.0).then_some((k, -1.0 / c))
        })
        .collect();
    let mut coo = CooMatrix::new(kept.len(), forms.nrows());
    for (r, &(k, w)) in kept.iter().enumerate() {
        coo.push(r, k, w);
    }
    forms.then(&CsrMatrix::from(&coo))
}

/// Checks samples on a grid of parameters: `us.len() · vs.len() > 0` of them (`count`), each
/// finite (`finite(j)`; `what` names one in the message).
///
/// # Errors
/// [`ErrorKind::InvalidLength`] for another count or an empty grid; [`ErrorKind::NonFinite`]
/// naming the first sample that is not finite.
pub(crate) fn check_grid(
    us: &[f64],
    vs: &[f64],
    count: usize,
    finite: impl Fn(usize) -> bool,
    what: &str,
) -> Result<()> {
    if us.is_empty() || vs.is_empty() || count != us.len() * vs.len() {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "a grid of {} × {} parameters needs as many samples (at least one), got {count}",
                us.len(),
                vs.len()
            ),
        ));
    }
    if let Some(j) = (0..count).find(|&j| !finite(j)) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("{what} {j} is not finite"),
        ));
    }
    Ok(())
}
