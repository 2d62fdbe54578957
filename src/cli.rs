//! The command line (design.md, "Command line", contract): `list`, `run`, `trajectory`,
//! `reference`; no subcommand runs the whole catalogue (the main job). Exit status: 0
//! success, 1 a run or check failed, 2 bad input or usage. Every command takes `--cases DIR`
//! (default: the embedded copy of the source tree's `cases/`) and `--references DIR`.
use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;

/// mbdbench: rotation parameterizations x time integrators on canonical multibody problems.
#[derive(Debug, Parser)]
#[command(name = "mbdbench", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    #[command(flatten)]
    pub common: Common,
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
}

/// Filters selecting cases, scenes and variants (repeatable; empty = all).
#[derive(Debug, Args, Clone, Default)]
pub struct Filters {
    #[arg(long = "case")]
    pub case: Vec<String>,
    #[arg(long = "scene")]
    pub scene: Vec<String>,
    #[arg(long = "param")]
    pub param: Vec<String>,
    #[arg(long = "integrator")]
    pub integrator: Vec<String>,
    #[arg(long = "formulation")]
    pub formulation: Vec<String>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Cases, scenes, and the variant matrix with n/a reasons.
    List {
        #[arg(long)]
        json: bool,
    },
    /// Run the selected variants over their ladders; write summary.json and series.
    Run(RunArgs),
    /// One run, its samples written as JSON.
    Trajectory(TrajectoryArgs),
    /// Regenerate a stored reference, or (--check) recompute and compare.
    Reference {
        #[arg(long)]
        case: String,
        #[arg(long)]
        scene: Option<String>,
        #[arg(long)]
        check: bool,
    },
}

#[derive(Debug, Args, Clone, Default)]
pub struct RunArgs {
    #[command(flatten)]
    pub filters: Filters,
    /// Only the quick tier of each ladder.
    #[arg(long)]
    pub quick: bool,
    /// Parallel jobs (default: available cores).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Output folder.
    #[arg(long, default_value = "reports/latest")]
    pub out: PathBuf,
    /// Override every selected scene's horizon (errors against references are then absent).
    #[arg(long = "t-end")]
    pub t_end: Option<f64>,
}

#[derive(Debug, Args, Clone)]
pub struct TrajectoryArgs {
    #[arg(long)]
    pub case: String,
    #[arg(long)]
    pub scene: String,
    #[arg(long)]
    pub param: String,
    #[arg(long)]
    pub integrator: String,
    #[arg(long, default_value = "body")]
    pub formulation: String,
    #[arg(long, conflicts_with = "tol", required_unless_present = "tol")]
    pub dt: Option<f64>,
    #[arg(long)]
    pub tol: Option<f64>,
    #[arg(long = "t-end")]
    pub t_end: Option<f64>,
    #[arg(long)]
    pub out: PathBuf,
}
