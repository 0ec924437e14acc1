//! The entities of CAD files: their geometry, exactly as (rational) B-splines, with the name
//! and identifier the file gives them.

use nalgebra::{Vector2, Vector3};
use spline_geom::{BSpline, NurbsCurve2, NurbsCurve3, NurbsSurface3, Surface};

/// The geometry of one imported or exported entity, converted exactly to (rational) B-splines.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// A polynomial B-spline curve in the plane.
    Curve2(BSpline<f64, Vector2<f64>>),
    /// A polynomial B-spline curve in space.
    Curve3(BSpline<f64, Vector3<f64>>),
    /// A rational (NURBS) curve in the plane.
    NurbsCurve2(NurbsCurve2<f64>),
    /// A rational (NURBS) curve in space.
    NurbsCurve3(NurbsCurve3<f64>),
    /// A polynomial tensor-product B-spline surface in space.
    Surface(Surface<f64, Vector3<f64>>),
    /// A rational (NURBS) tensor-product surface in space.
    NurbsSurface(NurbsSurface3<f64>),
}

impl Geometry {
    /// Every coordinate of the Cartesian control points, point after point.
    pub(crate) fn coordinates(&self) -> Box<dyn Iterator<Item = f64> + '_> {
        fn flat<const D: usize>(
            points: &[nalgebra::SVector<f64, D>],
        ) -> Box<dyn Iterator<Item = f64> + '_> {
            Box::new(points.iter().flat_map(|p| p.iter().copied()))
        }
        match self {
            Geometry::Curve2(c) => flat(c.control_points()),
            Geometry::Curve3(c) => flat(c.control_points()),
            Geometry::NurbsCurve2(c) => flat(c.control_points()),
            Geometry::NurbsCurve3(c) => flat(c.control_points()),
            Geometry::Surface(s) => flat(s.control_points()),
            Geometry::NurbsSurface(s) => flat(s.control_points()),
        }
    }
}

/// One entity of a CAD file: its geometry, with the name and identifier the file gives it.
#[derive(Clone, Debug, PartialEq)]
pub struct Item {
    /// The entity's identifier in the file: the STEP instance number (`#12` → 12), or the IGES
    /// directory-entry sequence number. Writers number entities themselves and ignore it.
    pub id: u64,
    /// The entity's name (STEP: the `name` attribute, or the name of the face or edge that
    /// holds the geometry; IGES: the entity label); empty when the file gives none.
    pub name: String,
    /// The entity type the geometry was read from (`B_SPLINE_CURVE_WITH_KNOTS`,
    /// `CYLINDRICAL_SURFACE`, `126`, …); writers ignore it.
    pub entity: String,
    /// The geometry.
    pub geometry: Geometry,
}
