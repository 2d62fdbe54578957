//! Tests of the method face: the built-in factories behind the face give the numbers of a
//! direct call bit for bit (a method written outside the crate keeps its order through the
//! face: `tests/byo_integrator.rs`); a stepping of the wrong kind is an error; and the
//! applicability rule admits the Lie-group methods on Lie-group systems only.
use super::builtin::{Dopri5, Rk4};
use super::*;
use crate::integrate::adaptive_rk::AdaptiveRk;
use crate::integrate::explicit_rk::ExplicitRk;
use crate::integrate::test_support::{Oscillator, rotor_system};
use crate::model::rigid_body::RigidSystem;
use crate::rotation::{Body, Quat};

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
