//! The work and memory budgets every case shares (README, "Budgets"): the default step budget
//! of a run and the most samples one run keeps in memory. A case or `--t-end` over the sample
//! budget is refused before any run, naming the key or option; a run over its step or RHS
//! budget ends as a typed `work_limit` (`integrate::Limits`).
//!
//! # Example
//!
//! ```
//! use mbdbench::case::{MAX_SAMPLES, over_sample_budget};
//!
//! assert!(over_sample_budget(1000, 10).is_none()); // 10,001 samples
//! let why = over_sample_budget(MAX_SAMPLES, 1).unwrap(); // one sample too many
//! assert!(why.contains("at most 1000000"));
//! ```

/// `max_steps` when a case does not set it.
pub const DEFAULT_MAX_STEPS: u64 = 100_000_000;

/// `max_rhs_evals` (every run) when a case does not set it: a fixed-step run is bounded by
/// `max_steps` before it starts, so this only stops a runaway Newton iteration count.
pub const DEFAULT_MAX_RHS_EVALS: u64 = 2_000_000_000;

/// `max_adaptive_rhs_evals` when a case does not set it: the RHS budget of an adaptive run,
/// whose work is not known up front. The catalogue's costliest adaptive run takes 251,741
/// (`gimbal_lock/spin_d1e-8`, `euler_zyx/dop853` at tol 1e-12); a run that diverges at a
/// loose tolerance crawls on steps of 1e-7 s and would take 1e8 steps (`se3_hq/dopri5` at
/// tol 0.5 on `nine_spring/two_angles`: 7.8e8 evaluations, 413 s).
pub const DEFAULT_MAX_ADAPTIVE_RHS_EVALS: u64 = 1_000_000;

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
            "{n} samples over the horizon; a run keeps at most {MAX_SAMPLES} (README, \
             \"Budgets\"): sample less often or shorten t_end"
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A full sample budget of the rigid body's observations fits in 200 MB (the bound
    /// on a run's peak memory), so the budget is what bounds memory.
    #[test]
    fn sample_budget_fits_in_200_mb() {
        let bytes = std::mem::size_of::<crate::run::Sample>() as u64 * MAX_SAMPLES;
        assert!(bytes <= 200 << 20, "{bytes} bytes");
    }
}
