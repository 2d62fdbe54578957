//! Tests of the gate: expansion of `where` over scenes, variants and ladders, verdicts and
//! their notes (stale records and references, missing records, n/a, failures, null metrics),
//! the exit code and the printed table.
use super::fixture::{self, nine, opts, passing};
use super::*;

fn table(rows: &[GateRow]) -> String {
    let mut out = vec![];
    print_table(rows, &mut out).unwrap();
    String::from_utf8(out).unwrap()
}

fn find<'a>(rows: &'a [GateRow], metric: &str, param: &str) -> &'a GateRow {
    rows.iter()
        .find(|r| r.metric == metric && r.key.param == param)
        .unwrap()
}

fn rec_mut<'a>(s: &'a mut Summary, integrator: &str, dt: f64) -> &'a mut Record {
    s.records
        .iter_mut()
        .find(|r| r.key.integrator == integrator && r.dt == Some(dt))
        .unwrap()
}

/// A summary whose ladder records all lie on their scenes' quick ladders is quick; one
/// record off them (a full-ladder point) or no ladder record at all makes it not quick.
#[test]
fn quick_summary_is_recognised() {
    let cases: Vec<_> = crate::catalogue::embedded()
        .unwrap()
        .into_iter()
        .filter(|c| c.model() == "rigid_body")
        .collect();
    let plans = crate::model::rigid_body::plan::plans(&cases, &[], &[]).unwrap();
    let p = plans
        .iter()
        .find(|p| p.header.case == "nine_spring" && p.header.scene == "two_angles")
        .unwrap();
    let mut s = passing(&nine());
    s.records.truncate(1);
    let r = &mut s.records[0];
    (r.key.case, r.key.scene, r.tol) = ("nine_spring".into(), "two_angles".into(), None);
    r.dt = Some(p.quick.order2_4[0]);
    assert!(is_quick_summary(&cases, &s));
    let off = *p
        .ladders
        .order2_4
        .iter()
        .find(|h| !p.quick.order2_4.contains(h))
        .expect("a full-only point");
    let mut full = s.records[0].clone();
    full.dt = Some(off);
    s.records.push(full);
    assert!(!is_quick_summary(&cases, &s));
    s.records.clear();
    assert!(!is_quick_summary(&cases, &s));
}

/// A summary within every bound passes: one row per expanded point (1 + 1 + 2), exit 0.
#[test]
fn passing_summary_passes() {
    let c = nine();
    let rows = evaluate(std::slice::from_ref(&c), &passing(&c), None, &opts(false)).unwrap();
    assert_eq!(rows.len(), 4);
    assert!(rows.iter().all(|r| r.verdict == Verdict::Pass), "{rows:?}");
    assert_eq!(exit_code(&rows), 0);
    let t = table(&rows);
    assert_eq!(
        t.lines().last(),
        Some("4 passed, 0 failed, 0 skipped"),
        "{t}"
    );
    // The conditioning gate is a minimum over two parameterizations, in registry order.
    let cond: Vec<&str> = rows
        .iter()
        .filter(|r| r.metric == "conditioning_min")
        .map(|r| r.key.param.as_str())
        .collect();
    assert_eq!(cond.len(), 2);
    assert!(cond.contains(&"so3") && cond.contains(&"quat"));
    assert_eq!(find(&rows, "conditioning_min", "quat").threshold, ">= 5e-1");
}

/// A gated metric 10x worse than its threshold fails (exit 1) with a row, and a printed
/// line, naming case, variant, metric, value and threshold.
#[test]
fn ten_times_worse_fails() {
    let c = nine();
    let mut s = passing(&c);
    rec_mut(&mut s, "rk4", 1.0e-2)
        .metrics
        .insert("rotation_error_max".into(), Some(1.0e-4));
    let rows = evaluate(std::slice::from_ref(&c), &s, None, &opts(false)).unwrap();
    assert_eq!(exit_code(&rows), 1);
    let r = find(&rows, "rotation_error_max", "so3");
    assert_eq!(r.verdict, Verdict::Fail);
    assert_eq!((r.value, r.threshold.as_str()), (Some(1.0e-4), "<= 1e-5"));
    assert!(r.note.contains("10.000x"), "{}", r.note);
    let t = table(&rows);
    let line = t.lines().find(|l| l.contains("FAIL")).unwrap();
    for part in [
        "nine_spring",
        "two_angles/so3/rk4/body dt=1e-2",
        "rotation_error_max",
        "1.000e-4",
        "<= 1e-5",
    ] {
        assert!(line.contains(part), "{part} not in {line}");
    }
    assert_eq!(t.lines().last(), Some("3 passed, 1 failed, 0 skipped"));
    // A value exactly at the maximum passes (the bound is inclusive).
    rec_mut(&mut s, "rk4", 1.0e-2)
        .metrics
        .insert("rotation_error_max".into(), Some(1.0e-5));
    let rows = evaluate(std::slice::from_ref(&c), &s, None, &opts(false)).unwrap();
    assert_eq!(exit_code(&rows), 0);
    // Below a minimum fails too.
    s.records[3]
        .metrics
        .insert("conditioning_min".into(), Some(0.25));
    let rows = evaluate(&[c], &s, None, &opts(false)).unwrap();
    let r = find(&rows, "conditioning_min", "quat");
    assert_eq!(r.verdict, Verdict::Fail);
    assert!(r.note.contains("below the minimum"));
}

/// A record made from other physics (inputs hash) fails as stale.
#[test]
fn stale_inputs_hash_fails() {
    let c = nine();
    let mut s = passing(&c);
    rec_mut(&mut s, "rk4", 1.0e-2).inputs_sha256 = "0".repeat(64);
    let rows = evaluate(&[c], &s, None, &opts(false)).unwrap();
    let r = find(&rows, "rotation_error_max", "so3");
    assert_eq!(r.verdict, Verdict::Fail);
    assert!(
        r.note
            .starts_with("stale: the record's inputs_sha256 000000000000")
    );
    assert_eq!(exit_code(&rows), 1);
    assert_eq!(
        rows.iter().filter(|r| r.verdict == Verdict::Fail).count(),
        1
    );
}

/// A record scored against another reference file fails as stale; so does every point
/// when the reference file is missing.
#[test]
fn stale_reference_hash_fails() {
    let c = nine();
    let mut s = passing(&c);
    rec_mut(&mut s, "rk4", 5.0e-3).reference_sha256 = Some("ab".repeat(32));
    let rows = evaluate(std::slice::from_ref(&c), &s, None, &opts(false)).unwrap();
    let r = find(&rows, "energy_drift_max", "so3");
    assert_eq!(r.verdict, Verdict::Fail);
    assert!(
        r.note.contains("reference_sha256 abababababab"),
        "{}",
        r.note
    );
    assert_eq!(exit_code(&rows), 1);
    // A record without a reference hash (a --t-end run) is stale as well.
    rec_mut(&mut s, "rk4", 5.0e-3).reference_sha256 = None;
    let rows = evaluate(std::slice::from_ref(&c), &s, None, &opts(false)).unwrap();
    assert!(find(&rows, "energy_drift_max", "so3").note.contains("null"));
    // No reference files at all.
    let dir = fixture::scratch("noref");
    let o = GateOptions {
        references: dir.clone(),
        ..opts(false)
    };
    let rows = evaluate(&[c], &passing(&nine()), None, &o).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(rows.len(), 4);
    for r in &rows {
        assert_eq!(r.verdict, Verdict::Fail);
        assert!(r.note.contains("stale") && r.note.contains("missing reference"));
    }
}

/// A gated variant without a record fails ("no record"), as do a failed run, a null
/// metric (with its reason) and an absent one.
#[test]
fn missing_record_and_unusable_values_fail() {
    let c = nine();
    let mut s = passing(&c);
    s.records.retain(|r| r.key.param != "quat");
    let rows = evaluate(std::slice::from_ref(&c), &s, None, &opts(false)).unwrap();
    let r = find(&rows, "conditioning_min", "quat");
    assert_eq!((r.verdict, r.value), (Verdict::Fail, None));
    assert_eq!(r.note, "no record in the summary");
    assert_eq!(exit_code(&rows), 1);

    let mut s = passing(&c);
    let r = rec_mut(&mut s, "rk4", 1.0e-2);
    r.metrics.insert("rotation_error_max".into(), None);
    r.metric_reasons.insert(
        "rotation_error_max".into(),
        "the run ended before t_end".into(),
    );
    let r = rec_mut(&mut s, "rk4", 5.0e-3);
    r.status = Status::Failed;
    r.failure = Some(crate::integrate::Failure::new(
        crate::integrate::FailureKind::NewtonFailure,
        2.5,
        "no convergence in 50 iterations",
    ));
    s.records[3].metrics.remove("conditioning_min");
    let rows = evaluate(&[c], &s, None, &opts(false)).unwrap();
    assert_eq!(
        find(&rows, "rotation_error_max", "so3").note,
        "null: the run ended before t_end"
    );
    assert_eq!(
        find(&rows, "energy_drift_max", "so3").note,
        "run failed: newton_failure at t = 2.5: no convergence in 50 iterations"
    );
    assert!(
        find(&rows, "conditioning_min", "quat")
            .note
            .starts_with("metric absent")
    );
    assert_eq!(
        find(&rows, "conditioning_min", "so3").verdict,
        Verdict::Pass
    );
}

/// --quick evaluates only quick gates, on the quick ladder points.
#[test]
fn quick_evaluates_only_quick_gates() {
    let c = nine();
    let rows = evaluate(std::slice::from_ref(&c), &passing(&c), None, &opts(true)).unwrap();
    assert_eq!(rows.len(), 3);
    assert!(rows.iter().all(|r| r.metric != "energy_drift_max"));
    assert!(rows.iter().all(|r| r.verdict == Verdict::Pass));
    // A failing full-only gate does not affect the quick gate.
    let mut s = passing(&c);
    rec_mut(&mut s, "rk4", 5.0e-3)
        .metrics
        .insert("energy_drift_max".into(), Some(1.0));
    assert_eq!(
        exit_code(&evaluate(std::slice::from_ref(&c), &s, None, &opts(true)).unwrap()),
        0
    );
    assert_eq!(
        exit_code(&evaluate(&[c], &s, None, &opts(false)).unwrap()),
        1
    );
}

/// A per-variant stability metric (`largest_stable_dt`) is gated on the stability
/// summary's record without a ladder point and without a stored reference hash: the
/// measured step passes, a halved step fails, a missing record fails, and a stale physics
/// hash fails.
#[test]
fn halved_stable_step_fails() {
    let gate = "[[gates]]\nmetric = \"largest_stable_dt\"\nmin = 0.276793332\n\
                where = { scene = \"two_angles\", param = \"so3\", integrator = \"simo_wong\", \
                formulation = \"body\" }\nquick = true\nbaseline = 0.46132222\nmargin = 0.6\n";
    let c = fixture::with_gates("nine_spring", gate);
    let stable = |dt: f64| {
        let mut r = fixture::record(
            &c,
            "two_angles",
            ("so3", "simo_wong", "body"),
            None,
            None,
            &[("largest_stable_dt", dt)],
            0,
        );
        r.reference_sha256 = None;
        r
    };
    let s = fixture::summary(vec![]);
    let eval = |st: Vec<Record>| {
        let st = fixture::summary(st);
        evaluate(std::slice::from_ref(&c), &s, Some(&st), &opts(true)).unwrap()
    };
    let rows = eval(vec![stable(0.46132222)]);
    assert_eq!(rows.len(), 1);
    assert_eq!((rows[0].dt, rows[0].tol), (None, None));
    assert_eq!(rows[0].verdict, Verdict::Pass, "{rows:?}");
    let rows = eval(vec![stable(0.46132222 / 2.0)]);
    assert_eq!(rows[0].verdict, Verdict::Fail);
    assert_eq!(rows[0].note, "below the minimum");
    assert_eq!(exit_code(&rows), 1);
    let rows = eval(vec![]);
    assert!(rows[0].note.contains("no record"), "{}", rows[0].note);
    let mut stale = stable(0.46132222);
    stale.inputs_sha256 = "0".repeat(64);
    let rows = eval(vec![stale]);
    assert!(rows[0].note.starts_with("stale"), "{}", rows[0].note);
}

/// A stability record at a ladder point that does not carry the gated metric (a
/// sensitivity run at tol 1e-6, say) does not stand in for the summary's missing run: the
/// point has no record.
#[test]
fn stability_record_without_the_metric_is_no_stand_in() {
    let c = nine();
    let mut s = passing(&c);
    s.records
        .retain(|r| !(r.key.param == "quat" && r.key.integrator == "dopri5"));
    let mut other = fixture::record(
        &c,
        "two_angles",
        ("quat", "dopri5", "body"),
        None,
        Some(1.0e-6),
        &[("sensitivity_growth_max", 12.0)],
        0,
    );
    other.reference_sha256 = None;
    let st = fixture::summary(vec![other]);
    let rows = evaluate(std::slice::from_ref(&c), &s, Some(&st), &opts(true)).unwrap();
    let r = find(&rows, "conditioning_min", "quat");
    assert_eq!(r.verdict, Verdict::Fail);
    assert!(r.note.contains("no record"), "{}", r.note);
}

/// Records of the stability summary are searched too, and their metric names are known.
#[test]
fn stability_records_are_searched() {
    let c = fixture::with_gates(
        "nine_spring",
        "[[gates]]\nmetric = \"stable_fraction\"\nmin = 0.9\nwhere = { scene = \"large\", \
         param = \"so3\", integrator = \"lgvi\", dt = 1.0e-2 }\n",
    );
    let s = fixture::summary(vec![]);
    // Without the stability summary the metric is unknown: bad input.
    let e = evaluate(std::slice::from_ref(&c), &s, None, &opts(false)).unwrap_err();
    assert!(matches!(e, GateError::UnknownMetric { .. }), "{e}");
    let st = fixture::summary(vec![fixture::record(
        &c,
        "large",
        ("so3", "lgvi", "body"),
        Some(1.0e-2),
        None,
        &[("stable_fraction", 0.95)],
        1000,
    )]);
    let rows = evaluate(&[c], &s, Some(&st), &opts(false)).unwrap();
    assert_eq!(rows.len(), 1);
    assert_eq!(
        (rows[0].verdict, rows[0].value),
        (Verdict::Pass, Some(0.95))
    );
}

/// A gated point without a record says so, and adds the reason when the summary is of the
/// other tier than the gates (quick gates on a full run, full gates on a quick run); on the
/// matching tier the note is plain.
#[test]
fn missing_point_names_the_tier() {
    let c = nine();
    let cases = std::slice::from_ref(&c);
    let mut s = passing(&c);
    // Only the quick ladders' points: a quick-tier run, missing the full gates' points.
    s.records.retain(|r| {
        let q = &c.scene(&r.key.scene).unwrap().quick;
        r.dt.or(r.tol).is_some_and(|v| {
            [&q.order1, &q.order2_4, &q.order6]
                .iter()
                .any(|l| l.iter().any(|f| f.dt == v))
                || q.tol.contains(&v)
        })
    });
    let quick_summary = is_quick_summary(cases, &s);
    assert!(quick_summary);
    let mut seen_hint = false;
    for quick in [true, false] {
        let rows = evaluate(cases, &s, None, &opts(quick)).unwrap();
        for r in rows.iter().filter(|r| r.note.contains("no record")) {
            let hinted = r.note.contains("tier run");
            assert_eq!(hinted, quick != quick_summary, "{}", r.note);
            seen_hint |= hinted;
        }
    }
    assert!(seen_hint, "no missing point on the other tier");
}

/// An expected-failure gate on nine_spring's quick rk4 point: diverge after 5 s and before
/// 20 s.
const EXPECT_DIVERGED: &str = "[[gates]]\nexpect = { status = \"failed\", kind = \"diverged\", \
     after = 5.0, before = 20.0 }\nwhere = { scene = \"two_angles\", param = \"so3\", integrator = \"rk4\", \
     formulation = \"body\", dt = 1.0e-2 }\nquick = true\n";

/// The summary of `passing`, with its quick rk4 run failed as `kind` at `t` (None: left ok).
fn failed_at(c: &Case, failure: Option<(crate::integrate::FailureKind, f64)>) -> Summary {
    let mut s = passing(c);
    if let Some((kind, t)) = failure {
        let r = rec_mut(&mut s, "rk4", 1.0e-2);
        r.status = Status::Failed;
        r.failure = Some(crate::integrate::Failure::new(
            kind,
            t,
            "the bound was crossed",
        ));
    }
    s
}

/// An expected-failure gate passes only on a typed failure of its kind at
/// `after < t <= before`: `diverged` at t = 12 (and at exactly 20) passes; a run that ended ok,
/// `non_finite` at t = 12, `diverged` at t = 25, and `diverged` at the start (t = 0) or at
/// exactly `after` (another cause) fail, each saying what happened and what was expected.
#[test]
fn expected_failure_passes_only_on_its_kind_in_time() {
    use crate::integrate::FailureKind::{Diverged, NonFinite};
    let c = fixture::with_gates("nine_spring", EXPECT_DIVERGED);
    let eval = |f| {
        let rows = evaluate(
            std::slice::from_ref(&c),
            &failed_at(&c, f),
            None,
            &opts(true),
        );
        let rows = rows.unwrap();
        assert_eq!(rows.len(), 1, "{rows:?}");
        rows.into_iter().next().unwrap()
    };
    let r = eval(Some((Diverged, 12.0)));
    assert_eq!((r.verdict, r.note.as_str()), (Verdict::Pass, ""));
    assert_eq!(
        (
            r.metric.as_str(),
            r.outcome.as_deref(),
            r.threshold.as_str(),
            r.value
        ),
        (
            "expect failed (diverged)",
            Some("diverged at t = 12"),
            "after 5, before 20 s",
            None
        )
    );
    assert!(is_expect_row(&r) && !is_baseline_row(&r));
    assert_eq!(eval(Some((Diverged, 20.0))).verdict, Verdict::Pass);

    let r = eval(None);
    assert_eq!(r.verdict, Verdict::Fail);
    assert_eq!(r.outcome.as_deref(), Some("ok"));
    assert_eq!(
        r.note,
        "ran to t_end without failing; expected diverged after 5 and before 20 s"
    );

    let r = eval(Some((NonFinite, 12.0)));
    assert_eq!(r.verdict, Verdict::Fail);
    assert_eq!(r.outcome.as_deref(), Some("non_finite at t = 12"));
    assert_eq!(
        r.note,
        "failed with non_finite at t = 12: the bound was crossed; expected diverged after 5 and before 20 s"
    );

    let r = eval(Some((Diverged, 25.0)));
    assert_eq!(r.verdict, Verdict::Fail);
    assert_eq!(
        r.note,
        "diverged at t = 25, too late: expected diverged after 5 and before 20 s"
    );
    for early in [0.0, 1.0e-2, 5.0] {
        let r = eval(Some((Diverged, early)));
        assert_eq!(r.verdict, Verdict::Fail, "diverged at t = {early}");
        assert!(
            r.note.contains("too early (another cause)"),
            "{early}: {}",
            r.note
        );
    }
}

/// An expected-failure gate is judged beside the bound gates, one row per matched record, in
/// the verdict line and the exit code; like theirs, its point fails without a record or with
/// a stale one, and its `where` must match some point (else bad input).
#[test]
fn expected_failure_counts_like_a_bound_gate() {
    use crate::integrate::FailureKind::Diverged;
    let c = fixture::with_gates(
        "nine_spring",
        &format!("{}\n{EXPECT_DIVERGED}", fixture::GATES),
    );
    let cases = std::slice::from_ref(&c);
    // The bound gate on the same run now sees a failed run.
    let s = failed_at(&c, Some((Diverged, 12.0)));
    let rows = evaluate(cases, &s, None, &opts(true)).unwrap();
    assert_eq!(rows.len(), 4);
    assert_eq!(verdict_line(&rows), "3 passed, 1 failed, 0 skipped");
    assert_eq!(
        find(&rows, "rotation_error_max", "so3").note,
        "run failed: diverged at t = 12: the bound was crossed"
    );
    assert_eq!(
        find(&rows, "expect failed (diverged)", "so3").verdict,
        Verdict::Pass
    );
    // Without the record.
    let mut s = failed_at(&c, Some((Diverged, 12.0)));
    s.records.retain(|r| r.dt != Some(1.0e-2));
    let rows = evaluate(cases, &s, None, &opts(true)).unwrap();
    let r = find(&rows, "expect failed (diverged)", "so3");
    assert_eq!((r.verdict, r.outcome.as_deref()), (Verdict::Fail, None));
    assert!(r.note.starts_with("no record in the summary"), "{}", r.note);
    assert_eq!(exit_code(&rows), 1);
    // A stale record does not pass, whatever it says.
    let mut s = failed_at(&c, Some((Diverged, 12.0)));
    rec_mut(&mut s, "rk4", 1.0e-2).inputs_sha256 = "0".repeat(64);
    let rows = evaluate(cases, &s, None, &opts(true)).unwrap();
    let r = find(&rows, "expect failed (diverged)", "so3");
    assert_eq!(r.verdict, Verdict::Fail);
    assert!(r.note.starts_with("stale"), "{}", r.note);
    // A `where` matching no point of the tier is bad input, as for a bound gate.
    let c = fixture::with_gates(
        "nine_spring",
        &EXPECT_DIVERGED.replace("dt = 1.0e-2", "dt = 5.0e-3"),
    );
    let e = evaluate(&[c], &s, None, &opts(true)).unwrap_err();
    assert!(
        matches!(e, GateError::Where { .. }) && e.to_string().contains("gates[0].where"),
        "{e}"
    );
}

/// The printed table shows an expected-failure gate's label, outcome and bound, and why a
/// failing one failed.
#[test]
fn expected_failure_renders() {
    use crate::integrate::FailureKind::Diverged;
    let c = fixture::with_gates("nine_spring", EXPECT_DIVERGED);
    let rows = evaluate(
        std::slice::from_ref(&c),
        &failed_at(&c, Some((Diverged, 12.0))),
        None,
        &opts(true),
    )
    .unwrap();
    let t = table(&rows);
    let line = t.lines().find(|l| l.contains("PASS")).unwrap();
    for part in [
        "two_angles/so3/rk4/body dt=1e-2",
        "expect failed (diverged)",
        "diverged at t = 12",
        "after 5, before 20 s",
    ] {
        assert!(line.contains(part), "{part} not in {line}");
    }
    assert_eq!(t.lines().last(), Some("1 passed, 0 failed, 0 skipped"));
    let ok = failed_at(&c, None);
    let rows = evaluate(&[c], &ok, None, &opts(true)).unwrap();
    let t = table(&rows);
    let line = t.lines().find(|l| l.contains("FAIL")).unwrap();
    for part in [
        "expect failed (diverged)",
        " ok ",
        "after 5, before 20 s",
        "FAIL  ran to t_end without failing; expected diverged after 5 and before 20 s",
    ] {
        assert!(line.contains(part), "{part} not in {line}");
    }
    // The row, with its outcome, survives a JSON round trip.
    let back: GateRow = serde_json::from_str(&serde_json::to_string(&rows[0]).unwrap()).unwrap();
    assert_eq!(back, rows[0]);
}
