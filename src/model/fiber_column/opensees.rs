//! The fiber column's external references: OpenSees' runs of the same column
//! (`references/fiber_column/opensees/<scene>.json`, schema `mbdbench.opensees_reference/1`,
//! made by `generate.py` beside them). `mbdbench` cannot recompute such a run, so it checks it
//! before scoring against it, and refuses it naming the file and the key:
//!
//! - **the folder** ([`read_listed`]): `MANIFEST.json` has its schema, a `provenance` block
//!   naming the tool, the command, the accuracy claim and the cross-check, and lists the
//!   generator (`generate.py`) and its pinned inputs (`../requirements.txt`); every file it
//!   lists (the records, the generator, its companions, its README) is present with the
//!   SHA-256 it lists, so nothing in the folder was changed after it was generated;
//! - **the record** ([`load_external`]): its top-level keys are the schema's, no other; its
//!   schema and scene; its `generator` block names a listed script with the hash the
//!   manifest lists and the manifest's versions; its `model` and `settings` are the case's
//!   (a check the caller passes: `opensees_model.rs` compares them field by field); `data`
//!   holds `t` and the five columns of [`COLUMNS`], no other, of one length, `t` strictly
//!   increasing (a repeated row is refused), every value finite, no column zero throughout
//!   (its peak divides the relative errors and the claims); every score time is present;
//!   `half_increment` states, per column, its peak (the data's, to 1e-12) and its accuracy
//!   claim `relative_to_peak` (the largest difference from the same run at half the
//!   increment, relative to that peak), finite, at least 0 and below [`CLAIM_MAX`];
//!   its `provenance` block, as every stored reference has one ([`check_provenance`]):
//!   exactly the keys of [`PROVENANCE_KEYS`], each a non-empty string, the tool naming the
//!   generator's OpenSees version, the command and the script the generator's.
//!
//! Where it fails: the hashes prove the files are those the generator wrote, not that
//! OpenSees computed them correctly; that is the cross-check's business (the manifest's
//! provenance).
use crate::read_limited::{MANIFEST, REFERENCE, read_within};
use serde::Deserialize;
use serde::de::IgnoredAny;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use super::reference::{COLUMNS, Track};
use crate::problem::ReferenceVariant;
use crate::reference::sha256_hex;

/// The schema of an OpenSees reference file.
pub const OPENSEES_SCHEMA: &str = "mbdbench.opensees_reference/1";

/// The schema of the folder's `MANIFEST.json`.
pub const MANIFEST_SCHEMA: &str = "mbdbench.opensees_manifest/1";

/// The generator and its pinned inputs, which the manifest must list (repository paths).
pub const GENERATOR: &str = "references/fiber_column/opensees/generate.py";
pub const REQUIREMENTS: &str = "references/fiber_column/requirements.txt";

/// The bound on an accuracy claim relative to its column's peak: a run whose half-increment
/// rerun differs from it by as much as the column's peak has not converged at all, and a
/// claim that large (or negative, or not finite) is a broken file, not a reference.
pub const CLAIM_MAX: f64 = 1.0;

/// The keys of a record's `provenance` block, written by `generate.py` (`record_provenance`):
/// the tool and its versions, the command that regenerates the record, its script, the
/// accuracy claim (read from `half_increment`) and the cross-check (mbdbench's agreement
/// with the record, as mbdbench measured it).
pub const PROVENANCE_KEYS: [&str; 5] = ["tool", "command", "script", "accuracy_claim", "cross_check"];

/// The folder of the OpenSees references under a references root.
pub fn opensees_dir(root: &Path) -> PathBuf {
    root.join("fiber_column").join("opensees")
}

/// The folder's `MANIFEST.json`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct Manifest {
    schema: String,
    opensees: String,
    openseespy: String,
    python: String,
    /// Repository path (`references/...`) to hex SHA-256.
    sha256: BTreeMap<String, String>,
    provenance: Option<BTreeMap<String, Value>>,
}

/// The file a manifest key names under the references root: the key must lie under
/// `references/` and must not climb out of it.
fn listed_path(root: &Path, key: &str) -> Option<PathBuf> {
    let rest = key.strip_prefix("references/")?;
    if rest.split('/').any(|part| part == ".." || part.is_empty()) {
        return None;
    }
    Some(root.join(rest))
}

/// Reads and checks the manifest of the OpenSees folder under `root` (module docs): its
/// schema, its provenance block, the generator and requirements listed, and every listed file
/// present with its listed hash.
fn check_manifest(root: &Path) -> Result<Manifest, String> {
    let path = opensees_dir(root).join("MANIFEST.json");
    let shown = path.display().to_string();
    let bytes = read_within(root, &path, MANIFEST).map_err(|e| e.to_string())?;
    let m: Manifest = serde_json::from_slice(&bytes).map_err(|e| format!("{shown}: {e}"))?;
    if m.schema != MANIFEST_SCHEMA {
        return Err(format!(
            "{shown}: key `schema` is `{}`, expected `{MANIFEST_SCHEMA}`",
            m.schema
        ));
    }
    for k in ["tool", "command", "accuracy_claim", "cross_check"] {
        let given = m.provenance.as_ref().and_then(|p| p.get(k)?.as_str());
        if given.is_none() {
            return Err(format!("{shown}: key `provenance.{k}` is missing"));
        }
    }
    for k in [GENERATOR, REQUIREMENTS] {
        if !m.sha256.contains_key(k) {
            return Err(format!(
                "{shown}: key `sha256.{k}` is missing: the generator and its pinned inputs \
                 must be hashed"
            ));
        }
    }
    for (key, listed) in &m.sha256 {
        let file = listed_path(root, key).ok_or_else(|| {
            format!("{shown}: key `sha256.{key}` does not name a file under references/")
        })?;
        let bytes = read_within(root, &file, REFERENCE)
            .map_err(|e| format!("{shown}: key `sha256.{key}`: {e}"))?;
        let sha = sha256_hex(&bytes);
        if &sha != listed {
            return Err(format!(
                "{}: its SHA-256 {sha} differs from MANIFEST.json's {listed} (key \
                 `sha256.{key}`): the file was changed after it was generated (after editing \
                 a companion such as README.md, `generate.py --manifest` lists it anew)",
                file.display()
            ));
        }
    }
    Ok(m)
}

/// The bytes of `file` under the OpenSees folder (`opensees_dir(root)`), its SHA-256 and
/// path, after the folder's check (module docs): `file` must be listed in `MANIFEST.json`,
/// and every listed file must have its listed hash. `what` names the reference in the error
/// when the file cannot be read.
pub fn read_listed(
    root: &Path,
    file: &str,
    what: &str,
) -> Result<(Vec<u8>, String, PathBuf), String> {
    read_checked(root, file, what).map(|(bytes, sha, path, _)| (bytes, sha, path))
}

/// [`read_listed`], with the manifest.
fn read_checked(
    root: &Path,
    file: &str,
    what: &str,
) -> Result<(Vec<u8>, String, PathBuf, Manifest), String> {
    let path = opensees_dir(root).join(file);
    let bytes = read_within(root, &path, REFERENCE).map_err(|e| {
        format!(
            "{e}; the OpenSees reference of {what} is made by \
             references/fiber_column/opensees/generate.py"
        )
    })?;
    let manifest = check_manifest(root)?;
    let key = format!("references/fiber_column/opensees/{file}");
    if !manifest.sha256.contains_key(&key) {
        return Err(format!(
            "{}: key `sha256.{key}` is missing",
            opensees_dir(root).join("MANIFEST.json").display()
        ));
    }
    let sha = sha256_hex(&bytes);
    Ok((bytes, sha, path, manifest))
}

/// An OpenSees reference file: the top-level keys of its schema, no other.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct OpenSeesFile {
    schema: String,
    scene: String,
    generator: Generator,
    /// The run's model and settings: compared with the case by the caller's check.
    model: Value,
    settings: Value,
    /// `t` and [`COLUMNS`], in that order.
    columns: Vec<String>,
    /// Descriptions of the columns (units, signs): documentation, not used.
    #[serde(rename = "units")]
    _units: IgnoredAny,
    #[serde(rename = "conventions")]
    _conventions: IgnoredAny,
    data: BTreeMap<String, Vec<f64>>,
    /// OpenSees' Newton iteration counts: documentation, not used.
    #[serde(rename = "iterations")]
    _iterations: IgnoredAny,
    half_increment: HalfIncrement,
    /// How the record was made ([`PROVENANCE_KEYS`]); read as a value so that a missing or
    /// malformed block is refused naming its key ([`check_provenance`]).
    provenance: Option<Value>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct Generator {
    script: String,
    script_sha256: String,
    opensees: String,
    openseespy: String,
    python: String,
    regenerate: String,
}

/// The run at half the increment (cyclic, `increment` in m) or step (pulse, `dt` in s),
/// compared at the common points; a column whose peak is zero has a null ratio.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct HalfIncrement {
    max_abs_diff: BTreeMap<String, Option<f64>>,
    peak_abs: BTreeMap<String, Option<f64>>,
    relative_to_peak: BTreeMap<String, Option<f64>>,
    /// The half run's increment or step and its iteration count: documentation, not used.
    #[serde(rename = "increment")]
    _increment: Option<f64>,
    #[serde(rename = "dt")]
    _dt: Option<f64>,
    #[serde(rename = "iterations_total")]
    _iterations_total: f64,
}

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
    /// The variant the record's scheme is (`scheme`), when it is one of ours.
    pub variant: Option<ReferenceVariant>,
}

/// The caller's comparison of a record's `model` and `settings` with its case: `Err` names
/// the first differing key of each side (`opensees_model.rs`).
pub type ModelCheck<'a> = &'a dyn Fn(&Value, &Value) -> Result<(), String>;

/// The record's generator is a listed script with its listed hash, run with the manifest's
/// versions.
fn check_generator(shown: &str, g: &Generator, m: &Manifest) -> Result<(), String> {
    let listed = m.sha256.get(&g.script).ok_or_else(|| {
        format!(
            "{shown}: key `generator.script` is `{}`, which MANIFEST.json does not list",
            g.script
        )
    })?;
    if &g.script_sha256 != listed {
        return Err(format!(
            "{shown}: key `generator.script_sha256` is {}, MANIFEST.json lists {listed} for \
             {}: the record was made by another version of its generator",
            g.script_sha256, g.script
        ));
    }
    for (key, got, want) in [
        ("opensees", &g.opensees, &m.opensees),
        ("openseespy", &g.openseespy, &m.openseespy),
        ("python", &g.python, &m.python),
    ] {
        if got != want {
            return Err(format!(
                "{shown}: key `generator.{key}` is `{got}`, MANIFEST.json's `{key}` is `{want}`"
            ));
        }
    }
    Ok(())
}

/// The record's `provenance` block: an object with exactly the keys of [`PROVENANCE_KEYS`],
/// each a non-empty string; its tool names the generator's OpenSees version, its command and
/// script are the generator's (`generator.regenerate`, `generator.script`).
fn check_provenance(shown: &str, p: Option<&Value>, g: &Generator) -> Result<(), String> {
    let p = p.ok_or_else(|| {
        format!(
            "{shown}: key `provenance` is missing: every record states how it was made \
             ({PROVENANCE_KEYS:?}); regenerate it ({})",
            g.regenerate
        )
    })?;
    let block = p.as_object().ok_or_else(|| {
        format!("{shown}: key `provenance` is {p}, expected an object of {PROVENANCE_KEYS:?}")
    })?;
    if let Some(k) = block.keys().find(|k| !PROVENANCE_KEYS.contains(&k.as_str())) {
        return Err(format!(
            "{shown}: key `provenance.{k}` is not a key of the schema ({PROVENANCE_KEYS:?})"
        ));
    }
    for k in PROVENANCE_KEYS {
        match block.get(k) {
            None => return Err(format!("{shown}: key `provenance.{k}` is missing")),
            Some(Value::String(s)) if !s.trim().is_empty() => {}
            Some(v) => {
                return Err(format!(
                    "{shown}: key `provenance.{k}` is {v}, expected a non-empty string"
                ));
            }
        }
    }
    let text = |k: &str| block[k].as_str().unwrap_or_default();
    let tool = format!("OpenSees {}", g.opensees);
    if !text("tool").contains(&tool) {
        return Err(format!(
            "{shown}: key `provenance.tool` is `{}`, which does not name `{tool}` \
             (`generator.opensees`)",
            text("tool")
        ));
    }
    for (k, want, from) in [
        ("command", &g.regenerate, "generator.regenerate"),
        ("script", &g.script, "generator.script"),
    ] {
        if text(k) != want {
            return Err(format!(
                "{shown}: key `provenance.{k}` is `{}`, `{from}` is `{want}`",
                text(k)
            ));
        }
    }
    Ok(())
}

/// The data's `t` and columns (in [`COLUMNS`] order), checked (module docs).
fn check_data<'f>(shown: &str, f: &'f OpenSeesFile) -> Result<Vec<&'f [f64]>, String> {
    let want: Vec<&str> = std::iter::once("t").chain(COLUMNS).collect();
    if f.columns != want {
        return Err(format!(
            "{shown}: key `columns` is {:?}, expected {want:?}",
            f.columns
        ));
    }
    if let Some(k) = f.data.keys().find(|k| !want.contains(&k.as_str())) {
        return Err(format!("{shown}: key `data.{k}` is not a column of the schema"));
    }
    let mut cols = vec![];
    for c in want {
        let col = f
            .data
            .get(c)
            .ok_or_else(|| format!("{shown}: key `data.{c}` is missing"))?;
        if let Some(k) = col.iter().position(|x| !x.is_finite()) {
            return Err(format!("{shown}: key `data.{c}[{k}]` is not finite"));
        }
        cols.push(col.as_slice());
    }
    let t = cols[0];
    if t.is_empty() {
        return Err(format!("{shown}: key `data.t` is empty"));
    }
    for (c, col) in COLUMNS.iter().zip(&cols[1..]) {
        if col.len() != t.len() {
            return Err(format!(
                "{shown}: key `data.{c}` has {} values, `data.t` {}",
                col.len(),
                t.len()
            ));
        }
        if col.iter().all(|x| *x == 0.0) {
            return Err(format!(
                "{shown}: key `data.{c}` is zero at every row: its peak, which the relative \
                 errors and claims divide by, would be zero"
            ));
        }
    }
    if let Some(k) = (1..t.len()).find(|&k| t[k] <= t[k - 1]) {
        let what = if t[k] == t[k - 1] {
            "repeats"
        } else {
            "goes back to"
        };
        return Err(format!(
            "{shown}: key `data.t` {what} t = {} at row {k} (row {} has {}): t must increase \
             strictly, one row per time",
            t[k],
            k - 1,
            t[k - 1]
        ));
    }
    Ok(cols)
}

/// The accuracy claims and peaks per column, checked against the data (module docs).
type Claims = (BTreeMap<String, f64>, BTreeMap<String, f64>);

fn check_claims(shown: &str, h: &HalfIncrement, cols: &[&[f64]]) -> Result<Claims, String> {
    for (block, map) in [
        ("max_abs_diff", &h.max_abs_diff),
        ("peak_abs", &h.peak_abs),
        ("relative_to_peak", &h.relative_to_peak),
    ] {
        if let Some(k) = map.keys().find(|k| !COLUMNS.contains(&k.as_str())) {
            return Err(format!(
                "{shown}: key `half_increment.{block}.{k}` is not a column of the schema"
            ));
        }
    }
    let get = |block: &str, map: &BTreeMap<String, Option<f64>>, c: &str| {
        match map.get(c) {
            None => Err(format!("{shown}: key `half_increment.{block}.{c}` is missing")),
            Some(None) => Err(format!(
                "{shown}: key `half_increment.{block}.{c}` is null (a column whose peak is \
                 zero)"
            )),
            Some(Some(x)) => Ok(*x),
        }
    };
    let (mut claim, mut peak) = (BTreeMap::new(), BTreeMap::new());
    for (c, col) in COLUMNS.iter().zip(&cols[1..]) {
        let data_peak = col.iter().fold(0.0f64, |p, x| p.max(x.abs()));
        let p = get("peak_abs", &h.peak_abs, c)?;
        if (p - data_peak).abs() > 1e-12 * data_peak {
            return Err(format!(
                "{shown}: key `half_increment.peak_abs.{c}` is {p:e}, the peak of `data.{c}` \
                 is {data_peak:e}"
            ));
        }
        let r = get("relative_to_peak", &h.relative_to_peak, c)?;
        if !(r.is_finite() && (0.0..CLAIM_MAX).contains(&r)) {
            return Err(format!(
                "{shown}: key `half_increment.relative_to_peak.{c}` is {r:e}; an accuracy \
                 claim relative to the column's peak must be finite, >= 0 and below \
                 {CLAIM_MAX:e}"
            ));
        }
        let d = get("max_abs_diff", &h.max_abs_diff, c)?;
        if (d / p - r).abs() > 1e-12 * r.max(f64::MIN_POSITIVE) {
            return Err(format!(
                "{shown}: key `half_increment.relative_to_peak.{c}` is {r:e}, but \
                 max_abs_diff / peak_abs is {:e}",
                d / p
            ));
        }
        claim.insert(c.to_string(), r);
        peak.insert(c.to_string(), p);
    }
    Ok((claim, peak))
}

/// The track at the score times `k score_every`, `k = 0..=t_end/score_every`: each must be a
/// row's `t` (to 1e-9 of `t_end`).
fn sample(shown: &str, cols: &[&[f64]], t_end: f64, score_every: f64) -> Result<Track, String> {
    let n = crate::case::steps_dividing(t_end, score_every)
        .ok_or("score_every does not divide t_end")?;
    let t = cols[0];
    let tol = 1e-9 * t_end.max(1.0);
    let mut track = Track::default();
    let mut j = 0;
    for k in 0..=n {
        let tk = k as f64 * score_every;
        while j < t.len() && t[j] < tk - tol {
            j += 1;
        }
        if j >= t.len() || (t[j] - tk).abs() > tol {
            return Err(format!(
                "{shown}: key `data.t` has no value at the score time {tk}"
            ));
        }
        track.t.push(tk);
        for (i, col) in cols[1..].iter().enumerate() {
            track.columns[i].push(col[j]);
        }
    }
    Ok(track)
}

/// Loads and checks the OpenSees reference of `scene` (module docs), sampled at the score
/// times `k score_every`, `k = 0..=t_end/score_every`; `model` compares the record's model
/// and settings with the case.
pub fn load_external(
    root: &Path,
    scene: &str,
    t_end: f64,
    score_every: f64,
    model: ModelCheck<'_>,
) -> Result<External, String> {
    let (bytes, sha, path, manifest) = read_checked(root, &format!("{scene}.json"), scene)?;
    let shown = path.display().to_string();
    let f: OpenSeesFile = serde_json::from_slice(&bytes).map_err(|e| format!("{shown}: {e}"))?;
    if f.schema != OPENSEES_SCHEMA {
        return Err(format!(
            "{shown}: key `schema` is `{}`, expected `{OPENSEES_SCHEMA}`",
            f.schema
        ));
    }
    if f.scene != scene {
        return Err(format!(
            "{shown}: key `scene` is `{}`, expected `{scene}`",
            f.scene
        ));
    }
    check_generator(&shown, &f.generator, &manifest)?;
    check_provenance(&shown, f.provenance.as_ref(), &f.generator)?;
    model(&f.model, &f.settings).map_err(|e| {
        format!(
            "{shown}: {e}; regenerate it ({})",
            f.generator.regenerate
        )
    })?;
    let cols = check_data(&shown, &f)?;
    let (claim, peak) = check_claims(&shown, &f.half_increment, &cols)?;
    let track = sample(&shown, &cols, t_end, score_every)?;
    Ok(External {
        track,
        claim,
        peak,
        sha256: sha,
        path,
        variant: scheme(&f.settings, &f.generator.opensees),
        regenerate: f.generator.regenerate,
        opensees: f.generator.opensees,
    })
}

/// The variant a record's scheme is, read from its `settings` once the model check has
/// passed (that check establishes the element is our `force_based` one and, for a cyclic
/// record, that its increment is the case's): OpenSees' `Newmark` with `gamma = 1/2`,
/// `beta = 1/4` at `dt` is our `newmark` (the trapezoidal rule) at `dt`; its
/// `DisplacementControl` at the protocol's increment is our `newton_disp` at one increment
/// with plain `Newton`, `newton_disp_ls` with `NewtonLineSearch`, `newton_disp_krylov` with
/// `KrylovNewton` (the algorithm decides only how the increment's equilibrium is found).
/// Anything else (another integrator or algorithm) is no variant of ours: None.
fn scheme(settings: &Value, opensees: &str) -> Option<ReferenceVariant> {
    let text = |k: &str| settings.get(k).and_then(Value::as_str);
    let num = |k: &str| settings.get(k).and_then(Value::as_f64);
    let (integrator, step, step_unit) = match text("integrator")? {
        "Newmark" if num("gamma") == Some(0.5) && num("beta") == Some(0.25) => {
            ("newmark", num("dt").filter(|h| h.is_finite() && *h > 0.0)?, "s")
        }
        "DisplacementControl" => {
            let ours = match text("algorithm")? {
                "Newton" => "newton_disp",
                "NewtonLineSearch" => "newton_disp_ls",
                "KrylovNewton" => "newton_disp_krylov",
                _ => return None,
            };
            (ours, 1.0, "protocol increment")
        }
        _ => return None,
    };
    Some(ReferenceVariant {
        integrator: integrator.into(),
        formulation: "force_based".into(),
        step,
        step_unit: step_unit.into(),
        made_by: format!("OpenSees {opensees}"),
    })
}

#[cfg(test)]
mod scheme_tests {
    use super::*;
    use serde_json::json;

    /// A record's scheme is one of our variants only where its settings say so: Newmark with
    /// gamma 1/2 and beta 1/4 at its dt, DisplacementControl per algorithm at one increment;
    /// another Newmark or algorithm is none.
    #[test]
    fn settings_name_the_variant() {
        let v = scheme(
            &json!({"integrator": "Newmark", "gamma": 0.5, "beta": 0.25, "dt": 5e-4}),
            "3.7.1",
        )
        .unwrap();
        assert_eq!((v.integrator.as_str(), v.step), ("newmark", 5e-4));
        assert_eq!(v.made_by, "OpenSees 3.7.1");
        let k = scheme(
            &json!({"integrator": "DisplacementControl", "algorithm": "KrylovNewton"}),
            "3.7.1",
        )
        .unwrap();
        assert_eq!((k.integrator.as_str(), k.step), ("newton_disp_krylov", 1.0));
        let other = json!({"integrator": "Newmark", "gamma": 0.6, "beta": 0.3025, "dt": 5e-4});
        assert!(scheme(&other, "3.7.1").is_none());
        let bfgs = json!({"integrator": "DisplacementControl", "algorithm": "BFGS"});
        assert!(scheme(&bfgs, "3.7.1").is_none());
    }
}
