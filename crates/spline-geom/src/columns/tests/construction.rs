//! Reference values from scipy 1.17 (see the parent module): knot insertion, basis
//! elements, design matrices, the power basis and knots repeated beyond the order.

use super::*;

#[test]
fn insert_knot_matches_scipy() {
    let s = cubic().insert_knot(1.2, 2, false).unwrap();
    // insert_knot(1.2, 2) t, c
    assert_eq!(
        s.knots(),
        &[-1.0, -0.5, 0.0, 0.3, 1.0, 1.2, 1.2, 1.7, 2.0, 2.6, 3.0, 3.1]
    );
    close(
        s.coefficients(),
        &[
            1.0,
            -2.0,
            0.5,
            0.0,
            1.5588235294117647,
            0.7058823529411765,
            0.8214285714285715,
            1.5756302521008403,
            0.1606617647058824,
            2.1845588235294118,
            -0.84375,
            2.6875,
            0.25,
            0.5,
            1.5,
            -1.0,
        ],
        1e-12,
    );
    let tp: Vec<f64> = (-3..11).map(f64::from).collect();
    let cp = vec![1.0, 2.0, -1.0, 0.5, 3.0, 0.0, 1.5, 1.0, 2.0, -1.0];
    let p = ColumnSpline::new(tp, cp, 3, 1).unwrap();
    // periodic insert_knot(0.5), (6.5), (3.2) t, c
    let cases: [(f64, [f64; 15], [f64; 11]); 3] = [
        (
            0.5,
            [
                -3.0, -2.0, -1.0, 0.0, 0.5, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 7.5, 8.0, 9.0,
            ],
            [
                1.0,
                1.8333333333333335,
                0.5,
                -0.75,
                0.5,
                3.0,
                0.0,
                1.5,
                1.0,
                1.8333333333333335,
                0.5,
            ],
        ),
        (
            6.5,
            [
                -2.0, -1.0, -0.5, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 6.5, 7.0, 8.0, 9.0, 10.0,
            ],
            [
                1.5,
                1.5,
                -1.0,
                0.5,
                3.0,
                0.0,
                1.5,
                1.0833333333333333,
                1.5,
                1.5,
                -1.0,
            ],
        ),
        (
            3.2,
            [
                -3.0, -2.0, -1.0, 0.0, 1.0, 2.0, 3.0, 3.2, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0,
            ],
            [
                1.0,
                2.0,
                -1.0,
                0.5,
                2.3333333333333335,
                1.7999999999999996,
                0.10000000000000009,
                1.5,
                1.0,
                2.0,
                -1.0,
            ],
        ),
    ];
    for (x, t, c) in cases {
        let q = p.insert_knot(x, 1, true).unwrap();
        close(q.knots(), &t, 1e-14);
        close(q.coefficients(), &c, 1e-12);
    }
    assert!(p.insert_knot(7.5, 1, false).is_err());
    assert!(p.insert_knot(2.0, 0, false).is_err());
}

#[test]
fn basis_element_matches_scipy() {
    let e = ColumnSpline::basis_element(&[0.0, 1.0, 1.0, 3.0]).unwrap();
    // basis_element [0,1,1,3] t, values
    assert_eq!(e.knots(), &[-1.0, -1.0, 0.0, 1.0, 1.0, 3.0, 4.0, 4.0]);
    let got = e
        .eval(&[-0.5, 0.5, 1.0, 2.0, 3.5], 0, Extrapolate::On)
        .unwrap();
    close(&got, &[0.25, 0.25, 1.0, 0.25, 0.0625], 1e-14);
}

#[test]
fn design_matrix_matches_scipy() {
    let t = cubic().knots().to_vec();
    let x = [-0.5, 0.3, 1.0, 1.5, 2.0, 2.5];
    // design_matrix extrapolate=True data, indices
    let data = [
        3.2142857142857144,
        -3.710684273709485,
        1.8037214885954387,
        -0.3073229291716688,
        0.3266666666666666,
        0.6203921568627451,
        0.052941176470588235,
        0.0,
        0.20588235294117646,
        0.5882352941176471,
        0.20588235294117646,
        0.0,
        0.00480192076830732,
        0.21308523409363742,
        0.6705057022809122,
        0.11160714285714285,
        0.0,
        0.25,
        0.673076923076923,
        0.07692307692307693,
        -0.24509803921568626,
        0.9406998910675379,
        -1.15429131054131,
        1.4586894586894585,
    ];
    let first = [0, 0, 1, 1, 2, 2];
    let m = ColumnSpline::design_matrix(&x, &t, 3, Extrapolate::On).unwrap();
    assert_eq!((m.nrows(), m.ncols(), m.nnz()), (6, 6, 24));
    close(m.values(), &data, 1e-12);
    let cols: Vec<usize> = first.iter().flat_map(|&f| f..f + 4).collect();
    assert_eq!(m.col_indices(), &cols[..]);
    // design_matrix periodic data, indices
    let data_p = [
        0.07503001200480193,
        0.5037214885954382,
        0.4141056422569027,
        0.0071428571428571366,
        0.3266666666666666,
        0.6203921568627451,
        0.052941176470588235,
        0.0,
        0.20588235294117646,
        0.5882352941176471,
        0.20588235294117646,
        0.0,
        0.00480192076830732,
        0.21308523409363742,
        0.6705057022809122,
        0.11160714285714285,
        0.3266666666666666,
        0.6203921568627451,
        0.052941176470588235,
        0.0,
        0.007619047619047589,
        0.4136294517807119,
        0.5037214885954383,
        0.07503001200480201,
    ];
    let first_p = [1, 0, 1, 1, 0, 0];
    let m = ColumnSpline::design_matrix(&x, &t, 3, Extrapolate::Periodic).unwrap();
    close(m.values(), &data_p, 1e-12);
    let cols: Vec<usize> = first_p.iter().flat_map(|&f| f..f + 4).collect();
    assert_eq!(m.col_indices(), &cols[..]);
    let e = ColumnSpline::design_matrix(&x, &t, 3, Extrapolate::Off).unwrap_err();
    assert!(e.message().contains("Out of bounds"), "{e}");
    let e = ColumnSpline::design_matrix(&x, &t[..7], 3, Extrapolate::On).unwrap_err();
    assert!(e.message().contains("Length t is not enough"), "{e}");
}

/// The breakpoints of the `from_power_basis` reference cases.
const XS: [f64; 6] = [0.0, 0.7, 1.5, 2.0, 3.2, 4.0];

/// Knot choice, `pp.c`, expected `t` and `c` of one `from_power_basis` case.
type PowerCase = (
    PowerBasisKnots,
    &'static [f64],
    &'static [f64],
    &'static [f64],
);

#[test]
fn from_power_basis_matches_scipy() {
    // from_power_basis not-a-knot / natural / clamped / periodic: pp.c, t, c
    let cases: [PowerCase; 4] = [
        (
            PowerBasisKnots::NotAKnot,
            &[
                1.018750196712334,
                1.018750196712334,
                -0.9822336547295754,
                -0.564276375371406,
                -0.5642763753714061,
                -2.7365188877723394,
                -0.5971434746764381,
                1.8478569974331638,
                0.37450651533880097,
                -1.6568884359982596,
                1.1509253823914967,
                -1.182638271322647,
                -0.18206745311726663,
                0.9291143032687158,
                -0.6097440015226361,
                1.0,
                0.8141848301379321,
                0.00750249000360903,
                0.25565380596206977,
                0.9348107753306125,
            ],
            &[0.0, 0.0, 0.0, 0.0, 1.5, 2.0, 4.0, 4.0, 4.0, 4.0],
            &[
                1.0,
                1.5754626911957483,
                -0.39377260831559296,
                0.595375452483494,
                1.9938148974387584,
                -0.9023025291165417,
            ],
        ),
        (
            PowerBasisKnots::Augmented,
            &[
                -0.6100101519664717,
                1.3745692526921995,
                -0.9557938988934502,
                -0.8073047442954209,
                0.9675179335300007,
                0.0,
                -1.2810213191295903,
                2.017944887331689,
                0.5842540389915147,
                -2.322043040472001,
                0.03345473180347407,
                -0.8632601915872392,
                -0.27372133702556045,
                1.0273781261360408,
                -1.0579686756405429,
                1.0,
                0.8141848301379321,
                0.00750249000360903,
                0.25565380596206977,
                0.9348107753306125,
            ],
            &[0.0, 0.0, 0.0, 0.0, 0.7, 1.5, 2.0, 3.2, 4.0, 4.0, 4.0, 4.0],
            &[
                1.0,
                1.0078061040874773,
                1.0245334699892141,
                -0.23418469460472652,
                0.3785245609288427,
                1.8189270383670586,
                -0.12480836697837028,
                -0.9023025291165417,
            ],
        ),
        (
            PowerBasisKnots::Augmented,
            &[
                -0.6360818506390152,
                1.3281422587161846,
                -0.5539570171410744,
                -1.3309153384454946,
                4.109317552913386,
                0.06604266307574341,
                -1.269729223266188,
                1.9178121976526556,
                1.0868766719410439,
                -3.704418546462737,
                0.0,
                -0.8425805921333115,
                -0.32411421262413775,
                1.1782302221727121,
                -1.9628200272533203,
                1.0,
                0.8141848301379321,
                0.00750249000360903,
                0.25565380596206977,
                0.9348107753306125,
            ],
            &[0.0, 0.0, 0.0, 0.0, 0.7, 1.5, 2.0, 3.2, 4.0, 4.0, 4.0, 4.0],
            &[
                1.0,
                1.0,
                1.02311493207651,
                -0.2157943817543313,
                0.31319885674749404,
                2.3819340471657977,
                -0.9023025291165415,
                -0.9023025291165413,
            ],
        ),
        (
            PowerBasisKnots::Periodic,
            &[
                -0.5787164014054166,
                0.08320894532095378,
                0.8143735269844647,
                0.34302514852011007,
                -0.6003532712366716,
                -0.01107282609701199,
                -1.2263772690483863,
                -1.0266758002780954,
                0.19488449019860282,
                1.4297750248709995,
                1.5641884780828024,
                0.6979734114810233,
                -1.1044690439801634,
                -1.52036469901991,
                0.4292267190636126,
                0.0,
                0.8910065241883678,
                std::f64::consts::FRAC_1_SQRT_2,
                1.2246467991473532e-16,
                -0.9510565162951536,
            ],
            &[
                -2.5,
                -2.0,
                -0.7999999999999998,
                0.0,
                0.7,
                1.5,
                2.0,
                3.2,
                4.0,
                4.7,
                5.5,
                6.0,
            ],
            &[
                -1.4658147534623551,
                -0.0500726883979844,
                1.143196061460101,
                0.95444379228831,
                -0.393728661144366,
                -1.4658147534623551,
                -0.05007268839798429,
                1.1431960614601002,
            ],
        ),
    ];
    for (bc, pp, t, c) in cases {
        let s = ColumnSpline::from_power_basis(&XS, pp, 4, 1, bc).unwrap();
        close(s.knots(), t, 1e-14);
        close(s.coefficients(), c, 1e-11);
    }
}

/// Knots repeated more than `k + 1` times, and empty end spans: values from scipy 1.17
/// (`BSpline(t, c, k)(x, nu)`, `design_matrix`, `integrate`, `insert_knot` on the same data).
#[test]
fn knots_repeated_beyond_the_order_match_scipy() {
    // 0 five times for a cubic: basis function 0 is identically zero, and the span below
    // t[3] = t[4] is empty, so points below 0 give 0.
    let t = vec![0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0];
    let c: Vec<f64> = (0..7).map(f64::from).collect();
    let s = ColumnSpline::new(t.clone(), c, 3, 1).unwrap();
    assert_eq!(s.knots(), &t[..]);
    assert_eq!(s.num_basis(), 7);
    assert_eq!(s.knot_vector().num_basis(), 6);
    let x = [-0.5, 0.0, 0.5, 1.5, 3.0, 3.5];
    let want = [0.0, 1.0, 2.1770833333333335, 3.5, 6.0, 7.927083333333334];
    close(&s.eval(&x, 0, Extrapolate::On).unwrap(), &want, 1e-14);
    let want = [0.0, 3.0, 1.8125, 1.125, 3.0, 4.8125];
    close(&s.eval(&x, 1, Extrapolate::On).unwrap(), &want, 1e-13);
    close(
        &s.integrate(0.0, 3.0, Extrapolate::On).unwrap(),
        &[10.5],
        1e-13,
    );
    let d = ColumnSpline::design_matrix(&[0.25, 2.5], &t, 3, Extrapolate::On).unwrap();
    let dense = nalgebra::DMatrix::from(&d);
    let want = [
        [
            0.0,
            0.421875,
            0.49609375,
            0.07942708333333333,
            0.00260416666666667,
            0.0,
            0.0,
        ],
        [
            0.0,
            0.0,
            0.0,
            0.02083333333333333,
            0.26041666666666663,
            0.59375,
            0.125,
        ],
    ];
    for (i, row) in want.iter().enumerate() {
        close(
            &dense.row(i).iter().copied().collect::<Vec<_>>(),
            row,
            1e-15,
        );
    }

    // de Boor's example (scipy's test_derivative_jumps): t_n = 6 is a triple knot followed
    // by the empty span [6, 6]; at 6 and beyond scipy gives 0.
    let t = vec![-1.0, -1.0, 0.0, 1.0, 1.0, 3.0, 4.0, 6.0, 6.0, 6.0, 7.0, 7.0];
    let c = vec![0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 0.0, 0.0];
    let b = ColumnSpline::new(t, c, 2, 1).unwrap();
    let x = [5.5, 6.0 - 1e-10, 6.0, 6.5];
    close(
        &b.eval(&x, 0, Extrapolate::On).unwrap(),
        &[4.520833333333333, 4.9999999999, 0.0, 0.0],
        1e-12,
    );
    close(
        &b.eval(&x, 1, Extrapolate::On).unwrap(),
        &[0.9166666666666665, 0.9999999999833333, 0.0, 0.0],
        1e-9,
    );
    let off = b.eval(&[6.0, 6.5], 0, Extrapolate::Off).unwrap();
    assert_eq!(off[0], 0.0);
    assert!(off[1].is_nan());

    // Degree 0 with the last knot twice (the degree-0 interpolant): the empty last span
    // gives its own coefficient.
    let z = ColumnSpline::new(
        vec![0.0, 1.0, 2.0, 3.0, 4.0, 4.0],
        vec![0.0, 1.0, 4.0, 9.0, 16.0],
        0,
        1,
    )
    .unwrap();
    let got = z
        .eval(&[-1.0, 0.0, 3.5, 4.0, 4.5], 0, Extrapolate::On)
        .unwrap();
    close(&got, &[0.0, 0.0, 9.0, 16.0, 16.0], 0.0);

    // Inserting a knot at a clamped end (FITPACK's insert, as scipy's insert_knot).
    let s = ColumnSpline::new(
        vec![0.0, 0.0, 0.0, 0.0, 2.0, 3.0, 4.0, 5.0, 7.0, 7.0, 7.0, 7.0],
        vec![0.1, -0.4, 0.9, 0.3, -0.2, 0.6, 0.8, -0.5],
        3,
        1,
    )
    .unwrap();
    let i = s.insert_knot(0.0, 1, false).unwrap();
    close(
        i.knots(),
        &[
            0.0, 0.0, 0.0, 0.0, 0.0, 2.0, 3.0, 4.0, 5.0, 7.0, 7.0, 7.0, 7.0,
        ],
        0.0,
    );
    close(
        i.coefficients(),
        &[0.1, 0.1, -0.4, 0.9, 0.3, -0.2, 0.6, 0.8, -0.5],
        1e-15,
    );
    let i = s.insert_knot(7.0, 2, false).unwrap();
    close(&i.knots()[7..], &[5.0, 7.0, 7.0, 7.0, 7.0, 7.0, 7.0], 0.0);
    close(&i.coefficients()[7..], &[-0.5, -0.5, -0.5], 1e-15);
    let x = [0.0, 1.0, 6.5];
    close(
        &i.eval(&x, 0, Extrapolate::On).unwrap(),
        &[0.1, 0.10694444444444444, 0.22586805555555556],
        1e-15,
    );
}
