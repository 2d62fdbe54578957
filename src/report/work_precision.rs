//! Work-precision plots: a case's primary error metric (log y) against cost (log x), one line
//! per variant through its whole ladder (fixed steps coarse to fine, tolerances loose to
//! tight), in the style of Hairer & Wanner's work-precision diagrams (Solving ODEs II,
//! section IV.10). Two costs: wall time (`wall_s.min`, the minimum over the timing repeats,
//! machine-dependent) and RHS evaluations (deterministic). Lower left is better.
//!
//! A run that failed has no error: it is marked in the "failed" band at its cost (the work
//! done until the failure), so a chart that breaks down stays visible. Failed runs are not
//! timed (the suite's timing pass skips them), so in a wall-time plot their marks sit at the
//! left edge. A completed run with a
//! null primary metric (no reference) is left out.
use super::chart::{FailMark, Legend, Line, Plot};
use super::data::{CaseView, SceneView};
use super::select::{Admits, Panel, panels};
use crate::summary::{Record, Status};

/// The cost axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cost {
    Wall,
    Rhs,
}

impl Cost {
    fn of(self, r: &Record) -> Option<f64> {
        match self {
            Cost::Wall => r.wall_s.map(|w| w.min),
            Cost::Rhs => Some(r.stats.rhs_evals as f64),
        }
    }
    fn id(self) -> &'static str {
        match self {
            Cost::Wall => "wall",
            Cost::Rhs => "rhs",
        }
    }
    fn label(self) -> &'static str {
        match self {
            Cost::Wall => "wall time per run, min of repeats (s)",
            Cost::Rhs => "RHS evaluations per run",
        }
    }
}

/// The work-precision plots of a scene: each panel of each selection that draws something in
/// the scene, against wall time and RHS evaluations.
/// `timing` says how the wall times were taken (the summary's `env.timing`; None for a
/// summary written before it was recorded).
pub fn plots(cv: &CaseView, sv: &SceneView, footer: &str, timing: Option<&str>) -> Vec<Plot> {
    let mut out = vec![];
    for &sel in cv.family.figures.work_precision {
        for panel in panels(sel, cv.family) {
            if !sv.variants.iter().any(|v| panel.admits(v)) {
                continue;
            }
            for cost in [Cost::Wall, Cost::Rhs] {
                out.push(plot(cv, sv, &panel, cost, footer, timing));
            }
        }
    }
    out
}

/// How the timing pass ran, as a clause of a wall-time caption.
fn timing_clause(timing: Option<&str>) -> String {
    match timing {
        Some("serial") => "; timed one run at a time on one thread (--serial-timing)".into(),
        Some(t) if t.starts_with("parallel") => format!(
            "; timed {t}, one run per worker at a time beside the others (--serial-timing \
             times one run at a time)"
        ),
        Some(t) => format!("; timing: {t}"),
        None => String::new(),
    }
}

/// One work-precision plot.
pub fn plot(
    cv: &CaseView,
    sv: &SceneView,
    sel: &Panel,
    cost: Cost,
    footer: &str,
    timing: Option<&str>,
) -> Plot {
    let mut lines = vec![];
    let mut fails = vec![];
    for v in sv.variants.iter().filter(|v| sel.admits(v)) {
        let mut points = vec![];
        for r in &v.runs {
            match r.status {
                Status::Ok => {
                    if let (Some(x), Some(Some(y))) = (cost.of(r), r.metrics.get(&cv.primary)) {
                        points.push((x, *y));
                    }
                }
                Status::Failed => fails.push(FailMark {
                    key: v.key.clone(),
                    x: cost.of(r).unwrap_or(0.0),
                }),
                Status::NotApplicable => {}
            }
        }
        lines.push(Line {
            key: v.key.clone(),
            points,
            label: None,
            marker_every: 1,
        });
    }
    let what = match cost {
        Cost::Wall => format!(
            "against wall time (the minimum over the timing repeats; machine-dependent, never \
             gated{}; failed runs are not timed and are marked at the left edge)",
            timing_clause(timing)
        ),
        Cost::Rhs => "against right-hand-side evaluations (deterministic)".into(),
    };
    Plot {
        id: format!("{}/wp_{}_{}", sv.name, cost.id(), sel.id),
        round_off: None,
        title: format!(
            "{}/{}: {} vs {} ({})",
            cv.name,
            sv.name,
            cv.primary,
            match cost {
                Cost::Wall => "wall time",
                Cost::Rhs => "RHS evals",
            },
            sel.short
        ),
        x_label: cost.label().into(),
        y_label: super::data::error_label(cv, sv),
        x: super::axes::Scale::Log,
        y: super::axes::Scale::Log,
        lines,
        fails,
        legend: Legend::Factored,
        caption: format!(
            "Work-precision: {}{} {what}, each line through the variant's \
             whole ladder (fixed steps coarse to fine, tolerances loose to tight). {} Lower \
             left is better; marks in the red band are runs that failed, at the work they did.{}",
            cv.primary,
            super::data::aggregate(&cv.primary),
            sel.drawn(cv.family, false),
            super::data::reference_clause(sv)
        ),
        footer: footer.into(),
    }
}
