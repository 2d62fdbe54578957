//! The one reader of every input file the suite did not compile in: stored and external
//! references, their manifests, summaries (`summary.json`, `stability.json`, a gate baseline),
//! an output folder's manifest, case files and series files. It reads a *regular file* of at
//! most a stated size and nothing else: a link to `/dev/zero` used to be read to 1 GB, and a
//! FIFO in place of a manifest blocked the command forever.
//!
//! - The file's type is checked before it is opened (following links) and again on the open
//!   file; on unix it is opened with `O_NONBLOCK` and `O_NOCTTY`, so that a FIFO or a device
//!   swapped in between is refused instead of waited on.
//! - Its size is checked against the [`Limit`] of its kind before anything is read, and the
//!   read stops one byte past the cap (a file growing while it is read is refused too).
//! - [`read_within`] also resolves every link and refuses a file that lands outside the
//!   given folder (the references folder, for references and their manifests).
//!
//! Every refusal is a [`ReadError`] naming the file; a missing file is told apart
//! ([`ReadError::is_missing`]) so that callers can say what would make it.
//!
//! # Example
//!
//! ```
//! use mbdbench::read_limited::{self, Limit};
//!
//! let dir = std::env::temp_dir().join(format!("read-limited-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! let f = dir.join("small.json");
//! std::fs::write(&f, "{}").unwrap();
//! assert_eq!(read_limited::read(&f, read_limited::SUMMARY).unwrap(), b"{}");
//! let tiny = Limit { what: "test file", name: "TINY", cap: 1 };
//! let e = read_limited::read(&f, tiny).unwrap_err().to_string();
//! assert!(e.contains("small.json") && e.contains("more than the 1 bytes"), "{e}");
//! # std::fs::remove_dir_all(&dir).unwrap();
//! ```
use std::fs::{File, Metadata};
use std::io::Read;
use std::path::{Path, PathBuf};

/// What kind of file is read and the most bytes it may have.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limit {
    /// The kind, for the error (`a stored reference`).
    pub what: &'static str,
    /// The constant's name, for the error (`read_limited::REFERENCE`).
    pub name: &'static str,
    /// The most bytes a file of this kind may have.
    pub cap: u64,
}

/// A stored reference (`references/<case>/<scene>.json`) or an external (OpenSees) one:
/// 64 MiB. The largest stored today is 657,476 bytes (`fiber_column/opensees/rc_cyclic_c02.json`),
/// so the cap leaves a hundredfold room for longer horizons or finer score grids.
pub const REFERENCE: Limit = Limit {
    what: "reference",
    name: "REFERENCE",
    cap: 64 << 20,
};

/// A manifest: the OpenSees references' `MANIFEST.json` (2,326 bytes today) or an output
/// folder's `mbdbench-manifest.json` (a line of about 200 bytes per file the suite wrote: the
/// full main job's folder holds about 500 files, some 100 KB): 16 MiB.
pub const MANIFEST: Limit = Limit {
    what: "manifest",
    name: "MANIFEST",
    cap: 16 << 20,
};

/// A file in the summary's schema: `summary.json`, `stability.json` or a gate baseline:
/// 256 MiB. The quick tier's baseline (`reports/baseline/quick.json`, 5,454 records) is
/// 5,134,214 bytes; the full main job's summary (7,459 runs and the same 3,648 `n/a`
/// records) comes to about 12 MB, twenty times below the cap.
pub const SUMMARY: Limit = Limit {
    what: "summary",
    name: "SUMMARY",
    cap: 256 << 20,
};

/// A case file (`--cases DIR`): 64 MiB. The catalogue's largest is 10,405 bytes; a ladder of
/// a million tolerances (the loader's scaling test, about 24 MB) still loads.
pub const CASE: Limit = Limit {
    what: "case file",
    name: "CASE",
    cap: 64 << 20,
};

/// A series file beside a summary (`series/...`): 1 GiB, the bound the report has always
/// applied (a series holds a few numbers per score time; the run's sample budget keeps it far
/// below this).
pub const SERIES: Limit = Limit {
    what: "series file",
    name: "SERIES",
    cap: 1 << 30,
};

/// Why a file was not read.
#[derive(Debug, thiserror::Error)]
pub enum Why {
    #[error("cannot read: no such file")]
    Missing,
    #[error("not a regular file (it is {0}); refused without reading it")]
    NotRegular(&'static str),
    #[error("resolves to {target}, outside the folder {root}; refused")]
    Outside { target: String, root: String },
    #[error(
        "{len} bytes, more than the {cap} bytes a {what} may have (read_limited::{name}); refused"
    )]
    TooLarge {
        len: u64,
        cap: u64,
        what: &'static str,
        name: &'static str,
    },
    #[error("cannot read: {0}")]
    Io(std::io::Error),
}

/// A file that was not read, and why; displays as `<file>: <why>`.
#[derive(Debug, thiserror::Error)]
#[error("{}: {why}", path.display())]
pub struct ReadError {
    pub path: PathBuf,
    pub why: Why,
}

impl ReadError {
    /// Whether the file (or a folder on its way) does not exist.
    pub fn is_missing(&self) -> bool {
        matches!(self.why, Why::Missing)
    }
}

fn io(e: std::io::Error) -> Why {
    if e.kind() == std::io::ErrorKind::NotFound {
        Why::Missing
    } else {
        Why::Io(e)
    }
}

/// What a file that is not a regular file is, for the error.
fn kind_of(m: &Metadata) -> &'static str {
    let t = m.file_type();
    if t.is_dir() {
        return "a folder";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    "a special file"
}

fn regular(m: &Metadata) -> Result<(), Why> {
    if m.is_file() {
        Ok(())
    } else {
        Err(Why::NotRegular(kind_of(m)))
    }
}

/// Opens `path` for reading without waiting on a FIFO or adopting a terminal.
fn open(path: &Path) -> std::io::Result<File> {
    let mut o = std::fs::OpenOptions::new();
    o.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        o.custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY);
    }
    o.open(path)
}

fn too_large(len: u64, limit: Limit) -> Why {
    Why::TooLarge {
        len,
        cap: limit.cap,
        what: limit.what,
        name: limit.name,
    }
}

fn read_checked(path: &Path, limit: Limit) -> Result<Vec<u8>, Why> {
    regular(&std::fs::metadata(path).map_err(io)?)?;
    let file = open(path).map_err(io)?;
    let meta = file.metadata().map_err(io)?;
    regular(&meta)?;
    if meta.len() > limit.cap {
        return Err(too_large(meta.len(), limit));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(limit.cap + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > limit.cap {
        return Err(too_large(bytes.len() as u64, limit));
    }
    Ok(bytes)
}

/// The bytes of the regular file at `path` (links followed), at most `limit.cap` of them.
pub fn read(path: &Path, limit: Limit) -> Result<Vec<u8>, ReadError> {
    read_checked(path, limit).map_err(|why| ReadError {
        path: path.to_path_buf(),
        why,
    })
}

/// [`read`] for a file that must be inside the folder `root` once every link is resolved (a
/// reference, or a references manifest, under the references folder).
pub fn read_within(root: &Path, path: &Path, limit: Limit) -> Result<Vec<u8>, ReadError> {
    let fail = |why| ReadError {
        path: path.to_path_buf(),
        why,
    };
    let target = std::fs::canonicalize(path).map_err(|e| fail(io(e)))?;
    let base = std::fs::canonicalize(root).map_err(|e| fail(io(e)))?;
    if !target.starts_with(&base) {
        return Err(fail(Why::Outside {
            target: target.display().to_string(),
            root: base.display().to_string(),
        }));
    }
    read_checked(&target, limit).map_err(fail)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::mpsc;
    use std::time::Duration;

    /// A fresh folder holding `root/` (the folder reads must stay in) and `outside.json`.
    fn scratch(tag: &str) -> (PathBuf, PathBuf) {
        let d = std::env::temp_dir().join(format!("mbdbench-read-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(d.join("root")).unwrap();
        std::fs::write(d.join("outside.json"), "{}").unwrap();
        (d.clone(), d.join("root"))
    }

    /// Runs `f` on a thread and gives its result within 20 s, or fails the test (a read that
    /// blocks, on a FIFO say, must fail the test instead of hanging it).
    fn within_20_s<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || {
            let _ = tx.send(f());
        });
        rx.recv_timeout(Duration::from_secs(20))
            .expect("the read did not return within 20 s")
    }

    /// A regular file inside the folder is read whole, and a link inside the folder to
    /// another file inside it is followed.
    #[test]
    fn reads_regular_files() {
        let (d, root) = scratch("ok");
        std::fs::write(root.join("a.json"), "[1]").unwrap();
        assert_eq!(
            read_within(&root, &root.join("a.json"), REFERENCE).unwrap(),
            b"[1]"
        );
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink("a.json", root.join("b.json")).unwrap();
            assert_eq!(
                read_within(&root, &root.join("b.json"), REFERENCE).unwrap(),
                b"[1]"
            );
        }
        let e = read(&root.join("absent.json"), SUMMARY).unwrap_err();
        assert!(e.is_missing(), "{e}");
        assert!(e.to_string().contains("absent.json"), "{e}");
        std::fs::remove_dir_all(&d).unwrap();
    }

    /// A file over its kind's cap is refused before it is read, the file, the size and the
    /// cap named (a sparse file: nothing is written to disk).
    #[test]
    fn oversize_is_refused() {
        let (d, root) = scratch("big");
        let p = root.join("big.json");
        let f = File::create(&p).unwrap();
        f.set_len(REFERENCE.cap + 1).unwrap();
        let e = within_20_s({
            let (root, p) = (root.clone(), p.clone());
            move || read_within(&root, &p, REFERENCE).unwrap_err()
        });
        let m = e.to_string();
        assert!(matches!(e.why, Why::TooLarge { .. }), "{m}");
        assert!(
            m.contains("big.json") && m.contains(&REFERENCE.cap.to_string()),
            "{m}"
        );
        assert!(m.contains("read_limited::REFERENCE"), "{m}");
        std::fs::remove_dir_all(&d).unwrap();
    }

    /// A link to `/dev/zero` (an endless file) and a FIFO (no writer: reading it would wait
    /// forever) are refused at once as not regular files, naming the file and what it is.
    #[cfg(unix)]
    #[test]
    fn special_files_are_refused() {
        let (d, root) = scratch("special");
        let zero = root.join("zero.json");
        std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
        let fifo = root.join("fifo.json");
        let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: `c` is a valid NUL-terminated path that outlives the call.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        for (p, what) in [(zero, "a character device"), (fifo, "a FIFO")] {
            let e = within_20_s({
                let p = p.clone();
                move || read(&p, MANIFEST).unwrap_err()
            });
            let m = e.to_string();
            assert!(matches!(e.why, Why::NotRegular(_)), "{m}");
            assert!(
                m.starts_with(&p.display().to_string()) && m.contains(what),
                "{m}"
            );
        }
        std::fs::remove_dir_all(&d).unwrap();
    }

    /// A link (or a `..` path) that leaves the folder is refused by `read_within`, naming
    /// the file, where it resolves to and the folder; `read` alone follows it.
    #[cfg(unix)]
    #[test]
    fn escaping_links_are_refused() {
        let (d, root) = scratch("escape");
        let link = root.join("link.json");
        std::os::unix::fs::symlink(d.join("outside.json"), &link).unwrap();
        for p in [link.clone(), root.join("../outside.json")] {
            let e = read_within(&root, &p, REFERENCE).unwrap_err();
            let m = e.to_string();
            assert!(matches!(e.why, Why::Outside { .. }), "{m}");
            assert!(
                m.contains("outside.json") && m.contains("outside the folder"),
                "{m}"
            );
        }
        assert_eq!(read(&link, REFERENCE).unwrap(), b"{}");
        std::fs::remove_dir_all(&d).unwrap();
    }
}
