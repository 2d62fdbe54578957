//! `simo_wong`: the energy-momentum midpoint scheme on SO(3) x R^3 of Simo & Wong ("Unconditionally
//! stable algorithms for rigid body dynamics that exactly preserve energy and momentum", IJNME
//! 31, 1991), with the rotation updated by the Cayley map, and the potential (springs, gravity)
//! taken by its discrete gradient as Gonzalez ("Time integration and discrete Hamiltonian
//! systems", J. Nonlinear Sci. 6, 1996) and Simo & Tarnow (ZAMP 43, 1992) do, so that the
//! energy is conserved exactly (to round-off). Equation numbers are this file's.
//!
//! Variables: pose `(R, x)`, body angular velocity `Omega`, `Pi = J Omega`, world velocity `v`;
//! `F_g = -m g0 e_z`. Unknowns of a step `n -> n+1`: `Theta` and `x_{n+1}`. Equations:
//! - (SW1) `C = cay(Theta)`, `R_{n+1} = R_n C`; then `R_{n+1} - R_n = Rbar [Theta]x` exactly
//!   with `Rbar = (R_n + R_{n+1})/2 = R_n (I + C)/2`.
//! - (SW2) discrete gradient of spring `i` (`d = a_i - x - R b_i`, `l = |d|`, energy
//!   `k/2 (l - L)^2`, a function of `l^2`, and `l^2` is quadratic in `(x, R)`): the Gonzalez
//!   quotient `q_i = (V(l_1) - V(l_0)) / (l_1^2 - l_0^2) = k/2 (1 - 2 L / (l_0 + l_1))` (closed
//!   form: no cancellation when `l_1 -> l_0`, where it tends to the derivative `V'(l^2)`),
//!   force `fbar_i = q_i (d_0 + d_1)` (world), moment `mbar_i = b_i x (Rbar^T fbar_i)`; gravity:
//!   `fbar += F_g` (free body, linear in `x`) or `mbar += X x (Rbar^T F_g)` (pinned body, `X`
//!   the centre of mass, linear in `R`).
//! - (SW3) hence exactly `V_{n+1} - V_n = -fbar . (x_{n+1} - x_n) - Theta . mbar`.
//! - (SW4) `C Pi_{n+1} - Pi_n = h (I + C)/2 mbar` (in the world: `pi_{n+1} - pi_n = h Rbar mbar`).
//! - (SW5) `Theta = h/2 (Omega_n + Omega_{n+1})`.
//! - (SW6) `m (v_{n+1} - v_n) = h fbar`, `x_{n+1} - x_n = h/2 (v_n + v_{n+1})`.
//!
//! Energy: `C^T Theta = Theta` (C turns about Theta), so `Theta . (SW4)` with (SW5) gives
//! `T_rot,n+1 - T_rot,n = Theta . mbar`, (SW6) gives `T_tr,n+1 - T_tr,n = fbar . dx`, and (SW3)
//! closes `E_{n+1} = E_n`. Momentum: torque-free, (SW4) is `pi_{n+1} = pi_n` exactly; a pinned
//! body under gravity has `e_z . Rbar mbar = (Rbar^T e_z) . (X x Rbar^T F_g) = 0`, so the
//! vertical `L_z` is conserved (the weight `(I + C)/2` in (SW4) is the only one that keeps both
//! energy and `L_z` and the symmetry below). The scheme is invariant under
//! `(n <-> n+1, h -> -h, Theta -> -Theta)`, hence symmetric and of order 2.
//!
//! Solution: `Omega_{n+1} = 2 Theta/h - Omega_n`, `v_{n+1} = 2 (x_{n+1} - x_n)/h - v_n` turn
//! (SW4), (SW6) into the residual (scaled by `h/2`)
//! - (SW7) `G_rot = C J (Theta - h/2 Omega_n) - h/2 Pi_n - h^2/4 (mbar + C mbar)`,
//!   `G_tr = m (x_{n+1} - x_n - h v_n) - h^2/2 fbar`,
//!
//! six equations (three for a pinned body, whose translation is frozen), solved by Newton with a
//! forward-difference Jacobian, formed at the predictor `Theta = h Omega_n - h^2/2 J^-1
//! (Omega_n x Pi_n)`, `x = x_n + h v_n` and re-formed at the current iterate when an update
//! shrinks by less than 4x; the iteration stops when the update is below `10 eps` relative to
//! `|Theta|` and to `|x|` (`newton_stop`). `stats.rhs_evals` counts evaluations of the residual
//! (each evaluates the springs at both ends: about one force evaluation), Jacobian columns
//! included; `stats.newton_iters` the updates (measured: 4 to 5 updates and 7 to 11
//! residuals a step on the catalogue's cases). Fails (`newton_failure`) when `h |Omega|` approaches the Cayley map's range
//! (`|Theta| -> infinity` is a half turn) or the forces are too stiff for the step.
use nalgebra::{Matrix3, Matrix6, UnitQuaternion, Vector3, Vector6};

use crate::integrate::lu6::Lu6;
use crate::integrate::newton_stop::{NewtonStop, relative, update_norm};
use super::So3State;
use crate::integrate::{Failure, FailureKind, FixedStep, MethodInfo, MethodKind, Stats};
use crate::math::so3;
use crate::model::rigid_body::{RigidBody, RigidSystem};
use crate::rotation::{Body, Pose, So3};

/// The energy-momentum midpoint scheme with discrete-gradient forces.
#[derive(Debug, Clone, Copy, Default)]
pub struct SimoWong;

impl SimoWong {
    pub fn new() -> Self {
        SimoWong
    }
}

/// The data of one step (also used by `simo_wong_kahan`).
pub(super) struct StepData<'a> {
    pub(super) b: &'a RigidBody,
    pub(super) r0: Matrix3<f64>,
    pub(super) x0: Vector3<f64>,
    pub(super) v0: Vector3<f64>,
    pub(super) omega0: Vector3<f64>,
    pub(super) pi0: Vector3<f64>,
    pub(super) h: f64,
    pub(super) translates: bool,
}

impl StepData<'_> {
    /// (SW2): `(fbar, mbar)` for `R_{n+1}`, `Rbar` and `x_{n+1}`.
    #[inline]
    pub(super) fn discrete_wrench(
        &self,
        r1: &Matrix3<f64>,
        rbar: &Matrix3<f64>,
        x1: &Vector3<f64>,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let b = self.b;
        let mut f = Vector3::zeros();
        let mut m = Vector3::zeros();
        for s in &b.springs {
            let d0 = s.anchor - (self.x0 + self.r0 * s.body_point);
            let d1 = s.anchor - (x1 + r1 * s.body_point);
            let sum = d0.norm() + d1.norm();
            if sum > 0.0 {
                let q = 0.5 * s.stiffness * (1.0 - 2.0 * s.rest_length / sum);
                let fi = (d0 + d1) * q;
                f += fi;
                m += s.body_point.cross(&(rbar.transpose() * fi));
            }
        }
        if let Some(g) = b.gravity {
            let fg = Vector3::new(0.0, 0.0, -b.mass * g);
            match b.pivot_com {
                Some(com) => m += com.cross(&(rbar.transpose() * fg)),
                None => f += fg,
            }
        }
        (f, m)
    }

    /// (SW7).
    #[inline]
    fn residual(&self, z: &Vector6<f64>) -> Vector6<f64> {
        let theta = z.fixed_rows::<3>(0).into_owned();
        // The translation unknown is the increment dx = x1 - x0 (like Theta for the rotation):
        // recovering v1 from an absolute x1 would cancel about |x| eps / h each step, which on
        // nine_spring at 6.25e-4 s drifted the energy by 2.8e-12 in 16000 steps.
        let dx = z.fixed_rows::<3>(3).into_owned();
        let x1 = if self.translates {
            self.x0 + dx
        } else {
            self.x0
        };
        let c = so3::cay(&theta);
        let r1 = self.r0 * c;
        let rbar = (self.r0 + r1) * 0.5;
        let (f, m) = self.discrete_wrench(&r1, &rbar, &x1);
        let h = self.h;
        let g_rot = c * (self.b.inertia * (theta - self.omega0 * (0.5 * h)))
            - self.pi0 * (0.5 * h)
            - (m + c * m) * (0.25 * h * h);
        let g_tr = if self.translates {
            (dx - self.v0 * h) * self.b.mass - f * (0.5 * h * h)
        } else {
            dx
        };
        Vector6::new(g_rot.x, g_rot.y, g_rot.z, g_tr.x, g_tr.y, g_tr.z)
    }

    /// Forward-difference Jacobian of (SW7) at `z` with residual `g0` there.
    fn jacobian(&self, z: &Vector6<f64>, g0: &Vector6<f64>, stats: &mut Stats) -> Matrix6<f64> {
        forward_jacobian(z, g0, self.translates, |zp| self.residual(zp), stats)
    }
}

/// Forward-difference Jacobian of a residual of the 6 unknowns (rotational block 0..3,
/// translational block 3..6; only the first when the body does not translate, the rest of
/// the matrix being the identity) at `z`, whose residual is `g0`: each column's step is
/// `sqrt(eps) max(|z_j|, size of its block)`, rounded to a representable difference. Shared
/// by `simo_wong` and `simo_wong_kahan`; every evaluation counts as one RHS evaluation.
pub(super) fn forward_jacobian(
    z: &Vector6<f64>,
    g0: &Vector6<f64>,
    translates: bool,
    residual: impl Fn(&Vector6<f64>) -> Vector6<f64>,
    stats: &mut Stats,
) -> Matrix6<f64> {
    let mut jac = Matrix6::identity();
    let n = if translates { 6 } else { 3 };
    let rot_size = z.fixed_rows::<3>(0).amax().max(1e-6);
    let tr_size = z.fixed_rows::<3>(3).amax().max(1e-6);
    let sq = f64::EPSILON.sqrt();
    for j in 0..n {
        let size = if j < 3 { rot_size } else { tr_size };
        let dz = sq * z[j].abs().max(size);
        let mut zp = *z;
        zp[j] += dz;
        let dz = zp[j] - z[j];
        let gp = residual(&zp);
        stats.rhs_evals += 1;
        jac.set_column(j, &((gp - g0) / dz));
    }
    jac
}

impl FixedStep<RigidSystem<So3, Body>> for SimoWong {
    fn info(&self) -> MethodInfo {
        MethodInfo::new("simo_wong", MethodKind::Geometric, 2)
            .with_implicit(true)
            .with_lie_group(true)
            .with_energy_conserving(true)
    }

    fn step(
        &mut self,
        sys: &RigidSystem<So3, Body>,
        t: f64,
        h: f64,
        s: &mut So3State,
        stats: &mut Stats,
    ) -> Result<(), Failure> {
        if h == 0.0 {
            return Ok(());
        }
        let b = &sys.body;
        let omega0 = s.vel.fixed_rows::<3>(3).into_owned();
        let pi0 = b.inertia * omega0;
        let d = StepData {
            b,
            r0: s.pose.rot.to_rotation_matrix().into_inner(),
            x0: s.pose.x,
            v0: s.vel.fixed_rows::<3>(0).into_owned(),
            omega0,
            pi0,
            h,
            translates: b.translates(),
        };
        // Predictor (torque-free second-order Taylor step).
        let th = omega0 * h - b.inertia_inv * omega0.cross(&pi0) * (0.5 * h * h);
        let xp = if d.translates {
            d.v0 * h
        } else {
            Vector3::zeros()
        };
        let mut z = Vector6::new(th.x, th.y, th.z, xp.x, xp.y, xp.z);

        let mut g = d.residual(&z);
        stats.rhs_evals += 1;
        let mut lu = Lu6::new(d.jacobian(&z, &g, stats));
        let mut stop = NewtonStop::new();
        let mut prev = f64::INFINITY;
        loop {
            let delta = lu.solve(&(-g)).ok_or_else(|| {
                Failure::new(
                    FailureKind::NewtonFailure,
                    t,
                    "simo_wong: singular Newton matrix",
                )
            })?;
            z += delta;
            stats.newton_iters += 1;
            let dth = delta.fixed_rows::<3>(0).amax();
            let rel_th = relative(dth, z.fixed_rows::<3>(0).amax());
            let rel = if update_norm(delta.as_slice()).is_nan() {
                f64::NAN
            } else if d.translates {
                let x_size = z.fixed_rows::<3>(3).amax();
                rel_th.max(relative(delta.fixed_rows::<3>(3).amax(), x_size))
            } else {
                rel_th
            };
            if stop.judge(rel, t, "simo_wong")? {
                break;
            }
            g = d.residual(&z);
            stats.rhs_evals += 1;
            if rel > 0.25 * prev {
                lu = Lu6::new(d.jacobian(&z, &g, stats));
            }
            prev = rel;
        }

        let theta = z.fixed_rows::<3>(0).into_owned();
        // Recovered exactly as (SW7) scales them: `2 Theta/h - Omega_n` would round `2/h`
        // (h = 0.1: 20 instead of 19.99999999999999889) the same way every step, a drift of
        // 1e-16 per step in |Pi| and the energy (measured on gni; 2e-17 this way).
        let omega1 = (theta - omega0 * (0.5 * h)) / (0.5 * h);
        let (x1, v1) = if d.translates {
            let dx = z.fixed_rows::<3>(3).into_owned();
            (d.x0 + dx, (dx - d.v0 * (0.5 * h)) / (0.5 * h))
        } else {
            (d.x0, d.v0)
        };
        let q1 = UnitQuaternion::new_unchecked(
            s.pose.rot.into_inner() * so3::cay_quat(&theta).into_inner(),
        );
        let vel = Vector6::new(v1.x, v1.y, v1.z, omega1.x, omega1.y, omega1.z);
        let finite = vel.iter().all(|c| c.is_finite())
            && q1.coords.iter().all(|c| c.is_finite())
            && x1.iter().all(|c| c.is_finite());
        if !finite {
            return Err(Failure::new(
                FailureKind::NonFinite,
                t + h,
                "simo_wong: non-finite state",
            ));
        }
        *s = So3State {
            pose: Pose { rot: q1, x: x1 },
            vel,
        };
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::rigid_test_support as ts;

    /// The discrete gradient identity (SW3) holds to round-off for a large finite step.
    #[test]
    fn discrete_gradient_identity() {
        for (sys, s) in [ts::three_springs(), ts::nine_spring(), ts::heavy_top()] {
            let b = &sys.body;
            let r0 = s.pose.rot.to_rotation_matrix().into_inner();
            let d = StepData {
                b,
                r0,
                x0: s.pose.x,
                v0: Vector3::zeros(),
                omega0: Vector3::zeros(),
                pi0: Vector3::zeros(),
                h: 0.1,
                translates: b.translates(),
            };
            let theta = Vector3::new(0.3, -0.5, 0.2);
            let x1 = if b.translates() {
                s.pose.x + Vector3::new(0.1, 0.05, -0.2)
            } else {
                s.pose.x
            };
            let r1 = r0 * so3::cay(&theta);
            let (f, m) = d.discrete_wrench(&r1, &((r0 + r1) * 0.5), &x1);
            let dv = b.potential(&r1, &x1) - b.potential(&r0, &s.pose.x);
            let work = -f.dot(&(x1 - s.pose.x)) - theta.dot(&m);
            let scale = b.potential(&r0, &s.pose.x).abs() + dv.abs();
            assert!((dv - work).abs() <= 1e-14 * scale, "{dv} {work}");
        }
    }

    ts::order_two_tests!("simo_wong", SimoWong::new);

    /// Max relative energy error and max |L - L0| over a run (and the stats).
    fn invariants(sys: &ts::Sys, x0: &ts::St, t_end: f64, n: usize) -> (f64, f64, Stats) {
        let (de, dl, _, st) = ts::invariant_errors(&mut SimoWong::new(), sys, x0, t_end, n);
        (de, dl, st)
    }

    /// Energy conserved to 1e-12 (relative) and world angular momentum to 1e-13 over the gni
    /// horizon (100 s, dt = 0.1).
    #[test]
    fn conserves_energy_and_momentum_gni() {
        let (sys, x0) = ts::gni();
        let (de, dl, st) = invariants(&sys, &x0, 100.0, 1000);
        eprintln!("simo_wong gni dt=0.1: max |dE/E0| {de:.3e}, max |dL| {dl:.3e}, {st:?}");
        assert!(de <= 1e-12);
        assert!(dl <= 1e-13);
    }

    /// Energy conserved to 1e-12 (relative) on nine_spring `large`, 10 s, dt = 1e-2 and 5e-3.
    #[test]
    fn conserves_energy_nine_spring() {
        let (sys, x0) = ts::nine_spring();
        let e0 = ts::energy(&sys, &x0);
        assert!((e0 - 25035.29).abs() < 0.01, "E0 = {e0}");
        for n in [1000, 2000] {
            let (de, _, st) = invariants(&sys, &x0, 10.0, n);
            eprintln!(
                "simo_wong nine_spring dt={}: max |dE/E0| {de:.3e}, {st:?}",
                10.0 / n as f64
            );
            assert!(de <= 1e-12);
        }
    }

    /// The heavy top runs 0.2 s at dt = 1e-3 with energy and L_z conserved.
    #[test]
    fn heavy_top_conserves_energy_and_lz() {
        let (sys, x0) = ts::heavy_top();
        let e0 = ts::energy(&sys, &x0);
        let lz0 = ts::momentum(&sys, &x0).z;
        let (mut de, mut dlz) = (0.0_f64, 0.0_f64);
        let mut m = SimoWong::new();
        let (_, st) = ts::run(&mut m, &sys, &x0, 0.2, 200, |_, x| {
            de = de.max(((ts::energy(&sys, x) - e0) / e0).abs());
            dlz = dlz.max((ts::momentum(&sys, x).z - lz0).abs());
        })
        .unwrap();
        eprintln!("simo_wong heavy_top dt=1e-3: max |dE/E0| {de:.3e}, max |dLz| {dlz:.3e}, {st:?}");
        assert!(de <= 1e-12);
        assert!(dlz <= 1e-12 * ts::momentum(&sys, &x0).norm());
    }
}
