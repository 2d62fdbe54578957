//! Standard output and standard error that go quiet when their reader has gone, and never
//! print a terminal control sequence they were handed.
//!
//! Once a write fails with `BrokenPipe` (EPIPE: `mbdbench list | head -1`, or
//! `mbdbench run ... 2>&1 | head -1` for stderr), every later write to that stream is dropped,
//! and the command finishes its work (its files are still written) and exits with its normal
//! status. Rust ignores SIGPIPE, so without this `println!` and `eprintln!` would panic
//! (exit 101). Every line the command line prints goes through [`Stdout`] ([`say!`]) or
//! [`Stderr`] ([`tell!`]); other write errors are returned to the caller of the writers (and
//! dropped by the macros).
//!
//! Text from input files (a case's `title`, names in a hand-edited summary, a key quoted in
//! an error) reaches both streams, so every control character except newline and tab (ESC,
//! carriage return, the other C0 controls, DEL and the C1 controls U+0080 to U+009F) is written
//! as the visible text `\u001b` instead ([`terminal_safe`]): a case file cannot move the
//! cursor, recolour or retitle the terminal. Inside JSON output (`list --json`) that is the
//! JSON escape of the same character, so the value read back is unchanged.
//!
//! # Example
//!
//! ```
//! use std::io::Write;
//! // Writes like `println!`, but never panics on a closed pipe.
//! writeln!(mbdbench::quiet::Stdout, "ok").unwrap();
//! mbdbench::say!("{} runs", 3);
//! mbdbench::tell!("note: {}", "on stderr");
//! assert_eq!(mbdbench::quiet::terminal_safe("a\u{1b}[2Jb\n"), "a\\u001b[2Jb\n");
//! ```
use std::borrow::Cow;
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

/// Whether a character is written escaped: a control character other than newline and tab.
fn hidden(c: char) -> bool {
    c.is_control() && c != '\n' && c != '\t'
}

/// `s` with every control character but newline and tab written as `\uXXXX` (module docs).
pub fn terminal_safe(s: &str) -> Cow<'_, str> {
    if !s.chars().any(hidden) {
        return Cow::Borrowed(s);
    }
    let mut out = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        if hidden(c) {
            out.push_str(&format!("\\u{:04x}", c as u32));
        } else {
            out.push(c);
        }
    }
    Cow::Owned(out)
}

/// `buf` made terminal-safe: its UTF-8 text through [`terminal_safe`], any byte that is not
/// UTF-8 as `\xNN`.
fn safe_bytes(buf: &[u8]) -> Cow<'_, [u8]> {
    if let Ok(s) = std::str::from_utf8(buf) {
        return match terminal_safe(s) {
            Cow::Borrowed(_) => Cow::Borrowed(buf),
            Cow::Owned(o) => Cow::Owned(o.into_bytes()),
        };
    }
    let mut out = String::with_capacity(buf.len() + 8);
    for chunk in buf.utf8_chunks() {
        out.push_str(&terminal_safe(chunk.valid()));
        for b in chunk.invalid() {
            out.push_str(&format!("\\x{b:02x}"));
        }
    }
    Cow::Owned(out.into_bytes())
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

/// Writes `buf`, terminal-safe, to `w` unless the stream is closed.
fn put(closed: &AtomicBool, mut w: impl Write, buf: &[u8]) -> io::Result<()> {
    if closed.load(Ordering::Relaxed) {
        return Ok(());
    }
    quiet(closed, w.write_all(&safe_bytes(buf)), ())
}

fn flush(closed: &AtomicBool, mut w: impl Write) -> io::Result<()> {
    if closed.load(Ordering::Relaxed) {
        return Ok(());
    }
    quiet(closed, w.flush(), ())
}

/// The process's standard output, quiet after a broken pipe, terminal-safe.
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

/// The process's standard error, quiet after a broken pipe, terminal-safe.
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

    /// ESC, carriage return, BEL, DEL and the C1 controls (CSI, U+009B) are written as visible
    /// `\uXXXX` text; newline, tab and other text pass unchanged.
    #[test]
    fn control_characters_are_made_visible() {
        assert_eq!(terminal_safe("plain — text\n\tok"), "plain — text\n\tok");
        assert!(matches!(terminal_safe("plain"), Cow::Borrowed(_)));
        assert_eq!(
            terminal_safe("\u{1b}]0;pwned\u{7}\r\u{7f}\u{9b}31m"),
            "\\u001b]0;pwned\\u0007\\u000d\\u007f\\u009b31m"
        );
        let safe = safe_bytes(b"a\x1b[2J\xff\n");
        assert_eq!(&*safe, b"a\\u001b[2J\\xff\n");
    }

    /// Escaped control characters inside JSON strings are the JSON escapes of the same
    /// characters: the text read back is the original.
    #[test]
    fn json_values_survive() {
        let v = serde_json::json!({ "title": "a\u{9b}b\u{7f}\u{1b}" });
        let text = serde_json::to_string(&v).unwrap();
        let back: serde_json::Value = serde_json::from_str(&terminal_safe(&text)).unwrap();
        assert_eq!(back, v);
        assert!(!terminal_safe(&text).chars().any(hidden));
    }
}
