//! `mbdbench reference --check` for the flexible beam: recomputes the stored reference at
//! coarser steps and checks every stored column and self-convergence track against bounds
//! that come from the recomputation alone, never from numbers in the file it checks.
//!
//! - The reference (`fe_exact` with the case's `reference_elements`, Newmark at `h`): runs at
//!   `2h` and `4h`. Newmark is of order 2, so `u(2h)` carries four times the stored run's time
//!   error and the stored run differs from it by about `|u(2h) - u(4h)| / 4`; the bound is
//!   `BOUND_FACTOR` times the recomputed estimate of `u(2h)`'s own error, `|u(2h) - u(4h)| / 3`.
//! - The accuracy claim: recomputed as the reference makes it (cross-check against
//!   `modal_stiffened`, time estimate `|u(2h) - u(4h)| / 12` scaled to `h`, mesh estimate from
//!   half the elements at `2h`), and the stored claim must lie within `CLAIM_SLACK` of it.
//! - Every stored self-convergence track, recomputed one notch coarser than it was made:
//!   an adaptive track at its coarse tolerance (bound: `BOUND_FACTOR` times its difference from
//!   ten times that tolerance); a Richardson track (stored: extrapolated from `h'/2` and `h'/4`)
//!   extrapolated from `h'` and `2h'` (bound: `BOUND_FACTOR` times its difference from the
//!   extrapolation of `2h'` and `4h'`).
//!
//! Each bound has a round-off floor of `FLOOR_REL` times the column's peak. Cost: about 0.9 of
//! the reference's own run plus the tracks' coarse runs (measured in the note).
use std::path::Path;

use super::observe::BeamObs;
use super::problem::BeamProblem;
use super::reference::{BeamReference, Diff, diff, fe_run, max3, third};
use crate::problem::Problem;
use crate::reference;
use crate::run::Stepping;

/// A recomputed bound is this many times the recomputed error estimate.
pub const BOUND_FACTOR: f64 = 2.0;
/// How far the stored claim may lie from the recomputed one, either way.
pub const CLAIM_SLACK: f64 = 10.0;
/// The round-off floor of every bound, relative to the column's peak.
pub const FLOOR_REL: f64 = 1e-12;

fn peak(x: impl Iterator<Item = f64>) -> f64 {
    x.map(f64::abs).fold(0.0, f64::max)
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// `(4 y(h/2) - y(h)) / 3`, Newmark's order-2 error removed.
fn extrapolate(fine: &[f64], coarse: &[f64]) -> Vec<f64> {
    fine.iter()
        .zip(coarse)
        .map(|(f, c)| (4.0 * f - c) / 3.0)
        .collect()
}

/// Checks the scene's stored reference against a recomputation (module docs).
pub fn check(p: &BeamProblem, root: &Path) -> Result<(bool, String), String> {
    let (stored, _): (BeamReference, _) =
        reference::load_as(root, p.case(), p.scene(), p.inputs_sha256())
            .map_err(|e| e.to_string())?;
    let s = &p.setup;
    let n = s.numerics.reference_elements;
    let h = s.scene.reference_dt.unwrap_or(s.numerics.reference_dt);
    // The runs are the case's (its mesh and step are in the physics hash), never the file's:
    // a file whose provenance says otherwise was not made from this case and is refused
    // before any run (an edited one said 10,000 elements).
    let made = &stored.provenance;
    if made.elements != n || made.step != h {
        let why = format!(
            "provenance: {} elements at {} s, but the case makes its reference with \
             numerics.reference_elements = {n} at {h} s",
            made.elements, made.step
        );
        return Err(reference::grid_error(root, p.case(), p.scene(), why).to_string());
    }
    let u2 = fe_run(s, n, 2.0 * h)?;
    let u4 = fe_run(s, n, 4.0 * h)?;
    let track: Vec<(f64, BeamObs)> = stored
        .t
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let o = BeamObs {
                tip_deflection: stored.tip_deflection[i],
                hub_rate: stored.hub_rate[i],
                ..BeamObs::default()
            };
            (*t, o)
        })
        .collect();
    let floor = Diff {
        tip_deflection: FLOOR_REL * peak(u2.iter().map(|x| x.1.tip_deflection)),
        hub_rate: FLOOR_REL * peak(u2.iter().map(|x| x.1.hub_rate)),
    };
    let d24 = diff(&u2, &u4)?;
    let d = diff(&u2, &track)?;
    let bound = Diff {
        tip_deflection: BOUND_FACTOR * d24.tip_deflection / 3.0 + floor.tip_deflection,
        hub_rate: BOUND_FACTOR * d24.hub_rate / 3.0 + floor.hub_rate,
    };
    let columns_ok = d.tip_deflection <= bound.tip_deflection && d.hub_rate <= bound.hub_rate;
    let (claim_ok, claim_text) = check_claim(p, &stored, &u2, d24, floor)?;
    let (tracks_ok, tracks_text) = check_tracks(p, &stored, h)?;
    Ok((
        columns_ok && claim_ok && tracks_ok,
        format!(
            "{}/{}: recomputed at 2h vs stored: tip {:.2e} m, hub rate {:.2e} rad/s (bounds from \
             the recomputation at 2h and 4h: {:.2e}, {:.2e}); {claim_text}; {tracks_text}",
            p.case(),
            p.scene(),
            d.tip_deflection,
            d.hub_rate,
            bound.tip_deflection,
            bound.hub_rate,
        ),
    ))
}

/// The stored claim against the claim recomputed as `reference::make` computes it, with
/// coarser runs: the cross-check's difference, the time estimate (`|u(2h) - u(4h)| / 12`,
/// the stored run's own) and the mesh estimate (half the elements, at `2h`).
fn check_claim(
    p: &BeamProblem,
    stored: &BeamReference,
    u2: &[(f64, BeamObs)],
    d24: Diff,
    floor: Diff,
) -> Result<(bool, String), String> {
    let s = &p.setup;
    let n = s.numerics.reference_elements;
    let h = s.scene.reference_dt.unwrap_or(s.numerics.reference_dt);
    let (_, cross) = super::family::cross_check(s)?;
    let cross = diff(u2, &cross.map_err(|e| format!("the cross-check failed: {e}"))?)?;
    let time = Diff {
        tip_deflection: d24.tip_deflection / 12.0,
        hub_rate: d24.hub_rate / 12.0,
    };
    let mesh = third(diff(u2, &fe_run(s, (n / 2).max(1), 2.0 * h)?)?);
    let now = max3(cross, time, mesh);
    let within = |x: f64, now: f64, floor: f64| {
        let (x, now) = (x.max(floor), now.max(floor));
        x.is_finite() && x >= now / CLAIM_SLACK && x <= now * CLAIM_SLACK
    };
    let c = stored.accuracy_claim;
    let ok = within(c.tip_deflection, now.tip_deflection, floor.tip_deflection)
        && within(c.hub_rate, now.hub_rate, floor.hub_rate);
    Ok((
        ok,
        format!(
            "claim tip {:.2e} m, hub rate {:.2e} rad/s against recomputed {:.2e}, {:.2e} \
             (within {CLAIM_SLACK}x: {})",
            c.tip_deflection,
            c.hub_rate,
            now.tip_deflection,
            now.hub_rate,
            if ok { "yes" } else { "NO" }
        ),
    ))
}

/// A track recomputed one notch coarser and its error estimate, or why it could not be.
type Recomputed = Result<(Vec<f64>, f64), String>;

/// Every stored self-convergence track against its recomputation one notch coarser.
fn check_tracks(
    p: &BeamProblem,
    stored: &BeamReference,
    h_ref: f64,
) -> Result<(bool, String), String> {
    use super::family::SelfPlan;
    let s = &p.setup;
    let mut ok = true;
    let mut worst = (0.0f64, String::new());
    // Formulations that share a tight run (the AIGC forms) share its recomputation.
    let mut cache: Vec<(usize, Recomputed)> = vec![];
    for t in &stored.self_convergence {
        let Some((v, plan, _)) = super::family::self_convergence(&t.formulation, h_ref) else {
            return Err(format!(
                "self_convergence: formulation `{}` has no self-convergence plan",
                t.formulation
            ));
        };
        let Some(tip) = &t.tip_deflection else {
            continue;
        };
        if !cache.iter().any(|(i, _)| *i == v.index) {
            let run = |st| -> Result<Vec<f64>, String> {
                let tr = super::family::track(s, v, st)?;
                tr.map(|t| t.iter().map(|x| x.1.tip_deflection).collect())
            };
            let got = match plan {
                SelfPlan::Tolerances(_, coarse) => (|| {
                    let a = run(Stepping::Tol(coarse))?;
                    let b = run(Stepping::Tol(10.0 * coarse))?;
                    let e = max_diff(&a, &b);
                    Ok((a, e))
                })(),
                SelfPlan::Richardson(h) => (|| {
                    let (y1, y2, y4) = (
                        run(Stepping::Dt(h))?,
                        run(Stepping::Dt(2.0 * h))?,
                        run(Stepping::Dt(4.0 * h))?,
                    );
                    let r = extrapolate(&y1, &y2);
                    let e = max_diff(&r, &extrapolate(&y2, &y4));
                    Ok((r, e))
                })(),
            };
            cache.push((v.index, got));
        }
        let (_, got) = cache.iter().find(|(i, _)| *i == v.index).expect("cached above");
        let (now, estimate) = got
            .as_ref()
            .map_err(|e| format!("self_convergence `{}`: {e}", t.formulation))?;
        if now.len() != tip.len() {
            return Err(format!(
                "self_convergence `{}`: {} samples, the recomputation {}",
                t.formulation,
                tip.len(),
                now.len()
            ));
        }
        let d = max_diff(now, tip);
        let bound = BOUND_FACTOR * estimate + FLOOR_REL * peak(now.iter().copied());
        ok &= d <= bound;
        if d / bound > worst.0 || worst.1.is_empty() {
            worst = (
                d / bound,
                format!("{} {d:.2e} m (bound {bound:.2e})", t.formulation),
            );
        }
    }
    Ok((
        ok,
        format!(
            "{} self-convergence tracks recomputed one notch coarser, the closest to its bound: {}",
            stored.self_convergence.len(),
            worst.1
        ),
    ))
}
