//! The simplified Newton iteration of the stage equations of an implicit Gauss step
//! (`ImplicitRk`, `mod.rs`; Hairer & Wanner, *Solving ODEs II*, sec. IV.8): the
//! finite-difference Jacobian `J = dF/dZ` at `Z = 0`, the iteration matrix
//! `M = I - h (A (x) J)` factored by `math::lu::DenseLu`, and one Newton attempt from a given
//! guess (`predictor.rs`) with its convergence, stagnation and divergence tests.
//!
//! Convergence: iterate until the max-norm of the Newton update is at most
//! `10 eps max(1, state_scale, |Z|)` (round-off in the tangent's units; `state_scale` is an
//! option, default 1, because a generic `State` has no norm). The compensated variants iterate
//! to `1 eps |Z|`, the round-off of the stage increments themselves
//! (`NewtonOptions::increment_relative`, `tol_factor`): the absolute test leaves a residual of
//! consistent sign that shows as a linear energy drift over 1e7 steps (see there). Near round-off the updates stop
//! shrinking: once the updates are below `1e3 eps max(...)`, the third iteration there whose
//! update is at least half the previous one ends the iteration as stagnated at the noise floor
//! and is accepted (genuine convergence at rate below 1/2 never counts; at a slower rate the
//! remaining error `theta/(1-theta) |dZ|` is still within a few `1e3 eps`).
//! Two consecutive growing updates above that level (divergence), 50 iterations, a non-finite
//! update, or a singular iteration matrix end the attempt; it is retried once from the
//! explicit predictor with a fresh Jacobian if the first attempt used a reused Jacobian or an
//! extrapolated guess, and then gives a `newton_failure` (`non_finite` if the right-hand side
//! itself returned NaN or infinity) with `t` and the residual in the message.
use super::ImplicitRk;
use super::predictor::{Guess, lagrange};
use crate::integrate::{Failure, FailureKind, Stats, System};
use crate::math::lu::LinearSolve;
use crate::math::vector::Vector;

impl<S: System> ImplicitRk<S> {
    /// `max(1, state_scale)`.
    fn base_scale(&self) -> f64 {
        self.opts.state_scale.abs().max(1.0)
    }

    /// `F(v) = dexp_inv(v, f(t, retract(x, v)))`, one evaluation.
    #[inline(always)]
    fn stage_rate(sys: &S, t: f64, x: &S::State, v: &S::Tangent, stats: &mut Stats) -> S::Tangent {
        stats.rhs_evals += 1;
        sys.rkmk_stage(t, x, v).2
    }

    /// `J = dF/dZ` at `Z = 0` by forward differences; returns `f(t, x)`.
    fn jacobian(
        &mut self,
        sys: &S,
        t: f64,
        x: &S::State,
        stats: &mut Stats,
    ) -> Result<S::Tangent, Failure> {
        let n = self.n;
        self.jac_valid = false;
        let f0 = Self::stage_rate(sys, t, x, &S::Tangent::zero(), stats);
        if !f0.is_finite() {
            return Err(Failure::new(
                FailureKind::NonFinite,
                t,
                format!("right-hand side is non-finite at the step's initial state (t = {t})"),
            ));
        }
        // sqrt(eps) balances truncation O(delta) against cancellation O(eps / delta).
        let delta = f64::EPSILON.sqrt() * self.base_scale();
        for k in 0..n {
            self.col.iter_mut().for_each(|v| *v = 0.0);
            self.col[k] = delta;
            let e = S::Tangent::read_from(&self.col);
            let fk = Self::stage_rate(sys, t, x, &e, stats);
            fk.minus(&f0).write_to(&mut self.col);
            for p in 0..n {
                self.jac[p * n + k] = self.col[p] / delta;
            }
        }
        self.jac_evals += 1;
        self.jac_valid = true;
        self.lu_h = f64::NAN;
        Ok(f0)
    }

    /// Forms and factors `I - h (A (x) J)`.
    fn factor(&mut self, t: f64, h: f64) -> Result<(), Failure> {
        let (n, s) = (self.n, self.tab.s);
        let m = s * n;
        let mat = self.lu.matrix_mut();
        for i in 0..s {
            for j in 0..s {
                let ha = h * self.tab.a[i][j];
                for p in 0..n {
                    // Row i n + p, columns j n + q of the column-major buffer.
                    let row = i * n + p;
                    for q in 0..n {
                        let id = if i == j && p == q { 1.0 } else { 0.0 };
                        mat[(j * n + q) * m + row] = id - ha * self.jac[p * n + q];
                    }
                }
            }
        }
        self.lu_h = f64::NAN;
        self.lu.factor().map_err(|e| {
            Failure::new(
                FailureKind::NewtonFailure,
                t,
                format!("Newton iteration matrix I - h A(x)J at t = {t}: {e}"),
            )
        })?;
        self.lu_h = h;
        Ok(())
    }

    /// One Newton attempt; returns the iterations used. `self.z` holds the solution on success.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn attempt(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        x: &S::State,
        stats: &mut Stats,
        fresh: bool,
        guess: Guess,
        iters: &mut u32,
    ) -> Result<(), Failure> {
        let f0 = self.prepare_matrix(sys, t, h, x, stats, fresh)?;
        self.initial_guess(sys, t, h, x, stats, guess, f0)?;
        let eps = f64::EPSILON;
        let mut stop = StopTests::new();
        let mut residual = f64::NAN;
        let mut dz = f64::NAN;
        let mut tol = f64::NAN;
        for k in 1..=self.opts.max_iters {
            stats.newton_iters += 1;
            let scale;
            (residual, dz, scale) = match self.iterate(sys, t, h, x, stats, k) {
                Ok(v) => v,
                Err(e) => {
                    *iters += k;
                    return Err(e);
                }
            };
            tol = self.opts.tol_factor * eps * scale;
            match stop.judge(dz, tol, 1e3 * eps * scale) {
                Next::Iterate => continue,
                Next::Converged => {}
                Next::Stagnated => self.stagnations += 1,
                Next::Diverged => {
                    *iters += k;
                    return Err(Failure::new(
                        FailureKind::NewtonFailure,
                        t,
                        format!(
                            "Newton diverges at iterate {k} (t = {t}): update {dz:.3e}, \
                             residual {residual:.3e}"
                        ),
                    ));
                }
            }
            *iters += k;
            return Ok(());
        }
        *iters += self.opts.max_iters;
        Err(Failure::new(
            FailureKind::NewtonFailure,
            t,
            format!(
                "Newton did not converge in {} iterations (t = {t}): update {dz:.3e} > \
                 {tol:.3e}, residual {residual:.3e}",
                self.opts.max_iters
            ),
        ))
    }

    /// The Jacobian (when `fresh` or none is valid) and the factored iteration matrix for
    /// `h`; returns `f(t, x)` when the Jacobian was evaluated.
    #[inline]
    fn prepare_matrix(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        x: &S::State,
        stats: &mut Stats,
        fresh: bool,
    ) -> Result<Option<S::Tangent>, Failure> {
        let mut f0 = None;
        if fresh || !self.jac_valid {
            f0 = Some(self.jacobian(sys, t, x, stats)?);
        }
        if self.lu_h != h || !self.lu.is_factored() {
            self.factor(t, h)?;
        }
        Ok(f0)
    }

    /// The stage increments `self.z` the iteration starts from: the previous step's
    /// collocation polynomial extrapolated, or the explicit predictor `Z_i = c_i h f(t, x)`
    /// (`f0`, when the Jacobian already evaluated it).
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn initial_guess(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        x: &S::State,
        stats: &mut Stats,
        guess: Guess,
        f0: Option<S::Tangent>,
    ) -> Result<(), Failure> {
        let s = self.tab.s;
        match guess {
            Guess::Extrapolated => {
                // Z_i = Theta(1 + r c_i) - Theta(1), Theta the previous collocation polynomial.
                let r = h / self.h_prev;
                let c = &self.tab.c[..s];
                for i in 0..s {
                    let mut zi = S::Tangent::zero();
                    for j in 0..s {
                        let e = lagrange(c, j, 1.0 + r * c[i]) - self.tab.d[j];
                        zi.axpy(e, &self.z_prev[j]);
                    }
                    self.z[i] = zi;
                }
            }
            Guess::Predictor => {
                let f0 = match f0 {
                    Some(v) => v,
                    None => Self::stage_rate(sys, t, x, &S::Tangent::zero(), stats),
                };
                if !f0.is_finite() {
                    return Err(Failure::new(
                        FailureKind::NonFinite,
                        t,
                        format!(
                            "right-hand side is non-finite at the step's initial state (t = {t})"
                        ),
                    ));
                }
                for i in 0..s {
                    self.z[i] = f0.scaled(self.tab.c[i] * h);
                }
            }
        }
        Ok(())
    }

    /// Newton iterate `k`: the stage rates at `self.z`, the update solved from the residual
    /// and added to `self.z`. Returns (residual, update, scale), the max-norms of `-G` and
    /// `dZ` and the scale of the convergence test.
    #[inline]
    fn iterate(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        x: &S::State,
        stats: &mut Stats,
        k: u32,
    ) -> Result<(f64, f64, f64), Failure> {
        self.stage_rates(sys, t, h, x, stats, k)?;
        let residual = self.solve_update(t, h)?;
        let dz = self.buf.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        if !dz.is_finite() {
            return Err(Failure::new(
                FailureKind::NewtonFailure,
                t,
                format!(
                    "non-finite Newton update at iterate {k} (t = {t}), residual {residual:.3e}"
                ),
            ));
        }
        let zmax = self.add_update();
        let scale = if self.opts.increment_relative {
            zmax
        } else {
            self.base_scale().max(zmax)
        };
        Ok((residual, dz, scale))
    }

    /// `self.f[j] = F(Z_j)` at the stage times; a non-finite rate fails.
    #[inline]
    fn stage_rates(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        x: &S::State,
        stats: &mut Stats,
        k: u32,
    ) -> Result<(), Failure> {
        for j in 0..self.tab.s {
            self.f[j] = Self::stage_rate(sys, t + self.tab.c[j] * h, x, &self.z[j], stats);
            if !self.f[j].is_finite() {
                return Err(Failure::new(
                    FailureKind::NonFinite,
                    t,
                    format!(
                        "right-hand side non-finite at stage {j} of Newton iterate {k} (t = {t})"
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Writes `-G_i = h sum_j a_ij F_j - Z_i` into `self.buf` and solves `M dZ = -G` in
    /// place; returns the residual's max-norm.
    #[inline]
    fn solve_update(&mut self, t: f64, h: f64) -> Result<f64, Failure> {
        let (n, s) = (self.n, self.tab.s);
        let mut residual = 0.0_f64;
        for i in 0..s {
            let mut g = self.z[i].scaled(-1.0);
            for j in 0..s {
                g.axpy(h * self.tab.a[i][j], &self.f[j]);
            }
            residual = residual.max(g.norm_inf());
            g.write_to(&mut self.buf[i * n..(i + 1) * n]);
        }
        self.lu
            .solve(&mut self.buf)
            .map_err(|e| Failure::new(FailureKind::NewtonFailure, t, e.to_string()))?;
        Ok(residual)
    }

    /// `Z += dZ` (`self.buf`); returns the new `max_i |Z_i|`.
    #[inline]
    fn add_update(&mut self) -> f64 {
        let n = self.n;
        let mut zmax = 0.0_f64;
        for i in 0..self.tab.s {
            let d = S::Tangent::read_from(&self.buf[i * n..(i + 1) * n]);
            self.z[i].axpy(1.0, &d);
            zmax = zmax.max(self.z[i].norm_inf());
        }
        zmax
    }
}

/// What an iterate's update says about the Newton iteration.
enum Next {
    Iterate,
    Converged,
    /// At the noise floor: accepted.
    Stagnated,
    Diverged,
}

/// The convergence, stagnation and divergence tests over the updates of one attempt.
struct StopTests {
    /// The previous update's max-norm.
    prev: f64,
    stalled: u32,
    grown: u32,
}

impl StopTests {
    fn new() -> Self {
        StopTests {
            prev: f64::INFINITY,
            stalled: 0,
            grown: 0,
        }
    }

    /// Judges the update `dz` against the tolerance `tol` and the noise band's top `band`
    /// (`1e3 eps` x scale).
    #[inline]
    fn judge(&mut self, dz: f64, tol: f64, band: f64) -> Next {
        if dz <= tol {
            return Next::Converged;
        }
        // Stagnation: inside the band (tol, 1e3 eps], count the iterations that do not
        // halve the update; leaving the band resets the count.
        if dz <= band {
            if dz >= 0.5 * self.prev {
                self.stalled += 1;
                if self.stalled >= 3 {
                    return Next::Stagnated;
                }
            }
        } else {
            self.stalled = 0;
        }
        if dz > self.prev && dz > band {
            self.grown += 1;
            if self.grown >= 2 {
                return Next::Diverged;
            }
        } else {
            self.grown = 0;
        }
        self.prev = dz;
        Next::Iterate
    }
}
