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
/// Its facts: order 2, energy-conserving.
///
/// ```
/// use mbdbench::structural::equilibrium::Newton;
/// use mbdbench::structural::method::Method;
/// use mbdbench::structural::midpoint::Midpoint;
/// use mbdbench::structural::path_step::Path;
/// use mbdbench::model::fiber_column::column::Column;
/// use mbdbench::rotation::So3;
///
/// type P = Path<Column<So3>, Newton, fn(f64) -> f64>;
/// let info = Method::<P>::info(&Midpoint);
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
