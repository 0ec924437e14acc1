//! `cargo xtask reproduce`: the published numbers of the seeds next to ours.
//!
//! 1. Thesis Table 6.1 (selective eraser on UIUC airfoils, chord 1 m): with at most the
//!    thesis's control points and its extrema, the closest curve over degrees 3–5, the
//!    knot densities of `--thorough` and the search over the knots of `--knot-search`; each result is checked by dense sampling of its
//!    curvature (both one-sided limits at every knot), independently of the constraints.
//! 2. Thesis §5.1: the costs of the constrained approximations of functions (11 and 200
//!    coefficients; the thesis reports 235.6 → 158.2 for §5.1.4 bis).
//! 3. Seed 000 §3, Tables 1 and 2: J = P²/A per iteration of the shape optimisation with
//!    adaptive parametrisation, degree 3 (converges to 2π) and degree 5 (the seed sees it
//!    diverge).

use nalgebra::Vector2;
use spline::io::airfoil::parse_airfoil;
use spline::shape::{
    AdaptiveOptions, Extremum, ExtremumKind, FunctionApproximation, Sign, SmoothingOptions,
    optimise_perimeter_over_area, sampled_curvature_extrema, smooth,
};
use std::f64::consts::PI;
use std::path::Path;
use std::time::Instant;

/// One row of Table 6.1: the airfoil, the thesis's control points, its extrema, its deviation
/// in millimetres.
struct Row {
    name: &'static str,
    control_points: usize,
    extrema: &'static [&'static str],
    thesis_mm: f64,
}

const TABLE_6_1: [Row; 7] = [
    Row {
        name: "a18sm",
        control_points: 17,
        extrema: &["max"],
        thesis_mm: 0.8,
    },
    Row {
        name: "ah81k144wfKlappe",
        control_points: 15,
        extrema: &["max"],
        thesis_mm: 2.0,
    },
    Row {
        name: "ch10sm",
        control_points: 22,
        extrema: &["max"],
        thesis_mm: 0.7,
    },
    Row {
        name: "bambino6",
        control_points: 17,
        extrema: &["max", "min"],
        thesis_mm: 5.6,
    },
    Row {
        name: "2032c",
        control_points: 16,
        extrema: &["max", "min"],
        thesis_mm: 2.2,
    },
    Row {
        name: "e377",
        control_points: 19,
        extrema: &["max", "min"],
        thesis_mm: 1.1,
    },
    Row {
        name: "ah63k127",
        control_points: 26,
        extrema: &["min@0.02", "max"],
        thesis_mm: 2.7,
    },
];

/// The best smoothing of one airfoil of Table 6.1 over degrees 3–5, and its check.
fn table_row(root: &Path, row: &Row) -> Result<String, String> {
    let path = root
        .join("data/airfoils/table61")
        .join(format!("{}.dat", row.name));
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let airfoil = parse_airfoil(&text).map_err(|e| e.to_string())?;
    // Chord 1 m: deviations in the units of the file (chord ≈ 1), printed in millimetres.
    let chord = airfoil
        .points
        .iter()
        .map(|p| p.x)
        .fold(f64::NEG_INFINITY, f64::max)
        - airfoil
            .points
            .iter()
            .map(|p| p.x)
            .fold(f64::INFINITY, f64::min);
    let extrema: Vec<Extremum> = row
        .extrema
        .iter()
        .map(|e| {
            e.parse()
                .map_err(|err: spline::core::Error| err.to_string())
        })
        .collect::<Result<_, _>>()?;
    let started = Instant::now();
    let mut best = None;
    for degree in 3..=5 {
        let mut options = SmoothingOptions::new(row.control_points);
        options.degree = degree;
        options.extrema.clone_from(&extrema);
        options.thorough = true;
        options.knot_search = true;
        let Ok(result) = smooth(&airfoil.points, &options) else {
            continue;
        };
        // The independent check: the sampled curvature turns exactly where the kinds say.
        let turns = sampled_curvature_extrema(&result.curve, result.orientation, 400, 1e-9)
            .map_err(|e| e.to_string())?;
        let kinds_ok = turns.len() == extrema.len()
            && turns
                .iter()
                .zip(&extrema)
                .all(|(t, e)| t.maximum == (e.kind == ExtremumKind::Maximum));
        if !kinds_ok {
            continue;
        }
        let deviation = result.deviation.to_curve.max / chord * 1e3;
        if best.as_ref().is_none_or(|(d, _, _)| deviation < *d) {
            let to_data = result.deviation.to_data / chord * 1e3;
            best = Some((deviation, degree, to_data));
        }
    }
    let seconds = started.elapsed().as_secs_f64();
    let settings = format!("{} cp, {}", row.control_points, row.extrema.join(" + "));
    Ok(match best {
        Some((mm, degree, to_data)) => format!(
            "| {} | {settings} | {:.1} | {mm:.2} (degree {degree}) | {to_data:.2} | {:.2}× | {} ✓ | {seconds:.1} s |",
            row.name,
            row.thesis_mm,
            mm / row.thesis_mm,
            row.extrema.len(),
        ),
        None => format!(
            "| {} | {settings} | {:.1} | not found | | | | {seconds:.1} s |",
            row.name, row.thesis_mm
        ),
    })
}

/// The costs of thesis §5.1 with 11 and 200 coefficients, samples every 0.01 on [0, 4π].
fn section_5_1() -> Result<Vec<String>, String> {
    let params: Vec<f64> = (0..=1256).map(|j| 0.01 * f64::from(j)).collect();
    type Target = fn(f64) -> f64;
    let experiments: [(&str, usize, usize, Target, &str); 4] = [
        ("5.1.3: s ≥ 0, cos u", 3, 0, f64::cos, "figures only"),
        (
            "5.1.4: s′ ≥ 0, sin u + u/2",
            3,
            1,
            |u| u.sin() + 0.5 * u,
            "figures only",
        ),
        (
            "5.1.4 bis: s″ ≥ 0, cos 2u + 0.2(u − 2π)²",
            4,
            2,
            |u| (2.0 * u).cos() + 0.2 * (u - 2.0 * PI).powi(2),
            "235.6 → 158.2",
        ),
        (
            "5.1.5: s‴ ≥ 0, sin 2u + 0.05(u − 2π)³",
            5,
            3,
            |u| (2.0 * u).sin() + 0.05 * (u - 2.0 * PI).powi(3),
            "figures only",
        ),
    ];
    let mut lines = Vec::new();
    for (what, degree, order, f, thesis) in experiments {
        let values: Vec<f64> = params.iter().map(|&u| f(u)).collect();
        let mut costs = Vec::new();
        for n in [11, 200] {
            let fit = FunctionApproximation::uniform(degree, n, 0.0, 4.0 * PI)
                .map_err(|e| e.to_string())?
                .sign(order, Sign::NonNegative)
                .fit(&params, &values)
                .map_err(|e| e.to_string())?;
            costs.push(fit.objective);
        }
        lines.push(format!(
            "| {what} | degree {degree} | {thesis} | {:.2} → {:.2} |",
            costs[0], costs[1]
        ));
    }
    Ok(lines)
}

/// A flattened arch from (0, 0) to (1, 0), vertical at the origin: half an ellipse.
fn flat_arch(count: usize) -> Vec<Vector2<f64>> {
    (0..count)
        .map(|i| {
            let t = PI * i as f64 / (count - 1) as f64;
            if i + 1 == count {
                Vector2::new(1.0, 0.0)
            } else {
                Vector2::new(0.5 - 0.5 * t.cos(), 0.3 * t.sin())
            }
        })
        .collect()
}

/// Seed 000 Tables 1 and 2.
fn seed_tables() -> Result<Vec<String>, String> {
    let seed1 = [6.3632, 6.2941, 6.2903, 6.2842, 6.284, 6.284, 6.2839, 6.2839];
    let seed2 = [
        6.3361, 6.5839, 6.6306, 6.6883, 6.7551, 6.828, 6.9004, 6.9644,
    ];
    let mut lines = vec![
        "| iteration | seed Table 1 (d = 3) | ours (d = 3) | seed Table 2 (d = 5) | ours (d = 5) |"
            .into(),
        "|---|---|---|---|---|".into(),
    ];
    // The seed stops its simplex at about 1e-4 of J; a budget of 100 simplex iterations per
    // step gives the same gradual convergence (run to convergence, every step gives 2π).
    let run = |degree: usize| -> Result<Vec<f64>, String> {
        let options = AdaptiveOptions {
            degree,
            max_simplex_iterations: 100,
            ..AdaptiveOptions::default()
        };
        Ok(optimise_perimeter_over_area(&flat_arch(41), &options)
            .map_err(|e| e.to_string())?
            .iter()
            .map(|h| h.criterion)
            .collect())
    };
    let (ours3, ours5) = (run(3)?, run(5)?);
    for i in 0..8 {
        let cell = |v: &[f64]| v.get(i).map_or_else(String::new, |j| format!("{j:.4}"));
        lines.push(format!(
            "| {} | {} | {} | {} | {} |",
            i + 1,
            seed1[i],
            cell(&ours3),
            seed2[i],
            cell(&ours5)
        ));
    }
    lines.push(format!(
        "\n2π = {:.4}. 100 simplex iterations per step (as the seed, whose simplex stops near \
         1e-4); run to convergence, every step of either degree gives 2π. The divergence of \
         Table 2 is not reproduced: the seed attributes it to the control polygon moving a lot \
         at high degree without a constraint against it; here the re-fit keeps the seed's fixed \
         coordinates (x0 = x1 = y0 = yn = 0, xn = 1) and least squares on the adapted \
         parameters, and the degree-5 iteration stays at the half circle.",
        2.0 * PI
    ));
    Ok(lines)
}

/// Runs the reproduction and prints the tables.
pub(crate) fn run(root: &Path) -> Result<(), String> {
    println!("## Thesis Table 6.1: selective eraser of curvature extrema (chord 1 m)\n");
    println!(
        "Closest curve over degrees 3–5 with at most the thesis's control points and extrema; \
         deviation = largest distance from a database point to the curve; curve → data = \
         largest distance from the curve to the polyline of the points; extrema checked by \
         dense sampling of the curvature.\n"
    );
    println!(
        "| airfoil | thesis settings | thesis (mm) | ours (mm) | curve → data (mm) | ours / thesis | extrema | time |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for row in &TABLE_6_1 {
        println!("{}", table_row(root, row)?);
    }
    println!(
        "\n## Thesis §5.1: constrained approximation of functions (cost ½‖Ax − b‖², 11 → 200 coefficients)\n"
    );
    println!("| experiment | | thesis | ours |");
    println!("|---|---|---|---|");
    for line in section_5_1()? {
        println!("{line}");
    }
    println!("\n## Seed 000 §3: J = P²/A with adaptive parametrisation (n = 10, N = 10)\n");
    for line in seed_tables()? {
        println!("{line}");
    }
    Ok(())
}
