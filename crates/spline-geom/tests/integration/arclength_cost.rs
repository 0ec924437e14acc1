//! The work of an arc-length table grows linearly with the number of pieces (issue 25, item
//! 6: `spline arclength` on 10⁵ control points ran over a minute, every piece listing the
//! curve's breaks again). Counted, not timed: a wrapper counts the calls the table makes,
//! up to the reproducer's 10⁵ control points, where the lengths are checked too: the steep
//! zigzag's pieces nearly stop inside, narrower than the Gauss nodes' spacing, and the
//! table missed 8.5·10⁻⁷ of its length at an accuracy of 10⁻⁹ until pieces were cut around
//! their near-stops (now within 3·10⁻⁸ of the extrapolated polyline, itself 3·10⁻⁸ short
//! of scipy's `quad` at 10⁻¹³ per piece: 38511.00061).
//! And tight accuracies on steep rational curves (issue 26: 1e-12 asked of a degree-6 NURBS
//! whose speed runs from 236 down to 0.4 failed, "did not reach the accuracy 2.0e-27"),
//! against the circle's closed form.

use std::cell::Cell;

use nalgebra::Vector2;
use spline_core::Result;
use spline_geom::{ArcLengthTable, BSpline, Frame, NurbsCurve, ParamCurve, param_at_length};

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
        // The reproducer's size: 10⁵ control points.
        (100_000, 1.0, 1.0),
        (100_000, 1e-5, 2.0),
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
        // About 1 step per gentle piece at every size; a steep piece is first cut around its
        // near-stop (about 17 halvings where the speed dips 10⁵ times below its size): 9 to
        // 17 steps per steep piece (10⁵ pieces: 24·17).
        let bound = if step < 1.0 { 24.0 * 20.0 } else { 24.0 * 4.0 };
        assert!(
            per_piece <= bound,
            "n = {n}, step {step}: {per_piece} per piece"
        );
        // The length against an independent one: the polyline through 320 points per
        // piece, corrected by Richardson extrapolation from 160 points per piece (its error
        // is O(h²): the differences shrink by 4 from there on).
        let polyline = |m: usize| -> f64 {
            let k = m * pieces;
            let params: Vec<f64> = (0..=k).map(|j| j as f64 / k as f64).collect();
            let points = counted.curve.eval_many(&params).unwrap();
            points.windows(2).map(|w| (w[1] - w[0]).norm()).sum()
        };
        let (coarse, fine) = (polyline(160), polyline(320));
        let extrapolated = fine + (fine - coarse) / 3.0;
        assert!(
            (table.total() - extrapolated).abs() <= 1e-7 * extrapolated,
            "n = {n}, step {step}: {} vs {extrapolated} (polyline {fine})",
            table.total()
        );
    }
}

/// The OCCT geometry suite's reproducer (issue 26): a rational degree-6 curve on
/// `[-1.9, -0.5]` whose weights (0.2 next to 2.9) put a third of its length in the first
/// 0.4 % of the domain.
fn steep_sextic() -> NurbsCurve<f64, 2> {
    let mut knots = vec![-1.9; 7];
    knots.extend([-0.5; 7]);
    let points = [
        (-0.9, 1.6),
        (0.0, -2.1),
        (0.0, 0.9),
        (0.3, 0.6),
        (1.0, -1.6),
        (-0.5, 1.0),
        (-2.0, 0.3),
    ];
    NurbsCurve::from_knots(
        6,
        knots,
        points.iter().map(|&(x, y)| Vector2::new(x, y)).collect(),
        vec![0.2, 2.9, 1.9, 1.0, 1.9, 0.4, 2.5],
    )
    .unwrap()
}

#[test]
fn tight_accuracies_on_a_steep_rational_sextic() {
    let curve = steep_sextic();
    let (a, _) = ParamCurve::domain(&curve);
    for accuracy in [1e-12, 1e-13, 1e-14] {
        let length = curve.arc_length(accuracy).unwrap();
        let table = ArcLengthTable::new(&curve, accuracy).unwrap();
        assert!((table.total() - length).abs() <= 2.0 * accuracy * length);
        // `spline arclength --at-length` of the reproducer.
        let lengths = [0.45074023774924005, 1.1531665466919585, 1.449930409480189];
        let params = table.params_at(&lengths).unwrap();
        for (&s, &u) in lengths.iter().zip(&params) {
            // The length up to the parameter found, measured again, more tightly.
            let back = curve.arc_length_between(a, u, 1e-14).unwrap();
            assert!(
                (back - s).abs() <= accuracy * length,
                "accuracy {accuracy:e}: s = {s}, u = {u}: {back} ({:e})",
                (back - s) / length
            );
            let alone = table.param_at(s).unwrap();
            let back = curve.arc_length_between(a, alone, 1e-14).unwrap();
            assert!(
                (back - s).abs() <= accuracy * length,
                "accuracy {accuracy:e}: s = {s}"
            );
        }
    }
}

/// A circular arc (centre, radius, start and sweep in radians) made steep by the Möbius
/// reparametrization with `factor`, raised to degree 6 and mapped onto `[-1.9, -0.5]`: the
/// kind of curve of the reproducer, with a closed-form length.
fn steep_sextic_arc(
    centre: Vector2<f64>,
    radius: f64,
    start: f64,
    sweep: f64,
    factor: f64,
) -> NurbsCurve<f64, 2> {
    NurbsCurve::arc(&Frame::planar(centre), radius, start, sweep)
        .unwrap()
        .mobius_reparametrized(factor)
        .unwrap()
        .elevate_degree(4)
        .unwrap()
        .reparametrized(-1.9, -0.5)
        .unwrap()
}

#[test]
fn lengths_and_parameters_at_lengths_of_steep_rational_circular_arcs() {
    // Arcs of circles (rational quadratic pieces of at most 90°), made steep by a Möbius
    // reparametrization (the speed varies by about factor² over the domain), raised to
    // degree 6 and moved to the domain [-1.9, -0.5] like the reproducer: the length is
    // r θ and the point at arc length s is at angle start + s / r, to 1e-12 of the length.
    let cases = [
        (Vector2::new(0.0, 0.0), 1.0, 0.3, 1.2, 1.0),
        (Vector2::new(-3.0, 2.0), 0.7, -2.0, 4.0, 20.0),
        (Vector2::new(-3.0, 1.2), 2e-3, 1.0, 5.5, 0.05),
        (Vector2::new(0.3, -0.1), 2e-3, -1.0, 5.5, 20.0),
        (Vector2::new(0.5, 0.25), 250.0, 2.5, 2.0, 40.0),
    ];
    for (centre, radius, start, sweep, factor) in cases {
        let arc = steep_sextic_arc(centre, radius, start, sweep, factor);
        let exact = radius * sweep;
        let case = format!("radius {radius}, sweep {sweep}, factor {factor}");
        let angle = |u: f64| {
            let p = arc.eval(u).unwrap() - centre;
            let e = Vector2::new(start.cos(), start.sin());
            let a = (e.x * p.y - e.y * p.x).atan2(e.dot(&p));
            if a < -1e-9 {
                a + std::f64::consts::TAU
            } else {
                a
            }
        };
        for accuracy in [1e-9, 1e-12] {
            let length = arc.arc_length(accuracy).unwrap();
            assert!(
                (length - exact).abs() <= accuracy * exact,
                "{case}, accuracy {accuracy:e}: {length} vs {exact} ({:e})",
                (length - exact) / exact
            );
            let table = ArcLengthTable::new(&arc, accuracy).unwrap();
            assert!((table.total() - exact).abs() <= accuracy * exact, "{case}");
            let mut sorted: Vec<f64> = (0..=16)
                .map(|k| exact * f64::from(k) / 16.0)
                .chain([1e-9 * exact, exact * (1.0 - 1e-9)])
                .collect();
            sorted.sort_by(f64::total_cmp);
            let params = table.params_at(&sorted).unwrap();
            for (&s, &u) in sorted.iter().zip(&params) {
                let e = (radius * angle(u) - s).abs();
                // The accuracy, plus the rounding of the angle (the points are rounded at
                // the scale of the centre).
                let rounding = 8.0 * f64::EPSILON * (radius + centre.norm());
                assert!(
                    e <= accuracy * exact + rounding,
                    "{case}, accuracy {accuracy:e}: s = {s}, u = {u}: {e:e}"
                );
            }
            let u = param_at_length(&arc, 0.3 * exact, accuracy).unwrap();
            assert!(
                (radius * angle(u) - 0.3 * exact).abs()
                    <= accuracy * exact + 8.0 * f64::EPSILON * (radius + centre.norm()),
                "{case}"
            );
        }
    }
}

#[test]
fn accuracies_below_the_rounding_of_the_speed_give_what_rounding_allows() {
    // A small arc far from the origin: its control points, and so its speed, are rounded at
    // the scale of the centre, ε |c| / r ≈ 1e-10 of the speed, and no bisection gets two
    // estimates closer than that. The accuracy asked is then raised to the speed's rounding
    // (it took 2⁴⁸ bisections): the length is as accurate as the curve's own rounding.
    let (centre, radius, sweep): (Vector2<f64>, f64, f64) = (Vector2::new(1e3, -5e2), 2e-3, 5.5);
    let arc = steep_sextic_arc(centre, radius, 1.0, sweep, 0.05);
    let exact = radius * sweep;
    let rounding = 64.0 * f64::EPSILON * centre.norm() / radius;
    for accuracy in [1e-12, 1e-15] {
        let length = arc.arc_length(accuracy).unwrap();
        assert!(
            (length - exact).abs() <= (accuracy + rounding) * exact,
            "accuracy {accuracy:e}: {:e}",
            (length - exact) / exact
        );
        let table = ArcLengthTable::new(&arc, accuracy).unwrap();
        let u = table.param_at(0.5 * exact).unwrap();
        // The angle from the start (1 rad), through π.
        let p = arc.eval(u).unwrap() - centre;
        let e = Vector2::new(1f64.cos(), 1f64.sin());
        let angle = (e.x * p.y - e.y * p.x).atan2(e.dot(&p));
        assert!((radius * angle - 0.5 * exact).abs() <= (accuracy + rounding) * exact);
    }
}

/// Weights far apart (issue 25: `[1, 1e300, 1]` gave length 0): the quadratic over
/// `(0, 0), (1, 1), (2, 0)` is, to rounding, its two legs; by symmetry each half of the
/// domain is one leg, and the table agrees with `arc_length`.
#[test]
fn weights_1e300_apart_give_the_legs() {
    let curve = NurbsCurve::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(2.0, 0.0),
        ],
        vec![1.0, 1e300, 1.0],
    )
    .unwrap();
    let leg = 2f64.sqrt();
    let whole = curve.arc_length(1e-12).unwrap();
    assert!((whole - 2.0 * leg).abs() < 1e-12, "{whole}");
    let half = curve.arc_length_between(0.0, 0.5, 1e-12).unwrap();
    assert!((half - leg).abs() < 1e-12, "{half}");
    let table = ArcLengthTable::new(&curve, 1e-12).unwrap();
    assert!((table.total() - whole).abs() < 1e-12, "{}", table.total());
}
