//! The bounds that keep the curve near the data between data points.

use super::{EraserProblem, Excursion};
use nalgebra::{DVector, Vector2};

impl EraserProblem {
    /// Sets the excursion bounds from the anchors and the curve of `x`: the curve point halfway
    /// (in parameter) between the foot points of data points `j` and `j + 1` stays within
    /// `‖Q_{j+1} − Q_j‖/2 + allowance` of the middle of their chord (and within 1.1 times
    /// its current distance, so that `x` stays strictly feasible).
    pub(crate) fn set_excursions(&mut self, x: &DVector<f64>, allowance: f64) {
        let control = self.control_points(x);
        let params = self.distances.params.borrow().clone();
        let points = &self.distances.points;
        let knots = &self.distances.knots;
        let p = knots.degree();
        let mut basis = [0.0; spline_core::MAX_ORDER];
        // A closed curve also joins the last data point to the first, across the closing point.
        let pairs = if self.closed {
            points.len()
        } else {
            points.len() - 1
        };
        self.excursions = (0..pairs)
            .filter_map(|j| {
                let next = (j + 1) % points.len();
                let (a, mut b) = (params[j], params[next]);
                if next == 0 {
                    b += 1.0;
                }
                if !(b > a) {
                    return None;
                }
                let u = (0.5 * (a + b)).rem_euclid(1.0);
                let span = knots.span_in_domain(u);
                knots.basis_values(span, u, &mut basis[..=p]);
                let c: Vector2<f64> = (0..=p).map(|k| control[span - p + k] * basis[k]).sum();
                let centre = (points[j] + points[next]) * 0.5;
                let half = 0.5 * (points[next] - points[j]).norm();
                let radius = (half + allowance).max(1.1 * (c - centre).norm());
                Some(Excursion {
                    param: u,
                    centre,
                    radius2: radius * radius,
                })
            })
            .collect();
    }
}
