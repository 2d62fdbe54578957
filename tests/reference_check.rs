//! `mbdbench reference --check` recomputes and judges a stored reference by bounds of its own
//! (never by numbers in the file it checks): a tampered column passes no more when its file also claims a loose
//! accuracy, a tampered self-convergence track is caught, and a claim far from the
//! recomputed one is refused, each through the binary on a copy of the stored references.
mod common;

use std::path::Path;
use std::process::Command;

use serde_json::Value;

/// Runs `reference --check` for one scene against `refs`; (exit code, output).
fn check(refs: &Path, case: &str, scene: &str) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .args([
            "reference",
            "--case",
            case,
            "--scene",
            scene,
            "--check",
            "--references",
        ])
        .arg(refs)
        .output()
        .unwrap();
    (out.status.code().unwrap_or(-1), common::text(&out))
}

/// Edits the JSON file at `path` in place.
fn edit(path: &Path, f: impl Fn(&mut Value)) {
    let mut v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    f(&mut v);
    std::fs::write(path, serde_json::to_string(&v).unwrap()).unwrap();
}

/// The beam's tip column shifted by 0.1 m fails even when the file claims 1.0 m; one
/// self-convergence track shifted by 1e-3 m fails; the untouched copy passes.
#[test]
fn beam_check_recomputes_columns_and_tracks() {
    let refs = common::copy_references("refcheck-beam");
    let file = refs.join("flexible_beam").join("spinup_w4.json");
    let original = std::fs::read_to_string(&file).unwrap();
    let (code, text) = check(&refs, "flexible_beam", "spinup_w4");
    assert_eq!(code, 0, "{text}");

    edit(&file, |v| {
        for x in v["tip_deflection"].as_array_mut().unwrap() {
            *x = Value::from(x.as_f64().unwrap() + 0.1);
        }
        v["accuracy_claim"]["tip_deflection"] = Value::from(1.0);
    });
    let (code, text) = check(&refs, "flexible_beam", "spinup_w4");
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("FAIL flexible_beam/spinup_w4"), "{text}");

    std::fs::write(&file, &original).unwrap();
    edit(&file, |v| {
        let track = &mut v["self_convergence"][1]["tip_deflection"];
        for x in track.as_array_mut().unwrap() {
            *x = Value::from(x.as_f64().unwrap() + 1.0e-3);
        }
    });
    let (code, text) = check(&refs, "flexible_beam", "spinup_w4");
    assert_eq!(code, 1, "{text}");
    let _ = std::fs::remove_dir_all(&refs);
}

/// A rigid reference's rotation shifted by 5e-7 rad fails even when the file claims 1e-6 (the
/// loosest claim the loader accepts, which used to be the bound), and a stored claim 100
/// times looser than the recomputed one fails on its own.
#[test]
fn rigid_check_bounds_come_from_the_recomputation() {
    let refs = common::copy_references("refcheck-rigid");
    let file = refs.join("nine_spring").join("two_angles.json");
    let original = std::fs::read_to_string(&file).unwrap();
    edit(&file, |v| {
        let q = v["quaternion"].as_array_mut().unwrap();
        let last = q.last_mut().unwrap().as_array_mut().unwrap();
        // A turn of 5e-7 rad about x: w and x change together, the quaternion stays unit.
        let (w, x) = (last[0].as_f64().unwrap(), last[1].as_f64().unwrap());
        let (c, s) = (2.5e-7f64.cos(), 2.5e-7f64.sin());
        last[0] = Value::from(c * w - s * x);
        last[1] = Value::from(s * w + c * x);
        for k in ["position", "rotation", "velocity", "omega"] {
            v["accuracy_claim"][k] = Value::from(1.0e-6);
        }
    });
    let (code, text) = check(&refs, "nine_spring", "two_angles");
    assert_eq!(code, 1, "{text}");

    std::fs::write(&file, &original).unwrap();
    edit(&file, |v| {
        let r = v["accuracy_claim"]["rotation"].as_f64().unwrap();
        v["accuracy_claim"]["rotation"] = Value::from(100.0 * r);
    });
    let (code, text) = check(&refs, "nine_spring", "two_angles");
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("within 10x of them: NO"), "{text}");
    let _ = std::fs::remove_dir_all(&refs);
}
