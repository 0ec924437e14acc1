//! Malformed files: one-line errors naming the section and the record.

use super::{Hand, QUARTER, ROTATE_Z, SHIFT_X, hand_file, one};
use spline_core::ErrorKind;
use spline_io::Geometry;
use spline_io::iges::{read_iges, read_iges_bytes};

fn error(text: &str) -> String {
    let e = read_iges(text).unwrap_err();
    assert_eq!(e.message().lines().count(), 1);
    e.message().to_string()
}

fn quarter_file() -> String {
    hand_file(&[Hand(126, 0, 0, "ARC1", QUARTER)])
}

#[test]
fn truncated_files_and_wrong_counts() {
    let text = quarter_file();
    let lines: Vec<_> = text.lines().collect();
    let cut = lines[..lines.len() - 1].join("\n");
    assert_eq!(
        error(&cut),
        "IGES line 2 (P): the file ends without a Terminate (T) record (truncated?)"
    );
    // A Parameter Data record dropped: the Terminate count disagrees.
    let mut dropped: Vec<_> = lines.clone();
    dropped.remove(dropped.len() - 2);
    assert!(
        error(&dropped.join("\n")).starts_with("IGES line"),
        "{}",
        error(&dropped.join("\n"))
    );
    let wrong_t = text.replace(
        "S0000001G0000002D0000002P0000002",
        "S0000001G0000002D0000002P0000009",
    );
    assert_eq!(
        error(&wrong_t),
        "IGES line 1 (T): the Terminate record counts 9 P records, the file has 2 (truncated or damaged)"
    );
    // Every truncation and every single-byte change: an error or a result, no panic.
    for k in 0..text.len() {
        let _ = read_iges(&text[..k]);
    }
    let bytes = text.as_bytes();
    for k in (0..bytes.len()).step_by(3) {
        for b in [b'9', b',', b';', b' ', b'H', b'-', b'0'] {
            let mut m = bytes.to_vec();
            m[k] = b;
            let _ = read_iges_bytes(&m);
        }
    }
}

#[test]
fn counts_inconsistent_with_the_parameters() {
    let short = QUARTER.replace("126,2,2,", "126,3,2,");
    let e = error(&hand_file(&[Hand(126, 0, 0, "", &short)]));
    assert!(
        e.starts_with("IGES line 1 (P): entity 126: K = 3 and M = 2"),
        "{e}"
    );
    let huge = QUARTER.replace("126,2,2,", "126,1000000000000,2,");
    let e = error(&hand_file(&[Hand(126, 0, 0, "", &huge)]));
    assert!(e.contains("K = 1000000000000"), "{e}");
    let huge = QUARTER.replace("126,2,2,", "126,18446744073709551615,2,");
    assert!(error(&hand_file(&[Hand(126, 0, 0, "", &huge)])).contains("IGES line 1 (P)"));
    let negative = QUARTER.replace("126,2,2,", "126,-1,2,");
    assert!(
        error(&hand_file(&[Hand(126, 0, 0, "", &negative)]))
            .contains("K (upper index of the control points) = -1")
    );
    let surface = "128,1000000,1000000,1,1,0,0,1,0,0,0.,0.,1.,1.;";
    let e = error(&hand_file(&[Hand(128, 0, 0, "", surface)]));
    assert!(
        e.starts_with("IGES line 1 (P): entity 128: K1 = 1000000"),
        "{e}"
    );
}

#[test]
fn geometry_errors_name_the_record() {
    let unsorted = QUARTER.replace("0.,0.,0.,1.,1.,1.,", "0.,0.,0.,1.,0.5,1.,");
    let e = error(&hand_file(&[Hand(126, 0, 0, "", &unsorted)]));
    assert!(
        e.starts_with("IGES line 1 (P): knots must be non-decreasing"),
        "{e}"
    );
    let zero_weight = QUARTER.replace("1.0D0,1.,2.", "1.0D0,0.,2.");
    let e = read_iges(&hand_file(&[Hand(126, 0, 0, "", &zero_weight)])).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidWeight);
    assert!(e.message().starts_with("IGES line 1 (P): "), "{e}");
    let outside = QUARTER.replace("0.25,0.75", "2.,3.");
    assert!(
        error(&hand_file(&[Hand(126, 0, 0, "", &outside)])).contains("outside the knot domain")
    );
    let zero_arc = "100,0.,1.,1.,1.,1.,1.,1.;";
    assert!(error(&hand_file(&[Hand(100, 0, 0, "", zero_arc)])).contains("zero radius"));
}

#[test]
fn pointers_out_of_range_and_cycles() {
    // Transformation pointer outside the directory.
    let e = error(&hand_file(&[Hand(126, 0, 9, "", QUARTER)]));
    assert!(
        e.starts_with("IGES line 1 (D): transformation matrix pointer 9"),
        "{e}"
    );
    // An even pointer.
    let e = error(&hand_file(&[Hand(126, 0, 2, "", QUARTER)]));
    assert!(
        e.starts_with("IGES line 1 (D): transformation matrix pointer 2"),
        "{e}"
    );
    // A pointer to something other than a 124.
    let e = error(&hand_file(&[Hand(126, 0, 1, "", QUARTER)]));
    assert!(e.contains("designates an entity 126, not a 124"), "{e}");
    // A 124 referencing itself, and two referencing each other.
    let e = error(&hand_file(&[
        Hand(124, 0, 1, "", ROTATE_Z),
        Hand(126, 0, 1, "", QUARTER),
    ]));
    assert_eq!(
        e,
        "IGES line 1 (D): the transformation matrices reference each other in a cycle"
    );
    let e = error(&hand_file(&[
        Hand(124, 0, 3, "", ROTATE_Z),
        Hand(124, 0, 1, "", SHIFT_X),
        Hand(126, 0, 1, "", QUARTER),
    ]));
    assert!(e.contains("cycle"), "{e}");
    // Parameter data pointer outside the Parameter Data section.
    let text = quarter_file().replace("     126       1       0", "     126      99       0");
    let e = error(&text);
    assert!(
        e.starts_with("IGES line 1 (D): entity 126: parameter data pointer 99"),
        "{e}"
    );
    // A property pointer outside the directory.
    let params = QUARTER.replace("0.,0.,1.;", "0.,0.,1.,0,1,77;");
    let e = error(&hand_file(&[Hand(126, 0, 0, "", &params)]));
    assert!(e.contains("property pointer 77"), "{e}");
    // A 120 whose axis pointer is outside.
    let e = error(&hand_file(&[Hand(120, 0, 0, "", "120,41,1,0.,1.;")]));
    assert!(e.starts_with("IGES line 1 (P): axis pointer 41"), "{e}");
}

#[test]
fn records_and_characters() {
    let text = quarter_file();
    // Non-ASCII text: the line and column of the first bad byte.
    let bad = text.replacen("hand-written", "hand-wrïtten", 1);
    let e = read_iges_bytes(bad.as_bytes()).unwrap_err();
    assert_eq!(
        e.message(),
        "IGES file line 1: non-ASCII byte 0xC3 in column 8; IGES files are ASCII"
    );
    assert_eq!(read_iges(&bad).unwrap_err(), e);
    let mut latin1 = text.as_bytes().to_vec();
    latin1[81 * 2 + 5] = 0xE9;
    let e = read_iges_bytes(&latin1).unwrap_err();
    assert!(
        e.message()
            .starts_with("IGES file line 3: non-ASCII byte 0xE9 in column 6"),
        "{e}"
    );
    // A short record.
    let short = text.replacen("1H,,1H;", "1H,,1H;\n", 1);
    assert!(error(&short).starts_with("IGES file line 2: the record has"));
    // An unterminated Hollerith string.
    let holl = hand_file(&[Hand(406, 15, 0, "", "406,1,99Habc;")]);
    let e = read_iges(&holl);
    assert!(
        e.is_ok(),
        "406 entities are skipped, their parameters not read"
    );
    let params = QUARTER.replace("0.,0.,1.;", "0.,0.,1.,0,1,3;");
    let holl = hand_file(&[
        Hand(126, 0, 0, "", &params),
        Hand(406, 15, 0, "", "406,1,99Habc;"),
    ]);
    assert!(
        error(&holl).contains("Hollerith string of 99 characters"),
        "{}",
        error(&holl)
    );
    // Sequence numbers out of order.
    let swapped = text.replace("D0000002", "D0000003");
    assert!(error(&swapped).starts_with("IGES line 2 (D): sequence number '0000003'"));
    // Compressed files.
    let compressed = text.replacen("S0000001\n", "C0000001\n", 1);
    assert!(error(&compressed).contains("compressed ASCII"));
    // The wrong back-pointer in columns 65–72.
    let lines: Vec<String> = text.lines().map(str::to_string).collect();
    let p = lines.iter().position(|l| l.as_bytes()[72] == b'P').unwrap();
    let mut changed = lines.clone();
    changed[p] = format!("{}{:8}{}", &lines[p][..64], 3, &lines[p][72..]);
    assert!(error(&changed.join("\n")).starts_with("IGES line 1 (P): the directory pointer '3'"));
    // Records without line breaks read the same.
    let flat: String = text.lines().collect();
    assert_eq!(read_iges(&flat).unwrap(), read_iges(&text).unwrap());
    let crlf = text.replace('\n', "\r\n");
    assert_eq!(read_iges(&crlf).unwrap(), read_iges(&text).unwrap());
}

#[test]
fn delimiters_from_the_global_section() {
    let params = QUARTER.replace(',', "/").replace(';', "$");
    let text = hand_file(&[Hand(126, 0, 0, "", &params)])
        .replace(
            "1H,,1H;,4Htest,,,,32,38,6,308,15,,1.0,2,2HMM,1,1.0,",
            "1H//1H$/4Htest////32/38/6/308/15//1.0/2/2HMM/1/1.0/",
        )
        .replace(
            "15H20260101.120000,1.0E-7,10.0,,,11,0;",
            "15H20260101.120000/1.0E-7/10.0///11/0$",
        );
    let Geometry::NurbsCurve3(c) = one(&text).geometry else {
        panic!()
    };
    assert_eq!(c.domain(), (0.25, 0.75));
}
