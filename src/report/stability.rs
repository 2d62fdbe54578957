//! The stability part of a case's section (issue 4), from `stability.json` (the summary's
//! schema, written by `mbdbench stability` beside `summary.json`) and its long-horizon series
//! files. A record is read by the metrics it carries, so later parts of the study need no
//! change here to be shown:
//!
//! - step search (`largest_stable_dt` or `largest_stable_tol`): one table per scene (the case
//!   file's scenes first, then generated ones such as the stiffness ladder's `two_angles_k1e2`,
//!   `two_angles_k1e2_T10`, folded), each variant's largest stable and accurate step, what
//!   limits each (shortened; the full `metric_reasons` text on hover and in the markdown), and
//!   `t_h`. A step that passed at the cap (`t_h / 20`) is written `(cap)` and "bounded up to the
//!   cap": a lower bound, not a limit;
//! - stiffness ladder (fits whose metric ends in `_vs_stiffness`): log-log step against the
//!   stiffness factor, one line per variant through the fit's measured points, its slope in the
//!   legend; capped and null points are not measurements and are listed in the caption;
//! - long horizon (`energy_growth_exponent`): energy and momentum error against t (log-log,
//!   from `series/long_horizon/<case>/<scene>/<id>.json` under the stability.json folder),
//!   the exponent in the legend, and a table of exponents and final errors;
//! - singularity ladder (records with `approach_distance`): per run setting (integrator, step
//!   or tolerance) the rotation error, the minimum conditioning and, for adaptive settings, the
//!   RHS evaluations against `d`, log-log, one line per chart, failures in the red band and
//!   named in the caption; a sentence per setting on where each Euler chart's error peaks;
//! - sensitivity (`sensitivity_growth_max`): the growth `G(t)` of each scene from its series
//!   file, the predictable horizon in the legend, and a sentence with each scene's growth;
//! - everything not drawn (the singularity and sensitivity numbers too, `n/a` records, other
//!   fits): generic tables of their metrics, so nothing in the file is dropped.
//!
//! A missing series file gives "no data" in its plot, named in the caption; nothing here fails.
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use super::Figure;
use super::axes::Scale;
use super::chart::{Legend, Line, Plot};
use super::data::{VariantKey, num, time};
use super::tables::{Cell, Table, kind_name};
use crate::case::Case;
use crate::summary::{FitRecord, Record, Status, Summary};

/// A stability summary and the folder its `series` paths are relative to.
#[derive(Debug, Clone, Copy)]
pub struct Source<'a> {
    pub summary: &'a Summary,
    pub dir: &'a Path,
}

/// One step-search table and whether it is shown unfolded.
#[derive(Debug, Clone)]
pub struct StepTable {
    pub table: Table,
    /// A scene of the case file (unfolded); generated scenes are folded.
    pub open: bool,
}

/// The stability part of one case.
#[derive(Debug, Clone)]
pub struct StabilitySection {
    /// Commit and date of stability.json.
    pub env_line: String,
    /// Sentences on how to read the part and what it shows.
    pub text: Vec<String>,
    pub steps: Vec<StepTable>,
    pub ladder: Vec<Figure>,
    pub long_horizon: Vec<Figure>,
    pub long_table: Option<Table>,
    /// Singularity-ladder plots (error, work, conditioning against the approach distance).
    pub singularity: Vec<Figure>,
    /// The growth of an initial perturbation per scene.
    pub sensitivity: Vec<Figure>,
    /// Records of other kinds.
    pub other: Option<Table>,
    /// Fits of other kinds.
    pub other_fits: Option<Table>,
}

impl StabilitySection {
    /// Every plot of the part.
    pub fn figures(&self) -> impl Iterator<Item = &Figure> {
        self.ladder
            .iter()
            .chain(&self.long_horizon)
            .chain(&self.singularity)
            .chain(&self.sensitivity)
    }

    /// Every table of the part, in page order.
    pub fn tables(&self) -> Vec<&Table> {
        let mut out: Vec<&Table> = self.steps.iter().map(|s| &s.table).collect();
        out.extend(self.long_table.iter());
        out.extend(self.other.iter());
        out.extend(self.other_fits.iter());
        out
    }
}

/// The explicit-Euler sentence (issue 4).
pub const EULER_NOTE: &str = "Explicit Euler has no stability interval on the imaginary axis \
    (|1 + i w h| > 1 for every h > 0), so on these undamped oscillations it always grows: its \
    stable step comes from the energy growth bound alone (relative energy error < 1 over t_h), \
    not from an eigenvalue limit.";

/// Reads `stability.json` beside a summary: `(None, None)` when absent, `(None, Some(warning))`
/// when present but unusable (the report goes on without it).
pub fn load_beside(summary_path: &Path) -> (Option<Summary>, Option<String>) {
    match crate::gate::stability_beside(summary_path) {
        Ok(s) => (s, None),
        Err(e) => (
            None,
            Some(format!(
                "warning: {e}; the report is written without the stability study"
            )),
        ),
    }
}

/// The cases a stability summary speaks about, in order of first appearance.
pub fn case_names(s: &Summary) -> Vec<String> {
    let mut out: Vec<String> = vec![];
    for c in s
        .records
        .iter()
        .map(|r| &r.case)
        .chain(s.fits.iter().map(|f| &f.case))
    {
        if !out.contains(c) {
            out.push(c.clone());
        }
    }
    out
}

fn key_of_fit(f: &FitRecord) -> VariantKey {
    VariantKey {
        param: f.param.clone(),
        integrator: f.integrator.clone(),
        formulation: f.formulation.clone(),
    }
}

/// The stable-step metric of a step-search record.
fn stable_metric(r: &Record) -> Option<&'static str> {
    ["largest_stable_dt", "largest_stable_tol"]
        .into_iter()
        .find(|m| r.metrics.contains_key(*m))
}

fn is_long(r: &Record) -> bool {
    r.metrics.contains_key("energy_growth_exponent")
}

fn is_ladder_fit(f: &FitRecord) -> bool {
    f.metric.ends_with("_vs_stiffness")
}

fn is_growth_fit(f: &FitRecord) -> bool {
    f.metric == "energy_growth" || f.metric == "momentum_growth"
}

fn capped(reason: &str) -> bool {
    reason.starts_with("bounded up to the cap")
}

/// A `metric_reasons` text in a few words: the failure kind (or which bound) and its time.
pub fn short_reason(reason: &str) -> String {
    if reason.is_empty() {
        return "-".into();
    }
    if capped(reason) {
        return "bounded up to the cap".into();
    }
    if reason.starts_with("search not completed") {
        return "search not completed".into();
    }
    let (prefix, rest) = if let Some(r) = reason.strip_prefix("limited by ") {
        ("", r)
    } else if let Some(r) = reason.strip_prefix("nothing passed: ") {
        ("nothing passed: ", r)
    } else if reason == "nothing passed" {
        return "nothing passed".into();
    } else {
        return abbreviate(reason, 48);
    };
    // `<kind> at t = <t> with <probe>: <message>`
    let kind = rest.split_whitespace().next().unwrap_or("");
    let t = rest
        .split_once(" at t = ")
        .and_then(|(_, x)| x.split_whitespace().next())
        .and_then(|x| x.parse::<f64>().ok());
    let message = rest.split_once(": ").map(|(_, m)| m).unwrap_or("");
    let what = if kind == "bound_exceeded" {
        if message.starts_with("energy error") {
            "energy error >= 1".to_string()
        } else if message.starts_with("rotation error") {
            match message.split_once(">= ") {
                Some((_, b)) => format!("rotation error >= {b}"),
                None => "rotation error bound".into(),
            }
        } else {
            abbreviate(message, 32)
        }
    } else if kind.is_empty() {
        return abbreviate(reason, 48);
    } else {
        kind.to_string()
    };
    match t {
        Some(t) => format!("{prefix}{what} at t = {} s", time(t)),
        None => format!("{prefix}{what}"),
    }
}

/// `x` with `n` decimals, without a minus sign on a value that rounds to zero.
fn decimals(x: f64, n: usize) -> String {
    let s = format!("{x:.n$}");
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_string()
    } else {
        s
    }
}

fn abbreviate(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        let cut: String = s.chars().take(n - 3).collect();
        format!("{}...", cut.trim_end())
    }
}

/// `dt 1.2e-3`, `tol 1e-6`, `dt 5e-2 (cap)` or `none`.
fn step_cell(value: Option<f64>, adaptive: bool, reason: &str) -> Cell {
    let unit = if adaptive { "tol" } else { "dt" };
    match value {
        Some(v) if capped(reason) => Cell::plain(format!("{unit} {} (cap)", num(v))),
        Some(v) => Cell::plain(format!("{unit} {}", num(v))),
        None => Cell::plain("none"),
    }
}

fn metric_text(r: &Record, m: &str) -> Cell {
    match r.metrics.get(m) {
        Some(Some(x)) => Cell::plain(num(*x)),
        Some(None) => match r.metric_reasons.get(m) {
            Some(why) => Cell::abridged("null", format!("null: {why}")),
            None => Cell::plain("null"),
        },
        None => Cell::plain("-"),
    }
}

fn status_cell(r: &Record) -> Cell {
    match (&r.status, &r.failure) {
        (Status::Ok, _) => Cell::plain("ok"),
        (Status::Failed, Some(f)) => Cell::abridged(
            format!("failed: {} at t = {}", kind_name(f.kind), time(f.t)),
            format!(
                "failed: {} at t = {}: {}",
                kind_name(f.kind),
                time(f.t),
                f.message
            ),
        ),
        (Status::Failed, None) => Cell::plain("failed"),
        (Status::NotApplicable, _) => Cell::abridged(
            "n/a",
            format!("n/a: {}", r.reason.as_deref().unwrap_or("no reason given")),
        ),
    }
}

fn variant_cells(k: &VariantKey) -> [Cell; 3] {
    [
        Cell::plain(&k.param),
        Cell::plain(&k.integrator),
        Cell::plain(&k.formulation),
    ]
}

/// Scenes in the case file's order, then the others (generated ones: periods before the
/// fixed-horizon `_T10` variants, then by name).
fn ordered_scenes<'a>(names: impl Iterator<Item = &'a str>, case: Option<&Case>) -> Vec<String> {
    let set: BTreeSet<&str> = names.collect();
    let mut out: Vec<String> = case
        .map(|c| {
            c.scenes
                .iter()
                .map(|s| s.name.as_str())
                .filter(|s| set.contains(s))
                .map(String::from)
                .collect()
        })
        .unwrap_or_default();
    let mut rest: Vec<&str> = set
        .iter()
        .copied()
        .filter(|s| !out.iter().any(|o| o == s))
        .collect();
    rest.sort_by_key(|s| (s.ends_with("_T10"), s.len(), *s));
    out.extend(rest.into_iter().map(String::from));
    out
}

fn in_case_file(case: Option<&Case>, scene: &str) -> bool {
    case.is_some_and(|c| c.scenes.iter().any(|s| s.name == scene))
}

/// The step-search table of one scene.
fn step_table(case: &str, scene: &str, records: &[&Record]) -> Table {
    let mut rows = vec![];
    let mut rs: Vec<&Record> = records.to_vec();
    rs.sort_by_key(|r| VariantKey::of(r));
    let mut horizons: Vec<f64> = vec![];
    for r in rs {
        let Some(sm) = stable_metric(r) else { continue };
        let am = sm.replace("stable", "accurate");
        let adaptive = sm.ends_with("_tol");
        let mut row: Vec<Cell> = variant_cells(&VariantKey::of(r)).to_vec();
        for m in [sm, am.as_str()] {
            let why = r.metric_reasons.get(m).map(String::as_str).unwrap_or("");
            row.push(step_cell(
                r.metrics.get(m).copied().flatten(),
                adaptive,
                why,
            ));
            row.push(Cell::abridged(short_reason(why), why));
        }
        let th = r.metrics.get("stability_horizon").copied().flatten();
        if let Some(h) = th
            && !horizons.iter().any(|x| (x - h).abs() <= 1e-12 * h.abs())
        {
            horizons.push(h);
        }
        row.push(Cell::plain(th.map(time).unwrap_or_else(|| "-".into())));
        rows.push(row);
    }
    let capped_n = rows.iter().filter(|r| r[3].text.ends_with("(cap)")).count();
    let horizon = match horizons.as_slice() {
        [h] => format!("t_h = {} s", time(*h)),
        _ => "t_h per row".to_string(),
    };
    Table {
        kind: "stability-steps",
        title: format!("{case} / {scene}: largest stable and accurate step"),
        note: format!(
            "{horizon}; {} variant{}, {capped_n} stable up to the cap (t_h / 20).",
            rows.len(),
            if rows.len() == 1 { "" } else { "s" }
        ),
        header: [
            "param",
            "integrator",
            "formulation",
            "largest stable dt / tol",
            "what limits it",
            "largest accurate dt / tol",
            "what limits it",
            "t_h (s)",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    }
}

/// The record scenes of a ladder fit scene: `two_angles_stiffness[_T10]` ->
/// `two_angles_k1e<j>[_T10]` with their factors `10^j`.
fn ladder_records<'a>(fit_scene: &str, records: &[&'a Record]) -> Vec<(f64, &'a Record)> {
    let Some((base, suffix)) = fit_scene.split_once("_stiffness") else {
        return vec![];
    };
    let head = format!("{base}_k1e");
    records
        .iter()
        .filter_map(|r| {
            let rest = r.scene.strip_prefix(&head)?.strip_suffix(suffix)?;
            let j: i32 = rest.parse().ok()?;
            Some((10f64.powi(j), *r))
        })
        .collect()
}

/// The stiffness-ladder plots of a case: one per fit scene and metric.
fn ladder_plots(case: &str, fits: &[&FitRecord], records: &[&Record], footer: &str) -> Vec<Plot> {
    let mut groups: BTreeMap<(bool, String, usize, String), Vec<&FitRecord>> = BTreeMap::new();
    for f in fits.iter().filter(|f| is_ladder_fit(f)) {
        let base = f.metric.trim_end_matches("_vs_stiffness").to_string();
        let accurate = usize::from(base.contains("accurate"));
        groups
            .entry((f.scene.ends_with("_T10"), f.scene.clone(), accurate, base))
            .or_default()
            .push(f);
    }
    let mut out = vec![];
    for ((fixed, scene, _, metric), mut fs) in groups {
        fs.sort_by_key(|f| key_of_fit(f));
        let rs = ladder_records(&scene, records);
        let mut lines = vec![];
        let mut unmeasured: Vec<String> = vec![];
        for f in &fs {
            let key = key_of_fit(f);
            let slope = match f.order {
                Some(p) => format!("slope {}", decimals(p, 2)),
                None => "slope - (too few points)".into(),
            };
            // Points the fit left out: capped (a lower bound) or null (nothing passed).
            let mut skipped: BTreeMap<String, Vec<String>> = BTreeMap::new();
            let mut mine: Vec<(f64, &Record)> = rs
                .iter()
                .filter(|(_, r)| VariantKey::of(r) == key)
                .copied()
                .collect();
            mine.sort_by(|a, b| a.0.total_cmp(&b.0));
            for (k, r) in mine {
                let why = r
                    .metric_reasons
                    .get(&metric)
                    .map(String::as_str)
                    .unwrap_or("");
                let what = match r.metrics.get(&metric).copied().flatten() {
                    Some(_) if capped(why) => "bounded up to the cap".to_string(),
                    Some(_) => continue,
                    None => short_reason(why),
                };
                skipped.entry(what).or_default().push(num(k));
            }
            for (what, ks) in skipped {
                unmeasured.push(format!("{} at k x {}: {what}", key.label(), ks.join(", ")));
            }
            let points: Vec<(f64, f64)> = f.points.iter().map(|p| (p[0], p[1])).collect();
            if points.is_empty() {
                continue;
            }
            lines.push(Line {
                key: key.clone(),
                points,
                label: Some(format!("{} / {}: {slope}", key.param, key.integrator)),
                marker_every: 1,
            });
        }
        let horizon = if fixed {
            "a fixed 10 s horizon".to_string()
        } else {
            "t_h in periods of the fastest mode (t_h shrinks as k^(-1/2))".to_string()
        };
        let what = metric.replace('_', " ");
        let mut caption = format!(
            "The {what} of each variant against the stiffness factor k (every spring of \
             nine_spring/two_angles times k), over {horizon}; lines join the points the \
             log-log slope was fitted on (slope in the legend; -1/2: limited by w h, -1: by \
             w^2 h t_h)."
        );
        if unmeasured.is_empty() {
            caption.push_str(" Every ladder point was measured.");
        } else {
            caption.push_str(&format!(
                " Not drawn (no measured step, not in the fit): {}.",
                unmeasured.join("; ")
            ));
        }
        let y_label = if metric.ends_with("_dt") {
            format!("{what} (s)")
        } else {
            what.clone()
        };
        let short_scene = if fixed { "10 s" } else { "t_h periods" };
        out.push(Plot {
            id: format!("stability/{scene}_{metric}"),
            title: format!("{case}: {what} vs stiffness ({short_scene})"),
            x_label: "stiffness factor k".into(),
            y_label,
            x: Scale::Log,
            y: Scale::Log,
            lines,
            fails: vec![],
            legend: Legend::PerLine,
            caption,
            footer: footer.into(),
        });
    }
    out
}

/// The columns of a long-horizon series file: `t`, energy error, momentum error (None when the
/// body conserves no momentum component).
type LongSeries = (Vec<f64>, Vec<f64>, Option<Vec<f64>>);

fn load_long_series(dir: &Path, r: &Record) -> Option<LongSeries> {
    let id = crate::summary::run_id(&r.param, &r.integrator, &r.formulation, r.dt, r.tol);
    let mut candidates = vec![];
    if let Some(rel) = &r.series {
        candidates.push(dir.join(rel));
    }
    candidates.push(
        dir.join("series/long_horizon")
            .join(&r.case)
            .join(&r.scene)
            .join(format!("{id}.json")),
    );
    let v: serde_json::Value = candidates.iter().find_map(|p| {
        let text = std::fs::read_to_string(p).ok()?;
        serde_json::from_str(&text).ok()
    })?;
    Some((
        column(&v, "t")?,
        column(&v, "energy_error")?,
        column(&v, "momentum_error"),
    ))
}

/// Column `name` of a series file's JSON (a non-number, e.g. `null`, reads as NaN).
fn column(v: &serde_json::Value, name: &str) -> Option<Vec<f64>> {
    v.get(name)?
        .as_array()?
        .iter()
        .map(|x| x.as_f64().or(Some(f64::NAN)))
        .collect()
}

/// The long-horizon plots of one scene (energy, and momentum when any record has it).
fn long_plots(case: &str, scene: &str, rs: &[&Record], dir: &Path, footer: &str) -> Vec<Plot> {
    let loaded: Vec<(&Record, Option<LongSeries>)> =
        rs.iter().map(|r| (*r, load_long_series(dir, r))).collect();
    let mut out = vec![];
    for momentum in [false, true] {
        let metric = if momentum {
            "momentum_growth_exponent"
        } else {
            "energy_growth_exponent"
        };
        if !rs.iter().any(|r| r.metrics.contains_key(metric)) {
            continue;
        }
        let mut lines = vec![];
        let mut missing = vec![];
        let mut steps: BTreeSet<String> = BTreeSet::new();
        for (r, s) in &loaded {
            let key = VariantKey::of(r);
            if (!momentum || r.metrics.contains_key(metric))
                && let Some(n) = r.metrics.get("long_horizon_steps").copied().flatten()
            {
                steps.insert(num(n));
            }
            let Some((t, e, m)) = s else {
                missing.push(format!("{} (no series file)", key.label()));
                continue;
            };
            let ys = if momentum {
                match m {
                    Some(m) => m,
                    None => continue,
                }
            } else {
                e
            };
            let points: Vec<(f64, f64)> = t.iter().copied().zip(ys.iter().copied()).collect();
            let p = match r.metrics.get(metric).copied().flatten() {
                Some(p) => format!("p = {}", decimals(p, 2)),
                None => "p -".into(),
            };
            let n = points.len();
            lines.push(Line {
                key: key.clone(),
                points,
                label: Some(format!("{} / {}: {p}", key.param, key.integrator)),
                marker_every: (n / 8).max(1),
            });
        }
        let (name, y) = if momentum {
            ("momentum error", "max |L_i - L_i(0)| / |L(0)|")
        } else {
            ("energy error", "|E - E0| / max(|E0|, E_scale)")
        };
        let mut caption = format!(
            "The relative {name} of each variant against t (log-log) over {} steps of the \
             dt in the table below, at 200 log-spaced times; p in the legend is the fitted \
             growth exponent of its running maximum over the last two decades (error ~ t^p: 1 \
             drift, 0 bounded, 1/2 round-off random walk). Exact zeros are not drawn.",
            if steps.is_empty() {
                "-".to_string()
            } else {
                steps.into_iter().collect::<Vec<_>>().join(" or ")
            }
        );
        if !missing.is_empty() {
            caption.push_str(&format!(" No data: {}.", missing.join("; ")));
        }
        out.push(Plot {
            id: format!(
                "stability/long_{scene}_{}",
                if momentum { "momentum" } else { "energy" }
            ),
            title: format!("{case}/{scene}: {name} over a long horizon"),
            x_label: "t (s)".into(),
            y_label: y.into(),
            x: Scale::Log,
            y: Scale::Log,
            lines,
            fails: vec![],
            legend: Legend::PerLine,
            caption,
            footer: footer.into(),
        });
    }
    out
}

/// The long-horizon table of a case.
fn long_table(case: &str, rs: &[&Record]) -> Table {
    let rows = rs
        .iter()
        .map(|r| {
            let mut row = variant_cells(&VariantKey::of(r)).to_vec();
            row.insert(0, Cell::plain(&r.scene));
            row.push(Cell::plain(r.dt.map(num).unwrap_or_else(|| "-".into())));
            row.push(
                match r.metrics.get("long_horizon_steps").copied().flatten() {
                    Some(n) => Cell::plain(format!("{n:.0}")),
                    None => Cell::plain("-"),
                },
            );
            row.push(status_cell(r));
            for m in [
                "energy_growth_exponent",
                "momentum_growth_exponent",
                "energy_error_final",
                "momentum_error_final",
            ] {
                let mut c = metric_text(r, m);
                if m.ends_with("_exponent")
                    && let Some(Some(p)) = r.metrics.get(m)
                {
                    c.text = decimals(*p, 3);
                }
                row.push(c);
            }
            row
        })
        .collect();
    Table {
        kind: "stability-long-horizon",
        title: format!("{case}: long horizon"),
        note: "Growth exponents p of the energy and momentum errors (fitted on their running \
               maximum over the last two decades of t: ~1 truncation drift, ~0 bounded, ~1/2 \
               round-off random walk) and the errors at the end. `-`: the body conserves no \
               momentum component; `null`: no exponent (hover, or the markdown, for why)."
            .into(),
        header: [
            "scene",
            "param",
            "integrator",
            "formulation",
            "dt",
            "steps",
            "status",
            "energy exponent",
            "momentum exponent",
            "final energy error",
            "final momentum error",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    }
}

fn is_singularity(r: &Record) -> bool {
    r.metrics.contains_key("approach_distance")
}

fn is_sensitivity(r: &Record) -> bool {
    r.metrics.contains_key("sensitivity_growth_max")
}

/// `x` in plain notation: whole above 100, else at most 3 decimals without trailing zeros.
fn plain(x: f64) -> String {
    if x.abs() >= 100.0 {
        return format!("{x:.0}");
    }
    let s = format!("{x:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

/// The quantities of a singularity-ladder record drawn against `d`: name, axis label, value.
type Quantity = (&'static str, &'static str, fn(&Record) -> Option<f64>);

const SINGULARITY_QUANTITIES: [Quantity; 3] = [
    ("rotation_error", "max rotation error (rad)", |r| {
        r.metrics.get("rotation_error_max").copied().flatten()
    }),
    ("rhs_evals", "RHS evaluations", |r| {
        Some(r.stats.rhs_evals as f64)
    }),
    ("conditioning", "minimum chart conditioning", |r| {
        r.metrics.get("conditioning_min").copied().flatten()
    }),
];

/// The singularity-ladder records of a case grouped by run setting (integrator, step or
/// tolerance), fixed steps first.
fn singularity_groups<'a>(rs: &[&'a Record]) -> Vec<((String, String), Vec<&'a Record>)> {
    let mut groups: BTreeMap<(bool, String, u64), Vec<&Record>> = BTreeMap::new();
    for r in rs.iter().copied().filter(|r| is_singularity(r)) {
        let value = super::data::step_of(r).unwrap_or(f64::NAN);
        // Coarse steps and loose tolerances first: larger values sort first.
        groups
            .entry((r.tol.is_some(), r.integrator.clone(), !value.to_bits()))
            .or_default()
            .push(r);
    }
    groups
        .into_values()
        .map(|mut v| {
            v.sort_by_key(|r| VariantKey::of(r));
            let label = (v[0].integrator.clone(), super::data::step_label(v[0]));
            (label, v)
        })
        .collect()
}

/// The singularity-ladder plots of a case (`gimbal_lock`): per run setting, the rotation
/// error, the RHS evaluations (adaptive settings only: a fixed step's work does not depend on
/// `d`) and the chart's minimum conditioning against the approach distance `d`, log-log, one
/// line per chart; failed runs are marked at their `d`.
fn singularity_plots(case: &str, rs: &[&Record], footer: &str) -> Vec<Plot> {
    let mut out = vec![];
    for ((integrator, setting), group) in singularity_groups(rs) {
        let adaptive = group[0].tol.is_some();
        for (name, y_label, value) in SINGULARITY_QUANTITIES {
            if name == "rhs_evals" && !adaptive {
                continue;
            }
            let mut by_key: BTreeMap<VariantKey, Vec<(f64, f64)>> = BTreeMap::new();
            let mut fails = vec![];
            let mut undrawn: BTreeSet<String> = BTreeSet::new();
            let mut failed: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
            for r in &group {
                let key = VariantKey::of(r);
                let Some(d) = r.metrics.get("approach_distance").copied().flatten() else {
                    continue;
                };
                if r.status == Status::Failed {
                    let what = r.failure.as_ref().map_or("failed".to_string(), |f| {
                        format!("{} at t = {}", kind_name(f.kind), num(f.t))
                    });
                    failed.entry(key.param.clone()).or_default().insert(what);
                    fails.push(super::chart::FailMark { key, x: d });
                    continue;
                }
                match value(r) {
                    Some(y) if y > 0.0 && y.is_finite() => {
                        by_key.entry(key).or_default().push((d, y))
                    }
                    Some(_) => {
                        undrawn.insert(format!("{} (exact zero)", key.label()));
                    }
                    None => {
                        undrawn.insert(format!("{} (null)", key.label()));
                    }
                }
            }
            let lines: Vec<Line> = by_key
                .into_iter()
                .map(|(key, mut points)| {
                    points.sort_by(|a, b| a.0.total_cmp(&b.0));
                    Line {
                        label: Some(key.param.clone()),
                        key,
                        points,
                        marker_every: 1,
                    }
                })
                .collect();
            let regime = match group[0].dt {
                Some(h) => format!(
                    " One step travels Omega h = {} rad (Omega = 1 rad/s): for d below it a \
                     fixed step jumps over the singular set instead of resolving it, so the \
                     Euler charts' error stops growing there (the regime change).",
                    num(h)
                ),
                None => " An adaptive method resolves the spike by shrinking its steps (its \
                          work grows as d shrinks); at a loose tolerance it can step over the \
                          spike unnoticed, and its work then stops growing."
                    .to_string(),
            };
            let mut caption = format!(
                "gimbal_lock's spin passing within d of the xyz and zyx charts' singular set \
                 (generated scenes ladder_d1e-k, exact reference): the {} of each chart with \
                 {integrator} at {setting} against d, log-log; failed runs are marked at their \
                 d.{regime}",
                y_label.split(" (").next().unwrap_or(y_label)
            );
            if !failed.is_empty() {
                let list: Vec<String> = failed
                    .into_iter()
                    .map(|(p, w)| format!("{p} ({})", w.into_iter().collect::<Vec<_>>().join(", ")))
                    .collect();
                caption.push_str(&format!(" Failed (red band): {}.", list.join("; ")));
            }
            if !undrawn.is_empty() {
                caption.push_str(&format!(
                    " Not drawn: {}.",
                    undrawn.into_iter().collect::<Vec<_>>().join(", ")
                ));
            }
            let id_setting = setting.replace(' ', "_");
            out.push(Plot {
                id: format!("stability/singularity_{integrator}_{id_setting}_{name}"),
                title: format!(
                    "{case}: {} vs approach distance ({integrator}, {setting})",
                    y_label.split(" (").next().unwrap_or(y_label)
                ),
                x_label: "approach distance d (rad)".into(),
                y_label: y_label.into(),
                x: Scale::Log,
                y: Scale::Log,
                lines,
                fails,
                legend: Legend::PerLine,
                caption,
                footer: footer.into(),
            });
        }
    }
    out
}

/// Sentences on the singularity ladder, from its records: per fixed-step setting, where each
/// Euler chart's error peaks and what it is at the smallest `d`.
fn singularity_facts(rs: &[&Record]) -> Vec<String> {
    let mut out = vec![];
    for ((integrator, setting), group) in singularity_groups(rs) {
        let mut parts = vec![];
        let mut by_key: BTreeMap<VariantKey, Vec<(f64, f64)>> = BTreeMap::new();
        for r in &group {
            let d = r.metrics.get("approach_distance").copied().flatten();
            let e = r.metrics.get("rotation_error_max").copied().flatten();
            if let (Some(d), Some(e), Status::Ok) = (d, e, r.status) {
                by_key.entry(VariantKey::of(r)).or_default().push((d, e));
            }
        }
        for (key, mut pts) in by_key {
            if !key.is_euler() || pts.len() < 2 {
                continue;
            }
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let peak = pts.iter().max_by(|a, b| a.1.total_cmp(&b.1)).copied();
            let (d_min, e_min) = pts[0];
            if let Some((d_peak, e_peak)) = peak {
                parts.push(format!(
                    "{} peaks at {} (d = {}), {} at d = {}",
                    key.param,
                    num(e_peak),
                    num(d_peak),
                    num(e_min),
                    num(d_min)
                ));
            }
        }
        if !parts.is_empty() {
            out.push(format!(
                "Singularity ladder, {integrator} at {setting}, max rotation error: {}.",
                parts.join("; ")
            ));
        }
    }
    out
}

/// The growth series of a sensitivity record: `(t, G(t))`.
fn load_growth(dir: &Path, r: &Record) -> Option<Vec<(f64, f64)>> {
    let rel = r.series.as_ref()?;
    let text = std::fs::read_to_string(dir.join(rel)).ok()?;
    let v: serde_json::Value = serde_json::from_str(&text).ok()?;
    let (t, g) = (column(&v, "t")?, column(&v, "growth")?);
    Some(t.into_iter().zip(g).collect())
}

/// The sensitivity plot of a case: the growth `G(t)` of a 1e-9 perturbation of each scene's
/// initial state against t (log y), one line per scene.
fn sensitivity_plot(case: &str, rs: &[&Record], dir: &Path, footer: &str) -> Option<Plot> {
    let rs: Vec<&Record> = rs.iter().copied().filter(|r| is_sensitivity(r)).collect();
    if rs.is_empty() {
        return None;
    }
    let mut lines = vec![];
    let mut missing = vec![];
    for r in &rs {
        let Some(points) = load_growth(dir, r) else {
            missing.push(r.scene.clone());
            continue;
        };
        let points: Vec<(f64, f64)> = points.into_iter().filter(|p| p.1 > 0.0).collect();
        let n = points.len();
        let horizon = r.metrics.get("predictable_horizon").copied().flatten();
        lines.push(Line {
            key: VariantKey {
                param: "so3".into(),
                integrator: r.scene.clone(),
                formulation: "body".into(),
            },
            points,
            label: Some(match horizon {
                Some(h) => format!("{} (predictable to t = {})", r.scene, num(h)),
                None => r.scene.clone(),
            }),
            marker_every: (n / 8).max(1),
        });
    }
    let mut caption = format!(
        "How far each scene carries a 1e-9 change of its initial state: G(t), the largest \
         singular value of the finite-difference state-transition matrix (the growth of the \
         worst initial direction of attitude, position, velocity and rate), against t \
         (dop853/so3/body at tol {}). Where G passes 1e7 a round-off-sized difference has grown \
         past 1e-9, so errors below 1e-9 measured beyond that time (the predictable horizon in \
         the legend) say nothing about a method.",
        num(crate::stability::sensitivity::TOL)
    );
    if !missing.is_empty() {
        caption.push_str(&format!(" No series file for: {}.", missing.join(", ")));
    }
    Some(Plot {
        id: "stability/sensitivity".into(),
        title: format!("{case}: growth of a 1e-9 initial perturbation"),
        x_label: "t (s)".into(),
        y_label: "growth G(t)".into(),
        x: Scale::Linear,
        y: Scale::Log,
        lines,
        fails: vec![],
        legend: Legend::PerLine,
        caption,
        footer: footer.into(),
    })
}

/// Records of kinds this part does not know: a generic table of their metrics.
fn other_table(case: &str, rs: &[&Record]) -> Table {
    let metrics: BTreeSet<&str> = rs
        .iter()
        .flat_map(|r| r.metrics.keys().map(String::as_str))
        .collect();
    let rows = rs
        .iter()
        .map(|r| {
            let mut row = vec![Cell::plain(&r.scene)];
            row.extend(variant_cells(&VariantKey::of(r)));
            row.push(Cell::plain(super::data::step_label(r)));
            row.push(status_cell(r));
            row.extend(metrics.iter().map(|m| metric_text(r, m)));
            row
        })
        .collect();
    let mut header: Vec<String> = [
        "scene",
        "param",
        "integrator",
        "formulation",
        "step",
        "status",
    ]
    .map(String::from)
    .to_vec();
    header.extend(metrics.iter().map(|m| m.to_string()));
    Table {
        kind: "stability-other",
        title: format!("{case}: other stability records"),
        note: "Records of stability.json that are neither step searches nor long-horizon runs \
               (later parts of the study, n/a combinations), with every metric they carry; \
               `-`: absent, `null`: not computed (hover, or the markdown, for why)."
            .into(),
        header,
        rows,
    }
}

/// Fits of kinds this part does not draw.
fn other_fits_table(case: &str, fs: &[&FitRecord]) -> Table {
    let rows = fs
        .iter()
        .map(|f| {
            let mut row = vec![Cell::plain(&f.scene)];
            row.extend(variant_cells(&key_of_fit(f)));
            row.push(Cell::plain(&f.metric));
            row.push(Cell::plain(
                f.order.map(|p| decimals(p, 3)).unwrap_or("null".into()),
            ));
            row.push(Cell::abridged(
                abbreviate(f.reason.as_deref().unwrap_or(""), 48),
                f.reason.clone().unwrap_or_default(),
            ));
            row.push(Cell::plain(f.points.len().to_string()));
            row
        })
        .collect();
    Table {
        kind: "stability-other",
        title: format!("{case}: other stability fits"),
        note: "Fits of stability.json not drawn above, with their fitted value.".into(),
        header: [
            "scene",
            "param",
            "integrator",
            "formulation",
            "metric",
            "value",
            "reason",
            "points",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    }
}

/// Sentences computed from the step searches of the case file's scenes: the variants bounded
/// up to the cap everywhere, and the most restrictive stable step.
fn search_facts(search: &[&Record], case: Option<&Case>) -> Vec<String> {
    let own: Vec<&Record> = search
        .iter()
        .copied()
        .filter(|r| case.is_none() || in_case_file(case, &r.scene))
        .collect();
    let mut out = vec![];
    let mut by_variant: BTreeMap<VariantKey, Vec<bool>> = BTreeMap::new();
    for r in &own {
        let Some(sm) = stable_metric(r) else { continue };
        let why = r.metric_reasons.get(sm).map(String::as_str).unwrap_or("");
        by_variant
            .entry(VariantKey::of(r))
            .or_default()
            .push(capped(why));
    }
    let always: Vec<String> = by_variant
        .iter()
        .filter(|(_, c)| c.iter().all(|x| *x))
        .map(|(k, _)| k.label())
        .collect();
    if !always.is_empty() {
        out.push(format!(
            "Stable up to the cap (t_h / 20) in every searched scene, i.e. no stability limit \
             found: {}.",
            always.join(", ")
        ));
    }
    let smallest = own
        .iter()
        .filter_map(|r| {
            let sm = stable_metric(r)?;
            let v = r.metrics.get(sm).copied().flatten()?;
            Some((sm.ends_with("_dt"), v, *r, sm))
        })
        .filter(|x| x.0)
        .min_by(|a, b| a.1.total_cmp(&b.1));
    if let Some((_, v, r, sm)) = smallest {
        out.push(format!(
            "The most restrictive stable step is {} in {} at dt {} ({}).",
            VariantKey::of(r).label(),
            r.scene,
            num(v),
            short_reason(r.metric_reasons.get(sm).map(String::as_str).unwrap_or(""))
        ));
    }
    out
}

/// The stability part of case `name`; None when stability.json has nothing on it.
pub fn section(
    src: Source,
    name: &str,
    case: Option<&Case>,
    footer: &str,
) -> Option<StabilitySection> {
    let s = src.summary;
    let records: Vec<&Record> = s.records.iter().filter(|r| r.case == name).collect();
    let fits: Vec<&FitRecord> = s.fits.iter().filter(|f| f.case == name).collect();
    if records.is_empty() && fits.is_empty() {
        return None;
    }
    let search: Vec<&Record> = records
        .iter()
        .copied()
        .filter(|r| stable_metric(r).is_some())
        .collect();
    let long: Vec<&Record> = records.iter().copied().filter(|r| is_long(r)).collect();
    let other: Vec<&Record> = records
        .iter()
        .copied()
        .filter(|r| stable_metric(r).is_none() && !is_long(r))
        .collect();
    let other_fits: Vec<&FitRecord> = fits
        .iter()
        .copied()
        .filter(|f| !is_ladder_fit(f) && !is_growth_fit(f))
        .collect();

    let mut text = vec![];
    if !search.is_empty() {
        text.push(
            "Step search: per scene, the largest step (or loosest tolerance) at which each \
             variant stays stable, and stays accurate, over the horizon t_h (periods of the \
             scene's fastest linearised mode; probes dt = t_h / n from the cap t_h / 20 down, \
             bisected to 5 %)."
                .to_string(),
        );
        text.push(
            "In the tables, 'what limits it' is the failure at the next coarser probe (hover \
             for the full text); '(cap)' with 'bounded up to the cap' means the coarsest step \
             tried, t_h / 20, passed: a lower bound, no limit was found."
                .to_string(),
        );
        if search.iter().any(|r| r.integrator == "euler") {
            text.push(EULER_NOTE.to_string());
        }
        text.extend(search_facts(&search, case));
    }
    if fits.iter().any(|f| is_ladder_fit(f)) {
        text.push(
            "Stiffness ladder: the springs stiffened by factors k; the slope of log step \
             against log k says what limits the step (w h: -1/2; the energy growth of explicit \
             Euler over a fixed time, w^2 h t_h: -1)."
                .to_string(),
        );
    }
    if !long.is_empty() {
        text.push(
            "Long horizon: energy and momentum errors over 10^4 to 10^7 steps with their growth \
             exponents p (error ~ t^p: ~1 truncation drift, ~0 bounded, ~1/2 round-off random \
             walk)."
                .to_string(),
        );
    }

    if other.iter().any(|r| is_singularity(r)) {
        text.push(
            "Singularity ladder: gimbal_lock's spin passing within d of the Euler charts' \
             singular set, d = 1e-1 ... 1e-12; error, work and conditioning against d per \
             chart and setting (plots below, numbers in the table of other records)."
                .to_string(),
        );
        text.extend(singularity_facts(&other));
    }
    if other.iter().any(|r| is_sensitivity(r)) {
        let facts: Vec<String> = other
            .iter()
            .filter(|r| is_sensitivity(r))
            .filter_map(|r| {
                let g = r.metrics.get("sensitivity_growth_max").copied().flatten()?;
                let h = r.metrics.get("predictable_horizon").copied().flatten()?;
                Some(format!(
                    "{} {}x (predictable to t = {} s)",
                    r.scene,
                    plain(g),
                    plain(h)
                ))
            })
            .collect();
        text.push(format!(
            "Sensitivity: the largest growth of a 1e-9 initial perturbation over each scene's \
             horizon: {}.",
            if facts.is_empty() {
                "not computed".to_string()
            } else {
                facts.join(", ")
            }
        ));
    }

    let steps = ordered_scenes(search.iter().map(|r| r.scene.as_str()), case)
        .into_iter()
        .map(|scene| {
            let rs: Vec<&Record> = search
                .iter()
                .copied()
                .filter(|r| r.scene == scene)
                .collect();
            StepTable {
                open: case.is_none() || in_case_file(case, &scene),
                table: step_table(name, &scene, &rs),
            }
        })
        .collect();
    let ladder = ladder_plots(name, &fits, &search, footer)
        .iter()
        .map(super::figure)
        .collect();
    let mut long_figs = vec![];
    let mut long_sorted = long.clone();
    long_sorted.sort_by_key(|r| VariantKey::of(r));
    for scene in ordered_scenes(long.iter().map(|r| r.scene.as_str()), case) {
        let rs: Vec<&Record> = long_sorted
            .iter()
            .copied()
            .filter(|r| r.scene == scene)
            .collect();
        long_figs.extend(
            long_plots(name, &scene, &rs, src.dir, footer)
                .iter()
                .map(super::figure),
        );
    }
    Some(StabilitySection {
        env_line: format!(
            "stability.json: commit {} | {} | {} | {} build, {} threads",
            s.git_commit, s.created_utc, s.env.rustc, s.env.profile, s.env.threads
        ),
        text,
        steps,
        ladder,
        long_horizon: long_figs,
        long_table: (!long_sorted.is_empty()).then(|| long_table(name, &long_sorted)),
        singularity: singularity_plots(name, &other, footer)
            .iter()
            .map(super::figure)
            .collect(),
        sensitivity: sensitivity_plot(name, &other, src.dir, footer)
            .iter()
            .map(super::figure)
            .collect(),
        other: (!other.is_empty()).then(|| other_table(name, &other)),
        other_fits: (!other_fits.is_empty()).then(|| other_fits_table(name, &other_fits)),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::{fixture, html, markdown, render_check, write_report};
    use crate::summary::{Env, FitRecord, Summary, run_id};

    fn rec(case: &str, scene: &str, p: &str, i: &str, metrics: &[(&str, Option<f64>)]) -> Record {
        let mut r = fixture::summary().records[0].clone();
        r.case = case.into();
        r.scene = scene.into();
        r.param = p.into();
        r.integrator = i.into();
        r.formulation = "body".into();
        r.dt = None;
        r.tol = None;
        r.status = Status::Ok;
        r.series = None;
        r.metrics = metrics.iter().map(|(k, v)| (k.to_string(), *v)).collect();
        r.metric_reasons.clear();
        r
    }

    const LIMITED: &str = "limited by bound_exceeded at t = 30.135874 with dt = 9.287436e-4 (n = \
        33280): energy error |E - E0| / max(|E0|, energy_scale) = 1.000e0 >= 1";
    const CAP: &str = "bounded up to the cap (dt = t_h / 20, tol = 1e0; t_h = 30.910000 s)";

    /// A search record with its reasons.
    fn search(scene: &str, p: &str, i: &str, stable: Option<f64>, why: &str) -> Record {
        let m = if i == "dopri5" { "tol" } else { "dt" };
        let sm = format!("largest_stable_{m}");
        let am = format!("largest_accurate_{m}");
        let mut r = rec(
            fixture::CASE,
            scene,
            p,
            i,
            &[
                (&sm, stable),
                (&am, stable.map(|x| x / 10.0)),
                ("stability_horizon", Some(30.91)),
                ("fastest_period", Some(1.5455)),
            ],
        );
        r.metric_reasons.insert(sm, why.into());
        r.metric_reasons.insert(
            am,
            "limited by bound_exceeded at t = 30.58077 with dt = 2.34156e-2 (n = 1320): \
             rotation error 1.046e-1 rad >= 0.1 rad"
                .into(),
        );
        r
    }

    /// A small stability summary: step searches (one capped), a stiffness ladder, a
    /// long-horizon run, a record of a later kind and a case found only here.
    pub fn stability_summary() -> Summary {
        let mut records = vec![
            search("two_angles", "so3", "euler", Some(8.94e-4), LIMITED),
            search("two_angles", "so3", "rk4", Some(0.187), LIMITED),
            search("two_angles", "so3", "simo_wong", Some(1.5455), CAP),
            search("two_angles", "quat", "dopri5", Some(1e-3), LIMITED),
        ];
        for (j, dt) in [(0, 0.187), (2, 0.0187), (4, 0.00187)] {
            records.push(search(
                &format!("two_angles_k1e{j}"),
                "so3",
                "rk4",
                Some(dt),
                LIMITED,
            ));
            let simo = if j == 0 { CAP } else { LIMITED };
            records.push(search(
                &format!("two_angles_k1e{j}"),
                "so3",
                "simo_wong",
                Some(dt * 2.0),
                simo,
            ));
        }
        let mut long = rec(
            "free_body",
            "gni",
            "so3",
            "rk4",
            &[
                ("long_horizon_steps", Some(1e4)),
                ("energy_growth_exponent", Some(0.98)),
                ("momentum_growth_exponent", None),
                ("energy_error_final", Some(1e-9)),
                ("momentum_error_final", Some(2e-9)),
            ],
        );
        long.dt = Some(1e-2);
        long.metric_reasons.insert(
            "momentum_growth_exponent".into(),
            "the error is exactly 0 at every sample".into(),
        );
        let id = run_id("so3", "rk4", "body", Some(1e-2), None);
        long.series = Some(format!("series/long_horizon/free_body/gni/{id}.json"));
        records.push(long);
        records.push(rec(
            fixture::CASE,
            "two_angles",
            "so3",
            "rk4",
            &[("sensitivity_growth_max", Some(3.5e-2))],
        ));
        records.push(rec(
            "gimbal_lock",
            "approach",
            "euler_zyx",
            "rk4",
            &[("approach_distance", Some(1e-3))],
        ));
        let fit = |i: &str, order: Option<f64>, points: Vec<[f64; 2]>| FitRecord {
            case: fixture::CASE.into(),
            scene: "two_angles_stiffness".into(),
            param: "so3".into(),
            integrator: i.into(),
            formulation: "body".into(),
            metric: "largest_stable_dt_vs_stiffness".into(),
            order,
            reason: order.is_none().then(|| "2 of 3 stiffness factors".into()),
            points,
        };
        let fits = vec![
            fit(
                "rk4",
                Some(-0.5),
                vec![[1.0, 0.187], [1e2, 0.0187], [1e4, 0.00187]],
            ),
            fit("simo_wong", None, vec![[1e2, 0.0374], [1e4, 0.00374]]),
        ];
        Summary {
            schema: 1,
            git_commit: "def5678".into(),
            created_utc: "2026-01-02T04:00:00Z".into(),
            env: Env {
                rustc: "rustc 1.95.0".into(),
                cpu: "Test CPU".into(),
                os: "Test OS".into(),
                profile: "release".into(),
                threads: 2,
                timing: None,
            },
            records,
            fits,
        }
    }

    fn write_long_series(dir: &Path) {
        let id = run_id("so3", "rk4", "body", Some(1e-2), None);
        let p = dir.join(format!("series/long_horizon/free_body/gni/{id}.json"));
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        let t: Vec<f64> = (0..50)
            .map(|k| 10f64.powf(k as f64 / 12.0) * 1e-2)
            .collect();
        let e: Vec<f64> = t.iter().map(|x| 1e-13 * x).collect();
        let v = serde_json::json!({"t": t, "energy_error": e, "momentum_error": e});
        std::fs::write(p, v.to_string()).unwrap();
    }

    fn section_of<'a>(html: &'a str, case: &str) -> &'a str {
        let start = html
            .find(&format!("<section class=\"case\" data-case=\"{case}\""))
            .expect("case section");
        let end = html[start..].find("</section>").unwrap() + start;
        &html[start..end]
    }

    /// The stability fixture renders, per case, its step tables (the cap visible as such, the
    /// Euler sentence, short reasons with the full text on hover and in the markdown), the
    /// stiffness-ladder plot with slopes and the unmeasured points in its caption, the
    /// long-horizon plots and table, the generic table of other records, and a section for a
    /// case found only in stability.json; the page stays self-contained and passes its check.
    #[test]
    fn stability_fixture_renders_tables_and_plots() {
        let s = fixture::summary();
        let st = stability_summary();
        let dir = fixture::temp_dir("stability");
        fixture::write_series(&dir.join("series"), &s, |_| false);
        write_long_series(&dir);
        let out = dir.join("report");
        let src = Source {
            summary: &st,
            dir: &dir,
        };
        let files = write_report(&s, &dir.join("series"), &[], None, Some(src), &out).unwrap();
        let page = std::fs::read_to_string(&files.index_html).unwrap();
        assert_eq!(render_check(&page), Vec::<String>::new());
        for t in html::start_tags(&page) {
            for (n, _) in &t.attrs {
                assert!(n != "src" && n != "href" && !n.ends_with(":href"), "{n}");
            }
        }
        let nine = section_of(&page, fixture::CASE);
        assert!(nine.contains("data-section=\"stability\""));
        assert!(nine.contains(&html::esc(EULER_NOTE)));
        assert_eq!(page.matches(&html::esc(EULER_NOTE)).count(), 1);
        assert!(nine.contains("nine_spring / two_angles: largest stable and accurate step"));
        assert!(nine.contains("nine_spring / two_angles_k1e2: largest stable and accurate step"));
        assert!(nine.contains("<td>dt 1.55e0 (cap)</td>"), "capped value");
        assert!(nine.contains(">bounded up to the cap</td>"));
        assert!(nine.contains("<td>tol 1e-3</td>"), "adaptive row");
        assert!(nine.contains(&format!(
            "<td title=\"{}\">energy error &gt;= 1 at t = 30.14 s</td>",
            html::esc(LIMITED)
        )));
        // The ladder: one plot (stable dt), the slopes in the legend, capped point in the caption.
        let ladder = files
            .svgs
            .iter()
            .find(|p| p.ends_with("stability/two_angles_stiffness_largest_stable_dt.svg"))
            .expect("ladder svg");
        let svg = std::fs::read_to_string(ladder).unwrap();
        assert!(
            svg.contains("so3 / rk4: slope -0.50"),
            "slope in the legend"
        );
        assert!(svg.contains("so3 / simo_wong: slope - (too few points)"));
        assert!(
            svg.contains("\n1e4\n") && svg.contains("\n1\n"),
            "end labels"
        );
        assert!(nine.contains("so3 / simo_wong / body at k x 1: bounded up to the cap"));
        assert!(
            nine.contains("<td>3.5e-2</td>"),
            "other records: sensitivity"
        );
        // Long horizon: both plots drawn from the series file, and the table.
        let fb = section_of(&page, "free_body");
        assert_eq!(fb.matches("<svg").count(), 2, "energy and momentum plots");
        assert!(fb.contains("so3 / rk4: p = 0.98"));
        assert!(fb.contains("free_body: long horizon"));
        assert!(fb.contains("<td>0.980</td>"));
        assert!(
            out.join("svg/free_body/stability/long_gni_energy.svg")
                .is_file()
        );
        // A case only in stability.json gets a section with its record.
        let gl = section_of(&page, "gimbal_lock");
        assert!(gl.contains("approach_distance") && gl.contains("<td>1e-3</td>"));
        let md = std::fs::read_to_string(&files.summary_md).unwrap();
        assert!(md.contains("### Stability"));
        assert!(md.contains("#### nine_spring / two_angles: largest stable and accurate step"));
        assert!(md.contains("| so3 | simo_wong | body | dt 1.55e0 (cap) | bounded up to the cap"));
        assert!(md.contains("energy error \\|E - E0\\| / max(\\|E0\\|, energy_scale)"));
        assert!(md.contains(EULER_NOTE));
        assert!(md.contains("#### free_body: long horizon"));
        assert!(md.contains("#### nine_spring: other stability records"));
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A singularity-ladder record: chart, setting, distance, error, conditioning, RHS count,
    /// and optionally a failure.
    fn sing(p: &str, i: &str, step: (Option<f64>, Option<f64>), d: f64, e: f64) -> Record {
        let mut r = rec(
            "gimbal_lock",
            &format!("ladder_d{d:e}"),
            p,
            i,
            &[
                ("approach_distance", Some(d)),
                ("rotation_error_max", Some(e)),
                ("conditioning_min", Some(d.max(1e-3))),
            ],
        );
        (r.dt, r.tol) = step;
        r.stats.rhs_evals = (1e3 * e.max(1e-9).log10().abs()) as u64;
        r
    }

    /// The singularity ladder gives, per setting, error and conditioning plots (and work for
    /// an adaptive setting), one line per chart sorted by d, a failed chart in the red band and
    /// named with its failure in the caption, the regime-change step in the caption; its
    /// sentence names where each Euler chart's error peaks.
    #[test]
    fn singularity_plots_per_setting() {
        let fixed = (Some(1e-2), None);
        let tol = (None, Some(1e-8));
        let mut rs = vec![];
        for (d, e) in [(1e-2, 1e-4), (1e-10, 1e-11), (1e-6, 1e-2)] {
            rs.push(sing("euler_xyz", "rk4", fixed, d, e));
            rs.push(sing("so3", "rk4", fixed, d, 1e-15));
            rs.push(sing("euler_xyz", "dop853", tol, d, e / 10.0));
            let mut z = sing("euler_zxz", "rk4", fixed, d, 0.0);
            z.status = Status::Failed;
            z.metrics.insert("rotation_error_max".into(), None);
            z.failure = Some(crate::integrate::Failure::new(
                crate::integrate::FailureKind::SingularChart,
                0.0,
                "conditioning 0",
            ));
            rs.push(z);
        }
        let refs: Vec<&Record> = rs.iter().collect();
        let plots = singularity_plots("gimbal_lock", &refs, "footer");
        let ids: Vec<&str> = plots.iter().map(|p| p.id.as_str()).collect();
        assert_eq!(
            ids,
            [
                "stability/singularity_rk4_dt_1e-2_rotation_error",
                "stability/singularity_rk4_dt_1e-2_conditioning",
                "stability/singularity_dop853_tol_1e-8_rotation_error",
                "stability/singularity_dop853_tol_1e-8_rhs_evals",
                "stability/singularity_dop853_tol_1e-8_conditioning",
            ]
        );
        let err = &plots[0];
        let params: Vec<&str> = err.lines.iter().map(|l| l.key.param.as_str()).collect();
        assert_eq!(params, ["euler_xyz", "so3"]);
        assert_eq!(
            err.lines[0].points,
            vec![(1e-10, 1e-11), (1e-6, 1e-2), (1e-2, 1e-4)]
        );
        assert_eq!(err.fails.len(), 3);
        assert!(err.caption.contains("Omega h = 1e-2"), "{}", err.caption);
        assert!(
            err.caption
                .contains("Failed (red band): euler_zxz (singular_chart at t = 0)"),
            "{}",
            err.caption
        );
        assert_eq!(plots[3].lines[0].points[0], (1e-10, 9000.0));
        let facts = singularity_facts(&refs);
        assert_eq!(
            facts[0],
            "Singularity ladder, rk4 at dt 1e-2, max rotation error: euler_xyz peaks at 1e-2 \
             (d = 1e-6), 1e-11 at d = 1e-10."
        );
    }

    /// The sensitivity plot draws each scene's growth series from its file, names the
    /// predictable horizon in the legend, and names a scene whose file is missing.
    #[test]
    fn sensitivity_plot_from_series() {
        let dir = fixture::temp_dir("sensitivity");
        let mut a = rec(
            "nine_spring",
            "large",
            "so3",
            "dop853",
            &[
                ("sensitivity_growth_max", Some(945.0)),
                ("predictable_horizon", Some(10.0)),
            ],
        );
        a.series = Some("series/sensitivity/nine_spring/large.json".into());
        let p = dir.join(a.series.as_ref().unwrap());
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        let v = serde_json::json!({"t": [0.0, 5.0, 10.0], "growth": [1.0, 30.0, 597.0]});
        std::fs::write(&p, v.to_string()).unwrap();
        let mut b = a.clone();
        b.scene = "two_angles".into();
        b.series = Some("series/sensitivity/nine_spring/two_angles.json".into());
        let plot = sensitivity_plot("nine_spring", &[&a, &b], &dir, "f").unwrap();
        assert_eq!(plot.lines.len(), 1);
        assert_eq!(
            plot.lines[0].points,
            vec![(0.0, 1.0), (5.0, 30.0), (10.0, 597.0)]
        );
        assert_eq!(
            plot.lines[0].label.as_deref(),
            Some("large (predictable to t = 10)")
        );
        assert!(plot.caption.contains("No series file for: two_angles."));
        assert!(sensitivity_plot("nine_spring", &[], &dir, "f").is_none());
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// Without stability.json the page and the markdown have no stability part; with one whose
    /// series files are missing the long-horizon plots say "no data" in place.
    #[test]
    fn no_stability_no_part() {
        let s = fixture::summary();
        let dir = fixture::temp_dir("no-stability");
        let page = html::render(&crate::report::build_page(&s, &dir, &[], None, None));
        assert!(!page.contains("data-section=\"stability"));
        assert!(!page.contains(EULER_NOTE));
        let md = markdown::render(&crate::report::build_page(&s, &dir, &[], None, None));
        assert!(!md.contains("Stability"));
        let st = stability_summary();
        let src = Source {
            summary: &st,
            dir: &dir,
        };
        let page = html::render(&crate::report::build_page(&s, &dir, &[], None, Some(src)));
        assert_eq!(render_check(&page), Vec::<String>::new());
        let fb = section_of(&page, "free_body");
        assert!(fb.contains("no series file"));
        assert!(fb.contains("<p class=\"nodata\">"));
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A corrupt stability.json is a warning naming the file and the report is written without
    /// the part; an absent one is silently no part.
    #[test]
    fn corrupt_stability_json_warns_and_report_goes_on() {
        let s = fixture::summary();
        let dir = fixture::temp_dir("corrupt-stability");
        let summary_path = dir.join("summary.json");
        std::fs::write(&summary_path, serde_json::to_string(&s).unwrap()).unwrap();
        assert_eq!(load_beside(&summary_path), (None, None));
        std::fs::write(dir.join("stability.json"), "{\"schema\": 1, \"records\": [").unwrap();
        let (st, warning) = load_beside(&summary_path);
        assert!(st.is_none());
        let w = warning.expect("a warning");
        assert!(
            w.starts_with("warning:") && w.contains("stability.json"),
            "{w}"
        );
        let files = write_report(
            &s,
            &dir.join("series"),
            &[],
            None,
            st.as_ref().map(|s| Source {
                summary: s,
                dir: &dir,
            }),
            &dir.join("report"),
        )
        .unwrap();
        let page = std::fs::read_to_string(&files.index_html).unwrap();
        assert_eq!(render_check(&page), Vec::<String>::new());
        assert!(page.contains("data-case=\"nine_spring\""));
        assert!(!page.contains("data-section=\"stability"));
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// Reasons shorten to the failure kind or the bound and its time; the cap stays "bounded up
    /// to the cap"; unknown texts are cut with an ellipsis.
    #[test]
    fn short_reasons() {
        assert_eq!(short_reason(LIMITED), "energy error >= 1 at t = 30.14 s");
        assert_eq!(short_reason(CAP), "bounded up to the cap");
        assert_eq!(
            short_reason(
                "nothing passed: bound_exceeded at t = 18.854163 with n = 327680 steps: \
                 rotation error 1.388e-1 rad >= 0.1 rad"
            ),
            "nothing passed: rotation error >= 0.1 rad at t = 18.85 s"
        );
        assert_eq!(
            short_reason(
                "limited by newton_failure at t = 28.055488 with dt = 4.7e-1 (n = 65): \
                 simo_wong: Newton diverges"
            ),
            "newton_failure at t = 28.06 s"
        );
        assert_eq!(short_reason("nothing passed"), "nothing passed");
        assert_eq!(
            short_reason("search not completed: x"),
            "search not completed"
        );
        assert!(short_reason(&"x".repeat(80)).ends_with("..."));
        assert_eq!(short_reason(""), "-");
        assert_eq!(decimals(-0.0004, 3), "0.000");
        assert_eq!(decimals(-0.5, 2), "-0.50");
    }
}
