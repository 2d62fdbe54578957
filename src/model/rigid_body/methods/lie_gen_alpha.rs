//! `lie_gen_alpha`: the Lie-group generalized-alpha method of Brüls & Cardona ("On the use of
//! Lie group time integrators in multibody dynamics", J. Comput. Nonlinear Dynam. 5, 031002,
//! 2010) and Arnold & Brüls ("Convergence of the generalized-alpha scheme for
//! constrained mechanical systems", Multibody Syst. Dyn. 18, 2007), with the parameters of
//! Chung & Hulbert (J. Appl. Mech. 60, 1993) from the spectral radius at infinity `rho_inf`.
//! Equation numbers are this file's.
//!
//! Configuration `q = (R, x)` on SO(3) x R^3, velocity `w = (v, Omega)` (world velocity,
//! body angular velocity: the right-trivialised velocity, `R' = R [Omega]x`), acceleration
//! `wdot = f(q, w)` from the Newton-Euler equations (`RigidSystem::rhs`). One step `n -> n+1`:
//! - (GA1) `q_{n+1} = q_n exp(h Dq)`, `Dq = w_n + (1/2 - beta) h a_n + beta h a_{n+1}`;
//! - (GA2) `w_{n+1} = w_n + (1 - gamma) h a_n + gamma h a_{n+1}`;
//! - (GA3) `(1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) wdot_{n+1} + alpha_f wdot_n`;
//! - (GA4) `wdot_{n+1} = f(q_{n+1}, w_{n+1})`;
//! - (GA5) `alpha_m = (2 rho - 1)/(rho + 1)`, `alpha_f = rho/(rho + 1)`,
//!   `gamma = 1/2 + alpha_f - alpha_m`, `beta = (gamma + 1/2)^2 / 4`.
//!
//! `a` is an acceleration-like variable (it approximates `wdot(t_n + (alpha_m - alpha_f) h)`);
//! `a`, `wdot` are carried between steps in the method, so the method is not one-step in the
//! strict sense: it starts from the consistent `a_0 = wdot_0 = f(q_0, w_0)` (one evaluation)
//! whenever the state handed in is not the one its last step produced (`own_state`). `gamma`
//! as in (GA5) makes it second order; `rho_inf < 1` damps the highest frequencies (no energy
//! conservation, no symplecticity; energy decays slowly at resolved frequencies).
//!
//! Newton on the increment of the unknown `wdot_{n+1}`, residual `r = wdot_{n+1} -
//! f(q_{n+1}, w_{n+1})`, with the iteration matrix `I - gamma' df/dw` (`gamma' = gamma h
//! (1 - alpha_f)/(1 - alpha_m)`; `df/dw` the analytic gyroscopic derivative
//! `J^-1 ([J Omega]x - [Omega]x J)`); the stiffness term `beta h^2 (1 - alpha_f)/(1 - alpha_m)
//! df/dq` is left out (a simplified Newton: it makes the contraction factor about
//! `beta h^2 omega_max^2`, below 1e-3 at the catalogue's steps). Predictor `wdot_{n+1} = wdot_n`.
//! Stops when the update is below `10 eps` relative to `|wdot_{n+1}| + |w_n|/h` (`newton_stop`).
//! `stats.rhs_evals` counts evaluations of `f` (one per Newton update, plus the start),
//! `stats.newton_iters` the updates. A pinned body (heavy top) keeps its translation frozen.
//! Fails (`newton_failure`) when the simplified Newton does not contract (steps far beyond
//! `1/omega_max`).
use nalgebra::{Matrix3, UnitQuaternion, Vector3, Vector6};
use std::sync::Mutex;

use crate::integrate::newton_stop::{NewtonStop, relative, update_norm};
use super::own_state::{OwnState, So3State};
use crate::integrate::{Failure, FailureKind, FixedStep, MethodInfo, MethodKind, Stats, System};
use crate::math::so3;
use crate::model::rigid_body::RigidSystem;
use crate::rotation::{Body, Pose, So3};

/// The Lie-group generalized-alpha method.
#[derive(Debug, Clone)]
pub struct LieGenAlpha {
    rho_inf: f64,
    alpha_m: f64,
    alpha_f: f64,
    gamma: f64,
    beta: f64,
    name: &'static str,
    /// `wdot_n` and `a_n` of the state last produced.
    wdot: Vector6<f64>,
    a: Vector6<f64>,
    own: OwnState,
}

/// The registry name of `rho_inf`: `lie_gen_alpha` for 0.9, else `lie_gen_alpha_r` followed by
/// the decimal digits of `rho_inf` without the point (0.5 -> `lie_gen_alpha_r05`, 0.25 ->
/// `_r025`, 0 -> `_r00`, 1 -> `_r10`).
pub fn lie_gen_alpha_name(rho_inf: f64) -> String {
    if rho_inf == 0.9 {
        return "lie_gen_alpha".to_string();
    }
    let s = format!("{rho_inf}");
    let digits = if s.contains('.') {
        s.replace('.', "")
    } else {
        format!("{s}0")
    };
    format!("lie_gen_alpha_r{digits}")
}

/// A `&'static str` for `name`, leaked once per distinct name.
fn intern(name: String) -> &'static str {
    static NAMES: Mutex<Vec<&'static str>> = Mutex::new(Vec::new());
    let mut names = NAMES.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(n) = names.iter().find(|n| **n == name) {
        return n;
    }
    let n: &'static str = Box::leak(name.into_boxed_str());
    names.push(n);
    n
}

impl Default for LieGenAlpha {
    fn default() -> Self {
        Self::new(0.9).expect("0.9 is a valid rho_inf")
    }
}

impl LieGenAlpha {
    /// The method with spectral radius at infinity `rho_inf` in `[0, 1]` (None otherwise).
    pub fn new(rho_inf: f64) -> Option<Self> {
        // The one derivation of the coefficients (Chung & Hulbert; `structural::gen_alpha`).
        let c = crate::structural::gen_alpha::Coefficients::new(rho_inf, "lie_gen_alpha").ok()?;
        Some(LieGenAlpha {
            rho_inf,
            alpha_m: c.alpha_m,
            alpha_f: c.alpha_f,
            gamma: c.gamma,
            beta: c.beta,
            name: intern(lie_gen_alpha_name(rho_inf)),
            wdot: Vector6::zeros(),
            a: Vector6::zeros(),
            own: OwnState::default(),
        })
    }

    pub fn rho_inf(&self) -> f64 {
        self.rho_inf
    }

    /// `(alpha_m, alpha_f, gamma, beta)`.
    pub fn parameters(&self) -> (f64, f64, f64, f64) {
        (self.alpha_m, self.alpha_f, self.gamma, self.beta)
    }
}

/// The state (GA1), (GA2) and `a_{n+1}` (GA3) for a trial `wdot_{n+1}`.
struct Trial {
    s: So3State,
    a: Vector6<f64>,
}

impl LieGenAlpha {
    #[inline(always)]
    fn trial(&self, s: &So3State, h: f64, translates: bool, wdot1: &Vector6<f64>) -> Trial {
        let a1 = (self.wdot * self.alpha_f - self.a * self.alpha_m + wdot1 * (1.0 - self.alpha_f))
            / (1.0 - self.alpha_m);
        let w1 = s.vel + self.a * ((1.0 - self.gamma) * h) + a1 * (self.gamma * h);
        let dq = s.vel + self.a * ((0.5 - self.beta) * h) + a1 * (self.beta * h);
        let rot = UnitQuaternion::new_unchecked(
            s.pose.rot.into_inner()
                * so3::exp_quat(&(dq.fixed_rows::<3>(3).into_owned() * h)).into_inner(),
        );
        let x = if translates {
            s.pose.x + dq.fixed_rows::<3>(0) * h
        } else {
            s.pose.x
        };
        Trial {
            s: So3State {
                pose: Pose { rot, x },
                vel: w1,
            },
            a: a1,
        }
    }
}

impl FixedStep<RigidSystem<So3, Body>> for LieGenAlpha {
    fn info(&self) -> MethodInfo {
        MethodInfo {
            name: self.name,
            order: 2,
            stages: 1,
            implicit: true,
            symplectic: false,
            lie_group: true,
            energy_conserving: false,
            adaptive: false,
            kind: MethodKind::Geometric,
            twin_of: None,
        }
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
        let translates = b.translates();
        if !self.own.matches(s) {
            // Consistent start: a_0 = wdot_0 = f(q_0, w_0).
            let (_, acc) = sys.rhs(t, s);
            stats.rhs_evals += 1;
            self.wdot = acc;
            self.a = acc;
        }
        self.own.clear();
        let gp = self.gamma * h * (1.0 - self.alpha_f) / (1.0 - self.alpha_m);
        let size_w = s.vel.amax() / h.abs();
        let mut wdot1 = self.wdot;
        let mut stop = NewtonStop::new();
        loop {
            let tr = self.trial(s, h, translates, &wdot1);
            let (_, acc) = sys.rhs(t + h, &tr.s);
            stats.rhs_evals += 1;
            let r = wdot1 - acc;
            // Iteration matrix: identity on the translation, I - gamma' J^-1 ([J W]x - [W]x J)
            // on the rotation.
            let w = tr.s.vel.fixed_rows::<3>(3).into_owned();
            let jw = b.inertia * w;
            let m = Matrix3::identity()
                - b.inertia_inv * (so3::hat(&jw) - so3::hat(&w) * b.inertia) * gp;
            let r_rot = r.fixed_rows::<3>(3).into_owned();
            let d_rot: Vector3<f64> = m.lu().solve(&(-r_rot)).ok_or_else(|| {
                Failure::new(
                    FailureKind::NewtonFailure,
                    t,
                    format!("{}: singular Newton matrix", self.name),
                )
            })?;
            let delta = Vector6::new(-r[0], -r[1], -r[2], d_rot.x, d_rot.y, d_rot.z);
            wdot1 += delta;
            stats.newton_iters += 1;
            let rel = relative(update_norm(delta.as_slice()), wdot1.amax() + size_w);
            if stop.judge(rel, t, self.name)? {
                break;
            }
        }
        let tr = self.trial(s, h, translates, &wdot1);
        let finite = tr.s.vel.iter().all(|c| c.is_finite())
            && tr.s.pose.rot.coords.iter().all(|c| c.is_finite())
            && tr.s.pose.x.iter().all(|c| c.is_finite());
        if !finite {
            return Err(Failure::new(
                FailureKind::NonFinite,
                t + h,
                format!("{}: non-finite state", self.name),
            ));
        }
        *s = tr.s;
        self.wdot = wdot1;
        self.a = tr.a;
        self.own.record(s);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::rigid_test_support as ts;

    /// Chung-Hulbert parameters and the names (0.9 -> lie_gen_alpha, 0.5 -> _r05).
    #[test]
    fn parameters_and_names() {
        let m = LieGenAlpha::new(0.9).unwrap();
        let (am, af, g, bt) = m.parameters();
        assert!((am - 0.8 / 1.9).abs() < 1e-15 && (af - 0.9 / 1.9).abs() < 1e-15);
        assert!(
            (g - (0.5 + af - am)).abs() < 1e-15 && (bt - 0.25 * (g + 0.5).powi(2)).abs() < 1e-15
        );
        assert_eq!(FixedStep::<ts::Sys>::info(&m).name, "lie_gen_alpha");
        // Its coefficients are the family's one derivation (`structural::gen_alpha`).
        let c = crate::structural::gen_alpha::Coefficients::new(0.9, "x").unwrap();
        let m9 = LieGenAlpha::new(0.9).unwrap();
        assert_eq!(m9.parameters(), (c.alpha_m, c.alpha_f, c.gamma, c.beta));
        let m = LieGenAlpha::new(0.5).unwrap();
        assert_eq!(FixedStep::<ts::Sys>::info(&m).name, "lie_gen_alpha_r05");
        assert_eq!(lie_gen_alpha_name(0.0), "lie_gen_alpha_r00");
        assert_eq!(lie_gen_alpha_name(1.0), "lie_gen_alpha_r10");
        assert!(LieGenAlpha::new(1.5).is_none() && LieGenAlpha::new(f64::NAN).is_none());
    }

    ts::order_two_tests!("lie_gen_alpha(0.9)", LieGenAlpha::default);

    /// Order 2 with rho_inf = 0.5 as well, on the torque-free body with full inertia and on the
    /// body with three springs and gravity.
    #[test]
    fn order_two_rho_inf_05() {
        for problem in [
            ts::OrderTwoProblem::FreeFull,
            ts::OrderTwoProblem::ThreeSprings,
        ] {
            ts::assert_order_two("lie_gen_alpha(0.5)", problem, || {
                LieGenAlpha::new(0.5).unwrap()
            });
        }
    }

    /// The heavy top (cases/README.md, `heavy_top`) runs 0.2 s at dt = 1e-3; its energy drift is
    /// reported and bounded by the method's second-order error.
    #[test]
    fn heavy_top_energy_drift() {
        let (sys, x0) = ts::heavy_top();
        let e0 = ts::energy(&sys, &x0);
        let mut m = LieGenAlpha::default();
        let mut worst = 0.0_f64;
        let (x, st) = ts::run(&mut m, &sys, &x0, 0.2, 200, |_, x| {
            worst = worst.max(((ts::energy(&sys, x) - e0) / e0).abs());
        })
        .unwrap();
        let end = (ts::energy(&sys, &x) - e0) / e0;
        eprintln!(
            "lie_gen_alpha heavy_top 0.2 s dt=1e-3: relative dE at end {end:.3e}, max {worst:.3e}, {st:?}"
        );
        // A second-order method's energy error at this step is of the size of its relative
        // state error, 8e-4 here (|Omega| = 150 rad/s; see the heavy-top order test).
        assert!(worst < 1e-3);
    }

    /// A state the method did not produce restarts it (one extra evaluation), and the state it
    /// produced (raw or caller-normalized) continues it.
    #[test]
    fn restarts_on_foreign_state() {
        let (sys, x0) = ts::three_springs();
        let mut m = LieGenAlpha::default();
        let mut st = Stats::default();
        // Evaluations and Newton updates of one step.
        let mut one = |m: &mut LieGenAlpha, t: f64, x: &mut ts::St| {
            let (e, n) = (st.rhs_evals, st.newton_iters);
            m.step(&sys, t, 0.01, x, &mut st).unwrap();
            (st.rhs_evals - e, st.newton_iters - n)
        };
        let mut x = x0;
        let (e, n) = one(&mut m, 0.0, &mut x);
        assert_eq!(e, 1 + n);
        sys.normalize(&mut x);
        let (e, n) = one(&mut m, 0.01, &mut x);
        assert_eq!(e, n);
        let mut y = x0;
        let (e, n) = one(&mut m, 0.0, &mut y);
        assert_eq!(e, 1 + n);
        // The restarted step reproduces the first step bit for bit.
        let mut z = x0;
        let mut fresh = LieGenAlpha::default();
        fresh
            .step(&sys, 0.0, 0.01, &mut z, &mut Stats::default())
            .unwrap();
        assert_eq!(y.vel, z.vel);
    }

    /// Bad numbers end a step with a typed failure, never a panic.
    #[test]
    fn typed_failures() {
        ts::check_typed_failures(LieGenAlpha::default);
    }
}
