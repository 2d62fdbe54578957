//! Tests of the method face: a method written once outside the built-ins (Kutta's
//! third-order Runge-Kutta, as RKMK on Lie groups) keeps its order on an additive system and
//! on the rigid body's Lie-group chart; the built-in factories behind the face give the
//! numbers of a direct call bit for bit; a stepping of the wrong kind is an error; and the
//! applicability rule admits the Lie-group methods on Lie-group systems only.
use super::builtin::{Dopri5, Rk4};
use super::*;
use crate::integrate::adaptive_rk::AdaptiveRk;
use crate::integrate::explicit_rk::ExplicitRk;
use crate::integrate::test_support::{
    Oscillator, assert_last_order, rotor_distance, rotor_initial, rotor_reference, rotor_system,
};
use crate::integrate::{Failure, MethodKind, Stats};
use crate::math::vector::Vector;
use crate::model::rigid_body::RigidSystem;
use crate::rotation::{Body, Quat};
use std::marker::PhantomData;

/// Kutta's third-order method (c = 0, 1/2, 1; a31 = -1, a32 = 2; b = 1/6, 2/3, 1/6),
/// written as a user would: once, for every system, with the Munthe-Kaas correction on a Lie
/// group.
struct Kutta3;
struct Kutta3On<S>(PhantomData<S>);

impl<S: System> FixedStep<S> for Kutta3On<S> {
    fn info(&self) -> MethodInfo {
        MethodInfo::new("kutta3", MethodKind::Explicit, 3)
            .with_stages(3)
            .with_lie_group(S::LIE)
    }
    fn step(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        x: &mut S::State,
        stats: &mut Stats,
    ) -> Result<(), Failure> {
        let k1 = sys.rhs(t, x);
        let (_, _, k2) = sys.rkmk_stage(t + 0.5 * h, x, &k1.scaled(0.5 * h));
        let mut theta3 = k2.scaled(2.0 * h);
        theta3.axpy(-h, &k1);
        let (_, _, k3) = sys.rkmk_stage(t + h, x, &theta3);
        stats.rhs_evals += 3;
        let mut dx = k1.scaled(h / 6.0);
        dx.axpy(2.0 / 3.0 * h, &k2);
        dx.axpy(h / 6.0, &k3);
        *x = sys.retract(x, &dx);
        Ok(())
    }
}

impl FixedStepMethod for Kutta3 {
    type On<S: System> = Kutta3On<S>;
    fn on<S: System>(&self) -> Kutta3On<S> {
        Kutta3On(PhantomData)
    }
}

/// The fixed-step run of `m` from `x0` over `[0, t_end]` in `n` steps (the test support's
/// loop, normalizing after each step).
fn steps<S: System, M: FixedStepMethod>(
    m: &M,
    sys: &S,
    x0: S::State,
    t_end: f64,
    n: usize,
) -> S::State {
    crate::integrate::test_support::run_fixed(&mut m.on::<S>(), sys, x0, t_end, n).0
}

#[test]
fn a_method_written_once_keeps_its_order_on_vector_spaces_and_lie_groups() {
    // Invariant: a user's method written once through `FixedStepMethod` is order 3 on an
    // additive system and, with the dexp_inv correction, on the rigid body's so3 chart.
    let osc = Oscillator;
    let errs: Vec<f64> = [20, 40, 80, 160]
        .iter()
        .map(|&n| (steps(&Kutta3, &osc, osc.initial(), 2.0, n) - osc.exact(2.0)).norm())
        .collect();
    assert_last_order("kutta3 oscillator", &errs, 3.0);
    let sys = rotor_system();
    let exact = rotor_reference(&sys, 1.0);
    let errs: Vec<f64> = [20, 40, 80, 160]
        .iter()
        .map(|&n| rotor_distance(&steps(&Kutta3, &sys, rotor_initial(&sys), 1.0, n), &exact))
        .collect();
    assert_last_order("kutta3 so3 rotor", &errs, 3.0);
    assert!(
        Fixed(Kutta3)
            .info::<crate::integrate::test_support::RotorSys>()
            .lie_group
    );
}

/// The quat-chart rotor scene as a grid and its first state.
fn quat_rotor() -> (RigidSystem<Quat, Body>, Grid) {
    let sys = RigidSystem::<Quat, Body>::new(rotor_system().body);
    let grid = Grid {
        t_end: 2.0,
        sample_every: 0.5,
        score_every: 0.5,
    };
    (sys, grid)
}

#[test]
fn the_face_gives_the_numbers_of_a_direct_call() {
    // Invariant: running a built-in through the face (`Fixed`, `Tolerance`) does exactly
    // the work of the direct call it replaced: every sample and counter equal, bit for bit.
    let (sys, grid) = quat_rotor();
    let x0 = sys.state_from(&crate::integrate::test_support::rotor_observation());
    let lim = Limits::default();
    let face = Fixed(Rk4)
        .run(&sys, x0, Stepping::Dt(1e-2), &grid, &lim, &Observe::Grid)
        .unwrap();
    let direct = run_fixed(
        &sys,
        &mut ExplicitRk::rk4(),
        x0,
        1e-2,
        &grid,
        &lim,
        &Observe::Grid,
    )
    .unwrap();
    assert_eq!(
        format!("{:?}", face.samples),
        format!("{:?}", direct.samples)
    );
    assert_eq!(face.stats, direct.stats);
    let face = Tolerance(Dopri5)
        .run(&sys, x0, Stepping::Tol(1e-8), &grid, &lim, &Observe::Grid)
        .unwrap();
    let direct = run_adaptive(
        &sys,
        &mut AdaptiveRk::dopri5(1e-8),
        x0,
        &grid,
        &lim,
        &Observe::Grid,
    )
    .unwrap();
    assert_eq!(
        format!("{:?}", face.samples),
        format!("{:?}", direct.samples)
    );
    assert_eq!(face.stats, direct.stats);
    assert!(face.stats.rejected + face.stats.steps > 10);
}

#[test]
fn a_stepping_of_the_wrong_kind_is_an_error() {
    // Invariant: a fixed-step method refuses a tolerance and an adaptive one a step, with a
    // message naming the method (no panic, no run).
    let (sys, grid) = quat_rotor();
    let x0 = sys.state_from(&crate::integrate::test_support::rotor_observation());
    let lim = Limits::default();
    let e = Fixed(Rk4)
        .run(&sys, x0, Stepping::Tol(1e-6), &grid, &lim, &Observe::Grid)
        .unwrap_err();
    assert!(e.contains("rk4") && e.contains("tolerance"), "{e}");
    let e = Tolerance(Dopri5)
        .run(&sys, x0, Stepping::Dt(1e-2), &grid, &lim, &Observe::Grid)
        .unwrap_err();
    assert!(e.contains("dopri5") && e.contains("step"), "{e}");
    assert_eq!(Fixed(Rk4).stepping(0.1), Stepping::Dt(0.1));
    assert_eq!(Tolerance(Dopri5).stepping(1e-6), Stepping::Tol(1e-6));
}

#[test]
fn lie_group_methods_are_admitted_on_lie_group_systems_only() {
    // Invariant: `Where::LieGroup` admits a system exactly when it is a Lie-group system;
    // `Where::Everywhere` admits every system.
    type So3Sys = crate::integrate::test_support::RotorSys;
    assert!(Where::LieGroup.admits::<So3Sys>());
    assert!(!Where::LieGroup.admits::<RigidSystem<Quat, Body>>());
    assert!(!Where::LieGroup.admits::<Oscillator>());
    assert!(Where::Everywhere.admits::<Oscillator>());
}

#[test]
fn every_builtin_reaches_every_chart_where_it_applies() {
    // Invariant: the rigid body's table holds each built-in generic method on all eleven
    // charts in both formulations (the Lie-group ones on the three Lie-group charts), under
    // the name it is listed by, with the facts of that system.
    struct Listed(Vec<(&'static str, Where)>);
    impl Visit for Listed {
        fn method<M: OdeMethod>(&mut self, name: &'static str, at: Where, _m: M) {
            self.0.push((name, at));
        }
    }
    let mut listed = Listed(vec![]);
    builtin::each(&mut listed);
    let table = crate::model::rigid_body::registry::variants();
    for (name, at) in listed.0 {
        let on: Vec<_> = table.iter().filter(|v| v.integrator == name).collect();
        let want = if at == Where::LieGroup { 3 * 2 } else { 11 * 2 };
        assert_eq!(on.len(), want, "{name}");
        assert!(on.iter().all(|v| v.info.name == name), "{name}");
        for v in on {
            let lie = crate::model::rigid_body::registry::LIE_PARAMS.contains(&v.param);
            assert_eq!(v.info.lie_group, lie, "{name} on {}", v.param);
        }
    }
}
