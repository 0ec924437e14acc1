//! Tessellation: closed surfaces give closed meshes of the right topology, vertices lie on
//! the surface, normals point outwards (the OBJ, OFF and SVG outputs are spline-io's).

use nalgebra::Vector3;
use spline_core::ErrorKind;
use spline_geom::{BSpline, MAX_MESH_SEGMENTS, NurbsSurface, Surface, TriangleMesh};
use std::f64::consts::PI;

#[test]
fn sphere_mesh_is_a_closed_sphere() {
    let center = Vector3::new(1.0, 2.0, -1.0);
    let s = NurbsSurface::sphere(center, 2.0).unwrap();
    let mesh = s.tessellate(24, 48).unwrap();
    assert_eq!(mesh.boundary_edges(), 0);
    assert_eq!(mesh.euler_characteristic(), 2);
    for v in &mesh.vertices {
        assert!(((v - center).norm() - 2.0).abs() < 1e-13);
    }
    for (v, n) in mesh.vertices.iter().zip(&mesh.normals) {
        assert!((n.norm() - 1.0).abs() < 1e-12);
        assert!(n.dot(&(v - center).normalize()) > 0.99);
    }
    // Every triangle faces outwards (counter-clockwise seen from outside).
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|k| mesh.vertices[k]);
        assert!((b - a).cross(&(c - a)).dot(&((a + b + c) / 3.0 - center)) > 0.0);
    }
    // The inscribed polyhedron's area approaches 4πr² from below.
    let area = mesh.area();
    assert!(
        area < 4.0 * PI * 4.0 && area > 0.99 * 4.0 * PI * 4.0,
        "area {area}"
    );
}

#[test]
fn torus_mesh_has_euler_characteristic_zero() {
    let t = NurbsSurface::torus(Vector3::zeros(), Vector3::new(1.0, 1.0, 0.0), 3.0, 1.0).unwrap();
    let mesh = t.tessellate(20, 40).unwrap();
    assert_eq!(mesh.boundary_edges(), 0);
    assert_eq!(mesh.euler_characteristic(), 0);
    // Area of the torus 4π² R r within 1%.
    let area = mesh.area();
    assert!(
        (area / (4.0 * PI * PI * 3.0) - 1.0).abs() < 0.01,
        "area {area}"
    );
}

#[test]
fn open_surfaces_give_open_meshes() {
    // A bilinear patch: a disc topologically; knots are kept as grid lines.
    let patch = Surface::from_knots(
        (1, 1),
        vec![0.0, 0.0, 0.3, 1.0, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        vec![
            vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.0, 1.0, 0.0)],
            vec![Vector3::new(0.3, 0.0, 1.0), Vector3::new(0.3, 1.0, 1.0)],
            vec![Vector3::new(1.0, 0.0, 0.0), Vector3::new(1.0, 1.0, 0.0)],
        ],
    )
    .unwrap();
    let mesh = patch.tessellate(4, 3).unwrap();
    assert_eq!(mesh.euler_characteristic(), 1);
    assert_eq!(mesh.boundary_edges(), 2 * (5 + 3));
    // The crease at u = 0.3 is a grid line: the ridge points are vertices.
    assert_eq!(
        mesh.vertices
            .iter()
            .filter(|v| v.x == 0.3 && v.z == 1.0)
            .count(),
        4
    );
    // An open tube (an extruded circle) is an annulus: χ = 0 with two boundary loops.
    let circle = spline_geom::NurbsCurve::circle(
        &spline_geom::Frame::with_normal(Vector3::zeros(), Vector3::z()).unwrap(),
        1.0,
        spline_geom::CircleConstruction::Square,
    )
    .unwrap();
    let tube = NurbsSurface::extrusion(&circle, Vector3::new(0.0, 0.0, 1.0))
        .unwrap()
        .tessellate(16, 2)
        .unwrap();
    assert_eq!(tube.euler_characteristic(), 0);
    assert_eq!(tube.boundary_edges(), 2 * 16);
    // Planar surfaces are padded with z = 0.
    let flat = Surface::extrusion(
        &BSpline::from_knots(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![
                nalgebra::Vector2::new(0.0, 0.0),
                nalgebra::Vector2::new(1.0, 0.0),
            ],
        )
        .unwrap(),
        nalgebra::Vector2::new(0.0, 2.0),
    )
    .unwrap()
    .tessellate(2, 2)
    .unwrap();
    assert!(flat.vertices.iter().all(|v| v.z == 0.0));
    assert!((flat.area() - 2.0).abs() < 1e-14);
}

#[test]
fn bad_tessellations_are_errors() {
    let s = NurbsSurface::sphere(Vector3::zeros(), 1.0).unwrap();
    let e = s.tessellate(0, 4).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!(e.counts(), Some((1, 0)));
    let e = s.tessellate(4, MAX_MESH_SEGMENTS + 1).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!(e.counts(), Some((MAX_MESH_SEGMENTS, MAX_MESH_SEGMENTS + 1)));
    assert_eq!(
        TriangleMesh::from_grid(1, 3, &[Vector3::zeros(); 3])
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidLength
    );
    assert_eq!(
        TriangleMesh::from_grid(2, 2, &[Vector3::zeros(); 3])
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidLength
    );
    assert_eq!(
        TriangleMesh::from_grid(2, 2, &[Vector3::new(f64::NAN, 0.0, 0.0); 4])
            .unwrap_err()
            .kind(),
        ErrorKind::NonFinite
    );
    let s4 = NurbsSurface::<f64, 4>::new(
        spline_core::KnotVector::bezier(1, 0.0, 1.0).unwrap(),
        spline_core::KnotVector::bezier(1, 0.0, 1.0).unwrap(),
        vec![nalgebra::Vector4::zeros(); 4],
        vec![1.0; 4],
    )
    .unwrap();
    assert_eq!(
        s4.tessellate(2, 2).unwrap_err().kind(),
        ErrorKind::DimensionMismatch
    );
}
