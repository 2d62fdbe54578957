//! Sensitivity of each scene to its initial state (issue 4): the finite-time growth of a
//! `PERTURBATION` = 1e-9 perturbation, so the report can say over what horizon a trajectory
//! error is meaningful (spec/cases.md, 1: `nine_spring` amplifies 1e-9 by up to ~600x in 10 s).
//!
//! For each scene, the unperturbed run and one run per perturbed direction are integrated by
//! `dop853` on `so3`/`body` at tolerance `TOL` (1e-12, so the integration error, ~1e-11 over
//! these horizons, stays below the perturbation's effect); the directions are a body-frame
//! rotation of 1e-9 rad about each axis, a body angular velocity change of `1e-9 max(|omega|, 1)`
//! rad/s along each axis and, for a translating body, a 1e-9 m shift along each world axis. The
//! growth `G(t)` is the largest geodesic rotation difference over the directions divided by
//! 1e-9, at every score time. Metrics: `sensitivity_growth_max` (max of `G` over the scene),
//! `sensitivity_growth_final`, `sensitivity_rate` (`ln G(t_end) / t_end`, a finite-time
//! Lyapunov exponent, 1/s) and `predictable_horizon`: the last score time before `G` first
//! exceeds `1e7` — beyond it a round-off-sized (1e-16) difference has grown past 1e-9 rad, so
//! errors below that say nothing about a method. The series file holds `t` and `growth`.
//!
//! Where it fails: `G` measures one trajectory's neighbourhood over one horizon, not a
//! Lyapunov spectrum; a growth at the integration error's level (G ~ 1e-2) is noise.
use std::collections::BTreeMap;

use nalgebra::Vector3;

use super::{Part, StudyOptions};
use crate::case::Case;
use crate::math::so3;
use crate::registry;
use crate::run::RunOutput;
use crate::suite::ScenePlan;
use crate::summary::{Record, Status};

/// The size of the perturbation.
pub const PERTURBATION: f64 = 1e-9;
/// The integrator tolerance.
pub const TOL: f64 = 1e-12;
/// `G` beyond which a round-off-sized difference exceeds 1e-9 rad.
pub const PREDICTABLE_GROWTH: f64 = 1e7;

/// The metric names.
pub const METRICS: &[&str] = &[
    "sensitivity_growth_max",
    "sensitivity_growth_final",
    "sensitivity_rate",
    "predictable_horizon",
];

/// The perturbed initial states of a plan.
fn perturbed(plan: &ScenePlan) -> Vec<crate::model::rigid_body::Observation> {
    let o = plan.setup.initial;
    let mut out = vec![];
    let w_scale = o.omega.norm().max(1.0);
    for i in 0..3 {
        let e = Vector3::ith(i, 1.0);
        let mut a = o;
        a.q = o.q * so3::exp_quat(&(e * PERTURBATION));
        out.push(a);
        let mut b = o;
        b.omega += e * (PERTURBATION * w_scale);
        out.push(b);
        if plan.setup.body.translates() {
            let mut c = o;
            c.x += e * PERTURBATION;
            out.push(c);
        }
    }
    out
}

/// The growth series of one scene: `(t, G(t))` at the score times, or why it is missing.
pub fn growth(plan: &ScenePlan) -> Result<Vec<(f64, f64)>, String> {
    let v = registry::find("so3", "dop853", "body").ok_or("dop853/so3/body is not registered")?;
    let run = |initial| -> Result<RunOutput, String> {
        let mut setup = plan.setup.clone();
        setup.initial = initial;
        let out = (v.run)(&setup, TOL)?;
        match &out.failure {
            Some(f) => Err(format!("{:?} at t = {}: {}", f.kind, f.t, f.message)),
            None => Ok(out),
        }
    };
    let base = run(plan.setup.initial)?;
    let base: Vec<_> = base.scored().map(|s| (s.t, s.obs.q)).collect();
    let mut g: Vec<(f64, f64)> = base.iter().map(|(t, _)| (*t, 0.0)).collect();
    for init in perturbed(plan) {
        let out = run(init)?;
        for ((k, s), (t, q)) in out.scored().enumerate().zip(&base) {
            let d = so3::geodesic_quat(&s.obs.q, q) / PERTURBATION;
            if (s.t - t).abs() > 1e-9 * t.abs().max(1.0) {
                return Err(format!("score times differ at sample {k}"));
            }
            g[k].1 = g[k].1.max(d);
        }
    }
    Ok(g)
}

/// Runs the sensitivity of every scene of the selected cases (the quick tier: the cases'
/// `[stability].quick` scenes).
pub fn study(cases: &[Case], plans: &[ScenePlan], opts: &StudyOptions) -> Result<Part, String> {
    use rayon::prelude::*;
    let chosen: Vec<&ScenePlan> = plans
        .iter()
        .filter(|p| {
            !opts.quick
                || cases.iter().any(|c| {
                    c.name == p.case
                        && c.stability
                            .as_ref()
                            .is_some_and(|s| s.quick.contains(&p.scene))
                })
        })
        .collect();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.jobs.max(1))
        .build()
        .map_err(|e| e.to_string())?;
    let done: Vec<(Record, Option<(String, serde_json::Value)>)> = pool.install(|| {
        chosen
            .par_iter()
            .map(|p| {
                let g = growth(p);
                record(p, g)
            })
            .collect()
    });
    let mut part = Part::default();
    for (r, s) in done {
        part.records.push(r);
        part.series.extend(s);
    }
    Ok(part)
}

fn record(
    plan: &ScenePlan,
    g: Result<Vec<(f64, f64)>, String>,
) -> (Record, Option<(String, serde_json::Value)>) {
    let mut metrics = BTreeMap::new();
    let mut reasons = BTreeMap::new();
    let mut series = None;
    match g {
        Err(e) => {
            for m in METRICS {
                metrics.insert(m.to_string(), None);
                reasons.insert(m.to_string(), format!("not computed: {e}"));
            }
        }
        Ok(g) => {
            let max = g.iter().map(|x| x.1).fold(0.0_f64, f64::max);
            let (t_end, last) = g.last().copied().unwrap_or((0.0, 0.0));
            metrics.insert("sensitivity_growth_max".into(), Some(max));
            metrics.insert("sensitivity_growth_final".into(), Some(last));
            let rate = (last > 0.0 && t_end > 0.0).then(|| last.ln() / t_end);
            metrics.insert("sensitivity_rate".into(), rate);
            if rate.is_none() {
                reasons.insert("sensitivity_rate".into(), "no growth to fit".into());
            }
            let horizon = match g.iter().position(|x| x.1 > PREDICTABLE_GROWTH) {
                None => t_end,
                Some(0) => 0.0,
                Some(i) => g[i - 1].0,
            };
            metrics.insert("predictable_horizon".into(), Some(horizon));
            let rel = format!("series/sensitivity/{}/{}.json", plan.case, plan.scene);
            series = Some((
                rel,
                serde_json::json!({
                    "t": g.iter().map(|x| x.0).collect::<Vec<_>>(),
                    "growth": g.iter().map(|x| x.1).collect::<Vec<_>>(),
                }),
            ));
        }
    }
    let rec = Record {
        case: plan.case.clone(),
        scene: plan.scene.clone(),
        param: "so3".into(),
        integrator: "dop853".into(),
        formulation: "body".into(),
        dt: None,
        tol: Some(TOL),
        status: Status::Ok,
        failure: None,
        reason: None,
        metrics,
        metric_reasons: reasons,
        stats: Default::default(),
        wall_s: None,
        inputs_sha256: plan.inputs_sha256.clone(),
        reference_sha256: None,
        series: series.as_ref().map(|s| s.0.clone()),
    };
    (rec, series)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan(case: &str, scene: &str) -> ScenePlan {
        let cases = crate::case::embedded().unwrap();
        let c = cases.iter().find(|c| c.name == case).unwrap();
        crate::plan::scene_plan(c, c.scene(scene).unwrap()).unwrap()
    }

    /// A spherical body's uniform spin is neutrally stable: a 1e-9 perturbation grows at most
    /// linearly (G of order 1 + |dw| t ~ a few) over the 3.2 s spin.
    #[test]
    fn spin_is_neutral() {
        let g = growth(&plan("gimbal_lock", "spin_d1e-2")).unwrap();
        let max = g.iter().map(|x| x.1).fold(0.0, f64::max);
        assert!(max > 0.5 && max < 10.0, "{max}");
    }

    /// nine_spring/two_angles amplifies a 1e-9 perturbation of its attitude, rates or position
    /// (measured in rotation) by more than ten within its 10 s, several times the neutral
    /// spin's growth; far from the 1e7 at which round-off would reach 1e-9 rad.
    #[test]
    fn nine_spring_amplifies() {
        let g = growth(&plan("nine_spring", "two_angles")).unwrap();
        let spin = growth(&plan("gimbal_lock", "spin_d1e-2")).unwrap();
        let max = |g: &[(f64, f64)]| g.iter().map(|x| x.1).fold(0.0, f64::max);
        assert!(max(&g) > 10.0, "{}", max(&g));
        assert!(max(&g) > 3.0 * max(&spin), "{} vs {}", max(&g), max(&spin));
        assert!(max(&g) < PREDICTABLE_GROWTH);
    }
}
