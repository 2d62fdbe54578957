//! The report (README.md, "The report"): from a summary, its series files, the case files
//! and optionally the gate's rows, writes `out/index.html` (one self-contained page, every
//! plot an inline SVG with an HTML legend, no external `src`/`href`, one small inline script:
//! `script`), `out/summary.md` (the answer for a CI log or PR comment: the gate verdict, the
//! recommendation, a line per case) and, on request (`Extras::svg_files`, `report --svg`),
//! every plot with its own legend as `out/svg/<case>/[<scene>/]<plot>.svg`.
//!
//! The figures are the case's family's (`problem::figures`: which selections of variants each
//! kind of plot draws, how to read the markers, the chart group the narrative contrasts); this
//! module composes them and names no chart or integrator itself.
//!
//! Per case: a "what this shows" paragraph computed from the numbers (`narrative`); a heat map
//! of variants x metrics per scene, open (`heatmap`); for a case with several scenes, the
//! family's measures across scenes (`scenes`); per scene, work-precision (error vs wall time
//! and vs RHS evaluations, `work_precision`), convergence with the fitted orders and their fit
//! quality (`convergence`), energy drift and constraint residual over time (`timeseries`),
//! each selection in panels of at most eight lines (`select`), and the full variants x
//! metrics matrix; then the failure table, the
//! largest completed ladder step per variant, the stability study's part when a
//! `stability.json` is given (`stability`: step-search tables, stiffness-ladder and
//! long-horizon plots), and the n/a combinations (`tables`). Colour =
//! integrator, marker = parameterization, dashed = the family's second formulation in every plot
//! (`style`; colours that share a panel differ by CIEDE2000 >= 20, `colour`); log axes carry
//! explicit decade ticks with both end labels (`axes`).
//!
//! Robustness: a missing or unreadable series file, an `n/a` record, a null metric or a case
//! absent from `cases` never stops the report: the affected plot or cell says "no data" (or
//! `null`, `-`) in place. Only I/O errors writing the output are errors. The files are built
//! in a staging folder and swapped in as a whole (`output::Staging`): a reader never sees a
//! page without its SVG files or beside an older report's.
pub mod advice;
pub mod axes;
pub mod chart;
pub mod colour;
pub mod convergence;
pub mod css;
pub mod data;
pub mod explain;
pub mod heatmap;
pub mod html;
pub mod markdown;
pub mod narrative;
pub mod scenes;
pub mod script;
pub mod select;
pub mod stability;
pub mod style;
pub mod svg_compact;
pub mod svg_page;
pub mod tables;
pub mod timeseries;
pub mod work_precision;

use std::path::{Path, PathBuf};

use crate::case::Case;
use crate::gate::{GateRow, Verdict};
use crate::summary::Summary;

pub use html::render_check;

/// How to read the plots (page and markdown header): the key of each family on the page, in
/// family-table order (the first family's when the page has no case).
fn key_text(views: &[data::CaseView]) -> String {
    let present: Vec<&str> = crate::catalogue::FAMILIES
        .iter()
        .filter(|f| views.iter().any(|v| std::ptr::eq(v.family, **f)))
        .map(|f| f.figures.key_text)
        .collect();
    if present.is_empty() {
        crate::catalogue::FAMILIES[0].figures.key_text.to_string()
    } else {
        present.join(" ")
    }
}

/// A plot on the page.
#[derive(Debug, Clone)]
pub struct Figure {
    /// Unique within the case (`<scene>/<plot>` or `<plot>`): the `data-plot` attribute and
    /// the SVG file's path under `svg/<case>/`.
    pub kind: String,
    pub title: String,
    pub caption: String,
    pub body: chart::Rendered,
}

/// One scene of a case section.
#[derive(Debug, Clone)]
pub struct SceneSection {
    pub name: String,
    pub work_precision: Vec<Figure>,
    pub convergence: Vec<Figure>,
    pub timeseries: Vec<Figure>,
    /// What the time-series plots draw (`timeseries::section_title`).
    pub timeseries_title: String,
    pub matrix: tables::Table,
    /// The matrix as a heat map (shown open on the page).
    pub heat: heatmap::HeatMap,
    /// Variants of the scene (not table rows: a gated run adds a row).
    pub variants: usize,
    /// The advice's sentence when the scene's reference is itself one of the variants.
    pub reference_note: Option<String>,
}

/// One case of the page.
#[derive(Debug, Clone)]
pub struct CaseSection {
    pub name: String,
    /// The family's `model` name (the table of contents groups cases by it).
    pub family: &'static str,
    pub title: String,
    pub narrative: Vec<String>,
    pub across: Vec<Figure>,
    pub scenes: Vec<SceneSection>,
    pub failures: tables::Table,
    pub largest: tables::Table,
    pub gates: Option<tables::Table>,
    pub na: tables::Table,
    /// The stability study's part (None: no stability.json, or nothing on this case).
    pub stability: Option<stability::StabilitySection>,
    /// One line for `summary.md`: scenes, variants, runs, failures by kind, gates.
    pub line: String,
}

/// The whole report as data (rendered by `html` and `markdown`).
#[derive(Debug, Clone)]
pub struct Page {
    /// Commit, date, rustc, CPU, OS, profile, threads.
    pub env_line: String,
    /// How to read the plots (the families' keys).
    pub key_text: String,
    pub cases: Vec<CaseSection>,
    /// The gate verdict when gate rows were given: `N passed, N failed, N skipped` (the
    /// gate's own last line) and the skipped rows' reasons with their counts.
    pub gate_summary: Option<GateSummary>,
    /// The recommendation, when given (`write_report`).
    pub advice: Option<crate::advise::Advice>,
    /// The recommendation on the physical metric of the families that declare one.
    pub physical: Option<crate::advise::Advice>,
    /// Where the run's time went, per family (the summary's `env.families`), and the run's
    /// wall time (`env.elapsed_s`).
    pub time: Option<(Vec<crate::summary::FamilyTime>, Option<f64>)>,
}

/// The gate verdict of the page (the same rows and words as `mbdbench gate`).
#[derive(Debug, Clone, PartialEq)]
pub struct GateSummary {
    pub line: String,
    pub failed: usize,
    /// (reason, rows) of the skipped rows.
    pub skipped: Vec<(String, usize)>,
    /// The verdict as Markdown (`gate::markdown`, the one renderer of `summary.md`'s block
    /// and `gate --markdown`).
    pub markdown: String,
}

impl GateSummary {
    fn of(rows: &[GateRow]) -> GateSummary {
        GateSummary {
            line: crate::gate::verdict_line(rows),
            failed: rows.iter().filter(|r| r.verdict == Verdict::Fail).count(),
            skipped: crate::gate::skipped_by_reason(rows),
            markdown: crate::gate::markdown::verdict(rows),
        }
    }
}

/// The one-line account of a case for `summary.md`.
fn case_line(cv: &data::CaseView, gate_rows: Option<&[GateRow]>) -> String {
    let mut variants: std::collections::HashSet<&data::VariantKey> = Default::default();
    let (mut runs, mut failed) = (0usize, 0usize);
    let mut kinds: std::collections::BTreeMap<&'static str, usize> = Default::default();
    for sv in &cv.scenes {
        for v in &sv.variants {
            variants.insert(&v.key);
            for r in &v.runs {
                runs += 1;
                if let Some(f) = &r.failure {
                    failed += 1;
                    *kinds.entry(f.kind.name()).or_default() += 1;
                }
            }
        }
    }
    let mut line = format!(
        "{}, {} variants, {runs} runs",
        crate::summary::count(cv.scenes.len(), "scene"),
        variants.len()
    );
    if failed > 0 {
        let k: Vec<String> = kinds.iter().map(|(k, n)| format!("{n} {k}")).collect();
        line.push_str(&format!(
            " ({failed} with a typed failure: {})",
            k.join(", ")
        ));
    }
    if let Some(rows) = gate_rows {
        let mine: Vec<GateRow> = rows
            .iter()
            .filter(|r| r.key.case == cv.name)
            .cloned()
            .collect();
        if !mine.is_empty() {
            line.push_str(&format!("; gates: {}", crate::gate::verdict_line(&mine)));
        }
    }
    line
}

/// The files written.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportFiles {
    pub index_html: PathBuf,
    pub summary_md: PathBuf,
    pub svgs: Vec<PathBuf>,
}

/// Why the report could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    /// Building or committing the output folder (`output::Staging`).
    #[error("{0}")]
    Output(String),
}

/// The environment line of a summary.
pub fn env_line(s: &Summary) -> String {
    format!(
        "commit {} | {} | {} | CPU {} | {} | {} build, {} threads",
        s.git_commit, s.created_utc, s.env.rustc, s.env.cpu, s.env.os, s.env.profile, s.env.threads
    )
}

fn footer(s: &Summary) -> String {
    format!(
        "mbdbench {} | {} | {} | {} | {}",
        s.git_commit, s.created_utc, s.env.rustc, s.env.cpu, s.env.os
    )
}

fn figure(p: &chart::Plot) -> Figure {
    let body = match chart::render(p) {
        Ok(r) => r,
        Err(e) => {
            chart::Rendered::NoData(format!("no data: the plot could not be drawn ({})", e.0))
        }
    };
    Figure {
        kind: p.id.clone(),
        title: p.title.clone(),
        caption: p.caption.clone(),
        body,
    }
}

/// Builds the page from a summary (no I/O other than reading series files), with the
/// stability study's part from `stability` when given (a case found only there gets a section
/// of its own).
pub fn build_page(
    summary: &Summary,
    series_root: &Path,
    cases: &[Case],
    gate_rows: Option<&[GateRow]>,
    stability: Option<stability::Source>,
) -> Page {
    build_page_with(summary, series_root, cases, gate_rows, stability, None)
}

/// The scenes' reference labels from the advice's notes (`advise::reference`): the scenes
/// whose reference is itself one of the variants.
fn mark_references(views: &mut [data::CaseView], advice: &crate::advise::Advice) {
    for cv in views {
        let Some(ca) = advice.cases.iter().find(|c| c.case == cv.name) else {
            continue;
        };
        for sv in &mut cv.scenes {
            sv.reference = ca
                .references
                .iter()
                .find(|n| n.scene == sv.name)
                .map(|n| n.reference.label());
        }
    }
}

/// `build_page`, with the recommendation's notes naming the references that are variants
/// beside the errors measured against them.
fn build_page_with(
    summary: &Summary,
    series_root: &Path,
    cases: &[Case],
    gate_rows: Option<&[GateRow]>,
    stability: Option<stability::Source>,
    advice: Option<&crate::advise::Advice>,
) -> Page {
    let foot = footer(summary);
    let mut views = data::case_views(summary, cases);
    if let Some(a) = advice {
        mark_references(&mut views, a);
    }
    if let Some(src) = stability {
        for name in stability::case_names(src.summary) {
            if views.iter().any(|v| v.name == name) {
                continue;
            }
            let case = cases.iter().find(|c| c.name == name);
            let family = crate::catalogue::family_of_case(
                case,
                src.summary.records.iter().filter(|r| r.key.case == name),
            );
            views.push(data::CaseView {
                title: case.map(|c| c.title.clone()).unwrap_or_default(),
                primary: case
                    .map(|c| c.primary_metric.clone())
                    .unwrap_or_else(|| family.default_primary().to_string()),
                energy_scale: case.map(|c| c.energy_scale),
                scenes: vec![],
                case,
                family,
                name,
            });
        }
    }
    // Families in the family table's order (rigid bodies first), then the case files' order.
    views.sort_by_key(|v| {
        crate::catalogue::FAMILIES
            .iter()
            .position(|f| std::ptr::eq(*f, v.family))
            .unwrap_or(usize::MAX)
    });
    let sections = views
        .iter()
        .map(|cv| {
            let columns = heatmap::columns(cv, gate_rows);
            let scenes = cv
                .scenes
                .iter()
                .map(|sv| {
                    let timeseries = timeseries::plots(cv, sv, series_root, &foot);
                    SceneSection {
                        name: sv.name.clone(),
                        work_precision: work_precision::plots(
                            cv,
                            sv,
                            &foot,
                            summary.env.timing.as_deref(),
                        )
                        .iter()
                        .map(figure)
                        .collect(),
                        convergence: convergence::plots(cv, sv, &foot)
                            .iter()
                            .map(figure)
                            .collect(),
                        timeseries_title: timeseries::section_title(cv.family, &timeseries),
                        timeseries: timeseries.iter().map(figure).collect(),
                        matrix: tables::matrix(cv, sv, gate_rows),
                        heat: heatmap::heatmap(cv, sv, &columns, gate_rows),
                        variants: sv.variants.len(),
                        reference_note: advice
                            .and_then(|a| a.cases.iter().find(|c| c.case == cv.name))
                            .and_then(|c| c.references.iter().find(|n| n.scene == sv.name))
                            .map(|n| n.text.clone()),
                    }
                })
                .collect();
            CaseSection {
                name: cv.name.clone(),
                family: cv.family.model,
                title: cv.title.clone(),
                narrative: narrative::paragraph(cv),
                across: scenes::plots(cv, &foot).iter().map(figure).collect(),
                scenes,
                failures: tables::failures(cv),
                largest: tables::largest_step(cv),
                gates: tables::gate_table(cv, gate_rows),
                na: tables::not_applicable(cv),
                stability: stability
                    .and_then(|src| stability::section(src, &cv.name, cv.case, &foot)),
                line: case_line(cv, gate_rows),
            }
        })
        .collect();
    let gate_summary = gate_rows.map(GateSummary::of);
    Page {
        env_line: env_line(summary),
        key_text: key_text(&views),
        cases: sections,
        gate_summary,
        advice: None,
        physical: None,
        time: summary
            .env
            .families
            .clone()
            .map(|f| (f, summary.env.elapsed_s)),
    }
}

/// The longest path component `safe` writes (file systems allow 255 bytes).
const MAX_COMPONENT: usize = 96;

/// A path component made of `[A-Za-z0-9_.-]` (anything else becomes `_`; `..` cannot occur),
/// at most `MAX_COMPONENT` bytes: a longer name (a case named by a hostile summary) keeps its
/// first 64 characters and a hash of the whole, so distinct names stay distinct (a 300-byte
/// case name failed the report with ENAMETOOLONG).
pub(super) fn safe(component: &str) -> String {
    let s = safe_chars(component);
    if s.len() <= MAX_COMPONENT {
        return s;
    }
    let hash = crate::digest::sha256_hex(component.as_bytes());
    format!("{}-{}", &s[..64], &hash[..16])
}

fn safe_chars(component: &str) -> String {
    let s: String = component
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() || s.chars().all(|c| c == '.') {
        "_".into()
    } else {
        s
    }
}

/// What a report adds to the summary's runs, and whether its plots are also written as files.
#[derive(Default)]
pub struct Extras<'a> {
    /// The gates' rows: they colour the matrices and add a gate table per case.
    pub gate_rows: Option<&'a [GateRow]>,
    /// The stability study: its part of each case it covers.
    pub stability: Option<stability::Source<'a>>,
    /// The recommendation (`crate::advise`): the first thing on the page and in `summary.md`.
    pub advice: Option<crate::advise::Advice>,
    /// The recommendation on the physical metric (`advice::physical_specs`), when a family
    /// declares one: its cases' blocks rank against the physical reference first.
    pub physical: Option<crate::advise::Advice>,
    /// Also write every plot as `svg/<case>/...svg` (`mbdbench report --svg`). Off by default:
    /// the page inlines every plot, and the files would double the plots' bytes in a report
    /// that must stay within its size budget.
    pub svg_files: bool,
}

/// Writes `out/index.html`, `out/summary.md` and, with `extras.svg_files`,
/// `out/svg/<case>/...svg`.
///
/// `series_root` is the directory of the series files (`<summary dir>/series`, holding
/// `<case>/<scene>/<id>.json`; the summary's directory also works).
pub fn write_report(
    summary: &Summary,
    series_root: &Path,
    cases: &[Case],
    extras: Extras,
    out: &Path,
) -> Result<ReportFiles, ReportError> {
    let mut page = build_page_with(
        summary,
        series_root,
        cases,
        extras.gate_rows,
        extras.stability,
        extras.advice.as_ref(),
    );
    // "What this shows" uses the targets the recommendation offers (never one it refuses).
    if let Some(a) = &extras.advice {
        let views = data::case_views(summary, cases);
        for c in &mut page.cases {
            let view = views.iter().find(|v| v.name == c.name);
            let advice = a.cases.iter().find(|x| x.case == c.name);
            if let (Some(cv), Some(ca)) = (view, advice) {
                let offered: Vec<f64> = ca.targets.iter().map(|t| t.target).collect();
                c.narrative = narrative::paragraph_with(cv, Some(&offered));
            }
        }
    }
    page.advice = extras.advice;
    page.physical = extras.physical;
    let mut staging = crate::output::Staging::begin(out, crate::output::Writer::Report)
        .map_err(ReportError::Output)?;
    let mut write = |rel: &str, bytes: &[u8]| -> Result<PathBuf, ReportError> {
        staging.write(rel, bytes).map_err(ReportError::Output)?;
        Ok(out.join(rel))
    };
    let mut svgs = vec![];
    for c in page.cases.iter().filter(|_| extras.svg_files) {
        let figs = c.across.iter().chain(c.scenes.iter().flat_map(|s| {
            s.work_precision
                .iter()
                .chain(&s.convergence)
                .chain(&s.timeseries)
        }));
        let figs = figs.chain(c.stability.iter().flat_map(|st| st.figures()));
        for f in figs {
            let chart::Rendered::Svg(drawn) = &f.body else {
                continue;
            };
            let svg = &drawn.file;
            let mut rel = format!("svg/{}", safe(&c.name));
            for part in f.kind.split('/') {
                rel.push('/');
                rel.push_str(&safe(part));
            }
            rel.push_str(".svg");
            svgs.push(write(&rel, svg.as_bytes())?);
        }
    }
    let summary_md = write("summary.md", markdown::render(&page).as_bytes())?;
    let index_html = write("index.html", html::render(&page).as_bytes())?;
    staging.commit().map_err(ReportError::Output)?;
    Ok(ReportFiles {
        index_html,
        summary_md,
        svgs,
    })
}

#[cfg(test)]
mod fixture;

#[cfg(test)]
mod tests;
