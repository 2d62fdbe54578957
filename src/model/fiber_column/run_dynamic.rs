//! One run of the fiber column's dynamic scene: the column of a formulation (`run.rs`), its
//! axial prelude, then the ground-acceleration pulse stepped by one structural method
//! (`newmark`, `hht`, `gen_alpha`, the energy-consistent `midpoint`: the structural module's,
//! on the column as a path-dependent system, `dynamic.rs`) at a fixed step, its steps solved
//! by Newton's iteration, observed at the sample times.
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
//! typed `newton_failure` at the end of that step (the method's failure).
use super::case::Loading;
use super::column::Column;
use super::dynamic::{Ground, Shaken, energies, ground_motion};
use super::run::{ColumnObs, ColumnSetup, Form, Keep, Log, RunOut, build, prelude, steps};
use crate::rotation::RotationChart;
use crate::structural::equilibrium::Newton;
use crate::structural::method::Method;

/// The system the dynamic scene's methods step on chart `C`.
pub type Pulse<C> = Shaken<C, Newton, Ground>;

/// Runs the dynamic scene with `method` at step `dt`.
pub fn run_dynamic<C: RotationChart, M: Method<Pulse<C>>>(
    s: &ColumnSetup,
    form: Form,
    mut method: M,
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
    let mut newton = Newton::new(num.tol, num.max_iter)?;
    let f_static = match prelude(&mut col, &mut newton, s, &mut log) {
        Ok(f) => f,
        Err(e) => {
            out.stats = log.stats;
            out.failure = Some(e.at(0.0));
            return Ok(out);
        }
    };
    let work0 = col.energies();
    let ground = Ground(s.scene.loading.clone());
    let mut p = ground_motion(col, f_static, mass, a0, newton, ground)?;
    let mut state = method.new_state(&p);
    if let Err(f) = method.init(&mut p, 0.0, &mut state, &mut log.stats) {
        out.stats = log.stats;
        out.failure = Some(f);
        return Ok(out);
    }
    // The reaction is reported from the first step on (0 at t = 0, as the stored series).
    let observe = |p: &Pulse<C>, t: f64| {
        let c: &Column<C> = &p.system;
        let d = c.top_displacement();
        let e = energies(p, work0);
        let base = if t > 0.0 {
            c.base_reaction()
        } else {
            nalgebra::Vector3::zeros()
        };
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
    let mut obs = observe(&p, 0.0);
    if keep == Keep::Samples {
        log.samples.push(obs);
    }
    let mut balance_max = 0.0f64;
    for k in 1..=n {
        let t = k as f64 * dt;
        let t0 = (k - 1) as f64 * dt;
        if let Err(f) = method.step(&mut p, t0, dt, &mut state, &mut log.stats) {
            out.failure = Some(f);
            break;
        }
        balance_max = balance_max.max(energies(&p, work0).balance().abs());
        if k % per_sample == 0 || k == n {
            obs = observe(&p, t);
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
