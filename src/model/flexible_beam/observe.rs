//! What a beam run observes, for every formulation alike: the [`Beamlike`] trait (the
//! quantities each model computes from its own coordinates) and the [`BeamObs`] record of one
//! instant (tip deflection and axial tip displacement in the base frame, hub angle and rate,
//! kinetic and strain energy, angular momentum about the axis, the running work integral and
//! the boundary-constraint residual).
//!
//! The work done on the beam (energy balance, since it starts at rest with `E(0) = 0`):
//!
//! - prescribed base: the drive's torque is `dH/dt`, so its work is
//!   `W(t) = int Om dH = Om(t) H(t) - int_0^t H Om' ds`; the integral is the run's extra
//!   quantity `w` (an extra state of the ODE forms, integrated at the method's order; a
//!   trapezoid along the steps of the structural methods, order 2 like them);
//! - free hub: the torque is constant on `[0, t_off)` and zero after, so
//!   `W(t) = tau (theta(min(t, t_off)) - theta(0))`, exact along the discrete path given the
//!   hub angle at `t_off` (a breakpoint: every sample grid holds it).
//!
//! Invariant: for the exact solution `E(t) - W(t) = 0`; the scores divide the difference by
//! the scene's `energy_scale`. Where it fails: a sample grid without `t_off` (refused at
//! loading) leaves the free hub's work undefined after `t_off`.
use nalgebra::DVector;

use super::base::Base;
use crate::structural::SecondOrder;

/// The observable quantities of a beam model (implemented by `fe_exact` and the modal
/// models).
pub trait Beamlike: SecondOrder {
    fn base(&self) -> Base;
    /// The lateral tip displacement in the base frame (m).
    fn tip_deflection(&self, q: &DVector<f64>) -> f64;
    /// The axial tip displacement in the base frame (m).
    fn tip_axial(&self, q: &DVector<f64>) -> f64;
    /// Hub angle (rad) and rate (rad/s).
    fn hub(&self, t: f64, q: &DVector<f64>, v: &DVector<f64>) -> [f64; 2];
    /// Kinetic (with the rigid rotation and the hub) and strain energy (J).
    fn energy(&self, t: f64, q: &DVector<f64>, v: &DVector<f64>) -> (f64, f64);
    /// Angular momentum about the axis (N m s).
    fn momentum(&self, t: f64, q: &DVector<f64>, v: &DVector<f64>) -> f64;
    /// Whether the mass matrix `dr/da` is constant (true for these models on a prescribed
    /// base; a free hub's row and column depend on the deformation). Every `Beamlike` model's
    /// mass matrix outside a free hub's row and column is constant (`ode.rs` relies on it).
    fn constant_mass(&self) -> bool {
        !matches!(self.base(), Base::Free { .. })
    }
    /// A free hub's column of the mass matrix (`dr/da`, column 0; the rest is constant) into
    /// `col`; false when the model does not provide it (its callers then form the whole
    /// mass matrix).
    fn hub_column(&self, q: &DVector<f64>, col: &mut DVector<f64>) -> bool {
        let _ = (q, col);
        false
    }
    /// The largest boundary-constraint residual (0 for a model without constraints).
    fn constraint(&self, q: &DVector<f64>) -> f64 {
        let _ = q;
        0.0
    }
    /// The integrand of the prescribed drive's work integral, `H Om'` (0 for a free hub).
    fn work_rate(&self, t: f64, q: &DVector<f64>, v: &DVector<f64>) -> f64 {
        match self.base().motion(t) {
            Some(m) => self.momentum(t, q, v) * m.accel,
            None => 0.0,
        }
    }
}

/// One observation of a beam run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BeamObs {
    pub tip_deflection: f64,
    pub tip_axial: f64,
    pub hub_angle: f64,
    pub hub_rate: f64,
    pub kinetic: f64,
    pub strain: f64,
    pub momentum: f64,
    /// `int_0^t H Om' ds` (prescribed base; 0 for a free hub).
    pub work_integral: f64,
    pub constraint: f64,
}

/// The observation of `(t, q, v)` with work integral `w`.
pub fn observe<S: Beamlike + ?Sized>(
    sys: &S,
    t: f64,
    q: &DVector<f64>,
    v: &DVector<f64>,
    w: f64,
) -> BeamObs {
    let [hub_angle, hub_rate] = sys.hub(t, q, v);
    let (kinetic, strain) = sys.energy(t, q, v);
    BeamObs {
        tip_deflection: sys.tip_deflection(q),
        tip_axial: sys.tip_axial(q),
        hub_angle,
        hub_rate,
        kinetic,
        strain,
        momentum: sys.momentum(t, q, v),
        work_integral: w,
        constraint: sys.constraint(q),
    }
}

/// The work done on the beam at each sample `(t, obs)` of a run from `t = 0`
/// (module docs); None for a free hub whose samples miss `t_off` while passing it.
pub fn work(base: &Base, samples: &[(f64, BeamObs)]) -> Option<Vec<f64>> {
    match *base {
        Base::SpinUp { .. } => Some(
            samples
                .iter()
                .map(|(t, o)| {
                    let rate = base.motion(*t).map_or(0.0, |m| m.rate);
                    rate * o.momentum - o.work_integral
                })
                .collect(),
        ),
        Base::Free { torque, t_off, .. } => {
            let theta0 = samples.first().map_or(0.0, |s| s.1.hub_angle);
            let at_off = samples
                .iter()
                .find(|(t, _)| (t - t_off).abs() <= 1e-9 * t_off.max(1.0))
                .map(|s| s.1.hub_angle);
            samples
                .iter()
                .map(|(t, o)| {
                    if *t < t_off {
                        Some(torque * (o.hub_angle - theta0))
                    } else {
                        at_off.map(|a| torque * (a - theta0))
                    }
                })
                .collect()
        }
    }
}

/// `E - W` at each sample (J; module docs).
pub fn balance(base: &Base, samples: &[(f64, BeamObs)]) -> Option<Vec<f64>> {
    let w = work(base, samples)?;
    Some(
        samples
            .iter()
            .zip(w)
            .map(|((_, o), w)| o.kinetic + o.strain - w)
            .collect(),
    )
}
