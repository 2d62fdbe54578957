//! The long-horizon part of the stability study: `free_body/gni` at `dt = 1e-2` and
//! `heavy_top/bruls_cardona` at `dt = 1e-4` run for `N = 10^6` steps (`10^7` for the few
//! variants listed in `LONG`; `10^4` in the quick tier), observed at `SAMPLES = 200`
//! log-spaced step indices, with the growth exponent of the energy and momentum errors fitted
//! in log-log.
//!
//! Errors at a sample `t_k`: `e_E(t) = |E(t) - E_0| / max(|E_0|, energy_scale)` (as
//! `metrics::energy_drift`) and `e_L(t) = max_i |L_i(t) - L_i(0)| / |L(0)|` over the momentum
//! components the body conserves (`RigidBody::conserved_momenta`, as `model::rigid_body::momentum_drift`:
//! the world vector `L` for gni; `L_z` about the pivot and the spin `L_3` for the heavy top).
//! Fit rule: the envelope `m(t_k) = max_{j <= k} e(t_j)` (the running maximum over the samples:
//! an error that crosses zero, a random walk above all, has a log that dives at every
//! crossing; the envelope of a walk grows like it, `t^(1/2)`, of a drift like `t`, and of a
//! bounded error saturates) is fitted by least squares, `log10 m = p log10 t + c`, over the
//! samples in the last `FIT_DECADES = 2` decades of time (`t >= t_N / 100`: past the initial
//! transient, where a bounded oscillation has not yet reached its amplitude); samples where
//! the envelope is still exactly 0 (an error exactly 0 in floating point carries no exponent)
//! are skipped, and fewer than `MIN_FIT_POINTS` usable samples, or usable ones spanning less
//! than one decade, give a null exponent with the reason. The exponent is the `order` of the
//! fit records `energy_growth` and `momentum_growth`, whose points are `(t, m(t))`.
//!
//! What to expect (Hairer, Lubich & Wanner, GNI, ch. IX-XI; Hairer, McLachlan & Razakarivony,
//! BIT 48, 2008, "Achieving Brouwer's law with implicit Runge-Kutta methods"): `p ~ 1` for
//! non-symplectic methods (the truncation error drifts), `p ~ 0` for symplectic, symmetric and
//! variational methods at practical steps (bounded by backward error analysis), and `p ~ 1/2`
//! (Brouwer's law: unbiased round-off adds up like a random walk) where the method conserves
//! the quantity exactly, so only round-off is left: the quadratic invariants of gni under the
//! Gauss methods, and energy and momentum under `simo_wong`; `p ~ 1` there means the round-off
//! is biased (a systematic rounding or a Newton iteration stopped short), which the Kahan
//! variants (`model::rigid_body::methods::compensated`) are there to expose.
//!
//! Runs go in parallel (rayon, `opts.jobs` threads) and are deterministic: records, fits and
//! series do not depend on `jobs`, only `wall_s` (one run, timed under that load) does.

use crate::model::rigid_body::Observation;
use rayon::prelude::*;
use std::sync::Arc;
use std::time::Instant;

use crate::stability::{Part, StudyOptions};
use crate::case::Case;
use crate::integrate::Limits;
use crate::model::rigid_body::registry::{self, RigidSetup, Variant};
use crate::run::{Observe, RunOutput};
use crate::selection::VariantFilter;
use crate::summary::{self, FitRecord, Record, RunKey, Wall};

/// Number of log-spaced observation times.
pub const SAMPLES: usize = 200;
/// The fit uses the samples in the last this many decades of time.
pub const FIT_DECADES: f64 = 2.0;
/// Fewest usable samples for a fit.
pub const MIN_FIT_POINTS: usize = 8;
/// Steps of the full tier, of the variants in `LONG`, and of the quick tier.
pub const STEPS_FULL: u64 = 1_000_000;
pub const STEPS_LONG: u64 = 10_000_000;
pub const STEPS_QUICK: u64 = 10_000;

/// The scenes of the study and their steps: `(case, scene, dt)`.
pub const SCENES: &[(&str, &str, f64)] = &[
    ("free_body", "gni", 1e-2),
    ("heavy_top", "bruls_cardona", 1e-4),
];

/// The variants of the study `(param, integrator, formulation)`, in report order.
pub const VARIANTS: &[(&str, &str, &str)] = &[
    ("so3", "rk4", "body"),
    ("quat_proj", "rk4", "body"),
    ("so3", "splitting", "body"),
    ("so3", "lgvi", "body"),
    ("so3", "simo_wong", "body"),
    ("so3", "simo_wong_kahan", "body"),
    ("quat", "implicit_midpoint", "body"),
    ("quat", "implicit_midpoint_kahan", "body"),
    ("so3", "implicit_midpoint", "body"),
    ("so3", "implicit_midpoint_kahan", "body"),
    ("quat", "gauss6", "body"),
    ("quat", "gauss6_kahan", "body"),
    ("so3", "gauss6", "body"),
    ("so3", "gauss6_kahan", "body"),
];

/// `(case, param, integrator)` run for `STEPS_LONG` steps in the full tier, on gni: rk4, whose
/// truncation drift (`1.4e-10` at `10^6` steps) still competes with its bounded oscillation
/// in the fit window at `10^6` (exponent 0.68), and the cheaper of the round-off-only methods
/// (about 50 s for the midpoint rule, 17 s for `simo_wong` at `10^7`; `gauss6`, about 140 s,
/// stays at `10^6`).
pub const LONG: &[(&str, &str, &str)] = &[
    ("free_body", "so3", "rk4"),
    ("free_body", "quat_proj", "rk4"),
    ("free_body", "so3", "simo_wong"),
    ("free_body", "so3", "simo_wong_kahan"),
    ("free_body", "so3", "implicit_midpoint"),
    ("free_body", "so3", "implicit_midpoint_kahan"),
];

/// Steps of a run of the study.
pub fn steps_for(case: &str, param: &str, integrator: &str, quick: bool) -> u64 {
    if quick {
        STEPS_QUICK
    } else if LONG.contains(&(case, param, integrator)) {
        STEPS_LONG
    } else {
        STEPS_FULL
    }
}

/// `count` log-spaced step indices in `[1, n]`, strictly ascending and distinct (at small
/// indices, where rounding would repeat an index, the next free integer is taken), ending at `n`.
pub fn sample_steps(n: u64, count: usize) -> Vec<u64> {
    if n == 0 || count == 0 {
        return vec![];
    }
    let count = count.min(n as usize);
    let ln = (n as f64).ln();
    let mut out: Vec<u64> = Vec::with_capacity(count);
    for i in 0..count {
        let f = if count == 1 {
            1.0
        } else {
            i as f64 / (count - 1) as f64
        };
        let k = ((f * ln).exp().round() as u64).clamp(1, n);
        let prev = out.last().copied().unwrap_or(0);
        // Leave room for the remaining indices below n.
        let room = n - (count - 1 - i) as u64;
        out.push(k.max(prev + 1).min(room));
    }
    out
}

/// The running maximum of `e` (the envelope the fit uses).
pub fn envelope(e: &[f64]) -> Vec<f64> {
    let mut m = 0.0_f64;
    e.iter()
        .map(|&v| {
            m = if v.is_nan() { f64::NAN } else { m.max(v) };
            m
        })
        .collect()
}

/// A growth fit: exponent and the points `(t, envelope)` it used.
#[derive(Debug, Clone, PartialEq)]
pub struct GrowthFit {
    pub exponent: f64,
    pub points: Vec<[f64; 2]>,
}

/// Fits the growth exponent of `err` sampled at `t` (module docs: envelope, last `decades`
/// decades, zeros skipped). Err gives the reason when no exponent can be fitted.
pub fn fit_growth(t: &[f64], err: &[f64], decades: f64) -> Result<GrowthFit, String> {
    if t.len() != err.len() || t.is_empty() {
        return Err("no samples".into());
    }
    if err.iter().any(|e| !e.is_finite()) {
        return Err("non-finite error".into());
    }
    let env = envelope(err);
    let t_end = t[t.len() - 1];
    let t_min = t_end / 10f64.powf(decades);
    let points: Vec<[f64; 2]> = t
        .iter()
        .zip(&env)
        .filter(|(tk, m)| **tk >= t_min && **tk > 0.0 && **m > 0.0)
        .map(|(tk, m)| [*tk, *m])
        .collect();
    if points.len() < MIN_FIT_POINTS {
        return Err(if env[env.len() - 1] == 0.0 {
            "the error is exactly 0 at every sample".into()
        } else {
            format!(
                "{} samples with a non-zero error in the last {decades} decades (< {MIN_FIT_POINTS})",
                points.len()
            )
        });
    }
    let span = (points[points.len() - 1][0] / points[0][0]).log10();
    if span < 1.0 {
        return Err(format!(
            "the samples with a non-zero error span {span:.2} decades (< 1)"
        ));
    }
    let n = points.len() as f64;
    let (mut sx, mut sy) = (0.0, 0.0);
    for p in &points {
        sx += p[0].log10();
        sy += p[1].log10();
    }
    let (mx, my) = (sx / n, sy / n);
    let (mut sxx, mut sxy) = (0.0, 0.0);
    for p in &points {
        let (dx, dy) = (p[0].log10() - mx, p[1].log10() - my);
        sxx += dx * dx;
        sxy += dx * dy;
    }
    Ok(GrowthFit {
        exponent: sxy / sxx,
        points,
    })
}

/// The energy and momentum errors of a run at its samples: `(t, e_E, e_L)`; `e_L` is None when
/// the body conserves no momentum component.
pub fn errors(
    out: &RunOutput<Observation>,
    body: &crate::model::rigid_body::RigidBody,
    energy_scale: f64,
) -> (Vec<f64>, Vec<f64>, Option<Vec<f64>>) {
    let Some(first) = out.samples.first() else {
        return (vec![], vec![], None);
    };
    let (l0, nl, norm0) = body.conserved_momenta(&first.obs);
    let t = out.samples.iter().map(|s| s.t).collect();
    let e: Vec<f64> = out.samples.iter().map(|s| body.energy(&s.obs)).collect();
    let ee = crate::metrics::energy_drift::relative(&e, energy_scale).collect();
    let el = (nl > 0).then(|| {
        out.samples
            .iter()
            .map(|s| {
                let (l, _, _) = body.conserved_momenta(&s.obs);
                (0..nl).fold(0.0_f64, |m, i| m.max((l[i] - l0[i]).abs() / norm0))
            })
            .collect()
    });
    (t, ee, el)
}

/// One run of the study.
struct Job {
    case: String,
    scene: String,
    inputs_sha256: String,
    energy_scale: f64,
    setup: RigidSetup,
    dt: f64,
    steps: u64,
    variant: &'static Variant,
}

/// What one job produced.
struct Done {
    record: Record,
    fits: Vec<FitRecord>,
    series: Option<(String, serde_json::Value)>,
}

fn record(job: &Job, param: &str, integrator: &str, formulation: &str) -> Record {
    let mut r = Record::new(
        RunKey::new(&job.case, &job.scene, param, integrator, formulation),
        &job.inputs_sha256,
    );
    r.dt = Some(job.dt);
    r
}

/// Runs one job and scores it.
fn run_job(job: &Job) -> Done {
    let v = job.variant;
    let mut rec = record(job, v.param, v.integrator, v.formulation);
    rec.metrics
        .insert("long_horizon_steps".into(), Some(job.steps as f64));
    let t0 = Instant::now();
    let out = (v.run)(&job.setup, job.dt);
    let wall = t0.elapsed().as_secs_f64();
    let out = match out {
        Ok(o) => o,
        Err(msg) => {
            rec.refuse(msg);
            return Done {
                record: rec,
                fits: vec![],
                series: None,
            };
        }
    };
    rec.wall_s = Some(Wall {
        min: wall,
        median: wall,
    });
    rec.take_run(out.stats, out.failure.clone());
    let body = &job.setup.body;
    let (t, ee, el) = errors(&out, body, job.energy_scale);
    let mut fits = vec![];
    let mut score = |name: &str, fit_metric: &str, err: &[f64], rec: &mut Record| {
        let final_name = format!("{name}_error_final");
        let exp_name = format!("{name}_growth_exponent");
        let fit = match &out.failure {
            Some(f) => Err(format!("run failed ({}) at t = {}", f.kind.name(), f.t)),
            None => fit_growth(&t, err, FIT_DECADES),
        };
        match (&out.failure, err.last()) {
            (None, Some(&e)) if e.is_finite() => {
                rec.metrics.insert(final_name, Some(e));
            }
            _ => {
                rec.metrics.insert(final_name.clone(), None);
                rec.metric_reasons
                    .insert(final_name, "run failed or non-finite error".into());
            }
        }
        let (order, reason, points) = match fit {
            Ok(f) => (Some(f.exponent), None, f.points),
            Err(why) => (None, Some(why), vec![]),
        };
        rec.metrics.insert(exp_name.clone(), order);
        if let Some(why) = &reason {
            rec.metric_reasons.insert(exp_name, why.clone());
        }
        fits.push(FitRecord {
            key: crate::summary::RunKey::new(
                &job.case,
                &job.scene,
                v.param,
                v.integrator,
                v.formulation,
            ),
            metric: fit_metric.into(),
            order,
            reason,
            points,
        });
    };
    score("energy", "energy_growth", &ee, &mut rec);
    if let Some(el) = &el {
        score("momentum", "momentum_growth", el, &mut rec);
    }
    let id = summary::run_id(v.param, v.integrator, v.formulation, Some(job.dt), None);
    let path = format!("series/long_horizon/{}/{}/{id}.json", job.case, job.scene);
    rec.series = Some(path.clone());
    let value = serde_json::json!({
        "case": job.case,
        "scene": job.scene,
        "param": v.param,
        "integrator": v.integrator,
        "formulation": v.formulation,
        "dt": job.dt,
        "steps": job.steps,
        "t": t,
        "energy_error": ee,
        "momentum_error": el,
    });
    Done {
        record: rec,
        fits,
        series: Some((path, value)),
    }
}

/// The long-horizon study over the selected cases and variants (module docs).
pub fn study(cases: &[Case], filter: &VariantFilter, opts: &StudyOptions) -> Result<Part, String> {
    let mut jobs = vec![];
    let mut na = vec![];
    for &(case_name, scene_name, dt) in SCENES {
        let Some(case) = cases.iter().find(|c| c.name == case_name) else {
            continue;
        };
        let Some(scene) = case.scene(scene_name) else {
            continue;
        };
        let plan =
            crate::model::rigid_body::plan::scene_plan(case, scene).map_err(|e| e.to_string())?;
        for &(param, integ, form) in VARIANTS {
            if !filter.admits(param, integ, form) {
                continue;
            }
            let steps = steps_for(case_name, param, integ, opts.quick);
            let mut setup = plan.setup.clone();
            setup.grid.t_end = steps as f64 * dt;
            setup.grid.sample_every = setup.grid.t_end;
            setup.grid.score_every = setup.grid.t_end;
            setup.observe = Observe::Steps {
                n: steps,
                at: Arc::from(sample_steps(steps, SAMPLES)),
                watch: None,
            };
            setup.limits = Limits {
                max_steps: steps,
                max_rhs_evals: Limits::default().max_rhs_evals.max(100 * steps),
                ..setup.limits
            };
            let mut job = Job {
                case: plan.header.case.clone(),
                scene: plan.header.scene.clone(),
                inputs_sha256: plan.header.inputs_sha256.clone(),
                energy_scale: plan.energy_scale,
                setup,
                dt,
                steps,
                variant: &registry::variants()[0],
            };
            match registry::find(param, integ, form) {
                None => {
                    let mut r = record(&job, param, integ, form);
                    r.reason = Some(registry::static_na_reason(param, integ, form));
                    na.push(r);
                }
                Some(v) => match registry::scene_na_reason(v, &job.setup.body) {
                    Some(why) => {
                        let mut r = record(&job, param, integ, form);
                        r.reason = Some(why);
                        na.push(r);
                    }
                    None => {
                        job.variant = v;
                        jobs.push(job);
                    }
                },
            }
        }
    }
    // The longest runs first, so that the pool's threads finish together.
    let mut order: Vec<usize> = (0..jobs.len()).collect();
    order.sort_by_key(|&i| std::cmp::Reverse(jobs[i].steps));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.jobs.max(1))
        .build()
        .map_err(|e| e.to_string())?;
    let mut done: Vec<(usize, Done)> = pool.install(|| {
        order
            .par_iter()
            .with_max_len(1)
            .map(|&i| {
                let d = run_job(&jobs[i]);
                if opts.progress {
                    let r = &d.record;
                    crate::tell!(
                        "  long_horizon {}/{} {}/{}/{} {} steps: {:.1} s",
                        r.key.case,
                        r.key.scene,
                        r.key.param,
                        r.key.integrator,
                        r.key.formulation,
                        jobs[i].steps,
                        r.wall_s.map(|w| w.min).unwrap_or(f64::NAN)
                    );
                }
                (i, d)
            })
            .collect()
    });
    done.sort_by_key(|(i, _)| *i);
    let mut part = Part::default();
    for (_, d) in done {
        part.records.push(d.record);
        part.fits.extend(d.fits);
        part.series.extend(d.series);
    }
    part.records.extend(na);
    Ok(part)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sample indices are 200 distinct ascending steps from 1 to N, log-spaced (the
    /// ratio of consecutive indices at the top is 10^(6/199)) and fewer when N is small.
    #[test]
    fn sample_steps_are_log_spaced() {
        let s = sample_steps(1_000_000, SAMPLES);
        assert_eq!(s.len(), SAMPLES);
        assert_eq!((s[0], s[SAMPLES - 1]), (1, 1_000_000));
        assert!(s.windows(2).all(|w| w[0] < w[1]));
        let r = s[SAMPLES - 1] as f64 / s[SAMPLES - 2] as f64;
        assert!((r - 10f64.powf(6.0 / 199.0)).abs() < 1e-4, "{r}");
        let s = sample_steps(50, SAMPLES);
        assert_eq!(s, (1..=50).collect::<Vec<_>>());
    }

    /// The fit recovers the exponent of synthetic power laws (drift t, walk-like t^(1/2),
    /// bounded t^0) exactly, of an oscillation about a power law to a few percent, and the
    /// envelope turns a zero-crossing signal into its running maximum.
    #[test]
    fn fit_recovers_power_laws() {
        let t: Vec<f64> = sample_steps(1_000_000, SAMPLES)
            .iter()
            .map(|&k| k as f64 * 1e-2)
            .collect();
        for p in [1.0, 0.5, 0.0, 2.0] {
            let e: Vec<f64> = t.iter().map(|x| 3e-14 * x.powf(p)).collect();
            let f = fit_growth(&t, &e, FIT_DECADES).unwrap();
            assert!((f.exponent - p).abs() < 1e-9, "{p}: {}", f.exponent);
            assert!(f.points.iter().all(|q| q[0] >= t[t.len() - 1] / 100.0));
        }
        // |sin| under a t^(1/2) envelope: the running maximum follows the envelope.
        let e: Vec<f64> = t.iter().map(|x| x.sqrt() * (3.0 * x).sin().abs()).collect();
        let f = fit_growth(&t, &e, FIT_DECADES).unwrap();
        assert!((f.exponent - 0.5).abs() < 0.05, "{}", f.exponent);
        assert_eq!(envelope(&[1.0, 0.0, 3.0, 2.0]), vec![1.0, 1.0, 3.0, 3.0]);
    }

    /// Exactly conserved quantities, too few or too short samples, and non-finite errors give
    /// a reason instead of an exponent.
    #[test]
    fn fit_reasons() {
        let t: Vec<f64> = (1..=100).map(|k| k as f64).collect();
        let z = vec![0.0; 100];
        assert!(fit_growth(&t, &z, 2.0).unwrap_err().contains("exactly 0"));
        let mut e = z.clone();
        e[99] = 1e-16;
        assert!(fit_growth(&t, &e, 2.0).is_err());
        let t2: Vec<f64> = (1..=100).map(|k| 1.0 + k as f64 * 1e-3).collect();
        let e2: Vec<f64> = t2.clone();
        assert!(fit_growth(&t2, &e2, 2.0).unwrap_err().contains("decades"));
        e[5] = f64::NAN;
        assert!(fit_growth(&t, &e, 2.0).unwrap_err().contains("non-finite"));
    }

    /// The quick tier (10^4 steps) already separates the behaviours: rk4's energy error on the
    /// heavy top drifts (exponent about 1; measured 1.08) while the symplectic splitting's stays
    /// bounded on both scenes (about 0; measured 0.08 and 0.09); records carry the steps and a
    /// series path, and the study is deterministic across thread counts.
    #[test]
    fn quick_tier_drift_and_bounded() {
        let cases = crate::catalogue::embedded().unwrap();
        let filter = VariantFilter {
            param: vec!["so3".into()],
            integrator: vec!["rk4".into(), "splitting".into()],
            formulation: vec!["body".into()],
        };
        let opts = |jobs| StudyOptions {
            quick: true,
            jobs,
            out: std::env::temp_dir(),
            references: "references".into(),
            progress: false,
        };
        let part = study(&cases, &filter, &opts(2)).unwrap();
        let p = |case: &str, integ: &str| {
            let r = part
                .records
                .iter()
                .find(|r| r.key.case == case && r.key.integrator == integ)
                .unwrap();
            assert_eq!(r.metrics["long_horizon_steps"], Some(STEPS_QUICK as f64));
            assert!(
                r.series
                    .as_ref()
                    .unwrap()
                    .starts_with("series/long_horizon/")
            );
            r.metrics["energy_growth_exponent"].unwrap()
        };
        let rk4 = p("heavy_top", "rk4");
        assert!((0.8..1.3).contains(&rk4), "rk4 {rk4}");
        for case in ["free_body", "heavy_top"] {
            let sp = p(case, "splitting");
            assert!(sp.abs() < 0.3, "splitting {case} {sp}");
        }
        let again = study(&cases, &filter, &opts(1)).unwrap();
        let strip = |v: &[Record]| {
            v.iter()
                .map(|r| (r.metrics.clone(), r.stats))
                .collect::<Vec<_>>()
        };
        assert_eq!(strip(&part.records), strip(&again.records));
    }

    /// Prints the exponent table of a tier (not a check: `cargo test --release --lib
    /// long_horizon::tests::print_table -- --ignored --nocapture`, with `LH_FULL=1` for the
    /// full tier and `LH_FILTER=integrator,...` to select integrators).
    #[test]
    #[ignore]
    fn print_table() {
        let cases = crate::catalogue::embedded().unwrap();
        let quick = std::env::var("LH_FULL").is_err();
        let mut filter = VariantFilter::default();
        if let Ok(f) = std::env::var("LH_FILTER") {
            filter.integrator = f.split(',').map(String::from).collect();
        }
        let opts = StudyOptions {
            quick,
            jobs: 2,
            out: std::env::temp_dir(),
            references: "references".into(),
            progress: true,
        };
        let t0 = Instant::now();
        let part = study(&cases, &filter, &opts).unwrap();
        eprintln!("total {:.1} s", t0.elapsed().as_secs_f64());
        for r in &part.records {
            let m = |k: &str| r.metrics.get(k).copied().flatten().unwrap_or(f64::NAN);
            eprintln!(
                "{:<10} {:<10} {:<24} {:>9.0} steps  E p={:>6.3} fin={:>9.2e}  L p={:>6.3} fin={:>9.2e}  {:>7.2} s {:?}",
                r.key.case,
                r.key.param,
                r.key.integrator,
                m("long_horizon_steps"),
                m("energy_growth_exponent"),
                m("energy_error_final"),
                m("momentum_growth_exponent"),
                m("momentum_error_final"),
                r.wall_s.map(|w| w.min).unwrap_or(f64::NAN),
                r.status
            );
        }
        if let Ok(dir) = std::env::var("LH_SERIES") {
            for (path, v) in &part.series {
                let p = std::path::Path::new(&dir).join(path);
                std::fs::create_dir_all(p.parent().unwrap()).unwrap();
                std::fs::write(p, serde_json::to_string(v).unwrap()).unwrap();
            }
        }
    }
}
