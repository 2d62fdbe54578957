//! Test problems for the integrator tests (compiled only for tests): systems with known
//! solutions and the helpers to measure observed orders.
//!
//! - `Oscillator`: `q' = p, p' = -q`, exact `(cos t, -sin t)` from `(1, 0)`; linear.
//! - `Kepler`: `q'' = -q/|q|^3` with eccentricity `e`, started at pericentre; the orbit has
//!   period `2 pi` (semi-major axis 1), so the exact state after one period is the initial
//!   state; nonlinear.
//! - `Blowup`: `y' = y^2`, `y(0) = 1`, exact `1/(1 - t)`, which blows up at `t = 1` (or a
//!   vector field that returns NaN, for the failure paths).
//! - the free rotor: `RigidSystem<So3, Body>` with `J = diag(1, 2, 3)`, no force; its reference
//!   solution comes from classical RK4 with `h = 1e-4` on the independent additive
//!   quaternion form `q' = q (0, omega)/2`, `J omega' = -omega x J omega` (no Lie-group code
//!   involved); it is checked against the rotor's exact invariants (energy, world angular
//!   momentum) in the tests below.
use nalgebra::{SVector, UnitQuaternion, Vector1, Vector2, Vector3, Vector4};

use super::adaptive_rk::ErrorScale;
use super::explicit_rk::ExplicitRk;
use super::{Failure, FailureKind, FixedStep, Stats, System};
use crate::math::so3;
use crate::model::rigid_body::{Observation, RigidBody, RigidState, RigidSystem};
use crate::rotation::{Body, Pose, So3};

/// `log2(e_i / e_{i+1})` for errors at successively halved steps.
pub fn observed_orders(errs: &[f64]) -> Vec<f64> {
    errs.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

/// The observed orders of `errs` (`observed_orders`), printed under `label` with the errors;
/// asserts that the last one is within 0.2 of `p` and returns them.
pub fn assert_last_order(label: &str, errs: &[f64], p: f64) -> Vec<f64> {
    let q = observed_orders(errs);
    let (e_s, q_s) = (sci(errs), fixed(&q));
    eprintln!("{label}: errors {e_s} orders {q_s}");
    assert!((q.last().unwrap() - p).abs() < 0.2, "{label}");
    q
}

/// Integrates with `n` fixed steps of `m` over `[0, t_end]` from `x0`, counting the steps and
/// normalizing after each one (the run loop without its checks); the end state and the stats.
pub fn run_fixed<S: System, M: FixedStep<S>>(
    m: &mut M,
    sys: &S,
    x0: S::State,
    t_end: f64,
    n: usize,
) -> (S::State, Stats) {
    let mut x = x0;
    let mut st = Stats::default();
    let h = t_end / n as f64;
    for k in 0..n {
        m.step(sys, k as f64 * h, h, &mut x, &mut st).unwrap();
        st.steps += 1;
        sys.normalize(&mut x);
    }
    (x, st)
}

/// `[1.234e-5, ...]` for test output.
pub fn sci(v: &[f64]) -> String {
    let s: Vec<String> = v.iter().map(|x| format!("{x:.3e}")).collect();
    format!("[{}]", s.join(", "))
}

/// `[1.234, ...]` for test output.
pub fn fixed(v: &[f64]) -> String {
    let s: Vec<String> = v.iter().map(|x| format!("{x:.3}")).collect();
    format!("[{}]", s.join(", "))
}

fn finite_or_fail<const N: usize>(t: f64, x: &SVector<f64, N>) -> Result<(), Failure> {
    if x.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(Failure::new(FailureKind::NonFinite, t, "non-finite state"))
    }
}

/// The harmonic oscillator.
pub struct Oscillator;

impl Oscillator {
    pub fn initial(&self) -> Vector2<f64> {
        Vector2::new(1.0, 0.0)
    }
    pub fn exact(&self, t: f64) -> Vector2<f64> {
        Vector2::new(t.cos(), -t.sin())
    }
}

impl System for Oscillator {
    type State = Vector2<f64>;
    type Tangent = Vector2<f64>;
    const LIE: bool = false;
    fn rhs(&self, _t: f64, x: &Vector2<f64>) -> Vector2<f64> {
        Vector2::new(x[1], -x[0])
    }
    fn retract(&self, x: &Vector2<f64>, d: &Vector2<f64>) -> Vector2<f64> {
        x + d
    }
    fn check(&self, t: f64, x: &Vector2<f64>) -> Result<(), Failure> {
        finite_or_fail(t, x)
    }
}

impl ErrorScale for Oscillator {
    fn coords(&self, x: &Vector2<f64>) -> Vector2<f64> {
        *x
    }
}

/// The Kepler problem `(q1, q2, p1, p2)`.
pub struct Kepler {
    pub e: f64,
}

impl Kepler {
    pub fn new(e: f64) -> Self {
        Kepler { e }
    }
    pub fn initial(&self) -> Vector4<f64> {
        Vector4::new(
            1.0 - self.e,
            0.0,
            0.0,
            ((1.0 + self.e) / (1.0 - self.e)).sqrt(),
        )
    }
    pub fn period(&self) -> f64 {
        2.0 * std::f64::consts::PI
    }
}

impl System for Kepler {
    type State = Vector4<f64>;
    type Tangent = Vector4<f64>;
    const LIE: bool = false;
    fn rhs(&self, _t: f64, x: &Vector4<f64>) -> Vector4<f64> {
        let r2 = x[0] * x[0] + x[1] * x[1];
        let r3 = r2 * r2.sqrt();
        Vector4::new(x[2], x[3], -x[0] / r3, -x[1] / r3)
    }
    fn retract(&self, x: &Vector4<f64>, d: &Vector4<f64>) -> Vector4<f64> {
        x + d
    }
    fn check(&self, t: f64, x: &Vector4<f64>) -> Result<(), Failure> {
        finite_or_fail(t, x)
    }
}

impl ErrorScale for Kepler {
    fn coords(&self, x: &Vector4<f64>) -> Vector4<f64> {
        *x
    }
}

/// `y' = y^2` (or NaN when `nan`).
pub struct Blowup {
    pub nan: bool,
}

impl System for Blowup {
    type State = Vector1<f64>;
    type Tangent = Vector1<f64>;
    const LIE: bool = false;
    fn rhs(&self, _t: f64, x: &Vector1<f64>) -> Vector1<f64> {
        if self.nan {
            Vector1::new(f64::NAN)
        } else {
            Vector1::new(x[0] * x[0])
        }
    }
    fn retract(&self, x: &Vector1<f64>, d: &Vector1<f64>) -> Vector1<f64> {
        x + d
    }
    fn check(&self, t: f64, x: &Vector1<f64>) -> Result<(), Failure> {
        finite_or_fail(t, x)
    }
}

impl ErrorScale for Blowup {
    fn coords(&self, x: &Vector1<f64>) -> Vector1<f64> {
        *x
    }
}

/// The free rotor's system type.
pub type RotorSys = RigidSystem<So3, Body>;
/// Its state.
pub type RotorState = RigidState<Pose<UnitQuaternion<f64>>>;

/// `J = diag(1, 2, 3)`, unit mass, no springs, no gravity, free.
pub fn rotor_system() -> RotorSys {
    let j = nalgebra::Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 3.0));
    RigidSystem::new(RigidBody::new(1.0, j, Vec::new(), None, None).unwrap())
}

/// The rotor's initial physical state: a generic attitude, spin not near a principal axis,
/// and a uniform translation.
pub fn rotor_observation() -> Observation {
    Observation {
        q: so3::exp_quat(&Vector3::new(0.3, -0.2, 0.5)),
        x: Vector3::new(0.1, 0.2, -0.3),
        v: Vector3::new(0.4, -0.5, 0.6),
        omega: Vector3::new(1.0, 0.6, -0.7),
    }
}

pub fn rotor_initial(sys: &RotorSys) -> RotorState {
    sys.state_from(&rotor_observation())
}

/// The additive quaternion form of the free rotor: `(q (4), omega (3))`.
struct QuatRotor {
    j: Vector3<f64>,
}

impl System for QuatRotor {
    type State = SVector<f64, 7>;
    type Tangent = SVector<f64, 7>;
    const LIE: bool = false;
    fn rhs(&self, _t: f64, x: &Self::State) -> Self::Tangent {
        let q = nalgebra::Quaternion::new(x[0], x[1], x[2], x[3]);
        let w = Vector3::new(x[4], x[5], x[6]);
        let qd = q * nalgebra::Quaternion::from_imag(w) * 0.5;
        let jw = w.component_mul(&self.j);
        let wd = (-w.cross(&jw)).component_div(&self.j);
        SVector::<f64, 7>::from_column_slice(&[qd.w, qd.i, qd.j, qd.k, wd.x, wd.y, wd.z])
    }
    fn retract(&self, x: &Self::State, d: &Self::Tangent) -> Self::State {
        x + d
    }
    fn check(&self, t: f64, x: &Self::State) -> Result<(), Failure> {
        finite_or_fail(t, x)
    }
}

/// The rotor's state at `t_end` from the independent reference integration.
pub fn rotor_reference(sys: &RotorSys, t_end: f64) -> RotorState {
    let o = rotor_observation();
    let rot = QuatRotor {
        j: sys.body.inertia.diagonal(),
    };
    let q = o.q.into_inner();
    let mut x = SVector::<f64, 7>::from_column_slice(&[
        q.w, q.i, q.j, q.k, o.omega.x, o.omega.y, o.omega.z,
    ]);
    let n = (t_end / 1e-4).round() as usize;
    let h = t_end / n as f64;
    let mut m = ExplicitRk::rk4();
    let mut st = Stats::default();
    for k in 0..n {
        m.step(&rot, k as f64 * h, h, &mut x, &mut st).unwrap();
    }
    let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(x[0], x[1], x[2], x[3]));
    sys.state_from(&Observation {
        q,
        x: o.x + o.v * t_end,
        v: o.v,
        omega: Vector3::new(x[4], x[5], x[6]),
    })
}

/// Geodesic attitude distance plus the Euclidean distances of position and velocities.
pub fn rotor_distance(a: &RotorState, b: &RotorState) -> f64 {
    so3::geodesic_quat(&a.pose.rot, &b.pose.rot)
        + (a.pose.x - b.pose.x).norm()
        + (a.vel - b.vel).norm()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reference rotor solution keeps the exact invariants of the free rotor (energy and
    /// world angular momentum) to 1e-13 and unit quaternion norm: RK4 at h = 1e-4 has local
    /// errors ~1e-20 and 2e4 steps of rounding ~1e-13 at most.
    #[test]
    fn rotor_reference_keeps_invariants() {
        let sys = rotor_system();
        let o0 = rotor_observation();
        let x = rotor_reference(&sys, 5.0);
        let o1 = sys.observe(&x);
        let b = &sys.body;
        assert!((b.energy(&o1) - b.energy(&o0)).abs() < 1e-13);
        assert!((b.angular_momentum(&o1) - b.angular_momentum(&o0)).norm() < 1e-13);
        assert!((o1.omega - o0.omega).norm() > 0.1, "the rotor does precess");
    }
}
