//! The report's tables as data (rendered by `html` and `markdown`):
//!
//! - failures: one row per scene, variant and failure kind, with the failing ladder values
//!   and the failure times aligned, and the message of the finest failing run;
//! - largest completed ladder step per variant and scene (the stability margin: the coarsest
//!   step, or loosest tolerance, that ran to the end; `none` when every run failed);
//! - the matrix of a scene: one row per variant at its finest ladder point (the terminal
//!   table's row) plus any gated run at another point; columns = the case's metrics, the
//!   fitted order (`not asymptotic` when its local slopes disagree), the work counters that
//!   are report columns (`integrate::Counter::column`: RHS evaluations, Newton iterations) and
//!   wall time. With gate rows, a gated cell is green (pass) or red (fail) and every other cell
//!   neutral grey; without, no colour (the page's heat map, `heatmap`, colours by value);
//! - the gate rows of the case; the `n/a` combinations grouped by reason.
use std::collections::BTreeMap;

use super::data::{self, CaseView, SceneView, VariantKey, num, step_label, time};
use crate::gate::{GateRow, Verdict};
use crate::integrate::COUNTERS;
use crate::summary::{Record, Status};

/// A cell's colour class.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tone {
    /// No colouring (no gate information).
    Plain,
    /// Gate information given, this cell is not gated.
    Neutral,
    Pass,
    Fail,
}

/// One cell.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    pub text: String,
    pub tone: Tone,
    /// The unabridged text when `text` is a shortened form (an HTML `title`, the markdown's
    /// cell text).
    pub full: Option<String>,
}

impl Cell {
    pub fn plain(text: impl Into<String>) -> Cell {
        Cell {
            text: text.into(),
            tone: Tone::Plain,
            full: None,
        }
    }

    /// A shortened text with its full form (shown on hover in the page, in full in the
    /// markdown); no full form when they are equal.
    pub fn abridged(text: impl Into<String>, full: impl Into<String>) -> Cell {
        let (text, full) = (text.into(), full.into());
        Cell {
            full: (full != text).then_some(full),
            text,
            tone: Tone::Plain,
        }
    }
}

/// A table.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// `failures`, `largest-step`, `matrix`, `gates`, `na` (the HTML `data-section`).
    pub kind: &'static str,
    pub title: String,
    /// A sentence on how to read it.
    pub note: String,
    pub header: Vec<String>,
    pub rows: Vec<Vec<Cell>>,
}

fn opt(v: Option<f64>) -> String {
    v.map(num).unwrap_or_else(|| "-".into())
}

/// The failures of a case.
pub fn failures(cv: &CaseView) -> Table {
    let mut rows = vec![];
    for s in &cv.scenes {
        for v in &s.variants {
            let mut by_kind: BTreeMap<String, Vec<&Record>> = BTreeMap::new();
            for r in v.failed() {
                let kind = r
                    .failure
                    .as_ref()
                    .map(|f| kind_name(f.kind))
                    .unwrap_or_else(|| "unknown".into());
                by_kind.entry(kind).or_default().push(r);
            }
            for (kind, rs) in by_kind {
                // `dt 1e-2, 5e-3, 2.5e-3`: the kind of ladder named once.
                let steps: Vec<String> = rs
                    .iter()
                    .enumerate()
                    .map(|(i, r)| match (i, data::step_of(r)) {
                        (0, _) => step_label(r),
                        (_, Some(v)) => num(v),
                        (_, None) => "-".into(),
                    })
                    .collect();
                let times: Vec<String> = rs
                    .iter()
                    .map(|r| r.failure.as_ref().map(|f| time(f.t)).unwrap_or_default())
                    .collect();
                let msg = rs
                    .last()
                    .and_then(|r| r.failure.as_ref())
                    .map(|f| f.message.clone())
                    .unwrap_or_default();
                rows.push(vec![
                    Cell::plain(&s.name),
                    Cell::plain(&v.key.param),
                    Cell::plain(&v.key.integrator),
                    Cell::plain(&v.key.formulation),
                    Cell::plain(steps.join(", ")),
                    Cell::plain(kind),
                    Cell::plain(times.join(", ")),
                    Cell::plain(msg),
                ]);
            }
        }
    }
    let n: usize = cv
        .scenes
        .iter()
        .flat_map(|s| &s.variants)
        .map(|v| v.failed().count())
        .sum();
    Table {
        kind: "failures",
        title: format!("{}: failed runs", cv.name),
        note: if n == 0 {
            "No run ended with a typed failure.".into()
        } else {
            format!(
                "{n} runs ended with a typed failure; one row per scene, variant and kind, the \
                 failing ladder values with their failure points t in the same order (seconds \
                 for a dynamic scene; a static scene's load factor, a cyclic protocol's \
                 increment, as the plots' axes say), and the message of the finest one."
            )
        },
        header: [
            "scene",
            "param",
            "integrator",
            "formulation",
            "step",
            "kind",
            "t",
            "message",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    }
}

/// The snake_case name of a failure kind (as in summary.json).
pub fn kind_name(k: crate::integrate::FailureKind) -> String {
    k.name().to_string()
}

/// The largest completed ladder step of every variant in every scene.
pub fn largest_step(cv: &CaseView) -> Table {
    let mut keys: Vec<VariantKey> = cv
        .scenes
        .iter()
        .flat_map(|s| s.variants.iter().map(|v| v.key.clone()))
        .collect();
    keys.sort();
    keys.dedup();
    let rows = keys
        .iter()
        .map(|k| {
            let mut row = vec![
                Cell::plain(&k.param),
                Cell::plain(&k.integrator),
                Cell::plain(&k.formulation),
            ];
            for s in &cv.scenes {
                let text = match s.variant(&k.param, &k.integrator, &k.formulation) {
                    None => "-".to_string(),
                    Some(v) => {
                        let failed = v.failed().count();
                        match v.coarsest_ok() {
                            Some(r) => {
                                let coarser = v
                                    .failed()
                                    .filter(|f| data::step_of(f) > data::step_of(r))
                                    .count();
                                if coarser > 0 {
                                    format!("{} ({coarser} coarser failed)", step_label(r))
                                } else {
                                    step_label(r)
                                }
                            }
                            None => format!("none ({failed} of {} failed)", v.runs.len()),
                        }
                    }
                };
                row.push(Cell::plain(text));
            }
            row
        })
        .collect();
    let mut header: Vec<String> = ["param", "integrator", "formulation"]
        .map(String::from)
        .to_vec();
    header.extend(cv.scenes.iter().map(|s| s.name.clone()));
    Table {
        kind: "largest-step",
        title: format!("{}: largest completed ladder step", cv.name),
        note: "Per variant and scene, the coarsest step (or loosest tolerance) of its ladder \
               that ran to the end; `none` when every run failed, `-` when it did not run."
            .into(),
        header,
        rows,
    }
}

fn same_value(a: Option<f64>, b: Option<f64>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(x), Some(y)) => (x - y).abs() <= 1e-9 * x.abs().max(y.abs()),
        _ => false,
    }
}

/// Gate rows about a record.
pub fn gates_of<'g>(r: &Record, gates: &'g [GateRow]) -> Vec<&'g GateRow> {
    gates
        .iter()
        .filter(|g| {
            g.key.case == r.key.case
                && g.key.scene == r.key.scene
                && g.key.param == r.key.param
                && g.key.integrator == r.key.integrator
                && g.key.formulation == r.key.formulation
                && same_value(g.dt, r.dt)
                && same_value(g.tol, r.tol)
        })
        .collect()
}

fn tone(gates: Option<&[GateRow]>, matched: &[&GateRow], metric: &str) -> Tone {
    let Some(_) = gates else { return Tone::Plain };
    let mine: Vec<_> = matched
        .iter()
        .filter(|g| g.metric == metric && g.verdict != Verdict::Skip)
        .collect();
    if mine.is_empty() {
        Tone::Neutral
    } else if mine.iter().any(|g| g.verdict == Verdict::Fail) {
        Tone::Fail
    } else {
        Tone::Pass
    }
}

/// The status cell's tone: by the expected-failure gates of the run (`gate::is_expect_row`),
/// plain when none gates it.
fn status_tone(matched: &[&GateRow]) -> Tone {
    let mine: Vec<_> = matched
        .iter()
        .filter(|g| crate::gate::is_expect_row(g) && g.verdict != Verdict::Skip)
        .collect();
    if mine.is_empty() {
        Tone::Plain
    } else if mine.iter().any(|g| g.verdict == Verdict::Fail) {
        Tone::Fail
    } else {
        Tone::Pass
    }
}

/// The runs of a variant in its scene's matrix: its finest ladder point (the terminal
/// table's row), then every gated run at another point.
pub fn shown<'a>(v: &data::VariantRuns<'a>, gates: Option<&[GateRow]>) -> Vec<&'a Record> {
    let mut shown: Vec<&Record> = vec![];
    if let Some(f) = v.finest() {
        shown.push(f);
    }
    if let Some(g) = gates {
        for r in &v.runs {
            if !shown.iter().any(|s| std::ptr::eq(*s, *r)) && !gates_of(r, g).is_empty() {
                shown.push(r);
            }
        }
    }
    shown
}

/// The variants x metrics matrix of a scene.
pub fn matrix(cv: &CaseView, sv: &SceneView, gates: Option<&[GateRow]>) -> Table {
    let metrics = cv.metrics();
    let mut rows = vec![];
    for v in &sv.variants {
        for r in shown(v, gates) {
            let matched = gates.map(|g| gates_of(r, g)).unwrap_or_default();
            let status = match (&r.status, &r.failure) {
                (Status::Failed, Some(f)) => {
                    format!("failed: {} at t = {}", kind_name(f.kind), time(f.t))
                }
                (Status::Failed, None) => "failed".into(),
                (Status::Ok, _) => {
                    let n = v.failed().count();
                    if n > 0 {
                        format!("ok ({n} other failed)")
                    } else {
                        "ok".into()
                    }
                }
                (Status::NotApplicable, _) => "n/a".into(),
            };
            let mut row = vec![
                Cell::plain(&v.key.param),
                Cell::plain(&v.key.integrator),
                Cell::plain(&v.key.formulation),
                Cell::plain(step_label(r)),
                Cell {
                    text: status,
                    tone: status_tone(&matched),
                    full: None,
                },
            ];
            for m in &metrics {
                let text = match r.metrics.get(m) {
                    Some(Some(x)) => num(*x),
                    Some(None) => "null".into(),
                    None => "-".into(),
                };
                row.push(Cell {
                    text,
                    tone: tone(gates, &matched, m),
                    full: None,
                });
            }
            // A fit whose local slopes disagree is not an order (`narrative::asymptotic`).
            let mut order = match v.fit {
                Some(f) if f.order.is_some() && !super::narrative::asymptotic(f) => {
                    Cell::abridged("not asymptotic", super::convergence::fit_text(Some(f)))
                }
                Some(f) => match f.order {
                    Some(p) => {
                        Cell::abridged(format!("{p:.2}"), super::convergence::fit_text(Some(f)))
                    }
                    None => Cell::plain("-"),
                },
                None => Cell::plain("-"),
            };
            if gates.is_some() {
                order.tone = Tone::Neutral;
            }
            row.push(order);
            for c in COUNTERS.iter().filter(|c| c.column) {
                row.push(Cell {
                    text: (c.get)(&r.stats).to_string(),
                    tone: tone(gates, &matched, c.name),
                    full: None,
                });
            }
            row.push(Cell {
                text: opt(r.wall_s.map(|w| w.min)),
                tone: if gates.is_some() {
                    Tone::Neutral
                } else {
                    Tone::Plain
                },
                full: None,
            });
            rows.push(row);
        }
    }
    let mut header: Vec<String> = ["param", "integrator", "formulation", "step", "status"]
        .map(String::from)
        .to_vec();
    header.extend(metrics.iter().cloned());
    header.push("order".into());
    header.extend(
        COUNTERS
            .iter()
            .filter(|c| c.column)
            .map(|c| c.name.to_string()),
    );
    header.push("wall_s".into());
    Table {
        kind: "matrix",
        title: format!("{} / {}: variants x metrics", cv.name, sv.name),
        note: format!(
            "One row per variant at its finest ladder point{}. `null`: the metric could not be \
             computed (the record says why); `-`: it does not apply. order: fitted order of {}. \
             {}",
            if gates.is_some() {
                ", plus any gated run at another point"
            } else {
                ""
            },
            cv.primary,
            if gates.is_some() {
                "Gated cells: green pass, red fail; other cells are not gated."
            } else {
                "No gate results were given: cells are not coloured."
            }
        ),
        header,
        rows,
    }
}

/// The gate rows of a case (None without gate rows).
pub fn gate_table(cv: &CaseView, gates: Option<&[GateRow]>) -> Option<Table> {
    let gates: Vec<GateRow> = gates?
        .iter()
        .filter(|g| g.key.case == cv.name)
        .cloned()
        .collect();
    let rows: Vec<Vec<Cell>> = gates
        .iter()
        .map(|g| {
            let step = match (g.dt, g.tol) {
                (Some(h), _) => format!("dt {}", num(h)),
                (None, Some(t)) => format!("tol {}", num(t)),
                _ => "-".into(),
            };
            let t = match g.verdict {
                Verdict::Pass => Tone::Pass,
                Verdict::Fail => Tone::Fail,
                Verdict::Skip => Tone::Neutral,
            };
            vec![
                Cell::plain(&g.key.scene),
                Cell::plain(&g.key.param),
                Cell::plain(&g.key.integrator),
                Cell::plain(&g.key.formulation),
                Cell::plain(step),
                Cell::plain(&g.metric),
                Cell::plain(g.outcome.clone().unwrap_or_else(|| opt(g.value))),
                Cell::plain(&g.threshold),
                Cell {
                    text: match g.verdict {
                        Verdict::Pass => "pass".into(),
                        Verdict::Fail => "FAIL".into(),
                        Verdict::Skip => "skip".into(),
                    },
                    tone: t,
                    full: None,
                },
                Cell::plain(&g.note),
            ]
        })
        .collect();
    Some(Table {
        kind: "gates",
        title: format!("{}: gates", cv.name),
        note: format!("{}.", crate::gate::verdict_line(&gates)),
        header: [
            "scene",
            "param",
            "integrator",
            "formulation",
            "step",
            "metric",
            "value",
            "threshold",
            "verdict",
            "note",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    })
}

/// The `n/a` combinations of a case, grouped by reason.
pub fn not_applicable(cv: &CaseView) -> Table {
    let mut by_reason: BTreeMap<String, (usize, Vec<String>, Vec<String>)> = BTreeMap::new();
    for s in &cv.scenes {
        for r in &s.na {
            let e = by_reason
                .entry(r.reason.clone().unwrap_or_else(|| "no reason given".into()))
                .or_default();
            e.0 += 1;
            if !e.1.contains(&r.key.param) {
                e.1.push(r.key.param.clone());
            }
            if !e.2.contains(&r.key.integrator) {
                e.2.push(r.key.integrator.clone());
            }
        }
    }
    let rows = by_reason
        .into_iter()
        .map(|(reason, (n, p, i))| {
            vec![
                Cell::plain(reason),
                Cell::plain(n.to_string()),
                Cell::plain(p.join(", ")),
                Cell::plain(i.join(", ")),
            ]
        })
        .collect();
    Table {
        kind: "na",
        title: format!("{}: not applicable", cv.name),
        note: "Combinations that do not apply (not registered, or not to this scene), counted \
               over all scenes."
            .into(),
        header: ["reason", "count", "params", "integrators"]
            .map(String::from)
            .to_vec(),
        rows,
    }
}
