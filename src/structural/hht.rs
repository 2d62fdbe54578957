//! `hht`: the Hilber-Hughes-Taylor alpha method (Hilber, Hughes & Taylor, "Improved
//! numerical dissipation for time integration algorithms in structural dynamics", Earthquake
//! Eng. Struct. Dyn. 5, 1977, 283-292), implicit, for `M(q) a + f(t, q, v) = 0`, with
//! `alpha` in `[-1/3, 0]` (default `-0.05`), `beta = (1 - alpha)^2 / 4`,
//! `gamma = 1/2 - alpha`. Equation labels are this file's.
//!
//! One step `t_n -> t_{n+1} = t_n + h`: Newmark's updates (NM1)-(NM2) with these `beta`,
//! `gamma`, and the equations of motion with the forces at the alpha-weighted point,
//!
//! ```text
//! (H1)  q_{n+1} = q_n + h v_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1},
//! (H2)  v_{n+1} = v_n + h (1 - gamma) a_n + h gamma a_{n+1},
//! (H3)  M(q_a) a_{n+1} + f(t_a, q_a, v_a) = 0,   x_a = (1 + alpha) x_{n+1} - alpha x_n
//!       for x = t, q, v (t_a = t_{n+1} + alpha h).
//! ```
//!
//! For a linear system (H3) is the alpha-method of HHT 1977,
//!
//! ```text
//! M a_{n+1} + (1 + alpha)(C v_{n+1} + K q_{n+1}) - alpha (C v_n + K q_n) = F(t_{n+1+alpha});
//! ```
//!
//! for a nonlinear one it is the generalized-midpoint form (forces at the weighted state
//! rather than weighted forces), one residual evaluation per Newton iteration through the
//! `SecondOrder` residual. Newton (`newton`, (N1)-(N4)) on `a_{n+1}` with the evaluation
//! point `q_a = q_n + (1 + alpha) (h v_n + h^2 (1/2 - beta) a_n) + (1 + alpha) beta h^2
//! a_{n+1}`, i.e. `c_k = (1 + alpha) beta h^2`, `c_c = (1 + alpha) gamma h`; predictor
//! `a_{n+1} = a_n`.
//!
//! Order 2 (the choice of `gamma`; `a_{n+1}` approximates `q''(t_{n+1} + alpha h)`, and
//! starting from `a_0 = q''(t_0)` costs an `O(alpha h^2)` error in `v_1` that stays `O(h^2)`).
//! Unconditionally stable for linear systems; the spectral radius of the amplification
//! matrix is 1 at `h omega -> 0` and `(1 + alpha)/(1 - alpha)` at `h omega -> infinity`
//! (1/2 at `alpha = -1/3`), so unresolved modes decay. `alpha = 0` is Newmark.
//! Where it fails: the dissipation also damps resolved modes slightly (the amplitude shrinks
//! by `1 - O(|alpha| (h omega)^3)` a step) and it cannot be tuned apart from the low-frequency accuracy
//! (generalized-alpha can); a nonlinear massless equation holds at `q_a`, so the massless
//! coordinates' `q_{n+1}` satisfy it only to `O(h^2)`; Newton failures and non-finite
//! states are `newton_failure` and `non_finite`.
use super::SecondOrder;
use super::method::Method;
use super::newton::{self, NewtonOptions, Point};
use super::path_step::AlphaFamily;
use super::state::State;
use crate::integrate::{Failure, Stats};

/// The method's name (`Method::NAME`), in its `info` and its failures.
const NAME: &str = "hht";

/// The HHT alpha method.
///
/// # Example
///
/// The default `alpha = -0.05` on `q'' + q = 0`: second order at resolved frequencies (the
/// energy after one period with 100 steps is within `1e-3` of its start, slightly below it),
/// and an `alpha` outside `[-1/3, 0]` is an error naming it:
///
/// ```
/// use mbdbench::integrate::Stats;
/// use mbdbench::structural::hht::Hht;
/// use mbdbench::structural::method::Method;
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
/// assert!(Hht::new(-0.5, NewtonOptions::default()).unwrap_err().contains("alpha"));
/// let mut hht = Hht::new(-0.05, NewtonOptions::default()).unwrap();
/// let (mut st, mut stats) = (State::for_system(&Oscillator), Stats::default());
/// st.set(&[1.0], &[0.0]);
/// hht.init(&mut Oscillator, 0.0, &mut st, &mut stats).unwrap();
/// let h = 2.0 * std::f64::consts::PI / 100.0;
/// for k in 0..100 {
///     hht.step(&mut Oscillator, k as f64 * h, h, &mut st, &mut stats).unwrap();
/// }
/// let energy = 0.5 * (st.q[0] * st.q[0] + st.v[0] * st.v[0]);
/// assert!(energy < 0.5 && energy > 0.5 - 1e-3);
/// ```
#[derive(Debug, Clone)]
pub struct Hht {
    alpha: f64,
    beta: f64,
    gamma: f64,
    newton: NewtonOptions,
}

impl Default for Hht {
    /// `alpha = -0.05`, default Newton options.
    fn default() -> Self {
        Hht::new(-0.05, NewtonOptions::default()).expect("valid defaults")
    }
}

impl Hht {
    /// The method for `alpha` in `[-1/3, 0]`; an error names a bad `alpha` or Newton option.
    pub fn new(alpha: f64, newton: NewtonOptions) -> Result<Self, String> {
        let c = super::gen_alpha::Coefficients::hht(alpha, "hht")?;
        newton.validate()?;
        Ok(Hht {
            alpha,
            beta: c.beta,
            gamma: c.gamma,
            newton,
        })
    }

    /// `(alpha, beta, gamma)`.
    pub fn parameters(&self) -> (f64, f64, f64) {
        (self.alpha, self.beta, self.gamma)
    }

    /// The spectral radius at `h omega -> infinity`, `(1 + alpha)/(1 - alpha)`.
    pub fn rho_inf(&self) -> f64 {
        (1.0 + self.alpha) / (1.0 - self.alpha)
    }
}

impl<S: SecondOrder + ?Sized> Method<S> for Hht {
    const NAME: &'static str = NAME;

    /// Advances `state` from `t` to `t + h` by (H1)-(H3).
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
        let (al, be, ga) = (self.alpha, self.beta, self.gamma);
        let w1 = 1.0 + al;
        let w = &mut state.work;
        // The unknown-free part of the evaluation point.
        w.qe.copy_from(&state.q);
        w.qe.axpy(w1 * h, &state.v, 1.0);
        w.qe.axpy(w1 * h * h * (0.5 - be), &state.a, 1.0);
        w.ve.copy_from(&state.v);
        w.ve.axpy(w1 * h * (1.0 - ga), &state.a, 1.0);
        w.a1.copy_from(&state.a);
        let p = Point {
            t_e: t + w1 * h,
            c_k: w1 * be * h * h,
            c_c: w1 * ga * h,
            scale: state.q.amax() + h * state.v.amax(),
            t_n: t,
        };
        newton::solve_acceleration(sys, p, &self.newton, NAME, w, stats)?;
        // q_{n+1}, v_{n+1} from (H1)-(H2) (w.q1, w.v1 held the evaluation point).
        w.q1.copy_from(&state.q);
        w.q1.axpy(h, &state.v, 1.0);
        w.q1.axpy(h * h * (0.5 - be), &state.a, 1.0);
        w.q1.axpy(h * h * be, &w.a1, 1.0);
        w.v1.copy_from(&state.v);
        w.v1.axpy(h * (1.0 - ga), &state.a, 1.0);
        w.v1.axpy(h * ga, &w.a1, 1.0);
        w.aux1.copy_from(&w.a1);
        newton::accept(state, stats, t, NAME, newton::Trial::Plain)
    }
}

/// On a path-dependent structure ([`AlphaFamily`]): `am = 0`, `af = -alpha`, its `beta`, `gamma`.
impl AlphaFamily for Hht {
    const NAME: &'static str = NAME;

    fn coefficients(&self) -> (f64, f64, f64, f64) {
        (0.0, -self.alpha, self.beta, self.gamma)
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_support::*;
    use super::*;

    /// The measured spectral radius at `h omega = 1e4` is `(1 + alpha)/(1 - alpha)` for the
    /// default, the most dissipative and the Newmark end of the range. At `alpha = -1/3`
    /// the eigenvalues at infinity coincide (a Jordan block) and the radius approaches its
    /// limit like `(h omega)^(-2/3)` (`1.7e-3` away at `1e4`, `8e-5` at `1e6`, measured);
    /// elsewhere like `(h omega)^(-2)`.
    #[test]
    fn spectral_radius_matches_theory() {
        for alpha in [-0.05, -1.0 / 3.0, -0.2, 0.0] {
            let mut m = Hht::new(alpha, tight()).unwrap();
            let rho = spectral_radius(&mut m);
            let far = spectral_radius_at(&mut m, 1e6);
            let theory = m.rho_inf();
            eprintln!(
                "hht alpha = {alpha:.4}: spectral radius at h omega = 1e4: {rho:.6}, at 1e6: \
                 {far:.6} (theory {theory:.6})"
            );
            assert!(
                (rho - theory).abs() < 3e-3,
                "alpha {alpha}: {rho} vs {theory}"
            );
            assert!(
                (far - theory).abs() < 2e-4,
                "alpha {alpha}: {far} vs {theory}"
            );
        }
        let rho = spectral_radius(&mut Hht::default());
        assert!((rho - 0.95 / 1.05).abs() < 1e-7, "default: {rho}");
    }

    /// Order 2 (within 0.25) on the nonlinear test systems, for the default and the most
    /// dissipative alpha.
    #[test]
    fn order_two_on_nonlinear_systems() {
        check_order(|| Hht::new(-0.05, tight()).unwrap(), "hht(-0.05)");
        check_order(|| Hht::new(-1.0 / 3.0, tight()).unwrap(), "hht(-1/3)");
    }

    /// HHT dissipates the energy of a linear undamped oscillator: it ends below its start,
    /// at a resolved and an unresolved step, and never rises far above it.
    #[test]
    fn energy_decays_for_linear_systems() {
        let mut sys = Linear::two_dof(0.0);
        for hw in [0.3, 30.0] {
            let mut m = Hht::default();
            let (mut st, mut stats) = (State::for_system(&sys), Stats::default());
            st.set(&[1.0, -0.5], &[0.3, 0.0]);
            m.init(&mut sys, 0.0, &mut st, &mut stats).unwrap();
            let h = hw / sys.omega_max();
            let e0 = sys.energy(&st);
            let mut top: f64 = 0.0;
            for k in 0..2000 {
                m.step(&mut sys, k as f64 * h, h, &mut st, &mut stats)
                    .unwrap();
                top = top.max(sys.energy(&st) / e0);
            }
            let end = sys.energy(&st) / e0;
            eprintln!("hht at h omega_max = {hw}: energy end/start {end:.6}, max/start {top:.6}");
            assert!(end < 1.0, "no dissipation at h omega = {hw}");
            assert!(top < 1.05, "energy rose to {top} of its start");
        }
    }

    /// A spring chain with a massless middle node matches the reduced system.
    #[test]
    fn massless_node_matches_reduced_system() {
        let err = massless_vs_reduced(|| Hht::new(-0.1, tight()).unwrap());
        eprintln!("hht: massless chain vs reduced system {err:e}");
        assert!(err < 1e-11, "{err:e}");
    }

    /// A cap of one Newton update on a stiff nonlinear problem is a `newton_failure`.
    #[test]
    fn newton_cap_fails() {
        newton_cap_check(&mut Hht::new(-0.05, cap_one()).unwrap());
    }

    /// `alpha` outside `[-1/3, 0]` or non-finite is an error naming `alpha`; a non-finite
    /// step is a failure.
    #[test]
    fn bad_parameters_are_errors() {
        for alpha in [0.01, -0.34, f64::NAN, f64::NEG_INFINITY] {
            let e = Hht::new(alpha, NewtonOptions::default()).unwrap_err();
            assert!(e.contains("alpha"), "{e}");
        }
        assert!(Hht::new(-1.0 / 3.0, NewtonOptions::default()).is_ok());
        bad_step_check(&mut Hht::default());
    }
}
