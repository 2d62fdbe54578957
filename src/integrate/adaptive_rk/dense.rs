//! The continuous extension (dense output) of the adaptive pairs (`AdaptiveRk`, `mod.rs`): the
//! appended stages and the interpolant of an accepted step.
//!
//! Dense output (`integrate_dense`; HNW I, sec. II.6): the run steps freely over the whole
//! span (only the last step is clipped, to land exactly on `t0 + n dt_out`) and each output
//! time `t_k = t0 + k dt_out` inside an accepted step `[t, t + h]` is interpolated in the Lie
//! algebra of that step: `x(t + s h) = x_n (+) theta(s)`, `theta(s) = h sum_i b_i(s) K_i`
//! with the step's `dexp_inv`-corrected stages and the continuous weights of `tableau.rs`
//! (dopri5: order 4, from its 7 stages, `K_7` the FSAL stage at the new point; dop853:
//! order 7, from stage 13 = `dexp_inv(Delta, f(t + h, x_n+1))`, the next step's first stage,
//! and three more stages 14..16 evaluated from `x_n`). On additive systems this is the
//! classical dense output; on a Lie group `theta` is exactly the increment curve whose
//! derivative the RKMK stages approximate, so the order carries over (measured in the tests).
//! `theta(0) = 0` and `theta(1) = Delta` exactly, with derivatives `h K_1`, `h K_end` there.
//! An output on a step's end is that step's state; others get a normalized copy of the
//! interpolant (the integration state is untouched). Work: dop853's three extra stages are
//! evaluated lazily, only for accepted steps with an output strictly inside them, and are
//! counted in `rhs_evals` (3 per such step); dopri5's dense output costs nothing. Output
//! normalizations are not counted in `normalizations`. Steps, rejections, `check`,
//! normalization and `Limits::check` are as in `advance` (the latter after the step's
//! outputs), and so is the continuation rule (`t0` equal to the previous end continues).
//!
//! Where it fails: `interpolate` returns None when the increment is not finite (dop853's
//! extra stages can overflow where the step's own stages did not); `integrate_dense` reports
//! it as `non_finite`.
use super::{AdaptiveRk, ErrorScale};
use crate::integrate::Stats;
use crate::integrate::explicit_rk::combine;
use crate::math::vector::Vector;

impl<S: ErrorScale> AdaptiveRk<S> {
    /// The dense output's appended stages of the accepted step from `(t, x_prev)` with signed
    /// step `dh` and increment `delta`, into `self.k[s..]` (`self.k[..s]` hold the step's
    /// stages and `self.f0` the field at the new point). The stage at the new point is
    /// `dexp_inv(delta, self.f0)`, no new evaluation (its row of `A` is `b`, so its increment is
    /// `delta`; `self.f0` was evaluated at the normalized new state, which differs by round-off);
    /// the others are RK(MK) stages from `x_prev`, one counted evaluation each.
    pub(super) fn dense_stages(
        &mut self,
        sys: &S,
        t: f64,
        dh: f64,
        x_prev: &S::State,
        delta: &S::Tangent,
        stats: &mut Stats,
    ) {
        let ns = self.tab.rk.stages();
        let dense = &self.tab.dense;
        for (j, (row, c)) in dense.a.iter().zip(dense.c).enumerate() {
            let i = ns + j;
            if i == dense.end {
                self.k[i] = if S::LIE {
                    sys.dexp_inv(delta, &self.f0)
                } else {
                    self.f0
                };
                continue;
            }
            let theta = combine(dh, row, &self.k[..i]);
            let (_, _, ki) = sys.rkmk_stage(t + c * dh, x_prev, &theta);
            stats.rhs_evals += 1;
            self.k[i] = ki;
        }
    }

    /// The dense output `x_prev (+) theta(s)`, `theta(s) = dh sum_i b_i(s) K_i`, of the step
    /// from `x_prev` with signed step `dh` (all its dense stages in `self.k`), before
    /// normalization; None when the increment is not finite.
    pub(super) fn interpolate(
        &mut self,
        sys: &S,
        x_prev: &S::State,
        dh: f64,
        s: f64,
    ) -> Option<S::State> {
        let n = self.tab.dense_stages();
        self.tab.dense_weights(s, &mut self.w[..n]);
        let theta = combine(dh, &self.w[..n], &self.k[..n]);
        theta.is_finite().then(|| sys.retract(x_prev, &theta))
    }
}
