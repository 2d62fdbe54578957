//! The gate (README.md, "The gate"; the keys in cases/README.md, "`[[gates]]`"): every case's
//! `[[gates]]` threshold evaluated against a summary (and the `stability.json` beside it), plus the
//! comparison with an earlier summary (`regression`), printed as a table with an exit code
//! (`table`). The input files are read by `load`, the gates checked against what exists by
//! `validate`; this file expands and judges them.
//!
//! A gate names a metric, a bound (`max`: the value must be `<=` it; `min`: `>=`) and a
//! `where` whose lists select scenes, parameterizations, integrators, formulations and ladder
//! points (`dt` for fixed-step methods, `tol` for adaptive ones; an absent key means any).
//! The `where` is expanded over the case's scenes x the registered variants that apply to the
//! scene (`registry::scene_na_reason`) x the variant's ladder of the tier being gated (the
//! quick ladder with `--quick`, the full ladder otherwise). Every expanded point must have a
//! record, searched in the summary and then in the stability summary. A point fails when it has
//! no record, when the record is stale (its `inputs_sha256` is not the case's current physics
//! hash, or its `reference_sha256` is not the SHA-256 of the current, loadable reference file),
//! when the run is `n/a` or ended in a typed failure, when the metric is null or absent, or when
//! the value crosses the bound. Wall time is never gated; deterministic work counts
//! (`WORK_METRICS`, read from the record's `stats`) may be.
//!
//! A gate of the other form, `expect = { status = "failed", kind, after, before }`
//! (`Check::Expect`), is for a variant known to fail: it is expanded and matched the same way,
//! and fails for the same missing, stale and `n/a` records, but a point passes only when its
//! run ended in a typed failure of `kind` at `after < t <= before`; a run that ended `ok`, or
//! failed otherwise, earlier (another cause) or later, fails. Its row's value is the outcome as text (`outcome`: `diverged at t = 12`, `ok`).
//!
//! Unusable input is a `GateError` (exit 2), never a failing row: a summary that cannot be read
//! or parsed, an unknown metric name (of a bound gate), a `where` value that names no registered variant or no
//! ladder point, a `where` that expands to nothing in the tier being gated, a gate whose
//! `baseline x margin` is not its bound (relative `BOUND_REL_TOL`), an unreadable baseline.
//! Validation of names, values and bounds covers every gate; the expansion check covers the
//! gates of the tier being evaluated.
//!
//! Limits: a `quick = true` gate is also evaluated by the full gate, so it must name a point
//! present in both ladders (else the full gate reports its `where` as matching nothing).
//! Stability records are matched by ladder point like the summary's; a study whose runs lie
//! off the ladders needs its own expansion when its metrics are gated.
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::case::gate::Check;
use crate::case::{self, Case, Gate};
use crate::problem::{Problem, Variant};
use crate::summary::{Record, Status, Summary};
use judge::{check_label, judge_bound, judge_expect, outcome_text, t_unit, threshold_text};

mod judge;
pub mod load;
pub mod markdown;
pub mod regression;
pub mod table;
pub mod validate;

#[cfg(test)]
mod fixture;

pub use load::{load_summary, stability_beside, stability_paired};
pub use regression::{DEFAULT_FACTOR, compare_baseline, is_baseline_row, update_baseline};
pub use table::{exit_code, print_table, print_verdict, skipped_by_reason, verdict_line};
pub use validate::known_metrics;
use validate::{check_threshold, check_where_values, describe, keep};

/// Outcome of one gate row.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    Pass,
    Fail,
    /// Not evaluated, and why (`note`): outside the run's selection, or a stability gate
    /// without `stability.json` (a failure under `--require-stability`).
    Skip,
}

/// One evaluated row: a gated (or baseline-compared) record and metric.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GateRow {
    #[serde(flatten)]
    pub key: crate::summary::RunKey,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub dt: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub tol: Option<f64>,
    /// The metric (or a compared work counter, `integrate::Counter::compared`, for baseline rows; `expect failed (kind)`
    /// for an expected-failure gate, `check_label`).
    pub metric: String,
    /// The value found (None: no record, or a null metric).
    pub value: Option<f64>,
    /// The value as text where it is no number: an expected-failure gate's outcome,
    /// `diverged at t = 12` or `ok` (None: no record, or a metric row).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub outcome: Option<String>,
    /// The threshold as written, e.g. `<= 3.0e-9`, `<= 3 x baseline 1.2e-8` or `before 20 s`.
    pub threshold: String,
    pub verdict: Verdict,
    /// Why it failed (stale reference, no record, null metric, regression ...), or empty.
    pub note: String,
    /// How far the value lies from the number its threshold names, as a factor: value /
    /// bound for an upper bound (bound / value for a lower one), value / baseline for a
    /// baseline comparison; above 1 past it. None where there is no such number (no record,
    /// an expected failure, a stale scene).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub ratio: Option<f64>,
}

/// The deterministic work counters of a record (`stats`) a gate may name: every counter of
/// `integrate::COUNTERS`.
pub const WORK_METRICS: &[&str] = &crate::integrate::COUNTER_NAMES;

/// The metric-name lists a gate may name besides the names found in the records and every
/// model family's metrics (`problem::Family::metrics`); a new study is one more entry.
pub const KNOWN_METRIC_LISTS: &[&[&str]] = &[WORK_METRICS, crate::stability::steps::METRICS];

/// Whether a metric belongs to a variant as a whole (the stability search's largest steps),
/// not to a ladder point: its gates expand over scenes x variants only, and match the
/// records without `dt`/`tol`.
pub fn per_variant(metric: &str) -> bool {
    crate::stability::steps::METRICS.contains(&metric)
}

/// Relative slack between a gate's bound and its `baseline x margin`.
pub const BOUND_REL_TOL: f64 = 1e-9;

/// Options of `mbdbench gate`.
#[derive(Debug, Clone, PartialEq)]
pub struct GateOptions {
    /// Evaluate only `quick = true` gates, on the quick ladders.
    pub quick: bool,
    /// An earlier summary to compare with (`--baseline FILE`).
    pub baseline: Option<PathBuf>,
    /// How much worse an error metric may become before it is a regression (`--factor`).
    pub factor: f64,
    /// The references folder (`references/`).
    pub references: PathBuf,
    /// Only these cases and scenes (`--case`, `--scene`; empty: all).
    pub cases: Vec<String>,
    pub scenes: Vec<String>,
    /// A gate that needs `stability.json` fails when it is absent (`--require-stability`);
    /// otherwise it is skipped.
    pub require_stability: bool,
    /// The catalogue the summary was made with: its families (with the methods it registered)
    /// name what a gate may select.
    pub catalogue: crate::catalogue::Catalogue,
}

impl GateOptions {
    /// The full gate, no baseline, the default factor.
    pub fn new(references: PathBuf) -> Self {
        GateOptions {
            quick: false,
            baseline: None,
            factor: DEFAULT_FACTOR,
            references,
            cases: vec![],
            scenes: vec![],
            require_stability: false,
            catalogue: crate::catalogue::Catalogue::builtin(),
        }
    }
}

/// Why a gate row needing `stability.json` is not evaluated without it.
pub const NO_STABILITY: &str = "not run: no stability.json beside the summary";

/// Input the gate cannot use (exit 2). Every message names the file and the key or value.
#[derive(Debug, thiserror::Error)]
pub enum GateError {
    /// A summary, stability summary or baseline that is missing, corrupt or truncated.
    #[error("{path}: unusable {what}: {message}")]
    Unreadable {
        what: &'static str,
        path: String,
        message: String,
    },
    /// A gate names a metric no case reports.
    #[error("{file}: gates[{index}].metric: unknown metric \"{metric}\" (known: {known})")]
    UnknownMetric {
        file: String,
        index: usize,
        metric: String,
        known: String,
    },
    /// A `where` (or one of its values) that selects no registered variant or ladder point.
    #[error("{file}: gates[{index}].{key}: {message}")]
    Where {
        file: String,
        index: usize,
        key: String,
        message: String,
    },
    /// A bound inconsistent with its `baseline` and `margin`.
    #[error("{file}: gates[{index}].{key}: {message}")]
    Threshold {
        file: String,
        index: usize,
        key: String,
        message: String,
    },
    /// A scene that cannot be planned.
    #[error(transparent)]
    Case(#[from] case::CaseError),
    /// `--update-baseline` could not write.
    #[error("{path}: cannot write the baseline: {message}")]
    Write { path: String, message: String },
    /// The gates' tier is not the summary's (`check_tier`).
    #[error("{path}: {message}")]
    Tier { path: String, message: String },
    /// The baseline has no run in common with the summary (another tier, other cases).
    #[error(
        "{path}: the baseline shares no run (case, scene, variant, dt|tol) with the summary: nothing to compare (another tier?)"
    )]
    Disjoint { path: String },
}

pub(super) fn all_records<'a>(
    summary: &'a Summary,
    stability: Option<&'a Summary>,
) -> impl Iterator<Item = &'a Record> {
    summary
        .records
        .iter()
        .chain(stability.into_iter().flat_map(|s| s.records.iter()))
}

pub(crate) use crate::case::same_value;

/// A record's value of `metric`: `None` absent, `Some(None)` null. Work counters come from
/// `stats`.
pub fn metric_value(r: &Record, metric: &str) -> Option<Option<f64>> {
    if let Some(v) = r.metrics.get(metric) {
        return Some(*v);
    }
    r.stats.count(metric).map(|n| Some(n as f64))
}

/// The start of an expected-failure gate's `metric` column (`expect_label`).
pub const EXPECT_PREFIX: &str = "expect failed";

/// Whether a row comes from an expected-failure gate (`Check::Expect`).
pub fn is_expect_row(r: &GateRow) -> bool {
    r.metric.starts_with(EXPECT_PREFIX)
}

/// A failure's one-line description.
pub(crate) fn failure_text(r: &Record) -> String {
    match &r.failure {
        Some(f) => {
            let kind = serde_json::to_value(f.kind)
                .ok()
                .and_then(|v| v.as_str().map(str::to_string))
                .unwrap_or_else(|| format!("{:?}", f.kind));
            format!("run failed: {kind} at t = {}: {}", f.t, f.message)
        }
        None => "run failed".into(),
    }
}

fn short(hash: &str) -> &str {
    &hash[..hash.len().min(12)]
}

// ---------------------------------------------------------------------------------------
// ---------------------------------------------------------------------------------------
// Expansion and evaluation

/// One gated run: a scene, a registered variant and a ladder value (None for a per-variant
/// metric).
struct Point<'p> {
    problem: &'p dyn Problem,
    variant: &'static Variant,
    value: Option<f64>,
}

fn expand<'p>(
    c: &Case,
    index: usize,
    g: &Gate,
    problems: &'p [Box<dyn Problem>],
    quick: bool,
) -> Result<Vec<Point<'p>>, GateError> {
    let f = &g.filter;
    let mut points = vec![];
    let mut matching = 0usize;
    let mut ladders: BTreeSet<String> = BTreeSet::new();
    let mut na: BTreeSet<String> = BTreeSet::new();
    for problem in problems.iter().filter(|p| keep(&f.scene, p.scene())) {
        let problem = &**problem;
        for v in problem.family().variants() {
            let adaptive = v.info.adaptive;
            if !(keep(&f.param, v.param)
                && keep(&f.integrator, v.integrator)
                && keep(&f.formulation, v.formulation))
                || (adaptive && !f.dt.is_empty())
                || (!adaptive && !f.tol.is_empty())
            {
                continue;
            }
            if let Some(why) = problem.na_reason(v) {
                na.insert(format!(
                    "{}/{}/{} is n/a on {}: {why}",
                    v.param,
                    v.integrator,
                    v.formulation,
                    problem.scene()
                ));
                continue;
            }
            matching += 1;
            if g.check.metric().is_some_and(per_variant) {
                points.push(Point {
                    problem,
                    variant: v,
                    value: None,
                });
                continue;
            }
            let ladder = problem.ladder(quick, &v.info);
            let wanted = if adaptive { &f.tol } else { &f.dt };
            ladders.extend(ladder.iter().map(|x| format!("{x:e}")));
            for &x in ladder {
                if wanted.is_empty() || wanted.iter().any(|w| same_value(*w, x)) {
                    points.push(Point {
                        problem,
                        variant: v,
                        value: Some(x),
                    });
                }
            }
        }
    }
    if points.is_empty() {
        let tier = if quick { "quick" } else { "full" };
        let message = if matching == 0 {
            let mut m = format!("{} matches no registered variant", describe(f));
            if !na.is_empty() {
                m.push_str(&format!(
                    " that applies ({})",
                    na.into_iter().collect::<Vec<_>>().join("; ")
                ));
            }
            m
        } else {
            format!(
                "{} matches {matching} registered variant(s) but no point of their {tier} \
                 ladders (values there: {})",
                describe(f),
                if ladders.is_empty() {
                    "none".into()
                } else {
                    ladders.into_iter().collect::<Vec<_>>().join(", ")
                }
            )
        };
        return Err(GateError::Where {
            file: c.file.clone(),
            index,
            key: "where".into(),
            message,
        });
    }
    Ok(points)
}

/// Records of the summary, then of the stability summary, by (case, scene, variant).
/// A variant's records (case, scene, param, integrator, formulation), each with whether it
/// comes from the stability summary.
type VariantRecords<'a> =
    BTreeMap<(&'a str, &'a str, &'a str, &'a str, &'a str), Vec<(&'a Record, bool)>>;

struct RecordIndex<'a> {
    map: VariantRecords<'a>,
}

impl<'a> RecordIndex<'a> {
    fn new(summary: &'a Summary, stability: Option<&'a Summary>) -> Self {
        let mut map: BTreeMap<_, Vec<(&Record, bool)>> = BTreeMap::new();
        let tagged = summary.records.iter().map(|r| (r, false)).chain(
            stability
                .into_iter()
                .flat_map(|s| s.records.iter().map(|r| (r, true))),
        );
        for (r, from_stability) in tagged {
            map.entry((
                r.key.case.as_str(),
                r.key.scene.as_str(),
                r.key.param.as_str(),
                r.key.integrator.as_str(),
                r.key.formulation.as_str(),
            ))
            .or_default()
            .push((r, from_stability));
        }
        RecordIndex { map }
    }

    /// The record of a point; among several, the first that carries `metric`. A stability
    /// record is a candidate only when it carries the metric: the study's other records at a
    /// step or tolerance (a long-horizon run, a sensitivity run) are not the catalogue's
    /// ladder runs, and must not stand in for a missing one. Without a metric (an
    /// expected-failure gate) the summary's first record of the point.
    fn find(&self, case: &str, p: &Point, metric: Option<&str>) -> Option<&'a Record> {
        let carries = |r: &Record| metric.is_some_and(|m| r.metrics.contains_key(m));
        let v = p.variant;
        let list = self.map.get(&(
            case,
            p.problem.scene(),
            v.param,
            v.integrator,
            v.formulation,
        ))?;
        let at = |(r, from_stability): &&(&Record, bool)| {
            let x = if v.info.adaptive { r.tol } else { r.dt };
            let here = match p.value {
                Some(want) => x.is_some_and(|x| same_value(x, want)),
                None => r.dt.is_none() && r.tol.is_none(),
            };
            here && (!from_stability || carries(r))
        };
        let mut candidates = list.iter().filter(at).map(|(r, _)| *r);
        let first = candidates.clone().next();
        candidates.find(|r| carries(r)).or(first)
    }
}

/// The SHA-256 of each scene's current reference file, or why it cannot be used (loaded
/// once per scene, by a copy of the scene's problem).
struct ReferenceHashes<'r> {
    root: &'r Path,
    cache: BTreeMap<(String, String), Result<String, String>>,
}

impl ReferenceHashes<'_> {
    fn get(&mut self, c: &Case, problem: &dyn Problem) -> &Result<String, String> {
        let root = self.root;
        self.cache
            .entry((problem.case().to_string(), problem.scene().to_string()))
            .or_insert_with(|| {
                let scene = c
                    .scene(problem.scene())
                    .ok_or_else(|| format!("no scene {}", problem.scene()))?;
                let mut p = (problem.family().compile)(c, scene).map_err(|e| e.to_string())?;
                p.attach_reference(root)?;
                p.reference_sha256()
                    .map(str::to_string)
                    .ok_or_else(|| "no reference".to_string())
            })
    }
}

/// Whether `summary` is a quick-tier run: it has ladder records and every one of them lies on
/// its scene's quick ladder (a full run also has the points off it). The report evaluates the
/// quick gates for such a summary: the full gates would ask for points it does not have.
pub fn is_quick_summary(cases: &[Case], summary: &Summary) -> bool {
    let mut any = false;
    for r in &summary.records {
        let Some(value) = r.dt.or(r.tol) else {
            continue;
        };
        let Some(s) = cases
            .iter()
            .find(|c| c.name == r.key.case)
            .and_then(|c| c.scene(&r.key.scene))
        else {
            return false;
        };
        let q = &s.quick;
        let on_quick = [&q.order1, &q.order2_4, &q.order6]
            .iter()
            .any(|l| l.iter().any(|f| f.dt == value))
            || q.tol.contains(&value);
        if !on_quick {
            return false;
        }
        any = true;
    }
    any
}

/// The tier of a summary: its recorded selection's, else what its ladder points show
/// (summaries written before `selection`).
pub fn summary_tier(cases: &[Case], summary: &Summary) -> crate::selection::Tier {
    match &summary.selection {
        Some(s) => s.tier,
        None => crate::selection::Tier::of(is_quick_summary(cases, summary)),
    }
}

/// Bad input when the gates' tier is not the summary's: the other tier's gates name ladder
/// points the summary does not have (the quick order-1 steps are not on the full ladder).
pub fn check_tier(summary: &Summary, path: &Path, quick: bool) -> Result<(), GateError> {
    let Some(sel) = &summary.selection else {
        return Ok(());
    };
    let want = crate::selection::Tier::of(quick);
    if sel.tier == want {
        return Ok(());
    }
    Err(GateError::Tier {
        path: path.display().to_string(),
        message: match sel.tier {
            crate::selection::Tier::Quick => {
                "the summary is a quick-tier run (`selection.tier`): gate it with --quick".into()
            }
            crate::selection::Tier::Full => "the summary is a full-tier run (`selection.tier`), \
                 whose ladders do not hold every quick-ladder point: gate it without --quick"
                .into(),
        },
    })
}

/// Evaluates the gates of `cases` (only `quick = true` ones with `opts.quick`) against the
/// records of `summary` and `stability`, then, with `opts.baseline`, compares `summary` with
/// the baseline. Rows come in case, gate, scene, registry and ladder order, baseline rows
/// last.
pub fn evaluate(
    cases: &[Case],
    summary: &Summary,
    stability: Option<&Summary>,
    opts: &GateOptions,
) -> Result<Vec<GateRow>, GateError> {
    let known = known_metrics(summary, stability);
    for c in cases {
        for (i, g) in c.gates.iter().enumerate() {
            if let Some(metric) = g.check.metric()
                && !known.contains(metric)
            {
                return Err(GateError::UnknownMetric {
                    file: c.file.clone(),
                    index: i,
                    metric: metric.to_string(),
                    known: known.iter().cloned().collect::<Vec<_>>().join(", "),
                });
            }
            check_threshold(c, i, g)?;
            check_where_values(c, i, g, &opts.catalogue)?;
        }
    }
    let index = RecordIndex::new(summary, stability);
    let mut refs = ReferenceHashes {
        root: &opts.references,
        cache: BTreeMap::new(),
    };
    let mut rows = vec![];
    let wanted = |list: &[String], name: &str| list.is_empty() || list.iter().any(|x| x == name);
    for c in cases.iter().filter(|c| wanted(&opts.cases, &c.name)) {
        let gated: Vec<(usize, &Gate)> = c
            .gates
            .iter()
            .enumerate()
            .filter(|(_, g)| g.quick || !opts.quick)
            .collect();
        if gated.is_empty() {
            continue;
        }
        let problems = c
            .scenes
            .iter()
            .map(|s| opts.catalogue.compile(c, s))
            .collect::<Result<Vec<_>, _>>()?;
        for (i, g) in gated {
            for p in expand(c, i, g, &problems, opts.quick)? {
                if !wanted(&opts.scenes, p.problem.scene()) {
                    continue;
                }
                if let Some(why) = skip_reason(&p, g, summary, stability) {
                    let mut row = judge(c, g, &p, None, &mut refs, false);
                    row.note = why;
                    if !(opts.require_stability && row.note == NO_STABILITY) {
                        row.verdict = Verdict::Skip;
                    }
                    rows.push(row);
                    continue;
                }
                let rec = index.find(&c.name, &p, g.check.metric());
                let mut row = judge(c, g, &p, rec, &mut refs, stability.is_some());
                if rec.is_none() && !summary.records.is_empty() {
                    row.note.push_str(&tier_hint(cases, summary, opts.quick));
                }
                rows.push(row);
            }
        }
    }
    if let Some(path) = &opts.baseline {
        let base = regression::load_baseline(path)?;
        // `--case` and `--scene` filter the comparison as they filter the gates: every row
        // of it is keyed by one case and scene.
        rows.extend(
            compare_baseline(cases, summary, &base, path, &opts.references, opts.factor)?
                .into_iter()
                .filter(|r| wanted(&opts.cases, &r.key.case) && wanted(&opts.scenes, &r.key.scene)),
        );
    }
    Ok(rows)
}

/// Why a gated point is not evaluated: it lies outside what the run (or the stability study)
/// was asked to compute, or it needs `stability.json` and there is none.
fn skip_reason(
    p: &Point,
    g: &Gate,
    summary: &Summary,
    stability: Option<&Summary>,
) -> Option<String> {
    let v = p.variant;
    let key = crate::summary::RunKey::new(
        p.problem.case(),
        p.problem.scene(),
        v.param,
        v.integrator,
        v.formulation,
    );
    let outside = |s: &Summary| {
        s.selection
            .as_ref()
            .filter(|sel| !sel.admits(&key))
            .cloned()
    };
    if !g.check.metric().is_some_and(per_variant) {
        return outside(summary)
            .map(|sel| format!("not run: outside the run's selection ({})", sel.flags()));
    }
    match stability {
        None => Some(NO_STABILITY.into()),
        Some(st) => outside(st).map(|sel| {
            format!(
                "not run: outside the stability study's selection ({})",
                sel.flags()
            )
        }),
    }
}

/// Why a gated point may be missing when the summary is of the other tier than the gates
/// (quick gates ask for quick-ladder points, full gates for the full ladders), or "".
fn tier_hint(cases: &[Case], summary: &Summary, quick: bool) -> String {
    match (quick, is_quick_summary(cases, summary)) {
        (true, false) => "; the summary is not a quick-tier run (it has points off the quick \
                          ladders): gate it without --quick"
            .into(),
        (false, true) => "; the summary is a quick-tier run: gate it with --quick".into(),
        _ => String::new(),
    }
}

/// The row of one gated point.
fn judge(
    c: &Case,
    g: &Gate,
    p: &Point,
    rec: Option<&Record>,
    refs: &mut ReferenceHashes,
    with_stability: bool,
) -> GateRow {
    let v = p.variant;
    let mut row = GateRow {
        key: crate::summary::RunKey::new(
            p.problem.case(),
            p.problem.scene(),
            v.param,
            v.integrator,
            v.formulation,
        ),
        dt: p.value.filter(|_| !v.info.adaptive),
        tol: p.value.filter(|_| v.info.adaptive),
        metric: check_label(&g.check),
        value: None,
        outcome: None,
        threshold: threshold_text(&g.check, &t_unit(c, p.problem.scene())),
        verdict: Verdict::Fail,
        note: String::new(),
        ratio: None,
    };
    let Some(r) = rec else {
        row.note = format!(
            "no record in the summary{}",
            if with_stability {
                " or stability.json"
            } else {
                ""
            }
        );
        return row;
    };
    match &g.check {
        Check::Bound { metric, .. } => row.value = metric_value(r, metric).flatten(),
        Check::Expect { .. } => row.outcome = Some(outcome_text(r)),
    }
    if let Some(why) = unusable(c, p, r, refs) {
        row.note = why;
        return row;
    }
    match &g.check {
        Check::Bound { metric, bound } => judge_bound(&mut row, r, metric, *bound),
        Check::Expect {
            kind,
            after,
            before,
        } => judge_expect(
            &mut row,
            r,
            *kind,
            (*after, *before),
            &t_unit(c, p.problem.scene()),
        ),
    }
    row
}

/// Why a point's record cannot be judged whatever the gate checks: it is stale (other
/// physics, another reference file) or `n/a`.
fn unusable(c: &Case, p: &Point, r: &Record, refs: &mut ReferenceHashes) -> Option<String> {
    if r.inputs_sha256 != p.problem.inputs_sha256() {
        return Some(format!(
            "stale: the record's inputs_sha256 {} is not the case's current {} (rerun)",
            short(&r.inputs_sha256),
            short(p.problem.inputs_sha256())
        ));
    }
    // A per-variant study record judged against an on-the-fly reference carries no stored
    // reference hash: only its physics hash can be stale.
    let no_stored_reference = p.value.is_none() && r.reference_sha256.is_none();
    match refs.get(c, p.problem) {
        _ if no_stored_reference => {}
        Err(e) => return Some(format!("stale: {e}")),
        Ok(sha) if r.reference_sha256.as_deref() != Some(sha.as_str()) => {
            return Some(format!(
                "stale: the record's reference_sha256 {} is not the current reference file's {} \
                 (rerun)",
                r.reference_sha256.as_deref().map_or("null", short),
                short(sha)
            ));
        }
        Ok(_) => {}
    }
    (r.status == Status::NotApplicable)
        .then(|| format!("n/a: {}", r.reason.as_deref().unwrap_or("no reason given")))
}

#[cfg(test)]
mod tests;
