//! The stability part of a case's section (README.md, "The stability study"), from `stability.json`
//! (the summary's schema, written by `mbdbench stability` beside `summary.json`) and its
//! long-horizon series files. A record is read by the metrics it carries, so later parts of the
//! study need no change here to be shown:
//!
//! - step search (`largest_stable_dt` or `largest_stable_tol`): one table per scene (the case
//!   file's scenes first, then generated ones such as the stiffness ladder's `two_angles_k1e2`,
//!   `two_angles_k1e2_T10`, folded), each variant's largest stable and accurate step, what
//!   limits each (shortened; the full `metric_reasons` text on hover and in the markdown), and
//!   `t_h`. A step that passed at the cap (the coarsest step tried) is written `(cap)` and "bounded up to the
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
use super::tables::{Cell, Table, kind_name};
use crate::case::Case;
use crate::report::chart::{Line, Plot};
use crate::report::data::{VariantKey, num, time};
use crate::summary::methods::Methods;
use crate::summary::{FitRecord, Record, Status, Summary};

mod long_horizon;
mod other;
mod search;
mod sensitivity;
mod singularity;
mod stiffness;

use long_horizon::*;
use other::*;
use search::*;
use sensitivity::*;
use singularity::*;
use stiffness::*;

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

/// The explicit-Euler sentence: why its stable step is so small.
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
        .map(|r| &r.key.case)
        .chain(s.fits.iter().map(|f| &f.key.case))
    {
        if !out.contains(c) {
            out.push(c.clone());
        }
    }
    out
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

/// `x` in plain notation: whole above 100, else at most 3 decimals without trailing zeros.
fn plain(x: f64) -> String {
    if x.abs() >= 100.0 {
        return format!("{x:.0}");
    }
    let s = format!("{x:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

/// The stability part of case `name`; None when stability.json has nothing on it.
pub fn section(
    src: Source,
    name: &str,
    case: Option<&Case>,
    footer: &str,
) -> Option<StabilitySection> {
    let s = src.summary;
    let CaseRecords {
        fits,
        search,
        long,
        other,
        other_fits,
    } = case_records(s, name)?;
    let text = section_text(&search, &fits, &long, &other, case);
    let steps = step_tables(name, &search, case);
    // The kinds that split the plots are the study's facts (its `methods` table).
    let methods = crate::catalogue::methods_of(s);
    let split = |ps| split_figures(&methods, ps);
    let ladder = split(ladder_plots(name, &fits, &search, footer));
    let (long_figs, long_sorted) = long_horizon_figures(src, &methods, name, &long, footer, case);
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
        singularity: split(singularity_plots(name, &other, footer)),
        sensitivity: split(
            sensitivity_plot(name, &other, src.dir, footer)
                .into_iter()
                .collect(),
        ),
        other: (!other.is_empty()).then(|| other_table(name, &other)),
        other_fits: (!other_fits.is_empty()).then(|| other_fits_table(name, &other_fits)),
    })
}

/// A case's records and fits, by the part of its section that shows them.
struct CaseRecords<'a> {
    /// Every fit of the case.
    fits: Vec<&'a FitRecord>,
    /// Step-search records (a largest stable step or tolerance).
    search: Vec<&'a Record>,
    /// Long-horizon records.
    long: Vec<&'a Record>,
    /// Every other record (singularity, sensitivity, `n/a`).
    other: Vec<&'a Record>,
    /// Fits neither of the stiffness ladder nor of a growth exponent.
    other_fits: Vec<&'a FitRecord>,
}

/// The records and fits of case `name`, grouped; None when there are none.
fn case_records<'a>(s: &'a Summary, name: &str) -> Option<CaseRecords<'a>> {
    let records: Vec<&Record> = s.records.iter().filter(|r| r.key.case == name).collect();
    let fits: Vec<&FitRecord> = s.fits.iter().filter(|f| f.key.case == name).collect();
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
    Some(CaseRecords {
        fits,
        search,
        long,
        other,
        other_fits,
    })
}

/// The sentences on how to read each part the case has and what it shows.
fn section_text(
    search: &[&Record],
    fits: &[&FitRecord],
    long: &[&Record],
    other: &[&Record],
    case: Option<&Case>,
) -> Vec<String> {
    let mut text = vec![];
    if !search.is_empty() {
        push_step_search_text(&mut text, search, case);
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
        text.extend(singularity_facts(other));
    }
    if other.iter().any(|r| is_sensitivity(r)) {
        text.push(sensitivity_text(other));
    }
    text
}

/// Appends the step search's sentences: how it searched (the seam's search or a family's own),
/// how to read its tables, the Euler note when explicit Euler ran, and its facts.
fn push_step_search_text(text: &mut Vec<String>, search: &[&Record], case: Option<&Case>) {
    let seam = search
        .iter()
        .any(|r| r.metrics.contains_key("first_period"));
    text.push(if seam {
        "Step search: per scene, the largest fixed step at which each variant stays \
         stable (no typed failure such as the divergence bound, finite scores) over the \
         horizon t_h (periods of the scene's first mode; probes dt = s / n with s the \
         sample interval, from the cap s down, bisected to 5 %); adaptive variants and \
         accuracy are not searched here."
            .to_string()
    } else {
        "Step search: per scene, the largest step (or loosest tolerance) at which each \
         variant stays stable, and stays accurate, over the horizon t_h (periods of the \
         scene's fastest linearised mode; probes dt = t_h / n from the cap t_h / 20 down, \
         bisected to 5 %)."
            .to_string()
    });
    text.push(
        "In the tables, 'what limits it' is the failure at the next coarser probe (hover \
         for the full text); '(cap)' with 'bounded up to the cap' means the coarsest step \
         tried passed: a lower bound, no limit was found."
            .to_string(),
    );
    if search.iter().any(|r| r.key.integrator == "euler") {
        text.push(EULER_NOTE.to_string());
    }
    text.extend(search_facts(search, case));
}

/// The sensitivity sentence: each scene's largest growth and predictable horizon.
fn sensitivity_text(other: &[&Record]) -> String {
    let facts: Vec<String> = other
        .iter()
        .filter(|r| is_sensitivity(r))
        .filter_map(|r| {
            let g = r.metrics.get("sensitivity_growth_max").copied().flatten()?;
            let h = r.metrics.get("predictable_horizon").copied().flatten()?;
            Some(format!(
                "{} {}x (predictable to t = {} s)",
                r.key.scene,
                plain(g),
                plain(h)
            ))
        })
        .collect();
    format!(
        "Sensitivity: the largest growth of a 1e-9 initial perturbation over each scene's \
         horizon: {}.",
        if facts.is_empty() {
            "not computed".to_string()
        } else {
            facts.join(", ")
        }
    )
}

/// One step-search table per scene, the case file's scenes first and unfolded.
fn step_tables(name: &str, search: &[&Record], case: Option<&Case>) -> Vec<StepTable> {
    ordered_scenes(search.iter().map(|r| r.key.scene.as_str()), case)
        .into_iter()
        .map(|scene| {
            let rs: Vec<&Record> = search
                .iter()
                .copied()
                .filter(|r| r.key.scene == scene)
                .collect();
            StepTable {
                open: case.is_none() || in_case_file(case, &scene),
                table: step_table(name, &scene, &rs),
            }
        })
        .collect()
}

/// The figures of plots whose lines follow the run's variants, cut to at most eight lines each.
fn split_figures(methods: &Methods, ps: Vec<Plot>) -> Vec<Figure> {
    ps.into_iter()
        .flat_map(|p| super::select::split_crowded(methods, p))
        .map(|p| super::figure(&p))
        .collect()
}

/// The long-horizon figures, scene by scene, and the long-horizon records in variant order.
fn long_horizon_figures<'a>(
    src: Source,
    methods: &Methods,
    name: &str,
    long: &[&'a Record],
    footer: &str,
    case: Option<&Case>,
) -> (Vec<Figure>, Vec<&'a Record>) {
    let mut long_figs = vec![];
    let mut long_sorted = long.to_vec();
    long_sorted.sort_by_key(|r| VariantKey::of(&r.key));
    for scene in ordered_scenes(long.iter().map(|r| r.key.scene.as_str()), case) {
        let rs: Vec<&Record> = long_sorted
            .iter()
            .copied()
            .filter(|r| r.key.scene == scene)
            .collect();
        long_figs.extend(
            long_plots(methods, name, &scene, &rs, src.dir, footer)
                .iter()
                .map(super::figure),
        );
    }
    (long_figs, long_sorted)
}

#[cfg(test)]
mod tests;
