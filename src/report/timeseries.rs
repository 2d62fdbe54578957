//! Quantities over time, from the per-run series files (values at the scene's `score_every`
//! times): the relative energy drift `|E(t) - E0| / max(|E0|, energy_scale)` (the same
//! normalisation as `energy_drift_max`, docs/schemas.md) and the chart's own constraint
//! residual (`||q|^2 - 1|`, `|R^T R - I|`, the dual quaternion's two; none for minimal charts),
//! both on a log axis against linear time; the energy balance `|K + U + D - W| / energy_scale`
//! of a family whose series' `energy` is the balance's residual (the fiber column's pulse); and a family's own column (`Series::tracks`, the
//! beam's tip deflection) on a linear axis against the reference's, drawn as an ink line.
//!
//! Which run of a variant: its coarsest *completed* ladder point (largest `dt`, loosest
//! `tol`), where drift and residual are largest and furthest above round-off; the caption
//! lists the steps used. A family that draws failed runs (`Figures::draw_failed`) draws a
//! variant without a completed run by its finest failed run, up to the failure. A symplectic or energy-momentum method shows a bounded energy error,
//! a non-symplectic one a secular drift; an additive chart without projection shows its
//! constraint residual growing. Exact zeros (e.g. the drift at t = 0) cannot be drawn on a log
//! axis and are left out. A variant with no completed run or no series file has no line and
//! is named in the caption. Both quantities are relative, so a plot whose every value is
//! below `chart::ROUND_OFF` is replaced by one sentence with the bound (`Plot::round_off`).
use std::collections::BTreeMap;
use std::path::Path;

use super::axes::Scale;
use super::chart::{Legend, Line, Plot};
use super::data::{self, CaseView, SceneView, VariantKey};
use super::select::{Admits, Panel, panels};
use crate::problem::figures::FormulationGroup;
use crate::summary::{Record, Status};

pub use crate::problem::figures::Quantity;

/// The title of a scene's time-series section: the quantities of its family's declaration that
/// `plots` draw, in order, "along the run" (over time, or over a static scene's load path).
pub fn section_title(family: &crate::problem::Family, plots: &[Plot]) -> String {
    let mut names: Vec<String> = vec![];
    for (q, _) in family.figures.timeseries {
        let (id, name) = match q {
            Quantity::Energy => ("energy", "energy drift".to_string()),
            Quantity::Balance { .. } => ("balance", "energy balance".to_string()),
            Quantity::Constraint { .. } => ("constraint", "constraint residual".to_string()),
            Quantity::Track {
                id,
                y_label,
                x: None,
                ..
            } => (*id, strip_unit(y_label)),
            Quantity::Track {
                id,
                y_label,
                x: Some((_, _, x_label)),
                ..
            } => (
                *id,
                format!("{} against {}", strip_unit(y_label), strip_unit(x_label)),
            ),
        };
        let drawn = plots.iter().any(|p| {
            p.id.rsplit_once('/')
                .map_or(p.id.as_str(), |(_, plot)| plot)
                .starts_with(&format!("{id}_"))
        });
        if drawn && !names.contains(&name) {
            names.push(name);
        }
    }
    if names.is_empty() {
        return "along the run".into();
    }
    format!("{} along the run", names.join(", "))
}

/// "over time" where the scene's `t` is time in seconds, else "along the run" (a load
/// factor, a protocol's increments: `data::t_labels`).
fn over(cv: &CaseView, scene: &str) -> &'static str {
    if data::t_labels(cv, scene).0 == crate::problem::figures::seconds_label() {
        "over time"
    } else {
        "along the run"
    }
}

/// An axis label without its unit (`u_top (m)` -> `u_top`).
fn strip_unit(label: &str) -> String {
    label
        .split_once(" (")
        .map_or(label, |(name, _)| name)
        .to_string()
}

/// The time-series plots of a scene: each quantity and panel of each selection the family
/// declares (panels that draw no variant of the scene are left out), and each group of a
/// `Quantity::Track`.
pub fn plots(cv: &CaseView, sv: &SceneView, series_root: &Path, footer: &str) -> Vec<Plot> {
    let mut out = vec![];
    for &(q, sel) in cv.family.figures.timeseries {
        if let Quantity::Track { groups, .. } = q {
            out.extend(
                groups
                    .iter()
                    .filter_map(|g| track_plot(cv, sv, series_root, q, g, footer)),
            );
            continue;
        }
        out.extend(
            panels(sel, cv.family)
                .into_iter()
                .filter(|p| sv.variants.iter().any(|v| p.admits(v)))
                .filter_map(|p| plot(cv, sv, series_root, q, &p, footer)),
        );
    }
    out
}

/// The relative energy drift of a series (`metrics::energy_drift::relative`; a case the
/// report does not know has no scale).
pub fn energy_drift(energy: &[f64], energy_scale: Option<f64>) -> Vec<f64> {
    crate::metrics::energy_drift::relative(energy, energy_scale.unwrap_or(0.0)).collect()
}

/// The run a time-series plot draws for a variant: its coarsest completed ladder point, or,
/// for a family that draws failed runs, its finest failed run that kept a series.
fn drawn<'a>(cv: &CaseView, v: &data::VariantRuns<'a>) -> Option<&'a Record> {
    v.coarsest_ok().or_else(|| {
        cv.family
            .figures
            .draw_failed
            .then(|| v.failed().filter(|r| r.series.is_some()).last())
            .flatten()
    })
}

/// One energy or constraint plot; None for a constraint plot whose every variant is on a
/// chart without a residual (a panel of minimal charts), and for a `Track` quantity (drawn by
/// `track_plot`).
pub fn plot(
    cv: &CaseView,
    sv: &SceneView,
    series_root: &Path,
    q: Quantity,
    sel: &Panel,
    footer: &str,
) -> Option<Plot> {
    let balance_label;
    let (id, name, y_label) = match q {
        Quantity::Energy => ("energy", "energy drift", "|E - E0| / max(|E0|, E_scale)"),
        Quantity::Balance { books, .. } => {
            balance_label = format!("{books} / E_scale");
            ("balance", "energy balance", balance_label.as_str())
        }
        Quantity::Constraint { .. } => ("constraint", "constraint residual", "constraint residual"),
        Quantity::Track { .. } => return None,
    };
    let found = quantity_lines(cv, sv, series_root, q, sel);
    let used: Vec<String> = found
        .steps
        .iter()
        .map(|(step, integ)| format!("{step} ({})", integ.join(", ")))
        .collect();
    if found.lines.is_empty() && found.unbooked > 0 {
        return None;
    }
    let caption = quantity_caption(cv, q, sel, &used, &found)?;
    Some(Plot {
        id: format!("{}/{id}_{}", sv.name, sel.id),
        title: format!(
            "{}/{}: {name} {} ({})",
            cv.name,
            sv.name,
            over(cv, &sv.name),
            sel.short
        ),
        x_label: data::t_labels(cv, &sv.name).0.into(),
        y_label: y_label.into(),
        x: Scale::Linear,
        y: Scale::Log,
        lines: found.lines,
        fails: vec![],
        legend: Legend::Factored,
        caption,
        footer: footer.into(),
        round_off: Some(format!("{name} ({})", sel.short)),
    })
}

/// The lines of an energy or constraint plot and what its caption says of the variants.
struct QuantityLines {
    /// One line per admitted variant with values.
    lines: Vec<Line>,
    /// The step labels of the completed runs drawn, each with its integrators.
    steps: BTreeMap<String, Vec<String>>,
    /// Variants without a drawn run or a series file, with why.
    missing: Vec<String>,
    /// The charts without a residual (a constraint plot).
    unconstrained: Vec<String>,
    /// Failed runs drawn up to their failure.
    failed: Vec<String>,
    /// Runs without energy books (a balance plot).
    unbooked: usize,
}

/// Each admitted variant's line of quantity `q` from its drawn run's series file.
fn quantity_lines(
    cv: &CaseView,
    sv: &SceneView,
    series_root: &Path,
    q: Quantity,
    sel: &Panel,
) -> QuantityLines {
    let mut lines = vec![];
    let mut steps: BTreeMap<String, Vec<String>> = BTreeMap::new();
    let mut missing: Vec<String> = vec![];
    let mut unconstrained: Vec<String> = vec![];
    let mut failed: Vec<String> = vec![];
    let mut unbooked = 0usize;
    for v in sv.variants.iter().filter(|v| sel.admits(v)) {
        let Some(r) = drawn(cv, v) else {
            missing.push(format!("{} (no completed run)", v.key.label()));
            continue;
        };
        let Some(s) = data::load_series(series_root, r) else {
            missing.push(format!("{} (no series file)", v.key.label()));
            continue;
        };
        let ys = quantity_values(q, &s, cv.energy_scale);
        if matches!(q, Quantity::Balance { .. }) && ys.iter().all(Option::is_none) {
            unbooked += 1;
            continue;
        }
        if matches!(q, Quantity::Constraint { .. }) && ys.iter().all(Option::is_none) {
            if !unconstrained.contains(&v.key.param) {
                unconstrained.push(v.key.param.clone());
            }
            continue;
        }
        let points = pairs(&s.t, &ys);
        let label = data::step_label(r);
        if r.status != Status::Ok {
            failed.push(format!("{} at {label}", v.key.label()));
        } else {
            let e = steps.entry(label).or_default();
            if !e.contains(&v.key.integrator) {
                e.push(v.key.integrator.clone());
            }
        }
        let n = points.len();
        lines.push(Line {
            key: v.key.clone(),
            points,
            label: None,
            marker_every: (n / 8).max(1),
        });
    }
    QuantityLines {
        lines,
        steps,
        missing,
        unconstrained,
        failed,
        unbooked,
    }
}

/// A series' values of quantity `q` (energy drift, balance residual or constraint residual)
/// at its times; None where there is none.
fn quantity_values(
    q: Quantity,
    s: &crate::summary::Series,
    energy_scale: Option<f64>,
) -> Vec<Option<f64>> {
    match q {
        Quantity::Energy => energy_drift(&s.energy, energy_scale)
            .into_iter()
            .map(Some)
            .collect(),
        Quantity::Balance { .. } => {
            let scale = energy_scale.filter(|x| *x > 0.0).unwrap_or(1.0);
            s.energy
                .iter()
                .map(|e| e.is_finite().then(|| e.abs() / scale))
                .collect()
        }
        _ => s.constraint.clone(),
    }
}

/// The caption of an energy or constraint plot (what it shows, the panel's variants, the
/// steps drawn, the failed, the charts without a residual, the missing); None when no
/// variant has a line, none is missing and some chart has no residual (no plot).
fn quantity_caption(
    cv: &CaseView,
    q: Quantity,
    sel: &Panel,
    used: &[String],
    found: &QuantityLines,
) -> Option<String> {
    let mut caption = match q {
        Quantity::Constraint { what } => what.to_string(),
        Quantity::Balance { what, books } => format!(
            "The energy balance {books} over the case's energy scale E_scale = {} J at the \
             score times. {what} ",
            cv.energy_scale.map(data::num).unwrap_or_else(|| "1".into())
        ),
        _ => format!(
            "Relative energy drift |E(t) - E0| / max(|E0|, {}) at the score times. ",
            cv.energy_scale.map(data::num).unwrap_or_else(|| "0".into())
        ),
    };
    caption.push_str(&sel.drawn(cv.family, false));
    caption.push_str(&format!(
        " Each variant at its coarsest completed ladder point: {}.",
        if used.is_empty() {
            "none".to_string()
        } else {
            used.join("; ")
        }
    ));
    if !found.failed.is_empty() {
        caption.push_str(&format!(
            " No completed run, drawn up to the failure at its finest step: {}.",
            found.failed.join("; ")
        ));
    }
    if found.lines.is_empty() && found.missing.is_empty() && !found.unconstrained.is_empty() {
        return None;
    }
    if !found.unconstrained.is_empty() {
        caption.push_str(&format!(
            " No residual (minimal charts): {}.",
            found.unconstrained.join(", ")
        ));
    }
    if !found.missing.is_empty() {
        caption.push_str(&format!(" No data: {}.", found.missing.join("; ")));
    }
    Some(caption)
}

/// One panel of a `Quantity::Track` plot: a line per formulation of `group` (see
/// `Quantity::Track`) and the reference; None when no formulation of the group ran here.
fn track_plot(
    cv: &CaseView,
    sv: &SceneView,
    series_root: &Path,
    q: Quantity,
    group: &FormulationGroup,
    footer: &str,
) -> Option<Plot> {
    let Quantity::Track {
        column,
        reference: r_col,
        id,
        what,
        y_label,
        x,
        ..
    } = q
    else {
        return None;
    };
    if !group.formulations.iter().any(|f| ran(sv, f)) {
        return None;
    }
    let TrackLines {
        mut lines,
        reference,
        missing,
        used,
    } = track_lines(cv, sv, series_root, group, (column, r_col, x));
    push_reference_line(&mut lines, reference);
    let caption = track_caption(what, &used, &missing);
    Some(Plot {
        id: format!("{}/{id}_{}", sv.name, group.id),
        title: match x {
            None => format!(
                "{}/{}: {column} {} ({})",
                cv.name,
                sv.name,
                over(cv, &sv.name),
                group.label
            ),
            Some((x_col, ..)) => format!(
                "{}/{}: {column} against {x_col} ({})",
                cv.name, sv.name, group.label
            ),
        },
        x_label: x.map_or(data::t_labels(cv, &sv.name).0, |x| x.2).into(),
        y_label: y_label.into(),
        x: Scale::Linear,
        y: Scale::Linear,
        ..Plot::per_line(lines, caption, footer)
    })
}

/// Whether some variant of formulation `f` ran in the scene.
fn ran(sv: &SceneView, f: &str) -> bool {
    sv.variants.iter().any(|v| v.key.formulation == f)
}

/// The columns a Track plot draws: its column, the reference's column, and the x columns
/// (`Quantity::Track`'s `column`, `reference`, `x`).
type TrackColumns = (
    &'static str,
    &'static str,
    Option<(&'static str, &'static str, &'static str)>,
);

/// The lines of a Track panel and what its caption says of its formulations.
struct TrackLines {
    /// One line per formulation drawn.
    lines: Vec<Line>,
    /// The longest reference series among the drawn runs.
    reference: Vec<(f64, f64)>,
    /// Formulations or variants without data, with why.
    missing: Vec<String>,
    /// Each drawn formulation's integrator and step (and failure).
    used: Vec<String>,
}

/// A line per formulation of `group` that ran, from its picked run's series, and the
/// reference from the longest of those series.
fn track_lines(
    cv: &CaseView,
    sv: &SceneView,
    series_root: &Path,
    group: &FormulationGroup,
    (column, r_col, x): TrackColumns,
) -> TrackLines {
    let mut lines: Vec<Line> = vec![];
    let mut reference: Vec<(f64, f64)> = vec![];
    let mut missing: Vec<String> = vec![];
    let mut used: Vec<String> = vec![];
    for f in group.formulations.iter().filter(|f| ran(sv, f)) {
        let Some((v, r)) = pick_track_run(cv, sv, f, &lines) else {
            missing.push(format!("{f} (no drawn run)"));
            continue;
        };
        let Some(s) = data::load_series(series_root, r) else {
            missing.push(format!("{} (no series file)", v.key.label()));
            continue;
        };
        let Some(track) = s.tracks.get(column) else {
            missing.push(format!("{} (no {column} in its series)", v.key.label()));
            continue;
        };
        let x_ref = x.map_or("", |x| x.1);
        let refs = track_points(
            &s,
            s.tracks.get(r_col).map_or(&[][..], |x| &x[..]),
            x,
            x_ref,
        );
        if refs.len() > reference.len() {
            reference = refs;
        }
        let how = match &r.failure {
            Some(fail) if r.status != Status::Ok => format!(
                "{}, failed at t = {}",
                data::step_label(r),
                data::time(fail.t)
            ),
            _ => data::step_label(r),
        };
        used.push(format!("{f}: {} at {how}", v.key.integrator));
        let points = track_points(&s, track, x, x.map_or("", |x| x.0));
        let n = points.len();
        lines.push(Line {
            key: v.key.clone(),
            points,
            label: Some(format!("{f} ({}, {how})", v.key.integrator)),
            marker_every: (n / 8).max(1),
        });
    }
    TrackLines {
        lines,
        reference,
        missing,
        used,
    }
}

/// The run a Track panel draws for formulation `f`: among its variants' drawn runs that kept
/// a series, a completed run on an integrator no line of the panel uses yet, else a completed
/// run, else the first.
fn pick_track_run<'a, 'b>(
    cv: &CaseView,
    sv: &'b SceneView<'a>,
    f: &str,
    lines: &[Line],
) -> Option<(&'b data::VariantRuns<'a>, &'a Record)> {
    let candidates: Vec<(&data::VariantRuns, &Record)> = sv
        .variants
        .iter()
        .filter(|v| v.key.formulation == *f)
        .filter_map(|v| Some((v, drawn(cv, v)?)))
        // Only runs whose series was kept (a family's selection may keep a subset).
        .filter(|(_, r)| r.series.is_some())
        .collect();
    // A completed run first, on an integrator no line of the panel uses yet.
    let fresh = |v: &data::VariantRuns| !lines.iter().any(|l| l.key.integrator == v.key.integrator);
    let pick = candidates
        .iter()
        .find(|(v, r)| r.status == Status::Ok && fresh(v))
        .or_else(|| candidates.iter().find(|(_, r)| r.status == Status::Ok))
        .or_else(|| candidates.first());
    pick.copied()
}

/// Points of a column: against time, or against the x column `x_col` of the same series.
fn track_points(
    s: &crate::summary::Series,
    ys: &[Option<f64>],
    x: Option<(&str, &str, &str)>,
    x_col: &str,
) -> Vec<(f64, f64)> {
    match x {
        None => pairs(&s.t, ys),
        Some(_) => match s.tracks.get(x_col) {
            Some(xs) => xs
                .iter()
                .zip(ys)
                .filter_map(|(a, b)| Some(((*a)?, (*b)?)))
                .collect(),
            None => vec![],
        },
    }
}

/// The reference line (drawn in ink, under the first line's names) when there are a reference
/// and a line.
fn push_reference_line(lines: &mut Vec<Line>, reference: Vec<(f64, f64)>) {
    if !reference.is_empty() && !lines.is_empty() {
        let n = reference.len();
        lines.push(Line {
            key: VariantKey {
                param: lines[0].key.param.clone(),
                integrator: REFERENCE.into(),
                formulation: lines[0].key.formulation.clone(),
            },
            points: reference,
            label: Some("reference".into()),
            marker_every: n.max(1),
        });
    }
}

/// A Track panel's caption: `what`, how each formulation's run was picked, the runs drawn,
/// and the missing.
fn track_caption(what: &str, used: &[String], missing: &[String]) -> String {
    let mut caption = format!(
        "{what} One line per formulation, on the first of its integrators (a different one for \
         each line where possible) at its coarsest completed ladder point; a formulation without \
         a completed run is drawn up to its failure: {}.",
        if used.is_empty() {
            "none".to_string()
        } else {
            used.join("; ")
        }
    );
    if !missing.is_empty() {
        caption.push_str(&format!(" No data: {}.", missing.join("; ")));
    }
    caption
}

/// The name a Track plot's reference line carries on the integrator axis (drawn in ink).
pub const REFERENCE: &str = "reference";

/// `(t, y)` for every `y` present.
fn pairs(t: &[f64], ys: &[Option<f64>]) -> Vec<(f64, f64)> {
    t.iter()
        .zip(ys)
        .filter_map(|(t, y)| y.map(|y| (*t, y)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The drift is relative to max(|E0|, scale) and exactly zero at t = 0.
    #[test]
    fn drift_normalisation() {
        let d = energy_drift(&[-2.0, -2.5, -1.0], Some(4.0));
        assert_eq!(d, vec![0.0, 0.125, 0.25]);
        let d = energy_drift(&[10.0, 11.0], Some(1.0));
        assert_eq!(d, vec![0.0, 0.1]);
        assert!(energy_drift(&[], None).is_empty());
    }
}
