//! OFF meshes (the geomview format of seed 000): `OFF`, the counts `V F E`, `V` vertex lines,
//! then `F` face lines `n i₁ … iₙ` (0-based).

use nalgebra::Vector3;
use spline_core::{Error, ErrorKind, Result};
use spline_geom::TriangleMesh;
use std::fmt::Write;

/// The mesh in the OFF format of geomview: `OFF`, the counts `V F 0`, the vertices, then
/// `3 a b c` per triangle (0-based).
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::NurbsSurface;
/// use spline_io::off::write_off;
/// let mesh = NurbsSurface::sphere(Vector3::zeros(), 1.0)?.tessellate(16, 32)?;
/// assert!(write_off(&mesh).starts_with("OFF\n"));
/// # Ok::<(), spline_core::Error>(())
/// ```
#[must_use]
pub fn write_off(mesh: &TriangleMesh) -> String {
    let mut out = String::with_capacity(48 * (mesh.vertices.len() + mesh.triangles.len()));
    let _ = writeln!(
        out,
        "OFF\n{} {} 0",
        mesh.vertices.len(),
        mesh.triangles.len()
    );
    for v in &mesh.vertices {
        let _ = writeln!(out, "{} {} {}", v.x, v.y, v.z);
    }
    for t in &mesh.triangles {
        let _ = writeln!(out, "3 {} {} {}", t[0], t[1], t[2]);
    }
    out
}

/// Where the reader is in an OFF file.
enum Stage {
    /// Before the `OFF` keyword.
    Keyword,
    /// Before the counts.
    Counts,
    /// Reading vertices, then faces.
    Body,
}

/// Reads an OFF text: the keyword `OFF` (the counts may follow on its line), the counts
/// `V F E` (`E` is not used), `V` lines with the three coordinates of a vertex (further
/// numbers, such as a colour, are ignored), then `F` lines `n i₁ … iₙ` (0-based indices,
/// further numbers ignored); polygons are fanned into triangles. `#` starts a comment; blank
/// lines are skipped. The normals are computed ([`TriangleMesh::compute_normals`]). The
/// counts are checked against the lines, never used to reserve memory.
///
/// ```
/// let mesh = spline_io::off::read_off("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n")?;
/// assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::Parse`] for a file that does not start with `OFF`, counts that are not
/// integers, a vertex without three numbers, a face with fewer than three vertices or an
/// index of a vertex the file does not have, fewer or more lines than the counts say;
/// [`ErrorKind::NonFinite`] for a vertex that is not finite. Every message names the line.
pub fn read_off(text: &str) -> Result<TriangleMesh> {
    let mut stage = Stage::Keyword;
    let (mut nv, mut nf) = (0usize, 0usize);
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    let mut faces = 0usize;
    let mut last = 0;
    for (n, raw) in text.lines().enumerate() {
        let line_number = n + 1;
        last = line_number;
        let bad = |what: &str| Error::new(ErrorKind::Parse, format!("line {line_number}: {what}"));
        let mut words = raw
            .split('#')
            .next()
            .unwrap_or("")
            .split_whitespace()
            .peekable();
        if words.peek().is_none() {
            continue;
        }
        if matches!(stage, Stage::Keyword) {
            if words.next() != Some("OFF") {
                return Err(bad("an OFF file starts with the keyword OFF"));
            }
            stage = Stage::Counts;
            if words.peek().is_none() {
                continue;
            }
        }
        if matches!(stage, Stage::Counts) {
            let mut count = || words.next().and_then(|w| w.parse::<usize>().ok());
            match (count(), count()) {
                (Some(v), Some(f)) => (nv, nf) = (v, f),
                _ => return Err(bad("expected the counts of vertices, faces and edges")),
            }
            stage = Stage::Body;
            continue;
        }
        let numbers = |words: &mut dyn Iterator<Item = &str>, k: usize| -> Option<Vec<f64>> {
            words.take(k).map(|w| w.parse::<f64>().ok()).collect()
        };
        if vertices.len() < nv {
            let p = numbers(&mut words, 3)
                .filter(|c| c.len() == 3)
                .ok_or_else(|| bad("a vertex needs three numbers"))?;
            if !p.iter().all(|x| x.is_finite()) {
                return Err(Error::new(
                    ErrorKind::NonFinite,
                    format!("line {line_number}: the vertex is not finite"),
                ));
            }
            vertices.push(Vector3::new(p[0], p[1], p[2]));
        } else if faces < nf {
            let k = words
                .next()
                .and_then(|w| w.parse::<usize>().ok())
                .filter(|&k| k >= 3)
                .ok_or_else(|| bad("a face starts with its number of vertices, at least 3"))?;
            let mut corners = Vec::new();
            for _ in 0..k {
                let i = words
                    .next()
                    .and_then(|w| w.parse::<usize>().ok())
                    .ok_or_else(|| bad("the face has fewer indices than it says"))?;
                if i >= nv {
                    return Err(bad(&format!(
                        "vertex {i} of a file with {nv} vertices (indices start at 0)"
                    )));
                }
                corners.push(i);
            }
            for j in 1..k - 1 {
                triangles.push([corners[0], corners[j], corners[j + 1]]);
            }
            faces += 1;
        } else {
            return Err(bad(&format!(
                "more lines than the {nv} vertices and {nf} faces the header gives"
            )));
        }
    }
    if matches!(stage, Stage::Keyword | Stage::Counts) {
        return Err(Error::new(
            ErrorKind::Parse,
            "an OFF file starts with the keyword OFF and the counts of vertices, faces and edges",
        ));
    }
    if vertices.len() < nv || faces < nf {
        return Err(Error::new(
            ErrorKind::Parse,
            format!(
                "line {last}: the file ends after {} of {nv} vertices and {faces} of {nf} faces",
                vertices.len()
            ),
        ));
    }
    let mut mesh = TriangleMesh {
        vertices,
        normals: Vec::new(),
        triangles,
    };
    mesh.compute_normals();
    Ok(mesh)
}
