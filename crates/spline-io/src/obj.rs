//! Wavefront OBJ meshes: triangle meshes written with their vertex normals, and read from
//! the `v`, `vn` and `f` statements of any OBJ file (polygons fanned into triangles).

use nalgebra::Vector3;
use spline_core::{Error, ErrorKind, Result};
use spline_geom::TriangleMesh;
use std::fmt::Write;

/// The mesh in Wavefront OBJ: a comment with the counts, `v` lines, `vn` lines, then
/// `f a//a b//b c//c` (1-based; a vertex's normal has its index). A mesh without one normal
/// per vertex is written without normals (`f a b c`).
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::NurbsSurface;
/// use spline_io::obj::{read_obj, write_obj};
/// let mesh = NurbsSurface::sphere(Vector3::zeros(), 1.0)?.tessellate(8, 16)?;
/// let text = write_obj(&mesh);
/// assert!(text.starts_with("# spline mesh: "));
/// assert_eq!(read_obj(&text)?, mesh);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[must_use]
pub fn write_obj(mesh: &TriangleMesh) -> String {
    let mut out = String::with_capacity(64 * (mesh.vertices.len() + mesh.triangles.len()));
    let _ = writeln!(
        out,
        "# spline mesh: {} vertices, {} triangles",
        mesh.vertices.len(),
        mesh.triangles.len()
    );
    for v in &mesh.vertices {
        let _ = writeln!(out, "v {} {} {}", v.x, v.y, v.z);
    }
    let normals = mesh.normals.len() == mesh.vertices.len();
    if normals {
        for n in &mesh.normals {
            let _ = writeln!(out, "vn {} {} {}", n.x, n.y, n.z);
        }
    }
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|k| k + 1);
        if normals {
            let _ = writeln!(out, "f {a}//{a} {b}//{b} {c}//{c}");
        } else {
            let _ = writeln!(out, "f {a} {b} {c}");
        }
    }
    out
}

/// One corner of a face: the vertex and, if the face gives one, the normal (0-based).
struct Corner {
    vertex: usize,
    normal: Option<usize>,
}

/// Reads a Wavefront OBJ text: `v x y z` vertices (further numbers, a `w` or a colour, are
/// ignored), `vn` normals and `f` faces whose entries are `i`, `i/t`, `i//n` or `i/t/n`
/// (1-based, or negative: relative to the last vertex read); polygons are fanned into
/// triangles. Other statements (`vt`, groups, materials, lines) are skipped. The normals are
/// the file's when it gives one per vertex and every face corner names its vertex's normal
/// (as [`write_obj`] writes them); otherwise they are computed
/// ([`TriangleMesh::compute_normals`]).
///
/// # Errors
/// [`ErrorKind::Parse`] for a vertex or normal without three numbers, a face with fewer than
/// three corners or an entry that does not start with a vertex index, an index of a vertex
/// the file does not have; [`ErrorKind::NonFinite`] for a vertex that is not finite. Every
/// message names the line.
pub fn read_obj(text: &str) -> Result<TriangleMesh> {
    let mut vertices = Vec::new();
    let mut normals = Vec::new();
    let mut faces: Vec<(usize, Vec<Corner>)> = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line_number = n + 1;
        let bad =
            |what: String| Error::new(ErrorKind::Parse, format!("line {line_number}: {what}"));
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let p =
                    three(&mut words).ok_or_else(|| bad("a vertex needs three numbers".into()))?;
                if !p.iter().all(|x| x.is_finite()) {
                    return Err(Error::new(
                        ErrorKind::NonFinite,
                        format!("line {line_number}: the vertex is not finite"),
                    ));
                }
                vertices.push(p);
            }
            Some("vn") => {
                let p =
                    three(&mut words).ok_or_else(|| bad("a normal needs three numbers".into()))?;
                normals.push(p);
            }
            Some("f") => {
                let corners = words
                    .map(|w| corner(w, vertices.len(), normals.len()))
                    .collect::<Option<Vec<_>>>()
                    .ok_or_else(|| bad("face indices must be non-zero integers".into()))?;
                if corners.len() < 3 {
                    return Err(bad("a face needs three vertices".into()));
                }
                faces.push((line_number, corners));
            }
            _ => {}
        }
    }
    let mut triangles = Vec::with_capacity(faces.len());
    let mut file_normals = normals.len() == vertices.len();
    for (line_number, corners) in &faces {
        for c in corners {
            if c.vertex >= vertices.len() {
                return Err(Error::new(
                    ErrorKind::Parse,
                    format!(
                        "line {line_number}: vertex {} of a file with {} vertices",
                        c.vertex + 1,
                        vertices.len()
                    ),
                ));
            }
            // A normal the file does not have (or a face without normals) leaves the normals
            // to be computed.
            file_normals &= c.normal == Some(c.vertex) && c.vertex < normals.len();
        }
        for k in 1..corners.len() - 1 {
            triangles.push([corners[0].vertex, corners[k].vertex, corners[k + 1].vertex]);
        }
    }
    let mut mesh = TriangleMesh {
        vertices,
        normals: Vec::new(),
        triangles,
    };
    if file_normals && !mesh.triangles.is_empty() {
        mesh.normals = normals;
    } else {
        mesh.compute_normals();
    }
    Ok(mesh)
}

/// The first three numbers of a statement (further ones are ignored), if there are three.
fn three<'a>(words: &mut impl Iterator<Item = &'a str>) -> Option<Vector3<f64>> {
    let mut c = [0.0; 3];
    for x in &mut c {
        *x = words.next()?.parse().ok()?;
    }
    Some(Vector3::from(c))
}

/// An index of OBJ (1-based, or negative: counted back from the `count` items read so far)
/// as a 0-based index; `None` for zero, a non-integer or a negative index beyond the start.
fn index(text: &str, count: usize) -> Option<usize> {
    let i: i64 = text.parse().ok()?;
    match i {
        0 => None,
        1.. => usize::try_from(i - 1).ok(),
        _ => count.checked_sub(usize::try_from(i.checked_neg()?).ok()?),
    }
}

/// A face entry `i`, `i/t`, `i//n` or `i/t/n`: `None` unless the vertex index is one. The
/// texture index is not used, nor a normal index that is not one (the normals are then
/// computed).
fn corner(word: &str, vertices: usize, normals: usize) -> Option<Corner> {
    let mut parts = word.split('/');
    let vertex = index(parts.next()?, vertices)?;
    let _texture = parts.next();
    let normal = parts.next().and_then(|n| index(n, normals));
    Some(Corner { vertex, normal })
}
