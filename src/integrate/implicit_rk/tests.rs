//! Tests of the implicit Gauss methods (`mod.rs`): the tableau identities, observed orders
//! on vector spaces and on SO(3), conservation properties, Jacobian reuse and its work, and
//! typed failures.
use super::predictor::lagrange;
use super::*;
use crate::model::rigid_body::{Observation, RigidBody, RigidSystem, Spring};
use crate::rotation::{Body, So3};
use nalgebra::{Matrix3, SVector, UnitQuaternion, Vector1, Vector2, Vector3, Vector4};

/// An additive system `y' = g(t, y)` on R^N, with `check` for finiteness.
struct Ode<const N: usize, G: Fn(f64, &SVector<f64, N>) -> SVector<f64, N> + Send + Sync>(G);

impl<const N: usize, G> System for Ode<N, G>
where
    G: Fn(f64, &SVector<f64, N>) -> SVector<f64, N> + Send + Sync,
{
    type State = SVector<f64, N>;
    type Tangent = SVector<f64, N>;
    const LIE: bool = false;
    fn rhs(&self, t: f64, x: &Self::State) -> Self::Tangent {
        (self.0)(t, x)
    }
    fn retract(&self, x: &Self::State, dx: &Self::Tangent) -> Self::State {
        x + dx
    }
    fn check(&self, t: f64, x: &Self::State) -> Result<(), Failure> {
        if x.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(Failure::new(FailureKind::NonFinite, t, "non-finite"))
        }
    }
}

fn oscillator() -> Ode<2, impl Fn(f64, &Vector2<f64>) -> Vector2<f64> + Send + Sync> {
    Ode(|_t, y: &Vector2<f64>| Vector2::new(y[1], -y[0]))
}

fn kepler() -> Ode<4, impl Fn(f64, &Vector4<f64>) -> Vector4<f64> + Send + Sync> {
    Ode(|_t, y: &Vector4<f64>| {
        let r3 = (y[0] * y[0] + y[1] * y[1]).powf(1.5);
        Vector4::new(y[2], y[3], -y[0] / r3, -y[1] / r3)
    })
}

fn pendulum() -> Ode<2, impl Fn(f64, &Vector2<f64>) -> Vector2<f64> + Send + Sync> {
    Ode(|_t, y: &Vector2<f64>| Vector2::new(y[1], -y[0].sin()))
}

/// `n` steps of size `h` from `t = 0`, normalizing and checking like the run loop.
fn run<S: System>(
    m: &mut ImplicitRk<S>,
    sys: &S,
    x0: S::State,
    h: f64,
    n: usize,
) -> (S::State, Stats) {
    let mut x = x0;
    let mut stats = Stats::default();
    for k in 0..n {
        let t = k as f64 * h;
        m.step(sys, t, h, &mut x, &mut stats).unwrap();
        stats.steps += 1;
        sys.normalize(&mut x);
        sys.check(t + h, &x).unwrap();
    }
    (x, stats)
}

fn method<S: System>(scheme: GaussScheme) -> ImplicitRk<S> {
    ImplicitRk::new(scheme, NewtonOptions::default())
}

fn order(e1: f64, e2: f64) -> f64 {
    (e1 / e2).log2()
}

/// Errors at steps h, h/2, h/4 and the two observed orders.
fn orders(err: impl Fn(usize) -> f64, n0: usize) -> ([f64; 3], [f64; 2]) {
    let e = [err(n0), err(2 * n0), err(4 * n0)];
    (e, [order(e[0], e[1]), order(e[1], e[2])])
}

const SCHEMES: [(GaussScheme, f64); 2] = [
    (GaussScheme::ImplicitMidpoint, 2.0),
    (GaussScheme::Gauss6, 6.0),
];

/// The tableaux are consistent: row sums of A are c, sum b = 1, and d = b^T A^{-1} equals
/// the collocation polynomial's Lagrange weights at 1 (two independent computations).
#[test]
fn tableau_identities() {
    for (scheme, _) in SCHEMES {
        let t = Tableau::new(scheme);
        let s = t.s;
        assert!((t.b[..s].iter().sum::<f64>() - 1.0).abs() < 1e-15);
        for i in 0..s {
            let row: f64 = t.a[i][..s].iter().sum();
            assert!((row - t.c[i]).abs() < 1e-15, "{scheme:?} row {i}");
            assert!((lagrange(&t.c[..s], i, 1.0) - t.d[i]).abs() < 1e-13);
        }
    }
}

fn rigid(springs: Vec<Spring>) -> RigidSystem<So3, Body> {
    let body = RigidBody::new(
        1.0,
        Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 3.0)),
        springs,
        None,
        None,
    )
    .unwrap();
    RigidSystem::new(body)
}

fn spring() -> Vec<Spring> {
    vec![Spring {
        body_point: Vector3::new(0.3, 0.2, 0.1),
        anchor: Vector3::new(0.5, -0.2, 1.0),
        stiffness: 20.0,
        rest_length: 0.5,
    }]
}

fn rigid_x0(sys: &RigidSystem<So3, Body>) -> <RigidSystem<So3, Body> as System>::State {
    sys.state_from(&Observation {
        q: UnitQuaternion::from_euler_angles(0.3, -0.2, 0.5),
        x: Vector3::new(0.1, 0.0, 0.2),
        v: Vector3::new(0.2, -0.1, 0.3),
        omega: Vector3::new(1.0, 0.5, -0.3) * 2.0,
    })
}

fn rigid_dist(
    sys: &RigidSystem<So3, Body>,
    a: &<RigidSystem<So3, Body> as System>::State,
    b: &<RigidSystem<So3, Body> as System>::State,
) -> f64 {
    let (oa, ob) = (sys.observe(a), sys.observe(b));
    crate::math::so3::geodesic_quat(&oa.q, &ob.q)
        .max((oa.x - ob.x).norm())
        .max((oa.v - ob.v).norm())
        .max((oa.omega - ob.omega).norm())
}

/// Determinant of the one-step map's Jacobian at `x`, by central differences with two
/// Richardson levels (truncation O(delta^6)).
fn det_one_step<S: System<State = Vector2<f64>>>(
    scheme: GaussScheme,
    sys: &S,
    x: Vector2<f64>,
    h: f64,
    delta: f64,
) -> f64 {
    let phi = |y: Vector2<f64>| {
        let mut m = method::<S>(scheme);
        let mut y = y;
        m.step(sys, 0.0, h, &mut y, &mut Stats::default()).unwrap();
        y
    };
    let d = |dl: f64| {
        let mut jm = nalgebra::Matrix2::zeros();
        for k in 0..2 {
            let mut e = Vector2::zeros();
            e[k] = dl;
            jm.set_column(k, &((phi(x + e) - phi(x - e)) / (2.0 * dl)));
        }
        jm
    };
    let (d1, d2, d4) = (d(delta), d(delta / 2.0), d(delta / 4.0));
    let r1 = (d2 * 4.0 - d1) / 3.0;
    let r2 = (d4 * 4.0 - d2) / 3.0;
    let jm = (r2 * 16.0 - r1) / 15.0;
    jm.determinant()
}

/// Kepler initial state at pericentre, eccentricity `e`, `mu = a = 1` (period 2 pi).
fn kepler_x0(e: f64) -> Vector4<f64> {
    Vector4::new(1.0 - e, 0.0, 0.0, ((1.0 + e) / (1.0 - e)).sqrt())
}

/// Observed orders on the harmonic oscillator (exact solution cos/sin, t = 10) are 2 and 6
/// within 0.2, with errors well above round-off at the finest step.
#[test]
fn order_harmonic_oscillator() {
    let sys = oscillator();
    let tend = 10.0;
    for (scheme, p) in SCHEMES {
        let err = |n: usize| {
            let mut m = method(scheme);
            let (x, _) = run(&mut m, &sys, Vector2::new(1.0, 0.0), tend / n as f64, n);
            (x - Vector2::new(tend.cos(), -tend.sin())).norm()
        };
        let n0 = if p == 2.0 { 40 } else { 10 };
        let (e, o) = orders(err, n0);
        eprintln!("oscillator {scheme:?} errors {e:?} orders {o:.3?}");
        assert!(
            e[2] > 1e-11,
            "finest error must stay 100x above round-off (~1e-13)"
        );
        for oi in o {
            assert!((oi - p).abs() < 0.2, "{scheme:?}: order {oi} vs {p}");
        }
    }
}

/// Observed orders on a Kepler orbit (e = 0.5, one period, exact solution = initial
/// state) are 2 and 6 within 0.2.
#[test]
fn order_kepler() {
    let sys = kepler();
    let x0 = kepler_x0(0.5);
    let tend = 2.0 * std::f64::consts::PI;
    for (scheme, p) in SCHEMES {
        let err = |n: usize| {
            let mut m = method(scheme);
            let (x, _) = run(&mut m, &sys, x0, tend / n as f64, n);
            (x - x0).norm()
        };
        let (e, o) = orders(err, 100);
        eprintln!("kepler {scheme:?} errors {e:?} orders {o:.3?}");
        assert!(e[2] > 1e-11);
        for oi in o {
            assert!((oi - p).abs() < 0.2, "{scheme:?}: order {oi} vs {p}");
        }
    }
}

/// One step on the oscillator equals the stability function (the diagonal Pade
/// approximant of exp) applied to the initial value, to round-off: Newton solves the
/// stage equations to round-off, not to a looser tolerance.
#[test]
fn one_step_is_pade_to_round_off() {
    use nalgebra::Complex;
    let sys = oscillator();
    let h = 0.7;
    // u = x + i v satisfies u' = -i u; R(z) with z = -i h.
    let z = Complex::new(0.0, -h);
    let one = Complex::new(1.0, 0.0);
    let r_mid = (one + z / 2.0) / (one - z / 2.0);
    let r_g6 = (one + z / 2.0 + z * z / 10.0 + z * z * z / 120.0)
        / (one - z / 2.0 + z * z / 10.0 - z * z * z / 120.0);
    for (scheme, r) in [
        (GaussScheme::ImplicitMidpoint, r_mid),
        (GaussScheme::Gauss6, r_g6),
    ] {
        let mut m = method(scheme);
        let mut x = Vector2::new(1.0, 0.0);
        m.step(&sys, 0.0, h, &mut x, &mut Stats::default()).unwrap();
        let d = (x - Vector2::new(r.re, r.im)).norm();
        // A few eps: Newton stops at 10 eps on |Z| <= 1, plus the rounding of the update.
        assert!(d < 1e-14, "{scheme:?}: {d:e}");
    }
}

/// The oscillator's energy x^2 + v^2 (a quadratic invariant, which Gauss methods conserve
/// exactly) stays constant to round-off over 10^4 steps: below N eps = 2.2e-12, the bound
/// for one rounding error of systematic sign per step (a random walk would give ~1e-14).
#[test]
fn oscillator_energy_to_round_off() {
    let sys = oscillator();
    for (scheme, _) in SCHEMES {
        let mut m = method(scheme);
        let x0 = Vector2::new(0.3, -0.8);
        let (mut x, mut st) = (x0, Stats::default());
        let e0 = x0.norm_squared();
        let mut worst = 0.0_f64;
        for k in 0..10_000 {
            m.step(&sys, k as f64 * 0.1, 0.1, &mut x, &mut st).unwrap();
            worst = worst.max((x.norm_squared() - e0).abs() / e0);
        }
        eprintln!("oscillator energy {scheme:?}: worst relative drift {worst:.3e}");
        assert!(worst < 1e4 * f64::EPSILON, "{scheme:?}: {worst:e}");
    }
}

/// The one-step map preserves area: det of its Jacobian (central differences, Richardson
/// to O(delta^6)) is 1 to 1e-12 for the linear oscillator (differences exact up to
/// rounding ~ 10 eps / delta) and the nonlinear pendulum at a large angle (truncation
/// ~1e-14 at delta = 0.02, measured 1e-13 at delta = 0.03); a damped oscillator, whose
/// map contracts area, gives its own determinant |R(h lambda)|^2 instead (the check can fail).
#[test]
fn one_step_map_preserves_area() {
    for (scheme, _) in SCHEMES {
        let d_osc = det_one_step(scheme, &oscillator(), Vector2::new(0.3, -0.8), 0.5, 0.1);
        let d_pen = det_one_step(scheme, &pendulum(), Vector2::new(2.5, 0.4), 0.5, 0.02);
        eprintln!(
            "area {scheme:?}: det - 1 = {:.2e} (oscillator), {:.2e} (pendulum)",
            d_osc - 1.0,
            d_pen - 1.0
        );
        assert!((d_osc - 1.0).abs() < 1e-12, "{scheme:?} oscillator {d_osc}");
        assert!((d_pen - 1.0).abs() < 1e-12, "{scheme:?} pendulum {d_pen}");
        let c = 0.1;
        let damped = Ode(move |_t, y: &Vector2<f64>| Vector2::new(y[1], -y[0] - c * y[1]));
        let d_damp = det_one_step(scheme, &damped, Vector2::new(0.3, -0.8), 0.5, 0.1);
        // The map is R(h A), so det = R(h l) R(h conj l) = |R(h l)|^2 with
        // l = -c/2 + i sqrt(1 - c^2/4) (about e^(-c h) = 0.951); exact up to rounding.
        let z = nalgebra::Complex::new(-c / 2.0, (1.0 - c * c / 4.0).sqrt()) * 0.5;
        let one = nalgebra::Complex::new(1.0, 0.0);
        let r = match scheme {
            GaussScheme::ImplicitMidpoint => (one + z / 2.0) / (one - z / 2.0),
            GaussScheme::Gauss6 => {
                (one + z / 2.0 + z * z / 10.0 + z * z * z / 120.0)
                    / (one - z / 2.0 + z * z / 10.0 - z * z * z / 120.0)
            }
        };
        let expect = r.norm_sqr();
        let tol = 1e-12;
        assert!((d_damp - expect).abs() < tol, "{scheme:?} damped {d_damp}");
    }
}

/// On `RigidSystem<So3, Body>` (torque-free, J = diag(1, 2, 3), translating) the RKMK
/// forms have observed orders 2 and 6 within 0.2 on rotation, position and velocities;
/// reference: gauss6 with 64 times smaller steps (its error is below 1e-13).
#[test]
fn order_rigid_body_rkmk() {
    let sys = rigid(vec![]);
    let x0 = rigid_x0(&sys);
    let tend = 5.0;
    let mut mref = method(GaussScheme::Gauss6);
    let (xref, _) = run(&mut mref, &sys, x0, tend / 6400.0, 6400);
    for (scheme, p) in SCHEMES {
        let err = |n: usize| {
            let mut m = method(scheme);
            let (x, _) = run(&mut m, &sys, x0, tend / n as f64, n);
            rigid_dist(&sys, &x, &xref)
        };
        let (e, o) = orders(err, 25);
        eprintln!("rigid body {scheme:?} errors {e:?} orders {o:.3?}");
        assert!(e[2] > 1e-11);
        for oi in o {
            assert!((oi - p).abs() < 0.2, "{scheme:?}: order {oi} vs {p}");
        }
    }
}

/// Torque-free, Euler's equations are decoupled from the rotation and integrated by the
/// additive Gauss method, so the kinetic energy and |J omega|^2 (quadratic in omega) are
/// conserved to round-off (below N eps over N = 2000 steps), and |q| = 1 after
/// normalization.
#[test]
fn rigid_body_quadratic_invariants() {
    let sys = rigid(vec![]);
    let x0 = rigid_x0(&sys);
    for (scheme, _) in SCHEMES {
        let mut m = method(scheme);
        let o0 = sys.observe(&x0);
        let ek = |o: &Observation| sys.body.kinetic(&o.v, &o.omega);
        let lb = |o: &Observation| (sys.body.inertia * o.omega).norm_squared();
        let (x, _) = run(&mut m, &sys, x0, 0.05, 2000);
        let o = sys.observe(&x);
        let de = (ek(&o) - ek(&o0)).abs() / ek(&o0);
        let dl = (lb(&o) - lb(&o0)).abs() / lb(&o0);
        eprintln!("rigid invariants {scheme:?}: energy {de:.2e}, |L|^2 {dl:.2e}");
        assert!(de < 2000.0 * f64::EPSILON && dl < 2000.0 * f64::EPSILON);
        assert!((o.q.into_inner().norm() - 1.0).abs() < 4.0 * f64::EPSILON);
    }
}

/// Reusing the Jacobian across steps gives the same solution (both converge to round-off)
/// for fewer right-hand-side evaluations than a new Jacobian every step (rigid body with a
/// spring, where the Jacobian changes along the path).
#[test]
fn jacobian_reuse_saves_work() {
    let sys = rigid(spring());
    let x0 = rigid_x0(&sys);
    for (scheme, _) in SCHEMES {
        let n = 200;
        let mut reuse = method(scheme);
        let mut every = ImplicitRk::new(
            scheme,
            NewtonOptions {
                jacobian: JacobianUpdate::EveryStep,
                ..Default::default()
            },
        );
        let (xa, sa) = run(&mut reuse, &sys, x0, 5.0 / n as f64, n);
        let (xb, sb) = run(&mut every, &sys, x0, 5.0 / n as f64, n);
        let per = |s: &Stats, v: u64| v as f64 / s.steps as f64;
        eprintln!(
            "{scheme:?} h = 0.025 reuse: {:.2} iters, {:.2} evals, {} Jacobians; \
             every step: {:.2} iters, {:.2} evals",
            per(&sa, sa.newton_iters),
            per(&sa, sa.rhs_evals),
            reuse.jacobian_evals(),
            per(&sb, sb.newton_iters),
            per(&sb, sb.rhs_evals)
        );
        // Differences: round-off per step, amplified by the flow over 200 steps.
        assert!(rigid_dist(&sys, &xa, &xb) < 1e-11);
        assert!(sa.rhs_evals < sb.rhs_evals);
        assert_eq!(sa.steps, n as u64);
    }
}

/// Every right-hand-side evaluation (Newton and finite-difference ones) is counted: the
/// system's own call counter equals `stats.rhs_evals`.
#[test]
fn rhs_evals_are_all_counted() {
    use std::sync::atomic::{AtomicU64, Ordering};
    let calls = AtomicU64::new(0);
    let sys = Ode(|_t, y: &Vector4<f64>| {
        calls.fetch_add(1, Ordering::Relaxed);
        let r3 = (y[0] * y[0] + y[1] * y[1]).powf(1.5);
        Vector4::new(y[2], y[3], -y[0] / r3, -y[1] / r3)
    });
    for (scheme, _) in SCHEMES {
        calls.store(0, Ordering::Relaxed);
        let mut m = method(scheme);
        let (_, st) = run(&mut m, &sys, kepler_x0(0.5), 0.1, 100);
        assert_eq!(st.rhs_evals, calls.load(Ordering::Relaxed));
        assert!(st.newton_iters >= 100);
    }
}

/// Stiff decay y' = -1e6 y at h = 1 (h lambda = -1e6): both methods stay bounded
/// (A-stability, |R| <= 1), reproduce R(-1e6)^n to round-off (Newton converges on the
/// stiff stage equations), and need few iterations.
#[test]
fn stiff_decay_is_stable() {
    let lam = -1e6;
    let sys = Ode(move |_t, y: &Vector1<f64>| y * lam);
    let z = lam;
    let r_mid = (1.0 + z / 2.0) / (1.0 - z / 2.0);
    let r_g6 = (1.0 + z / 2.0 + z * z / 10.0 + z * z * z / 120.0)
        / (1.0 - z / 2.0 + z * z / 10.0 - z * z * z / 120.0);
    for (scheme, r) in [
        (GaussScheme::ImplicitMidpoint, r_mid),
        (GaussScheme::Gauss6, r_g6),
    ] {
        let mut m = method(scheme);
        let n = 100;
        let (y, st) = run(&mut m, &sys, Vector1::new(1.0), 1.0, n);
        let exact = r.powi(n as i32);
        eprintln!(
            "stiff {scheme:?}: y_100 = {:.6e} (R^100 = {exact:.6e}), {:.2} iters/step",
            y[0],
            st.newton_iters as f64 / n as f64
        );
        assert!(y[0].abs() <= 1.0);
        // Per step: rounding of a few eps, relative; 100 steps.
        assert!((y[0] - exact).abs() < 1e-12, "{scheme:?}");
        assert!(st.newton_iters <= 5 * n as u64);
    }
}

/// y' = y^2 from y = 1 with h = 1: the midpoint stage equation Z = (1 + Z)^2 / 2 has no
/// real solution, so Newton fails with `newton_failure` (t and residual in the message);
/// the state is left untouched and nothing panics. Gauss6 (whose solution also blows up
/// inside the step) fails the same way or as `non_finite`.
#[test]
fn newton_failure_without_solution() {
    let sys = Ode(|_t, y: &Vector1<f64>| Vector1::new(y[0] * y[0]));
    for (scheme, _) in SCHEMES {
        let mut m = method(scheme);
        let mut y = Vector1::new(1.0);
        let mut st = Stats::default();
        let r = m.step(&sys, 2.0, 1.0, &mut y, &mut st);
        let f = r.expect_err("no solution near the predictor");
        eprintln!("{scheme:?}: {:?} {}", f.kind, f.message);
        if scheme == GaussScheme::ImplicitMidpoint {
            assert_eq!(f.kind, FailureKind::NewtonFailure);
            assert!(f.message.contains("residual") && f.message.contains("t = 2"));
        } else {
            assert!(matches!(
                f.kind,
                FailureKind::NewtonFailure | FailureKind::NonFinite
            ));
        }
        assert_eq!(f.t, 2.0);
        assert_eq!(y[0], 1.0);
        assert_eq!(st.steps, 0);
        assert!(st.newton_iters > 0 && st.newton_iters <= 2 * 50);
    }
}

/// A right-hand side that returns NaN past y = 0.5 gives `non_finite` (or
/// `newton_failure`), never a panic; so does a NaN initial state.
#[test]
fn nan_rhs_is_a_failure() {
    let sys = Ode(|_t, y: &Vector1<f64>| Vector1::new(if y[0] < 0.5 { 1.0 } else { f64::NAN }));
    for (scheme, _) in SCHEMES {
        let mut m = method(scheme);
        let mut st = Stats::default();
        let mut y = Vector1::new(0.0);
        let f = m.step(&sys, 0.0, 1.0, &mut y, &mut st).unwrap_err();
        assert!(matches!(
            f.kind,
            FailureKind::NonFinite | FailureKind::NewtonFailure
        ));
        assert_eq!(y[0], 0.0);
        let mut bad = Vector1::new(f64::NAN);
        let f = m.step(&sys, 1.0, 0.1, &mut bad, &mut st).unwrap_err();
        assert_eq!(f.kind, FailureKind::NonFinite);
        // A good step afterwards still works (the workspace is not poisoned).
        let mut y = Vector1::new(0.0);
        m.step(&sys, 0.0, 0.1, &mut y, &mut st).unwrap();
        assert!((y[0] - 0.1).abs() < 1e-15);
    }
}

/// A right-hand side with deterministic noise (a hash of the argument's bits): at 3e-13
/// (stage noise between the 10 eps tolerance and 1e3 eps) Newton stagnates at the noise
/// and the step is accepted through the stagnation test; at 1e-9 it is a `newton_failure`.
#[test]
fn noisy_rhs_stagnation() {
    fn noise(y: f64) -> f64 {
        let mut b = y.to_bits().wrapping_mul(0x9E37_79B9_7F4A_7C15);
        b ^= b >> 29;
        (b >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
    for (amp, ok) in [(3e-13, true), (1e-9, false)] {
        let sys = Ode(move |_t, y: &Vector1<f64>| Vector1::new(-y[0] + amp * noise(y[0])));
        for (scheme, _) in SCHEMES {
            let mut m = method(scheme);
            let mut st = Stats::default();
            let mut y = Vector1::new(1.0);
            let r = m.step(&sys, 0.0, 1.0, &mut y, &mut st);
            eprintln!(
                "noise {amp:e} {scheme:?}: {r:?} after {} iterations",
                m.last_iters()
            );
            if ok {
                assert!(r.is_ok());
                assert!(m.last_iters() < 50);
                assert_eq!(m.stagnations(), 1, "accepted through the stagnation test");
            } else {
                assert_eq!(r.unwrap_err().kind, FailureKind::NewtonFailure);
            }
        }
    }
}

/// The method describes itself: name, order, stages, and symplectic only off Lie groups.
#[test]
fn method_info() {
    let m = ImplicitRk::<RigidSystem<So3, Body>>::gauss6();
    let i = FixedStep::<RigidSystem<So3, Body>>::info(&m);
    assert_eq!((i.name, i.order, i.stages), ("gauss6", 6, 3));
    assert!(i.implicit && i.lie_group && !i.symplectic && !i.adaptive);
    let m = ImplicitRk::<Ode<2, fn(f64, &Vector2<f64>) -> Vector2<f64>>>::implicit_midpoint();
    let i = m.info();
    assert_eq!((i.name, i.order, i.stages), ("implicit_midpoint", 2, 1));
    assert!(i.implicit && !i.lie_group && i.symplectic);
}
