//! Test support for the geometric rigid-body integrators (compiled for tests only): the
//! canonical bodies of cases/README.md (`nine_spring`, `free_body` gni,
//! `heavy_top`) and two small ones (a torque-free body with full inertia, a body on three
//! springs with gravity), an independent reference integrator (classical RK4 in its
//! Runge-Kutta-Munthe-Kaas form on SO(3) x R^3, Munthe-Kaas 1998: fourth order, so at 1/64 of
//! the tested step its error is some 1e-7 of the tested method's), the fixed-step run loop
//! the caller uses (step, then normalize), the errors and invariants the tests measure, and
//! the tests the second-order methods share (`order_two_tests!`).
use nalgebra::{Matrix3, Vector3};

use super::{Failure, FixedStep, Stats, System};
use crate::math::so3;
use crate::math::vector::Vector;
use crate::model::rigid_body::{Observation, RigidBody, RigidState, RigidSystem, Spring};
use crate::rotation::{Body, Pose, So3};

pub(crate) type Sys = RigidSystem<So3, Body>;
pub(crate) type St = RigidState<Pose<nalgebra::UnitQuaternion<f64>>>;

fn state(sys: &Sys, r: &Matrix3<f64>, x: Vector3<f64>, v: Vector3<f64>, w: Vector3<f64>) -> St {
    sys.state_from(&Observation {
        q: so3::quat_from_matrix(r),
        x,
        v,
        omega: w,
    })
}

/// cases/README.md, `free_body`, scene `gni`: `J = diag(2, 1, 2/3)`,
/// `J omega = (cos 1.1, 0, sin 1.1)`.
pub(crate) fn gni() -> (Sys, St) {
    let j = Matrix3::from_diagonal(&Vector3::new(2.0, 1.0, 2.0 / 3.0));
    let body = RigidBody::new(1.0, j, vec![], None, None).unwrap();
    let l0 = Vector3::new(1.1_f64.cos(), 0.0, 1.1_f64.sin());
    let w = body.inertia_inv * l0;
    let sys = Sys::new(body);
    let s = state(
        &sys,
        &Matrix3::identity(),
        Vector3::zeros(),
        Vector3::zeros(),
        w,
    );
    (sys, s)
}

/// The nine-spring inertia (full, not diagonal), kg m^2.
fn full_inertia() -> Matrix3<f64> {
    Matrix3::new(
        800.0, -60.0, 40.0, -60.0, 1000.0, -80.0, 40.0, -80.0, 1200.0,
    )
}

/// A torque-free body with full inertia, tumbling and translating.
pub(crate) fn free_full() -> (Sys, St) {
    let body = RigidBody::new(1000.0, full_inertia(), vec![], None, None).unwrap();
    let sys = Sys::new(body);
    let r0 = so3::exp(&Vector3::new(0.4, -0.3, 0.2));
    let s = state(
        &sys,
        &r0,
        Vector3::new(0.1, 0.2, -0.3),
        Vector3::new(0.5, -0.2, 0.1),
        Vector3::new(0.7, -1.2, 0.9),
    );
    (sys, s)
}

/// A free body on three springs, with gravity (full inertia, off-axis attachment points).
pub(crate) fn three_springs() -> (Sys, St) {
    let j = Matrix3::new(2.0, 0.1, -0.2, 0.1, 1.5, 0.05, -0.2, 0.05, 1.0);
    let sp = |b: [f64; 3], a: [f64; 3], k: f64| Spring {
        body_point: Vector3::from(b),
        anchor: Vector3::from(a),
        stiffness: k,
        rest_length: 1.0,
    };
    let springs = vec![
        sp([0.5, 0.1, 0.0], [1.6, 0.1, 0.3], 40.0),
        sp([-0.2, 0.4, 0.1], [-0.2, 1.5, 0.4], 60.0),
        sp([0.1, -0.1, 0.3], [0.2, -0.1, 1.6], 50.0),
    ];
    let body = RigidBody::new(3.0, j, springs, Some(9.81), None).unwrap();
    let sys = Sys::new(body);
    let r0 = so3::exp(&Vector3::new(0.3, -0.2, 0.5));
    let s = state(
        &sys,
        &r0,
        Vector3::new(0.05, -0.1, 0.02),
        Vector3::new(0.1, 0.0, -0.2),
        Vector3::new(0.4, -0.3, 0.6),
    );
    (sys, s)
}

/// cases/README.md, `nine_spring`, scene `large`: `R0 = Rx(0) Ry(pi/3) Rz(-pi/2)`.
pub(crate) fn nine_spring() -> (Sys, St) {
    let bs = [
        ([1.0, 0.0, 0.0], 0),
        ([1.0, 0.5, 0.0], 0),
        ([1.0, 0.0, 0.4], 0),
        ([0.0, 0.8, 0.0], 1),
        ([0.0, 0.8, 0.4], 1),
        ([0.6, 0.8, 0.0], 1),
        ([0.0, 0.0, 0.6], 2),
        ([0.6, 0.0, 0.6], 2),
        ([0.0, 0.5, 0.6], 2),
    ];
    let springs = bs
        .iter()
        .map(|(b, axis)| {
            let b = Vector3::from(*b);
            let mut a = b;
            a[*axis] += 1.0;
            Spring {
                body_point: b,
                anchor: a,
                stiffness: 5.0e3,
                rest_length: 1.0,
            }
        })
        .collect();
    let body = RigidBody::new(1000.0, full_inertia(), springs, Some(9.81), None).unwrap();
    let sys = Sys::new(body);
    let r0 =
        so3::rx(0.0) * so3::ry(std::f64::consts::FRAC_PI_3) * so3::rz(-std::f64::consts::FRAC_PI_2);
    let s = state(
        &sys,
        &r0,
        Vector3::zeros(),
        Vector3::zeros(),
        Vector3::zeros(),
    );
    (sys, s)
}

/// cases/README.md, `heavy_top`, scene `bruls_cardona`.
pub(crate) fn heavy_top() -> (Sys, St) {
    let jc = Matrix3::from_diagonal(&Vector3::new(0.234375, 0.46875, 0.234375));
    let body = RigidBody::new(
        15.0,
        jc,
        vec![],
        Some(9.81),
        Some(Vector3::new(0.0, 1.0, 0.0)),
    )
    .unwrap();
    let sys = Sys::new(body);
    let s = state(
        &sys,
        &Matrix3::identity(),
        Vector3::zeros(),
        Vector3::zeros(),
        Vector3::new(0.0, 150.0, -4.61538),
    );
    (sys, s)
}

/// One step of RKMK4 (classical RK4 on the increment, with the `dexp_inv` correction).
pub(crate) fn rkmk4_step(sys: &Sys, t: f64, h: f64, x: &St) -> St {
    type T = <Sys as System>::Tangent;
    let f = |tt: f64, th: &T| -> T {
        let y = sys.retract(x, th);
        sys.dexp_inv(th, &sys.rhs(tt, &y))
    };
    let k1 = f(t, &T::zero());
    let k2 = f(t + 0.5 * h, &k1.scaled(0.5 * h));
    let k3 = f(t + 0.5 * h, &k2.scaled(0.5 * h));
    let k4 = f(t + h, &k3.scaled(h));
    let mut th = T::zero();
    th.axpy(h / 6.0, &k1);
    th.axpy(h / 3.0, &k2);
    th.axpy(h / 3.0, &k3);
    th.axpy(h / 6.0, &k4);
    let mut y = sys.retract(x, &th);
    sys.normalize(&mut y);
    y
}

/// The RKMK4 solution at `t_end` with `n` steps.
pub(crate) fn reference(sys: &Sys, x0: &St, t_end: f64, n: usize) -> St {
    let h = t_end / n as f64;
    let mut x = *x0;
    for k in 0..n {
        x = rkmk4_step(sys, k as f64 * h, h, &x);
    }
    x
}

/// Runs `n` steps of `m` from `x0` over `[0, t_end]` as the run loop does (step, normalize,
/// check), calling `each(k, state)` after every step.
pub(crate) fn run<M: FixedStep<Sys>>(
    m: &mut M,
    sys: &Sys,
    x0: &St,
    t_end: f64,
    n: usize,
    mut each: impl FnMut(usize, &St),
) -> Result<(St, Stats), Failure> {
    let h = t_end / n as f64;
    let mut x = *x0;
    let mut stats = Stats::default();
    for k in 0..n {
        let t = k as f64 * h;
        m.step(sys, t, h, &mut x, &mut stats)?;
        stats.steps += 1;
        if sys.normalize(&mut x) {
            stats.normalizations += 1;
        }
        sys.check(t + h, &x)?;
        each(k + 1, &x);
    }
    Ok((x, stats))
}

/// Distance of two states: rotation angle + position + velocities (SI, summed).
pub(crate) fn distance(a: &St, b: &St) -> f64 {
    so3::geodesic_quat(&a.pose.rot, &b.pose.rot)
        + (a.pose.x - b.pose.x).norm()
        + (a.vel - b.vel).norm()
}

/// Total energy.
pub(crate) fn energy(sys: &Sys, s: &St) -> f64 {
    sys.body.energy(&sys.observe(s))
}

/// World angular momentum about the reference point.
pub(crate) fn momentum(sys: &Sys, s: &St) -> Vector3<f64> {
    sys.body.angular_momentum(&sys.observe(s))
}

/// Observed orders `log2(e(h)/e(h/2))` on the ladder `t_end/n0, /2, /4` against an RKMK4
/// reference at 1/64 of the finest step; returns the errors and the two orders.
pub(crate) fn observed_orders<M: FixedStep<Sys>>(
    mut make: impl FnMut() -> M,
    sys: &Sys,
    x0: &St,
    t_end: f64,
    n0: usize,
) -> ([f64; 3], [f64; 2]) {
    let r = reference(sys, x0, t_end, 4 * n0 * 64);
    let mut e = [0.0; 3];
    for (i, ei) in e.iter_mut().enumerate() {
        let mut m = make();
        let (x, _) = run(&mut m, sys, x0, t_end, n0 << i, |_, _| {}).unwrap();
        *ei = distance(&x, &r);
    }
    let p = [(e[0] / e[1]).log2(), (e[1] / e[2]).log2()];
    (e, p)
}

/// A problem of the order-2 tests, with the span and the coarsest step count of its ladder.
#[derive(Debug, Clone, Copy)]
pub(crate) enum OrderTwoProblem {
    /// `free_full` over 2 s, 50 / 100 / 200 steps.
    FreeFull,
    /// `three_springs` over 1 s, 50 / 100 / 200 steps.
    ThreeSprings,
    /// `heavy_top` over 0.1 s, 100 / 200 / 400 steps.
    HeavyTop,
}

/// Asserts that the method `make` builds (called `name` in the messages) is of order 2 on
/// `problem`: both observed orders of its ladder (`observed_orders`) within 0.2 of 2.
pub(crate) fn assert_order_two<M: FixedStep<Sys>>(
    name: &str,
    problem: OrderTwoProblem,
    make: impl FnMut() -> M,
) {
    let (label, (sys, x0), t_end, n0) = match problem {
        OrderTwoProblem::FreeFull => ("free_full", free_full(), 2.0, 50),
        OrderTwoProblem::ThreeSprings => ("three_springs", three_springs(), 1.0, 50),
        OrderTwoProblem::HeavyTop => ("heavy_top", heavy_top(), 0.1, 100),
    };
    let (e, p) = observed_orders(make, &sys, &x0, t_end, n0);
    eprintln!("{name} {label}: errors {e:?} orders {p:?}");
    for pi in p {
        assert!((pi - 2.0).abs() <= 0.2, "{name} {label}: order {pi}");
    }
}

/// The tests every second-order rigid-body method shares: the three order-2 tests, one per
/// `OrderTwoProblem`, so that a failure names the method's module and the problem; the heavy
/// top's energy error (`assert_heavy_top_energy`); and the typed failures
/// (`check_typed_failures`). In the method's test module:
/// `ts::order_two_tests!("lgvi", Lgvi::new);` (a name for the messages, a constructor).
macro_rules! order_two_tests {
    ($name:expr, $make:expr) => {
        /// Order 2 (both observed orders within 0.2 of 2) on a torque-free body with full
        /// inertia.
        #[test]
        fn order_two_torque_free_full_inertia() {
            $crate::integrate::rigid_test_support::assert_order_two(
                $name,
                $crate::integrate::rigid_test_support::OrderTwoProblem::FreeFull,
                $make,
            );
        }

        /// Order 2 (both observed orders within 0.2 of 2) on a free body with three springs
        /// and gravity.
        #[test]
        fn order_two_three_springs_gravity() {
            $crate::integrate::rigid_test_support::assert_order_two(
                $name,
                $crate::integrate::rigid_test_support::OrderTwoProblem::ThreeSprings,
                $make,
            );
        }

        /// Order 2 (both observed orders within 0.2 of 2) on the pinned heavy top.
        #[test]
        fn order_two_heavy_top() {
            $crate::integrate::rigid_test_support::assert_order_two(
                $name,
                $crate::integrate::rigid_test_support::OrderTwoProblem::HeavyTop,
                $make,
            );
        }

        /// The heavy top runs 0.2 s at dt = 1e-3 with a relative energy error below 1e-3.
        #[test]
        fn heavy_top_energy() {
            $crate::integrate::rigid_test_support::assert_heavy_top_energy($name, &mut $make());
        }

        /// Bad numbers end a step with a typed failure, never a panic.
        #[test]
        fn typed_failures() {
            $crate::integrate::rigid_test_support::check_typed_failures($make);
        }
    };
}
pub(crate) use order_two_tests;

/// `max |E - E0|` over the first and the last tenth of an `n`-step run.
pub(crate) fn energy_error_tenths<M: FixedStep<Sys>>(
    m: &mut M,
    sys: &Sys,
    x0: &St,
    t_end: f64,
    n: usize,
) -> (f64, f64) {
    let e0 = energy(sys, x0);
    let (mut first, mut last) = (0.0_f64, 0.0_f64);
    run(m, sys, x0, t_end, n, |k, x| {
        let de = (energy(sys, x) - e0).abs();
        if k <= n / 10 {
            first = first.max(de);
        }
        if k > n - n / 10 {
            last = last.max(de);
        }
    })
    .unwrap();
    (first, last)
}

/// The worst relative energy error `|E - E0| / E0` and the worst world angular momentum error
/// `|L - L0|` over an `n`-step run of `m` (`run`), with its end state and stats.
pub(crate) fn invariant_errors<M: FixedStep<Sys>>(
    m: &mut M,
    sys: &Sys,
    x0: &St,
    t_end: f64,
    n: usize,
) -> (f64, f64, St, Stats) {
    let e0 = energy(sys, x0);
    let l0 = momentum(sys, x0);
    let (mut de, mut dl) = (0.0_f64, 0.0_f64);
    let (x, st) = run(m, sys, x0, t_end, n, |_, x| {
        de = de.max(((energy(sys, x) - e0) / e0).abs());
        dl = dl.max((momentum(sys, x) - l0).norm());
    })
    .unwrap();
    (de, dl, x, st)
}

/// Asserts that `m` (called `name` in the messages) keeps its energy error bounded over 1e5
/// steps of 1e-2 from `x0` (`energy_error_tenths`: the last tenth's maximum at most twice the
/// first's); returns the two maxima.
pub(crate) fn assert_bounded_energy<M: FixedStep<Sys>>(
    name: &str,
    m: &mut M,
    (sys, x0): (Sys, St),
) -> (f64, f64) {
    let (first, last) = energy_error_tenths(m, &sys, &x0, 1000.0, 100_000);
    eprintln!("{name} 1e5 steps: max|dE| first 10% {first:.3e}, last 10% {last:.3e}");
    assert!(last <= 2.0 * first, "{name}: {first} {last}");
    (first, last)
}

/// Asserts that the heavy top runs 0.2 s at dt = 1e-3 under `m` (called `name`) with a
/// relative energy error below 1e-3: a second-order method's energy error at this step is of
/// the size of its relative state error, 8e-4 here (|Omega| = 150 rad/s; see the heavy-top
/// order test). Prints the energy error at the end too (the drift).
pub(crate) fn assert_heavy_top_energy<M: FixedStep<Sys>>(name: &str, m: &mut M) {
    let (sys, x0) = heavy_top();
    let (worst, _, x, st) = invariant_errors(m, &sys, &x0, 0.2, 200);
    let e0 = energy(&sys, &x0);
    let end = (energy(&sys, &x) - e0) / e0;
    eprintln!(
        "{name} heavy_top 0.2 s dt=1e-3: max relative |dE| {worst:.3e}, at the end {end:.3e}, \
         stats {st:?}"
    );
    assert!(worst < 1e-3, "{name}: {worst:e}");
}

/// A step of `h` then one of `-h` from `three_springs`: the distance back to the start and the
/// stats of the two steps.
pub(crate) fn reversal<M: FixedStep<Sys>>(m: &mut M, h: f64) -> (f64, Stats) {
    let (sys, x0) = three_springs();
    let mut x = x0;
    let mut st = Stats::default();
    m.step(&sys, 0.0, h, &mut x, &mut st).unwrap();
    m.step(&sys, h, -h, &mut x, &mut st).unwrap();
    (distance(&x, &x0), st)
}

/// A method neither panics nor returns a wrong kind on bad input: a NaN state is `non_finite`,
/// and a step far too large (h = 1 s on the 150 rad/s heavy top) either runs or ends with a
/// typed `newton_failure` / `non_finite`.
pub(crate) fn check_typed_failures<M: FixedStep<Sys>>(mut make: impl FnMut() -> M) {
    use super::FailureKind;
    let (sys, x0) = heavy_top();
    let mut bad = x0;
    bad.vel[4] = f64::NAN;
    let mut st = Stats::default();
    let e = make().step(&sys, 0.0, 1e-3, &mut bad, &mut st).unwrap_err();
    assert_eq!(e.kind, FailureKind::NonFinite, "{e:?}");
    let (sys, x0) = three_springs();
    let mut bad = x0;
    bad.pose.x[0] = f64::INFINITY;
    let e = make().step(&sys, 0.0, 1e-2, &mut bad, &mut st).unwrap_err();
    assert_eq!(e.kind, FailureKind::NonFinite, "{e:?}");
    let (sys, x0) = heavy_top();
    let mut m = make();
    let r = run(&mut m, &sys, &x0, 20.0, 20, |_, _| {});
    eprintln!(
        "h = 1 s on the heavy top: {:?}",
        r.as_ref().map(|(_, s)| *s)
    );
    if let Err(e) = r {
        assert!(
            matches!(e.kind, FailureKind::NewtonFailure | FailureKind::NonFinite),
            "{e:?}"
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// RKMK4 halves its error by 16 when the step halves (order 4 within 0.2).
    #[test]
    fn reference_is_fourth_order() {
        let (sys, x0) = three_springs();
        let r = reference(&sys, &x0, 1.0, 3200);
        let e1 = distance(&reference(&sys, &x0, 1.0, 50), &r);
        let e2 = distance(&reference(&sys, &x0, 1.0, 100), &r);
        let p = (e1 / e2).log2();
        assert!((p - 4.0).abs() < 0.2, "order {p}");
    }
}
