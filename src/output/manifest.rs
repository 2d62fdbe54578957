//! The manifest of an output folder, `mbdbench-manifest.json`: every file the suite's folder
//! writers (`run`, `stability`, `report`) put there, with the writer, its size and SHA-256.
//! It is committed with the files it lists (`output::Staging::commit` swaps the whole folder),
//! so it always describes the folder as one writer left it complete.
//!
//! Readers check it (`verify`): a file the manifest lists must have the listed SHA-256, or
//! the folder was changed after the suite wrote it (by hand, or by an older build writing in
//! place) and may mix two runs. A file the manifest does not list, or a folder without a
//! manifest, is the user's and is read as it is. Writers use it to tell their own files
//! (replaced or dropped on the next commit) from everyone else's (always kept).
//!
//! # Example
//!
//! ```
//! use mbdbench::output::{Manifest, Writer};
//!
//! let mut m = Manifest::default();
//! m.add("summary.json", Writer::Run, b"{}");
//! assert!(m.verify("summary.json", b"{}").is_ok());
//! assert!(m.verify("summary.json", b"{ }").is_err()); // changed after it was written
//! assert!(m.verify("notes.txt", b"anything").is_ok()); // not the suite's file
//! ```
use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

/// The manifest's file name, at the root of an output folder.
pub const MANIFEST: &str = "mbdbench-manifest.json";

/// The commands that write output folders.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Writer {
    /// `run`: `summary.json` and `series/<case>/...`.
    Run,
    /// `stability`: `stability.json` and `series/long_horizon/...`, `series/sensitivity/...`.
    Stability,
    /// `report`: `index.html`, `summary.md`, `svg/...`.
    Report,
}

impl Writer {
    /// Whether this writer's files are made from `other`'s, so that a new commit of `other`
    /// makes them stale (the report is made from the summary and `stability.json`).
    pub fn derives_from(self, other: Writer) -> bool {
        self == Writer::Report && other != Writer::Report
    }

    /// The command that writes this writer's files.
    pub fn command(self) -> &'static str {
        match self {
            Writer::Run => "run",
            Writer::Stability => "stability",
            Writer::Report => "report",
        }
    }
}

/// One file of the manifest.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct FileEntry {
    pub writer: Writer,
    pub bytes: u64,
    pub sha256: String,
}

/// The files of an output folder written by the suite, by path relative to the folder
/// (`/`-separated).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Manifest {
    pub schema: u32,
    pub files: BTreeMap<String, FileEntry>,
}

impl Manifest {
    /// Records `rel` as written by `writer` with content `bytes`.
    pub fn add(&mut self, rel: &str, writer: Writer, bytes: &[u8]) {
        self.schema = 1;
        self.files.insert(
            rel.to_string(),
            FileEntry {
                writer,
                bytes: bytes.len() as u64,
                sha256: crate::digest::sha256_hex(bytes),
            },
        );
    }

    /// The manifest of folder `dir`: None when it has none; an error naming the file when it
    /// cannot be read (not a regular file, over `read_limited::MANIFEST` bytes) or parsed.
    pub fn load(dir: &Path) -> Result<Option<Manifest>, String> {
        let path = dir.join(MANIFEST);
        let bytes = match crate::read_limited::read(&path, crate::read_limited::MANIFEST) {
            Ok(b) => b,
            Err(e) if e.is_missing() => return Ok(None),
            Err(e) => return Err(e.to_string()),
        };
        let m: Manifest = serde_json::from_slice(&bytes)
            .map_err(|e| format!("{}: not a manifest: {e}", path.display()))?;
        if m.schema != 1 {
            return Err(format!(
                "{}: schema {}; expected 1",
                path.display(),
                m.schema
            ));
        }
        Ok(Some(m))
    }

    /// Ok when `rel` is not listed or `bytes` are what was listed for it.
    pub fn verify(&self, rel: &str, bytes: &[u8]) -> Result<(), String> {
        let Some(e) = self.files.get(rel) else {
            return Ok(());
        };
        if e.bytes == bytes.len() as u64 && e.sha256 == crate::digest::sha256_hex(bytes) {
            return Ok(());
        }
        Err(format!(
            "{rel} changed after `mbdbench {}` wrote the folder ({} bytes now, {} in {MANIFEST}): \
             the folder may mix two runs; rerun the command into it",
            e.writer.command(),
            bytes.len(),
            e.bytes
        ))
    }
}

/// Checks a file a reader has read against the manifest of its folder (if any): the
/// completion check every reader of `summary.json` and `stability.json` makes.
pub fn verify(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let Some(name) = path.file_name().and_then(|n| n.to_str()) else {
        return Ok(());
    };
    match Manifest::load(dir)? {
        Some(m) => m.verify(name, bytes),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A manifest round-trips through JSON, and `verify` accepts listed files with their
    /// content only (size and hash), unlisted files always.
    #[test]
    fn round_trip_and_verify() {
        let mut m = Manifest::default();
        m.add("series/a/b/c.json", Writer::Run, b"[1,2]");
        m.add("index.html", Writer::Report, b"<html>");
        let back: Manifest = serde_json::from_str(&serde_json::to_string(&m).unwrap()).unwrap();
        assert_eq!(back, m);
        assert!(m.verify("series/a/b/c.json", b"[1,2]").is_ok());
        let e = m.verify("series/a/b/c.json", b"[1,3]").unwrap_err();
        assert!(e.contains("mbdbench run") && e.contains("mix"), "{e}");
        assert!(m.verify("other.json", b"x").is_ok());
    }

    /// Only the report derives from other writers.
    #[test]
    fn derivation() {
        assert!(Writer::Report.derives_from(Writer::Run));
        assert!(Writer::Report.derives_from(Writer::Stability));
        assert!(!Writer::Report.derives_from(Writer::Report));
        assert!(!Writer::Run.derives_from(Writer::Stability));
        assert!(!Writer::Stability.derives_from(Writer::Run));
    }
}
