//! Oriented slabs around the leaves of the closest-point hierarchy: a tighter lower bound of
//! the distance to a small, nearly flat piece of surface than its axis-aligned box.

use spline_core::{ControlPoint, Scalar};

/// A convex set containing points $c_k$: with an origin $o$ and orthonormal directions
/// $e_1, e_2$ (along the rows and the columns of a control net), the points $x$ with
/// $(x - o) \cdot e_1 \in [a_0, a_1]$, $(x - o) \cdot e_2 \in [b_0, b_1]$ and the rest of
/// $x - o$ within $[w_0, w_1]$ along the normal $n = e_1 \times e_2$ (3-D points) or of
/// length at most $w_1$ (other dimensions). It contains the convex hull of the points, so
/// the distance to it bounds the distance to a surface piece from below.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Slab<T, P> {
    origin: P,
    e1: P,
    e2: P,
    normal: Option<P>,
    a: (T, T),
    b: (T, T),
    w: (T, T),
}

/// `x` with its components along `e` removed, and those components.
fn split<T: Scalar, P: ControlPoint<T>>(x: P, e1: &P, e2: &P) -> (T, T, P) {
    let (a, b) = (x.dot(e1), x.dot(e2));
    (a, b, x - *e1 * a - *e2 * b)
}

fn widen<T: Scalar>((lo, hi): (T, T), x: T) -> (T, T) {
    (lo.min(x), hi.max(x))
}

fn gap<T: Scalar>((lo, hi): (T, T), x: T) -> T {
    (lo - x).max(x - hi).max(T::zero())
}

impl<T: Scalar, P: ControlPoint<T>> Slab<T, P> {
    /// The slab of a control net (`rows × cols`, row-major Cartesian points), or `None` when
    /// the net has no two independent directions.
    pub(crate) fn of_net(points: &[P], rows: usize, cols: usize) -> Option<Self> {
        if points.len() != rows * cols || rows < 2 || cols < 2 {
            return None;
        }
        let count: T = spline_core::from_count(points.len());
        let origin = points.iter().fold(P::origin(), |s, p| s + *p) * (T::one() / count);
        let (mut du, mut dv) = (P::origin(), P::origin());
        for j in 0..cols {
            du += points[(rows - 1) * cols + j] - points[j];
        }
        for i in 0..rows {
            dv += points[i * cols + cols - 1] - points[i * cols];
        }
        let lu = du.length();
        if !(lu > T::zero()) {
            return None;
        }
        let e1 = du * (T::one() / lu);
        let dv = dv - e1 * dv.dot(&e1);
        let lv = dv.length();
        if !(lv > lu * T::default_epsilon().sqrt()) {
            return None;
        }
        let e2 = dv * (T::one() / lv);
        let normal = (P::DIM == 3).then(|| {
            let c = |p: &P, i: usize| p.coord(i);
            P::from_coords(|i| {
                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                c(&e1, j) * c(&e2, k) - c(&e1, k) * c(&e2, j)
            })
        });
        let mut slab = Self {
            origin,
            e1,
            e2,
            normal,
            a: (T::max_value()?, T::min_value()?),
            b: (T::max_value()?, T::min_value()?),
            w: (T::max_value()?, T::min_value()?),
        };
        for p in points {
            let (a, b, rest) = split(*p - origin, &e1, &e2);
            slab.a = widen(slab.a, a);
            slab.b = widen(slab.b, b);
            slab.w = widen(slab.w, slab.along_normal(&rest));
        }
        // Rounding of the projections: widen by a relative few ulps of the net's size.
        let pad = (lu + lv) * T::default_epsilon() * spline_core::cast::<T>(64.0);
        slab.a = (slab.a.0 - pad, slab.a.1 + pad);
        slab.b = (slab.b.0 - pad, slab.b.1 + pad);
        slab.w = (slab.w.0 - pad, slab.w.1 + pad);
        slab.all_finite().then_some(slab)
    }

    fn along_normal(&self, rest: &P) -> T {
        match &self.normal {
            Some(n) => rest.dot(n),
            None => rest.length(),
        }
    }

    fn all_finite(&self) -> bool {
        [self.a.0, self.a.1, self.b.0, self.b.1, self.w.0, self.w.1]
            .iter()
            .all(nalgebra::ComplexField::is_finite)
    }

    /// A start for Newton's iteration in the piece over `rect`: the position of `q` along
    /// `e_1, e_2` mapped linearly onto the rectangle.
    pub(crate) fn start(&self, q: &P, ((u0, u1), (v0, v1)): ((T, T), (T, T))) -> (T, T) {
        let (a, b, _) = split(*q - self.origin, &self.e1, &self.e2);
        let unit = |x: T, (lo, hi): (T, T)| ((x - lo) / (hi - lo)).max(T::zero()).min(T::one());
        (
            u0 + (u1 - u0) * unit(a, self.a),
            v0 + (v1 - v0) * unit(b, self.b),
        )
    }

    /// The distance from `q` to the slab (zero inside).
    pub(crate) fn distance(&self, q: &P) -> T {
        let (a, b, rest) = split(*q - self.origin, &self.e1, &self.e2);
        let (ga, gb) = (gap(self.a, a), gap(self.b, b));
        let gw = match &self.normal {
            Some(n) => gap(self.w, rest.dot(n)),
            None => (rest.length() - self.w.1).max(T::zero()),
        };
        // Divided by the largest gap first: no overflow of the squares at 1e300.
        let m = ga.max(gb).max(gw);
        if m > T::zero() {
            let (ga, gb, gw) = (ga / m, gb / m, gw / m);
            m * (ga * ga + gb * gb + gw * gw).sqrt()
        } else {
            T::zero()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Slab;
    use nalgebra::{Vector2, Vector3};

    fn lcg(seed: u64) -> impl FnMut() -> f64 {
        let mut s = seed;
        move || {
            s = s
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            #[allow(clippy::cast_precision_loss)]
            let x = (s >> 11) as f64 / (1u64 << 53) as f64;
            x
        }
    }

    /// Random convex combinations of a random net lie in the slab, and the slab's distance
    /// never exceeds the distance to any of them (a lower bound), in 3-D and in the plane.
    #[test]
    fn contains_the_hull_and_bounds_from_below() {
        let mut rand = lcg(3);
        for _ in 0..50 {
            let net: Vec<Vector3<f64>> = (0..16)
                .map(|k| {
                    let (i, j) = (f64::from(k / 4), f64::from(k % 4));
                    Vector3::new(i + 0.3 * rand(), j + 0.3 * rand(), rand() - 0.5)
                })
                .collect();
            let slab = Slab::of_net(&net, 4, 4).unwrap();
            let flat: Vec<Vector2<f64>> = net.iter().map(nalgebra::Matrix::xy).collect();
            let slab2 = Slab::of_net(&flat, 4, 4).unwrap();
            for _ in 0..20 {
                let weights: Vec<f64> = (0..16).map(|_| rand()).collect();
                let total: f64 = weights.iter().sum();
                let x = net
                    .iter()
                    .zip(&weights)
                    .fold(Vector3::zeros(), |s, (p, w)| s + p * (w / total));
                assert!(slab.distance(&x) < 1e-12);
                assert!(slab2.distance(&x.xy()) < 1e-12);
                let q = Vector3::new(6.0 * rand() - 1.5, 6.0 * rand() - 1.5, 4.0 * rand() - 2.0);
                assert!(slab.distance(&q) <= (q - x).norm() + 1e-12);
                assert!(slab2.distance(&q.xy()) <= (q.xy() - x.xy()).norm() + 1e-12);
            }
        }
    }

    /// A net without two directions has no slab.
    #[test]
    fn degenerate_nets() {
        let line: Vec<Vector3<f64>> = (0..4)
            .map(|k| Vector3::new(f64::from(k), 0.0, 0.0))
            .collect();
        assert!(Slab::of_net(&line, 2, 2).is_none());
        assert!(Slab::of_net(&line, 4, 1).is_none());
    }
}
