//! Hostile input: property-based fuzzing of the case parser, of the run loop and of
//! the command line. Every input either runs or gives a typed error within its work limit;
//! nothing panics, hangs, or leaves a half-written file that looks complete.
//!
//! Four layers, a file each:
//! - `parser.rs`: the real case files, mutated (lines deleted, duplicated, swapped; keys
//!   renamed; values retyped; numbers replaced by extremes; huge and deeply nested arrays;
//!   junk; truncation; the mutations themselves are `mutate.rs`), fed to `catalogue::load_str`;
//! - `run_loop.rs`: generated, valid-looking cases with random physics (tiny and huge masses,
//!   near-singular inertias, random springs and initial states, tiny and huge horizons, fine
//!   sample grids) and small work limits, planned and run with random registered variants at
//!   their ladder steps, at steps longer than the horizon, and with horizon overrides;
//! - `binary.rs`: bad case files and hostile arguments exit 2 naming the file and the key and
//!   write nothing; output files are written whole or not at all;
//! - `corpus.rs`: a fixed, seeded corpus of about 2,000 mutated case files, summaries and
//!   references (its seeded mutations are `corpus_mutate.rs`) through the binary under an
//!   address-space cap of 1.5 GiB: no panic, no signal, exit 0, 1 or 2 only, nothing written on
//!   exit 2.
//!
//! The number of cases per property is `MBDBENCH_FUZZ_CASES` (default 256 for the in-process
//! parser property, a fraction of it for the slower ones; see `cases`); the corpus size is
//! `MBDBENCH_FUZZ_CORPUS` (default 2000). CI runs the defaults; a long run is
//! `MBDBENCH_FUZZ_CASES=20000 MBDBENCH_FUZZ_CORPUS=20000 cargo test --release --test fuzz`.
#[path = "../common/mod.rs"]
mod common;

mod binary;
#[cfg(unix)]
mod corpus;
#[cfg(unix)]
mod corpus_mutate;
mod mutate;
mod parser;
mod run_loop;

use std::path::{Path, PathBuf};
use std::time::Duration;

use proptest::test_runner::Config;

// ---------------------------------------------------------------------------------------
// Configuration

/// Cases for a property: `MBDBENCH_FUZZ_CASES` (or `base`) divided by `divisor` (the cost of
/// one case relative to the parser property's), at least 4.
fn cases(divisor: u32) -> u32 {
    let base = std::env::var("MBDBENCH_FUZZ_CASES")
        .ok()
        .and_then(|s| s.trim().parse::<u32>().ok())
        .unwrap_or(256);
    (base / divisor).max(4)
}

fn config(divisor: u32) -> Config {
    Config {
        cases: cases(divisor),
        // Shrinking a slow failing case can take long; the failing input is printed anyway.
        max_shrink_iters: 256,
        failure_persistence: None,
        ..Config::default()
    }
}

/// The slowest one run may take before it counts as a hang (its work limit is small).
const RUN_DEADLINE: Duration = Duration::from_secs(20);
/// The slowest one binary invocation may take before it counts as a hang.
const PROCESS_DEADLINE: Duration = Duration::from_secs(60);

// ---------------------------------------------------------------------------------------
// Files

/// Files under `dir` that look like leftovers of an interrupted atomic write.
fn temp_files(dir: &Path) -> Vec<PathBuf> {
    all_files(dir)
        .into_iter()
        .filter(|p| {
            p.extension()
                .and_then(|x| x.to_str())
                .is_some_and(|x| x.starts_with("tmp"))
        })
        .collect()
}

/// Every file under `dir`.
fn all_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = vec![];
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(rd) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in rd.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else {
                out.push(p);
            }
        }
    }
    out
}

/// A fresh, unique temporary folder (proptest runs many cases per test process).
fn fresh_dir(tag: &str) -> PathBuf {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static N: AtomicUsize = AtomicUsize::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    common::temp_dir(&format!("{tag}-{n}"))
}
