//! IGES: curves and surfaces through a file and back bit for bit, hand-written files
//! (formatted here, independently of the writer), malformed files, files of Open CASCADE.

mod errors;
mod hand_written;
mod occt;
mod round_trips;

use nalgebra::Vector3;
use spline_core::KnotVector;
use spline_io::iges::read_iges;
use spline_io::{Geometry, Item};

pub(crate) fn item(name: &str, geometry: Geometry) -> Item {
    Item {
        id: 0,
        name: name.to_string(),
        entity: String::new(),
        geometry,
    }
}

/// Reproducible awkward numbers (not representable in few decimal digits).
pub(crate) struct Numbers(pub(crate) u64);

impl Numbers {
    pub(crate) fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let unit = (self.0 >> 11) as f64 / (1u64 << 53) as f64;
        (unit - 0.5) * 7.0 / 3.0
    }

    pub(crate) fn point3(&mut self) -> Vector3<f64> {
        Vector3::new(self.next(), self.next() * 1e3, self.next() * 1e-6)
    }

    pub(crate) fn weight(&mut self) -> f64 {
        0.3 + (self.next() + 1.2).abs()
    }
}

pub(crate) fn bits3(points: &[Vector3<f64>]) -> Vec<[u64; 3]> {
    points
        .iter()
        .map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
        .collect()
}

pub(crate) fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|x| x.to_bits()).collect()
}

/// A knot vector of degree `p` on `[0, 1]` with interior knots of multiplicities 1, p,
/// 2 (awkward values), clamped or not.
pub(crate) fn knots(p: usize, clamped: bool) -> KnotVector<f64> {
    let mut k = Vec::new();
    if clamped {
        k.extend(std::iter::repeat_n(0.0, p + 1));
    } else {
        k.extend((0..=p).map(|i| -0.1 * (p - i) as f64));
    }
    k.push(0.1);
    k.extend(std::iter::repeat_n(1.0 / 3.0, p));
    k.extend(std::iter::repeat_n(0.7, 2.min(p)));
    if clamped {
        k.extend(std::iter::repeat_n(1.0, p + 1));
    } else {
        k.extend((0..=p).map(|i| 1.0 + 0.25 * i as f64));
    }
    KnotVector::new(p, k).unwrap()
}

pub(crate) fn one(text: &str) -> Item {
    let items = read_iges(text).unwrap();
    assert_eq!(items.len(), 1, "{items:?}");
    items.into_iter().next().unwrap()
}

/// One entity of a hand-written file: type, form, transformation pointer, label,
/// parameters (with their delimiters, as they appear in the file).
pub(crate) struct Hand<'a>(
    pub(crate) i64,
    pub(crate) i64,
    pub(crate) i64,
    pub(crate) &'a str,
    pub(crate) &'a str,
);

pub(crate) fn hand_file(entities: &[Hand<'_>]) -> String {
    let mut s = String::new();
    let mut rec = |data: &str, letter: char, seq: usize| {
        s.push_str(&format!("{data:<72}{letter}{seq:07}\n"));
    };
    rec("hand-written IGES test file", 'S', 1);
    rec(
        "1H,,1H;,4Htest,,,,32,38,6,308,15,,1.0,2,2HMM,1,1.0,",
        'G',
        1,
    );
    rec("15H20260101.120000,1.0E-7,10.0,,,11,0;", 'G', 2);
    let mut p_lines: Vec<(String, usize)> = Vec::new();
    let mut d_lines = Vec::new();
    for (k, Hand(kind, form, transform, label, params)) in entities.iter().enumerate() {
        let de = 2 * k + 1;
        let first = p_lines.len() + 1;
        // Split after delimiters into records of at most 64 columns.
        let mut current = String::new();
        for piece in params.split_inclusive([',', ';', '/', '$']) {
            if current.len() + piece.len() > 64 {
                p_lines.push((std::mem::take(&mut current), de));
            }
            current.push_str(piece);
        }
        p_lines.push((current, de));
        let count = p_lines.len() + 1 - first;
        d_lines.push(format!(
            "{kind:8}{first:8}{:8}{:8}{:8}{:8}{transform:8}{:8}00000000",
            0, 0, 1, 0, 0
        ));
        d_lines.push(format!(
            "{kind:8}{:8}{:8}{count:8}{form:8}{:8}{:8}{label:>8}{:8}",
            0, 0, "", "", 0
        ));
    }
    for (k, d) in d_lines.iter().enumerate() {
        rec(d, 'D', k + 1);
    }
    for (k, (p, de)) in p_lines.iter().enumerate() {
        rec(&format!("{p:<64}{de:8}"), 'P', k + 1);
    }
    rec(
        &format!(
            "S{:07}G{:07}D{:07}P{:07}",
            1,
            2,
            d_lines.len(),
            p_lines.len()
        ),
        'T',
        1,
    );
    s
}

/// The quarter circle `((1 − t²)/(1 + t²), 2t/(1 + t²))`, `t ∈ [0, 1]`, with the
/// parameter range given (entity 126, numbers in the D and bare-point notations).
pub(crate) const QUARTER: &str =
    "126,2,2,1,0,0,0,0.,0.,0.,1.,1.,1.,1.0D0,1.,2.,1.,0.,0.,1.,1.,0.,0.,1.,0.,0.25,0.75,0.,0.,1.;";

/// A rotation by 90° about `z` (entity 124).
pub(crate) const ROTATE_Z: &str = "124,0.,-1.,0.,0.,1.,0.,0.,0.,0.,0.,1.,0.;";
/// A translation by 1 along `x` (entity 124).
pub(crate) const SHIFT_X: &str = "124,1.,0.,0.,1.,0.,1.,0.,0.,0.,0.,1.,0.;";
