//! The main job (`mbdbench` with no command; `cargo run --release`): the whole catalogue on
//! its full ladders into `reports/latest`, the quick tier of the stability study beside it
//! (`--full-stability`: the full study), the report (so its "at what step" part and the
//! gate see `stability.json`), then, last where the terminal shows them, the recommendation
//! and the gate's verdict: the failing rows, the skipped ones by reason and
//! `N passed, N failed, N skipped`, exactly what `mbdbench gate --require-stability` says on
//! the same files and what the page's "Gates" line says. Exit 0 when every gate passes, 1
//! when any fails. Its time on 2 cores: README.md, at the top.
use super::*;

pub(super) fn run(common: &Common, full_stability: bool) -> Result<i32, String> {
    let t0 = std::time::Instant::now();
    let args = RunArgs::default();
    opening(common, &args.out, full_stability)?;
    // The folder the run wrote: `reports/latest`, or its sibling when that holds a run this
    // one may not replace (a quick-tier run: `run.rs`, `where_to_write`); every later step
    // reads and writes there, so the stability study, report and gate describe this run.
    let (code, out) = cmd_run_into(common, &args)?;
    if code != EXIT_OK {
        return Ok(code);
    }
    let run_s = t0.elapsed().as_secs_f64();
    let t1 = std::time::Instant::now();
    let code = cmd_stability(
        common,
        &StabilityArgs {
            filters: Filters::default(),
            quick: !full_stability,
            jobs: None,
            out: out.clone(),
            verbose: false,
        },
    )?;
    if code != EXIT_OK {
        return Ok(code);
    }
    let stability_s = t1.elapsed().as_secs_f64();
    let summary = out.join("summary.json");
    let code = cmd_report(common, &summary, None, false, None)?;
    if code != EXIT_OK {
        return Ok(code);
    }
    crate::say!("");
    cmd_advise(
        common,
        &AdviseArgs {
            summary: summary.clone(),
            case: vec![],
            target: vec![],
            by: "work".into(),
            json: false,
        },
    )?;
    crate::say!("\nGates (mbdbench gate --require-stability; full table in index.html):");
    let code = cmd_gate(
        common,
        &GateArgs {
            summary: summary.clone(),
            quick: false,
            baseline: None,
            factor: crate::gate::DEFAULT_FACTOR,
            update_baseline: false,
            case: vec![],
            scene: vec![],
            require_stability: true,
            verdict_only: true,
            markdown: false,
        },
    )?;
    crate::say!(
        "\nTime: the run {run_s:.0} s, the stability study {stability_s:.0} s, the report, \
         advice and gate {:.0} s. The run by family (CPU s on the worker threads; also in \
         summary.md):",
        t0.elapsed().as_secs_f64() - run_s - stability_s
    );
    match crate::gate::load_summary(&summary)
        .ok()
        .and_then(|s| s.env.families)
    {
        Some(f) => {
            for line in crate::suite::account::lines(&f) {
                crate::say!("{line}");
            }
        }
        None => crate::say!("  (the summary has no account)"),
    }
    crate::say!(
        "main job: {:.0} s; report {}",
        t0.elapsed().as_secs_f64(),
        out.join("index.html").display()
    );
    Ok(code)
}

/// What the main job is about to do, said before it starts: the cases and scenes, how long
/// the last full run in the folder took (when its summary says), that an interruption
/// leaves nothing mixed, and the quicker first look.
fn opening(common: &Common, out: &std::path::Path, full_stability: bool) -> Result<(), String> {
    let cases = load_cases(common)?;
    let scenes: usize = cases.iter().map(|c| c.scenes.len()).sum();
    crate::say!(
        "mbdbench: the main job: {} cases ({scenes} scenes), every registered variant on the \
         full ladders, into {}; then the {} stability study, the report, the recommendation \
         and the gates.",
        cases.len(),
        out.display(),
        if full_stability { "full" } else { "quick" }
    );
    let last = crate::gate::load_summary(&out.join("summary.json")).ok();
    let full = |s: &crate::summary::Summary| {
        s.selection
            .as_ref()
            .is_some_and(|sel| sel.covers(&crate::selection::Selection::everything(sel.tier)))
            && !crate::gate::is_quick_summary(&cases, s)
    };
    match last.as_ref().filter(|s| full(s)) {
        Some(s) => crate::say!(
            "  The last full run here: {} runs in {} (commit {}, {}).",
            s.records.len(),
            s.env
                .elapsed_s
                .map_or("a time it did not record".into(), |t| format!("{t:.0} s")),
            s.git_commit,
            s.created_utc
        ),
        None => crate::say!(
            "  No full run in {} yet to time it by (README.md gives one measured on 2 \
             cores at the top).",
            out.display()
        ),
    }
    crate::say!(
        "  Ctrl-C at any moment leaves {} as it was: nothing half-written, nothing mixed.\n  \
         A first look, the quick tier's short ladders: `mbdbench run --quick --out reports/quick` \
         (in reports/latest, a quick run sends the next main job beside it); `mbdbench --help` \
         lists the commands.\n",
        out.display()
    );
    Ok(())
}
