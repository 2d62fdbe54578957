//! Tests of the column's dynamic step (the structural module's Newmark, average
//! acceleration, on the column as a path-dependent system) against the stored OpenSees run
//! of the RC column under the ground-acceleration pulse; the scene's pieces (the column after
//! the axial prelude, the pulse, the damping, a driver of any structural method) shared with
//! `dynamic_tests.rs`.
use nalgebra::DVector;

use super::column::Column;
use super::dynamic::{Energies, Shaken, energies, ground_motion};
use super::rc_tests::{H, P, rc_column, reference, reference_column};
use crate::integrate::{Failure, Stats};
use crate::rotation::So3;
use crate::structural::equilibrium::Newton;
use crate::structural::method::Method;
use crate::structural::newmark::Newmark;
use crate::structural::newton::NewtonOptions;
use crate::structural::state::State;

/// The damping coefficient `a0 = 2 zeta omega_1` of the OpenSees script (zeta = 0.02,
/// omega_1 = 14.820708227335706 rad/s after the axial prelude).
pub(super) const A0: f64 = 0.5928283290934282;
pub(super) const G0: f64 = 9.80665;
/// OpenSees' step (s) and number of steps.
pub(super) const DT: f64 = 5e-4;
pub(super) const STEPS: usize = 10_000;

/// The ground acceleration (m/s^2): half a g at 2 Hz for the first second.
pub(super) fn ground(t: f64) -> f64 {
    if t <= 1.0 {
        0.5 * G0 * (std::f64::consts::TAU * t / 0.5).sin()
    } else {
        0.0
    }
}

/// The c01 column after the axial prelude (P in 10 load steps) and its static load.
pub(super) fn prelude() -> (Column<So3>, DVector<f64>) {
    let mut col: Column<So3> = rc_column(false, 1, true);
    let mut f = DVector::zeros(col.dim());
    for k in 1..=10 {
        f[col.top_dof(2)] = -P * k as f64 / 10.0;
        col.step(&mut newton(), &f, None).unwrap();
    }
    (col, f)
}

/// The tests' Newton: 1e-20 J, 50 iterations.
fn newton() -> Newton {
    Newton::new(1e-20, 50).unwrap()
}

/// The scene as the structural methods see it.
pub(super) type Scene = Shaken<So3, Newton, fn(f64) -> f64>;

/// A structural method stepping the scene at a fixed step from the prelude's state.
pub(super) struct Driver<M> {
    pub scene: Scene,
    method: M,
    state: State,
    pub stats: Stats,
    h: f64,
    k: u64,
    work0: (f64, f64),
}

impl<M: Method<Scene>> Driver<M> {
    /// The scene's driver with `method` at step `h`.
    pub fn new(mut method: M, h: f64) -> Self {
        let (col, f) = prelude();
        let work0 = col.energies();
        let ground: fn(f64) -> f64 = ground;
        let mut scene = ground_motion(col, f, P / G0, A0, newton(), ground).unwrap();
        let mut state = method.new_state(&scene);
        let mut stats = Stats::default();
        method
            .init(&mut scene, 0.0, &mut state, &mut stats)
            .unwrap();
        Driver {
            scene,
            method,
            state,
            stats,
            h,
            k: 0,
            work0,
        }
    }

    /// One step.
    pub fn step(&mut self) -> Result<(), Failure> {
        let t = self.k as f64 * self.h;
        self.method
            .step(&mut self.scene, t, self.h, &mut self.state, &mut self.stats)?;
        self.k += 1;
        Ok(())
    }

    /// The column.
    pub fn column(&self) -> &Column<So3> {
        &self.scene.system
    }

    /// The energies since the start.
    pub fn energies(&self) -> Energies {
        energies(&self.scene, self.work0)
    }
}

// Newmark's average-acceleration rule on the c01 column with the top mass P/g0 and 2 %
// mass-proportional damping, at OpenSees' step 5e-4 s: the peak top displacement and the
// residual one at 5 s lie within 2 % of the peak of OpenSees' Newmark run of the same column
// (measured: the whole record within 2e-12 of the peak).
#[test]
fn rc_pulse_newmark_matches_opensees() {
    let mut d = Driver::new(Newmark::new(NewtonOptions::default()).unwrap(), DT);
    let mut top = vec![0.0];
    for step in 1..=STEPS {
        d.step()
            .unwrap_or_else(|e| panic!("step {step}: {}", e.message));
        if step % 10 == 0 {
            top.push(d.column().top_displacement().x);
        }
    }
    let r = reference("rc_pulse");
    let want = reference_column(&r, "top_displacement");
    assert_eq!(want.len(), top.len());
    let peak_ref = want.iter().fold(0.0f64, |p, x| p.max(x.abs()));
    let peak = top.iter().fold(0.0f64, |p, x| p.max(x.abs()));
    let (end, end_ref) = (top[top.len() - 1], want[want.len() - 1]);
    let worst = top
        .iter()
        .zip(&want)
        .fold(0.0f64, |w, (x, y)| w.max((x - y).abs()));
    eprintln!(
        "rc_pulse newmark: peak {peak:.6e} vs {peak_ref:.6e} m, residual {end:.6e} vs {end_ref:.6e} m, max difference {:.3e} of the peak, {} iterations (H = {H} m)",
        worst / peak_ref,
        d.stats.newton_iters
    );
    assert!((peak - peak_ref).abs() < 0.02 * peak_ref);
    assert!((end - end_ref).abs() < 0.02 * peak_ref);
    assert!(worst < 1e-9 * peak_ref);
}
