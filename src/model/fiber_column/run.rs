//! One run of a fiber-column scene: the column of a formulation built from the case
//! (`force_based` with the case's element count, `force_based_fine`, `disp_based_nN`), its
//! prelude (the axial load in `axial_steps` load steps, before `t = 0`, documented in
//! cases/README.md) and the stepping of its loading with one solution algorithm, observed at
//! the sample times.
//!
//! Pseudo-time: a static scene's `t` is the load factor (the tip load `t F` or `t M`), a
//! cyclic scene's the protocol's increment count (the top moves `increment` per unit of
//! `t`), a dynamic scene's real time. A step `dt` must divide the sample spacing (and, for
//! a cyclic scene, be a whole number of increments landing on every reversal).
//!
//! Energies along the run (J), one quadrature for all: `energy_strain` the elements'
//! recoverable energy and `energy_dissipated` the elements' work minus it (the fibers'
//! work by the trapezoid rule on their stress-strain paths, `material/`), `work_input` the
//! work of the applied loads by the trapezoid rule on the steps: the tip load against the
//! tip's displacement or rotation, and for a cyclic scene `V du + N dw` (base shear against
//! the top's lateral displacement, axial force against its axial one), the axial prelude's
//! work included (the elements' work includes it).
//! `equilibrium_residual` (at score times, when asked) is the largest out-of-balance force
//! after a fresh state determination of every element at the converged configuration.
//!
//! Where it fails: a load step past the column's limit point (load control), an element
//! that does not converge even with its increment cut 64 times, or a Newton iteration
//! limit: each ends the run with a typed `newton_failure` at the step's `t`; iterations past
//! the run's budgets (`max_rhs_evals`, `max_work`: `meter.rs`) end it as `work_limit`.
use nalgebra::DVector;

use super::basic::{Basic, DispBased, ForceBased};
use super::case::{ColumnCase, ColumnScene, Loading};
use super::column::{Column, StepCount};
use super::estimate::Mesh;
use super::meter::Meter;
use super::section::Section;
use crate::case::steps_dividing;
use crate::integrate::{Failure, Stats};
use crate::rotation::RotationChart;
use crate::run::Grid;
use crate::structural::equilibrium::{Equilibrium, Newton};
use crate::structural::path::{PathFailure, Prescribed};

/// What a run function needs.
#[derive(Debug, Clone)]
pub struct ColumnSetup {
    pub case: ColumnCase,
    pub scene: ColumnScene,
    pub grid: Grid,
    /// The case's budgets: the steps (the prelude's included), the state determinations and
    /// element iterations, the work units (`meter.rs`).
    pub max_steps: u64,
    pub max_rhs_evals: u64,
    pub max_work: u64,
}

/// One observation of the column (SI units; energies in J).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ColumnObs {
    pub t: f64,
    /// The top's displacement across the axis (global x, the bending plane), m.
    pub top_displacement: f64,
    /// The top's displacement along the axis (global z, negative when shortening), m.
    pub top_axial: f64,
    /// The top's unwrapped in-plane rotation (about global y), rad.
    pub top_rotation: f64,
    /// Minus the support's horizontal reaction, N.
    pub base_shear: f64,
    /// Minus the support's vertical reaction (compression negative), N.
    pub axial_force: f64,
    pub energy_kinetic: f64,
    pub energy_strain: f64,
    pub energy_dissipated: f64,
    pub work_input: f64,
    /// The equilibrium check's largest out-of-balance force (N or N m), when made.
    pub equilibrium_residual: Option<f64>,
}

/// A formulation: the element kind and count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Form {
    /// Force-based elements: the case's `elements` (`Fine`: `fine_elements`).
    ForceBased,
    ForceBasedFine,
    /// `n` displacement-based elements.
    DispBased(usize),
}

/// What a run keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Keep {
    /// The final observation only (the timing pass).
    Final,
    /// Every sample, and the equilibrium check at the score times.
    Samples,
}

/// A run's result.
#[derive(Debug, Clone, Default)]
pub struct RunOut {
    pub stats: Stats,
    pub failure: Option<Failure>,
    pub samples: Vec<ColumnObs>,
    /// The largest applied load over the run (N or N m): the tip load, the axial load, the
    /// prescribed displacement's reaction.
    pub peak_load: f64,
    /// A dynamic run's largest `|energy balance|` over its steps (J).
    pub balance_max: Option<f64>,
}

/// The column of a formulation (errors name the case key at fault).
pub fn build<C: RotationChart>(s: &ColumnSetup, form: Form) -> Result<Column<C>, String> {
    let n = &s.case.numerics;
    let (count, force) = match form {
        Form::ForceBased => (n.elements, true),
        Form::ForceBasedFine => (
            n.fine_elements
                .ok_or("force_based_fine needs numerics.fine_elements")?,
            true,
        ),
        Form::DispBased(k) => (k, false),
    };
    let h = s.case.height / count as f64;
    let section = &s.scene.section.build()?;
    let mut els = Vec::with_capacity(count);
    for _ in 0..count {
        els.push(if force {
            Basic::Force(Box::new(ForceBased::new(
                h,
                s.case.gj,
                section,
                n.points,
                n.element_tol,
                n.element_max_iter,
            )?))
        } else {
            Basic::Disp(DispBased::new(h, s.case.gj, section, n.points)?)
        });
    }
    let mut col = Column::new(s.case.height, els)?;
    let fibers = match section {
        Section::Fiber(f) => f.fibers().len() as f64,
        Section::Elastic(_) => 1.0,
    };
    let mesh = Mesh {
        count: count as f64,
        points: n.points as f64,
        fibers,
        force,
    };
    col.set_meter(Meter::new(s.max_rhs_evals, s.max_work, &mesh));
    Ok(col)
}

/// The axial prelude's load steps of a scene (0 without an axial load).
pub fn prelude_steps(loading: &Loading) -> u64 {
    match *loading {
        Loading::Cyclic { axial_steps, .. } | Loading::Pulse { axial_steps, .. } => {
            axial_steps as u64
        }
        _ => 0,
    }
}

/// The axial prelude of a scene with an axial load (in its load steps, load control, plain
/// Newton, before `t = 0`): returns the load vector with the axial load in place (zero for
/// a scene without one). Its work goes into the log's input work (the elements' work counts
/// it).
pub(super) fn prelude<C: RotationChart>(
    col: &mut Column<C>,
    newton: &mut Newton,
    s: &ColumnSetup,
    log: &mut Log,
) -> Result<DVector<f64>, PathFailure> {
    let mut f = DVector::zeros(col.dim());
    let (axial, steps) = match s.scene.loading {
        Loading::Cyclic {
            axial, axial_steps, ..
        }
        | Loading::Pulse {
            axial, axial_steps, ..
        } => (axial, axial_steps),
        _ => return Ok(f),
    };
    let top = col.top_dof(2);
    for j in 1..=steps {
        let (f0, z0) = (f[top], col.top_displacement().z);
        f[top] = -axial * j as f64 / steps as f64;
        let (c, _) = col.step(newton, &f, None)?;
        log.count(c);
        log.work += 0.5 * (f0 + f[top]) * (col.top_displacement().z - z0);
    }
    log.peak_load = axial;
    Ok(f)
}

/// The steps of a run at `dt`, checked against the grid and the case's budget: `(steps,
/// steps per sample, steps per score)`.
pub(super) fn steps(s: &ColumnSetup, dt: f64) -> Result<(u64, u64, u64), String> {
    let g = &s.grid;
    let n = steps_dividing(g.t_end, dt)
        .ok_or_else(|| format!("the step {dt} does not divide t_end = {}", g.t_end))?;
    let per_sample = steps_dividing(g.sample_every, dt).ok_or_else(|| {
        format!(
            "the step {dt} does not divide sample_every = {}",
            g.sample_every
        )
    })?;
    let per_score = steps_dividing(g.score_every, dt).ok_or_else(|| {
        format!(
            "the step {dt} does not divide score_every = {}",
            g.score_every
        )
    })?;
    let prelude = prelude_steps(&s.scene.loading);
    if n.saturating_add(prelude) > s.max_steps {
        return Err(format!(
            "{n} steps after {prelude} prelude steps are over the case's max_steps = {}",
            s.max_steps
        ));
    }
    Ok((n, per_sample, per_score))
}

/// The top's position at a step: displacement across and along the axis (m), turn (rad).
#[derive(Default, Clone, Copy)]
struct Top {
    across: f64,
    along: f64,
    turn: f64,
}

/// The run's bookkeeping: counters, the input work and the samples.
pub(super) struct Log {
    pub(super) stats: Stats,
    pub(super) work: f64,
    /// The top's displacement across and along the axis and its turn at the last step,
    /// for the input work's trapezoid.
    last: Top,
    pub(super) samples: Vec<ColumnObs>,
    pub(super) peak_load: f64,
    keep: Keep,
}

impl Log {
    pub(super) fn new(keep: Keep) -> Self {
        Log {
            stats: Stats::default(),
            work: 0.0,
            last: Top::default(),
            samples: vec![],
            peak_load: 0.0,
            keep,
        }
    }

    pub(super) fn count(&mut self, c: StepCount) {
        self.stats.steps += 1;
        self.stats.newton_iters += c.iterations as u64;
        // A state determination per iteration plus the final one of the step.
        self.stats.rhs_evals += c.iterations as u64 + 1;
        self.stats.element_iters += c.element_iterations;
    }

    /// The observation of the column now.
    fn observe<C: RotationChart>(
        &self,
        col: &Column<C>,
        t: f64,
        base: nalgebra::Vector3<f64>,
    ) -> ColumnObs {
        let d = col.top_displacement();
        let (work, recoverable) = col.energies();
        ColumnObs {
            t,
            top_displacement: d.x,
            top_axial: d.z,
            top_rotation: col.top_turn(),
            base_shear: -base.x,
            axial_force: -base.z,
            energy_kinetic: 0.0,
            energy_strain: recoverable,
            energy_dissipated: work - recoverable,
            work_input: self.work,
            equilibrium_residual: None,
        }
    }
}

/// The constructor of a solution algorithm from the case's `numerics.tol` (J) and
/// `max_iter` (`Newton::new` and its siblings).
pub type Solver<E> = fn(f64, usize) -> Result<E, String>;

/// What a static scene controls: the loaded unknown and the load's value per unit of `t`
/// (a tip force or moment), or none for a cyclic scene, whose step `dt` must be a whole number
/// of protocol increments landing on every reversal (an error says why not).
fn control<C: RotationChart>(
    s: &ColumnSetup,
    col: &Column<C>,
    dt: f64,
) -> Result<(Option<usize>, f64), String> {
    Ok(match s.scene.loading {
        Loading::TipForce(v) => (Some(col.top_dof(0)), v),
        Loading::TipMoment(v) => (Some(col.top_dof(4)), v),
        Loading::Cyclic { ref protocol, .. } => {
            let k = dt.round() as u64;
            if (dt - dt.round()).abs() > 1e-9 || k == 0 {
                return Err(format!(
                    "the step {dt} is not a whole number of protocol increments"
                ));
            }
            if let Some(i) = protocol.skipped_reversal(k) {
                return Err(format!(
                    "the step {dt} skips the protocol's reversal at t = {i}; a step must divide \
                     every protocol segment"
                ));
            }
            (None, 0.0)
        }
        Loading::Pulse { .. } => return Err("a dynamic scene needs a dynamic integrator".into()),
    })
}

/// Runs a static or cyclic scene with the algorithm `solver` makes at step `dt` (the axial
/// prelude with plain Newton).
pub fn run_static<C: RotationChart, E: Equilibrium<Column<C>>>(
    s: &ColumnSetup,
    form: Form,
    solver: Solver<E>,
    dt: f64,
    keep: Keep,
) -> Result<RunOut, String> {
    let (n, per_sample, per_score) = steps(s, dt)?;
    let mut col = build::<C>(s, form)?;
    let num = &s.case.numerics;
    let mut newton = Newton::new(num.tol, num.max_iter)?;
    let mut algorithm = solver(num.tol, num.max_iter)?;
    let mut log = Log::new(keep);
    let mut out = RunOut::default();
    let mut f = match prelude(&mut col, &mut newton, s, &mut log) {
        Ok(f) => f,
        Err(e) => {
            out.stats = log.stats;
            out.failure = Some(e.at(0.0));
            return Ok(out);
        }
    };
    let (load_dof, value) = control(s, &col, dt)?;
    log.peak_load = log.peak_load.max(value.abs());
    let mut base = nalgebra::Vector3::zeros();
    let first = log.observe(&col, 0.0, base);
    log.last = Top {
        across: first.top_displacement,
        along: first.top_axial,
        turn: first.top_rotation,
    };
    if keep == Keep::Samples {
        log.samples.push(first);
    }
    let mut obs = first;
    let mut prev_load = (0.0, first.base_shear, first.axial_force);
    for k in 1..=n {
        let t = k as f64 * dt;
        let prescribed = match &s.scene.loading {
            Loading::Cyclic { protocol, .. } => Some(Prescribed {
                dof: col.top_dof(0),
                value: protocol.at(t.round() as u64),
            }),
            _ => None,
        };
        if let Some(d) = load_dof {
            f[d] = t * value;
        }
        match col.step(&mut algorithm, &f, prescribed) {
            Ok((c, b)) => {
                log.count(c);
                base = b;
            }
            Err(e) => {
                out.failure = Some(e.at(t));
                break;
            }
        }
        let d = col.top_displacement();
        let turn = col.top_turn();
        // The input work, trapezoid on the step.
        let (v, nz) = (-base.x, -base.z);
        log.work += match (&s.scene.loading, load_dof) {
            (Loading::TipMoment(_), _) => 0.5 * (prev_load.0 + t * value) * (turn - log.last.turn),
            (_, Some(_)) => 0.5 * (prev_load.0 + t * value) * (d.x - log.last.across),
            _ => {
                0.5 * (prev_load.1 + v) * (d.x - log.last.across)
                    + 0.5 * (prev_load.2 + nz) * (d.z - log.last.along)
            }
        };
        prev_load = (t * value, v, nz);
        log.last = Top {
            across: d.x,
            along: d.z,
            turn,
        };
        if prescribed.is_some() {
            log.peak_load = log.peak_load.max(v.abs());
        }
        let sample = k % per_sample == 0;
        if sample || k == n {
            obs = log.observe(&col, t, base);
            if keep == Keep::Samples && k % per_score == 0 {
                obs.equilibrium_residual = Some(
                    col.residual_max(&f, prescribed.map(|p| p.dof))
                        .map_err(|e| format!("the equilibrium check at t = {t}: {e}"))?,
                );
            }
            if keep == Keep::Samples && sample {
                log.samples.push(obs);
            }
        }
    }
    if log.keep == Keep::Final {
        log.samples.push(obs);
    }
    out.stats = log.stats;
    out.samples = log.samples;
    out.peak_load = log.peak_load;
    Ok(out)
}
