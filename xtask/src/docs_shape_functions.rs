//! Pictures of the constrained approximation of functions (thesis chapter 5) for `docs/`
//! (`cargo xtask docs`): the one-variable experiments of §5.1 and §5.4 with 11 and 200
//! coefficients (data, unconstrained fit, constrained fit), and the two-variable experiments
//! of §5.5–5.6 as height-coloured maps (target, unconstrained fit, constrained fit) and
//! iso-curves.
//!
//! Samples: `u_j = 0.01 j` on `[0, 4π]` (1257 points) for one variable — with them the costs
//! of §5.1.4 bis match the thesis (235.6 and 158.2); a uniform grid of `[0, 4π]²` for two.

use nalgebra::Vector2;
use spline::geom::{BSpline, Surface};
use spline::io::svg::SvgPlot;
use spline::shape::{FunctionApproximation, Sign, SurfaceApproximation};
use spline::{Error, Result};
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::Path;

const FOUR_PI: f64 = 4.0 * PI;

/// The one-variable sample parameters of every experiment.
fn thesis_params() -> Vec<f64> {
    (0..=1256).map(|j| 0.01 * f64::from(j)).collect()
}

/// `count + 1` uniform parameters on `[a, b]`.
fn linspace(a: f64, b: f64, count: u32) -> Vec<f64> {
    (0..=count)
        .map(|j| a + (b - a) * f64::from(j) / f64::from(count))
        .collect()
}

/// A one-variable experiment: the target, the degree, and the builder of its constraints.
struct Experiment {
    file: &'static str,
    title: &'static str,
    degree: usize,
    target: fn(f64) -> f64,
    constrain: fn(FunctionApproximation) -> FunctionApproximation,
}

fn experiments() -> Vec<Experiment> {
    const EPS: f64 = 0.05;
    vec![
        Experiment {
            file: "5_1_3",
            title: "§5.1.3 cos u, cubic, s ≥ 0",
            degree: 3,
            target: f64::cos,
            constrain: |a| a.sign(0, Sign::NonNegative),
        },
        Experiment {
            file: "5_1_4",
            title: "§5.1.4 sin u + 0.5u, cubic, s′ ≥ 0",
            degree: 3,
            target: |u| u.sin() + 0.5 * u,
            constrain: |a| a.sign(1, Sign::NonNegative),
        },
        Experiment {
            file: "5_1_4_bis",
            title: "§5.1.4 cos 2u + 0.2(u − 2π)², quartic, s″ ≥ 0",
            degree: 4,
            target: |u| (2.0 * u).cos() + 0.2 * (u - 2.0 * PI).powi(2),
            constrain: |a| a.sign(2, Sign::NonNegative),
        },
        Experiment {
            file: "5_1_5",
            title: "§5.1.5 sin 2u + 0.05(u − 2π)³, quintic, s‴ ≥ 0",
            degree: 5,
            target: |u| (2.0 * u).sin() + 0.05 * (u - 2.0 * PI).powi(3),
            constrain: |a| a.sign(3, Sign::NonNegative),
        },
        Experiment {
            file: "5_4",
            title: "§5.4 −4 cos 4u − (u − 2π)², cubic, s′ ≥ 0 | one root in 2π ± 0.05 | s′ ≤ 0",
            degree: 3,
            target: |u| -4.0 * (4.0 * u).cos() - (u - 2.0 * PI).powi(2),
            constrain: |a| {
                a.sign_on(1, Sign::NonNegative, 0.0, 2.0 * PI - EPS)
                    .sign_on(1, Sign::NonPositive, 2.0 * PI + EPS, FOUR_PI)
                    .sign_change(1, Sign::NonNegative, 2.0 * PI - EPS, 2.0 * PI + EPS)
            },
        },
    ]
}

/// The points `(u, k · s(u))` of a function at 800 parameters.
fn graph(spline: &BSpline<f64, f64>, k: f64) -> Result<Vec<Vector2<f64>>> {
    linspace(0.0, FOUR_PI, 800)
        .into_iter()
        .map(|u| spline.eval(u).map(|s| Vector2::new(u, k * s)))
        .collect()
}

/// One picture: every 10th sample (`data`), the unconstrained fit (`curve2`), the
/// constrained fit (`curve`) and, for few coefficients, its control polygon at the Greville
/// abscissae. The vertical axis is scaled so that the picture is about twice as wide as high.
fn function_picture(e: &Experiment, n: usize) -> Result<String> {
    let approx = (e.constrain)(FunctionApproximation::uniform(e.degree, n, 0.0, FOUR_PI)?);
    let params = thesis_params();
    let values: Vec<f64> = params.iter().map(|&u| (e.target)(u)).collect();
    let fit = approx.fit(&params, &values)?;
    let (lo, hi) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let k = (FOUR_PI / 2.0) / (hi - lo).max(1e-12);
    let mut svg = SvgPlot::new();
    svg.set_width(760.0);
    svg.set_title(format!("{}, {n} coefficients", e.title));
    svg.add_polyline(
        &[Vector2::new(0.0, 0.0), Vector2::new(FOUR_PI, 0.0)],
        "axis",
    );
    let data: Vec<Vector2<f64>> = params
        .iter()
        .zip(&values)
        .step_by(10)
        .map(|(&u, &v)| Vector2::new(u, k * v))
        .collect();
    svg.add_markers(&data, "data");
    svg.add_polyline(&graph(&fit.unconstrained, k)?, "curve2");
    if n <= 20 {
        let polygon: Vec<Vector2<f64>> = fit
            .spline
            .knots()
            .greville()
            .iter()
            .zip(fit.spline.control_points())
            .map(|(&g, &c)| Vector2::new(g, k * c))
            .collect();
        svg.add_polyline(&polygon, "polygon");
        svg.add_markers(&polygon, "control");
    }
    svg.add_polyline(&graph(&fit.spline, k)?, "curve");
    let legend = format!(
        "cost {:.1} (unconstrained {:.1}), {} Newton steps; blue: constrained, red: unconstrained, dots: data; y ×{k:.2}",
        fit.objective, fit.unconstrained_objective, fit.report.newton_iterations
    );
    Ok(with_second_line(&svg.render(), &legend))
}

/// Adds a second caption line under the title of an [`SvgPlot`] picture (the plot area
/// starts 44 pixels from the top when there is a title).
fn with_second_line(svg: &str, text: &str) -> String {
    let line = format!(r#"<text x="20" y="35" style="font-size:12px">{text}</text>"#);
    svg.replacen("</svg>", &format!("{line}\n</svg>"), 1)
}

/// A diverging colour for `t ∈ [−1, 1]`: blue below zero, white at zero, red above.
fn colour(t: f64) -> String {
    let t = t.clamp(-1.0, 1.0);
    let (r, g, b) = if t < 0.0 {
        (1.0 + 0.85 * t, 1.0 + 0.6 * t, 1.0)
    } else {
        (1.0, 1.0 - 0.7 * t, 1.0 - 0.85 * t)
    };
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let byte = |x: f64| (x * 255.0).round().clamp(0.0, 255.0) as u8;
    format!("#{:02x}{:02x}{:02x}", byte(r), byte(g), byte(b))
}

const CELLS: u32 = 32;
const CELL: f64 = 8.0;

/// Height-coloured maps of functions on `[0, 4π]²`, side by side, on one colour scale
/// (white = 0), `u` to the right and `v` upwards.
/// A named function of two variables to draw.
type Panel<'a> = (&'a str, &'a dyn Fn(f64, f64) -> Result<f64>);

fn height_maps(title: &str, panels: &[Panel<'_>]) -> Result<String> {
    let centres: Vec<f64> = (0..CELLS)
        .map(|j| FOUR_PI * (f64::from(j) + 0.5) / f64::from(CELLS))
        .collect();
    let mut grids = Vec::with_capacity(panels.len());
    for (_, f) in panels {
        let mut grid = Vec::with_capacity(centres.len() * centres.len());
        for &v in &centres {
            for &u in &centres {
                grid.push(f(u, v)?);
            }
        }
        grids.push(grid);
    }
    let extent = grids
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(1e-12);
    let side = CELL * f64::from(CELLS);
    let (margin, top) = (16.0, 56.0);
    #[allow(clippy::cast_precision_loss)]
    let width = margin + panels.len() as f64 * (side + margin);
    let height = top + side + 2.0 * margin;
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}">"#
    );
    out.push_str("<style>text{font:13px sans-serif;fill:#333}</style>\n");
    out.push_str(r#"<rect width="100%" height="100%" fill="white"/>"#);
    out.push('\n');
    let _ = writeln!(out, r#"<text x="{margin}" y="18">{title}</text>"#);
    let _ = writeln!(
        out,
        r#"<text x="{margin}" y="36">colour: blue &lt; 0 (down to {:.2}), white = 0, red &gt; 0 (up to {extent:.2}); u → right, v ↑ up</text>"#,
        -extent
    );
    for (p, ((name, _), grid)) in panels.iter().zip(&grids).enumerate() {
        #[allow(clippy::cast_precision_loss)]
        let x0 = margin + p as f64 * (side + margin);
        let _ = writeln!(out, r#"<text x="{x0}" y="{}">{name}</text>"#, top - 4.0);
        let _ = writeln!(out, "<g>");
        for (row, chunk) in grid.chunks(centres.len()).enumerate() {
            #[allow(clippy::cast_precision_loss)]
            let y = top + side - (row as f64 + 1.0) * CELL;
            for (col, &value) in chunk.iter().enumerate() {
                #[allow(clippy::cast_precision_loss)]
                let x = x0 + col as f64 * CELL;
                let _ = writeln!(
                    out,
                    r#"<rect x="{x}" y="{y}" width="{CELL}" height="{CELL}" fill="{}"/>"#,
                    colour(value / extent)
                );
            }
        }
        let _ = writeln!(
            out,
            r##"<rect x="{x0}" y="{top}" width="{side}" height="{side}" fill="none" stroke="#444"/></g>"##
        );
    }
    out.push_str("</svg>\n");
    Ok(out)
}

/// Iso-curves `v ↦ s(u_i, v)` (or `u ↦ s(u, v_i)` with `along_u`) of a surface for a few
/// values, in the palette classes `c0 … c7`.
fn iso_curves(
    title: &str,
    caption: &str,
    surface: &Surface<f64, f64>,
    along_u: bool,
) -> Result<String> {
    let mut svg = SvgPlot::new();
    svg.set_width(760.0);
    svg.set_title(title);
    let fixed = linspace(0.0, FOUR_PI, 6);
    let free = linspace(0.0, FOUR_PI, 400);
    let mut curves = Vec::new();
    for &c in &fixed {
        let points = free
            .iter()
            .map(|&t| {
                let (u, v) = if along_u { (t, c) } else { (c, t) };
                surface.eval(u, v).map(|s| Vector2::new(t, s))
            })
            .collect::<Result<Vec<_>>>()?;
        curves.push(points);
    }
    let (lo, hi) = curves
        .iter()
        .flatten()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.y), b.max(p.y))
        });
    let k = (FOUR_PI / 2.0) / (hi - lo).max(1e-12);
    for (i, points) in curves.iter().enumerate() {
        let scaled: Vec<_> = points.iter().map(|p| Vector2::new(p.x, k * p.y)).collect();
        svg.add_polyline(&scaled, &format!("c{}", i % 8));
    }
    Ok(with_second_line(
        &svg.render(),
        &format!("{caption}; y ×{k:.2}"),
    ))
}

fn surface_pictures(out_dir: &Path) -> std::result::Result<(), String> {
    let failed = |e: Error| format!("docs_shape_functions: {e}");
    let domain = (0.0, FOUR_PI);
    type Target = fn(f64, f64) -> f64;
    let cases: [(&str, &str, Target, SurfaceApproximation, usize); 3] = [
        (
            "5_5_2",
            "§5.5.2 sin u sin v, bicubic 20 × 20, s ≥ 0",
            |u, v| u.sin() * v.sin(),
            SurfaceApproximation::uniform((3, 3), (20, 20), domain, domain)
                .map_err(failed)?
                .sign(0, 0, Sign::NonNegative),
            50,
        ),
        (
            "5_5_3",
            "§5.5.3 cos u sin v + 0.25v, bicubic 20 × 20, s_v ≥ 0",
            |u, v| u.cos() * v.sin() + 0.25 * v,
            SurfaceApproximation::uniform((3, 3), (20, 20), domain, domain)
                .map_err(failed)?
                .sign(0, 1, Sign::NonNegative),
            50,
        ),
        (
            "5_6",
            "§5.6 sin u sin v + 0.05((u − 2π)² + (v − 2π)²), bicubic 10 × 10, convex",
            |u, v| u.sin() * v.sin() + 0.05 * ((u - 2.0 * PI).powi(2) + (v - 2.0 * PI).powi(2)),
            SurfaceApproximation::uniform((3, 3), (10, 10), domain, domain)
                .map_err(failed)?
                .convex(),
            40,
        ),
    ];
    for (file, title, target, approx, samples) in cases {
        let fit = approx
            .fit_function((samples, samples), target)
            .map_err(failed)?;
        let heading = format!(
            "{title}, {samples} × {samples} samples: cost {:.2} (unconstrained {:.2}), {} Newton steps",
            fit.objective, fit.unconstrained_objective, fit.report.newton_iterations
        );
        let gamma = |u: f64, v: f64| Ok(target(u, v));
        let free = |u: f64, v: f64| fit.unconstrained.eval(u, v);
        let constrained = |u: f64, v: f64| fit.surface.eval(u, v);
        let maps = height_maps(
            &heading,
            &[
                ("target γ", &gamma),
                ("unconstrained fit", &free),
                ("constrained fit", &constrained),
            ],
        )
        .map_err(failed)?;
        crate::docs_output::write_doc(out_dir, &format!("shape_{file}.svg"), &maps)?;
        if file != "5_5_2" {
            let (along_u, what) = if file == "5_6" {
                (true, "u ↦ s(u, v) for v = 0, 2π/3, …, 4π (convex)")
            } else {
                (false, "v ↦ s(u, v) for u = 0, 2π/3, …, 4π (non-decreasing)")
            };
            let iso = iso_curves(title, &format!("iso-curves {what}"), &fit.surface, along_u)
                .map_err(failed)?;
            crate::docs_output::write_doc(out_dir, &format!("shape_{file}_iso.svg"), &iso)?;
        }
    }
    Ok(())
}

/// Writes `shape_<experiment>_<11|200>.svg` for the one-variable experiments, and
/// `shape_5_5_2.svg`, `shape_5_5_3.svg`, `shape_5_6.svg` (height maps) with
/// `shape_5_5_3_iso.svg` and `shape_5_6_iso.svg` (iso-curves) into `out_dir` (created if
/// needed).
///
/// # Errors
/// A message if a file cannot be written (or, which would be a bug, a fit fails).
pub(crate) fn render(out_dir: &Path) -> std::result::Result<(), String> {
    std::fs::create_dir_all(out_dir)
        .map_err(|e| format!("cannot create {}: {e}", out_dir.display()))?;
    let failed = |e: Error| format!("docs_shape_functions: {e}");
    for e in &experiments() {
        for n in [11, 200] {
            let svg = function_picture(e, n).map_err(failed)?;
            crate::docs_output::write_doc(out_dir, &format!("shape_{}_{n}.svg", e.file), &svg)?;
        }
    }
    surface_pictures(out_dir)
}
