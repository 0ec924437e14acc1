//! The batch of the piecewise polynomial form across SIMD lanes (issue 27): eight parameters
//! are evaluated at once, each lane with its own span, in the vector unit the CPU has.
//!
//! The kernel is plain Rust over fixed-size arrays of lanes — the group's buckets, spans, local
//! parameters `t = u − u_s` and Horner accumulators, `G = 8` points of `W` doubles (1, 2, or 4
//! for 3 and 4 coordinates) — and [`pulp::Arch`] runs it compiled for the unit it detects at
//! run time (AVX2 with FMA), where LLVM turns the lane loops into vector instructions: the
//! bucket formula for eight parameters at once, Horner's steps on whole registers of points.
//! pulp does the `unsafe` (calling code compiled for a detected feature); this crate has none.
//! Without AVX2 (or on other architectures without a vector unit pulp knows) the scalar
//! batch runs.
//!
//! It is the scalar batch's arithmetic, lane by lane and coordinate by coordinate: the same
//! span, `t` by one subtraction, Horner's scheme by a multiplication and an addition per
//! step (no fused multiply-add), so the values are the scalar path's **bit for bit** (the
//! tests compare the bits). The lanes take `f64` only (other scalars — `f32`, dual numbers —
//! keep the scalar path) and points of 1 to 4 coordinates, homogeneous ones included (the
//! NURBS batch projects each point as before); the span is found with the [`SpanTable`]'s
//! buckets, so the lanes are used when every bucket holds at most one distinct knot value
//! (all but strongly clustered knots, which keep the scalar path: it walks them).

use pulp::{Arch, Simd, WithSimd};
use spline_core::{ControlPoint, KnotVector, Scalar, SpanTable, cast, to_f64};
use std::any::TypeId;
use std::marker::PhantomData;

/// `2^52`: for `0 ≤ x < 2^51`, `x + 2^52` holds `x` rounded to an integer in its low bits.
const MAGIC: f64 = 4_503_599_627_370_496.0;

/// A bucket of the span table, with the knot that decides between its two spans.
#[derive(Clone, Copy, Debug)]
struct Bucket {
    /// The knot starting span `next` (`u ≥ threshold` lies in `next`, otherwise in `left`).
    threshold: f64,
    /// The first double of the block of the span at the bucket's left edge.
    left: u32,
    /// The first double of the block of the span starting inside the bucket (or `left`).
    next: u32,
}

/// The piecewise polynomial form laid out for the lanes: the span table's buckets with their
/// deciding knots, every span's left knot, and its Taylor coefficients as `N` blocks of `W`
/// doubles. Empty (inactive) where the lanes do not apply.
#[derive(Debug, Default)]
pub(crate) struct LaneForm {
    active: bool,
    /// `N = p + 1`.
    order: usize,
    /// `W`: 1, 2 or 4 doubles per point (3 coordinates padded to 4).
    width: usize,
    /// The bucket formula: `⌊min(max(0, (u − start) · scale), last_bucket)⌋`.
    start: f64,
    scale: f64,
    last_bucket: f64,
    /// The domain's end: parameters there go through the triangular scheme.
    end: f64,
    buckets: Vec<Bucket>,
    /// `(N + 1) · W` doubles per span (from the first): its left knot (padded to `W`), then
    /// `c_0 … c_p`, each padded to `W` coordinates.
    blocks: Vec<f64>,
}

/// Whether the scalar type is `f64` (the only one the lanes take).
fn is_f64<T: 'static>() -> bool {
    TypeId::of::<T>() == TypeId::of::<f64>()
}

impl LaneForm {
    /// Lays out the Taylor coefficients (`order` per span, from the first span) of a curve
    /// with these knots and span table, reusing the storage; inactive where the lanes do not
    /// apply (not `f64`, more than 4 coordinates, a bucket with several distinct knots).
    pub(crate) fn fill<T: Scalar, P: ControlPoint<T>>(
        &mut self,
        table: &SpanTable,
        knots: &KnotVector<T>,
        coefficients: &[P],
        order: usize,
    ) {
        self.active = false;
        let width = match P::DIM {
            1 => 1,
            2 => 2,
            3 | 4 => 4,
            _ => return,
        };
        let count = table.buckets().len();
        let spans = coefficients.len() / order;
        #[allow(clippy::cast_precision_loss)]
        let last_bucket = (count - 1) as f64;
        let stride = width * (order + 1);
        if !is_f64::<T>()
            || u32::try_from(spans.saturating_mul(stride)).is_err()
            || last_bucket >= MAGIC / 2.0
        {
            return;
        }
        let p = order - 1;
        let k = knots.knots();
        self.buckets.clear();
        for bucket in table.buckets() {
            let Some([left, next]) = bucket else {
                return;
            };
            let row = |s: usize| u32::try_from((s - p) * stride).expect("checked above");
            self.buckets.push(Bucket {
                threshold: to_f64(k[next]),
                left: row(left),
                next: row(next),
            });
        }
        self.blocks.clear();
        for (&left, row) in k[p..p + spans].iter().zip(coefficients.chunks_exact(order)) {
            self.blocks.push(to_f64(left));
            self.blocks.extend(std::iter::repeat_n(0.0, width - 1));
            for c in row {
                self.blocks
                    .extend((0..width).map(|d| if d < P::DIM { to_f64(c.coord(d)) } else { 0.0 }));
            }
        }
        let (start, scale) = table.bucket_scale();
        self.order = order;
        self.width = width;
        self.start = start;
        self.scale = scale;
        self.last_bucket = last_bucket;
        self.end = to_f64(knots.domain().1);
        self.active = true;
    }

    /// The points `C(u)` of a group of `G` parameters below the domain's end, `W` doubles
    /// each, by the scalar batch's arithmetic in every lane.
    #[inline(always)]
    fn group<const N: usize, const W: usize, const G: usize>(
        &self,
        us: &[f64; G],
    ) -> [[f64; W]; G] {
        // The table's bucket formula in every lane at once, the integer read from the low
        // bits of the floor plus 2^52 (no conversion instruction, which AVX2 lacks).
        let mut buckets = [0u64; G];
        for (bucket, &u) in buckets.iter_mut().zip(us) {
            let x = ((u - self.start) * self.scale)
                .max(0.0)
                .min(self.last_bucket);
            *bucket = (x.floor() + MAGIC).to_bits() - MAGIC.to_bits();
        }
        // Lane by lane: the span's block (its left knot, then the coefficients).
        let stride = W * (N + 1);
        let mut blocks: [&[f64]; G] = [&[]; G];
        for ((block, &bucket), &u) in blocks.iter_mut().zip(&buckets).zip(us) {
            #[allow(clippy::cast_possible_truncation)]
            let bucket = self.buckets[bucket as usize];
            let first = if u >= bucket.threshold {
                bucket.next
            } else {
                bucket.left
            } as usize;
            *block = &self.blocks[first..first + stride];
        }
        let mut t = [0.0; G];
        for ((t, &u), block) in t.iter_mut().zip(us).zip(&blocks) {
            *t = u - block[0];
        }
        let mut acc = [[0.0; W]; G];
        for (acc, block) in acc.iter_mut().zip(&blocks) {
            acc.copy_from_slice(&block[N * W..(N + 1) * W]);
        }
        for k in (0..N - 1).rev() {
            for ((acc, block), &t) in acc.iter_mut().zip(&blocks).zip(&t) {
                for (a, &ck) in acc.iter_mut().zip(&block[(k + 1) * W..(k + 2) * W]) {
                    *a = *a * t + ck;
                }
            }
        }
        acc
    }
}

/// Writes `map(C(u))` for every parameter (all in the domain) across SIMD lanes, the domain's
/// end through `exact`; `false`, with nothing written, where the lanes do not apply.
pub(crate) fn eval_many_map<T: Scalar, P: ControlPoint<T>, Q>(
    form: &LaneForm,
    params: &[T],
    out: &mut [Q],
    map: &impl Fn(P) -> Q,
    exact: &impl Fn(T) -> P,
) -> bool {
    let arch = Arch::new();
    // Without a vector unit (x86 before AVX2) the scalar path is as fast, and the floor
    // would be a library call.
    if !form.active || !is_f64::<T>() || matches!(arch, Arch::Scalar) {
        return false;
    }
    arch.dispatch(Batch {
        form,
        params,
        out,
        map,
        exact,
        point: PhantomData,
    });
    true
}

/// One batch, run by [`Arch::dispatch`] compiled for the unit it finds.
struct Batch<'a, T, P, Q, M, E> {
    form: &'a LaneForm,
    params: &'a [T],
    out: &'a mut [Q],
    map: &'a M,
    exact: &'a E,
    point: PhantomData<P>,
}

impl<T: Scalar, P: ControlPoint<T>, Q, M: Fn(P) -> Q, E: Fn(T) -> P> WithSimd
    for Batch<'_, T, P, Q, M, E>
{
    type Output = ();

    #[inline(always)]
    fn with_simd<S: Simd>(self, _simd: S) {
        match self.form.width {
            1 => self.by_order::<1, 8>(),
            2 => self.by_order::<2, 8>(),
            _ => self.by_order::<4, 8>(),
        }
    }
}

impl<T: Scalar, P: ControlPoint<T>, Q, M: Fn(P) -> Q, E: Fn(T) -> P> Batch<'_, T, P, Q, M, E> {
    #[inline(always)]
    fn by_order<const W: usize, const G: usize>(self) {
        match self.form.order {
            2 => self.run::<2, W, G>(),
            3 => self.run::<3, W, G>(),
            4 => self.run::<4, W, G>(),
            5 => self.run::<5, W, G>(),
            _ => self.run::<6, W, G>(),
        }
    }

    /// Groups of `G` parameters; a group reaching the domain's end, and the last parameters,
    /// one lane at a time.
    #[inline(always)]
    fn run<const N: usize, const W: usize, const G: usize>(self) {
        let Self {
            form,
            params,
            out,
            map,
            exact,
            ..
        } = self;
        let one = |u: T| {
            let x = to_f64(u);
            if x < form.end {
                point::<T, P, W>(&form.group::<N, W, 1>(&[x])[0])
            } else {
                exact(u)
            }
        };
        let mut slots = out.chunks_exact_mut(G);
        let mut inputs = params.chunks_exact(G);
        for (slots, us) in (&mut slots).zip(&mut inputs) {
            let mut xs = [0.0; G];
            for (x, &u) in xs.iter_mut().zip(us) {
                *x = to_f64(u);
            }
            if xs.iter().fold(true, |inside, &x| inside & (x < form.end)) {
                let values = form.group::<N, W, G>(&xs);
                for (slot, v) in slots.iter_mut().zip(&values) {
                    *slot = map(point::<T, P, W>(v));
                }
            } else {
                for (slot, &u) in slots.iter_mut().zip(us) {
                    *slot = map(one(u));
                }
            }
        }
        for (slot, &u) in slots.into_remainder().iter_mut().zip(inputs.remainder()) {
            *slot = map(one(u));
        }
    }
}

/// The point of the first `P::DIM` of `W` doubles.
#[inline(always)]
fn point<T: Scalar, P: ControlPoint<T>, const W: usize>(v: &[f64; W]) -> P {
    P::from_coords(|d| cast(v[d]))
}

#[cfg(test)]
impl LaneForm {
    /// Whether the lanes apply to this form.
    pub(crate) fn is_active(&self) -> bool {
        self.active
    }
}

#[cfg(test)]
mod tests;
