//! Adaptive embedded Runge-Kutta(-Munthe-Kaas) pairs: Dormand-Prince 5(4) (`dopri5`) and
//! 8(5,3) (`dop853`), with Hairer's error norm, PI step-size controller and initial step,
//! and their continuous extensions (dense output).
//!
//! Stages are those of `explicit_rk.rs` (RK on vector spaces, RKMK on Lie groups): with
//! `K_i = dexp_inv(Theta_i, f(t + c_i h, x (+) Theta_i))` the step increment is
//! `Delta = h sum b_i K_i` and the error estimate is the tangent vector `E = h sum e_i K_i`,
//! `e = b - b_hat` (`tableau.rs`). Both are taken in the tangent at `x` (normal coordinates
//! centred at `x` on a Lie group), where the local error of the propagated solution and its
//! estimate differ only at higher order (Munthe-Kaas 1998, sec. 5).
//!
//! Spans may run backwards (`t1 < t0`). State across `advance` calls: a call starting where
//! the previous one ended (`t0` equal to its `t1`) continues with the stored step size and
//! the stored first stage `f(t0, x)` (so the caller must pass back the state it received);
//! any other `t0` starts afresh (new `f(t0, x)`, new initial step). Work counted: every RHS
//! evaluation (the first-same-as-last stage of dopri5 once), accepted steps in `steps`,
//! rejected ones in `rejected`, normalizations; `Limits::check` after every attempt, and
//! `Limits::room` before it, so a run never passes its RHS budget. Per
//! attempt dopri5 costs 6 evaluations and dop853 11, plus 1 per accepted dop853 step (its
//! next first stage, taken after normalization); a fresh start costs 2 (`f(t0, x)` and the
//! heuristic's Euler probe). With dopri5 the reused stage was evaluated before `normalize`,
//! which moves the state by round-off only.
//!
//! Failures: `step_size_underflow` when the step falls to `1e-14 |t|` or below (a
//! finite-time blow-up, or a tolerance below round-off); `work_limit` (an attempt that could
//! pass `max_rhs_evals` is not started; a diverging solution at a loose tolerance, whose step
//! is limited by the blown-up velocities rather than by the floor, ends here); the system's own
//! `check` after every accepted step (`non_finite`, `singular_chart`); `non_finite` for a
//! non-finite time span or a non-finite dense-output increment (dop853's extra stages can
//! overflow where the step's own stages did not); an error from the output callback.
//!
//! Files: this one holds the stepper proper (`AdaptiveRk`: construction, the start of a span
//! and its continuation rule, taking an accepted step, `advance` and `integrate_dense`);
//! `error_scale.rs` the error norm and the componentwise scale it uses (`ErrorScale`);
//! `controller.rs` one attempt, the PI step-size controller and the starting step;
//! `dense.rs` the continuous extension; `tests.rs` the tests.
mod controller;
mod dense;
mod error_scale;
#[cfg(test)]
mod tests;

use super::tableau::{DOP853, DOPRI5, EmbeddedTableau, MAX_DENSE_STAGES};
use super::{Adaptive, Failure, FailureKind, Limits, MethodInfo, MethodKind, Stats, System};
use crate::math::vector::Vector;
use controller::{BETA, Controller};
pub use error_scale::ErrorScale;

/// An adaptive embedded RK(MK) pair.
#[derive(Debug, Clone)]
pub struct AdaptiveRk<S: System> {
    tab: &'static EmbeddedTableau,
    tol: f64,
    ctl: Controller,
    /// Stages of the last attempt, then (lazily, after an accepted step with an output
    /// inside it) the dense output's appended stages.
    k: [S::Tangent; MAX_DENSE_STAGES],
    /// Dense-output weights `b_i(s)`.
    w: [f64; MAX_DENSE_STAGES],
    /// `f(t_last, x)`, valid when `t_last` is not NaN.
    f0: S::Tangent,
    /// Magnitude of the next step.
    h: f64,
    /// End of the previous successful call (NaN: none).
    t_last: f64,
    errold: f64,
    rejected_last: bool,
    buf_y: Vec<f64>,
    buf_d: Vec<f64>,
    buf_e: Vec<f64>,
    buf_e2: Vec<f64>,
}

/// The smallest tolerance an adaptive run accepts (10 unit roundoffs, Hairer's floor).
pub const MIN_TOL: f64 = 10.0 * f64::EPSILON;

impl<S: ErrorScale> AdaptiveRk<S> {
    /// The pair `tab` with `atol = rtol = tol`.
    pub fn new(tab: &'static EmbeddedTableau, tol: f64) -> Self {
        assert!(
            tab.dense_stages() <= MAX_DENSE_STAGES,
            "tableau {} too large",
            tab.rk.name
        );
        let q = tab.rk.order as f64;
        let (k, facmin, facmax) = if tab.rk.order >= 8 {
            (0.2, 1.0 / 3.0, 6.0)
        } else {
            (0.75, 0.2, 10.0)
        };
        let n = S::Tangent::DIM;
        AdaptiveRk {
            tab,
            tol,
            ctl: Controller {
                alpha: 1.0 / q - k * BETA,
                beta: BETA,
                facmin,
                facmax,
            },
            k: [S::Tangent::zero(); MAX_DENSE_STAGES],
            w: [0.0; MAX_DENSE_STAGES],
            f0: S::Tangent::zero(),
            h: 0.0,
            t_last: f64::NAN,
            errold: 1e-4,
            rejected_last: false,
            buf_y: vec![0.0; n],
            buf_d: vec![0.0; n],
            buf_e: vec![0.0; n],
            buf_e2: vec![0.0; n],
        }
    }

    /// Dormand-Prince 5(4).
    pub fn dopri5(tol: f64) -> Self {
        Self::new(&DOPRI5, tol)
    }

    /// Dormand-Prince 8(5,3).
    pub fn dop853(tol: f64) -> Self {
        Self::new(&DOP853, tol)
    }

    /// The tolerance.
    pub fn tol(&self) -> f64 {
        self.tol
    }

    /// The step size the next attempt will use (0 before the first call).
    pub fn step_size(&self) -> f64 {
        self.h
    }

    /// End time of the last successful `advance` (None before it or after a failure).
    pub fn time(&self) -> Option<f64> {
        (!self.t_last.is_nan()).then_some(self.t_last)
    }

    /// The most RHS evaluations one attempt can take: its stages, the dense output's appended
    /// stages and the next first stage (an upper bound: dopri5 takes 6, dop853 12 to 16).
    fn attempt_cost(&self) -> u64 {
        self.tab.dense_stages() as u64 + 1
    }

    /// Forgets the step size and the stored first stage: the next call starts afresh.
    pub fn reset(&mut self) {
        self.h = 0.0;
        self.t_last = f64::NAN;
        self.errold = 1e-4;
        self.rejected_last = false;
    }

    /// Validates the span and prepares the first attempt: a call starting where the previous
    /// one ended keeps the step size and first stage, any other starts afresh (`f(t0, x)` and
    /// the initial step for a span of length `span`). Returns the direction of time.
    fn start(
        &mut self,
        sys: &S,
        t0: f64,
        t1: f64,
        x: &S::State,
        stats: &mut Stats,
    ) -> Result<f64, Failure> {
        if !(t0.is_finite() && t1.is_finite()) {
            return Err(Failure::new(
                FailureKind::NonFinite,
                t0,
                format!("{}: non-finite time span [{t0}, {t1}]", self.tab.rk.name),
            ));
        }
        // A tolerance below round-off cannot be met: the error estimate is noise, the step
        // shrinks until the stages coincide and the run crawls on steps of ~1e-20 s to its
        // work limit (minutes; found by tests/fuzz.rs). Refused at once, as Hairer's codes do.
        if self.tol.is_nan() || self.tol < MIN_TOL {
            return Err(Failure::new(
                FailureKind::StepSizeUnderflow,
                t0,
                format!(
                    "{}: tolerance {:e} is below round-off; expected >= {MIN_TOL:e}",
                    self.tab.rk.name, self.tol
                ),
            ));
        }
        let dir = if t1 > t0 { 1.0 } else { -1.0 };
        let fresh = t0 != self.t_last;
        self.t_last = f64::NAN;
        if fresh {
            self.f0 = sys.rhs(t0, x);
            stats.rhs_evals += 1;
            self.errold = 1e-4;
            self.rejected_last = false;
            self.h = self.initial_step(sys, t0, dir, x, (t1 - t0).abs(), stats);
        }
        Ok(dir)
    }

    /// Takes an accepted step: `x` becomes `y` at time `t`, normalized and checked, and the
    /// next first stage is stored (`f_last` when first same as last, else a new evaluation).
    fn accept(
        &mut self,
        sys: &S,
        t: f64,
        x: &mut S::State,
        y: S::State,
        f_last: S::Tangent,
        stats: &mut Stats,
    ) -> Result<(), Failure> {
        *x = y;
        stats.steps += 1;
        if sys.normalize(x) {
            stats.normalizations += 1;
        }
        sys.check(t, x)?;
        if self.tab.fsal {
            self.f0 = f_last;
        } else {
            self.f0 = sys.rhs(t, x);
            stats.rhs_evals += 1;
        }
        Ok(())
    }
}

impl<S: ErrorScale> Adaptive<S> for AdaptiveRk<S> {
    fn info(&self) -> MethodInfo {
        MethodInfo::new(self.tab.rk.name, MethodKind::Explicit, self.tab.rk.order)
            .with_stages(self.tab.rk.stages() as u32)
            .with_lie_group(S::LIE)
            .with_adaptive(true)
    }

    fn advance(
        &mut self,
        sys: &S,
        t0: f64,
        t1: f64,
        x: &mut S::State,
        stats: &mut Stats,
        limits: &Limits,
    ) -> Result<(), Failure> {
        if t1 == t0 && t0.is_finite() {
            return Ok(());
        }
        let dir = self.start(sys, t0, t1, x, stats)?;
        let mut t = t0;
        loop {
            self.check_step(t)?;
            limits.room(t, stats, self.attempt_cost())?;
            let last = (t + 1.01 * dir * self.h - t1) * dir >= 0.0;
            let dh = dir * if last { (t1 - t).abs() } else { self.h };
            match self.attempt(sys, t, dh, x, stats) {
                Some(acc) => {
                    t = if last { t1 } else { t + dh };
                    self.accept(sys, t, x, acc.y, acc.f_last, stats)?;
                    self.h = if last { acc.hnew.max(self.h) } else { acc.hnew };
                    limits.check(t, stats)?;
                    if last {
                        self.t_last = t1;
                        return Ok(());
                    }
                }
                None => limits.check(t, stats)?,
            }
        }
    }

    fn integrate_dense(
        &mut self,
        sys: &S,
        t0: f64,
        x: &mut S::State,
        dt_out: f64,
        n_out: u64,
        on_output: &mut dyn FnMut(u64, &S::State) -> Result<(), Failure>,
        stats: &mut Stats,
        limits: &Limits,
    ) -> Result<(), Failure> {
        let t_out = |k: u64| t0 + k as f64 * dt_out;
        let t_end = t_out(n_out);
        if n_out == 0 {
            return Ok(());
        }
        if t_end == t0 && t0.is_finite() {
            // A zero span (dt_out = 0): every output is the (normalized) initial state.
            let mut y = *x;
            sys.normalize(&mut y);
            for k in 1..=n_out {
                on_output(k, &y)?;
            }
            return Ok(());
        }
        let dir = self.start(sys, t0, t_end, x, stats)?;
        let mut t = t0;
        let mut next = 1;
        loop {
            self.check_step(t)?;
            limits.room(t, stats, self.attempt_cost())?;
            let last = (t + 1.01 * dir * self.h - t_end) * dir >= 0.0;
            let dh = dir * if last { (t_end - t).abs() } else { self.h };
            let x_prev = *x;
            match self.attempt(sys, t, dh, x, stats) {
                Some(acc) => {
                    let t_new = if last { t_end } else { t + dh };
                    self.accept(sys, t_new, x, acc.y, acc.f_last, stats)?;
                    self.h = if last { acc.hnew.max(self.h) } else { acc.hnew };
                    let mut stages_ready = false;
                    while next <= n_out {
                        let tk = t_out(next);
                        if (tk - t_new) * dir > 0.0 {
                            break;
                        }
                        if tk == t_new {
                            on_output(next, x)?;
                        } else {
                            if !stages_ready {
                                self.dense_stages(sys, t, dh, &x_prev, &acc.delta, stats);
                                stages_ready = true;
                            }
                            let Some(mut y) = self.interpolate(sys, &x_prev, dh, (tk - t) / dh)
                            else {
                                return Err(Failure::new(
                                    FailureKind::NonFinite,
                                    tk,
                                    format!("{}: non-finite dense output", self.tab.rk.name),
                                ));
                            };
                            sys.normalize(&mut y);
                            on_output(next, &y)?;
                        }
                        next += 1;
                    }
                    limits.check(t_new, stats)?;
                    if last {
                        self.t_last = t_end;
                        return Ok(());
                    }
                    t = t_new;
                }
                None => limits.check(t, stats)?,
            }
        }
    }
}
