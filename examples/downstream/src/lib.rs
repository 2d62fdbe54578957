//! A user's own integrator, outside mbdbench: Heun's method (the explicit trapezoidal rule,
//! order 2; as Runge-Kutta-Munthe-Kaas on Lie-group charts), written once for every system
//! through mbdbench's method face. `tests/gate.rs` scores it with the suite and fails when it
//! regresses past its gate: the pull-request gate of the crate that owns the method.
//!
//! `MBDBENCH_DOWNSTREAM_BREAK=1` perturbs its second weight (1/2 -> 0.55), the kind of slip a
//! pull request makes: the method then drops to order 1 and its gate fails.
use mbdbench::integrate::{Failure, FixedStep, MethodInfo, MethodKind, Stats, System};
use mbdbench::math::vector::Vector;
use mbdbench::methods::FixedStepMethod;
use std::marker::PhantomData;

/// Heun's method, for every system, with its weights `(b1, b2)` (`(1/2, 1/2)`).
pub struct Heun {
    pub b: [f64; 2],
}

impl Heun {
    /// Heun's weights, or the broken ones when `MBDBENCH_DOWNSTREAM_BREAK` is set.
    pub fn from_env() -> Heun {
        let broken = std::env::var_os("MBDBENCH_DOWNSTREAM_BREAK").is_some();
        Heun {
            b: [0.5, if broken { 0.55 } else { 0.5 }],
        }
    }
}

/// Heun's method on systems of type `S`.
pub struct HeunOn<S> {
    b: [f64; 2],
    _s: PhantomData<S>,
}

impl<S: System> FixedStep<S> for HeunOn<S> {
    fn info(&self) -> MethodInfo {
        MethodInfo::new("heun", MethodKind::Explicit, 2)
            .with_stages(2)
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
        let (_, _, k2) = sys.rkmk_stage(t + h, x, &k1.scaled(h));
        stats.rhs_evals += 2;
        let mut dx = k1.scaled(self.b[0] * h);
        dx.axpy(self.b[1] * h, &k2);
        let next = sys.retract(x, &dx);
        sys.check(t + h, &next)?;
        *x = next;
        Ok(())
    }
}

impl FixedStepMethod for Heun {
    type On<S: System> = HeunOn<S>;
    fn on<S: System>(&self) -> HeunOn<S> {
        HeunOn {
            b: self.b,
            _s: PhantomData,
        }
    }
}
