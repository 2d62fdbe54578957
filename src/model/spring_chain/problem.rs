//! One compiled spring-chain scene behind the `Problem` seam: the chain, the initial state,
//! the grid, the ladders, and its reference file (`references/spring_chain/<scene>.json`: the
//! exact modal solution at the score times, cross-checked by `dopri5` at tolerance 1e-12 in
//! the other formulation; the family has only `param = none`, so the cross-check cannot
//! differ in parameterization). Scores: `displacement_error_max` and `velocity_error_max`
//! (max Euclidean norm over the score times against the reference), `energy_drift_max` and
//! `energy_drift_final` (the shared relative drift).
use serde::{Deserialize, Serialize};
use std::path::Path;

use super::case::{ChainCase, ChainScene};
use super::family::{FAMILY, RunFn};
use super::{Chain, ChainObs};
use crate::case::{Case, CaseError, Scene};
use crate::integrate::Limits;
use crate::metrics::{Scores, energy_drift};
use crate::problem::{Columns, Outcome, Problem, SceneHeader, Stepping, Variant, Want};
use crate::reference::{self, Stored};
use crate::run::{Grid, Observe, RunOutput};
use crate::case::Ladders;
use crate::summary::{self, Series};

/// What a run function needs.
#[derive(Debug, Clone)]
pub struct ChainSetup {
    pub chain: Chain,
    pub initial: ChainObs,
    pub grid: Grid,
    pub limits: Limits,
}

/// The cross-check of the exact reference.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CrossCheck {
    pub method: String,
    pub max_displacement_diff: f64,
    pub max_velocity_diff: f64,
}

/// How the reference was made.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Provenance {
    pub command: String,
    pub method: String,
    pub git_commit: String,
    pub created_utc: String,
    pub rustc: String,
    pub cross_check: CrossCheck,
    pub energy_drift: f64,
}

/// Max-abs accuracy the reference claims.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Claim {
    pub displacement: f64,
    pub velocity: f64,
}

/// The stored reference of a scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChainReference {
    pub case: String,
    pub scene: String,
    pub t: Vec<f64>,
    pub displacement: Vec<[f64; 3]>,
    pub velocity: Vec<[f64; 3]>,
    pub energy: Vec<f64>,
    pub provenance: Provenance,
    pub accuracy_claim: Claim,
    pub inputs_sha256: String,
}

impl Stored for ChainReference {
    fn times(&self) -> &[f64] {
        &self.t
    }
    fn check_columns(&self) -> Result<(), String> {
        reference::columns_fit(
            self.t.len(),
            &[self.displacement.len(), self.velocity.len(), self.energy.len()],
        )
    }
}

/// A spring-chain scene with its reference (once attached).
#[derive(Debug, Clone)]
pub struct ChainProblem {
    header: SceneHeader,
    energy_scale: f64,
    setup: ChainSetup,
    ladders: Ladders,
    quick: Ladders,
    reference: Option<(ChainReference, String)>,
}


impl ChainProblem {
    pub fn new(case: &Case, scene: &Scene) -> Result<Self, CaseError> {
        let (Some(c), Some(s)) = (case.physics::<ChainCase>(), scene.physics::<ChainScene>())
        else {
            return Err(CaseError::model(case, "not a spring-chain case"));
        };
        Ok(ChainProblem {
            header: SceneHeader::new(&FAMILY, case, scene),
            energy_scale: case.energy_scale,
            setup: ChainSetup {
                chain: c.chain(),
                initial: s.initial,
                grid: Grid::of_scene(scene),
                limits: case.limits(),
            },
            ladders: scene.ladders.values(),
            quick: scene.quick.values(),
            reference: None,
        })
    }

    /// The exact solution at the score times.
    fn exact_track(&self) -> Result<(Vec<f64>, Vec<ChainObs>), String> {
        let g = &self.setup.grid;
        let n = crate::run::divides(g.t_end, g.score_every)
            .ok_or("score_every does not divide t_end")?;
        let t: Vec<f64> = (0..=n).map(|k| k as f64 * g.score_every).collect();
        let obs = t
            .iter()
            .map(|&t| self.setup.chain.exact(&self.setup.initial, t))
            .collect();
        Ok((t, obs))
    }

    fn run_raw(
        &self,
        v: &Variant,
        stepping: Stepping,
        observe: &Observe,
    ) -> Result<RunOutput<ChainObs>, String> {
        (v.run_fn::<RunFn>()?)(&self.setup, stepping, observe)
    }
}

/// Max over the track of `|x - x_ref|` and `|v - v_ref|`.
fn max_diffs(a: &[ChainObs], b: &[ChainObs]) -> Result<[f64; 2], String> {
    if a.len() != b.len() {
        return Err(format!("tracks differ in length: {} vs {}", a.len(), b.len()));
    }
    let mut m = [0.0_f64; 2];
    for (x, y) in a.iter().zip(b) {
        m[0] = m[0].max((x.x - y.x).norm());
        m[1] = m[1].max((x.v - y.v).norm());
    }
    Ok(m)
}

fn stored_track(r: &ChainReference) -> Vec<ChainObs> {
    r.displacement
        .iter()
        .zip(&r.velocity)
        .map(|(x, v)| ChainObs {
            x: (*x).into(),
            v: (*v).into(),
        })
        .collect()
}

impl Problem for ChainProblem {
    crate::problem::scene_problem_methods!();
    fn accuracy_claim(&self, metric: &str) -> Option<f64> {
        let (r, _) = self.reference.as_ref()?;
        Some(match metric {
            "velocity_error_max" => r.accuracy_claim.velocity,
            _ => r.accuracy_claim.displacement,
        })
    }
    fn run(&self, v: &Variant, stepping: Stepping, want: Want) -> Result<Outcome, String> {
        let out = self.run_raw(v, stepping, &want.observe())?;
        let mut o = Outcome::of_run(&out);
        match want {
            Want::Timing => {}
            Want::Scored => {
                let (scores, series) = self.score(&out);
                o.scores = scores;
                o.series = Some(series);
            }
            Want::Trajectory => {
                let chain = &self.setup.chain;
                let s = &out.samples;
                o.columns = Some(Columns {
                    t: s.iter().map(|x| x.t).collect(),
                    columns: vec![
                        (
                            "displacement",
                            3,
                            s.iter().flat_map(|x| x.obs.x.iter().copied()).collect(),
                        ),
                        (
                            "velocity",
                            3,
                            s.iter().flat_map(|x| x.obs.v.iter().copied()).collect(),
                        ),
                        ("energy", 1, s.iter().map(|x| chain.energy(&x.obs)).collect()),
                    ],
                });
            }
        }
        Ok(o)
    }
    fn make_reference(&self, root: &Path) -> Result<String, String> {
        let (t, exact) = self.exact_track()?;
        // The cross-check: dopri5 at 1e-12 in modal coordinates.
        let cross_v = FAMILY
            .find("none", "dopri5", "chain_modal")
            .ok_or("dopri5/chain_modal is not registered")?;
        let mut setup = self.clone();
        setup.setup.grid.sample_every = setup.setup.grid.score_every;
        let cross = setup.run_raw(cross_v, Stepping::Tol(1e-12), &Observe::Grid)?;
        if let Some(f) = cross.failure {
            return Err(format!("the cross-check failed: {}", f.message));
        }
        let cross_obs: Vec<ChainObs> = cross.scored().map(|s| s.obs).collect();
        let d = max_diffs(&exact, &cross_obs)?;
        let energy: Vec<f64> = exact.iter().map(|o| self.setup.chain.energy(o)).collect();
        let drift = energy_drift::max_relative(&energy, self.energy_scale);
        let r = ChainReference {
            case: self.header.case.clone(),
            scene: self.header.scene.clone(),
            t,
            displacement: exact.iter().map(|o| [o.x.x, o.x.y, o.x.z]).collect(),
            velocity: exact.iter().map(|o| [o.v.x, o.v.y, o.v.z]).collect(),
            energy,
            provenance: Provenance {
                command: format!(
                    "mbdbench reference --case {} --scene {}",
                    self.header.case, self.header.scene
                ),
                method: "exact modal solution".into(),
                git_commit: summary::git_commit().into(),
                created_utc: summary::now_utc(),
                rustc: summary::rustc_version().into(),
                cross_check: CrossCheck {
                    method: "dopri5/none/chain_modal tol 1e-12".into(),
                    max_displacement_diff: d[0],
                    max_velocity_diff: d[1],
                },
                energy_drift: drift,
            },
            accuracy_claim: Claim {
                displacement: d[0].max(drift),
                velocity: d[1].max(drift),
            },
            inputs_sha256: self.header.inputs_sha256.clone(),
        };
        let path = reference::save_as(root, &self.header.case, &self.header.scene, &r)
            .map_err(|e| e.to_string())?;
        Ok(format!(
            "{}: exact modal solution; cross-check {}: displacement {:.2e}, velocity {:.2e}; claim displacement {:.2e}",
            path.display(),
            r.provenance.cross_check.method,
            d[0],
            d[1],
            r.accuracy_claim.displacement
        ))
    }
    fn check_reference(&self, root: &Path) -> Result<(bool, String), String> {
        let h = &self.header;
        let (stored, _): (ChainReference, _) =
            reference::load_as(root, &h.case, &h.scene, &h.inputs_sha256)
                .map_err(|e| e.to_string())?;
        let (_, now) = self.exact_track()?;
        let d = max_diffs(&now, &stored_track(&stored))?;
        let c = stored.accuracy_claim;
        let ok = d[0] <= c.displacement && d[1] <= c.velocity;
        Ok((
            ok,
            format!(
                "{}/{}: recomputed vs stored: displacement {:.2e}, velocity {:.2e} (claims {:.2e}, {:.2e})",
                h.case, h.scene, d[0], d[1], c.displacement, c.velocity
            ),
        ))
    }
}

impl ChainProblem {
    /// The scores and series of a run.
    fn score(&self, out: &RunOutput<ChainObs>) -> (Scores, Series) {
        let mut s = Scores::default();
        let chain = &self.setup.chain;
        let scored: Vec<_> = out.scored().collect();
        let energies: Vec<f64> = scored.iter().map(|x| chain.energy(&x.obs)).collect();
        energy_drift::score(out, &energies, self.energy_scale, &mut s);
        let mut primary_error = None;
        if let Some((r, _)) = &self.reference {
            let names = ["displacement_error_max", "velocity_error_max"];
            let reference = stored_track(r);
            if let Some(f) = &out.failure {
                for n in names {
                    s.null(n, format!("run failed ({:?}) at t = {}", f.kind, f.t));
                }
            } else if scored.len() != reference.len() {
                for n in names {
                    s.null(
                        n,
                        format!(
                            "run has {} score points, reference {}",
                            scored.len(),
                            reference.len()
                        ),
                    );
                }
            } else {
                let obs: Vec<ChainObs> = scored.iter().map(|x| x.obs).collect();
                if let Ok(d) = max_diffs(&obs, &reference) {
                    s.set(names[0], d[0]);
                    s.set(names[1], d[1]);
                }
                let vel = self.header.primary_metric == "velocity_error_max";
                primary_error = Some(
                    obs.iter()
                        .zip(&reference)
                        .map(|(a, b)| if vel { (a.v - b.v).norm() } else { (a.x - b.x).norm() })
                        .collect(),
                );
            }
        }
        let series = Series {
            t: scored.iter().map(|x| x.t).collect(),
            energy: energies,
            constraint: scored.iter().map(|x| x.residual).collect(),
            conditioning: scored.iter().map(|x| x.conditioning).collect(),
            primary_error,
            primary_metric: self.header.primary_metric.clone(),
            tracks: Default::default(),
        };
        (s, series)
    }
}
