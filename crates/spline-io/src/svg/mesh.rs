//! Shaded SVG pictures of triangle meshes, with curves and points drawn over them (the
//! curvature features of a surface: [`feature_overlays`]).

use nalgebra::Vector3;
use spline_algebra::SurfaceFeatureLines;
use spline_geom::TriangleMesh;
use std::fmt::Write;

/// The viewpoint and style of [`mesh_svg`]: an orthographic view from the
/// direction given by azimuth (about `z`, from `x`) and elevation (above the `xy` plane),
/// in degrees.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshView {
    /// Azimuth of the viewer in degrees.
    pub azimuth: f64,
    /// Elevation of the viewer in degrees.
    pub elevation: f64,
    /// Width of the picture in pixels.
    pub width: f64,
    /// Fill colour of lit triangles, as RGB.
    pub color: [u8; 3],
    /// Draw the triangle edges.
    pub wireframe: bool,
    /// Optional caption.
    pub title: Option<String>,
}

impl Default for MeshView {
    fn default() -> Self {
        Self {
            azimuth: 30.0,
            elevation: 25.0,
            width: 600.0,
            color: [70, 130, 200],
            wireframe: true,
            title: None,
        }
    }
}

/// An SVG picture of a mesh: orthographic projection, triangles painted back to front with
/// Lambert shading (two-sided); back faces are skipped when the mesh is closed.
#[must_use]
pub fn mesh_svg(mesh: &TriangleMesh, view: &MeshView) -> String {
    mesh_svg_with(mesh, view, &[])
}

/// [`mesh_svg`] with curves and points drawn over the surface (feature
/// lines, umbilics): each segment and point is painted in depth order with the
/// triangles, slightly in front of them, so that the surface hides what lies behind it.
#[must_use]
pub fn mesh_svg_with(mesh: &TriangleMesh, view: &MeshView, overlays: &[SvgOverlay]) -> String {
    let (az, el) = (view.azimuth.to_radians(), view.elevation.to_radians());
    let eye = Vector3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
    let right = Vector3::z().cross(&eye);
    let right = if right.norm() > 1e-12 {
        right.normalize()
    } else {
        Vector3::y()
    };
    let up = eye.cross(&right);
    let light = (eye + up * 0.6 + right * 0.4).normalize();
    let closed = mesh.boundary_edges() == 0 && !mesh.triangles.is_empty();
    let project = |p: &Vector3<f64>| (p.dot(&right), p.dot(&up), p.dot(&eye));
    let mut faces: Vec<Face> = mesh
        .triangles
        .iter()
        .filter_map(|t| {
            let n = mesh.face_normal(t);
            let len = n.norm();
            if len == 0.0 || (closed && n.dot(&eye) < 0.0) {
                return None;
            }
            let corners = t.map(|k| project(&mesh.vertices[k]));
            let depth = (corners[0].2 + corners[1].2 + corners[2].2) / 3.0;
            let shade = 0.25 + 0.75 * (n.dot(&light) / len).abs();
            Some(Face {
                depth,
                corners: corners.map(|c| (c.0, c.1)),
                shade,
            })
        })
        .collect();
    // In front of every triangle it lies on: the largest depth spread of a triangle.
    let bias = mesh
        .triangles
        .iter()
        .map(|t| {
            let d = t.map(|k| project(&mesh.vertices[k]).2);
            d[0].max(d[1]).max(d[2]) - d[0].min(d[1]).min(d[2])
        })
        .fold(0.0f64, f64::max);
    let mut strokes: Vec<Stroke> = Vec::new();
    for (k, overlay) in overlays.iter().enumerate() {
        for w in overlay.points.windows(2) {
            let (a, b) = (project(&w[0]), project(&w[1]));
            strokes.push((0.5 * (a.2 + b.2) + bias, k, [(a.0, a.1), (b.0, b.1)]));
        }
        if overlay.points.len() == 1 || overlay.markers {
            for q in &overlay.points {
                let a = project(q);
                strokes.push((a.2 + bias, k, [(a.0, a.1), (a.0, a.1)]));
            }
        }
    }
    strokes.sort_by(|a, b| a.0.total_cmp(&b.0));
    faces.sort_by(|a, b| a.depth.total_cmp(&b.depth));
    let (mut xmin, mut xmax, mut ymin, mut ymax) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for v in &mesh.vertices {
        let (x, y, _) = project(v);
        xmin = xmin.min(x);
        xmax = xmax.max(x);
        ymin = ymin.min(y);
        ymax = ymax.max(y);
    }
    if xmin > xmax {
        (xmin, xmax, ymin, ymax) = (0.0, 1.0, 0.0, 1.0);
    }
    let margin = 10.0;
    let extent = (xmax - xmin).max(ymax - ymin).max(1e-12);
    let scale = (view.width - 2.0 * margin) / extent;
    let height =
        (ymax - ymin) * scale + 2.0 * margin + if view.title.is_some() { 20.0 } else { 0.0 };
    let top = if view.title.is_some() { 20.0 } else { 0.0 };
    let map = |(x, y): (f64, f64)| {
        (
            margin + (x - xmin) * scale,
            top + margin + (ymax - y) * scale,
        )
    };
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{height:.0}" viewBox="0 0 {w:.0} {height:.0}">"#,
        w = view.width
    );
    out.push_str("<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
    let stroke_width = if view.wireframe { 0.4 } else { 0.6 };
    let mut pending = strokes.iter().peekable();
    let mut draw_strokes = |out: &mut String, depth: f64| {
        while let Some((_, k, [a, b])) = pending.next_if(|s| s.0 <= depth) {
            let o = &overlays[*k];
            let [r, g, bl] = o.color;
            let ((x0, y0), (x1, y1)) = (map(*a), map(*b));
            if a == b {
                let _ = writeln!(
                    out,
                    r#"<circle cx="{x0:.2}" cy="{y0:.2}" r="{:.1}" fill="rgb({r},{g},{bl})" stroke="black" stroke-width="0.6"/>"#,
                    2.0 * o.width
                );
            } else {
                let _ = writeln!(
                    out,
                    r#"<line x1="{x0:.2}" y1="{y0:.2}" x2="{x1:.2}" y2="{y1:.2}" stroke="rgb({r},{g},{bl})" stroke-width="{:.1}" stroke-linecap="round"/>"#,
                    o.width
                );
            }
        }
    };
    for Face {
        corners,
        shade,
        depth,
    } in &faces
    {
        draw_strokes(&mut out, *depth);
        let [r, g, b] = view.color.map(|c| {
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let v = (f64::from(c) * shade).round().clamp(0.0, 255.0) as u8;
            v
        });
        let pts: Vec<String> = corners
            .iter()
            .map(|&c| {
                let (x, y) = map(c);
                format!("{x:.2},{y:.2}")
            })
            .collect();
        let stroke = if view.wireframe {
            "#1b2a3a".to_owned()
        } else {
            format!("rgb({r},{g},{b})")
        };
        let _ = writeln!(
            out,
            r#"<polygon points="{}" fill="rgb({r},{g},{b})" stroke="{stroke}" stroke-width="{stroke_width}" stroke-linejoin="round"/>"#,
            pts.join(" ")
        );
    }
    draw_strokes(&mut out, f64::INFINITY);
    if let Some(title) = &view.title {
        let escaped = title
            .replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;");
        let _ = writeln!(
            out,
            r##"<text x="{margin}" y="18" font-family="sans-serif" font-size="14" fill="#333">{escaped}</text>"##
        );
    }
    out.push_str("</svg>\n");
    out
}

/// A curve (or, with `markers`, points) drawn over a mesh by [`mesh_svg_with`].
#[derive(Clone, Debug, PartialEq)]
pub struct SvgOverlay {
    /// The points in space: a polyline, or single points.
    pub points: Vec<Vector3<f64>>,
    /// The colour, as RGB.
    pub color: [u8; 3],
    /// The stroke width in pixels (points are drawn with twice this radius).
    pub width: f64,
    /// Draw every point as a dot (and the segments between them unless there is one point).
    pub markers: bool,
}

/// A projected overlay segment (equal ends: a point): depth, overlay index, screen ends.
type Stroke = (f64, usize, [(f64, f64); 2]);

/// A projected triangle of an SVG picture.
struct Face {
    /// Mean distance towards the viewer.
    depth: f64,
    /// Screen coordinates of the corners.
    corners: [(f64, f64); 3],
    /// Lambert intensity.
    shade: f64,
}

/// The colour of parabolic lines in [`feature_overlays`].
pub const PARABOLIC_COLOUR: [u8; 3] = [235, 110, 20];
/// The colour of red ridges (of `κ₂`) in [`feature_overlays`].
pub const RED_RIDGE_COLOUR: [u8; 3] = [215, 30, 40];
/// The colour of blue ridges (of `κ₁`) in [`feature_overlays`].
pub const BLUE_RIDGE_COLOUR: [u8; 3] = [30, 80, 220];
/// The colour of umbilics in [`feature_overlays`].
pub const UMBILIC_COLOUR: [u8; 3] = [250, 220, 0];

/// The curvature features of a surface ([`spline_algebra::surface_feature_lines`]) as
/// overlays of its picture: parabolic lines in orange, ridges in red (of `κ₂`) and blue (of
/// `κ₁`), umbilics as yellow dots.
#[must_use]
pub fn feature_overlays(features: &SurfaceFeatureLines) -> Vec<SvgOverlay> {
    let line = |points: &Vec<Vector3<f64>>, color: [u8; 3], width: f64| SvgOverlay {
        points: points.clone(),
        color,
        width,
        markers: false,
    };
    let mut overlays = Vec::new();
    overlays.extend(
        features
            .parabolic
            .iter()
            .map(|c| line(c, PARABOLIC_COLOUR, 2.5)),
    );
    overlays.extend(
        features
            .red_ridges
            .iter()
            .map(|c| line(c, RED_RIDGE_COLOUR, 2.0)),
    );
    overlays.extend(
        features
            .blue_ridges
            .iter()
            .map(|c| line(c, BLUE_RIDGE_COLOUR, 2.0)),
    );
    overlays.extend(features.umbilics.iter().map(|p| SvgOverlay {
        points: vec![*p],
        color: UMBILIC_COLOUR,
        width: 3.0,
        markers: true,
    }));
    overlays
}
