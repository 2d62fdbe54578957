//! `skip`: where a ladder stops. A ladder runs in sequence, coarsest step (loosest tolerance)
//! first, and before each point after the first the rules below look at what is known then:
//! the same ladder's earlier points, and the committed cost table (`crate::cost`), never
//! another variant's results. A point they stop, and every finer one, becomes an `n/a`
//! record with its step and the reason, so a reader sees what was not run and why.
//!
//! The rules, in the order they are asked:
//!
//! 1. **The reference's floor.** An earlier point of the ladder ended `ok` with its primary
//!    error at or below the reference's accuracy claim for its formulation: a finer point
//!    would measure the reference, not the method (`metrics::order` leaves such points out of
//!    an order fit for the same reason, below 100 times the claim), and would cost more for
//!    an answer no target above the floor can use.
//! 2. **A first-order method's order is established.** A method of order 1 (fixed step)
//!    whose last [`FIT_POINTS`] points all ended `ok` with errors inside the order fit's
//!    window (`[100 claim, 1e-2]`, `metrics::order::fit`) and whose local slopes between
//!    them all lie within [`ORDER1_SLACK`] of 1 (the error halved with the step, as the
//!    order predicts): those points fit its order, and each finer point costs as much as all
//!    the coarser ones together for an error the fit already predicts.
//! 3. **The cost cap.** The point's predicted wall time exceeds the cap (`Rules::cap_s`,
//!    `mbdbench run --max-run-s`): predicted from the previous point's work scaled to this
//!    point's step count (fixed step: `steps = T / dt` exactly, the other counters in
//!    proportion; adaptive: the previous point's work times `(tol_prev / tol)^(1/p)` for
//!    order `p`, the growth of a step-size controller's step count) and the cost table's
//!    coefficients for the scene. A ladder's first point always runs: nothing of that ladder
//!    is known before it.
//!
//! Invariants: the decisions depend on the ladder's own earlier records only, so a run's
//! records are the same on any machine and in any shard that keeps the ladder whole (the
//! cost rule excepted, which depends on the committed table, the same on every machine);
//! an `n/a` record is never scored, timed or fitted.
use crate::cost::SceneModel;
use crate::metrics::order;
use crate::problem::{Problem, Variant};
use crate::summary::{Record, Status};

/// Points a fit of order needs (`metrics::order::fit` gives no order with fewer).
pub const FIT_POINTS: usize = 3;

/// How far a first-order method's local slopes may lie from 1 for its order to count as
/// established (rule 2): the observed order of the points it keeps then lies within this of
/// the order the dropped points would give, if they continue the same line.
pub const ORDER1_SLACK: f64 = 0.02;

/// The default cost cap of one run, s (rule 3; `mbdbench run --max-run-s`): above the
/// dearest run of the catalogue on the machine of the cost table (the main job at 771e124,
/// alone on 2 cores: `rc_cyclic_c02` `so3/newton_disp/disp_based_n8` 2.3 s, explicit Euler at
/// 6.25e-6 s over 100 s of `free_body/gni` up to 1.4 s), so that it guards against a ladder
/// point that would hold a run for minutes rather than shortening the catalogue's ladders.
pub const DEFAULT_CAP_S: f64 = 60.0;

/// What the rules need besides the ladder.
#[derive(Debug, Clone, Copy)]
pub struct Rules<'a> {
    /// The cost cap, s (`f64::INFINITY`: none).
    pub cap_s: f64,
    /// The cost table's model of the scene (None: rule 3 does not apply).
    pub cost: Option<SceneModel<'a>>,
}

/// Why the point at `value` of `v`'s ladder on `p` is not run, given the ladder's earlier
/// points `earlier` (coarse to fine, as run); None to run it.
pub fn reason(
    p: &dyn Problem,
    v: &Variant,
    value: f64,
    earlier: &[&Record],
    rules: &Rules,
) -> Option<String> {
    let metric = p.primary_metric();
    let claim = p.accuracy_claim_for(metric, v.formulation);
    let error = |r: &Record| {
        (r.status == Status::Ok)
            .then(|| r.metrics.get(metric).copied().flatten())
            .flatten()
            .filter(|e| e.is_finite())
    };
    let name = if v.info.adaptive { "tol" } else { "dt" };
    let point = |r: &Record| r.dt.or(r.tol).unwrap_or(f64::NAN);
    if let Some(c) = claim
        && let Some((r, e)) = earlier
            .iter()
            .find_map(|r| error(r).filter(|&e| e <= c).map(|e| (r, e)))
    {
        return Some(format!(
            "not run: the ladder's {name} = {:e} point already has {metric} {e:.2e}, at or below \
             the reference's accuracy claim {c:.1e}; a finer point would measure the reference",
            point(r)
        ));
    }
    if v.info.order == 1
        && !v.info.adaptive
        && let Some(c) = claim
        && earlier.len() >= FIT_POINTS
    {
        let last = &earlier[earlier.len() - FIT_POINTS..];
        let pts: Option<Vec<[f64; 2]>> = last
            .iter()
            .map(|r| {
                error(r)
                    .filter(|&e| e >= 100.0 * c && e <= 1e-2)
                    .map(|e| [point(r), e])
            })
            .collect();
        if let Some(pts) = pts {
            let slopes = order::local_slopes(&pts);
            if slopes.len() == FIT_POINTS - 1
                && slopes.iter().all(|s| (s - 1.0).abs() <= ORDER1_SLACK)
            {
                let shown: Vec<String> = slopes.iter().map(|s| format!("{s:.3}")).collect();
                return Some(format!(
                    "not run: order 1 is established by the ladder's points {name} = {:e} to \
                     {:e} (local slopes {}, within {ORDER1_SLACK} of 1); a finer point would \
                     cost as much as all coarser ones for an error the fit predicts",
                    pts[0][0],
                    pts[FIT_POINTS - 1][0],
                    shown.join(", ")
                ));
            }
        }
    }
    if let (Some(cost), Some(prev)) = (rules.cost, earlier.last())
        && rules.cap_s.is_finite()
    {
        let key = crate::cost::variant_key(v.param, v.integrator, v.formulation);
        let predicted = cost.seconds(&key, &predicted_work(p, v, value, prev));
        if predicted > rules.cap_s {
            return Some(format!(
                "not run: predicted {predicted:.1} s (cost table, from the {name} = {:e} point's \
                 work), over the cap of {} s a run (--max-run-s)",
                point(prev),
                rules.cap_s
            ));
        }
    }
    None
}

/// The work of the point at `value`, predicted from the ladder's previous point `prev`
/// (rule 3 of the file's opening).
pub fn predicted_work(p: &dyn Problem, v: &Variant, value: f64, prev: &Record) -> [f64; 4] {
    let w = crate::cost::work(&prev.stats);
    let scale = if v.info.adaptive {
        let prev_tol = prev.tol.unwrap_or(value);
        (prev_tol / value).powf(1.0 / f64::from(v.info.order.max(1)))
    } else {
        let steps = crate::case::steps_dividing(p.t_end(), value).unwrap_or(0) as f64;
        if prev.stats.steps == 0 {
            0.0
        } else {
            steps / prev.stats.steps as f64
        }
    };
    w.map(|x| x * scale)
}

/// The work of a ladder's first point, before anything of its ladder is known: `T / dt`
/// steps and the method's stages per step of right-hand sides (an implicit method's Newton
/// iterations unknown, counted 0), for the main job's estimate only.
pub fn first_point_work(p: &dyn Problem, v: &Variant, value: f64) -> Option<[f64; 4]> {
    if v.info.adaptive {
        return None;
    }
    let steps = crate::case::steps_dividing(p.t_end(), value)? as f64;
    Some([steps, steps * f64::from(v.info.stages.max(1)), 0.0, 0.0])
}

#[cfg(test)]
#[path = "skip_tests.rs"]
mod tests;
