//! Batches and grids on every core (feature `parallel`, rayon): the parameters are cut into
//! chunks and each chunk runs the sequential kernel ([`BSpline::eval_many_into`],
//! [`NurbsCurve::eval_many_into`], [`Surface::eval_grid_into`]), so the results are the
//! same bit for bit. The thread count is rayon's (`RAYON_NUM_THREADS`).

use crate::{BSpline, ColumnSpline, Extrapolate, NurbsCurve, Surface};
use nalgebra::SVector;
use rayon::prelude::*;
use spline_core::{ControlPoint, Result, Scalar};

/// Parameters per task: enough to hide rayon's overhead (a few microseconds per task).
const MIN_CHUNK: usize = 4096;

/// The chunk length for `len` items: about four tasks per thread, at least [`MIN_CHUNK`].
fn chunk_len(len: usize) -> usize {
    let tasks = 4 * rayon::current_num_threads();
    len.div_ceil(tasks).max(MIN_CHUNK)
}

/// Runs `kernel` on matching chunks of `params` and `out` in parallel; the first error wins.
fn chunked<T: Sync, Q: Send>(
    params: &[T],
    out: &mut [Q],
    chunk: usize,
    kernel: impl Fn(&[T], &mut [Q]) -> Result<()> + Sync,
) -> Result<()> {
    params
        .par_chunks(chunk)
        .zip(out.par_chunks_mut(chunk))
        .try_for_each(|(p, o)| kernel(p, o))
}

impl<T: Scalar, P: ControlPoint<T> + Send + Sync> BSpline<T, P> {
    /// [`BSpline::eval_many_into`] on every core: the same points, bit for bit.
    ///
    /// ```
    /// use spline_geom::BSpline;
    /// let f = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0], vec![0.0, 1.0, 3.0, 2.0])?;
    /// let params: Vec<f64> = (0..10_000).map(|i| f64::from(i) / 9999.0).collect();
    /// let mut out = vec![0.0; params.len()];
    /// f.par_eval_many_into(&params, &mut out)?;
    /// assert_eq!(out, f.eval_many(&params)?);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BSpline::eval_many_into`] (the error of one bad parameter, not necessarily the
    /// first).
    pub fn par_eval_many_into(&self, params: &[T], out: &mut [P]) -> Result<()> {
        crate::bspline::check_same_len(params.len(), out.len())?;
        chunked(params, out, chunk_len(params.len()), |p, o| {
            self.eval_many_into(p, o)
        })
    }
}

impl<T: Scalar, const D: usize> NurbsCurve<T, D> {
    /// [`NurbsCurve::eval_many_into`] on every core: the same points, bit for bit.
    ///
    /// # Errors
    /// As [`NurbsCurve::eval_many_into`] (the error of one bad parameter, not necessarily
    /// the first).
    pub fn par_eval_many_into(&self, params: &[T], out: &mut [SVector<T, D>]) -> Result<()> {
        crate::bspline::check_same_len(params.len(), out.len())?;
        chunked(params, out, chunk_len(params.len()), |p, o| {
            self.eval_many_into(p, o)
        })
    }
}

impl<T: Scalar, P: ControlPoint<T> + Send + Sync> Surface<T, P> {
    /// [`Surface::eval_grid_into`] on every core, rows of `us` shared among the threads:
    /// the same points, bit for bit.
    ///
    /// # Errors
    /// As [`Surface::eval_grid_into`].
    pub fn par_eval_grid_into(&self, us: &[T], vs: &[T], out: &mut [P]) -> Result<()> {
        crate::bspline::check_same_len(us.len() * vs.len(), out.len())?;
        if vs.is_empty() {
            return self.eval_grid_into(us, vs, out);
        }
        let rows = chunk_len(us.len() * vs.len()).div_ceil(vs.len());
        us.par_chunks(rows)
            .zip(out.par_chunks_mut(rows * vs.len()))
            .try_for_each(|(u, o)| self.eval_grid_into(u, vs, o))
    }
}

impl ColumnSpline {
    /// [`ColumnSpline::eval_into`] on every core: the points cut into chunks, each evaluated
    /// by the sequential kernel, so the rows are the same bit for bit; returns the number of
    /// NaN rows.
    ///
    /// ```
    /// use spline_geom::{ColumnSpline, Extrapolate};
    /// let s = ColumnSpline::new(vec![0.0, 0.0, 1.0, 2.0, 2.0], vec![0.0, 1.0, 1.0, 1.0, 2.0, 1.0], 1, 2)?;
    /// let x: Vec<f64> = (0..20_000).map(|i| f64::from(i) / 9999.0 - 0.5).collect();
    /// let (mut a, mut b) = (vec![0.0; 40_000], vec![0.0; 40_000]);
    /// s.par_eval_into(&x, 0, Extrapolate::On, &mut a)?;
    /// s.eval_into(&x, 0, Extrapolate::On, &mut b)?;
    /// assert_eq!(a, b);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`ColumnSpline::eval_into`].
    pub fn par_eval_into(
        &self,
        x: &[f64],
        nu: usize,
        mode: Extrapolate,
        out: &mut [f64],
    ) -> Result<usize> {
        let m = self.columns();
        crate::columns::check_rows(x.len(), m, out.len())?;
        let chunk = chunk_len(x.len().saturating_mul(m)).div_ceil(m).max(1);
        x.par_chunks(chunk)
            .zip(out.par_chunks_mut(chunk * m))
            .map(|(p, o)| self.eval_into(p, nu, mode, o))
            .try_reduce(|| 0, |a, b| Ok(a + b))
    }
}
