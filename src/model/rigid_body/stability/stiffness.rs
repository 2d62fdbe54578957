//! The stiffness ladder: `nine_spring/two_angles` with every spring stiffness
//! multiplied by `10^0 ... 10^4` (generated scenes `two_angles_k1e<j>`), the largest stable and
//! accurate step of each variant against the stiffness factor, and the log-log slopes.
//!
//! Two horizons. (a) In periods of the fastest mode (`[stability].periods`, so `t_h` shrinks as
//! `k^(-1/2)` with the frequencies): a method whose stability is set by `w h` (a stability
//! interval on the imaginary axis: `rk4`'s `w h < 2 sqrt 2`) has `dt ~ k^(-1/2)`, slope -1/2;
//! explicit Euler, which grows like `exp(w^2 h t_h / 2)` with `w t_h` fixed, has `w h` fixed
//! too: slope -1/2. (b) A fixed 10 s horizon (scenes `two_angles_k1e<j>_T10`, only `euler` and
//! `rk4` on `so3`/`quat`, body): Euler's bound `w^2 h t_h ~ const` gives `dt ~ k^(-1)`; `rk4`'s
//! interval edge gives `k^(-1/2)` but its weak growth just past the edge is integrated over a
//! number of periods that grows as `k^(1/2)`, which tilts the slope below -1/2.
//!
//! Slopes are fitted (`metrics::order::loglog_slope`) over the factors where the search found a
//! step that is neither capped (`t_h / 20` passed: no stability limit to measure) nor null;
//! fewer than three such points give `order: null` with the reason.

use super::search::StudyScene;
use super::step_search;
use super::narrowed;
use crate::stability::{Part, StudyOptions};
use crate::case::Case;
use crate::metrics::order::loglog_slope;
use crate::model::rigid_body::case::RigidCase;
use crate::selection::VariantFilter;
use crate::summary::{FitRecord, Record, RunKey};

/// The case and scene the ladder is generated from.
pub const CASE: &str = "nine_spring";
pub const SCENE: &str = "two_angles";
/// Stiffness exponents `j` (factor `10^j`) of the full and the quick tier.
pub const EXPONENTS: &[i32] = &[0, 1, 2, 3, 4];
pub const QUICK_EXPONENTS: &[i32] = &[0, 2, 4];
/// The fixed horizon of part (b), s.
pub const FIXED_HORIZON: f64 = 10.0;

/// The generated scene name of factor `10^j` (and of the fixed-horizon variant).
pub fn scene_name(j: i32, fixed: bool) -> String {
    format!("{SCENE}_k1e{j}{}", if fixed { "_T10" } else { "" })
}

/// The stiffened case: every spring's stiffness times `10^j`.
pub fn stiffened(c: &Case, j: i32) -> Case {
    let mut c = c.clone();
    let f = 10f64.powi(j);
    if let Some(rc) = c.physics_mut::<RigidCase>() {
        for s in &mut rc.springs {
            s.stiffness *= f;
        }
    }
    c
}

/// The study scenes of the ladder: (exponent, periods-horizon scene, fixed-horizon scene).
pub fn scenes(c: &Case, quick: bool) -> Result<Vec<(i32, StudyScene, StudyScene)>, String> {
    let Some(spec) = &c.stability else {
        return Err(format!("{}: no [stability] table", c.file));
    };
    let scene = c
        .scene(SCENE)
        .ok_or_else(|| format!("{}: no scene {SCENE}", c.file))?;
    let mut out = vec![];
    for &j in if quick { QUICK_EXPONENTS } else { EXPONENTS } {
        let cj = stiffened(c, j);
        let mut plan =
            crate::model::rigid_body::plan::scene_plan(&cj, scene).map_err(|e| e.to_string())?;
        plan.header.scene = scene_name(j, false);
        let periods = StudyScene::new(&cj, &plan)?
            .ok_or_else(|| format!("{}: no [stability] table", c.file))?
            .tier(quick);
        plan.header.scene = scene_name(j, true);
        let fixed =
            StudyScene::with_horizon(&plan, periods.period, FIXED_HORIZON, spec).tier(quick);
        out.push((j, periods, fixed));
    }
    Ok(out)
}

/// Runs the ladder and fits the slopes. `done` are step-search records already made on the
/// case's own scenes: factor 10^0 is the case's own `SCENE`, so its records are reused
/// (renamed) rather than searched a second time (`run_study` searches that scene with the
/// same filter whenever it runs the ladder).
pub fn study(
    cases: &[Case],
    filter: &VariantFilter,
    opts: &StudyOptions,
    done: &[Record],
) -> Result<Part, String> {
    let Some(c) = cases.iter().find(|c| c.name == CASE) else {
        return Ok(Part::default());
    };
    let ladder = scenes(c, opts.quick)?;
    let (periods, fixed): (Vec<StudyScene>, Vec<StudyScene>) = ladder
        .iter()
        .map(|(_, p, f)| (p.clone(), f.clone()))
        .unzip();
    // `filter` is already the tier's (the quick tier: `super::quick_filter`).
    let own: Vec<&Record> = done
        .iter()
        .filter(|r| r.key.case == CASE && r.key.scene == SCENE)
        .collect();
    let unit = scene_name(0, false);
    let unit_first = periods.first().is_some_and(|s| s.plan.header.scene == unit);
    let mut part = if !own.is_empty() && unit_first {
        let mut p = step_search(&periods[1..], filter, opts, "stiffness")?;
        p.records.extend(own.into_iter().map(|r| {
            let mut r = r.clone();
            r.key.scene = unit.clone();
            r
        }));
        p
    } else {
        step_search(&periods, filter, opts, "stiffness")?
    };
    // The fixed horizon: euler and rk4 (the quick tier: rk4 only; Euler's stiff points there
    // need more steps than the quick budget).
    let few = if opts.quick {
        narrowed(filter, &["so3"], &["rk4"])
    } else {
        narrowed(filter, &["so3", "quat"], &["euler", "rk4"])
    };
    part.extend(step_search(&fixed, &few, opts, "stiffness, 10 s")?);
    let exps: Vec<i32> = ladder.iter().map(|(j, _, _)| *j).collect();
    part.fits = fits(&part.records, &exps);
    Ok(part)
}

/// The slope fits of the ladder's records: per variant, horizon kind and metric.
pub fn fits(records: &[Record], exps: &[i32]) -> Vec<FitRecord> {
    let mut keys: Vec<(&str, &str, &str)> = records
        .iter()
        .map(|r| {
            (
                r.key.param.as_str(),
                r.key.integrator.as_str(),
                r.key.formulation.as_str(),
            )
        })
        .collect();
    // The family's own axis order (the report's, as the rigid body comes first in the table).
    let at = |list: &[&str], x: &str| list.iter().position(|y| *y == x).unwrap_or(usize::MAX);
    keys.sort_by_key(|k| {
        use crate::model::rigid_body::registry::{FORMULATIONS, INTEGRATORS, PARAMS};
        [at(PARAMS, k.0), at(INTEGRATORS, k.1), at(FORMULATIONS, k.2)]
    });
    keys.dedup();
    let mut out = vec![];
    for (param, integ, form) in keys {
        for fixed in [false, true] {
            let rs: Vec<(f64, &Record)> = exps
                .iter()
                .filter_map(|&j| {
                    let name = scene_name(j, fixed);
                    records
                        .iter()
                        .find(|r| {
                            r.key.scene == name
                                && r.key.param == param
                                && r.key.integrator == integ
                                && r.key.formulation == form
                        })
                        .map(|r| (10f64.powi(j), r))
                })
                .collect();
            if rs.is_empty() {
                continue;
            }
            let adaptive = rs[0].1.metrics.contains_key("largest_stable_tol");
            let (sm, am) = crate::stability::steps::metric_names(adaptive);
            for metric in [sm, am] {
                let mut points = vec![];
                let mut skipped = vec![];
                for (k, r) in &rs {
                    let v = r.metrics.get(metric).copied().flatten();
                    let why = r.metric_reasons.get(metric).cloned().unwrap_or_default();
                    match v {
                        Some(x) if !why.starts_with("bounded up to the cap") => {
                            points.push([*k, x])
                        }
                        _ => skipped.push(format!("k x {k:e}: {why}")),
                    }
                }
                let (order, reason) = if points.len() >= 3 {
                    match loglog_slope(&points) {
                        Some(s) => (Some(s), None),
                        None => (None, Some("degenerate points".to_string())),
                    }
                } else {
                    (
                        None,
                        Some(format!(
                            "{} of {} stiffness factors have a measured (not capped) step; {}",
                            points.len(),
                            rs.len(),
                            skipped.join("; ")
                        )),
                    )
                };
                let scene = if fixed {
                    format!("{SCENE}_stiffness_T10")
                } else {
                    format!("{SCENE}_stiffness")
                };
                out.push(FitRecord {
                    key: RunKey::new(CASE, &scene, param, integ, form),
                    metric: format!("{metric}_vs_stiffness"),
                    order,
                    reason,
                    points,
                });
            }
        }
    }
    out
}
