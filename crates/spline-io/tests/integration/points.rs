//! Point files and airfoil coordinates: the forms found in practice, and errors that name
//! the line.

use nalgebra::Vector2;
use spline_core::ErrorKind;
use spline_io::airfoil::{AirfoilFormat, parse_airfoil};
use spline_io::points::parse_points;

#[test]
fn point_files_in_json_and_text() {
    assert_eq!(
        parse_points("[[1, 2, 3], [4.5, -6, 7e-3]]").unwrap(),
        vec![vec![1.0, 2.0, 3.0], vec![4.5, -6.0, 0.007]]
    );
    let text = "x, y\n# comment\n\n 1.0\t2.0\n(3) 4\n5,6\nnot a point 7\n";
    assert_eq!(
        parse_points(text).unwrap(),
        vec![vec![1.0, 2.0], vec![3.0, 4.0], vec![5.0, 6.0]]
    );
    for (text, kind, words) in [
        ("", ErrorKind::TooFewPoints, "no points"),
        ("# only a comment\n", ErrorKind::TooFewPoints, "no points"),
        ("1 2\n3 4 5\n", ErrorKind::DimensionMismatch, "line 2"),
        ("[[1, 2], [3]]", ErrorKind::DimensionMismatch, "line 2"),
        ("1 2\ninf 4\n", ErrorKind::NonFinite, "line 2"),
        ("[[1, 2], [3, ", ErrorKind::Parse, "JSON"),
        ("[[]]", ErrorKind::DimensionMismatch, "line 1"),
    ] {
        let e = parse_points(text).unwrap_err();
        assert_eq!(e.kind(), kind, "{text:?}: {e}");
        assert!(e.message().contains(words), "{text:?}: {e}");
    }
}

#[test]
fn airfoils_in_both_layouts_agree() {
    let selig = "NACA 0012\n1.0 0.0013\n0.5 0.0529\n0.0 0.0\n0.5 -0.0529\n1.0 -0.0013\n";
    let lednicer = "NACA 0012\n3. 3.\n\n0.0 0.0\n0.5 0.0529\n1.0 0.0013\n\n0.0 0.0\n0.5 -0.0529\n1.0 -0.0013\n";
    let a = parse_airfoil(selig).unwrap();
    let b = parse_airfoil(lednicer).unwrap();
    assert_eq!(
        (a.format, b.format),
        (AirfoilFormat::Selig, AirfoilFormat::Lednicer)
    );
    assert_eq!(a.points, b.points);
    assert_eq!(a.points[2], Vector2::new(0.0, 0.0));
    assert_eq!(b.name.as_deref(), Some("NACA 0012"));
    // Every airfoil shipped with the project reads, with its trailing edge near x = 1.
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/airfoils");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "dat") {
            let text = std::fs::read_to_string(&path).unwrap();
            let airfoil =
                parse_airfoil(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            assert!(airfoil.points.len() >= 10, "{}", path.display());
            count += 1;
        }
    }
    assert!(count >= 1);
}
