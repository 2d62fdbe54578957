//! The flexible beam's stored reference (docs/schemas.md, "Stored references"): the tip
//! deflection, axial tip displacement, hub angle and rate, energy and angular momentum at the
//! score times, computed by `fe_exact` with the case's `reference_elements` and Newmark at
//! `reference_dt`, restarted at every breakpoint.
//!
//! Its accuracy claim, per column (`tip_deflection`, `hub_rate`), is the largest of three
//! measured numbers: the time-discretisation estimate (the difference from the same mesh at
//! twice the step, over 3: Newmark is of order 2), the mesh estimate (the difference from half
//! the elements, over 3: the element's frequencies converge as the square of the element
//! length), and the cross-check (the largest difference from a run that differs in mesh,
//! integrator and formulation: `modal_stiffened` with the case's modes under `dop853` at
//! tolerance 1e-10). The file also holds one self-convergence track per formulation
//! (`family::self_convergence`), the floor of that formulation's `tip_time_error_max`.
//! `reference --check` recomputes it at coarser steps and checks every stored column and track
//! against bounds of its own (`reference_check.rs`); a file whose provenance names another
//! mesh or step than the case's is refused before any run. Where it fails: a claim is only as
//! good as the estimates' asymptotic regime; the note of the issue that built it shows the
//! mesh ladder.
use serde::{Deserialize, Serialize};
use std::path::Path;

use super::family::{Track, track};
use super::observe::BeamObs;
use super::problem::{BeamProblem, BeamSetup};
use crate::problem::Problem;
use crate::reference::{self, Stored};
use crate::run::Stepping;
use crate::summary;

/// Max differences of the two scored columns.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Diff {
    pub tip_deflection: f64,
    pub hub_rate: f64,
}

/// The cross-check and the two estimates.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Checks {
    pub cross_check_method: String,
    pub cross_check: Diff,
    /// The difference from twice the step, over 3.
    pub time_estimate: Diff,
    /// The difference from half the elements, over 3.
    pub mesh_estimate: Diff,
    /// The peak `|v_tip|` of the reference (m).
    pub peak_tip_deflection: f64,
}

/// How the reference was made.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Provenance {
    pub command: String,
    pub method: String,
    pub elements: usize,
    pub step: f64,
    pub git_commit: String,
    pub created_utc: String,
    pub rustc: String,
    pub checks: Checks,
}

/// A time-converged run of one formulation with the case's own mesh or modes (the
/// self-convergence reference of the order fits and work-precision plots: it holds the
/// formulation's spatial error fixed, so a run's difference from it is its time error).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SelfTrack {
    pub formulation: String,
    pub method: String,
    /// The tip deflection at the score times; None when the formulation's run failed (a
    /// model that diverges has no converged trajectory).
    pub tip_deflection: Option<Vec<f64>>,
    /// Why there is no track.
    pub failure: Option<String>,
    /// The difference from the same run one ladder notch coarser (m): the track's own error
    /// is below it (None without a track).
    pub time_estimate: Option<f64>,
}

/// The stored reference of a scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BeamReference {
    pub case: String,
    pub scene: String,
    pub t: Vec<f64>,
    pub tip_deflection: Vec<f64>,
    pub tip_axial: Vec<f64>,
    pub hub_angle: Vec<f64>,
    pub hub_rate: Vec<f64>,
    pub energy: Vec<f64>,
    pub momentum: Vec<f64>,
    pub provenance: Provenance,
    pub accuracy_claim: Diff,
    pub self_convergence: Vec<SelfTrack>,
    pub inputs_sha256: String,
}

impl Stored for BeamReference {
    fn times(&self) -> &[f64] {
        &self.t
    }
    fn check_columns(&self) -> Result<(), String> {
        reference::columns_fit(
            self.t.len(),
            &[
                self.tip_deflection.len(),
                self.tip_axial.len(),
                self.hub_angle.len(),
                self.hub_rate.len(),
                self.energy.len(),
                self.momentum.len(),
            ],
        )
    }
}

/// `fe_exact` with `elements` under Newmark at `h`, on the score grid.
pub(super) fn fe_run(setup: &BeamSetup, elements: usize, h: f64) -> Result<Track, String> {
    let mut s = setup.clone();
    s.numerics.elements = elements;
    let v = super::family::FAMILY
        .find("none", "newmark", "fe_exact")
        .ok_or("newmark/fe_exact is not registered")?;
    track(&s, v, Stepping::Dt(h))?
        .map_err(|e| format!("fe_exact with {elements} elements at {h} s failed: {e}"))
}

pub(super) fn diff(a: &[(f64, BeamObs)], b: &[(f64, BeamObs)]) -> Result<Diff, String> {
    if a.len() != b.len() {
        return Err(format!("tracks differ in length: {} vs {}", a.len(), b.len()));
    }
    let mut d = Diff {
        tip_deflection: 0.0,
        hub_rate: 0.0,
    };
    for ((_, x), (_, y)) in a.iter().zip(b) {
        d.tip_deflection = d.tip_deflection.max((x.tip_deflection - y.tip_deflection).abs());
        d.hub_rate = d.hub_rate.max((x.hub_rate - y.hub_rate).abs());
    }
    Ok(d)
}

pub(super) fn third(d: Diff) -> Diff {
    Diff {
        tip_deflection: d.tip_deflection / 3.0,
        hub_rate: d.hub_rate / 3.0,
    }
}

pub(super) fn max3(a: Diff, b: Diff, c: Diff) -> Diff {
    Diff {
        tip_deflection: a.tip_deflection.max(b.tip_deflection).max(c.tip_deflection),
        hub_rate: a.hub_rate.max(b.hub_rate).max(c.hub_rate),
    }
}

/// Computes, cross-checks and writes the scene's reference.
pub fn make(p: &BeamProblem, root: &Path) -> Result<String, String> {
    let s = &p.setup;
    let n = s.numerics.reference_elements;
    let h = s.scene.reference_dt.unwrap_or(s.numerics.reference_dt);
    let main = fe_run(s, n, h)?;
    let coarse_t = fe_run(s, n, 2.0 * h)?;
    let coarse_m = fe_run(s, (n / 2).max(1), h)?;
    let (cross_method, cross) = super::family::cross_check(s)?;
    let cross = diff(&main, &cross.map_err(|e| format!("the cross-check failed: {e}"))?)?;
    let time_estimate = third(diff(&main, &coarse_t)?);
    let mesh_estimate = third(diff(&main, &coarse_m)?);
    let claim = max3(cross, time_estimate, mesh_estimate);
    let peak = main
        .iter()
        .map(|(_, o)| o.tip_deflection.abs())
        .fold(0.0, f64::max);
    let col = |f: fn(&BeamObs) -> f64| main.iter().map(|(_, o)| f(o)).collect::<Vec<f64>>();
    let r = BeamReference {
        case: p.case().into(),
        scene: p.scene().into(),
        t: main.iter().map(|x| x.0).collect(),
        tip_deflection: col(|o| o.tip_deflection),
        tip_axial: col(|o| o.tip_axial),
        hub_angle: col(|o| o.hub_angle),
        hub_rate: col(|o| o.hub_rate),
        energy: col(|o| o.kinetic + o.strain),
        momentum: col(|o| o.momentum),
        provenance: Provenance {
            command: format!(
                "mbdbench reference --case {} --scene {}",
                p.case(),
                p.scene()
            ),
            method: format!("fe_exact, {n} elements, newmark at {h} s"),
            elements: n,
            step: h,
            git_commit: summary::git_commit().into(),
            created_utc: summary::now_utc(),
            rustc: summary::rustc_version().into(),
            checks: Checks {
                cross_check_method: cross_method,
                cross_check: cross,
                time_estimate,
                mesh_estimate,
                peak_tip_deflection: peak,
            },
        },
        accuracy_claim: claim,
        self_convergence: self_tracks(s)?,
        inputs_sha256: p.inputs_sha256().into(),
    };
    let path =
        reference::save_as(root, p.case(), p.scene(), &r).map_err(|e| e.to_string())?;
    Ok(format!(
        "{}: {}; cross-check ({}) tip {:.2e} m, hub rate {:.2e} rad/s; time estimate tip {:.2e}; \
         mesh estimate tip {:.2e}; claim tip {:.2e} m ({:.3} % of the peak {:.4} m)",
        path.display(),
        r.provenance.method,
        r.provenance.checks.cross_check_method,
        cross.tip_deflection,
        cross.hub_rate,
        time_estimate.tip_deflection,
        mesh_estimate.tip_deflection,
        claim.tip_deflection,
        100.0 * claim.tip_deflection / peak.max(f64::MIN_POSITIVE),
        peak
    ))
}

/// The self-convergence track of every formulation (`family::self_convergence` names the
/// tight run and the coarser one of each).
fn self_tracks(s: &BeamSetup) -> Result<Vec<SelfTrack>, String> {
    use super::family::SelfPlan;
    let mut out = vec![];
    // Formulations that share a tight run (the AIGC forms) share its track.
    let mut cache: Vec<(usize, SelfTrack)> = vec![];
    let h_ref = s.scene.reference_dt.unwrap_or(s.numerics.reference_dt);
    for f in super::family::FORMULATIONS {
        let Some((v, plan, method)) = super::family::self_convergence(f, h_ref) else {
            continue;
        };
        if let Some(done) = cache.iter().find(|(idx, _)| *idx == v.index) {
            out.push(SelfTrack {
                formulation: f.to_string(),
                ..done.1.clone()
            });
            continue;
        }
        let run = |st| -> Result<Result<Vec<f64>, String>, String> {
            Ok(track(s, v, st)?.map(|t| t.iter().map(|x| x.1.tip_deflection).collect()))
        };
        let max_diff = |a: &[f64], b: &[f64]| {
            a.iter()
                .zip(b)
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max)
        };
        let extrapolate = |fine: &[f64], coarse: &[f64]| -> Vec<f64> {
            fine.iter()
                .zip(coarse)
                .map(|(f, c)| (4.0 * f - c) / 3.0)
                .collect()
        };
        let result: Result<(Vec<f64>, f64), String> = match plan {
            SelfPlan::Tolerances(fine, coarse) => {
                let a = run(Stepping::Tol(fine))?;
                let b = run(Stepping::Tol(coarse))?;
                a.and_then(|a| b.map(|b| (max_diff(&a, &b), a)))
                    .map(|(e, a)| (a, e))
            }
            SelfPlan::Richardson(h) => {
                let y1 = run(Stepping::Dt(h))?;
                let y2 = run(Stepping::Dt(h / 2.0))?;
                let y4 = run(Stepping::Dt(h / 4.0))?;
                y1.and_then(|y1| {
                    let (y2, y4) = (y2?, y4?);
                    let r1 = extrapolate(&y2, &y1);
                    let r2 = extrapolate(&y4, &y2);
                    Ok((max_diff(&r2, &r1), r2))
                })
                .map(|(e, r)| (r, e))
            }
        };
        let track = match result {
            Ok((tip, e)) => SelfTrack {
                formulation: f.to_string(),
                method,
                tip_deflection: Some(tip),
                failure: None,
                time_estimate: Some(e),
            },
            Err(why) => SelfTrack {
                formulation: f.to_string(),
                method,
                tip_deflection: None,
                failure: Some(why),
                time_estimate: None,
            },
        };
        cache.push((v.index, track.clone()));
        out.push(track);
    }
    Ok(out)
}
