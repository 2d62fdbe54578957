//! The step-size control of the adaptive pairs (`AdaptiveRk`, `mod.rs`): one attempt (the
//! stages, the error estimate, accept or reject), the PI controller proposing the next step,
//! the starting step and the step-size floor.
//!
//! Step control: PI control (Gustafsson, Lundh & Soderlind, BIT 28, 1988) in the form of the
//! `BETA` option of Hairer's DOPRI5/DOP853 codes, safety factor 0.9. A step is accepted when
//! `err <= 1`; then `h_new = h / clamp(err^alpha / errold^beta / 0.9, 1/facmax, 1/facmin)`,
//! `beta = 0.04`, `alpha = 1/q - k beta`, `errold = max(previous accepted err, 1e-4)`, with
//! `q` the power of `h` in the estimate: dopri5 `q = 5, k = 0.75, facmin = 0.2,
//! facmax = 10`; dop853 `q = 8, k = 0.2, facmin = 1/3, facmax = 6`. After a rejection
//! `h_new = h / min(1/facmin, err^alpha / 0.9)`, and the next accepted step may not grow. A
//! non-finite error estimate counts as a rejection with the largest decrease. The first
//! step comes from Hairer's heuristic (HNW I, sec. II.4, "Starting step size", (a)-(f)). The
//! last step of a span is clipped to land exactly on `t1` (`t + 1.01 h >= t1` ->
//! `h = t1 - t`; the time is then set to `t1`, not `t + h`); the controller's unclipped
//! proposal is kept for the next call, so sampling does not shrink the steps.
//!
//! Where it fails: `check_step` gives `step_size_underflow` when the step falls to `1e-14 |t|`
//! or below (a finite-time blow-up, or a tolerance below round-off).
use super::{AdaptiveRk, ErrorScale};
use crate::integrate::explicit_rk::{combine, rkmk_stages};
use crate::integrate::{Failure, FailureKind, Stats, System};
use crate::math::vector::Vector;

/// Step-size controller constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Controller {
    /// Exponent `alpha` of the current error.
    pub(super) alpha: f64,
    /// Exponent `beta` of the previous accepted error.
    pub(super) beta: f64,
    pub(super) facmin: f64,
    pub(super) facmax: f64,
}

const SAFETY: f64 = 0.9;
pub(super) const BETA: f64 = 0.04;

/// An accepted attempt: the new point (before normalization), the raw vector field at the
/// last stage, the step's increment, and the controller's next step size.
pub(super) struct Accepted<S: System> {
    pub(super) y: S::State,
    pub(super) f_last: S::Tangent,
    pub(super) delta: S::Tangent,
    pub(super) hnew: f64,
}

impl<S: ErrorScale> AdaptiveRk<S> {
    /// Hairer's starting step (magnitude) from `(t0, x)` with `f0 = f(t0, x)`.
    pub(super) fn initial_step(
        &mut self,
        sys: &S,
        t0: f64,
        dir: f64,
        x: &S::State,
        hmax: f64,
        stats: &mut Stats,
    ) -> f64 {
        sys.coords(x).write_to(&mut self.buf_y);
        self.f0.write_to(&mut self.buf_d);
        let d0 = Self::rms_scaled(self.tol, &self.buf_y, &self.buf_y);
        let d1 = Self::rms_scaled(self.tol, &self.buf_y, &self.buf_d);
        let mut h0 = if d0 < 1e-10 || d1 < 1e-10 {
            1e-6
        } else {
            0.01 * d0 / d1
        };
        h0 = h0.min(hmax);
        let y1 = sys.retract(x, &self.f0.scaled(dir * h0));
        let f1 = sys.rhs(t0 + dir * h0, &y1);
        stats.rhs_evals += 1;
        f1.minus(&self.f0).write_to(&mut self.buf_e);
        let d2 = Self::rms_scaled(self.tol, &self.buf_y, &self.buf_e) / h0;
        let dm = d1.max(d2);
        let h1 = if dm.is_nan() {
            h0
        } else if dm <= 1e-15 {
            (h0 * 1e-3).max(1e-6)
        } else {
            (0.01 / dm).powf(1.0 / self.tab.rk.order as f64)
        };
        (100.0 * h0).min(h1).min(hmax)
    }

    /// `step_size_underflow` when the stored step is too small at `t`.
    pub(super) fn check_step(&self, t: f64) -> Result<(), Failure> {
        if self.h.is_nan() || self.h <= 1e-14 * t.abs() || self.h < 1e-300 {
            return Err(Failure::new(
                FailureKind::StepSizeUnderflow,
                t,
                format!(
                    "{}: step size {:.3e} too small at t = {t}",
                    self.tab.rk.name, self.h
                ),
            ));
        }
        Ok(())
    }

    /// One attempt with signed step `dh` from `(t, x)` (first stage `self.f0`). Accepted:
    /// returns the new point (before normalization), the raw field there (the next first
    /// stage when first same as last), the increment, and the controller's next step size;
    /// the stages stay in `self.k`. Rejected: counts it, shrinks `self.h`, returns None.
    pub(super) fn attempt(
        &mut self,
        sys: &S,
        t: f64,
        dh: f64,
        x: &S::State,
        stats: &mut Stats,
    ) -> Option<Accepted<S>> {
        let s = self.tab.rk.stages();
        let c = self.ctl;
        let hs = dh.abs();
        self.k[0] = self.f0;
        let (y_last, f_last) = rkmk_stages(sys, &self.tab.rk, t, dh, x, &mut self.k[..s], stats);
        let delta = combine(dh, self.tab.rk.b, &self.k[..s]);
        let err = self.error(sys, x, &delta, dh);
        let fac11 = if err.is_finite() {
            err.powf(c.alpha)
        } else {
            f64::INFINITY
        };
        if err <= 1.0 {
            let fac =
                (fac11 / self.errold.powf(c.beta) / SAFETY).clamp(1.0 / c.facmax, 1.0 / c.facmin);
            let mut hnew = hs / fac;
            if self.rejected_last {
                hnew = hnew.min(hs);
            }
            self.errold = err.max(1e-4);
            self.rejected_last = false;
            let y = if self.tab.fsal {
                y_last
            } else {
                sys.retract(x, &delta)
            };
            Some(Accepted {
                y,
                f_last,
                delta,
                hnew,
            })
        } else {
            stats.rejected += 1;
            self.rejected_last = true;
            self.h = hs / (1.0 / c.facmin).min(fac11 / SAFETY);
            None
        }
    }
}
