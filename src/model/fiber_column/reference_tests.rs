//! Tests of the external (OpenSees) references' loader, `reference::load_external`, on a copy
//! of the stored files: the stored `rc_cyclic_c01` loads and matches the case; each of the
//! refusals (a changed file, a manifest without its provenance, a model that is not the
//! case's, a score time the file does not hold) names the file and the key.
use std::path::{Path, PathBuf};

use super::reference::{ModelCheck, load_external, opensees_dir};

const SCENE: &str = "rc_cyclic_c01";

/// A references root holding copies of the scene's file and the manifest.
fn copied_root(tag: &str) -> PathBuf {
    let root = std::env::temp_dir().join(format!("mbdbench-ext-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    let (from, to) = (
        opensees_dir(&crate::cli::default_references()),
        opensees_dir(&root),
    );
    std::fs::create_dir_all(&to).unwrap();
    for f in [format!("{SCENE}.json"), "MANIFEST.json".to_string()] {
        std::fs::copy(from.join(&f), to.join(&f)).unwrap();
    }
    root
}

/// The case's model values (`column.height`, `load.axial`).
fn model(h: f64) -> ModelCheck {
    vec![("H", h, "column.height"), ("P", 750.0e3, "load.axial")]
}

fn load(root: &Path, h: f64, score_every: f64) -> Result<super::reference::External, String> {
    load_external(root, SCENE, 5880.0, score_every, &model(h))
}

fn edit(path: &Path, f: impl Fn(&mut serde_json::Value)) {
    let mut v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    f(&mut v);
    std::fs::write(path, serde_json::to_vec(&v).unwrap()).unwrap();
}

/// The stored reference loads: its track at every score time, its accuracy claim (the
/// half-increment difference of the base shear, 4.2e-5 of the peak) and its hash.
#[test]
fn stored_reference_loads() {
    let root = copied_root("ok");
    let e = load(&root, 3.0, 5.0).unwrap();
    assert_eq!(e.track.t.len(), 5880 / 5 + 1);
    let claim = e.claim["base_shear"];
    assert!(claim > 1e-5 && claim < 1e-4, "{claim}");
    assert_eq!(e.sha256.len(), 64);
    let _ = std::fs::remove_dir_all(&root);
}

/// Each refusal names its file and key: a file changed after generation (its SHA-256 no
/// longer the manifest's), a manifest without its provenance block, a case whose height is
/// not the model's (stale, with the command that regenerates it), a score grid the file's
/// `t` does not hold.
#[test]
fn refusals_name_file_and_key() {
    let root = copied_root("bad");
    let dir = opensees_dir(&root);
    // A model that is not the case's.
    let e = load(&root, 3.5, 5.0).err().unwrap();
    assert!(
        e.contains("stale") && e.contains("model.H") && e.contains("column.height"),
        "{e}"
    );
    assert!(e.contains("generate.py"), "says how to regenerate: {e}");
    // A score time between the file's samples.
    let e = load(&root, 3.0, 0.5).err().unwrap();
    assert!(e.contains("data.t") && e.contains("0.5"), "{e}");
    // A manifest without provenance.
    edit(&dir.join("MANIFEST.json"), |m| {
        m.as_object_mut().unwrap().remove("provenance");
    });
    let e = load(&root, 3.0, 5.0).err().unwrap();
    assert!(
        e.contains("MANIFEST.json") && e.contains("provenance.tool"),
        "{e}"
    );
    // A file changed after generation.
    std::fs::copy(
        opensees_dir(&crate::cli::default_references()).join("MANIFEST.json"),
        dir.join("MANIFEST.json"),
    )
    .unwrap();
    edit(&dir.join(format!("{SCENE}.json")), |f| {
        f["data"]["base_shear"][1] = serde_json::json!(1.0);
    });
    let e = load(&root, 3.0, 5.0).err().unwrap();
    assert!(
        e.contains(&format!("{SCENE}.json")) && e.contains("differs from MANIFEST.json"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&root);
}
