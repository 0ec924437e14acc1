//! Pictures of the surface constructions for `docs/` (`cargo xtask docs`): a wing skinned
//! through UIUC airfoil sections, a Coons patch from four boundary curves, and a sweep along
//! rotation-minimising frames — meshed and shaded. Each picture's caption states how far the
//! surface is from the curves it must contain (evaluated, not assumed).

use nalgebra::{Vector2, Vector3};
use spline::fit::{LeastSquares, Parametrization, parametrize, skin, sweep};
use spline::geom::{BSpline, KnotVector, Surface};
use spline::io::airfoil::parse_airfoil;
use spline::io::svg::{MeshView, mesh_svg};
use spline::{Error, Result};
use std::path::Path;

type V3 = Vector3<f64>;

/// Control points of each fitted airfoil section (all on the same knots).
const SECTION_POINTS: usize = 24;

/// The wing: (airfoil, span station, chord, leading-edge sweep offset, twist in degrees,
/// dihedral height).
const WING: [(&str, f64, f64, f64, f64, f64); 4] = [
    ("goe398", 0.0, 1.0, 0.0, 0.0, 0.0),
    ("e422", 1.6, 0.85, 0.18, -1.0, 0.06),
    ("e580", 3.0, 0.65, 0.42, -2.0, 0.16),
    ("e580", 4.0, 0.4, 0.7, -3.0, 0.28),
];

/// One airfoil of `data/airfoils/` fitted by least squares on clamped uniform knots
/// (chord-length parameters), placed in space.
fn section(root: &Path, station: (&str, f64, f64, f64, f64, f64)) -> Result<BSpline<f64, V3>> {
    let (name, span, chord, sweep_x, twist, dihedral) = station;
    let path = root.join("data/airfoils").join(format!("{name}.dat"));
    let text = std::fs::read_to_string(&path).map_err(|e| {
        Error::new(
            spline::ErrorKind::InvalidArgument,
            format!("{}: {e}", path.display()),
        )
    })?;
    let points: Vec<Vector2<f64>> = parse_airfoil(&text)?.points;
    let params = parametrize(&points, &Parametrization::Chordal)?;
    let knots = KnotVector::clamped_uniform(3, SECTION_POINTS, 0.0, 1.0)?;
    let curve = LeastSquares::new(&points, &params, knots).solve()?.curve;
    let (s, c) = twist.to_radians().sin_cos();
    // Twist about the quarter chord.
    Ok(curve.map_control_points(|p| {
        let (x, z) = (p.x - 0.25, p.y);
        V3::new(
            sweep_x + chord * (0.25 + c * x + s * z),
            span,
            dihedral + chord * (c * z - s * x),
        )
    }))
}

/// The largest distance between `surface(u, v)` and `curve(u)` on 200 samples of `u`.
fn section_error(surface: &Surface<f64, V3>, v: f64, curve: &BSpline<f64, V3>) -> Result<f64> {
    let mut worst: f64 = 0.0;
    for i in 0..=200 {
        let u = f64::from(i) / 200.0;
        worst = worst.max((surface.eval(u, v)? - curve.eval(u)?).norm());
    }
    Ok(worst)
}

fn wing(root: &Path) -> Result<String> {
    let sections = WING
        .iter()
        .map(|&w| section(root, w))
        .collect::<Result<Vec<_>>>()?;
    let skinned = skin(&sections, 3, None)?;
    let mut worst: f64 = 0.0;
    for (curve, &v) in sections.iter().zip(&skinned.params) {
        worst = worst.max(section_error(&skinned.surface, v, curve)?);
    }
    let view = MeshView {
        azimuth: -60.0,
        elevation: 22.0,
        width: 640.0,
        color: [90, 140, 210],
        wireframe: true,
        title: Some(format!(
            "Wing skinned through 4 UIUC airfoils: max |S(u, v_k) − C_k(u)| = {worst:.0e}"
        )),
    };
    Ok(mesh_svg(&skinned.surface.tessellate(80, 12)?, &view))
}

fn cubic(points: [[f64; 3]; 4]) -> Result<BSpline<f64, V3>> {
    BSpline::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        points.iter().map(|&p| V3::from(p)).collect(),
    )
}

fn coons() -> Result<String> {
    let bottom = cubic([
        [0.0, 0.0, 0.0],
        [0.4, -0.2, 0.6],
        [0.8, 0.1, -0.3],
        [1.2, 0.0, 0.2],
    ])?;
    let top = cubic([
        [0.0, 1.0, 0.3],
        [0.4, 1.2, -0.2],
        [0.8, 1.1, 0.5],
        [1.2, 1.0, 0.0],
    ])?;
    let left = cubic([
        [0.0, 0.0, 0.0],
        [-0.2, 0.35, 0.5],
        [0.1, 0.7, 0.5],
        [0.0, 1.0, 0.3],
    ])?;
    let right = cubic([
        [1.2, 0.0, 0.2],
        [1.4, 0.3, -0.3],
        [1.3, 0.7, 0.2],
        [1.2, 1.0, 0.0],
    ])?;
    let patch = Surface::coons(&bottom, &top, &left, &right)?;
    let mut worst: f64 = 0.0;
    for i in 0..=200 {
        let t = f64::from(i) / 200.0;
        for (point, curve) in [
            (patch.eval(t, 0.0)?, &bottom),
            (patch.eval(t, 1.0)?, &top),
            (patch.eval(0.0, t)?, &left),
            (patch.eval(1.0, t)?, &right),
        ] {
            worst = worst.max((point - curve.eval(t)?).norm());
        }
    }
    let view = MeshView {
        azimuth: 35.0,
        elevation: 35.0,
        width: 600.0,
        color: [200, 140, 70],
        wireframe: true,
        title: Some(format!(
            "Coons patch of four cubic boundary curves: bicubic, max boundary error {worst:.1e}"
        )),
    };
    Ok(mesh_svg(&patch.tessellate(24, 24)?, &view))
}

fn swept() -> Result<String> {
    // A closed rounded-square profile (cubic, the first control point repeated) in the
    // plane x = 0, around the start of the path.
    let square = [
        [0.0, 0.2, 0.0],
        [0.0, 0.2, 0.2],
        [0.0, 0.0, 0.2],
        [0.0, -0.2, 0.2],
        [0.0, -0.2, 0.0],
        [0.0, -0.2, -0.2],
        [0.0, 0.0, -0.2],
        [0.0, 0.2, -0.2],
        [0.0, 0.2, 0.0],
    ];
    let knots = KnotVector::clamped_uniform(3, square.len(), 0.0, 1.0)?;
    let profile = BSpline::new(knots, square.iter().map(|&p| V3::from(p)).collect())?;
    let path = BSpline::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
        vec![
            V3::new(0.0, 0.0, 0.0),
            V3::new(1.0, 0.0, 0.0),
            V3::new(1.8, 1.0, 0.4),
            V3::new(1.8, 2.0, 1.2),
            V3::new(3.0, 2.4, 1.6),
        ],
    )?;
    let sections = 24;
    let swept = sweep(&profile, &path, sections, None)?;
    // Each station's copy of the profile must lie on the surface exactly: its centre is the
    // path point and its shape the profile's.
    let mut worst: f64 = 0.0;
    for &v in &swept.params {
        let centre = path.eval(v)?;
        for i in 0..=100 {
            let u = f64::from(i) / 100.0;
            let r = (swept.surface.eval(u, v)? - centre).norm();
            worst = worst.max((r - (profile.eval(u)? - V3::zeros()).norm()).abs());
        }
    }
    let view = MeshView {
        azimuth: 20.0,
        elevation: 30.0,
        width: 640.0,
        color: [110, 170, 110],
        wireframe: true,
        title: Some(format!(
            "Sweep along {sections} rotation-minimising frames: profile error {worst:.0e}"
        )),
    };
    Ok(mesh_svg(&swept.surface.tessellate(20, 64)?, &view))
}

/// Writes `wing.svg`, `coons.svg` and `sweep.svg` into `out_dir`.
///
/// # Errors
/// A message if an airfoil or a file cannot be read or written (or, which would be a bug, a
/// construction fails).
pub(crate) fn render(root: &Path, out_dir: &Path) -> std::result::Result<(), String> {
    let failed = |e: Error| format!("docs_constructions: {e}");
    crate::docs_output::write_doc(out_dir, "wing.svg", &wing(root).map_err(failed)?)?;
    crate::docs_output::write_doc(out_dir, "coons.svg", &coons().map_err(failed)?)?;
    crate::docs_output::write_doc(out_dir, "sweep.svg", &swept().map_err(failed)?)?;
    Ok(())
}
