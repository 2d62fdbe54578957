//! `matrix` and `matrix_proj`: the rotation matrix as nine additive numbers (direction
//! cosines), with the translation additive beside them; `matrix_proj` replaces it by the
//! nearest rotation after every step, `matrix` never does.
//!
//! Kinematics: `R' = R [omega]x` (Poisson's equation), linear in `R`. Runge-Kutta steps keep
//! `R^T R = I` only to their local error (the orthogonality constraint is quadratic), so the
//! unprojected chart drifts; its residual is `|R^T R - I|` (Frobenius) and `rotation()`
//! returns the stored numbers as they are, so the drift enters the dynamics.
//!
//! Projection: the orthogonal polar factor `U = R (R^T R)^(-1/2)`, the nearest orthogonal
//! matrix in the Frobenius norm (Higham, *Functions of Matrices*, 2008, Thm. 8.4), a rotation
//! whenever `det R > 0`. Computed by Newton's polar iteration `X <- (X + X^-T)/2` while the
//! defect `|X^T X - I|` exceeds 1e-2 (globally convergent for nonsingular `X`, Higham
//! sec. 8.3), then the Newton-Schulz iteration `X <- X (3 I - X^T X)/2` (quadratic, no
//! inverse: defect `d -> ~3 d^2/4`), until the defect stops decreasing below 1e-15. A matrix
//! that is already orthogonal to round-off is changed by about 1 ulp, so the projection is
//! idempotent to a few eps. A singular or non-finite matrix is left unprojected (returned as
//! is; the run's `check` then reports it): `normalize` never panics.
use nalgebra::{Matrix3, SVector, Vector3};

use super::{Pose, PoseChart};
use crate::math::so3;

/// `|X^T X - I|` (Frobenius).
#[inline(always)]
pub fn orthogonality_defect(x: &Matrix3<f64>) -> f64 {
    (x.transpose() * x - Matrix3::identity()).norm()
}

/// `X^T X - I` and its Frobenius norm, the defect.
#[inline(always)]
fn gram_defect(x: &Matrix3<f64>) -> (Matrix3<f64>, f64) {
    let m = x.transpose() * x - Matrix3::identity();
    let d = m.norm();
    (m, d)
}

/// The orthogonal polar factor of `x` (module docs); `None` if `x` is singular or
/// non-finite, or the iteration does not converge in 60 steps. The Newton-Schulz step reuses
/// the Gram matrix of the defect test (`I - X^T X = -(X^T X - I)` exactly in floating point).
pub fn polar_rotation(x: &Matrix3<f64>) -> Option<Matrix3<f64>> {
    let mut y = *x;
    let (mut m, mut d) = gram_defect(&y);
    for _ in 0..60 {
        if !d.is_finite() {
            return None;
        }
        if d > 1e-2 {
            y = (y + y.try_inverse()?.transpose()) * 0.5;
            (m, d) = gram_defect(&y);
            continue;
        }
        if d <= 1e-15 {
            return Some(y);
        }
        let e = -m;
        let next = y + y * e * 0.5;
        let (mn, dn) = gram_defect(&next);
        if dn >= d {
            // Round-off floor reached: the last step changed y at ulp level only.
            return Some(next);
        }
        y = next;
        (m, d) = (mn, dn);
    }
    None
}

/// One matrix chart; `$proj` says whether it projects after each step.
macro_rules! matrix_chart {
    ($t:ident, $name:literal, $proj:literal) => {
        #[doc = concat!("The `", $name, "` chart: tangent `(R' column-major, xdot)` (12 numbers).")]
        #[derive(Debug, Clone, Copy, Default)]
        pub struct $t;

        impl PoseChart for $t {
            const NAME: &'static str = $name;
            type Coords = Pose<Matrix3<f64>>;
            /// `(R'` column by column`, xdot)`.
            type Tangent = SVector<f64, 12>;
            const LIE: bool = false;
            const SE3: bool = false;
            const CONSTRAINED: bool = true;
            const NORMALIZES: bool = $proj;

            fn from_pose(r: &Matrix3<f64>, x: &Vector3<f64>) -> Self::Coords {
                Pose { rot: *r, x: *x }
            }
            #[inline(always)]
            fn rotation(c: &Self::Coords) -> Matrix3<f64> {
                c.rot
            }
            #[inline(always)]
            fn velocity(
                _c: &Self::Coords,
                r: &Matrix3<f64>,
                omega_body: &Vector3<f64>,
                xdot: &Vector3<f64>,
                _spatial: bool,
            ) -> Self::Tangent {
                let rd = r * so3::hat(omega_body);
                let mut t = SVector::<f64, 12>::zeros();
                t.fixed_rows_mut::<9>(0).copy_from_slice(rd.as_slice());
                t.fixed_rows_mut::<3>(9).copy_from(xdot);
                t
            }
            #[inline(always)]
            fn retract(c: &Self::Coords, d: &Self::Tangent, _spatial: bool) -> Self::Coords {
                Pose {
                    rot: c.rot + Matrix3::from_column_slice(&d.as_slice()[..9]),
                    x: c.x + d.fixed_rows::<3>(9),
                }
            }
            #[inline(always)]
            fn dexp_inv(
                _theta: &Self::Tangent,
                v: &Self::Tangent,
                _spatial: bool,
            ) -> Self::Tangent {
                *v
            }
            fn residual(c: &Self::Coords) -> Option<f64> {
                Some(orthogonality_defect(&c.rot))
            }
            fn conditioning(_c: &Self::Coords) -> f64 {
                1.0
            }
            #[inline(always)]
            fn normalize(c: &mut Self::Coords) -> bool {
                if !$proj {
                    return false;
                }
                match polar_rotation(&c.rot) {
                    Some(u) => {
                        c.rot = u;
                        true
                    }
                    None => false,
                }
            }
            #[inline]
            fn is_finite(c: &Self::Coords) -> bool {
                c.rot.iter().chain(c.x.iter()).all(|v| v.is_finite())
            }
        }
    };
}

matrix_chart!(Matrix, "matrix", false);
matrix_chart!(MatrixProj, "matrix_proj", true);

#[cfg(test)]
mod tests {
    use super::*;

    /// The polar factor agrees with U V^T of the SVD (1e-14), is orthogonal to 1e-15, and
    /// re-projecting it moves it by at most 4 eps; from far (defect ~1) and near (1e-8).
    #[test]
    fn polar_factor_is_svd_factor_and_idempotent() {
        let r = so3::exp(&Vector3::new(0.4, -1.2, 2.0));
        let p = Matrix3::new(0.3, -0.1, 0.2, 0.05, -0.4, 0.1, 0.2, 0.3, 0.25);
        for s in [1e-8, 1e-4, 0.5, 1.0] {
            let x = r + p * s;
            let u = polar_rotation(&x).unwrap();
            let svd = x.svd(true, true);
            let uv = svd.u.unwrap() * svd.v_t.unwrap();
            assert!((u - uv).amax() < 1e-14, "{s}: {:e}", (u - uv).amax());
            assert!(orthogonality_defect(&u) < 1e-15, "{s}");
            assert!(u.determinant() > 0.0);
            let u2 = polar_rotation(&u).unwrap();
            assert!(
                (u2 - u).amax() <= 4.0 * f64::EPSILON,
                "{s}: {:e}",
                (u2 - u).amax()
            );
        }
        assert!(polar_rotation(&Matrix3::zeros()).is_none());
        assert!(polar_rotation(&(r * f64::NAN)).is_none());
    }
}
