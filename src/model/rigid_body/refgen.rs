//! Making and checking references (`mbdbench reference`; cases/README.md, "References and how
//! they are checked").
//!
//! - Numerical references (`reference = "numerical"`: nine_spring, heavy_top): `gauss6` on
//!   `so3` in the body formulation at a small step, cross-checked by `dop853` at a tight
//!   tolerance on `quat_proj` in the spatial formulation, a run that differs in integrator,
//!   parameterization *and* formulation.
//! - Exact references (`reference = "exact"`: gimbal_lock, free_body): the matrix exponential
//!   for a spherical body's constant spin, the Jacobi-elliptic Euler-Poinsot solution
//!   otherwise (`model::rigid_body::torque_free`), cross-checked by the same numerical run as above.
//!
//! The accuracy claim is, per quantity, the larger of the cross-check difference and the
//! reference's own energy error. `--check` recomputes the primary trajectory and the cross-check,
//! and passes when the stored trajectory differs from the recomputed one by at most the claim
//! recomputed now (never the file's own), and the file's claim lies within `CLAIM_SLACK` of it.
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

use crate::case::ReferenceKind;
use crate::math::so3;
use crate::model::rigid_body::{Observation, RigidBody};
use crate::model::rigid_body::torque_free::{TorqueFreeExact, spin_exact};

use super::reference::{AccuracyClaim, CrossCheck, Provenance, Reference};
use crate::model::rigid_body::registry::{self, RigidSetup};
use crate::run::Grid;
use crate::model::rigid_body::plan::ScenePlan;
use crate::summary;

/// A trajectory at the score times.
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    pub t: Vec<f64>,
    pub obs: Vec<Observation>,
}

/// How a primary reference trajectory is computed.
#[derive(Debug, Clone, PartialEq)]
pub enum Primary {
    /// `gauss6`/`so3`/`body` at step `dt`.
    Gauss6 { dt: f64 },
    /// Constant spin of a spherical body.
    Spin,
    /// Euler-Poinsot via Jacobi elliptic functions.
    EllipticTorqueFree,
}

/// The step of a numerical reference or cross-check run: the largest step at most `target`
/// that divides `score_every` (halving from `score_every`).
fn fine_step(grid: &Grid, target: f64) -> f64 {
    let mut h = grid.score_every;
    while h > target {
        h *= 0.5;
    }
    h
}

fn numerical_step(body: &RigidBody) -> f64 {
    numerical_target(body.pivot_com.is_some())
}

/// The target step of a numerical reference: fast spin (heavy top, 150 rad/s, on a pivot)
/// needs a finer step than the slow cases.
fn numerical_target(pivoted: bool) -> f64 {
    if pivoted { 1e-4 } else { 2e-3 }
}

/// The step of a numerical reference (`gauss6`) of a scene on `grid`, for a body on a pivot
/// or not (the family's estimate counts the reference's steps with it).
pub fn reference_step(grid: &Grid, pivoted: bool) -> f64 {
    fine_step(grid, numerical_target(pivoted))
}

/// Chooses how the primary reference of a scene is computed.
pub fn primary_for(kind: ReferenceKind, plan: &ScenePlan) -> Result<Primary, String> {
    match kind {
        ReferenceKind::NUMERICAL => Ok(Primary::Gauss6 {
            dt: fine_step(&plan.setup.grid, numerical_step(&plan.setup.body)),
        }),
        ReferenceKind::EXACT => {
            let b = &plan.setup.body;
            if !b.springs.is_empty() || b.gravity.is_some() || b.pivot_com.is_some() {
                return Err(format!(
                    "{}/{}: an exact reference needs a torque-free body",
                    plan.header.case, plan.header.scene
                ));
            }
            let j = b.inertia;
            let off = j[(0, 1)].abs() + j[(0, 2)].abs() + j[(1, 2)].abs();
            if off != 0.0 {
                return Err(format!(
                    "{}/{}: an exact reference needs a diagonal inertia",
                    plan.header.case, plan.header.scene
                ));
            }
            if j[(0, 0)] == j[(1, 1)] && j[(1, 1)] == j[(2, 2)] {
                Ok(Primary::Spin)
            } else {
                Ok(Primary::EllipticTorqueFree)
            }
        }
        other => Err(format!(
            "{}/{}: the rigid body computes its references; `reference = \"{}\"` is not one \
             of its kinds (numerical, exact)",
            plan.header.case,
            plan.header.scene,
            other.name()
        )),
    }
}

fn score_times(grid: &Grid) -> Result<Vec<f64>, String> {
    let n = crate::run::divides(grid.t_end, grid.score_every)
        .ok_or("score_every does not divide t_end")?;
    Ok((0..=n).map(|k| k as f64 * grid.score_every).collect())
}

/// Runs a registered variant and returns its score-grid trajectory.
fn run_track(
    setup: &RigidSetup,
    param: &str,
    integ: &str,
    form: &str,
    value: f64,
) -> Result<Track, String> {
    let v = registry::find(param, integ, form)
        .ok_or_else(|| format!("{param}/{integ}/{form} is not registered"))?;
    let out = (v.run)(setup, value)?;
    if let Some(f) = out.failure {
        return Err(format!(
            "reference run {param}/{integ}/{form} failed: {:?} at t = {}: {}",
            f.kind, f.t, f.message
        ));
    }
    let scored: Vec<_> = out.scored().collect();
    Ok(Track {
        t: scored.iter().map(|s| s.t).collect(),
        obs: scored.iter().map(|s| s.obs).collect(),
    })
}

/// Computes the primary trajectory.
pub fn primary_track(p: &Primary, plan: &ScenePlan) -> Result<Track, String> {
    let setup = &plan.setup;
    match p {
        Primary::Gauss6 { dt } => run_track(setup, "so3", "gauss6", "body", *dt),
        Primary::Spin => {
            let o = setup.initial;
            let r0 = o.q.to_rotation_matrix().into_inner();
            let w = r0 * o.omega;
            exact_track(setup, |t| spin_exact(w, r0, t))
        }
        Primary::EllipticTorqueFree => {
            let o = setup.initial;
            let j = setup.body.inertia;
            let r0 = o.q.to_rotation_matrix().into_inner();
            let exact =
                TorqueFreeExact::new(Vector3::new(j[(0, 0)], j[(1, 1)], j[(2, 2)]), o.omega, r0)?;
            exact_track(setup, |t| exact.at(t))
        }
    }
}

/// The track of a torque-free body at the score times: the attitude and body angular
/// velocity from `rotation(t)`, the centre of mass in uniform motion.
fn exact_track(
    setup: &RigidSetup,
    rotation: impl Fn(f64) -> (UnitQuaternion<f64>, Vector3<f64>),
) -> Result<Track, String> {
    let o = setup.initial;
    let t = score_times(&setup.grid)?;
    let obs = t
        .iter()
        .map(|&t| {
            let (q, omega) = rotation(t);
            Observation {
                q,
                x: o.x + o.v * t,
                v: o.v,
                omega,
            }
        })
        .collect();
    Ok(Track { t, obs })
}

/// The round-off `reference --check` allows (relative, as the summary's drift) between the
/// stored energy column and the energy of the stored states, and on top of the stated drift.
pub const ENERGY_ROUNDOFF: f64 = 1e-14;

/// Tolerance of the cross-check of a numerical reference: `dop853` on `quat_proj`, spatial
/// formulation (differs from `gauss6/so3/body` in integrator, chart and formulation).
pub const CROSS_TOL: f64 = 1e-13;

/// Step target of the cross-check of an exact reference: `gauss6` on `quat_proj`, spatial.
/// Below about 1e-3 round-off, not truncation, dominates over 1e5 steps (measured on
/// free_body/gni: 1.7e-12 rad at 7.8e-4, 4.0e-12 at 2.5e-4), so a finer step is not better.
pub const CROSS_STEP_EXACT: f64 = 1e-3;

/// The independent cross-check run and its description.
fn cross_track(kind: ReferenceKind, plan: &ScenePlan) -> Result<(Track, String), String> {
    match kind {
        ReferenceKind::NUMERICAL => Ok((
            run_track(&plan.setup, "quat_proj", "dop853", "spatial", CROSS_TOL)?,
            format!("dop853/quat_proj/spatial, tol {CROSS_TOL:e}"),
        )),
        ReferenceKind::EXACT => {
            let h = fine_step(&plan.setup.grid, CROSS_STEP_EXACT);
            Ok((
                run_track(&plan.setup, "quat_proj", "gauss6", "spatial", h)?,
                format!("gauss6/quat_proj/spatial, dt {h:e}"),
            ))
        }
        other => Err(format!(
            "no cross-check for a `{}` reference: the rigid body's are numerical or exact",
            other.name()
        )),
    }
}

/// Max differences between two tracks: (position, rotation, velocity, omega).
pub fn max_diffs(a: &Track, b: &Track) -> Result<[f64; 4], String> {
    if a.t.len() != b.t.len() {
        return Err(format!(
            "tracks differ in length: {} vs {}",
            a.t.len(),
            b.t.len()
        ));
    }
    let mut m = [0.0_f64; 4];
    for (x, y) in a.obs.iter().zip(&b.obs) {
        let d = [
            (x.x - y.x).norm(),
            so3::geodesic_quat(&x.q, &y.q),
            (x.v - y.v).norm(),
            (x.omega - y.omega).norm(),
        ];
        for i in 0..4 {
            if !d[i].is_finite() {
                return Err("non-finite difference".into());
            }
            m[i] = m[i].max(d[i]);
        }
    }
    Ok(m)
}

fn energy_drift(body: &RigidBody, tr: &Track, scale: f64) -> f64 {
    let e: Vec<f64> = tr.obs.iter().map(|o| body.energy(o)).collect();
    crate::metrics::energy_drift::max_relative(&e, scale)
}

fn method_name(p: &Primary) -> (String, Option<f64>) {
    match p {
        Primary::Gauss6 { dt } => ("gauss6/so3/body".into(), Some(*dt)),
        Primary::Spin => ("exact: R(t) = exp(t [w]x) R0 (constant spin)".into(), None),
        Primary::EllipticTorqueFree => (
            "exact: Euler-Poinsot, Jacobi sn/cn/dn by AGM, attitude via Carlson R_F/R_J".into(),
            None,
        ),
    }
}

/// Builds the reference of a scene (primary + cross-check + claim).
pub fn build(kind: ReferenceKind, plan: &ScenePlan) -> Result<Reference, String> {
    let p = primary_for(kind, plan)?;
    let primary = primary_track(&p, plan)?;
    let (cross, cross_method) = cross_track(kind, plan)?;
    let d = max_diffs(&primary, &cross)?;
    let translates = plan.setup.body.translates();
    let drift = energy_drift(&plan.setup.body, &primary, plan.energy_scale);
    // The energy error, as a relative number, bounds the reference's own error only in
    // order of magnitude; the claim takes the larger of it and the cross-check difference.
    let claim = |x: f64| x.max(drift);
    let (method, step) = method_name(&p);
    let body = &plan.setup.body;
    let to_arr3 = |v: &Vector3<f64>| [v.x, v.y, v.z];
    Ok(Reference {
        case: plan.header.case.clone(),
        scene: plan.header.scene.clone(),
        t: primary.t.clone(),
        position: primary.obs.iter().map(|o| to_arr3(&o.x)).collect(),
        quaternion: primary
            .obs
            .iter()
            .map(|o| {
                let q = so3::canonical(&o.q);
                [q.w, q.i, q.j, q.k]
            })
            .collect(),
        velocity: primary.obs.iter().map(|o| to_arr3(&o.v)).collect(),
        omega_body: primary.obs.iter().map(|o| to_arr3(&o.omega)).collect(),
        energy: primary.obs.iter().map(|o| body.energy(o)).collect(),
        provenance: Provenance {
            command: format!(
                "mbdbench reference --case {} --scene {}",
                plan.header.case, plan.header.scene
            ),
            method,
            tolerance: None,
            step,
            git_commit: summary::git_commit().into(),
            created_utc: summary::now_utc(),
            rustc: summary::rustc_version().into(),
            cross_check: CrossCheck {
                method: cross_method,
                max_position_diff: translates.then_some(d[0]),
                max_rotation_diff: d[1],
                max_velocity_diff: translates.then_some(d[2]),
                max_omega_diff: d[3],
            },
            energy_drift: drift,
        },
        accuracy_claim: AccuracyClaim {
            position: translates.then_some(claim(d[0])),
            rotation: claim(d[1]),
            velocity: translates.then_some(claim(d[2])),
            omega: claim(d[3]),
        },
        inputs_sha256: plan.header.inputs_sha256.clone(),
    })
}

/// Track of a stored reference.
pub fn stored_track(r: &Reference) -> Track {
    Track {
        t: r.t.clone(),
        obs: (0..r.t.len())
            .map(|k| {
                let q = r.quaternion[k];
                Observation {
                    q: UnitQuaternion::new_unchecked(Quaternion::new(q[0], q[1], q[2], q[3])),
                    x: Vector3::from(r.position[k]),
                    v: Vector3::from(r.velocity[k]),
                    omega: Vector3::from(r.omega_body[k]),
                }
            })
            .collect(),
    }
}

/// `reference --check`: recomputes the primary and compares with the stored reference.
/// Returns the differences and whether each is within the claim.
pub fn check(
    kind: ReferenceKind,
    plan: &ScenePlan,
    stored: &Reference,
) -> Result<(bool, String), String> {
    let p = primary_for(kind, plan)?;
    let now = primary_track(&p, plan)?;
    let d = max_diffs(&now, &stored_track(stored))?;
    // The bounds come from the recomputation alone: the claim the reference would have if it
    // were made now (its cross-check run and energy drift, recomputed), never the file's.
    let (cross, _) = cross_track(kind, plan)?;
    let dc = max_diffs(&now, &cross)?;
    let drift_now = energy_drift(&plan.setup.body, &now, plan.energy_scale);
    let recomputed: [f64; 4] = std::array::from_fn(|i| dc[i].max(drift_now));
    let c = &stored.accuracy_claim;
    let translates = plan.setup.body.translates();
    let claims = [
        c.position.filter(|_| translates),
        Some(c.rotation),
        c.velocity.filter(|_| translates),
        Some(c.omega),
    ];
    // The stored claim must say what the recomputation shows, within CLAIM_SLACK either way:
    // a claim far looser hides a wrong reference behind the gate's floors, one far tighter
    // promises what the reference does not hold.
    let claim_ok = claims.iter().zip(&recomputed).all(|(stored, now)| match stored {
        None => true,
        Some(x) => {
            let (x, now) = (x.max(CLAIM_FLOOR), now.max(CLAIM_FLOOR));
            x.is_finite() && x >= now / CLAIM_SLACK && x <= now * CLAIM_SLACK
        }
    });
    // The stored energy column: the energy of the stored states (to round-off, relative as the
    // summary's drift), and its drift within the reference's own stated energy drift.
    let scale = stored.energy[0].abs().max(plan.energy_scale);
    let body = &plan.setup.body;
    let de = stored_track(stored)
        .obs
        .iter()
        .zip(&stored.energy)
        .map(|(o, e)| (body.energy(o) - e).abs() / scale)
        .fold(0.0, f64::max);
    let drift = crate::metrics::energy_drift::max_relative(&stored.energy, plan.energy_scale);
    let ok = (0..4).all(|i| {
        claims[i].is_none() || d[i] <= recomputed[i].max(CLAIM_FLOOR)
    }) && claim_ok
        && de <= ENERGY_ROUNDOFF
        && drift <= drift_now + ENERGY_ROUNDOFF;
    let text = |x: Option<f64>| x.map_or("-".to_string(), |x| format!("{x:.2e}"));
    let msg = format!(
        "{}/{}: recomputed vs stored: position {:.2e}, rotation {:.2e}, velocity {:.2e}, omega {:.2e} (bounds recomputed from the cross-check and energy drift: {:.2e}, {:.2e}, {:.2e}, {:.2e}; stored claims {}, {}, {}, {} within {CLAIM_SLACK}x of them: {}); energy column vs its states {:.2e}, its drift {:.2e} (recomputed {:.2e})",
        plan.header.case,
        plan.header.scene,
        d[0],
        d[1],
        d[2],
        d[3],
        recomputed[0],
        recomputed[1],
        recomputed[2],
        recomputed[3],
        text(claims[0]),
        text(claims[1]),
        text(claims[2]),
        text(claims[3]),
        if claim_ok { "yes" } else { "NO" },
        de,
        drift,
        drift_now
    );
    Ok((ok, msg))
}

/// How far a stored claim may lie from the recomputed one, either way (round-off of the
/// cross-check run on another machine moves it by far less).
pub const CLAIM_SLACK: f64 = 10.0;

/// Below this a recomputed bound is round-off (rad, m, m/s or rad/s over the catalogue's
/// unit-scale bodies).
pub const CLAIM_FLOOR: f64 = 1e-15;
