//! An independent check of a smoothed curve: its curvature sampled densely, knot span by knot
//! span with both one-sided limits at the knots, and the turning points of the samples
//! counted — no constraint algebra involved.

use nalgebra::Vector2;
use spline_core::Result;
use spline_geom::Curve2;

/// A turning point of the sampled curvature.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampledExtremum {
    /// Parameter of the sample where the curvature turns.
    pub param: f64,
    /// `true` for a maximum of the oriented curvature, `false` for a minimum.
    pub maximum: bool,
}

/// The turning points of the oriented curvature `orientation · κ(u)` of `curve`, sampled at
/// `per_span + 1` points of every knot span (both ends included, evaluated on the span's own
/// polynomial, so that each knot contributes its left and right limits). Monotone runs are
/// followed with a hysteresis of `noise` times the range of the curvature: a turn counts
/// once the curvature has moved back by more than that, so rounding on flat stretches does
/// not count.
///
/// # Errors
/// The errors of curve evaluation (none for a valid curve).
pub fn sampled_curvature_extrema(
    curve: &Curve2<f64>,
    orientation: f64,
    per_span: usize,
    noise: f64,
) -> Result<Vec<SampledExtremum>> {
    let samples = sampled_curvature(curve, orientation, per_span)?;
    let (lo, hi) = samples
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
            (lo.min(s.1), hi.max(s.1))
        });
    let threshold = noise * (hi - lo).max(f64::MIN_POSITIVE);
    let mut extrema = Vec::new();
    // Direction of the current run (+1 rising, −1 falling, 0 unknown) and its extreme sample.
    let mut direction = 0i8;
    let mut extreme = samples[0];
    for &(u, k) in &samples[1..] {
        match direction {
            0 => {
                if k - extreme.1 > threshold {
                    direction = 1;
                    extreme = (u, k);
                } else if extreme.1 - k > threshold {
                    direction = -1;
                    extreme = (u, k);
                }
            }
            1 => {
                if k >= extreme.1 {
                    extreme = (u, k);
                } else if extreme.1 - k > threshold {
                    extrema.push(SampledExtremum {
                        param: extreme.0,
                        maximum: true,
                    });
                    direction = -1;
                    extreme = (u, k);
                }
            }
            _ => {
                if k <= extreme.1 {
                    extreme = (u, k);
                } else if k - extreme.1 > threshold {
                    extrema.push(SampledExtremum {
                        param: extreme.0,
                        maximum: false,
                    });
                    direction = 1;
                    extreme = (u, k);
                }
            }
        }
    }
    Ok(extrema)
}

/// `(u, orientation · κ(u))` on every knot span, both ends included.
fn sampled_curvature(
    curve: &Curve2<f64>,
    orientation: f64,
    per_span: usize,
) -> Result<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    for segment in curve.bezier_segments() {
        let (a, b) = segment.interval();
        let first = segment.derivative();
        let second = first.derivative();
        for k in 0..=per_span {
            let u = if k == per_span {
                b
            } else {
                (a + (b - a) * k as f64 / per_span as f64).min(b)
            };
            let d1: Vector2<f64> = first.eval(u)?;
            let d2: Vector2<f64> = second.eval(u)?;
            let speed = d1.norm();
            let kappa = if speed > 0.0 {
                (d1.x * d2.y - d1.y * d2.x) / (speed * speed * speed)
            } else {
                0.0
            };
            out.push((u, orientation * kappa));
        }
    }
    Ok(out)
}
