//! One run of the fiber column's dynamic scene: the column of a formulation (`run.rs`), its
//! axial prelude, then the ground-acceleration pulse stepped by one scheme of `dynamic.rs`
//! (Newmark, HHT, generalized-alpha, the energy-consistent midpoint rule) at a fixed step,
//! observed at the sample times.
//!
//! The energies of a dynamic run count from `t = 0`, the state after the prelude
//! (`dynamic.rs`, one trapezoid quadrature for every scheme): `energy_kinetic`, the change of
//! the recoverable strain energy `energy_strain`, `energy_dissipated` the hysteretic
//! (elements' work minus recoverable) plus the damping dissipation, `work_input` the work
//! of the ground motion's load and of the axial load. Their balance
//! `kinetic + strain + dissipated - input` is tracked at every step; its largest magnitude
//! is the run's `balance_max`.
//!
//! Where it fails: a step whose Newton iteration does not converge ends the run with a
//! typed `newton_failure` at that step's `t`.
use super::case::Loading;
use crate::rotation::RotationChart;
use super::column::Algorithm;
use super::dynamic::{Dynamic, Scheme};
use super::run::{ColumnObs, Form, Keep, Log, RunOut, ColumnSetup, build, failure, prelude, steps};

/// Runs the dynamic scene with `scheme` at step `dt`.
pub fn run_dynamic<C: RotationChart>(
    s: &ColumnSetup,
    form: Form,
    scheme: Scheme,
    dt: f64,
    keep: Keep,
) -> Result<RunOut, String> {
    let Loading::Pulse { mass, a0, .. } = s.scene.loading else {
        return Err("a static or cyclic scene needs a newton_* algorithm".into());
    };
    let (n, per_sample, _) = steps(s, dt)?;
    let mut col = build::<C>(s, form)?;
    let num = &s.case.numerics;
    let mut log = Log::new(keep);
    let mut out = RunOut::default();
    let f_static = match prelude(&mut col, s, &mut log) {
        Ok(f) => f,
        Err(e) => {
            out.stats = log.stats;
            out.failure = Some(failure(0.0, e));
            return Ok(out);
        }
    };
    let mut dy = Dynamic::new(col, f_static, mass, a0, scheme, dt)?;
    let ground = |t: f64| s.scene.loading.ground(t);
    let observe = |dy: &Dynamic<C>, t: f64| {
        let c = dy.column();
        let d = c.top_displacement();
        let e = dy.energies();
        let base = dy.base_reaction();
        ColumnObs {
            t,
            top_displacement: d.x,
            top_axial: d.z,
            top_rotation: c.top_turn(),
            base_shear: -base.x,
            axial_force: -base.z,
            energy_kinetic: e.kinetic,
            energy_strain: e.strain,
            energy_dissipated: e.hysteretic + e.damping,
            work_input: e.input,
            equilibrium_residual: None,
        }
    };
    let mut obs = observe(&dy, 0.0);
    if keep == Keep::Samples {
        log.samples.push(obs);
    }
    let mut balance_max = 0.0f64;
    for k in 1..=n {
        let t = k as f64 * dt;
        match dy.step(&ground, num.tol, num.max_iter, Algorithm::Newton) {
            Ok(c) => log.count(c),
            Err(e) => {
                out.failure = Some(failure(t, e));
                break;
            }
        }
        balance_max = balance_max.max(dy.energies().balance().abs());
        if k % per_sample == 0 || k == n {
            obs = observe(&dy, t);
            if keep == Keep::Samples && k % per_sample == 0 {
                log.samples.push(obs);
            }
        }
    }
    if keep == Keep::Final {
        log.samples.push(obs);
    }
    out.stats = log.stats;
    out.samples = log.samples;
    out.peak_load = log.peak_load;
    out.balance_max = Some(balance_max);
    Ok(out)
}
