//! Standard output and standard error that go quiet when their reader has gone.
//!
//! Once a write fails with `BrokenPipe` (EPIPE: `mbdbench list | head -1`, or
//! `mbdbench run ... 2>&1 | head -1` for stderr), every later write to that stream is dropped,
//! and the command finishes its work (its files are still written) and exits with its normal
//! status. Rust ignores SIGPIPE, so without this `println!` and `eprintln!` would panic
//! (exit 101). Every line the command line prints goes through [`Stdout`] ([`say!`]) or
//! [`Stderr`] ([`tell!`]); other write errors are returned to the caller of the writers (and
//! dropped by the macros).
//!
//! # Example
//!
//! ```
//! use std::io::Write;
//! // Writes like `println!`, but never panics on a closed pipe.
//! writeln!(mbdbench::quiet::Stdout, "ok").unwrap();
//! mbdbench::say!("{} runs", 3);
//! mbdbench::tell!("note: {}", "on stderr");
//! ```
use std::io::{self, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// Set once stdout's reader has gone.
static STDOUT_CLOSED: AtomicBool = AtomicBool::new(false);
/// Set once stderr's reader has gone.
static STDERR_CLOSED: AtomicBool = AtomicBool::new(false);

/// Whether stdout's reader has gone (a write failed with `BrokenPipe`).
pub fn closed() -> bool {
    STDOUT_CLOSED.load(Ordering::Relaxed)
}

/// `r`, with a broken pipe recorded in `closed` and turned into success (`or`).
fn quiet<T>(closed: &AtomicBool, r: io::Result<T>, or: T) -> io::Result<T> {
    match r {
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => {
            closed.store(true, Ordering::Relaxed);
            Ok(or)
        }
        r => r,
    }
}

/// Writes `buf` to `w` unless the stream is closed.
fn put(closed: &AtomicBool, mut w: impl Write, buf: &[u8]) -> io::Result<()> {
    if closed.load(Ordering::Relaxed) {
        return Ok(());
    }
    quiet(closed, w.write_all(buf), ())
}

fn flush(closed: &AtomicBool, mut w: impl Write) -> io::Result<()> {
    if closed.load(Ordering::Relaxed) {
        return Ok(());
    }
    quiet(closed, w.flush(), ())
}

/// The process's standard output, quiet after a broken pipe.
#[derive(Debug, Clone, Copy, Default)]
pub struct Stdout;

impl Write for Stdout {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        put(&STDOUT_CLOSED, io::stdout().lock(), buf).map(|()| buf.len())
    }
    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        put(&STDOUT_CLOSED, io::stdout().lock(), buf)
    }
    fn flush(&mut self) -> io::Result<()> {
        flush(&STDOUT_CLOSED, io::stdout().lock())
    }
}

/// The process's standard error, quiet after a broken pipe.
#[derive(Debug, Clone, Copy, Default)]
pub struct Stderr;

impl Write for Stderr {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        put(&STDERR_CLOSED, io::stderr().lock(), buf).map(|()| buf.len())
    }
    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        put(&STDERR_CLOSED, io::stderr().lock(), buf)
    }
    fn flush(&mut self) -> io::Result<()> {
        flush(&STDERR_CLOSED, io::stderr().lock())
    }
}

/// `println!` to [`Stdout`]: quiet after a broken pipe, never a panic.
#[macro_export]
macro_rules! say {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!($crate::quiet::Stdout, $($t)*);
    }};
}

/// `eprintln!` to [`Stderr`]: quiet after a broken pipe, never a panic.
#[macro_export]
macro_rules! tell {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!($crate::quiet::Stderr, $($t)*);
    }};
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A broken pipe (simulated by the flags) drops later writes to either stream without an
    /// error.
    #[test]
    fn writes_after_close_are_dropped() {
        STDOUT_CLOSED.store(true, Ordering::Relaxed);
        STDERR_CLOSED.store(true, Ordering::Relaxed);
        assert!(writeln!(Stdout, "dropped").is_ok());
        assert!(Stdout.flush().is_ok());
        assert!(writeln!(Stderr, "dropped").is_ok());
        assert!(Stderr.flush().is_ok());
        STDOUT_CLOSED.store(false, Ordering::Relaxed);
        STDERR_CLOSED.store(false, Ordering::Relaxed);
    }
}
