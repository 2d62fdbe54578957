//! One compiled fiber-column scene behind the `Problem` seam: the setup, the ladders, which
//! variants apply to its loading, its reference (`reference.rs`: exact for the static
//! scenes, OpenSees' run for the cyclic and dynamic ones) and the scores.
//!
//! Scores (cases/README.md, "fiber_column"), each relative so that one bound reads the
//! same on every scene:
//! - `tip_error`: `|tip - exact| / L` at the end of a static scene; `tip_error_max` its
//!   largest value over the score times (the roll-up's arc);
//! - `base_shear_error_rms` and `base_shear_error_max` over the score times, relative to
//!   the reference's peak `|V|`;
//! - `dissipated_energy_error`: `|W - W_ref| / |W_ref|` with `W = integral of V du + N dw`
//!   by the trapezoid rule on the score grid, the same way from both tracks;
//! - `equilibrium_residual_max`: the equilibrium check's largest out-of-balance force over
//!   the score times (`run.rs`) relative to the run's peak applied load.
//!
//! A metric that does not apply to the scene's kind is null with the reason.
use std::path::Path;

use super::case::{ColumnCase, ColumnScene, Loading};
use super::elastica::{elastica_tip, rollup_tip};
use super::family::{FAMILY, RunFn};
use super::opensees::{self, External};
use super::opensees_model;
use super::reference::{CrossCheck, ExactReference, Provenance, Track};
use super::run::{ColumnObs, Form, Keep, RunOut, ColumnSetup};
use super::shooting::shooting_tip;
use crate::case::{Case, CaseError, Scene};
use crate::integrate::MethodInfo;
use crate::metrics::Scores;
use crate::problem::{Columns, Outcome, Problem, SceneHeader, Stepping, Variant, Want};
use crate::reference;
use crate::run::Grid;
use crate::case::Ladders;
use crate::summary::{self, Series};

/// The attached reference.
#[derive(Debug, Clone)]
enum Attached {
    Exact(Box<ExactReference>, String),
    External(Box<External>),
}

/// A fiber-column scene with its reference (once attached).
#[derive(Debug, Clone)]
pub struct FiberProblem {
    header: SceneHeader,
    /// The scene's place in its case file (`scene[i]` in case keys).
    scene_index: usize,
    energy_scale: f64,
    setup: ColumnSetup,
    ladders: Ladders,
    quick: Ladders,
    reference: Option<Attached>,
}

const STATIC_METRICS: [&str; 2] = ["tip_error", "tip_error_max"];
const DYNAMIC_METRICS: [&str; 3] = [
    "top_displacement_error_max",
    "peak_displacement_error",
    "residual_displacement_error",
];
const FORCE_METRICS: [&str; 3] = [
    "base_shear_error_rms",
    "base_shear_error_max",
    "dissipated_energy_error",
];

impl FiberProblem {
    pub fn new(case: &Case, scene: &Scene) -> Result<Self, CaseError> {
        let (Some(c), Some(s)) = (
            case.physics::<ColumnCase>(),
            scene.physics::<ColumnScene>(),
        ) else {
            return Err(CaseError {
                file: case.file.clone(),
                key: "model".into(),
                message: "not a fiber-column case".into(),
            });
        };
        Ok(FiberProblem {
            header: SceneHeader::new(&FAMILY, case, scene),
            scene_index: scene.index,
            energy_scale: case.energy_scale,
            setup: ColumnSetup {
                case: c.clone(),
                scene: s.clone(),
                grid: Grid {
                    t_end: scene.t_end,
                    sample_every: scene.sample_every,
                    score_every: scene.score_every,
                },
                max_steps: case.max_steps,
                max_rhs_evals: case.max_rhs_evals,
                max_work: case.max_work,
            },
            ladders: scene.ladders.values(),
            quick: scene.quick.values(),
            reference: None,
        })
    }

    fn loading(&self) -> &Loading {
        &self.setup.scene.loading
    }

    /// The exact tip (m, rad) at load factor `t`, by the closed form and by shooting.
    fn exact_at(&self, t: f64) -> Result<([f64; 3], [f64; 3]), String> {
        let l = self.setup.case.height;
        let ei = self.setup.case.elastic.ok_or("an exact tip needs an elastic section")?.1;
        let (tip, shot) = match *self.loading() {
            Loading::TipForce(f) => {
                let alpha = t * f * l * l / ei;
                (elastica_tip(alpha)?, shooting_tip(alpha, 0.0, 1 << 13))
            }
            Loading::TipMoment(m) => {
                let k = t * m * l / ei;
                (
                    rollup_tip(k / std::f64::consts::TAU),
                    shooting_tip(0.0, k, 1 << 13),
                )
            }
            _ => return Err("only a static scene has an exact reference".into()),
        };
        let d = |e: &super::elastica::ElasticaTip| {
            [e.across * l, (e.along - 1.0) * l, e.rotation]
        };
        Ok((d(&tip), d(&shot)))
    }

    /// The scene's OpenSees reference, checked (`opensees.rs`) and compared with the case's
    /// model field by field (`opensees_model.rs`).
    fn external(&self, root: &Path) -> Result<External, String> {
        let (g, s) = (&self.setup.grid, &self.setup);
        let same_model = |model: &serde_json::Value, settings: &serde_json::Value| {
            let at = (self.scene_index, g.t_end);
            opensees_model::check(&s.case, &s.scene, at.0, at.1, model, settings)
        };
        opensees::load_external(root, &self.header.scene, g.t_end, g.score_every, &same_model)
    }

    /// The exact track at the score times and the shooting cross-check's largest
    /// difference.
    fn exact_track(&self) -> Result<(Track, f64), String> {
        let g = &self.setup.grid;
        let n = crate::case::steps_dividing(g.t_end, g.score_every)
            .ok_or("score_every does not divide t_end")?;
        let mut track = Track::default();
        let mut worst = 0.0f64;
        for k in 0..=n {
            let t = k as f64 * g.score_every;
            let (e, s) = self.exact_at(t)?;
            track.t.push(t);
            for i in 0..3 {
                track.columns[i].push(e[i]);
                worst = worst.max((e[i] - s[i]).abs());
            }
        }
        Ok((track, worst))
    }

    fn reference_track(&self) -> Option<Track> {
        match self.reference.as_ref()? {
            Attached::Exact(r, _) => Some(r.track()),
            Attached::External(x) => Some(x.track.clone()),
        }
    }
}

/// `sum of V du + N dw` by the trapezoid rule over a track.
fn input_work(u: &[f64], w: &[f64], v: &[f64], n: &[f64]) -> f64 {
    (1..u.len())
        .map(|k| {
            0.5 * (v[k] + v[k - 1]) * (u[k] - u[k - 1]) + 0.5 * (n[k] + n[k - 1]) * (w[k] - w[k - 1])
        })
        .sum()
}

impl Problem for FiberProblem {
    fn header(&self) -> &SceneHeader {
        &self.header
    }
    fn header_mut(&mut self) -> &mut SceneHeader {
        &mut self.header
    }
    fn grid(&self) -> &Grid {
        &self.setup.grid
    }
    // The attached reference's times are the old grid's: dropped.
    fn set_t_end(&mut self, t_end: f64) {
        self.setup.grid.t_end = t_end;
        self.reference = None;
    }
    fn ladder(&self, quick: bool, info: &MethodInfo) -> &[f64] {
        if quick { &self.quick } else { &self.ladders }.for_method(info)
    }
    fn na_reason(&self, v: &Variant) -> Option<String> {
        let kind = self.loading().kind();
        let int = v.integrator;
        match kind {
            "static" if int != "newton_load" => {
                return Some(format!(
                    "{int} is for the {} scenes; a static scene steps its load with \
                     newton_load",
                    if int.starts_with("newton") { "cyclic" } else { "dynamic" }
                ));
            }
            "cyclic" if !int.starts_with("newton_disp") => {
                return Some(format!(
                    "{int} is for {}; a cyclic scene prescribes the top's displacement \
                     (newton_disp*)",
                    if int == "newton_load" { "load control" } else { "the pulse" }
                ));
            }
            "dynamic" if int.starts_with("newton") => {
                return Some(format!(
                    "{int} is a static algorithm; the pulse is stepped in time by newmark, \
                     hht, gen_alpha or midpoint"
                ));
            }
            _ => {}
        }
        if v.formulation == "force_based_fine" && self.setup.case.numerics.fine_elements.is_none()
        {
            return Some("the case gives no numerics.fine_elements".into());
        }
        None
    }
    fn as_load_path(&mut self) -> bool {
        if self.loading().kind() != "static" {
            return false;
        }
        let g = &mut self.setup.grid;
        (g.sample_every, g.score_every) = (g.t_end, g.t_end);
        self.reference = None;
        true
    }
    fn first_period(&self) -> Option<f64> {
        let Loading::Pulse { mass, .. } = *self.loading() else {
            return None;
        };
        let mut col = super::run::build::<crate::rotation::So3>(&self.setup, Form::ForceBased).ok()?;
        let mut log = super::run::Log::new(Keep::Final);
        let num = &self.setup.case.numerics;
        let mut newton = crate::structural::equilibrium::Newton::new(num.tol, num.max_iter).ok()?;
        super::run::prelude(&mut col, &mut newton, &self.setup, &mut log).ok()?;
        let w = super::dynamic::omega1(&mut col, mass).ok()?;
        Some(std::f64::consts::TAU / w)
    }
    fn attach_reference(&mut self, root: &Path) -> Result<(), String> {
        if matches!(self.loading(), Loading::TipForce(_) | Loading::TipMoment(_)) {
            let (r, sha): (ExactReference, String) =
                self.header.load_reference(root, &self.setup.grid)?;
            self.reference = Some(Attached::Exact(Box::new(r), sha));
        } else {
            self.reference = Some(Attached::External(Box::new(self.external(root)?)));
        }
        Ok(())
    }
    fn reference_sha256(&self) -> Option<&str> {
        match self.reference.as_ref()? {
            Attached::Exact(_, sha) => Some(sha),
            Attached::External(x) => Some(&x.sha256),
        }
    }
    fn accuracy_claim(&self, metric: &str) -> Option<f64> {
        match self.reference.as_ref()? {
            Attached::Exact(r, _) if STATIC_METRICS.contains(&metric) => {
                Some(r.accuracy_claim / self.setup.case.height)
            }
            Attached::External(x) if FORCE_METRICS.contains(&metric) => {
                x.claim.get("base_shear").copied()
            }
            Attached::External(x) if DYNAMIC_METRICS.contains(&metric) => {
                x.claim.get("top_displacement").copied()
            }
            _ => None,
        }
    }
    fn reference_variant(&self) -> Option<crate::problem::ReferenceVariant> {
        match self.reference.as_ref()? {
            Attached::External(x) => x.variant.clone(),
            Attached::Exact(..) => None,
        }
    }
    fn run(&self, v: &Variant, stepping: Stepping, want: Want) -> Result<Outcome, String> {
        let Stepping::Dt(dt) = stepping else {
            return Err("the fiber column's methods take a fixed step".into());
        };
        let keep = match want {
            Want::Timing => Keep::Final,
            Want::Scored | Want::Trajectory => Keep::Samples,
        };
        let out = (v.run_fn::<RunFn>()?)(&self.setup, dt, keep)?;
        let mut o = Outcome {
            stats: out.stats,
            failure: out.failure.clone(),
            ..Outcome::default()
        };
        match want {
            Want::Timing => {}
            Want::Scored => {
                let (scores, series) = self.score(&out);
                o.scores = scores;
                o.series = Some(series);
            }
            Want::Trajectory => o.columns = Some(columns(&out.samples)),
        }
        Ok(o)
    }
    fn make_reference(&self, root: &Path) -> Result<String, String> {
        if !matches!(self.loading(), Loading::TipForce(_) | Loading::TipMoment(_)) {
            let x = self.external(root)?;
            return Ok(format!(
                "{}: external reference (OpenSees {}), not made by mbdbench; the folder's \
                 SHA-256s and generator, its schema, columns, claims, score times and whole \
                 model check out; regenerate with: {}",
                x.path.display(),
                x.opensees,
                x.regenerate
            ));
        }
        let (track, diff) = self.exact_track()?;
        let method = match self.loading() {
            Loading::TipForce(_) => "the elastica (Bisshopp-Drucker, Carlson's forms)",
            _ => "the roll-up's circle",
        };
        let claim = diff.max(f64::EPSILON * self.setup.case.height);
        let r = ExactReference {
            case: self.header.case.clone(),
            scene: self.header.scene.clone(),
            t: track.t.clone(),
            top_displacement: track.columns[0].clone(),
            top_axial: track.columns[1].clone(),
            top_rotation: track.columns[2].clone(),
            provenance: Provenance {
                command: format!(
                    "mbdbench reference --case {} --scene {}",
                    self.header.case, self.header.scene
                ),
                method: method.into(),
                git_commit: summary::git_commit().into(),
                created_utc: summary::now_utc(),
                rustc: summary::rustc_version().into(),
                cross_check: CrossCheck {
                    method: "shooting on the equilibrium ODE, RK4 with 8192 steps".into(),
                    max_diff: diff,
                },
            },
            accuracy_claim: claim,
            inputs_sha256: self.header.inputs_sha256.clone(),
        };
        let path = reference::save_as(root, &self.header.case, &self.header.scene, &r)
            .map_err(|e| e.to_string())?;
        Ok(format!(
            "{}: {method}; cross-check by shooting: {diff:.2e}; claim {claim:.2e}",
            path.display()
        ))
    }
    fn check_reference(&self, root: &Path) -> Result<(bool, String), String> {
        if !matches!(self.loading(), Loading::TipForce(_) | Loading::TipMoment(_)) {
            return Ok(match self.external(root) {
                Ok(x) => (
                    true,
                    format!(
                        "{}/{}: external OpenSees reference {}: every file MANIFEST.json \
                         lists (the generator too) with its SHA-256, schema, columns, claims, \
                         score times, and every field of its model and settings as the \
                         case's; regenerate with: {}",
                        self.header.case,
                        self.header.scene,
                        x.path.display(),
                        x.regenerate
                    ),
                ),
                Err(e) => (false, format!("{}/{}: {e}", self.header.case, self.header.scene)),
            });
        }
        let h = &self.header;
        let (stored, _): (ExactReference, _) =
            reference::load_as(root, &h.case, &h.scene, &h.inputs_sha256)
                .map_err(|e| e.to_string())?;
        // The bound is the claim recomputed now (the shooting cross-check's difference, as
        // `make_reference` computes it), never the file's; the file's claim must lie within
        // `CLAIM_SLACK` of it either way.
        let (now, cross) = self.exact_track()?;
        let claim_now = cross.max(f64::EPSILON * self.setup.case.height);
        let old = stored.track();
        let mut d = 0.0f64;
        for i in 0..3 {
            for (a, b) in now.columns[i].iter().zip(&old.columns[i]) {
                d = d.max((a - b).abs());
            }
        }
        let c = stored.accuracy_claim;
        let claim_ok = c.is_finite() && c >= claim_now / CLAIM_SLACK && c <= claim_now * CLAIM_SLACK;
        let ok = d <= claim_now && claim_ok && now.t.len() == old.t.len();
        Ok((
            ok,
            format!(
                "{}/{}: recomputed vs stored: {d:.2e} (bound: the recomputed claim {claim_now:.2e}; the stored claim {c:.2e} within {CLAIM_SLACK}x of it: {})",
                h.case,
                h.scene,
                if claim_ok { "yes" } else { "NO" }
            ),
        ))
    }
}

/// How far a stored exact reference's claim may lie from the recomputed one, either way.
pub const CLAIM_SLACK: f64 = 10.0;

/// The samples as the family's columns.
fn columns(s: &[ColumnObs]) -> Columns {
    let col = |f: fn(&ColumnObs) -> f64| s.iter().map(f).collect::<Vec<f64>>();
    Columns {
        t: col(|o| o.t),
        columns: vec![
            ("top_displacement", 1, col(|o| o.top_displacement)),
            ("top_axial", 1, col(|o| o.top_axial)),
            ("top_rotation", 1, col(|o| o.top_rotation)),
            ("base_shear", 1, col(|o| o.base_shear)),
            ("axial_force", 1, col(|o| o.axial_force)),
            ("energy_kinetic", 1, col(|o| o.energy_kinetic)),
            ("energy_strain", 1, col(|o| o.energy_strain)),
            ("energy_dissipated", 1, col(|o| o.energy_dissipated)),
            ("work_input", 1, col(|o| o.work_input)),
        ],
    }
}

/// A run's named tracks beside its series (`Series::tracks`).
type Tracks = std::collections::BTreeMap<String, Vec<Option<f64>>>;

impl FiberProblem {
    /// The scores and series of a run.
    fn score(&self, out: &RunOut) -> (Scores, Series) {
        let mut s = Scores::default();
        let g = &self.setup.grid;
        let per_score = (g.score_every / g.sample_every).round().max(1.0) as usize;
        let scored: Vec<&ColumnObs> = out.samples.iter().step_by(per_score).collect();
        let failed = out
            .failure
            .as_ref()
            .map(|f| format!("run failed ({}) at t = {}", f.kind.name(), f.t));
        let kind = self.loading().kind();
        equilibrium_check(&mut s, &scored, out, &failed);
        let reference = self.reference_track();
        let mut tracks = Tracks::new();
        let why = why_unscored(&failed, reference.as_ref(), scored.len());
        let primary_error = match (kind, &why, &reference) {
            ("static", None, Some(r)) => {
                Some(score_static(&mut s, &scored, r, self.setup.case.height))
            }
            ("dynamic", None, Some(r)) => self.score_dynamic(&mut s, &scored, r, &mut tracks),
            (_, None, Some(r)) => self.score_cyclic(&mut s, &scored, r, &mut tracks),
            _ => None,
        };
        self.close_scores(&mut s, out, kind, &failed, why.unwrap_or_default());
        let series = self.series(&scored, kind, reference.as_ref(), tracks, primary_error);
        (s, series)
    }

    /// The dynamic scene's displacement and base-shear errors against `r`; returns the
    /// primary error track when the primary metric is the displacement's.
    fn score_dynamic(
        &self,
        s: &mut Scores,
        scored: &[&ColumnObs],
        r: &Track,
        tracks: &mut Tracks,
    ) -> Option<Vec<f64>> {
        let u_ref = r.column("top_displacement");
        let peak_ref = u_ref.iter().fold(0.0f64, |p, x| p.max(x.abs()));
        let d: Vec<f64> = scored
            .iter()
            .zip(u_ref)
            .map(|(o, x)| (o.top_displacement - x).abs() / peak_ref)
            .collect();
        let peak = scored
            .iter()
            .fold(0.0f64, |p, o| p.max(o.top_displacement.abs()));
        s.set("top_displacement_error_max", d.iter().copied().fold(0.0, f64::max));
        s.set("peak_displacement_error", (peak - peak_ref).abs() / peak_ref);
        s.set("residual_displacement_error", *d.last().unwrap_or(&f64::NAN));
        let v_ref = r.column("base_shear");
        base_shear_errors(s, scored, v_ref);
        tracks.insert(
            "base_shear_reference".to_string(),
            v_ref.iter().map(|x| Some(*x)).collect(),
        );
        (self.header.primary_metric == "top_displacement_error_max").then_some(d)
    }

    /// The cyclic scene's base-shear and dissipated-energy errors against `r`; returns the
    /// primary error track when the primary metric is a base-shear one.
    fn score_cyclic(
        &self,
        s: &mut Scores,
        scored: &[&ColumnObs],
        r: &Track,
        tracks: &mut Tracks,
    ) -> Option<Vec<f64>> {
        let v_ref = r.column("base_shear");
        let d = base_shear_errors(s, scored, v_ref);
        let col = |f: fn(&ColumnObs) -> f64| scored.iter().map(|o| f(o)).collect::<Vec<_>>();
        let w = input_work(
            &col(|o| o.top_displacement),
            &col(|o| o.top_axial),
            &col(|o| o.base_shear),
            &col(|o| o.axial_force),
        );
        let w_ref = input_work(
            r.column("top_displacement"),
            r.column("top_axial"),
            v_ref,
            r.column("axial_force"),
        );
        s.set("dissipated_energy_error", ((w - w_ref) / w_ref).abs());
        tracks.insert(
            "base_shear_reference".to_string(),
            v_ref.iter().map(|x| Some(*x)).collect(),
        );
        self.header.primary_metric.starts_with("base_shear").then_some(d)
    }

    /// The scene kind's metrics not computed become null with `why` (the dynamic scene's
    /// energy balance from the run's books); the other kinds' metrics stay absent.
    fn close_scores(
        &self,
        s: &mut Scores,
        out: &RunOut,
        kind: &str,
        failed: &Option<String>,
        why: String,
    ) {
        if kind == "dynamic" {
            s.values.remove("equilibrium_residual_max");
            s.reasons.remove("equilibrium_residual_max");
            match (&out.balance_max, failed) {
                (Some(b), None) => s.set("energy_balance_error_max", b / self.energy_scale),
                (_, Some(f)) => s.null("energy_balance_error_max", f.clone()),
                (None, None) => s.null("energy_balance_error_max", "no energy books"),
            }
        }
        for m in applicable_metrics(kind) {
            if !s.values.contains_key(*m) {
                s.null(m, why.clone());
            }
        }
    }

    /// The run's series at the score points: the tracks of the top displacement and base
    /// shear (and the reference's), the dynamic scene's energy balance residual.
    fn series(
        &self,
        scored: &[&ColumnObs],
        kind: &str,
        reference: Option<&Track>,
        mut tracks: Tracks,
        primary_error: Option<Vec<f64>>,
    ) -> Series {
        if let Some(r) = reference {
            tracks.insert(
                "top_displacement_reference".to_string(),
                r.columns[0].iter().map(|x| Some(*x)).collect(),
            );
        }
        tracks.insert(
            "top_displacement".to_string(),
            scored.iter().map(|o| Some(o.top_displacement)).collect(),
        );
        tracks.insert(
            "base_shear".to_string(),
            scored.iter().map(|o| Some(o.base_shear)).collect(),
        );
        Series {
            t: scored.iter().map(|o| o.t).collect(),
            // The balance's residual where the scene keeps energy books (the pulse; the
            // report's `Quantity::Balance`), else none.
            energy: scored
                .iter()
                .map(|o| match kind {
                    "dynamic" => {
                        o.energy_kinetic + o.energy_strain + o.energy_dissipated - o.work_input
                    }
                    _ => f64::NAN,
                })
                .collect(),
            constraint: vec![None; scored.len()],
            conditioning: vec![f64::NAN; scored.len()],
            primary_error,
            primary_metric: self.header.primary_metric.clone(),
            tracks,
        }
    }
}

/// The equilibrium check: the largest residual over the score points relative to the peak
/// load, or null when the run failed.
fn equilibrium_check(s: &mut Scores, scored: &[&ColumnObs], out: &RunOut, failed: &Option<String>) {
    match failed {
        Some(why) => s.null("equilibrium_residual_max", why.clone()),
        None => {
            let r = scored
                .iter()
                .filter_map(|o| o.equilibrium_residual)
                .fold(0.0f64, f64::max);
            s.set(
                "equilibrium_residual_max",
                r / out.peak_load.max(f64::MIN_POSITIVE),
            );
        }
    }
}

/// Why the reference errors cannot be scored: the run failed, its score points are not the
/// reference's, or there is no reference; None when they can.
fn why_unscored(failed: &Option<String>, reference: Option<&Track>, n: usize) -> Option<String> {
    let mismatch = reference.and_then(|r| {
        (r.t.len() != n).then(|| format!("run has {n} score points, reference {}", r.t.len()))
    });
    failed.clone().or(mismatch).or_else(|| {
        reference
            .is_none()
            .then(|| "no reference attached".to_string())
    })
}

/// The base shear's error against `v_ref` relative to its peak at every score point, its
/// RMS and maximum set as scores.
fn base_shear_errors(s: &mut Scores, scored: &[&ColumnObs], v_ref: &[f64]) -> Vec<f64> {
    let peak = v_ref.iter().fold(0.0f64, |p, x| p.max(x.abs()));
    let d: Vec<f64> = scored
        .iter()
        .zip(v_ref)
        .map(|(o, x)| (o.base_shear - x).abs() / peak)
        .collect();
    let rms = (d.iter().map(|x| x * x).sum::<f64>() / d.len() as f64).sqrt();
    s.set("base_shear_error_rms", rms);
    s.set("base_shear_error_max", d.iter().copied().fold(0.0, f64::max));
    d
}

/// The static scene's tip error against `r`, relative to the column's height `l`, at every
/// score point (the primary error track).
fn score_static(s: &mut Scores, scored: &[&ColumnObs], r: &Track, l: f64) -> Vec<f64> {
    let e: Vec<f64> = scored
        .iter()
        .enumerate()
        .map(|(k, o)| {
            (o.top_displacement - r.columns[0][k]).hypot(o.top_axial - r.columns[1][k]) / l
        })
        .collect();
    s.set("tip_error", *e.last().unwrap_or(&f64::NAN));
    s.set("tip_error_max", e.iter().copied().fold(0.0, f64::max));
    e
}

/// The metrics of a scene kind (the others' do not apply and are absent, never 0).
fn applicable_metrics(kind: &str) -> &'static [&'static str] {
    match kind {
        "static" => &["tip_error", "tip_error_max", "equilibrium_residual_max"],
        "cyclic" => &[
            "base_shear_error_rms",
            "base_shear_error_max",
            "dissipated_energy_error",
            "equilibrium_residual_max",
        ],
        _ => &[
            "top_displacement_error_max",
            "peak_displacement_error",
            "residual_displacement_error",
            "base_shear_error_rms",
            "base_shear_error_max",
            "energy_balance_error_max",
        ],
    }
}
