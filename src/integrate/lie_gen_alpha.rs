//! `lie_gen_alpha`: the Lie-group generalized-alpha method of Brüls & Cardona ("On the use of
//! Lie group time integrators in multibody dynamics", J. Comput. Nonlinear Dynam. 5, 031002,
//! 2010) and Arnold & Brüls ("Convergence of the generalized-alpha scheme for
//! constrained mechanical systems", Multibody Syst. Dyn. 18, 2007), with the parameters of
//! Chung & Hulbert (J. Appl. Mech. 60, 1993) from the spectral radius at infinity `rho_inf`.
//! Equation numbers are this file's.
//!
//! Written once for every [`LieSecondOrder`] system: configuration `q` on an `N`-dimensional
//! Lie group, velocity `w` in its algebra's coordinates, acceleration `wdot = f(q, w)` (for the
//! rigid body, `q = (R, x)` on SO(3) x R^3, `w = (v, Omega)` the world velocity and the body
//! angular velocity, `f` the Newton-Euler equations). One step `n -> n+1`:
//! - (GA1) `q_{n+1} = q_n exp(h Dq)` (the system's `advance`),
//!   `Dq = w_n + (1/2 - beta) h a_n + beta h a_{n+1}`;
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
//! (1 - alpha_f)/(1 - alpha_m)`; `df/dw` the system's tangent Jacobian, solved by its
//! `solve_iteration`: for the rigid body the analytic gyroscopic derivative
//! `J^-1 ([J Omega]x - [Omega]x J)`); the stiffness term `beta h^2 (1 - alpha_f)/(1 - alpha_m)
//! df/dq` is left out (a simplified Newton: it makes the contraction factor about
//! `beta h^2 omega_max^2`, below 1e-3 at the catalogue's steps). Predictor `wdot_{n+1} = wdot_n`.
//! Stops when the update is below `10 eps` relative to `|wdot_{n+1}| + |w_n|/h` (`newton_stop`).
//! `stats.rhs_evals` counts evaluations of `f` (one per Newton update, plus the start),
//! `stats.newton_iters` the updates. On a vector space (`advance` the sum) it is Chung and
//! Hulbert's generalized-alpha method in acceleration form.
//! Fails (`newton_failure`) when the simplified Newton does not contract (steps far beyond
//! `1/omega_max`).
use nalgebra::SVector;
use std::sync::Mutex;

use super::lie_second_order::LieSecondOrder;
use super::newton_stop::{NewtonStop, relative, update_norm};
use super::own_state::OwnState;
use super::{Failure, FailureKind, FixedStep, MethodInfo, MethodKind, Stats};

/// The Lie-group generalized-alpha method on an `N`-dimensional group, for states `St`.
///
/// # Example
///
/// A harmonic oscillator on the line (the group R with addition, where the method is the
/// classical generalized-alpha method): second order, so halving the step divides the error
/// after one period by about 4.
///
/// ```
/// use mbdbench::integrate::lie_gen_alpha::LieGenAlpha;
/// use mbdbench::integrate::lie_second_order::LieSecondOrder;
/// use mbdbench::integrate::{Failure, FixedStep, Stats, System};
/// use nalgebra::{Vector1, Vector2};
///
/// struct Oscillator;
/// impl System for Oscillator {
///     type State = Vector2<f64>;
///     type Tangent = Vector2<f64>;
///     const LIE: bool = false;
///     fn rhs(&self, _t: f64, x: &Vector2<f64>) -> Vector2<f64> { Vector2::new(x[1], -x[0]) }
///     fn retract(&self, x: &Vector2<f64>, d: &Vector2<f64>) -> Vector2<f64> { x + d }
///     fn check(&self, _t: f64, _x: &Vector2<f64>) -> Result<(), Failure> { Ok(()) }
/// }
/// impl LieSecondOrder<1> for Oscillator {
///     fn velocity(&self, x: &Vector2<f64>) -> Vector1<f64> { Vector1::new(x[1]) }
///     fn acceleration(&self, _t: f64, x: &Vector2<f64>) -> Vector1<f64> { Vector1::new(-x[0]) }
///     fn advance(&self, x: &Vector2<f64>, dq: &Vector1<f64>, w: &Vector1<f64>) -> Vector2<f64> {
///         Vector2::new(x[0] + dq[0], w[0])
///     }
///     fn solve_iteration(&self, _x: &Vector2<f64>, _c: f64, r: &Vector1<f64>)
///         -> Option<Vector1<f64>> { Some(-r) }
/// }
/// let period_error = |n: usize| {
///     let h = 2.0 * std::f64::consts::PI / n as f64;
///     let (mut x, mut st) = (Vector2::new(1.0, 0.0), Stats::default());
///     let mut m = LieGenAlpha::<1, Vector2<f64>>::default();
///     for k in 0..n {
///         m.step(&Oscillator, k as f64 * h, h, &mut x, &mut st).unwrap();
///     }
///     (x - Vector2::new(1.0, 0.0)).norm()
/// };
/// let ratio = period_error(100) / period_error(200);
/// assert!((3.5..4.5).contains(&ratio), "{ratio}");
/// ```
#[derive(Debug, Clone)]
pub struct LieGenAlpha<const N: usize, St: Copy> {
    rho_inf: f64,
    alpha_m: f64,
    alpha_f: f64,
    gamma: f64,
    beta: f64,
    name: &'static str,
    /// `wdot_n` and `a_n` of the state last produced.
    wdot: SVector<f64, N>,
    a: SVector<f64, N>,
    own: OwnState<St>,
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

impl<const N: usize, St: Copy> Default for LieGenAlpha<N, St> {
    fn default() -> Self {
        Self::new(0.9).expect("0.9 is a valid rho_inf")
    }
}

impl<const N: usize, St: Copy> LieGenAlpha<N, St> {
    /// The method with spectral radius at infinity `rho_inf` in `[0, 1]` (None otherwise).
    pub fn new(rho_inf: f64) -> Option<Self> {
        // The one derivation of the coefficients (Chung & Hulbert; `structural::gen_alpha`).
        let c = super::gen_alpha_coefficients::Coefficients::new(rho_inf, "lie_gen_alpha").ok()?;
        Some(LieGenAlpha {
            rho_inf,
            alpha_m: c.alpha_m,
            alpha_f: c.alpha_f,
            gamma: c.gamma,
            beta: c.beta,
            name: intern(lie_gen_alpha_name(rho_inf)),
            wdot: SVector::zeros(),
            a: SVector::zeros(),
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

    /// The state (GA1), (GA2) and `a_{n+1}` (GA3) for a trial `wdot_{n+1}`.
    #[inline(always)]
    fn trial<S: LieSecondOrder<N, State = St>>(
        &self,
        sys: &S,
        s: &St,
        w0: &SVector<f64, N>,
        h: f64,
        wdot1: &SVector<f64, N>,
    ) -> (St, SVector<f64, N>) {
        let a1 = (self.wdot * self.alpha_f - self.a * self.alpha_m + wdot1 * (1.0 - self.alpha_f))
            / (1.0 - self.alpha_m);
        let w1 = w0 + self.a * ((1.0 - self.gamma) * h) + a1 * (self.gamma * h);
        let dq = w0 + self.a * ((0.5 - self.beta) * h) + a1 * (self.beta * h);
        (sys.advance(s, &(dq * h), &w1), a1)
    }
}

impl<const N: usize, S> FixedStep<S> for LieGenAlpha<N, S::State>
where
    S: LieSecondOrder<N>,
    S::State: Copy + PartialEq,
{
    fn info(&self) -> MethodInfo {
        MethodInfo::new(self.name, MethodKind::Geometric, 2)
            .with_implicit(true)
            .with_lie_group(true)
    }

    fn step(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        s: &mut S::State,
        stats: &mut Stats,
    ) -> Result<(), Failure> {
        if h == 0.0 {
            return Ok(());
        }
        if !self.own.matches(s) {
            // Consistent start: a_0 = wdot_0 = f(q_0, w_0).
            let acc = sys.acceleration(t, s);
            stats.rhs_evals += 1;
            self.wdot = acc;
            self.a = acc;
        }
        self.own.clear();
        let w0 = sys.velocity(s);
        let gp = self.gamma * h * (1.0 - self.alpha_f) / (1.0 - self.alpha_m);
        let size_w = w0.amax() / h.abs();
        let mut wdot1 = self.wdot;
        let mut stop = NewtonStop::new();
        loop {
            let (trial, _) = self.trial(sys, s, &w0, h, &wdot1);
            let acc = sys.acceleration(t + h, &trial);
            stats.rhs_evals += 1;
            let r = wdot1 - acc;
            let delta = sys.solve_iteration(&trial, gp, &r).ok_or_else(|| {
                Failure::new(
                    FailureKind::NewtonFailure,
                    t,
                    format!("{}: singular Newton matrix", self.name),
                )
            })?;
            wdot1 += delta;
            stats.newton_iters += 1;
            let rel = relative(update_norm(delta.as_slice()), wdot1.amax() + size_w);
            if stop.judge(rel, t, self.name)? {
                break;
            }
        }
        let (next, a1) = self.trial(sys, s, &w0, h, &wdot1);
        if let Err(e) = sys.check(t + h, &next) {
            let message = match e.kind {
                FailureKind::NonFinite => format!("{}: non-finite state", self.name),
                _ => format!("{}: {}", self.name, e.message),
            };
            return Err(Failure::new(e.kind, t + h, message));
        }
        *s = next;
        self.wdot = wdot1;
        self.a = a1;
        self.own.record(sys, s);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::System;
    use crate::integrate::rigid_test_support as ts;

    /// The method on the rigid body's states.
    type Rigid = LieGenAlpha<6, ts::St>;

    /// Chung-Hulbert parameters and the names (0.9 -> lie_gen_alpha, 0.5 -> _r05).
    #[test]
    fn parameters_and_names() {
        let m = Rigid::new(0.9).unwrap();
        let (am, af, g, bt) = m.parameters();
        assert!((am - 0.8 / 1.9).abs() < 1e-15 && (af - 0.9 / 1.9).abs() < 1e-15);
        assert!(
            (g - (0.5 + af - am)).abs() < 1e-15 && (bt - 0.25 * (g + 0.5).powi(2)).abs() < 1e-15
        );
        assert_eq!(FixedStep::<ts::Sys>::info(&m).name, "lie_gen_alpha");
        // Its coefficients are the family's one derivation (`structural::gen_alpha`).
        let c = crate::integrate::gen_alpha_coefficients::Coefficients::new(0.9, "x").unwrap();
        let m9 = Rigid::new(0.9).unwrap();
        assert_eq!(m9.parameters(), (c.alpha_m, c.alpha_f, c.gamma, c.beta));
        let m = Rigid::new(0.5).unwrap();
        assert_eq!(FixedStep::<ts::Sys>::info(&m).name, "lie_gen_alpha_r05");
        assert_eq!(lie_gen_alpha_name(0.0), "lie_gen_alpha_r00");
        assert_eq!(lie_gen_alpha_name(1.0), "lie_gen_alpha_r10");
        assert!(Rigid::new(1.5).is_none() && Rigid::new(f64::NAN).is_none());
    }

    ts::order_two_tests!("lie_gen_alpha(0.9)", Rigid::default);

    /// Order 2 with rho_inf = 0.5 as well, on the torque-free body with full inertia and on the
    /// body with three springs and gravity.
    #[test]
    fn order_two_rho_inf_05() {
        for problem in [
            ts::OrderTwoProblem::FreeFull,
            ts::OrderTwoProblem::ThreeSprings,
        ] {
            ts::assert_order_two("lie_gen_alpha(0.5)", problem, || Rigid::new(0.5).unwrap());
        }
    }

    /// A state the method did not produce restarts it (one extra evaluation), and the state it
    /// produced (raw or caller-normalized) continues it.
    #[test]
    fn restarts_on_foreign_state() {
        let (sys, x0) = ts::three_springs();
        let mut m = Rigid::default();
        let mut st = Stats::default();
        // Evaluations and Newton updates of one step.
        let mut one = |m: &mut Rigid, t: f64, x: &mut ts::St| {
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
        let mut fresh = Rigid::default();
        fresh
            .step(&sys, 0.0, 0.01, &mut z, &mut Stats::default())
            .unwrap();
        assert_eq!(y.vel, z.vel);
    }

    /// The pendulum `theta'' = -sin theta` on the circle group (a state that is not a rigid
    /// body: a unit complex number and one velocity coordinate).
    struct CirclePendulum;
    type Circle = nalgebra::Vector3<f64>;
    impl System for CirclePendulum {
        type State = Circle;
        type Tangent = nalgebra::Vector2<f64>;
        const LIE: bool = true;
        fn rhs(&self, t: f64, x: &Circle) -> nalgebra::Vector2<f64> {
            nalgebra::Vector2::new(x[2], self.acceleration(t, x)[0])
        }
        fn retract(&self, x: &Circle, d: &nalgebra::Vector2<f64>) -> Circle {
            self.advance(x, &SVector::from([d[0]]), &SVector::from([x[2] + d[1]]))
        }
        fn check(&self, t: f64, x: &Circle) -> Result<(), Failure> {
            if x.iter().all(|v| v.is_finite()) {
                Ok(())
            } else {
                Err(Failure::new(FailureKind::NonFinite, t, "non-finite"))
            }
        }
    }
    impl LieSecondOrder<1> for CirclePendulum {
        fn velocity(&self, x: &Circle) -> SVector<f64, 1> {
            SVector::from([x[2]])
        }
        fn acceleration(&self, _t: f64, x: &Circle) -> SVector<f64, 1> {
            SVector::from([-x[1]])
        }
        fn advance(&self, x: &Circle, dq: &SVector<f64, 1>, w: &SVector<f64, 1>) -> Circle {
            let (s, c) = dq[0].sin_cos();
            Circle::new(x[0] * c - x[1] * s, x[0] * s + x[1] * c, w[0])
        }
        fn solve_iteration(
            &self,
            _x: &Circle,
            _c: f64,
            r: &SVector<f64, 1>,
        ) -> Option<SVector<f64, 1>> {
            Some(-r)
        }
    }

    /// On a group that is not the rigid body's (the circle), the same code is second order
    /// (error ratio 4 per halving of the step against a fine RK4 solution of the angle ODE) and
    /// keeps the configuration on the group to round-off.
    #[test]
    fn second_order_on_the_circle() {
        let (theta0, t_end) = (1.0_f64, 2.0);
        // Reference: classical RK4 on (theta, w), 20000 steps.
        let f = |y: [f64; 2]| [y[1], -y[0].sin()];
        let (mut y, n, h) = ([theta0, 0.0], 20000, t_end / 20000.0);
        for _ in 0..n {
            let k1 = f(y);
            let k2 = f([y[0] + h / 2.0 * k1[0], y[1] + h / 2.0 * k1[1]]);
            let k3 = f([y[0] + h / 2.0 * k2[0], y[1] + h / 2.0 * k2[1]]);
            let k4 = f([y[0] + h * k3[0], y[1] + h * k3[1]]);
            for i in 0..2 {
                y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        let error = |n: usize| {
            let h = t_end / n as f64;
            let mut x = Circle::new(theta0.cos(), theta0.sin(), 0.0);
            let mut m = LieGenAlpha::<1, Circle>::default();
            let mut st = Stats::default();
            let mut off_group = 0.0_f64;
            for k in 0..n {
                m.step(&CirclePendulum, k as f64 * h, h, &mut x, &mut st)
                    .unwrap();
                off_group = off_group.max((x[0].hypot(x[1]) - 1.0).abs());
            }
            assert!(off_group < 1e-14, "left the circle by {off_group:e}");
            (x[1].atan2(x[0]) - y[0]).abs().max((x[2] - y[1]).abs())
        };
        let (e1, e2, e3) = (error(50), error(100), error(200));
        eprintln!("lie_gen_alpha on the circle: errors {e1:.3e} {e2:.3e} {e3:.3e}");
        for r in [e1 / e2, e2 / e3] {
            assert!((3.5..4.6).contains(&r), "ratio {r}");
        }
    }
}
