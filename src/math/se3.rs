//! The rigid-motion group SE(3): the exponential and logarithm of a twist, the adjoint, and
//! the Jacobian of the exponential (`dexp`, 6x6) with its closed-form inverse.
//!
//! A twist is `xi = (omega, v)` (rotation first), with `xi^ = [[ [omega]x, v ], [0, 0]]` and
//! the group element `g = (R, x)`, `g1 g2 = (R1 R2, x1 + R1 x2)`. Then
//! `exp(xi) = (exp([omega]x), J(omega) v)` with `J = so3::dexp` the left Jacobian of SO(3)
//! (Murray, Li & Sastry, *A Mathematical Introduction to Robotic Manipulation*, 1994,
//! Prop. 2.9; Barfoot, *State Estimation for Robotics*, 2017, eq. 7.83-7.85).
//!
//! In this ordering `ad_xi = [[W, 0], [V, W]]` (`W = [omega]x`, `V = [v]x`) and
//! `dexp(xi) = sum_k ad_xi^k / (k+1)! = [[J, 0], [Q, J]]`, where `Q(omega, v)` is Barfoot's
//! coupling block (eq. 7.86b, there with the rows and columns in the order `(v, omega)`):
//! `Q = V/2 + c1 (WV + VW + WVW) + c2 (WWV + VWW - 3 WVW) + c3 (WVWW + WWVW)` with
//! `c1 = (t - sin t)/t^3`, `c2 = (t^2 + 2 cos t - 2)/(2 t^4)`,
//! `c3 = (2 t - 3 sin t + t cos t)/(2 t^5)`, `t = |omega|`. The inverse is block-triangular,
//! `dexp_inv(xi) = [[A, 0], [-A Q A, A]]` with `A = so3::dexp_inv(omega)`.
//! Conventions follow `math::so3` (Iserles et al., Acta Numerica 2000, sec. 2-3): for
//! `g(t) = exp(theta(t)) g0` with `g' = xi^ g`, `theta' = dexp_inv(theta) xi`; for
//! `g(t) = g0 exp(theta(t))` with `g' = g xi^`, `theta' = dexp_inv(-theta) xi`.
//!
//! The coefficients switch to their Taylor series below `t^2 < 1e-6` (truncation below 1e-19
//! relative); above it the closed forms lose at most `eps` in absolute terms, because each
//! coefficient multiplies a product of `W`s that is as small as its cancellation is large.
//! The inverse is singular at `|omega| = 2 pi`, as on SO(3); `log` returns `|omega| <= pi`.
use nalgebra::{Matrix3, Matrix4, Matrix6, UnitQuaternion, Vector3, Vector6};

use super::so3;

/// The 4x4 matrix `xi^` of a twist `(omega, v)`.
pub fn hat(xi: &Vector6<f64>) -> Matrix4<f64> {
    let w = so3::hat(&omega(xi));
    let mut m = Matrix4::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&w);
    m[(0, 3)] = xi[3];
    m[(1, 3)] = xi[4];
    m[(2, 3)] = xi[5];
    m
}

/// The rotational part of a twist.
#[inline(always)]
pub fn omega(xi: &Vector6<f64>) -> Vector3<f64> {
    Vector3::new(xi[0], xi[1], xi[2])
}

/// The translational part of a twist.
#[inline(always)]
pub fn linear(xi: &Vector6<f64>) -> Vector3<f64> {
    Vector3::new(xi[3], xi[4], xi[5])
}

/// The twist `(omega, v)` from its parts.
#[inline(always)]
pub fn twist(omega: &Vector3<f64>, v: &Vector3<f64>) -> Vector6<f64> {
    Vector6::new(omega.x, omega.y, omega.z, v.x, v.y, v.z)
}

/// `exp(xi)` as `(R, x)`.
#[inline(always)]
pub fn exp(xi: &Vector6<f64>) -> (Matrix3<f64>, Vector3<f64>) {
    let w = omega(xi);
    (so3::exp(&w), so3::dexp(&w) * linear(xi))
}

/// `exp(xi)` as `(q, x)` with the rotation as a unit quaternion.
#[inline(always)]
pub fn exp_quat(xi: &Vector6<f64>) -> (UnitQuaternion<f64>, Vector3<f64>) {
    let w = omega(xi);
    (so3::exp_quat(&w), so3::dexp(&w) * linear(xi))
}

/// The twist of `(R, x)` with `|omega| <= pi`: `omega = log R`, `v = J(omega)^-1 x`.
pub fn log(r: &Matrix3<f64>, x: &Vector3<f64>) -> Vector6<f64> {
    let w = so3::log(r);
    twist(&w, &so3::dexp_inv_apply(&w, x))
}

/// `ad_xi` (6x6): `ad_xi eta = [xi, eta] = (w1 x w2, w1 x v2 + v1 x w2)`.
pub fn ad(xi: &Vector6<f64>) -> Matrix6<f64> {
    let w = so3::hat(&omega(xi));
    let v = so3::hat(&linear(xi));
    let mut m = Matrix6::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&w);
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(&w);
    m.fixed_view_mut::<3, 3>(3, 0).copy_from(&v);
    m
}

/// `(c1, c2, c3)` of the coupling block as functions of `t2 = |omega|^2`.
#[inline(always)]
fn coupling_coeffs(t2: f64) -> (f64, f64, f64) {
    if t2 < 1e-6 {
        (
            1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0,
            1.0 / 24.0 - t2 / 720.0 + t2 * t2 / 40320.0,
            1.0 / 120.0 - t2 / 2520.0 + t2 * t2 / 120960.0,
        )
    } else {
        let t = t2.sqrt();
        let (s, c) = t.sin_cos();
        (
            (t - s) / (t2 * t),
            (t2 + 2.0 * c - 2.0) / (2.0 * t2 * t2),
            (2.0 * t - 3.0 * s + t * c) / (2.0 * t2 * t2 * t),
        )
    }
}

/// The coupling block `Q(omega, v)` of `dexp` (module docs) as a matrix.
pub fn coupling(w: &Vector3<f64>, v: &Vector3<f64>) -> Matrix3<f64> {
    let (c1, c2, c3) = coupling_coeffs(w.norm_squared());
    let ww = so3::hat(w);
    let vv = so3::hat(v);
    let wv = ww * vv;
    let vw = vv * ww;
    let wvw = wv * ww;
    vv * 0.5
        + (wv + vw + wvw) * c1
        + (ww * wv + vw * ww - wvw * 3.0) * c2
        + (wvw * ww + ww * wvw) * c3
}

/// `Q(omega, v) y` without forming matrices.
#[inline(always)]
pub fn coupling_apply(w: &Vector3<f64>, v: &Vector3<f64>, y: &Vector3<f64>) -> Vector3<f64> {
    let (c1, c2, c3) = coupling_coeffs(w.norm_squared());
    let wy = w.cross(y);
    let vy = v.cross(y);
    let wvy = w.cross(&vy); // W V y
    let vwy = v.cross(&wy); // V W y
    let wvwy = w.cross(&vwy); // W V W y
    let wwvy = w.cross(&wvy); // W W V y
    let vwwy = v.cross(&w.cross(&wy)); // V W W y
    let wvwwy = w.cross(&v.cross(&w.cross(&wy))); // W V W W y
    let wwvwy = w.cross(&wvwy); // W W V W y
    vy * 0.5 + (wvy + vwy + wvwy) * c1 + (wwvy + vwwy - wvwy * 3.0) * c2 + (wvwwy + wwvwy) * c3
}

/// `dexp(xi)` (6x6), the left Jacobian of the exponential.
pub fn dexp(xi: &Vector6<f64>) -> Matrix6<f64> {
    let w = omega(xi);
    let j = so3::dexp(&w);
    let mut m = Matrix6::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&j);
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(&j);
    m.fixed_view_mut::<3, 3>(3, 0)
        .copy_from(&coupling(&w, &linear(xi)));
    m
}

/// `dexp_inv(xi)` (6x6) in closed form: `[[A, 0], [-A Q A, A]]`.
pub fn dexp_inv(xi: &Vector6<f64>) -> Matrix6<f64> {
    let w = omega(xi);
    let a = so3::dexp_inv(&w);
    let q = coupling(&w, &linear(xi));
    let mut m = Matrix6::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&a);
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(&a);
    m.fixed_view_mut::<3, 3>(3, 0).copy_from(&(-(a * q * a)));
    m
}

/// `dexp_inv(xi) u` without forming the matrix: `(A u_w, A (u_v - Q A u_w))`.
#[inline(always)]
pub fn dexp_inv_apply(xi: &Vector6<f64>, u: &Vector6<f64>) -> Vector6<f64> {
    let w = omega(xi);
    let y = so3::dexp_inv_apply(&w, &omega(u));
    let z = linear(u) - coupling_apply(&w, &linear(xi), &y);
    twist(&y, &so3::dexp_inv_apply(&w, &z))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn twists() -> Vec<Vector6<f64>> {
        vec![
            Vector6::zeros(),
            Vector6::new(1e-9, -2e-9, 3e-10, 0.4, -0.1, 0.3),
            Vector6::new(3e-4, 1e-4, -2e-4, -1.0, 0.5, 2.0),
            Vector6::new(0.3, -0.2, 0.9, 0.7, 1.1, -0.4),
            Vector6::new(-1.0, 2.0, 0.5, -0.3, 0.2, 0.8),
            Vector6::new(0.0, 0.0, std::f64::consts::PI - 1e-7, 1.0, -2.0, 0.5),
        ]
    }

    /// The 4x4 matrix exponential, summed as a series, agrees with the closed form.
    fn exp_series(xi: &Vector6<f64>) -> Matrix4<f64> {
        let a = hat(xi);
        let mut term = Matrix4::identity();
        let mut sum = Matrix4::identity();
        for k in 1..60 {
            term = term * a / k as f64;
            sum += term;
        }
        sum
    }

    /// exp matches the power series of the 4x4 matrix (to 1e-14), exp_quat matches exp, and
    /// log inverts exp to round-off (angle below pi; near pi the axis costs 1e-9 as on SO(3)).
    #[test]
    fn exp_log_round_trip() {
        for xi in twists() {
            let (r, x) = exp(&xi);
            let m = exp_series(&xi);
            assert!((m.fixed_view::<3, 3>(0, 0) - r).norm() < 1e-14, "{xi}");
            assert!(
                (m.fixed_view::<3, 1>(0, 3) - x).norm() < 1e-14 * (1.0 + x.norm()),
                "{xi}"
            );
            let (q, xq) = exp_quat(&xi);
            assert!((q.to_rotation_matrix().into_inner() - r).norm() < 1e-15 * 10.0);
            assert_eq!(xq, x);
            let back = log(&r, &x);
            let tol = if omega(&xi).norm() > 3.0 {
                1e-8
            } else {
                1e-14 * (1.0 + xi.norm())
            };
            assert!((back - xi).norm() <= tol, "{xi}: {}", (back - xi).norm());
        }
    }

    /// dexp_inv is the inverse of dexp (1e-14), dexp is the series sum of ad^k/(k+1)! and the
    /// apply form matches the matrix.
    #[test]
    fn dexp_inv_inverts_dexp() {
        let u = Vector6::new(0.7, -0.4, 0.2, 0.3, 0.9, -1.2);
        for xi in twists() {
            let prod = dexp(&xi) * dexp_inv(&xi);
            assert!((prod - Matrix6::identity()).norm() < 1e-14, "{xi}");
            let a = ad(&xi);
            let mut term = Matrix6::identity();
            let mut sum = Matrix6::identity();
            for k in 1..60 {
                term = term * a / (k + 1) as f64;
                sum += term;
            }
            assert!((sum - dexp(&xi)).norm() < 1e-14 * (1.0 + xi.norm()), "{xi}");
            let d = dexp_inv_apply(&xi, &u) - dexp_inv(&xi) * u;
            assert!(d.norm() < 1e-14, "{xi}: {}", d.norm());
        }
    }

    /// dexp is the derivative of exp: d/ds exp(xi + s u) = (dexp(xi) u)^ exp(xi), checked by a
    /// central difference (h = 1e-6: truncation ~1e-12, round-off ~1e-10).
    #[test]
    fn dexp_is_left_jacobian() {
        let u = Vector6::new(0.7, -0.4, 0.2, 0.3, 0.9, -1.2);
        let to4 = |(r, x): (Matrix3<f64>, Vector3<f64>)| {
            let mut m = Matrix4::identity();
            m.fixed_view_mut::<3, 3>(0, 0).copy_from(&r);
            m.fixed_view_mut::<3, 1>(0, 3).copy_from(&x);
            m
        };
        let h = 1e-6;
        for xi in twists() {
            let d = (to4(exp(&(xi + u * h))) - to4(exp(&(xi - u * h)))) / (2.0 * h);
            let expected = hat(&(dexp(&xi) * u)) * to4(exp(&xi));
            assert!(
                (d - expected).norm() < 1e-8,
                "{xi}: {}",
                (d - expected).norm()
            );
        }
    }
}
