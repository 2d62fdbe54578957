//! Exact motion of the torque-free rigid body (Euler-Poinsot), the reference of
//! `free_body/*` and `gimbal_lock/tumble` (cases/README.md, `gimbal_lock` and `free_body`), and of
//! the constant-angular-velocity spins `gimbal_lock/spin_*` ([`spin_exact`]).
//!
//! Equations: `J omega' = J omega x omega`, `R' = R [omega]x` (`R` body -> world, `omega`
//! body frame, `J = diag` in the body frame). Conserved: `T = omega.J.omega / 2`, the body
//! `|L|` (`L = J omega`), the world `R L`.
//!
//! **Angular velocity** (Landau & Lifshitz, *Mechanics*, sec. 37, in a role-free form). Name
//! the principal axes `a, b, c` with `b` the intermediate one and, with the cancellation-free
//! `S = |L|^2 - 2 T J_b = sum_i J_i (J_i - J_b) omega_i^2`, `c` the axis the motion
//! circulates around: the largest if `S > 0`, the smallest if `S < 0`; `a` the other.
//! `(a, b, c)` is made right-handed by a signed permutation `P` (`det P = 1`,
//! `omega_can = P omega`). With
//! `A = 2 T J_c - |L|^2 = sum_i J_i (J_c - J_i) omega_i^2`,
//! `C = |L|^2 - 2 T J_a = sum_i J_i (J_i - J_a) omega_i^2` (each a sum of same-sign terms),
//! `omega_a = al_a cn tau`, `omega_b = s_b al_b sn tau`, `omega_c = s_c al_c dn tau`,
//! `al_a^2 = A / (J_a (J_c - J_a))`, `al_b^2 = A / (J_b (J_c - J_b))`,
//! `al_c^2 = C / (J_c (J_c - J_a))`, `tau = lambda t + tau0`,
//! `lambda^2 = (J_c - J_b) C / (J_a J_b J_c)`, `m = (J_b - J_a) A / ((J_c - J_b) C)`,
//! `m1 = 1 - m = (J_c - J_a) S / ((J_c - J_b) C)` (computed from `S`, not as `1 - m`),
//! `s_c = sign omega_c(0)` (never zero), `s_b = sign(J_c - J_a) s_c`. All ratios are positive
//! on either side of the separatrix (the signs cancel), and substituting into Euler's
//! equations checks them term by term. The phase `tau0` has `cn tau0 = omega_a(0)/al_a`,
//! `sn tau0 = omega_b(0)/(s_b al_b)`: `tau0 = F(phi0|m)`, or `2K sgn(sn) - F(pi - phi0|m)` if
//! `cn < 0`, by Carlson's `R_F` (math/elliptic.rs). `dn` comes from the elliptic module in its
//! cancellation-free form (`dn^2 = m1 + m cn^2` to round-off), so near the separatrix
//! (`m1 ~ 1e-6 .. 1e-11`) no digit of `omega` is lost.
//!
//! **Attitude.** With `n = L_can/|L|` (body), write `R_can(t) = G Rz(phi(t)) M(t)`,
//! `M = Rx(theta) Rz(psi)`, `n = M^T e3 = (sin theta sin psi, sin theta cos psi, cos theta)`,
//! i.e. `psi = atan2(L_a, L_b)`, `theta = atan2(hypot(L_a, L_b), L_c)` (Landau's Euler
//! angles), and `G e3 = L_world/|L|` constant. Then `R^T R' = [phi' n]x + M^T M'` gives
//! `phi' = omega.n - vee(M^T M').n = |L| (J_a w_a^2 + J_b w_b^2)/(L_a^2 + L_b^2)`, which with
//! the solution above is
//! `phi' = |L|/J_c + |L| (J_c - J_a)/(J_c J_a) / (1 + nu sn^2 tau)`,
//! `nu = J_c (J_b - J_a) / (J_a (J_c - J_b)) >= 0`, so
//! `phi(t) - phi(0) = |L| t / J_c + |L| (J_c - J_a)/(J_c J_a lambda) (W(tau) - W(tau0))`,
//! `W(tau) = ∫_0^tau du / (1 + nu sn^2 u) = Pi(am tau, -nu | m)`, the incomplete integral of
//! the third kind with a negative characteristic (no pole). `sn^2` has period `2K`, so with
//! `tau = 2K j + tau_r`, `|tau_r| <= K`: `W = j W2 + W_r`, `W2 = 2 Pi(-nu|m)` (complete),
//! `W_r = s R_F(c^2, d^2, 1) - (nu/3) s^3 R_J(c^2, d^2, 1, 1 + nu s^2)` (DLMF 19.25.14),
//! `s, c, d = sn, cn, dn (tau_r)` (`c >= 0`). Choosing `phi(0) = 0` and `R(0) = R0`:
//! `R(t) = R0 P^T M(0)^T Rz(phi(t)) M(t) P`, i.e. `R = R0 R_I` with `R_I` the solution from
//! `R = I`. World `L` is `|L(t)| R0 P^T M(0)^T e3`: its direction is exact by construction and
//! its size is `|L|` to the round-off of the elliptic identities.
//!
//! Non-generic case, in closed form `R(t) = R0 exp(t [omega0]x)`, `omega(t) = omega0`:
//! `omega0` an eigenvector of `J` (steady spin, including the unstable intermediate axis, the
//! zero vector and every spherical body; detected exactly, component by component).
//! Axisymmetric bodies off their symmetry planes go through the elliptic path with `m = 0`,
//! `nu = 0` (checked against the regular precession `exp(t [L_w/J_perp]x) R0
//! exp(t (1/J_e - 1/J_perp) L_e [e]x)` in the tests). An exact separatrix (`S = 0` but not a
//! steady spin) is rejected with `Err`, as are non-positive or non-finite moments, a
//! non-finite `omega0` and a non-rotation `R0`.
//!
//! Accuracy (measured in the tests): `|L|`, `T`, world `L` constant to 2e-15 relative;
//! against a 30-digit mpmath Taylor integration, within 2e-14 rad and 1e-14 relative in
//! `omega` over 100 s (`gni`) and 20 s (`tumble`, two flips): a few ulps of the phases
//! `lambda t + tau0` and `phi` (up to ~150 rad), which is the conditioning of the problem.
//!
//! Files: this one holds `TorqueFreeExact` (the checks, the steady-spin case and the
//! construction of the elliptic data above, and `at`); `elliptic.rs` the evaluation of the
//! elliptic solution at a phase; `spin.rs` the constant-angular-velocity spin (`spin_exact`);
//! `tests.rs` the tests.
mod elliptic;
mod spin;
#[cfg(test)]
mod tests;

use nalgebra::{Matrix3, UnitQuaternion, Vector3};

use crate::math::elliptic::{Jacobi, incomplete_f_sc, incomplete_pi_sc};
use crate::math::so3;
use elliptic::{Elliptic, quat_z};
pub use spin::spin_exact;

/// The exact torque-free motion from `(J, omega0, R0)`.
#[derive(Clone, Debug)]
pub struct TorqueFreeExact {
    motion: Motion,
}

#[derive(Clone, Debug)]
enum Motion {
    /// Steady spin: `R(t) = R0 exp(t [omega0]x)`, `omega(t) = omega0`.
    Steady {
        q0: UnitQuaternion<f64>,
        omega0: Vector3<f64>,
    },
    Elliptic(Box<Elliptic>),
}

impl TorqueFreeExact {
    /// The motion with principal moments `inertia_diag` (body frame, any order),
    /// body angular velocity `omega0_body` and attitude `r0` (body -> world) at `t = 0`.
    pub fn new(
        inertia_diag: Vector3<f64>,
        omega0_body: Vector3<f64>,
        r0: Matrix3<f64>,
    ) -> Result<Self, String> {
        check_inputs(&inertia_diag, &omega0_body, &r0)?;
        let q0 = so3::quat_from_matrix(&r0);
        let (jd, w) = (inertia_diag, omega0_body);

        if is_steady_spin(&jd, &w) {
            return Ok(TorqueFreeExact {
                motion: Motion::Steady { q0, omega0: w },
            });
        }

        let frame = Frame::of(&jd, &w)?;
        let e = elliptic_motion(q0, &jd, &w, frame)?;
        Ok(TorqueFreeExact {
            motion: Motion::Elliptic(Box::new(e)),
        })
    }

    /// `(R(t), omega(t))`: the rotation body -> world (sign-canonical quaternion) and the
    /// body angular velocity.
    pub fn at(&self, t: f64) -> (UnitQuaternion<f64>, Vector3<f64>) {
        match &self.motion {
            Motion::Steady { q0, omega0 } => {
                let q = q0 * so3::exp_quat(&(omega0 * t));
                (so3::canonical(&q), *omega0)
            }
            Motion::Elliptic(e) => {
                let tau = e.lambda.mul_add(t, e.tau0);
                let (omega, w) = e.state(tau);
                let phi = e.prec_rate.mul_add(t, e.prec_coef * (w - e.w0));
                let q = e.q_left * quat_z(phi) * e.align(&omega) * e.q_perm;
                (so3::canonical(&q), e.perm.transpose() * omega)
            }
        }
    }
}

/// Refuses non-positive or non-finite moments, a non-finite `omega0` and an `R0` that is not
/// a rotation.
fn check_inputs(
    inertia_diag: &Vector3<f64>,
    omega0_body: &Vector3<f64>,
    r0: &Matrix3<f64>,
) -> Result<(), String> {
    if !inertia_diag.iter().all(|v| v.is_finite() && *v > 0.0) {
        return Err(format!(
            "TorqueFreeExact: moments {inertia_diag:?} must be positive"
        ));
    }
    if !omega0_body.iter().all(|v| v.is_finite()) {
        return Err(format!(
            "TorqueFreeExact: omega0 {omega0_body:?} is not finite"
        ));
    }
    let orth = (r0.transpose() * r0 - Matrix3::identity()).abs().max();
    if !(orth <= 1e-9 && r0.determinant() > 0.0) {
        return Err(format!(
            "TorqueFreeExact: R0 is not a rotation (|R^T R - I| = {orth})"
        ));
    }
    Ok(())
}

/// Steady spin: every non-zero component of omega0 on axes of one and the same moment.
fn is_steady_spin(jd: &Vector3<f64>, w: &Vector3<f64>) -> bool {
    let mut moment = None;
    let mut steady = true;
    for i in 0..3 {
        if w[i] != 0.0 {
            match moment {
                None => moment = Some(jd[i]),
                Some(mi) => steady &= mi == jd[i],
            }
        }
    }
    steady
}

/// `sum_i J_i (sign (J_i - pivot)) omega_i^2` (`S`, `A` and `C` of the module's notation).
fn signed_sum(jd: &Vector3<f64>, w: &Vector3<f64>, pivot: f64, sign: f64) -> f64 {
    (0..3)
        .map(|i| jd[i] * (sign * (jd[i] - pivot)) * w[i] * w[i])
        .sum()
}

/// The axes `(a, b, c)` of the module's notation, made right-handed by `perm`.
struct Frame {
    /// `S = |L|^2 - 2 T J_b`.
    s_sep: f64,
    /// The signed permutation `P` (`omega_can = P omega`) and its quaternion.
    perm: Matrix3<f64>,
    q_perm: UnitQuaternion<f64>,
    ja: f64,
    jb: f64,
    jc: f64,
    /// `(J_a, J_b, J_c)`.
    inertia: Vector3<f64>,
    /// `P omega0`.
    wc: Vector3<f64>,
}

impl Frame {
    /// The frame of `(J, omega0)` from the sign of `S`; an error on the separatrix (`S = 0`).
    fn of(jd: &Vector3<f64>, w: &Vector3<f64>) -> Result<Frame, String> {
        let mut idx = [0usize, 1, 2];
        idx.sort_by(|&i, &k| jd[i].total_cmp(&jd[k]));
        let ib = idx[1];
        let s_sep = signed_sum(jd, w, jd[ib], 1.0);
        if s_sep == 0.0 {
            return Err(format!(
                "TorqueFreeExact: omega0 {w:?} lies exactly on the separatrix of J = {jd:?} \
                 (|L|^2 = 2 T J_2): the heteroclinic motion is not handled"
            ));
        }
        let (ia, ic) = if s_sep > 0.0 {
            (idx[0], idx[2])
        } else {
            (idx[2], idx[0])
        };
        // Row a carries the sign that makes (a, b, c) right-handed.
        let cyclic = ib == (ia + 1) % 3;
        let mut perm = Matrix3::zeros();
        perm[(0, ia)] = if cyclic { 1.0 } else { -1.0 };
        perm[(1, ib)] = 1.0;
        perm[(2, ic)] = 1.0;
        let q_perm = so3::quat_from_matrix(&perm);
        let (ja, jb, jc) = (jd[ia], jd[ib], jd[ic]);
        let inertia = Vector3::new(ja, jb, jc);
        let wc = perm * w;
        Ok(Frame {
            s_sep,
            perm,
            q_perm,
            ja,
            jb,
            jc,
            inertia,
            wc,
        })
    }
}

/// The elliptic solution in `frame`: amplitudes, rate, parameter, initial phase and the
/// precession's constants, aligned so that `R(0) = R0`; an error on degenerate data.
fn elliptic_motion(
    q0: UnitQuaternion<f64>,
    jd: &Vector3<f64>,
    w: &Vector3<f64>,
    frame: Frame,
) -> Result<Elliptic, String> {
    let Frame {
        s_sep,
        perm,
        q_perm,
        ja,
        jb,
        jc,
        inertia,
        wc,
    } = frame;
    let a_int = signed_sum(jd, w, jc, -1.0); // 2 T J_c - |L|^2
    let c_int = signed_sum(jd, w, ja, 1.0); // |L|^2 - 2 T J_a
    let al_a = (a_int / (ja * (jc - ja))).sqrt();
    let al_b = (a_int / (jb * (jc - jb))).sqrt();
    let al_c = (c_int / (jc * (jc - ja))).sqrt();
    let lambda = ((jc - jb) * c_int / (ja * jb * jc)).sqrt();
    let m = (jb - ja) * a_int / ((jc - jb) * c_int);
    let m1 = (jc - ja) * s_sep / ((jc - jb) * c_int);
    let jac = if m1 <= 0.5 {
        Jacobi::from_m1(m1)?
    } else {
        Jacobi::from_m(m)?
    };
    let s_c = wc.z.signum();
    let s_b = (jc - ja).signum() * s_c;
    let amp = Vector3::new(al_a, s_b * al_b, s_c * al_c);

    let tau0 = initial_phase(&wc, al_a, &amp, &jac)?;

    let l_norm = inertia.component_mul(&wc).norm();
    let nu = jc * (jb - ja) / (ja * (jc - jb));
    let mut e = Elliptic {
        perm,
        q_perm,
        inertia,
        amp,
        lambda,
        tau0,
        jac,
        prec_rate: l_norm / jc,
        prec_coef: l_norm * (jc - ja) / (jc * ja * lambda),
        nu,
        w_period: 0.0,
        w0: 0.0,
        q_left: UnitQuaternion::identity(),
    };
    e.w_period = 2.0 * incomplete_pi_sc(1.0, 0.0, jac.m1(), -nu)?;
    let (omega_start, w0) = e.state(tau0);
    if !(w0.is_finite() && e.w_period.is_finite() && lambda.is_finite() && lambda > 0.0) {
        return Err(format!(
            "TorqueFreeExact: degenerate elliptic data for J = {jd:?}, omega0 = {w:?}"
        ));
    }
    e.w0 = w0;
    e.q_left = q0 * q_perm.inverse() * e.align(&omega_start).inverse();
    Ok(e)
}

/// Initial phase from (cn, sn)(tau0): `F(phi0|m)`, or `2K sgn(sn) - F(pi - phi0|m)` if
/// `cn < 0`.
fn initial_phase(
    wc: &Vector3<f64>,
    al_a: f64,
    amp: &Vector3<f64>,
    jac: &Jacobi,
) -> Result<f64, String> {
    let (x, y) = (wc.x / al_a, wc.y / amp.y);
    let r = x.hypot(y);
    let (sn0, cn0) = (y / r, x / r);
    let f = incomplete_f_sc(sn0, cn0.abs(), jac.m1())?;
    let tau0 = if cn0 >= 0.0 {
        f
    } else {
        let sgn = if sn0 < 0.0 { -1.0 } else { 1.0 };
        sgn * 2.0 * jac.k() - f
    };
    Ok(tau0)
}
