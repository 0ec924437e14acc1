//! The campaign's starting material: the subcommands, the seed files made with the tool
//! itself, and the valid command lines that the cases mutate.

use std::path::Path;
use std::process::Command;

/// The subcommands the campaign runs, in the order of the cases.
pub(super) const SUBCOMMANDS: &[&str] = &[
    "basis",
    "eval",
    "insert",
    "refine",
    "remove",
    "elevate",
    "split",
    "bezier",
    "derivative",
    "plot",
    "product",
    "curvature",
    "features",
    "interpolate",
    "natural",
    "approximate",
    "smooth",
    "make",
    "mesh",
    "closest",
    "intersect",
    "approximate-surface",
];

/// Writes the campaign's seed files into its directory, by hand or with the tool.
pub(super) struct SeedWriter<'a> {
    /// The tool.
    pub(super) binary: &'a Path,
    /// The campaign's directory (the tool runs there).
    pub(super) dir: &'a Path,
}

impl SeedWriter<'_> {
    /// Writes `text` to the file `name`.
    pub(super) fn write(&self, name: &str, text: &str) -> Result<(), String> {
        std::fs::write(self.dir.join(name), text).map_err(|e| format!("seed {name}: {e}"))
    }

    /// Runs the tool with `args` in the directory; its standard output goes to the file
    /// `stdout_to` when given (the files it writes itself stay where it puts them).
    pub(super) fn run(&self, args: &[&str], stdout_to: Option<&str>) -> Result<(), String> {
        let out = Command::new(self.binary)
            .args(args)
            .current_dir(self.dir)
            .output()
            .map_err(|e| format!("cannot run {}: {e}", self.binary.display()))?;
        if !out.status.success() {
            return Err(format!(
                "seed {args:?}: {}",
                String::from_utf8_lossy(&out.stderr)
            ));
        }
        match stdout_to {
            Some(name) => std::fs::write(self.dir.join(name), &out.stdout)
                .map_err(|e| format!("seed {name}: {e}")),
            None => Ok(()),
        }
    }
}

/// The seed files of the campaign, made with the tool itself.
pub(super) fn make_seed_files(seeds: &SeedWriter<'_>, root: &Path) -> Result<(), String> {
    let write = |name: &str, text: &str| seeds.write(name, text);
    let run = |args: &[&str], name: &str| seeds.run(args, Some(name));
    write(
        "line.json",
        r#"{"degree":1,"knots":[0.0,0.0,1.0,1.0],"control_points":[[0.0,0.0],[1.0,1.0]]}"#,
    )?;
    write(
        "cubic.json",
        r#"{"degree":3,"knots":[0.0,0.0,0.0,0.0,1.0,2.0,3.0,3.0,3.0,3.0],"control_points":[[0.41705,0.10673],[0.28802,0.60088],[0.90553,0.46053],[1.3203,0.79678],[1.8041,0.63012],[1.477,0.13012]]}"#,
    )?;
    write(
        "f.json",
        r#"{"degree":2,"knots":[0.0,0.0,0.0,0.5,1.0,1.0,1.0],"control_points":[[1.0],[-0.5],[2.0],[0.25]]}"#,
    )?;
    write(
        "g.json",
        r#"{"degree":1,"knots":[0.0,0.0,0.3,1.0,1.0],"control_points":[[0.5],[1.5],[-1.0]]}"#,
    )?;
    write(
        "points.json",
        "[[0.0,0.0],[1.0,2.0],[2.5,2.0],[4.0,0.5],[5.0,1.5],[6.0,0.0],[7.5,-1.0]]",
    )?;
    write(
        "points.txt",
        "# x y\n0 0\n1 2\n2.5 2\n4 0.5\n5 1.5\n6 0\n7.5 -1\n",
    )?;
    let airfoil = std::fs::read_to_string(root.join("data/airfoils/clarkv.dat"))
        .map_err(|e| format!("cannot read the airfoil: {e}"))?;
    write("airfoil.dat", &airfoil)?;
    run(
        &["make", "circle", "--center", "[0,0]", "--radius", "1"],
        "circle.json",
    )?;
    run(
        &[
            "make", "arc", "--center", "[0,0]", "--radius", "2", "--sweep", "135",
        ],
        "arc.json",
    )?;
    run(
        &["make", "sphere", "--center", "[0,0,0]", "--radius", "1"],
        "sphere.json",
    )?;
    run(
        &[
            "make", "torus", "--center", "[0,0,0]", "--major", "2", "--minor", "0.5",
        ],
        "torus.json",
    )?;
    run(&["make", "ruled", "cubic.json", "line.json"], "ruled.json")?;
    // Space curves and points for the surface commands.
    write(
        "line3.json",
        r#"{"degree":1,"knots":[0.0,0.0,1.0,1.0],"control_points":[[-2.0,0.1,0.2],[2.0,0.3,-0.1]]}"#,
    )?;
    write(
        "cloud.json",
        "[[0,0,0],[1,0,0.1],[2,0,0],[0,1,0.2],[1,1,0.3],[2,1,0.1],[0,2,0],[1,2,0.2],[2,2,0.1],[0.5,0.5,0.1],[1.5,0.5,0.2],[0.5,1.5,0.1],[1.5,1.5,0.2],[1,0.5,0.15],[0.5,1,0.12],[1.5,1,0.2]]",
    )?;
    Ok(())
}

/// Valid command lines: every subcommand on every kind of object it takes.
pub(super) fn templates(sub: &str) -> Vec<Vec<&'static str>> {
    let v = |args: &[&'static str]| args.to_vec();
    match sub {
        "basis" => vec![
            v(&[
                "basis",
                "--degree",
                "3",
                "--knots",
                "[0,0,0,0,1,2,3,3,3,3]",
                "--at",
                "[0.5,1.5,3]",
                "--derivatives",
                "2",
            ]),
            v(&[
                "basis",
                "--degree",
                "1",
                "--knots",
                "[0,0,1,1]",
                "--at",
                "[0.5]",
            ]),
        ],
        "eval" => vec![
            v(&[
                "eval",
                "cubic.json",
                "--at",
                "[0,0.5,1.5,3]",
                "--derivatives",
                "2",
            ]),
            v(&["eval", "line.json", "--at", "[0.5]", "--derivatives", "1"]),
            v(&[
                "eval",
                "circle.json",
                "--at",
                "[0,0.3,1]",
                "--derivatives",
                "3",
            ]),
            v(&[
                "eval",
                "sphere.json",
                "--at",
                "[[0.5,0.5],[0,1]]",
                "--derivatives",
                "1",
            ]),
            v(&[
                "eval",
                "ruled.json",
                "--at",
                "[[0.5,0.5]]",
                "--derivatives",
                "2",
            ]),
        ],
        "insert" => vec![
            v(&["insert", "cubic.json", "--knot", "1.5", "--times", "2"]),
            v(&["insert", "line.json", "--knot", "0.5", "--times", "1"]),
            v(&["insert", "circle.json", "--knot", "0.3"]),
            v(&["insert", "sphere.json", "--knot", "0.3", "--direction", "v"]),
        ],
        "refine" => vec![
            v(&["refine", "cubic.json", "--knots", "[0.5,1.5,1.5,2.5]"]),
            v(&["refine", "arc.json", "--knots", "[0.2,0.7]"]),
            v(&[
                "refine",
                "torus.json",
                "--knots",
                "[0.1]",
                "--direction",
                "u",
            ]),
            v(&["refine", "line.json", "--knots", "[]"]),
        ],
        "remove" => vec![
            v(&[
                "remove",
                "cubic.json",
                "--knot",
                "1",
                "--times",
                "1",
                "--tolerance",
                "1",
            ]),
            v(&["remove", "circle.json", "--knot", "0.25", "--times", "1"]),
            v(&["remove", "sphere.json", "--knot", "0.5", "--direction", "u"]),
        ],
        "elevate" => vec![
            v(&["elevate", "cubic.json", "--times", "2"]),
            v(&["elevate", "line.json"]),
            v(&["elevate", "circle.json", "--times", "1"]),
            v(&["elevate", "sphere.json", "--times", "1", "--direction", "v"]),
        ],
        "split" => vec![
            v(&["split", "cubic.json", "--at", "1.5"]),
            v(&["split", "arc.json", "--at", "0.5"]),
            v(&["split", "torus.json", "--at", "0.5", "--direction", "v"]),
        ],
        "bezier" => vec![
            v(&["bezier", "cubic.json"]),
            v(&["bezier", "circle.json"]),
            v(&["bezier", "sphere.json"]),
        ],
        "derivative" => vec![
            v(&["derivative", "cubic.json", "--order", "2"]),
            v(&["derivative", "ruled.json", "--order", "1"]),
            v(&["derivative", "f.json"]),
        ],
        "plot" => vec![
            v(&[
                "plot",
                "cubic.json",
                "-o",
                "OUT.svg",
                "--comb",
                "--features",
            ]),
            v(&[
                "plot",
                "circle.json",
                "line.json",
                "-o",
                "OUT.svg",
                "--comb",
            ]),
        ],
        "product" => vec![
            v(&["product", "f.json", "g.json", "--jacobian"]),
            v(&["product", "f.json", "f.json"]),
        ],
        "curvature" => vec![
            v(&["curvature", "cubic.json", "--at", "[0,1.5,3]"]),
            v(&["curvature", "circle.json", "--at", "[0,0.5,1]"]),
        ],
        "features" => vec![
            v(&["features", "cubic.json"]),
            v(&["features", "line.json"]),
        ],
        "interpolate" => vec![
            v(&["interpolate", "points.json", "--degree", "3"]),
            v(&[
                "interpolate",
                "points.txt",
                "--degree",
                "2",
                "--parametrization",
                "centripetal",
                "--report",
            ]),
            v(&["interpolate", "points.json", "--degree", "3", "--closed"]),
            v(&[
                "interpolate",
                "points.json",
                "--degree",
                "3",
                "--start-derivative",
                "[1,0]",
                "--end-derivative",
                "[0,1]",
            ]),
        ],
        "natural" => vec![
            v(&["natural", "--x", "[0,1,2.5,4,5]", "--y", "[0,1,0.5,2,1]"]),
            v(&[
                "natural",
                "--x",
                "[0,1,2,3,4,5]",
                "--y",
                "[[0,1],[1,0],[2,2],[3,1],[4,0],[5,1]]",
                "--order",
                "6",
            ]),
        ],
        "approximate" => vec![
            v(&[
                "approximate",
                "points.json",
                "--degree",
                "2",
                "--control-points",
                "5",
            ]),
            v(&[
                "approximate",
                "airfoil.dat",
                "--degree",
                "3",
                "--control-points",
                "12",
                "--correct-parameters",
                "5",
                "--report",
            ]),
            v(&[
                "approximate",
                "points.txt",
                "--degree",
                "3",
                "--control-points",
                "5",
                "--smoothing",
                "0.1",
                "--method",
                "qr",
                "--pin-ends",
            ]),
        ],
        "smooth" => vec![v(&[
            "smooth",
            "airfoil.dat",
            "--control-points",
            "12",
            "--curvature-extrema",
            "1",
        ])],
        "make" => vec![
            v(&["make", "circle", "--center", "[0,0]", "--radius", "1"]),
            v(&[
                "make",
                "arc",
                "--center",
                "[0,0,0]",
                "--radius",
                "2",
                "--sweep",
                "200",
                "--max-piece",
                "60",
            ]),
            v(&[
                "make", "conic", "--p0", "[0,0]", "--p1", "[1,1]", "--p2", "[2,0]", "--w1", "0.5",
            ]),
            v(&["make", "sphere", "--center", "[0,0,0]", "--radius", "2"]),
            v(&[
                "make", "torus", "--center", "[0,0,0]", "--major", "3", "--minor", "1",
            ]),
            v(&["make", "extrude", "cubic.json", "--vector", "[0,0]"]),
            v(&["make", "revolve", "line.json", "--angle", "90"]),
            v(&["make", "cone", "circle.json", "--apex", "[0,1]"]),
            v(&["make", "ruled", "cubic.json", "line.json"]),
        ],
        "mesh" => vec![
            v(&[
                "mesh",
                "sphere.json",
                "-o",
                "OUT.obj",
                "--segments-u",
                "8",
                "--segments-v",
                "8",
            ]),
            v(&["mesh", "torus.json", "-o", "OUT.off"]),
            v(&["mesh", "ruled.json", "-o", "OUT.svg", "--segments-u", "4"]),
        ],
        "closest" => vec![
            v(&["closest", "sphere.json", "--points", "[[3,4,0],[0,0,5]]"]),
            v(&["closest", "torus.json", "--points", "[[0,0,0]]"]),
            v(&["closest", "line3.json", "--points", "[[0,1,0]]"]),
        ],
        "intersect" => vec![
            v(&["intersect", "line3.json", "sphere.json"]),
            v(&[
                "intersect",
                "sphere.json",
                "torus.json",
                "--tolerance",
                "1e-3",
            ]),
        ],
        "approximate-surface" => vec![
            v(&[
                "approximate-surface",
                "cloud.json",
                "--control-points",
                "[4,4]",
            ]),
            v(&[
                "approximate-surface",
                "cloud.json",
                "--control-points",
                "[5,5]",
                "--smoothing",
                "1e-3",
            ]),
        ],
        _ => Vec::new(),
    }
}
