//! The generic (elliptic) torque-free motion evaluated at a phase: the data `TorqueFreeExact::new`
//! computes in the canonical frame `(a, b, c)` (`mod.rs`, where the equations are derived:
//! Landau & Lifshitz, *Mechanics*, sec. 37; DLMF 19.25.14), the reduction of the phase
//! `tau = 2K j + tau_r`, `|tau_r| <= K`, the canonical body angular velocity
//! `omega = (al_a cn, s_b al_b sn, s_c al_c dn)(tau)` (the sign of `cn` and `sn` flipping with
//! `j` odd), the precession integral `W(tau) = j W2 + W_r(tau_r)` and the alignment
//! `M = Rx(theta) Rz(psi)` with `M L = |L| e3`.
//!
//! Invariants: `dn` is the elliptic module's cancellation-free one (`dn^2 = m1 + m cn^2` to
//! round-off), so no digit of `omega` is lost near the separatrix; `W_r` is evaluated with
//! `cn >= 0`, where Carlson's form holds. Where it fails: `w_reduced` is NaN where the
//! elliptic integral refuses its arguments; `new` rejects data whose `W(tau0)` or period `W2`
//! is not finite.
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};

use crate::math::elliptic::{Jacobi, incomplete_pi_sc};

/// Everything the elliptic solution needs, in the canonical frame `(a, b, c)`.
#[derive(Clone, Debug)]
pub(super) struct Elliptic {
    /// User body -> canonical body (a signed permutation, `det = 1`).
    pub(super) perm: Matrix3<f64>,
    pub(super) q_perm: UnitQuaternion<f64>,
    /// `J_a, J_b, J_c`.
    pub(super) inertia: Vector3<f64>,
    /// `al_a, s_b al_b, s_c al_c`.
    pub(super) amp: Vector3<f64>,
    pub(super) lambda: f64,
    pub(super) tau0: f64,
    pub(super) jac: Jacobi,
    /// `|L| / J_c` and `|L| (J_c - J_a)/(J_c J_a lambda)`.
    pub(super) prec_rate: f64,
    pub(super) prec_coef: f64,
    pub(super) nu: f64,
    /// `W` over one period `2K` of `sn^2`, and `W(tau0)`.
    pub(super) w_period: f64,
    pub(super) w0: f64,
    /// `R0 P^T M(0)^T` as a quaternion.
    pub(super) q_left: UnitQuaternion<f64>,
}

/// `Rx(a)` as a unit quaternion.
fn quat_x(a: f64) -> UnitQuaternion<f64> {
    let (s, c) = (0.5 * a).sin_cos();
    UnitQuaternion::new_unchecked(Quaternion::new(c, s, 0.0, 0.0))
}

/// `Rz(a)` as a unit quaternion.
pub(super) fn quat_z(a: f64) -> UnitQuaternion<f64> {
    let (s, c) = (0.5 * a).sin_cos();
    UnitQuaternion::new_unchecked(Quaternion::new(c, 0.0, 0.0, s))
}

impl Elliptic {
    /// `(sn, cn, dn)(tau_r)` and `j` with `tau = 2K j + tau_r`, `|tau_r| <= K`.
    #[inline]
    fn reduce(&self, tau: f64) -> (f64, (f64, f64, f64)) {
        let half = 2.0 * self.jac.k();
        let j = (tau / half).round();
        let tau_r = (-j).mul_add(half, tau);
        (j, self.jac.sn_cn_dn(tau_r))
    }

    /// `W_r = ∫_0^{tau_r} du / (1 + nu sn^2)` from `sn, cn >= 0, dn` of `tau_r`.
    #[inline]
    fn w_reduced(&self, s: f64, c: f64) -> f64 {
        incomplete_pi_sc(s, c, self.jac.m1(), -self.nu).unwrap_or(f64::NAN)
    }

    /// Canonical body angular velocity and `W(tau)` at phase `tau`.
    #[inline]
    pub(super) fn state(&self, tau: f64) -> (Vector3<f64>, f64) {
        let (j, (s, c, d)) = self.reduce(tau);
        let sign = if j.rem_euclid(2.0) == 0.0 { 1.0 } else { -1.0 };
        let omega = Vector3::new(self.amp.x * sign * c, self.amp.y * sign * s, self.amp.z * d);
        let w = j.mul_add(self.w_period, self.w_reduced(s, c.abs()));
        (omega, w)
    }

    /// `M = Rx(theta) Rz(psi)` with `M L = |L| e3` for the canonical body `omega`.
    #[inline]
    pub(super) fn align(&self, omega: &Vector3<f64>) -> UnitQuaternion<f64> {
        let l = self.inertia.component_mul(omega);
        let h = l.x.hypot(l.y);
        quat_x(h.atan2(l.z)) * quat_z(l.x.atan2(l.y))
    }
}
