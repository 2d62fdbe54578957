//! `path_step`: a [`PathDependent`] structure made a system the structural time integrators
//! run ([`Path`]: the structure, its solution algorithm, its lumped mass, mass-proportional
//! damping and load), and the two steps they take on it: the generalized-alpha family's
//! ([`Path::alpha_step`], which `Newmark`, `Hht` and `GenAlpha` call with their
//! coefficients) and the energy-consistent midpoint rule's ([`Path::midpoint_step`]).
//!
//! **Generalized-alpha family** (Chung & Hulbert 1993, J. Appl. Mech. 60, 371-375):
//! Newmark's kinematics `u_{n+1} = u_n + h v_n + h^2 ((1/2 - beta) a_n + beta a_{n+1})`,
//! `v_{n+1} = v_n + h ((1 - gamma) a_n + gamma a_{n+1})`, and the balance
//!
//! ```text
//! M ((1-am) a_{n+1} + am a_n) + C ((1-af) v_{n+1} + af v_n)
//!     + (1-af) f(u_{n+1}) + af f_n = (1-af) F_{n+1} + af F_n
//! ```
//!
//! (Newmark: `am = af = 0`; HHT: `am = 0`, `af = -alpha`). For a path-dependent structure the
//! weighted internal forces `(1-af) f(u_{n+1}) + af f_n` are used, with `f_n` the committed
//! internal force: the state determination is always made at the end-of-step configuration
//! and the committed history is that of the end points (one determination at
//! `u_{n+1-af}` would commit element states at a configuration the structure never occupies
//! at a step end); this is the form whose accuracy and dissipation Erlicher, Bonaventura &
//! Bursi (2002, Comput. Mech. 28, 83-104) analyse for nonlinear problems, second order for
//! smooth responses.
//!
//! **Midpoint** (energy-consistent): `(u_{n+1} - u_n)/h = (v_n + v_{n+1})/2 =: v_bar` and
//! `M (v_{n+1} - v_n)/h + C v_bar + f_bar = (F_n + F_{n+1})/2` with
//! `f_bar = (f_n + f(u_{n+1}))/2 + e M du / (du . M du)` (the correction of
//! `equilibrium.rs`). Dotting the balance with `du = h v_bar` gives, to the Newton tolerance,
//!
//! ```text
//! (1/2 v^T M v)_{n+1} - (1/2 v^T M v)_n + h v_bar^T C v_bar + dW = du . (F_n + F_{n+1})/2,
//! ```
//!
//! with `dW` the elements' own work over the step. Without the correction (`O(h^3)` per
//! step) the rule is algebraically Newmark's average acceleration.
//!
//! **The load** is `F(t) = F_0 + p s(t)`: a constant part (a prelude's, e.g. a column's axial
//! load) and a pattern `p` scaled by a time series `s` (a ground motion: `p = -M r`, `s` the
//! ground acceleration). **Energies**, counted from [`Path::new`] with one quadrature for
//! every non-conservative force (the trapezoid along the discrete path,
//! `sum du . (g_n + g_{n+1})/2`): `kinetic = 1/2 v^T M v`,
//! `damping = sum du . C (v_n + v_{n+1})/2`, `input = sum du . (F_n + F_{n+1})/2`.
//!
//! Invariants: the state's `q` holds the additive unknowns' displacements (0 for the
//! rotational ones), `v`, `a` the massive unknowns' velocities and accelerations; the start
//! is a static equilibrium under `F_0` (`M a_0 = p s(t_0) - C v_0`). The inner solver is the
//! path's own (its tolerance an energy, J): a method's Newton options serve second-order
//! systems only. No allocation per step. Where it fails: the solver's failure ends the step
//! at `t + h` (the load level the step could not reach, as a static step's), the system
//! reverted and the state unchanged; the schemes' stability is proven for linear problems
//! only.
use nalgebra::DVector;

use super::equilibrium::{Equilibrium, Inertia};
use super::method::Method;
use super::newton::check_step;
use super::path::PathDependent;
use super::state::State;
use crate::integrate::{Failure, Stats};

/// A path-dependent structure with mass, damping and load: what the structural methods
/// step (module docs).
///
/// # Example
///
/// A unit mass on a spring of stiffness 4 (`omega = 2`) shaken by a ground pulse of one
/// second, stepped by Newmark: afterwards it swings freely, its energy (kinetic plus the
/// spring's) equal to the work the pulse did, to the Newton tolerance.
///
/// ```
/// use mbdbench::integrate::Stats;
/// use mbdbench::structural::equilibrium::Newton;
/// use mbdbench::structural::method::Method;
/// use mbdbench::structural::newmark::Newmark;
/// use mbdbench::structural::newton::NewtonOptions;
/// use mbdbench::structural::path_step::Path;
/// # use mbdbench::structural::path::{PathDependent, PathFailure};
/// # use nalgebra::{DMatrix, DVector};
/// # /// A linear spring of stiffness 4 to the ground (the tests have yielding ones).
/// # struct Spring { u: f64, u_c: f64, f: DVector<f64>, k: DMatrix<f64>, fresh: bool }
/// # impl PathDependent for Spring {
/// #     fn dim(&self) -> usize { 1 }
/// #     fn assemble(&mut self) -> Result<(), PathFailure> {
/// #         self.f[0] = 4.0 * self.u; self.k[(0, 0)] = 4.0; self.fresh = true; Ok(())
/// #     }
/// #     fn assembled(&self) -> bool { self.fresh }
/// #     fn internal_force(&self) -> &DVector<f64> { &self.f }
/// #     fn stiffness(&self) -> &DMatrix<f64> { &self.k }
/// #     fn apply(&mut self, dx: &DVector<f64>, eta: f64) { self.u += eta * dx[0]; self.fresh = false; }
/// #     fn mark(&mut self) {}
/// #     fn return_to_mark(&mut self) {}
/// #     fn commit(&mut self) { self.u_c = self.u; }
/// #     fn revert(&mut self) { self.u = self.u_c; self.fresh = false; }
/// #     fn additive(&self, _: usize) -> bool { true }
/// #     fn displacement(&self, _: usize) -> f64 { self.u }
/// #     fn committed_displacement(&self, _: usize) -> f64 { self.u_c }
/// #     fn work(&self) -> f64 { 2.0 * self.u * self.u }
/// # }
/// # let spring = Spring { u: 0.0, u_c: 0.0, f: DVector::zeros(1), k: DMatrix::zeros(1, 1), fresh: false };
/// let one = DVector::from_element(1, 1.0);
/// let ground = |t: f64| if t < 1.0 { 1.0 } else { 0.0 };
/// let newton = Newton::new(1e-20, 20).unwrap();
/// let mut p = Path::new(spring, newton, one.clone(), 0.0, 0.0 * &one, -&one, ground).unwrap();
/// let mut m = Newmark::new(NewtonOptions::default()).unwrap();
/// let (mut st, mut stats) = (m.new_state(&p), Stats::default());
/// m.init(&mut p, 0.0, &mut st, &mut stats).unwrap();
/// for k in 0..400 {
///     m.step(&mut p, k as f64 * 0.01, 0.01, &mut st, &mut stats).unwrap();
/// }
/// let energy = p.kinetic() + p.system.work();
/// assert!(p.input().abs() > 0.1);
/// assert!((energy - p.input()).abs() < 1e-9 * p.input().abs());
/// ```
pub struct Path<S, E, G> {
    /// The structure.
    pub system: S,
    /// Its solution algorithm.
    pub solver: E,
    series: G,
    mass: DVector<f64>,
    a0: f64,
    load: DVector<f64>,
    pattern: DVector<f64>,
    f_ext: DVector<f64>,
    f_old: DVector<f64>,
    u_pred: DVector<f64>,
    v_pred: DVector<f64>,
    u_eff: DVector<f64>,
    v_eff: DVector<f64>,
    kinetic: f64,
    damping: f64,
    input: f64,
}

/// A scalar time series `s(t)` scaling a load pattern (a ground acceleration, m/s^2); every
/// `Fn(f64) -> f64` is one.
pub trait Series {
    /// `s(t)`.
    fn at(&self, t: f64) -> f64;
}

impl<F: Fn(f64) -> f64> Series for F {
    fn at(&self, t: f64) -> f64 {
        self(t)
    }
}

/// A member of the generalized-alpha family as it steps a path-dependent structure: its
/// name and `(alpha_m, alpha_f, beta, gamma)` ([`Path::alpha_step`]). `Newmark`, `Hht` and
/// `GenAlpha` are; every member is a [`Method`] on every [`Path`].
pub trait AlphaFamily {
    /// The method's name.
    const NAME: &'static str;

    /// `(alpha_m, alpha_f, beta, gamma)`.
    fn coefficients(&self) -> (f64, f64, f64, f64);
}

impl<M: AlphaFamily, S: PathDependent, E: Equilibrium<S>, G: Series> Method<Path<S, E, G>> for M {
    const NAME: &'static str = <M as AlphaFamily>::NAME;

    fn step(
        &mut self,
        sys: &mut Path<S, E, G>,
        t: f64,
        h: f64,
        state: &mut State,
        stats: &mut Stats,
    ) -> Result<(), Failure> {
        let name = <M as AlphaFamily>::NAME;
        sys.alpha_step(t, h, state, stats, self.coefficients(), name)
    }
}

/// How a scheme's new velocity and acceleration follow from the converged displacement.
#[derive(Debug, Clone, Copy)]
enum Kinematics {
    /// Newmark's: `a = (u - u_pred)/(beta h^2)`, `v = v_pred + gamma h a`.
    Newmark { beta: f64, gamma: f64, h: f64 },
    /// The midpoint rule's: `v = 2 (u - u_n)/h - v_n`, `a = (v - v_n)/h`.
    Midpoint { h: f64 },
}

impl<S: PathDependent, E: Equilibrium<S>, G: Series> Path<S, E, G> {
    /// `system` (committed, in static equilibrium under `load`), its solver, the lumped
    /// `mass` per unknown, `a0` of `C = a0 M`, the constant `load` and the time-varying
    /// `pattern * series(t)`. An error names the bad input: lengths other than `dim`, a
    /// negative or non-finite mass or `a0`, mass or load on a rotational unknown.
    pub fn new(
        mut system: S,
        solver: E,
        mass: DVector<f64>,
        a0: f64,
        load: DVector<f64>,
        pattern: DVector<f64>,
        series: G,
    ) -> Result<Self, String> {
        let n = system.dim();
        for (what, x) in [("mass", &mass), ("load", &load), ("pattern", &pattern)] {
            if x.len() != n {
                return Err(format!("{what} has {} entries, not {n}", x.len()));
            }
            if let Some(i) = (0..n).find(|&i| x[i] != 0.0 && !system.additive(i)) {
                return Err(format!(
                    "{what} acts on unknown {i}, which is not a translation"
                ));
            }
        }
        if let Some(m) = mass.iter().find(|m| !(m.is_finite() && **m >= 0.0)) {
            return Err(format!("mass {m} is not finite and non-negative"));
        }
        if !(a0.is_finite() && a0 >= 0.0) {
            return Err(format!("damping coefficient {a0} is negative"));
        }
        if !system.assembled() {
            system.assemble().map_err(|e| e.to_string())?;
        }
        let f_old = system.internal_force().clone();
        let zeros = DVector::zeros(n);
        Ok(Path {
            system,
            solver,
            series,
            mass,
            a0,
            f_ext: load.clone(),
            load,
            pattern,
            f_old,
            u_pred: zeros.clone(),
            v_pred: zeros.clone(),
            u_eff: zeros.clone(),
            v_eff: zeros,
            kinetic: 0.0,
            damping: 0.0,
            input: 0.0,
        })
    }

    /// The kinetic energy `1/2 v^T M v` after the last step (J).
    pub fn kinetic(&self) -> f64 {
        self.kinetic
    }

    /// The damping's dissipation since the start (J).
    pub fn damping(&self) -> f64 {
        self.damping
    }

    /// The load's work since the start (J).
    pub fn input(&self) -> f64 {
        self.input
    }

    /// The start at `t0`: `q` from the structure, `a` of the massive unknowns from
    /// `M a_0 = p s(t_0) - C v_0` (a static equilibrium under `F_0`), the energies zero.
    pub(crate) fn start_from_equilibrium(&mut self, t0: f64, state: &mut State) {
        let s0 = self.series.at(t0);
        for i in 0..self.system.dim() {
            state.q[i] = self.additive_displacement(i);
            state.a[i] = if self.mass[i] != 0.0 {
                (self.pattern[i] * s0 - self.a0 * self.mass[i] * state.v[i]) / self.mass[i]
            } else {
                0.0
            };
        }
        state.aux.copy_from(&state.a);
        (self.kinetic, self.damping, self.input) = (0.0, 0.0, 0.0);
        self.f_old.copy_from(self.system.internal_force());
    }

    fn additive_displacement(&self, i: usize) -> f64 {
        if self.system.additive(i) {
            self.system.displacement(i)
        } else {
            0.0
        }
    }

    /// One step of the generalized-alpha family with `(am, af, beta, gamma)` (module docs);
    /// `am = af = 0` is Newmark's end-point equilibrium.
    pub fn alpha_step(
        &mut self,
        t: f64,
        h: f64,
        state: &mut State,
        stats: &mut Stats,
        (am, af, beta, gamma): (f64, f64, f64, f64),
        method: &str,
    ) -> Result<(), Failure> {
        check_step(t, h, method)?;
        let (s0, s1) = (self.series.at(t), self.series.at(t + h));
        for i in (0..self.mass.len()).filter(|&i| self.mass[i] != 0.0) {
            self.u_pred[i] = state.q[i] + state.v[i] * h + state.a[i] * (h * h * (0.5 - beta));
            self.v_pred[i] = state.v[i] + state.a[i] * (h * (1.0 - gamma));
        }
        self.f_ext.copy_from(&self.load);
        let (c_a, c_v, w_int);
        if am == 0.0 && af == 0.0 {
            self.u_eff.copy_from(&self.u_pred);
            self.v_eff.copy_from(&self.v_pred);
            (c_a, c_v, w_int) = (1.0 / (beta * h * h), gamma * h, 1.0);
            self.add_pattern(|p| p * s1);
        } else {
            // a_eff = (1-am) a_{n+1} + am a_n, v_eff = (1-af) v_{n+1} + af v_n, both affine
            // in u through Newmark's a_{n+1} = (u - u_pred)/(beta h^2).
            c_a = (1.0 - am) / (beta * h * h);
            c_v = (1.0 - af) * gamma * h / (1.0 - am);
            w_int = 1.0 - af;
            for i in (0..self.mass.len()).filter(|&i| self.mass[i] != 0.0) {
                let a = state.a[i];
                self.u_eff[i] = self.u_pred[i] - am * a / c_a;
                self.v_eff[i] = (1.0 - af) * self.v_pred[i] + af * state.v[i] - c_v * am * a;
            }
            self.add_pattern(|p| (1.0 - af) * (p * s1) + af * (p * s0));
        }
        let kin = Kinematics::Newmark { beta, gamma, h };
        self.solve(t + h, (c_a, c_v, w_int, None), kin, state, stats, (s0, s1))
    }

    /// One step of the energy-consistent midpoint rule (module docs).
    pub fn midpoint_step(
        &mut self,
        t: f64,
        h: f64,
        state: &mut State,
        stats: &mut Stats,
        method: &str,
    ) -> Result<(), Failure> {
        check_step(t, h, method)?;
        let (s0, s1) = (self.series.at(t), self.series.at(t + h));
        // a_eff = (v_{n+1} - v_n)/h = (2/h^2)(u - u_n - h v_n), v_eff = (u - u_n)/h.
        for i in (0..self.mass.len()).filter(|&i| self.mass[i] != 0.0) {
            self.u_eff[i] = state.q[i] + h * state.v[i];
            self.v_eff[i] = state.v[i];
        }
        self.f_ext.copy_from(&self.load);
        self.add_pattern(|p| 0.5 * (p * s0 + p * s1));
        let w_n = self.system.work();
        let kin = Kinematics::Midpoint { h };
        self.solve(
            t + h,
            (2.0 / (h * h), 0.5 * h, 0.5, Some(w_n)),
            kin,
            state,
            stats,
            (s0, s1),
        )
    }

    /// `f_ext += w(p)` where the pattern is not zero.
    fn add_pattern(&mut self, w: impl Fn(f64) -> f64) {
        for i in (0..self.pattern.len()).filter(|&i| self.pattern[i] != 0.0) {
            self.f_ext[i] += w(self.pattern[i]);
        }
    }

    /// Solves the step's equation with the inertia `(c_a, c_v, w_int, W_n)` of the scheme;
    /// on success counts the step and books it, on failure (at `t_end`) leaves the state.
    #[allow(clippy::too_many_arguments)]
    fn solve(
        &mut self,
        t_end: f64,
        (c_a, c_v, w_int, work_consistent): (f64, f64, f64, Option<f64>),
        kin: Kinematics,
        state: &mut State,
        stats: &mut Stats,
        series: (f64, f64),
    ) -> Result<(), Failure> {
        let inertia = Inertia {
            mass: &self.mass,
            a0: self.a0,
            c_a,
            c_v,
            u_pred: &self.u_eff,
            v_pred: &self.v_eff,
            w_int,
            f_old: (w_int != 1.0).then_some(&self.f_old),
            work_consistent,
        };
        let before = self.system.inner_iterations();
        let iterations = self
            .solver
            .step(&mut self.system, &self.f_ext, None, Some(inertia))
            .map_err(|e| e.at(t_end))? as u64;
        stats.steps += 1;
        stats.newton_iters += iterations;
        // A state determination per iteration plus the final one of the step.
        stats.rhs_evals += iterations + 1;
        stats.element_iters += self.system.inner_iterations() - before;
        self.book(kin, state, series);
        Ok(())
    }

    /// The converged step's new state and energy books; `(s0, s1)` the series at its ends.
    fn book(&mut self, kin: Kinematics, state: &mut State, (s0, s1): (f64, f64)) {
        let mut kinetic = 0.0;
        for i in (0..self.mass.len()).filter(|&i| self.mass[i] != 0.0) {
            let x = self.system.displacement(i);
            let v_old = state.v[i];
            let (a, v) = match kin {
                Kinematics::Newmark { beta, gamma, h } => {
                    let a = (x - self.u_pred[i]) / (beta * h * h);
                    (a, self.v_pred[i] + gamma * h * a)
                }
                Kinematics::Midpoint { h } => {
                    let v_new = 2.0 * (x - state.q[i]) / h - v_old;
                    ((v_new - v_old) / h, v_new)
                }
            };
            (state.a[i], state.v[i]) = (a, v);
            let du = x - state.q[i];
            self.damping += self.a0 * self.mass[i] * du * 0.5 * (v_old + v);
            kinetic += 0.5 * self.mass[i] * v * v;
        }
        for i in (0..self.load.len()).filter(|&i| self.load[i] != 0.0) {
            self.input += (self.system.displacement(i) - state.q[i]) * self.load[i];
        }
        for i in (0..self.pattern.len()).filter(|&i| self.pattern[i] != 0.0) {
            let (du, p) = (self.system.displacement(i) - state.q[i], self.pattern[i]);
            self.input += du * 0.5 * (p * s0 + p * s1);
        }
        for i in 0..state.q.len() {
            state.q[i] = self.additive_displacement(i);
        }
        state.aux.copy_from(&state.a);
        self.kinetic = kinetic;
        self.f_old.copy_from(self.system.internal_force());
    }
}
