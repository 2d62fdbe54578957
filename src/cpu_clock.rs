//! `cpu_clock`: the CPU time of the calling thread, in seconds, for the accounts of where a
//! run's time went (the main job's time per family, `suite`): a worker's CPU seconds are
//! what its runs cost, whatever else the machine was doing, where its wall time would also
//! count the time the operating system gave to other processes.
//!
//! On Unix it is POSIX's `clock_gettime(CLOCK_THREAD_CPUTIME_ID)` (nanosecond resolution on
//! Linux; user plus system time of this thread). Elsewhere, or if that call fails, it falls
//! back to a monotonic wall clock started with the process ([`Clock::Wall`]), and says so, so
//! that an account never passes wall seconds off as CPU seconds.
//!
//! Invariant: for one thread, successive readings never decrease.

/// Which clock a reading came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Clock {
    /// The thread's CPU time.
    ThreadCpu,
    /// Wall time since the first reading (the fallback).
    Wall,
}

/// Seconds of the calling thread's CPU time (or, where the platform has no such clock, of
/// wall time since the first reading), and which clock gave them.
///
/// # Example
///
/// ```
/// let (t0, clock) = mbdbench::cpu_clock::now();
/// let mut x = 0u64;
/// for k in 0..1_000_000u64 {
///     x = std::hint::black_box(x.wrapping_add(k * k));
/// }
/// let (t1, _) = mbdbench::cpu_clock::now();
/// assert!(t1 >= t0);
/// # let _ = (x, clock);
/// ```
pub fn now() -> (f64, Clock) {
    #[cfg(unix)]
    {
        let mut ts = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `ts` is a valid, writable timespec; the call writes it and nothing else.
        let r = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
        if r == 0 {
            return (
                ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9,
                Clock::ThreadCpu,
            );
        }
    }
    (wall(), Clock::Wall)
}

fn wall() -> f64 {
    static START: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
    START
        .get_or_init(std::time::Instant::now)
        .elapsed()
        .as_secs_f64()
}

/// The CPU seconds `f` took on this thread, with its result.
pub fn measure<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let (t0, _) = now();
    let out = f();
    let (t1, _) = now();
    (out, (t1 - t0).max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A busy loop costs CPU time on this thread, and a sleep does not (on a platform with a
    /// thread CPU clock): the account counts work, not waiting.
    #[test]
    fn counts_work_not_sleep() {
        let (_, clock) = now();
        let ((), busy) = measure(|| {
            let t = std::time::Instant::now();
            let mut x = 0u64;
            while t.elapsed().as_secs_f64() < 0.05 {
                x = std::hint::black_box(x.wrapping_add(1));
            }
        });
        assert!(busy > 0.01, "50 ms of work measured as {busy} s");
        if clock == Clock::ThreadCpu {
            let ((), idle) = measure(|| std::thread::sleep(std::time::Duration::from_millis(50)));
            assert!(idle < 0.02, "a 50 ms sleep measured as {idle} CPU s");
        }
    }
}
