//! The campaign's material for the subcommands added after its first version (issue 25: "a
//! fuzzing campaign over these subcommands"): calculus and roots of functions, N-dimensional
//! splines, offsets, arc length, degree reduction, smoothing splines, surface features,
//! shape optimisation, CAD files, and the surface constructions with reports.

use super::templates::SeedWriter;

/// The newer subcommands, after [`super::templates::SUBCOMMANDS`] in the order of the cases.
pub(super) const NEWER_SUBCOMMANDS: &[&str] = &[
    "antiderivative",
    "integrate",
    "roots",
    "nd-eval",
    "nd-interpolate",
    "optimize",
    "surface-features",
    "offset",
    "arclength",
    "reduce",
    "smoothing",
    "export",
    "import",
    "make-surfaces",
];

/// The seed files the newer templates read, made with the tool (after the first seeds).
pub(super) fn make_newer_seed_files(seeds: &SeedWriter<'_>) -> Result<(), String> {
    let write = |name: &str, text: &str| seeds.write(name, text);
    write(
        "space.json",
        r#"{"degree":3,"knots":[0,0,0,0,0.5,1,1,1,1],"control_points":[[0,0,0],[1,1,0.5],[2,0,1],[3,1,0.5],[4,0,0]]}"#,
    )?;
    write(
        "bicubic.json",
        r#"{"degree":[3,3],"knots":[[0,0,0,0,1,1,1,1],[0,0,0,0,1,1,1,1]],"control_points":[[[0,0,0],[0,1,0.2],[0,2,-0.1],[0,3,0]],[[1,0,0.3],[1,1,0.8],[1,2,0.1],[1,3,0.2]],[[2,0,-0.2],[2,1,0.1],[2,2,0.9],[2,3,0]],[[3,0,0],[3,1,0.3],[3,2,0.1],[3,3,0.4]]]}"#,
    )?;
    for (name, a, b) in [
        ("bottom.json", "[0,0,0]", "[2,0,0]"),
        ("top.json", "[0,2,0]", "[2,2,0.5]"),
        ("left.json", "[0,0,0]", "[0,2,0]"),
        ("right.json", "[2,0,0]", "[2,2,0.5]"),
    ] {
        write(
            name,
            &format!(r#"{{"degree":1,"knots":[0,0,1,1],"control_points":[{a},{b}]}}"#),
        )?;
    }
    write(
        "rational_bottom.json",
        r#"{"degree":2,"knots":[0,0,0,1,1,1],"control_points":[[0,0,0],[1,-0.5,0.3],[2,0,0]],"weights":[1,0.4,1]}"#,
    )?;
    let run = |args: &[&str]| seeds.run(args, None);
    run(&[
        "export",
        "seed.step",
        "cubic.json",
        "sphere.json",
        "space.json",
    ])?;
    run(&["export", "seed.igs", "circle.json", "torus.json"])?;
    seeds.run(
        &[
            "nd-interpolate",
            "--grid",
            "[[0,1,2,3],[0,1,2,3,4]]",
            "--values",
            "[[0,1,0,1,0],[1,2,1,2,1],[0,1,3,1,0],[2,1,0,1,2]]",
        ],
        Some("nd.json"),
    )
}

/// Valid command lines of the newer subcommands.
pub(super) fn newer_templates(sub: &str) -> Vec<Vec<&'static str>> {
    let v = |args: &[&'static str]| args.to_vec();
    match sub {
        "antiderivative" => vec![
            v(&["antiderivative", "f.json", "--order", "2"]),
            v(&["antiderivative", "cubic.json"]),
        ],
        "integrate" => vec![
            v(&["integrate", "f.json", "--from", "0", "--to", "1"]),
            v(&[
                "integrate",
                "cubic.json",
                "--from",
                "-1",
                "--to",
                "4",
                "--extrapolate",
                "periodic",
            ]),
        ],
        "roots" => vec![
            v(&["roots", "f.json"]),
            v(&["roots", "cubic.json", "--coordinate", "1"]),
        ],
        "nd-eval" => vec![
            v(&["nd-eval", "nd.json", "--at", "[[0.5,1.5],[3,4]]"]),
            v(&["nd-eval", "nd.json", "--at", "[[1,1]]", "--nu", "[1,0]"]),
        ],
        "nd-interpolate" => vec![
            v(&[
                "nd-interpolate",
                "--grid",
                "[[0,1,2,3]]",
                "--values",
                "[0,1,0,2]",
            ]),
            v(&[
                "nd-interpolate",
                "--grid",
                "[[0,1,2],[0,1,2]]",
                "--values",
                "[[0,1,2],[1,2,3],[2,3,5]]",
                "--degree",
                "2",
            ]),
        ],
        "optimize" => vec![v(&[
            "optimize",
            "--control-points",
            "8",
            "--iterations",
            "2",
        ])],
        "surface-features" => vec![
            v(&["surface-features", "bicubic.json"]),
            v(&["surface-features", "torus.json", "--samples", "4"]),
        ],
        "offset" => vec![
            v(&["offset", "cubic.json", "--distance", "0.05"]),
            v(&["offset", "arc.json", "--distance", "-0.5"]),
            v(&[
                "offset",
                "space.json",
                "--distance",
                "0.1",
                "--direction",
                "0,0,1",
            ]),
            v(&[
                "offset",
                "bicubic.json",
                "--distance",
                "0.05",
                "--tolerance",
                "1e-4",
            ]),
            v(&["offset", "torus.json", "--distance", "0.2"]),
        ],
        "arclength" => vec![
            v(&["arclength", "cubic.json"]),
            v(&["arclength", "circle.json", "--at-length", "[0,1,3]"]),
            v(&[
                "arclength",
                "space.json",
                "--reparametrize",
                "--tolerance",
                "1e-6",
            ]),
        ],
        "reduce" => vec![
            v(&["reduce", "cubic.json", "--tolerance", "0.1", "--refine"]),
            v(&[
                "reduce",
                "space.json",
                "--tolerance",
                "1e-3",
                "--times",
                "1",
            ]),
        ],
        "smoothing" => vec![
            v(&[
                "smoothing",
                "--x",
                "[0,1,2,3,4,5,6]",
                "--y",
                "[0,0.8,0.9,0.1,-0.7,-1,-0.3]",
                "--gcv",
            ]),
            v(&[
                "smoothing",
                "--x",
                "[0,1,2,3,4,5,6]",
                "--y",
                "[[0,1],[1,0],[2,1],[3,0],[4,1],[5,0],[6,1]]",
                "--lambda",
                "0.1",
            ]),
            v(&[
                "smoothing",
                "--x",
                "[0,1,2,3,4,5,6,7,8]",
                "--y",
                "[0,1,0,1,0,1,0,1,0]",
                "--residual",
                "0.5",
            ]),
        ],
        "export" => vec![
            v(&["export", "OUT.step", "cubic.json", "torus.json"]),
            v(&["export", "OUT.igs", "space.json", "bicubic.json"]),
        ],
        "import" => vec![v(&["import", "seed.step"]), v(&["import", "seed.igs"])],
        "make-surfaces" => vec![
            v(&[
                "make",
                "coons",
                "--curves",
                "bottom.json",
                "top.json",
                "left.json",
                "right.json",
            ]),
            v(&[
                "make",
                "coons",
                "--curves",
                "rational_bottom.json",
                "top.json",
                "left.json",
                "right.json",
            ]),
            v(&["make", "skin", "--curves", "circle.json", "arc.json"]),
            v(&[
                "make",
                "gordon",
                "--u-curves",
                "bottom.json",
                "top.json",
                "--v-curves",
                "left.json",
                "right.json",
            ]),
            v(&[
                "make",
                "sweep",
                "--profile",
                "line3.json",
                "--path",
                "space.json",
                "--sections",
                "4",
            ]),
        ],
        _ => Vec::new(),
    }
}
