//! The two file-system steps of committing a staging folder (`output::Staging::commit`):
//! carrying over the entries of the old output folder that the committing writer does not
//! replace (hard links, so nothing is copied and nothing of the user's is lost), and
//! exchanging the staging folder with the output folder in one step.
//!
//! The exchange is `renameat2(RENAME_EXCHANGE)` (Linux 3.15+; ext4, xfs, btrfs, tmpfs and
//! most others): both names stay valid throughout, and a process killed at any instant leaves
//! the output folder either wholly old or wholly new. Where it is not available (another
//! system, or a file system that refuses it with `EINVAL`), two renames move the old folder
//! aside and the new one into place; a kill between them leaves the output's name absent for
//! that instant, with the old output complete in the hidden folder beside it.
use std::io;
use std::path::Path;

/// What to do with one entry of the old folder.
pub(super) enum Keep {
    /// Carry it over into the new folder.
    Yes,
    /// Leave it behind (it is replaced or dropped).
    No,
}

/// Carries the entries of `old` that `keep` (given the `/`-separated relative path) accepts
/// into `new`: folders are made, files hard-linked, symbolic links recreated (never
/// followed). An entry already present in `new` is left as the new one; a folder left empty
/// by the files it does not carry is not made. Returns the relative paths of the files
/// carried over.
pub(super) fn carry_over(
    old: &Path,
    new: &Path,
    keep: &dyn Fn(&str) -> Keep,
) -> Result<Vec<String>, String> {
    let (mut carried, mut dropped) = (vec![], vec![]);
    let mut stack = vec![String::new()];
    while let Some(rel_dir) = stack.pop() {
        let dir = old.join(&rel_dir);
        let entries = std::fs::read_dir(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        for entry in entries {
            let entry = entry.map_err(|e| format!("{}: {e}", dir.display()))?;
            let name = entry.file_name();
            let Some(name) = name.to_str() else {
                // A name that is not UTF-8 cannot be the suite's: carried as it is.
                let to = new.join(&rel_dir).join(entry.file_name());
                link_one(&entry.path(), &to)?;
                continue;
            };
            let rel = if rel_dir.is_empty() {
                name.to_string()
            } else {
                format!("{rel_dir}/{name}")
            };
            let from = entry.path();
            let to = new.join(&rel);
            let meta =
                std::fs::symlink_metadata(&from).map_err(|e| format!("{}: {e}", from.display()))?;
            if meta.is_dir() {
                match std::fs::symlink_metadata(&to) {
                    Ok(m) if !m.is_dir() => return Err(in_the_way(&from, &to)),
                    Ok(_) => {}
                    Err(_) => {
                        std::fs::create_dir(&to).map_err(|e| format!("{}: {e}", to.display()))?
                    }
                }
                stack.push(rel);
                continue;
            }
            if let Keep::No = keep(&rel) {
                dropped.push(rel);
                continue;
            }
            match std::fs::symlink_metadata(&to) {
                Ok(m) if m.is_dir() => return Err(in_the_way(&from, &to)),
                Ok(_) => continue,
                Err(_) => {}
            }
            link_one(&from, &to)?;
            carried.push(rel);
        }
    }
    // A folder made here that holds nothing now held only files left behind (a report's
    // `svg/` when the new report writes none): removed, up to the first folder that still
    // holds something. A folder of the user's that held none of them is never touched.
    for rel in &dropped {
        let mut dir = Path::new(rel).parent();
        while let Some(d) = dir.filter(|d| !d.as_os_str().is_empty()) {
            if std::fs::remove_dir(new.join(d)).is_err() {
                break;
            }
            dir = d.parent();
        }
    }
    Ok(carried)
}

fn in_the_way(from: &Path, to: &Path) -> String {
    format!(
        "{}: in the way of the new output {} (a file where a folder is written, or the \
         reverse); move it and rerun",
        from.display(),
        to.display()
    )
}

/// A hard link of `from` at `to` (a symbolic link is recreated, not followed).
fn link_one(from: &Path, to: &Path) -> Result<(), String> {
    let meta = std::fs::symlink_metadata(from).map_err(|e| format!("{}: {e}", from.display()))?;
    let r = if meta.file_type().is_symlink() {
        symlink(from, to)
    } else {
        std::fs::hard_link(from, to)
    };
    r.map_err(|e| {
        format!(
            "{}: cannot keep it in the new output ({e}); nothing was changed",
            from.display()
        )
    })
}

#[cfg(unix)]
fn symlink(from: &Path, to: &Path) -> io::Result<()> {
    std::os::unix::fs::symlink(std::fs::read_link(from)?, to)
}

#[cfg(not(unix))]
fn symlink(from: &Path, to: &Path) -> io::Result<()> {
    std::fs::copy(from, to).map(|_| ())
}

/// Exchanges the folders `a` and `b` atomically; false when the system or file system
/// cannot (the caller then moves them one after the other).
pub(super) fn exchange(a: &Path, b: &Path) -> io::Result<bool> {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::ffi::OsStrExt;
        let ca = std::ffi::CString::new(a.as_os_str().as_bytes())?;
        let cb = std::ffi::CString::new(b.as_os_str().as_bytes())?;
        // SAFETY: two valid NUL-terminated paths; renameat2 reads them only.
        let r = unsafe {
            libc::syscall(
                libc::SYS_renameat2,
                libc::AT_FDCWD,
                ca.as_ptr(),
                libc::AT_FDCWD,
                cb.as_ptr(),
                libc::RENAME_EXCHANGE,
            )
        };
        if r == 0 {
            return Ok(true);
        }
        let e = io::Error::last_os_error();
        match e.raw_os_error() {
            Some(libc::EINVAL) | Some(libc::ENOSYS) | Some(libc::ENOTSUP) => Ok(false),
            _ => Err(e),
        }
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = (a, b);
        Ok(false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tree(root: &Path, files: &[(&str, &str)]) {
        for (rel, text) in files {
            let p = root.join(rel);
            std::fs::create_dir_all(p.parent().unwrap()).unwrap();
            std::fs::write(p, text).unwrap();
        }
    }

    /// Carrying over keeps what `keep` accepts (as hard links: same content, no copy), never
    /// replaces an entry of the new folder, makes no folder that only dropped files filled,
    /// keeps the user's empty folders, and refuses a file where a folder is written.
    #[test]
    fn carry_over_keeps_and_never_replaces() {
        let base = std::env::temp_dir().join(format!("mbdbench-swap-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        let (old, new) = (base.join("old"), base.join("new"));
        tree(
            &old,
            &[
                ("notes.txt", "user"),
                ("summary.json", "old summary"),
                ("series/a/x.json", "old series"),
                ("deep/user/file", "deep"),
            ],
        );
        tree(&new, &[("summary.json", "new summary")]);
        std::fs::create_dir_all(old.join("empty/inner")).unwrap();
        let carried = carry_over(&old, &new, &|rel: &str| {
            if rel.starts_with("series/") {
                Keep::No
            } else {
                Keep::Yes
            }
        })
        .unwrap();
        let mut carried = carried;
        carried.sort();
        assert_eq!(carried, ["deep/user/file", "notes.txt"]);
        let read = |p: &str| std::fs::read_to_string(new.join(p)).unwrap();
        assert_eq!(read("summary.json"), "new summary");
        assert_eq!(read("notes.txt"), "user");
        assert_eq!(read("deep/user/file"), "deep");
        assert!(!new.join("series/a/x.json").exists());
        // The folders of the dropped files are not made; the user's empty ones are.
        assert!(!new.join("series").exists());
        assert!(new.join("empty/inner").is_dir());
        // A file of the new folder where the old one has a folder is in the way.
        std::fs::remove_dir_all(new.join("deep")).unwrap();
        tree(&new, &[("deep", "a file now")]);
        let e = carry_over(&old, &new, &|_| Keep::Yes).unwrap_err();
        assert!(e.contains("in the way"), "{e}");
        std::fs::remove_dir_all(&base).unwrap();
    }

    /// The exchange swaps two folders (on Linux it must be available; elsewhere it may report
    /// that it cannot).
    #[test]
    fn exchange_swaps() {
        let base = std::env::temp_dir().join(format!("mbdbench-xchg-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        tree(&base, &[("a/f", "A"), ("b/f", "B")]);
        let swapped = exchange(&base.join("a"), &base.join("b")).unwrap();
        // Linux's temporary folders (tmpfs, ext4) support the exchange: it must happen there.
        #[cfg(target_os = "linux")]
        assert!(swapped, "renameat2(RENAME_EXCHANGE) refused on Linux");
        if swapped {
            assert_eq!(std::fs::read_to_string(base.join("a/f")).unwrap(), "B");
            assert_eq!(std::fs::read_to_string(base.join("b/f")).unwrap(), "A");
        }
        std::fs::remove_dir_all(&base).unwrap();
    }
}
