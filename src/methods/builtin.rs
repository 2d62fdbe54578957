//! The built-in generic first-order methods as factories over systems, and the one list that
//! hands them to every family ([`each`]): explicit Euler and classical RK4 (`integrate::
//! explicit_rk`, RKMK on Lie groups: Munthe-Kaas, BIT 38, 1998), the Gauss collocation
//! methods of order 2 and 6 (`integrate::implicit_rk`), Dormand-Prince 5(4) and 8(5,3)
//! (`integrate::adaptive_rk`, Hairer-Norsett-Wanner I, II.4-II.5) and the Crouch-Grossman
//! methods Lie-Euler and CG3 (`integrate::crouch_grossman`, Crouch & Grossman, J. Nonlinear
//! Sci. 3, 1993), which apply on Lie-group systems only ([`Where::LieGroup`]).
//!
//! Each factory builds exactly the stepper the families built by hand before it (same tableau,
//! same Newton options), so every result is bit-identical to a direct call; the order of
//! [`each`] is the report order of the integrators.
//!
//! # Example
//!
//! ```
//! use mbdbench::methods::{builtin, OdeMethod, Visit, Where};
//! struct Names(Vec<(&'static str, Where)>);
//! impl Visit for Names {
//!     fn method<M: OdeMethod>(&mut self, name: &'static str, at: Where, _m: M) {
//!         self.0.push((name, at));
//!     }
//! }
//! let mut n = Names(vec![]);
//! builtin::each(&mut n);
//! assert_eq!(n.0[1], ("rk4", Where::Everywhere));
//! assert!(n.0.contains(&("cg3", Where::LieGroup)));
//! ```
use super::{AdaptiveMethod, Fixed, FixedStepMethod, Tolerance, Visit, Where};
use crate::integrate::System;
use crate::integrate::adaptive_rk::{AdaptiveRk, ErrorScale};
use crate::integrate::crouch_grossman::{Cg3Tableau, CrouchGrossman, LieEulerTableau};
use crate::integrate::explicit_rk::{EulerTableau, ExplicitRk, Rk4Tableau};
use crate::integrate::implicit_rk::ImplicitRk;

/// A unit type for a fixed-step method built by `$ctor` as `$ty` (a type in `S`).
macro_rules! fixed_factory {
    ($name:ident, $ty:ty, $ctor:path, $doc:literal) => {
        #[doc = $doc]
        #[derive(Debug, Clone, Copy, Default)]
        pub struct $name;
        impl FixedStepMethod for $name {
            type On<S: System> = $ty;
            fn on<S: System>(&self) -> Self::On<S> {
                $ctor()
            }
        }
    };
}

/// A unit type for an adaptive Runge-Kutta pair built by `AdaptiveRk::$ctor`.
macro_rules! adaptive_factory {
    ($name:ident, $ctor:ident, $doc:literal) => {
        #[doc = $doc]
        #[derive(Debug, Clone, Copy, Default)]
        pub struct $name;
        impl AdaptiveMethod for $name {
            type On<S: ErrorScale> = AdaptiveRk<S>;
            fn on<S: ErrorScale>(&self, tol: f64) -> AdaptiveRk<S> {
                AdaptiveRk::$ctor(tol)
            }
        }
    };
}

fixed_factory!(
    Euler,
    ExplicitRk<S, EulerTableau>,
    ExplicitRk::euler,
    "Explicit (Lie-)Euler, order 1."
);
fixed_factory!(
    Rk4,
    ExplicitRk<S, Rk4Tableau>,
    ExplicitRk::rk4,
    "Classical RK4 (RKMK4 on a Lie group)."
);
fixed_factory!(
    ImplicitMidpoint,
    ImplicitRk<S>,
    ImplicitRk::implicit_midpoint,
    "The implicit midpoint rule (1-stage Gauss), order 2."
);
fixed_factory!(
    Gauss6,
    ImplicitRk<S>,
    ImplicitRk::gauss6,
    "3-stage Gauss collocation, order 6."
);
fixed_factory!(
    LieEuler,
    CrouchGrossman<S, LieEulerTableau>,
    CrouchGrossman::lie_euler,
    "Lie-Euler (Crouch-Grossman, order 1)."
);
fixed_factory!(
    Cg3,
    CrouchGrossman<S, Cg3Tableau>,
    CrouchGrossman::cg3,
    "Crouch-Grossman CG3, order 3."
);
adaptive_factory!(Dopri5, dopri5, "Dormand-Prince 5(4) with dense output.");
adaptive_factory!(Dop853, dop853, "Dormand-Prince 8(5,3) with dense output.");

/// Hands every built-in generic method to `v`, in the integrators' report order.
pub fn each(v: &mut impl Visit) {
    v.method("euler", Where::Everywhere, Fixed(Euler));
    v.method("rk4", Where::Everywhere, Fixed(Rk4));
    v.method("dopri5", Where::Everywhere, Tolerance(Dopri5));
    v.method("dop853", Where::Everywhere, Tolerance(Dop853));
    v.method(
        "implicit_midpoint",
        Where::Everywhere,
        Fixed(ImplicitMidpoint),
    );
    v.method("gauss6", Where::Everywhere, Fixed(Gauss6));
    v.method("lie_euler", Where::LieGroup, Fixed(LieEuler));
    v.method("cg3", Where::LieGroup, Fixed(Cg3));
}
