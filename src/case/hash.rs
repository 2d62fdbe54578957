//! The two hashes that bind results to the inputs they were made from (cases/README.md,
//! "Physics hash").
//!
//! - `inputs_sha256` (of a scene, stamped on its stored reference and on every record): the hex
//!   SHA-256 of the canonical JSON (object keys sorted at every level, shortest round-trip
//!   floats, `-0.0` written as `0.0`) of the case name, its `model`, `t_end`, `score_every` and
//!   the family's physics of the scene (`problem::Family::inputs`: for a rigid body the body
//!   with the scene's effective inertia, the springs and the initial state; for the beam also
//!   the numerical settings its reference is computed with, such as `reference_elements`). A
//!   stored reference whose stamp differs is stale. A rival formulation's setting is not in it,
//!   so tuning a rival never makes the reference stale.
//! - `settings_sha256` (of a scene, stamped on every record): the same canonical hash of every
//!   key of the case file that can change a run's result, read from the file as written: the
//!   case-level keys and the scene's own, less the presentation keys
//!   ([`PRESENTATION_KEYS`], [`PRESENTATION_SCENE_KEYS`]: title, advice, gates, ladders, the
//!   stability study's selection, a scene's name and control flag). It is computed from the
//!   file's text, not from what a family chose to keep, so a key a family adds is covered
//!   without declaring it. The gate compares a record with the baseline's only when both
//!   hashes agree; a record made with other settings is a new record, not a regression.
//!
//! Invariants: the hashes depend on values, not on how they were written (`1.0e3` and `1000.0`
//! and `1000` hash alike; key order and comments do not count); a family's inputs map may not
//! use the keys the hash adds itself ([`RESERVED_INPUT_KEYS`]): [`check_family_inputs`] refuses
//! such a family when a case of it is loaded, so no two physics can hash alike because one key
//! overwrote another. Which key moves which hash is checked for every key of every case file
//! by `case/hash_tests.rs`.
//!
//! # Example
//!
//! ```
//! let cases = mbdbench::catalogue::embedded().unwrap();
//! let c = cases.iter().find(|c| c.name == "nine_spring").unwrap();
//! let s = c.scene("two_angles").unwrap();
//! let inputs = mbdbench::case::inputs_sha256(c, s);
//! assert_eq!(inputs.len(), 64);
//! assert_eq!(s.settings_sha256.len(), 64);
//! assert_ne!(inputs, s.settings_sha256);
//! ```
use serde_json::Value;

use super::{Case, CaseError, Scene};

/// Keys of the physics hash that the hash itself adds; a family's inputs map may not use them.
pub const RESERVED_INPUT_KEYS: [&str; 4] = ["case", "model", "t_end", "score_every"];

/// Case-level keys that change no run's result: what is shown (`title`), judged (`gates`,
/// the advice's targets and drift limit), selected (`ladders`: which steps run, each its own
/// record; `stability`: the study's horizon and scenes, outside the run records) or the
/// schema version. Every other case-level key is in the settings hash.
pub const PRESENTATION_KEYS: [&str; 7] = [
    "schema",
    "title",
    "advise_targets",
    "advise_max_energy_drift",
    "gates",
    "ladders",
    "stability",
];

/// Scene keys that change no run's result: the scene's name (the record's own key), its
/// ladders and its control flag (the advice's business). Every other scene key is in the
/// settings hash.
pub const PRESENTATION_SCENE_KEYS: [&str; 3] = ["name", "ladders", "control"];

/// The shared case-file keys that change results but not a stored reference, for every
/// family (a family declares its own in `problem::Family::settings`): the scoring's
/// normalisation and primary metric, how references are made, the work budgets, the
/// sampling of the series and trajectories.
pub const SHARED_SETTINGS: [&str; 9] = [
    "primary_metric",
    "energy_scale",
    "reference",
    "max_steps",
    "max_rhs_evals",
    "max_adaptive_rhs_evals",
    "max_memory_mib",
    "max_work",
    "scene.sample_every",
];

/// Hex SHA-256 of the canonical JSON of the physics of `scene`.
pub fn inputs_sha256(case: &Case, scene: &Scene) -> String {
    sha256_of(&inputs_value(case, scene))
}

/// Hex SHA-256 of a value's canonical JSON.
pub fn sha256_of(v: &Value) -> String {
    crate::digest::sha256_hex(canonical_json(v).as_bytes())
}

/// A number as the hash writes it (`-0.0` as `0.0`).
pub fn num(x: f64) -> Value {
    Value::from(x + 0.0)
}

/// The value `inputs_sha256` hashes (exposed for provenance and debugging).
pub fn inputs_value(case: &Case, scene: &Scene) -> Value {
    let mut m = case.family.inputs(case, scene);
    m.insert("case".into(), Value::from(case.name.as_str()));
    m.insert("model".into(), Value::from(case.model()));
    m.insert("t_end".into(), num(scene.t_end));
    m.insert("score_every".into(), num(scene.score_every));
    Value::Object(m)
}

/// Refuses a family whose physics map uses a key the hash adds itself (it would be
/// overwritten, and two different physics would hash alike). Called for every scene of every
/// case when the case is loaded, so a family, built in or a user's, cannot skip it.
pub fn check_family_inputs(case: &Case) -> Result<(), CaseError> {
    for scene in &case.scenes {
        let m = case.family.inputs(case, scene);
        if let Some(k) = RESERVED_INPUT_KEYS.iter().find(|k| m.contains_key(**k)) {
            return Err(CaseError {
                file: case.file.clone(),
                key: "model".into(),
                message: format!(
                    "family `{}` puts the reserved key `{k}` in its physics hash (scene `{}`); \
                     the hash adds {} itself: the family must name its keys otherwise",
                    case.model(),
                    scene.name,
                    RESERVED_INPUT_KEYS.join(", ")
                ),
            });
        }
    }
    Ok(())
}

/// Sets every scene's `settings_sha256` from the case file's text (`settings_sha256s`), by
/// the scene's position in the file.
pub fn stamp_settings(
    case: &mut Case,
    model: &str,
    file: &str,
    text: &str,
) -> Result<(), CaseError> {
    let settings = settings_sha256s(file, text)?;
    for scene in &mut case.scenes {
        let Some(h) = settings.get(scene.index) else {
            return Err(CaseError {
                file: file.to_string(),
                key: format!("scene[{}]", scene.index),
                message: format!(
                    "family `{model}` loaded a scene the text does not have ({} scenes)",
                    settings.len()
                ),
            });
        };
        scene.settings_sha256 = h.clone();
    }
    Ok(())
}

/// Every scene's `settings_sha256`, in file order, from the case file's text: the case-level
/// keys and the scene's own, less the presentation keys, numbers as floats.
pub fn settings_sha256s(file: &str, text: &str) -> Result<Vec<String>, CaseError> {
    let raw: toml::Table = super::parse(file, text)?;
    let mut case_keys = serde_json::Map::new();
    for (k, v) in &raw {
        if k != "scene" && !PRESENTATION_KEYS.contains(&k.as_str()) {
            case_keys.insert(k.clone(), json_of(v));
        }
    }
    let scenes = match raw.get("scene") {
        Some(toml::Value::Array(a)) => a.as_slice(),
        _ => &[],
    };
    Ok(scenes
        .iter()
        .map(|s| {
            let mut own = serde_json::Map::new();
            if let toml::Value::Table(t) = s {
                for (k, v) in t {
                    if !PRESENTATION_SCENE_KEYS.contains(&k.as_str()) {
                        own.insert(k.clone(), json_of(v));
                    }
                }
            }
            let mut m = serde_json::Map::new();
            m.insert("case".into(), Value::Object(case_keys.clone()));
            m.insert("scene".into(), Value::Object(own));
            sha256_of(&Value::Object(m))
        })
        .collect())
}

/// A TOML value as the settings hash writes it: every number a float (so `10` and `10.0`
/// hash alike), dates as their text.
fn json_of(v: &toml::Value) -> Value {
    match v {
        toml::Value::String(s) => Value::from(s.as_str()),
        toml::Value::Integer(i) => num(*i as f64),
        toml::Value::Float(x) => num(*x),
        toml::Value::Boolean(b) => Value::from(*b),
        toml::Value::Datetime(d) => Value::from(d.to_string()),
        toml::Value::Array(a) => Value::Array(a.iter().map(json_of).collect()),
        toml::Value::Table(t) => Value::Object(
            t.iter()
                .map(|(k, v)| (k.clone(), json_of(v)))
                .collect::<serde_json::Map<_, _>>(),
        ),
    }
}

/// Compact JSON with object keys sorted at every level, whatever map type serde_json was
/// built with; numbers as serde_json prints them (shortest round-trip).
pub fn canonical_json(v: &Value) -> String {
    let mut out = String::new();
    write_canonical(v, &mut out);
    out
}

fn write_canonical(v: &Value, out: &mut String) {
    match v {
        Value::Object(m) => {
            let mut keys: Vec<&String> = m.keys().collect();
            keys.sort();
            out.push('{');
            for (i, k) in keys.into_iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                out.push_str(&Value::String(k.clone()).to_string());
                out.push(':');
                write_canonical(&m[k], out);
            }
            out.push('}');
        }
        Value::Array(a) => {
            out.push('[');
            for (i, x) in a.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                write_canonical(x, out);
            }
            out.push(']');
        }
        other => out.push_str(&other.to_string()),
    }
}

#[cfg(test)]
#[path = "hash_tests.rs"]
mod tests;
