//! The variants x metrics heat map of a scene: the rows of the scene's matrix (`tables::shown`:
//! each variant at its finest ladder point, plus any gated run), one column per metric of the
//! case and per cost (RHS evaluations, Newton iterations, wall time), each cell coloured by its
//! value on a log scale of its own column.
//!
//! Invariants: a column's scale is the min..max of its finite positive values over every row
//! of every scene of the case (`Scales`), so one colour means the same value in every scene
//! of the case; the colour is a sequential ramp from light and cool (best) to dark and warm
//! (worst), where best is smallest except for a metric the family declares larger-is-better
//! (`problem::Metric::higher_is_better`, the conditioning). A zero is at the best end (worst for
//! a larger-is-better metric); a negative value, or a column whose values are all equal, gets
//! the best colour of its column only when it is the column's value, and no colour when it is
//! not positive (it cannot be placed on a log scale). A failed run's cells are hatched red
//! with the failure kind; a metric that does not apply is blank grey, one that could not be
//! computed grey `null`. The gate verdict of a cell is a frame and a mark (✓ pass, ✗ fail),
//! never the fill. The HTML carries the row's registry position on its first cell (`data-k`)
//! and each fill as one of `LEVELS` classes (`css`); the page's inline script sorts by the
//! values the cells show (best first within the column's direction, then failed, null,
//! n/a); without the script the rows stay
//! in registry order. Everything is computed here, so the page is byte-identical for one
//! summary.
use std::collections::BTreeMap;

use super::data::{CaseView, SceneView, num, step_label};
use super::html::esc;
use crate::gate::{GateRow, Verdict};
use crate::integrate::COUNTERS;
use crate::summary::{Record, Status};

/// The colour ramp, best to worst: light blue, pale yellow, orange, red, dark red (its
/// lightness falls at every stop, tested).
pub const RAMP: [(u8, u8, u8); 7] = [
    (236, 244, 250),
    (255, 240, 170),
    (253, 196, 110),
    (246, 130, 70),
    (215, 48, 39),
    (150, 15, 35),
    (80, 0, 25),
];

/// The value of a cell.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A number and its badness on its column's scale (0 best .. 1 worst; None: cannot be
    /// placed on the scale).
    Num(f64, Option<f64>),
    /// The run failed with this kind.
    Failed(String),
    /// The metric could not be computed (`null` in the summary).
    Null,
    /// The metric does not apply.
    NotApplicable,
}

/// One cell.
#[derive(Debug, Clone, PartialEq)]
pub struct HeatCell {
    pub value: Value,
    pub gate: Option<Verdict>,
}

/// One row: a variant at one ladder point.
#[derive(Debug, Clone, PartialEq)]
pub struct HeatRow {
    pub param: String,
    pub integrator: String,
    pub formulation: String,
    pub step: String,
    pub cells: Vec<HeatCell>,
}

/// One column and its scale.
#[derive(Debug, Clone, PartialEq)]
pub struct HeatColumn {
    pub name: String,
    pub higher_is_better: bool,
    /// Smallest and largest finite positive value over the case.
    pub range: Option<(f64, f64)>,
}

/// A heat map.
#[derive(Debug, Clone, PartialEq)]
pub struct HeatMap {
    pub title: String,
    pub caption: String,
    pub columns: Vec<HeatColumn>,
    pub rows: Vec<HeatRow>,
}

/// The cost columns after a case's metrics: the work counters that are report columns
/// (`integrate::Counter::column`), then the wall time.
fn costs() -> impl Iterator<Item = &'static str> {
    COUNTERS
        .iter()
        .filter(|c| c.column)
        .map(|c| c.name)
        .chain(["wall_s"])
}

fn raw(r: &Record, column: &str) -> Option<Option<f64>> {
    if let Some(c) = COUNTERS.iter().find(|c| c.column && c.name == column) {
        return Some(Some((c.get)(&r.stats) as f64));
    }
    match column {
        "wall_s" => Some(r.wall_s.map(|w| w.min)),
        m => r.metrics.get(m).copied(),
    }
}

/// The columns of a case with their scales over every scene.
pub fn columns(cv: &CaseView, gates: Option<&[GateRow]>) -> Vec<HeatColumn> {
    let mut names = cv.metrics();
    names.extend(costs().map(String::from));
    let mut ranges: BTreeMap<&str, (f64, f64)> = BTreeMap::new();
    for sv in &cv.scenes {
        for v in &sv.variants {
            for r in super::tables::shown(v, gates) {
                if r.status != Status::Ok {
                    continue;
                }
                for n in &names {
                    if let Some(Some(x)) = raw(r, n)
                        && x.is_finite()
                        && x > 0.0
                    {
                        let e = ranges.entry(n.as_str()).or_insert((x, x));
                        e.0 = e.0.min(x);
                        e.1 = e.1.max(x);
                    }
                }
            }
        }
    }
    names
        .iter()
        .map(|n| HeatColumn {
            name: n.clone(),
            higher_is_better: cv
                .family
                .metrics
                .iter()
                .any(|m| m.name == n && m.higher_is_better),
            range: ranges.get(n.as_str()).copied(),
        })
        .collect()
}

/// The badness of `x` on a column's scale (0 best .. 1 worst).
pub fn badness(c: &HeatColumn, x: f64) -> Option<f64> {
    let t = if x == 0.0 {
        0.0
    } else if !(x.is_finite() && x > 0.0) {
        return None;
    } else {
        match c.range {
            Some((lo, hi)) if hi > lo => ((x.ln() - lo.ln()) / (hi.ln() - lo.ln())).clamp(0.0, 1.0),
            _ => 0.0,
        }
    };
    Some(if c.higher_is_better { 1.0 - t } else { t })
}

/// The ramp's colour at badness `t` (linear between the stops).
pub fn colour(t: f64) -> (u8, u8, u8) {
    let f = t.clamp(0.0, 1.0) * (RAMP.len() - 1) as f64;
    let i = (f.floor() as usize).min(RAMP.len() - 2);
    let w = f - i as f64;
    let (a, b) = (RAMP[i], RAMP[i + 1]);
    let mix = |p: u8, q: u8| (f64::from(p) + w * (f64::from(q) - f64::from(p))).round() as u8;
    (mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// The fills a cell can take: the ramp sampled at this many levels (a class each, `c0` best
/// .. `c24` worst, in the page's CSS: `css`), finer than the eye tells apart on a table.
pub const LEVELS: usize = 25;

/// The level of badness `t` (0 best .. `LEVELS - 1` worst).
pub fn level(t: f64) -> usize {
    (t.clamp(0.0, 1.0) * (LEVELS - 1) as f64).round() as usize
}

/// The CSS of the fill levels: each level's ramp colour, white text on the dark ones
/// (relative luminance below about 0.35).
pub fn css() -> String {
    let mut s = String::new();
    for k in 0..LEVELS {
        let (r, g, b) = colour(k as f64 / (LEVELS - 1) as f64);
        let lum = 0.2126 * f64::from(r) + 0.7152 * f64::from(g) + 0.0722 * f64::from(b);
        s.push_str(&format!(
            "table.heatmap td.c{k}{{background:#{r:02x}{g:02x}{b:02x}{}}}\n",
            if lum < 110.0 { ";color:#fff" } else { "" }
        ));
    }
    s
}

/// The heat map of a scene.
pub fn heatmap(
    cv: &CaseView,
    sv: &SceneView,
    columns: &[HeatColumn],
    gates: Option<&[GateRow]>,
) -> HeatMap {
    let mut rows = vec![];
    for v in &sv.variants {
        for r in super::tables::shown(v, gates) {
            let matched = gates
                .map(|g| super::tables::gates_of(r, g))
                .unwrap_or_default();
            let cells = columns
                .iter()
                .map(|c| {
                    let mine: Vec<_> = matched
                        .iter()
                        .filter(|g| g.metric == c.name && g.verdict != Verdict::Skip)
                        .collect();
                    let gate = if mine.is_empty() {
                        None
                    } else if mine.iter().any(|g| g.verdict == Verdict::Fail) {
                        Some(Verdict::Fail)
                    } else {
                        Some(Verdict::Pass)
                    };
                    let value = match (&r.status, &r.failure, raw(r, &c.name)) {
                        (Status::Failed, f, _) => Value::Failed(
                            f.as_ref()
                                .map(|f| super::tables::kind_name(f.kind))
                                .unwrap_or_else(|| "failed".into()),
                        ),
                        (_, _, Some(Some(x))) => Value::Num(x, badness(c, x)),
                        (_, _, Some(None)) => Value::Null,
                        (_, _, None) => Value::NotApplicable,
                    };
                    HeatCell { value, gate }
                })
                .collect();
            rows.push(HeatRow {
                param: v.key.param.clone(),
                integrator: v.key.integrator.clone(),
                formulation: v.key.formulation.clone(),
                step: step_label(r),
                cells,
            });
        }
    }
    let variants = sv.variants.len();
    let better: Vec<&str> = columns
        .iter()
        .filter(|c| c.higher_is_better)
        .map(|c| c.name.as_str())
        .collect();
    HeatMap {
        title: format!("{} / {}: heat map of variants x metrics", cv.name, sv.name),
        caption: format!(
            "{variants} variants, each at its finest ladder point{}. Colour: each column on its \
             own log scale, from the smallest to the largest positive value of that column over \
             the case's scenes (the range under its name); light blue = best, dark red = \
             worst; smaller is better{}. Hatched red: the run failed (its kind in the cell). \
             Blank grey: does not apply; grey null: could not be computed. Gated cells have a \
             frame: green with ✓ passed, black with ✗ failed. Click a column's name to sort \
             the rows best first, again for worst first; param restores registry order. The \
             table scrolls inside its frame.",
            if gates.is_some() {
                ", plus any gated run at another point"
            } else {
                ""
            },
            if better.is_empty() {
                String::new()
            } else {
                format!(", except {} where larger is better", better.join(", "))
            }
        ),
        columns: columns.to_vec(),
        rows,
    }
}

/// The HTML of a heat map (`data-section="heatmap"`), open on the page.
/// `caption`: whether to write how to read it (the first heat map of a case does; the others
/// read the same).
pub fn html(h: &HeatMap, caption: bool) -> String {
    let mut s = format!(
        "<div data-section=\"heatmap\" class=\"heat\">\n<h3>{}</h3>\n",
        esc(&h.title)
    );
    if caption {
        s.push_str(&format!("<p>{}</p>\n", esc(&h.caption)));
    }
    s.push_str("<p class=\"ramp\">best ");
    for i in 0..RAMP.len() {
        let (r, g, b) = colour(i as f64 / (RAMP.len() - 1) as f64);
        s.push_str(&format!(
            "<span style=\"background:#{r:02x}{g:02x}{b:02x}\"></span>"
        ));
    }
    s.push_str(" worst <span class=\"hfail\">failed</span> <span class=\"hna\"></span> n/a</p>\n");
    if h.rows.is_empty() {
        s.push_str("<p class=\"nodata\">no rows</p>\n</div>\n");
        return s;
    }
    s.push_str("<div class=\"tablewrap\">\n<table class=\"heatmap\">\n<thead><tr>");
    for (i, name) in ["param", "integrator", "formulation", "step"]
        .iter()
        .enumerate()
    {
        // Only `param` sorts among the label columns: back to registry order.
        if i == 0 {
            s.push_str(&format!(
                "<th data-col=\"{i}\"><button type=\"button\">{name}</button></th>"
            ));
        } else {
            s.push_str(&format!("<th data-col=\"{i}\">{name}</th>"));
        }
    }
    for (i, c) in h.columns.iter().enumerate() {
        let range = c
            .range
            .map(|(lo, hi)| format!("{}..{}", num(lo), num(hi)))
            .unwrap_or_else(|| "no values".into());
        s.push_str(&format!(
            "<th data-col=\"{}\"><button type=\"button\">{}</button><br><small>{}{}</small></th>",
            i + 4,
            esc(&c.name),
            range,
            if c.higher_is_better {
                ", larger better"
            } else {
                ""
            }
        ));
    }
    s.push_str("</tr></thead>\n<tbody>\n");
    for (i, r) in h.rows.iter().enumerate() {
        s.push_str(&format!(
            "<tr><td data-k=\"{i}\">{}</td><td>{}</td><td>{}</td><td>{}</td>",
            esc(&r.param),
            esc(&r.integrator),
            esc(&r.formulation),
            esc(&r.step)
        ));
        for c in &r.cells {
            s.push_str(&cell_html(c));
        }
        s.push_str("</tr>\n");
    }
    s.push_str("</tbody>\n</table>\n</div>\n</div>\n");
    s
}

fn cell_html(c: &HeatCell) -> String {
    let (mark, gate_class) = match c.gate {
        Some(Verdict::Pass) => ("✓ ", " gp"),
        Some(Verdict::Fail) => ("✗ ", " gf"),
        Some(Verdict::Skip) | None => ("", ""),
    };
    match &c.value {
        Value::Num(x, Some(t)) => format!(
            "<td class=\"c{}{gate_class}\">{mark}{}</td>",
            level(*t),
            num(*x)
        ),
        Value::Num(x, None) => {
            let class = gate_class.trim_start();
            let class = if class.is_empty() {
                String::new()
            } else {
                format!(" class=\"{class}\"")
            };
            format!("<td{class}>{mark}{}</td>", num(*x))
        }
        Value::Failed(kind) => format!(
            "<td class=\"hfail{gate_class}\" title=\"the run failed: {}\">{mark}{}</td>",
            esc(kind),
            esc(kind)
        ),
        Value::Null => {
            format!("<td class=\"hna{gate_class}\">{mark}null</td>")
        }
        Value::NotApplicable => {
            format!("<td class=\"hna{gate_class}\">{mark}</td>")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn col(range: Option<(f64, f64)>, higher_is_better: bool) -> HeatColumn {
        HeatColumn {
            name: "m".into(),
            higher_is_better,
            range,
        }
    }

    /// Badness is the log position in the column's range (0 at the smallest, 1 at the
    /// largest, 0.5 at the geometric mean), reversed for a larger-is-better column; zero is
    /// best and a negative value has no place.
    #[test]
    fn log_scale_per_column() {
        let c = col(Some((1e-8, 1e-2)), false);
        assert_eq!(badness(&c, 1e-8), Some(0.0));
        assert_eq!(badness(&c, 1e-2), Some(1.0));
        assert!((badness(&c, 1e-5).unwrap() - 0.5).abs() < 1e-12);
        assert_eq!(badness(&c, 0.0), Some(0.0));
        assert_eq!(badness(&c, -1.0), None);
        let up = col(Some((1e-3, 1.0)), true);
        assert_eq!(badness(&up, 1.0), Some(0.0));
        assert_eq!(badness(&up, 0.0), Some(1.0));
    }

    /// The ramp runs from light to dark: its ends are the first and last stops and the
    /// relative luminance falls at every stop.
    #[test]
    fn ramp_is_sequential() {
        assert_eq!(colour(0.0), RAMP[0]);
        assert_eq!(colour(1.0), RAMP[RAMP.len() - 1]);
        let lum = |(r, g, b): (u8, u8, u8)| {
            super::super::colour::lab(plotters::style::RGBColor(r, g, b)).l
        };
        for w in RAMP.windows(2) {
            assert!(lum(w[1]) < lum(w[0]), "{:?} then {:?}", w[0], w[1]);
        }
    }
}
