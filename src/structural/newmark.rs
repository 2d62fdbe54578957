//! `newmark`: Newmark's average-acceleration method (the trapezoidal rule of structural
//! dynamics; Newmark, "A method of computation for structural dynamics", J. Eng. Mech. Div.
//! ASCE 85, 1959, with `beta = 1/4`, `gamma = 1/2`), implicit, for `M(q) a + f(t, q, v) = 0`.
//! Equation labels are this file's.
//!
//! One step `t_n -> t_{n+1} = t_n + h`:
//!
//! ```text
//! (NM1)  q_{n+1} = q_n + h v_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1},
//! (NM2)  v_{n+1} = v_n + h (1 - gamma) a_n + h gamma a_{n+1},
//! (NM3)  M(q_{n+1}) a_{n+1} + f(t_{n+1}, q_{n+1}, v_{n+1}) = 0,
//! ```
//!
//! solved for `a_{n+1}` by Newton (`newton`, (N1)-(N4), with `c_k = beta h^2`,
//! `c_c = gamma h`), predictor `a_{n+1} = a_n`. Order 2 (`gamma = 1/2`); unconditionally
//! stable for linear systems, without numerical dissipation (spectral radius 1 for every
//! `h omega`), and it conserves the energy `(v^T M v + q^T K q)/2` of a linear undamped
//! system exactly (to the Newton tolerance and round-off): (NM1)-(NM2) give
//! `q_{n+1} - q_n = h (v_{n+1} + v_n)/2` and `v_{n+1} - v_n = h (a_{n+1} + a_n)/2`, so the
//! energy changes by `h/2 (v_{n+1} + v_n)^T (M (a_{n+1} + a_n) + K (q_{n+1} + q_n))/2 = 0`. It is symplectic only for a non-canonical form and does not conserve energy for
//! nonlinear systems. The initial acceleration is (I1)/(I2) of `init`.
//!
//! Where it fails: unresolved high frequencies are not damped, so spurious oscillations of
//! stiff or algebraic components (massless coordinates' velocities and accelerations, the
//! multipliers of constrained systems) persist; nonlinear stiff problems can lose energy
//! stability (the reason for energy-momentum methods). A Newton that does not converge is a
//! `newton_failure`, a non-finite state `non_finite`.
use super::SecondOrder;
use super::method::Method;
use super::newton::{self, NewtonOptions, Point};
use super::path_step::AlphaFamily;
use super::state::State;
use crate::integrate::{Failure, Stats};

const BETA: f64 = 0.25;
const GAMMA: f64 = 0.5;
/// The method's name (`Method::NAME`), in its `info` and its failures.
const NAME: &str = "newmark";

/// Newmark's average-acceleration method.
///
/// # Example
///
/// A linear undamped oscillator `q'' + q = 0` over ten periods with 20 steps a period: the
/// energy is kept to round-off while the phase lags by Newmark's `(h omega)^2 / 12` per
/// radian:
///
/// ```
/// use mbdbench::integrate::Stats;
/// use mbdbench::structural::method::Method;
/// use mbdbench::structural::newmark::Newmark;
/// use mbdbench::structural::newton::NewtonOptions;
/// use mbdbench::structural::state::State;
/// use mbdbench::structural::SecondOrder;
/// use nalgebra::{DMatrix, DVector};
///
/// struct Oscillator;
/// impl SecondOrder for Oscillator {
///     fn dim(&self) -> usize { 1 }
///     fn residual(&self, _t: f64, q: &DVector<f64>, _v: &DVector<f64>, a: &DVector<f64>,
///                 r: &mut DVector<f64>) {
///         r[0] = a[0] + q[0];
///     }
///     fn tangent(&self, _t: f64, _q: &DVector<f64>, _v: &DVector<f64>, _a: &DVector<f64>,
///                c_m: f64, _c_c: f64, c_k: f64, s: &mut DMatrix<f64>) {
///         s[(0, 0)] = c_m + c_k;
///     }
/// }
/// let mut nm = Newmark::new(NewtonOptions::default()).unwrap();
/// let (mut st, mut stats) = (State::for_system(&Oscillator), Stats::default());
/// st.set(&[1.0], &[0.0]);
/// nm.init(&mut Oscillator, 0.0, &mut st, &mut stats).unwrap();
/// let h = 2.0 * std::f64::consts::PI / 20.0;
/// for k in 0..200 {
///     nm.step(&mut Oscillator, k as f64 * h, h, &mut st, &mut stats).unwrap();
/// }
/// let energy = 0.5 * (st.q[0] * st.q[0] + st.v[0] * st.v[0]);
/// assert!((energy - 0.5).abs() < 1e-13);
/// assert!((st.q[0] - 1.0).abs() > 0.1);
/// assert_eq!(stats.steps, 200);
/// assert_eq!(Method::<Oscillator>::info(&nm).order, 2);
/// ```
#[derive(Debug, Clone)]
pub struct Newmark {
    newton: NewtonOptions,
}

impl Newmark {
    /// The method with the given Newton options (an error names a bad one).
    pub fn new(newton: NewtonOptions) -> Result<Self, String> {
        newton.validate()?;
        Ok(Newmark { newton })
    }

    /// `beta` and `gamma`.
    pub fn parameters(&self) -> (f64, f64) {
        (BETA, GAMMA)
    }
}

impl<S: SecondOrder + ?Sized> Method<S> for Newmark {
    const NAME: &'static str = NAME;

    /// Advances `state` from `t` to `t + h` by (NM1)-(NM3).
    fn step(
        &mut self,
        sys: &mut S,
        t: f64,
        h: f64,
        state: &mut State,
        stats: &mut Stats,
    ) -> Result<(), Failure> {
        let sys: &S = sys;
        newton::check_step(t, h, NAME)?;
        state.assert_sizes(sys.dim(), state.n_constraints());
        let w = &mut state.work;
        w.qe.copy_from(&state.q);
        w.qe.axpy(h, &state.v, 1.0);
        w.qe.axpy(h * h * (0.5 - BETA), &state.a, 1.0);
        w.ve.copy_from(&state.v);
        w.ve.axpy(h * (1.0 - GAMMA), &state.a, 1.0);
        w.a1.copy_from(&state.a);
        let p = Point {
            t_e: t + h,
            c_k: BETA * h * h,
            c_c: GAMMA * h,
            scale: state.q.amax() + h * state.v.amax(),
            t_n: t,
        };
        newton::solve_acceleration(sys, p, &self.newton, NAME, w, stats)?;
        w.aux1.copy_from(&w.a1);
        newton::accept(state, stats, t, NAME, newton::Trial::Plain)
    }
}

/// On a path-dependent structure ([`AlphaFamily`]): `am = af = 0`, `beta = 1/4`, `gamma = 1/2`.
impl AlphaFamily for Newmark {
    const NAME: &'static str = NAME;

    fn coefficients(&self) -> (f64, f64, f64, f64) {
        (0.0, 0.0, BETA, GAMMA)
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_support::*;
    use super::*;

    /// Newmark conserves the energy of a linear undamped two-degree-of-freedom oscillator to
    /// round-off over 10 000 steps (a coarse `h omega_max = 0.8`), for any step size.
    #[test]
    fn energy_is_conserved_for_linear_systems() {
        let mut sys = Linear::two_dof(0.0);
        let mut nm = Newmark::new(tight()).unwrap();
        let (mut st, mut stats) = (State::for_system(&sys), Stats::default());
        st.set(&[1.0, -0.5], &[0.3, 0.0]);
        nm.init(&mut sys, 0.0, &mut st, &mut stats).unwrap();
        let e0 = sys.energy(&st);
        let h = 0.8 / sys.omega_max();
        let mut worst: f64 = 0.0;
        for k in 0..10_000 {
            nm.step(&mut sys, k as f64 * h, h, &mut st, &mut stats)
                .unwrap();
            worst = worst.max((sys.energy(&st) - e0).abs() / e0);
        }
        eprintln!("newmark: relative energy error over 10000 steps {worst:e}");
        assert!(worst < 1e-12, "energy error {worst:e}");
        assert_eq!(stats.steps, 10_000);
        assert!(stats.newton_iters >= 2 * stats.steps);
        assert_eq!(stats.rhs_evals, stats.newton_iters + 1);
    }

    /// The spectral radius of Newmark's amplification matrix is 1 at `h omega = 1e4` (no
    /// dissipation at any frequency).
    #[test]
    fn no_dissipation_at_high_frequency() {
        let rho = spectral_radius(&mut Newmark::new(tight()).unwrap());
        eprintln!("newmark: spectral radius at h omega = 1e4: {rho}");
        assert!((rho - 1.0).abs() < 1e-6, "rho = {rho}");
    }

    /// Order 2 (within 0.25) on the nonlinear test systems, on a step ladder.
    #[test]
    fn order_two_on_nonlinear_systems() {
        check_order(|| Newmark::new(tight()).unwrap(), "newmark");
    }

    /// A spring chain with a massless middle node runs, its mass node follows the reduced
    /// one-degree-of-freedom system run by the same method, and the massless node stays in
    /// static equilibrium.
    #[test]
    fn massless_node_matches_reduced_system() {
        let err = massless_vs_reduced(|| Newmark::new(tight()).unwrap());
        eprintln!("newmark: massless chain vs reduced system {err:e}");
        assert!(err < 1e-11, "{err:e}");
    }

    /// A cap of one Newton update on a stiff nonlinear problem is a `newton_failure` at the
    /// step's time, and the state is left as it was.
    #[test]
    fn newton_cap_fails() {
        newton_cap_check(&mut Newmark::new(cap_one()).unwrap());
    }

    /// Bad Newton options are rejected by name, and a non-finite step is a failure.
    #[test]
    fn bad_parameters_are_errors() {
        let bad = NewtonOptions {
            tol: f64::NAN,
            max_iters: 5,
        };
        let e = Newmark::new(bad).unwrap_err();
        assert!(e.contains("tol"), "{e}");
        bad_step_check(&mut Newmark::new(NewtonOptions::default()).unwrap());
    }
}
