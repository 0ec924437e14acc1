//! The banded solvers against dense products and each other.

use super::*;

fn dense_mul(a: &[Vec<f64>], x: &[f64]) -> Vec<f64> {
    a.iter()
        .map(|r| r.iter().zip(x).map(|(p, q)| p * q).sum())
        .collect()
}

#[test]
fn band_lu_with_border_matches_dense_product() {
    // A 7×7 matrix: band kl = 1, ku = 1, plus a 2-column right border; needs pivoting.
    let n = 7;
    let mut a = vec![vec![0.0; n]; n];
    for i in 0..n {
        for j in i.saturating_sub(1)..(i + 2).min(n) {
            a[i][j] = ((i * 7 + j * 3) % 5) as f64 - 1.5;
        }
        a[i][5] = 0.3 * i as f64 - 0.7;
        a[i][6] = if i % 2 == 0 { 1.0 } else { -0.25 };
    }
    a[0][0] = 0.0; // forces a row exchange
    let x: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
    let b = dense_mul(&a, &x);
    let mut lu = BandLu::<f64>::zeros(n, 1, 1, 2);
    for i in 0..n {
        for j in 0..n {
            if a[i][j] != 0.0 {
                lu.add(i, j, a[i][j]);
            }
        }
    }
    lu.factor().unwrap();
    let mut rhs = b.clone();
    lu.solve(&mut rhs);
    for (g, e) in rhs.iter().zip(&x) {
        assert!((g - e).abs() < 1e-12, "{rhs:?}");
    }
}

#[test]
fn band_lu_reports_singular() {
    let mut lu = BandLu::<f64>::zeros(3, 1, 1, 0);
    lu.add(0, 0, 1.0);
    lu.add(1, 0, 1.0);
    lu.add(2, 2, 1.0);
    let e = lu.factor().unwrap_err();
    assert_eq!(e.kind(), ErrorKind::SingularSystem);
}

#[test]
fn cholesky_and_qr_agree_on_a_small_problem() {
    // Rows of width 2 over 4 unknowns.
    let rows: Vec<(usize, [f64; 2], f64)> = (0..12)
        .map(|k| {
            let f = k % 3;
            let t = 0.1 * k as f64;
            (f, [1.0 - t / 2.0, 0.3 + t], (k as f64).sin())
        })
        .collect();
    let mut ch = BandCholesky::<f64>::zeros(4, 1);
    let mut rhs = vec![0.0; 4];
    let mut qr = BandQr::<f64, f64>::new(4, 1);
    for (f, v, b) in &rows {
        ch.add_outer(*f, v, 1.0);
        rhs[*f] += v[0] * b;
        rhs[*f + 1] += v[1] * b;
        qr.add_row(*f, v, *b);
    }
    ch.factor(&|i| format!("x{i}")).unwrap();
    ch.solve(&mut rhs);
    let x = qr.solve(&|i| format!("x{i}")).unwrap();
    for (a, b) in rhs.iter().zip(&x) {
        assert!((a - b).abs() < 1e-12, "{rhs:?} {x:?}");
    }
}
