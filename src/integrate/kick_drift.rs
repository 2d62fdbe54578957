//! Kick-drift-kick: the symmetric splitting of a mechanical system into its potential part,
//! whose flow at a fixed configuration is a kick of the momenta by the force, and its free
//! (kinetic) part, whose flow on the configuration group a [`FreeFlow`] approximates (Strang
//! splitting; Hairer, Lubich & Wanner, "Geometric Numerical Integration", 2nd ed., sec. II.5
//! and VII.5 on Lie groups). One step of size `h`:
//!
//! ```text
//! (K1)  p <- p + h/2 F(q_n)                  (the force at the step's start configuration)
//! (D)   (q, p) <- Phi_h(q, p)                (the free flow, or its discrete approximation)
//! (K2)  p <- p + h/2 F(q_{n+1})              (the force at the new, caller-normalized one)
//! ```
//!
//! Written once for every [`SplitMechanics`] system (a configuration on a Lie group with its
//! momenta: SO(3) x R^3 for the rigid body; SE(2) for a planar link) and every free flow of
//! it: with the exact free flow, or a composition of exact sub-flows, it is the splitting
//! method; with the discrete free flow of a discrete Lagrangian, the Lie-group variational
//! integrator (Lee, Leok & McClamroch 2007: its discrete Euler-Lagrange equations are (K1), the
//! discrete free flow, (K2)). Every sub-step is a symplectic map and the composition is
//! symmetric, so the method is symplectic, time-reversible and of order 2 whenever the free
//! flow is (symmetric, second order); the free flow keeps the configuration on the group.
//!
//! Cost: one force evaluation per step (`stats.rhs_evals`): the force of (K2) is kept and
//! reused for (K1) of the next step when the state handed back is the one the step produced
//! (as returned or caller-normalized, [`OwnState`]); the free flow may carry its momenta the
//! same way ([`FreeFlow::CARRIES_MOMENTA`]). Failures: the free flow's own (a Newton iteration
//! that does not converge), and a non-finite state (`non_finite`); the state is then unchanged.
use super::own_state::{OwnState, normalized};
use super::{Failure, FailureKind, FixedStep, MethodInfo, Stats, System};

/// A mechanical system in the variables of a kick-drift-kick step: its force at a
/// configuration, its momenta, and the kick.
pub trait SplitMechanics: System
where
    Self::State: Copy + PartialEq,
{
    /// What one force evaluation gives, in the frame the momenta are kept in (the rigid body:
    /// the world force and the body-frame torque).
    type Force: Copy + Default;
    /// The step's variables: configuration and momenta as the free flow moves them.
    type Phase: Copy;

    /// The force at the configuration of `at` (one evaluation).
    fn force(&self, at: &Self::State) -> Self::Force;

    /// The phase of `x`; its momenta are `carried`'s where given (the end of the step that
    /// produced `x`), else computed from the velocity of `x`.
    fn open(&self, x: &Self::State, carried: Option<&Self::Phase>) -> Self::Phase;

    /// The kick `p <- p + s F` by the force `f` (`force`'s value, in the frame the momenta
    /// are kept in).
    fn kick(&self, f: &Self::Force, p: &mut Self::Phase, s: f64);

    /// A state at the phase's configuration (its velocity need not be set): where the next
    /// force is evaluated.
    fn configuration(&self, p: &Self::Phase) -> Self::State;

    /// The state of a phase (the velocity recovered from the momenta).
    fn close(&self, p: &Self::Phase) -> Self::State;
}

/// An approximation of the free (kinetic) flow of systems `S` over one step.
pub trait FreeFlow<S: SplitMechanics>
where
    S::State: Copy + PartialEq,
{
    /// Whether the method carries the momenta of its last step into the next one (instead of
    /// recomputing them from the velocity, whose rounding can bias a conserved quantity).
    const CARRIES_MOMENTA: bool;

    /// What the method is (name, order, implicit, ...).
    fn info(&self) -> MethodInfo;

    /// Checks or prepares what the flow needs of `sys` before a step (nothing is evaluated
    /// yet when it fails).
    fn prepare(&mut self, _sys: &S, _t: f64) -> Result<(), Failure> {
        Ok(())
    }

    /// The free flow over `h`, in place.
    fn drift(
        &mut self,
        sys: &S,
        p: &mut S::Phase,
        t: f64,
        h: f64,
        stats: &mut Stats,
    ) -> Result<(), Failure>;
}

/// The kick-drift-kick method with the free flow `D`.
pub struct KickDriftKick<S: SplitMechanics, D>
where
    S::State: Copy + PartialEq,
{
    flow: D,
    own: OwnState<S::State>,
    /// The force of (K2) of the last step (read only when `own` recognises the state).
    end_force: S::Force,
    /// The closing phase of the last step, kept only for a flow that carries its momenta.
    end_phase: Option<S::Phase>,
}

impl<S: SplitMechanics, D: FreeFlow<S>> KickDriftKick<S, D>
where
    S::State: Copy + PartialEq,
{
    /// The method with the free flow `flow`.
    pub fn with_flow(flow: D) -> Self {
        KickDriftKick {
            flow,
            own: OwnState::default(),
            end_force: S::Force::default(),
            end_phase: None,
        }
    }

    /// The free flow.
    pub fn flow(&self) -> &D {
        &self.flow
    }
}

impl<S: SplitMechanics, D: FreeFlow<S> + Default> Default for KickDriftKick<S, D>
where
    S::State: Copy + PartialEq,
{
    fn default() -> Self {
        Self::with_flow(D::default())
    }
}

impl<S: SplitMechanics, D: FreeFlow<S>> FixedStep<S> for KickDriftKick<S, D>
where
    S::State: Copy + PartialEq,
{
    fn info(&self) -> MethodInfo {
        self.flow.info()
    }

    fn step(
        &mut self,
        sys: &S,
        t: f64,
        h: f64,
        s: &mut S::State,
        stats: &mut Stats,
    ) -> Result<(), Failure> {
        self.flow.prepare(sys, t)?;
        let continuing = self.own.matches(s);
        let f0 = if continuing {
            self.end_force
        } else {
            stats.rhs_evals += 1;
            sys.force(s)
        };
        let momenta = if D::CARRIES_MOMENTA && continuing {
            self.end_phase.as_ref()
        } else {
            None
        };
        let mut p = sys.open(s, momenta);
        // (K1), (D).
        sys.kick(&f0, &mut p, 0.5 * h);
        if let Err(e) = self.flow.drift(sys, &mut p, t, h, stats) {
            self.own.clear();
            return Err(e);
        }
        // (K2) at the caller-normalized configuration: its force is reused next step.
        let at = normalized(sys, &sys.configuration(&p));
        stats.rhs_evals += 1;
        let f1 = sys.force(&at);
        sys.kick(&f1, &mut p, 0.5 * h);
        let out = sys.close(&p);
        if let Err(e) = sys.check(t + h, &out) {
            self.own.clear();
            let name = self.flow.info().name;
            let message = match e.kind {
                FailureKind::NonFinite => format!("{name}: non-finite state"),
                _ => format!("{name}: {}", e.message),
            };
            return Err(Failure::new(e.kind, t + h, message));
        }
        *s = out;
        self.own.record(sys, s);
        self.end_force = f1;
        if D::CARRIES_MOMENTA {
            self.end_phase = Some(p);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::MethodKind;
    use nalgebra::{Vector2, Vector3};

    /// The pendulum `theta'' = -sin theta` on the circle group: configuration a unit complex
    /// number `(cos theta, sin theta)`, momentum the angular velocity (unit inertia). Its free
    /// flow is the rotation at constant rate (exact), so the method is Stormer-Verlet written
    /// on the group.
    struct Pendulum;
    type St = Vector3<f64>;
    impl System for Pendulum {
        type State = St;
        type Tangent = Vector2<f64>;
        const LIE: bool = true;
        fn rhs(&self, _t: f64, x: &St) -> Vector2<f64> {
            Vector2::new(x[2], -x[1])
        }
        fn retract(&self, x: &St, d: &Vector2<f64>) -> St {
            let (s, c) = d[0].sin_cos();
            St::new(x[0] * c - x[1] * s, x[0] * s + x[1] * c, x[2] + d[1])
        }
        fn normalize(&self, x: &mut St) -> bool {
            let n = x[0].hypot(x[1]);
            x[0] /= n;
            x[1] /= n;
            true
        }
        fn check(&self, t: f64, x: &St) -> Result<(), Failure> {
            if x.iter().all(|v| v.is_finite()) {
                Ok(())
            } else {
                Err(Failure::new(FailureKind::NonFinite, t, "non-finite"))
            }
        }
    }
    impl SplitMechanics for Pendulum {
        type Force = f64;
        type Phase = St;
        fn force(&self, at: &St) -> f64 {
            -at[1]
        }
        fn open(&self, x: &St, carried: Option<&St>) -> St {
            St::new(x[0], x[1], carried.map_or(x[2], |p| p[2]))
        }
        fn kick(&self, f: &f64, p: &mut St, s: f64) {
            p[2] += s * f;
        }
        fn configuration(&self, p: &St) -> St {
            *p
        }
        fn close(&self, p: &St) -> St {
            *p
        }
    }
    /// The exact free flow: rotation by `h w`.
    struct Rotation;
    impl FreeFlow<Pendulum> for Rotation {
        const CARRIES_MOMENTA: bool = false;
        fn info(&self) -> MethodInfo {
            MethodInfo::new("verlet_circle", MethodKind::Geometric, 2)
                .with_symplectic(true)
                .with_lie_group(true)
        }
        fn drift(
            &mut self,
            sys: &Pendulum,
            p: &mut St,
            _t: f64,
            h: f64,
            _stats: &mut Stats,
        ) -> Result<(), Failure> {
            *p = sys.retract(p, &Vector2::new(h * p[2], 0.0));
            Ok(())
        }
    }

    fn energy(x: &St) -> f64 {
        0.5 * x[2] * x[2] - x[0]
    }

    /// Second order on the circle (the error after 2 s divides by 4 per halving of the step,
    /// against a fine classical RK4 solution of the angle), one force evaluation a step once
    /// running (the end force is reused), the configuration stays on the circle, and the energy
    /// error stays bounded over 1e5 steps (symplectic: last tenth within 2x the first).
    #[test]
    fn second_order_symplectic_on_the_circle() {
        let f = |y: [f64; 2]| [y[1], -y[0].sin()];
        let (mut y, n, h) = ([1.0_f64, 0.0], 20000, 2.0 / 20000.0);
        for _ in 0..n {
            let k1 = f(y);
            let k2 = f([y[0] + h / 2.0 * k1[0], y[1] + h / 2.0 * k1[1]]);
            let k3 = f([y[0] + h / 2.0 * k2[0], y[1] + h / 2.0 * k2[1]]);
            let k4 = f([y[0] + h * k3[0], y[1] + h * k3[1]]);
            for i in 0..2 {
                y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        let run = |n: usize, t_end: f64, track: &mut dyn FnMut(&St)| {
            let h = t_end / n as f64;
            let mut x = St::new(1.0_f64.cos(), 1.0_f64.sin(), 0.0);
            let mut m = KickDriftKick::<Pendulum, Rotation>::with_flow(Rotation);
            let mut st = Stats::default();
            for k in 0..n {
                m.step(&Pendulum, k as f64 * h, h, &mut x, &mut st).unwrap();
                Pendulum.normalize(&mut x);
                track(&x);
            }
            (x, st)
        };
        let mut errors = Vec::new();
        for n in [50, 100, 200] {
            let mut off = 0.0_f64;
            let (x, st) = run(n, 2.0, &mut |x| {
                off = off.max((x[0].hypot(x[1]) - 1.0).abs())
            });
            assert!(off < 1e-15, "left the circle by {off:e}");
            assert_eq!(st.rhs_evals, n as u64 + 1);
            errors.push((x[1].atan2(x[0]) - y[0]).abs().max((x[2] - y[1]).abs()));
        }
        for w in errors.windows(2) {
            assert!((3.6..4.4).contains(&(w[0] / w[1])), "{errors:?}");
        }
        let e0 = energy(&St::new(1.0_f64.cos(), 1.0_f64.sin(), 0.0));
        let (mut k, mut first, mut last) = (0, 0.0_f64, 0.0_f64);
        run(100_000, 10_000.0, &mut |x| {
            let de = (energy(x) - e0).abs();
            if k < 10_000 {
                first = first.max(de);
            } else if k >= 90_000 {
                last = last.max(de);
            }
            k += 1;
        });
        assert!(first > 0.0 && last <= 2.0 * first, "{first:e} {last:e}");
    }

    /// A foreign state restarts the method (a fresh force evaluation), and a failing state
    /// leaves the state unchanged with a typed failure.
    #[test]
    fn restarts_and_fails_typed() {
        let mut m = KickDriftKick::<Pendulum, Rotation>::with_flow(Rotation);
        let mut st = Stats::default();
        let mut x = St::new(1.0, 0.0, 0.5);
        m.step(&Pendulum, 0.0, 0.1, &mut x, &mut st).unwrap();
        assert_eq!(st.rhs_evals, 2);
        let mut y = St::new(0.0, 1.0, 0.5);
        m.step(&Pendulum, 0.1, 0.1, &mut y, &mut st).unwrap();
        assert_eq!(st.rhs_evals, 4);
        let mut bad = St::new(1.0, 0.0, f64::INFINITY);
        let before = bad;
        let e = m.step(&Pendulum, 0.2, 0.1, &mut bad, &mut st).unwrap_err();
        assert_eq!(e.kind, FailureKind::NonFinite);
        assert!(e.message.starts_with("verlet_circle"), "{}", e.message);
        assert_eq!(bad, before);
    }
}
