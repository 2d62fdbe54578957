//! The fiber column's references: exact for the static scenes, external (OpenSees) for the
//! cyclic and dynamic ones.
//!
//! **Exact** (`references/<case>/<scene>.json`, made by `mbdbench reference`): the tip at
//! every score time `t` (the load factor) from the Bisshopp-Drucker elastica
//! (`elastica.rs`, at `alpha = t F L^2/EI`) or the roll-up's circle (at
//! `lambda = t M L/(2 pi EI)`), as displacements `top_displacement = across L`,
//! `top_axial = (along - 1) L` and `top_rotation`; cross-checked by shooting on the
//! equilibrium ODE (`shooting.rs`, RK4 with 8192 steps, no elliptic integral), whose largest
//! difference is the accuracy claim.
//!
//! **External** (`references/fiber_column/opensees/<scene>.json`, schema
//! `mbdbench.opensees_reference/1`, made by the Python script beside it): `mbdbench` cannot
//! recompute it, so it checks it: the file's SHA-256 against `MANIFEST.json` in the same
//! folder (whose `provenance` block must name the tool, the command, the accuracy claim and
//! the cross-check), its schema and scene, its columns (`t`, `top_displacement`, `top_axial`,
//! `top_rotation`, `base_shear`, `axial_force`, of one length), that it holds every score
//! time, and that its model is the case's (height, axial load, and for the pulse the mass
//! and the damping coefficient): a reference of another column is stale. Its accuracy claim
//! per column is its stored difference from a run at half the increment, relative to the
//! column's peak (`half_increment.relative_to_peak`). `reference --check` says how to
//! regenerate it (`generator.regenerate`).
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::read_limited::{MANIFEST, REFERENCE, read_within};
use crate::reference::{self, Stored};

/// The columns a reference holds after `t`, in this order.
pub const COLUMNS: [&str; 5] = [
    "top_displacement",
    "top_axial",
    "top_rotation",
    "base_shear",
    "axial_force",
];

/// A reference track at the score times: `t` and the columns of [`COLUMNS`] (an exact
/// reference has no forces: those columns are empty).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Track {
    pub t: Vec<f64>,
    pub columns: [Vec<f64>; 5],
}

impl Track {
    /// The column named `name` (empty when the reference has none).
    pub fn column(&self, name: &str) -> &[f64] {
        COLUMNS
            .iter()
            .position(|c| *c == name)
            .map_or(&[][..], |i| &self.columns[i])
    }
}

/// The exact reference's cross-check.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CrossCheck {
    pub method: String,
    /// The largest difference over the score times and the three columns (m, rad).
    pub max_diff: f64,
}

/// How the exact reference was made.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Provenance {
    pub command: String,
    pub method: String,
    pub git_commit: String,
    pub created_utc: String,
    pub rustc: String,
    pub cross_check: CrossCheck,
}

/// A static scene's stored exact reference.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExactReference {
    pub case: String,
    pub scene: String,
    pub t: Vec<f64>,
    pub top_displacement: Vec<f64>,
    pub top_axial: Vec<f64>,
    pub top_rotation: Vec<f64>,
    pub provenance: Provenance,
    /// The claim on the tip's position and rotation (m, rad): the cross-check's difference.
    pub accuracy_claim: f64,
    pub inputs_sha256: String,
}

impl Stored for ExactReference {
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
        reference::columns_fit(
            self.t.len(),
            &[
                self.top_displacement.len(),
                self.top_axial.len(),
                self.top_rotation.len(),
            ],
        )
    }
}

impl ExactReference {
    /// Its track (no force columns).
    pub fn track(&self) -> Track {
        Track {
            t: self.t.clone(),
            columns: [
                self.top_displacement.clone(),
                self.top_axial.clone(),
                self.top_rotation.clone(),
                vec![],
                vec![],
            ],
        }
    }
}

/// The parts of an OpenSees reference file `mbdbench` reads.
#[derive(Debug, Clone, Deserialize)]
struct OpenSeesFile {
    schema: String,
    scene: String,
    generator: Generator,
    model: serde_json::Value,
    data: BTreeMap<String, Vec<f64>>,
    half_increment: HalfIncrement,
}

#[derive(Debug, Clone, Deserialize)]
struct Generator {
    opensees: String,
    regenerate: String,
}

#[derive(Debug, Clone, Deserialize)]
struct HalfIncrement {
    relative_to_peak: BTreeMap<String, f64>,
    peak_abs: BTreeMap<String, f64>,
}

/// The schema of an OpenSees reference file.
pub const OPENSEES_SCHEMA: &str = "mbdbench.opensees_reference/1";

/// A checked OpenSees reference at the score times.
#[derive(Debug, Clone, PartialEq)]
pub struct External {
    pub track: Track,
    /// Per column: the claim relative to the column's peak.
    pub claim: BTreeMap<String, f64>,
    pub peak: BTreeMap<String, f64>,
    pub sha256: String,
    pub path: PathBuf,
    pub regenerate: String,
    pub opensees: String,
}

/// What the case says the reference's model must be: `(key path in the file's `model`,
/// value, the case key it comes from)`.
pub type ModelCheck = Vec<(&'static str, f64, &'static str)>;

/// The folder of the OpenSees references under a references root.
pub fn opensees_dir(root: &Path) -> PathBuf {
    root.join("fiber_column").join("opensees")
}

fn model_value(model: &serde_json::Value, path: &str) -> Option<f64> {
    path.split('.').try_fold(model, |v, k| v.get(k))?.as_f64()
}

/// The bytes of `file` under the OpenSees folder (`opensees_dir(root)`), its SHA-256 and
/// path, checked against the folder's `MANIFEST.json`: the manifest's `provenance` block must
/// name the tool, the command, the accuracy claim and the cross-check, and the file's hash
/// must be the one it lists (else it was changed after generation). Both are read as regular
/// files inside `root` of at most `read_limited::REFERENCE` and `MANIFEST` bytes. `what` names
/// the reference in the error when the file cannot be read.
pub fn read_listed(root: &Path, file: &str, what: &str) -> Result<(Vec<u8>, String, PathBuf), String> {
    let dir = opensees_dir(root);
    let path = dir.join(file);
    let shown = path.display().to_string();
    let bytes = read_within(root, &path, REFERENCE).map_err(|e| {
        format!("{e}; the OpenSees reference of {what} is made by references/fiber_column/opensees/generate.py")
    })?;
    let sha = reference::sha256_hex(&bytes);
    let manifest_path = dir.join("MANIFEST.json");
    let manifest: serde_json::Value = read_within(root, &manifest_path, MANIFEST)
        .map_err(|e| e.to_string())
        .and_then(|b| {
            serde_json::from_slice(&b).map_err(|e| format!("{}: {e}", manifest_path.display()))
        })?;
    for k in ["tool", "command", "accuracy_claim", "cross_check"] {
        if manifest
            .get("provenance")
            .and_then(|p| p.get(k))
            .and_then(|v| v.as_str())
            .is_none()
        {
            return Err(format!(
                "{}: key `provenance.{k}` is missing",
                manifest_path.display()
            ));
        }
    }
    let key = format!("references/fiber_column/opensees/{file}");
    let listed = manifest
        .get("sha256")
        .and_then(|m| m.get(&key))
        .and_then(|v| v.as_str())
        .ok_or_else(|| format!("{}: key `sha256.{key}` is missing", manifest_path.display()))?;
    if listed != sha {
        return Err(format!(
            "{shown}: its SHA-256 {sha} differs from MANIFEST.json's {listed}: the file was \
             changed after it was generated"
        ));
    }
    Ok((bytes, sha, path))
}

/// Loads and checks the OpenSees reference of `scene` (module docs), sampled at the score
/// times `k score_every`, `k = 0..=t_end/score_every`.
pub fn load_external(
    root: &Path,
    scene: &str,
    t_end: f64,
    score_every: f64,
    model: &ModelCheck,
) -> Result<External, String> {
    let (bytes, sha, path) = read_listed(root, &format!("{scene}.json"), scene)?;
    let shown = path.display().to_string();
    let f: OpenSeesFile =
        serde_json::from_slice(&bytes).map_err(|e| format!("{shown}: {e}"))?;
    if f.schema != OPENSEES_SCHEMA {
        return Err(format!(
            "{shown}: key `schema` is `{}`, expected `{OPENSEES_SCHEMA}`",
            f.schema
        ));
    }
    if f.scene != scene {
        return Err(format!("{shown}: key `scene` is `{}`, expected `{scene}`", f.scene));
    }
    for (path_in_model, want, case_key) in model {
        let got = model_value(&f.model, path_in_model);
        let same = got.is_some_and(|g| (g - want).abs() <= 1e-12 * want.abs().max(1e-300));
        if !same {
            return Err(format!(
                "{shown}: stale: key `model.{path_in_model}` is {got:?}, the case's `{case_key}` \
                 is {want}; regenerate it ({})",
                f.generator.regenerate
            ));
        }
    }
    let t = f.data.get("t").ok_or(format!("{shown}: key `data.t` is missing"))?;
    let mut cols: Vec<&Vec<f64>> = vec![];
    for c in COLUMNS {
        let col = f
            .data
            .get(c)
            .ok_or_else(|| format!("{shown}: key `data.{c}` is missing"))?;
        if col.len() != t.len() {
            return Err(format!(
                "{shown}: key `data.{c}` has {} values, `data.t` {}",
                col.len(),
                t.len()
            ));
        }
        cols.push(col);
    }
    let n = crate::case::steps_dividing(t_end, score_every)
        .ok_or("score_every does not divide t_end")?;
    let mut track = Track::default();
    let mut j = 0;
    for k in 0..=n {
        let tk = k as f64 * score_every;
        while j < t.len() && t[j] < tk - 1e-9 * t_end.max(1.0) {
            j += 1;
        }
        if j >= t.len() || (t[j] - tk).abs() > 1e-9 * t_end.max(1.0) {
            return Err(format!(
                "{shown}: key `data.t` has no value at the score time {tk}"
            ));
        }
        track.t.push(tk);
        for (i, col) in cols.iter().enumerate() {
            track.columns[i].push(col[j]);
        }
    }
    Ok(External {
        track,
        claim: f.half_increment.relative_to_peak,
        peak: f.half_increment.peak_abs,
        sha256: sha,
        path,
        regenerate: f.generator.regenerate,
        opensees: f.generator.opensees,
    })
}
