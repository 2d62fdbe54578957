//! One interface over the structural integrators, so that a family's run loop is written once
//! and monomorphised per method (static dispatch, no allocation per step): [`Method`] for
//! systems of type `S`, implemented by `Newmark`, `Hht` and `GenAlpha` for every
//! [`SecondOrder`] system and by `GenAlphaI3` for every [`Constraints`] system. Each call
//! delegates to the method's own `init`, `step` and `info` (their equations and orders are in
//! their files); on failure the state is unchanged.
use super::gen_alpha::GenAlpha;
use super::gen_alpha_i3::GenAlphaI3;
use super::hht::Hht;
use super::newmark::Newmark;
use super::state::State;
use super::{Constraints, SecondOrder};
use crate::integrate::{Failure, MethodInfo, Stats};

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
/// ```
pub trait Method<S: ?Sized> {
    /// Consistent initial accelerations (and multipliers) at `t0` from `state.q`, `state.v`.
    fn init(
        &mut self,
        sys: &S,
        t0: f64,
        state: &mut State,
        stats: &mut Stats,
    ) -> Result<(), Failure>;
    /// One step from `t` to `t + h`.
    fn step(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        state: &mut State,
        stats: &mut Stats,
    ) -> Result<(), Failure>;
    /// What the method is.
    fn info(&self) -> MethodInfo;
    /// A state sized for `sys` (with multipliers for a constrained method).
    fn new_state(&self, sys: &S) -> State;
}

/// `Method<S>` for a method whose own `init`, `step` and `info` take every `S` with the
/// bound `$bound`, and whose state has the multipliers `$state` makes room for.
macro_rules! method {
    ($t:ty, $bound:path, $state:ident) => {
        impl<S: $bound + ?Sized> Method<S> for $t {
            fn init(
                &mut self,
                sys: &S,
                t0: f64,
                state: &mut State,
                stats: &mut Stats,
            ) -> Result<(), Failure> {
                <$t>::init(self, sys, t0, state, stats)
            }
            fn step(
                &mut self,
                sys: &S,
                t: f64,
                h: f64,
                state: &mut State,
                stats: &mut Stats,
            ) -> Result<(), Failure> {
                <$t>::step(self, sys, t, h, state, stats)
            }
            fn info(&self) -> MethodInfo {
                <$t>::info(self)
            }
            fn new_state(&self, sys: &S) -> State {
                State::$state(sys)
            }
        }
    };
}
method!(Newmark, SecondOrder, for_system);
method!(Hht, SecondOrder, for_system);
method!(GenAlpha, SecondOrder, for_system);
method!(GenAlphaI3, Constraints, for_constrained);
