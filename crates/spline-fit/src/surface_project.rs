//! Closest points on surfaces (point inversion): a hierarchy of bounding boxes over the
//! Bézier patches, built once, then a best-first search with a box-constrained Newton
//! iteration on the leaves.

use crate::slab::Slab;
use spline_core::{
    ControlPoint, Error, ErrorKind, Result, Scalar, cast, power_of_two_scale, to_f64,
};
use spline_geom::{Direction, ParamSurface, Surface};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Leaves of the hierarchy are sub-patches whose box diagonal is at most this fraction of
/// the whole surface's (or that were split [`MAX_SPLITS`] times).
const LEAF_FRACTION: f64 = 1.0 / 12.0;
/// Splits of one Bézier patch at most (each halves one direction).
const MAX_SPLITS: usize = 10;
/// Newton iterations at most.
const MAX_NEWTON: usize = 60;

/// The point of a surface closest to a given point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceProjection<T, P> {
    /// The parameter `u` of the closest point.
    pub u: T,
    /// The parameter `v` of the closest point.
    pub v: T,
    /// The closest point $S(u, v)$.
    pub point: P,
    /// Its distance to the given point.
    pub distance: T,
}

/// A parameter rectangle `((u0, u1), (v0, v1))`.
pub(crate) type Rect<T> = ((T, T), (T, T));

/// A node of the hierarchy: the box of its control points, its parameter rectangle and its
/// children (none for a leaf); leaves also hold the oriented slab of their control points.
#[derive(Clone, Debug)]
pub(crate) struct Node<T, P> {
    pub(crate) lo: P,
    pub(crate) hi: P,
    pub(crate) rect: Rect<T>,
    pub(crate) children: Option<(usize, usize)>,
    pub(crate) slab: Option<Slab<T, P>>,
}

impl<T: Scalar, P: ControlPoint<T>> Node<T, P> {
    /// A lower bound of the distance from `q` to the node's piece of surface: the distance
    /// to its box, or to its slab where that is larger.
    pub(crate) fn bound(&self, q: &P) -> T {
        let d = box_distance(&self.lo, &self.hi, q);
        self.slab.as_ref().map_or(d, |s| d.max(s.distance(q)))
    }
}

/// The box `(min, max)` of points (not empty).
pub(crate) fn bounding_box<T: Scalar, P: ControlPoint<T>>(
    points: impl Iterator<Item = P>,
) -> (P, P) {
    let mut points = points;
    let first = points.next().expect("a box of at least one point");
    let (mut lo, mut hi) = (first, first);
    for p in points {
        for c in 0..P::DIM {
            lo.set_coord(c, lo.coord(c).min(p.coord(c)));
            hi.set_coord(c, hi.coord(c).max(p.coord(c)));
        }
    }
    (lo, hi)
}

/// The distance from `q` to the box `[lo, hi]` (zero inside).
pub(crate) fn box_distance<T: Scalar, P: ControlPoint<T>>(lo: &P, hi: &P, q: &P) -> T {
    // The length of the gap vector, without overflow or underflow of its squares.
    P::from_coords(|c| {
        let x = q.coord(c);
        (lo.coord(c) - x).max(x - hi.coord(c)).max(T::zero())
    })
    .length()
}

/// A bounding-box hierarchy over a surface: the Bézier patches of its container, split by
/// de Casteljau (in homogeneous space for rational surfaces) until each leaf is small; every
/// node holds the box of its Cartesian control points, which contains its piece of the
/// surface (convex hull property, positive weights).
#[derive(Clone, Debug)]
pub(crate) struct BoxTree<T, P> {
    pub(crate) nodes: Vec<Node<T, P>>,
    pub(crate) root: usize,
}

impl<T: Scalar, P: ControlPoint<T>> BoxTree<T, P> {
    /// The hierarchy of `surface`.
    pub(crate) fn new<S: ParamSurface<T, Point = P>>(surface: &S) -> Result<Self> {
        let patches = surface.bezier_patches();
        let project = |s: &Surface<T, S::Coefficient>| {
            bounding_box(s.control_points().iter().map(S::project))
        };
        let mut all = Vec::new();
        for row in &patches {
            for patch in row {
                all.push(project(patch));
            }
        }
        let (lo, hi) = bounding_box(all.iter().flat_map(|(a, b)| [*a, *b]));
        let size = (hi - lo).length();
        let mut tree = Self {
            nodes: Vec::new(),
            root: 0,
        };
        let min_size = size * cast::<T>(LEAF_FRACTION);
        let (rows, cols) = (patches.len(), patches.first().map_or(0, Vec::len));
        if rows == 0 || cols == 0 {
            return Err(Error::new(
                ErrorKind::DegenerateGeometry,
                "the surface has no Bézier patch",
            ));
        }
        tree.root = tree.build_range::<S>(&patches, (0, rows), (0, cols), min_size)?;
        Ok(tree)
    }

    fn push(&mut self, node: Node<T, P>) -> usize {
        self.nodes.push(node);
        self.nodes.len() - 1
    }

    fn join(&mut self, a: usize, b: usize) -> usize {
        let (na, nb) = (&self.nodes[a], &self.nodes[b]);
        let (lo, hi) = bounding_box([na.lo, na.hi, nb.lo, nb.hi].into_iter());
        let rect = (
            (na.rect.0.0.min(nb.rect.0.0), na.rect.0.1.max(nb.rect.0.1)),
            (na.rect.1.0.min(nb.rect.1.0), na.rect.1.1.max(nb.rect.1.1)),
        );
        self.push(Node {
            lo,
            hi,
            rect,
            children: Some((a, b)),
            slab: None,
        })
    }

    fn build_range<S: ParamSurface<T, Point = P>>(
        &mut self,
        patches: &[Vec<Surface<T, S::Coefficient>>],
        (i0, i1): (usize, usize),
        (j0, j1): (usize, usize),
        min_size: T,
    ) -> Result<usize> {
        if i1 - i0 == 1 && j1 - j0 == 1 {
            return self.build_patch::<S>(&patches[i0][j0], 0, min_size);
        }
        let (a, b) = if i1 - i0 >= j1 - j0 {
            let mid = (i0 + i1) / 2;
            (
                self.build_range::<S>(patches, (i0, mid), (j0, j1), min_size)?,
                self.build_range::<S>(patches, (mid, i1), (j0, j1), min_size)?,
            )
        } else {
            let mid = (j0 + j1) / 2;
            (
                self.build_range::<S>(patches, (i0, i1), (j0, mid), min_size)?,
                self.build_range::<S>(patches, (i0, i1), (mid, j1), min_size)?,
            )
        };
        Ok(self.join(a, b))
    }

    fn build_patch<S: ParamSurface<T, Point = P>>(
        &mut self,
        patch: &Surface<T, S::Coefficient>,
        splits: usize,
        min_size: T,
    ) -> Result<usize> {
        let (lo, hi) = bounding_box(patch.control_points().iter().map(S::project));
        let rect = patch.domain();
        let (nu, nv) = patch.net_size();
        let leaf = || {
            let net: Vec<P> = patch.control_points().iter().map(S::project).collect();
            Node {
                lo,
                hi,
                rect,
                children: None,
                slab: Slab::of_net(&net, nu, nv),
            }
        };
        if (hi - lo).length() <= min_size || splits >= MAX_SPLITS {
            return Ok(self.push(leaf()));
        }
        // Split the direction along which the control net is longer.
        let cp = patch.control_points();
        let mut along = [T::zero(); 2];
        for i in 0..nu {
            for j in 0..nv {
                let p = S::project(&cp[i * nv + j]);
                if i + 1 < nu {
                    along[0] = along[0].max((S::project(&cp[(i + 1) * nv + j]) - p).length());
                }
                if j + 1 < nv {
                    along[1] = along[1].max((S::project(&cp[i * nv + j + 1]) - p).length());
                }
            }
        }
        let direction = if along[0] >= along[1] {
            Direction::U
        } else {
            Direction::V
        };
        let (a, b) = match direction {
            Direction::U => rect.0,
            Direction::V => rect.1,
        };
        let mid = (a + b) * cast::<T>(0.5);
        if !(mid > a && mid < b) {
            return Ok(self.push(leaf()));
        }
        let (left, right) = patch.split(direction, mid)?;
        let l = self.build_patch::<S>(&left, splits + 1, min_size)?;
        let r = self.build_patch::<S>(&right, splits + 1, min_size)?;
        Ok(self.join(l, r))
    }
}

/// A heap entry ordered by its bound (smallest first).
struct Entry {
    bound: f64,
    node: usize,
}

impl PartialEq for Entry {
    fn eq(&self, other: &Self) -> bool {
        self.bound == other.bound
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other.bound.total_cmp(&self.bound)
    }
}

/// Closest points on one surface for many query points: the box hierarchy is built once
/// ([`SurfaceProjector::new`]); each query ([`SurfaceProjector::closest`]) visits the
/// nodes in the order of their box distance — a lower bound of the distance to their piece
/// of the surface — and runs a Newton iteration in every leaf that can still beat the best
/// distance found, so the search is global: a piece is skipped only when its box proves that
/// it is farther away.
///
/// The Newton iteration minimises $f(u, v) = \tfrac12 \lVert S(u, v) - Q \rVert^2$ with
/// the exact Hessian (Gauss–Newton where it is not positive definite), box-constrained to
/// the leaf's rectangle (a variable at a bound whose gradient points outward is held, the
/// other one moves: minima on the boundary of the domain are found as such), with a
/// decrease test on every step; the best leaf result is polished on the whole domain.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_fit::SurfaceProjector;
/// use spline_geom::NurbsSurface;
/// let sphere = NurbsSurface::sphere(Vector3::new(0.0f64, 0.0, 0.0), 2.0)?;
/// let projector = SurfaceProjector::new(&sphere)?;
/// let hit = projector.closest(Vector3::new(3.0, 4.0, 0.0))?;
/// assert!((hit.distance - 3.0).abs() < 1e-12);
/// assert!((hit.point - Vector3::new(1.2, 1.6, 0.0)).norm() < 1e-12);
/// # Ok::<(), spline_core::Error>(())
/// ```
pub struct SurfaceProjector<'a, T: Scalar, S: ParamSurface<T>> {
    surface: &'a S,
    tree: BoxTree<T, S::Point>,
}

impl<'a, T: Scalar, S: ParamSurface<T>> SurfaceProjector<'a, T, S> {
    /// The hierarchy of bounding boxes of `surface` (any kind: B-spline or NURBS,
    /// [`ParamSurface`]).
    ///
    /// # Errors
    /// [`ErrorKind::DegenerateGeometry`] for a surface without patches (never for a valid
    /// surface); errors of subdivision.
    pub fn new(surface: &'a S) -> Result<Self> {
        Ok(Self {
            surface,
            tree: BoxTree::new(surface)?,
        })
    }

    /// The surface.
    #[must_use]
    pub fn surface(&self) -> &'a S {
        self.surface
    }

    /// The point of the surface closest to `target` (ties go to the first found).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] if `target` is not finite.
    ///
    /// # Panics
    /// Never: the root of the hierarchy is always visited.
    pub fn closest(&self, target: S::Point) -> Result<SurfaceProjection<T, S::Point>> {
        if !target.all_finite() {
            return Err(Error::new(
                ErrorKind::NonFinite,
                "the point to project is not finite",
            ));
        }
        let nodes = &self.tree.nodes;
        let mut best: Option<SurfaceProjection<T, S::Point>> = None;
        let mut best_rect = self.surface.domain();
        let mut heap = BinaryHeap::new();
        let root = &nodes[self.tree.root];
        heap.push(Entry {
            bound: to_f64(root.bound(&target)),
            node: self.tree.root,
        });
        while let Some(Entry { bound, node }) = heap.pop() {
            if best.is_some_and(|b| bound > to_f64(b.distance)) {
                break;
            }
            let n = &nodes[node];
            match n.children {
                Some((a, b)) => {
                    for c in [a, b] {
                        let child = &nodes[c];
                        let bound = to_f64(child.bound(&target));
                        if best.is_none_or(|b| bound <= to_f64(b.distance)) {
                            heap.push(Entry { bound, node: c });
                        }
                    }
                }
                None => {
                    let start = n
                        .slab
                        .as_ref()
                        .map_or_else(|| center(n.rect), |s| s.start(&target, n.rect));
                    let found = newton_in(self.surface, &target, start, n.rect)?;
                    if best.is_none_or(|b| found.distance < b.distance) {
                        best = Some(found);
                        best_rect = n.rect;
                    }
                }
            }
        }
        let best = best.expect("the root is always visited");
        // Polish on the whole domain a leaf result on a leaf's edge inside the domain (one
        // strictly inside its leaf, or on the domain's edge, is already a constrained
        // minimum of the whole domain).
        let ((a, b), (c, d)) = self.surface.domain();
        let settled = |x: T, (lo, hi): (T, T), (first, last): (T, T)| {
            (x > lo && x < hi) || x == first || x == last
        };
        if settled(best.u, best_rect.0, (a, b)) && settled(best.v, best_rect.1, (c, d)) {
            return Ok(best);
        }
        let polished = newton_in(
            self.surface,
            &target,
            (best.u, best.v),
            self.surface.domain(),
        )?;
        Ok(if polished.distance <= best.distance {
            polished
        } else {
            best
        })
    }

    /// The closest points of many targets (the hierarchy is shared).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] for a target that is not finite, naming it.
    pub fn closest_many(
        &self,
        targets: &[S::Point],
    ) -> Result<Vec<SurfaceProjection<T, S::Point>>> {
        targets
            .iter()
            .enumerate()
            .map(|(k, q)| {
                self.closest(*q)
                    .map_err(|e| e.context(format_args!("point {k}")))
            })
            .collect()
    }

    /// A local closest point: the box-constrained Newton iteration from `(u, v)` on the
    /// whole domain (parameter correction of fits, tracing). It finds the nearest local
    /// minimum of the distance, which is global only near a good start.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`] for the start or the target.
    pub fn local(
        &self,
        target: S::Point,
        (u, v): (T, T),
    ) -> Result<SurfaceProjection<T, S::Point>> {
        closest_local(self.surface, target, (u, v))
    }
}

/// The centre of a rectangle.
fn center<T: Scalar>(((u0, u1), (v0, v1)): Rect<T>) -> (T, T) {
    let half: T = cast(0.5);
    ((u0 + u1) * half, (v0 + v1) * half)
}

/// The point of `surface` (any kind, [`ParamSurface`]) closest to `target`: builds a
/// [`SurfaceProjector`] and asks it once (build the projector yourself for many points).
///
/// # Errors
/// As [`SurfaceProjector::new`] and [`SurfaceProjector::closest`].
pub fn closest_point_on_surface<T: Scalar, S: ParamSurface<T>>(
    surface: &S,
    target: S::Point,
) -> Result<SurfaceProjection<T, S::Point>> {
    SurfaceProjector::new(surface)?.closest(target)
}

/// A local closest point by the box-constrained Newton iteration from `(u, v)` on the whole
/// domain ([`SurfaceProjector::local`] without a projector).
///
/// # Errors
/// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`] for the start or the target.
pub fn closest_local<T: Scalar, S: ParamSurface<T>>(
    surface: &S,
    target: S::Point,
    (u, v): (T, T),
) -> Result<SurfaceProjection<T, S::Point>> {
    if !target.all_finite() {
        return Err(Error::new(
            ErrorKind::NonFinite,
            "the point to project is not finite",
        ));
    }
    let domain = surface.domain();
    for (x, (a, b)) in [(u, domain.0), (v, domain.1)] {
        if !x.is_finite() {
            return Err(Error::non_finite(format_args!(
                "start parameter {}",
                to_f64(x)
            )));
        }
        if x < a || x > b {
            return Err(Error::out_of_domain(to_f64(x), (to_f64(a), to_f64(b))));
        }
    }
    newton_in(surface, &target, (u, v), domain)
}

/// The partials `S, S_u, S_v, S_uu, S_uv, S_vv` at `(u, v)`.
pub(crate) fn partials<T: Scalar, S: ParamSurface<T>>(
    surface: &S,
    (u, v): (T, T),
) -> Result<[S::Point; 6]> {
    let mut d = [S::Point::origin(); 9];
    surface.derivatives_into(u, v, 2, &mut d)?;
    // d[k * 3 + l] = ∂^{k+l} S / ∂u^k ∂v^l.
    Ok([d[0], d[3], d[1], d[6], d[4], d[2]])
}

/// The box-constrained, safeguarded Newton iteration for the closest point from `start`
/// inside `rect`.
fn newton_in<T: Scalar, S: ParamSurface<T>>(
    surface: &S,
    target: &S::Point,
    start: (T, T),
    rect: Rect<T>,
) -> Result<SurfaceProjection<T, S::Point>> {
    let ((u0, u1), (v0, v1)) = rect;
    let eps = T::default_epsilon();
    let half: T = cast(0.5);
    let (mut u, mut v) = start;
    // The iteration runs on the points divided by a power of four near their size (exact):
    // the squares and the Hessian's determinant (fourth powers) neither overflow at 1e150
    // nor underflow at 1e-150, and the steps are those of the unscaled problem.
    let first = partials(surface, (u, v))?;
    let size = first
        .iter()
        .fold(target.max_abs(), |m, p| m.max(p.max_abs()));
    let scale: T = cast(power_of_two_scale(to_f64(size)));
    let inverse = T::one() / scale;
    let target = &(*target * inverse);
    let scaled = |d: [S::Point; 6]| d.map(|p| p * inverse);
    let mut d = scaled(first);
    let mut f = (d[0] - *target).length_squared();
    let clamp = |x: T, a: T, b: T| x.max(a).min(b);
    for _ in 0..MAX_NEWTON {
        let r = d[0] - *target;
        // The rounding noise of f = ‖r‖²: r carries errors of the order of eps times the
        // magnitude of the points.
        let noise = cast::<T>(16.0) * eps * r.length() * (d[0].length() + target.length());
        let (su, sv) = (d[1], d[2]);
        let g = [r.dot(&su), r.dot(&sv)];
        let jtj = [su.length_squared(), su.dot(&sv), sv.length_squared()];
        let hess = [
            jtj[0] + r.dot(&d[3]),
            jtj[1] + r.dot(&d[4]),
            jtj[2] + r.dot(&d[5]),
        ];
        // Variables held at a bound with the gradient pointing out of the rectangle.
        let held = [
            (u <= u0 && g[0] > T::zero()) || (u >= u1 && g[0] < T::zero()),
            (v <= v0 && g[1] > T::zero()) || (v >= v1 && g[1] < T::zero()),
        ];
        let step = |h: [T; 3]| -> Option<(T, T)> {
            match held {
                [true, true] => None,
                [true, false] => (h[2] > T::zero()).then(|| (T::zero(), -g[1] / h[2])),
                [false, true] => (h[0] > T::zero()).then(|| (-g[0] / h[0], T::zero())),
                [false, false] => {
                    let det = h[0] * h[2] - h[1] * h[1];
                    (h[0] > T::zero() && det > eps * h[0] * h[2]).then(|| {
                        (
                            -(h[2] * g[0] - h[1] * g[1]) / det,
                            -(h[0] * g[1] - h[1] * g[0]) / det,
                        )
                    })
                }
            }
        };
        let model = step(hess).or_else(|| step(jtj));
        let (mut du, mut dv) = match model {
            Some(s) => s,
            None => {
                // No curvature information (a pole, a flat spot): a gradient step scaled
                // to the rectangle.
                let gn = (g[0] * g[0] + g[1] * g[1]).sqrt();
                if !(gn > T::zero()) || held == [true, true] {
                    break;
                }
                let scale = ((u1 - u0) + (v1 - v0)) * cast::<T>(0.25) / gn;
                (
                    if held[0] { T::zero() } else { -g[0] * scale },
                    if held[1] { T::zero() } else { -g[1] * scale },
                )
            }
        };
        let mut moved = false;
        for halving in 0..50 {
            let (cu, cv) = (clamp(u + du, u0, u1), clamp(v + dv, v0, v1));
            if cu == u && cv == v {
                break;
            }
            let dc = scaled(partials(surface, (cu, cv))?);
            let fc = (dc[0] - *target).length_squared();
            if fc < f || (model.is_some() && halving == 0 && fc <= f + noise) {
                moved = (cu - u).abs() > eps * (u.abs() + (u1 - u0))
                    || (cv - v).abs() > eps * (v.abs() + (v1 - v0));
                (u, v, d) = (cu, cv, dc);
                f = fc.min(f);
                break;
            }
            du *= half;
            dv *= half;
        }
        if !moved {
            break;
        }
    }
    Ok(SurfaceProjection {
        u,
        v,
        point: d[0] * scale,
        distance: (d[0] - *target).length() * scale,
    })
}
