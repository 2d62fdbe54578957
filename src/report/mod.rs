//! The report (README.md, "The report"): from a summary, its series files, the case files
//! and optionally the gate's rows, writes `out/index.html` (one self-contained page, every
//! plot an inline SVG with an HTML legend, no external `src`/`href`, one small inline script:
//! `script`), `out/summary.md` (the answer for a CI log or PR comment: the gate verdict, the
//! recommendation, a line per case) and every plot with its own legend as
//! `out/svg/<case>/[<scene>/]<plot>.svg`.
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
pub mod data;
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
    let present: Vec<&str> = crate::problem::FAMILIES
        .iter()
        .filter(|f| views.iter().any(|v| std::ptr::eq(v.family, **f)))
        .map(|f| f.figures.key_text)
        .collect();
    if present.is_empty() {
        crate::problem::FAMILIES[0].figures.key_text.to_string()
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
    pub matrix: tables::Table,
    /// The matrix as a heat map (shown open on the page).
    pub heat: heatmap::HeatMap,
    /// Variants of the scene (not table rows: a gated run adds a row).
    pub variants: usize,
}

/// One case of the page.
#[derive(Debug, Clone)]
pub struct CaseSection {
    pub name: String,
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
}

/// The gate verdict of the page (the same rows and words as `mbdbench gate`).
#[derive(Debug, Clone, PartialEq)]
pub struct GateSummary {
    pub line: String,
    pub failed: usize,
    /// (reason, rows) of the skipped rows.
    pub skipped: Vec<(String, usize)>,
}

impl GateSummary {
    fn of(rows: &[GateRow]) -> GateSummary {
        GateSummary {
            line: crate::gate::verdict_line(rows),
            failed: rows.iter().filter(|r| r.verdict == Verdict::Fail).count(),
            skipped: crate::gate::skipped_by_reason(rows),
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
    let foot = footer(summary);
    let mut views = data::case_views(summary, cases);
    if let Some(src) = stability {
        for name in stability::case_names(src.summary) {
            if views.iter().any(|v| v.name == name) {
                continue;
            }
            let case = cases.iter().find(|c| c.name == name);
            let family = crate::problem::family_of_case(
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
    let sections = views
        .iter()
        .map(|cv| {
            let columns = heatmap::columns(cv, gate_rows);
            let scenes = cv
                .scenes
                .iter()
                .map(|sv| SceneSection {
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
                    timeseries: timeseries::plots(cv, sv, series_root, &foot)
                        .iter()
                        .map(figure)
                        .collect(),
                    matrix: tables::matrix(cv, sv, gate_rows),
                    heat: heatmap::heatmap(cv, sv, &columns, gate_rows),
                    variants: sv.variants.len(),
                })
                .collect();
            CaseSection {
                name: cv.name.clone(),
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
    let hash = crate::reference::sha256_hex(component.as_bytes());
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

/// Writes `out/index.html`, `out/summary.md` and `out/svg/<case>/...svg`.
///
/// `series_root` is the directory of the series files (`<summary dir>/series`, holding
/// `<case>/<scene>/<id>.json`; the summary's directory also works). `gate_rows`, when given,
/// colour the matrices and add a gate table per case. `stability`, when given, adds the
/// stability study's part to each case it covers. `advice`, when given, is the first thing
/// on the page and in `summary.md`: a table of the recommendation (`crate::advise`).
pub fn write_report(
    summary: &Summary,
    series_root: &Path,
    cases: &[Case],
    gate_rows: Option<&[GateRow]>,
    stability: Option<stability::Source>,
    advice: Option<crate::advise::Advice>,
    out: &Path,
) -> Result<ReportFiles, ReportError> {
    let mut page = build_page(summary, series_root, cases, gate_rows, stability);
    page.advice = advice;
    let mut staging = crate::output::Staging::begin(out, crate::output::Writer::Report)
        .map_err(ReportError::Output)?;
    let mut write = |rel: &str, bytes: &[u8]| -> Result<PathBuf, ReportError> {
        staging.write(rel, bytes).map_err(ReportError::Output)?;
        Ok(out.join(rel))
    };
    let mut svgs = vec![];
    for c in &page.cases {
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
mod tests {
    use super::*;
    use crate::gate::{GateRow, Verdict};

    /// The plots the page holds for a case (each scene's and the across-scene ones).
    fn plots_of(c: &CaseSection) -> usize {
        c.across.len()
            + c.scenes
                .iter()
                .map(|s| s.work_precision.len() + s.convergence.len() + s.timeseries.len())
                .sum::<usize>()
    }

    fn case_html<'a>(html: &'a str, case: &str) -> &'a str {
        let start = html
            .find(&format!("<section class=\"case\" data-case=\"{case}\""))
            .expect("case section");
        let end = html[start..].find("</section>").unwrap() + start;
        &html[start..end]
    }

    /// The page is self-contained (no src/href attribute, no script), holds one inline SVG per
    /// expected plot of the case, the tables and the environment line; every SVG is also a
    /// file; the markdown has the same tables.
    #[test]
    fn page_is_self_contained_and_complete() {
        let s = fixture::summary();
        let dir = fixture::temp_dir("complete");
        fixture::write_series(&dir.join("series"), &s, |_| false);
        let cases = crate::case::embedded().unwrap();
        let out = dir.join("report");
        let files = write_report(&s, &dir.join("series"), &cases, None, None, None, &out).unwrap();
        let html = std::fs::read_to_string(&files.index_html).unwrap();
        assert_eq!(render_check(&html), Vec::<String>::new());
        for t in html::start_tags(&html) {
            for (n, _) in &t.attrs {
                assert!(
                    n != "src" && n != "href" && !n.ends_with(":href"),
                    "<{}> {n}",
                    t.name
                );
            }
        }
        assert!(!html.contains(" src=") && !html.contains(" href="));
        let sec = case_html(&html, fixture::CASE);
        let page = build_page(&s, &dir.join("series"), &cases, None, None);
        let expected = plots_of(&page.cases[0]);
        // Plots at round-off are one sentence instead of an SVG.
        let c = &page.cases[0];
        let bodies: Vec<&chart::Rendered> = c
            .across
            .iter()
            .chain(c.scenes.iter().flat_map(|s| {
                s.work_precision
                    .iter()
                    .chain(&s.convergence)
                    .chain(&s.timeseries)
            }))
            .map(|f| &f.body)
            .collect();
        let svgs = bodies
            .iter()
            .filter(|b| matches!(b, chart::Rendered::Svg(_)))
            .count();
        let notes = bodies
            .iter()
            .filter(|b| matches!(b, chart::Rendered::Note(_)))
            .count();
        assert!(
            notes > 0,
            "the fixture's constraint residuals are at round-off"
        );
        assert_eq!(sec.matches("<p class=\"nodata roundoff\">").count(), notes);
        assert_eq!(sec.matches("<figure").count(), expected);
        assert_eq!(sec.matches("<svg").count(), svgs);
        assert_eq!(sec.matches("<svg data-lines=\"").count(), svgs);
        assert_eq!(files.svgs.len(), svgs);
        assert!(files.svgs.iter().all(|p| p.is_file()));
        // rk4 on so3 is in the Lie-group charts' panel, lgvi in the geometric methods' one.
        for f in [
            "wp_wall_rk4_group",
            "wp_rhs_so3_geometric",
            "conv_so3_explicit",
        ] {
            assert!(
                out.join(format!("svg/nine_spring/large/{f}.svg")).is_file(),
                "{f}: {:?}",
                files.svgs
            );
        }
        // No panel draws more than MAX_LINES lines, and the page says how many it draws.
        let figs = page.cases[0].scenes.iter().flat_map(|s| {
            s.work_precision
                .iter()
                .chain(&s.convergence)
                .chain(&s.timeseries)
        });
        for f in figs {
            if let chart::Rendered::Svg(d) = &f.body {
                assert!(d.lines <= select::MAX_LINES, "{}: {}", f.kind, d.lines);
                assert!(sec.contains(&format!("<svg data-lines=\"{}\"", d.lines)));
            }
        }
        // The heat maps are open (outside any <details>), one per scene.
        let heat = sec.find("data-section=\"heatmaps\"").expect("heat maps");
        assert!(!sec[..heat].contains("<details"));
        assert_eq!(
            sec.matches("<table class=\"heatmap\">").count(),
            fixture::SCENES.len()
        );
        // No literal markdown reaches the page.
        for md in ["**", "`", "]("] {
            assert!(!html.contains(md), "{md} in the page");
        }
        for kind in html::REQUIRED_SECTIONS
            .iter()
            .chain(&["na", "across-scenes"])
        {
            assert!(sec.contains(&format!("data-section=\"{kind}\"")), "{kind}");
        }
        let env = env_line(&s);
        for part in [
            "abc1234",
            "2026-01-02T03:04:05Z",
            "rustc 1.95.0",
            "Test CPU",
            "Test OS",
        ] {
            assert!(env.contains(part), "{part}");
        }
        assert!(
            sec.contains(&html::esc(&env)),
            "env line in the case section"
        );
        let md = std::fs::read_to_string(&files.summary_md).unwrap();
        assert!(md.contains(&env));
        for title in [
            "nine_spring: failed runs",
            "nine_spring: largest completed ladder step",
            "nine_spring / two_angles: variants x metrics",
            "nine_spring / large: variants x metrics",
            "nine_spring: not applicable",
        ] {
            assert!(html.contains(title), "{title}");
        }
        // summary.md has a line per case (its failures by kind) and points to the page.
        assert!(
            md.contains("39 runs (3 with a typed failure: 3 singular_chart)"),
            "{md}"
        );
        assert!(md.contains("index.html#case-nine_spring"), "{md}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// Failed and n/a records, missing series files and a case file that was not given still
    /// give a complete page: the time series say "no data" in place.
    #[test]
    fn failed_na_and_missing_series_render() {
        let s = fixture::summary();
        let dir = fixture::temp_dir("missing");
        let out = dir.join("report");
        // No series at all, and no case files.
        let files = write_report(&s, &dir.join("nowhere"), &[], None, None, None, &out).unwrap();
        let html = std::fs::read_to_string(&files.index_html).unwrap();
        assert_eq!(render_check(&html), Vec::<String>::new());
        let sec = case_html(&html, fixture::CASE);
        let page = build_page(&s, &dir.join("nowhere"), &[], None, None);
        let timeseries: usize = page.cases[0]
            .scenes
            .iter()
            .map(|s| s.timeseries.len())
            .sum();
        assert!(
            timeseries >= 2 * fixture::SCENES.len(),
            "energy and constraint per scene"
        );
        assert_eq!(sec.matches("<figure").count(), plots_of(&page.cases[0]));
        assert_eq!(sec.matches("<p class=\"nodata\">").count(), timeseries);
        assert_eq!(
            sec.matches("<svg").count(),
            plots_of(&page.cases[0]) - timeseries
        );
        assert!(sec.contains("no series file"));
        assert!(sec.contains("written on SO(3) x R^3 (chart so3) only"));
        // Only one scene's series present: that scene's time series are drawn.
        fixture::write_series(&dir.join("series"), &s, |r| r.key.scene == "large");
        let files = write_report(&s, &dir.join("series"), &[], None, None, None, &out).unwrap();
        let html = std::fs::read_to_string(&files.index_html).unwrap();
        let page = build_page(&s, &dir.join("series"), &[], None, None);
        // The predicate names the records whose series are left out: those of `large`.
        let large = page.cases[0]
            .scenes
            .iter()
            .find(|s| s.name == "large")
            .unwrap();
        let nodata = |f: &Figure| matches!(f.body, chart::Rendered::NoData(_));
        assert!(
            large.timeseries.iter().all(nodata),
            "{:?}",
            large
                .timeseries
                .iter()
                .map(|f| (&f.kind, &f.body))
                .filter(|(_, b)| !matches!(b, chart::Rendered::Svg(_)))
                .collect::<Vec<_>>()
        );
        let all_nodata = page.cases[0]
            .scenes
            .iter()
            .flat_map(|s| {
                s.work_precision
                    .iter()
                    .chain(&s.convergence)
                    .chain(&s.timeseries)
            })
            .filter(|f| nodata(f))
            .count();
        assert_eq!(
            case_html(&html, fixture::CASE)
                .matches("<p class=\"nodata\">")
                .count(),
            all_nodata
        );
        // An empty summary.
        let mut empty = s.clone();
        empty.records.clear();
        empty.fits.clear();
        let files = write_report(&empty, &dir.join("series"), &[], None, None, None, &out).unwrap();
        let html = std::fs::read_to_string(&files.index_html).unwrap();
        assert_eq!(render_check(&html), Vec::<String>::new());
        assert!(html.contains("none (no data)"));
        let _ = std::fs::remove_dir_all(&dir);
    }

    fn gate(scene: &str, dt: f64, metric: &str, verdict: Verdict) -> GateRow {
        GateRow {
            key: crate::summary::RunKey::new(fixture::CASE, scene, "so3", "rk4", "body"),
            dt: Some(dt),
            tol: None,
            metric: metric.into(),
            value: Some(1.0),
            outcome: None,
            threshold: "<= 1".into(),
            verdict,
            note: String::new(),
        }
    }

    /// An expected-failure gate row shows in the case's gate table (HTML and markdown) as
    /// its label, outcome and bound, and colours the gated run's status cell.
    #[test]
    fn expect_gate_renders() {
        let s = fixture::summary();
        let dir = fixture::temp_dir("expect-gates");
        let expect = |dt: f64, outcome: &str, verdict: Verdict| GateRow {
            key: crate::summary::RunKey::new(fixture::CASE, "large", "euler_zxz", "rk4", "body"),
            dt: Some(dt),
            tol: None,
            metric: "expect failed (singular_chart)".into(),
            value: None,
            outcome: Some(outcome.into()),
            threshold: "before 0.55 s".into(),
            verdict,
            note: String::new(),
        };
        let mut late = expect(1e-2, "singular_chart at t = 0.6", Verdict::Fail);
        late.note =
            "singular_chart at t = 0.6, too late: expected singular_chart before 0.55 s".into();
        let rows = vec![
            expect(2e-2, "singular_chart at t = 0.5", Verdict::Pass),
            late,
        ];
        let page = build_page(&s, &dir, &[], Some(&rows), None);
        let c = &page.cases[0];
        let g = c.gates.as_ref().unwrap();
        let col = |name: &str| g.header.iter().position(|h| h == name).unwrap();
        assert_eq!(g.rows.len(), 2);
        assert_eq!(
            g.rows[0][col("metric")].text,
            "expect failed (singular_chart)"
        );
        assert_eq!(g.rows[0][col("value")].text, "singular_chart at t = 0.5");
        assert_eq!(g.rows[0][col("threshold")].text, "before 0.55 s");
        let large = c.scenes.iter().find(|sc| sc.name == "large").unwrap();
        let m = &large.matrix;
        let status = m.header.iter().position(|h| h == "status").unwrap();
        let tone = |step: &str| {
            m.rows
                .iter()
                .find(|r| r[0].text == "euler_zxz" && r[3].text == step)
                .map(|r| r[status].tone)
        };
        assert_eq!(tone("dt 2e-2"), Some(tables::Tone::Pass));
        assert_eq!(tone("dt 1e-2"), Some(tables::Tone::Fail));
        let html = html::render(&page);
        for part in [
            "expect failed (singular_chart)",
            "singular_chart at t = 0.5",
            "before 0.55 s",
        ] {
            assert!(html.contains(part), "{part} not in the page");
        }
        let md = markdown::render(&page);
        assert!(
            md.contains("singular_chart at t = 0.6") && md.contains("Gates: 1 passed, 1 failed"),
            "{md}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// Gated cells are coloured by verdict (a gated run at a coarser step gets its own row),
    /// other cells neutral; the gate table and the markdown marks agree.
    #[test]
    fn gate_colours() {
        let s = fixture::summary();
        let dir = fixture::temp_dir("gates");
        let rows = vec![
            gate("two_angles", 5e-3, fixture::PRIMARY, Verdict::Pass),
            gate("two_angles", 2e-2, "energy_drift_max", Verdict::Fail),
        ];
        let page = build_page(&s, &dir, &[], Some(&rows), None);
        let c = &page.cases[0];
        // Without the case file, scenes sort by name: large, two_angles.
        assert_eq!(c.scenes[1].name, "two_angles");
        let m = &c.scenes[1].matrix;
        let so3_rk4_body: Vec<&Vec<tables::Cell>> = m
            .rows
            .iter()
            .filter(|r| r[0].text == "so3" && r[1].text == "rk4" && r[2].text == "body")
            .collect();
        assert_eq!(
            so3_rk4_body.len(),
            2,
            "finest row plus the gated coarse row"
        );
        let col = |name: &str| m.header.iter().position(|h| h == name).unwrap();
        assert_eq!(so3_rk4_body[0][3].text, "dt 5e-3");
        assert_eq!(
            so3_rk4_body[0][col(fixture::PRIMARY)].tone,
            tables::Tone::Pass
        );
        assert_eq!(
            so3_rk4_body[0][col("energy_drift_max")].tone,
            tables::Tone::Neutral
        );
        assert_eq!(so3_rk4_body[1][3].text, "dt 2e-2");
        assert_eq!(
            so3_rk4_body[1][col("energy_drift_max")].tone,
            tables::Tone::Fail
        );
        let g = page.gate_summary.as_ref().unwrap();
        assert_eq!(g.line, "1 passed, 1 failed, 0 skipped");
        assert_eq!(g.failed, 1);
        let g = c.gates.as_ref().unwrap();
        assert_eq!(g.rows.len(), 2);
        let html = html::render(&page);
        assert!(html.contains("<td class=\"pass\">") && html.contains("<td class=\"fail\">"));
        let md = markdown::render(&page);
        // summary.md lists the failing rows only.
        assert!(
            md.contains(": failing gates") && md.contains("| FAIL |"),
            "{md}"
        );
        assert!(!md.contains("| pass |"), "{md}");
        assert!(md.contains("Gates: 1 passed, 1 failed, 0 skipped."));
        // Without gate rows nothing is coloured.
        let plain = build_page(&s, &dir, &[], None, None);
        assert!(
            plain.cases[0].scenes[0]
                .matrix
                .rows
                .iter()
                .flatten()
                .all(|c| c.tone == tables::Tone::Plain)
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// Path components are plain and short: a 300-byte case name becomes 64 characters and a
    /// hash (two such names stay distinct), so the report of a summary naming it is written.
    #[test]
    fn long_names_are_shortened() {
        let (a, b) = ("x".repeat(300), format!("{}y", "x".repeat(299)));
        assert!(safe(&a).len() <= MAX_COMPONENT && safe(&a) != safe(&b));
        assert_eq!(safe("two_angles"), "two_angles");
        assert_eq!(safe(".."), "_");
        let dir = std::env::temp_dir().join(format!("mbdbench-long-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let mut s = fixture::summary();
        for r in &mut s.records {
            r.key.case = a.clone();
        }
        let out = dir.join("out");
        let files = write_report(&s, &dir.join("series"), &[], None, None, None, &out).unwrap();
        assert!(!files.svgs.is_empty());
        assert!(files.svgs.iter().all(|p| p.exists()));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
