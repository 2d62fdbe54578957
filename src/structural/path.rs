//! `path`: the second kind of structural system, a structure whose internal force depends on
//! the path it was loaded along (plastic fibers, cracked concrete), solved in displacement
//! increments from its last committed state, as OpenSees' domain is (McKenna, Fenves & Scott,
//! "Open system for earthquake engineering simulation", 2000: `update`, `commitState`,
//! `revertToLastCommit`).
//!
//! A [`PathDependent`] system holds a *trial* configuration and trial element states beside
//! the committed ones. A solution algorithm ([`super::equilibrium`]) moves the trial
//! configuration by increments `dx` (the additive unknowns, translations, by addition; the
//! rotational ones through a chart's retraction, so a rotation unknown has no value of its
//! own, only increments), asks for the internal force `f_int` and tangent stiffness `K` there
//! (`assemble`, a state determination of every element), and once the step's equation holds
//! commits the trial states (or reverts to the committed ones). Its step's equation is
//!
//! ```text
//! (P1)  w f_int(u) + (1 - w) f_int(u_n) - F + M (a(u) + a0 v(u)) = 0,
//!       a(u) = c_a (u - u_pred),   v(u) = v_pred + c_v a(u),
//! ```
//!
//! a static equilibrium without the inertia terms ([`super::equilibrium::Inertia`]), and a
//! time step of the Newmark family with them (the methods' files give `w`, `c_a`, `c_v` and the
//! predictors; [`Path`] runs them). Mass is lumped and carried by additive unknowns only;
//! damping is mass-proportional (`C = a0 M`).
//!
//! Invariants: between steps the trial state equals the committed one; `assemble` leaves
//! `internal_force` and `stiffness` those of the trial state, and `apply` makes them stale.
//! Where it fails: an element whose state determination fails, or a budget spent, ends the
//! step with a typed [`PathFailure`]; the system then reverts.
use nalgebra::{DMatrix, DVector};

/// Why a step of a path-dependent system failed.
#[derive(Debug, Clone, PartialEq)]
pub enum PathFailure {
    /// No convergence within the iteration limit.
    NoConvergence { iterations: usize, energy: f64 },
    /// An element's state determination failed (its index and why).
    Element { element: usize, failure: String },
    /// The tangent is singular.
    SingularTangent,
    /// The run's budget is spent (the message names the key).
    WorkLimit(String),
}

impl std::fmt::Display for PathFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NoConvergence { iterations, energy } => write!(
                f,
                "Newton did not converge in {iterations} iterations (last energy {energy:e} J)"
            ),
            Self::Element { element, failure } => write!(f, "element {element}: {failure}"),
            Self::SingularTangent => write!(f, "singular tangent"),
            Self::WorkLimit(why) => write!(f, "{why}"),
        }
    }
}

impl PathFailure {
    /// The suite's failure at `t`: `work_limit` for a spent budget, `newton_failure`
    /// otherwise, with this failure's message.
    pub fn at(self, t: f64) -> crate::integrate::Failure {
        use crate::integrate::{Failure, FailureKind};
        let kind = match self {
            PathFailure::WorkLimit(_) => FailureKind::WorkLimit,
            _ => FailureKind::NewtonFailure,
        };
        Failure::new(kind, t, self.to_string())
    }
}

/// One prescribed displacement (displacement control): the unknown and its target value.
#[derive(Debug, Clone, Copy)]
pub struct Prescribed {
    pub dof: usize,
    pub value: f64,
}

/// A structure solved in increments from its committed state (module docs).
///
/// # Example
///
/// A spring that yields at 1 N (elastic-perfectly plastic, stiffness 10 N/m) pulled to
/// 0.3 m by displacement control, then unloaded to zero force: the set that stays is the
/// path's memory.
///
/// ```
/// use mbdbench::structural::equilibrium::{Equilibrium, Newton};
/// use mbdbench::structural::path::{PathDependent, PathFailure, Prescribed};
/// use nalgebra::{DMatrix, DVector};
///
/// struct Yielding { u: f64, plastic: f64, committed: (f64, f64), f: DVector<f64>,
///                   k: DMatrix<f64>, fresh: bool }
/// impl Yielding {
///     fn trial_plastic(&self) -> f64 {
///         let s = 10.0 * (self.u - self.committed.1);
///         if s.abs() > 1.0 { self.u - s.signum() * 0.1 } else { self.committed.1 }
///     }
/// }
/// impl PathDependent for Yielding {
///     fn dim(&self) -> usize { 1 }
///     fn assemble(&mut self) -> Result<(), PathFailure> {
///         self.plastic = self.trial_plastic();
///         let yielding = self.plastic != self.committed.1;
///         self.f[0] = 10.0 * (self.u - self.plastic);
///         self.k[(0, 0)] = if yielding { 0.0 } else { 10.0 };
///         self.fresh = true;
///         Ok(())
///     }
///     fn assembled(&self) -> bool { self.fresh }
///     fn internal_force(&self) -> &DVector<f64> { &self.f }
///     fn stiffness(&self) -> &DMatrix<f64> { &self.k }
///     fn apply(&mut self, dx: &DVector<f64>, eta: f64) { self.u += dx[0] * eta; self.fresh = false; }
///     fn mark(&mut self) {}
///     fn return_to_mark(&mut self) {}
///     fn commit(&mut self) { self.committed = (self.u, self.plastic); self.fresh = false; }
///     fn revert(&mut self) { (self.u, self.plastic) = self.committed; self.fresh = false; }
///     fn additive(&self, _: usize) -> bool { true }
///     fn displacement(&self, _: usize) -> f64 { self.u }
///     fn committed_displacement(&self, _: usize) -> f64 { self.committed.0 }
///     fn work(&self) -> f64 { 0.0 }
/// }
/// let mut s = Yielding { u: 0.0, plastic: 0.0, committed: (0.0, 0.0),
///     f: DVector::zeros(1), k: DMatrix::zeros(1, 1), fresh: false };
/// let mut newton = Newton::new(1e-20, 20).unwrap();
/// let zero = DVector::zeros(1);
/// newton.step(&mut s, &zero, Some(Prescribed { dof: 0, value: 0.3 }), None).unwrap();
/// assert!((s.internal_force()[0] - 1.0).abs() < 1e-12);
/// newton.step(&mut s, &zero, None, None).unwrap();
/// assert!((s.displacement(0) - 0.2).abs() < 1e-12);
/// ```
pub trait PathDependent {
    /// The number of unknowns.
    fn dim(&self) -> usize;

    /// A state determination of every element at the trial configuration: `internal_force`
    /// and `stiffness` become those of the trial state.
    fn assemble(&mut self) -> Result<(), PathFailure>;

    /// Whether the last assembly is that of the current trial configuration and states.
    fn assembled(&self) -> bool;

    /// `f_int` of the last assembly (length `dim`).
    fn internal_force(&self) -> &DVector<f64>;

    /// `K = df_int/du` of the last assembly (`dim x dim`).
    fn stiffness(&self) -> &DMatrix<f64>;

    /// Moves the trial configuration by `eta dx` (additive unknowns added, rotational ones
    /// retracted); the assembly becomes stale.
    fn apply(&mut self, dx: &DVector<f64>, eta: f64);

    /// Keeps the trial configuration, for a line search to return to.
    fn mark(&mut self);

    /// Returns the trial configuration to the last `mark`.
    fn return_to_mark(&mut self);

    /// The trial state becomes the committed one.
    fn commit(&mut self);

    /// The trial state returns to the committed one.
    fn revert(&mut self);

    /// Whether unknown `i` is additive (a translation, whose displacement is a number); only
    /// additive unknowns may carry mass, load work or be prescribed.
    fn additive(&self, i: usize) -> bool;

    /// The trial displacement of additive unknown `i` from the reference configuration.
    fn displacement(&self, i: usize) -> f64;

    /// The committed displacement of additive unknown `i`.
    fn committed_displacement(&self, i: usize) -> f64;

    /// The work done on the elements since their virgin state at the trial configuration
    /// (their own quadrature), for the energy-consistent midpoint rule.
    fn work(&self) -> f64;

    /// Called once per Newton iteration before it assembles: a budget may stop the step.
    fn iteration(&mut self) -> Result<(), PathFailure> {
        Ok(())
    }

    /// The inner iterations done so far (e.g. force-based elements' own), cumulative; 0 by
    /// default.
    fn inner_iterations(&self) -> u64 {
        0
    }
}
