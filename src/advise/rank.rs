//! The ranking of `advise` (see `mod.rs` for the rules): which targets a case is offered,
//! each variant's cheapest settings reaching a target on every non-control scene, and the
//! winner, runner-up and wall-time winner among them.
use std::collections::BTreeMap;

use super::TargetAdvice;
use super::{By, CaseSpec, MIN_TIMED_S, Pick, SceneSpec, Setting, Skipped, TIE_REL};
use crate::catalogue::Ordered;
use crate::summary::{Record, Status};

/// A variant's runs grouped by scene, keyed by the family's variant order.
type ByVariant<'a> = BTreeMap<[usize; 3], BTreeMap<&'a str, Vec<&'a Record>>>;

fn group<'a>(records: &[&'a Record]) -> ByVariant<'a> {
    let mut out: ByVariant = BTreeMap::new();
    for r in records {
        out.entry(r.variant_order())
            .or_default()
            .entry(r.key.scene.as_str())
            .or_default()
            .push(r);
    }
    out
}

/// The work of a run: RHS evaluations + Newton iterations.
pub(super) fn work(r: &Record) -> u64 {
    r.stats.rhs_evals.saturating_add(r.stats.newton_iters)
}

/// The offered targets of a case (each with its ranking) and the skipped ones.
pub(super) fn targets(
    spec: &CaseSpec,
    scenes: &[&SceneSpec],
    wanted: &[f64],
    records: &[&Record],
    by: By,
) -> (Vec<TargetAdvice>, Vec<Skipped>) {
    let floor = scenes.iter().filter_map(|s| s.claim).fold(0.0f64, f64::max);
    let groups = group(records);
    let mut offered = vec![];
    let mut skipped = vec![];
    for &target in wanted {
        if target < spec.claim_margin * floor {
            skipped.push(Skipped {
                target,
                reason: format!(
                    "below {}x the references' {} ({floor:.1e} {}): \
                     errors there measure the reference",
                    spec.claim_margin, spec.claim_name, spec.unit
                ),
            });
            continue;
        }
        offered.push(rank(target, &spec.metric, scenes, &groups, by));
    }
    (offered, skipped)
}

/// A variant's cheapest settings reaching `target` on every scene, with the shortest median
/// wall time among the chosen runs (None: one was not timed), or None.
fn pick(
    target: f64,
    metric: &str,
    scenes: &[&SceneSpec],
    runs: &BTreeMap<&str, Vec<&Record>>,
) -> Option<(Pick, Option<f64>)> {
    let mut chosen: Vec<&Record> = vec![];
    for s in scenes {
        let best = runs
            .get(s.name.as_str())?
            .iter()
            .filter(|r| r.status == Status::Ok)
            .filter(|r| {
                r.metrics
                    .get(metric)
                    .copied()
                    .flatten()
                    .is_some_and(|e| e <= target)
            })
            .min_by_key(|r| work(r))?;
        chosen.push(best);
    }
    let first = chosen.first()?;
    let mut settings = BTreeMap::new();
    let mut wall = Some(0.0);
    for r in &chosen {
        let setting = match (r.dt, r.tol) {
            (Some(dt), _) => Setting::Dt(dt),
            (None, Some(tol)) => Setting::Tol(tol),
            (None, None) => return None,
        };
        settings.insert(r.key.scene.clone(), setting);
        wall = match (wall, r.wall_s) {
            (Some(a), Some(w)) => Some(a + w.median),
            _ => None,
        };
    }
    let shortest = chosen
        .iter()
        .map(|r| r.wall_s.map(|w| w.median))
        .try_fold(f64::INFINITY, |m, w| w.map(|w| m.min(w)));
    let p = Pick {
        param: first.key.param.clone(),
        integrator: first.key.integrator.clone(),
        formulation: first.key.formulation.clone(),
        settings,
        cost: chosen.iter().map(|r| work(r)).sum(),
        rhs_evals: chosen.iter().map(|r| r.stats.rhs_evals).sum(),
        newton_iters: chosen.iter().map(|r| r.stats.newton_iters).sum(),
        wall_s: wall,
    };
    Some((p, shortest))
}

/// Winner, runner-up and wall-time winner at one target.
fn rank(
    target: f64,
    metric: &str,
    scenes: &[&SceneSpec],
    groups: &ByVariant,
    by: By,
) -> TargetAdvice {
    // In variant order, so that a stable sort keeps ties in the family's order.
    let mut picks: Vec<(Pick, Option<f64>)> = groups
        .values()
        .filter_map(|runs| pick(target, metric, scenes, runs))
        .collect();
    let by_work = |p: &Pick| p.cost as f64;
    let by_wall = |p: &Pick| p.wall_s.unwrap_or(f64::INFINITY);
    let primary: &dyn Fn(&Pick) -> f64 = match by {
        By::Work => &by_work,
        By::Time => &by_wall,
    };
    picks.sort_by(|a, b| primary(&a.0).total_cmp(&primary(&b.0)));
    let mut it = picks.iter();
    let first = it.next();
    let winner = first.map(|p| p.0.clone());
    let runner_up = it.next().map(|p| p.0.clone());
    let gap = match (&winner, &runner_up) {
        (Some(w), Some(r)) if primary(w) > 0.0 => Some(primary(r) / primary(w)),
        _ => None,
    };
    let tie: Vec<Pick> = match &winner {
        Some(w) => picks
            .iter()
            .skip(1)
            .map(|p| &p.0)
            .take_while(|p| primary(p) <= (1.0 + TIE_REL) * primary(w))
            .cloned()
            .collect(),
        None => vec![],
    };
    let mut note = None;
    if winner.is_none() {
        note = Some(if scenes.is_empty() {
            "no scene to advise on (only control scenes in the summary)".to_string()
        } else {
            format!(
                "no variant reaches {target:e} on every scene ({})",
                scenes
                    .iter()
                    .map(|s| s.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        });
    }
    // The second ranking, by wall time, only where the work winner's runs are long enough
    // for the timer (and each of them was timed).
    let timed = first.is_some_and(|p| p.1.is_some_and(|t| t > MIN_TIMED_S));
    let by_time = if by == By::Work && timed {
        let mut t: Vec<&Pick> = picks
            .iter()
            .map(|p| &p.0)
            .filter(|p| p.wall_s.is_some())
            .collect();
        t.sort_by(|a, b| by_wall(a).total_cmp(&by_wall(b)));
        t.first().map(|p| (*p).clone())
    } else {
        None
    };
    if winner.is_some() && by == By::Work && !timed {
        note = Some(format!(
            "no ranking by wall time: a run of the winner took {} ms or less (or was not \
             timed), where timer noise decides",
            MIN_TIMED_S * 1e3
        ));
    }
    TargetAdvice {
        target,
        winner,
        runner_up,
        gap,
        tie,
        by_time,
        note,
    }
}
