//! The work of an arc-length table grows linearly with the number of pieces (issue 25, item
//! 6: `spline arclength` on 10⁵ control points ran over a minute, every piece listing the
//! curve's breaks again). Counted, not timed: a wrapper counts the calls the table makes.

use std::cell::Cell;

use nalgebra::Vector2;
use spline_core::Result;
use spline_geom::{ArcLengthTable, BSpline, ParamCurve};

/// A curve that counts how often its breaks are listed and its derivatives evaluated.
struct Counted {
    curve: BSpline<f64, Vector2<f64>>,
    breaks: Cell<usize>,
    derivatives: Cell<usize>,
}

impl ParamCurve<f64> for Counted {
    type Point = Vector2<f64>;
    type Coefficient = Vector2<f64>;

    fn domain(&self) -> (f64, f64) {
        ParamCurve::domain(&self.curve)
    }

    fn eval(&self, u: f64) -> Result<Vector2<f64>> {
        ParamCurve::eval(&self.curve, u)
    }

    fn derivatives_into(&self, u: f64, out: &mut [Vector2<f64>]) -> Result<()> {
        self.derivatives.set(self.derivatives.get() + 1);
        self.curve.derivatives_into(u, out)
    }

    fn breaks(&self) -> Vec<f64> {
        self.breaks.set(self.breaks.get() + 1);
        self.curve.breaks()
    }

    fn bezier_pieces(&self) -> Vec<(f64, f64, Vec<Vector2<f64>>)> {
        self.curve.bezier_pieces()
    }

    fn project(coefficient: &Vector2<f64>) -> Vector2<f64> {
        *coefficient
    }

    fn control_polygon(&self) -> Vec<Vector2<f64>> {
        ParamCurve::control_polygon(&self.curve)
    }
}

/// A random cubic with `n` control points on uniform knots, `step` apart in x, random y in
/// `[0, height]`.
fn random_cubic(n: usize, step: f64, height: f64) -> BSpline<f64, Vector2<f64>> {
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut knots = vec![0.0; 4];
    knots.extend((1..n - 3).map(|i| i as f64 / (n - 3) as f64));
    knots.extend([1.0; 4]);
    let points = (0..n)
        .map(|i| Vector2::new(i as f64 * step, height * next()))
        .collect();
    BSpline::from_knots(3, knots, points).unwrap()
}

#[test]
fn an_arc_length_table_lists_the_breaks_once_and_evaluates_a_bounded_number_per_piece() {
    // Gentle (unit steps in x, y in [0, 1]) and steep (x steps of 1/n, y in [0, 2]: the
    // zigzag of the reproducer, nearly stopping inside many pieces).
    for (n, step, height) in [
        (500, 1.0, 1.0),
        (2000, 1.0, 1.0),
        (500, 2e-3, 2.0),
        (2000, 5e-4, 2.0),
    ] {
        let counted = Counted {
            curve: random_cubic(n, step, height),
            breaks: Cell::new(0),
            derivatives: Cell::new(0),
        };
        let table = ArcLengthTable::new(&counted, 1e-9).unwrap();
        let pieces = n - 3;
        assert_eq!(counted.breaks.get(), 1, "n = {n}");
        // 24 speeds per quadrature step (three 8-point rules). The pieces are alike at
        // every size (unit steps in x), so the steps per piece stay bounded although each
        // piece's share of the accuracy shrinks: about 2 here at both sizes (it was 10⁴
        // listings of 10⁴ breaks at the larger size).
        let per_piece = counted.derivatives.get() as f64 / pieces as f64;
        // Each half of a bisected interval gets half of its budget (an absolute share of the
        // piece's length): a relative accuracy asked of every sub-interval made the steep
        // zigzag cost 380 µs per piece at 10⁴ pieces and 2 ms at 2·10⁴ (issue 25, item 6).
        // About 2 steps per gentle piece, 10 per steep one, at both sizes.
        let bound = if step < 1.0 { 24.0 * 16.0 } else { 24.0 * 4.0 };
        assert!(
            per_piece <= bound,
            "n = {n}, step {step}: {per_piece} per piece"
        );
        // The length against an independent one: the polyline through 320 points per
        // piece, corrected by Richardson extrapolation from 160 points per piece (its error
        // is O(h²): the differences shrink by 4 from there on).
        let polyline = |m: usize| -> f64 {
            let k = m * pieces;
            (0..k)
                .map(|j| {
                    let a = counted.curve.eval(j as f64 / k as f64).unwrap();
                    let b = counted.curve.eval((j + 1) as f64 / k as f64).unwrap();
                    (b - a).norm()
                })
                .sum()
        };
        let (coarse, fine) = (polyline(160), polyline(320));
        let extrapolated = fine + (fine - coarse) / 3.0;
        assert!(
            (table.total() - extrapolated).abs() <= 1e-7 * extrapolated,
            "n = {n}, step {step}: {} vs {extrapolated}",
            table.total()
        );
    }
}
