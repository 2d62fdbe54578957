//! The beam's run loops: the structural methods (`structural::method::Method`) on a
//! [`Beamlike`] system in residual form, and the divergence bound shared by every loop.
//!
//! The structural loop takes `n = t_end / h` steps (the step must divide the horizon, the
//! output grid and the scene's breakpoints, all checked before it starts), integrates the
//! prescribed drive's work integral `int H Om' dt` by the trapezoid along the steps (order 2,
//! as the methods; `observe.rs`), and after every step checks the divergence bound
//! `|v_tip| <= bound` (a `diverged` failure with its time: without it an unstable model runs
//! on to 1e45 m and ends "ok") and the case's work budgets. It observes on the output grid
//! (`run::output_grid`), or only at the end (the timing pass). It allocates only the samples
//! and the state's workspace, once, before the first step.
use super::base::Base;
use super::observe::{BeamObs, Beamlike, observe};
use crate::integrate::{Failure, FailureKind, Limits, Stats};
use crate::run::{
    FixedPlan, Grid, Observe, RunOutput, Sample, divides, fixed_plan, over_budget, reserve,
};
use crate::structural::method::Method;
use crate::structural::state::State;

/// The `diverged` failure when `|v_tip|` exceeds `bound` (m).
pub fn check_bound(t: f64, tip: f64, bound: f64) -> Result<(), Failure> {
    if tip.is_finite() && tip.abs() <= bound {
        return Ok(());
    }
    if !tip.is_finite() {
        return Err(Failure::new(
            FailureKind::NonFinite,
            t,
            "non-finite tip deflection",
        ));
    }
    Err(Failure::new(
        FailureKind::Diverged,
        t,
        format!(
            "|v_tip| = {:.3e} m passed the divergence bound {bound} m",
            tip.abs()
        ),
    ))
}

fn sample<S: Beamlike + ?Sized>(sys: &S, t: f64, st: &State, w: f64) -> Sample<BeamObs> {
    let obs = observe(sys, t, &st.q, &st.v, w);
    Sample {
        t,
        obs,
        conditioning: 1.0,
        residual: (st.n_constraints() > 0).then_some(obs.constraint),
    }
}

/// The segments `[a, b)` of `[0, t_end]` between the breakpoints.
pub fn segments(breakpoints: &[f64], t_end: f64) -> Vec<(f64, f64)> {
    let mut cuts = vec![0.0];
    cuts.extend(breakpoints.iter().copied().filter(|b| *b > 0.0 && *b < t_end));
    cuts.push(t_end);
    cuts.windows(2).map(|w| (w[0], w[1])).collect()
}

/// Runs `method` from rest at `t = 0` with the fixed step `h` on the model that `build` makes
/// for each segment between breakpoints (`Base::on_segment`): the method restarts at every
/// breakpoint from the state reached (its `init` recomputes the consistent acceleration,
/// which jumps where the torque does).
#[allow(clippy::too_many_arguments)]
pub fn run_structural<S: Beamlike, M: Method<S>>(
    build: &dyn Fn(Base) -> Result<S, String>,
    base: Base,
    breakpoints: &[f64],
    method: &mut M,
    h_nominal: f64,
    grid: &Grid,
    limits: &Limits,
    observe_at: &Observe,
    bound: f64,
) -> Result<RunOutput<BeamObs>, String> {
    let all = match observe_at {
        Observe::Grid => true,
        Observe::Final => false,
        Observe::Steps { .. } => {
            return Err("the beam's structural runs observe on the grid or at the end".into());
        }
    };
    let FixedPlan {
        n_total,
        h,
        n_out,
        per_out,
        stride,
    } = fixed_plan(grid, h_nominal)?;
    let mut out = RunOutput {
        samples: Vec::with_capacity(if all { reserve(n_out) } else { 2 }),
        score_stride: stride,
        failure: None,
        stats: Stats::default(),
        conditioning_min: 1.0,
    };
    let segs = segments(breakpoints, grid.t_end);
    let first = build(base.on_segment(segs[0].0, segs[0].1))?;
    let mut state = method.new_state(&first);
    if let Some(f) = over_budget("steps", n_total, limits) {
        out.samples.push(sample(&first, 0.0, &state, 0.0));
        out.failure = Some(f);
        return Ok(out);
    }
    let mut w = 0.0;
    let mut k: u64 = 0;
    let mut sys = first;
    for (i, &(a, b)) in segs.iter().enumerate() {
        if i > 0 {
            sys = build(base.on_segment(a, b))?;
        }
        let k_end = divides(b, h).ok_or_else(|| format!("step {h} does not divide {b}"))?;
        if let Err(f) = method.init(&mut sys, a, &mut state, &mut out.stats) {
            if out.samples.is_empty() {
                out.samples.push(sample(&sys, a, &state, w));
            }
            out.failure = Some(f);
            return Ok(out);
        }
        if k == 0 {
            out.samples.push(sample(&sys, 0.0, &state, 0.0));
        }
        let mut rate = sys.work_rate(k as f64 * h, &state.q, &state.v);
        while k < k_end {
            let t = k as f64 * h;
            let t1 = (k + 1) as f64 * h;
            let r = method
                .step(&mut sys, t, h, &mut state, &mut out.stats)
                .and_then(|_| check_bound(t1, sys.tip_deflection(&state.q), bound))
                .and_then(|_| limits.check(t1, &out.stats));
            if let Err(f) = r {
                out.failure = Some(f);
                return Ok(out);
            }
            let rate1 = sys.work_rate(t1, &state.q, &state.v);
            w += 0.5 * h * (rate + rate1);
            rate = rate1;
            k += 1;
            if (all && k.is_multiple_of(per_out)) || k == n_total {
                out.samples.push(sample(&sys, t1, &state, w));
            }
        }
    }
    Ok(out)
}
