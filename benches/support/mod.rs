//! Shared by the benches (`step`, `case`, `structural`, `lu`): sizing criterion's sampling for each benchmark
//! from the measured cost of one of its iterations, so that every sample fits in the
//! measurement time (criterion warns "Unable to complete N samples" when one does not), and
//! reading criterion's own estimates back from its output folder for a closing table.
//!
//! A benchmark whose samples fit in [`MEASUREMENT`] with [`LINEAR_HEADROOM`] to spare is
//! sampled linearly (10 to 30 samples); a dearer one is sampled flat, 10 samples, its
//! measurement time stretched when needed: to keep [`CHEAP_HEADROOM`] while that takes at
//! most twice [`MEASUREMENT`], else [`FLAT_HEADROOM`] (two iterations a sample). The headroom
//! covers criterion's own estimate of an iteration (taken in the warm-up) coming out above
//! the calibration: on this shared two-core machine a burst of other work slowed every run
//! up to 9x for seconds, and its median of three runs reads up to 3x below criterion's
//! estimate at other times. Headroom is free where it only costs samples (linear) and cheap
//! on short runs; on the dearest runs it would cost their time over again, so they keep 2x.
//! Criterion's bootstrap draws 10,000 resamples instead of its default 100,000 (the analysis
//! of a thousand benchmarks would take a minute more; the point estimates do not depend on
//! it, only the confidence intervals).
#![allow(dead_code)] // Each bench uses its own part of this module.

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, SamplingMode};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant, SystemTime};

/// Measurement time of a benchmark whose samples fit in it, in seconds.
pub const MEASUREMENT: f64 = 0.1;
/// Warm-up time, in seconds, of a benchmark under 12 ms an iteration; a dearer one warms up
/// for 2.5 iterations' time, so three iterations (criterion doubles them: 1, then 2) and
/// not one that came out slow (it took twice the calibration once) make its estimate.
pub const WARM_UP: f64 = 0.03;
const WARM_UP_ITERATIONS: f64 = 2.5;
/// How much dearer criterion's warm-up estimate of an iteration may come out than the
/// calibration before a linear sample no longer fits (costs nothing but samples).
pub const LINEAR_HEADROOM: f64 = 8.0;
/// The same for a flat-sampled benchmark whose measurement needs at most twice
/// [`MEASUREMENT`] for it.
pub const CHEAP_HEADROOM: f64 = 4.0;
/// The same for a dearer one (costs time: two iterations a sample while the estimate is
/// within 1x to 2x of the calibration).
pub const FLAT_HEADROOM: f64 = 2.0;
/// Criterion's bootstrap resamples.
const RESAMPLES: usize = 10_000;
/// Below this (seconds), a calibration takes the median of three runs.
const SHORT_RUN: f64 = 0.1;
/// Criterion's minimum sample count.
const MIN_SAMPLES: usize = 10;
const MAX_SAMPLES: usize = 30;

/// Whether criterion measures in this process (`cargo bench`): not `cargo test --benches`
/// (each benchmark run once, untimed), `--test`, `--list` or `--profile-time`.
pub fn measuring() -> bool {
    let args: Vec<String> = std::env::args().collect();
    args.iter().any(|a| a == "--bench")
        && !args
            .iter()
            .any(|a| a == "--test" || a == "--list" || a.starts_with("--profile-time"))
}

/// Runs `f` once: its result and its wall time in seconds.
pub fn timed<R>(f: impl FnOnce() -> R) -> (R, f64) {
    let t0 = Instant::now();
    let r = f();
    (r, t0.elapsed().as_secs_f64())
}

/// Criterion's sampling of one benchmark.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sizing {
    pub samples: usize,
    pub flat: bool,
    /// Seconds.
    pub warm_up: f64,
    /// Seconds.
    pub measurement: f64,
}

impl Sizing {
    /// The sampling of a benchmark whose iteration costs `t` seconds.
    pub fn for_cost(t: f64) -> Sizing {
        let t = t.max(1e-9);
        let fits = |n: usize| (n * (n + 1) / 2) as f64 * t * LINEAR_HEADROOM <= MEASUREMENT;
        if fits(MIN_SAMPLES) {
            let samples = (MIN_SAMPLES..=MAX_SAMPLES)
                .rev()
                .find(|&n| fits(n))
                .unwrap_or(MIN_SAMPLES);
            return Sizing {
                samples,
                flat: false,
                warm_up: WARM_UP,
                measurement: MEASUREMENT,
            };
        }
        let sample = MIN_SAMPLES as f64 * t;
        Sizing {
            samples: MIN_SAMPLES,
            flat: true,
            warm_up: WARM_UP.max(WARM_UP_ITERATIONS * t),
            measurement: MEASUREMENT
                .max((CHEAP_HEADROOM * sample).min(2.0 * MEASUREMENT))
                .max(FLAT_HEADROOM * sample),
        }
    }

    /// How much dearer than `t` criterion's estimate may come out before it warns.
    pub fn headroom(&self, t: f64) -> f64 {
        let n = self.samples as f64;
        let per_iteration = if self.flat { n } else { n * (n + 1.0) / 2.0 };
        self.measurement / (per_iteration * t)
    }

    /// The iteration counts criterion would take for an iteration of `t` seconds, and
    /// whether it would warn (its `ActualSamplingMode::iteration_counts`).
    pub fn iterations(&self, t: f64) -> (Vec<u64>, bool) {
        let n = self.samples as u64;
        if self.flat {
            let per = ((self.measurement / n as f64 / t).ceil() as u64).max(1);
            (vec![per; self.samples], per == 1)
        } else {
            let runs = n * (n + 1) / 2;
            let d = ((self.measurement / t / runs as f64).ceil() as u64).max(1);
            ((1..=n).map(|a| a * d).collect(), d == 1)
        }
    }

    /// Expected wall time of warm-up and measurement, in seconds.
    pub fn expected(&self, t: f64) -> f64 {
        let t = t.max(1e-9);
        // Criterion's warm-up: 1, 2, 4, ... iterations until the warm-up time has passed.
        let (mut batch, mut warm) = (1_u64, 0_u64);
        loop {
            warm += batch;
            if warm as f64 * t > self.warm_up {
                break;
            }
            batch *= 2;
        }
        (warm + self.iterations(t).0.iter().sum::<u64>()) as f64 * t
    }

    /// Sets the group's sampling for the benchmarks registered next.
    pub fn apply(&self, g: &mut BenchmarkGroup<'_, WallTime>) {
        g.sample_size(self.samples)
            .sampling_mode(if self.flat {
                SamplingMode::Flat
            } else {
                SamplingMode::Linear
            })
            .nresamples(RESAMPLES)
            .warm_up_time(Duration::from_secs_f64(self.warm_up))
            .measurement_time(Duration::from_secs_f64(self.measurement));
    }
}

/// Checks the sizing against criterion's rule over iteration costs from 10 ns to 10 s: at
/// least [`FLAT_HEADROOM`], and no warning for an estimate anywhere from a tenth of the
/// calibration up to the headroom (run by every bench binary first; no timing is involved).
pub fn check_sizing() {
    let mut t = 1e-8;
    while t < 10.0 {
        let s = Sizing::for_cost(t);
        let headroom = s.headroom(t);
        assert!(
            headroom >= FLAT_HEADROOM,
            "{s:?}: headroom {headroom} at {t} s"
        );
        for f in [0.1, 0.5, 1.0, 0.99 * headroom] {
            assert!(!s.iterations(t * f).1, "{s:?} warns at {} s", t * f);
        }
        t *= 1.1;
    }
}

/// The cost of one iteration, in seconds, from a first run of `first` seconds: the median of
/// it and two more runs of `f` when it is under 0.1 s (one short run's time is off by up to
/// 2.5x here), else the first run.
pub fn calibrate(first: f64, mut f: impl FnMut()) -> f64 {
    if first >= SHORT_RUN {
        return first;
    }
    let mut t = [first, timed(&mut f).1, timed(&mut f).1];
    t.sort_by(f64::total_cmp);
    t[1]
}

/// Criterion's output folder, found as criterion finds it: `$CRITERION_HOME`, else
/// `$CARGO_TARGET_DIR/criterion`, else the target directory of `cargo metadata`, else
/// `target/criterion`.
pub fn criterion_home() -> PathBuf {
    if let Some(h) = std::env::var_os("CRITERION_HOME") {
        return PathBuf::from(h);
    }
    if let Some(t) = std::env::var_os("CARGO_TARGET_DIR") {
        return PathBuf::from(t).join("criterion");
    }
    let metadata = std::env::var_os("CARGO").and_then(|cargo| {
        std::process::Command::new(cargo)
            .args(["metadata", "--format-version", "1", "--no-deps"])
            .output()
            .ok()
    });
    metadata
        .and_then(|o| serde_json::from_slice::<serde_json::Value>(&o.stdout).ok())
        .and_then(|v| v["target_directory"].as_str().map(PathBuf::from))
        .map_or_else(
            || PathBuf::from("target/criterion"),
            |t| t.join("criterion"),
        )
}

/// One name as criterion makes it a folder name (`report::make_filename_safe`, not Windows).
fn folder_safe(s: &str) -> String {
    let mut s = s.replace(['?', '"', '/', '\\', '*', '<', '>', ':', '|', '^'], "_");
    let mut end = s.len().min(64);
    while !s.is_char_boundary(end) {
        end -= 1;
    }
    s.truncate(end);
    s
}

/// Criterion's estimate of one benchmark from this process's run.
#[derive(Debug, Clone)]
pub struct Estimate {
    /// Criterion's reported time per iteration (its `time:` line), in ns.
    pub ns: f64,
    /// Which statistic that is: `slope` (linear sampling) or `mean` (flat).
    pub statistic: &'static str,
    /// The benchmark's throughput in elements per iteration, if it has one.
    pub elements: Option<u64>,
}

/// Criterion's estimate of benchmark `parameter` (a `BenchmarkId::from_parameter`) of
/// `group`, read from `<home>/<group>/<parameter>/new/`, if this run wrote it (modified at or
/// after `since`); otherwise why not, in a few words.
pub fn estimate(
    home: &Path,
    group: &str,
    parameter: &str,
    since: SystemTime,
) -> Result<Estimate, String> {
    let dir = home
        .join(folder_safe(group))
        .join(folder_safe(parameter))
        .join("new");
    let read = |name: &str| -> Result<(serde_json::Value, SystemTime), String> {
        let path = dir.join(name);
        let text = std::fs::read_to_string(&path).map_err(|_| format!("no {name}"))?;
        let modified = std::fs::metadata(&path)
            .and_then(|m| m.modified())
            .map_err(|e| format!("{name}: {e}"))?;
        let v = serde_json::from_str(&text).map_err(|e| format!("{name}: {e}"))?;
        Ok((v, modified))
    };
    let (benchmark, _) = read("benchmark.json")?;
    let (estimates, modified) = read("estimates.json")?;
    if benchmark["full_id"].as_str() != Some(format!("{group}/{parameter}").as_str()) {
        return Err("its folder holds another benchmark".into());
    }
    if modified < since {
        return Err("not run by this process: an earlier run's estimates".into());
    }
    let (statistic, e) = match estimates.get("slope") {
        Some(s) if !s.is_null() => ("slope", s),
        _ => ("mean", &estimates["mean"]),
    };
    let ns = e["point_estimate"]
        .as_f64()
        .ok_or_else(|| format!("no {statistic} point estimate"))?;
    Ok(Estimate {
        ns,
        statistic,
        elements: benchmark["throughput"]["Elements"].as_u64(),
    })
}

/// Deterministic numbers uniform in `[-1, 1)` (a 64-bit linear congruential generator,
/// Knuth's MMIX constants, the top 53 bits): the same sequence on every machine, for the
/// benches' test matrices.
pub fn uniform() -> impl FnMut() -> f64 {
    let mut s = 0x2545_f491_4f6c_dd1d_u64;
    move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}
