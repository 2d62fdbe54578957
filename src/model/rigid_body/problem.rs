//! One compiled rigid-body scene behind the `Problem` seam: the scene plan (body, initial
//! state, grid, limits, ladders, physics hash), its stored reference once attached, and the
//! dispatch of a run to the registry's monomorphised run function of the variant. Scoring
//! (`score.rs` beside this file) and the trajectory's named columns (docs/schemas.md, "Trajectory
//! files": position, quaternion, velocity, body angular velocity, energy at the sample times) are
//! made here, so the suite sees only names and numbers.
//!
//! The timing pass runs the same function with `Observe::Final` on a setup prepared once, so
//! a timed repeat does exactly the work of the scored run minus its observations.
use crate::model::rigid_body::Observation;
use std::path::Path;

use crate::case::ReferenceKind;
use crate::integrate::MethodInfo;
use crate::problem::{Columns, Outcome, Problem, SceneHeader, Stepping, Variant, Want};
use super::reference::{self, Loaded};
use crate::model::rigid_body::refgen;
use crate::model::rigid_body::registry::{self, RigidSetup};
use crate::run::{Grid, Observe};
use crate::model::rigid_body::score::{self, ScoreContext};
use crate::model::rigid_body::plan::ScenePlan;

/// A rigid-body scene with its reference (once attached).
#[derive(Debug, Clone)]
pub struct RigidProblem {
    pub plan: ScenePlan,
    /// How the case's references are made.
    pub kind: ReferenceKind,
    /// The plan's setup observing only the final state (the timing pass).
    timing: RigidSetup,
    pub reference: Option<Loaded>,
}

impl RigidProblem {
    pub fn new(plan: ScenePlan, kind: ReferenceKind) -> Self {
        let mut timing = plan.setup.clone();
        timing.observe = Observe::Final;
        RigidProblem {
            plan,
            kind,
            timing,
            reference: None,
        }
    }
}

impl RigidProblem {
    /// The stored reference of the scene, its values valid (`Reference::check_columns`) and
    /// its times the scene's score times; errors name the file and key.
    fn load_reference(&self, root: &Path) -> Result<Loaded, String> {
        let (reference, file_sha256) =
            self.plan.header.load_reference(root, &self.plan.setup.grid)?;
        Ok(Loaded {
            reference,
            file_sha256,
        })
    }
}

/// The registry's variant behind a family variant (its chart's facts and its run).
fn registered(v: &Variant) -> Result<&registry::Variant, String> {
    v.run_fn::<registry::Variant>()
}

fn value(s: Stepping) -> f64 {
    match s {
        Stepping::Dt(h) => h,
        Stepping::Tol(t) => t,
    }
}

impl Problem for RigidProblem {
    fn header(&self) -> &SceneHeader {
        &self.plan.header
    }
    fn header_mut(&mut self) -> &mut SceneHeader {
        &mut self.plan.header
    }
    fn grid(&self) -> &Grid {
        &self.plan.setup.grid
    }
    // The timing setup's copy of the grid moves with it; the attached reference's times are
    // the old grid's: dropped.
    fn set_t_end(&mut self, t_end: f64) {
        self.plan.setup.grid.t_end = t_end;
        self.timing.grid.t_end = t_end;
        self.reference = None;
    }
    fn ladder(&self, quick: bool, info: &MethodInfo) -> &[f64] {
        let l = if quick {
            &self.plan.quick
        } else {
            &self.plan.ladders
        };
        l.for_method(info)
    }
    fn na_reason(&self, v: &Variant) -> Option<String> {
        match registered(v) {
            Ok(rv) => registry::scene_na_reason(rv, &self.plan.setup.body),
            Err(e) => Some(e),
        }
    }
    fn attach_reference(&mut self, root: &Path) -> Result<(), String> {
        self.reference = Some(self.load_reference(root)?);
        Ok(())
    }
    fn reference_sha256(&self) -> Option<&str> {
        self.reference.as_ref().map(|l| l.file_sha256.as_str())
    }
    fn accuracy_claim(&self, metric: &str) -> Option<f64> {
        self.reference
            .as_ref()
            .map(|l| reference::claim_for(&l.reference, metric))
    }
    fn run(&self, v: &Variant, stepping: Stepping, want: Want) -> Result<Outcome, String> {
        let rv = registered(v)?;
        let setup = match want {
            Want::Timing => &self.timing,
            Want::Scored | Want::Trajectory => &self.plan.setup,
        };
        let out = (rv.run)(setup, value(stepping))?;
        let mut o = Outcome::of_run(&out);
        match want {
            Want::Timing => {}
            Want::Scored => {
                let cx = ScoreContext {
                    body: &self.plan.setup.body,
                    energy_scale: self.plan.energy_scale,
                    primary_metric: &self.plan.header.primary_metric,
                    reference: self.reference.as_ref().map(|l| &l.reference),
                };
                let (scores, series) = score::score(&out, &cx);
                o.scores = scores;
                o.series = Some(series);
            }
            Want::Trajectory => o.columns = Some(columns(&self.plan, &out)),
        }
        Ok(o)
    }
    fn make_reference(&self, root: &Path) -> Result<String, String> {
        let t0 = std::time::Instant::now();
        let r = refgen::build(self.kind, &self.plan)?;
        let path = reference::save(root, &r).map_err(|e| e.to_string())?;
        Ok(format!(
            "{}: {} ({:.1} s); cross-check {}: rotation {:.2e}, omega {:.2e}, position {:?}; energy drift {:.2e}; claim rotation {:.2e}",
            path.display(),
            r.provenance.method,
            t0.elapsed().as_secs_f64(),
            r.provenance.cross_check.method,
            r.provenance.cross_check.max_rotation_diff,
            r.provenance.cross_check.max_omega_diff,
            r.provenance.cross_check.max_position_diff,
            r.provenance.energy_drift,
            r.accuracy_claim.rotation
        ))
    }
    fn check_reference(&self, root: &Path) -> Result<(bool, String), String> {
        let p = &self.plan;
        let stored = self.load_reference(root)?;
        refgen::check(self.kind, p, &stored.reference)
    }
}

/// Every sample as the family's named columns (the quaternion in canonical sign, w >= 0).
fn columns(plan: &ScenePlan, out: &crate::run::RunOutput<Observation>) -> Columns {
    let s = &out.samples;
    let body = &plan.setup.body;
    let flat = |f: &dyn Fn(&crate::run::Sample<Observation>) -> Vec<f64>| s.iter().flat_map(f).collect();
    Columns {
        t: s.iter().map(|x| x.t).collect(),
        columns: vec![
            ("position", 3, flat(&|x| x.obs.x.as_slice().to_vec())),
            (
                "quaternion",
                4,
                flat(&|x| {
                    let q = crate::math::so3::canonical(&x.obs.q);
                    vec![q.w, q.i, q.j, q.k]
                }),
            ),
            ("velocity", 3, flat(&|x| x.obs.v.as_slice().to_vec())),
            ("omega_body", 3, flat(&|x| x.obs.omega.as_slice().to_vec())),
            ("energy", 1, flat(&|x| vec![body.energy(&x.obs)])),
        ],
    }
}
