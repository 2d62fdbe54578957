//! `gen_alpha`: the generalized-alpha method of Chung & Hulbert ("A time integration
//! algorithm for structural dynamics with improved numerical dissipation: the
//! generalized-alpha method", J. Appl. Mech. 60, 1993, 371-375) in the form of Arnold & Brüls
//! ("Convergence of the generalized-alpha scheme for constrained mechanical systems",
//! Multibody Syst. Dyn. 18, 2007, 185-202), implicit, for `M(q) a + f(t, q, v) = 0`.
//! Equation labels are this file's.
//!
//! Parameters from the spectral radius at infinity `rho_inf` in `[0, 1]` (default 0.9),
//! Chung & Hulbert's optimal choice:
//!
//! ```text
//! (G0)  alpha_m = (2 rho_inf - 1)/(rho_inf + 1),  alpha_f = rho_inf/(rho_inf + 1),
//!       gamma = 1/2 - alpha_m + alpha_f,          beta = (1 - alpha_m + alpha_f)^2 / 4.
//! ```
//!
//! One step `t_n -> t_{n+1} = t_n + h`, with the true acceleration `qdd = v'` and the
//! auxiliary acceleration `a` (`State::aux`) kept apart:
//!
//! ```text
//! (G1)  q_{n+1} = q_n + h v_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1},
//! (G2)  v_{n+1} = v_n + h (1 - gamma) a_n + h gamma a_{n+1},
//! (G3)  (1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) qdd_{n+1} + alpha_f qdd_n,
//! (G4)  M(q_{n+1}) qdd_{n+1} + f(t_{n+1}, q_{n+1}, v_{n+1}) = 0.
//! ```
//!
//! The equations of motion hold at `t_{n+1}` on the true acceleration (G4); the alpha
//! weighting acts only through (G3), which is why this form keeps order 2 for nonlinear
//! systems, time-dependent loads and configuration-dependent masses, and extends to
//! constraints (`gen_alpha_i3`). For linear systems it has Chung & Hulbert's amplification
//! matrix. Newton (`newton`, (N1)-(N4)) on `qdd_{n+1}`: by (G3) `a_{n+1}` is affine in it,
//! so `c_k = beta h^2 (1 - alpha_f)/(1 - alpha_m)`, `c_c = gamma h (1 - alpha_f)/(1 -
//! alpha_m)`; predictor `qdd_{n+1} = qdd_n`.
//!
//! Order 2 in `q` and `v` (the choice of `gamma`; `a_n` approximates `qdd(t_n + (alpha_m -
//! alpha_f) h)` and starting with `a_0 = qdd_0` costs one `O(h^2)` velocity error).
//! Unconditionally stable for linear systems; spectral radius 1 at `h omega -> 0` and
//! `rho_inf` at `h omega -> infinity`, with the least low-frequency dissipation for that
//! `rho_inf`. `rho_inf = 1` is the trapezoidal rule (no dissipation); `rho_inf = 0`
//! annihilates the highest modes in one step. The initial acceleration is (I1)/(I2) of
//! `init`, and `a_0 = qdd_0`.
//!
//! Where it fails: the amplification matrix at infinity has a triple eigenvalue
//! `-rho_inf` (a Jordan block), so an unresolved mode can grow transiently (polynomially in
//! the step count) before it decays, and at finite `h omega` the spectral radius approaches
//! `rho_inf` only like `(h omega)^(-2/3)` (`1.5e-3` above it at `h omega = 1e4`, measured); resolved modes are slightly damped; Newton failures and non-finite states are
//! `newton_failure` and `non_finite`.
use super::SecondOrder;
use super::method::Method;
use super::newton::{self, NewtonOptions, Point};
use super::path_step::AlphaFamily;
use super::state::State;
pub use crate::integrate::gen_alpha_coefficients::Coefficients;
use crate::integrate::{Failure, Stats};

/// The method's name (`Method::NAME`), in its `info` and its failures.
const NAME: &str = "gen_alpha";

/// The generalized-alpha method (Arnold & Brüls form).
///
/// # Example
///
/// `q'' + q = 0` at a resolved step keeps its energy to `1e-3` over a period, while at
/// `h omega = 1e3` a single step scales the state by about `rho_inf`:
///
/// ```
/// use mbdbench::integrate::Stats;
/// use mbdbench::structural::gen_alpha::GenAlpha;
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
/// assert!(GenAlpha::new(1.5, NewtonOptions::default()).unwrap_err().contains("rho_inf"));
/// let mut ga = GenAlpha::new(0.9, NewtonOptions::default()).unwrap();
/// let (mut st, mut stats) = (State::for_system(&Oscillator), Stats::default());
/// st.set(&[1.0], &[0.0]);
/// ga.init(&mut Oscillator, 0.0, &mut st, &mut stats).unwrap();
/// let h = 2.0 * std::f64::consts::PI / 100.0;
/// for k in 0..100 {
///     ga.step(&mut Oscillator, k as f64 * h, h, &mut st, &mut stats).unwrap();
/// }
/// let energy = 0.5 * (st.q[0] * st.q[0] + st.v[0] * st.v[0]);
/// assert!((energy - 0.5).abs() < 1e-3);
/// assert_eq!(Method::<Oscillator>::info(&ga).name, "gen_alpha");
/// ```
#[derive(Debug, Clone)]
pub struct GenAlpha {
    c: Coefficients,
    newton: NewtonOptions,
}

impl Default for GenAlpha {
    /// `rho_inf = 0.9`, default Newton options.
    fn default() -> Self {
        GenAlpha::new(0.9, NewtonOptions::default()).expect("valid defaults")
    }
}

impl GenAlpha {
    /// The method for `rho_inf` in `[0, 1]`; an error names a bad `rho_inf` or Newton option.
    pub fn new(rho_inf: f64, newton: NewtonOptions) -> Result<Self, String> {
        let c = Coefficients::new(rho_inf, "gen_alpha")?;
        newton.validate()?;
        Ok(GenAlpha { c, newton })
    }

    /// The method's coefficients.
    pub fn parameters(&self) -> Coefficients {
        self.c
    }
}

impl<S: SecondOrder + ?Sized> Method<S> for GenAlpha {
    const NAME: &'static str = NAME;

    /// Advances `state` from `t` to `t + h` by (G1)-(G4).
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
        let (am, af, be, ga) = (self.c.alpha_m, self.c.alpha_f, self.c.beta, self.c.gamma);
        // a_{n+1} = (af qdd_n - am a_n)/(1 - am) + (1 - af)/(1 - am) qdd_{n+1}   (G3)
        let ratio = (1.0 - af) / (1.0 - am);
        let w = &mut state.work;
        // The unknown-free part of a_{n+1}, parked in aux1.
        w.aux1.copy_from(&state.a);
        w.aux1.scale_mut(af / (1.0 - am));
        w.aux1.axpy(-am / (1.0 - am), &state.aux, 1.0);
        w.qe.copy_from(&state.q);
        w.qe.axpy(h, &state.v, 1.0);
        w.qe.axpy(h * h * (0.5 - be), &state.aux, 1.0);
        w.qe.axpy(h * h * be, &w.aux1, 1.0);
        w.ve.copy_from(&state.v);
        w.ve.axpy(h * (1.0 - ga), &state.aux, 1.0);
        w.ve.axpy(h * ga, &w.aux1, 1.0);
        w.a1.copy_from(&state.a);
        let p = Point {
            t_e: t + h,
            c_k: be * h * h * ratio,
            c_c: ga * h * ratio,
            scale: state.q.amax() + h * state.v.amax(),
            t_n: t,
        };
        newton::solve_acceleration(sys, p, &self.newton, NAME, w, stats)?;
        w.aux1.axpy(ratio, &w.a1, 1.0);
        newton::accept(state, stats, t, NAME, newton::Trial::Aux)
    }
}

/// On a path-dependent structure ([`AlphaFamily`]): its coefficients `(alpha_m, alpha_f, beta, gamma)`.
impl AlphaFamily for GenAlpha {
    const NAME: &'static str = NAME;

    fn coefficients(&self) -> (f64, f64, f64, f64) {
        (self.c.alpha_m, self.c.alpha_f, self.c.beta, self.c.gamma)
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_support::*;
    use super::*;

    /// HHT is the member of the family with `alpha_m = 0`, `alpha_f = -alpha`: its `beta`
    /// and `gamma`, written in `alpha`, satisfy the family's second-order and stability
    /// conditions (`gamma = 1/2 - alpha_m + alpha_f`, `beta = (1 - alpha_m + alpha_f)^2 / 4`,
    /// Chung & Hulbert eq. 16, 23) to round-off, and `Hht` steps with them; a bad `alpha` is
    /// an error naming it.
    #[test]
    fn hht_is_the_family_member_with_alpha_m_zero() {
        for alpha in [0.0, -0.05, -0.3, -1.0 / 3.0] {
            let c = Coefficients::hht(alpha, "hht").unwrap();
            assert_eq!((c.alpha_m, c.alpha_f), (0.0, -alpha));
            let (am, af) = (c.alpha_m, c.alpha_f);
            assert!((c.gamma - (0.5 - am + af)).abs() <= 1e-16, "{c:?}");
            assert!(
                (c.beta - (1.0 - am + af).powi(2) / 4.0).abs() <= 1e-16,
                "{c:?}"
            );
            assert!((c.rho_inf - (1.0 + alpha) / (1.0 - alpha)).abs() < 1e-15);
            let h = crate::structural::hht::Hht::new(alpha, NewtonOptions::default()).unwrap();
            assert_eq!(h.parameters(), (alpha, c.beta, c.gamma));
        }
        let e = Coefficients::hht(0.1, "hht").unwrap_err();
        assert!(e.contains("alpha = 0.1"), "{e}");
    }

    /// The measured spectral radius at `h omega = 1e4` is `rho_inf`, across the range. The
    /// amplification matrix at infinity has the triple eigenvalue `-rho_inf` (a Jordan
    /// block), so the radius at finite `h omega` approaches `rho_inf` like
    /// `(h omega)^(-2/3)`: about `2e-3` away at `1e4`, `1e-4` at `1e6` (measured).
    #[test]
    fn spectral_radius_is_rho_inf() {
        for rho_inf in [0.9, 0.0, 0.5, 1.0] {
            let rho = spectral_radius(&mut GenAlpha::new(rho_inf, tight()).unwrap());
            let far = spectral_radius_at(&mut GenAlpha::new(rho_inf, tight()).unwrap(), 1e6);
            eprintln!(
                "gen_alpha rho_inf = {rho_inf}: spectral radius at h omega = 1e4: {rho:.6}, \
                 at 1e6: {far:.6}"
            );
            assert!((rho - rho_inf).abs() < 3e-3, "rho_inf {rho_inf}: {rho}");
            assert!(
                (far - rho_inf).abs() < 2e-4,
                "rho_inf {rho_inf}: {far} at 1e6"
            );
        }
    }

    /// Order 2 (within 0.25) on the nonlinear test systems, for the default and the most
    /// dissipative `rho_inf`.
    #[test]
    fn order_two_on_nonlinear_systems() {
        check_order(|| GenAlpha::new(0.9, tight()).unwrap(), "gen_alpha(0.9)");
        check_order(|| GenAlpha::new(0.0, tight()).unwrap(), "gen_alpha(0)");
    }

    /// `rho_inf = 1` is the trapezoidal rule: it keeps the energy of a linear undamped
    /// system to round-off, like Newmark.
    #[test]
    fn rho_one_conserves_linear_energy() {
        let mut sys = Linear::two_dof(0.0);
        let mut m = GenAlpha::new(1.0, tight()).unwrap();
        let (mut st, mut stats) = (State::for_system(&sys), Stats::default());
        st.set(&[1.0, -0.5], &[0.3, 0.0]);
        m.init(&mut sys, 0.0, &mut st, &mut stats).unwrap();
        let e0 = sys.energy(&st);
        let h = 0.8 / sys.omega_max();
        for k in 0..2000 {
            m.step(&mut sys, k as f64 * h, h, &mut st, &mut stats)
                .unwrap();
        }
        let err = (sys.energy(&st) - e0).abs() / e0;
        assert!(err < 1e-12, "{err:e}");
    }

    /// A spring chain with a massless middle node matches the reduced system.
    #[test]
    fn massless_node_matches_reduced_system() {
        let err = massless_vs_reduced(|| GenAlpha::new(0.8, tight()).unwrap());
        eprintln!("gen_alpha: massless chain vs reduced system {err:e}");
        assert!(err < 1e-11, "{err:e}");
    }

    /// A cap of one Newton update on a stiff nonlinear problem is a `newton_failure`.
    #[test]
    fn newton_cap_fails() {
        newton_cap_check(&mut GenAlpha::new(0.9, cap_one()).unwrap());
    }

    /// `rho_inf` outside `[0, 1]` or non-finite is an error naming it; a non-finite step is
    /// a failure.
    #[test]
    fn bad_parameters_are_errors() {
        for rho in [-0.1, 1.01, f64::NAN, f64::INFINITY] {
            let e = GenAlpha::new(rho, NewtonOptions::default()).unwrap_err();
            assert!(e.contains("rho_inf"), "{e}");
        }
        bad_step_check(&mut GenAlpha::default());
    }
}
