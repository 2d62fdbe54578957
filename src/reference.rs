//! Stored references (design.md, "References"): one JSON per scene under
//! `references/<case>/<scene>.json` holding the trajectory at the score times, its provenance
//! (how it was made, the cross-check by a run that differs in integrator, parameterization and
//! formulation), its accuracy claim and the SHA-256 of the physics it was made from.
//!
//! Floats are written with `serde_json`'s `float_roundtrip` so that they read back exactly.
//! Files are written atomically (a temporary file renamed into place), so an interrupted
//! write never leaves a truncated file that looks complete. A reference is *stale* when its
//! `inputs_sha256` differs from the case's current one; loading checks it.
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};

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

/// Why a reference cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum ReferenceError {
    #[error("{path}: missing reference (run `mbdbench reference --case {case} --scene {scene}`)")]
    Missing {
        path: String,
        case: String,
        scene: String,
    },
    #[error("{path}: {message}")]
    Unreadable { path: String, message: String },
    #[error(
        "{path}: stale reference: key `inputs_sha256` is {stored} but the case's physics hash to {current} (regenerate with `mbdbench reference --case {case} --scene {scene}`)"
    )]
    Stale {
        path: String,
        case: String,
        scene: String,
        stored: String,
        current: String,
    },
}

/// `references/<case>/<scene>.json` under `root`.
pub fn path(root: &Path, case: &str, scene: &str) -> PathBuf {
    root.join(case).join(format!("{scene}.json"))
}

/// Hex SHA-256 of bytes.
pub fn sha256_hex(bytes: &[u8]) -> String {
    let d = Sha256::digest(bytes);
    d.iter().map(|b| format!("{b:02x}")).collect()
}

/// A loaded reference with the SHA-256 of its file.
#[derive(Debug, Clone)]
pub struct Loaded {
    pub reference: Reference,
    pub file_sha256: String,
}

/// What the shared loader needs of a family's stored reference file.
pub trait Stored: serde::de::DeserializeOwned {
    fn case(&self) -> &str;
    fn scene(&self) -> &str;
    fn inputs_sha256(&self) -> &str;
    /// A message when the columns do not fit together (unequal or zero lengths).
    fn check_columns(&self) -> Result<(), String>;
}

impl Stored for Reference {
    fn case(&self) -> &str {
        &self.case
    }
    fn scene(&self) -> &str {
        &self.scene
    }
    fn inputs_sha256(&self) -> &str {
        &self.inputs_sha256
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
        )
    }
}

/// Every column as long as `t`, and `t` not empty.
pub fn columns_fit(n: usize, lens: &[usize]) -> Result<(), String> {
    if n == 0 || lens.iter().any(|l| *l != n) {
        return Err(format!(
            "columns have unequal or zero lengths: t {n}, others {lens:?}"
        ));
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

/// Loads and validates a family's reference file `references/<case>/<scene>.json`: readable,
/// its columns consistent, its case and scene the expected ones, not stale; returns it with
/// the SHA-256 of the file.
pub fn load_as<R: Stored>(
    root: &Path,
    case: &str,
    scene: &str,
    inputs_sha256: &str,
) -> Result<(R, String), ReferenceError> {
    let p = path(root, case, scene);
    let shown = p.display().to_string();
    let bytes = match std::fs::read(&p) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(ReferenceError::Missing {
                path: shown,
                case: case.into(),
                scene: scene.into(),
            });
        }
        Err(e) => {
            return Err(ReferenceError::Unreadable {
                path: shown,
                message: e.to_string(),
            });
        }
    };
    let reference: R = serde_json::from_slice(&bytes).map_err(|e| ReferenceError::Unreadable {
        path: shown.clone(),
        message: e.to_string(),
    })?;
    reference
        .check_columns()
        .map_err(|message| ReferenceError::Unreadable {
            path: shown.clone(),
            message,
        })?;
    if reference.case() != case || reference.scene() != scene {
        return Err(ReferenceError::Unreadable {
            path: shown,
            message: format!(
                "key `case`/`scene` is {}/{}, expected {case}/{scene}",
                reference.case(),
                reference.scene()
            ),
        });
    }
    if reference.inputs_sha256() != inputs_sha256 {
        return Err(ReferenceError::Stale {
            path: shown,
            case: case.into(),
            scene: scene.into(),
            stored: reference.inputs_sha256().to_string(),
            current: inputs_sha256.into(),
        });
    }
    let sha = sha256_hex(&bytes);
    Ok((reference, sha))
}

/// Writes `bytes` to `path` atomically (temporary file in the same folder, then rename).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let tmp = path.with_extension(format!("tmp{}", std::process::id()));
    std::fs::write(&tmp, bytes)?;
    std::fs::rename(&tmp, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&tmp);
    })
}

/// Writes a reference (pretty JSON, round-trip floats) atomically.
pub fn save(root: &Path, r: &Reference) -> std::io::Result<PathBuf> {
    save_as(root, &r.case, &r.scene, r)
}

/// Writes any family's reference file (pretty JSON, round-trip floats) atomically.
pub fn save_as<R: Serialize>(
    root: &Path,
    case: &str,
    scene: &str,
    r: &R,
) -> std::io::Result<PathBuf> {
    let p = path(root, case, scene);
    let text = serde_json::to_string_pretty(r).map_err(std::io::Error::other)?;
    write_atomic(&p, text.as_bytes())?;
    Ok(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(hash: &str) -> Reference {
        Reference {
            case: "c".into(),
            scene: "s".into(),
            t: vec![0.0, 0.1],
            position: vec![[0.0; 3], [0.1, 0.2, 1.0 / 3.0]],
            quaternion: vec![[1.0, 0.0, 0.0, 0.0], [0.9, 0.1, 0.0, 0.0]],
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
