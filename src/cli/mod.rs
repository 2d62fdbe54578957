//! The command line (README.md, "Commands"; its names and exit codes are a contract): `list`
//! (`list.rs`), `run`, `stability`, `trajectory` (`trajectory.rs`), `gate`, `report`, `advise`,
//! `reference`; no subcommand runs the whole catalogue, its report and the recommendation (the main
//! job). Exit status: 0 success, 1 a run or check failed, 2 bad input or usage. Every command takes
//! `--cases DIR` (default: the embedded copy of the source tree's `cases/`) and `--references DIR`.
use clap::{Args, Parser, Subcommand};
use std::path::{Path, PathBuf};

mod list;
mod main_job;
pub mod names;
mod run;
mod trajectory;
use list::cmd_list;
use run::{cmd_run, cmd_run_into};
use trajectory::cmd_trajectory;

/// mbdbench: rotation parameterizations x time integrators on canonical multibody problems.
#[derive(Debug, Parser)]
#[command(
    name = "mbdbench",
    version,
    about,
    long_about = None,
    after_help = "Without a command, mbdbench runs the main job: the whole catalogue (full \
                  ladders) into reports/latest, its report, then the recommendation \
                  (`cargo run --release` does this)."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    #[command(flatten)]
    pub common: Common,
    /// The main job (no command) runs the full stability study instead of its quick tier
    /// (about 10 minutes more on 2 cores).
    #[arg(long)]
    pub full_stability: bool,
}

/// Options every command accepts.
#[derive(Debug, Args, Clone)]
pub struct Common {
    /// Folder of case TOML files (default: the embedded copy of the source tree's cases/).
    #[arg(long, global = true)]
    pub cases: Option<PathBuf>,
    /// Folder of stored references (default: references/ of the source tree).
    #[arg(long, global = true)]
    pub references: Option<PathBuf>,
    /// The catalogue the commands run with ([`execute_with`]); None: the built-in one.
    #[arg(skip)]
    pub catalogue: Option<crate::catalogue::Catalogue>,
}

impl Common {
    /// The catalogue the commands run with: the one given to [`execute_with`], else the
    /// built-in one.
    pub fn catalogue(&self) -> crate::catalogue::Catalogue {
        self.catalogue
            .clone()
            .unwrap_or_else(crate::catalogue::Catalogue::builtin)
    }

    /// The references folder: `--references`, else the catalogue's, else `references/` of
    /// the source tree.
    pub fn references(&self) -> PathBuf {
        self.references
            .clone()
            .or_else(|| {
                self.catalogue
                    .as_ref()
                    .and_then(|c| c.references().map(Path::to_path_buf))
            })
            .unwrap_or_else(default_references)
    }
}

/// Filters selecting cases, scenes and variants (repeatable; empty = all).
#[derive(Debug, Args, Clone, Default)]
pub struct Filters {
    #[arg(long = "case", help = names::case_help())]
    pub case: Vec<String>,
    #[arg(long = "scene", help = names::scene_help())]
    pub scene: Vec<String>,
    #[arg(long = "param", help = names::param_help())]
    pub param: Vec<String>,
    #[arg(long = "integrator", help = names::integrator_help())]
    pub integrator: Vec<String>,
    #[arg(long = "formulation", help = names::formulation_help())]
    pub formulation: Vec<String>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Cases, scenes, and the variant matrix with n/a reasons.
    List {
        /// Print the cases, scenes and variant matrices as JSON (schema: docs/schemas.md).
        #[arg(long)]
        json: bool,
    },
    /// Run the selected variants over their ladders; write summary.json and series.
    Run(RunArgs),
    /// The stability study: largest stable and accurate steps, stiffness ladder, long
    /// horizon; writes stability.json.
    Stability(StabilityArgs),
    /// One run, its samples written as JSON.
    Trajectory(TrajectoryArgs),
    /// Evaluate the cases' [[gates]] against a summary; table, exit 0/1 (2: bad input).
    Gate(GateArgs),
    /// HTML + SVG + markdown report from a summary.
    Report {
        /// The summary (its series files are read from `series/` beside it).
        #[arg(long, default_value = "reports/latest/summary.json")]
        summary: PathBuf,
        /// Output folder (default: the summary's folder).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Also write every plot as a file, `svg/<case>/[<scene>/]<plot>.svg` (the page
        /// inlines them all either way).
        #[arg(long)]
        svg: bool,
        /// An earlier summary the page's and summary.md's gate verdict compares with, as
        /// `gate --baseline` does (default: the committed reports/baseline/quick.json for a
        /// quick-tier summary, none for a full one)
        #[arg(long)]
        baseline: Option<PathBuf>,
    },
    /// The recommendation: per case and target error, the cheapest variant reaching it on
    /// every non-control scene, its runner-up, and what to avoid and why.
    Advise(AdviseArgs),
    /// Regenerate a stored reference, or (--check) recompute and compare.
    Reference {
        /// The case whose references to make or check.
        #[arg(long)]
        case: String,
        /// Only this scene (default: every scene of the case).
        #[arg(long)]
        scene: Option<String>,
        /// Recompute each reference and compare it with the stored one (writes nothing).
        #[arg(long)]
        check: bool,
    },
    /// Fit the cost table (a run's time in its work counters, per family and scene) to the
    /// timing pass of a full run, and write it (regenerate it with the gate's baseline, on the
    /// machine whose times it states).
    Calibrate {
        /// A full run's summary (its records' `wall_s`).
        #[arg(long, default_value = "reports/latest/summary.json")]
        summary: PathBuf,
        /// Where to write the table.
        #[arg(long, default_value = "reports/baseline/cost.json")]
        out: PathBuf,
    },
}

#[derive(Debug, Args, Clone)]
pub struct RunArgs {
    #[command(flatten)]
    pub filters: Filters,
    /// Only the quick tier of each ladder.
    #[arg(long)]
    pub quick: bool,
    /// Parallel jobs (default and 0: all available cores; more than the cores is clamped to
    /// them, with a notice).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Output folder.
    #[arg(long, default_value = "reports/latest")]
    pub out: PathBuf,
    /// Override every selected scene's horizon (errors against references are then absent).
    #[arg(long = "t-end")]
    pub t_end: Option<f64>,
    /// Time every run on one thread, one after another, after the results pass (for
    /// publication numbers); by default the timing pass runs one job per `--jobs` worker.
    #[arg(long = "serial-timing")]
    pub serial_timing: bool,
    /// The cost cap of one run, in seconds: a ladder point whose time, predicted by the
    /// committed cost table from the ladder's previous point, exceeds it is not run (an `n/a`
    /// record with the reason). `inf` for none.
    #[arg(long = "max-run-s", default_value_t = crate::suite::skip::DEFAULT_CAP_S)]
    pub max_run_s: f64,
    /// Run every point of every ladder: no ladder stops early (by the reference's floor, an
    /// established first order or the cost cap; README, "Skipping what a scene doesn't need").
    #[arg(long = "no-skip")]
    pub no_skip: bool,
    /// Print the full table (one row per scene and variant); by default one line per case
    /// (the table is also in index.html).
    #[arg(long)]
    pub verbose: bool,
}

/// The main job's run: everything, full ladders, into `reports/latest`.
impl Default for RunArgs {
    fn default() -> Self {
        RunArgs {
            filters: Filters::default(),
            quick: false,
            jobs: None,
            out: PathBuf::from("reports/latest"),
            t_end: None,
            serial_timing: false,
            max_run_s: crate::suite::skip::DEFAULT_CAP_S,
            no_skip: false,
            verbose: false,
        }
    }
}

#[derive(Debug, Args, Clone)]
pub struct StabilityArgs {
    #[command(flatten)]
    pub filters: Filters,
    /// Only the quick tier (the cases' `[stability].quick` scenes, a shorter ladder).
    #[arg(long)]
    pub quick: bool,
    /// Parallel jobs (default and 0: all available cores; more than the cores is clamped to
    /// them, with a notice).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Output folder.
    #[arg(long, default_value = "reports/latest")]
    pub out: PathBuf,
    /// Print the study's full table; by default its closing line only.
    #[arg(long)]
    pub verbose: bool,
}

#[derive(Debug, Args, Clone)]
pub struct GateArgs {
    /// The summary to gate.
    #[arg(long, default_value = "reports/latest/summary.json")]
    pub summary: PathBuf,
    /// Only the `quick = true` gates, on the quick ladders.
    #[arg(long)]
    pub quick: bool,
    /// An earlier summary to compare with (error metrics, RHS evaluations, Newton iterations).
    #[arg(long)]
    pub baseline: Option<PathBuf>,
    /// How much worse an error metric may get against the baseline.
    #[arg(long, default_value_t = crate::gate::DEFAULT_FACTOR)]
    pub factor: f64,
    /// Rewrite the baseline file (default reports/baseline/quick.json) from the summary.
    #[arg(long)]
    pub update_baseline: bool,
    /// Only the gates of these cases (repeatable; default: every case).
    #[arg(long)]
    pub case: Vec<String>,
    /// Only the gated points on these scenes (repeatable; default: every scene).
    #[arg(long)]
    pub scene: Vec<String>,
    /// Gates that need stability.json fail when it is absent beside the summary (CI);
    /// without this flag they are skipped and counted as such.
    #[arg(long)]
    pub require_stability: bool,
    /// Print only the failing rows, the skipped ones by reason and the verdict line.
    #[arg(long)]
    pub verdict_only: bool,
    /// Print the verdict as Markdown (a pull-request comment): the block summary.md opens
    /// with, rolled up by integrator, chart, case and metric, within 60 KB.
    #[arg(long, conflicts_with = "verdict_only")]
    pub markdown: bool,
}

#[derive(Debug, Args, Clone)]
pub struct AdviseArgs {
    /// The summary to advise from.
    #[arg(long, default_value = "reports/latest/summary.json")]
    pub summary: PathBuf,
    /// Only these cases (repeatable; default: every case of the summary).
    #[arg(long)]
    pub case: Vec<String>,
    /// Target errors in each case's primary metric (repeatable; default: the case's
    /// `advise_targets`, else 1e-3, 1e-6 and 1e-9).
    #[arg(long)]
    pub target: Vec<f64>,
    /// Rank by deterministic work (RHS evaluations + Newton iterations) or by median wall
    /// time.
    #[arg(long, default_value = "work", value_parser = ["work", "time"])]
    pub by: String,
    /// Print the recommendation as JSON (schema: docs/schemas.md, "advise --json").
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, Args, Clone)]
pub struct TrajectoryArgs {
    /// The case (`mbdbench list` names them).
    #[arg(long)]
    pub case: String,
    /// The scene of the case.
    #[arg(long)]
    pub scene: String,
    #[arg(long, help = format!("The parameterization (may be omitted when the case's family \
        has only `none`). Per model family: {}", names::params()))]
    pub param: Option<String>,
    #[arg(long, help = format!("The integrator. Per model family: {}", names::integrators()))]
    pub integrator: String,
    #[arg(long, help = format!("The formulation (default: the family's first, `body` for rigid \
        bodies). Per model family: {}", names::formulations()))]
    pub formulation: Option<String>,
    /// The fixed step (s) of a fixed-step integrator.
    #[arg(long, conflicts_with = "tol", required_unless_present = "tol")]
    pub dt: Option<f64>,
    /// The tolerance of an adaptive integrator.
    #[arg(long)]
    pub tol: Option<f64>,
    /// Override the scene's horizon (s); errors against the reference are then absent.
    #[arg(long = "t-end")]
    pub t_end: Option<f64>,
    /// The JSON file to write (atomically).
    #[arg(long)]
    pub out: PathBuf,
}

use std::collections::BTreeMap;

use crate::case::{self, Case};
use crate::problem::{self, Entry, Family, Stepping, Want};
use crate::reference;
use crate::selection::VariantFilter;
use crate::suite::{self, RunOptions};

/// Exit codes (docs/schemas.md, "Exit codes"): success, a run or check failed, bad input or usage.
pub const EXIT_OK: i32 = 0;
pub const EXIT_FAILED: i32 = 1;
pub const EXIT_BAD_INPUT: i32 = 2;

/// The default references folder: `references/` of the source tree.
/// The committed baseline of the quick tier, relative to the source tree.
pub const DEFAULT_BASELINE: &str = "reports/baseline/quick.json";

pub fn default_references() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("references")
}

/// The cases: `--cases`, else the catalogue's (its case folder, or the embedded cases).
fn load_cases(common: &Common) -> Result<Vec<Case>, String> {
    match &common.cases {
        Some(dir) => crate::catalogue::load_dir(dir),
        None => common.catalogue().cases(),
    }
    .map_err(|e| e.to_string())
}

/// A `--t-end` for a problem: a multiple of its score grid, within the sample budget.
fn check_t_end(t: f64, p: &dyn problem::Problem) -> Result<(), String> {
    let Some(n_score) = crate::run::divides(t, p.score_every()) else {
        return Err(format!(
            "--t-end {t}: score_every = {} of {}/{} does not divide it",
            p.score_every(),
            p.case(),
            p.scene()
        ));
    };
    let per = crate::run::divides(p.score_every(), p.sample_every()).unwrap_or(1);
    match crate::case::over_sample_budget(n_score, per) {
        Some(why) => Err(format!("--t-end {t} for {}/{}: {why}", p.case(), p.scene())),
        None => Ok(()),
    }
}

/// The worker count: all available cores by default and for `--jobs 0`; a request above the
/// core count is clamped to it with a notice on stderr (more workers than cores only add
/// contention, and a thread per job of `--jobs 100000` exhausts the machine).
fn jobs_or_default(j: Option<usize>) -> usize {
    let cores = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1);
    match j {
        None | Some(0) => cores,
        Some(n) if n > cores => {
            crate::tell!(
                "note: --jobs {n} is more than the {cores} available cores; using {cores}"
            );
            cores
        }
        Some(n) => n,
    }
}

/// Runs the parsed command line with the built-in catalogue; returns the exit code. Errors
/// are printed to stderr.
pub fn execute(cli: Cli) -> i32 {
    execute_with(crate::catalogue::Catalogue::builtin(), cli)
}

/// Runs the parsed command line with `catalogue` (a library user's, with the methods it
/// registered: `examples/byo_integrator.rs`); returns the exit code.
///
/// # Example
///
/// ```no_run
/// use clap::Parser;
/// use mbdbench::catalogue::Catalogue;
/// use mbdbench::methods::{builtin::Rk4, Fixed, Where};
///
/// let cat = Catalogue::builtin().with_method("my_rk4", Where::Everywhere, Fixed(Rk4)).unwrap();
/// let cli = mbdbench::cli::Cli::parse_from(["mbdbench", "run", "--quick", "--out", "out"]);
/// std::process::exit(mbdbench::cli::execute_with(cat, cli));
/// ```
pub fn execute_with(catalogue: crate::catalogue::Catalogue, cli: Cli) -> i32 {
    let mut common = cli.common.clone();
    common.catalogue = Some(catalogue);
    let result = match cli.command {
        None => main_job::run(&common, cli.full_stability),
        Some(Command::List { json }) => cmd_list(&common, json),
        Some(Command::Run(a)) => cmd_run(&common, &a),
        Some(Command::Stability(a)) => cmd_stability(&common, &a),
        Some(Command::Trajectory(a)) => cmd_trajectory(&common, &a),
        Some(Command::Gate(a)) => cmd_gate(&common, &a),
        Some(Command::Advise(a)) => cmd_advise(&common, &a),
        Some(Command::Report {
            summary,
            out,
            svg,
            baseline,
        }) => cmd_report(&common, &summary, out.as_deref(), svg, baseline.as_deref()),
        Some(Command::Reference { case, scene, check }) => {
            cmd_reference(&common, &case, scene.as_deref(), check)
        }
        Some(Command::Calibrate { summary, out }) => cmd_calibrate(&common, &summary, &out),
    };
    match result {
        Ok(code) => code,
        Err(msg) => {
            crate::tell!("error: {msg}");
            EXIT_BAD_INPUT
        }
    }
}

/// `calibrate`: fits the cost table (`crate::cost`) to the timed records of `summary` and
/// writes it to `out` in one step; prints each family's fit quality.
fn cmd_calibrate(common: &Common, summary: &Path, out: &Path) -> Result<i32, String> {
    let cases = load_cases(common)?;
    let s = crate::gate::load_summary(summary).map_err(|e| e.to_string())?;
    let timed = s.records.iter().filter(|r| r.wall_s.is_some()).count();
    if timed == 0 {
        return Err(format!(
            "{}: no record has a wall time (a run with its timing pass is needed)",
            summary.display()
        ));
    }
    let models: Vec<&str> = crate::catalogue::FAMILIES.iter().map(|f| f.model).collect();
    let family_of = |r: &crate::summary::Record| {
        cases
            .iter()
            .find(|c| c.name == r.key.case)
            .map(|c| crate::catalogue::family_of(c).model)
    };
    let table = crate::cost::calibrate(&s, &models, family_of);
    let text = serde_json::to_string_pretty(&table).map_err(|e| e.to_string())? + "\n";
    crate::reference::write_atomic(out, text.as_bytes())
        .map_err(|e| format!("{}: {e}", out.display()))?;
    let quality = crate::cost::quality(&table, &s, family_of);
    for f in &table.families {
        let (median, p90) = quality
            .get(f.family.as_str())
            .copied()
            .unwrap_or((0.0, 0.0));
        crate::say!(
            "{}: {} timed runs, {} scenes; |ln(predicted / measured)| median {median:.2}, p90 \
             {p90:.2} (the variants' ns per step); the counters' model alone (ns per step {:.1}, \
             rhs {:.1}, Newton {:.1}, element {:.1}): median {:.2}, p90 {:.2}",
            f.family,
            f.pooled.runs,
            f.scenes.len(),
            f.pooled.ns_per_step,
            f.pooled.ns_per_rhs,
            f.pooled.ns_per_newton,
            f.pooled.ns_per_element,
            f.pooled.log_error_median,
            f.pooled.log_error_p90,
        );
    }
    crate::say!(
        "cost table: {} ({} timed runs of {})",
        out.display(),
        timed,
        summary.display()
    );
    Ok(EXIT_OK)
}

fn cmd_stability(common: &Common, a: &StabilityArgs) -> Result<i32, String> {
    let cases = load_cases(common)?;
    let filter = VariantFilter {
        param: a.filters.param.clone(),
        integrator: a.filters.integrator.clone(),
        formulation: a.filters.formulation.clone(),
    };
    names::check_variant_names(&filter, &common.catalogue())?;
    // Validates the case and scene names (an unknown one is bad input).
    crate::case::select(&cases, &a.filters.case, &a.filters.scene)?;
    crate::reference::check_writable(&a.out)?;
    let opts = crate::stability::StudyOptions {
        quick: a.quick,
        jobs: jobs_or_default(a.jobs),
        out: a.out.clone(),
        references: common.references(),
        progress: true,
    };
    let t0 = std::time::Instant::now();
    crate::tell!(
        "mbdbench stability: {} jobs{}",
        opts.jobs,
        if a.quick { ", quick tier" } else { "" }
    );
    let summary =
        crate::study::run_study(&cases, &a.filters.case, &a.filters.scene, &filter, &opts)?;
    if a.verbose {
        let mut stdout = crate::quiet::Stdout;
        crate::study::print_table(&summary, &mut stdout).map_err(|e| e.to_string())?;
        crate::say!("");
    }
    crate::say!(
        "stability{}: {} records, {} fits; {:.1} s; {}",
        if a.quick { " (quick tier)" } else { "" },
        summary.records.len(),
        summary.fits.len(),
        t0.elapsed().as_secs_f64(),
        opts.out.join("stability.json").display()
    );
    Ok(EXIT_OK)
}

/// Writes the report of the summary at `summary_path` into `out` (default: beside it), with
/// the cells of gated runs coloured by the gates (the quick gates for a quick summary, else the
/// full ones; rows without a record are left out); with `svg`, every plot also as a file.
fn cmd_report(
    common: &Common,
    summary_path: &std::path::Path,
    out: Option<&std::path::Path>,
    svg: bool,
    baseline: Option<&std::path::Path>,
) -> Result<i32, String> {
    let cases = load_cases(common)?;
    let summary = crate::gate::load_summary(summary_path).map_err(|e| e.to_string())?;
    let dir = summary_path
        .parent()
        .map(|p| p.to_path_buf())
        .unwrap_or_else(|| PathBuf::from("."));
    let out = out.map(|p| p.to_path_buf()).unwrap_or_else(|| dir.clone());
    let mut opts = crate::gate::GateOptions::new(common.references());
    opts.catalogue = common.catalogue();
    // The gates of the summary's tier: the page's verdict is `mbdbench gate`'s (with
    // `--quick` for a quick summary) on the same files.
    opts.quick = crate::gate::summary_tier(&cases, &summary) == crate::selection::Tier::Quick;
    // The comparison `gate --baseline` makes, so the page and summary.md give its verdict:
    // the committed quick baseline by default for a quick summary.
    let committed = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(DEFAULT_BASELINE);
    opts.baseline = match baseline {
        Some(b) => Some(b.to_path_buf()),
        None => (opts.quick && committed.is_file()).then_some(committed),
    };
    // stability.json beside the summary: its part of the report; unusable = a warning.
    let (mut stability, warning) = crate::report::stability::load_beside(summary_path);
    if let Some(w) = warning {
        crate::tell!("{w}");
    }
    // A study of another build or selection is left out, never drawn beside this run.
    if let Some(Err(e)) = stability.as_ref().map(|st| summary.pairs_with(st)) {
        crate::tell!("warning: {e}; the report is written without the stability study");
        stability = None;
    }
    let mut rows = crate::gate::evaluate(&cases, &summary, stability.as_ref(), &opts);
    // The committed baseline is a default, not a request: a summary it cannot be compared
    // with (another catalogue, no run in common) gets the verdict without it, and says so.
    if let (Err(e), None, Some(_)) = (&rows, baseline, &opts.baseline) {
        crate::tell!("warning: {e}; the report's verdict is made without a baseline");
        opts.baseline = None;
        rows = crate::gate::evaluate(&cases, &summary, stability.as_ref(), &opts);
    }
    let rows = match rows {
        Ok(rows) => Some(rows),
        Err(e) => {
            crate::tell!("warning: gates not evaluated for the report: {e}");
            None
        }
    };
    let t0 = std::time::Instant::now();
    let source = stability
        .as_ref()
        .map(|s| crate::report::stability::Source {
            summary: s,
            dir: &dir,
        });
    let files = crate::report::write_report(
        &summary,
        &dir.join("series"),
        &cases,
        crate::report::Extras {
            gate_rows: rows.as_deref(),
            stability: source,
            advice: Some(advice_for(
                common,
                &cases,
                &summary,
                &crate::advise::Options {
                    stability: stability.clone(),
                    ..Default::default()
                },
            )),
            physical: Some(physical_advice_for(common, &cases, &summary)),
            svg_files: svg,
        },
        &out,
    )
    .map_err(|e| e.to_string())?;
    crate::say!(
        "report: {} ({} SVGs, {} ) in {:.1} s",
        files.index_html.display(),
        files.svgs.len(),
        files.summary_md.display(),
        t0.elapsed().as_secs_f64()
    );
    Ok(EXIT_OK)
}

fn cmd_gate(common: &Common, a: &GateArgs) -> Result<i32, String> {
    if a.update_baseline {
        let target = a
            .baseline
            .clone()
            .unwrap_or_else(|| PathBuf::from(DEFAULT_BASELINE));
        crate::gate::update_baseline(&a.summary, &target).map_err(|e| e.to_string())?;
        crate::say!(
            "baseline {} rewritten from {}",
            target.display(),
            a.summary.display()
        );
        return Ok(EXIT_OK);
    }
    if !(a.factor.is_finite() && a.factor >= 1.0) {
        return Err(format!("--factor {}: must be a number >= 1", a.factor));
    }
    let cases = load_cases(common)?;
    // Unknown case or scene names are bad input, with the known ones listed.
    crate::case::select(&cases, &a.case, &a.scene)?;
    for s in &a.scene {
        if !cases
            .iter()
            .filter(|c| a.case.is_empty() || a.case.contains(&c.name))
            .any(|c| c.scene(s).is_some())
        {
            return Err(format!("--scene {s}: no such scene in the selected cases"));
        }
    }
    let summary = crate::gate::load_summary(&a.summary).map_err(|e| e.to_string())?;
    crate::gate::check_tier(&summary, &a.summary, a.quick).map_err(|e| e.to_string())?;
    let stability =
        crate::gate::stability_paired(&a.summary, &summary).map_err(|e| e.to_string())?;
    let opts = crate::gate::GateOptions {
        quick: a.quick,
        baseline: a.baseline.clone(),
        factor: a.factor,
        references: common.references(),
        cases: a.case.clone(),
        scenes: a.scene.clone(),
        require_stability: a.require_stability,
        catalogue: common.catalogue(),
    };
    let rows = crate::gate::evaluate(&cases, &summary, stability.as_ref(), &opts)
        .map_err(|e| e.to_string())?;
    let mut out = crate::quiet::Stdout;
    if a.markdown {
        use std::io::Write;
        write!(out, "{}", crate::gate::markdown::verdict(&rows)).map_err(|e| e.to_string())?;
    } else if a.verdict_only {
        crate::gate::print_verdict(&rows, &mut out).map_err(|e| e.to_string())?;
    } else {
        crate::gate::print_table(&rows, &mut out).map_err(|e| e.to_string())?;
    }
    Ok(crate::gate::exit_code(&rows))
}

/// The recommendation of `summary`, the references' accuracy claims deciding which targets
/// are offered (a scene whose reference cannot be loaded offers every target), and the
/// references that are themselves variants named.
fn advice_for(
    common: &Common,
    cases: &[Case],
    summary: &crate::summary::Summary,
    opts: &crate::advise::Options,
) -> crate::advise::Advice {
    let root = common.references();
    let reference = |c: &Case, scene: &str| {
        crate::advise::stored_reference(
            &root,
            c,
            scene,
            &c.primary_metric,
            crate::advise::Claim::Accuracy,
        )
    };
    crate::advise::advise(summary, &crate::advise::specs(cases, &reference), opts)
}

/// The recommendation on the physical metric of the cases whose family declares one
/// (`problem::figures::PhysicalView`): the same `advise` ranking, at the family's targets, the
/// references' claims for that metric deciding which targets are offered.
fn physical_advice_for(
    common: &Common,
    cases: &[Case],
    summary: &crate::summary::Summary,
) -> crate::advise::Advice {
    let root = common.references();
    let reference = |c: &Case, scene: &str| match crate::catalogue::family_of(c).figures.physical {
        Some(view) => crate::advise::stored_reference(
            &root,
            c,
            scene,
            view.metric,
            crate::advise::Claim::Physical,
        ),
        None => crate::advise::SceneReference::default(),
    };
    let specs = crate::report::advice::physical_specs(cases, &reference);
    crate::advise::advise(summary, &specs, &crate::advise::Options::default())
}

fn cmd_advise(common: &Common, a: &AdviseArgs) -> Result<i32, String> {
    let cases = load_cases(common)?;
    for c in &a.case {
        if !cases.iter().any(|k| &k.name == c) {
            let known: Vec<&str> = cases.iter().map(|k| k.name.as_str()).collect();
            return Err(format!(
                "--case {c}: no such case; known: {}",
                known.join(", ")
            ));
        }
    }
    for &t in &a.target {
        if !(t.is_finite() && t > 0.0) {
            return Err(format!("--target {t}: must be a positive number"));
        }
    }
    let summary = crate::gate::load_summary(&a.summary).map_err(|e| e.to_string())?;
    let stability =
        crate::gate::stability_paired(&a.summary, &summary).map_err(|e| e.to_string())?;
    let opts = crate::advise::Options {
        stability,
        cases: a.case.clone(),
        targets: a.target.clone(),
        by: if a.by == "time" {
            crate::advise::By::Time
        } else {
            crate::advise::By::Work
        },
    };
    let advice = advice_for(common, &cases, &summary, &opts);
    if a.json {
        crate::say!(
            "{}",
            serde_json::to_string_pretty(&advice).map_err(|e| e.to_string())?
        );
    } else {
        crate::say!("{}", crate::advise::render(&advice).trim_end());
    }
    Ok(EXIT_OK)
}

fn cmd_reference(
    common: &Common,
    case_name: &str,
    scene: Option<&str>,
    check: bool,
) -> Result<i32, String> {
    let cases = load_cases(common)?;
    if !cases.iter().any(|c| c.name == case_name) {
        return Err(format!("--case {case_name}: no such case"));
    }
    let scene_filter: Vec<String> = scene.map(|s| vec![s.to_string()]).unwrap_or_default();
    let problems = common
        .catalogue()
        .problems(&cases, &[case_name.to_string()], &scene_filter)?;
    let root = common.references();
    let mut all_ok = true;
    for p in &problems {
        if check {
            let (ok, msg) = p.check_reference(&root)?;
            crate::say!("{} {msg}", if ok { "pass" } else { "FAIL" });
            all_ok &= ok;
        } else {
            crate::say!("{}", p.make_reference(&root)?);
        }
    }
    Ok(if all_ok { EXIT_OK } else { EXIT_FAILED })
}
