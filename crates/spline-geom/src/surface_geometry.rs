//! Differential geometry of surfaces in space: normal, first and second fundamental forms,
//! Gaussian, mean and principal curvatures and directions.

use nalgebra::Vector3;
use spline_core::{Error, ErrorKind, Result, Scalar, cast, to_f64};

/// A symmetric quadratic form on the tangent plane in the basis $(S_u, S_v)$:
/// $Q(du, dv) = uu\\, du^2 + 2\\, uv\\, du\\, dv + vv\\, dv^2$.
///
/// The first fundamental form has $uu = E = S_u \cdot S_u$, $uv = F = S_u \cdot S_v$,
/// $vv = G = S_v \cdot S_v$; the second $uu = L = S_{uu} \cdot n$, $uv = M = S_{uv} \cdot n$,
/// $vv = N = S_{vv} \cdot n$.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FundamentalForm<T> {
    /// The coefficient of $du^2$ ($E$ or $L$).
    pub uu: T,
    /// The coefficient of $2\\,du\\,dv$ ($F$ or $M$).
    pub uv: T,
    /// The coefficient of $dv^2$ ($G$ or $N$).
    pub vv: T,
}

impl<T: Scalar> FundamentalForm<T> {
    /// The value $Q(du, dv)$.
    #[must_use]
    pub fn eval(&self, du: T, dv: T) -> T {
        self.uu * du * du + (self.uv + self.uv) * du * dv + self.vv * dv * dv
    }

    /// The determinant $uu\\,vv - uv^2$.
    #[must_use]
    pub fn determinant(&self) -> T {
        self.uu * self.vv - self.uv * self.uv
    }
}

/// The local differential properties of a surface at a regular point (the `SLProps` of
/// OpenCASCADE): point, first partial derivatives, unit normal
/// $n = S_u \times S_v / \lVert S_u \times S_v \rVert$, both fundamental forms, and the
/// curvatures, signed with respect to `n`.
///
/// With $I = (E, F, G)$ and $II = (L, M, N)$:
/// $K = \frac{LN - M^2}{EG - F^2}$, $H = \frac{EN - 2FM + GL}{2(EG - F^2)}$,
/// $\kappa_{1,2} = H \pm \sqrt{H^2 - K}$. A sphere whose normal points outwards has
/// $\kappa_1 = \kappa_2 = H = -1/r$ and $K = 1/r^2$.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalProperties<T> {
    /// The point $S(u, v)$.
    pub point: Vector3<T>,
    /// $\partial S / \partial u$.
    pub du: Vector3<T>,
    /// $\partial S / \partial v$.
    pub dv: Vector3<T>,
    /// The unit normal $S_u \times S_v / \lVert S_u \times S_v \rVert$.
    pub normal: Vector3<T>,
    /// The first fundamental form $(E, F, G)$.
    pub first_form: FundamentalForm<T>,
    /// The second fundamental form $(L, M, N)$.
    pub second_form: FundamentalForm<T>,
    /// The Gaussian curvature $K = \kappa_1 \kappa_2$.
    pub gaussian_curvature: T,
    /// The mean curvature $H = (\kappa_1 + \kappa_2) / 2$.
    pub mean_curvature: T,
    /// The largest normal curvature $\kappa_1$.
    pub max_curvature: T,
    /// The smallest normal curvature $\kappa_2$.
    pub min_curvature: T,
    /// The unit tangent along which the normal curvature is $\kappa_1$ (at an umbilic, the
    /// direction of $S_u$).
    pub max_direction: Vector3<T>,
    /// The unit tangent along which the normal curvature is $\kappa_2$,
    /// `normal × max_direction`.
    pub min_direction: Vector3<T>,
}

impl<T: Scalar> LocalProperties<T> {
    /// The properties from the partial derivatives $S, S_u, S_v, S_{uu}, S_{uv}, S_{vv}$.
    ///
    /// # Errors
    /// [`ErrorKind::DegenerateGeometry`] where $S_u \times S_v$ vanishes (numerically: its
    /// length is below `8 ε (|S_u|² + |S_v|²)`), e.g. at the poles of a sphere.
    pub fn from_partials(
        point: Vector3<T>,
        du: Vector3<T>,
        dv: Vector3<T>,
        duu: Vector3<T>,
        duv: Vector3<T>,
        dvv: Vector3<T>,
    ) -> Result<Self> {
        let cross = du.cross(&dv);
        let len = cross.norm();
        let scale = du.norm_squared() + dv.norm_squared();
        let eps = T::default_epsilon();
        if !(len > eps * cast::<T>(8.0) * scale) {
            return Err(Error::new(
                ErrorKind::DegenerateGeometry,
                format!(
                    "the surface is singular at ({}, {}, {}): S_u × S_v vanishes, so the normal and the curvatures are undefined",
                    to_f64(point.x),
                    to_f64(point.y),
                    to_f64(point.z)
                ),
            ));
        }
        let normal = cross / len;
        let first_form = FundamentalForm {
            uu: du.dot(&du),
            uv: du.dot(&dv),
            vv: dv.dot(&dv),
        };
        let second_form = FundamentalForm {
            uu: duu.dot(&normal),
            uv: duv.dot(&normal),
            vv: dvv.dot(&normal),
        };
        let (e, f, g) = (first_form.uu, first_form.uv, first_form.vv);
        let (l, m, n) = (second_form.uu, second_form.uv, second_form.vv);
        // EG − F² = |S_u × S_v|², computed without cancellation.
        let det = len * len;
        let gaussian = (l * n - m * m) / det;
        let mean = (e * n - (f + f) * m + g * l) / (det + det);
        let root = (mean * mean - gaussian).max(T::zero()).sqrt();
        let (k1, k2) = (mean + root, mean - root);
        // (II − κ I)(du, dv) = 0: take the null vector of the better-conditioned row.
        let a = (-(m - k1 * f), l - k1 * e);
        let b = (-(n - k1 * g), m - k1 * f);
        let ta = du * a.0 + dv * a.1;
        let tb = du * b.0 + dv * b.1;
        let t = if ta.norm() >= tb.norm() { ta } else { tb };
        let size = (l.abs() + m.abs() + n.abs() + k1.abs() * (e + f.abs() + g)) * scale.sqrt();
        let max_direction = if t.norm() > eps.sqrt() * size {
            t.normalize()
        } else {
            du.normalize()
        };
        let min_direction = normal.cross(&max_direction);
        Ok(Self {
            point,
            du,
            dv,
            normal,
            first_form,
            second_form,
            gaussian_curvature: gaussian,
            mean_curvature: mean,
            max_curvature: k1,
            min_curvature: k2,
            max_direction,
            min_direction,
        })
    }

    /// The normal curvature $II(du, dv) / I(du, dv)$ along the tangent $du\\,S_u + dv\\,S_v$.
    ///
    /// # Errors
    /// [`ErrorKind::DegenerateGeometry`] if the tangent is zero.
    pub fn normal_curvature(&self, du: T, dv: T) -> Result<T> {
        let first = self.first_form.eval(du, dv);
        if !(first > T::zero()) {
            return Err(Error::new(
                ErrorKind::DegenerateGeometry,
                "the normal curvature needs a non-zero tangent direction",
            ));
        }
        Ok(self.second_form.eval(du, dv) / first)
    }
}
