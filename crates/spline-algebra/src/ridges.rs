//! Ridges of a bivariate function (thesis §5.7): where an eigenvalue of the Hessian is
//! extremal along its own eigendirection, traced as the zero sets of the root-free ridge
//! polynomials ([`crate::ridge_polynomials`]) and coloured per eigenvalue (thesis 7.1).

use crate::polylines::UvPolyline;
use crate::tensor::ridge_polynomials;
use crate::zero_set::zero_set;
use spline_core::Result;
use spline_geom::Surface;
use std::collections::HashMap;

/// The ridges of a function ([`ridges`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Ridges {
    /// Ridges of the smaller eigenvalue `λ₂` of the Hessian (the larger principal radius
    /// where the graph is convex): red in thesis 7.1.
    pub red: Vec<UvPolyline>,
    /// Ridges of the larger eigenvalue `λ₁`: blue.
    pub blue: Vec<UvPolyline>,
    /// Singular points of the zero sets ([`crate::ZeroSet::singular`]) and umbilics of the
    /// Hessian met on them (`λ₁ = λ₂`, where the colour is undefined).
    pub singular: Vec<[f64; 2]>,
}

/// Which eigenvalue has a ridge at `(u, v)`: `Some(true)` for `λ₁` (blue), `Some(false)`
/// for `λ₂` (red), `None` where neither does (a zero of the ridge polynomial that comes
/// from a vanishing eigenvector form, not from a ridge) or at an umbilic.
fn classify(s: &Surface<f64, f64>, u: f64, v: f64) -> Result<Option<bool>> {
    let d = s.derivatives(u, v, 3)?;
    let (suu, svv, suv) = (d[2][0], d[0][2], d[1][1]);
    let (suuu, suuv, suvv, svvv) = (d[3][0], d[2][1], d[1][2], d[0][3]);
    let disc = (suu - svv).powi(2) + 4.0 * suv * suv;
    let scale = suu.abs().max(svv.abs()).max(suv.abs());
    if !(disc > 1e-16 * scale * scale) {
        return Ok(None);
    }
    let sd = disc.sqrt();
    let c1 = 0.5 * (suuu + suvv);
    let c2 = 2.0 * (suu - svv) * (suuu - suvv) + 8.0 * suv * suuv;
    let c3 = 0.5 * (suuv + svvv);
    let c4 = 2.0 * (suu - svv) * (suuv - svvv) + 8.0 * suv * suvv;
    let c5 = suu + svv;
    // The derivative of an eigenvalue along its eigendirection, relative to the size of
    // the third derivatives (on a ridge the whole gradient of the eigenvalue may vanish).
    let third = suuu.abs().max(suuv.abs()).max(suvv.abs()).max(svvv.abs());
    if !(third > 0.0) {
        return Ok(None);
    }
    let mut measure = [0.0; 2];
    for (k, sign) in [1.0, -1.0].into_iter().enumerate() {
        let lambda = 0.5 * (c5 + sign * sd);
        let grad = [c1 + sign * c2 / (4.0 * sd), c3 + sign * c4 / (4.0 * sd)];
        // The unit eigenvector from the better conditioned of the two forms.
        let (a, b) = ((suv, lambda - suu), (lambda - svv, suv));
        let t = if a.0.hypot(a.1) >= b.0.hypot(b.1) {
            a
        } else {
            b
        };
        let norm = t.0.hypot(t.1);
        measure[k] = if norm > 0.0 {
            (grad[0] * t.0 + grad[1] * t.1).abs() / (norm * third)
        } else {
            f64::INFINITY
        };
    }
    let tol = 1e-6;
    Ok(match (measure[0] < tol, measure[1] < tol) {
        (true, false) => Some(true),
        (false, true) => Some(false),
        _ => None,
    })
}

/// The ridges of a bivariate function `s(u, v)` of degree at least 3 in both directions
/// (thesis §5.7, Hessian model): the zero sets ([`crate::zero_set`], `samples` points per
/// patch width) of both ridge polynomials `e₁e₂d` and `f₁f₂d`, their vertices classified by
/// the eigenvalue whose derivative along its own eigendirection vanishes there (pointwise,
/// from the third derivatives; zeros that come from a degenerate eigenvector form are
/// dropped), the same ridge found in both zero sets kept once.
///
/// ```
/// use spline_core::KnotVector;
/// use spline_geom::Surface;
/// // s(u, v) = (u − ½)⁴ − v²·… : see the tests for closed forms; here a random bicubic.
/// let k = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0])?;
/// let c: Vec<f64> = (0..16).map(|i| ((i * 7) % 5) as f64 - 2.0).collect();
/// let s = Surface::new(k.clone(), k, c)?;
/// let r = spline_algebra::ridges(&s, 8)?;
/// assert!(!r.red.is_empty() || !r.blue.is_empty());
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`crate::ridge_polynomials`] and [`crate::zero_set`].
pub fn ridges(s: &Surface<f64, f64>, samples: usize) -> Result<Ridges> {
    let (first, second) = ridge_polynomials(s)?;
    let mut out = Ridges::default();
    let mut kept: Vec<(bool, UvPolyline)> = Vec::new();
    let ((u0, u1), (v0, v1)) = s.domain();
    let tol = 1e-6 * (u1 - u0).max(v1 - v0);
    for (pass, poly) in [&first, &second].into_iter().enumerate() {
        let set = zero_set(poly, samples)?;
        // On the second pass, the segments of the ridges kept from the first, by cell.
        let near_kept = Segments::new(kept.iter().map(|(_, line)| line.as_slice()), tol);
        out.singular.extend(&set.singular);
        let mut fresh = Vec::new();
        for curve in &set.curves {
            let mut run: Vec<[f64; 2]> = Vec::new();
            let mut colour = None;
            let mut flush = |run: &mut Vec<[f64; 2]>, colour: Option<bool>| {
                if let (Some(c), true) = (colour, run.len() >= 2) {
                    fresh.push((c, std::mem::take(run)));
                }
                run.clear();
            };
            for p in curve {
                let c = classify(s, p[0], p[1])?;
                // On the second pass, points already on a ridge of the first are duplicates.
                let duplicate = pass == 1 && near_kept.near(p);
                let c = if duplicate { None } else { c };
                if c != colour {
                    flush(&mut run, colour);
                    colour = c;
                }
                if c.is_some() {
                    run.push(*p);
                }
            }
            flush(&mut run, colour);
        }
        kept.extend(fresh);
    }
    for (blue, line) in kept {
        if blue {
            out.blue.push(line);
        } else {
            out.red.push(line);
        }
    }
    Ok(out)
}

/// The segments of some polylines by square cell, each listed in every cell its box
/// (widened by `tol`) meets, so that [`Segments::near`] looks at the segments of one cell
/// instead of all of them.
struct Segments<'a> {
    tol: f64,
    side: f64,
    cells: HashMap<(i64, i64), Vec<&'a [[f64; 2]]>>,
}

impl<'a> Segments<'a> {
    fn new(lines: impl Iterator<Item = &'a [[f64; 2]]>, tol: f64) -> Self {
        let segments: Vec<&[[f64; 2]]> = lines.flat_map(|l| l.windows(2)).collect();
        // Cells about as large as a typical segment, never smaller than the tolerance.
        let total: f64 = segments
            .iter()
            .map(|w| (w[1][0] - w[0][0]).abs().max((w[1][1] - w[0][1]).abs()))
            .filter(|x| x.is_finite())
            .sum();
        let mean = total / segments.len().max(1) as f64;
        let side = mean.max(2.0 * tol);
        let side = if side > 0.0 && side.is_finite() {
            side
        } else {
            1.0
        };
        let mut out = Self {
            tol,
            side,
            cells: HashMap::new(),
        };
        for w in segments {
            let lo = out.cell([
                w[0][0].min(w[1][0]) - 2.0 * tol,
                w[0][1].min(w[1][1]) - 2.0 * tol,
            ]);
            let hi = out.cell([
                w[0][0].max(w[1][0]) + 2.0 * tol,
                w[0][1].max(w[1][1]) + 2.0 * tol,
            ]);
            // Widened by twice the tolerance against rounding. A segment across more cells than this (or with invalid ends) goes everywhere.
            let span = hi.0.saturating_sub(lo.0).saturating_add(1) as f64
                * hi.1.saturating_sub(lo.1).saturating_add(1) as f64;
            if !(span <= 4096.0) {
                out.cells.entry((i64::MIN, i64::MIN)).or_default().push(w);
                continue;
            }
            for i in lo.0..=hi.0 {
                for j in lo.1..=hi.1 {
                    out.cells.entry((i, j)).or_default().push(w);
                }
            }
        }
        out
    }

    fn cell(&self, p: [f64; 2]) -> (i64, i64) {
        (
            (p[0] / self.side).floor() as i64,
            (p[1] / self.side).floor() as i64,
        )
    }

    /// Whether `p` is within `tol` of one of the segments.
    fn near(&self, p: &[f64; 2]) -> bool {
        let own = self.cells.get(&self.cell(*p)).into_iter().flatten();
        let everywhere = self.cells.get(&(i64::MIN, i64::MIN)).into_iter().flatten();
        own.chain(everywhere).any(|w| near_polyline(p, w, self.tol))
    }
}

/// Whether `p` is within `tol` of the polyline.
fn near_polyline(p: &[f64; 2], line: &[[f64; 2]], tol: f64) -> bool {
    line.windows(2).any(|w| {
        let (a, b) = (w[0], w[1]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (a[0] + t * dx - p[0]).hypot(a[1] + t * dy - p[1]) <= tol
    })
}

#[cfg(test)]
mod tests {
    use super::{Segments, near_polyline};

    /// Whether a point is near one of the polylines' segments, through the cells and by
    /// looking at every segment, agree on points scattered near and far from short and long
    /// segments.
    #[test]
    fn cells_find_every_near_segment() {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for tol in [1e-6, 1e-3, 0.02] {
            let lines: Vec<Vec<[f64; 2]>> = (0..60)
                .map(|k| {
                    let mut p = [next(), next()];
                    // Mostly short steps, some long ones (a line across many cells).
                    let step = if k % 10 == 0 { 0.5 } else { 0.01 };
                    (0..20)
                        .map(|_| {
                            p = [p[0] + step * (next() - 0.5), p[1] + step * (next() - 0.5)];
                            p
                        })
                        .collect()
                })
                .collect();
            let index = Segments::new(lines.iter().map(Vec::as_slice), tol);
            let (mut near, mut far) = (0, 0);
            for k in 0..20_000 {
                let p = if k % 2 == 0 {
                    // Near a vertex, within a few tolerances.
                    let line = &lines[k % lines.len()];
                    let q = line[(k / 2) % line.len()];
                    [
                        q[0] + 3.0 * tol * (next() - 0.5),
                        q[1] + 3.0 * tol * (next() - 0.5),
                    ]
                } else {
                    [next(), next()]
                };
                let expected = lines.iter().any(|l| near_polyline(&p, l, tol));
                assert_eq!(index.near(&p), expected, "tol {tol}, point {p:?}");
                if expected {
                    near += 1;
                } else {
                    far += 1;
                }
            }
            assert!(near > 1000 && far > 1000, "{near} near, {far} far");
        }
    }
}
