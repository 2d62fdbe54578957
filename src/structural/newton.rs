//! `newton`: the Newton iteration the unconstrained Newmark-family integrators share, its
//! stopping rule and options, and what opens and closes every structural step (a valid step
//! size; a finite result, which then becomes the state: `accept`).
//!
//! Newmark (Newmark 1959), HHT (Hilber, Hughes & Taylor 1977) and the generalized-alpha
//! method in Arnold & Brüls' form (2007) all reduce one step to one nonlinear equation in an
//! acceleration-like unknown `x`, with the coordinates and velocities of the point where the
//! equations of motion are evaluated affine in `x`:
//!
//! ```text
//! (N1)  R(x) = r(t_e, q_e + c_k x, v_e + c_c x, x) = 0,
//! (N2)  S = dR/dx = dr/da + c_c dr/dv + c_k dr/dq        (the system's tangent, c_m = 1),
//! (N3)  S dx = -R(x),   x <- x + dx,
//! (N4)  converged when  c_k |dx|_inf <= tol (|q_n|_inf + h |v_n|_inf + c_k |x|_inf + L),
//! ```
//!
//! (Newmark: `x = a_{n+1}`, `c_k = beta h^2`, `c_c = gamma h`; the method files give their
//! own `t_e, q_e, v_e`). (N4) measures the update as the displacement it causes, relative to
//! the size of the step's coordinates, so one tolerance serves every time step and unit
//! system; `L` is the system's `SecondOrder::length_scale` (0 by default), the size of the
//! coordinates' round-off: a beam that starts at rest has displacements far below the
//! round-off of its element lengths, where a purely relative test could never pass. Full Newton: the tangent is re-evaluated and re-factored every iteration; its
//! convergence is quadratic when the system's tangent is exact. One residual evaluation per
//! iteration (`stats.rhs_evals`), one update per iteration (`stats.newton_iters`).
//!
//! Where it fails: no convergence within `max_iters` updates is a `newton_failure` (so is a
//! singular iteration matrix); a non-finite residual, tangent or update is `non_finite`. A
//! linear system needs two updates (the first solves it, the second shows that it did).
//! A tolerance below about `1e-14` can stall on round-off and fail.
use nalgebra::DVector;

use super::SecondOrder;
use super::state::{State, Work};
use crate::integrate::{Failure, FailureKind, Stats};
use crate::math::lu::{LinearSolve, LuError};

/// The Newton options of a structural integrator.
///
/// # Example
///
/// The defaults, and the validation every constructor runs:
///
/// ```
/// use mbdbench::structural::newton::NewtonOptions;
///
/// let o = NewtonOptions::default();
/// assert_eq!((o.tol, o.max_iters), (1e-10, 25));
/// assert!(o.validate().is_ok());
/// let bad = NewtonOptions { tol: -1.0, ..o };
/// assert!(bad.validate().unwrap_err().contains("tol"));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonOptions {
    /// Tolerance on the scaled update (N4).
    pub tol: f64,
    /// The most updates in one step.
    pub max_iters: u32,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        NewtonOptions {
            tol: 1e-10,
            max_iters: 25,
        }
    }
}

impl NewtonOptions {
    /// An error naming the bad option: `tol` must be finite and in `(0, 1)`, `max_iters`
    /// at least 1.
    pub fn validate(&self) -> Result<(), String> {
        if !(self.tol.is_finite() && self.tol > 0.0 && self.tol < 1.0) {
            return Err(format!(
                "newton tol = {} must be finite and in (0, 1)",
                self.tol
            ));
        }
        if self.max_iters == 0 {
            return Err("newton max_iters = 0 must be at least 1".into());
        }
        Ok(())
    }
}

/// A `non_finite` failure unless `h` is finite and positive.
pub(crate) fn check_step(t: f64, h: f64, method: &str) -> Result<(), Failure> {
    if h.is_finite() && h > 0.0 && t.is_finite() {
        Ok(())
    } else {
        Err(Failure::new(
            FailureKind::NonFinite,
            t,
            format!("{method}: step h = {h} at t = {t}: h must be finite and positive"),
        ))
    }
}

/// The failure of a factorisation inside a step.
pub(crate) fn lu_failure(e: LuError, t: f64, method: &str) -> Failure {
    let kind = match e {
        LuError::NonFinite => FailureKind::NonFinite,
        LuError::Singular { .. }
        | LuError::NotFactored
        | LuError::Dimension { .. }
        | LuError::OutsidePattern { .. } => FailureKind::NewtonFailure,
    };
    Failure::new(kind, t, format!("{method}: iteration matrix: {e}"))
}

/// What a step's trial values hold beyond `q`, `v`, `a`, for [`accept`] to check.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Trial {
    /// Nothing: `aux` is a copy of `a` (Newmark, HHT), checked once as `a`.
    Plain,
    /// The auxiliary acceleration `aux` of its own (generalized-alpha).
    Aux,
    /// `aux` and the multipliers `lambda` (the index-3 generalized-alpha).
    AuxLambda,
}

/// Ends a step from `t` whose trial values are in the workspace: a `non_finite` failure
/// naming the first of them that is not finite (`q`, `v`, `a`, then `aux` and `lambda` as
/// `trial` says), the state left at `t`; otherwise they become the state (`State::commit`)
/// and the step is counted.
pub(crate) fn accept(
    state: &mut State,
    stats: &mut Stats,
    t: f64,
    method: &str,
    trial: Trial,
) -> Result<(), Failure> {
    let w = &state.work;
    let aux = (trial != Trial::Plain).then_some((&w.aux1, "aux"));
    let lambda = (trial == Trial::AuxLambda).then_some((&w.lambda1, "lambda"));
    let always = [(&w.q1, "q"), (&w.v1, "v"), (&w.a1, "a")];
    for (x, what) in always.into_iter().chain(aux).chain(lambda) {
        check_finite(x, t, method, what)?;
    }
    state.commit(trial == Trial::AuxLambda);
    stats.steps += 1;
    Ok(())
}

/// A `non_finite` failure unless every component of `x` is finite.
pub(crate) fn check_finite(
    x: &DVector<f64>,
    t: f64,
    method: &str,
    what: &str,
) -> Result<(), Failure> {
    if x.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(Failure::new(
            FailureKind::NonFinite,
            t,
            format!("{method}: non-finite {what}"),
        ))
    }
}

/// `num / den` with `0 / 0 = 0`.
#[inline]
pub(crate) fn ratio(num: f64, den: f64) -> f64 {
    if num == 0.0 { 0.0 } else { num / den }
}

/// The evaluation point of (N1) and its coefficients.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Point {
    /// Time of the evaluation.
    pub t_e: f64,
    /// `dq/dx` and `dv/dx` of the evaluation point.
    pub c_k: f64,
    pub c_c: f64,
    /// `|q_n|_inf + h |v_n|_inf`, the size the update is measured against (N4).
    pub scale: f64,
    /// The time the step starts at, for failures.
    pub t_n: f64,
}

/// Solves (N1) by (N3) for `x`, starting from the predictor in `w.a1` and with the
/// unknown-free parts of the evaluation point in `w.qe`, `w.ve`. On success `w.a1` holds `x`
/// and `w.q1`, `w.v1` the evaluation point at it; returns the number of updates.
pub(crate) fn solve_acceleration<S: SecondOrder + ?Sized>(
    sys: &S,
    p: Point,
    opts: &NewtonOptions,
    method: &str,
    w: &mut Work,
    stats: &mut Stats,
) -> Result<u32, Failure> {
    let Work {
        q1,
        v1,
        a1: x,
        qe,
        ve,
        r,
        iter: lu,
        ..
    } = w;
    for it in 1..=opts.max_iters {
        q1.copy_from(qe);
        q1.axpy(p.c_k, x, 1.0);
        v1.copy_from(ve);
        v1.axpy(p.c_c, x, 1.0);
        sys.residual(p.t_e, q1, v1, x, r);
        stats.rhs_evals += 1;
        check_finite(r, p.t_n, method, "residual")?;
        sys.tangent_into(p.t_e, q1, v1, x, 1.0, p.c_c, p.c_k, lu);
        lu.factor().map_err(|e| lu_failure(e, p.t_n, method))?;
        r.neg_mut();
        lu.solve_in_place(r)
            .map_err(|e| lu_failure(e, p.t_n, method))?;
        *x += &*r;
        stats.newton_iters += 1;
        let upd = p.c_k * r.amax();
        let rel = ratio(upd, p.scale + p.c_k * x.amax() + sys.length_scale());
        if rel.is_nan() || !upd.is_finite() {
            return Err(Failure::new(
                FailureKind::NonFinite,
                p.t_n,
                format!("{method}: non-finite Newton update"),
            ));
        }
        if rel <= opts.tol {
            q1.copy_from(qe);
            q1.axpy(p.c_k, x, 1.0);
            v1.copy_from(ve);
            v1.axpy(p.c_c, x, 1.0);
            return Ok(it);
        }
    }
    Err(newton_failure(p.t_n, method, opts))
}

/// The failure of a Newton iteration that reached its cap.
pub(crate) fn newton_failure(t: f64, method: &str, opts: &NewtonOptions) -> Failure {
    Failure::new(
        FailureKind::NewtonFailure,
        t,
        format!(
            "{method}: Newton did not reach tol = {:e} in max_iters = {} updates",
            opts.tol, opts.max_iters
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every bad option is named; good ones pass.
    #[test]
    fn options_are_validated() {
        let ok = NewtonOptions::default();
        assert!(ok.validate().is_ok());
        for tol in [0.0, -1e-10, f64::NAN, f64::INFINITY, 1.0] {
            let e = NewtonOptions { tol, ..ok }.validate().unwrap_err();
            assert!(e.contains("tol"), "{e}");
        }
        let e = NewtonOptions { max_iters: 0, ..ok }.validate().unwrap_err();
        assert!(e.contains("max_iters"), "{e}");
    }

    /// A non-finite, zero or negative step is a `non_finite` failure at the step's time.
    #[test]
    fn bad_steps_are_failures() {
        for h in [f64::NAN, f64::INFINITY, 0.0, -0.1] {
            let f = check_step(2.0, h, "m").unwrap_err();
            assert_eq!((f.kind, f.t), (FailureKind::NonFinite, 2.0));
            assert!(f.message.contains("step h"), "{}", f.message);
        }
        assert!(check_step(2.0, 0.1, "m").is_ok());
    }
}
