//! What every part of the stability study shares (`mbdbench stability`: how far each variant
//! can be pushed before it fails, not only how accurate it is at comfortable steps): the
//! study's options, what a part contributes to `stability.json` ([`Part`], records in the
//! summary's schema, docs/schemas.md "stability.json"), the step search itself ([`steps`]:
//! ladder and bisection over step counts or tolerances), the parallel timed runner of
//! searches, and the study a family declares ([`Study`], `problem::Family::study`).
//!
//! The parts: a family with a study of its own declares it (the rigid body's step search,
//! stiffness ladder, long horizon, singularity approach and sensitivity:
//! `model/rigid_body/stability/`); every other family's scenes with a `[stability]` table get
//! the seam's step search (`study::seam_search`). The command (`study::run_study`) runs both
//! and writes `stability.json`. This module sits below the families in the crate's layers
//! (docs/architecture.md), so a family's study can use it.
//!
//! Every part is deterministic: its records (all but `wall_s`, `created_utc`, `env`) do not
//! depend on `--jobs`.
use std::path::PathBuf;

use crate::case::Case;
use crate::selection::VariantFilter;
use crate::summary::{FitRecord, Record};

pub mod steps;

/// Options of the study.
#[derive(Debug, Clone)]
pub struct StudyOptions {
    /// The quick tier (CI): fewer scenes, shorter horizons.
    pub quick: bool,
    pub jobs: usize,
    pub out: PathBuf,
    pub references: PathBuf,
    /// Progress lines on stderr.
    pub progress: bool,
}

/// What one part of the study contributes to `stability.json`: records, fits, and series
/// files (path relative to the output folder, JSON value).
#[derive(Debug, Default)]
pub struct Part {
    pub records: Vec<Record>,
    pub fits: Vec<FitRecord>,
    pub series: Vec<(String, serde_json::Value)>,
}

impl Part {
    /// Appends another part.
    pub fn extend(&mut self, other: Part) {
        self.records.extend(other.records);
        self.fits.extend(other.fits);
        self.series.extend(other.series);
    }
}

/// What a family's study is given: the selected cases of the family (never another family's),
/// the case and scene filters narrowed to them, the variant filter and the options.
#[derive(Debug, Clone, Copy)]
pub struct StudyInput<'a> {
    pub cases: &'a [Case],
    pub case_filter: &'a [String],
    pub scene_filter: &'a [String],
    pub filter: &'a VariantFilter,
    pub opts: &'a StudyOptions,
}

/// A family's own stability study (`problem::Family::study`): its part of `stability.json`.
pub type Study = fn(&StudyInput) -> Result<Part, String>;

/// Runs `search` on every job in parallel over `opts.jobs` threads, one job at a time per
/// thread; each record gets the search's wall time, and progress goes to stderr
/// (`crate::progress`: a bar on a terminal, else a line every tenth of the jobs, `label`,
/// with the elapsed time and an estimate of what remains). Records in job order.
pub(crate) fn timed_searches<J: Sync>(
    jobs: &[J],
    opts: &StudyOptions,
    label: &str,
    search: impl Fn(&J) -> Record + Sync,
) -> Result<Vec<Record>, String> {
    use rayon::prelude::*;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.jobs.max(1))
        .build()
        .map_err(|e| e.to_string())?;
    let total = jobs.len();
    let progress = crate::progress::Progress::new(total, label, "searches", 10, opts.progress);
    let records = pool.install(|| {
        jobs.par_iter()
            .with_max_len(1)
            .map(|j| {
                let t0 = std::time::Instant::now();
                let mut r = search(j);
                let w = t0.elapsed().as_secs_f64();
                r.wall_s = Some(crate::summary::Wall { min: w, median: w });
                progress.tick();
                r
            })
            .collect()
    });
    progress.finish();
    Ok(records)
}
