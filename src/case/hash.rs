//! The physics hash of a scene (cases/README.md, "Physics hash"): `inputs_sha256` is the hex
//! SHA-256 of the canonical JSON (object keys sorted at every level, shortest round-trip floats,
//! `-0.0` written as `0.0`) of the case name, its `model`, the family's physics of the scene (for a
//! rigid body: the body with the scene's effective inertia, the springs and the initial state as
//! given), `t_end` and `score_every`. Ladders, gates, the title, `sample_every` and scene keys
//! outside the physics are not part of it, so editing them does not make a stored reference stale.
use serde_json::Value;
use sha2::{Digest, Sha256};

use super::{Case, Scene};

/// Hex SHA-256 of the canonical JSON of the physics of `scene`.
pub fn inputs_sha256(case: &Case, scene: &Scene) -> String {
    let json = canonical_json(&inputs_value(case, scene));
    let digest = Sha256::digest(json.as_bytes());
    digest.iter().map(|b| format!("{b:02x}")).collect()
}

/// A number as the hash writes it (`-0.0` as `0.0`).
pub fn num(x: f64) -> Value {
    Value::from(x + 0.0)
}

/// The value `inputs_sha256` hashes (exposed for provenance and debugging).
pub fn inputs_value(case: &Case, scene: &Scene) -> Value {
    let mut m = (crate::problem::family_of(case).inputs)(case, scene);
    m.insert("case".into(), Value::from(case.name.as_str()));
    m.insert("model".into(), Value::from(case.model));
    m.insert("t_end".into(), num(scene.t_end));
    m.insert("score_every".into(), num(scene.score_every));
    Value::Object(m)
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
