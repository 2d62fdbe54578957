//! Removing the suite's temporary files when the process is interrupted (SIGINT, SIGTERM,
//! SIGHUP). `install` (called first thing in `main`, before any thread exists) blocks those
//! signals in every thread and starts one thread that waits for them (`sigwait`): it takes the
//! registry's lock, removes every registered path (staging folders, `*.tmp<pid>` files), then
//! dies of the same signal (default action), so a shell sees the usual "killed by SIGINT".
//! The cleanup runs in an ordinary thread, not in a signal handler, so it may allocate and
//! call the file system.
//!
//! Writers hold the same lock while they make a staging folder the output (`with_lock`), so an
//! interrupt either removes the folder before the swap (the old output stays) or after it (the
//! folder then holds the superseded output, due for removal anyway).
//!
//! Where it fails: SIGKILL cannot be caught; its leftovers carry the dead process's id and the
//! next writer into the same place removes them (`Staging::begin`, `write_atomic`). Without
//! `install` (library use, tests) nothing is registered for signals, but writers still clean
//! up after their own errors. Not on Windows (no signal thread; Ctrl-C kills the process).
//!
//! # Example
//!
//! ```
//! use mbdbench::output::interrupt;
//!
//! let tmp = std::env::temp_dir().join(format!("interrupt-doc-{}", std::process::id()));
//! interrupt::register(&tmp); // removed if the process is interrupted from here...
//! std::fs::write(&tmp, b"partial").unwrap();
//! std::fs::remove_file(&tmp).unwrap();
//! interrupt::unregister(&tmp); // ...to here
//! ```
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

/// Paths to remove on an interrupt.
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn lock() -> MutexGuard<'static, Vec<PathBuf>> {
    PENDING.lock().unwrap_or_else(|e| e.into_inner())
}

/// Registers `path` (a file or a folder) for removal on an interrupt.
pub fn register(path: &Path) {
    lock().push(path.to_path_buf());
}

/// Forgets `path` (it was renamed into place or removed).
pub fn unregister(path: &Path) {
    let mut g = lock();
    if let Some(i) = g.iter().rposition(|p| p == path) {
        g.swap_remove(i);
    }
}

/// Runs `f` with the cleanup held off: an interrupt arriving meanwhile is handled after `f`.
pub fn with_lock<T>(f: impl FnOnce() -> T) -> T {
    let _g = lock();
    f()
}

fn remove_all(paths: &[PathBuf]) {
    for p in paths {
        match std::fs::symlink_metadata(p) {
            Ok(m) if m.is_dir() => {
                let _ = std::fs::remove_dir_all(p);
            }
            Ok(_) => {
                let _ = std::fs::remove_file(p);
            }
            Err(_) => {}
        }
    }
}

/// Blocks SIGINT, SIGTERM and SIGHUP in this thread (and every thread it starts later) and
/// starts the thread that handles them. Call once, before any other thread is started.
pub fn install() {
    #[cfg(unix)]
    unix::install();
}

#[cfg(unix)]
mod unix {
    use super::{lock, remove_all};

    fn signals() -> libc::sigset_t {
        // SAFETY: sigemptyset initialises the set; sigaddset only writes into it.
        unsafe {
            let mut set: libc::sigset_t = std::mem::zeroed();
            libc::sigemptyset(&mut set);
            for s in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
                libc::sigaddset(&mut set, s);
            }
            set
        }
    }

    pub(super) fn install() {
        let set = signals();
        // SAFETY: a valid set; the old mask is not needed.
        let r = unsafe { libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut()) };
        if r != 0 {
            return;
        }
        let spawned = std::thread::Builder::new()
            .name("interrupt".into())
            .spawn(move || {
                let mut sig: libc::c_int = 0;
                // SAFETY: `set` is valid and blocked in every thread; sigwait writes `sig`.
                while unsafe { libc::sigwait(&set, &mut sig) } != 0 {}
                let pending = lock();
                remove_all(&pending);
                // SAFETY: restore the default action and deliver the signal to this thread
                // with it unblocked: the process ends as killed by that signal.
                unsafe {
                    libc::signal(sig, libc::SIG_DFL);
                    let mut one: libc::sigset_t = std::mem::zeroed();
                    libc::sigemptyset(&mut one);
                    libc::sigaddset(&mut one, sig);
                    libc::pthread_sigmask(libc::SIG_UNBLOCK, &one, std::ptr::null_mut());
                    libc::raise(sig);
                }
                std::process::exit(128 + sig);
            });
        if spawned.is_err() {
            // No handler thread: let the signals act as before.
            // SAFETY: as above.
            unsafe { libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut()) };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A registered path is removed by the cleanup and an unregistered one is not; files and
    /// folders alike.
    #[test]
    fn cleanup_removes_registered_paths() {
        let d = std::env::temp_dir().join(format!("mbdbench-interrupt-{}", std::process::id()));
        std::fs::create_dir_all(d.join("sub")).unwrap();
        std::fs::write(d.join("sub/f"), b"x").unwrap();
        let f = d.with_extension("tmp");
        std::fs::write(&f, b"y").unwrap();
        let keep = d.with_extension("keep");
        std::fs::write(&keep, b"z").unwrap();
        register(&d);
        register(&f);
        register(&keep);
        unregister(&keep);
        let pending: Vec<PathBuf> = lock()
            .iter()
            .filter(|p| [&d, &f].contains(p))
            .cloned()
            .collect();
        remove_all(&pending);
        unregister(&d);
        unregister(&f);
        assert!(!d.exists() && !f.exists() && keep.exists());
        std::fs::remove_file(&keep).unwrap();
    }
}
