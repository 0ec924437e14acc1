//! [`NdSpline`] against scipy 1.17's `NdBSpline`: the constants below were printed by
//! `target/python-venv/bin/python crates/spline-geom/src/nd/reference.py` (see that file),
//! and against finite differences of the values.

use super::*;

const ONE_D: [f64; 8] = [
    0.8414709848078965,
    0.8551231085709121,
    0.4037992442149252,
    -0.2627873590469614,
    -0.6112417408850446,
    -0.8834546557201536,
    -0.23216487361235463,
    0.3490852126862283,
];
const ONE_D_NU1: [f64; 8] = [
    1.5019382564457207,
    -1.039661281514676,
    -2.716639363362257,
    -2.513378275119507,
    -2.095717081847475,
    0.9407546194494341,
    9.991358326439727,
    7.9359681397624655,
];
const ONE_D_NU2: [f64; 8] = [
    -31.09303036972598,
    -19.73896038948195,
    -0.4190578983889264,
    2.0451466043309283,
    3.5236693059628372,
    16.71947536934988,
    -53.80117033021404,
    29.915281432736947,
];
const ONE_D_NOEXT: [f64; 8] = [
    0.8414709848078965,
    0.8551231085709121,
    0.4037992442149252,
    -0.2627873590469614,
    -0.6112417408850446,
    -0.8834546557201536,
    f64::NAN,
    f64::NAN,
];
const TWO_D: [f64; 12] = [
    0.021123271280262916,
    -0.3644114987463654,
    -0.5516540621943434,
    -0.4081986049702746,
    0.22398861055144767,
    -0.3981988854190416,
    -0.04246803471694442,
    -0.6761178353877643,
    -0.8572477674214081,
    -1.0363466282659766,
    1.7723408162045593,
    -0.41909795774567254,
];
const TWO_D_NU12: [f64; 12] = [
    8.93025300290088,
    4.781732513316893,
    -0.3776119958127987,
    -1.769535614244833,
    -10.368986829075148,
    2.3522829160505605,
    -11.240870979079265,
    3.9927276350029928,
    -1.1874521796545219,
    -11.905307513343324,
    -10.009706608459865,
    -7.225994974880991,
];
const TWO_D_NOEXT: [f64; 12] = [
    0.021123271280262916,
    -0.3644114987463654,
    -0.5516540621943434,
    -0.4081986049702746,
    0.22398861055144767,
    -0.3981988854190416,
    -0.04246803471694442,
    -0.6761178353877643,
    f64::NAN,
    f64::NAN,
    f64::NAN,
    f64::NAN,
];
const TWO_D_DM_DATA: [f64; 36] = [
    0.045,
    0.21375,
    0.09,
    0.01125,
    0.07333333333333333,
    0.34833333333333333,
    0.14666666666666667,
    0.018333333333333333,
    0.006666666666666667,
    0.03166666666666667,
    0.013333333333333334,
    0.0016666666666666668,
    0.16666666666666666,
    0.3333333333333333,
    0.16666666666666666,
    0.0,
    0.08333333333333333,
    0.16666666666666666,
    0.08333333333333333,
    0.0,
    0.0,
    0.0,
    0.0,
    0.0,
    3.3333333333333483e-09,
    1.986666666666674e-06,
    0.0003940233333333344,
    0.012937320000000021,
    8.666666666666697e-08,
    5.165333333333347e-05,
    0.010244606666666684,
    0.3363703200000002,
    1.6000000000000035e-07,
    9.536000000000013e-05,
    0.01891312000000001,
    0.6209913599999997,
];
const TWO_D_DM_INDICES: [usize; 36] = [
    0, 1, 2, 3, 5, 6, 7, 8, 10, 11, 12, 13, 6, 7, 8, 9, 11, 12, 13, 14, 16, 17, 18, 19, 11, 12, 13,
    14, 16, 17, 18, 19, 21, 22, 23, 24,
];
const THREE_D: [f64; 5] = [
    0.008248412247072838,
    -0.5015474562463045,
    0.07801328238357191,
    -0.8903484806134702,
    3.5492329183479594,
];
const THREE_D_NU102: [f64; 5] = [
    -7.022966043262012,
    -13.738771572762511,
    -5.077408765160737,
    13.098080840536774,
    -46.91218590015699,
];
const THREE_D_NU011: [f64; 5] = [
    -0.4829999584159188,
    -14.79929718916447,
    11.61854588255697,
    -3.432982934020461,
    41.972673722029946,
];

const CUBIC_2D: [f64; 10] = [
    0.2156895019467794,
    0.2205516777592605,
    -0.009765682550216905,
    -0.09358136681105717,
    -0.5881691736694475,
    -0.7926980503915918,
    1081.3208894067045,
    608.9974917375387,
    0.02477542545335954,
    -0.6250706488928821,
];
const CUBIC_2D_NOEXT: [f64; 10] = [
    0.2156895019467794,
    0.2205516777592605,
    -0.009765682550216905,
    -0.09358136681105717,
    -0.5881691736694475,
    -0.7926980503915918,
    f64::NAN,
    f64::NAN,
    0.02477542545335954,
    -0.6250706488928821,
];
const QUAD_3D: [f64; 4] = [
    -0.10510548139493155,
    -0.1368794617905387,
    -0.4624771543299071,
    3.029016821038677,
];

const CUBIC_2D_NU21: [f64; 10] = [
    -308.8235792562206,
    130.34147275525126,
    135.5387169562211,
    105.20369531130794,
    -11458.135423227744,
    -1231.186792590971,
    -507123.84079256305,
    -338691.82138045545,
    -14285.30031292247,
    -15154.847995898024,
];
const QUAD_3D_NU101: [f64; 4] = [
    -2.0631167159110504,
    -3.31971302500472,
    -10.061928501931098,
    -111.19095754249567,
];

/// `c[i] = sin(1 + 0.7 i)`, as the reference script builds them.
fn coeffs(n: usize) -> Vec<f64> {
    (0..n).map(|i| (1.0 + 0.7 * i as f64).sin()).collect()
}

fn close(a: &[f64], b: &[f64], tol: f64) {
    assert_eq!(a.len(), b.len());
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        if y.is_nan() {
            assert!(x.is_nan(), "entry {i}: {x} should be NaN");
        } else {
            assert!(
                (x - y).abs() <= tol * (1.0 + y.abs()),
                "entry {i}: {x} vs {y}"
            );
        }
    }
}

fn one_d() -> NdSpline {
    let t = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.3, 0.7, 1.0, 1.0, 1.0, 1.0];
    NdSpline::new(vec![t], coeffs(7), &[3], 1, true).unwrap()
}

const X1: [f64; 8] = [0.0, 0.1, 0.3, 0.55, 0.7, 1.0, -0.2, 1.3];

fn two_d() -> NdSpline {
    let ta = vec![0.0, 0.0, 0.0, 0.5, 1.5, 2.0, 2.0, 2.0];
    let tb = vec![-1.0, -1.0, -1.0, -1.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    NdSpline::new(vec![ta, tb], coeffs(50), &[2, 3], 2, true).unwrap()
}

const X2: [f64; 12] = [
    0.2, -0.5, 0.5, 0.0, 1.9, 0.99, 2.0, 1.0, -0.3, 0.4, 1.0, 1.5,
];

fn three_d() -> NdSpline {
    let tx = vec![0.0, 0.0, 0.4, 1.0, 1.0];
    let ty = vec![0.0, 0.0, 0.0, 0.25, 0.5, 1.0, 1.0, 1.0];
    let tz = vec![-0.3, -0.2, -0.1, 0.0, 0.4, 0.6, 1.0, 1.1, 1.2, 1.3];
    NdSpline::new(vec![tx, ty, tz], coeffs(90), &[1, 2, 3], 1, true).unwrap()
}

const X3: [f64; 15] = [
    0.1, 0.2, 0.3, 0.4, 0.5, 0.0, 0.9, 0.95, 1.0, 1.0, 1.0, 0.5, 1.2, -0.1, 0.7,
];

#[test]
fn one_dimension_values_derivatives_and_extrapolation() {
    let s = one_d();
    close(&s.eval(&X1, &[]).unwrap(), &ONE_D, 1e-14);
    close(&s.eval(&X1, &[1]).unwrap(), &ONE_D_NU1, 1e-13);
    close(&s.eval(&X1, &[2]).unwrap(), &ONE_D_NU2, 1e-12);
    let mut out = [0.0; 8];
    assert_eq!(s.eval_into(&X1, &[0], false, &mut out).unwrap(), 2);
    close(&out, &ONE_D_NOEXT, 1e-14);
    // Orders above the degree vanish (scipy gives zeros), outside too with extrapolation.
    assert_eq!(s.eval(&X1, &[4]).unwrap(), vec![0.0; 8]);
}

#[test]
fn two_dimensions_two_columns() {
    let s = two_d();
    close(&s.eval(&X2, &[0, 0]).unwrap(), &TWO_D, 1e-14);
    close(&s.eval(&X2, &[1, 2]).unwrap(), &TWO_D_NU12, 1e-12);
    let mut out = [0.0; 12];
    assert_eq!(s.eval_into(&X2, &[], false, &mut out).unwrap(), 2);
    close(&out, &TWO_D_NOEXT, 1e-14);
}

#[test]
fn three_dimensions_values_and_mixed_partials() {
    let s = three_d();
    close(&s.eval(&X3, &[]).unwrap(), &THREE_D, 1e-14);
    close(&s.eval(&X3, &[1, 0, 2]).unwrap(), &THREE_D_NU102, 1e-12);
    close(&s.eval(&X3, &[0, 1, 1]).unwrap(), &THREE_D_NU011, 1e-12);
}

#[test]
fn partial_derivatives_match_central_differences() {
    let s = three_d();
    let h = 1e-6;
    // Interior points away from knots in every dimension.
    let x = [0.2, 0.3, 0.2, 0.7, 0.8, 0.8];
    for e in 0..3 {
        let mut nu = [0; 3];
        nu[e] = 1;
        let d = s.eval(&x, &nu).unwrap();
        let (mut xp, mut xm) = (x, x);
        for p in 0..2 {
            xp[3 * p + e] += h;
            xm[3 * p + e] -= h;
        }
        let (fp, fm) = (s.eval(&xp, &[]).unwrap(), s.eval(&xm, &[]).unwrap());
        for p in 0..2 {
            let fd = (fp[p] - fm[p]) / (2.0 * h);
            assert!(
                (d[p] - fd).abs() < 1e-6 * (1.0 + fd.abs()),
                "{e} {p}: {} vs {fd}",
                d[p]
            );
        }
    }
}

#[test]
fn nan_coordinates_give_nan_rows() {
    let s = two_d();
    let mut out = [0.0; 4];
    let n = s
        .eval_into(&[f64::NAN, 0.0, 0.5, f64::INFINITY], &[], true, &mut out)
        .unwrap();
    assert_eq!(n, 2);
    assert!(out.iter().all(|v| v.is_nan()));
}

#[test]
fn design_matrix_matches_scipy() {
    let s = two_d();
    let (indptr, indices, data) =
        NdSpline::design_matrix_parts(&X2[..6], s.knot_vectors(), true).unwrap();
    assert_eq!(indptr, vec![0, 12, 24, 36]);
    assert_eq!(indices, TWO_D_DM_INDICES.to_vec());
    close(&data, &TWO_D_DM_DATA, 1e-14);
    let m = NdSpline::design_matrix(&X2[..6], s.knot_vectors(), true).unwrap();
    assert_eq!((m.nrows(), m.ncols()), (3, 25));
    // Outside points are an error without extrapolation, NaN always.
    let e = NdSpline::design_matrix_parts(&[3.0, 0.0], s.knot_vectors(), false).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::OutOfDomain);
    let e = NdSpline::design_matrix_parts(&[f64::NAN, 0.0], s.knot_vectors(), true).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
}

#[test]
fn design_matrix_times_coefficients_is_the_value() {
    let s = three_d();
    let (indptr, indices, data) =
        NdSpline::design_matrix_parts(&X3, s.knot_vectors(), true).unwrap();
    let c = s.coefficients();
    for (p, want) in THREE_D.iter().enumerate() {
        let v: f64 = (indptr[p]..indptr[p + 1])
            .map(|j| data[j] * c[indices[j]])
            .sum();
        assert!((v - want).abs() < 1e-14, "{v} vs {want}");
    }
}

#[test]
fn bad_input_is_an_error() {
    let t = vec![0.0, 0.0, 1.0, 1.0];
    // Wrong number of coefficients.
    let e = NdSpline::new(vec![t.clone(), t.clone()], vec![0.0; 3], &[1, 1], 1, true).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    // Degrees and knot vectors disagree.
    let e = NdSpline::new(vec![t.clone()], vec![0.0; 2], &[1, 1], 1, true).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    assert_eq!(e.counts(), Some((1, 2)));
    // Unsorted knots in dimension 1 are named.
    let e = NdSpline::new(
        vec![t.clone(), vec![0.0, 1.0, 0.5, 1.0]],
        vec![0.0; 4],
        &[1, 1],
        1,
        true,
    )
    .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::UnsortedKnots);
    assert!(e.message().contains("dimension 1"), "{}", e.message());
    // Non-finite coefficient, no dimension, no columns.
    let e = NdSpline::new(vec![t.clone()], vec![0.0, f64::NAN], &[1], 1, true).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    assert!(NdSpline::new(vec![], vec![], &[], 1, true).is_err());
    assert!(NdSpline::new(vec![t.clone()], vec![0.0; 2], &[1], 0, true).is_err());
    // Wrong shapes at evaluation.
    let s = NdSpline::new(vec![t.clone(), t], vec![0.0; 4], &[1, 1], 1, true).unwrap();
    assert!(s.eval(&[0.5, 0.5, 0.5], &[]).is_err());
    assert!(s.eval(&[0.5, 0.5], &[1]).is_err());
    assert!(s.eval_into(&[0.5, 0.5], &[], true, &mut [0.0; 2]).is_err());
}

#[test]
fn derivative_spline_evaluates_to_scipy_partials() {
    let s = three_d();
    let d = s.derivative(&[1, 0, 2]).unwrap();
    assert_eq!(d.degrees(), vec![0, 2, 1]);
    assert_eq!(d.shape(), &[2, 5, 4]);
    close(&d.eval(&X3, &[]).unwrap(), &THREE_D_NU102, 1e-12);
    let s = two_d();
    let d = s.derivative(&[1, 2]).unwrap();
    close(&d.eval(&X2, &[]).unwrap(), &TWO_D_NU12, 1e-12);
    // Above the degree (scipy's test_2D_derivative): zero, of degree 0 along that
    // dimension, on the same base interval, extrapolated as zero too.
    let d = s.derivative(&[3, 0]).unwrap();
    assert_eq!(d.degrees()[0], 0);
    assert_eq!(d.degrees()[1], s.degrees()[1]);
    assert_eq!(d.knot_vectors()[0].domain(), s.knot_vectors()[0].domain());
    let (a, b) = s.knot_vectors()[0].domain();
    let far = [a - 1.0, X2[1], b + 1.0, X2[1]];
    assert!(d.eval(&X2, &[]).unwrap().iter().all(|&v| v == 0.0));
    assert!(d.eval(&far, &[]).unwrap().iter().all(|&v| v == 0.0));
    assert!(s.derivative(&[1]).is_err());
}

/// Rough timing against scipy's `NdBSpline.__call__` (run with `--ignored --nocapture`,
/// `CARGO_PROFILE_TEST_OPT_LEVEL=3` for release speed). On the shared 2-core machine:
/// scipy 1.17 2-D cubic 150–200 ns, 3-D cubic 350–420 ns, 3-D linear 93–110 ns per point;
/// this kernel 52, 73 and 26 ns.
#[test]
#[ignore = "timing, not a check"]
fn timing() {
    for (d, k) in [(2usize, 3usize), (3, 3), (3, 1)] {
        let t: Vec<f64> = std::iter::repeat_n(0.0, k)
            .chain((0..=20).map(|i| f64::from(i) / 20.0))
            .chain(std::iter::repeat_n(1.0, k))
            .collect();
        let n = t.len() - k - 1;
        let s = NdSpline::new(vec![t; d], coeffs(n.pow(d as u32)), &vec![k; d], 1, true).unwrap();
        let npts = 200_000;
        let xi: Vec<f64> = (0..npts * d)
            .map(|i| ((i as f64) * 0.618_033_988_749_895).fract())
            .collect();
        let mut out = vec![0.0; npts];
        let start = std::time::Instant::now();
        s.eval_into(&xi, &[], true, &mut out).unwrap();
        let ns = start.elapsed().as_nanos() as f64 / npts as f64;
        println!("d = {d}, k = {k}: {ns:.1} ns per point");
    }
}

#[test]
fn equal_degrees_use_the_fixed_kernels() {
    let tc = vec![0.0, 0.0, 0.0, 0.0, 0.2, 0.5, 0.9, 1.0, 1.0, 1.0, 1.0];
    let s = NdSpline::new(vec![tc.clone(), tc], coeffs(98), &[3, 3], 2, true).unwrap();
    let x = [0.1, 0.3, 0.5, 0.5, 1.0, 0.95, 1.2, -0.3, 0.0, 1.0];
    close(&s.eval(&x, &[]).unwrap(), &CUBIC_2D, 1e-14);
    close(&s.eval(&x, &[2, 1]).unwrap(), &CUBIC_2D_NU21, 1e-12);
    let mut out = [0.0; 10];
    assert_eq!(s.eval_into(&x, &[0, 0], false, &mut out).unwrap(), 1);
    close(&out, &CUBIC_2D_NOEXT, 1e-14);
    let tq = vec![0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0];
    let s = NdSpline::new(
        vec![tq.clone(), tq.clone(), tq],
        coeffs(125),
        &[2, 2, 2],
        1,
        true,
    )
    .unwrap();
    let x = [0.1, 0.3, 0.7, 0.6, 0.6, 0.0, 1.0, 0.95, 0.2, 1.2, -0.3, 0.5];
    close(&s.eval(&x, &[]).unwrap(), &QUAD_3D, 1e-14);
    close(&s.eval(&x, &[1, 0, 1]).unwrap(), &QUAD_3D_NU101, 1e-12);
    let mut out = [0.0; 2];
    let n = s
        .eval_into(
            &[f64::NAN, 0.5, 0.5, 0.5, f64::INFINITY, 0.5],
            &[],
            true,
            &mut out,
        )
        .unwrap();
    assert_eq!(n, 2);
}

/// Knots repeated more than `k + 1` times (scipy's test_2D_mixed_random has such knots):
/// values from scipy 1.17's `NdBSpline((tx, ty), c, (2, 3))(xi)` on the same data.
#[test]
fn knots_repeated_beyond_the_order_match_scipy() {
    let tx = vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.2, 2.0, 3.0, 3.0, 3.0, 3.0];
    let ty = vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.5, 4.0, 4.0, 4.0, 4.0];
    let c: Vec<f64> = (0..8)
        .flat_map(|i| {
            (0..6).map(move |j| {
                let (i, j) = (f64::from(i), f64::from(j));
                (i + 1.0) * 0.3 - j * 0.7 + 0.1 * i * j
            })
        })
        .collect();
    let s = NdSpline::new(vec![tx, ty], c, &[2, 3], 1, true).unwrap();
    // Dimension 0 loses one empty basis function at each end.
    assert_eq!(s.shape(), &[6, 6]);
    let xi = [1.0, 1.1, 1.5, 1.6, 2.9, 3.9, 0.1, 0.2];
    let want = [0.55609199, 0.73275867, 1.46668513, 0.41365872];
    close(&s.eval(&xi, &[]).unwrap(), &want, 1e-8);
    // The wrong number of coefficients for the knots as given is still an error.
    let t = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    assert!(NdSpline::new(vec![t], vec![0.0; 3], &[2], 1, true).is_err());
}
