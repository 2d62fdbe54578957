//! `mbdbench stability`: the stability study of the selected cases, written to
//! `stability.json` (docs/schemas.md, "stability.json"). The families with a study of their own
//! (`problem::Family::study`, the rigid body's) run it on their cases; every other family's
//! scenes with a `[stability]` table get the seam's step search (`seam_search`: the largest
//! stable step through `Problem::run`, over periods of each scene's first mode). The shared
//! parts (options, records, the step search) are `stability`'s, below the families; this
//! module is above the catalogue, as it runs every family (docs/architecture.md).
use crate::catalogue::Ordered;
use crate::stability::{Part, StudyOptions};
use crate::summary::Record;

pub mod seam_search;

/// The whole study: the step search on the case scenes, the stiffness ladder and the long
/// horizon; writes `stability.json` (and series) into `opts.out`; returns the summary.
pub fn run_study(
    cases: &[crate::case::Case],
    case_filter: &[String],
    scene_filter: &[String],
    filter: &crate::selection::VariantFilter,
    opts: &StudyOptions,
) -> Result<crate::summary::Summary, String> {
    // Unknown names in the filters are bad input, whichever family they would select.
    crate::case::select(cases, case_filter, scene_filter)?;
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
    // quick tier: each family's `stability_quick` integrators), then each other family's
    // own study on its cases, in the family table's order.
    let mut all = seam_search::study(cases, case_filter, scene_filter, filter, opts)?;
    for family in crate::catalogue::FAMILIES {
        let Some(study) = family.study else { continue };
        let Some((cases, case_filter, scene_filter)) =
            part_cases(cases, &[family.model], case_filter, scene_filter)
        else {
            continue;
        };
        all.extend(study(&crate::stability::StudyInput {
            cases: &cases,
            case_filter: &case_filter,
            scene_filter: &scene_filter,
            filter,
            opts,
        })?);
    }
    write_study(all, selection, opts)
}

/// The cases of `families`.
fn only(cases: &[crate::case::Case], families: &[&str]) -> Vec<crate::case::Case> {
    cases
        .iter()
        .filter(|c| families.contains(&c.model()))
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
        methods: Some(crate::catalogue::methods()),
        families: Some(crate::catalogue::family_models()),
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
