//! Stored references (docs/schemas.md, "Stored references"), the code every model family shares:
//! one JSON per scene under `references/<case>/<scene>.json` holding the family's columns at the
//! score times, its provenance, its accuracy claim and the SHA-256 of the physics it was made from.
//! The schema is the family's (a type implementing [`Stored`], e.g. the rigid body's
//! `model::rigid_body::reference::Reference`); locating, reading, validating and writing are here.
//!
//! Floats are written with `serde_json`'s `float_roundtrip` so that they read back exactly.
//! Files are written atomically (a temporary file renamed into place), so an interrupted
//! write never leaves a truncated file that looks complete. A reference is *stale* when its
//! `inputs_sha256` differs from the case's current one; loading checks it.
use serde::Serialize;
use std::path::{Path, PathBuf};

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

/// Hex SHA-256 of bytes (`digest`, the crate's one digest; here for the families' references).
pub use crate::digest::sha256_hex;

/// What the shared loader needs of a family's stored reference file.
/// Its stamp (`case`, `scene`, `inputs_sha256`: the keys every stored reference carries) is
/// read by the loader from the same file ([`Stamp`]), so a family's type need not expose it.
pub trait Stored: serde::de::DeserializeOwned {
    /// The score times the columns are given at (key `t`).
    fn times(&self) -> &[f64];
    /// A message when the columns do not fit together (unequal or zero lengths).
    fn check_columns(&self) -> Result<(), String>;
}

/// The keys of every stored reference that say what it was made for: its case and scene,
/// and the physics hash of the scene it was made from.
#[derive(Debug, serde::Deserialize)]
struct Stamp {
    case: String,
    scene: String,
    inputs_sha256: String,
}

/// The reference's times are the scene's score times: `t_k = k score_every` for `k = 0..=n`,
/// `n = t_end / score_every`, each within `1e-12 t_end`. The error names the key (`t`, or
/// `t[k]`) and is meant to be prefixed with the file (see `grid_error`).
pub fn check_grid(t: &[f64], t_end: f64, score_every: f64) -> Result<(), String> {
    let n = crate::case::steps_dividing(t_end, score_every)
        .ok_or_else(|| format!("score_every {score_every} does not divide t_end {t_end}"))?;
    if t.len() as u64 != n + 1 {
        return Err(format!(
            "key `t` has {} samples; expected {} (0 to {t_end} s every {score_every} s)",
            t.len(),
            n + 1
        ));
    }
    let tol = 1e-12 * t_end;
    for (k, &tk) in t.iter().enumerate() {
        let want = k as f64 * score_every;
        if (tk - want).abs() > tol {
            return Err(format!(
                "key `t[{k}]` is {tk}; expected {want} (the score times)"
            ));
        }
    }
    Ok(())
}

/// A reference file's error: `message` prefixed with the file's path.
pub fn grid_error(root: &Path, case: &str, scene: &str, message: String) -> ReferenceError {
    ReferenceError::Unreadable {
        path: path(root, case, scene).display().to_string(),
        message,
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

/// Loads and validates a family's reference file `references/<case>/<scene>.json`: a regular
/// file inside `root` of at most `read_limited::REFERENCE` bytes (`crate::read_limited`), its
/// columns consistent, its case and scene the expected ones, not stale; returns it with the
/// SHA-256 of the file.
pub fn load_as<R: Stored>(
    root: &Path,
    case: &str,
    scene: &str,
    inputs_sha256: &str,
) -> Result<(R, String), ReferenceError> {
    let p = path(root, case, scene);
    let shown = p.display().to_string();
    let bytes = match crate::read_limited::read_within(root, &p, crate::read_limited::REFERENCE) {
        Ok(b) => b,
        Err(e) if e.is_missing() => {
            return Err(ReferenceError::Missing {
                path: shown,
                case: case.into(),
                scene: scene.into(),
            });
        }
        Err(e) => {
            return Err(ReferenceError::Unreadable {
                path: shown,
                message: e.why.to_string(),
            });
        }
    };
    let unreadable = |message: String| ReferenceError::Unreadable {
        path: shown.clone(),
        message,
    };
    let reference: R = serde_json::from_slice(&bytes).map_err(|e| unreadable(e.to_string()))?;
    let stamp: Stamp = serde_json::from_slice(&bytes).map_err(|e| unreadable(e.to_string()))?;
    reference.check_columns().map_err(unreadable)?;
    if stamp.case != case || stamp.scene != scene {
        return Err(unreadable(format!(
            "key `case`/`scene` is {}/{}, expected {case}/{scene}",
            stamp.case, stamp.scene
        )));
    }
    if stamp.inputs_sha256 != inputs_sha256 {
        return Err(ReferenceError::Stale {
            path: shown,
            case: case.into(),
            scene: scene.into(),
            stored: stamp.inputs_sha256,
            current: inputs_sha256.into(),
        });
    }
    let sha = sha256_hex(&bytes);
    Ok((reference, sha))
}

/// Writes `bytes` to `path` atomically (temporary file in the same folder, then rename).
/// The temporary file is removed when writing or renaming fails (a full disk used to leave
/// `*.tmp<pid>` behind) and on SIGINT (`output::interrupt`); those a killed process left
/// beside `path` are removed by the next write of it.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomic_with(path, |w| w.write_all(bytes))
}

/// [`write_atomic`] of what `write` writes into the buffered temporary file: a large document
/// is serialised into the file as it is made, never held whole in memory.
pub fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    use std::io::Write;
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    crate::output::remove_stale_tmp(path);
    let tmp = path.with_extension(format!("tmp{}", std::process::id()));
    crate::output::interrupt::register(&tmp);
    let r = std::fs::File::create(&tmp)
        .and_then(|f| {
            let mut w = std::io::BufWriter::new(f);
            write(&mut w)?;
            w.flush()
        })
        .and_then(|()| std::fs::rename(&tmp, path))
        .inspect_err(|_| {
            let _ = std::fs::remove_file(&tmp);
        });
    crate::output::interrupt::unregister(&tmp);
    r
}

/// Checks, before any work, that the output folder `dir` can be written: it may not be a file,
/// a file-system root, the current folder or one of its ancestors (`output::Staging`); a
/// probe file is written and removed in `dir` when it exists, and in its parent (where the
/// new output is built), or, when that does not exist yet, in its nearest existing ancestor
/// (nothing is created, so bad input found later still leaves nothing behind). An unwritable
/// `--out` used to be found only after every run was computed. The error names the folder.
pub fn check_writable(dir: &Path) -> Result<(), String> {
    let fail =
        |e: std::io::Error| format!("{}: the output folder is not writable: {e}", dir.display());
    let full = crate::output::resolve(dir)?;
    if full.exists() && !full.is_dir() {
        return Err(format!(
            "{}: the output folder is not writable: it is not a folder",
            dir.display()
        ));
    }
    let mut probes = vec![];
    if full.is_dir() {
        probes.push(full.clone());
    }
    let mut at = full.parent().expect("resolve gives a path with a parent");
    while !at.exists() {
        match at.parent() {
            Some(p) => at = p,
            None => break,
        }
    }
    if !at.is_dir() {
        return Err(format!(
            "{}: the output folder is not writable: {} is not a folder",
            dir.display(),
            at.display()
        ));
    }
    probes.push(at.to_path_buf());
    for at in probes {
        let probe = at.join(format!(".mbdbench-probe-{}", std::process::id()));
        std::fs::write(&probe, b"probe").map_err(fail)?;
        std::fs::remove_file(&probe).map_err(fail)?;
    }
    Ok(())
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
    write_atomic(&p, text.as_bytes())
        .map_err(|e| std::io::Error::new(e.kind(), format!("{}: {e}", p.display())))?;
    Ok(p)
}
