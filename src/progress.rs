//! Progress of a pass over many runs or searches, on stderr: on a terminal an `indicatif`
//! bar with the elapsed time and an estimate of what remains; otherwise (a CI log, a pipe)
//! a plain line every `every`-th of the items, with the same two times, so that a log says
//! how far a phase is and how long it will still take. Each phase (`results`, `timing`, a
//! stability part) has its own. The estimate is the elapsed time scaled by the items left,
//! so it assumes the items left cost what the done ones did on average (the catalogue's
//! order mixes cheap and dear runs; it is a guide, not a promise).
//!
//! # Example
//!
//! ```
//! let p = mbdbench::progress::Progress::new(4, "results", "runs", 2, false);
//! for _ in 0..4 {
//!     p.tick();
//! }
//! p.finish();
//! ```
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// One phase's progress.
pub struct Progress {
    bar: Option<indicatif::ProgressBar>,
    total: usize,
    done: AtomicUsize,
    label: String,
    unit: &'static str,
    /// Plain lines at every `total / every`-th item.
    every: usize,
    enabled: bool,
    started: Instant,
}

/// `s` seconds as text: `42 s`, `3 min 05 s`.
fn duration(s: f64) -> String {
    let s = s.max(0.0).round() as u64;
    if s < 60 {
        format!("{s} s")
    } else {
        format!("{} min {:02} s", s / 60, s % 60)
    }
}

impl Progress {
    /// A phase of `total` items named `label`, counted in `unit`, with plain lines every
    /// `total / every` items (when `enabled`).
    pub fn new(total: usize, label: &str, unit: &'static str, every: usize, enabled: bool) -> Self {
        use std::io::IsTerminal;
        let bar = (enabled && std::io::stderr().is_terminal()).then(|| {
            let b = indicatif::ProgressBar::new(total as u64);
            b.set_message(label.to_string());
            if let Ok(style) = indicatif::ProgressStyle::with_template(
                "  {msg:<10} [{bar:40}] {pos}/{len} (elapsed {elapsed}, about {eta} left)",
            ) {
                b.set_style(style.progress_chars("=> "));
            }
            b
        });
        Progress {
            bar,
            total,
            done: AtomicUsize::new(0),
            label: label.to_string(),
            unit,
            every: every.max(1),
            enabled,
            started: Instant::now(),
        }
    }

    /// One item done.
    pub fn tick(&self) {
        let n = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        match &self.bar {
            Some(b) => b.inc(1),
            None if self.enabled
                && (n.is_multiple_of((self.total / self.every).max(1)) || n == self.total) =>
            {
                let t = self.started.elapsed().as_secs_f64();
                let left = t * (self.total - n) as f64 / n as f64;
                let rest = if n == self.total {
                    String::new()
                } else {
                    format!(", about {} left", duration(left))
                };
                crate::tell!(
                    "  {} {n}/{} {} ({} elapsed{rest})",
                    self.label,
                    self.total,
                    self.unit,
                    duration(t)
                );
            }
            None => {}
        }
    }

    /// The phase is over: the bar is cleared.
    pub fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Durations read as seconds below a minute and as minutes and seconds above.
    #[test]
    fn durations_read_as_a_person_says_them() {
        assert_eq!(duration(0.4), "0 s");
        assert_eq!(duration(42.4), "42 s");
        assert_eq!(duration(185.0), "3 min 05 s");
    }
}
