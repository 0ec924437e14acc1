//! Reference values from scipy 1.17: `crates/spline-fit/src/columns/reference.py` prints
//! them (the comment above each list names its section). Evaluation, calculus and roots
//! here; knot insertion, basis elements, design matrices and the power basis in
//! `construction`.

use super::*;
use crate::columns::PowerBasisKnots;

fn close(got: &[f64], want: &[f64], tol: f64) {
    assert_eq!(got.len(), want.len(), "lengths differ: {got:?} vs {want:?}");
    for (i, (&g, &w)) in got.iter().zip(want).enumerate() {
        if w.is_nan() {
            assert!(g.is_nan(), "entry {i}: {g} should be NaN");
            continue;
        }
        assert!(
            (g - w).abs() <= tol * (1.0 + w.abs()),
            "entry {i}: {g} vs {w} (got {got:?})"
        );
    }
}

fn cubic() -> ColumnSpline {
    let t = vec![-1.0, -0.5, 0.0, 0.3, 1.0, 1.7, 2.0, 2.6, 3.0, 3.1];
    let c = vec![
        1.0, -2.0, 0.5, 0.0, 2.0, 1.0, -1.0, 3.0, 0.25, 0.5, 1.5, -1.0,
    ];
    ColumnSpline::new(t, c, 3, 2).unwrap()
}

const X: [f64; 8] = [-2.0, 0.3, 0.3, 1.0, 1.35, 2.0, 2.2, 5.0];

#[test]
fn eval_extrapolates_both_sides_and_derivatives() {
    let s = cubic();
    // eval extrapolate=True nu=0 … nu=3
    let want: [&[f64]; 4] = [
        &[
            73.81362545018007,
            -40.33673469387755,
            0.7427450980392155,
            -0.6003921568627449,
            0.7427450980392155,
            -0.6003921568627449,
            1.073529411764706,
            1.2058823529411766,
            0.18718979779411732,
            2.093267463235294,
            0.033653846153846145,
            1.0096153846153846,
            0.4999497234791355,
            0.29348081112786956,
            -198.09276018099553,
            287.80542986425337,
        ],
        &[
            -87.10984393757504,
            40.03001200480191,
            0.09411764705882364,
            3.3294117647058816,
            0.09411764705882364,
            3.3294117647058816,
            -1.3235294117647058,
            2.6470588235294117,
            -2.9648437499999996,
            1.8708639705882346,
            2.5240384615384617,
            -4.278846153846153,
            1.8261689291101042,
            -2.456762192056307,
            -204.97737556561083,
            291.26696832579177,
        ],
        &[
            68.53541416566627,
            -27.44297719087635,
            7.294117647058823,
            -4.470588235294118,
            7.294117647058823,
            -4.470588235294118,
            -11.344537815126051,
            2.5210084033613445,
            1.9655987394958014,
            -6.956407563025213,
            1.2019230769230766,
            2.7243589743589736,
            -8.180618401206646,
            15.49648064353947,
            -139.53619909502262,
            194.3061840120663,
        ],
        &[
            -26.62665066026411,
            9.987995198079233,
            -26.62665066026411,
            9.987995198079233,
            -26.62665066026411,
            9.987995198079233,
            38.028961584633855,
            -27.078331332533015,
            38.028961584633855,
            -27.078331332533015,
            -46.91270739064856,
            63.86060834590246,
            -46.91270739064856,
            63.86060834590246,
            -46.91270739064856,
            63.86060834590246,
        ],
    ];
    for (nu, want) in want.iter().enumerate() {
        let got = s.eval(&X, nu, Extrapolate::On).unwrap();
        close(&got, want, 1e-12);
    }
    // Above the degree: zeros.
    assert_eq!(s.eval(&X, 4, Extrapolate::On).unwrap(), vec![0.0; 16]);
}

#[test]
fn eval_periodic_and_without_extrapolation() {
    let s = cubic();
    // eval extrapolate=periodic nu=0
    let periodic = [
        0.0421968787515002,
        2.1775510204081634,
        0.7427450980392155,
        -0.6003921568627449,
        0.7427450980392155,
        -0.6003921568627449,
        1.073529411764706,
        1.2058823529411766,
        0.18718979779411732,
        2.093267463235294,
        0.7427450980392155,
        -0.6003921568627449,
        0.871948779511805,
        -0.010604241696678063,
        -0.3935624249699884,
        2.2730792316926767,
    ];
    close(
        &s.eval(&X, 0, Extrapolate::Periodic).unwrap(),
        &periodic,
        1e-12,
    );
    // eval extrapolate=periodic nu=1
    let periodic1 = [
        -2.8190276110444175,
        1.4891956782713076,
        0.09411764705882364,
        3.3294117647058816,
        0.09411764705882364,
        3.3294117647058816,
        -1.3235294117647058,
        2.6470588235294117,
        -2.9648437499999996,
        1.8708639705882346,
        0.09411764705882364,
        3.3294117647058816,
        1.0204081632653064,
        2.6350540216086427,
        -1.2850390156062386,
        -0.7144357743097287,
    ];
    close(
        &s.eval(&X, 1, Extrapolate::Periodic).unwrap(),
        &periodic1,
        1e-12,
    );
    // eval extrapolate=False nu=0
    let nan = f64::NAN;
    let off = [
        nan,
        nan,
        0.7427450980392155,
        -0.6003921568627449,
        0.7427450980392155,
        -0.6003921568627449,
        1.073529411764706,
        1.2058823529411766,
        0.18718979779411732,
        2.093267463235294,
        0.033653846153846145,
        1.0096153846153846,
        nan,
        nan,
        nan,
        nan,
    ];
    let mut out = vec![0.0; 16];
    assert_eq!(s.eval_into(&X, 0, Extrapolate::Off, &mut out).unwrap(), 3);
    close(&out, &off, 1e-12);
    // NaN points give NaN rows in every mode.
    let got = s.eval(&[f64::NAN, 1.0], 0, Extrapolate::On).unwrap();
    assert!(got[0].is_nan() && got[1].is_nan() && got[2].is_finite());
}

#[test]
fn eval_general_degree() {
    let t: Vec<f64> = (0..20).map(|i| f64::from(i) / 19.0).collect();
    let c: Vec<f64> = (0..12).map(|i| f64::from(i).sin()).collect();
    let s = ColumnSpline::new(t, c, 7, 1).unwrap();
    let x = [-0.1, 0.4, 0.5, 0.61, 0.65, 1.2];
    // eval k=7 nu=0
    let want0 = [
        -414.7257277409832,
        -0.31618610821237886,
        -0.5041158546217667,
        0.6897591232606854,
        0.6284015471614773,
        -2318.0768098887447,
    ];
    close(&s.eval(&x, 0, Extrapolate::On).unwrap(), &want0, 1e-11);
    // eval k=7 nu=2
    let want2 = [
        -98572.47493842931,
        114.14358633297098,
        181.9766553240906,
        -248.99374838054663,
        -226.86106181233058,
        -264305.65418368345,
    ];
    close(&s.eval(&x, 2, Extrapolate::On).unwrap(), &want2, 1e-10);
}

#[test]
fn bad_input_is_an_error() {
    let e = ColumnSpline::new(vec![0.0, 1.0, 2.0], vec![1.0], 1, 1).unwrap_err();
    assert!(e.message().contains("Need at least 4 knots"), "{e}");
    let e = ColumnSpline::new(vec![0.0, 2.0, 1.0, 3.0], vec![1.0, 1.0], 1, 1).unwrap_err();
    assert!(e.message().contains("non-decreasing"), "{e}");
    let e = ColumnSpline::new(vec![0.0, 1.0, 1.0, 1.0], vec![1.0, 1.0], 1, 1).unwrap_err();
    assert!(e.message().contains("two internal knots"), "{e}");
    let e = ColumnSpline::new(vec![0.0, f64::NAN, 1.0, 1.0], vec![1.0, 1.0], 1, 1).unwrap_err();
    assert!(e.message().contains("nans or infs"), "{e}");
    let e = ColumnSpline::new(vec![0.0, 0.0, 1.0, 1.0], vec![1.0], 1, 1).unwrap_err();
    assert!(e.message().contains("inconsistent"), "{e}");
    let s = ColumnSpline::new(vec![0.0, 0.0, 1.0, 1.0], vec![1.0, 2.0], 1, 1).unwrap();
    assert!(
        s.eval_into(&[0.5], 0, Extrapolate::On, &mut [0.0; 2])
            .is_err()
    );
}

#[test]
fn derivative_and_antiderivative_match_scipy() {
    let s = cubic();
    let d = s.derivative(2).unwrap();
    // derivative(2) t, c
    assert_eq!(d.knots(), &[0.0, 0.3, 1.0, 1.7, 2.0, 2.6]);
    close(
        d.coefficients(),
        &[
            7.294117647058823,
            -4.470588235294118,
            -11.344537815126051,
            2.5210084033613445,
            15.275735294117647,
            -16.433823529411764,
            1.2019230769230766,
            2.7243589743589745,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        1e-12,
    );
    let a = s.antiderivative(2).unwrap();
    // antiderivative(2) t, c
    assert_eq!(
        a.knots(),
        &[
            -1.0, -1.0, -1.0, -0.5, 0.0, 0.3, 1.0, 1.7, 2.0, 2.6, 3.0, 3.1, 3.1, 3.1
        ]
    );
    let mut want = vec![
        0.0,
        0.0,
        0.0,
        0.0,
        0.27,
        -0.54,
        0.6575,
        -1.04,
        1.5805,
        -1.3,
        2.2284999999999995,
        -0.6384999999999998,
        2.7849999999999993,
        -0.01899999999999986,
    ];
    for _ in 0..7 {
        want.extend([3.3029999999999995, 0.29600000000000015]);
    }
    close(a.coefficients(), &want, 1e-12);
    // The derivative undoes the antiderivative (FITPACK's padding aside).
    let back = a.derivative(2).unwrap();
    assert_eq!(back.knots(), s.knots());
    close(&back.coefficients()[..12], s.coefficients(), 1e-13);
    // Errors: above the degree; an interior knot of multiplicity k + 1.
    let e = s.derivative(4).unwrap_err();
    assert!(e.message().contains("must be <= order of spline"), "{e}");
    let t = vec![0.0, 0.0, 1.0, 1.0, 2.0, 2.0];
    let e = ColumnSpline::new(t, vec![1.0; 4], 1, 1)
        .unwrap()
        .derivative(1)
        .unwrap_err();
    assert!(e.message().contains("internal repeated knots"), "{e}");
}

#[test]
fn integrals_match_scipy() {
    let s = cubic();
    let cases = [
        // integrate(-1.5, 4.0) extrapolate=True
        (
            -1.5,
            4.0,
            Extrapolate::On,
            [-3.8658756130658, 26.57103441804064],
        ),
        // integrate(0.5, 1.8), integrate(1.8, 0.5)
        (
            0.5,
            1.8,
            Extrapolate::On,
            [0.6511021588122426, 1.8637022415803932],
        ),
        (
            1.8,
            0.5,
            Extrapolate::On,
            [-0.6511021588122426, -1.8637022415803932],
        ),
        // integrate(-1.5, 4.0) extrapolate=False
        (
            -1.5,
            4.0,
            Extrapolate::Off,
            [0.7704639894419304, 2.0917922322775264],
        ),
        // integrate(-3.3, 7.9) periodic: several periods
        (
            -3.3,
            7.9,
            Extrapolate::Periodic,
            [5.376350339735251, 13.211543683231838],
        ),
        // integrate(1.9, 2.1) periodic: across the end of the period
        (
            1.9,
            2.1,
            Extrapolate::Periodic,
            [0.06699082237061504, 0.07844810493641907],
        ),
    ];
    for (a, b, mode, want) in cases {
        close(&s.integrate(a, b, mode).unwrap(), &want, 1e-12);
    }
    assert_eq!(
        s.integrate(-3.0, -2.0, Extrapolate::Off).unwrap(),
        vec![0.0, 0.0]
    );
    assert!(s.integrate(f64::NAN, 1.0, Extrapolate::On).is_err());
}

#[test]
fn roots_match_scipy() {
    // roots column 1
    close(&cubic().roots(1).unwrap(), &[0.5040318843835596], 1e-12);
    // roots linear jump: the sign change at the double knot is a root.
    let s = ColumnSpline::new(
        vec![0.0, 0.0, 1.0, 1.0, 2.0, 2.0],
        vec![-1.0, -0.5, 0.5, 2.0],
        1,
        1,
    )
    .unwrap();
    assert_eq!(s.roots(0).unwrap(), vec![1.0]);
    // roots quintic (companion matrix)
    let mut t5 = vec![0.0; 6];
    t5.extend([0.5, 1.1, 2.0]);
    t5.extend([3.0; 6]);
    let c5 = vec![1.0, -2.0, 0.5, 3.0, -1.0, 0.2, 0.7, -0.4, 1.0];
    let s5 = ColumnSpline::new(t5, c5, 5, 1).unwrap();
    close(
        &s5.roots(0).unwrap(),
        &[0.04239475451348046, 0.31065288990858764],
        1e-10,
    );
    assert!(s5.roots(1).is_err());
}

mod construction;
