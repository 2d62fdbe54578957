//! The baseline comparison of `mbdbench gate --baseline FILE` and the deliberate rewrite of
//! the baseline (`--update-baseline`): an earlier summary against the current one, run by run.
//!
//! Two runs are the same when case, scene, param, integrator, formulation and `dt | tol` agree
//! exactly (both summaries come from the same ladder literals). For each pair where both runs
//! are `ok` it adds one row per compared quantity:
//! - an error metric (the family's `problem::Metric::reference_error` ones) regresses when `new > factor * old`; it is compared
//!   only where both values lie above `FLOOR_CLAIMS` x the reference's accuracy claim
//!   (`Problem::accuracy_claim`), since below that the error measures the reference, not the run;
//! - a work count (`work_counts`: RHS evaluations, Newton iterations, element iterations;
//!   deterministic) regresses when `new > WORK_SLACK * old` (skipped when both are 0).
//!
//! A run `ok` in the baseline that now ends in a typed failure is a regression row; runs in
//! only one of the two are ignored (a new variant, a new ladder point), and so are runs made
//! with other settings than the baseline's (their `settings_sha256` differs: a changed
//! tolerance or budget makes a new record, not a regression), counted in one skipped row per
//! scene. A scene whose physics
//! hash differs between the two gives one failing row (the baseline is for other physics: it
//! must be updated deliberately), as does a scene whose reference cannot be loaded when
//! errors are to be compared. A baseline without any run in common is unusable input.
//! Wall time is never compared.
//!
//! Baseline rows are recognised by their threshold text, which always says `baseline`
//! (gate thresholds are `<= x` / `>= x`, or `before t s` for an expected failure).
use std::collections::BTreeMap;
use std::path::Path;

use super::load::{load_as, load_summary};
use super::{GateError, GateRow, Verdict, failure_text, metric_value};
use crate::case::Case;
use crate::integrate::COUNTERS;
use crate::problem::Problem;
use crate::reference;
use crate::summary::{Record, RunKey, Status, Summary};

/// The default `--factor`.
pub const DEFAULT_FACTOR: f64 = 3.0;
/// Allowed growth of a deterministic work count (5 %).
pub const WORK_SLACK: f64 = 1.05;
/// Errors are compared only above this multiple of the reference's accuracy claim.
pub const FLOOR_CLAIMS: f64 = 100.0;
/// The work counts compared with the baseline: the counters a cost
/// (`integrate::Counter::compared`).
pub fn work_counts() -> impl Iterator<Item = &'static str> {
    COUNTERS.iter().filter(|c| c.compared).map(|c| c.name)
}

/// Whether a row comes from the baseline comparison.
pub fn is_baseline_row(r: &GateRow) -> bool {
    r.threshold.contains("baseline")
}

/// Reads a baseline (a summary); unusable input names the file.
pub fn load_baseline(path: &Path) -> Result<Summary, GateError> {
    load_as(path, "baseline")
}

/// Rewrites the baseline from a summary (validated first), atomically.
pub fn update_baseline(summary_path: &Path, baseline_path: &Path) -> Result<(), GateError> {
    let s = load_summary(summary_path)?;
    let write = |message: String| GateError::Write {
        path: baseline_path.display().to_string(),
        message,
    };
    let text = serde_json::to_string_pretty(&s).map_err(|e| write(e.to_string()))?;
    reference::write_atomic(baseline_path, text.as_bytes()).map_err(|e| write(e.to_string()))
}

/// A run and its ladder point (dt bits, tol bits).
type PointKey<'a> = (&'a RunKey, u64, u64);

fn run_key(r: &Record) -> PointKey<'_> {
    (
        &r.key,
        r.dt.map_or(0, f64::to_bits),
        r.tol.map_or(0, f64::to_bits),
    )
}

fn row(r: &Record, metric: &str, value: Option<f64>, threshold: String) -> GateRow {
    GateRow {
        key: r.key.clone(),
        dt: r.dt,
        tol: r.tol,
        metric: metric.into(),
        value,
        outcome: None,
        threshold,
        verdict: Verdict::Pass,
        note: String::new(),
        ratio: None,
    }
}

/// A failing row about a whole scene.
fn scene_row(case: &str, scene: &str, metric: &str, threshold: &str, note: String) -> GateRow {
    GateRow {
        key: RunKey::new(case, scene, "*", "*", "*"),
        dt: None,
        tol: None,
        metric: metric.into(),
        value: None,
        outcome: None,
        threshold: threshold.into(),
        verdict: Verdict::Fail,
        note,
        ratio: None,
    }
}

/// A scene of a case: (case, scene).
type SceneKey = (String, String);

/// The references loaded for their accuracy claims, per scene (or why one cannot be).
type Claims = BTreeMap<SceneKey, Result<Box<dyn Problem>, String>>;

/// Compares `current` with `baseline` (read from `baseline_path`, named in errors). The
/// accuracy claims come from the references under `references`, loaded with the cases'
/// current physics hashes.
pub fn compare_baseline(
    cases: &[Case],
    current: &Summary,
    baseline: &Summary,
    baseline_path: &Path,
    references: &Path,
    factor: f64,
) -> Result<Vec<GateRow>, GateError> {
    let base: BTreeMap<PointKey, &Record> = baseline
        .records
        .iter()
        .filter(|r| r.status != Status::NotApplicable)
        .map(|r| (run_key(r), r))
        .collect();
    let mut now: Vec<&Record> = current
        .records
        .iter()
        .filter(|r| r.status != Status::NotApplicable)
        .collect();
    now.sort_by_key(|r| crate::catalogue::report_order(r));
    let mut claims = Claims::new();
    let mut stale: BTreeMap<SceneKey, usize> = BTreeMap::new();
    let mut renewed: BTreeMap<SceneKey, usize> = BTreeMap::new();
    let mut common = 0usize;
    let mut rows = vec![];
    for r in now {
        let Some(b) = base.get(&run_key(r)) else {
            continue;
        };
        common += 1;
        let scene = || (r.key.case.clone(), r.key.scene.clone());
        if b.inputs_sha256 != r.inputs_sha256 {
            *stale.entry(scene()).or_default() += 1;
            continue;
        }
        if let (Some(old), Some(new)) = (&b.settings_sha256, &r.settings_sha256)
            && old != new
        {
            *renewed.entry(scene()).or_default() += 1;
            continue;
        }
        if b.status == Status::Ok && r.status == Status::Failed {
            let mut x = row(r, "status", None, "ok as in the baseline".into());
            x.verdict = Verdict::Fail;
            x.note = failure_text(r);
            rows.push(x);
            continue;
        }
        if b.status != Status::Ok || r.status != Status::Ok {
            continue;
        }
        compare_errors(cases, references, factor, b, r, &mut claims, &mut rows);
        compare_work(b, r, &mut rows);
    }
    if common == 0 {
        return Err(GateError::Disjoint {
            path: baseline_path.display().to_string(),
        });
    }
    scene_rows(stale, renewed, claims, &mut rows);
    Ok(rows)
}

/// The error-metric rows of a run `ok` on both sides: one per reference error above the
/// floor of the reference's claim (loaded into `claims` once per scene) on both sides.
fn compare_errors(
    cases: &[Case],
    references: &Path,
    factor: f64,
    b: &Record,
    r: &Record,
    claims: &mut Claims,
    rows: &mut Vec<GateRow>,
) {
    let pairs: Vec<(&str, f64, f64)> = error_metrics(cases, &r.key.case)
        .iter()
        .filter_map(|m| {
            let old = metric_value(b, m).flatten()?;
            let new = metric_value(r, m).flatten()?;
            Some((*m, old, new))
        })
        .collect();
    if !pairs.is_empty() {
        let loaded = claims
            .entry((r.key.case.clone(), r.key.scene.clone()))
            .or_insert_with(|| load_reference(cases, references, &r.key.case, &r.key.scene));
        if let Ok(reference) = loaded {
            for (m, old, new) in pairs {
                let floor = FLOOR_CLAIMS
                    * reference
                        .accuracy_claim_for(m, &r.key.formulation)
                        .unwrap_or(f64::INFINITY);
                if !(old > floor && new > floor) {
                    continue;
                }
                let mut x = row(r, m, Some(new), format!("<= {factor} x baseline {old:e}"));
                x.ratio = Some(new / old);
                if new > factor * old {
                    x.verdict = Verdict::Fail;
                    x.note = format!(
                        "regression: {:.3}x the baseline (floor {floor:.2e})",
                        new / old
                    );
                }
                rows.push(x);
            }
        }
    }
}

/// The work-count rows of a run `ok` on both sides (`work_counts`; none where both are 0).
fn compare_work(b: &Record, r: &Record, rows: &mut Vec<GateRow>) {
    for m in work_counts() {
        let (Some(Some(old)), Some(Some(new))) = (metric_value(b, m), metric_value(r, m)) else {
            continue;
        };
        if old == 0.0 && new == 0.0 {
            continue;
        }
        let mut x = row(r, m, Some(new), format!("<= {WORK_SLACK} x baseline {old}"));
        x.ratio = (old > 0.0).then(|| new / old);
        if new > WORK_SLACK * old {
            x.verdict = Verdict::Fail;
            x.note = if old > 0.0 {
                format!("regression: {:+.1} % work", 100.0 * (new / old - 1.0))
            } else {
                "regression: work where the baseline had none".into()
            };
        }
        rows.push(x);
    }
}

/// The rows about whole scenes: stale physics (failing), other settings (skipped), a
/// reference that cannot be loaded for its claims (failing).
fn scene_rows(
    stale: BTreeMap<SceneKey, usize>,
    renewed: BTreeMap<SceneKey, usize>,
    claims: Claims,
    rows: &mut Vec<GateRow>,
) {
    for ((case, scene), n) in stale {
        rows.push(scene_row(
            &case,
            &scene,
            "inputs_sha256",
            "same physics as the baseline",
            format!(
                "{n} run(s) of this scene were made from other physics than the baseline's: \
                 update the baseline deliberately (gate --update-baseline)"
            ),
        ));
    }
    for ((case, scene), n) in renewed {
        let mut x = scene_row(
            &case,
            &scene,
            "settings_sha256",
            "same settings as the baseline",
            format!(
                "{n} run(s) of this scene were made with other numerical settings than the \
                 baseline's (the case file's settings_sha256 differs): new records, not compared"
            ),
        );
        x.verdict = Verdict::Skip;
        rows.push(x);
    }
    for ((case, scene), loaded) in claims {
        if let Err(e) = loaded {
            rows.push(scene_row(
                &case,
                &scene,
                "accuracy_claim",
                "baseline errors comparable",
                format!("cannot compare errors with the baseline: {e}"),
            ));
        }
    }
}

/// The reference errors of a case's family (none for a case not in the catalogue).
fn error_metrics(cases: &[Case], case_name: &str) -> Vec<&'static str> {
    cases
        .iter()
        .find(|c| c.name == case_name)
        .map(|c| {
            crate::catalogue::family_of(c)
                .metrics
                .iter()
                .filter(|m| m.reference_error)
                .map(|m| m.name)
                .collect()
        })
        .unwrap_or_default()
}

/// The scene compiled with its current reference attached (loaded with the case's current
/// physics hash): its accuracy claims.
fn load_reference(
    cases: &[Case],
    root: &Path,
    case_name: &str,
    scene_name: &str,
) -> Result<Box<dyn Problem>, String> {
    let c = cases
        .iter()
        .find(|c| c.name == case_name)
        .ok_or_else(|| format!("case `{case_name}` is not in the catalogue"))?;
    let s = c
        .scene(scene_name)
        .ok_or_else(|| format!("{}: no scene `{scene_name}`", c.file))?;
    let mut p = (crate::catalogue::family_of(c).compile)(c, s).map_err(|e| e.to_string())?;
    p.attach_reference(root)?;
    Ok(p)
}

#[cfg(test)]
mod tests {
    use super::super::fixture::{self, nine, opts, passing};
    use super::super::{GateOptions, evaluate, exit_code, print_table};
    use super::*;
    use crate::integrate::{Failure, FailureKind};

    const BASELINE: &str = "reports/baseline/quick.json";

    fn compare(c: &Case, current: &Summary, baseline: &Summary) -> Vec<GateRow> {
        compare_baseline(
            std::slice::from_ref(c),
            current,
            baseline,
            Path::new(BASELINE),
            &fixture::references(),
            DEFAULT_FACTOR,
        )
        .unwrap()
    }

    /// The accuracy claim of nine_spring/two_angles for `metric`.
    fn claim(c: &Case, metric: &str) -> f64 {
        let r = load_reference(
            std::slice::from_ref(c),
            &fixture::references(),
            "nine_spring",
            "two_angles",
        )
        .unwrap();
        r.accuracy_claim(metric).unwrap()
    }

    fn rk4_at(s: &mut Summary, dt: f64) -> &mut Record {
        s.records
            .iter_mut()
            .find(|r| r.key.integrator == "rk4" && r.dt == Some(dt))
            .unwrap()
    }

    fn failing(rows: &[GateRow]) -> Vec<&GateRow> {
        rows.iter().filter(|r| r.verdict == Verdict::Fail).collect()
    }

    /// An unchanged summary passes every comparison: one rhs_evals row per run (Newton
    /// counts, 0 on both sides, are skipped) plus the errors above the floor; the table shows
    /// only the count line for them.
    #[test]
    fn unchanged_summary_passes() {
        let c = nine();
        let s = passing(&c);
        let rows = compare(&c, &s, &s);
        assert!(
            rows.iter()
                .all(|r| r.verdict == Verdict::Pass && is_baseline_row(r))
        );
        assert_eq!(rows.iter().filter(|r| r.metric == "rhs_evals").count(), 4);
        assert!(rows.iter().all(|r| r.metric != "newton_iters"));
        let floor = FLOOR_CLAIMS * claim(&c, "rotation_error_max");
        assert!(
            floor < 4.0e-6,
            "the fixture's 4e-6 error lies above the floor {floor:e}"
        );
        assert!(
            rows.iter()
                .any(|r| r.metric == "rotation_error_max" && r.dt == Some(1.0e-2))
        );
        let mut out = vec![];
        print_table(&rows, &mut out).unwrap();
        let t = String::from_utf8(out).unwrap();
        let n = rows.len();
        assert_eq!(
            t,
            format!("baseline: {n} comparisons, 0 regressions\n{n} passed, 0 failed, 0 skipped\n")
        );
    }

    /// Doubled RHS evaluations are a regression; 4.75 % more are not, 5.25 % more are.
    #[test]
    fn doubled_rhs_evals_fail() {
        let c = nine();
        let base = passing(&c);
        let mut s = base.clone();
        rk4_at(&mut s, 1.0e-2).stats.rhs_evals = 8000;
        let rows = compare(&c, &s, &base);
        let f = failing(&rows);
        assert_eq!(f.len(), 1, "{f:?}");
        assert_eq!(
            (f[0].metric.as_str(), f[0].value, f[0].threshold.as_str()),
            ("rhs_evals", Some(8000.0), "<= 1.05 x baseline 4000")
        );
        assert_eq!(f[0].note, "regression: +100.0 % work");
        rk4_at(&mut s, 1.0e-2).stats.rhs_evals = 4190;
        assert!(failing(&compare(&c, &s, &base)).is_empty());
        rk4_at(&mut s, 1.0e-2).stats.rhs_evals = 4210;
        assert_eq!(failing(&compare(&c, &s, &base)).len(), 1);
        // Newton iterations appearing where there were none are a regression too.
        rk4_at(&mut s, 1.0e-2).stats.rhs_evals = 4000;
        rk4_at(&mut s, 1.0e-2).stats.newton_iters = 3;
        let rows = compare(&c, &s, &base);
        let f = failing(&rows);
        assert_eq!((f.len(), f[0].metric.as_str()), (1, "newton_iters"));
    }

    /// Element iterations (the fiber column's work) are compared like the other work counts:
    /// 10 % more than the baseline's is a regression row naming `element_iters`, 4 % more a
    /// passing row, none on both sides no row at all.
    #[test]
    fn element_iters_are_compared() {
        let c = nine();
        let mut base = passing(&c);
        assert!(
            compare(&c, &base, &base)
                .iter()
                .all(|r| r.metric != "element_iters")
        );
        rk4_at(&mut base, 1.0e-2).stats.element_iters = 1000;
        let mut s = base.clone();
        rk4_at(&mut s, 1.0e-2).stats.element_iters = 1040;
        let rows = compare(&c, &s, &base);
        let x: Vec<&GateRow> = rows
            .iter()
            .filter(|r| r.metric == "element_iters")
            .collect();
        assert_eq!((x.len(), x[0].verdict), (1, Verdict::Pass), "{rows:?}");
        rk4_at(&mut s, 1.0e-2).stats.element_iters = 1100;
        let rows = compare(&c, &s, &base);
        let f = failing(&rows);
        assert_eq!(
            (f.len(), f[0].metric.as_str(), f[0].threshold.as_str()),
            (1, "element_iters", "<= 1.05 x baseline 1000")
        );
    }

    /// A run made with other settings than the baseline's (its `settings_sha256` differs) is
    /// a new record: its doubled work is not a regression, and one skipped row per scene says
    /// how many runs were not compared; with equal settings the same work fails.
    #[test]
    fn other_settings_make_new_records() {
        let c = nine();
        let mut base = passing(&c);
        for r in &mut base.records {
            r.settings_sha256 = Some("a".repeat(64));
        }
        let mut s = base.clone();
        rk4_at(&mut s, 1.0e-2).stats.rhs_evals = 8000;
        assert_eq!(failing(&compare(&c, &s, &base)).len(), 1);
        rk4_at(&mut s, 1.0e-2).settings_sha256 = Some("b".repeat(64));
        let rows = compare(&c, &s, &base);
        assert!(failing(&rows).is_empty(), "{rows:?}");
        let skipped: Vec<&GateRow> = rows.iter().filter(|r| r.verdict == Verdict::Skip).collect();
        assert_eq!(skipped.len(), 1, "{rows:?}");
        assert_eq!(skipped[0].metric, "settings_sha256");
        assert!(
            skipped[0].note.starts_with("1 run(s) of this scene"),
            "{}",
            skipped[0].note
        );
        assert!(is_baseline_row(skipped[0]));
    }

    /// A 10x error growth above 100x the accuracy claim is a regression; below it (both
    /// values, or only the old one) it is not compared at all.
    #[test]
    fn error_growth_above_the_floor_only() {
        let c = nine();
        let k = claim(&c, "rotation_error_max");
        let set = |old: f64, new: f64| {
            let mut base = passing(&c);
            let mut s = base.clone();
            rk4_at(&mut base, 1.0e-2)
                .metrics
                .insert("rotation_error_max".into(), Some(old));
            rk4_at(&mut s, 1.0e-2)
                .metrics
                .insert("rotation_error_max".into(), Some(new));
            compare(&c, &s, &base)
        };
        let rot = |rows: &[GateRow]| {
            rows.iter()
                .filter(|r| r.metric == "rotation_error_max" && r.dt == Some(1.0e-2))
                .cloned()
                .collect::<Vec<_>>()
        };
        let rows = set(1.0e3 * k, 1.0e4 * k);
        let r = rot(&rows);
        assert_eq!(r.len(), 1);
        assert_eq!(r[0].verdict, Verdict::Fail);
        assert!(
            r[0].note.starts_with("regression: 10.000x"),
            "{}",
            r[0].note
        );
        assert_eq!(exit_code(&rows), 1);
        // 2.9x is within the factor 3.
        let rows = set(1.0e3 * k, 2.9e3 * k);
        assert_eq!(rot(&rows)[0].verdict, Verdict::Pass);
        // Both below the floor: not a comparison.
        let rows = set(k, 10.0 * k);
        assert!(rot(&rows).is_empty());
        assert_eq!(exit_code(&rows), 0);
        // Only the old value below the floor: not compared either.
        let rows = set(50.0 * k, 500.0 * k);
        assert!(rot(&rows).is_empty());
        assert_eq!(exit_code(&rows), 0);
    }

    /// A run ok in the baseline that now fails is a regression; one from other physics makes
    /// its scene fail once; a baseline with no run in common is unusable input.
    #[test]
    fn failures_stale_and_disjoint() {
        let c = nine();
        let base = passing(&c);
        let mut s = base.clone();
        let r = rk4_at(&mut s, 5.0e-3);
        r.status = Status::Failed;
        r.failure = Some(Failure::new(FailureKind::NonFinite, 7.5, "NaN in omega"));
        let rows = compare(&c, &s, &base);
        let f = failing(&rows);
        assert_eq!(f.len(), 1);
        assert_eq!(
            (f[0].metric.as_str(), f[0].note.as_str()),
            ("status", "run failed: non_finite at t = 7.5: NaN in omega")
        );
        let mut old = base.clone();
        for r in &mut old.records {
            r.inputs_sha256 = "1".repeat(64);
        }
        let rows = compare(&c, &base, &old);
        assert_eq!(rows.len(), 1);
        assert_eq!(
            (rows[0].metric.as_str(), rows[0].verdict),
            ("inputs_sha256", Verdict::Fail)
        );
        assert!(rows[0].note.starts_with("4 run(s) of this scene"));
        let mut other = base.clone();
        for r in &mut other.records {
            r.dt = r.dt.map(|h| h * 3.0);
            r.tol = r.tol.map(|t| t * 0.01);
        }
        let e = compare_baseline(
            std::slice::from_ref(&c),
            &base,
            &other,
            Path::new(BASELINE),
            &fixture::references(),
            DEFAULT_FACTOR,
        )
        .unwrap_err();
        assert!(
            matches!(e, GateError::Disjoint { .. }) && e.to_string().starts_with(BASELINE),
            "{e}"
        );
    }

    /// `--update-baseline` writes the summary as the baseline (its `methods` table and
    /// `families` list with it); `evaluate` with `--baseline` then passes, catches a later
    /// regression, and an unreadable baseline is bad input.
    #[test]
    fn update_then_compare_through_evaluate() {
        let dir = fixture::scratch("baseline");
        let c = nine();
        let s = passing(&c);
        let summary_path = dir.join("summary.json");
        std::fs::write(&summary_path, serde_json::to_string(&s).unwrap()).unwrap();
        let baseline = dir.join("baseline").join("quick.json");
        update_baseline(&summary_path, &baseline).unwrap();
        assert_eq!(load_baseline(&baseline).unwrap(), s);
        assert!(s.methods.is_some() && s.families.is_some());
        let o = GateOptions {
            baseline: Some(baseline.clone()),
            ..opts(true)
        };
        let rows = evaluate(std::slice::from_ref(&c), &s, None, &o).unwrap();
        assert_eq!(rows.iter().filter(|r| !is_baseline_row(r)).count(), 3);
        assert!(rows.iter().filter(|r| is_baseline_row(r)).count() >= 4);
        assert_eq!(exit_code(&rows), 0);
        let mut worse = s.clone();
        rk4_at(&mut worse, 1.0e-2).stats.rhs_evals = 8000;
        let rows = evaluate(std::slice::from_ref(&c), &worse, None, &o).unwrap();
        assert_eq!(exit_code(&rows), 1);
        let mut out = vec![];
        print_table(&rows, &mut out).unwrap();
        let t = String::from_utf8(out).unwrap();
        assert!(
            t.contains("rhs_evals") && t.contains("+100.0 % work"),
            "{t}"
        );
        assert!(t.contains(", 1 regressions\n"), "{t}");
        std::fs::write(&baseline, "{\"schema\": 1, ").unwrap();
        let e = evaluate(std::slice::from_ref(&c), &s, None, &o).unwrap_err();
        assert!(
            e.to_string().starts_with(&format!(
                "{}: unusable baseline: truncated",
                baseline.display()
            )),
            "{e}"
        );
        let e = update_baseline(&dir.join("none.json"), &baseline).unwrap_err();
        assert!(e.to_string().contains("none.json: unusable summary"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
