//! Errors about a file's content carry the line (`Error::line`) and, from `read_file`, the
//! file (`Error::file`) as fields a program reads, besides saying them in the message.

use spline_core::ErrorKind;
use spline_geom::BSpline;
use spline_io::airfoil::parse_airfoil;
use spline_io::exchange::from_json;
use spline_io::step::read_step;

fn step(data: &str) -> String {
    format!("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n{data}ENDSEC;\nEND-ISO-10303-21;\n")
}

#[test]
fn step_errors_carry_their_line() {
    // Line 6: a point whose parenthesis is not closed.
    let text = step("#2 = CARTESIAN_POINT('',(0.,0.,0.));\n#1 = CARTESIAN_POINT('',(0.,0.,0.);\n");
    let e = read_step(&text).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Parse);
    assert_eq!(e.line(), Some(6), "{e}");
    assert!(e.to_string().contains("STEP line 6"), "{e}");
}

#[test]
fn read_file_names_the_file_in_a_field() {
    let dir = std::env::temp_dir().join(format!("spline-io-fields-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("broken.step");
    std::fs::write(&path, step("#1 = CARTESIAN_POINT('',(0.,0.,0.);\n")).unwrap();
    let e = spline_io::read_file(&path).unwrap_err();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(e.file(), Some(path.display().to_string().as_str()));
    assert_eq!(e.line(), Some(5));
    // A file that does not exist is an I/O error, not a complaint about an argument.
    let e = spline_io::read_file(&dir.join("missing.igs")).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Io, "{e}");
    // An unknown extension names the file in the field too.
    let other = dir.join("curve.dxf");
    let e = spline_io::read_file(&other).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument, "{e}");
    assert_eq!(e.file(), Some(other.display().to_string().as_str()));
}

#[test]
fn airfoil_errors_carry_their_line() {
    let e = parse_airfoil("NACA 0012\n1.0 0.0\n0.5 0.1 7\n0.0 0.0\n").unwrap_err();
    assert_eq!(e.line(), Some(3), "{e}");
    let e = parse_airfoil("NACA 0012\n1.0 0.0\n0.5 nan\n0.0 0.0\n").unwrap_err();
    assert_eq!((e.kind(), e.line()), (ErrorKind::NonFinite, Some(3)), "{e}");
}

#[test]
fn json_errors_carry_their_line() {
    let e = from_json::<BSpline<f64, f64>>(
        "{\n\"degree\": 1,\n\"knots\": [0, 0, 1, 1],\n\"control_points\": [0, oops]\n}",
    )
    .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Parse);
    assert_eq!(e.line(), Some(4), "{e}");
}
