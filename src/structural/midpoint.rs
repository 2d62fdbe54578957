//! `midpoint`: the energy-consistent midpoint rule for path-dependent structures
//! ([`Path::midpoint_step`]; the equations are in `path_step.rs`): the velocity is the
//! displacement's difference quotient, the internal force the trapezoid of the step's end
//! forces corrected so that its work over the step is the elements' own work, so the
//! structure's energy balance (kinetic + strain + dissipated = input) closes to the Newton
//! tolerance at every step, whatever the material does.
//!
//! Order 2 (the correction is `O(h^3)` per step; without it the rule is Newmark's average
//! acceleration, `dynamic_tests.rs` of the fiber column measures both); no numerical
//! dissipation. It needs the elements' work, so it runs on path-dependent structures only
//! (a second-order system has no element work to be consistent with). Where it fails: the
//! inner solver's failures (`equilibrium.rs`), the step then reverted; the correction is left
//! out of the tangent, so Newton converges linearly once it dominates the residual (not
//! seen at the steps the suite runs).
use super::equilibrium::Equilibrium;
use super::method::Method;
use super::path::PathDependent;
use super::path_step::{Path, Series};
use super::state::State;
use crate::integrate::{Failure, MethodInfo, MethodKind, Stats};

/// The method's name (`Method::NAME`).
pub const NAME: &str = "midpoint";

/// The energy-consistent midpoint rule (module docs).
///
/// # Example
///
/// A unit mass on a spring of stiffness 4 under a ground pulse: at every step the energy
/// (kinetic plus the spring's work) equals the pulse's work to round-off, and the facts say
/// order 2, energy-conserving.
///
/// ```
/// use mbdbench::integrate::Stats;
/// use mbdbench::structural::equilibrium::Newton;
/// use mbdbench::structural::method::Method;
/// use mbdbench::structural::midpoint::Midpoint;
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
/// let ground = |t: f64| (3.0 * t).sin();
/// let newton = Newton::new(1e-24, 20).unwrap();
/// let mut p = Path::new(spring, newton, one.clone(), 0.0, 0.0 * &one, -&one, ground).unwrap();
/// let (mut m, mut stats) = (Midpoint, Stats::default());
/// let mut st = Method::new_state(&m, &p);
/// m.init(&mut p, 0.0, &mut st, &mut stats).unwrap();
/// for k in 0..300 {
///     m.step(&mut p, k as f64 * 0.05, 0.05, &mut st, &mut stats).unwrap();
///     let balance = p.kinetic() + p.system.work() - p.input();
///     assert!(balance.abs() < 1e-12, "step {k}: {balance:e}");
/// }
/// let info = Method::<Path<Spring, Newton, fn(f64) -> f64>>::info(&m);
/// assert_eq!((info.name, info.order, info.energy_conserving), ("midpoint", 2, true));
/// ```
#[derive(Debug, Clone, Copy, Default)]
pub struct Midpoint;

impl<S: PathDependent, E: Equilibrium<S>, G: Series> Method<Path<S, E, G>> for Midpoint {
    const NAME: &'static str = NAME;

    fn step(
        &mut self,
        sys: &mut Path<S, E, G>,
        t: f64,
        h: f64,
        state: &mut State,
        stats: &mut Stats,
    ) -> Result<(), Failure> {
        sys.midpoint_step(t, h, state, stats, NAME)
    }

    /// The structural methods' facts, energy-conserving.
    fn info(&self) -> MethodInfo {
        MethodInfo::new(NAME, MethodKind::Structural, 2)
            .with_implicit(true)
            .with_energy_conserving(true)
    }
}
