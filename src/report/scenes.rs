//! Across-scene plots for a case with several scenes (x = scene, a category axis): each
//! measure its family declares (`problem::figures::Measure`: the primary error, a metric, RHS
//! evaluations) for one of its selections. The rigid body's are the primary error and the
//! chart's minimum conditioning of rk4 on every parameterization, and the RHS evaluations of
//! the adaptive methods on every parameterization. On `gimbal_lock`,
//! whose scenes drive the Euler charts into or next to their singular sets, this is where
//! their breakdown shows: failures in the red band, conditioning falling toward 0, error and
//! adaptive cost rising while the other charts stay flat.
//!
//! One ladder value per plot so that scenes compare at equal step: among the ladder values
//! every drawn variant ran in every scene, the middle one (the lower median of the sorted
//! list; e.g. 5e-3 of {1e-2, 5e-3, 2.5e-3}, 1e-8 of {1e-4, ..., 1e-12}); when no value is
//! common to all, each variant uses the middle of its own common values (the caption says
//! which). Points of one scene are spread horizontally, one slot per variant of the panel in
//! registry order (so a chart's two formulations sit side by side, body left), so markers do
//! not hide each other; they are dots, never joined (the scenes are categories). Each selection is
//! drawn in its panels (`select::panels`), at most eight variants each.
use std::collections::BTreeSet;

use super::chart::{FailMark, Legend, Line, Plot};
use super::data::{self, CaseView, VariantKey};
use super::select::{Admits, Panel, panels};
use crate::problem::figures::Admit;
use crate::summary::{Record, Status};

pub use crate::problem::figures::Measure;

/// The across-scene plots the family declares (none for a case with fewer than 2 scenes).
pub fn plots(cv: &CaseView, footer: &str) -> Vec<Plot> {
    if cv.scenes.len() < 2 {
        return vec![];
    }
    cv.family
        .figures
        .across_scenes
        .iter()
        .flat_map(|&(sel, m)| panels(sel, cv.family).into_iter().map(move |p| (p, m)))
        .filter(|(p, _)| !keys(cv, p).is_empty())
        .map(|(p, m)| plot(cv, &p, m, footer))
        .collect()
}

/// Ladder values as bit patterns (exact: the values come from the same case file).
fn values(runs: &[&Record]) -> BTreeSet<u64> {
    runs.iter()
        .filter_map(|r| data::step_of(r))
        .map(f64::to_bits)
        .collect()
}

/// The middle of a set of ladder values (lower median, coarse to fine).
fn middle(set: &BTreeSet<u64>) -> Option<f64> {
    let mut v: Vec<f64> = set.iter().map(|b| f64::from_bits(*b)).collect();
    v.sort_by(|a, b| b.total_cmp(a));
    v.get(v.len().saturating_sub(1) / 2).copied()
}

/// The variants of a selection present in the case, in registry order.
fn keys(cv: &CaseView, sel: &Panel) -> Vec<VariantKey> {
    let mut ks: Vec<VariantKey> = cv
        .scenes
        .iter()
        .flat_map(|s| s.variants.iter().filter(|v| sel.admits(v)))
        .map(|v| v.key.clone())
        .collect();
    ks.sort();
    ks.dedup();
    ks
}

/// The ladder value a variant is drawn at, and whether it is the plot-wide common value.
pub fn chosen_values(cv: &CaseView, sel: &Panel) -> (Vec<(VariantKey, Option<f64>)>, bool) {
    let ks = keys(cv, sel);
    let per_variant: Vec<(VariantKey, BTreeSet<u64>)> = ks
        .into_iter()
        .map(|k| {
            let mut common: Option<BTreeSet<u64>> = None;
            for s in &cv.scenes {
                if let Some(v) = s.variant(&k.param, &k.integrator, &k.formulation) {
                    let vs = values(&v.runs);
                    common = Some(match common {
                        None => vs,
                        Some(c) => c.intersection(&vs).copied().collect(),
                    });
                }
            }
            (k, common.unwrap_or_default())
        })
        .collect();
    let mut all: Option<BTreeSet<u64>> = None;
    for (_, c) in &per_variant {
        all = Some(match all {
            None => c.clone(),
            Some(a) => a.intersection(c).copied().collect(),
        });
    }
    match all.as_ref().and_then(middle) {
        Some(v) => (
            per_variant.into_iter().map(|(k, _)| (k, Some(v))).collect(),
            true,
        ),
        None => (
            per_variant
                .into_iter()
                .map(|(k, c)| {
                    let m = middle(&c);
                    (k, m)
                })
                .collect(),
            false,
        ),
    }
}

/// One across-scene plot.
pub fn plot(cv: &CaseView, sel: &Panel, m: Measure, footer: &str) -> Plot {
    let names: Vec<String> = cv.scenes.iter().map(|s| s.name.clone()).collect();
    let (chosen, common) = chosen_values(cv, sel);
    let n_keys = chosen.len().max(1) as f64;
    let mut lines = vec![];
    let mut fails = vec![];
    for (idx, (k, value)) in chosen.iter().enumerate() {
        let Some(value) = value else { continue };
        // Spread over 70% of a category's width, one slot per variant of the panel (in
        // registry order: a chart's formulations side by side, body left).
        let jitter = 0.7 * (idx as f64 - 0.5 * (n_keys - 1.0)) / n_keys;
        let mut points = vec![];
        for (i, s) in cv.scenes.iter().enumerate() {
            let Some(r) = s
                .variant(&k.param, &k.integrator, &k.formulation)
                .and_then(|v| v.at(*value))
            else {
                continue;
            };
            let x = i as f64 + jitter;
            match (m, r.status) {
                (_, Status::Failed) => fails.push(FailMark { key: k.clone(), x }),
                (Measure::Primary, Status::Ok) => {
                    if let Some(Some(e)) = r.metrics.get(&cv.primary) {
                        points.push((x, *e));
                    }
                }
                (Measure::Metric { name, .. }, Status::Ok) => {
                    if let Some(Some(c)) = r.metrics.get(name) {
                        points.push((x, *c));
                    }
                }
                (Measure::RhsEvals, Status::Ok) => points.push((x, r.stats.rhs_evals as f64)),
                (_, Status::NotApplicable) => {}
            }
        }
        lines.push(Line {
            key: k.clone(),
            points,
            label: None,
            marker_every: 1,
        });
    }
    let mut vals: Vec<String> = chosen
        .iter()
        .filter_map(|(_, v)| *v)
        .map(data::num)
        .collect();
    vals.sort();
    vals.dedup();
    let step = if sel.sel.admit == Admit::Adaptive {
        "tol"
    } else {
        "dt"
    };
    let at = if common && !vals.is_empty() {
        format!(
            "{step} = {} for every variant (the middle of the ladder values common to all scenes)",
            vals[0]
        )
    } else {
        format!(
            "no {step} is common to every variant; each at the middle of its own common values ({})",
            vals.join(", ")
        )
    };
    let (id, y_label, what) = match m {
        Measure::Primary => (
            "scenes_error",
            super::data::with_unit(cv, &cv.primary),
            format!("{} per scene", cv.primary),
        ),
        Measure::Metric { name, id, what } => {
            (id, super::data::with_unit(cv, name), what.to_string())
        }
        Measure::RhsEvals => (
            "scenes_rhs",
            "RHS evaluations".to_string(),
            "RHS evaluations per scene (the adaptive methods' cost at equal tolerance)".to_string(),
        ),
    };
    Plot {
        id: if sel.id == sel.sel.id {
            id.to_string()
        } else {
            format!("{id}_{}", sel.id)
        },
        round_off: None,
        title: format!("{}: {} across scenes ({})", cv.name, y_label, sel.short),
        x_label: "scene".into(),
        y_label,
        x: super::axes::Scale::Category(names),
        y: super::axes::Scale::Log,
        lines,
        fails,
        legend: Legend::Factored,
        caption: format!(
            "Across scenes: {what}, {at}. {} One dot per variant and scene (scenes are \
             categories: the dots are not joined). Marks in the red band: runs that failed.",
            sel.drawn(cv.family, true)
        ),
        footer: footer.into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The middle of a ladder is its lower median, coarse to fine.
    #[test]
    fn middle_value() {
        let s: BTreeSet<u64> = [1e-2f64, 5e-3, 2.5e-3]
            .iter()
            .map(|x| x.to_bits())
            .collect();
        assert_eq!(middle(&s), Some(5e-3));
        let t: BTreeSet<u64> = [1e-4f64, 1e-6, 1e-8, 1e-10, 1e-12]
            .iter()
            .map(|x| x.to_bits())
            .collect();
        assert_eq!(middle(&t), Some(1e-8));
        let u: BTreeSet<u64> = [1e-2f64, 5e-3].iter().map(|x| x.to_bits()).collect();
        assert_eq!(middle(&u), Some(1e-2));
        assert_eq!(middle(&BTreeSet::new()), None);
    }
}
