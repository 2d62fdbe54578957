//! `mbdbench run`: the selected variants over their ladders into `--out` (summary.json and
//! the series files), then one line per case (the full table with `--verbose`).
//!
//! A filtered run never leaves a folder whose files disagree (`where_to_write`): when `--out`
//! already holds a summary whose selection (`crate::selection`) is broader than this run's,
//! the run merges into it if both come from this commit and tier (the old records outside
//! this run's selection, their fits and series are kept, the rest replaced) and otherwise
//! writes into a sibling folder named after its filters (`reports/latest-nine_spring`),
//! leaving the broader run untouched; either way it says which. A report that was in the
//! folder is regenerated from the new summary, so `index.html`, `summary.md`, the SVGs and
//! the series always describe the `summary.json` beside them.
use super::*;

use crate::selection::Selection;
use crate::summary::Summary;

/// Where a run writes, and what it does to the summary there.
#[derive(Debug)]
pub(super) enum Target {
    /// Write `out` (nothing there, or nothing broader): the run replaces it.
    Replace(PathBuf),
    /// Merge into the broader summary in `out` of the same commit and tier.
    Merge(PathBuf, Box<Summary>),
    /// `out` holds a broader run that cannot be merged: write to this sibling instead.
    Elsewhere { out: PathBuf, reason: String },
}

/// Decides where a run with selection `new` writes, given `out` (see the file's doc).
pub(super) fn where_to_write(cases: &[Case], out: &std::path::Path, new: &Selection) -> Target {
    let path = out.join("summary.json");
    // No summary, or one the suite cannot read (corrupt, changed by hand): replaced, as
    // before (the output folder's manifest keeps the user's own files).
    let Ok(old) = crate::gate::load_summary(&path) else {
        return Target::Replace(out.to_path_buf());
    };
    let old_sel = old.selection.clone().unwrap_or_else(|| {
        Selection::everything(crate::selection::Tier::of(crate::gate::is_quick_summary(
            cases, &old,
        )))
    });
    if new.covers(&old_sel) {
        return Target::Replace(out.to_path_buf());
    }
    let same_commit = old.git_commit == crate::summary::git_commit();
    if old_sel.covers(new) && same_commit {
        return Target::Merge(out.to_path_buf(), Box::new(old));
    }
    let reason = if old_sel.tier != new.tier || old_sel.t_end != new.t_end {
        format!(
            "{} holds a {}-tier run{}; this {}-tier run{} cannot merge into it",
            path.display(),
            old_sel.tier.name(),
            describe(&old_sel),
            new.tier.name(),
            if new.t_end.is_some() || old_sel.t_end.is_some() {
                " (or its --t-end)"
            } else {
                ""
            }
        )
    } else if !old_sel.covers(new) {
        format!(
            "{} holds a run{} that does not hold every run of this one ({})",
            path.display(),
            describe(&old_sel),
            new.flags()
        )
    } else {
        format!(
            "{} holds a broader run of commit {} (this binary is {}): merging would mix commits",
            path.display(),
            old.git_commit,
            crate::summary::git_commit()
        )
    };
    let name = out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let slug = match new.slug() {
        s if s.is_empty() => new.tier.name().to_string(),
        s => format!("{s}-{}", new.tier.name()),
    };
    Target::Elsewhere {
        out: out.with_file_name(format!("{name}-{slug}")),
        reason,
    }
}

fn describe(s: &Selection) -> String {
    match s.flags() {
        f if f.is_empty() => " of every case".into(),
        f => format!(" ({f})"),
    }
}

pub(super) fn cmd_run(common: &Common, a: &RunArgs) -> Result<i32, String> {
    cmd_run_into(common, a).map(|(code, _)| code)
}

/// `cmd_run`, also returning the folder it wrote (`--out`, or the sibling of
/// `where_to_write`), which the main job's later steps must read.
/// What the cost table predicts for the run, said before it starts (nothing when the table
/// predicts none of its points).
fn say_prediction(predicted: &suite::Prediction, opts: &RunOptions) {
    if predicted.cpu_s > 0.0 {
        crate::tell!(
            "  the cost table ({}) predicts at most {:.0} CPU s, about {:.0} s on {} workers, \
             for {} of the {} ladder points{}",
            if opts.cost.git_commit.is_empty() {
                "uncalibrated".to_string()
            } else {
                format!(
                    "commit {}, {}",
                    short_commit(&opts.cost.git_commit),
                    opts.cost.cpu
                )
            },
            predicted.cpu_s,
            predicted.cpu_s / opts.jobs.max(1) as f64,
            opts.jobs,
            predicted.points - predicted.unpredicted,
            predicted.points,
            if predicted.unpredicted > 0 {
                " (the adaptive runs' steps are known only once they ran)"
            } else {
                ""
            }
        );
    }
}

/// The first 7 characters of a commit hash.
fn short_commit(c: &str) -> &str {
    c.get(..7).unwrap_or(c)
}

pub(super) fn cmd_run_into(common: &Common, a: &RunArgs) -> Result<(i32, PathBuf), String> {
    let cases = load_cases(common)?;
    if let Some(t) = a.t_end
        && !(t.is_finite() && t > 0.0)
    {
        return Err(format!("--t-end {t}: must be a positive number"));
    }
    if a.max_run_s.is_nan() || a.max_run_s <= 0.0 {
        return Err(format!(
            "--max-run-s {}: must be a positive number of seconds (or inf)",
            a.max_run_s
        ));
    }
    let problems = common
        .catalogue()
        .problems(&cases, &a.filters.case, &a.filters.scene)?;
    let filter = VariantFilter {
        param: a.filters.param.clone(),
        integrator: a.filters.integrator.clone(),
        formulation: a.filters.formulation.clone(),
    };
    names::check_variant_names(&filter, &common.catalogue())?;
    if let Some(t) = a.t_end {
        for p in &problems {
            check_t_end(t, p.as_ref())?;
        }
    }
    let mut opts = RunOptions {
        quick: a.quick,
        jobs: jobs_or_default(a.jobs),
        out: a.out.clone(),
        t_end: a.t_end,
        references: common.references(),
        progress: true,
        repeats: 3,
        serial_timing: a.serial_timing,
        cases: a.filters.case.clone(),
        scenes: a.filters.scene.clone(),
        base: None,
        skip: !a.no_skip,
        cap_s: a.max_run_s,
        cost: crate::cost::CostTable::embedded(),
        catalogue: common.catalogue(),
    };
    let (out, how) = match where_to_write(&cases, &a.out, &opts.selection(&filter)) {
        Target::Replace(out) => (out, None),
        Target::Merge(out, old) => {
            opts.base = Some(*old);
            let how = format!(
                "merged into the broader summary in {} (same commit and tier): its records \
                 outside this run's selection are kept",
                out.display()
            );
            (out, Some(how))
        }
        Target::Elsewhere { out, reason } => {
            let how = format!("{reason}; this run is written to {} instead", out.display());
            (out, Some(how))
        }
    };
    if let Some(how) = &how {
        crate::tell!("note: {how}");
    }
    opts.out = out.clone();
    crate::reference::check_writable(&out)?;
    let had_report = out.join("index.html").is_file();
    let t0 = std::time::Instant::now();
    crate::tell!(
        "mbdbench run: {} scenes, {} jobs{}",
        problems.len(),
        opts.jobs,
        if a.quick { ", quick tier" } else { "" }
    );
    say_prediction(&suite::predict(&problems, &filter, &opts), &opts);
    let summary = suite::run_catalogue(problems, &filter, &opts)?;
    let mut stdout = crate::quiet::Stdout;
    if a.verbose {
        suite::print_table(&summary, &cases, &mut stdout).map_err(|e| e.to_string())?;
        crate::say!("");
    }
    suite::print_brief(&summary, &mut stdout).map_err(|e| e.to_string())?;
    let runs = summary
        .records
        .iter()
        .filter(|r| r.status != crate::summary::Status::NotApplicable)
        .count();
    let failed = summary
        .records
        .iter()
        .filter(|r| r.status == crate::summary::Status::Failed)
        .count();
    let skipped = summary
        .records
        .iter()
        .filter(|r| {
            r.status == crate::summary::Status::NotApplicable && (r.dt.is_some() || r.tol.is_some())
        })
        .count();
    let skipped = if skipped > 0 {
        format!(" ({skipped} of them ladder points not run: their ladder had told what it could)")
    } else {
        String::new()
    };
    crate::say!(
        "{runs} runs ({failed} ended with a typed failure), {} n/a{skipped}; {:.1} s; summary: {}{}",
        summary.records.len() - runs,
        t0.elapsed().as_secs_f64(),
        out.join("summary.json").display(),
        how.map(|h| format!(" ({h})")).unwrap_or_default()
    );
    // The report that was there described the old summary: made again from the new one.
    if had_report {
        cmd_report(common, &out.join("summary.json"), None, false, None)?;
    }
    Ok((EXIT_OK, out))
}
