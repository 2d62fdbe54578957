//! The rigid body's stored reference (docs/schemas.md, "Stored references"): position, unit
//! quaternion, velocity, body angular velocity and energy at the score times, with its provenance
//! (how it was made, the cross-check by a run that differs in integrator, parameterization and
//! formulation), its accuracy claim per quantity and the physics hash. Reading, staleness and
//! atomic writing are the shared code of `crate::reference`; this file is the schema, its column
//! check and the claim an order fit or baseline comparison uses per metric.
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

use crate::reference::{ReferenceError, Stored, columns_fit, load_as, save_as};

/// The cross-check of a numerical or exact reference against an independent run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CrossCheck {
    pub method: String,
    pub max_position_diff: Option<f64>,
    pub max_rotation_diff: f64,
    pub max_velocity_diff: Option<f64>,
    pub max_omega_diff: f64,
}

/// How a reference was made.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Provenance {
    pub command: String,
    pub method: String,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub tolerance: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub step: Option<f64>,
    pub git_commit: String,
    pub created_utc: String,
    pub rustc: String,
    pub cross_check: CrossCheck,
    /// max |E - E0| / max(|E0|, energy_scale) of the reference trajectory.
    pub energy_drift: f64,
}

/// Max-abs accuracy the reference claims, per quantity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AccuracyClaim {
    pub position: Option<f64>,
    pub rotation: f64,
    pub velocity: Option<f64>,
    pub omega: f64,
}

/// A stored reference trajectory.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Reference {
    pub case: String,
    pub scene: String,
    pub t: Vec<f64>,
    pub position: Vec<[f64; 3]>,
    pub quaternion: Vec<[f64; 4]>,
    pub velocity: Vec<[f64; 3]>,
    pub omega_body: Vec<[f64; 3]>,
    pub energy: Vec<f64>,
    pub provenance: Provenance,
    pub accuracy_claim: AccuracyClaim,
    pub inputs_sha256: String,
}

/// A loaded reference with the SHA-256 of its file.
#[derive(Debug, Clone)]
pub struct Loaded {
    pub reference: Reference,
    pub file_sha256: String,
}

impl Stored for Reference {
    fn times(&self) -> &[f64] {
        &self.t
    }
    fn check_columns(&self) -> Result<(), String> {
        columns_fit(
            self.t.len(),
            &[
                self.position.len(),
                self.quaternion.len(),
                self.velocity.len(),
                self.omega_body.len(),
                self.energy.len(),
            ],
        )?;
        finite_values("t", self.t.iter().map(std::slice::from_ref))?;
        finite_values("position", self.position.iter().map(|x| x.as_slice()))?;
        finite_values("quaternion", self.quaternion.iter().map(|x| x.as_slice()))?;
        finite_values("velocity", self.velocity.iter().map(|x| x.as_slice()))?;
        finite_values("omega_body", self.omega_body.iter().map(|x| x.as_slice()))?;
        finite_values("energy", self.energy.iter().map(std::slice::from_ref))?;
        for (k, q) in self.quaternion.iter().enumerate() {
            let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
            if (n - 1.0).abs() > UNIT_NORM_TOL {
                return Err(format!(
                    "key `quaternion[{k}]` has norm {n:e}; expected a unit quaternion (within \
                     {UNIT_NORM_TOL:e})"
                ));
            }
        }
        let c = &self.accuracy_claim;
        for (key, v) in [
            ("position", c.position),
            ("rotation", Some(c.rotation)),
            ("velocity", c.velocity),
            ("omega", Some(c.omega)),
        ] {
            if let Some(v) = v
                && !(0.0..=MAX_CLAIM).contains(&v)
            {
                return Err(format!(
                    "key `accuracy_claim.{key}` is {v:e}; expected a finite claim in [0, \
                     {MAX_CLAIM:e}]"
                ));
            }
        }
        Ok(())
    }
}

/// How far a stored quaternion may be from unit norm (the stored ones are within 4.5e-16; a
/// zero quaternion would score every run as exact: the geodesic of 0 is atan2(0, 0) = 0).
pub const UNIT_NORM_TOL: f64 = 1e-12;

/// The largest accuracy claim a rigid reference may make (rad, m, m/s, rad/s): the stored ones
/// are 1.2e-8 at most, and a reference no better than this cannot judge the targets of 1e-6
/// and below (a claim of 1e308 would make `reference --check` pass anything).
pub const MAX_CLAIM: f64 = 1e-6;

/// Every number of a column finite; the error names the first bad one by its key.
fn finite_values<'a>(key: &str, rows: impl Iterator<Item = &'a [f64]>) -> Result<(), String> {
    for (k, row) in rows.enumerate() {
        if let Some(x) = row.iter().find(|x| !x.is_finite()) {
            return Err(format!("key `{key}[{k}]` holds {x}; expected finite numbers"));
        }
    }
    Ok(())
}

/// Loads and validates a rigid-body reference; stale or malformed files are errors naming
/// the file.
pub fn load(
    root: &Path,
    case: &str,
    scene: &str,
    inputs_sha256: &str,
) -> Result<Loaded, ReferenceError> {
    let (reference, file_sha256) = load_as(root, case, scene, inputs_sha256)?;
    Ok(Loaded {
        reference,
        file_sha256,
    })
}

/// Writes a reference (pretty JSON, round-trip floats) atomically.
pub fn save(root: &Path, r: &Reference) -> std::io::Result<PathBuf> {
    save_as(root, &r.case, &r.scene, r)
}

/// Accuracy claim of a reference for a metric.
pub fn claim_for(r: &Reference, metric: &str) -> f64 {
    let c = &r.accuracy_claim;
    match metric {
        "position_error_max" => c.position.unwrap_or(c.rotation),
        "velocity_error_max" => c.velocity.unwrap_or(c.omega),
        "omega_error_max" => c.omega,
        _ => c.rotation,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::{ReferenceError, sha256_hex};

    fn sample(hash: &str) -> Reference {
        Reference {
            case: "c".into(),
            scene: "s".into(),
            t: vec![0.0, 0.1],
            position: vec![[0.0; 3], [0.1, 0.2, 1.0 / 3.0]],
            quaternion: vec![[1.0, 0.0, 0.0, 0.0], [0.6, 0.8, 0.0, 0.0]],
            velocity: vec![[0.0; 3]; 2],
            omega_body: vec![[0.0; 3]; 2],
            energy: vec![1.0, 1.0 + f64::EPSILON],
            provenance: Provenance {
                command: "x".into(),
                method: "m".into(),
                tolerance: None,
                step: Some(1e-3),
                git_commit: "abc".into(),
                created_utc: "now".into(),
                rustc: "r".into(),
                cross_check: CrossCheck {
                    method: "n".into(),
                    max_position_diff: Some(1e-12),
                    max_rotation_diff: 1e-12,
                    max_velocity_diff: None,
                    max_omega_diff: 2e-12,
                },
                energy_drift: 1e-15,
            },
            accuracy_claim: AccuracyClaim {
                position: Some(1e-12),
                rotation: 1e-12,
                velocity: None,
                omega: 1e-12,
            },
            inputs_sha256: hash.into(),
        }
    }

    /// A saved reference loads back bit-identically (round-trip floats), and a changed inputs
    /// hash makes it stale, a missing file is `Missing`, a truncated file `Unreadable`.
    #[test]
    fn round_trip_stale_missing_truncated() {
        let dir = std::env::temp_dir().join(format!("mbdbench-ref-{}", std::process::id()));
        let r = sample("h1");
        let p = save(&dir, &r).unwrap();
        let l = load(&dir, "c", "s", "h1").unwrap();
        assert_eq!(l.reference, r);
        assert_eq!(l.file_sha256, sha256_hex(&std::fs::read(&p).unwrap()));
        let e = load(&dir, "c", "s", "h2").unwrap_err();
        assert!(matches!(e, ReferenceError::Stale { .. }));
        assert!(e.to_string().contains("inputs_sha256"), "{e}");
        assert!(matches!(
            load(&dir, "c", "other", "h1").unwrap_err(),
            ReferenceError::Missing { .. }
        ));
        let text = std::fs::read_to_string(&p).unwrap();
        std::fs::write(&p, &text[..text.len() / 2]).unwrap();
        let e = load(&dir, "c", "s", "h1").unwrap_err();
        assert!(matches!(e, ReferenceError::Unreadable { .. }));
        assert!(e.to_string().contains("s.json"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
