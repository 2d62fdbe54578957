//! Output folders that are never seen half-written (a killed writer must not leave a folder
//! that mixes two runs): every folder writer (`run`,
//! `stability`, `report`) builds its new output in a staging folder beside the output folder
//! and makes it the output in one step, so after an interruption at any instant (SIGKILL
//! included) the folder holds either the old complete output or the new complete one.
//!
//! A commit (`Staging::commit`):
//! 1. the writer's files are written into the hidden staging folder
//!    `<parent>/.<name>.mbdbench-<pid>-<n>` (`Staging::write`);
//! 2. every entry of the old output folder that is not the writer's is carried over by hard
//!    link: the user's files (those the folder's manifest does not list) and the other
//!    writers' files, except those made from the writer's old output (a report is dropped
//!    when a new summary or `stability.json` is committed: it would describe the old one);
//!    the writer's own old files are left behind, so a file of a previous run can never sit
//!    beside the new summary;
//! 3. the manifest (`manifest.rs`: every suite file with its writer, size and SHA-256) is
//!    written into the staging folder;
//! 4. the staging folder and the output folder are exchanged atomically (`swap.rs`), and the
//!    old folder, now at the staging name, is removed: the suite deletes only files it wrote
//!    itself (the user's survive as the carried links).
//!
//! Readers (`gate`, `report`, and through them `advise`) check the files they read against
//! the manifest (`manifest::verify`). SIGINT, SIGTERM and SIGHUP remove the staging folder
//! (`interrupt`); a staging folder left by a killed process is removed by the next writer
//! beside it. `MBDBENCH_FAULT` (tests only) makes a writer kill itself at a named point:
//! `staged`, `carried`, `swapped`, or `file:<k>` (after the k-th file); with `:sigint`
//! appended it interrupts itself with SIGINT instead of SIGKILL.
//!
//! Where it fails: the parent folder must be writable (checked before any run by
//! `reference::check_writable`); the output folder may not be the current folder or one of
//! its ancestors (the process would be left inside the removed old folder); a file system
//! without hard links, or a mount point inside the output folder, stops the commit with the
//! old output untouched. Two writers committing into the same folder at the same time: the
//! last one wins.
//!
//! # Example
//!
//! ```
//! use mbdbench::output::{Manifest, Staging, Writer};
//!
//! let out = std::env::temp_dir().join(format!("output-doc-{}", std::process::id()));
//! let mut st = Staging::begin(&out, Writer::Run).unwrap();
//! st.write("summary.json", b"{}").unwrap();
//! st.commit().unwrap();
//! let m = Manifest::load(&out).unwrap().unwrap();
//! assert!(m.verify("summary.json", b"{}").is_ok());
//! std::fs::remove_dir_all(&out).unwrap();
//! ```
pub mod interrupt;
pub mod manifest;
mod swap;

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

pub use manifest::{MANIFEST, Manifest, Writer, verify};
use swap::Keep;

/// A new output being built for one folder.
pub struct Staging {
    /// The output folder (absolute, symbolic links resolved).
    out: PathBuf,
    /// The staging folder beside it.
    dir: PathBuf,
    writer: Writer,
    /// The files written so far.
    manifest: Manifest,
    /// Other writers whose old files the commit drops as well (`replace`).
    replaced: Vec<Writer>,
    /// The staging folder no longer exists or is no longer ours to remove.
    done: bool,
}

/// Distinguishes the staging folders of one process.
static NEXT: AtomicU64 = AtomicU64::new(0);

impl Staging {
    /// Starts a new output of `writer` for the folder `out` (made with its parents at commit;
    /// an existing `out` must be a folder). Removes the staging folders that killed processes
    /// left beside it.
    pub fn begin(out: &Path, writer: Writer) -> Result<Staging, String> {
        let out = resolve(out)?;
        let parent = out.parent().expect("resolve gives a path with a parent");
        std::fs::create_dir_all(parent).map_err(|e| format!("{}: {e}", parent.display()))?;
        let name = file_name(&out);
        remove_stale(parent, &name);
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        let dir = parent.join(format!(".{name}.mbdbench-{}-{n}", std::process::id()));
        interrupt::register(&dir);
        if let Err(e) = std::fs::create_dir(&dir) {
            interrupt::unregister(&dir);
            return Err(format!("{}: cannot create: {e}", dir.display()));
        }
        Ok(Staging {
            out,
            dir,
            writer,
            manifest: Manifest::default(),
            replaced: vec![],
            done: false,
        })
    }

    /// The output folder the commit will fill.
    pub fn out(&self) -> &Path {
        &self.out
    }

    /// Drops the old files of `other` at the commit too (a run drops a `stability.json`
    /// that is not of its build and selection: `Summary::pairs_with`).
    pub fn replace(&mut self, other: Writer) {
        self.replaced.push(other);
    }

    /// Writes the file `rel` (`/`-separated, inside the folder) of the new output.
    pub fn write(&mut self, rel: &str, bytes: &[u8]) -> Result<(), String> {
        let path = Path::new(rel);
        let plain = !rel.is_empty()
            && rel != MANIFEST
            && path
                .components()
                .all(|c| matches!(c, std::path::Component::Normal(_)));
        if !plain {
            return Err(format!(
                "{rel}: not a plain relative path inside the output"
            ));
        }
        let to = self.dir.join(path);
        let shown = |e: std::io::Error| format!("{}: {e}", self.out.join(rel).display());
        if let Some(d) = to.parent() {
            std::fs::create_dir_all(d).map_err(shown)?;
        }
        std::fs::write(&to, bytes).map_err(shown)?;
        self.manifest.add(rel, self.writer, bytes);
        if fault_point().is_some() {
            fault(&format!("file:{}", self.manifest.files.len()));
        }
        Ok(())
    }

    /// Makes the new output the folder's content (see the module's steps 2 to 4). Returns
    /// the other writers' old files it dropped (the report made from the old output, and
    /// those of `replace`), by their first path component, for the writer to say so.
    pub fn commit(mut self) -> Result<Vec<String>, String> {
        fault("staged");
        let old = match std::fs::symlink_metadata(&self.out) {
            Ok(m) if m.is_dir() => true,
            Ok(_) => {
                return Err(format!(
                    "{}: exists and is not a folder",
                    self.out.display()
                ));
            }
            Err(_) => false,
        };
        let mut dropped = vec![];
        if old {
            let previous = Manifest::load(&self.out).unwrap_or_else(|e| {
                crate::tell!("warning: {e}: every file of the folder is kept as the user's");
                None
            });
            let previous = previous.unwrap_or_default();
            let writer = self.writer;
            let gone = |w: Writer| w.derives_from(writer) || self.replaced.contains(&w);
            let keep = |rel: &str| match previous.files.get(rel) {
                _ if rel == MANIFEST => Keep::No,
                Some(e) if e.writer == writer || gone(e.writer) => Keep::No,
                _ => Keep::Yes,
            };
            for (rel, e) in &previous.files {
                let top = rel.split('/').next().unwrap_or(rel);
                let top = if top.len() < rel.len() {
                    format!("{top}/")
                } else {
                    top.into()
                };
                if e.writer != writer
                    && gone(e.writer)
                    && !dropped
                        .iter()
                        .any(|d: &(Writer, String)| d.0 == e.writer && d.1 == top)
                {
                    dropped.push((e.writer, top));
                }
            }
            let carried = swap::carry_over(&self.out, &self.dir, &keep)?;
            for rel in carried {
                if let Some(e) = previous.files.get(&rel) {
                    self.manifest.files.insert(rel, e.clone());
                }
            }
        }
        self.manifest.schema = 1;
        let text = serde_json::to_string_pretty(&self.manifest).map_err(|e| e.to_string())?;
        std::fs::write(self.dir.join(MANIFEST), text)
            .map_err(|e| format!("{}: {e}", self.out.join(MANIFEST).display()))?;
        fault("carried");
        interrupt::with_lock(|| self.swap(old))?;
        fault("swapped");
        // The staging name now holds the old output (or nothing).
        let _ = std::fs::remove_dir_all(&self.dir);
        interrupt::unregister(&self.dir);
        self.done = true;
        Ok(self.say_dropped(dropped))
    }

    /// Says which of the other writers' old files the commit removed, and what remakes them.
    fn say_dropped(&self, dropped: Vec<(Writer, String)>) -> Vec<String> {
        for w in [Writer::Run, Writer::Stability, Writer::Report] {
            let files: Vec<&str> = dropped
                .iter()
                .filter(|d| d.0 == w)
                .map(|d| d.1.as_str())
                .collect();
            if files.is_empty() {
                continue;
            }
            let why = if w.derives_from(self.writer) {
                "made from the files this replaces"
            } else {
                "not of this run's build and selection"
            };
            crate::tell!(
                "{}: removed {} ({why}; `mbdbench {}` remakes {})",
                self.out.display(),
                files.join(", "),
                w.command(),
                if files.len() == 1 { "it" } else { "them" }
            );
        }
        dropped.into_iter().map(|d| d.1).collect()
    }

    /// The new folder into place: exchanged with the old one, or renamed when there is none
    /// or the exchange is not available (then the old one is moved aside first).
    fn swap(&mut self, old: bool) -> Result<(), String> {
        let fail = |e: std::io::Error| format!("{}: cannot replace it: {e}", self.out.display());
        if old {
            if swap::exchange(&self.dir, &self.out).map_err(fail)? {
                return Ok(());
            }
            let aside = self.dir.with_extension("old");
            interrupt::register(&aside);
            std::fs::rename(&self.out, &aside).map_err(fail)?;
            let r = std::fs::rename(&self.dir, &self.out);
            if let Err(e) = r {
                let _ = std::fs::rename(&aside, &self.out);
                interrupt::unregister(&aside);
                return Err(fail(e));
            }
            let _ = std::fs::remove_dir_all(&aside);
            interrupt::unregister(&aside);
            return Ok(());
        }
        std::fs::rename(&self.dir, &self.out).map_err(fail)
    }
}

impl Drop for Staging {
    /// An output that was not committed leaves nothing behind.
    fn drop(&mut self) {
        if !self.done {
            let _ = std::fs::remove_dir_all(&self.dir);
            interrupt::unregister(&self.dir);
        }
    }
}

/// The absolute output path with symbolic links resolved (of the folder itself when it
/// exists, else of its nearest existing ancestor); refused when it is a root, the current
/// folder or one of its ancestors.
pub(crate) fn resolve(out: &Path) -> Result<PathBuf, String> {
    let abs = std::path::absolute(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut tail = vec![];
    let mut at = abs.as_path();
    let resolved = loop {
        match std::fs::canonicalize(at) {
            Ok(p) => break p,
            Err(_) => match (at.parent(), at.file_name()) {
                (Some(p), Some(n)) => {
                    tail.push(n.to_os_string());
                    at = p;
                }
                _ => break at.to_path_buf(),
            },
        }
    };
    let mut full = resolved;
    for n in tail.into_iter().rev() {
        full.push(n);
    }
    if full.parent().is_none() || full.file_name().is_none() {
        return Err(format!(
            "{}: an output folder cannot be a file-system root",
            out.display()
        ));
    }
    if let Ok(cwd) = std::env::current_dir().and_then(std::fs::canonicalize)
        && cwd.starts_with(&full)
    {
        return Err(format!(
            "{}: the output folder is replaced as a whole when written, so it cannot be the \
             current folder or one of its ancestors; name a folder of its own",
            out.display()
        ));
    }
    Ok(full)
}

fn file_name(p: &Path) -> String {
    p.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Removes the staging folders `.<name>.mbdbench-<pid>-<n>[.old]` in `parent` whose process
/// is gone (killed before it could clean up).
fn remove_stale(parent: &Path, name: &str) {
    let prefix = format!(".{name}.mbdbench-");
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    for e in entries.flatten() {
        let n = e.file_name();
        let Some(rest) = n.to_str().and_then(|n| n.strip_prefix(&prefix)) else {
            continue;
        };
        let pid = rest.split('-').next().and_then(|p| p.parse::<u32>().ok());
        if let Some(pid) = pid
            && pid != std::process::id()
            && !alive(pid)
        {
            let _ = std::fs::remove_dir_all(e.path());
        }
    }
}

/// Removes the temporary files `<stem>.tmp<pid>` of `path` (`reference::write_atomic`) whose
/// process is gone (killed between writing and renaming).
pub(crate) fn remove_stale_tmp(path: &Path) {
    let (Some(dir), Some(stem)) = (path.parent(), path.file_stem().and_then(|s| s.to_str())) else {
        return;
    };
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    let prefix = format!("{stem}.tmp");
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let n = e.file_name();
        let Some(pid) = n
            .to_str()
            .and_then(|n| n.strip_prefix(&prefix))
            .and_then(|p| p.parse::<u32>().ok())
        else {
            continue;
        };
        if pid != std::process::id() && !alive(pid) {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

/// Whether process `pid` exists (on systems without that test: assumed alive).
fn alive(pid: u32) -> bool {
    #[cfg(unix)]
    {
        let Ok(p) = libc::pid_t::try_from(pid) else {
            return false;
        };
        // SAFETY: signal 0 only checks that the process exists.
        let r = unsafe { libc::kill(p, 0) };
        r == 0 || std::io::Error::last_os_error().raw_os_error() == Some(libc::EPERM)
    }
    #[cfg(not(unix))]
    {
        let _ = pid;
        true
    }
}

/// `MBDBENCH_FAULT`, read once.
fn fault_point() -> Option<&'static str> {
    static POINT: std::sync::OnceLock<Option<String>> = std::sync::OnceLock::new();
    POINT
        .get_or_init(|| std::env::var("MBDBENCH_FAULT").ok())
        .as_deref()
}

/// Fault injection for the interruption tests: `MBDBENCH_FAULT=<point>` kills the process
/// with SIGKILL at that point, `<point>:sigint` interrupts it with SIGINT.
fn fault(point: &str) {
    let Some(want) = fault_point() else {
        return;
    };
    #[cfg(unix)]
    {
        let sig = if want == point {
            libc::SIGKILL
        } else if want.strip_suffix(":sigint") == Some(point) {
            libc::SIGINT
        } else {
            return;
        };
        // SAFETY: a signal to this process.
        unsafe { libc::kill(libc::getpid(), sig) };
        // SIGINT is handled by the interrupt thread: wait for it to end the process.
        std::thread::sleep(std::time::Duration::from_secs(60));
    }
    #[cfg(not(unix))]
    let _ = (want, point);
}

#[cfg(test)]
mod tests;
