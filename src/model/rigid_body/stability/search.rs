//! The largest stable and the largest accurate step of a variant on a scene.
//!
//! Horizon: `t_h` = `[stability].periods` periods of the scene's fastest linearised mode
//! (`model::rigid_body::linear_modes`). A fixed-step variant is probed with `n` steps of `dt = t_h / n`
//! (integer step counts, so every probe is deterministic and lands on `t_h`), observed at
//! `SCORE_POINTS` score times `k_j = floor(j n / M)` (every step when `n < M`). A probe is
//! - *stable* when the run ends without a typed failure and, at every score time, the state
//!   is finite and `|E - E0| / max(|E0|, energy_scale) < ENERGY_BOUND` (= 1);
//! - *accurate* when it is stable and the geodesic rotation error against an on-the-fly
//!   reference stays below the case's `rotation_error_max` at every score time. The reference
//!   is `dop853` on `so3`/`body` at `REFERENCE_TOL` (1e-12), interpolated by its dense output at
//!   the probe's own score times; its accuracy is checked against the stored references in
//!   the tests (well below the 0.1 rad bounds it judges).
//!
//! Search (`stability::steps`, shared with the seam's search of the other families): a geometric ladder `n = CAP_STEPS * 2^j` (the cap `dt = t_h / 20`), up to the first
//! passing `n` (at most `MAX_STEPS` for the stable search, `MAX_ACCURATE_STEPS` for the
//! accurate one; a probe stops at the first score time past a bound), then bisection on `n` between the last failing and the
//! first passing count until they differ by less than 5 % (`RESOLUTION`); the result is `t_h`
//! over the passing count. When the cap itself passes the variant is "bounded up to the cap"
//! (the A-stable implicit methods, the energy-conserving ones). The search assumes the
//! verdict is monotone in the step near the boundary; where it is not (a step can land past a
//! singular set by luck), the result is the first passing step from the coarse side, which is
//! what a user stepping down from a coarse step would find. The accurate search starts from the
//! stable count. Adaptive variants are searched on their tolerance the same way: from
//! `TOL_CAP` (1) down by decades to `TOL_FLOOR`, then bisection in `log tol`.
//!
//! Explicit Euler has no stability interval on the imaginary axis (`|1 + i w h| > 1` for every
//! `h > 0`): on an undamped oscillation it always grows, so its "stable" step is set by the
//! energy bound alone: amplitude growth `(1 + w^2 h^2)^(n/2) ~ exp(w^2 h t_h / 2)` over the
//! horizon, i.e. `h ~ 1 / (w^2 t_h)`.
//!
//! What limits each result is in the record's `metric_reasons` under the metric's name (the
//! failure kind or the bound crossed at the first failing step beyond it, with its time), or
//! why the metric is null (nothing passed down to `MAX_STEPS`).

use crate::model::rigid_body::Observation;
use std::collections::BTreeMap;
use std::sync::Arc;

use crate::case::{Case, StabilitySpec};
use crate::stability::steps::{
    CAP_STEPS, Found, Limit, Probe, QUICK_MAX_STEPS, TOL_CAP, TOL_FLOOR, Verdict, metric_names,
    probe_limits, search_steps, search_tol,
};
use crate::model::rigid_body::linear_modes;
use crate::model::rigid_body::plan::ScenePlan;
use crate::model::rigid_body::registry::{self, Variant};
use crate::run::{Observe, RunOutput, Sample};
use crate::summary::{Record, Status};

/// Score times over the horizon.
pub const SCORE_POINTS: u64 = 200;
/// The finest step tried in the stable search: `t_h / MAX_STEPS` (full tier; about 2e7
/// steps: explicit Euler's stable step over the stiffness ladder's fixed 10 s horizon takes
/// 2.5e6 steps at k x 1e3 and is "nothing passed" at k x 1e4, measured).
pub const MAX_STEPS: u64 = 20 * (1 << 20);
/// The finest step tried in the accurate search (full tier; about 2.6e6 steps). Only the
/// first-order methods get near it: explicit and Lie-Euler stay above the 0.1 rad bound over
/// 20 periods down to 2e7 steps on `nine_spring/two_angles` (rotation error 0.11 at
/// n = 20 x 2^20, measured), and the ladder down to that budget cost 8-10 s a variant, 240 of
/// the scene's 253 core-seconds; at this budget their accurate step is "nothing passed" with
/// the error at the finest step in the reason.
pub const MAX_ACCURATE_STEPS: u64 = 20 * (1 << 17);
/// Relative energy error that counts as unbounded growth.
pub const ENERGY_BOUND: f64 = 1.0;
/// Tolerance of the on-the-fly reference.
pub const REFERENCE_TOL: f64 = 1e-12;

/// One scene of the study: its plan with the grid stretched to the horizon.
#[derive(Debug, Clone)]
pub struct StudyScene {
    /// The plan; `setup.grid.t_end` is the horizon `t_h`.
    pub plan: ScenePlan,
    /// `t_h` (s).
    pub horizon: f64,
    /// The fastest linearised period (s).
    pub period: f64,
    pub spec: StabilitySpec,
    /// The finest step count tried (`MAX_STEPS`, or `QUICK_MAX_STEPS`).
    pub max_steps: u64,
    /// The same for the accurate search (`MAX_ACCURATE_STEPS`, or `QUICK_MAX_STEPS`).
    pub max_accurate_steps: u64,
}

impl StudyScene {
    /// The study scene of a planned scene of `c`: `t_h = periods x fastest period`. None when
    /// the case has no `[stability]` table; an error when the scene has no time scale.
    pub fn new(c: &Case, plan: &ScenePlan) -> Result<Option<StudyScene>, String> {
        let Some(spec) = &c.stability else {
            return Ok(None);
        };
        if spec.rotation_error_max.is_none() {
            return Err(format!(
                "{}: [stability]: no rotation_error_max; the accurate-step search needs a rotation error bound in rad",
                c.file
            ));
        }
        let period = linear_modes::fastest_period(&plan.setup.body, &plan.setup.initial)
            .ok_or_else(|| {
                format!(
                    "{}: [stability]: scene {} has no time scale (no elastic mode, no rotation)",
                    c.file, plan.header.scene
                )
            })?;
        let periods = spec.periods.ok_or_else(|| {
            format!(
                "{}: [stability]: key `periods` is required (the horizon in periods of the \
                 fastest mode)",
                c.file
            )
        })?;
        Ok(Some(Self::with_horizon(
            plan,
            period,
            periods * period,
            spec,
        )))
    }

    /// The study scene with an explicit horizon (the stiffness ladder's fixed-horizon runs).
    pub fn with_horizon(
        plan: &ScenePlan,
        period: f64,
        horizon: f64,
        spec: &StabilitySpec,
    ) -> StudyScene {
        let mut plan = plan.clone();
        plan.setup.grid.t_end = horizon;
        plan.setup.grid.score_every = horizon;
        plan.setup.grid.sample_every = horizon;
        StudyScene {
            plan,
            horizon,
            period,
            spec: spec.clone(),
            max_steps: MAX_STEPS,
            max_accurate_steps: MAX_ACCURATE_STEPS,
        }
    }

    /// The same with the step budget of a tier.
    pub fn tier(mut self, quick: bool) -> StudyScene {
        self.max_steps = if quick { QUICK_MAX_STEPS } else { MAX_STEPS };
        self.max_accurate_steps = if quick {
            QUICK_MAX_STEPS
        } else {
            MAX_ACCURATE_STEPS
        };
        self
    }
}

/// The score-time step indices of a run of `n` steps (strictly ascending, in `(0, n)`).
pub fn score_indices(n: u64) -> Arc<[u64]> {
    let m = SCORE_POINTS.min(n);
    let mut v: Vec<u64> = (1..m)
        .map(|j| ((j as u128 * n as u128) / m as u128) as u64)
        .collect();
    v.dedup();
    v.into()
}

/// The on-the-fly reference of a scene: `dop853`/`so3`/`body` at `REFERENCE_TOL`, observed on
/// `REFERENCE_POINTS` uniform times over the horizon and interpolated between them by cubic
/// Hermite on the quaternion (`q' = q (0, omega) / 2`, then normalised): with `w dt_ref` at
/// most 2 pi 20 / 20000 = 6e-3 over a horizon of 20 periods, the interpolation error is about
/// `(w dt_ref)^4 / 384 ~ 4e-12` rad, far below the 0.1 rad bounds it judges (the fixed 10 s
/// horizon of the stiffest ladder scene, `w dt_ref ~ 0.2`, gives ~4e-6). Computed once per
/// scene, on first use.
pub struct OnTheFly {
    dense: std::sync::OnceLock<Result<Vec<Sample<Observation>>, String>>,
}

/// Uniform reference samples over the horizon.
pub const REFERENCE_POINTS: u64 = 20_000;

impl Default for OnTheFly {
    fn default() -> Self {
        OnTheFly {
            dense: std::sync::OnceLock::new(),
        }
    }
}

impl OnTheFly {
    /// The reference rotation at time `t` of the horizon.
    pub fn rotation_at(
        &self,
        scene: &StudyScene,
        t: f64,
    ) -> Result<nalgebra::UnitQuaternion<f64>, String> {
        let samples = self
            .dense
            .get_or_init(|| reference_samples(scene))
            .as_ref()
            .map_err(Clone::clone)?;
        let dt = scene.horizon / REFERENCE_POINTS as f64;
        let i = ((t / dt).floor() as usize).min(samples.len() - 2);
        let (a, b) = (&samples[i], &samples[i + 1]);
        Ok(hermite(a, b, t))
    }
}

/// Cubic Hermite interpolation of the rotation between two samples.
fn hermite(
    a: &Sample<Observation>,
    b: &Sample<Observation>,
    t: f64,
) -> nalgebra::UnitQuaternion<f64> {
    use nalgebra::Quaternion;
    let h = b.t - a.t;
    let s = ((t - a.t) / h).clamp(0.0, 1.0);
    let rate = |x: &Sample<Observation>| {
        let w = x.obs.omega;
        x.obs.q.into_inner() * Quaternion::new(0.0, w[0], w[1], w[2]) * 0.5
    };
    let qa = a.obs.q.into_inner();
    // The samples come from one continuous chart run: flip b only if a sign jump slipped in.
    let sign = if qa.dot(&b.obs.q.into_inner()) < 0.0 {
        -1.0
    } else {
        1.0
    };
    let qb = b.obs.q.into_inner() * sign;
    let (da, db) = (rate(a), rate(b) * sign);
    let s2 = s * s;
    let s3 = s2 * s;
    let q = qa * (2.0 * s3 - 3.0 * s2 + 1.0)
        + da * (h * (s3 - 2.0 * s2 + s))
        + qb * (-2.0 * s3 + 3.0 * s2)
        + db * (h * (s3 - s2));
    nalgebra::UnitQuaternion::from_quaternion(q)
}

fn reference_samples(scene: &StudyScene) -> Result<Vec<Sample<Observation>>, String> {
    let v = registry::find("so3", "dop853", "body").ok_or("dop853/so3/body is not registered")?;
    let n = REFERENCE_POINTS;
    let at: Vec<u64> = (1..n).collect();
    let mut setup = scene.plan.setup.clone();
    setup.observe = Observe::Steps {
        n,
        at: at.into(),
        watch: None,
    };
    let out = (v.run)(&setup, REFERENCE_TOL)?;
    if let Some(f) = &out.failure {
        return Err(format!(
            "the on-the-fly reference (dop853/so3/body, tol {REFERENCE_TOL:e}) failed: {:?} at t = {}: {}",
            f.kind, f.t, f.message
        ));
    }
    if out.samples.len() != n as usize + 1 {
        return Err(format!(
            "the on-the-fly reference has {} samples, expected {}",
            out.samples.len(),
            n + 1
        ));
    }
    Ok(out.samples)
}

/// Runs `v` over the horizon observed at the score times of `n` steps; `value` is the step
/// (fixed: `t_h / n`) or the tolerance (adaptive). The run stops at the first observation
/// past the energy bound, and past the rotation bound when `reference` is given.
fn observe_run(
    v: &Variant,
    scene: &StudyScene,
    n: u64,
    value: f64,
    reference: Option<&OnTheFly>,
) -> Result<RunOutput<Observation>, String> {
    let at = score_indices(n);
    let rotation = match reference {
        None => None,
        Some(r) => {
            let dt = scene.horizon / n as f64;
            let mut refs = Vec::with_capacity(at.len() + 1);
            for &k in at.iter().chain(std::iter::once(&n)) {
                refs.push((k, r.rotation_at(scene, k as f64 * dt)?));
            }
            Some(crate::run::RotationWatch {
                reference: refs.into(),
                // Present: `StudyScene::new` and the rigid loader check it.
                max: scene.spec.rotation_error_max.unwrap_or(f64::INFINITY),
            })
        }
    };
    let mut setup = scene.plan.setup.clone();
    setup.observe = Observe::Steps {
        n,
        at,
        watch: Some(crate::run::BoundWatch {
            scale: scene.plan.energy_scale,
            max: ENERGY_BOUND,
            rotation,
        }),
    };
    setup.limits = probe_limits(scene.max_steps);
    (v.run)(&setup, value)
}

/// The probe of `v` with `n` steps (fixed) or at tolerance `tol` (adaptive, observed at
/// `SCORE_POINTS` uniform times), judged stable, and accurate when `reference` is given: a
/// typed failure, or a bound crossed at an observation (`run::BoundWatch`), fails it.
pub fn probe(
    v: &Variant,
    scene: &StudyScene,
    n_or_tol: Probe,
    reference: Option<&OnTheFly>,
) -> Verdict {
    let (n, value) = match n_or_tol {
        Probe::Steps(n) => (n, scene.horizon / n as f64),
        Probe::Tol(tol) => (SCORE_POINTS, tol),
    };
    let out = match observe_run(v, scene, n, value, reference) {
        Ok(o) => o,
        Err(message) => return Verdict::Error(message),
    };
    // The run's watch judged every observation after the first (energy, and rotation against
    // the reference when given) and ended the run at the first one past a bound.
    match &out.failure {
        Some(f) => Verdict::Fail(Limit::from_failure(f)),
        None => Verdict::Pass,
    }
}

/// Both searches of one variant on one scene: (largest stable, largest accurate).
pub fn search(v: &Variant, scene: &StudyScene, reference: &OnTheFly) -> (Found, Found) {
    if v.info.adaptive {
        let stable = search_tol(TOL_CAP, |tol| probe(v, scene, Probe::Tol(tol), None));
        let start = stable.value.unwrap_or(TOL_FLOOR);
        let accurate = search_tol(start, |tol| {
            probe(v, scene, Probe::Tol(tol), Some(reference))
        });
        (stable, accurate)
    } else {
        let h = scene.horizon;
        let stable = search_steps(
            CAP_STEPS,
            CAP_STEPS,
            scene.max_steps,
            |n| probe(v, scene, Probe::Steps(n), None),
            h,
        );
        let Some(n0) = stable.n else {
            let none = Found {
                value: None,
                n: None,
                capped: false,
                limit: stable.limit.clone(),
                probes: 0,
                error: stable.error.clone(),
            };
            return (stable, none);
        };
        let accurate = search_steps(
            n0,
            CAP_STEPS,
            scene.max_accurate_steps,
            |n| probe(v, scene, Probe::Steps(n), Some(reference)),
            h,
        );
        (stable, accurate)
    }
}

/// The record of one search (`dt`/`tol` absent: the record is per variant, not per ladder
/// point).
pub fn record(v: &Variant, scene: &StudyScene, stable: &Found, accurate: &Found) -> Record {
    let (sm, am) = metric_names(v.info.adaptive);
    let mut metrics = BTreeMap::new();
    let mut reasons = BTreeMap::new();
    for (name, f) in [(sm, stable), (am, accurate)] {
        metrics.insert(name.to_string(), f.value);
        reasons.insert(name.to_string(), f.reason(scene.horizon));
    }
    metrics.insert("stability_horizon".into(), Some(scene.horizon));
    metrics.insert("fastest_period".into(), Some(scene.period));
    Record {
        key: crate::summary::RunKey::new(
            &scene.plan.header.case,
            &scene.plan.header.scene,
            v.param,
            v.integrator,
            v.formulation,
        ),
        dt: None,
        tol: None,
        status: Status::Ok,
        failure: None,
        reason: None,
        metrics,
        metric_reasons: reasons,
        stats: crate::integrate::Stats::default(),
        wall_s: None,
        inputs_sha256: scene.plan.header.inputs_sha256.clone(),
        settings_sha256: Some(scene.plan.header.settings_sha256.clone()),
        reference_sha256: None,
        series: None,
        series_reason: None,
    }
}

#[cfg(test)]
#[path = "search_tests.rs"]
mod tests;
