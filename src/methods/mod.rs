//! The method face for first-order systems: how a time integrator is written **once** and
//! then run on every system of every family that offers one (the rigid body's eleven charts in
//! both formulations, the flexible beam's ODE forms), monomorphised per system as if it had been
//! called directly (no dynamic dispatch per step).
//!
//! A method is written as a *factory over systems*:
//! - a fixed-step method implements [`FixedStepMethod`]: for every [`System`] `S` it names the
//!   stepper type `On<S>` (an [`FixedStep<S>`], the one-step map `x_{n+1} = Phi_h(x_n)`) and
//!   builds one (`on::<S>()`), holding whatever workspace of `S`'s sizes it needs;
//! - an adaptive method implements [`AdaptiveMethod`]: `On<S>` is an [`Adaptive<S>`] built at a
//!   tolerance (`on::<S>(tol)`), for every system with an error scale ([`ErrorScale`]).
//!
//! [`Fixed`] and [`Tolerance`] wrap them into the one face a family calls, [`OdeMethod`]: the
//! method's facts on a system type (`info::<S>()`, which may depend on `S`: RK4 is RKMK4, a
//! Lie-group method, on a Lie-group chart) and one run of it (`run::<S>()`, through the
//! suite's run loops `run::run_fixed` and `run::run_adaptive`, which count the work, observe on
//! the grid and enforce the limits). A family instantiates each method it is handed for each of
//! its system types (`model::rigid_body::registry`, `model::flexible_beam::family`); the
//! built-in generic methods reach every family through the one list [`builtin::each`], so a
//! method written outside the crate and a built-in take the same path.
//!
//! Invariants: `info::<S>().name` is the name the method is listed under (checked where a
//! family builds its table); a fixed-step method's `run` refuses a tolerance and an adaptive
//! one's a step (an error, not a panic). What a method must uphold beyond the traits (typed
//! failures, the work counters, no allocation per step where the built-ins have none) is
//! `docs/library.md`.
//!
//! # Example
//!
//! Heun's method (explicit trapezoidal rule, order 2) written once, run on a harmonic
//! oscillator through the face a family calls:
//!
//! ```
//! use mbdbench::integrate::{Failure, FailureKind, FixedStep, MethodInfo, MethodKind, Stats, System};
//! use mbdbench::math::vector::Vector;
//! use mbdbench::methods::{Fixed, FixedStepMethod, OdeMethod};
//! use mbdbench::run::{Grid, Observe, Stepping};
//! use mbdbench::integrate::Limits;
//! # use nalgebra::Vector2;
//! # #[derive(Clone)]
//! # struct Oscillator;
//! # impl System for Oscillator {
//! #     type State = Vector2<f64>;
//! #     type Tangent = Vector2<f64>;
//! #     const LIE: bool = false;
//! #     fn rhs(&self, _t: f64, x: &Vector2<f64>) -> Vector2<f64> { Vector2::new(x[1], -x[0]) }
//! #     fn retract(&self, x: &Vector2<f64>, dx: &Vector2<f64>) -> Vector2<f64> { x + dx }
//! #     fn check(&self, t: f64, x: &Vector2<f64>) -> Result<(), Failure> {
//! #         if x.iter().all(|v| v.is_finite()) { Ok(()) }
//! #         else { Err(Failure::new(FailureKind::NonFinite, t, "non-finite")) }
//! #     }
//! # }
//! # impl mbdbench::integrate::adaptive_rk::ErrorScale for Oscillator {
//! #     fn coords(&self, x: &Vector2<f64>) -> Vector2<f64> { *x }
//! # }
//! # impl mbdbench::run::Observable for Oscillator {
//! #     type Obs = Vector2<f64>;
//! #     fn observe(&self, x: &Vector2<f64>) -> Vector2<f64> { *x }
//! #     fn residual(&self, _x: &Vector2<f64>) -> Option<f64> { None }
//! #     fn energy(&self, o: &Vector2<f64>) -> f64 { 0.5 * o.norm_squared() }
//! # }
//!
//! /// Heun's method on any system (additive only: no `dexp_inv`, so order 1 on a Lie group).
//! struct Heun;
//! struct HeunOn<S>(std::marker::PhantomData<S>);
//! impl<S: System> FixedStep<S> for HeunOn<S> {
//!     fn info(&self) -> MethodInfo {
//!         MethodInfo::new("heun", MethodKind::Explicit, 2).with_stages(2)
//!     }
//!     fn step(&mut self, sys: &S, t: f64, h: f64, x: &mut S::State, stats: &mut Stats)
//!         -> Result<(), Failure> {
//!         let k1 = sys.rhs(t, x);
//!         let k2 = sys.rhs(t + h, &sys.retract(x, &k1.scaled(h)));
//!         stats.rhs_evals += 2;
//!         let mut dx = k1.scaled(0.5 * h);
//!         dx.axpy(0.5 * h, &k2);
//!         *x = sys.retract(x, &dx);
//!         Ok(())
//!     }
//! }
//! impl FixedStepMethod for Heun {
//!     type On<S: System> = HeunOn<S>;
//!     fn on<S: System>(&self) -> HeunOn<S> {
//!         HeunOn(std::marker::PhantomData)
//!     }
//! }
//!
//! let m = Fixed(Heun);
//! assert_eq!(m.info::<Oscillator>().order, 2);
//! let grid = Grid { t_end: 1.0, score_every: 0.5, sample_every: 0.5 };
//! let out = m
//!     .run(&Oscillator, Vector2::new(1.0, 0.0), Stepping::Dt(1e-3), &grid,
//!          &Limits::default(), &Observe::Final)
//!     .unwrap();
//! let x = out.samples.last().unwrap().obs;
//! assert!((x[0] - 1f64.cos()).abs() < 1e-6);
//! assert_eq!(out.stats.steps, 1000);
//! // A fixed-step method is not run at a tolerance.
//! assert!(m.run(&Oscillator, Vector2::new(1.0, 0.0), Stepping::Tol(1e-6), &grid,
//!     &Limits::default(), &Observe::Final).is_err());
//! ```
use crate::integrate::adaptive_rk::ErrorScale;
use crate::integrate::{Adaptive, FixedStep, Limits, MethodInfo, System};
use crate::run::{
    Grid, Observable, Observe, RunOutput, Stepping, Watched, run_adaptive, run_fixed,
};

pub mod builtin;
pub mod second_order;
#[cfg(test)]
mod tests;

/// A fixed-step method written once for every system: `On<S>` steps systems of type `S`.
pub trait FixedStepMethod: Send + Sync + 'static {
    /// The stepper on systems of type `S`.
    type On<S: System>: FixedStep<S>;
    /// A fresh stepper for a run on a system of type `S` (its workspace sized for `S`).
    fn on<S: System>(&self) -> Self::On<S>;
}

/// An adaptive method written once for every system with an error scale: `On<S>` advances
/// systems of type `S` under its own step control at tolerance `tol`.
pub trait AdaptiveMethod: Send + Sync + 'static {
    /// The integrator on systems of type `S`.
    type On<S: ErrorScale>: Adaptive<S>;
    /// A fresh integrator at tolerance `tol` for a run on a system of type `S`.
    fn on<S: ErrorScale>(&self, tol: f64) -> Self::On<S>;
}

/// What a family's first-order systems offer every method: its run loops' observation, an
/// error scale for adaptive step control, and copies for the adaptive runs' watcher.
pub trait OdeSystem: Observable + ErrorScale + Clone {}
impl<S: Observable + ErrorScale + Clone> OdeSystem for S {}

/// The face a family calls: a method's facts on a system type and one run of it.
pub trait OdeMethod: Send + Sync + 'static {
    /// The method's facts on systems of type `S` (its name, order, kind; `lie_group` and
    /// `symplectic` may depend on `S`).
    fn info<S: OdeSystem>(&self) -> MethodInfo;
    /// Whether a run takes a tolerance (`Stepping::Tol`) rather than a step.
    fn adaptive(&self) -> bool;
    /// One run from `x0` over `grid`, observed as `observe` says; `Err` when it cannot start
    /// (a step that does not divide the horizon, a stepping of the wrong kind).
    fn run<S: OdeSystem>(
        &self,
        sys: &S,
        x0: S::State,
        stepping: Stepping,
        grid: &Grid,
        limits: &Limits,
        observe: &Observe,
    ) -> Result<RunOutput<S::Obs>, String>;

    /// The stepping of a ladder value: a tolerance for an adaptive method, else a step.
    fn stepping(&self, value: f64) -> Stepping {
        if self.adaptive() {
            Stepping::Tol(value)
        } else {
            Stepping::Dt(value)
        }
    }
}

/// A fixed-step method behind the face.
#[derive(Debug, Clone, Copy, Default)]
pub struct Fixed<M>(pub M);

/// An adaptive method behind the face.
#[derive(Debug, Clone, Copy, Default)]
pub struct Tolerance<M>(pub M);

impl<M: FixedStepMethod> OdeMethod for Fixed<M> {
    fn info<S: OdeSystem>(&self) -> MethodInfo {
        FixedStep::<S>::info(&self.0.on::<S>())
    }
    fn adaptive(&self) -> bool {
        false
    }
    fn run<S: OdeSystem>(
        &self,
        sys: &S,
        x0: S::State,
        stepping: Stepping,
        grid: &Grid,
        limits: &Limits,
        observe: &Observe,
    ) -> Result<RunOutput<S::Obs>, String> {
        match stepping {
            Stepping::Dt(h) => {
                let mut m = self.0.on::<S>();
                run_fixed(sys, &mut m, x0, h, grid, limits, observe)
            }
            Stepping::Tol(tol) => Err(format!(
                "{} is a fixed-step method: it takes a step, not a tolerance ({tol:e})",
                self.info::<S>().name
            )),
        }
    }
}

impl<M: AdaptiveMethod> OdeMethod for Tolerance<M> {
    fn info<S: OdeSystem>(&self) -> MethodInfo {
        // The facts do not depend on the tolerance; the runs' watcher is part of the system.
        Adaptive::<Watched<S>>::info(&self.0.on::<Watched<S>>(1.0e-6))
    }
    fn adaptive(&self) -> bool {
        true
    }
    fn run<S: OdeSystem>(
        &self,
        sys: &S,
        x0: S::State,
        stepping: Stepping,
        grid: &Grid,
        limits: &Limits,
        observe: &Observe,
    ) -> Result<RunOutput<S::Obs>, String> {
        match stepping {
            Stepping::Tol(tol) => {
                let mut m = self.0.on::<Watched<S>>(tol);
                run_adaptive(sys, &mut m, x0, grid, limits, observe)
            }
            Stepping::Dt(h) => Err(format!(
                "{} is an adaptive method: it takes a tolerance, not a step ({h:e})",
                self.info::<S>().name
            )),
        }
    }
}

/// Where a method applies among the systems a family offers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Where {
    /// On every system.
    Everywhere,
    /// On Lie-group systems only (`System::LIE`): the Crouch-Grossman methods, which freeze
    /// the vector field along the group's exponential.
    LieGroup,
}

impl Where {
    /// Whether the method applies to systems of type `S`.
    pub fn admits<S: System>(self) -> bool {
        match self {
            Where::Everywhere => true,
            Where::LieGroup => S::LIE,
        }
    }
}

/// What instantiates methods: a family building its variants visits every method of a list
/// (`builtin::each`), each with its name and where it applies.
pub trait Visit {
    /// One method: `name` is the name its records carry (the integrator axis).
    fn method<M: OdeMethod>(&mut self, name: &'static str, at: Where, m: M);
}

/// A shared method is the method: a catalogue hands one registered method to every family.
impl<M: OdeMethod> OdeMethod for std::sync::Arc<M> {
    fn info<S: OdeSystem>(&self) -> MethodInfo {
        (**self).info::<S>()
    }
    fn adaptive(&self) -> bool {
        (**self).adaptive()
    }
    fn run<S: OdeSystem>(
        &self,
        sys: &S,
        x0: S::State,
        stepping: Stepping,
        grid: &Grid,
        limits: &Limits,
        observe: &Observe,
    ) -> Result<RunOutput<S::Obs>, String> {
        (**self).run(sys, x0, stepping, grid, limits, observe)
    }
}
