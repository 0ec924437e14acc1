//! Tessellation of surfaces into triangle meshes (written and read as OBJ and OFF, drawn as
//! SVG pictures by `spline-io`).

use crate::nurbs::NurbsSurface;
use crate::param::ParamSurface;
use crate::surface::Surface;
use nalgebra::Vector3;
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, from_count, to_f64};
use std::collections::HashMap;

/// A triangle mesh with per-vertex normals. Triangles are oriented counter-clockwise seen
/// from the side the normals point to.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::NurbsSurface;
/// let mesh = NurbsSurface::sphere(Vector3::zeros(), 1.0)?.tessellate(16, 32)?;
/// assert_eq!(mesh.euler_characteristic(), 2); // a closed sphere: the seam and poles are welded
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq, Default)]
pub struct TriangleMesh {
    /// Vertex positions.
    pub vertices: Vec<Vector3<f64>>,
    /// Unit vertex normals (area-weighted averages of the adjacent triangles' normals).
    pub normals: Vec<Vector3<f64>>,
    /// Triangles as indices into `vertices`.
    pub triangles: Vec<[usize; 3]>,
}

impl TriangleMesh {
    /// The mesh of a grid of points `points[a * cols + b]` (`rows × cols`, `a` along the
    /// first parameter): each grid cell gives two triangles. Coincident points (within
    /// `1e-10` times the size of the grid, such as the seam of a closed surface or the pole
    /// of a sphere) are welded into one vertex, and triangles that collapse are dropped, so
    /// a closed surface gives a closed mesh.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless `points.len() = rows · cols` with
    /// `rows, cols ≥ 2`; [`ErrorKind::NonFinite`] for a non-finite point.
    pub fn from_grid(rows: usize, cols: usize, points: &[Vector3<f64>]) -> Result<Self> {
        if rows < 2 || cols < 2 || rows.checked_mul(cols) != Some(points.len()) {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "a grid mesh needs rows, cols ≥ 2 and rows · cols points, got {rows} × {cols} and {} points",
                    points.len()
                ),
            ));
        }
        if points
            .iter()
            .any(|p| !p.iter().all(nalgebra::ComplexField::is_finite))
        {
            return Err(Error::new(
                ErrorKind::NonFinite,
                "a mesh point is not finite",
            ));
        }
        let (lo, hi) = points.iter().fold(
            (
                Vector3::repeat(f64::INFINITY),
                Vector3::repeat(f64::NEG_INFINITY),
            ),
            |(lo, hi), p| (lo.inf(p), hi.sup(p)),
        );
        // The size of the grid without overflow (coordinates may be near the range of f64).
        let extent = (hi - lo).amax();
        let size = if extent.is_finite() {
            extent
        } else {
            hi.amax().max(lo.amax())
        };
        let tolerance = (size * 1e-10).max(f64::MIN_POSITIVE);
        let mut cells: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        let mut vertices: Vec<Vector3<f64>> = Vec::new();
        #[allow(clippy::cast_possible_truncation)]
        let cell_of = |p: &Vector3<f64>| p.map(|x| (x / tolerance).floor() as i64);
        let index: Vec<usize> = points
            .iter()
            .map(|p| {
                let c = cell_of(p);
                for dx in -1..=1 {
                    for dy in -1..=1 {
                        for dz in -1..=1 {
                            let cell = [
                                c.x.saturating_add(dx),
                                c.y.saturating_add(dy),
                                c.z.saturating_add(dz),
                            ];
                            if let Some(list) = cells.get(&cell) {
                                if let Some(&k) = list
                                    .iter()
                                    .find(|&&k| (vertices[k] - p).amax() <= tolerance)
                                {
                                    return k;
                                }
                            }
                        }
                    }
                }
                vertices.push(*p);
                cells
                    .entry([c.x, c.y, c.z])
                    .or_default()
                    .push(vertices.len() - 1);
                vertices.len() - 1
            })
            .collect();
        let mut triangles = Vec::with_capacity(2 * (rows - 1) * (cols - 1));
        for a in 0..rows - 1 {
            for b in 0..cols - 1 {
                let v00 = index[a * cols + b];
                let v10 = index[(a + 1) * cols + b];
                let v11 = index[(a + 1) * cols + b + 1];
                let v01 = index[a * cols + b + 1];
                for t in [[v00, v10, v11], [v00, v11, v01]] {
                    if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                        triangles.push(t);
                    }
                }
            }
        }
        let mut mesh = Self {
            normals: Vec::new(),
            vertices,
            triangles,
        };
        mesh.compute_normals();
        Ok(mesh)
    }

    /// Recomputes the vertex normals as area-weighted averages of the triangle normals
    /// (vertices without triangles get `+z`).
    pub fn compute_normals(&mut self) {
        // Directions do not depend on the scale: work on coordinates of magnitude at most 1,
        // so that cross products neither overflow nor underflow.
        let largest = self.vertices.iter().fold(0.0f64, |m, v| m.max(v.amax()));
        let scale = if largest > 0.0 && largest.is_finite() {
            largest
        } else {
            1.0
        };
        let mut normals = vec![Vector3::zeros(); self.vertices.len()];
        for t in &self.triangles {
            let [a, b, c] = t.map(|k| self.vertices[k] / scale);
            let n = (b - a).cross(&(c - a));
            for &k in t {
                normals[k] += n;
            }
        }
        for n in &mut normals {
            let len = n.norm();
            *n = if len > 0.0 { *n / len } else { Vector3::z() };
        }
        self.normals = normals;
    }

    /// The normal of a triangle (indices into `vertices`) scaled by twice its area, by the
    /// right-hand rule.
    ///
    /// # Panics
    /// If an index is not one of a vertex.
    #[must_use]
    pub fn face_normal(&self, t: &[usize; 3]) -> Vector3<f64> {
        let [a, b, c] = t.map(|k| self.vertices[k]);
        (b - a).cross(&(c - a))
    }

    /// The total area.
    #[must_use]
    pub fn area(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| self.face_normal(t).norm() / 2.0)
            .sum()
    }

    /// The edges with the number of triangles using each.
    fn edge_counts(&self) -> HashMap<(usize, usize), usize> {
        let mut edges = HashMap::new();
        for t in &self.triangles {
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        edges
    }

    /// The number of edges used by exactly one triangle (zero for a closed mesh).
    #[must_use]
    pub fn boundary_edges(&self) -> usize {
        self.edge_counts().values().filter(|&&c| c == 1).count()
    }

    /// The Euler characteristic `V − E + F` (2 for a closed sphere, 0 for a torus, 1 for a
    /// disc), counting only vertices used by triangles.
    #[must_use]
    pub fn euler_characteristic(&self) -> i64 {
        let mut used = vec![false; self.vertices.len()];
        for t in &self.triangles {
            for &k in t {
                used[k] = true;
            }
        }
        let v = used.iter().filter(|&&u| u).count();
        let count = |n: usize| i64::try_from(n).unwrap_or(i64::MAX);
        count(v) - count(self.edge_counts().len()) + count(self.triangles.len())
    }
}

/// The largest number of equal parameter steps of a tessellation in each direction
/// ([`Surface::tessellate`]): a mesh has at most about a million vertices besides those at
/// the knots.
pub const MAX_MESH_SEGMENTS: usize = 1000;

/// Parameters for tessellation: `segments` equal steps over the domain (the first and last
/// breaks), plus every interior break.
fn mesh_params<T: Scalar>(breaks: &[T], segments: usize) -> Result<Vec<T>> {
    if segments == 0 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "a tessellation needs at least one segment in each direction",
        )
        .with_counts(1, 0));
    }
    if segments > MAX_MESH_SEGMENTS {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{segments} segments in one direction are more than the supported maximum {MAX_MESH_SEGMENTS}"
            ),
        )
        .with_counts(MAX_MESH_SEGMENTS, segments));
    }
    let (a, b) = (breaks[0], breaks[breaks.len() - 1]);
    let mut params: Vec<T> = (0..=segments)
        .map(|k| a + (b - a) * from_count::<T>(k) / from_count::<T>(segments))
        .collect();
    params.extend_from_slice(&breaks[1..breaks.len() - 1]);
    params.sort_by(|x, y| x.partial_cmp(y).expect("finite parameters"));
    params.dedup_by(|x, y| to_f64(*x - *y).abs() <= 1e-12 * to_f64(b - a));
    *params.last_mut().expect("at least two parameters") = b;
    Ok(params)
}

fn to_vector3<T: Scalar, P: ControlPoint<T>>(p: &P) -> Vector3<f64> {
    Vector3::from_fn(|i, _| if i < P::DIM { to_f64(p.coord(i)) } else { 0.0 })
}

impl TriangleMesh {
    /// A triangle mesh of any surface ([`ParamSurface`]): `segments_u × segments_v` equal
    /// parameter steps, refined at every interior knot (so that creases at knots of high
    /// multiplicity are kept), evaluated on the grid ([`ParamSurface::eval_grid`], the
    /// tensor fast path for B-spline and NURBS surfaces) and welded (see
    /// [`TriangleMesh::from_grid`]). Points with fewer than 3 coordinates are padded with
    /// zeros.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use spline_geom::{NurbsSurface, TriangleMesh};
    /// let sphere = NurbsSurface::sphere(Vector3::new(0.0, 0.0, 0.0), 1.0)?;
    /// let mesh = TriangleMesh::from_surface(&sphere, 16, 8)?;
    /// assert_eq!(mesh.euler_characteristic(), 2); // a closed sphere
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::DimensionMismatch`] for points of more than 3 coordinates;
    /// [`ErrorKind::InvalidArgument`] for zero segments or more than [`MAX_MESH_SEGMENTS`].
    pub fn from_surface<T: Scalar, S: ParamSurface<T>>(
        surface: &S,
        segments_u: usize,
        segments_v: usize,
    ) -> Result<Self> {
        let dim = <S::Point as ControlPoint<T>>::DIM;
        if !(1..=3).contains(&dim) {
            return Err(Error::new(
                ErrorKind::DimensionMismatch,
                format!("meshes are built from surfaces with 1 to 3 coordinates, got {dim}"),
            ));
        }
        let (breaks_u, breaks_v) = surface.breaks();
        let us = mesh_params(&breaks_u, segments_u)?;
        let vs = mesh_params(&breaks_v, segments_v)?;
        let points: Vec<Vector3<f64>> = surface
            .eval_grid(&us, &vs)?
            .iter()
            .map(to_vector3::<T, S::Point>)
            .collect();
        Self::from_grid(us.len(), vs.len(), &points)
    }
}

impl<T: Scalar, P: ControlPoint<T>> Surface<T, P> {
    /// A triangle mesh of the surface ([`TriangleMesh::from_surface`]).
    ///
    /// # Errors
    /// As [`TriangleMesh::from_surface`].
    pub fn tessellate(&self, segments_u: usize, segments_v: usize) -> Result<TriangleMesh> {
        TriangleMesh::from_surface(self, segments_u, segments_v)
    }
}

impl<T: Scalar, const D: usize> NurbsSurface<T, D> {
    /// A triangle mesh of the surface ([`TriangleMesh::from_surface`]).
    ///
    /// # Errors
    /// As [`TriangleMesh::from_surface`].
    pub fn tessellate(&self, segments_u: usize, segments_v: usize) -> Result<TriangleMesh> {
        TriangleMesh::from_surface(self, segments_u, segments_v)
    }
}
