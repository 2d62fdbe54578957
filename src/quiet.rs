//! Standard output that goes quiet when its reader has gone: once a write fails with
//! `BrokenPipe` (EPIPE: `mbdbench list | head -1`), every later write to stdout is dropped, and
//! the command finishes its work (its files are still written) and exits with its normal
//! status. Rust ignores SIGPIPE, so without this `println!` would panic (exit 101). Other
//! write errors are returned to the caller of [`Stdout`] (and dropped by [`say!`]).
//!
//! # Example
//!
//! ```
//! use std::io::Write;
//! // Writes like `println!`, but never panics on a closed pipe.
//! writeln!(mbdbench::quiet::Stdout, "ok").unwrap();
//! mbdbench::say!("{} runs", 3);
//! ```
use std::io::{self, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// Set once stdout's reader has gone.
static CLOSED: AtomicBool = AtomicBool::new(false);

/// Whether stdout's reader has gone (a write failed with `BrokenPipe`).
pub fn closed() -> bool {
    CLOSED.load(Ordering::Relaxed)
}

/// The process's standard output, quiet after a broken pipe.
#[derive(Debug, Clone, Copy, Default)]
pub struct Stdout;

fn quiet<T>(r: io::Result<T>, or: T) -> io::Result<T> {
    match r {
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => {
            CLOSED.store(true, Ordering::Relaxed);
            Ok(or)
        }
        r => r,
    }
}

impl Write for Stdout {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if closed() {
            return Ok(buf.len());
        }
        quiet(io::stdout().lock().write(buf), buf.len())
    }
    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        if closed() {
            return Ok(());
        }
        quiet(io::stdout().lock().write_all(buf), ())
    }
    fn flush(&mut self) -> io::Result<()> {
        if closed() {
            return Ok(());
        }
        quiet(io::stdout().lock().flush(), ())
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

#[cfg(test)]
mod tests {
    /// A broken pipe (simulated by the flag) drops later writes without an error.
    #[test]
    fn writes_after_close_are_dropped() {
        use std::io::Write;
        super::CLOSED.store(true, std::sync::atomic::Ordering::Relaxed);
        assert!(writeln!(super::Stdout, "dropped").is_ok());
        assert!(super::Stdout.flush().is_ok());
        super::CLOSED.store(false, std::sync::atomic::Ordering::Relaxed);
    }
}
