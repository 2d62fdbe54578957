//! Euler-angle charts `euler_xyz`, `euler_zyx`, `euler_zxz`: three angles `(a, b, c)` with
//! `R = Ri(a) Rj(b) Rk(c)`, additive, with the translation additive beside them.
//!
//! Sequences (cases/README.md, "Conventions"): `xyz` is `Rx(a) Ry(b) Rz(c)` and `zyx` is
//! `Rz(a) Ry(b) Rx(c)`, singular where `cos b = 0`; `zxz` is `Rz(a) Rx(b) Rz(c)`, singular
//! where `sin b = 0`. Conditioning is `|cos b|` (resp. `|sin b|`) of the stored `b`.
//!
//! Kinematics: from `R^T R' = [omega]x`, `omega = Rk(c)^T Rj(b)^T e_i a' + Rk(c)^T e_j b' + e_k c'`
//! (e.g. Shuster, *A survey of attitude representations*, J. Astronaut. Sci. 41, 1993,
//! sec. 5.3), inverted in closed form; the rates are
//! - `xyz`: `a' = (cos c w1 - sin c w2)/cos b`, `b' = sin c w1 + cos c w2`, `c' = w3 - sin b a'`;
//! - `zyx`: `a' = (sin c w2 + cos c w3)/cos b`, `b' = cos c w2 - sin c w3`, `c' = w1 + sin b a'`;
//! - `zxz`: `a' = (sin c w1 + cos c w2)/sin b`, `b' = cos c w1 - sin c w2`, `c' = w3 - cos b a'`.
//!
//! These blow up like `1/conditioning` near the singular set and are deliberately not
//! clamped: that failure mode is what the gimbal-lock case measures (at conditioning 0 they
//! are infinite, and `RigidSystem::check` reports `singular_chart` at conditioning 1e-12).
//!
//! Extraction (`from_pose`) returns the principal branch, `b` in `[-pi/2, pi/2]` (`xyz`,
//! `zyx`) or `[0, pi]` (`zxz`), `a` and `c` in `(-pi, pi]`. Near the singular set only one
//! combination `a +- c` is determined by `R`; it is read from the 2x2 block whose entries are
//! `(1 +- s) cos(a +- c)`, `(1 +- s) sin(a +- c)` (`s = sin b` or `cos b`), choosing the sign
//! that keeps `1 +- s >= 1`, so it is accurate to round-off everywhere. `a` is read from its
//! own entries (`cos b` or `sin b` times `sin a`, `cos a`; error `~ eps / conditioning`) and
//! `c` is the determined combination minus (or plus) `a`. The rotation is insensitive to the
//! undetermined combination exactly in proportion to the conditioning, so `R` round-trips to
//! round-off even at conditioning 1e-12 or 0. Convention exactly on the singular set (both of
//! `a`'s entries zero): `a = 0`, `c` carries the whole combination.
use nalgebra::{Matrix3, Vector3, Vector6};
use std::f64::consts::{PI, TAU};

use super::{Pose, PoseChart};
use crate::math::so3::{rx, ry, rz};

/// `a` wrapped into `(-pi, pi]`.
#[inline]
fn wrap(a: f64) -> f64 {
    let r = a - TAU * (a / TAU).round();
    if r <= -PI { r + TAU } else { r }
}

/// `atan2(y, x)`, 0 when both are zero (of either sign).
#[inline]
fn atan2_or_zero(y: f64, x: f64) -> f64 {
    if y == 0.0 && x == 0.0 {
        0.0
    } else {
        y.atan2(x)
    }
}

/// `R = Rx(a) Ry(b) Rz(c)`.
pub fn xyz_rotation(e: &Vector3<f64>) -> Matrix3<f64> {
    rx(e.x) * ry(e.y) * rz(e.z)
}

/// `R = Rz(a) Ry(b) Rx(c)`.
pub fn zyx_rotation(e: &Vector3<f64>) -> Matrix3<f64> {
    rz(e.x) * ry(e.y) * rx(e.z)
}

/// `R = Rz(a) Rx(b) Rz(c)`.
pub fn zxz_rotation(e: &Vector3<f64>) -> Matrix3<f64> {
    rz(e.x) * rx(e.y) * rz(e.z)
}

/// Principal `xyz` angles of `R`. With `s = sin b`,
/// `R = [[cb cc, -cb sc, s], [ca sc + sa s cc, ca cc - sa s sc, -sa cb],
/// [sa sc - ca s cc, sa cc + ca s sc, ca cb]]`, so `R10 + R21 = (1+s) sin(a+c)`,
/// `R11 - R20 = (1+s) cos(a+c)`, `R10 - R21 = (1-s) sin(c-a)`, `R11 + R20 = (1-s) cos(c-a)`.
pub fn xyz_angles(r: &Matrix3<f64>) -> Vector3<f64> {
    let s = r[(0, 2)];
    let cb = 0.5 * (r[(0, 0)].hypot(r[(0, 1)]) + r[(1, 2)].hypot(r[(2, 2)]));
    let b = s.atan2(cb);
    let a = atan2_or_zero(-r[(1, 2)], r[(2, 2)]);
    let c = if s >= 0.0 {
        let sum = (r[(1, 0)] + r[(2, 1)]).atan2(r[(1, 1)] - r[(2, 0)]);
        sum - a
    } else {
        let diff = (r[(1, 0)] - r[(2, 1)]).atan2(r[(1, 1)] + r[(2, 0)]);
        diff + a
    };
    Vector3::new(wrap(a), b, wrap(c))
}

/// Principal `zyx` angles of `R`. With `s = sin b`,
/// `R = [[ca cb, ca s sc - sa cc, ca s cc + sa sc], [sa cb, sa s sc + ca cc, sa s cc - ca sc],
/// [-s, cb sc, cb cc]]`, so `R12 - R01 = (1+s) sin(a-c)`, `R11 + R02 = (1+s) cos(a-c)`,
/// `-(R12 + R01) = (1-s) sin(a+c)`, `R11 - R02 = (1-s) cos(a+c)`.
pub fn zyx_angles(r: &Matrix3<f64>) -> Vector3<f64> {
    let s = -r[(2, 0)];
    let cb = 0.5 * (r[(0, 0)].hypot(r[(1, 0)]) + r[(2, 1)].hypot(r[(2, 2)]));
    let b = s.atan2(cb);
    let a = atan2_or_zero(r[(1, 0)], r[(0, 0)]);
    let c = if s >= 0.0 {
        let diff = (r[(1, 2)] - r[(0, 1)]).atan2(r[(1, 1)] + r[(0, 2)]);
        a - diff
    } else {
        let sum = (-(r[(1, 2)] + r[(0, 1)])).atan2(r[(1, 1)] - r[(0, 2)]);
        sum - a
    };
    Vector3::new(wrap(a), b, wrap(c))
}

/// Principal `zxz` angles of `R`. With `k = cos b`,
/// `R = [[ca cc - k sa sc, -ca sc - k sa cc, sa sb], [sa cc + k ca sc, -sa sc + k ca cc, -ca sb],
/// [sb sc, sb cc, k]]`, so `R10 - R01 = (1+k) sin(a+c)`, `R00 + R11 = (1+k) cos(a+c)`,
/// `R10 + R01 = (1-k) sin(a-c)`, `R00 - R11 = (1-k) cos(a-c)`.
pub fn zxz_angles(r: &Matrix3<f64>) -> Vector3<f64> {
    let k = r[(2, 2)];
    let sb = 0.5 * (r[(0, 2)].hypot(r[(1, 2)]) + r[(2, 0)].hypot(r[(2, 1)]));
    let b = sb.atan2(k);
    let a = atan2_or_zero(r[(0, 2)], -r[(1, 2)]);
    let c = if k >= 0.0 {
        let sum = (r[(1, 0)] - r[(0, 1)]).atan2(r[(0, 0)] + r[(1, 1)]);
        sum - a
    } else {
        let diff = (r[(1, 0)] + r[(0, 1)]).atan2(r[(0, 0)] - r[(1, 1)]);
        a - diff
    };
    Vector3::new(wrap(a), b, wrap(c))
}

/// `xyz` angle rates from the body angular velocity.
#[inline(always)]
pub fn xyz_rates(e: &Vector3<f64>, w: &Vector3<f64>) -> Vector3<f64> {
    let (sb, cb) = e.y.sin_cos();
    let (sc, cc) = e.z.sin_cos();
    let ad = (cc * w.x - sc * w.y) / cb;
    Vector3::new(ad, sc * w.x + cc * w.y, w.z - sb * ad)
}

/// `zyx` angle rates from the body angular velocity.
#[inline(always)]
pub fn zyx_rates(e: &Vector3<f64>, w: &Vector3<f64>) -> Vector3<f64> {
    let (sb, cb) = e.y.sin_cos();
    let (sc, cc) = e.z.sin_cos();
    let ad = (sc * w.y + cc * w.z) / cb;
    Vector3::new(ad, cc * w.y - sc * w.z, w.x + sb * ad)
}

/// `zxz` angle rates from the body angular velocity.
#[inline(always)]
pub fn zxz_rates(e: &Vector3<f64>, w: &Vector3<f64>) -> Vector3<f64> {
    let (sb, cb) = e.y.sin_cos();
    let (sc, cc) = e.z.sin_cos();
    let ad = (sc * w.x + cc * w.y) / sb;
    Vector3::new(ad, cc * w.x - sc * w.y, w.z - cb * ad)
}

/// One Euler chart: the type, its name, its four sequence functions and its conditioning.
macro_rules! euler_chart {
    ($t:ident, $name:literal, $rot:ident, $angles:ident, $rates:ident, $cond:expr) => {
        #[doc = concat!("The `", $name, "` chart: angles `(a, b, c)`, tangent `(angle rates, xdot)`.")]
        #[derive(Debug, Clone, Copy, Default)]
        pub struct $t;

        impl PoseChart for $t {
            const NAME: &'static str = $name;
            type Coords = Pose<Vector3<f64>>;
            /// `(a', b', c', xdot)`.
            type Tangent = Vector6<f64>;
            const LIE: bool = false;
            const SE3: bool = false;
            const CONSTRAINED: bool = false;
            const NORMALIZES: bool = false;

            fn from_pose(r: &Matrix3<f64>, x: &Vector3<f64>) -> Self::Coords {
                Pose {
                    rot: $angles(r),
                    x: *x,
                }
            }
            #[inline(always)]
            fn rotation(c: &Self::Coords) -> Matrix3<f64> {
                $rot(&c.rot)
            }
            #[inline(always)]
            fn velocity(
                c: &Self::Coords,
                _r: &Matrix3<f64>,
                omega_body: &Vector3<f64>,
                xdot: &Vector3<f64>,
                _spatial: bool,
            ) -> Self::Tangent {
                let e = $rates(&c.rot, omega_body);
                Vector6::new(e.x, e.y, e.z, xdot.x, xdot.y, xdot.z)
            }
            #[inline(always)]
            fn retract(c: &Self::Coords, d: &Self::Tangent, _spatial: bool) -> Self::Coords {
                Pose {
                    rot: c.rot + d.fixed_rows::<3>(0),
                    x: c.x + d.fixed_rows::<3>(3),
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
            fn residual(_c: &Self::Coords) -> Option<f64> {
                None
            }
            #[inline]
            fn conditioning(c: &Self::Coords) -> f64 {
                let f: fn(f64) -> f64 = $cond;
                f(c.rot.y)
            }
            #[inline(always)]
            fn normalize(_c: &mut Self::Coords) -> bool {
                false
            }
            #[inline]
            fn is_finite(c: &Self::Coords) -> bool {
                c.rot.iter().chain(c.x.iter()).all(|v| v.is_finite())
            }
        }
    };
}

euler_chart!(
    EulerXyz,
    "euler_xyz",
    xyz_rotation,
    xyz_angles,
    xyz_rates,
    |b| b.cos().abs()
);
euler_chart!(
    EulerZyx,
    "euler_zyx",
    zyx_rotation,
    zyx_angles,
    zyx_rates,
    |b| b.cos().abs()
);
euler_chart!(
    EulerZxz,
    "euler_zxz",
    zxz_rotation,
    zxz_angles,
    zxz_rates,
    |b| b.sin().abs()
);

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::math::so3;
    use std::f64::consts::FRAC_PI_2;

    /// `r` with the absolute rounding of a generic rotation, `Q^T (Q r)` for a fixed generic
    /// `Q`: every entry, small or not, then carries an error of a few eps, as a rotation
    /// produced by integration or by a quaternion in general position does. (A matrix built
    /// from elementary rotations, or through its quaternion, has its small entries accurate
    /// relative to their size, which would hide a naive `atan2` of small entries.)
    pub(crate) fn generic(r: &Matrix3<f64>) -> Matrix3<f64> {
        let q = so3::exp(&Vector3::new(0.7, -1.9, 1.3));
        q.transpose() * (q * r)
    }

    type Seq = (
        fn(&Vector3<f64>) -> Matrix3<f64>,
        fn(&Matrix3<f64>) -> Vector3<f64>,
        fn(&Vector3<f64>, &Vector3<f64>) -> Vector3<f64>,
    );
    const SEQS: [(&str, Seq); 3] = [
        ("xyz", (xyz_rotation, xyz_angles, xyz_rates)),
        ("zyx", (zyx_rotation, zyx_angles, zyx_rates)),
        ("zxz", (zxz_rotation, zxz_angles, zxz_rates)),
    ];

    /// Where `b` is singular for a sequence: `+-pi/2` or `0, pi`.
    fn singular_b(name: &str) -> [f64; 2] {
        if name == "zxz" {
            [0.0, PI]
        } else {
            [-FRAC_PI_2, FRAC_PI_2]
        }
    }

    /// Angles in the principal branch away from the singular set are recovered to 1e-14
    /// (the extraction is then well conditioned: errors of a few eps per entry).
    #[test]
    fn principal_angles_recovered() {
        for (name, (rot, angles, _)) in SEQS {
            for a in [-3.0, -1.2, 0.0, 0.4, 2.9, PI] {
                for b in [-1.3, -0.4, 0.1, 0.7, 1.4] {
                    for c in [-2.8, -0.5, 0.0, 1.1, 3.1] {
                        let b = if name == "zxz" { b + FRAC_PI_2 } else { b };
                        let e = Vector3::new(a, b, c);
                        let back = angles(&rot(&e));
                        let d = Vector3::new(wrap(back.x - a), back.y - b, wrap(back.z - c));
                        assert!(d.amax() < 1e-14, "{name} {e}: {back}");
                    }
                }
            }
        }
    }

    /// On the singular set and within 1e-6..1e-12 of it, the extracted angles reproduce the
    /// rotation to round-off (geodesic 1e-14), also for a matrix with generic absolute
    /// rounding; exactly on it `a = 0` (documented split).
    #[test]
    fn singular_extraction_keeps_rotation() {
        for (name, (rot, angles, _)) in SEQS {
            for b0 in singular_b(name) {
                for d in [0.0, 1e-12, -1e-12, 1e-9, 1e-6, -1e-6] {
                    for (a, c) in [(0.3, -1.1), (2.9, 2.8), (-3.0, 0.2)] {
                        let e = Vector3::new(a, b0 + d, c);
                        let exact = rot(&e);
                        for r in [exact, generic(&exact)] {
                            let back = angles(&r);
                            let g = so3::geodesic(&r, &rot(&back));
                            assert!(g < 1e-14, "{name} {e}: {back} geodesic {g:e}");
                            assert!(back.y.abs() <= PI && back.x.abs() <= PI && back.z.abs() <= PI);
                            if name == "zxz" {
                                assert!((0.0..=PI).contains(&back.y));
                            } else {
                                assert!(back.y.abs() <= FRAC_PI_2);
                            }
                        }
                    }
                }
            }
            // Exactly singular matrices built from exact entries: a is 0 by convention.
            let exact = match name {
                "xyz" => Matrix3::new(0.0, 0.0, 1.0, 0.6, 0.8, 0.0, -0.8, 0.6, 0.0),
                "zyx" => Matrix3::new(0.0, 0.6, 0.8, 0.0, 0.8, -0.6, -1.0, 0.0, 0.0),
                _ => Matrix3::new(0.6, -0.8, 0.0, 0.8, 0.6, 0.0, 0.0, 0.0, 1.0),
            };
            let back = angles(&exact);
            assert_eq!(back.x, 0.0, "{name}");
            assert!((rot(&back) - exact).amax() < 1e-15 * 4.0, "{name}: {back}");
        }
    }

    /// The rates blow up like 1/conditioning (no clamping): at distance d from the singular
    /// set, a body rate across the singular axis gives |a'| conditioning = 1 to 1e-15.
    #[test]
    fn rates_blow_up_like_inverse_conditioning() {
        for (name, (_, _, rates)) in SEQS {
            for d in [1e-3, 1e-6, 1e-9, 1e-12] {
                let b = singular_b(name)[1] - d;
                let cond = if name == "zxz" {
                    b.sin().abs()
                } else {
                    b.cos().abs()
                };
                assert!(cond < 1.01 * d && cond > 0.99 * d);
                // c = 0: xyz a' = w1/cb, zyx a' = w3/cb, zxz a' = w2/sb.
                let w = match name {
                    "xyz" => Vector3::new(1.0, 0.0, 0.0),
                    "zyx" => Vector3::new(0.0, 0.0, 1.0),
                    _ => Vector3::new(0.0, 1.0, 0.0),
                };
                let r = rates(&Vector3::new(0.2, b, 0.0), &w);
                assert!((r.x.abs() * cond - 1.0).abs() < 1e-15, "{name} {d}: {r}");
            }
        }
    }
}
