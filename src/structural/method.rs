//! One interface over the structural integrators, so that a family's run loop is written once
//! and monomorphised per method (static dispatch, no allocation per step): [`Method`] for
//! systems of type `S`, implemented in their own files by `Newmark`, `Hht` and `GenAlpha` for
//! every [`SecondOrder`] system and every path-dependent structure ([`Path`]: the fiber
//! column's dynamic scene), by `GenAlphaI3` for every [`Constraints`] system and by
//! `Midpoint` (energy-consistent) for path-dependent structures. What a kind of system
//! brings for every method, its state and its consistent start, is [`Structural`].
//!
//! Each method writes its `NAME` and its `step` (the equations and orders are in its file,
//! the checks that open and close a step in `newton`); what the four share beyond that is
//! written here once, as provided methods: `init` is the consistent start (I1)/(I2) of
//! `init.rs` under the method's name, `info` the facts of the family, and `new_state` a
//! state without multipliers. The constrained method overrides `init` (the start (I3),
//! which also fixes the multipliers) and `new_state` (room for them). On failure the state
//! is unchanged.
//!
//! `init` and `step` of a concrete method need this trait in scope; where nothing names the
//! system (a method's `info` alone) the call names it, as `Method::<Fe>::info(&m)`.
//!
//! [`Constraints`]: super::Constraints
//! [`Path`]: super::path_step::Path
use super::SecondOrder;
use super::equilibrium::Equilibrium;
use super::path::PathDependent;
use super::path_step::{Path, Series};
use super::state::State;
use crate::integrate::{Failure, MethodInfo, MethodKind, Stats};

/// A kind of system the structural methods run on: its state and its consistent start.
/// Every [`SecondOrder`] system is one (the start (I1)/(I2) of `init.rs`), and so is every
/// path-dependent structure with mass and load ([`Path`]: `q` its displacements, the
/// accelerations from `M a_0 = p s(t_0) - C v_0`).
pub trait Structural {
    /// A state sized for the system.
    fn new_state(&self) -> State;

    /// Consistent initial accelerations at `t0` from `state.q`, `state.v` (for a path, `q`
    /// is read from the structure); `method` names the caller in a failure.
    fn start(
        &mut self,
        t0: f64,
        state: &mut State,
        stats: &mut Stats,
        method: &str,
    ) -> Result<(), Failure>;
}

impl<S: SecondOrder + ?Sized> Structural for S {
    fn new_state(&self) -> State {
        State::for_system(self)
    }

    fn start(
        &mut self,
        t0: f64,
        state: &mut State,
        stats: &mut Stats,
        method: &str,
    ) -> Result<(), Failure> {
        super::init::acceleration(&*self, t0, state, stats, method)
    }
}

impl<S: PathDependent, E: Equilibrium<S>, G: Series> Structural for Path<S, E, G> {
    fn new_state(&self) -> State {
        State::new(self.system.dim(), 0)
    }

    fn start(
        &mut self,
        t0: f64,
        state: &mut State,
        _stats: &mut Stats,
        _method: &str,
    ) -> Result<(), Failure> {
        self.start_from_equilibrium(t0, state);
        Ok(())
    }
}

/// A structural integrator for systems of type `S`.
///
/// # Example
///
/// ```
/// use mbdbench::structural::method::Method;
/// use mbdbench::structural::newmark::Newmark;
/// use mbdbench::structural::newton::NewtonOptions;
/// use mbdbench::structural::SecondOrder;
///
/// fn order<S: SecondOrder, M: Method<S>>(m: &M) -> u32 {
///     m.info().order
/// }
/// # struct Unit;
/// # impl SecondOrder for Unit {
/// #     fn dim(&self) -> usize { 1 }
/// #     fn residual(&self, _: f64, q: &nalgebra::DVector<f64>, _: &nalgebra::DVector<f64>,
/// #         a: &nalgebra::DVector<f64>, r: &mut nalgebra::DVector<f64>) { r[0] = a[0] + q[0]; }
/// #     fn tangent(&self, _: f64, _: &nalgebra::DVector<f64>, _: &nalgebra::DVector<f64>,
/// #         _: &nalgebra::DVector<f64>, c_m: f64, _: f64, c_k: f64, s: &mut nalgebra::DMatrix<f64>) {
/// #         s[(0, 0)] = c_m + c_k;
/// #     }
/// # }
/// let m = Newmark::new(NewtonOptions::default()).unwrap();
/// assert_eq!(order::<Unit, _>(&m), 2);
/// assert_eq!(Method::<Unit>::info(&m).name, "newmark");
/// ```
pub trait Method<S: Structural + ?Sized> {
    /// The method's name, in its `info` and in its failures.
    const NAME: &'static str;

    /// Consistent initial accelerations (and multipliers) at `t0` from `state.q`, `state.v`.
    /// Provided: the system's [`Structural::start`] into `state.a` and `state.aux`
    /// (`a_0 = qdd_0`); the constrained method solves (I3) instead.
    ///
    /// # Panics
    ///
    /// If `state` is not sized for `sys` ([`Method::new_state`]).
    fn init(
        &mut self,
        sys: &mut S,
        t0: f64,
        state: &mut State,
        stats: &mut Stats,
    ) -> Result<(), Failure> {
        sys.start(t0, state, stats, Self::NAME)
    }

    /// One step from `t` to `t + h`; on failure `state` is unchanged (and a path-dependent
    /// structure reverted).
    ///
    /// # Panics
    ///
    /// If `state` is not sized for `sys` ([`Method::new_state`]).
    fn step(
        &mut self,
        sys: &mut S,
        t: f64,
        h: f64,
        state: &mut State,
        stats: &mut Stats,
    ) -> Result<(), Failure>;

    /// What the method is. Provided, the same for the four but for the name: order 2, one
    /// implicit stage, neither symplectic nor energy-conserving in general (Newmark conserves
    /// a linear system's energy only), fixed step, of kind `structural`.
    fn info(&self) -> MethodInfo {
        MethodInfo::new(Self::NAME, MethodKind::Structural, 2).with_implicit(true)
    }

    /// A state sized for `sys`. Provided: the system's ([`Structural::new_state`], without
    /// multipliers); the constrained method makes room for them.
    fn new_state(&self, sys: &S) -> State {
        sys.new_state()
    }
}
