//! The singularity ladder's part: per run setting, the rotation error, the minimum
//! conditioning and (adaptive) the RHS evaluations against the approach distance `d`, one
//! line per chart, failures in the red band; a sentence per setting on where each Euler
//! chart's error peaks.
use super::*;

pub(super) fn is_singularity(r: &Record) -> bool {
    r.metrics.contains_key("approach_distance")
}

/// The quantities of a singularity-ladder record drawn against `d`: name, axis label, value.
pub(super) type Quantity = (&'static str, &'static str, fn(&Record) -> Option<f64>);

pub(super) const SINGULARITY_QUANTITIES: [Quantity; 3] = [
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
pub(super) fn singularity_groups<'a>(
    rs: &[&'a Record],
) -> Vec<((String, String), Vec<&'a Record>)> {
    let mut groups: BTreeMap<(bool, String, u64), Vec<&Record>> = BTreeMap::new();
    for r in rs.iter().copied().filter(|r| is_singularity(r)) {
        let value = crate::report::data::step_of(r).unwrap_or(f64::NAN);
        // Coarse steps and loose tolerances first: larger values sort first.
        groups
            .entry((r.tol.is_some(), r.key.integrator.clone(), !value.to_bits()))
            .or_default()
            .push(r);
    }
    groups
        .into_values()
        .map(|mut v| {
            v.sort_by_key(|r| VariantKey::of(&r.key));
            let label = (
                v[0].key.integrator.clone(),
                crate::report::data::step_label(v[0]),
            );
            (label, v)
        })
        .collect()
}

/// The singularity-ladder plots of a case (`gimbal_lock`): per run setting, the rotation
/// error, the RHS evaluations (adaptive settings only: a fixed step's work does not depend on
/// `d`) and the chart's minimum conditioning against the approach distance `d`, log-log, one
/// line per chart; failed runs are marked at their `d`.
pub(super) fn singularity_plots(case: &str, rs: &[&Record], footer: &str) -> Vec<Plot> {
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
                let key = VariantKey::of(&r.key);
                let Some(d) = r.metrics.get("approach_distance").copied().flatten() else {
                    continue;
                };
                if r.status == Status::Failed {
                    let what = r.failure.as_ref().map_or("failed".to_string(), |f| {
                        format!("{} at t = {}", kind_name(f.kind), num(f.t))
                    });
                    failed.entry(key.param.clone()).or_default().insert(what);
                    fails.push(crate::report::chart::FailMark { key, x: d });
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
                fails,
                ..Plot::per_line(lines, caption, footer)
            });
        }
    }
    out
}

/// Sentences on the singularity ladder, from its records: per fixed-step setting, where each
/// Euler chart's error peaks and what it is at the smallest `d`.
pub(super) fn singularity_facts(rs: &[&Record]) -> Vec<String> {
    let mut out = vec![];
    for ((integrator, setting), group) in singularity_groups(rs) {
        let mut parts = vec![];
        let mut by_key: BTreeMap<VariantKey, Vec<(f64, f64)>> = BTreeMap::new();
        for r in &group {
            let d = r.metrics.get("approach_distance").copied().flatten();
            let e = r.metrics.get("rotation_error_max").copied().flatten();
            if let (Some(d), Some(e), Status::Ok) = (d, e, r.status) {
                by_key
                    .entry(VariantKey::of(&r.key))
                    .or_default()
                    .push((d, e));
            }
        }
        for (key, mut pts) in by_key {
            if !key.in_chart_group() || pts.len() < 2 {
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
