//! Tests of the external (OpenSees) references' loader, `opensees::load_external`, on copies
//! of the stored folder: the stored `rc_cyclic_c01` loads; the folder's checks refuse a file
//! changed after generation (a record, the generator, its requirements, its README), a
//! manifest without its provenance or without the generator's inputs, and a record whose
//! generator hash is not the manifest's; the record's checks (with the manifest re-hashed, so
//! that only they can refuse) refuse an unknown key, a repeated row, a column that is zero
//! throughout, a claim that is negative, huge, null or missing, and a provenance block that is
//! missing or malformed; each names the file and the key. The model's comparison with the case is `opensees_model_tests.rs`.
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

use super::opensees::{External, load_external, opensees_dir};

const SCENE: &str = "rc_cyclic_c01";
const RECORD: &str = "references/fiber_column/opensees/rc_cyclic_c01.json";

/// A references root holding a copy of the OpenSees folder and its `requirements.txt`.
fn copied_root(tag: &str) -> PathBuf {
    let root = std::env::temp_dir().join(format!("mbdbench-ext-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    let refs = crate::cli::default_references();
    let (from, to) = (opensees_dir(&refs), opensees_dir(&root));
    std::fs::create_dir_all(&to).unwrap();
    for e in std::fs::read_dir(&from).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
    }
    let req = "fiber_column/requirements.txt";
    std::fs::copy(refs.join(req), root.join(req)).unwrap();
    root
}

/// Loads the scene at the case's grid with no model comparison (the loader's own checks).
fn load(root: &Path, score_every: f64) -> Result<External, String> {
    load_external(root, SCENE, 5880.0, score_every, &|_, _| Ok(()))
}

fn edit(path: &Path, f: impl Fn(&mut Value)) {
    let mut v: Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    f(&mut v);
    std::fs::write(path, serde_json::to_vec(&v).unwrap()).unwrap();
}

/// Edits the record and lists its new hash in the manifest, as a regeneration would.
fn tamper(root: &Path, f: impl Fn(&mut Value)) {
    let dir = opensees_dir(root);
    let file = dir.join(format!("{SCENE}.json"));
    edit(&file, f);
    let sha = crate::reference::sha256_hex(&std::fs::read(&file).unwrap());
    edit(&dir.join("MANIFEST.json"), |m| m["sha256"][RECORD] = json!(sha));
}

/// An edit of a record.
type Tamper = Box<dyn Fn(&mut Value)>;

/// Each edit, re-hashed into the manifest of the copy `copied_root(tag)` made, is refused with
/// an error naming the record and containing its expected text; the copy is put back after
/// each.
fn refused_by_key(root: &Path, tag: &str, cases: Vec<(&str, Tamper)>) {
    for (want, f) in cases {
        tamper(root, f);
        let e = load(root, 5.0).err().unwrap_or_else(|| panic!("accepted: {want}"));
        assert!(e.contains(&format!("{SCENE}.json: ")), "{e}");
        assert!(e.contains(want), "{e}\nwanted: {want}");
        restore(root, tag);
    }
}

/// Puts the stored folder back in `root`, the copy `copied_root(tag)` made.
fn restore(root: &Path, tag: &str) {
    assert_eq!(copied_root(tag), root);
}

/// The stored reference loads: its track at every score time, its accuracy claim (the
/// half-increment difference of the base shear, 4.2e-5 of the peak) and its hash.
#[test]
fn stored_reference_loads() {
    let root = copied_root("ok");
    let e = load(&root, 5.0).unwrap();
    assert_eq!(e.track.t.len(), 5880 / 5 + 1);
    let claim = e.claim["base_shear"];
    assert!(claim > 1e-5 && claim < 1e-4, "{claim}");
    assert_eq!(e.sha256.len(), 64);
    let _ = std::fs::remove_dir_all(&root);
}

/// The folder's checks name the file and key: a score grid the record's `t` does not hold, a
/// manifest without its provenance block, a record changed after generation, a model the
/// caller's comparison refuses (with the command that regenerates it).
#[test]
fn refusals_name_file_and_key() {
    let root = copied_root("bad");
    let dir = opensees_dir(&root);
    let e = load(&root, 0.5).err().unwrap();
    assert!(e.contains("data.t") && e.contains("0.5"), "{e}");
    let stale = load_external(&root, SCENE, 5880.0, 5.0, &|_, _| Err("stale: x".into()));
    let e = stale.err().unwrap();
    assert!(e.contains(&format!("{SCENE}.json: stale: x")), "{e}");
    assert!(e.contains("generate.py"), "says how to regenerate: {e}");
    edit(&dir.join("MANIFEST.json"), |m| {
        m.as_object_mut().unwrap().remove("provenance");
    });
    let e = load(&root, 5.0).err().unwrap();
    assert!(e.contains("MANIFEST.json") && e.contains("provenance.tool"), "{e}");
    restore(&root, "bad");
    edit(&dir.join(format!("{SCENE}.json")), |f| {
        f["data"]["base_shear"][1] = json!(1.0);
    });
    let e = load(&root, 5.0).err().unwrap();
    assert!(
        e.contains(&format!("{SCENE}.json")) && e.contains("differs from MANIFEST.json"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&root);
}

/// Every file the manifest lists is verified, not only the record: a changed generator,
/// requirements or README is refused naming it and its manifest key; a manifest that does
/// not list the generator's requirements, or a record whose generator hash is not the one
/// the manifest lists, is refused too.
#[test]
fn the_manifest_covers_the_generator_and_its_inputs() {
    let root = copied_root("manifest");
    let dir = opensees_dir(&root);
    for (file, key) in [
        (dir.join("generate.py"), "generate.py"),
        (root.join("fiber_column/requirements.txt"), "requirements.txt"),
        (dir.join("README.md"), "README.md"),
    ] {
        let mut text = std::fs::read(&file).unwrap();
        text.extend_from_slice(b"\n");
        std::fs::write(&file, text).unwrap();
        let e = load(&root, 5.0).err().unwrap();
        assert!(e.contains(key) && e.contains("differs from MANIFEST.json"), "{e}");
        assert!(e.contains("key `sha256.references/fiber_column/"), "{e}");
        restore(&root, "manifest");
    }
    edit(&dir.join("MANIFEST.json"), |m| {
        let files = m["sha256"].as_object_mut().unwrap();
        files.remove("references/fiber_column/requirements.txt");
    });
    let e = load(&root, 5.0).err().unwrap();
    assert!(
        e.contains("MANIFEST.json") && e.contains("requirements.txt` is missing"),
        "{e}"
    );
    restore(&root, "manifest");
    tamper(&root, |f| f["generator"]["script_sha256"] = json!("0".repeat(64)));
    let e = load(&root, 5.0).err().unwrap();
    assert!(e.contains(&format!("{SCENE}.json: key `generator.script_sha256`")), "{e}");
    let _ = std::fs::remove_dir_all(&root);
}

/// The record's own checks, on copies re-hashed into the manifest: an unknown top-level key,
/// a repeated row, a column that is zero throughout, an unknown data column, and an accuracy
/// claim that is negative, above the sanity bound, null or missing are refused, each naming
/// the file and the key.
#[test]
fn malformed_records_are_refused_by_key() {
    let root = copied_root("record");
    let cases: Vec<(&str, Tamper)> = vec![
        ("unknown field `comment`", Box::new(|f| f["comment"] = json!("x"))),
        (
            "key `data.t` repeats t = 0 at row 1",
            Box::new(|f| {
                for c in f["data"].as_object_mut().unwrap().values_mut() {
                    let first = c[0].clone();
                    c.as_array_mut().unwrap().insert(0, first);
                }
            }),
        ),
        (
            "key `data.base_shear` is zero at every row",
            Box::new(|f| {
                for x in f["data"]["base_shear"].as_array_mut().unwrap() {
                    *x = json!(0.0);
                }
            }),
        ),
        (
            "key `data.base_shear_2` is not a column",
            Box::new(|f| f["data"]["base_shear_2"] = json!([0.0])),
        ),
        (
            "key `half_increment.relative_to_peak.base_shear` is -1e-4",
            Box::new(|f| f["half_increment"]["relative_to_peak"]["base_shear"] = json!(-1e-4)),
        ),
        (
            "key `half_increment.relative_to_peak.top_axial` is 2e0",
            Box::new(|f| f["half_increment"]["relative_to_peak"]["top_axial"] = json!(2.0)),
        ),
        (
            "key `half_increment.relative_to_peak.top_rotation` is null",
            Box::new(|f| f["half_increment"]["relative_to_peak"]["top_rotation"] = Value::Null),
        ),
        (
            "key `half_increment.relative_to_peak.axial_force` is missing",
            Box::new(|f| {
                let m = f["half_increment"]["relative_to_peak"].as_object_mut().unwrap();
                m.remove("axial_force");
            }),
        ),
        (
            "key `half_increment.peak_abs.base_shear` is 1e0",
            Box::new(|f| f["half_increment"]["peak_abs"]["base_shear"] = json!(1.0)),
        ),
    ];
    refused_by_key(&root, "record", cases);
    let _ = std::fs::remove_dir_all(&root);
}

/// A record's `provenance` block is checked like the rest of it (on copies re-hashed into
/// the manifest): a missing block, one that is not an object, one missing a key, with an
/// unknown key, with an empty or non-string value, with a tool that does not name the
/// generator's OpenSees, or with a command other than the generator's is refused, each
/// naming the file and the key.
#[test]
fn malformed_provenance_is_refused_by_key() {
    let root = copied_root("provenance");
    let cases: Vec<(&str, Tamper)> = vec![
        (
            "key `provenance` is missing",
            Box::new(|f| {
                f.as_object_mut().unwrap().remove("provenance");
            }),
        ),
        (
            "key `provenance` is \"by hand\", expected an object",
            Box::new(|f| f["provenance"] = json!("by hand")),
        ),
        (
            "key `provenance.cross_check` is missing",
            Box::new(|f| {
                let p = f["provenance"].as_object_mut().unwrap();
                p.remove("cross_check");
            }),
        ),
        (
            "key `provenance.author` is not a key of the schema",
            Box::new(|f| f["provenance"]["author"] = json!("x")),
        ),
        (
            "key `provenance.accuracy_claim` is \"\", expected a non-empty string",
            Box::new(|f| f["provenance"]["accuracy_claim"] = json!("")),
        ),
        (
            "key `provenance.tool` is 42, expected a non-empty string",
            Box::new(|f| f["provenance"]["tool"] = json!(42)),
        ),
        (
            "key `provenance.tool` is `OpenSees 3.6.0`, which does not name `OpenSees 3.7.1`",
            Box::new(|f| f["provenance"]["tool"] = json!("OpenSees 3.6.0")),
        ),
        (
            "key `provenance.command` is `python generate.py`, `generator.regenerate` is",
            Box::new(|f| f["provenance"]["command"] = json!("python generate.py")),
        ),
    ];
    refused_by_key(&root, "provenance", cases);
    let e = load(&root, 5.0).unwrap();
    assert_eq!(e.track.t.len(), 5880 / 5 + 1, "the stored block passes");
    let _ = std::fs::remove_dir_all(&root);
}
