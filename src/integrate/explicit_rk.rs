//! Explicit Runge-Kutta methods in one code that is classical RK on vector spaces and
//! Runge-Kutta-Munthe-Kaas (RKMK) on Lie groups.
//!
//! For a tableau `(c, A, b)` (`tableau.rs`) one step from `(t, x)` with step `h` is
//! (Munthe-Kaas, BIT 38, 1998, Algorithm 2; Iserles et al., Acta Numerica 2000, sec. 5.3):
//!
//! ```text
//! Theta_i = h sum_{j<i} a_ij K_j,
//! K_i     = dexp_inv(Theta_i, f(t + c_i h, x (+) Theta_i)),
//! x_{n+1} = x (+) h sum_i b_i K_i,
//! ```
//!
//! where `(+)` is `System::retract` and `f` is `System::rhs`. On additive systems
//! (`S::LIE == false`) `dexp_inv` is the identity and is skipped: this is exactly the classical
//! method. On a Lie group the increments live in the Lie algebra and the method keeps the
//! classical order of the tableau *because* of the `dexp_inv` correction; without it RK4
//! drops to order 2 (tested below with a wrapper that removes the correction).
//!
//! Orders: `euler` 1, `rk4` 4, on both kinds of systems. Invariants: the state moves only
//! by `retract`, so it stays on the group up to the rounding of the retraction (the caller
//! normalizes); the stages are a fixed array on the stack of each step (no allocation), and
//! the tableau is a type (`FixedTableau`), so the stage loop is unrolled at compile time.
//! Failure: a non-finite step increment is returned as a `non_finite` failure (the state is
//! then left unchanged); the method has no other failure mode (explicit methods are
//! only conditionally stable: too large a step gives a growing but finite solution, caught by
//! the caller's checks).
use super::tableau::{EULER, MAX_STAGES, RK4, Tableau};
use super::{Failure, FailureKind, FixedStep, MethodInfo, MethodKind, Stats, System};
use crate::math::vector::Vector;

/// `h sum_i w_i k_i`, skipping zero weights (the skipped terms are exact zeros, so this is
/// the same number as the full sum).
#[inline(always)]
pub(crate) fn combine<V: Vector>(h: f64, w: &[f64], k: &[V]) -> V {
    let mut out = V::zero();
    for (wi, ki) in w.iter().zip(k) {
        if *wi != 0.0 {
            out.axpy(h * wi, ki);
        }
    }
    out
}

/// Evaluates the RK(MK) stages `2..s` of `tab` from `(t, x)` with step `h` into `k[1..s]`;
/// the caller has put the first stage `f(t, x)` into `k[0]` (evaluated, or reused when first
/// same as last). Every evaluation here is counted in `stats.rhs_evals`. Returns the last
/// stage's point `Y_s = x (+) Theta_s` and the raw vector field there (before `dexp_inv`),
/// which a first-same-as-last pair reuses as the next step's first stage.
#[inline(always)]
pub(crate) fn rkmk_stages<S: System>(
    sys: &S,
    tab: &Tableau,
    t: f64,
    h: f64,
    x: &S::State,
    k: &mut [S::Tangent],
    stats: &mut Stats,
) -> (S::State, S::Tangent) {
    let mut last_y = *x;
    let mut last_f = k[0];
    for i in 1..tab.stages() {
        let theta = combine(h, tab.a[i], &k[..i]);
        let (y, v, ki) = sys.rkmk_stage(t + tab.c[i] * h, x, &theta);
        stats.rhs_evals += 1;
        k[i] = ki;
        last_y = y;
        last_f = v;
    }
    (last_y, last_f)
}

/// A tableau known at compile time: with it the stage loop of `ExplicitRk` is unrolled, its
/// coefficients are constants and its zero weights are skipped by the compiler, so explicit
/// Euler compiles to `x (+) h f(x)` with nothing around it (measured in `benches/step.rs`).
pub trait FixedTableau: Send + Sync + 'static {
    const TAB: &'static Tableau;
}

/// A unit type naming a tableau known at compile time: `fixed_tableau!(Name, TABLEAU,
/// "doc")`.
macro_rules! fixed_tableau {
    ($name:ident, $tab:expr, $doc:literal) => {
        #[doc = $doc]
        #[derive(Debug, Clone, Copy, Default)]
        pub struct $name;
        impl $crate::integrate::explicit_rk::FixedTableau for $name {
            const TAB: &'static $crate::integrate::tableau::Tableau = &$tab;
        }
    };
}
pub(super) use fixed_tableau;

/// A stateless one-step method over a tableau type `T` (the stages live on the stack of one
/// step), with `new` (the stage count checked against `MAX_STAGES` at compile time) and
/// `Default`: `tableau_method!(Name, "doc")`.
macro_rules! tableau_method {
    ($name:ident, $doc:literal) => {
        #[doc = $doc]
        #[derive(Debug, Clone, Copy)]
        pub struct $name<S: System, T: FixedTableau> {
            _m: std::marker::PhantomData<(S, T)>,
        }

        impl<S: System, T: FixedTableau> $name<S, T> {
            /// The method of tableau `T` (at most `MAX_STAGES` stages, checked at compile
            /// time).
            pub const fn new() -> Self {
                const {
                    assert!(
                        T::TAB.stages() <= $crate::integrate::tableau::MAX_STAGES,
                        "tableau too large"
                    )
                };
                $name {
                    _m: std::marker::PhantomData,
                }
            }
        }

        impl<S: System, T: FixedTableau> Default for $name<S, T> {
            fn default() -> Self {
                Self::new()
            }
        }
    };
}
pub(super) use tableau_method;

fixed_tableau!(EulerTableau, EULER, "Explicit Euler's tableau as a type.");
fixed_tableau!(Rk4Tableau, RK4, "Classical RK4's tableau as a type.");
tableau_method!(
    ExplicitRk,
    "An explicit Runge-Kutta (Munthe-Kaas) method with the tableau `T`. It holds no state: \
     the stages live on the stack of one step."
);

impl<S: System> ExplicitRk<S, EulerTableau> {
    /// Explicit Euler (Lie-Euler on a Lie group), order 1.
    pub const fn euler() -> Self {
        Self::new()
    }
}

impl<S: System> ExplicitRk<S, Rk4Tableau> {
    /// Classical RK4 (RKMK4 on a Lie group), order 4.
    pub const fn rk4() -> Self {
        Self::new()
    }
}

impl<S: System, T: FixedTableau> FixedStep<S> for ExplicitRk<S, T> {
    fn info(&self) -> MethodInfo {
        MethodInfo::new(T::TAB.name, MethodKind::Explicit, T::TAB.order)
            .with_stages(T::TAB.stages() as u32)
            .with_lie_group(S::LIE)
    }

    /// One step; counts its `stages` RHS evaluations (the caller counts the step).
    #[inline]
    fn step(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        x: &mut S::State,
        stats: &mut Stats,
    ) -> Result<(), Failure> {
        let tab = T::TAB;
        let s = tab.stages();
        let mut k = [S::Tangent::zero(); MAX_STAGES];
        k[0] = sys.rhs(t, x);
        stats.rhs_evals += 1;
        rkmk_stages(sys, tab, t, h, x, &mut k[..s], stats);
        let d = combine(h, tab.b, &k[..s]);
        if !d.is_finite() {
            return Err(Failure::new(
                FailureKind::NonFinite,
                t,
                format!("{}: non-finite step increment", tab.name),
            ));
        }
        *x = sys.retract(x, &d);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::test_support::*;

    /// A `System` identical to `S` except that `dexp_inv` returns `v` unchanged (RKMK without
    /// its correction).
    struct NoDexp<S>(S);
    impl<S: System> System for NoDexp<S> {
        type State = S::State;
        type Tangent = S::Tangent;
        const LIE: bool = S::LIE;
        fn rhs(&self, t: f64, x: &S::State) -> S::Tangent {
            self.0.rhs(t, x)
        }
        fn retract(&self, x: &S::State, d: &S::Tangent) -> S::State {
            self.0.retract(x, d)
        }
        fn normalize(&self, x: &mut S::State) -> bool {
            self.0.normalize(x)
        }
        fn check(&self, t: f64, x: &S::State) -> Result<(), Failure> {
            self.0.check(t, x)
        }
    }

    /// Errors at `t_end` on the free rotor for each step count in `ns`, against the reference.
    fn rotor_errors<S, M>(sys: &S, mut m: M, t_end: f64, ns: &[usize]) -> Vec<f64>
    where
        S: System<State = RotorState>,
        M: FixedStep<S>,
    {
        let rotor = rotor_system();
        let reference = rotor_reference(&rotor, t_end);
        ns.iter()
            .map(|&n| {
                rotor_distance(
                    &run_fixed(&mut m, sys, rotor_initial(&rotor), t_end, n).0,
                    &reference,
                )
            })
            .collect()
    }

    /// Euler and RK4 on the harmonic oscillator (exact solution) converge with orders 1 and 4.
    #[test]
    fn oscillator_orders() {
        let sys = Oscillator;
        let t_end = 1.0;
        let exact = sys.exact(t_end);
        let errors = |m: &mut dyn FixedStep<Oscillator>, ns: &[usize]| -> Vec<f64> {
            ns.iter()
                .map(|&n| {
                    let mut x = sys.initial();
                    let mut st = Stats::default();
                    let h = t_end / n as f64;
                    for k in 0..n {
                        m.step(&sys, k as f64 * h, h, &mut x, &mut st).unwrap();
                    }
                    (x - exact).norm()
                })
                .collect()
        };
        for (m, ns, p) in [
            (
                &mut ExplicitRk::euler() as &mut dyn FixedStep<Oscillator>,
                vec![1000, 2000, 4000],
                1.0,
            ),
            (&mut ExplicitRk::rk4(), vec![10, 20, 40], 4.0),
        ] {
            let errs = errors(m, &ns);
            assert_last_order(&format!("oscillator {}", m.info().name), &errs, p);
        }
    }

    /// RK4 on the (nonlinear) Kepler problem, e = 0.5, over one period (exact solution: the
    /// initial state) has order 4; the step and RHS counts are exact.
    #[test]
    fn kepler_rk4_order_and_counts() {
        let sys = Kepler::new(0.5);
        let t_end = sys.period();
        let ns = [400, 800, 1600, 3200];
        let mut m = ExplicitRk::rk4();
        let mut errs = Vec::new();
        for &n in &ns {
            let (x, st) = run_fixed(&mut m, &sys, sys.initial(), t_end, n);
            assert_eq!(st.steps, n as u64);
            assert_eq!(st.rhs_evals, 4 * n as u64);
            errs.push((x - sys.initial()).norm());
        }
        assert_last_order("kepler rk4", &errs, 4.0);
    }

    /// RKMK Euler and RKMK4 on SO(3) (free rotor, J = diag(1, 2, 3)) converge with orders 1
    /// and 4; without the `dexp_inv` correction RK4 drops to order 2.
    #[test]
    fn rotor_rkmk_orders_and_dexp_correction() {
        let rotor = rotor_system();
        let t_end = 2.0;
        let ns = [1000, 2000, 4000];
        let e1 = rotor_errors(&rotor, ExplicitRk::euler(), t_end, &ns);
        assert_last_order("rotor lie euler", &e1, 1.0);

        let ns = [20, 40, 80, 160];
        let e4 = rotor_errors(&rotor, ExplicitRk::rk4(), t_end, &ns);
        assert_last_order("rotor rkmk4", &e4, 4.0);

        let plain = NoDexp(rotor_system());
        let e2 = rotor_errors(&plain, ExplicitRk::rk4(), t_end, &ns);
        assert_last_order("rotor rk4 without dexp_inv", &e2, 2.0);
        assert!(e2.last().unwrap() > &(100.0 * e4.last().unwrap()));
    }

    /// `info()` reports the tableau's facts and the system's Lie flag.
    #[test]
    fn method_info() {
        let i = FixedStep::<RotorSys>::info(&ExplicitRk::<RotorSys, _>::rk4());
        assert_eq!((i.name, i.order, i.stages), ("rk4", 4, 4));
        assert!(i.lie_group && !i.implicit && !i.adaptive);
        let i = FixedStep::<Oscillator>::info(&ExplicitRk::<Oscillator, _>::euler());
        assert_eq!((i.name, i.order, i.stages), ("euler", 1, 1));
        assert!(!i.lie_group);
    }

    /// A non-finite vector field gives a typed `non_finite` failure and leaves the state as is.
    #[test]
    fn non_finite_is_a_failure() {
        let sys = Blowup { nan: true };
        let mut x = nalgebra::Vector1::new(1.0);
        let mut st = Stats::default();
        let e = ExplicitRk::rk4()
            .step(&sys, 0.0, 0.1, &mut x, &mut st)
            .unwrap_err();
        assert_eq!(e.kind, FailureKind::NonFinite);
        assert_eq!(x[0], 1.0);
    }
}
