//! Crouch-Grossman methods: explicit Runge-Kutta methods on a Lie group whose stages are
//! products of exponentials instead of one exponential of a sum (Crouch & Grossman, J.
//! Nonlinear Sci. 3, 1993; Owren & Marthinsen, BIT 39, 1999, "Runge-Kutta methods adapted
//! to manifolds and based on rigid frames").
//!
//! With `(+)` = `System::retract` (right or left action of `exp`), one step is
//!
//! ```text
//! Y_i     = (...((x (+) h a_i1 K_1) (+) h a_i2 K_2) ...) (+) h a_i,i-1 K_i-1,
//! K_i     = f(t + c_i h, Y_i),
//! x_{n+1} = (...((x (+) h b_1 K_1) (+) h b_2 K_2) ...) (+) h b_s K_s.
//! ```
//!
//! The increments are applied in stage order, `K_1` nearest to `x`: `x exp(a_1 K_1) exp(a_2
//! K_2)` with the body trivialisation, `exp(a_2 K_2) exp(a_1 K_1) x` with the spatial one
//! (the two are mirror images under `g -> g^-1`, so the same order conditions hold). No
//! `dexp_inv` is needed; instead the coefficients must satisfy extra, non-commutative order
//! conditions (Owren & Marthinsen 1999, sec. 4): for order 3, besides the four classical
//! ones, `sum_i b_i^2 c_i + 2 sum_{i<j} b_i c_i b_j = 1/3`.
//!
//! Methods: `lie_euler` (1 stage, order 1; the same map as RKMK Euler) and `cg3` (3 stages,
//! order 3; Crouch & Grossman 1993: `c = (0, 3/4, 17/24)`, `a21 = 3/4`, `a31 = 119/216`,
//! `a32 = 17/108`, `b = (13/51, -2/3, 24/17)`). On an additive system the retractions are
//! sums and the methods are the classical RK methods of the same tableau (orders 1 and 3).
//! Invariants: the state moves only by `retract` (stays on the group up to rounding); the
//! stages are a fixed array on the stack of each step (no allocation). Failure: a non-finite
//! stage value is a `non_finite` failure, the state is left unchanged.
use super::explicit_rk::{FixedTableau, fixed_tableau, tableau_method};
use super::tableau::{MAX_STAGES, Tableau};
use super::{Failure, FailureKind, FixedStep, MethodInfo, MethodKind, Stats, System};
use crate::math::vector::Vector;

/// Lie-Euler: `x (+) h f(t, x)`.
pub const LIE_EULER: Tableau = Tableau {
    name: "lie_euler",
    order: 1,
    c: &[0.0],
    a: &[&[]],
    b: &[1.0],
};

/// Crouch & Grossman's third-order method.
pub const CG3: Tableau = Tableau {
    name: "cg3",
    order: 3,
    c: &[0.0, 3.0 / 4.0, 17.0 / 24.0],
    a: &[&[], &[3.0 / 4.0], &[119.0 / 216.0, 17.0 / 108.0]],
    b: &[13.0 / 51.0, -2.0 / 3.0, 24.0 / 17.0],
};

fixed_tableau!(LieEulerTableau, LIE_EULER, "Lie-Euler's tableau as a type.");
fixed_tableau!(Cg3Tableau, CG3, "CG3's tableau as a type.");
tableau_method!(
    CrouchGrossman,
    "The Crouch-Grossman method of tableau `T` (coefficients satisfying the CG order \
     conditions), known at compile time like `ExplicitRk`'s: the stage loop is unrolled. It \
     holds no state; the stages live on the stack of one step."
);

impl<S: System> CrouchGrossman<S, LieEulerTableau> {
    /// Lie-Euler, order 1.
    pub const fn lie_euler() -> Self {
        Self::new()
    }
}

impl<S: System> CrouchGrossman<S, Cg3Tableau> {
    /// CG3, order 3.
    pub const fn cg3() -> Self {
        Self::new()
    }
}

/// `x (+) h w_1 k_1 (+) h w_2 k_2 ...`, skipping zero weights.
#[inline(always)]
fn compose<S: System>(sys: &S, x: &S::State, h: f64, w: &[f64], k: &[S::Tangent]) -> S::State {
    let mut y = *x;
    for (wi, ki) in w.iter().zip(k) {
        if *wi != 0.0 {
            y = sys.retract(&y, &ki.scaled(h * wi));
        }
    }
    y
}

impl<S: System, T: FixedTableau> FixedStep<S> for CrouchGrossman<S, T> {
    fn info(&self) -> MethodInfo {
        MethodInfo::new(T::TAB.name, MethodKind::Geometric, T::TAB.order)
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
        let mut finite = true;
        for i in 0..s {
            let y = compose(sys, x, h, tab.a[i], &k[..i]);
            k[i] = sys.rhs(t + tab.c[i] * h, &y);
            stats.rhs_evals += 1;
            finite &= k[i].is_finite();
        }
        if !finite {
            return Err(Failure::new(
                FailureKind::NonFinite,
                t,
                format!("{}: non-finite stage value", tab.name),
            ));
        }
        *x = compose(sys, x, h, tab.b, &k[..s]);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::explicit_rk::ExplicitRk;
    use crate::integrate::tableau::trees::{gamma, worst};
    use crate::integrate::test_support::*;

    /// `run_fixed`'s end state, after asserting its step and RHS counts (`stages` a step).
    fn run<S: System, M: FixedStep<S>>(
        m: &mut M,
        sys: &S,
        x0: S::State,
        t: f64,
        n: usize,
    ) -> S::State {
        let (x, st) = run_fixed(m, sys, x0, t, n);
        assert_eq!(
            (st.steps, st.rhs_evals),
            (n as u64, (n * m_stages(m)) as u64)
        );
        x
    }

    fn m_stages<S: System, M: FixedStep<S>>(m: &M) -> usize {
        m.info().stages as usize
    }

    /// Left side of the non-commutative order-3 condition `sum b_i^2 c_i + 2 sum_{i<j}
    /// b_i c_i b_j` (must be 1/3).
    fn noncommutative3(tab: &Tableau) -> f64 {
        let (b, c) = (tab.b, tab.c);
        let mut s = 0.0;
        for i in 0..b.len() {
            s += b[i] * b[i] * c[i];
            for j in i + 1..b.len() {
                s += 2.0 * b[i] * c[i] * b[j];
            }
        }
        s
    }

    /// Kutta's classical third-order method: order 3 as RK, but it violates the
    /// non-commutative condition (13/36 instead of 1/3), so as a CG method it has order 2.
    const KUTTA3: Tableau = Tableau {
        name: "kutta3",
        order: 3,
        c: &[0.0, 0.5, 1.0],
        a: &[&[], &[0.5], &[-1.0, 2.0]],
        b: &[1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    };
    struct Kutta3Tableau;
    impl FixedTableau for Kutta3Tableau {
        const TAB: &'static Tableau = &KUTTA3;
    }

    /// CG3 satisfies the classical conditions up to order 3 (row sums included) and the
    /// non-commutative one, to rounding (all coefficients O(1), so 1e-15).
    #[test]
    fn cg3_order_conditions() {
        for i in 0..3 {
            let s: f64 = CG3.a[i].iter().sum();
            assert!((s - CG3.c[i]).abs() < 1e-15);
        }
        let (u, r, t) = worst(&CG3, CG3.b, 1..=3, |t| 1.0 / gamma(t));
        assert!(u <= 64.0, "tree {t}: residual {r:e}");
        assert!((noncommutative3(&CG3) - 1.0 / 3.0).abs() < 1e-15);
        let (u, _, _) = worst(&KUTTA3, KUTTA3.b, 1..=3, |t| 1.0 / gamma(t));
        assert!(u <= 64.0);
        assert!((noncommutative3(&KUTTA3) - 13.0 / 36.0).abs() < 1e-15);
    }

    /// Lie-Euler is the same map as RKMK Euler: 100 steps on the rotor agree to round-off.
    #[test]
    fn lie_euler_equals_rkmk_euler() {
        let sys = rotor_system();
        let x0 = rotor_initial(&sys);
        let a = run(&mut CrouchGrossman::lie_euler(), &sys, x0, 1.0, 100);
        let b = run(&mut ExplicitRk::euler(), &sys, x0, 1.0, 100);
        let d = rotor_distance(&a, &b);
        eprintln!("lie_euler vs rkmk euler: {d:e}");
        assert!(d <= 1e-14);
    }

    /// On the free rotor (SO(3), J = diag(1, 2, 3)) lie_euler has order 1 and cg3 order 3;
    /// Kutta's method used as a CG method drops to order 2 (the non-commutative condition).
    #[test]
    fn rotor_orders() {
        let sys = rotor_system();
        let reference = rotor_reference(&sys, 2.0);
        fn errs<T: FixedTableau>(sys: &RotorSys, reference: &RotorState, ns: &[usize]) -> Vec<f64> {
            ns.iter()
                .map(|&n| {
                    let mut m = CrouchGrossman::<RotorSys, T>::new();
                    let x = run(&mut m, sys, rotor_initial(sys), 2.0, n);
                    rotor_distance(&x, reference)
                })
                .collect()
        }
        for (e, tab, p) in [
            (
                errs::<LieEulerTableau>(&sys, &reference, &[1000, 2000, 4000]),
                &LIE_EULER,
                1.0,
            ),
            (
                errs::<Cg3Tableau>(&sys, &reference, &[50, 100, 200, 400]),
                &CG3,
                3.0,
            ),
            (
                errs::<Kutta3Tableau>(&sys, &reference, &[50, 100, 200, 400]),
                &KUTTA3,
                2.0,
            ),
        ] {
            assert_last_order(&format!("rotor {}", tab.name), &e, p);
        }
    }

    /// On an additive system CG3 is a classical third-order RK method (Kepler, e = 0.5, one
    /// period).
    #[test]
    fn kepler_cg3_order() {
        let sys = Kepler::new(0.5);
        let ns = [400, 800, 1600, 3200];
        let e: Vec<f64> = ns
            .iter()
            .map(|&n| {
                let x = run(
                    &mut CrouchGrossman::cg3(),
                    &sys,
                    sys.initial(),
                    sys.period(),
                    n,
                );
                (x - sys.initial()).norm()
            })
            .collect();
        assert_last_order("kepler cg3", &e, 3.0);
    }

    /// A NaN stage is a `non_finite` failure and leaves the state unchanged.
    #[test]
    fn non_finite_is_a_failure() {
        let sys = Blowup { nan: true };
        let mut x = nalgebra::Vector1::new(2.0);
        let e = CrouchGrossman::cg3()
            .step(&sys, 0.0, 0.1, &mut x, &mut Stats::default())
            .unwrap_err();
        assert_eq!(e.kind, FailureKind::NonFinite);
        assert_eq!(x[0], 2.0);
    }
}
