//! One compiled flexible-beam scene behind the `Problem` seam: the beam, its base, the
//! numerics, the grid, the ladders and the stored reference (`reference.rs`).
//!
//! Scores (cases/README.md, "flexible_beam"), on the score grid:
//! `tip_time_error_max` (m, max `|v_tip - v_tip,self|` against the time-converged run of the
//! same formulation and mesh: the time-discretisation error, which order fits and
//! work-precision plots measure), `tip_deflection_error_max` (m, max `|v_tip - v_tip,ref|`
//! against the reference: the formulation's own error), `hub_rate_error_max` (rad/s,
//! free hub only), `energy_balance_error_max` (max `|E - W| / energy_scale`, `observe.rs`),
//! `momentum_error_max` (free hub only: max over `t >= t_off` of `|H - tau t_off| / |tau
//! t_off|`), `constraint_error_max` (formulations with boundary constraints only),
//! `tip_deflection_max` (max `|v_tip|` over the samples, also of a failed run: the
//! divergence verdict's evidence). Errors against the reference are absent for a failed run;
//! a metric that does not apply is null with the reason.
use std::collections::BTreeMap;
use std::path::Path;

use super::base::Base;
use super::case::{BeamScene, Numerics};
use super::family::{FAMILY, RunFn};
use super::observe::{BeamObs, balance};
use super::reference::BeamReference;
use crate::case::{Case, CaseError, Scene};
use crate::integrate::Limits;
use crate::metrics::Scores;
use crate::problem::{Columns, Outcome, Problem, SceneHeader, Stepping, Variant, Want};
use crate::run::{Grid, Observe, RunOutput};
use crate::case::Ladders;
use crate::summary::Series;

/// What a run function needs.
#[derive(Debug, Clone)]
pub struct BeamSetup {
    pub scene: BeamScene,
    pub numerics: Numerics,
    pub grid: Grid,
    pub limits: Limits,
}

impl BeamSetup {
    /// The divergence bound on `|v_tip|` (m).
    pub fn bound(&self) -> f64 {
        self.numerics.divergence_bound * self.scene.beam.l
    }
}

/// A flexible-beam scene with its reference (once attached).
#[derive(Debug, Clone)]
pub struct BeamProblem {
    header: SceneHeader,
    pub(super) setup: BeamSetup,
    ladders: Ladders,
    quick: Ladders,
    pub(super) reference: Option<(BeamReference, String)>,
}

impl BeamProblem {
    pub fn new(case: &Case, scene: &Scene) -> Result<Self, CaseError> {
        let (Some(n), Some(s)) = (case.physics::<Numerics>(), scene.physics::<BeamScene>())
        else {
            return Err(CaseError::model(case, "not a flexible-beam case"));
        };
        Ok(BeamProblem {
            header: SceneHeader::new(&FAMILY, case, scene),
            setup: BeamSetup {
                scene: s.clone(),
                numerics: *n,
                grid: Grid::of_scene(scene),
                limits: case.limits(),
            },
            ladders: scene.ladders.values(),
            quick: scene.quick.values(),
            reference: None,
        })
    }


    /// One run of a registered variant with this scene's setup (or `setup`).
    pub(super) fn run_with(
        setup: &BeamSetup,
        v: &Variant,
        stepping: Stepping,
        observe: &Observe,
    ) -> Result<RunOutput<BeamObs>, String> {
        (v.run_fn::<RunFn>()?)(setup, stepping, observe)
    }

    /// The scores and series of a run: the whole-run measures (`run_measures`), the time
    /// error, the errors against the reference (`reference_errors`), then the series with
    /// the primary metric's error track and the tip's tracks (`tracks`).
    fn score(&self, v: &Variant, out: &RunOutput<BeamObs>) -> (Scores, Series) {
        let mut s = Scores::default();
        let tracked: Vec<(f64, BeamObs)> = out.samples.iter().map(|x| (x.t, x.obs)).collect();
        let scored: Vec<(f64, BeamObs)> = out.scored().map(|x| (x.t, x.obs)).collect();
        let failed = out
            .failure
            .as_ref()
            .map(|f| format!("run failed ({}) at t = {}", f.kind.name(), f.t));
        let bal_scored = self.run_measures(v, out, &tracked, &scored, &failed, &mut s);
        let mut primary_error = None;
        let time_error = self.time_error(v, &failed, &scored);
        match &time_error {
            Ok(e) => s.set(
                "tip_time_error_max",
                e.iter().copied().fold(0.0, f64::max),
            ),
            Err(why) => s.null("tip_time_error_max", why.clone()),
        }
        if self.header.primary_metric == "tip_time_error_max" {
            primary_error = time_error.ok();
        }
        if let Some(e) = self.reference_errors(&failed, &scored, &mut s) {
            primary_error = Some(e);
        }
        let series = Series {
            t: scored.iter().map(|x| x.0).collect(),
            energy: bal_scored.unwrap_or_else(|| vec![f64::NAN; scored.len()]),
            constraint: out.scored().map(|x| x.residual).collect(),
            conditioning: out.scored().map(|x| x.conditioning).collect(),
            primary_error,
            primary_metric: self.header.primary_metric.clone(),
            tracks: self.tracks(&scored),
        };
        (s, series)
    }

    /// The measures of a run that need no reference: `tip_deflection_max` over the samples
    /// (`tracked`), `energy_balance_error_max`, `momentum_error_max` and
    /// `constraint_error_max` over the score times (`scored`), each null with the reason
    /// where it does not apply. Returns the balance's residual at the score times (the
    /// series' `energy`), None when the samples miss the end of the torque.
    fn run_measures(
        &self,
        v: &Variant,
        out: &RunOutput<BeamObs>,
        tracked: &[(f64, BeamObs)],
        scored: &[(f64, BeamObs)],
        failed: &Option<String>,
        s: &mut Scores,
    ) -> Option<Vec<f64>> {
        let scene = &self.setup.scene;
        let tip_max = tracked
            .iter()
            .map(|(_, o)| o.tip_deflection.abs())
            .fold(0.0, f64::max);
        s.set("tip_deflection_max", tip_max);
        // The balance needs the free hub's angle at t_off: the whole sample track holds it.
        let bal = balance(&scene.base, tracked);
        let stride = out.score_stride.max(1);
        let bal_scored: Option<Vec<f64>> = bal
            .as_ref()
            .map(|b| b.iter().step_by(stride).copied().collect());
        match (failed, &bal_scored) {
            (Some(why), _) => s.null("energy_balance_error_max", why.clone()),
            (None, None) => s.null(
                "energy_balance_error_max",
                "the samples miss the end of the torque",
            ),
            (None, Some(b)) => s.set(
                "energy_balance_error_max",
                b.iter().fold(0.0_f64, |m, x| m.max(x.abs())) / scene.energy_scale,
            ),
        }
        match (scene.base, failed) {
            (Base::SpinUp { .. }, _) => s.null(
                "momentum_error_max",
                "prescribed base: the drive changes the angular momentum",
            ),
            (Base::Free { .. }, Some(why)) => s.null("momentum_error_max", why.clone()),
            (Base::Free { torque, t_off, .. }, None) => {
                let h = torque * t_off;
                let e = scored
                    .iter()
                    .filter(|(t, _)| *t >= t_off - 1e-9 * t_off)
                    .map(|(_, o)| ((o.momentum - h) / h).abs())
                    .fold(0.0, f64::max);
                s.set("momentum_error_max", e);
            }
        }
        if super::family::constrained(v.formulation) {
            match failed {
                Some(why) => s.null("constraint_error_max", why.clone()),
                None => s.set(
                    "constraint_error_max",
                    scored.iter().map(|(_, o)| o.constraint).fold(0.0, f64::max),
                ),
            }
        } else {
            s.null(
                "constraint_error_max",
                format!("{} has no boundary constraints", v.formulation),
            );
        }
        bal_scored
    }

    /// `tip_deflection_error_max` and `hub_rate_error_max` against the attached reference
    /// (nothing without one), null with the reason where they do not apply. Returns the
    /// primary metric's error at the score times when it is one of them.
    fn reference_errors(
        &self,
        failed: &Option<String>,
        scored: &[(f64, BeamObs)],
        s: &mut Scores,
    ) -> Option<Vec<f64>> {
        let (r, _) = self.reference.as_ref()?;
        let names = ["tip_deflection_error_max", "hub_rate_error_max"];
        let free = matches!(self.setup.scene.base, Base::Free { .. });
        if !free {
            s.null(names[1], "prescribed base: the hub rate is given");
        }
        if let Some(why) = failed {
            s.null(names[0], why.clone());
            if free {
                s.null(names[1], why.clone());
            }
            return None;
        }
        if scored.len() != r.t.len() {
            let why = format!(
                "run has {} score points, reference {}",
                scored.len(),
                r.t.len()
            );
            s.null(names[0], why.clone());
            if free {
                s.null(names[1], why);
            }
            return None;
        }
        let tip: Vec<f64> = scored
            .iter()
            .zip(&r.tip_deflection)
            .map(|((_, o), x)| (o.tip_deflection - x).abs())
            .collect();
        let rate: Vec<f64> = scored
            .iter()
            .zip(&r.hub_rate)
            .map(|((_, o), x)| (o.hub_rate - x).abs())
            .collect();
        s.set(names[0], tip.iter().copied().fold(0.0, f64::max));
        if free {
            s.set(names[1], rate.iter().copied().fold(0.0, f64::max));
        }
        match self.header.primary_metric.as_str() {
            "tip_deflection_error_max" => Some(tip),
            "hub_rate_error_max" if free => Some(rate),
            _ => None,
        }
    }

    /// The series' tracks: the tip deflection at the score times and, with a reference
    /// attached, the reference's where its score grid has the time.
    fn tracks(&self, scored: &[(f64, BeamObs)]) -> BTreeMap<String, Vec<Option<f64>>> {
        let mut tracks = BTreeMap::new();
        tracks.insert(
            "tip_deflection".to_string(),
            scored.iter().map(|(_, o)| Some(o.tip_deflection)).collect(),
        );
        if let Some((r, _)) = &self.reference {
            // The reference's score grid is the run's from t = 0 (a failed run's is a prefix).
            let on_grid = |i: usize, t: f64| {
                r.t.get(i)
                    .is_some_and(|x| (x - t).abs() <= 1e-9 * t.abs().max(1.0))
            };
            tracks.insert(
                "tip_deflection_reference".to_string(),
                scored
                    .iter()
                    .enumerate()
                    .map(|(i, (t, _))| on_grid(i, *t).then(|| r.tip_deflection[i]))
                    .collect(),
            );
        }
        tracks
    }

    /// `|v_tip - v_tip,self|` on the score grid against the formulation's self-convergence
    /// track (`reference.rs`), or why there is none.
    fn time_error(
        &self,
        v: &Variant,
        failed: &Option<String>,
        scored: &[(f64, BeamObs)],
    ) -> Result<Vec<f64>, String> {
        if let Some(why) = failed {
            return Err(why.clone());
        }
        let (r, _) = self.reference.as_ref().ok_or("no reference attached")?;
        let track = r
            .self_convergence
            .iter()
            .find(|x| x.formulation == v.formulation)
            .ok_or_else(|| format!("no self-convergence track of {}", v.formulation))?;
        let tip = track.tip_deflection.as_ref().ok_or_else(|| {
            format!(
                "{} has no converged trajectory ({})",
                v.formulation,
                track.failure.as_deref().unwrap_or("its run failed")
            )
        })?;
        if tip.len() != scored.len() {
            return Err(format!(
                "run has {} score points, the self-convergence track {}",
                scored.len(),
                tip.len()
            ));
        }
        Ok(scored
            .iter()
            .zip(tip)
            .map(|((_, o), x)| (o.tip_deflection - x).abs())
            .collect())
    }

    /// The trajectory columns of a run.
    fn columns(&self, out: &RunOutput<BeamObs>) -> Columns {
        let samples: Vec<(f64, BeamObs)> = out.samples.iter().map(|x| (x.t, x.obs)).collect();
        let col = |f: fn(&BeamObs) -> f64| samples.iter().map(|(_, o)| f(o)).collect();
        let bal = balance(&self.setup.scene.base, &samples)
            .unwrap_or_else(|| vec![f64::NAN; samples.len()]);
        Columns {
            t: samples.iter().map(|x| x.0).collect(),
            columns: vec![
                ("tip_deflection", 1, col(|o| o.tip_deflection)),
                ("tip_axial", 1, col(|o| o.tip_axial)),
                ("hub_angle", 1, col(|o| o.hub_angle)),
                ("hub_rate", 1, col(|o| o.hub_rate)),
                ("energy", 1, col(|o| o.kinetic + o.strain)),
                ("energy_balance", 1, bal),
                ("momentum", 1, col(|o| o.momentum)),
                ("constraint", 1, col(|o| o.constraint)),
            ],
        }
    }
}

impl Problem for BeamProblem {
    crate::problem::scene_problem_methods!();
    fn accuracy_claim(&self, metric: &str) -> Option<f64> {
        let (r, _) = self.reference.as_ref()?;
        match metric {
            "tip_deflection_error_max" => Some(r.accuracy_claim.tip_deflection),
            "hub_rate_error_max" => Some(r.accuracy_claim.hub_rate),
            "tip_time_error_max" => Some(
                r.self_convergence
                    .iter()
                    .filter_map(|x| x.time_estimate)
                    .fold(0.0, f64::max),
            ),
            _ => None,
        }
    }
    /// The reference's own error: the larger of its step and mesh estimates (the claim's
    /// third part, the cross-check against `modal_stiffened`, is that model's distance to
    /// this one, which the physical ranking measures).
    fn physical_claim(&self, metric: &str) -> Option<f64> {
        let (r, _) = self.reference.as_ref()?;
        let c = &r.provenance.checks;
        match metric {
            "tip_deflection_error_max" => Some(
                c.time_estimate
                    .tip_deflection
                    .max(c.mesh_estimate.tip_deflection),
            ),
            "hub_rate_error_max" => Some(c.time_estimate.hub_rate.max(c.mesh_estimate.hub_rate)),
            _ => self.accuracy_claim(metric),
        }
    }
    fn accuracy_claim_for(&self, metric: &str, formulation: &str) -> Option<f64> {
        if metric != "tip_time_error_max" {
            return self.accuracy_claim(metric);
        }
        let (r, _) = self.reference.as_ref()?;
        r.self_convergence
            .iter()
            .find(|x| x.formulation == formulation)
            .and_then(|x| x.time_estimate)
    }
    /// The clamped-free beam's first bending period at rest, `2 pi / ((beta_1 L)^2
    /// sqrt(EI / (rho A L^4)))` with `beta_1 L = 1.8751` (3.80 rad/s, 1.65 s on the spin-ups;
    /// 0.0440 rad/s, 143 s on flexsat, where it is the clamped beam's period, not the free
    /// hub's: a time scale for the search's horizon).
    fn first_period(&self) -> Option<f64> {
        let b = &self.setup.scene.beam;
        let z = super::shapes::clamped_free_root(1);
        let omega = z * z * (b.ei / (b.rho_a * b.l.powi(4))).sqrt();
        Some(2.0 * std::f64::consts::PI / omega)
    }
    fn run(&self, v: &Variant, stepping: Stepping, want: Want) -> Result<Outcome, String> {
        let out = Self::run_with(&self.setup, v, stepping, &want.observe())?;
        let mut o = Outcome::of_run(&out);
        if want != Want::Timing {
            let (scores, series) = self.score(v, &out);
            o.scores = scores;
            o.series = Some(series);
        }
        if want == Want::Trajectory {
            o.columns = Some(self.columns(&out));
        }
        Ok(o)
    }
    fn make_reference(&self, root: &Path) -> Result<String, String> {
        super::reference::make(self, root)
    }
    fn check_reference(&self, root: &Path) -> Result<(bool, String), String> {
        super::reference_check::check(self, root)
    }
}
