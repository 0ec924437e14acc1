//! What the fuzzers check: the exchange-format reader, the point-file reader and every
//! operation on arbitrary valid objects. An oracle returns `Err` when an `Ok` result holds
//! non-finite numbers (or a reader accepts rows of different dimensions); a panic is a failure
//! of its own. Shared by the stable mutation fuzzer (`cargo xtask fuzz`) and the
//! coverage-guided libFuzzer targets of `fuzz/` (which include this file and `mutate.rs`).

use crate::mutate::Rng;
use nalgebra::{Vector2, Vector3};
use spline::core::KnotVector;
use spline::geom::{BSpline, NurbsCurve, NurbsSurface, Surface};
use spline::io::airfoil::parse_airfoil;
use spline::io::exchange::{CurveRecord, SurfaceRecord, from_json};
use spline::io::points::parse_points;

thread_local! {
    /// What the `operations` target is doing, for the report of a panic.
    pub(crate) static CURRENT: std::cell::RefCell<String> = const { std::cell::RefCell::new(String::new()) };
}

/// The exchange-format reader: every record type and every container.
pub(crate) fn exchange(text: &str) -> Result<(), String> {
    if let Ok(record) = CurveRecord::from_json(text) {
        let _ = record.dimension();
        if let Ok(c) = record.to_bspline::<f64, Vector2<f64>>() {
            finite(c.control_points().iter().flat_map(|p| p.iter().copied()))?;
        }
        let _ = record.to_bspline::<f64, Vector3<f64>>();
        let _ = record.to_bspline::<f64, f64>();
        if let Ok(c) = record.to_nurbs::<f64, 2>() {
            let (a, b) = c.domain();
            if let Ok(p) = c.eval((a + b) / 2.0) {
                finite(p.iter().copied())?;
            }
        }
    }
    if let Ok(record) = SurfaceRecord::from_json(text) {
        let _ = record.dimension();
        let _ = record.to_surface::<f64, Vector3<f64>>();
        if let Ok(s) = record.to_nurbs_surface::<f64, 3>() {
            let (a, b) = s.knots_u().domain();
            let (c, d) = s.knots_v().domain();
            if let Ok(p) = s.eval((a + b) / 2.0, (c + d) / 2.0) {
                finite(p.iter().copied())?;
            }
        }
    }
    let _ = from_json::<BSpline<f64, Vector2<f64>>>(text);
    let _ = from_json::<NurbsSurface<f64, 3>>(text);
    let _ = spline::io::exchange::parse_json(text).map(spline::io::exchange::Record::from_value);
    Ok(())
}

/// The point-file and `.dat` readers.
pub(crate) fn points(text: &str) -> Result<(), String> {
    if let Ok(rows) = parse_points(text) {
        finite(rows.iter().flatten().copied())?;
        let d = rows.first().map_or(0, Vec::len);
        if rows.iter().any(|r| r.len() != d) {
            return Err("rows of different dimensions accepted".into());
        }
    }
    if let Ok(airfoil) = parse_airfoil(text) {
        finite(airfoil.points.iter().flat_map(|p| [p.x, p.y]))?;
    }
    Ok(())
}

fn finite(values: impl IntoIterator<Item = f64>) -> Result<(), String> {
    if values.into_iter().all(f64::is_finite) {
        Ok(())
    } else {
        Err("an Ok result holds non-finite numbers".into())
    }
}

fn finite_curve(c: &BSpline<f64, Vector2<f64>>) -> Result<(), String> {
    finite(c.knots().knots().iter().copied())?;
    finite(c.control_points().iter().flat_map(|p| p.iter().copied()))
}

/// A count at the edges: small, around degrees, or absurd.
fn count(rng: &mut Rng) -> usize {
    *rng.pick(&[
        0,
        1,
        2,
        3,
        4,
        5,
        7,
        31,
        32,
        33,
        1000,
        1001,
        100_000,
        1_000_000_000,
        usize::MAX / 2,
        usize::MAX - 1,
        usize::MAX,
    ])
}

/// A random valid planar curve: degree 0 to 5, knots with multiplicities, points at a
/// random scale.
fn curve(rng: &mut Rng) -> BSpline<f64, Vector2<f64>> {
    loop {
        let p = rng.below(6);
        let n = p + 1 + rng.below(6);
        let mut interior: Vec<f64> = Vec::new();
        let mut k = 0;
        while interior.len() < n - p - 1 {
            let m = 1 + rng.below(p + 1);
            let u = f64::from(u32::try_from(k + 1).unwrap_or(1))
                / f64::from(u32::try_from(n).unwrap_or(1));
            for _ in 0..m.min(n - p - 1 - interior.len()) {
                interior.push(u);
            }
            k += 1;
        }
        let scale = *rng.pick(&[1.0, 1.0, 1.0, 1e150, 1e-150, 1e80, 1e-100, 1e300]);
        let shift = *rng.pick(&[0.0, 0.0, 1e6, -3.0]);
        let points: Vec<Vector2<f64>> = (0..n)
            .map(|_| Vector2::new(rng.unit() * scale + shift, rng.unit() * scale))
            .collect();
        let (a, b) = *rng.pick(&[(0.0, 1.0), (-2.0, 5.0), (1e12, 1e12 + 1.0), (0.0, 1e-9)]);
        let interior: Vec<f64> = interior.iter().map(|u| a + u * (b - a)).collect();
        let interior: Vec<f64> = interior.into_iter().filter(|&u| u > a && u < b).collect();
        if let Ok(knots) = KnotVector::clamped(p, a, b, &interior) {
            let needed = knots.num_basis();
            let mut pts = points;
            pts.resize(needed, Vector2::new(1.0, 0.5));
            if let Ok(c) = BSpline::new(knots, pts) {
                return c;
            }
        }
    }
}

fn param(rng: &mut Rng, (a, b): (f64, f64)) -> f64 {
    match rng.below(8) {
        0 => a,
        1 => b,
        2 => b + 1.0,
        3 => f64::NAN,
        4 => -5e-324,
        _ => a + (b - a) * rng.unit(),
    }
}

/// Every operation on an arbitrary valid object, with arbitrary counts.
pub(crate) fn operations(rng: &mut Rng) -> Result<(), String> {
    let c = curve(rng);
    let (a, b) = c.domain();
    let u = param(rng, (a, b));
    let op = rng.below(16);
    CURRENT.with(|current| {
        *current.borrow_mut() = format!(
            "operation {op} at u = {u} on {}",
            CurveRecord::from_bspline(&c).to_json()
        );
    });
    operation(rng, op, &c, u).map_err(|e| {
        format!(
            "operation {op} at u = {u} on {}: {e}",
            CurveRecord::from_bspline(&c).to_json()
        )
    })
}

#[allow(clippy::too_many_lines)]
fn operation(
    rng: &mut Rng,
    op: usize,
    c: &BSpline<f64, Vector2<f64>>,
    u: f64,
) -> Result<(), String> {
    let c = c.clone();
    let (a, b) = c.domain();
    match op {
        0 => {
            if let Ok(d) = c.derivatives(u, count(rng)) {
                finite(d.iter().flat_map(|p| p.iter().copied()))?;
            }
            if let Ok(rows) = c.knots().dense_basis_derivatives(u, count(rng)) {
                finite(rows.iter().flatten().copied())?;
            }
        }
        1 => {
            if let Ok(e) = c.insert_knot(u, count(rng)) {
                finite_curve(&e)?;
            }
        }
        2 => {
            let knots: Vec<f64> = (0..rng.below(6)).map(|_| param(rng, (a, b))).collect();
            if let Ok(e) = c.refine(&knots) {
                finite_curve(&e)?;
            }
        }
        3 => {
            let tol = *rng.pick(&[0.0, 1e-9, 1.0, -1.0, f64::NAN, 1e300]);
            if let Ok(e) = c.remove_knot(u, count(rng), tol) {
                finite_curve(&e)?;
            }
        }
        4 => {
            if let Ok(e) = c.elevate_degree(count(rng)) {
                finite_curve(&e)?;
            }
        }
        5 => {
            if let Ok((l, r)) = c.split(u) {
                finite_curve(&l)?;
                finite_curve(&r)?;
            }
            for s in c.bezier_segments() {
                finite(s.control_points().iter().flat_map(|p| p.iter().copied()))?;
            }
        }
        6 => {
            if let Ok(d) = c.derivative(count(rng)) {
                finite_curve(&d)?;
            }
        }
        7 => {
            if let Ok(k) = c.signed_curvature(u) {
                finite([k])?;
            }
            if let Ok(f) = spline::algebra::planar_features(&c, 1e-12 * (b - a)) {
                finite(f.inflections.iter().chain(&f.curvature_extrema).copied())?;
            }
        }
        8 => {
            let w: Vec<f64> = (0..c.control_points().len())
                .map(|_| *rng.pick(&[1.0, 0.5, 1e-300, 1e300, 2.0]))
                .collect();
            CURRENT.with(|current| {
                current
                    .borrow_mut()
                    .push_str(&format!(" with weights {w:?}"));
            });
            if let Ok(n) = NurbsCurve::new(c.knots().clone(), c.control_points().to_vec(), w) {
                if let Ok(d) = n.derivatives(u, count(rng).min(2000)) {
                    finite(d.iter().flat_map(|p| p.iter().copied()))?;
                }
                if let Ok(k) = n.signed_curvature(u) {
                    finite([k])?;
                }
                if let Ok(e) = n.elevate_degree(count(rng)) {
                    finite(e.weights().iter().copied())?;
                }
            }
        }
        9 => {
            let f = c.map_control_points(|p| p.x);
            let g = curve(rng).map_control_points(|p| p.y);
            let product = spline::algebra::ProductMap::new(f.knots(), g.knots())
                .and_then(|map| map.product(&f, &g));
            if let Ok(h) = product {
                finite(h.control_points().iter().copied())?;
            }
        }
        10 => {
            let r = *rng.pick(&[1.0, 1e155, 1e-155, 1e300, 0.0, -1.0, f64::INFINITY]);
            if let Ok(s) = NurbsSurface::sphere(Vector3::new(0.0, 0.0, 0.0), r) {
                if let Ok(m) = s.tessellate(count(rng), 1 + rng.below(8)) {
                    finite(
                        m.vertices
                            .iter()
                            .chain(&m.normals)
                            .flat_map(|p| p.iter().copied()),
                    )?;
                }
                if let Ok(d) = s.derivatives(0.5, 0.5, count(rng)) {
                    finite(d.iter().flatten().flat_map(|p| p.iter().copied()))?;
                }
            }
        }
        11 => {
            let frame = spline::geom::Frame::planar(Vector2::new(0.0, 0.0));
            let sweep = *rng.pick(&[std::f64::consts::TAU, 1.0, 0.0, -3.0, 1e-19]);
            let piece = *rng.pick(&[1.5, 1e-19, 1e-6, 3.0, f64::NAN]);
            if let Ok(arc) = NurbsCurve::arc_with_max_piece(&frame, 1.0, 0.0, sweep, piece) {
                finite(arc.weights().iter().copied())?;
            }
        }
        12 => {
            let pts = c.control_points().to_vec();
            let degree = count(rng).min(40);
            if let Ok(fit) = spline::fit::interpolate(&pts, degree, &Default::default()) {
                finite_curve(&fit.curve)?;
            }
        }
        13 => {
            let pts: Vec<Vector2<f64>> = c
                .eval_many(&spline::ParamCurve::sample_params(&c, 4))
                .unwrap_or_default();
            let params = spline::fit::parametrize(&pts, &spline::fit::Parametrization::Chordal);
            if let Ok(params) = params {
                let n = count(rng).min(pts.len() + 2);
                if let Ok(knots) =
                    spline::fit::nurbs_book_knots(3.min(n.saturating_sub(1)), n, &params)
                {
                    let problem = spline::fit::LeastSquares::new(&pts, &params, knots);
                    let options = spline::fit::CorrectionOptions {
                        max_iterations: count(rng).min(20_000) % 50,
                        ..Default::default()
                    };
                    if let Ok((fit, _)) = spline::fit::correct_parameters(&problem, &options) {
                        finite_curve(&fit.curve)?;
                    }
                }
            }
        }
        14 => {
            let scale = *rng.pick(&[1.0, 1e-9, 1e9, 1e-200, 1e200]);
            let x: Vec<f64> = (0..2 + rng.below(6))
                .map(|k| f64::from(u32::try_from(k).unwrap_or(0)) * scale + 1.0)
                .collect();
            let y: Vec<f64> = x.iter().map(|_| rng.unit()).collect();
            let order = *rng.pick(&[2, 4, 6, 0, 3, 34, usize::MAX]);
            if let Ok(s) = spline::fit::natural_spline(&x, &y, order) {
                finite(s.control_points().iter().copied())?;
            }
        }
        _ => {
            let knots = c.knots().clone();
            let net: Vec<Vec<Vector3<f64>>> = (0..knots.num_basis())
                .map(|i| {
                    (0..2)
                        .map(|j| {
                            Vector3::new(
                                c.control_points()[i].x,
                                c.control_points()[i].y,
                                f64::from(j),
                            )
                        })
                        .collect()
                })
                .collect();
            if let Ok(s) = Surface::from_net(
                knots,
                KnotVector::bezier(1, 0.0, 1.0).map_err(|e| e.to_string())?,
                net,
            ) {
                if let Ok(d) = s.derivatives(u, 0.5, count(rng)) {
                    finite(d.iter().flatten().flat_map(|p| p.iter().copied()))?;
                }
                if let Ok(m) = s.tessellate(count(rng), count(rng)) {
                    finite(
                        m.vertices
                            .iter()
                            .chain(&m.normals)
                            .flat_map(|p| p.iter().copied()),
                    )?;
                }
            }
        }
    }
    Ok(())
}
