//! The stopping rule shared by the Newton iterations of the geometric implicit methods
//! (`lie_gen_alpha` here; `lgvi`, `simo_wong` of `model/rigid_body/methods/`).
//!
//! An iteration is judged on the relative size of its last update, `rel = |delta| / |z|`
//! (each method says which unknown `z` and which norm). It has converged when
//! `rel <= 10 eps` (the update no longer changes the unknown beyond round-off), or when it has
//! reached its round-off floor: `rel <= 1e3 eps` and the last update did not shrink by half
//! (the noise of the residual's evaluation, not a convergence failure). It has failed
//! (`newton_failure`) after `MAX_ITERS` updates, or when, after three updates, the updates
//! grow while larger than `1e-6` (divergence); a non-finite update is `non_finite`.
//! Quadratic (or fast linear) convergence reaches `10 eps` from a second-order predictor in 2
//! to 5 updates; `MAX_ITERS` is far above that and only stops hopeless iterations.
use super::{Failure, FailureKind};

/// Largest number of Newton updates in one step.
pub(crate) const MAX_ITERS: u32 = 50;

/// The state of one Newton iteration's stopping test.
#[derive(Debug, Clone, Copy)]
pub(crate) struct NewtonStop {
    prev: f64,
    iters: u32,
}

/// The largest absolute component of an update, NaN if any component is not finite (so that
/// `judge` reports `non_finite`; `amax` would skip a NaN).
#[inline(always)]
pub(crate) fn update_norm(v: &[f64]) -> f64 {
    let mut m = 0.0_f64;
    for c in v {
        if !c.is_finite() {
            return f64::NAN;
        }
        m = m.max(c.abs());
    }
    m
}

/// `upd / size`, with `0 / 0 = 0` (an exact zero solution reached exactly).
#[inline(always)]
pub(crate) fn relative(upd: f64, size: f64) -> f64 {
    if upd == 0.0 { 0.0 } else { upd / size }
}

impl NewtonStop {
    #[inline(always)]
    pub(crate) fn new() -> Self {
        NewtonStop {
            prev: f64::INFINITY,
            iters: 0,
        }
    }

    /// Judges an update of relative size `rel`: `Ok(true)` converged, `Ok(false)` go on.
    #[inline]
    pub(crate) fn judge(&mut self, rel: f64, t: f64, method: &str) -> Result<bool, Failure> {
        self.iters += 1;
        if rel.is_nan() {
            return Err(Failure::new(
                FailureKind::NonFinite,
                t,
                format!("{method}: non-finite Newton update"),
            ));
        }
        let eps = f64::EPSILON;
        if rel <= 10.0 * eps || (rel <= 1e3 * eps && rel >= 0.5 * self.prev) {
            return Ok(true);
        }
        if self.iters >= MAX_ITERS {
            return Err(Failure::new(
                FailureKind::NewtonFailure,
                t,
                format!(
                    "{method}: Newton did not converge in {MAX_ITERS} iterations (last relative update {rel:.3e})"
                ),
            ));
        }
        if self.iters > 3 && rel > self.prev && rel > 1e-6 {
            return Err(Failure::new(
                FailureKind::NewtonFailure,
                t,
                format!("{method}: Newton diverges (relative update {rel:.3e})"),
            ));
        }
        self.prev = rel;
        Ok(false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Converges at 10 eps, accepts a stalled round-off floor, fails on divergence and NaN.
    #[test]
    fn verdicts() {
        let mut s = NewtonStop::new();
        assert!(!s.judge(1e-3, 0.0, "t").unwrap());
        assert!(s.judge(1e-15, 0.0, "t").unwrap());
        let mut s = NewtonStop::new();
        assert!(!s.judge(1e-13, 0.0, "t").unwrap());
        assert!(s.judge(9e-14, 0.0, "t").unwrap());
        let mut s = NewtonStop::new();
        for r in [1e-1, 1.0, 10.0] {
            assert!(!s.judge(r, 0.0, "t").unwrap());
        }
        assert_eq!(
            s.judge(100.0, 0.0, "t").unwrap_err().kind,
            FailureKind::NewtonFailure
        );
        let mut s = NewtonStop::new();
        assert_eq!(
            s.judge(f64::NAN, 0.0, "t").unwrap_err().kind,
            FailureKind::NonFinite
        );
        assert_eq!(relative(0.0, 0.0), 0.0);
        assert!(update_norm(&[1.0, f64::NAN, 3.0]).is_nan());
        assert!(update_norm(&[1.0, f64::INFINITY]).is_nan());
        assert_eq!(update_norm(&[1.0, -3.0]), 3.0);
    }
}
