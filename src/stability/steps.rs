//! The step search every stability study shares: the largest passing step of a variant,
//! searched over integer step counts `n` of a horizon (`dt = unit / n`), or the largest passing
//! tolerance of an adaptive variant.
//!
//! Search ([`search_steps`]): a geometric ladder `n = n_start * 2^j` up to the first passing `n`
//! (at most the caller's `max_steps`; the cap is `n = cap`), then bisection on `n` between the
//! last failing and the first passing count until they differ by less than 5 %
//! ([`RESOLUTION`]); the result is `unit` over the passing count. When the cap itself passes
//! the variant is "bounded up to the cap". The search assumes the verdict is monotone in the
//! step near the boundary; where it is not, the result is the first passing step from the
//! coarse side, which is what a user stepping down from a coarse step would find. Adaptive
//! variants are searched on their tolerance the same way ([`search_tol`]): from the start
//! (at most [`TOL_CAP`], 1) down by decades to [`TOL_FLOOR`], then bisection in `log tol`.
//!
//! What a probe is (its run, its bounds) is the caller's: the rigid body's own study
//! (`model/rigid_body/stability/search.rs`) and the seam's search of the other families
//! (`study::seam_search`) each judge their probes and record what limits each result
//! ([`Found::reason`], the failure kind or the bound crossed at the first failing step beyond
//! it, with its time).
use crate::integrate::{Failure, FailureKind};

/// The coarsest step tried: `t_h / CAP_STEPS`.
pub const CAP_STEPS: u64 = 20;
/// The same in the quick tier (about 3e5 steps: explicit Euler's accurate step is then
/// usually "nothing passed").
pub const QUICK_MAX_STEPS: u64 = 20 * (1 << 14);
/// Bisection stops when the failing and passing values differ by less than this ratio.
pub const RESOLUTION: f64 = 1.05;
/// The loosest tolerance tried (adaptive variants).
pub const TOL_CAP: f64 = 1.0;
/// The tightest tolerance tried.
pub const TOL_FLOOR: f64 = 1e-13;
/// Why a probe failed, for `metric_reasons`.
#[derive(Debug, Clone, PartialEq)]
pub struct Limit {
    /// A failure kind (`non_finite`, `newton_failure` ...) or `bound_exceeded`.
    pub kind: FailureKind,
    pub t: f64,
    pub message: String,
}

impl Limit {
    pub(crate) fn from_failure(f: &Failure) -> Limit {
        Limit {
            kind: f.kind,
            t: f.t,
            message: f.message.clone(),
        }
    }
    fn text(&self, at: &str) -> String {
        let kind = serde_json::to_value(self.kind)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default();
        format!("{kind} at t = {:.6} with {at}: {}", self.t, self.message)
    }
}

/// A probe's verdict.
#[derive(Debug, Clone, PartialEq)]
pub enum Verdict {
    Pass,
    Fail(Limit),
    /// The probe could not be judged (the on-the-fly reference failed, a grid the run
    /// refused): the search stops and its metric is null with this reason.
    Error(String),
}

/// The work budget of one probe: the tier's step budget, for adaptive runs too (an adaptive
/// run that needs more steps than the finest fixed step tried is not a stable setting at
/// its tolerance: at loose tolerances some charts crawl on tiny steps, which the default
/// budget of 1e8 steps turned into searches of several minutes), and 16 RHS evaluations a
/// step (dop853's 12 plus rejections; Newton iterations are counted separately).
pub fn probe_limits(max_steps: u64) -> crate::integrate::Limits {
    crate::integrate::Limits {
        max_steps,
        max_rhs_evals: max_steps.saturating_mul(16),
        max_adaptive_rhs_evals: max_steps.saturating_mul(16),
    }
}

/// A probe point: a step count or a tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Probe {
    Steps(u64),
    Tol(f64),
}

/// The outcome of one search.
#[derive(Debug, Clone, PartialEq)]
pub struct Found {
    /// The largest passing step (or tolerance); None when nothing passed.
    pub value: Option<f64>,
    /// The step count that passed (fixed-step searches).
    pub n: Option<u64>,
    /// The passing value is the cap (no failure at any step tried).
    pub capped: bool,
    /// What failed at the next coarser probe, and where (none when capped).
    pub limit: Option<(String, Limit)>,
    /// Probes run.
    pub probes: u32,
    /// Why the search could not be completed (`Verdict::Error`).
    pub error: Option<String>,
}

impl Found {
    fn error(e: String, probes: u32) -> Found {
        Found {
            value: None,
            n: None,
            capped: false,
            limit: None,
            probes,
            error: Some(e),
        }
    }

    /// The sentence for `metric_reasons` (this search's cap, `t_h / CAP_STEPS`).
    pub fn reason(&self, horizon: f64) -> String {
        self.reason_with(&format!(
            "dt = t_h / {CAP_STEPS}, tol = {TOL_CAP:e}; t_h = {horizon:.6} s"
        ))
    }

    /// The sentence for `metric_reasons`, the cap described by `cap`.
    pub fn reason_with(&self, cap: &str) -> String {
        if let Some(e) = &self.error {
            return format!("search not completed: {e}");
        }
        match (&self.value, self.capped, &self.limit) {
            (Some(_), true, _) => format!("bounded up to the cap ({cap})"),
            (Some(_), false, Some((at, l))) => format!("limited by {}", l.text(at)),
            (None, _, Some((at, l))) => format!("nothing passed: {}", l.text(at)),
            _ => "nothing passed".into(),
        }
    }
}

/// Bisection-and-ladder search over step counts from `n_start` up (doubling, at most
/// `max_steps`), for the first `n` that passes `pass`; the step of `n` is `unit / n`, and a
/// pass at `n = cap` is the cap.
pub(crate) fn search_steps(
    n_start: u64,
    cap: u64,
    max_steps: u64,
    mut pass: impl FnMut(u64) -> Verdict,
    unit: f64,
) -> Found {
    let mut probes = 0;
    let mut last_fail: Option<(u64, Limit)> = None;
    let mut n = n_start;
    let n_pass = loop {
        probes += 1;
        match pass(n) {
            Verdict::Pass => break Some(n),
            Verdict::Fail(l) => last_fail = Some((n, l)),
            Verdict::Error(e) => return Found::error(e, probes),
        }
        if n >= max_steps {
            break None;
        }
        n = (n * 2).min(max_steps);
    };
    let Some(mut hi) = n_pass else {
        return Found {
            value: None,
            n: None,
            capped: false,
            limit: last_fail.map(|(n, l)| (format!("n = {n} steps"), l)),
            probes,
            error: None,
        };
    };
    let Some((mut lo, mut lo_limit)) = last_fail else {
        return Found {
            value: Some(unit / hi as f64),
            n: Some(hi),
            capped: hi == cap,
            limit: None,
            probes,
            error: None,
        };
    };
    while hi - lo > 1 && (hi as f64) / (lo as f64) >= RESOLUTION {
        let mid = lo + (hi - lo) / 2;
        probes += 1;
        match pass(mid) {
            Verdict::Pass => hi = mid,
            Verdict::Fail(l) => {
                lo = mid;
                lo_limit = l;
            }
            Verdict::Error(e) => return Found::error(e, probes),
        }
    }
    Found {
        value: Some(unit / hi as f64),
        n: Some(hi),
        capped: false,
        limit: Some((
            format!("dt = {:.6e} (n = {lo})", unit / lo as f64),
            lo_limit,
        )),
        probes,
        error: None,
    }
}

/// The same over tolerances, from `tol_start` down.
pub(crate) fn search_tol(tol_start: f64, mut pass: impl FnMut(f64) -> Verdict) -> Found {
    let mut probes = 0;
    let mut last_fail: Option<(f64, Limit)> = None;
    let mut tol = tol_start;
    let t_pass = loop {
        probes += 1;
        match pass(tol) {
            Verdict::Pass => break Some(tol),
            Verdict::Fail(l) => last_fail = Some((tol, l)),
            Verdict::Error(e) => return Found::error(e, probes),
        }
        if tol <= TOL_FLOOR * 1.000001 {
            break None;
        }
        tol = (tol / 10.0).max(TOL_FLOOR);
    };
    let Some(mut good) = t_pass else {
        return Found {
            value: None,
            n: None,
            capped: false,
            limit: last_fail.map(|(t, l)| (format!("tol = {t:.3e}"), l)),
            probes,
            error: None,
        };
    };
    let Some((mut bad, mut bad_limit)) = last_fail else {
        return Found {
            value: Some(good),
            n: None,
            capped: good == TOL_CAP,
            limit: None,
            probes,
            error: None,
        };
    };
    while bad / good >= RESOLUTION {
        let mid = (bad * good).sqrt();
        probes += 1;
        match pass(mid) {
            Verdict::Pass => good = mid,
            Verdict::Fail(l) => {
                bad = mid;
                bad_limit = l;
            }
            Verdict::Error(e) => return Found::error(e, probes),
        }
    }
    Found {
        value: Some(good),
        n: None,
        capped: false,
        limit: Some((format!("tol = {bad:.3e}"), bad_limit)),
        probes,
        error: None,
    }
}

/// The metric names of a variant's record: `largest_stable_dt`/`_tol` and
/// `largest_accurate_dt`/`_tol`.
pub fn metric_names(adaptive: bool) -> (&'static str, &'static str) {
    if adaptive {
        ("largest_stable_tol", "largest_accurate_tol")
    } else {
        ("largest_stable_dt", "largest_accurate_dt")
    }
}

/// Every metric name the search writes (the gate's known names).
pub const METRICS: &[&str] = &[
    "largest_stable_dt",
    "largest_accurate_dt",
    "largest_stable_tol",
    "largest_accurate_tol",
    "stability_horizon",
    "fastest_period",
    "first_period",
];
