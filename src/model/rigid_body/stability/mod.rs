//! The rigid body's stability study (`problem::Family::study` of the family): its parts, one
//! file each, return records in the summary's schema (docs/schemas.md, "stability.json") that
//! the command merges into `stability.json`:
//!
//! - `search`: the largest stable and the largest accurate step (or tolerance) per variant and
//!   scene over the scene's stability horizon `t_h` (20 periods of its fastest linearised
//!   mode), searched over integer step counts `n` (`dt = t_h / n`; `stability::steps`);
//! - `stiffness`: `nine_spring` with its springs stiffened by 10^0 ... 10^4, both steps against
//!   the stiffness with fitted log-log slopes;
//! - `long_horizon`: energy and momentum error over 10^6 - 10^7 steps at log-spaced times, with
//!   fitted growth exponents (truncation drift ~ t, bounded ~ t^0, round-off random walk ~
//!   t^(1/2));
//! - `singularity`: `gimbal_lock`'s spin at approach distances 1e-1 ... 1e-12, error, work and
//!   conditioning against the distance;
//! - `sensitivity`: the growth of a 1e-9 perturbation of each scene's initial state.
//!
//! Every part is deterministic: its records (all but `wall_s`, `created_utc`, `env`) do not
//! depend on `--jobs`.
use crate::selection::VariantFilter;
use crate::stability::{Part, StudyInput, StudyOptions, timed_searches};

pub mod long_horizon;
pub mod search;
pub mod sensitivity;
pub mod singularity;
pub mod stiffness;

/// The variants of the quick tier's step searches (CI): the gated pair and explicit Euler,
/// on `so3` in the body formulation.
pub const QUICK_PARAMS: &[&str] = &["so3"];
pub const QUICK_INTEGRATORS: &[&str] = &["euler", "rk4", "simo_wong"];

/// `filter` narrowed to the quick tier's variants.
pub fn quick_filter(filter: &crate::selection::VariantFilter) -> crate::selection::VariantFilter {
    narrowed(filter, QUICK_PARAMS, QUICK_INTEGRATORS)
}

/// `filter` narrowed to `params` x `integrators` x `body` (each list kept where the user's
/// filter is empty, intersected otherwise): the rigid body's parts study the body
/// formulation.
pub fn narrowed(filter: &VariantFilter, params: &[&str], integrators: &[&str]) -> VariantFilter {
    let meet = |user: &[String], ours: &[&str]| -> Vec<String> {
        ours.iter()
            .filter(|x| user.is_empty() || user.iter().any(|u| u == *x))
            .map(|x| x.to_string())
            .collect()
    };
    VariantFilter {
        param: meet(&filter.param, params),
        integrator: meet(&filter.integrator, integrators),
        formulation: meet(&filter.formulation, &["body"]),
    }
}

/// One search job: a scene and a variant.
struct Job {
    scene: usize,
    variant: &'static crate::model::rigid_body::registry::Variant,
}

/// The scenes of the step search: every scene of every case with a `[stability]` table (the
/// quick tier: the table's `quick` scenes), filtered by name.
pub fn study_scenes(
    cases: &[crate::case::Case],
    case_filter: &[String],
    scene_filter: &[String],
    quick: bool,
) -> Result<Vec<search::StudyScene>, String> {
    let plans = crate::model::rigid_body::plan::plans(cases, case_filter, scene_filter)?;
    let mut out = vec![];
    for p in &plans {
        let Some(c) = cases.iter().find(|c| c.name == p.header.case) else {
            continue;
        };
        let Some(spec) = &c.stability else { continue };
        if quick && !spec.quick.contains(&p.header.scene) {
            continue;
        }
        if let Some(s) = search::StudyScene::new(c, p)? {
            out.push(s.tier(quick));
        }
    }
    Ok(out)
}

/// Searches the largest stable and accurate steps of every admitted variant on `scenes`, in
/// parallel over `jobs` threads; records in registry order per scene.
pub fn step_search(
    scenes: &[search::StudyScene],
    filter: &crate::selection::VariantFilter,
    opts: &StudyOptions,
    label: &str,
) -> Result<Part, String> {
    let references: Vec<search::OnTheFly> = scenes.iter().map(|_| Default::default()).collect();
    let mut jobs = vec![];
    for (i, s) in scenes.iter().enumerate() {
        for v in crate::model::rigid_body::registry::variants() {
            if filter.admits(v.param, v.integrator, v.formulation)
                && crate::model::rigid_body::registry::scene_na_reason(v, &s.plan.setup.body)
                    .is_none()
            {
                jobs.push(Job {
                    scene: i,
                    variant: v,
                });
            }
        }
    }
    let records = timed_searches(&jobs, opts, label, |j| {
        let s = &scenes[j.scene];
        let (stable, accurate) = search::search(j.variant, s, &references[j.scene]);
        search::record(j.variant, s, &stable, &accurate)
    })?;
    Ok(Part {
        records,
        ..Default::default()
    })
}

/// The study: the step search on the case scenes, then (without a scene filter) the
/// stiffness ladder, the long horizon and the singularity approach, and the sensitivity of
/// every selected scene.
pub fn study(input: &StudyInput) -> Result<Part, String> {
    let StudyInput {
        cases,
        case_filter,
        scene_filter,
        filter,
        opts,
    } = *input;
    let mut all = Part::default();
    let scenes = study_scenes(cases, case_filter, scene_filter, opts.quick)?;
    let tier_filter = if opts.quick {
        quick_filter(filter)
    } else {
        filter.clone()
    };
    all.extend(step_search(&scenes, &tier_filter, opts, "steps")?);
    let wanted = |case: &str| case_filter.is_empty() || case_filter.iter().any(|c| c == case);
    if wanted(stiffness::CASE) && scene_filter.is_empty() {
        let done = all.records.clone();
        all.extend(stiffness::study(cases, &tier_filter, opts, &done)?);
    }
    if scene_filter.is_empty() {
        let kept: Vec<crate::case::Case> =
            cases.iter().filter(|c| wanted(&c.name)).cloned().collect();
        all.extend(long_horizon::study(&kept, filter, opts)?);
        if wanted(singularity::CASE) {
            all.extend(singularity::study(cases, filter, opts)?);
        }
    }
    let plans = super::plan::plans(cases, case_filter, scene_filter)?;
    all.extend(sensitivity::study(cases, &plans, opts)?);
    Ok(all)
}
