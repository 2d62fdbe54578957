//! The work and memory budgets every case shares (cases/README.md, "Budgets"), and the check
//! of a family's estimate against them. A case's budget keys (`max_steps`, `max_rhs_evals`,
//! `max_adaptive_rhs_evals`, `max_memory_mib`, `max_work`) default to the constants here and
//! may be raised up to their hard caps ([`HARD_CAPS`]); a key above its cap is refused when
//! the case loads. Every family declares an estimate of what one run of a scene needs
//! (`problem::Family::estimate`, an [`Estimate`] made from the case's parsed numbers, before
//! anything that grows with them exists); `catalogue::load_str` checks it with [`check`] for every
//! scene, so a case whose run would pass a budget is refused at load (`list` included, exit
//! 2, naming the file and the key that sets the cost). A run that passes its step or RHS
//! budget anyway (the count of an adaptive or Newton iteration is not known up front) ends
//! as a typed `work_limit` (`integrate::Limits`).
//!
//! Work is counted in work units, each about a nanosecond of one core on the machine the
//! estimates were calibrated on (cases/README.md, "Budgets", lists the measurements). An
//! estimate is of the nominal path (the catalogue's Newton iteration counts); the iterations
//! a Newton loop may add beyond it are bounded by the family's own iteration limits and the
//! RHS budget.
//!
//! # Example
//!
//! ```
//! use mbdbench::case::{Estimate, MAX_SAMPLES, over_sample_budget};
//!
//! assert!(over_sample_budget(1000, 10).is_none()); // 10,001 samples
//! let why = over_sample_budget(MAX_SAMPLES, 1).unwrap(); // one sample too many
//! assert!(why.contains("at most 1000000"));
//! // A run of 1e6 steps of 1e3 units each, holding 8 MB: the step count names its work.
//! let (ladder, mesh) = ("ladders.order2_4[0]", "numerics.elements");
//! let e = Estimate::run(8.0e6, mesh, 1.0e6, ladder, 1.0e3, mesh);
//! assert_eq!((e.work, e.work_key.as_str()), (1_000_000_000, ladder));
//! ```
use super::{Case, CaseError, Scene};

/// The default work budgets of a run are the run loop's (`integrate::Limits::default`); a case
/// file's `max_steps`, `max_rhs_evals` and `max_adaptive_rhs_evals` replace them.
pub use crate::integrate::{
    DEFAULT_MAX_ADAPTIVE_RHS_EVALS, DEFAULT_MAX_RHS_EVALS, DEFAULT_MAX_STEPS,
};

/// `max_memory_mib` when a case does not set it: the most memory (MiB) one run of a scene
/// may hold by its family's estimate. Two runs at once (`--jobs 2`) stay within 1.5 GB with
/// the program's own few tens of MB; the catalogue's largest run holds about 20 MB.
pub const DEFAULT_MAX_MEMORY_MIB: u64 = 512;

/// `max_work` when a case does not set it: the most work units (about a nanosecond each)
/// one run of a scene may need by its family's estimate, about 30 s. The catalogue's
/// costliest run is estimated at a few 1e9 and takes under 2 s.
pub const DEFAULT_MAX_WORK: u64 = 30_000_000_000;

/// The hard caps of the budget keys: a case may raise a budget up to its cap, not beyond
/// (about an hour of one core and 16 GiB: past them a run is no longer a benchmark point).
pub const HARD_CAPS: [(&str, u64); 5] = [
    ("max_steps", 10_000_000_000),
    ("max_rhs_evals", 40_000_000_000),
    ("max_adaptive_rhs_evals", 40_000_000_000),
    ("max_memory_mib", 16_384),
    ("max_work", 3_600_000_000_000),
];

/// The hard cap of budget key `key` (`u64::MAX` for a key that has none).
pub fn hard_cap(key: &str) -> u64 {
    HARD_CAPS
        .iter()
        .find(|(k, _)| *k == key)
        .map_or(u64::MAX, |(_, c)| *c)
}

/// `advise_max_energy_drift` when a case does not set it: the relative energy drift above
/// which the recommendation lists a variant to avoid.
pub const DEFAULT_ADVISE_MAX_ENERGY_DRIFT: f64 = 1e-3;

/// The most samples one run keeps in memory (its observations at every `sample_every`,
/// 136 bytes each for the rigid body: 136 MB): a case or `--t-end` that would need
/// more is refused before any run (the catalogue's largest run keeps 2,001).
pub const MAX_SAMPLES: u64 = 1_000_000;

/// Why `n_score` score intervals of `samples_per_score` samples each exceed the sample
/// budget, or None.
pub fn over_sample_budget(n_score: u64, samples_per_score: u64) -> Option<String> {
    let n = n_score.saturating_mul(samples_per_score).saturating_add(1);
    (n > MAX_SAMPLES).then(|| {
        format!(
            "{n} samples over the horizon; a run keeps at most {MAX_SAMPLES} \
             (cases/README.md, \"Budgets\"): sample less often or shorten t_end"
        )
    })
}

/// What the costliest runs of one scene need, estimated by its family from the case's
/// parsed numbers (`problem::Family::estimate`): each measure is the largest over the runs
/// the case asks for (every variant at its finest ladder point, the reference's runs), with
/// the case key that sets it (a dotted path, as in load errors), which a refusal names.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// Bytes one run holds at its peak (its matrices, states and samples).
    pub bytes: u64,
    pub bytes_key: String,
    /// Steps of the longest run, those before `t = 0` included.
    pub steps: u64,
    pub steps_key: String,
    /// Work units of the costliest run.
    pub work: u64,
    pub work_key: String,
    /// What the costliest run's work is made of (its steps and their cost, with their keys),
    /// for the refusal's message; empty when there is nothing to add to `work_key`.
    pub work_detail: String,
    /// Steps every run takes before `t = 0` (the fiber column's axial prelude): they count
    /// against `max_steps` like the run's own.
    pub prelude_steps: u64,
}

/// The fewest steps a run is assumed to need: a step that the default work budget affords
/// fewer times than this is too dear for any ladder, and a work refusal names its cost's key.
pub const MIN_STEPS: f64 = 1000.0;

/// A float count as `u64`, saturating (NaN counts as too many).
pub fn saturate(x: f64) -> u64 {
    if x.is_nan() { u64::MAX } else { x as u64 }
}

impl Estimate {
    /// One run of `steps` steps of `step_work` units each, holding `bytes`. Its work is
    /// named by `step_key` when the default work budget affords fewer than [`MIN_STEPS`] such
    /// steps (a mesh or a fiber count made a step too dear for any ladder), else by
    /// `steps_key` (a ladder, a horizon or a prelude made the steps too many); the message
    /// gives both.
    pub fn run(
        bytes: f64,
        bytes_key: &str,
        steps: f64,
        steps_key: &str,
        step_work: f64,
        step_key: &str,
    ) -> Estimate {
        let costly = step_work * MIN_STEPS > DEFAULT_MAX_WORK as f64;
        Estimate {
            bytes: saturate(bytes),
            bytes_key: bytes_key.into(),
            steps: saturate(steps),
            steps_key: steps_key.into(),
            work: saturate(steps * step_work),
            work_key: if costly { step_key } else { steps_key }.into(),
            work_detail: format!(
                "{steps:.0} steps ({steps_key}) of about {step_work:.1e} units ({step_key})"
            ),
            prelude_steps: 0,
        }
    }

    /// The larger of two estimates, measure by measure (each with its own key; the prelude
    /// is the larger too).
    pub fn max(self, other: Estimate) -> Estimate {
        fn pick<K>(a: u64, ka: K, b: u64, kb: K) -> (u64, K) {
            if b > a { (b, kb) } else { (a, ka) }
        }
        let (bytes, bytes_key) = pick(self.bytes, self.bytes_key, other.bytes, other.bytes_key);
        let (steps, steps_key) = pick(self.steps, self.steps_key, other.steps, other.steps_key);
        let (work, (work_key, work_detail)) = pick(
            self.work,
            (self.work_key, self.work_detail),
            other.work,
            (other.work_key, other.work_detail),
        );
        Estimate {
            bytes,
            bytes_key,
            steps,
            steps_key,
            work,
            work_key,
            work_detail,
            prelude_steps: self.prelude_steps.max(other.prelude_steps),
        }
    }
}

impl Estimate {
    /// A run whose work is bounded by a budget rather than a step count (an adaptive run:
    /// its RHS budget times the work of an evaluation), holding `bytes`.
    pub fn bounded(bytes: f64, bytes_key: &str, work: f64, work_key: &str) -> Estimate {
        Estimate {
            bytes: saturate(bytes),
            bytes_key: bytes_key.into(),
            steps: 0,
            steps_key: String::new(),
            work: saturate(work),
            work_key: work_key.into(),
            work_detail: String::new(),
            prelude_steps: 0,
        }
    }
}

/// The costs of a family whose runs integrate a small state of fixed size (the rigid body,
/// the test-only spring chain), for [`ode_estimate`].
#[derive(Debug, Clone, Copy)]
pub struct OdeCosts {
    /// Bytes a run holds per sample (its observation and its share of the scores, series and
    /// trajectory columns).
    pub bytes_per_sample: f64,
    /// Work units of one evaluation of the equations of motion.
    pub rhs_work: f64,
    /// Evaluations per step of the costliest fixed-step integrator of each order class
    /// (`order1`, `order2_4`, `order6`): its stages, times its Newton iterations if implicit.
    pub evals_per_step: [f64; 3],
}

/// The estimate of a scene of a small-state family: every sample of the horizon held (named
/// by `sample_every`); each order class's finest ladder step (either tier) at its costliest
/// integrator's evaluations per step (named by the ladder point); an adaptive run at its
/// whole RHS budget, the smaller of `max_rhs_evals` and `max_adaptive_rhs_evals` (named by
/// the latter), when the scene has tolerances.
pub fn ode_estimate(case: &Case, scene: &Scene, c: &OdeCosts) -> Estimate {
    let samples = scene.n_score as f64 * scene.samples_per_score as f64 + 1.0;
    let bytes = samples * c.bytes_per_sample;
    let bytes_key = format!("scene[{}].sample_every", scene.index);
    let mut e = Estimate::bounded(bytes, &bytes_key, 0.0, "");
    for (class, evals) in super::OrderClass::ALL.into_iter().zip(c.evals_per_step) {
        if let Some((key, step)) = scene.finest(class) {
            let step_work = evals * c.rhs_work;
            e = e.max(Estimate::run(
                bytes,
                &bytes_key,
                step.steps as f64,
                &key,
                step_work,
                &key,
            ));
        }
    }
    if !(scene.ladders.tol.is_empty() && scene.quick.tol.is_empty()) {
        let evals = case.max_rhs_evals.min(case.max_adaptive_rhs_evals) as f64;
        e = e.max(Estimate::bounded(
            bytes,
            &bytes_key,
            evals * c.rhs_work,
            "max_adaptive_rhs_evals",
        ));
    }
    e
}

/// Why a run of `scene` at the fixed step `dt` over `t_end` would pass its case's step
/// budget (the family's prelude steps included), or None. The CLI refuses such a `--dt` or
/// `--t-end` before the run with the same exit status in every family (2: the request
/// cannot be run; before, the beam and the rigid body started the run and failed it at
/// `t = 0` with exit 1, the fiber column refused it with exit 2).
pub fn over_step_budget(case: &Case, scene: &Scene, t_end: f64, dt: f64) -> Option<String> {
    let n = super::steps_dividing(t_end, dt)?;
    let prelude = case.family.estimate(case, scene).prelude_steps;
    (n.saturating_add(prelude) > case.max_steps).then(|| {
        format!(
            "needs {n} steps over t_end = {t_end} s ({prelude} more before t = 0), more than \
             max_steps = {} of case `{}` (cases/README.md, \"Budgets\")",
            case.max_steps, case.name
        )
    })
}

/// Checks one scene's estimate against its case's budgets: the first budget it passes is an
/// error naming the file and the estimate's key for that measure, with the budget key that
/// would have to be raised (and its hard cap).
pub fn check(case: &Case, scene: &Scene, e: &Estimate) -> Result<(), CaseError> {
    let refuse = |key: &str, message: String| {
        Err(CaseError {
            file: case.file.clone(),
            key: key.to_string(),
            message: format!(
                "scene `{}`: {message} (cases/README.md, \"Budgets\")",
                scene.name
            ),
        })
    };
    let budget = case.max_memory_mib.saturating_mul(1 << 20);
    if e.bytes > budget {
        return refuse(
            &e.bytes_key,
            format!(
                "one run would hold about {} MiB, more than max_memory_mib = {} (at most {})",
                e.bytes.div_ceil(1 << 20),
                case.max_memory_mib,
                hard_cap("max_memory_mib")
            ),
        );
    }
    if e.steps > case.max_steps {
        return refuse(
            &e.steps_key,
            format!(
                "its longest run takes {} steps ({} of them before t = 0), more than \
                 max_steps = {} (at most {})",
                e.steps,
                e.prelude_steps,
                case.max_steps,
                hard_cap("max_steps")
            ),
        );
    }
    if e.work > case.max_work {
        let detail = if e.work_detail.is_empty() {
            String::new()
        } else {
            format!(": {}", e.work_detail)
        };
        return refuse(
            &e.work_key,
            format!(
                "its costliest run needs about {:.2e} work units (about {:.0} s{detail}), more \
                 than max_work = {:.2e} (at most {:.2e})",
                e.work as f64,
                e.work as f64 * 1e-9,
                case.max_work as f64,
                hard_cap("max_work") as f64
            ),
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A full sample budget of the rigid body's observations fits in 200 MB (the bound
    /// on a run's peak memory), so the budget is what bounds memory.
    #[test]
    fn sample_budget_fits_in_200_mb() {
        let bytes = std::mem::size_of::<crate::run::Sample<crate::model::rigid_body::Observation>>()
            as u64
            * MAX_SAMPLES;
        assert!(bytes <= 200 << 20, "{bytes} bytes");
    }

    /// Every default budget lies within its hard cap, and a key without a cap has none.
    #[test]
    fn defaults_lie_within_the_caps() {
        for (key, default) in [
            ("max_steps", DEFAULT_MAX_STEPS),
            ("max_rhs_evals", DEFAULT_MAX_RHS_EVALS),
            ("max_adaptive_rhs_evals", DEFAULT_MAX_ADAPTIVE_RHS_EVALS),
            ("max_memory_mib", DEFAULT_MAX_MEMORY_MIB),
            ("max_work", DEFAULT_MAX_WORK),
        ] {
            assert!(default <= hard_cap(key), "{key}");
        }
        assert_eq!(hard_cap("energy_scale"), u64::MAX);
    }

    /// A small-state family's estimate (the rigid body's): every sample at 400 bytes; the
    /// finest `order1` step (1.28e6 steps of one evaluation) and an adaptive run at its whole
    /// RHS budget (1e6 evaluations) at 600 units an evaluation; a ladder step of 1e-7 s (1e8
    /// steps, 6e10 units) is refused naming it.
    #[test]
    fn small_state_estimates_count_samples_steps_and_budgets() {
        let text = include_str!("../../cases/nine_spring.toml");
        let c = crate::catalogue::load_str("cases/nine_spring.toml", text).unwrap();
        let s = c.scene("two_angles").unwrap();
        let e = (crate::catalogue::family_of(&c).estimate)(&c, s);
        assert_eq!(e.bytes, 1001 * 400);
        assert_eq!(
            (e.steps, e.steps_key.as_str()),
            (1_280_000, "ladders.order1[2]")
        );
        assert_eq!(e.work, 1_280_000 * 600);
        let costs = OdeCosts {
            bytes_per_sample: 1.0,
            rhs_work: 600.0,
            evals_per_step: [0.0; 3],
        };
        let adaptive = ode_estimate(&c, s, &costs);
        assert_eq!(
            (adaptive.work, adaptive.work_key.as_str()),
            (600_000_000, "max_adaptive_rhs_evals")
        );
        let fine = text.replacen("7.8125e-6]", "1.0e-7]", 1);
        let e = crate::catalogue::load_str("cases/nine_spring.toml", &fine).unwrap_err();
        assert_eq!(e.key, "ladders.order1[2]", "{e}");
        assert!(e.message.contains("max_work"), "{e}");
    }

    /// A run's work is named by its step count's key unless the default budget affords fewer
    /// than 1,000 of its steps (then by the step's cost key); the larger of two estimates
    /// keeps each measure's key; float counts saturate.
    #[test]
    fn estimates_name_the_key_that_sets_them() {
        let cheap = Estimate::run(1e3, "b", 1e9, "ladder", 10.0, "elements");
        assert_eq!(
            (cheap.work, cheap.work_key.as_str()),
            (10_000_000_000, "ladder")
        );
        assert!(
            cheap.work_detail.contains("(elements)"),
            "{}",
            cheap.work_detail
        );
        let dear = Estimate::run(1e9, "elements", 100.0, "ladder", 1e8, "elements");
        assert_eq!(dear.work_key, "elements");
        let fair = Estimate::run(0.0, "b", 1e5, "ladder", 1e7, "elements");
        assert_eq!(fair.work_key, "ladder");
        let both = cheap.clone().max(dear);
        assert_eq!(both.bytes_key, "elements");
        assert_eq!(both.steps_key, "ladder");
        assert_eq!(
            (both.work, both.work_key.as_str()),
            (10_000_000_000, "ladder")
        );
        assert_eq!(saturate(1e300), u64::MAX);
        assert_eq!(saturate(f64::NAN), u64::MAX);
    }
}
