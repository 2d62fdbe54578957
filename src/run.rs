//! The run loop: integrate one scene with one variant, observe the state at the sample
//! times, track the chart's conditioning every step, and return the samples, the work
//! counters and the typed failure, if any. Scoring (metrics) and timing live elsewhere.
//!
//! Time grid (deterministic by construction): a fixed-step run takes exactly `n = round(T/h)`
//! steps of `h = T/n` with `t_k = t0 + k h` computed from the integer `k`, so the same build on
//! the same input gives bit-identical results. Samples are taken on the scene's sample grid
//! when the step divides `sample_every`, otherwise on the score grid (every ladder step
//! divides `score_every`, cases/README.md, "Conventions"), always including `t_end`. Adaptive
//! methods step freely over the whole span (only their last step is clipped, to land on `t_end`)
//! and hand out their dense output at the output times, so the output grid does not constrain their
//! steps or inflate their work counts. A failure ends the run: the samples up to it are kept, the
//! failure records its time. The loop never allocates per step (the sample vector is reserved up
//! front) and observes only at output times: the grid, only the final state (timing), or a list of
//! step indices (`Observe::Steps`: the stability search's `t_h / n` steps, the long-horizon study's
//! log-spaced times).
use crate::integrate::{Adaptive, Failure, FixedStep, Limits, Stats, System};

/// What a run needs to observe of a state (chart-independent physical state, chart
/// diagnostics). Each model family has its own observation (a rigid body's pose and twist,
/// a chain's displacements and velocities).
pub trait Observable: System {
    /// The physical state, as the family scores it.
    type Obs: Copy + std::fmt::Debug + Send + Sync;
    /// The physical state.
    fn observe(&self, x: &Self::State) -> Self::Obs;
    /// The chart's own constraint residual (None for minimal charts).
    fn residual(&self, x: &Self::State) -> Option<f64>;
    /// The model's energy of an observation.
    fn energy(&self, o: &Self::Obs) -> f64;
    /// The attitude of an observation, for a `RotationWatch` (None: nothing to watch).
    fn attitude(o: &Self::Obs) -> Option<nalgebra::UnitQuaternion<f64>> {
        let _ = o;
        None
    }
}

/// Stability bounds checked at every observation of an `Observe::Steps` run: the run ends
/// with `bound_exceeded` as soon as `|E - E0| / max(|E0|, scale) >= max` (or is NaN), so a
/// probe that has already blown up does not integrate on (an adaptive run at a loose
/// tolerance can otherwise crawl on tiny steps to its work limit); and, when `rotation` is
/// given, as soon as the geodesic distance to the reference rotation at that observation
/// reaches its bound (the stability study's accuracy probes: a failing probe stops where it
/// fails instead of integrating to the horizon). Every observation after the first is
/// judged, so a run that ends without a failure stayed within the bounds throughout: the
/// stability search's probes need no second pass over the samples.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundWatch {
    pub scale: f64,
    pub max: f64,
    pub rotation: Option<RotationWatch>,
}

/// Reference rotations at observation indices `k` (of `Observe::Steps`' `n`), ascending in
/// `k`, and the bound on the geodesic distance to them (rad). An observation without an entry
/// is not judged.
#[derive(Debug, Clone, PartialEq)]
pub struct RotationWatch {
    pub reference: std::sync::Arc<[(u64, nalgebra::UnitQuaternion<f64>)]>,
    pub max: f64,
}

impl BoundWatch {
    /// The failure when the observation `s` at index `k` crosses a bound (energy relative to
    /// the initial energy `e0`, then rotation).
    fn judge<S: Observable>(
        &self,
        sys: &S,
        e0: f64,
        k: u64,
        s: &Sample<S::Obs>,
    ) -> Result<(), Failure> {
        use crate::integrate::FailureKind::BoundExceeded;
        let d = (sys.energy(&s.obs) - e0).abs() / e0.abs().max(self.scale);
        if d.is_nan() || d >= self.max {
            return Err(Failure::new(
                BoundExceeded,
                s.t,
                format!(
                    "energy error |E - E0| / max(|E0|, energy_scale) = {d:.3e} >= {}",
                    self.max
                ),
            ));
        }
        if let Some(rw) = &self.rotation
            && let Ok(i) = rw.reference.binary_search_by_key(&k, |(j, _)| *j)
            && let Some(q) = S::attitude(&s.obs)
        {
            let e = crate::math::so3::geodesic_quat(&q, &rw.reference[i].1);
            if e.is_nan() || e >= rw.max {
                return Err(Failure::new(
                    BoundExceeded,
                    s.t,
                    format!("rotation error {e:.3e} rad >= {} rad", rw.max),
                ));
            }
        }
        Ok(())
    }
}

/// When a run observes its state.
#[derive(Debug, Clone, PartialEq)]
pub enum Observe {
    /// On the scene's output grid (the sample grid, or the score grid; always `t_end`).
    Grid,
    /// Only the initial and final states (the timing pass).
    Final,
    /// At the times `k t_end / n` for the listed `k` (strictly ascending; 0 and `n` are always
    /// observed), for studies whose steps do not divide the score grid (the stability
    /// search's `t_h / n`) or whose times are log-spaced (the long-horizon study). A
    /// fixed-step run must take `n` steps (its step is `t_end / n`); an adaptive run steps
    /// freely and interpolates there. The samples' `score_stride` is 1.
    Steps {
        n: u64,
        at: std::sync::Arc<[u64]>,
        /// End the run when the energy bound is crossed at an observation.
        watch: Option<BoundWatch>,
    },
}

/// How a run steps: a fixed step or an adaptive tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stepping {
    Dt(f64),
    Tol(f64),
}

/// The time grid of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    pub t_end: f64,
    pub sample_every: f64,
    pub score_every: f64,
}

impl Grid {
    /// The time grid of `scene`'s runs.
    pub fn of_scene(scene: &crate::case::Scene) -> Grid {
        Grid {
            t_end: scene.t_end,
            sample_every: scene.sample_every,
            score_every: scene.score_every,
        }
    }
}

/// One observation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample<O> {
    pub t: f64,
    pub obs: O,
    pub conditioning: f64,
    pub residual: Option<f64>,
}

/// The outcome of a run.
#[derive(Debug, Clone)]
pub struct RunOutput<O> {
    pub samples: Vec<Sample<O>>,
    /// Index stride of the score grid within `samples`.
    pub score_stride: usize,
    pub failure: Option<Failure>,
    pub stats: Stats,
    /// Minimum of the chart's conditioning over every step.
    pub conditioning_min: f64,
}

impl<O> RunOutput<O> {
    /// The samples on the score grid (every `score_stride`-th).
    pub fn scored(&self) -> impl Iterator<Item = &Sample<O>> {
        self.samples.iter().step_by(self.score_stride.max(1))
    }
}

/// `Some(n)` when `h` divides `span` by the case-file rule (`case::steps_dividing`: `n =
/// round(span/h)`, `|n h - span| <= 1e-9 span`, `1 <= n <= 9e15`).
pub use crate::case::steps_dividing as divides;

/// Output grid for a run: `(output interval, number of outputs, outputs per score point)`.
/// Uses the sample grid when `h` (if fixed) divides `sample_every`, else the score grid.
fn output_grid(grid: &Grid, h: Option<f64>) -> Result<(f64, u64, usize), String> {
    let n_score = divides(grid.t_end, grid.score_every).ok_or_else(|| {
        format!(
            "score_every = {} does not divide t_end = {}",
            grid.score_every, grid.t_end
        )
    })?;
    let per_score = divides(grid.score_every, grid.sample_every);
    let use_sample = match (per_score, h) {
        (None, _) => false,
        (Some(_), None) => true,
        (Some(_), Some(h)) => divides(grid.sample_every, h).is_some(),
    };
    if use_sample {
        let k = per_score.unwrap_or(1);
        Ok((grid.score_every / k as f64, n_score * k, k as usize))
    } else {
        Ok((grid.score_every, n_score, 1))
    }
}

fn sample<S: Observable>(sys: &S, t: f64, x: &S::State) -> Sample<S::Obs> {
    Sample {
        t,
        obs: sys.observe(x),
        conditioning: sys.conditioning(x),
        residual: sys.residual(x),
    }
}

/// Samples reserved up front: the whole output grid, up to 65536 (a longer grid grows the
/// vector geometrically, never per step). Reserving the grid unbounded aborted the process on
/// a fine sample grid over a long horizon (tests/fuzz.rs).
pub(crate) fn reserve(n_out: u64) -> usize {
    n_out.min(1 << 16) as usize + 1
}

/// The `work_limit` failure of a run that needs `n` steps (fixed step) or output points
/// (adaptive) where its budget allows `max_steps`: it fails at once, at `t = 0`, instead of
/// integrating (and storing samples) up to the limit.
pub(crate) fn over_budget(what: &str, n: u64, limits: &Limits) -> Option<Failure> {
    (n > limits.max_steps).then(|| {
        Failure::new(
            crate::integrate::FailureKind::WorkLimit,
            0.0,
            format!(
                "needs {n} {what}, more than max_steps = {}",
                limits.max_steps
            ),
        )
    })
}

/// A fixed-step run's plan over the output grid (`output_grid`): `n_total` steps of `h =
/// t_end / n_total`, an output every `per_out` steps (`n_out` outputs), a score point every
/// `stride` outputs.
pub(crate) struct FixedPlan {
    pub n_total: u64,
    pub h: f64,
    pub n_out: u64,
    pub per_out: u64,
    pub stride: usize,
}

/// The plan of a run at the nominal step `h_nominal`; an error when the step does not divide
/// the horizon or the output interval.
pub(crate) fn fixed_plan(grid: &Grid, h_nominal: f64) -> Result<FixedPlan, String> {
    let n_total = divides(grid.t_end, h_nominal)
        .ok_or_else(|| format!("step {h_nominal} does not divide t_end = {}", grid.t_end))?;
    let (dt_out, n_out, stride) = output_grid(grid, Some(h_nominal))?;
    let per_out = divides(dt_out, h_nominal)
        .ok_or_else(|| format!("step {h_nominal} does not divide the output interval {dt_out}"))?;
    if per_out * n_out != n_total {
        return Err(format!(
            "inconsistent grid: {per_out} x {n_out} != {n_total} steps"
        ));
    }
    Ok(FixedPlan {
        n_total,
        h: grid.t_end / n_total as f64,
        n_out,
        per_out,
        stride,
    })
}

/// Runs a fixed-step method over the grid from `x0`; the loop counts the steps (adaptive
/// methods count their own accepted and rejected steps).
///
/// # Example
///
/// The oscillator with its energy as the observation, RK4 at `h = 0.01` over 10 s, sampled
/// every 0.1 s: 101 samples from `t = 0` to `t_end`, 1000 steps, energy kept to RK4's
/// truncation level.
///
/// ```
/// # use mbdbench::integrate::{Failure, FailureKind, System};
/// # use nalgebra::Vector2;
/// /// The harmonic oscillator `q'' = -q` on `(q, p)`.
/// struct Oscillator;
/// impl System for Oscillator {
///     type State = Vector2<f64>;
///     type Tangent = Vector2<f64>;
///     const LIE: bool = false;
///     fn rhs(&self, _t: f64, x: &Vector2<f64>) -> Vector2<f64> {
///         Vector2::new(x[1], -x[0])
///     }
///     fn retract(&self, x: &Vector2<f64>, dx: &Vector2<f64>) -> Vector2<f64> {
///         x + dx
///     }
///     fn check(&self, t: f64, x: &Vector2<f64>) -> Result<(), Failure> {
///         if x.iter().all(|v| v.is_finite()) {
///             Ok(())
///         } else {
///             Err(Failure::new(FailureKind::NonFinite, t, "non-finite state"))
///         }
///     }
/// }
/// use mbdbench::integrate::{Limits, explicit_rk::ExplicitRk};
/// use mbdbench::run::{Grid, Observable, Observe, run_fixed};
///
/// impl Observable for Oscillator {
///     type Obs = Vector2<f64>;
///     fn observe(&self, x: &Vector2<f64>) -> Vector2<f64> {
///         *x
///     }
///     fn residual(&self, _x: &Vector2<f64>) -> Option<f64> {
///         None
///     }
///     fn energy(&self, o: &Vector2<f64>) -> f64 {
///         0.5 * o.norm_squared()
///     }
/// }
/// let grid = Grid { t_end: 10.0, sample_every: 0.1, score_every: 0.1 };
/// let x0 = Vector2::new(1.0, 0.0);
/// let out = run_fixed(&Oscillator, &mut ExplicitRk::rk4(), x0, 0.01, &grid, &Limits::default(), &Observe::Grid)
///     .unwrap();
/// assert!(out.failure.is_none());
/// assert_eq!((out.samples.len(), out.stats.steps), (101, 1000));
/// assert_eq!(out.samples.last().unwrap().t, 10.0);
/// let drift = out.samples.iter().map(|s| (Oscillator.energy(&s.obs) - 0.5).abs()).fold(0.0, f64::max);
/// assert!(drift < 1e-9 && drift > 0.0, "{drift:e}");
/// ```
pub fn run_fixed<S: Observable, M: FixedStep<S>>(
    sys: &S,
    method: &mut M,
    x0: S::State,
    h_nominal: f64,
    grid: &Grid,
    limits: &Limits,
    observe: &Observe,
) -> Result<RunOutput<S::Obs>, String> {
    let n_total = divides(grid.t_end, h_nominal)
        .ok_or_else(|| format!("step {h_nominal} does not divide t_end = {}", grid.t_end))?;
    if let Observe::Steps { n, at, watch } = observe {
        if *n != n_total {
            return Err(format!(
                "observation grid of {n} steps, but the step {h_nominal} takes {n_total}"
            ));
        }
        check_ascending(at)?;
        return run_fixed_at(
            sys,
            method,
            x0,
            grid.t_end,
            n_total,
            at,
            watch.as_ref(),
            limits,
        );
    }
    let observe = *observe == Observe::Grid;
    let FixedPlan {
        h,
        n_out,
        per_out,
        stride,
        ..
    } = fixed_plan(grid, h_nominal)?;
    let mut out = RunOutput {
        samples: Vec::with_capacity(reserve(n_out)),
        score_stride: stride,
        failure: None,
        stats: Stats::default(),
        conditioning_min: f64::INFINITY,
    };
    let mut x = x0;
    if let Err(f) = sys.check(0.0, &x) {
        out.conditioning_min = sys.conditioning(&x);
        out.failure = Some(f);
        return Ok(out);
    }
    out.conditioning_min = sys.conditioning(&x);
    out.samples.push(sample(sys, 0.0, &x));
    if let Some(f) = over_budget("steps", n_total, limits) {
        out.failure = Some(f);
        return Ok(out);
    }
    let mut k: u64 = 0;
    for _ in 0..n_out {
        for _ in 0..per_out {
            let r = fixed_step(sys, method, &mut x, k, h, limits, &mut out);
            k += 1;
            if let Err(f) = r {
                out.failure = Some(f);
                return Ok(out);
            }
        }
        if observe || k == n_total {
            out.samples.push(sample(sys, k as f64 * h, &x));
        }
    }
    Ok(out)
}

/// One checked step of a fixed-step run from step index `k` (the shared body of both fixed
/// loops): step, count, normalize, check the state and the budgets, track the conditioning.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn fixed_step<S: Observable, M: FixedStep<S>>(
    sys: &S,
    method: &mut M,
    x: &mut S::State,
    k: u64,
    h: f64,
    limits: &Limits,
    out: &mut RunOutput<S::Obs>,
) -> Result<(), Failure> {
    let r = method.step(sys, k as f64 * h, h, x, &mut out.stats);
    out.stats.steps += 1;
    let t1 = (k + 1) as f64 * h;
    let c = r.and_then(|_| {
        if sys.normalize(x) {
            out.stats.normalizations += 1;
        }
        sys.check_conditioning(t1, x)
    })?;
    limits.check(t1, &out.stats)?;
    if c < out.conditioning_min {
        out.conditioning_min = c;
    }
    Ok(())
}

fn check_ascending(at: &[u64]) -> Result<(), String> {
    if at.windows(2).any(|w| w[0] >= w[1]) {
        return Err("observation step indices must be strictly ascending".into());
    }
    Ok(())
}

/// `run_fixed` with `Observe::Steps`: `n_total` steps of `t_end / n_total`, observed at step
/// 0, at the listed indices and at the last step.
#[allow(clippy::too_many_arguments)]
fn run_fixed_at<S: Observable, M: FixedStep<S>>(
    sys: &S,
    method: &mut M,
    x0: S::State,
    t_end: f64,
    n_total: u64,
    at: &[u64],
    watch: Option<&BoundWatch>,
    limits: &Limits,
) -> Result<RunOutput<S::Obs>, String> {
    let h = t_end / n_total as f64;
    let mut out = RunOutput {
        samples: Vec::with_capacity(at.len() + 2),
        score_stride: 1,
        failure: None,
        stats: Stats::default(),
        conditioning_min: sys.conditioning(&x0),
    };
    let mut x = x0;
    if let Err(f) = sys.check(0.0, &x) {
        out.failure = Some(f);
        return Ok(out);
    }
    out.samples.push(sample(sys, 0.0, &x));
    let e0 = sys.energy(&out.samples[0].obs);
    let mut next = at
        .iter()
        .copied()
        .filter(|&k| k > 0 && k < n_total)
        .peekable();
    for k in 0..n_total {
        if let Err(f) = fixed_step(sys, method, &mut x, k, h, limits, &mut out) {
            out.failure = Some(f);
            return Ok(out);
        }
        if next.peek() == Some(&(k + 1)) || k + 1 == n_total {
            next.next();
            let s = sample(sys, (k + 1) as f64 * h, &x);
            out.samples.push(s);
            if let Some(Err(f)) = watch.map(|w| w.judge(sys, e0, k + 1, &s)) {
                out.failure = Some(f);
                return Ok(out);
            }
        }
    }
    Ok(out)
}

/// A `System` wrapper that records the minimum conditioning seen by `check` (adaptive
/// methods check after every accepted step internally).
pub struct Watched<S: System> {
    inner: S,
    min_bits: std::sync::atomic::AtomicU64,
}

impl<S: System> System for Watched<S> {
    type State = S::State;
    type Tangent = S::Tangent;
    const LIE: bool = S::LIE;
    #[inline(always)]
    fn rhs(&self, t: f64, x: &S::State) -> S::Tangent {
        self.inner.rhs(t, x)
    }
    #[inline(always)]
    fn retract(&self, x: &S::State, dx: &S::Tangent) -> S::State {
        self.inner.retract(x, dx)
    }
    #[inline(always)]
    fn dexp_inv(&self, theta: &S::Tangent, v: &S::Tangent) -> S::Tangent {
        self.inner.dexp_inv(theta, v)
    }
    #[inline(always)]
    fn normalize(&self, x: &mut S::State) -> bool {
        self.inner.normalize(x)
    }
    #[inline]
    fn check(&self, t: f64, x: &S::State) -> Result<(), Failure> {
        use std::sync::atomic::Ordering::Relaxed;
        // A failed check still records the conditioning it saw (the singular-chart value).
        let c = match self.inner.check_conditioning(t, x) {
            Ok(c) => Ok(c),
            Err(f) => Err((self.inner.conditioning(x), f)),
        };
        let seen = c.as_ref().map_or_else(|(c, _)| *c, |c| *c);
        if seen < f64::from_bits(self.min_bits.load(Relaxed)) {
            self.min_bits.store(seen.to_bits(), Relaxed);
        }
        c.map(|_| ()).map_err(|(_, f)| f)
    }
    fn conditioning(&self, x: &S::State) -> f64 {
        self.inner.conditioning(x)
    }
}

impl<S: System> Watched<S> {
    /// Wraps `inner` (a copy of the system, made once per run).
    pub fn new(inner: S) -> Self {
        Watched {
            inner,
            min_bits: std::sync::atomic::AtomicU64::new(f64::INFINITY.to_bits()),
        }
    }
}

impl<S: crate::integrate::adaptive_rk::ErrorScale> crate::integrate::adaptive_rk::ErrorScale
    for Watched<S>
{
    #[inline(always)]
    fn coords(&self, x: &S::State) -> S::Tangent {
        self.inner.coords(x)
    }
}

/// Runs an adaptive method over the grid from `x0`, sampling its dense output.
pub fn run_adaptive<S: Observable + Clone, M: Adaptive<Watched<S>>>(
    sys: &S,
    method: &mut M,
    x0: S::State,
    grid: &Grid,
    limits: &Limits,
    observe: &Observe,
) -> Result<RunOutput<S::Obs>, String> {
    let (dt_out, n_out, stride, at, watch) = match observe {
        Observe::Grid => {
            let (d, n, s) = output_grid(grid, None)?;
            (d, n, s, None, None)
        }
        Observe::Final => (grid.t_end, 1, 1, None, None),
        Observe::Steps { n, at, watch } => {
            check_ascending(at)?;
            if *n == 0 {
                return Err("an observation grid of 0 steps".into());
            }
            (grid.t_end / *n as f64, *n, 1, Some(&at[..]), watch.as_ref())
        }
    };
    let w = Watched::new(sys.clone());
    let mut out = RunOutput {
        samples: Vec::with_capacity(reserve(n_out)),
        score_stride: stride,
        failure: None,
        stats: Stats::default(),
        conditioning_min: f64::INFINITY,
    };
    let mut x = x0;
    let first = w.check(0.0, &x);
    out.conditioning_min = sys.conditioning(&x);
    if let Err(f) = first {
        out.failure = Some(f);
        return Ok(out);
    }
    out.samples.push(sample(sys, 0.0, &x));
    if *observe == Observe::Grid
        && let Some(f) = over_budget("output points", n_out, limits)
    {
        out.failure = Some(f);
        return Ok(out);
    }
    let e0 = sys.energy(&out.samples[0].obs);
    let samples = &mut out.samples;
    let mut wanted = at.map(|a| a.iter().copied().filter(|&k| k > 0).peekable());
    let mut on_output = |k: u64, y: &S::State| {
        let keep = match wanted.as_mut() {
            None => true,
            Some(w) => {
                while w.peek().is_some_and(|&j| j < k) {
                    w.next();
                }
                w.peek() == Some(&k) || k == n_out
            }
        };
        if keep {
            let s = sample(sys, k as f64 * dt_out, y);
            samples.push(s);
            if let Some(w) = watch {
                w.judge(sys, e0, k, &s)?;
            }
        }
        Ok(())
    };
    let r = method.integrate_dense(
        &w,
        0.0,
        &mut x,
        dt_out,
        n_out,
        &mut on_output,
        &mut out.stats,
        &limits.adaptive(),
    );
    let c = f64::from_bits(w.min_bits.load(std::sync::atomic::Ordering::Relaxed));
    out.conditioning_min = out.conditioning_min.min(c);
    if let Err(f) = r {
        out.failure = Some(f);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use crate::integrate::FailureKind;

    // A horizon needing more steps (fixed step) or output points (adaptive) than max_steps
    // fails at once with work_limit at t = 0, keeping the initial sample; before, the run
    // reserved the whole output grid and the process aborted on the allocation (found by
    // tests/fuzz.rs).
    #[test]
    fn over_budget_grid_fails_at_once() {
        let cases = crate::catalogue::embedded().unwrap();
        let c = cases.iter().find(|c| c.name == "gimbal_lock").unwrap();
        let mut p =
            crate::model::rigid_body::plan::scene_plan(c, c.scene("spin_d1e-2").unwrap()).unwrap();
        p.setup.grid.t_end = 1.0e9; // 1e11 steps of 1e-2 s
        for (integrator, value) in [("rk4", 1.0e-2), ("dop853", 1.0e-8)] {
            let v = crate::model::rigid_body::registry::find("so3", integrator, "body").unwrap();
            let t0 = std::time::Instant::now();
            let out = (v.run)(&p.setup, value).unwrap();
            assert!(t0.elapsed().as_secs_f64() < 1.0, "{integrator}");
            let f = out.failure.expect(integrator);
            assert_eq!((f.kind, f.t), (FailureKind::WorkLimit, 0.0), "{f:?}");
            assert!(f.message.contains("max_steps"), "{f:?}");
            assert_eq!(out.samples.len(), 1);
            assert_eq!(out.stats.steps, 0);
        }
        // Within the budget nothing changes: the run completes on its grid.
        p.setup.grid.t_end = 3.2;
        p.setup.limits.max_steps = 320;
        let v = crate::model::rigid_body::registry::find("so3", "rk4", "body").unwrap();
        let out = (v.run)(&p.setup, 1.0e-2).unwrap();
        assert!(out.failure.is_none());
        assert_eq!(out.samples.len(), 321);
    }
}
