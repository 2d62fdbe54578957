//! The largest stable fixed step of the families without a study of their own (today the
//! flexible beam), searched through the family seam: every probe is a `Problem::run`, the
//! same run the suite makes, so nothing here names a family's variants.
//!
//! Horizon: `t_h` = `[stability].periods` periods of the scene's first (slowest) mode
//! (`Problem::first_period`; the beam's first clamped-free bending period, the fiber column's
//! first mode after its axial load), rounded up to a whole number of score intervals. A static
//! scene's load path (`Problem::as_load_path`, the fiber column's elastica and roll-up) is
//! searched over the whole path instead, `t_h = t_end`, with the path as its one sample
//! interval: its largest stable step is the largest load step with which Newton converges at
//! every step, up to the whole path in one step (the cap). The steps probed are `dt = s / n` with `s` the scene's
//! sample interval (which divides its score interval and its breakpoints, checked at load), so
//! every probe lands on every sample and breakpoint as the family's fixed-step loops require.
//! A probe is *stable* when the run ends without a typed failure (the family's divergence
//! bound, a non-finite state, a Newton failure, a budget) and every score it reports is
//! finite. The search is `steps::search_steps`: `n = 1, 2, 4, ...` up to the first passing
//! count, then bisection to 5 % (`steps::RESOLUTION`); the cap is one step per sample
//! interval, and a variant that passes there is "bounded up to the cap" (a lower bound, not a
//! limit). Each probe's steps are bounded by the tier's budget (`QUICK_MAX_STEPS`, `MAX_STEPS`
//! over the whole horizon); a variant that fails down to it is "nothing passed" with the last
//! failure, which is also what a formulation that diverges physically gives (the beam's
//! `modal_linear` on the spin-ups: no step makes it bounded).
//!
//! Adaptive variants are not searched (their step follows their tolerance; the suite's ladders
//! show their cost), and there is no accurate-step search: the beam has no reference beyond
//! its scenes' `t_end`, and its accuracy against the step is the work-precision of the run.
//! Deterministic: the records (all but `wall_s`) do not depend on `--jobs`.
use std::collections::BTreeMap;

use crate::case::Case;
use crate::integrate::FailureKind;
use crate::problem::{Problem, Stepping, Variant, Want};
use crate::stability::steps::{self, Found, Limit, Verdict};
use crate::stability::{Part, StudyOptions};
use crate::summary::{Record, RunKey, Status};

/// The step budget of one probe over the whole horizon, quick tier (about 3.3e5 steps).
pub const QUICK_MAX_STEPS: u64 = steps::QUICK_MAX_STEPS;
/// The same, full tier (about 2.6e6 steps).
pub const MAX_STEPS: u64 = 20 * (1 << 17);

/// One scene of the search: its compiled problem stretched to the horizon.
pub struct SeamScene {
    pub case: String,
    pub scene: String,
    pub problem: Box<dyn Problem>,
    /// `t_h` (s; the load parameter's end for a load path).
    pub horizon: f64,
    /// The first mode's period (s); None for a load path.
    pub period: Option<f64>,
    /// The sample interval `s` (s): probes step `s / n`.
    pub unit: f64,
    /// The largest `n` within the tier's step budget.
    pub max_n: u64,
}

impl SeamScene {
    /// The search scene of `scene` of `c` (whose `[stability]` gives `periods`); an error
    /// naming the file when a scene stepped in time has no first period or no `periods`.
    pub fn new(
        c: &Case,
        scene: &str,
        periods: Option<f64>,
        quick: bool,
    ) -> Result<SeamScene, String> {
        let family = crate::catalogue::family_of(c);
        let s = c
            .scene(scene)
            .ok_or_else(|| format!("{}: no scene {scene}", c.file))?;
        let mut p = (family.compile)(c, s).map_err(|e| e.to_string())?;
        let (horizon, period) = if p.as_load_path() {
            (p.t_end(), None)
        } else {
            let period = p.first_period().ok_or_else(|| {
                format!(
                    "{}: [stability]: scene {scene} has no first mode (model {} gives no period)",
                    c.file, family.model
                )
            })?;
            let periods = periods.ok_or_else(|| {
                format!(
                    "{}: [stability]: key `periods` is required (scene {scene} is stepped in \
                     time; its horizon is a number of first-mode periods)",
                    c.file
                )
            })?;
            let every = p.score_every();
            let horizon = (periods * period / every).ceil().max(1.0) * every;
            p.set_t_end(horizon);
            (horizon, Some(period))
        };
        let unit = p.sample_every();
        let intervals = (horizon / unit).round().max(1.0) as u64;
        let budget = if quick { QUICK_MAX_STEPS } else { MAX_STEPS };
        Ok(SeamScene {
            case: c.name.clone(),
            scene: scene.to_string(),
            problem: p,
            horizon,
            period,
            unit,
            max_n: (budget / intervals).max(1),
        })
    }

    /// The verdict of `v` at `n` steps per sample interval.
    pub fn probe(&self, v: &Variant, n: u64) -> Verdict {
        let out = match self
            .problem
            .run(v, Stepping::Dt(self.unit / n as f64), Want::Scored)
        {
            Ok(o) => o,
            Err(e) => return Verdict::Error(e),
        };
        if let Some(f) = &out.failure {
            return Verdict::Fail(Limit::from_failure(f));
        }
        let bad = out
            .scores
            .values
            .iter()
            .find(|(_, x)| x.is_some_and(|x| !x.is_finite()));
        match bad {
            Some((name, x)) => Verdict::Fail(Limit {
                kind: FailureKind::NonFinite,
                t: self.horizon,
                message: format!("{name} = {x:?} over the horizon"),
            }),
            None => Verdict::Pass,
        }
    }

    /// The search of `v`: its largest stable step.
    pub fn search(&self, v: &Variant) -> Found {
        steps::search_steps(1, 1, self.max_n, |n| self.probe(v, n), self.unit)
    }

    /// The record of a search (per variant: no `dt`/`tol`).
    pub fn record(&self, v: &Variant, found: &Found) -> Record {
        let cap = match self.period {
            Some(_) => format!(
                "one step per sample interval, dt = {} s; t_h = {:.6} s",
                self.unit, self.horizon
            ),
            None => format!("the whole load path in one step, dt = {}", self.unit),
        };
        let mut r = Record::new(
            RunKey::new(
                &self.case,
                &self.scene,
                v.param,
                v.integrator,
                v.formulation,
            ),
            self.problem.inputs_sha256(),
        );
        r.status = Status::Ok;
        r.metrics = BTreeMap::from([
            ("largest_stable_dt".to_string(), found.value),
            ("stability_horizon".to_string(), Some(self.horizon)),
        ]);
        if let Some(period) = self.period {
            r.metrics.insert("first_period".to_string(), Some(period));
        }
        r.metric_reasons
            .insert("largest_stable_dt".into(), found.reason_with(&cap));
        r
    }
}

/// The scenes of the search: every scene of every case with a `[stability]` table whose
/// family has no study of its own (the quick tier: the table's `quick` scenes), filtered by
/// name.
pub fn scenes(
    cases: &[Case],
    case_filter: &[String],
    scene_filter: &[String],
    quick: bool,
) -> Result<Vec<SeamScene>, String> {
    let mut out = vec![];
    for c in cases {
        if crate::catalogue::family_of(c).study.is_some()
            || !(case_filter.is_empty() || case_filter.contains(&c.name))
        {
            continue;
        }
        let Some(spec) = &c.stability else { continue };
        for s in &c.scenes {
            let wanted = scene_filter.is_empty() || scene_filter.contains(&s.name);
            if wanted && (!quick || spec.quick.contains(&s.name)) {
                out.push(SeamScene::new(c, &s.name, spec.periods, quick)?);
            }
        }
    }
    Ok(out)
}

/// Searches every admitted fixed-step variant of `scenes` in parallel over `opts.jobs`
/// threads (the quick tier: those of the family's `stability_quick` integrators); records per
/// scene in the family's variant order.
pub fn study(
    cases: &[Case],
    case_filter: &[String],
    scene_filter: &[String],
    filter: &crate::selection::VariantFilter,
    opts: &StudyOptions,
) -> Result<Part, String> {
    let scenes = scenes(cases, case_filter, scene_filter, opts.quick)?;
    let mut jobs: Vec<(usize, &'static Variant)> = vec![];
    for (i, s) in scenes.iter().enumerate() {
        let family = s.problem.family();
        for v in family.variants() {
            if filter.admits(v.param, v.integrator, v.formulation)
                && (!opts.quick || family.stability_quick.contains(&v.integrator))
                && !v.info.adaptive
                && s.problem.na_reason(v).is_none()
            {
                jobs.push((i, v));
            }
        }
    }
    let records = crate::stability::timed_searches(&jobs, opts, "seam steps", |&(i, v)| {
        let s = &scenes[i];
        s.record(v, &s.search(v))
    })?;
    Ok(Part {
        records,
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> SeamScene {
        let cases = crate::catalogue::embedded().unwrap();
        let c = cases.iter().find(|c| c.name == "flexible_beam").unwrap();
        let periods = c.stability.as_ref().unwrap().periods;
        SeamScene::new(c, "spinup_w4", periods, true).unwrap()
    }

    /// A static scene's load path is searched over the whole path (`t_h = t_end`, no first
    /// period): on the stiffest elastica Newton with the exponential update (`so3`) does not
    /// converge in one load step and does in two, while the quaternion projected after an
    /// additive update, whose retraction turns by `2 atan(|dw| / 2)` instead of `|dw|`,
    /// converges in one (bounded up to the cap).
    #[test]
    fn load_path_largest_converging_step() {
        let cases = crate::catalogue::embedded().unwrap();
        let c = cases
            .iter()
            .find(|c| c.name == "fiber_column_static")
            .unwrap();
        let s = SeamScene::new(c, "elastica_p10", None, true).unwrap();
        assert_eq!((s.horizon, s.unit, s.period), (1.0, 1.0, None));
        let family = crate::catalogue::find_family("fiber_column").unwrap();
        let so3 = family.find("so3", "newton_load", "force_based").unwrap();
        let found = s.search(so3);
        assert_eq!(found.value, Some(0.5), "{found:?}");
        let (_, limit) = found.limit.clone().unwrap();
        assert_eq!(limit.kind, FailureKind::NewtonFailure);
        let r = s.record(so3, &found);
        assert!(!r.metrics.contains_key("first_period"));
        let quat = family
            .find("quat_proj", "newton_load", "force_based")
            .unwrap();
        let found = s.search(quat);
        assert!(found.capped && found.value == Some(1.0), "{found:?}");
        assert!(
            s.record(quat, &found).metric_reasons["largest_stable_dt"]
                .contains("the whole load path in one step")
        );
        // A scene stepped in time needs its horizon in periods: refused by key without it.
        let beam = cases.iter().find(|c| c.name == "flexible_beam").unwrap();
        let e = SeamScene::new(beam, "spinup_w4", None, true).err().unwrap();
        assert!(
            e.contains("`periods` is required") && e.contains(&beam.file),
            "{e}"
        );
    }

    fn variant(integrator: &str, formulation: &str) -> &'static Variant {
        crate::catalogue::find_family("flexible_beam")
            .unwrap()
            .find("none", integrator, formulation)
            .unwrap()
    }

    /// The search agrees with linear stability theory where it has an answer: rk4 on
    /// `modal_stiffened` is bounded by its rod mode, `omega = (pi / 2) sqrt(EA / (rho A L^2))`
    /// = 758.8 rad/s, so the limit `2.785 / omega` = 3.67e-3 s lies between the largest
    /// passing step and the next coarser, failing one (a diverged failure); Newmark on
    /// `fe_exact` is bounded up to the cap; `modal_linear`, which diverges physically on the
    /// spin-ups, passes at no step within the budget. The horizon is 20 first periods
    /// (2 pi / 3.798 rad/s each) rounded up to the score grid.
    #[test]
    fn beam_limits_match_linear_theory() {
        let s = scene();
        let period = s.period.unwrap();
        assert!((period - 1.6543).abs() < 1e-3, "{period}");
        assert!((s.horizon - 33.1).abs() < 1e-9, "{}", s.horizon);
        let omega = std::f64::consts::FRAC_PI_2 * (2.8e7_f64 / (1.2 * 100.0)).sqrt();
        let theory = 2.785 / omega;
        let rk4 = s.search(variant("rk4", "modal_stiffened"));
        let (pass, (at, limit)) = (rk4.value.unwrap(), rk4.limit.clone().unwrap());
        let fail: f64 = at
            .strip_prefix("dt = ")
            .and_then(|x| x.split(' ').next())
            .unwrap()
            .parse()
            .unwrap();
        assert!(pass <= theory && theory <= fail, "{pass} {theory} {fail}");
        assert_eq!(limit.kind, FailureKind::Diverged);
        let newmark = s.search(variant("newmark", "fe_exact"));
        assert!(
            newmark.capped && newmark.value == Some(s.unit),
            "{newmark:?}"
        );
        let linear = s.search(variant("newmark", "modal_linear"));
        assert_eq!(linear.value, None);
        let r = s.record(variant("newmark", "modal_linear"), &linear);
        assert!(
            r.metric_reasons["largest_stable_dt"].starts_with("nothing passed: diverged"),
            "{:?}",
            r.metric_reasons
        );
    }
}
