//! The error norm of the adaptive pairs (`AdaptiveRk`, `mod.rs`) and the componentwise size of
//! a state it scales by (`ErrorScale`).
//!
//! Error norm (Hairer, Norsett & Wanner I, sec. II.4, "Automatic step size control"), with
//! `atol = rtol = tol`:
//! `err = sqrt(mean_i (E_i / sk_i)^2)`, `sk_i = atol + rtol max(|y_n,i|, |y_n+1,i|)`.
//! The components `y_i` come from `ErrorScale::coords`, expressed on the tangent: for an
//! additive component they are the state itself (`y_n+1 = y_n + Delta`, Hairer's scale
//! exactly); for a Lie-group component the state is measured in normal coordinates centred at
//! `y_n`, so `y_n = 0` and `y_n+1 = Delta`, and the scale is `atol + rtol |Delta_i|`, the
//! increment's own scale on the tangent. (Choice: group elements have no origin-free
//! componentwise size; this scale is invariant under a change of reference frame.) The rigid
//! body uses it for its whole pose (positions too: their origin is arbitrary) and Hairer's
//! scale for its velocities.
//! DOP853 combines its two estimators as in Hairer's code (HNW I, sec. II.10):
//! `err = err5^2 / sqrt(err5^2 + 0.01 err3^2)`, which behaves like `h^8`.
//!
//! Where it fails: an infinite estimate gives a non-finite `err` (a rejection, `controller.rs`);
//! but a NaN estimate of dop853 gives `err = 0` (its `den > 0` test is false), so such a step
//! is accepted and the system's `check` then ends the run as `non_finite` (measured with a
//! NaN vector field; dopri5 rejects it until the step underflows).
use super::AdaptiveRk;
use crate::integrate::System;
use crate::integrate::explicit_rk::combine;
use crate::math::vector::Vector;

/// The componentwise size of a state for the error norm, expressed on the tangent.
pub trait ErrorScale: System {
    /// The state's components on the tangent: the coordinates themselves for additive
    /// components, 0 for components on a Lie group (normal coordinates centred at `x`).
    /// The default treats every component as a group component.
    fn coords(&self, x: &Self::State) -> Self::Tangent {
        let _ = x;
        Self::Tangent::zero()
    }
}

impl<S: ErrorScale> AdaptiveRk<S> {
    /// `sqrt(mean (v_i / sk_i)^2)` with `sk_i = tol (1 + |y_i|)` over the buffers `y`, `v`.
    pub(super) fn rms_scaled(tol: f64, y: &[f64], v: &[f64]) -> f64 {
        let n = y.len().max(1) as f64;
        let s: f64 = y
            .iter()
            .zip(v)
            .map(|(y, v)| {
                let r = v / (tol + tol * y.abs());
                r * r
            })
            .sum();
        (s / n).sqrt()
    }

    /// The scaled error of a step from `x` with increment `delta` and signed step `dh`.
    pub(super) fn error(&mut self, sys: &S, x: &S::State, delta: &S::Tangent, dh: f64) -> f64 {
        let s = self.tab.rk.stages();
        sys.coords(x).write_to(&mut self.buf_y);
        delta.write_to(&mut self.buf_d);
        combine(dh, self.tab.e, &self.k[..s]).write_to(&mut self.buf_e);
        let tol = self.tol;
        let n = S::Tangent::DIM.max(1) as f64;
        let mut s5 = 0.0;
        let mut s3 = 0.0;
        let low = self.tab.e_low.map(|(w, _)| w);
        if let Some(w) = low {
            combine(dh, w, &self.k[..s]).write_to(&mut self.buf_e2);
        }
        for i in 0..S::Tangent::DIM {
            let y0 = self.buf_y[i];
            let y1 = y0 + self.buf_d[i];
            let sk = tol + tol * y0.abs().max(y1.abs());
            let r = self.buf_e[i] / sk;
            s5 += r * r;
            if low.is_some() {
                let r3 = self.buf_e2[i] / sk;
                s3 += r3 * r3;
            }
        }
        let e5 = s5 / n;
        if low.is_some() {
            let den = e5 + 0.01 * (s3 / n);
            if den > 0.0 { e5 / den.sqrt() } else { 0.0 }
        } else {
            e5.sqrt()
        }
    }
}
