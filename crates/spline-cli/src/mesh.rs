//! `spline mesh`: triangulate a surface of either kind into an OBJ, OFF or SVG file
//! ([`TriangleMesh::from_surface`]).

use crate::io::{self, Pt};
use crate::objects::{Object, read_object, surface3};
use clap::Args;
use nalgebra::Vector3;
use serde_json::json;
use spline_core::{Error, ErrorKind, Result};
use spline_geom::TriangleMesh;
use spline_io::svg::{MeshView, feature_overlays, mesh_svg, mesh_svg_with};

fn invalid(message: impl Into<String>) -> Error {
    Error::new(ErrorKind::InvalidArgument, message)
}

/// Triangulate a surface and write the mesh.
#[derive(Args)]
pub struct MeshArgs {
    /// Surface file (JSON: a B-spline or NURBS surface with 1 to 3 coordinates), or - for
    /// standard input.
    surface: String,
    /// Output file; the extension picks the format: FILE.obj (Wavefront, with vertex
    /// normals), FILE.off (geomview OFF) or FILE.svg (a shaded picture).
    #[arg(short, long)]
    output: String,
    /// Number of equal parameter steps in u (every interior knot is added as well).
    #[arg(long, default_value_t = 32)]
    segments_u: usize,
    /// Number of equal parameter steps in v (every interior knot is added as well).
    #[arg(long, default_value_t = 32)]
    segments_v: usize,
    /// With an SVG output of a 3-D surface: draw its parabolic lines (orange) and umbilics
    /// (yellow dots) over it (see `spline surface-features`).
    #[arg(long)]
    features: bool,
}

#[derive(Clone, Copy)]
enum MeshFormat {
    Obj,
    Off,
    Svg,
}

fn mesh_format(path: &str) -> Result<MeshFormat> {
    let ext = std::path::Path::new(path)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("obj") => Ok(MeshFormat::Obj),
        Some("off") => Ok(MeshFormat::Off),
        Some("svg") => Ok(MeshFormat::Svg),
        _ => Err(
            invalid(format!("{path}: the output must end in .obj, .off or .svg")).with_file(path),
        ),
    }
}

/// `spline mesh SURFACE -o FILE`: writes the mesh and prints
/// `{"output", "vertices", "triangles"}`.
pub fn mesh(args: &MeshArgs) -> Result<()> {
    let format = mesh_format(&args.output)?;
    if args.features && !matches!(format, MeshFormat::Svg) {
        return Err(invalid(
            "--features draws on an SVG picture: the output must end in .svg",
        ));
    }
    let object = read_object(&args.surface)?;
    let dim = match &object {
        Object::Surface(s) => s.dim,
        Object::NurbsSurface(s) => s.dim,
        Object::Curve(_) | Object::Nurbs(_) => {
            return Err(invalid(format!(
                "{}: mesh needs a surface (degree [p, q])",
                args.surface
            ))
            .with_file(&args.surface));
        }
    };
    if dim > 3 {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!("meshes are built from surfaces with 1 to 3 coordinates, got {dim}"),
        ));
    }
    // Open the output before the work, so that a bad path fails at once.
    let file = io::create_file(&args.output)?;
    let to3 = |p: &Pt| Vector3::new(p[0], p[1], p[2]);
    let (nu, nv) = (args.segments_u, args.segments_v);
    let mesh = match &object {
        Object::Surface(s) => TriangleMesh::from_surface(&s.value.map_control_points(to3), nu, nv)?,
        Object::NurbsSurface(s) => {
            TriangleMesh::from_surface(&s.value.map_control_points(to3), nu, nv)?
        }
        Object::Curve(_) | Object::Nurbs(_) => unreachable!("checked above"),
    };
    let text = match format {
        MeshFormat::Obj => spline_io::obj::write_obj(&mesh),
        MeshFormat::Off => spline_io::off::write_off(&mesh),
        MeshFormat::Svg if args.features => mesh_svg_with(
            &mesh,
            &MeshView::default(),
            &spline_algebra::surface_feature_lines(
                &surface3(&object, &args.surface, "--features")?,
                8,
            )
            .map(|lines| feature_overlays(&lines))
            .map_err(|e| e.context(&args.surface))?,
        ),
        MeshFormat::Svg => mesh_svg(&mesh, &MeshView::default()),
    };
    io::write_file(file, &args.output, text.as_bytes())?;
    io::print_json(&json!({
        "output": args.output,
        "vertices": mesh.vertices.len(),
        "triangles": mesh.triangles.len(),
    }))
}
