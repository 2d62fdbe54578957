//! What `advise` lists to avoid, from the runs of a case's non-control scenes: typed
//! failures (one entry per variant, scene and kind, with how many ladder points failed),
//! charts whose conditioning fell below `MIN_CONDITIONING` (one entry per chart and scene, at
//! its lowest), and variants whose energy drift at their finest completed ladder point exceeds
//! the case's `advise_max_energy_drift`, and variants whose observed order is not one: an
//! order fit whose local slopes spread by more than `metrics::order::ASYMPTOTIC_SPREAD`
//! (the ladder straddles a change of regime; the report prints "not asymptotic" instead of
//! the order).
use std::collections::BTreeMap;

use super::{Avoid, CaseSpec, MIN_CONDITIONING, SceneSpec};
use crate::catalogue::{Ordered, report_order};
use crate::metrics::order::{ASYMPTOTIC_SPREAD, slope_spread};
use crate::summary::{FitRecord, Record, Status};

/// The avoid list of one case (failures, then conditioning, then drift, then order fits;
/// each in the family's variant order).
pub(super) fn avoid(
    spec: &CaseSpec,
    scenes: &[&SceneSpec],
    records: &[&Record],
    fits: &[&FitRecord],
) -> Vec<Avoid> {
    let in_scope = |r: &&&Record| scenes.iter().any(|s| s.name == r.key.scene);
    let mut out = vec![];
    // Failures: (variant, scene, kind) -> (count, first time).
    let mut failures: BTreeMap<([usize; 3], String, String), (usize, &Record)> = BTreeMap::new();
    for r in records.iter().filter(in_scope) {
        if r.status != Status::Failed {
            continue;
        }
        let kind = r
            .failure
            .as_ref()
            .map_or("failed", |f| f.kind.name())
            .to_string();
        failures
            .entry((r.variant_order(), r.key.scene.clone(), kind))
            .or_insert((0, r))
            .0 += 1;
    }
    for ((_, scene, kind), (n, r)) in failures {
        let total = records
            .iter()
            .filter(|o| o.key.scene == scene && o.key.same_variant(&r.key))
            .count();
        out.push(Avoid {
            param: r.key.param.clone(),
            integrator: Some(r.key.integrator.clone()),
            formulation: Some(r.key.formulation.clone()),
            scene,
            reason: format!("{kind} at {n} of its {total} ladder points"),
        });
    }
    // Conditioning: (chart order, scene) -> lowest.
    let mut worst: BTreeMap<(usize, String), (f64, &Record)> = BTreeMap::new();
    for r in records.iter().filter(in_scope) {
        let Some(Some(c)) = r.metrics.get("conditioning_min") else {
            continue;
        };
        if *c < MIN_CONDITIONING {
            let e = worst
                .entry((r.variant_order()[0], r.key.scene.clone()))
                .or_insert((*c, r));
            if *c < e.0 {
                *e = (*c, r);
            }
        }
    }
    for ((_, scene), (c, r)) in worst {
        out.push(Avoid {
            param: r.key.param.clone(),
            integrator: None,
            formulation: None,
            scene,
            reason: format!(
                "the chart's conditioning fell to {c:.1e} (below {MIN_CONDITIONING:e}): next to \
                 its singular set"
            ),
        });
    }
    // Drift at the finest completed point: records are in report order (coarse first).
    let mut finest: BTreeMap<([usize; 3], String), &Record> = BTreeMap::new();
    for r in records.iter().filter(in_scope) {
        if r.status == Status::Ok {
            let k = (r.variant_order(), r.key.scene.clone());
            let finer = finest
                .get(&k)
                .is_none_or(|f| report_order(r) > report_order(f));
            if finer {
                finest.insert(k, r);
            }
        }
    }
    for ((_, scene), r) in finest {
        let Some(Some(d)) = r.metrics.get("energy_drift_max") else {
            continue;
        };
        if *d > spec.max_energy_drift {
            out.push(Avoid {
                param: r.key.param.clone(),
                integrator: Some(r.key.integrator.clone()),
                formulation: Some(r.key.formulation.clone()),
                scene,
                reason: format!(
                    "energy drift {d:.1e} at its finest completed point ({}), above {:e}",
                    setting(r),
                    spec.max_energy_drift
                ),
            });
        }
    }
    for f in fits {
        if !scenes.iter().any(|s| s.name == f.key.scene) || f.order.is_none() {
            continue;
        }
        if let Some((spread, lo, hi)) = slope_spread(&f.points)
            && spread > ASYMPTOTIC_SPREAD
        {
            out.push(Avoid {
                param: f.key.param.clone(),
                integrator: Some(f.key.integrator.clone()),
                formulation: Some(f.key.formulation.clone()),
                scene: f.key.scene.clone(),
                reason: format!(
                    "its {} ladder is not asymptotic: local slopes {lo:.2} to {hi:.2} (spread \
                     above {ASYMPTOTIC_SPREAD}), so its fitted order is not an order",
                    f.metric
                ),
            });
        }
    }
    out
}

fn setting(r: &Record) -> String {
    match (r.dt, r.tol) {
        (Some(dt), _) => format!("dt = {dt:e}"),
        (None, Some(tol)) => format!("tol = {tol:e}"),
        _ => "-".into(),
    }
}
