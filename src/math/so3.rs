//! The rotation group SO(3): hat/vee, the exponential and logarithm, the Jacobian of the
//! exponential (`dexp`) and its inverse, the Cayley map, and the geodesic distance.
//!
//! Conventions (Iserles, Munthe-Kaas, Norsett & Zanna, *Lie-group methods*, Acta Numerica
//! 2000, sec. 2-3): for `Y(t) = exp([theta(t)]x) Y0` (left, "spatial" trivialisation) with
//! `Y' = [a]x Y`, `theta' = dexp_inv(theta) a`; for `Y(t) = Y0 exp([theta(t)]x)` (right, "body")
//! with `Y' = Y [a]x`, `theta' = dexp_inv(-theta) a`. `dexp(theta)` is the left Jacobian
//! `I + (1 - cos t)/t^2 [theta] + (t - sin t)/t^3 [theta]^2` (`t = |theta|`) and
//! `dexp_inv(theta) = I - [theta]/2 + (1 - (t/2) cot(t/2))/t^2 [theta]^2`.
//! Every coefficient switches to its Taylor series below `|theta| < 1e-3` (error below 1e-19),
//! so the maps are accurate to round-off at and near zero. The fused map of an RKMK stage
//! (`exp_quat_dexp_inv`) keeps longer Taylor polynomials of the half-angle coefficients up to
//! `|theta| < 0.5` (truncation below 1e-17 relative, `half_angle_coeffs_series`), where a
//! stage's increments are; this also avoids the closed form's cancellation in
//! `1 - (t/2) cot(t/2)`. `exp_quat` and `dexp_inv_apply` keep the closed forms (the structural
//! charts use them, and their Newton iterations amplify round-off into different failures). `dexp_inv` is singular at
//! `|theta| = 2 pi` (the cotangent), which no method reaches in one step at sensible step sizes.
//! The logarithm goes through the unit quaternion (`2 atan2(|v|, w)`), which is well
//! conditioned everywhere including angles near pi.
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};

/// `[v]x`, the skew matrix with `[v]x u = v x u`.
#[inline(always)]
pub fn hat(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// The axial vector of the skew part of `m` (exact inverse of `hat` on skew matrices).
#[inline(always)]
pub fn vee(m: &Matrix3<f64>) -> Vector3<f64> {
    Vector3::new(
        0.5 * (m[(2, 1)] - m[(1, 2)]),
        0.5 * (m[(0, 2)] - m[(2, 0)]),
        0.5 * (m[(1, 0)] - m[(0, 1)]),
    )
}

/// `(sin t)/t`, `(1 - cos t)/t^2`, `(t - sin t)/t^3` as functions of `t2 = t^2`.
#[inline(always)]
fn rodrigues_coeffs(t2: f64) -> (f64, f64, f64) {
    if t2 < 1e-6 {
        (
            1.0 - t2 / 6.0 * (1.0 - t2 / 20.0),
            0.5 - t2 / 24.0 * (1.0 - t2 / 30.0),
            1.0 / 6.0 - t2 / 120.0 * (1.0 - t2 / 42.0),
        )
    } else {
        let t = t2.sqrt();
        let (s, c) = t.sin_cos();
        (s / t, (1.0 - c) / t2, (t - s) / (t2 * t))
    }
}

/// The rotation matrix `exp([v]x)` (Rodrigues' formula).
#[inline(always)]
pub fn exp(v: &Vector3<f64>) -> Matrix3<f64> {
    let (a, b, _) = rodrigues_coeffs(v.norm_squared());
    let k = hat(v);
    Matrix3::identity() + k * a + k * k * b
}

/// Below `t2 = SERIES_T2` (`|theta| < 0.5`) the half-angle coefficients are their Taylor
/// polynomials in `t2` (no square root, no `sin_cos`, no division: in an RKMK stage they sit
/// on the path from one stage's increment to the next stage's forces). The truncation errors
/// there are below 1e-17 relative (`cos(t/2)`: 7 terms, 4e-20; `sin(t/2)/t`: 7 terms, 1e-20;
/// `dexp_inv`'s coefficient: 8 terms, 1.6e-18, at `t2 = 0.25`; mpmath), under the f64 rounding.
const SERIES_T2: f64 = 0.25;

/// `cos(t/2) = sum_n (-1)^n t2^n / (4^n (2n)!)`.
const COS_HALF: [f64; 7] = [
    1.0,
    -1.0 / 8.0,
    1.0 / 384.0,
    -1.0 / 46080.0,
    1.0 / 10321920.0,
    -1.0 / 3715891200.0,
    1.0 / 1961990553600.0,
];

/// `sin(t/2)/t = sum_n (-1)^n t2^n / (2 4^n (2n+1)!)`.
const SIN_HALF_OVER_T: [f64; 7] = [
    0.5,
    -1.0 / 48.0,
    1.0 / 3840.0,
    -1.0 / 645120.0,
    1.0 / 185794560.0,
    -1.0 / 81749606400.0,
    1.0 / 51011754393600.0,
];

/// `(1 - (t/2) cot(t/2))/t^2 = sum_{n>=1} |B_2n| t2^(n-1) / (2n)!` (Bernoulli numbers; the
/// series converges for `|t| < 2 pi`).
const DEXP_INV_G: [f64; 8] = [
    1.0 / 12.0,
    1.0 / 720.0,
    1.0 / 30240.0,
    1.0 / 1209600.0,
    1.0 / 47900160.0,
    691.0 / 1307674368000.0,
    1.0 / 74724249600.0,
    3617.0 / 10670622842880000.0,
];

/// `sum_i p[i] x^i` for 7 coefficients, by Estrin's scheme (pairs, then pairs of pairs: four
/// dependent multiply-adds instead of Horner's six, on an RKMK stage's critical path).
#[inline(always)]
fn poly7(p: &[f64; 7], x: f64) -> f64 {
    let (x2, x4) = (x * x, x * x * (x * x));
    (p[0] + p[1] * x) + x2 * (p[2] + p[3] * x) + x4 * ((p[4] + p[5] * x) + x2 * p[6])
}

/// `sum_i p[i] x^i` for 8 coefficients (Estrin, as [`poly7`]).
#[inline(always)]
fn poly8(p: &[f64; 8], x: f64) -> f64 {
    let (x2, x4) = (x * x, x * x * (x * x));
    (p[0] + p[1] * x) + x2 * (p[2] + p[3] * x) + x4 * ((p[4] + p[5] * x) + x2 * (p[6] + p[7] * x))
}

/// `(cos(t/2), sin(t/2)/t, (1 - (t/2) cot(t/2))/t^2)` as functions of `t2 = t^2`: the
/// quaternion exponential's two coefficients and `dexp_inv`'s, from one `sin_cos` of `t/2`
/// (short Taylor forms below `t2 = 1e-6`). Each number is the same expression in
/// `exp_quat` and `dexp_inv_apply`.
#[inline(always)]
fn half_angle_coeffs(t2: f64) -> (f64, f64, f64) {
    if t2 < 1e-6 {
        (
            1.0 - t2 / 8.0 * (1.0 - t2 / 48.0),
            0.5 - t2 / 48.0 * (1.0 - t2 / 80.0),
            1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0,
        )
    } else {
        let t = t2.sqrt();
        let h = 0.5 * t;
        let (s, c) = h.sin_cos();
        (c, s / t, (1.0 - h * c / s) / t2)
    }
}

/// The half-angle coefficients of [`half_angle_coeffs`], as their Taylor polynomials below
/// `SERIES_T2` (the same numbers to round-off, not bit for bit), above it the same.
#[inline(always)]
fn half_angle_coeffs_series(t2: f64) -> (f64, f64, f64) {
    if t2 < SERIES_T2 {
        (
            poly7(&COS_HALF, t2),
            poly7(&SIN_HALF_OVER_T, t2),
            poly8(&DEXP_INV_G, t2),
        )
    } else {
        half_angle_coeffs(t2)
    }
}

/// The unit quaternion `(c, s_over_t v)`.
#[inline(always)]
fn quat_of(v: &Vector3<f64>, c: f64, s_over_t: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::new_unchecked(Quaternion::new(
        c,
        s_over_t * v.x,
        s_over_t * v.y,
        s_over_t * v.z,
    ))
}

/// The unit quaternion of `exp([v]x)`: `(cos(t/2), sin(t/2) v/t)`.
#[inline(always)]
pub fn exp_quat(v: &Vector3<f64>) -> UnitQuaternion<f64> {
    let (c, s_over_t, _) = half_angle_coeffs(v.norm_squared());
    quat_of(v, c, s_over_t)
}

/// `exp_quat(v)` and the coefficient `g` of `dexp_inv(+-v) a = a -+ (v x a)/2 + g v x (v x a)`
/// (for [`dexp_inv_apply_coeff`]) together, as an RKMK stage needs them (it retracts by an
/// increment and corrects by `dexp_inv` at the same increment): below `|v| = 0.5` from
/// Taylor polynomials in `|v|^2` (no square root, `sin_cos` or division on the stage's
/// critical path; the two `sin_cos` of `|v|/2` a stage took were a fifth of an `so3` RK4
/// step), above it from one `sin_cos`. The numbers of `exp_quat(v)` and
/// `dexp_inv_apply(+-v, .)` to round-off (bit for bit above `|v| = 0.5`).
///
/// # Example
///
/// ```
/// use mbdbench::math::so3;
/// use nalgebra::Vector3;
///
/// let (v, a) = (Vector3::new(0.03, -0.02, 0.09), Vector3::new(0.7, -0.4, 0.2));
/// let (q, g) = so3::exp_quat_dexp_inv(&v);
/// assert!(q.angle_to(&so3::exp_quat(&v)) < 1e-15);
/// let d = so3::dexp_inv_apply_coeff(&(-v), &a, g) - so3::dexp_inv_apply(&(-v), &a);
/// assert!(d.norm() < 1e-15);
/// ```
#[inline(always)]
pub fn exp_quat_dexp_inv(v: &Vector3<f64>) -> (UnitQuaternion<f64>, f64) {
    let (c, s_over_t, g) = half_angle_coeffs_series(v.norm_squared());
    (quat_of(v, c, s_over_t), g)
}

/// The rotation vector of a unit quaternion, angle in `[0, pi]` (the sign of `q` is free).
#[inline(always)]
pub fn log_quat(q: &UnitQuaternion<f64>) -> Vector3<f64> {
    let (w, v) = if q.w < 0.0 {
        (-q.w, -q.imag())
    } else {
        (q.w, q.imag())
    };
    let s = v.norm();
    if s < 1e-300 {
        return v * 2.0;
    }
    let angle = 2.0 * s.atan2(w);
    v * (angle / s)
}

/// The rotation vector of a rotation matrix, angle in `[0, pi]`.
pub fn log(r: &Matrix3<f64>) -> Vector3<f64> {
    log_quat(&quat_from_matrix(r))
}

/// The unit quaternion of a rotation matrix (Shepperd's method: the largest of the four
/// squared components is taken first, so it is accurate for every rotation).
pub fn quat_from_matrix(r: &Matrix3<f64>) -> UnitQuaternion<f64> {
    let tr = r[(0, 0)] + r[(1, 1)] + r[(2, 2)];
    let d = [tr, r[(0, 0)], r[(1, 1)], r[(2, 2)]];
    let mut k = 0;
    for i in 1..4 {
        if d[i] > d[k] {
            k = i;
        }
    }
    let q = match k {
        0 => {
            let s = 2.0 * (1.0 + tr).sqrt();
            Quaternion::new(
                0.25 * s,
                (r[(2, 1)] - r[(1, 2)]) / s,
                (r[(0, 2)] - r[(2, 0)]) / s,
                (r[(1, 0)] - r[(0, 1)]) / s,
            )
        }
        1 => {
            let s = 2.0 * (1.0 + r[(0, 0)] - r[(1, 1)] - r[(2, 2)]).sqrt();
            Quaternion::new(
                (r[(2, 1)] - r[(1, 2)]) / s,
                0.25 * s,
                (r[(0, 1)] + r[(1, 0)]) / s,
                (r[(0, 2)] + r[(2, 0)]) / s,
            )
        }
        2 => {
            let s = 2.0 * (1.0 - r[(0, 0)] + r[(1, 1)] - r[(2, 2)]).sqrt();
            Quaternion::new(
                (r[(0, 2)] - r[(2, 0)]) / s,
                (r[(0, 1)] + r[(1, 0)]) / s,
                0.25 * s,
                (r[(1, 2)] + r[(2, 1)]) / s,
            )
        }
        _ => {
            let s = 2.0 * (1.0 - r[(0, 0)] - r[(1, 1)] + r[(2, 2)]).sqrt();
            Quaternion::new(
                (r[(1, 0)] - r[(0, 1)]) / s,
                (r[(0, 2)] + r[(2, 0)]) / s,
                (r[(1, 2)] + r[(2, 1)]) / s,
                0.25 * s,
            )
        }
    };
    canonical(&UnitQuaternion::new_normalize(q))
}

/// `q / |q|` for a quaternion that is unit up to the rounding of a step. When
/// `d = |q|^2 - 1` is at most 1e-8 in magnitude, `q (3 - |q|^2) / 2 = q (1 - d/2)` is used: one
/// Newton step for `1 / sqrt(|q|^2)` from 1, whose error `3 d^2 / 8 <= 3.75e-17` is below the
/// rounding of the exact formula, and which needs neither a square root nor a division (their
/// latencies were a third of an `so3` Euler step). Otherwise the exact `q / |q|`.
#[inline(always)]
pub fn renormalize(q: Quaternion<f64>) -> Quaternion<f64> {
    let n2 = q.norm_squared();
    if (n2 - 1.0).abs() <= 1e-8 {
        q * (1.5 - 0.5 * n2)
    } else {
        q / n2.sqrt()
    }
}

/// The sign-canonical representative of a unit quaternion (cases/README.md, "Conventions"):
/// `w > 0`, or, if `w = 0`, the first non-zero of `x, y, z` positive.
pub fn canonical(q: &UnitQuaternion<f64>) -> UnitQuaternion<f64> {
    let c = [q.w, q.i, q.j, q.k];
    let first = c.iter().copied().find(|v| *v != 0.0).unwrap_or(1.0);
    if first < 0.0 {
        UnitQuaternion::new_unchecked(-q.into_inner())
    } else {
        *q
    }
}

/// Left Jacobian of the exponential, `dexp(theta)`.
#[inline(always)]
pub fn dexp(v: &Vector3<f64>) -> Matrix3<f64> {
    let (_, b, c) = rodrigues_coeffs(v.norm_squared());
    let k = hat(v);
    Matrix3::identity() + k * b + k * k * c
}

/// `(1 - (t/2) cot(t/2)) / t^2` as a function of `t2 = t^2`.
#[inline(always)]
fn dexp_inv_coeff(t2: f64) -> f64 {
    half_angle_coeffs(t2).2
}

/// Inverse of the left Jacobian, `dexp_inv(theta)` as a matrix.
#[inline(always)]
pub fn dexp_inv(v: &Vector3<f64>) -> Matrix3<f64> {
    let k = hat(v);
    Matrix3::identity() - k * 0.5 + k * k * dexp_inv_coeff(v.norm_squared())
}

/// `dexp_inv(theta) a` without forming the matrix.
#[inline(always)]
pub fn dexp_inv_apply(v: &Vector3<f64>, a: &Vector3<f64>) -> Vector3<f64> {
    dexp_inv_apply_coeff(v, a, dexp_inv_coeff(v.norm_squared()))
}

/// `dexp_inv(theta) a` given its coefficient `g = (1 - (t/2) cot(t/2))/t^2` of `|theta|`
/// (from [`exp_quat_dexp_inv`]).
#[inline(always)]
pub fn dexp_inv_apply_coeff(v: &Vector3<f64>, a: &Vector3<f64>, g: f64) -> Vector3<f64> {
    let va = v.cross(a);
    a - va * 0.5 + v.cross(&va) * g
}

/// The Cayley map `cay(theta) = I + 4/(4 + |theta|^2) ([theta]x + [theta]x^2 / 2)`, a rational
/// second-order approximation of `exp` used by the energy-momentum scheme (Simo & Wong 1991):
/// with `R1 = R0 cay(theta)`, `R1 - R0 = (R0 + R1)/2 [theta]x` exactly.
#[inline(always)]
pub fn cay(v: &Vector3<f64>) -> Matrix3<f64> {
    let k = hat(v);
    Matrix3::identity() + (k + k * k * 0.5) * (4.0 / (4.0 + v.norm_squared()))
}

/// The unit quaternion of `cay(theta)`: `(1, theta/2) / sqrt(1 + |theta|^2/4)`.
#[inline(always)]
pub fn cay_quat(v: &Vector3<f64>) -> UnitQuaternion<f64> {
    let s = 1.0 / (1.0 + 0.25 * v.norm_squared()).sqrt();
    UnitQuaternion::new_unchecked(Quaternion::new(
        s,
        0.5 * s * v.x,
        0.5 * s * v.y,
        0.5 * s * v.z,
    ))
}

/// Geodesic distance (rad, in `[0, pi]`) between two rotations given as unit quaternions.
#[inline]
pub fn geodesic_quat(a: &UnitQuaternion<f64>, b: &UnitQuaternion<f64>) -> f64 {
    let d = a.inverse() * b;
    let s = d.imag().norm();
    2.0 * s.atan2(d.w.abs())
}

/// Geodesic distance (rad) between two rotation matrices.
pub fn geodesic(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    geodesic_quat(&quat_from_matrix(a), &quat_from_matrix(b))
}

/// Active elementary rotations `Rx(a)`, `Ry(a)`, `Rz(a)` (cases/README.md, "Conventions").
pub fn rx(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}
/// See [`rx`].
pub fn ry(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)
}
/// See [`rx`].
pub fn rz(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vecs() -> Vec<Vector3<f64>> {
        vec![
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(1e-9, -2e-9, 3e-10),
            Vector3::new(3e-4, 1e-4, -2e-4),
            Vector3::new(0.3, -0.2, 0.9),
            Vector3::new(-1.0, 2.0, 0.5),
            Vector3::new(0.0, 0.0, std::f64::consts::PI - 1e-7),
        ]
    }

    /// exp and log are inverse to round-off (angle below pi), and exp agrees with exp_quat.
    #[test]
    fn exp_log_round_trip() {
        for v in vecs() {
            let r = exp(&v);
            assert!(
                (log(&r) - v).norm()
                    <= 1e-14 * (1.0 + v.norm()) + 1e-9 * (v.norm() > 3.0) as u8 as f64,
                "{v}"
            );
            let rq = exp_quat(&v).to_rotation_matrix().into_inner();
            assert!((rq - r).norm() < 1e-15 * 10.0);
            assert!((r.transpose() * r - Matrix3::identity()).norm() < 1e-15 * 10.0);
        }
    }

    /// dexp_inv inverts dexp, and dexp is the derivative of exp: d/ds exp(v + s a) =
    /// [dexp(v) a]x exp(v) (checked by a central difference).
    #[test]
    fn dexp_is_jacobian_and_inverse() {
        let a = Vector3::new(0.7, -0.4, 0.2);
        for v in vecs() {
            let prod = dexp(&v) * dexp_inv(&v);
            assert!((prod - Matrix3::identity()).norm() < 1e-14, "{v}");
            assert!((dexp_inv_apply(&v, &a) - dexp_inv(&v) * a).norm() < 1e-15);
            let h = 1e-6;
            let d = (exp(&(v + a * h)) - exp(&(v - a * h))) / (2.0 * h);
            let expected = hat(&(dexp(&v) * a)) * exp(&v);
            assert!((d - expected).norm() < 1e-8, "{v}");
        }
    }

    /// The fused exponential and `dexp_inv` coefficient agree with `exp_quat` and
    /// `dexp_inv_apply` to round-off on both sides of every switch and in both
    /// trivialisations, and bit for bit above the series' range.
    #[test]
    fn fused_exp_dexp_inv_agrees() {
        let a = Vector3::new(0.7, -0.4, 0.2);
        let more = (1..200).map(|i| {
            let s = 1.07_f64.powi(i) * 1e-5;
            Vector3::new(0.3 * s, -0.8 * s, 0.5 * s)
        });
        for v in vecs().into_iter().chain(more) {
            let (q, g) = exp_quat_dexp_inv(&v);
            let exact = v.norm_squared() >= SERIES_T2;
            let dq = (q.into_inner() - exp_quat(&v).into_inner()).norm();
            assert!(if exact { dq == 0.0 } else { dq < 3e-16 }, "{v}");
            for w in [v, -v] {
                let d = (dexp_inv_apply_coeff(&w, &a, g) - dexp_inv_apply(&w, &a)).norm();
                assert!(if exact { d == 0.0 } else { d < 1e-15 }, "{v}");
            }
        }
    }

    /// The Taylor polynomials of the half-angle coefficients agree with the closed forms
    /// (and, at the switch `t2 = SERIES_T2`, with each other across it) to round-off: `cos`
    /// and `sin/t` to 6e-16 relative (the closed form's own sqrt, sin and division round);
    /// `dexp_inv`'s coefficient to the closed form's own cancellation error `eps 12/t2`.
    #[test]
    fn half_angle_series_matches_closed_form() {
        let closed = |t2: f64| {
            let t = t2.sqrt();
            let h = 0.5 * t;
            let (s, c) = h.sin_cos();
            (c, s / t, (1.0 - h * c / s) / t2)
        };
        let rel = |a: f64, b: f64| ((a - b) / b).abs();
        let mut t2 = 1e-6;
        while t2 <= SERIES_T2 * (1.0 + 1e-12) {
            let t2s = t2.min(SERIES_T2 * (1.0 - 1e-16));
            let (a, b) = (half_angle_coeffs_series(t2s), closed(t2s));
            assert!(rel(a.0, b.0) < 6e-16 && rel(a.1, b.1) < 6e-16, "{t2s}");
            assert!(
                rel(a.2, b.2) < 1e-16 + 4.0 * f64::EPSILON * 12.0 / t2s,
                "{t2s}"
            );
            t2 *= 1.01;
        }
        let (below, above) = (
            half_angle_coeffs_series(SERIES_T2 * (1.0 - 1e-15)),
            half_angle_coeffs_series(SERIES_T2),
        );
        assert!(rel(below.0, above.0) < 4e-16 && rel(below.1, above.1) < 4e-16);
        assert!(rel(below.2, above.2) < 1e-14);
    }

    /// This libm's `sin_cos` gives the bits of separate `sin` and `cos` calls (`dexp_inv`
    /// took them separately before it shared `half_angle_coeffs`); `black_box` keeps
    /// the compiler from fusing the separate calls into one.
    #[test]
    fn sin_cos_matches_sin_and_cos() {
        for i in 0..20_000 {
            let h = 1e-4 + i as f64 * 1.7e-4;
            let (s, c) = h.sin_cos();
            let (s1, c1) = (std::hint::black_box(h).sin(), std::hint::black_box(h).cos());
            assert_eq!(
                (s.to_bits(), c.to_bits()),
                (s1.to_bits(), c1.to_bits()),
                "{h}"
            );
        }
    }

    /// The Cayley map's defining identity R1 - R0 = (R0 + R1)/2 [theta]x, and its quaternion.
    #[test]
    fn cayley_identity() {
        let r0 = exp(&Vector3::new(0.2, 0.5, -0.3));
        for v in vecs() {
            let r1 = r0 * cay(&v);
            let lhs = r1 - r0;
            let rhs = (r0 + r1) * 0.5 * hat(&v);
            assert!((lhs - rhs).norm() < 1e-14);
            let q = cay_quat(&v).to_rotation_matrix().into_inner();
            assert!((q - cay(&v)).norm() < 1e-14);
        }
    }

    /// Shepperd's conversion recovers the quaternion for every branch, sign-canonical.
    #[test]
    fn quaternion_from_matrix_all_branches() {
        for v in vecs().into_iter().chain([
            Vector3::new(3.1, 0.0, 0.0),
            Vector3::new(0.0, 3.1, 0.1),
            Vector3::new(0.0, 0.1, 3.1),
        ]) {
            let q = canonical(&exp_quat(&v));
            let q2 = quat_from_matrix(&exp(&v));
            assert!(
                (q.into_inner() - q2.into_inner()).norm() < 1e-15 * 4.0,
                "{v}"
            );
            assert!(geodesic_quat(&q, &q2) < 1e-14);
        }
    }
}
