//! The stability study behind `mbdbench stability`: how far each variant can be
//! pushed before it fails, not only how accurate it is at comfortable steps. Its parts, one
//! file each, return records in the summary's schema (docs/schemas.md, "stability.json") that this
//! module merges into `stability.json`:
//!
//! - `search`: the largest stable and the largest accurate step (or tolerance) per variant and
//!   scene over the scene's stability horizon `t_h` (20 periods of its fastest linearised
//!   mode), searched over integer step counts `n` (`dt = t_h / n`);
//! - `stiffness`: `nine_spring` with its springs stiffened by 10^0 ... 10^4, both steps against
//!   the stiffness with fitted log-log slopes;
//! - `long_horizon`: energy and momentum error over 10^6 - 10^7 steps at log-spaced times, with
//!   fitted growth exponents (truncation drift ~ t, bounded ~ t^0, round-off random walk ~
//!   t^(1/2));
//! - `singularity`: `gimbal_lock`'s spin at approach distances 1e-1 ... 1e-12, error, work and
//!   conditioning against the distance;
//! - `sensitivity`: the growth of a 1e-9 perturbation of each scene's initial state;
//! - `seam_search`: the largest stable step of the families without a study of their own
//!   (the flexible beam), through `Problem::run`, over periods of each scene's first mode.
//!
//! Every part is deterministic: its records (all but `wall_s`, `created_utc`, `env`) do not
//! depend on `--jobs`. Each of the first five declares the model families it applies to
//! (`FAMILIES` in its file; the rigid body) and sees only their cases; `seam_search` takes
//! the cases of every other family.
use std::path::PathBuf;

use crate::summary::{FitRecord, Record};

pub mod long_horizon;
pub mod seam_search;
pub mod search;
pub mod sensitivity;
pub mod singularity;
pub mod stiffness;

/// Options of the study.
#[derive(Debug, Clone)]
pub struct StudyOptions {
    /// The quick tier (CI): fewer scenes, shorter horizons.
    pub quick: bool,
    pub jobs: usize,
    pub out: PathBuf,
    pub references: PathBuf,
    /// Progress lines on stderr.
    pub progress: bool,
}

/// What one part of the study contributes to `stability.json`: records, fits, and series
/// files (path relative to the output folder, JSON value).
#[derive(Debug, Default)]
pub struct Part {
    pub records: Vec<Record>,
    pub fits: Vec<FitRecord>,
    pub series: Vec<(String, serde_json::Value)>,
}

impl Part {
    /// Appends another part.
    pub fn extend(&mut self, other: Part) {
        self.records.extend(other.records);
        self.fits.extend(other.fits);
        self.series.extend(other.series);
    }
}

/// The variants of the quick tier's step searches (CI): the gated pair and explicit Euler,
/// on `so3` in the body formulation.
pub const QUICK_PARAMS: &[&str] = &["so3"];
pub const QUICK_INTEGRATORS: &[&str] = &["euler", "rk4", "simo_wong"];

/// `filter` narrowed to the quick tier's variants.
pub fn quick_filter(filter: &crate::suite::VariantFilter) -> crate::suite::VariantFilter {
    narrowed(filter, QUICK_PARAMS, QUICK_INTEGRATORS)
}

/// `filter` narrowed to `params` x `integrators` x `body` (each list kept where the user's
/// filter is empty, intersected otherwise).
pub fn narrowed(
    filter: &crate::suite::VariantFilter,
    params: &[&str],
    integrators: &[&str],
) -> crate::suite::VariantFilter {
    let meet = |user: &[String], ours: &[&str]| -> Vec<String> {
        ours.iter()
            .filter(|x| user.is_empty() || user.iter().any(|u| u == *x))
            .map(|x| x.to_string())
            .collect()
    };
    crate::suite::VariantFilter {
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
        let Some(c) = cases.iter().find(|c| c.name == p.case) else {
            continue;
        };
        let Some(spec) = &c.stability else { continue };
        if quick && !spec.quick.contains(&p.scene) {
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
    filter: &crate::suite::VariantFilter,
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

/// Runs `search` on every job in parallel over `opts.jobs` threads, one job at a time per
/// thread; each record gets the search's wall time, and progress goes to stderr
/// (`crate::progress`: a bar on a terminal, else a line every tenth of the jobs, `label`,
/// with the elapsed time and an estimate of what remains). Records in job order.
pub(crate) fn timed_searches<J: Sync>(
    jobs: &[J],
    opts: &StudyOptions,
    label: &str,
    search: impl Fn(&J) -> Record + Sync,
) -> Result<Vec<Record>, String> {
    use rayon::prelude::*;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.jobs.max(1))
        .build()
        .map_err(|e| e.to_string())?;
    let total = jobs.len();
    let progress = crate::progress::Progress::new(total, label, "searches", 10, opts.progress);
    let records = pool.install(|| {
        jobs.par_iter()
            .with_max_len(1)
            .map(|j| {
                let t0 = std::time::Instant::now();
                let mut r = search(j);
                let w = t0.elapsed().as_secs_f64();
                r.wall_s = Some(crate::summary::Wall { min: w, median: w });
                progress.tick();
                r
            })
            .collect()
    });
    progress.finish();
    Ok(records)
}

/// The whole study: the step search on the case scenes, the stiffness ladder and the long
/// horizon; writes `stability.json` (and series) into `opts.out`; returns the summary.
pub fn run_study(
    cases: &[crate::case::Case],
    case_filter: &[String],
    scene_filter: &[String],
    filter: &crate::suite::VariantFilter,
    opts: &StudyOptions,
) -> Result<crate::summary::Summary, String> {
    // Unknown names in the filters are bad input, whichever family they would select.
    crate::plan::select(cases, case_filter, scene_filter)?;
    let selection = crate::selection::Selection {
        tier: crate::selection::Tier::of(opts.quick),
        cases: case_filter.to_vec(),
        scenes: scene_filter.to_vec(),
        params: filter.param.clone(),
        integrators: filter.integrator.clone(),
        formulations: filter.formulation.clone(),
        t_end: None,
    }
    .deduped();
    // The step search of the families without a study of their own, through the seam (the
    // quick tier: each family's `stability_quick` integrators).
    let mut all = seam_search::study(cases, case_filter, scene_filter, filter, opts)?;
    // The parts below are the rigid body's (each file's FAMILIES).
    let Some((cases, case_filter, scene_filter)) =
        part_cases(cases, search::FAMILIES, case_filter, scene_filter)
    else {
        return write_study(all, selection, opts);
    };
    let (cases, case_filter, scene_filter) = (&cases[..], &case_filter[..], &scene_filter[..]);
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
        let cases = only(cases, stiffness::FAMILIES);
        all.extend(stiffness::study(&cases, &tier_filter, opts, &done)?);
    }
    if scene_filter.is_empty() {
        let kept: Vec<crate::case::Case> = only(cases, long_horizon::FAMILIES)
            .into_iter()
            .filter(|c| wanted(&c.name))
            .collect();
        all.extend(long_horizon::study(&kept, filter, opts)?);
        if wanted(singularity::CASE) {
            all.extend(singularity::study(
                &only(cases, singularity::FAMILIES),
                filter,
                opts,
            )?);
        }
    }
    let sensitive = only(cases, sensitivity::FAMILIES);
    let plans = crate::model::rigid_body::plan::plans(&sensitive, case_filter, scene_filter)?;
    all.extend(sensitivity::study(&sensitive, &plans, opts)?);
    write_study(all, selection, opts)
}

/// The cases of `families`.
fn only(cases: &[crate::case::Case], families: &[&str]) -> Vec<crate::case::Case> {
    cases
        .iter()
        .filter(|c| families.contains(&c.model))
        .cloned()
        .collect()
}

/// The cases of `families` in the selection, with the case and scene filters narrowed to
/// them; None when the selection holds none of them.
fn part_cases(
    cases: &[crate::case::Case],
    families: &[&str],
    case_filter: &[String],
    scene_filter: &[String],
) -> Option<(Vec<crate::case::Case>, Vec<String>, Vec<String>)> {
    let kept = only(cases, families);
    let narrow = |f: &[String], known: &dyn Fn(&str) -> bool| -> Option<Vec<String>> {
        let n: Vec<String> = f.iter().filter(|x| known(x)).cloned().collect();
        (f.is_empty() || !n.is_empty()).then_some(n)
    };
    let case_filter = narrow(case_filter, &|x| kept.iter().any(|c| c.name == x))?;
    let scene_filter = narrow(scene_filter, &|x| {
        kept.iter()
            .filter(|c| case_filter.is_empty() || case_filter.contains(&c.name))
            .any(|c| c.scene(x).is_some())
    })?;
    (!kept.is_empty()).then_some((kept, case_filter, scene_filter))
}

/// Sorts the study's records, writes its series and `stability.json`; returns the summary.
fn write_study(
    all: Part,
    selection: crate::selection::Selection,
    opts: &StudyOptions,
) -> Result<crate::summary::Summary, String> {
    let mut records = all.records;
    records.sort_by_key(record_order);
    let mut staging = crate::output::Staging::begin(&opts.out, crate::output::Writer::Stability)?;
    for (rel, value) in &all.series {
        let text = serde_json::to_string(value).map_err(|e| e.to_string())?;
        staging.write(rel, text.as_bytes())?;
    }
    let summary = crate::summary::Summary {
        schema: 1,
        git_commit: crate::summary::git_commit().into(),
        created_utc: crate::summary::now_utc(),
        env: crate::summary::Env::current(opts.jobs, None),
        records,
        fits: all.fits,
        selection: Some(selection),
    };
    let text = serde_json::to_string_pretty(&summary).map_err(|e| e.to_string())?;
    staging.write("stability.json", text.as_bytes())?;
    staging.commit()?;
    Ok(summary)
}

/// A record's place in `stability.json`: case, scene, variant order, ladder value (fine
/// steps first, unlike the summary's report order).
fn record_order(r: &Record) -> (String, String, [usize; 3], u64, u64) {
    (
        r.key.case.clone(),
        r.key.scene.clone(),
        r.variant_order(),
        r.dt.map(f64::to_bits).unwrap_or(0),
        r.tol.map(f64::to_bits).unwrap_or(0),
    )
}

/// The terminal table of the study: the step-search records per scene (largest stable and
/// accurate step or tolerance, what limits them), then the fitted slopes and exponents.
pub fn print_table(
    s: &crate::summary::Summary,
    out: &mut impl std::io::Write,
) -> std::io::Result<()> {
    let num = |v: Option<f64>| v.map_or_else(|| format!("{:>10}", "-"), |x| format!("{x:10.3e}"));
    let mut scene = (String::new(), String::new());
    for r in &s.records {
        let stable = ["largest_stable_dt", "largest_stable_tol"]
            .into_iter()
            .find(|m| r.metrics.contains_key(*m));
        let Some(sm) = stable else { continue };
        let am = sm.replace("stable", "accurate");
        if (r.key.case.clone(), r.key.scene.clone()) != scene {
            scene = (r.key.case.clone(), r.key.scene.clone());
            writeln!(
                out,
                "\n{}/{} (t_h = {} s)\n  {:<12} {:<18} {:<8} {:>10} {:>10}  limited by (stable)",
                r.key.case,
                r.key.scene,
                num(r.metrics.get("stability_horizon").copied().flatten()).trim(),
                "param",
                "integrator",
                "form",
                "stable",
                "accurate"
            )?;
        }
        let why = r.metric_reasons.get(sm).map_or("", String::as_str);
        let short: String = why.chars().take(70).collect();
        writeln!(
            out,
            "  {:<12} {:<18} {:<8} {} {}  {}",
            r.key.param,
            r.key.integrator,
            r.key.formulation,
            num(r.metrics.get(sm).copied().flatten()),
            num(r.metrics.get(am.as_str()).copied().flatten()),
            short
        )?;
    }
    if !s.fits.is_empty() {
        writeln!(out, "\nfits")?;
        for f in &s.fits {
            writeln!(
                out,
                "  {:<24} {:<12} {:<18} {:<8} {:<36} {}",
                f.key.scene,
                f.key.param,
                f.key.integrator,
                f.key.formulation,
                f.metric,
                f.order.map_or_else(
                    || format!("- ({})", f.reason.as_deref().unwrap_or("")),
                    |o| format!("{o:.3}")
                )
            )?;
        }
    }
    Ok(())
}
