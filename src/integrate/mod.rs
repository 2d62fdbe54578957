//! Time integrators: the `System` a method advances, the typed failures and work counters a
//! run reports, and the two method traits (fixed-step one-step methods, adaptive whole-span
//! methods). One file per method family lives beside this one: the methods generic over a kind
//! of system. `integrate` imports no model family (docs/architecture.md): a method written for
//! one family's equations lives in that family's folder (the rigid body's `simo_wong` and
//! compensated variants in `model/rigid_body/methods/`), and uses the shared pieces here
//! (`lu6`, `newton_stop`, `own_state`, `implicit_rk`). A method for a kind of system is written
//! once over that kind's trait, which a family implements for its systems: `lie_gen_alpha`
//! over `LieSecondOrder` (a second-order system on a Lie group); `kick_drift` over
//! `SplitMechanics` (a mechanical system split into kicks and a free flow on its group), with
//! the free flow the family supplies (the rigid body's principal-axis rotor: `splitting`; its
//! discrete Lagrangian's flow: `lgvi`).
//!
//! A `System` separates the state (what is stored: a quaternion has 4 numbers) from its
//! increment (`Tangent`: 3 numbers on SO(3)). `retract(x, dx)` is `x + dx` on additive charts
//! and `x * exp(dx)` (or `exp(dx) * x`) on Lie groups; `rhs` returns coordinate rates on
//! additive charts and the trivialised velocity on Lie groups; `dexp_inv` turns a velocity
//! into the rate of a stage increment (identity on additive charts). With these three, one
//! Runge-Kutta code is classical RK on vectors and Runge-Kutta-Munthe-Kaas on Lie groups
//! (Munthe-Kaas 1998; Iserles et al., Acta Numerica 2000, sec. 5.3).
//!
//! Invariants: methods never allocate per step (workspaces live in the method struct), never
//! panic on a bad state (a non-finite value or a singular chart becomes a typed `Failure`),
//! and count every right-hand-side evaluation and Newton iteration in `Stats`.
use serde::{Deserialize, Serialize};

use crate::math::vector::Vector;

pub mod adaptive_rk;
pub mod crouch_grossman;
pub mod explicit_rk;
pub mod gen_alpha_coefficients;
pub mod implicit_rk;
pub mod kick_drift;
pub mod lie_gen_alpha;
pub mod lie_second_order;
pub mod lu6;
pub(crate) mod newton_stop;
pub mod own_state;
#[cfg(test)]
pub(crate) mod rigid_test_support;
pub mod tableau;
#[cfg(test)]
pub(crate) mod test_support;

/// A dynamical system on a state space with a retraction.
///
/// # Example
///
/// A harmonic oscillator on a vector space, advanced one period by classical RK4 (through
/// `FixedStep::step`): it returns to its start to RK4's global phase error `~ 2 pi h^4 / 120`,
/// with 4 right-hand-side evaluations a step.
///
/// ```
/// # use mbdbench::integrate::{Failure, FailureKind, System};
/// # use nalgebra::Vector2;
/// /// The harmonic oscillator `q'' = -q` on `(q, p)`.
/// struct Oscillator;
/// impl System for Oscillator {
///     type State = Vector2<f64>;
///     type Tangent = Vector2<f64>;
///     const LIE: bool = false;
///     fn rhs(&self, _t: f64, x: &Vector2<f64>) -> Vector2<f64> {
///         Vector2::new(x[1], -x[0])
///     }
///     fn retract(&self, x: &Vector2<f64>, dx: &Vector2<f64>) -> Vector2<f64> {
///         x + dx
///     }
///     fn check(&self, t: f64, x: &Vector2<f64>) -> Result<(), Failure> {
///         if x.iter().all(|v| v.is_finite()) {
///             Ok(())
///         } else {
///             Err(Failure::new(FailureKind::NonFinite, t, "non-finite state"))
///         }
///     }
/// }
/// use mbdbench::integrate::explicit_rk::ExplicitRk;
/// use mbdbench::integrate::{FixedStep, Stats};
///
/// let (sys, x0) = (Oscillator, Vector2::new(1.0, 0.0));
/// let n = 200;
/// let h = 2.0 * std::f64::consts::PI / n as f64;
/// let (mut x, mut stats, mut rk4) = (x0, Stats::default(), ExplicitRk::rk4());
/// for k in 0..n {
///     rk4.step(&sys, k as f64 * h, h, &mut x, &mut stats).unwrap();
/// }
/// assert!((x - x0).norm() < 1e-7 && (x - x0).norm() > 1e-11);
/// assert_eq!(stats.rhs_evals, 4 * n as u64);
/// ```
pub trait System: Send + Sync {
    /// The stored state.
    type State: Copy + std::fmt::Debug + Send + Sync;
    /// Its increment (an element of R^n).
    type Tangent: Vector;
    /// `retract` is a group action and `dexp_inv` is not the identity.
    const LIE: bool;
    /// The vector field at `(t, x)`: coordinate rates, or the trivialised velocity on a Lie group.
    fn rhs(&self, t: f64, x: &Self::State) -> Self::Tangent;
    /// `x (+) dx`.
    fn retract(&self, x: &Self::State, dx: &Self::Tangent) -> Self::State;
    /// Rate of the increment `theta` of `x (+) theta` whose velocity is `v`; identity on
    /// additive spaces.
    fn dexp_inv(&self, theta: &Self::Tangent, v: &Self::Tangent) -> Self::Tangent {
        let _ = theta;
        *v
    }
    /// One Runge-Kutta-Munthe-Kaas stage at the increment `theta`: the point
    /// `y = x (+) theta`, the vector field `v = f(t, y)` and its correction
    /// `dexp_inv(theta, v)` (`v` itself on an additive system), as `(y, v, k)`. A system may
    /// share work between the retraction and the correction, which see the same `theta`, but
    /// must return the numbers of the default (the three calls apart).
    #[inline(always)]
    fn rkmk_stage(
        &self,
        t: f64,
        x: &Self::State,
        theta: &Self::Tangent,
    ) -> (Self::State, Self::Tangent, Self::Tangent) {
        let y = self.retract(x, theta);
        let v = self.rhs(t, &y);
        let k = if Self::LIE {
            self.dexp_inv(theta, &v)
        } else {
            v
        };
        (y, v, k)
    }
    /// Projection or re-charting after a step; returns whether it changed the state.
    fn normalize(&self, x: &mut Self::State) -> bool {
        let _ = x;
        false
    }
    /// A typed failure when the state is non-finite or its chart is singular.
    fn check(&self, t: f64, x: &Self::State) -> Result<(), Failure>;
    /// The chart's conditioning at `x` (0 on its singular set; 1 where it has none).
    fn conditioning(&self, x: &Self::State) -> f64 {
        let _ = x;
        1.0
    }
    /// `check`, returning the conditioning it saw: the run loop tracks the minimum
    /// conditioning every step, and a system whose `check` already computes it (the Euler
    /// charts' `|cos b|`) overrides this to compute it once.
    fn check_conditioning(&self, t: f64, x: &Self::State) -> Result<f64, Failure> {
        self.check(t, x)?;
        Ok(self.conditioning(x))
    }
}

/// Why a run ended early (docs/schemas.md, "Failure kinds").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FailureKind {
    /// The chart's conditioning fell to 1e-12 or below.
    SingularChart,
    /// A state component became NaN or infinite.
    NonFinite,
    /// Newton's method did not converge.
    NewtonFailure,
    /// An adaptive method's step fell below its floor.
    StepSizeUnderflow,
    /// The run exceeded its step or RHS-evaluation budget.
    WorkLimit,
    /// A case's own bound was crossed.
    Diverged,
    /// A stability-study bound was crossed.
    BoundExceeded,
}

impl FailureKind {
    /// Every kind, in declaration order.
    pub const ALL: [FailureKind; 7] = [
        FailureKind::SingularChart,
        FailureKind::NonFinite,
        FailureKind::NewtonFailure,
        FailureKind::StepSizeUnderflow,
        FailureKind::WorkLimit,
        FailureKind::Diverged,
        FailureKind::BoundExceeded,
    ];

    /// The kind named `name` (`FailureKind::name`), if any.
    pub fn from_name(name: &str) -> Option<FailureKind> {
        FailureKind::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The kind's name as the files write it (snake_case).
    pub fn name(self) -> &'static str {
        match self {
            FailureKind::SingularChart => "singular_chart",
            FailureKind::NonFinite => "non_finite",
            FailureKind::NewtonFailure => "newton_failure",
            FailureKind::StepSizeUnderflow => "step_size_underflow",
            FailureKind::WorkLimit => "work_limit",
            FailureKind::Diverged => "diverged",
            FailureKind::BoundExceeded => "bound_exceeded",
        }
    }
}

/// A typed failure: what, when, and a sentence for the report.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Failure {
    pub kind: FailureKind,
    pub t: f64,
    pub message: String,
}

impl Failure {
    pub fn new(kind: FailureKind, t: f64, message: impl Into<String>) -> Self {
        Failure {
            kind,
            t,
            message: message.into(),
        }
    }
}

/// Deterministic work counters of one run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Stats {
    pub steps: u64,
    pub rhs_evals: u64,
    pub newton_iters: u64,
    pub rejected: u64,
    pub normalizations: u64,
    /// Element-level iterations inside the structure's state determinations (the fiber
    /// column's force-based elements); absent from the summary when 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub element_iters: u64,
}

fn is_zero(x: &u64) -> bool {
    *x == 0
}

/// One counter of [`Stats`]: its key (in the summary's `stats`, a gate's `metric`, a
/// report's column), its field, what it counts, and which consumers treat it as a cost.
#[derive(Debug, Clone, Copy)]
pub struct Counter {
    pub name: &'static str,
    pub get: fn(&Stats) -> u64,
    pub get_mut: fn(&mut Stats) -> &mut u64,
    /// What one unit is (docs/schemas.md's `stats` table).
    pub counts: &'static str,
    /// A cost of the method, compared with the gate's baseline (`gate::regression`).
    pub compared: bool,
    /// A cost column of the report's variant tables and heat maps.
    pub column: bool,
}

/// Every counter of [`Stats`], in the summary's order: a new counter is its field and one
/// line here. Every consumer (the gate's metrics and baseline rows, the report's cost
/// columns, the sum of segments) iterates this table.
#[rustfmt::skip]
pub const COUNTERS: [Counter; 6] = [
    Counter { name: "steps", get: |s| s.steps, get_mut: |s| &mut s.steps, compared: false, column: false, counts: "accepted steps" },
    Counter { name: "rhs_evals", get: |s| s.rhs_evals, get_mut: |s| &mut s.rhs_evals, compared: true, column: true, counts: "evaluations of the right-hand side" },
    Counter { name: "newton_iters", get: |s| s.newton_iters, get_mut: |s| &mut s.newton_iters, compared: true, column: true, counts: "Newton iterations (implicit methods)" },
    Counter { name: "rejected", get: |s| s.rejected, get_mut: |s| &mut s.rejected, compared: false, column: false, counts: "rejected step attempts (adaptive methods)" },
    Counter { name: "normalizations", get: |s| s.normalizations, get_mut: |s| &mut s.normalizations, compared: false, column: false, counts: "projections or re-chartings after a step that changed the state" },
    Counter { name: "element_iters", get: |s| s.element_iters, get_mut: |s| &mut s.element_iters, compared: true, column: false, counts: "element-level iterations inside the structure's state determinations" },
];

/// The keys of [`COUNTERS`], in its order.
pub const COUNTER_NAMES: [&str; COUNTERS.len()] = counter_names();

const fn counter_names() -> [&'static str; COUNTERS.len()] {
    let mut names = [""; COUNTERS.len()];
    let mut i = 0;
    while i < COUNTERS.len() {
        names[i] = COUNTERS[i].name;
        i += 1;
    }
    names
}

impl Stats {
    /// The counter named `name` (a key of [`COUNTERS`]), or None.
    pub fn count(&self, name: &str) -> Option<u64> {
        COUNTERS
            .iter()
            .find(|c| c.name == name)
            .map(|c| (c.get)(self))
    }
}

/// The counters of two runs together (a run made of segments, each its own run).
impl std::ops::AddAssign for Stats {
    fn add_assign(&mut self, b: Stats) {
        for c in &COUNTERS {
            *(c.get_mut)(self) += (c.get)(&b);
        }
    }
}

/// `max_steps` when a case does not set it.
pub const DEFAULT_MAX_STEPS: u64 = 100_000_000;

/// `max_rhs_evals` (every run) when a case does not set it: a fixed-step run is bounded by
/// `max_steps` before it starts, so this only stops a runaway Newton iteration count.
pub const DEFAULT_MAX_RHS_EVALS: u64 = 2_000_000_000;

/// `max_adaptive_rhs_evals` when a case does not set it: the RHS budget of an adaptive run,
/// whose work is not known up front. The catalogue's costliest adaptive run takes 251,741
/// (`gimbal_lock/spin_d1e-8`, `euler_zyx/dop853` at tol 1e-12); a run that diverges at a
/// loose tolerance crawls on steps of 1e-7 s and would take 1e8 steps (`se3_hq/dopri5` at
/// tol 0.5 on `nine_spring/two_angles`: 7.8e8 evaluations, 413 s).
pub const DEFAULT_MAX_ADAPTIVE_RHS_EVALS: u64 = 1_000_000;

/// Per-run budgets; exceeding one is a `work_limit` failure. An adaptive run's work is not
/// known up front (a fixed-step run's is, and is checked against `max_steps` before it
/// starts): `run::run_adaptive` bounds it by `max_adaptive_rhs_evals` too ([`Limits::adaptive`]),
/// and the adaptive pairs stop before an attempt that could pass their RHS budget
/// ([`Limits::room`]), so they never spend more than it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    pub max_steps: u64,
    pub max_rhs_evals: u64,
    /// The RHS budget of an adaptive run (default [`DEFAULT_MAX_ADAPTIVE_RHS_EVALS`]).
    pub max_adaptive_rhs_evals: u64,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_steps: DEFAULT_MAX_STEPS,
            max_rhs_evals: DEFAULT_MAX_RHS_EVALS,
            max_adaptive_rhs_evals: DEFAULT_MAX_ADAPTIVE_RHS_EVALS,
        }
    }
}

impl Limits {
    /// `work_limit` failure if a budget is exhausted.
    #[inline]
    pub fn check(&self, t: f64, stats: &Stats) -> Result<(), Failure> {
        if stats.steps > self.max_steps {
            return Err(Failure::new(
                FailureKind::WorkLimit,
                t,
                format!("more than max_steps = {} steps", self.max_steps),
            ));
        }
        if stats.rhs_evals > self.max_rhs_evals {
            return Err(Failure::new(
                FailureKind::WorkLimit,
                t,
                format!(
                    "more than max_rhs_evals = {} evaluations",
                    self.max_rhs_evals
                ),
            ));
        }
        Ok(())
    }

    /// `work_limit` failure if `evals` more RHS evaluations would pass the RHS budget (an
    /// adaptive pair calls it before each attempt with the attempt's most evaluations).
    #[inline]
    pub fn room(&self, t: f64, stats: &Stats, evals: u64) -> Result<(), Failure> {
        if stats.rhs_evals.saturating_add(evals) > self.max_rhs_evals {
            return Err(Failure::new(
                FailureKind::WorkLimit,
                t,
                format!(
                    "{} RHS evaluations spent; the next attempt's {evals} would pass the \
                     budget of {} (case keys max_rhs_evals, max_adaptive_rhs_evals)",
                    stats.rhs_evals, self.max_rhs_evals
                ),
            ));
        }
        Ok(())
    }

    /// The limits of an adaptive run: the RHS budget is the smaller of `max_rhs_evals` and
    /// `max_adaptive_rhs_evals`.
    pub fn adaptive(&self) -> Limits {
        Limits {
            max_rhs_evals: self.max_rhs_evals.min(self.max_adaptive_rhs_evals),
            ..*self
        }
    }
}

/// What a method is, as data (reported and used by the registry and the order tests).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct MethodInfo {
    pub name: &'static str,
    pub order: u32,
    pub stages: u32,
    pub implicit: bool,
    pub symplectic: bool,
    pub lie_group: bool,
    pub energy_conserving: bool,
    pub adaptive: bool,
    /// The family of method, for grouping (the report draws one panel per kind).
    pub kind: MethodKind,
    /// For a twin that differs from another method only in how it sums (Kahan-compensated
    /// summation), that method's name: the twins matter over long horizons only, and the
    /// short-horizon plots leave them out.
    pub twin_of: Option<&'static str>,
}

impl MethodInfo {
    /// A method of `kind` and `order` with one stage and every property off (explicit, fixed
    /// step, neither symplectic nor Lie-group nor energy-conserving, no twin); the `with_`
    /// methods set the rest, so a method states only what it is.
    ///
    /// # Example
    ///
    /// ```
    /// use mbdbench::integrate::{MethodInfo, MethodKind};
    ///
    /// let lgvi = MethodInfo::new("lgvi", MethodKind::Geometric, 2)
    ///     .with_implicit(true)
    ///     .with_symplectic(true)
    ///     .with_lie_group(true);
    /// assert!(lgvi.implicit && lgvi.symplectic && !lgvi.energy_conserving && lgvi.stages == 1);
    /// ```
    pub const fn new(name: &'static str, kind: MethodKind, order: u32) -> Self {
        MethodInfo {
            name,
            order,
            stages: 1,
            implicit: false,
            symplectic: false,
            lie_group: false,
            energy_conserving: false,
            adaptive: false,
            kind,
            twin_of: None,
        }
    }

    /// With `stages` stages.
    pub const fn with_stages(mut self, stages: u32) -> Self {
        self.stages = stages;
        self
    }

    /// Implicit or not.
    pub const fn with_implicit(mut self, yes: bool) -> Self {
        self.implicit = yes;
        self
    }

    /// Symplectic or not.
    pub const fn with_symplectic(mut self, yes: bool) -> Self {
        self.symplectic = yes;
        self
    }

    /// Running on a Lie group (its state moved by a retraction) or not.
    pub const fn with_lie_group(mut self, yes: bool) -> Self {
        self.lie_group = yes;
        self
    }

    /// Conserving the energy exactly or not.
    pub const fn with_energy_conserving(mut self, yes: bool) -> Self {
        self.energy_conserving = yes;
        self
    }

    /// Adaptive (choosing its own steps) or not.
    pub const fn with_adaptive(mut self, yes: bool) -> Self {
        self.adaptive = yes;
        self
    }

    /// The twin of method `name` (the same method with another summation).
    pub const fn with_twin_of(mut self, name: &'static str) -> Self {
        self.twin_of = Some(name);
        self
    }
}

/// The family a method belongs to, independent of the chart it runs on (RKMK4 on a Lie-group
/// chart is still an explicit Runge-Kutta method).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MethodKind {
    /// Explicit Runge-Kutta methods, fixed step or adaptive (Euler, RK4, Dormand-Prince).
    Explicit,
    /// Implicit Runge-Kutta methods on any chart (the Gauss collocation methods).
    Implicit,
    /// Structure-preserving methods written for the problem: Lie-group (Crouch-Grossman,
    /// Lie generalized-alpha), variational (LGVI, Stormer-Verlet), splitting and
    /// energy-momentum (Simo-Wong) methods.
    Geometric,
    /// The Newmark family of structural dynamics on second-order systems in residual form
    /// (`structural`: Newmark, HHT, generalized-alpha and its index-3 form).
    Structural,
}

impl MethodKind {
    /// Every kind, in report order.
    pub const ALL: [MethodKind; 4] = [
        MethodKind::Explicit,
        MethodKind::Implicit,
        MethodKind::Geometric,
        MethodKind::Structural,
    ];

    /// The kind's name (`explicit`, `implicit`, `geometric`, `structural`).
    pub fn name(self) -> &'static str {
        match self {
            MethodKind::Explicit => "explicit",
            MethodKind::Implicit => "implicit",
            MethodKind::Geometric => "geometric",
            MethodKind::Structural => "structural",
        }
    }
}

/// A fixed-step one-step method. It counts its RHS evaluations and Newton iterations in
/// `stats`; the caller counts steps, normalizes and checks the state after each step.
///
/// # Example
///
/// A method states its facts as data; the implicit midpoint rule (one Gauss stage, order 2,
/// symplectic) keeps the oscillator's quadratic energy to its Newton tolerance:
///
/// ```
/// # use mbdbench::integrate::{Failure, FailureKind, System};
/// # use nalgebra::Vector2;
/// /// The harmonic oscillator `q'' = -q` on `(q, p)`.
/// struct Oscillator;
/// impl System for Oscillator {
///     type State = Vector2<f64>;
///     type Tangent = Vector2<f64>;
///     const LIE: bool = false;
///     fn rhs(&self, _t: f64, x: &Vector2<f64>) -> Vector2<f64> {
///         Vector2::new(x[1], -x[0])
///     }
///     fn retract(&self, x: &Vector2<f64>, dx: &Vector2<f64>) -> Vector2<f64> {
///         x + dx
///     }
///     fn check(&self, t: f64, x: &Vector2<f64>) -> Result<(), Failure> {
///         if x.iter().all(|v| v.is_finite()) {
///             Ok(())
///         } else {
///             Err(Failure::new(FailureKind::NonFinite, t, "non-finite state"))
///         }
///     }
/// }
/// use mbdbench::integrate::implicit_rk::ImplicitRk;
/// use mbdbench::integrate::{FixedStep, Stats};
///
/// let mut m = ImplicitRk::implicit_midpoint();
/// let info = FixedStep::<Oscillator>::info(&m);
/// assert_eq!((info.name, info.order, info.implicit, info.symplectic), ("implicit_midpoint", 2, true, true));
/// let (mut x, mut stats) = (Vector2::new(1.0, 0.0), Stats::default());
/// for k in 0..1000 {
///     m.step(&Oscillator, k as f64 * 0.1, 0.1, &mut x, &mut stats).unwrap();
/// }
/// assert!((x.norm_squared() - 1.0).abs() < 1e-12);
/// assert!(stats.newton_iters > 0);
/// ```
pub trait FixedStep<S: System> {
    fn info(&self) -> MethodInfo;
    /// Advances `x` from `t` to `t + h`.
    fn step(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        x: &mut S::State,
        stats: &mut Stats,
    ) -> Result<(), Failure>;
}

/// An adaptive method: it advances over a whole span with its own step control, keeping the
/// controller state between calls; it normalizes and checks after each accepted step.
///
/// # Example
///
/// Dormand-Prince 5(4) over one period of the oscillator (its error norm needs the state's
/// componentwise size, `ErrorScale`: all components additive here):
///
/// ```
/// # use mbdbench::integrate::{Failure, FailureKind, System};
/// # use nalgebra::Vector2;
/// /// The harmonic oscillator `q'' = -q` on `(q, p)`.
/// struct Oscillator;
/// impl System for Oscillator {
///     type State = Vector2<f64>;
///     type Tangent = Vector2<f64>;
///     const LIE: bool = false;
///     fn rhs(&self, _t: f64, x: &Vector2<f64>) -> Vector2<f64> {
///         Vector2::new(x[1], -x[0])
///     }
///     fn retract(&self, x: &Vector2<f64>, dx: &Vector2<f64>) -> Vector2<f64> {
///         x + dx
///     }
///     fn check(&self, t: f64, x: &Vector2<f64>) -> Result<(), Failure> {
///         if x.iter().all(|v| v.is_finite()) {
///             Ok(())
///         } else {
///             Err(Failure::new(FailureKind::NonFinite, t, "non-finite state"))
///         }
///     }
/// }
/// use mbdbench::integrate::adaptive_rk::{AdaptiveRk, ErrorScale};
/// use mbdbench::integrate::{Adaptive, Limits, Stats};
///
/// impl ErrorScale for Oscillator {
///     fn coords(&self, x: &Vector2<f64>) -> Vector2<f64> {
///         *x
///     }
/// }
/// let mut m = AdaptiveRk::dopri5(1e-10);
/// assert!(Adaptive::<Oscillator>::info(&m).adaptive);
/// let (x0, mut stats) = (Vector2::new(1.0, 0.0), Stats::default());
/// let mut x = x0;
/// let period = 2.0 * std::f64::consts::PI;
/// m.advance(&Oscillator, 0.0, period, &mut x, &mut stats, &Limits::default()).unwrap();
/// assert!((x - x0).norm() < 1e-8);
/// assert!(stats.steps > 10 && stats.rhs_evals >= 6 * stats.steps);
/// ```
pub trait Adaptive<S: System> {
    fn info(&self) -> MethodInfo;
    /// Advances `x` from `t0` to exactly `t1`.
    fn advance(
        &mut self,
        sys: &S,
        t0: f64,
        t1: f64,
        x: &mut S::State,
        stats: &mut Stats,
        limits: &Limits,
    ) -> Result<(), Failure>;
    /// Integrates `x` from `t0` to `t0 + n_out dt_out` with free steps (only the last one is
    /// clipped, to land exactly on the end) and hands out the state at every output time
    /// `t_k = t0 + k dt_out` (computed from the integer `k`), `k = 1..=n_out` in order, by
    /// `on_output(k, &state)`: the method's dense output, normalized (a copy: the integration
    /// state is not touched). An error from `on_output` ends the run. `x` ends at the state of
    /// the last accepted step, on failure at the last state accepted before it.
    #[allow(clippy::too_many_arguments, clippy::type_complexity)]
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
    ) -> Result<(), Failure>;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The counter table is the struct: its names are the summary's `stats` keys in order,
    /// each accessor reads and writes its own field, and the sum of two runs adds every
    /// counter.
    #[test]
    fn counters_are_the_fields_of_stats() {
        let mut s = Stats::default();
        for (i, c) in COUNTERS.iter().enumerate() {
            *(c.get_mut)(&mut s) = 10 + i as u64;
        }
        let json = serde_json::to_value(s).unwrap();
        let mut found: Vec<&str> = json
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        found.sort_unstable();
        let mut sorted = COUNTER_NAMES.to_vec();
        sorted.sort_unstable();
        assert_eq!(found, sorted);
        for (i, c) in COUNTERS.iter().enumerate() {
            assert_eq!(json[c.name], 10 + i as u64);
            assert_eq!((c.get)(&s), 10 + i as u64);
            assert_eq!(s.count(c.name), Some(10 + i as u64));
        }
        let mut sum = s;
        sum += s;
        assert!(COUNTERS.iter().all(|c| (c.get)(&sum) == 2 * (c.get)(&s)));
        assert_eq!(s.count("wall_s"), None);
    }
}
