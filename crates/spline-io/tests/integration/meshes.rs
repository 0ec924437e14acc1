//! Meshes as text: OFF and OBJ written from tessellations are checked by hand-written parsers
//! (independent of the readers), the readers on hand-written files (polygons, relative
//! indices, every face-entry form) and on the writers' output (exact round trips), one-line
//! errors naming the line; shaded SVG pictures with overlays.

use nalgebra::Vector3;
use spline_algebra::SurfaceFeatureLines;
use spline_core::ErrorKind;
use spline_geom::{NurbsSurface, TriangleMesh};
use spline_io::obj::{read_obj, write_obj};
use spline_io::off::{read_off, write_off};
use spline_io::svg::{
    BLUE_RIDGE_COLOUR, MeshView, PARABOLIC_COLOUR, RED_RIDGE_COLOUR, UMBILIC_COLOUR,
    feature_overlays, mesh_svg, mesh_svg_with,
};

/// OFF parsed by hand: the counts, then as many vertex and face lines.
fn parse_off(text: &str) -> (Vec<Vector3<f64>>, Vec<[usize; 3]>) {
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("OFF"));
    let counts: Vec<usize> = lines
        .next()
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(counts[2], 0);
    let vertices = (0..counts[0])
        .map(|_| {
            let c: Vec<f64> = lines
                .next()
                .unwrap()
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            Vector3::new(c[0], c[1], c[2])
        })
        .collect();
    let faces = (0..counts[1])
        .map(|_| {
            let c: Vec<usize> = lines
                .next()
                .unwrap()
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            assert_eq!(c[0], 3);
            [c[1], c[2], c[3]]
        })
        .collect();
    assert_eq!(lines.next(), None);
    (vertices, faces)
}

fn sphere() -> TriangleMesh {
    NurbsSurface::sphere(Vector3::new(1.0, 2.0, -1.0), 2.0)
        .unwrap()
        .tessellate(12, 24)
        .unwrap()
}

fn torus() -> TriangleMesh {
    NurbsSurface::torus(Vector3::zeros(), Vector3::new(1.0, 1.0, 0.0), 3.0, 1.0)
        .unwrap()
        .tessellate(20, 40)
        .unwrap()
}

#[test]
fn off_is_written_as_geomview_reads_it_and_read_back_exactly() {
    let mesh = sphere();
    let text = write_off(&mesh);
    let (vertices, faces) = parse_off(&text);
    assert_eq!(vertices, mesh.vertices);
    assert_eq!(faces, mesh.triangles);
    // Shortest round-trip decimals: the vertices come back bit for bit, and the normals,
    // computed from the same triangles, are the tessellation's.
    assert_eq!(read_off(&text).unwrap(), mesh);
}

#[test]
fn obj_is_written_with_normals_and_read_back_exactly() {
    let mesh = torus();
    let obj = write_obj(&mesh);
    let v = obj.lines().filter(|l| l.starts_with("v ")).count();
    let vn = obj.lines().filter(|l| l.starts_with("vn ")).count();
    let f: Vec<&str> = obj.lines().filter(|l| l.starts_with("f ")).collect();
    assert_eq!(
        (v, vn, f.len()),
        (
            mesh.vertices.len(),
            mesh.vertices.len(),
            mesh.triangles.len()
        )
    );
    for (line, t) in f.iter().zip(&mesh.triangles) {
        let corners: Vec<usize> = line
            .split_whitespace()
            .skip(1)
            .map(|corner| {
                let (a, b) = corner.split_once("//").unwrap();
                assert_eq!(a, b);
                a.parse().unwrap()
            })
            .collect();
        assert_eq!(corners, t.map(|k| k + 1));
    }
    assert_eq!(read_obj(&obj).unwrap(), mesh);
    // Without one normal per vertex, faces name vertices only.
    let bare = TriangleMesh {
        normals: Vec::new(),
        ..mesh.clone()
    };
    let text = write_obj(&bare);
    assert!(!text.contains("vn ") && !text.contains("//"));
    let back = read_obj(&text).unwrap();
    assert_eq!(
        (back.vertices, back.triangles),
        (mesh.vertices, mesh.triangles)
    );
}

/// A unit cube written by hand in the forms OBJ allows: quads, `i/t/n` and `i//n` entries,
/// negative (relative) indices, texture coordinates, groups and comments.
#[test]
fn hand_written_obj_files() {
    let cube = "# a cube\nmtllib cube.mtl\no cube\n\
        v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1 1.0\n\
        vt 0 0\nvn 0 0 -1\ng bottom\nusemtl grey\n\
        f 1/1/1 4/1/1 3/1/1 2/1/1\n\
        f 5 6 7 8\n\
        f 1//1 2//1 6//1 5//1\n\
        f -6 -5 -1 -2\n\
        f 2 3 7 6\n\
        f 4/1 1/1 5/1 8/1\n";
    let mesh = read_obj(cube).unwrap();
    assert_eq!(mesh.vertices.len(), 8);
    assert_eq!(mesh.triangles.len(), 12);
    assert_eq!(mesh.triangles[0], [0, 3, 2]);
    assert_eq!(mesh.triangles[1], [0, 2, 1]);
    // `f -6 -5 -1 -2` after 8 vertices: vertices 3, 4, 8, 7 (1-based).
    assert_eq!(mesh.triangles[6], [2, 3, 7]);
    assert_eq!(mesh.triangles[7], [2, 7, 6]);
    // Closed and outward: the surface area is 6, every triangle faces away from the
    // centre, and so do the vertex normals (computed: the file's single normal is not one
    // per vertex).
    assert_eq!(mesh.boundary_edges(), 0);
    assert_eq!(mesh.euler_characteristic(), 2);
    assert!((mesh.area() - 6.0).abs() < 1e-15);
    let centre = Vector3::repeat(0.5);
    for t in &mesh.triangles {
        let middle = t.iter().map(|&k| mesh.vertices[k]).sum::<Vector3<f64>>() / 3.0;
        assert!(mesh.face_normal(t).dot(&(middle - centre)) > 0.0, "{t:?}");
    }
    for (v, n) in mesh.vertices.iter().zip(&mesh.normals) {
        assert!((n.norm() - 1.0).abs() < 1e-15);
        // Each corner's normal lies in the octant of its corner.
        assert!(
            (v - centre).iter().zip(n.iter()).all(|(d, c)| d * c > 0.0),
            "{v} {n}"
        );
    }
    // Normals the file does not have are not used (the tool has read such files): the
    // normals are computed.
    let square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1//1 2//7 3//x 4//4\n";
    let mesh = read_obj(square).unwrap();
    assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    assert!(mesh.normals.iter().all(|n| *n == Vector3::z()));
    // Lines, points and texture vertices only: no triangles.
    let empty = read_obj("v 0 0 0\nv 1 0 0\nl 1 2\np 1\n").unwrap();
    assert_eq!((empty.vertices.len(), empty.triangles.len()), (2, 0));
}

#[test]
fn obj_errors_name_the_line() {
    for (text, kind, line) in [
        (
            "v 0 0\n",
            ErrorKind::Parse,
            "line 1: a vertex needs three numbers",
        ),
        (
            "v 0 0 x\n",
            ErrorKind::Parse,
            "line 1: a vertex needs three numbers",
        ),
        ("v 0 0 0\nv 0 0 inf\n", ErrorKind::NonFinite, "line 2: "),
        (
            "v 0 0 0\nvn 1 0\n",
            ErrorKind::Parse,
            "line 2: a normal needs three numbers",
        ),
        (
            "v 0 0 0\nv 1 0 0\nf 1 2\n",
            ErrorKind::Parse,
            "line 3: a face needs three vertices",
        ),
        (
            "v 0 0 0\nf 1 2 x\n",
            ErrorKind::Parse,
            "line 2: face indices",
        ),
        (
            "v 0 0 0\nf 0 1 1\n",
            ErrorKind::Parse,
            "line 2: face indices",
        ),
        (
            "v 0 0 0\nf 1 -2 1\n",
            ErrorKind::Parse,
            "line 2: face indices",
        ),
        (
            "v 0 0 0\nv 1 0 0\nf 1 2 3\n",
            ErrorKind::Parse,
            "line 3: vertex 3 of a file with 2 vertices",
        ),
        (
            "v 0 0 0\nf 1 1 18446744073709551616\n",
            ErrorKind::Parse,
            "line 2: face indices",
        ),
    ] {
        let e = read_obj(text).unwrap_err();
        assert_eq!(e.kind(), kind, "{text:?}: {e}");
        assert!(e.message().starts_with(line), "{text:?}: {e}");
        assert!(!e.message().contains('\n'));
    }
}

#[test]
fn hand_written_off_files() {
    // A square as one quad (fanned), comments, blank lines, the counts on the keyword's
    // line, a colour after a face.
    let square =
        "OFF 4 1 4 # counts here\n\n0 0 0\n2 0 0\n2 2 0 # corner\n0 2 0\n4 0 1 2 3 255 0 0\n";
    let mesh = read_off(square).unwrap();
    assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    assert!((mesh.area() - 4.0).abs() < 1e-15);
    assert!(mesh.normals.iter().all(|n| *n == Vector3::z()));
}

#[test]
fn off_errors_name_the_line_and_counts_reserve_nothing() {
    for (text, kind, start) in [
        ("", ErrorKind::Parse, "an OFF file starts"),
        (
            "COFF\n1 0 0\n0 0 0\n",
            ErrorKind::Parse,
            "line 1: an OFF file starts",
        ),
        (
            "OFF\n1 x 0\n0 0 0\n",
            ErrorKind::Parse,
            "line 2: expected the counts",
        ),
        ("OFF\n", ErrorKind::Parse, "an OFF file starts"),
        (
            "OFF\n2 0 0\n0 0 0\n0 0\n",
            ErrorKind::Parse,
            "line 4: a vertex needs three numbers",
        ),
        ("OFF\n1 0 0\nnan 0 0\n", ErrorKind::NonFinite, "line 3: "),
        (
            "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
            ErrorKind::Parse,
            "line 6: a face starts",
        ),
        (
            "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
            ErrorKind::Parse,
            "line 6: vertex 3 of a file with 3 vertices",
        ),
        (
            "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n",
            ErrorKind::Parse,
            "line 6: the face has fewer indices",
        ),
        (
            "OFF\n1 0 0\n0 0 0\n0 0 0\n",
            ErrorKind::Parse,
            "line 4: more lines than",
        ),
        // Counts far beyond the file: an error at its end, nothing reserved for them.
        (
            "OFF\n1000000000000000 1000000000000000 0\n0 0 0\n",
            ErrorKind::Parse,
            "line 3: the file ends after 1 of 1000000000000000 vertices",
        ),
        (
            "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1000000000000 0 1 2\n",
            ErrorKind::Parse,
            "line 6: the face has fewer indices",
        ),
    ] {
        let e = read_off(text).unwrap_err();
        assert_eq!(e.kind(), kind, "{text:?}: {e}");
        assert!(e.message().starts_with(start), "{text:?}: {e}");
        assert!(!e.message().contains('\n'));
    }
}

#[test]
fn svg_pictures_of_meshes() {
    let mesh = NurbsSurface::sphere(Vector3::zeros(), 1.0)
        .unwrap()
        .tessellate(8, 16)
        .unwrap();
    let svg = mesh_svg(
        &mesh,
        &MeshView {
            title: Some("sphere <1>".into()),
            ..MeshView::default()
        },
    );
    assert!(svg.starts_with("<svg"));
    assert!(svg.trim_end().ends_with("</svg>"));
    assert!(svg.contains("sphere &lt;1&gt;"));
    let polygons = svg.matches("<polygon").count();
    // Back faces of a closed mesh are culled: about half the triangles are drawn.
    assert!(
        polygons > mesh.triangles.len() / 4 && polygons < mesh.triangles.len(),
        "{polygons}"
    );
    assert!(!svg.contains("NaN"));
    // Overlays: a line is drawn as segments, a point as a dot, in their colours.
    let features = SurfaceFeatureLines {
        parabolic: vec![vec![
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
        ]],
        red_ridges: vec![vec![
            Vector3::new(0.0, 0.0, 1.0),
            Vector3::new(0.0, 0.6, 0.8),
            Vector3::new(0.0, 0.8, 0.6),
        ]],
        blue_ridges: Vec::new(),
        umbilics: vec![Vector3::new(0.0, 0.0, -1.0)],
    };
    let overlays = feature_overlays(&features);
    let colours: Vec<[u8; 3]> = overlays.iter().map(|o| o.color).collect();
    assert_eq!(
        colours,
        [PARABOLIC_COLOUR, RED_RIDGE_COLOUR, UMBILIC_COLOUR]
    );
    assert_ne!(BLUE_RIDGE_COLOUR, RED_RIDGE_COLOUR);
    assert!(overlays[2].markers && !overlays[0].markers);
    let drawn = mesh_svg_with(&mesh, &MeshView::default(), &overlays);
    assert_eq!(drawn.matches("<line").count(), 1 + 2);
    assert_eq!(drawn.matches("<circle").count(), 1);
    assert_eq!(drawn.matches("rgb(235,110,20)").count(), 1);
    assert_eq!(drawn.matches("<polygon").count(), polygons);
}
