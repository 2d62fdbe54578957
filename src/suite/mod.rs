//! The catalogue run behind `mbdbench run` and the main job: expand cases x scenes x
//! registered variants x ladder points into jobs, run them in parallel, score them against the
//! stored references, fit observed orders, and write `summary.json` with the series files.
//!
//! Timing (wall time is reported, never gated: it is not deterministic): results come from a
//! parallel pass (`--jobs`) that observes and scores; wall times from a second, single-threaded
//! pass that re-runs each variant without observation: the min and median of 3 repeats when one run
//! takes under 1 s, else the single run. The computation is deterministic, so the repeats re-run
//! the identical work. Records are sorted in a fixed order so that the summary does not depend on
//! `--jobs`.
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Instant;

use crate::catalogue::Ordered;
use crate::metrics::order;
use crate::output;
use crate::problem::{self, Entry, Problem, Variant, Want};
use crate::selection::VariantFilter;
use crate::summary::{self, Env, FitRecord, Record, RunKey, Status, Summary, Wall};

pub mod account;
pub mod skip;
mod terminal;

pub use terminal::{print_brief, print_table};

/// Options of a catalogue run.
#[derive(Debug, Clone)]
pub struct RunOptions {
    pub quick: bool,
    pub jobs: usize,
    pub out: PathBuf,
    pub t_end: Option<f64>,
    pub references: PathBuf,
    /// Print progress lines to stderr.
    pub progress: bool,
    /// Timing repeats for runs under 1 s in the timing pass (3 in the suite; 0 skips the
    /// timing pass, where only results matter: `wall_s` is then null).
    pub repeats: usize,
    /// Time on one thread, one run after another (`--serial-timing`); otherwise the timing
    /// pass runs one job per worker at a time, longest first.
    pub serial_timing: bool,
    /// The `--case` and `--scene` filters that chose the problems (empty: all), recorded in
    /// the summary's `selection`.
    pub cases: Vec<String>,
    pub scenes: Vec<String>,
    /// A broader summary already in `out` (same commit and tier, its selection covering this
    /// run's) that this run merges into: its records outside this run's selection, their
    /// fits and series files are kept, the rest replaced (`mbdbench run` decides, `cli`).
    pub base: Option<Summary>,
    /// Whether ladders stop early (`skip`; `--no-skip` runs every point).
    pub skip: bool,
    /// The cost cap of one run, s (`skip`, rule 3; `--max-run-s`; `f64::INFINITY`: none).
    pub cap_s: f64,
    /// The cost table that predicts a run's time (`crate::cost`; the committed one by
    /// default, `CostTable::empty()` to predict nothing).
    pub cost: crate::cost::CostTable,
    /// The catalogue the problems were compiled with: the summary's `methods` table lists
    /// every method it registers.
    pub catalogue: crate::catalogue::Catalogue,
}

impl RunOptions {
    /// The summary's `selection` of a run with these options and variant filter.
    pub fn selection(&self, filter: &VariantFilter) -> crate::selection::Selection {
        crate::selection::Selection {
            tier: crate::selection::Tier::of(self.quick),
            cases: self.cases.clone(),
            scenes: self.scenes.clone(),
            params: filter.param.clone(),
            integrators: filter.integrator.clone(),
            formulations: filter.formulation.clone(),
            t_end: self.t_end,
        }
        .deduped()
    }

    /// How the timing pass runs, as recorded in the summary's `env.timing`.
    pub fn timing_mode(&self) -> String {
        if self.repeats == 0 {
            "none".into()
        } else if self.serial_timing || self.jobs <= 1 {
            "serial".into()
        } else {
            format!("parallel ({} workers)", self.jobs)
        }
    }
}

struct Job {
    problem: usize,
    variant: &'static Variant,
    value: f64,
}

/// One variant's ladder on one problem: its jobs, `jobs[range]`, coarse to fine.
struct LadderJobs {
    problem: usize,
    variant: &'static Variant,
    range: std::ops::Range<usize>,
}

struct Done {
    record: Record,
    series: Option<(String, summary::Series)>,
    /// CPU seconds of the run in the results pass and in the timing pass (`cpu_clock`).
    results_cpu_s: f64,
    timing_cpu_s: f64,
}

impl Done {
    fn of(record: Record) -> Done {
        Done {
            record,
            series: None,
            results_cpu_s: 0.0,
            timing_cpu_s: 0.0,
        }
    }
}

/// Times one variant at one ladder value without observation (`Want::Timing`): `repeats`
/// runs when one takes under 1 s, else one; min and median. None if it cannot run.
pub fn time_run(p: &dyn Problem, v: &Variant, value: f64, repeats: usize) -> Option<Wall> {
    let mut times = Vec::with_capacity(repeats.max(1));
    for k in 0..repeats.max(1) {
        let t = Instant::now();
        let r = std::hint::black_box(p.run(v, v.stepping(value), Want::Timing));
        times.push(t.elapsed().as_secs_f64());
        if r.is_err() {
            return None;
        }
        if k == 0 && times[0] >= 1.0 {
            break;
        }
    }
    times.sort_by(f64::total_cmp);
    Some(Wall {
        min: times[0],
        median: times[times.len() / 2],
    })
}

fn base_record(p: &dyn Problem, param: &str, integrator: &str, formulation: &str) -> Record {
    let mut r = Record::new(
        RunKey::new(p.case(), p.scene(), param, integrator, formulation),
        p.inputs_sha256(),
    );
    r.settings_sha256 = Some(p.settings_sha256().to_string());
    r
}

/// Attaches the stored references of the problems (none with a `--t-end` override, which
/// replaces every horizon instead). A missing or stale reference is bad input.
pub fn prepare(problems: &mut [Box<dyn Problem>], opts: &RunOptions) -> Result<(), String> {
    for p in problems.iter_mut() {
        match opts.t_end {
            Some(t) => p.set_t_end(t),
            None => p.attach_reference(&opts.references)?,
        }
    }
    Ok(())
}

/// Runs the catalogue over `problems` and writes the summary; returns it.
pub fn run_catalogue(
    mut problems: Vec<Box<dyn Problem>>,
    filter: &VariantFilter,
    opts: &RunOptions,
) -> Result<Summary, String> {
    let started = std::time::Instant::now();
    prepare(&mut problems, opts)?;
    let (jobs, ladders, mut records) = plan_jobs(&problems, filter, opts.quick);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.jobs.max(1))
        .build()
        .map_err(|e| e.to_string())?;
    let done = results_pass(&pool, &problems, &jobs, &ladders, opts);
    // Longest first for the timing pass (the results pass orders whole ladders).
    let (jobs, mut done) = longest_first(&problems, jobs, done);
    if opts.repeats > 0 {
        timing_pass(&pool, &problems, &jobs, &mut done, opts);
    }
    keep_drawn_series(&problems, &jobs, &mut done);
    let families = account::by_family(&problems, &jobs, &done);
    // The new output is built beside the folder and swapped in whole (`output`): a reader
    // never sees this run's series beside another run's summary.
    let mut staging = output::Staging::begin(&opts.out, output::Writer::Run)?;
    for d in done {
        if let Some((rel, series)) = &d.series {
            let text =
                serde_json::to_string(&series.rounded(SERIES_DIGITS)).map_err(|e| e.to_string())?;
            staging.write(rel, text.as_bytes())?;
        }
        records.push(d.record);
    }
    let mut fits = fit_orders(&problems, &records);
    let mut selection = opts.selection(filter);
    if let Some(base) = &opts.base {
        selection = keep_base_runs(base, &mut staging, &mut records, &mut fits, selection, opts)?;
    }
    records.sort_by_key(crate::catalogue::report_order);
    // The facts of the methods this build registers, and those of a merged run's kept records.
    let mut methods = crate::catalogue::methods_in(opts.catalogue.families());
    if let Some(kept) = opts.base.as_ref().and_then(|b| b.methods.as_ref()) {
        methods.extend_missing(kept);
    }
    let mut env = Env::current(opts.jobs, Some(opts.timing_mode()));
    env.elapsed_s = Some(started.elapsed().as_secs_f64());
    env.families = (!families.is_empty()).then_some(families);
    let summary = Summary {
        schema: 1,
        git_commit: summary::git_commit().into(),
        created_utc: summary::now_utc(),
        env,
        records,
        fits,
        selection: Some(selection),
        methods: Some(methods),
        families: Some(crate::catalogue::family_models()),
    };
    commit_summary(&summary, staging, opts)?;
    Ok(summary)
}

/// What the cost table predicts for a run before it starts (`predict`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prediction {
    /// CPU seconds of the results and timing passes over every ladder point, none skipped
    /// (an upper bound: the early stops are known only as the ladders run).
    pub cpu_s: f64,
    /// Ladder points the table cannot predict (adaptive methods' step counts are known only
    /// once they ran, and a scene or family the table has no row for).
    pub unpredicted: usize,
    /// Ladder points in all.
    pub points: usize,
}

/// The cost table's prediction of a run over `problems` with `filter` and `opts` (each
/// fixed-step point's `T / dt` steps at its variant's cost per step, or the scene's model of
/// its work, `skip::first_point_work`; the timing pass's repeats counted as `time_run` makes
/// them).
pub fn predict(
    problems: &[Box<dyn Problem>],
    filter: &VariantFilter,
    opts: &RunOptions,
) -> Prediction {
    let (jobs, _, _) = plan_jobs(problems, filter, opts.quick);
    let mut out = Prediction {
        cpu_s: 0.0,
        unpredicted: 0,
        points: jobs.len(),
    };
    for j in &jobs {
        let p = &*problems[j.problem];
        let v = j.variant;
        let seconds = opts
            .cost
            .for_scene(p.family().model, p.case(), p.scene())
            .zip(skip::first_point_work(p, v, j.value))
            .map(|(m, w)| {
                m.seconds(
                    &crate::cost::variant_key(v.param, v.integrator, v.formulation),
                    &w,
                )
            });
        match seconds {
            Some(t) => {
                let repeats = if t < 1.0 { opts.repeats.max(1) } else { 1 };
                let timed = if opts.repeats == 0 { 0 } else { repeats };
                out.cpu_s += t * (1 + timed) as f64;
            }
            None => out.unpredicted += 1,
        }
    }
    out
}

/// The runs of the selected variants over every problem's ladder (one job per ladder point,
/// each ladder's jobs together, coarse to fine: largest step or loosest tolerance first),
/// the ladders, and the records of the combinations that do not apply (`n/a`, with the
/// reason).
fn plan_jobs(
    problems: &[Box<dyn Problem>],
    filter: &VariantFilter,
    quick: bool,
) -> (Vec<Job>, Vec<LadderJobs>, Vec<Record>) {
    let mut jobs: Vec<Job> = vec![];
    let mut ladders: Vec<LadderJobs> = vec![];
    let mut records: Vec<Record> = vec![];
    for (pi, p) in problems.iter().enumerate() {
        for cell in problem::matrix(p.family()) {
            if !filter.admits(cell.param, cell.integrator, cell.formulation) {
                continue;
            }
            let applies = match cell.entry {
                Entry::NotApplicable(why) => Err(why),
                Entry::Registered(v) => p.na_reason(v).map_or(Ok(v), Err),
            };
            let v = match applies {
                Ok(v) => v,
                Err(why) => {
                    let mut r = base_record(&**p, cell.param, cell.integrator, cell.formulation);
                    r.reason = Some(why);
                    records.push(r);
                    continue;
                }
            };
            let mut values = p.ladder(quick, &v.info).to_vec();
            values.sort_by(|a, b| b.total_cmp(a));
            let first = jobs.len();
            jobs.extend(values.into_iter().map(|value| Job {
                problem: pi,
                variant: v,
                value,
            }));
            ladders.push(LadderJobs {
                problem: pi,
                variant: v,
                range: first..jobs.len(),
            });
        }
    }
    (jobs, ladders, records)
}

/// A job's length for ordering: its step count, `t_end / dt` (adaptive runs 0, last).
fn steps(problems: &[Box<dyn Problem>], j: &Job) -> f64 {
    if j.variant.info.adaptive {
        0.0
    } else {
        problems[j.problem].t_end() / j.value
    }
}

/// The jobs and their results reordered longest first (by step count; adaptive runs last),
/// so that the timing pass, one job per rayon task (`with_max_len(1)`), ends on short runs.
/// Without it rayon hands each thread a contiguous block it cannot split once started, and
/// one core ground through the long Euler runs alone (full ladder: 60.6 s wall on 2 cores for
/// 70.7 s of work). Records are sorted before they are written, so the order does not show
/// in the summary.
fn longest_first(
    problems: &[Box<dyn Problem>],
    jobs: Vec<Job>,
    done: Vec<Done>,
) -> (Vec<Job>, Vec<Done>) {
    let mut pairs: Vec<(Job, Done)> = jobs.into_iter().zip(done).collect();
    pairs.sort_by(|a, b| steps(problems, &b.0).total_cmp(&steps(problems, &a.0)));
    pairs.into_iter().unzip()
}

/// The results pass: every ladder run in sequence (`skip` decides, before each point, from
/// the ladder's earlier points), the ladders in parallel on the pool, one ladder per task,
/// longest first (by their total step count). Returns one result per job, in `jobs`' order.
fn results_pass(
    pool: &rayon::ThreadPool,
    problems: &[Box<dyn Problem>],
    jobs: &[Job],
    ladders: &[LadderJobs],
    opts: &RunOptions,
) -> Vec<Done> {
    let progress = crate::progress::Progress::new(jobs.len(), "results", "runs", 20, opts.progress);
    let mut order: Vec<&LadderJobs> = ladders.iter().collect();
    let total = |l: &LadderJobs| -> f64 {
        jobs[l.range.clone()]
            .iter()
            .map(|j| steps(problems, j))
            .sum()
    };
    order.sort_by(|a, b| total(b).total_cmp(&total(a)));
    let mut out: Vec<(usize, Done)> = pool.install(|| {
        order
            .par_iter()
            .with_max_len(1)
            .flat_map_iter(|l| {
                let d = run_ladder(&*problems[l.problem], l, jobs, opts, &progress);
                l.range.clone().zip(d)
            })
            .collect()
    });
    progress.finish();
    out.sort_by_key(|(i, _)| *i);
    out.into_iter().map(|(_, d)| d).collect()
}

/// One ladder, coarse to fine, each point run unless `skip` stops it (then it and every finer
/// point are `n/a` records with the reason).
fn run_ladder(
    p: &dyn Problem,
    l: &LadderJobs,
    jobs: &[Job],
    opts: &RunOptions,
    progress: &crate::progress::Progress,
) -> Vec<Done> {
    let v = l.variant;
    let rules = skip::Rules {
        cap_s: opts.cap_s,
        cost: opts.cost.for_scene(p.family().model, p.case(), p.scene()),
    };
    let mut done: Vec<Done> = Vec::with_capacity(l.range.len());
    let mut stopped: Option<String> = None;
    for job in &jobs[l.range.clone()] {
        // A point a gate names always runs (the verdict must not depend on the stop).
        let gated = p.gated(v, job.value);
        if opts.skip && stopped.is_none() && !gated {
            let earlier: Vec<&Record> = done.iter().map(|d| &d.record).collect();
            stopped = skip::reason(p, v, job.value, &earlier, &rules);
        }
        let d = match &stopped {
            Some(why) if !gated => {
                let mut r = base_record(p, v.param, v.integrator, v.formulation);
                r.set_stepping(v.stepping(job.value));
                r.reference_sha256 = p.reference_sha256().map(str::to_string);
                r.reason = Some(why.clone());
                Done::of(r)
            }
            _ => {
                let (mut d, cpu) = crate::cpu_clock::measure(|| run_job(p, job));
                d.results_cpu_s = cpu;
                d
            }
        };
        progress.tick();
        done.push(d);
    }
    done
}

/// The timing pass, after the results pass: runs without observation, one job per worker at
/// a time (one rayon task per job, longest first: `jobs` is sorted), or on this thread alone
/// with `--serial-timing`. Two runs on two cores slow each other by about 1 % (measured,
/// README "Benchmarks"). A failed run is not timed: its wall time says nothing about the
/// method, and a run that ends at its work budget would cost that budget again per repeat.
fn timing_pass(
    pool: &rayon::ThreadPool,
    problems: &[Box<dyn Problem>],
    jobs: &[Job],
    done: &mut [Done],
    opts: &RunOptions,
) {
    let timing = crate::progress::Progress::new(jobs.len(), "timing", "runs", 20, opts.progress);
    let time_one = |job: &Job, d: &mut Done| {
        if d.record.status == Status::Ok {
            let p = &*problems[job.problem];
            let (wall, cpu) =
                crate::cpu_clock::measure(|| time_run(p, job.variant, job.value, opts.repeats));
            d.record.wall_s = wall;
            d.timing_cpu_s = cpu;
        }
        timing.tick();
    };
    if opts.serial_timing {
        for (job, d) in jobs.iter().zip(done.iter_mut()) {
            time_one(job, d);
        }
    } else {
        pool.install(|| {
            jobs.par_iter()
                .zip(done.par_iter_mut())
                .with_max_len(1)
                .for_each(|(job, d)| time_one(job, d));
        });
    }
    timing.finish();
}

/// A run over part of an earlier summary (`--base`): keeps the earlier records, fits and
/// series this run's selection does not cover, and returns the earlier selection (the whole
/// summary's).
fn keep_base_runs(
    base: &Summary,
    staging: &mut output::Staging,
    records: &mut Vec<Record>,
    fits: &mut Vec<FitRecord>,
    selection: crate::selection::Selection,
    opts: &RunOptions,
) -> Result<crate::selection::Selection, String> {
    let kept = |k: &RunKey| !selection.admits(k);
    for r in base.records.iter().filter(|r| kept(&r.key)) {
        if let Some(rel) = &r.series {
            let bytes = crate::read_limited::read(&opts.out.join(rel), crate::read_limited::SERIES)
                .map_err(|e| format!("{e}; cannot keep it"))?;
            staging.write(rel, &bytes)?;
        }
        records.push(r.clone());
    }
    fits.extend(base.fits.iter().filter(|f| kept(&f.key)).cloned());
    fits.sort_by_key(|f| {
        let k = &f.key;
        (
            k.case.clone(),
            k.scene.clone(),
            k.variant_order(),
            f.metric.clone(),
        )
    });
    Ok(base
        .selection
        .clone()
        .unwrap_or_else(|| crate::selection::Selection::everything(selection.tier)))
}

/// Writes `summary.json` into the staged folder and swaps the folder in. A stability study
/// beside the old summary that is not of this build and selection would be judged beside
/// this run: it goes with the old output (unusable, too).
fn commit_summary(
    summary: &Summary,
    mut staging: output::Staging,
    opts: &RunOptions,
) -> Result<(), String> {
    let text = summary.to_json_lines().map_err(|e| e.to_string())?;
    staging.write("summary.json", text.as_bytes())?;
    let beside = crate::gate::stability_beside(&opts.out.join("summary.json"));
    if !matches!(&beside, Ok(None))
        && !matches!(&beside, Ok(Some(st)) if summary.pairs_with(st).is_ok())
    {
        staging.replace(output::Writer::Stability);
    }
    staging.commit().map(|_| ())
}

/// Significant digits of the numbers in a series file: plot data (a figure resolves a few
/// parts in 1e3), and 6 digits keep a full run's output within its 30 MB budget.
pub const SERIES_DIGITS: usize = 6;

/// Keeps the series only of the runs a figure draws: per scene and variant that one of the
/// family's time-series selections admits, its coarsest completed ladder point (largest
/// `dt`, loosest `tol`: `report::timeseries`), or, for a family whose figures draw failed
/// runs (`Figures::draw_failed`) and a variant with no completed run, its finest failed run
/// (up to the failure); every other record gets `series: null` and the reason. A full run
/// wrote 6,895 series files (129 MB) before; 474 (5.3 MB) remain.
fn keep_drawn_series(problems: &[Box<dyn Problem>], jobs: &[Job], done: &mut [Done]) {
    let mut coarsest: BTreeMap<(usize, [usize; 3]), (usize, f64)> = BTreeMap::new();
    let mut finest_failed: BTreeMap<(usize, [usize; 3]), (usize, f64)> = BTreeMap::new();
    for (k, (job, d)) in jobs.iter().zip(done.iter()).enumerate() {
        if d.series.is_none() {
            continue;
        }
        let key = (job.problem, d.record.variant_order());
        if d.record.status == Status::Ok {
            let e = coarsest.entry(key).or_insert((k, job.value));
            if job.value > e.1 {
                *e = (k, job.value);
            }
        } else if problems[job.problem].family().figures.draw_failed
            && d.record.status == Status::Failed
        {
            let e = finest_failed.entry(key).or_insert((k, job.value));
            if job.value < e.1 {
                *e = (k, job.value);
            }
        }
    }
    for (key, failed) in finest_failed {
        coarsest.entry(key).or_insert(failed);
    }
    for (k, (job, d)) in jobs.iter().zip(done.iter_mut()).enumerate() {
        if d.record.status == Status::NotApplicable {
            // A skipped ladder point (`skip`): its reason says it was not run.
            continue;
        }
        let v = job.variant;
        let p = &*problems[job.problem];
        let drawn = p
            .family()
            .figures
            .timeseries
            .iter()
            .any(|(_, sel)| sel.admit.admits(v.param, v.integrator, v.info.adaptive));
        let chosen = coarsest.get(&(job.problem, d.record.variant_order()));
        let why = match chosen {
            Some(&(best, _)) if best == k && d.record.status == Status::Failed => None,
            _ if d.record.status != Status::Ok => {
                Some("not written: a failed run (no figure draws it)".to_string())
            }
            _ if !drawn => Some(
                "not written: no time-series figure draws this variant (`mbdbench trajectory` \
                 gives its samples)"
                    .to_string(),
            ),
            Some(&(best, value)) if best != k => Some(format!(
                "not written: the time-series figures draw this variant's coarsest completed \
                 ladder point ({} = {value:e})",
                if v.info.adaptive { "tol" } else { "dt" }
            )),
            None if d.series.is_none() => Some("not written: the run made none".to_string()),
            _ => None,
        };
        if let Some(why) = why {
            d.series = None;
            d.record.series = None;
            d.record.series_reason = Some(why);
        }
    }
}

fn run_job(p: &dyn Problem, job: &Job) -> Done {
    let v = job.variant;
    let mut rec = base_record(p, v.param, v.integrator, v.formulation);
    let stepping = v.stepping(job.value);
    rec.set_stepping(stepping);
    rec.reference_sha256 = p.reference_sha256().map(str::to_string);
    let out = match p.run(v, stepping, Want::Scored) {
        Ok(o) => o,
        Err(msg) => {
            rec.refuse(msg);
            return Done::of(rec);
        }
    };
    rec.take_run(out.stats, out.failure);
    rec.metrics = out.scores.values;
    rec.metric_reasons = out.scores.reasons;
    let id = summary::run_id(v.param, v.integrator, v.formulation, rec.dt, rec.tol);
    let rel = format!("series/{}/{}/{id}.json", p.case(), p.scene());
    rec.series = Some(rel.clone());
    Done {
        record: rec,
        series: out.series.map(|s| (rel, s)),
        results_cpu_s: 0.0,
        timing_cpu_s: 0.0,
    }
}

/// Observed orders of the fixed-step variants over their ladders, on the primary metric.
fn fit_orders(problems: &[Box<dyn Problem>], records: &[Record]) -> Vec<FitRecord> {
    let mut fits = vec![];
    for p in problems {
        if p.accuracy_claim(p.primary_metric()).is_none() {
            continue;
        }
        let mut groups: BTreeMap<[usize; 3], Vec<&Record>> = BTreeMap::new();
        for r in records
            .iter()
            .filter(|r| r.key.case == p.case() && r.key.scene == p.scene() && r.dt.is_some())
        {
            groups.entry(r.variant_order()).or_default().push(r);
        }
        for rs in groups.values() {
            let pts: Vec<(f64, Option<f64>)> = rs
                .iter()
                .map(|r| {
                    (
                        r.dt.unwrap_or(0.0),
                        r.metrics.get(p.primary_metric()).copied().flatten(),
                    )
                })
                .collect();
            let Some(claim) = p.accuracy_claim_for(p.primary_metric(), &rs[0].key.formulation)
            else {
                continue;
            };
            let f = order::fit(&pts, claim);
            fits.push(FitRecord {
                key: crate::summary::RunKey::new(
                    p.case(),
                    p.scene(),
                    &rs[0].key.param,
                    &rs[0].key.integrator,
                    &rs[0].key.formulation,
                ),
                metric: p.primary_metric().to_string(),
                order: f.order,
                reason: f.reason,
                points: f.points,
            });
        }
    }
    fits
}
