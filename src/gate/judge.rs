//! The verdicts and texts of one gate row: a bound gate passes a record that ended `ok` with
//! its metric within the bound; an expected-failure gate passes only a typed failure of its
//! kind inside its window `after < t <= before` (`Check::Expect`); the row's `metric` column, threshold and
//! value texts for both forms.
use super::{EXPECT_PREFIX, GateRow, Verdict, failure_text, metric_value};
use crate::case::Bound;
use crate::case::gate::Check;
use crate::integrate::FailureKind;
use crate::summary::{Record, Status};

/// The `metric` column of a gate row: the metric, or `expect failed (diverged)`.
pub(super) fn check_label(c: &Check) -> String {
    match c {
        Check::Bound { metric, .. } => metric.clone(),
        Check::Expect { kind, .. } => format!("{EXPECT_PREFIX} ({})", kind.name()),
    }
}

/// `<= t`, `>= t` or `before t s`.
/// How a gate names the scene's `t` after a number: ` s` where the family declares it in
/// seconds (`Figures::t_axis`), else the declared pseudo-time in words (a static scene's
/// load factor, a cyclic scene's protocol increment), never seconds.
pub(super) fn t_unit(c: &crate::case::Case, scene: &str) -> String {
    let family = crate::catalogue::family_of(c);
    let label = c
        .scene(scene)
        .map_or(crate::problem::figures::seconds_label(), |s| {
            (family.figures.t_axis)(s).0
        });
    if label == crate::problem::figures::seconds_label() {
        " s".into()
    } else {
        format!(" ({label})")
    }
}

pub(super) fn threshold_text(c: &Check, unit: &str) -> String {
    match c {
        Check::Bound {
            bound: Bound::Max(t),
            ..
        } => format!("<= {t:e}"),
        Check::Bound {
            bound: Bound::Min(t),
            ..
        } => format!(">= {t:e}"),
        Check::Expect { after, before, .. } => {
            format!(
                "after {}, before {}{unit}",
                time_text(*after),
                time_text(*before)
            )
        }
    }
}

/// A time as written (`20`, `12.5`), in exponent form when that is long.
pub(super) fn time_text(t: f64) -> String {
    let s = format!("{t}");
    if s.len() <= 10 { s } else { format!("{t:.4e}") }
}

/// A bound gate's verdict on a current, applicable record: the run ended `ok` and its
/// metric lies within the bound.
pub(super) fn judge_bound(row: &mut GateRow, r: &Record, metric: &str, bound: Bound) {
    if r.status == Status::Failed {
        row.note = failure_text(r);
        return;
    }
    let x = match metric_value(r, metric) {
        None => {
            row.note = "metric absent from the record (it does not apply to this case)".into();
            return;
        }
        Some(None) => {
            row.note = format!(
                "null: {}",
                r.metric_reasons
                    .get(metric)
                    .map_or("no reason given", String::as_str)
            );
            return;
        }
        Some(Some(x)) => x,
    };
    let pass = match bound {
        Bound::Max(t) => x <= t,
        Bound::Min(t) => x >= t,
    };
    row.ratio = match bound {
        Bound::Max(t) if t > 0.0 => Some(x / t),
        Bound::Min(t) if x > 0.0 => Some(t / x),
        _ => None,
    };
    if pass {
        row.verdict = Verdict::Pass;
    } else {
        row.note = match bound {
            Bound::Max(t) if t > 0.0 => format!("{:.3}x the maximum", x / t),
            Bound::Max(_) => "above the maximum".into(),
            Bound::Min(_) => "below the minimum".into(),
        };
    }
}

/// An expected-failure gate's verdict on a current, applicable record: a pass only for a
/// typed failure of `kind` at `after < t <= before`.
pub(super) fn judge_expect(
    row: &mut GateRow,
    r: &Record,
    kind: FailureKind,
    (after, before): (f64, f64),
    unit: &str,
) {
    let expected = format!(
        "expected {} after {} and before {}{unit}",
        kind.name(),
        time_text(after),
        time_text(before)
    );
    match (&r.status, &r.failure) {
        (Status::Failed, Some(f)) if f.kind == kind && f.t > after && f.t <= before => {
            row.verdict = Verdict::Pass;
        }
        (Status::Failed, Some(f)) if f.kind == kind && f.t <= after => {
            row.note = format!(
                "{} at t = {}, too early (another cause): {expected}",
                kind.name(),
                time_text(f.t)
            );
        }
        (Status::Failed, Some(f)) if f.kind == kind => {
            row.note = format!(
                "{} at t = {}, too late: {expected}",
                kind.name(),
                time_text(f.t)
            );
        }
        (Status::Failed, Some(f)) => {
            row.note = format!(
                "failed with {} at t = {}: {}; {expected}",
                f.kind.name(),
                time_text(f.t),
                f.message
            );
        }
        (Status::Failed, None) => {
            row.note = format!("failed without a typed failure; {expected}");
        }
        _ => row.note = format!("ran to t_end without failing; {expected}"),
    }
}

/// An expected-failure gate's value: the failure's kind and time, or the status.
pub(super) fn outcome_text(r: &Record) -> String {
    match (&r.status, &r.failure) {
        (_, Some(f)) => format!("{} at t = {}", f.kind.name(), time_text(f.t)),
        (Status::Ok, None) => "ok".into(),
        (Status::Failed, None) => "failed".into(),
        (Status::NotApplicable, None) => "n/a".into(),
    }
}
