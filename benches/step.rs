//! ns/step of every registered variant of every family, per case (its first scene), run
//! through the `Problem` seam as the suite times it (`Want::Timing`: final state only), next
//! to a hand-written fixed-size RK4 loop of the nine-spring model
//! (`mbdbench::model::rigid_body::baseline`). Criterion's throughput is set to the run's step
//! count, so "elem/s" reads as steps per second and the time per element as ns/step.
//!
//! A fixed-step variant runs 1000 steps of the coarsest step of its ladder that completes
//! them (a coarser point may fail by design, as the beam's rk4 at 5e-3 s beyond its
//! stability limit), the horizon rounded up to a whole number of score intervals (a run's
//! score grid must divide it: explicit Euler's 1.6e-5 s on free_body runs 6250 steps); an
//! adaptive one runs tolerance 1e-8 over ten score intervals, per accepted step. A case whose
//! dearest fixed-step variant would take over 0.1 s for 1000 steps (the least of three probes
//! of 10 steps) runs all its fixed-step variants over the longest of 500, 200, 100, 50, 20 or
//! 10 steps that fits, so that its variants share one horizon and an iteration stays short:
//! here the static fiber column runs 20 steps (its force-based element on 40 elements costs
//! about 3 ms a step) and the cyclic one 100 or 200 (the probe decides); each group's first
//! line names its horizon. Every variant is kept.
//!
//! Under `cargo bench` each benchmark is sampled as `support` sizes it from the cost of a run
//! at its stepping. The hand-written loop runs the step and step count `quat/rk4/body` got on
//! nine_spring/large. After the benches, a table of ns/step on nine_spring/large is printed
//! from criterion's own estimates of this run (`target/criterion/<group>/<id>/new/
//! estimates.json`: the statistic of criterion's `time:` line, the slope when sampled
//! linearly, else the mean, divided by the benchmark's steps), with the ratio of
//! `quat/rk4/body` to the hand loop (target: at most 1.5x); a benchmark this run did not
//! measure (a filter left it out) is listed as missing. `cargo test --benches` runs each
//! benchmark once, untimed, and prints no table. A first look at the table's benchmarks
//! alone: `cargo bench --bench step -- nine_spring` (37 s here; every case's probes still
//! run). `-- --quick` works too but saves little: criterion's quick mode still spends at
//! least 0.1 s on a benchmark, and its two samples make a noisier table.
mod support;

use criterion::{BenchmarkId, Criterion, Throughput};
use mbdbench::case;
use mbdbench::model::rigid_body::baseline;
use mbdbench::model::rigid_body::plan;
use mbdbench::model::rigid_body::registry::RigidSetup;
use mbdbench::problem::{self, Problem, Variant, Want};
use mbdbench::run::Stepping;
use std::hint::black_box;
use std::time::SystemTime;
use support::{Sizing, timed};

/// Steps of a fixed-step variant's run, unless its case's horizon is shorter.
const STEPS: usize = 1000;
/// The horizons a case can get, longest first: a case's horizon changes only when its cost
/// crosses one of them.
const HORIZONS: [usize; 7] = [STEPS, 500, 200, 100, 50, 20, 10];
/// Steps of the probe that measures a fixed-step variant's cost per step.
const PROBE_STEPS: usize = 10;
/// The longest a case's dearest fixed-step run may take, in seconds.
const RUN_CAP: f64 = 0.1;
/// The case and scene of the hand-written loop and the table.
const TABLE_CASE: &str = "nine_spring";
const TABLE_GROUP: &str = "step/nine_spring";
const BASELINE_GROUP: &str = "step/baseline";
const BASELINE_ID: &str = "hand_written_rk4_quat_nine_spring";
/// The variant compared with the hand-written loop.
const PAIR: &str = "quat/rk4/body";

/// The rigid body and initial state of nine_spring's first scene (large) for the
/// hand-written loop (the one part of this bench that is the rigid family's own).
fn setup(k: &case::Case) -> RigidSetup {
    plan::scene_plan(k, &k.scenes[0]).expect("plan").setup
}

fn baseline_run(setup: &RigidSetup, n: usize, h: f64) -> baseline::Y {
    let o = &setup.initial;
    let mut y = baseline::Y::zeros();
    y[0] = o.q.w;
    y[1] = o.q.i;
    y[2] = o.q.j;
    y[3] = o.q.k;
    y.fixed_rows_mut::<3>(4).copy_from(&o.x);
    y.fixed_rows_mut::<3>(7).copy_from(&o.v);
    y.fixed_rows_mut::<3>(10).copy_from(&o.omega);
    for _ in 0..n {
        baseline::step(&setup.body, &mut y, h);
    }
    y
}

fn id(v: &Variant) -> String {
    format!("{}/{}/{}", v.param, v.integrator, v.formulation)
}

/// One benchmark of a case: what it runs, its steps and the cost of one run (seconds).
struct Chosen {
    v: &'static Variant,
    stepping: Stepping,
    t_end: f64,
    steps: u64,
    secs: f64,
}

/// The end time of `n` steps of `h`, rounded up to a whole number of score intervals `every`
/// (a run's score grid must divide it): at least `n` steps.
fn horizon(h: f64, n: usize, every: f64) -> f64 {
    let intervals = h * n as f64 / every;
    if (intervals - intervals.round()).abs() <= 1e-9 * intervals.max(1.0) {
        h * n as f64
    } else {
        every * intervals.ceil()
    }
}

/// Runs `v` over `t_end` once: its steps and wall time if it completes.
fn try_run(p: &mut dyn Problem, v: &Variant, stepping: Stepping, t_end: f64) -> Option<(u64, f64)> {
    p.set_t_end(t_end);
    match timed(|| p.run(v, stepping, Want::Timing)) {
        (Ok(o), secs) if o.failure.is_none() => Some((o.stats.steps.max(1), secs)),
        _ => None,
    }
}

/// The benchmarks of one case and its fixed-step horizon: each variant's coarsest ladder
/// step that completes the horizon (adaptive: tolerance 1e-8 over ten score intervals).
fn plan_case(p: &mut dyn Problem, family: &'static problem::Family) -> (usize, Vec<Chosen>) {
    let variants: Vec<&'static Variant> = problem::matrix::registered(family)
        .filter(|v| p.na_reason(v).is_none())
        .collect();
    // The first ladder step of each fixed-step variant that completes the probe, and the
    // dearest cost per step among them.
    let every = p.score_every();
    let mut first = vec![0; variants.len()];
    let mut per_step = 0.0_f64;
    for (i, v) in variants
        .iter()
        .enumerate()
        .filter(|(_, v)| !v.info.adaptive)
    {
        let ladder = p.ladder(false, &v.info).to_vec();
        first[i] = ladder.len();
        for (j, &h) in ladder.iter().enumerate() {
            let t_end = horizon(h, PROBE_STEPS, every);
            if let Some((steps, secs)) = try_run(p, v, v.stepping(h), t_end) {
                // The least of three probes: a preempted one reads dearer, never cheaper.
                let secs = (0..2)
                    .filter_map(|_| try_run(p, v, v.stepping(h), t_end))
                    .fold(secs, |a, (_, s)| a.min(s));
                first[i] = j;
                per_step = per_step.max(secs / steps as f64);
                break;
            }
        }
    }
    let n = *HORIZONS
        .iter()
        .find(|&&n| n as f64 * per_step <= RUN_CAP)
        .unwrap_or(&HORIZONS[HORIZONS.len() - 1]);
    let mut chosen = Vec::new();
    for (i, &v) in variants.iter().enumerate() {
        let tries: Vec<(Stepping, f64)> = if v.info.adaptive {
            vec![(v.stepping(1e-8), p.score_every() * 10.0)]
        } else {
            let ladder = p.ladder(false, &v.info).to_vec();
            ladder[first[i]..]
                .iter()
                .map(|&h| (v.stepping(h), horizon(h, n, every)))
                .collect()
        };
        for (stepping, t_end) in tries {
            if let Some((steps, first)) = try_run(p, v, stepping, t_end) {
                let secs = if support::measuring() {
                    support::calibrate(first, || {
                        black_box(p.run(v, stepping, Want::Timing)).ok();
                    })
                } else {
                    first
                };
                chosen.push(Chosen {
                    v,
                    stepping,
                    t_end,
                    steps,
                    secs,
                });
                break;
            }
        }
    }
    (n, chosen)
}

/// The hand-written loop at the step and step count `quat/rk4/body` got on nine_spring/large
/// (1e-3 s and 1000 steps if it got none).
fn bench_baseline(c: &mut Criterion, k: &case::Case, pair: Option<&Chosen>) {
    let setup = setup(k);
    let (h, n) = match pair {
        Some(Chosen {
            stepping: Stepping::Dt(h),
            steps,
            ..
        }) => (*h, *steps as usize),
        _ => (1e-3, STEPS),
    };
    let (_, first) = timed(|| black_box(baseline_run(&setup, n, h)));
    let secs = support::calibrate(first, || {
        black_box(baseline_run(&setup, n, h));
    });
    let mut g = c.benchmark_group(BASELINE_GROUP);
    if support::measuring() {
        Sizing::for_cost(secs).apply(&mut g);
        println!("{BASELINE_GROUP}: {n} steps of {h:e} s");
    }
    g.throughput(Throughput::Elements(n as u64));
    g.bench_function(BASELINE_ID, |b| {
        b.iter(|| black_box(baseline_run(black_box(&setup), n, h)))
    });
    g.finish();
}

/// Every case's group, and the hand-written loop after nine_spring's.
fn bench_steps(c: &mut Criterion) {
    let cases = mbdbench::catalogue::embedded().expect("embedded cases load");
    for k in &cases {
        let family = mbdbench::catalogue::family_of(k);
        let mut p = (family.compile)(k, &k.scenes[0]).expect("compile");
        let (horizon, chosen) = plan_case(&mut *p, family);
        let name = format!("step/{}", k.name);
        let mut g = c.benchmark_group(&name);
        if support::measuring() {
            let expected: f64 = chosen
                .iter()
                .map(|b| Sizing::for_cost(b.secs).expected(b.secs))
                .sum();
            println!(
                "{name}: {} benchmarks, fixed steps over {horizon} steps, about {expected:.0} s",
                chosen.len()
            );
        }
        for b in &chosen {
            if support::measuring() {
                Sizing::for_cost(b.secs).apply(&mut g);
            }
            p.set_t_end(b.t_end);
            g.throughput(Throughput::Elements(b.steps));
            let (v, stepping, p) = (b.v, b.stepping, &*p);
            g.bench_function(BenchmarkId::from_parameter(id(v)), |bencher| {
                bencher.iter(|| black_box(p.run(v, stepping, Want::Timing)))
            });
        }
        g.finish();
        if k.name == TABLE_CASE {
            bench_baseline(c, k, chosen.iter().find(|b| id(b.v) == PAIR));
        }
    }
}

/// ns/step of one benchmark from criterion's estimates of this run.
fn ns_per_step(
    home: &std::path::Path,
    group: &str,
    id: &str,
    since: SystemTime,
) -> Result<(f64, &'static str, u64), String> {
    let e = support::estimate(home, group, id, since)?;
    let steps = e
        .elements
        .ok_or_else(|| format!("{group}/{id}: no throughput"))?;
    Ok((e.ns / steps as f64, e.statistic, steps))
}

/// The closing table: ns/step on nine_spring/large of the hand loop and of every registered
/// variant, from criterion's estimates of this run.
fn table(since: SystemTime) {
    if !support::measuring() {
        return;
    }
    let home = support::criterion_home();
    let cases = mbdbench::catalogue::embedded().expect("embedded cases load");
    let k = cases
        .iter()
        .find(|c| c.name == TABLE_CASE)
        .expect(TABLE_CASE);
    let family = mbdbench::catalogue::family_of(k);
    println!(
        "\nns/step on {TABLE_CASE}/{}: criterion's estimates of this run (time per iteration, \
         slope or mean as its `time:` line, / steps), from {}/<group>/<id>/new/estimates.json",
        k.scenes[0].name,
        home.display()
    );
    let row = |label: &str, r: &Result<(f64, &str, u64), String>| match r {
        Ok((ns, stat, steps)) => println!("  {label:<40} {ns:>10.1}  ({stat}, {steps} steps)"),
        Err(why) => println!("  {label:<40} {:>10}  ({why})", "missing"),
    };
    let base = ns_per_step(&home, BASELINE_GROUP, BASELINE_ID, since);
    row("hand_written_rk4_quat", &base);
    let mut pair = Err(format!("{PAIR} is not registered"));
    for v in problem::matrix::registered(family) {
        let r = ns_per_step(&home, TABLE_GROUP, &id(v), since);
        row(&id(v), &r);
        if id(v) == PAIR {
            pair = r;
        }
    }
    match (pair, base) {
        (Ok((q, _, n)), Ok((b, ..))) => println!(
            "{PAIR} vs hand-written loop: {:.2}x (target <= 1.5x; both {n} steps)",
            q / b
        ),
        (Err(why), _) | (_, Err(why)) => {
            println!("{PAIR} vs hand-written loop: not measured in this run ({why})")
        }
    }
}

fn main() {
    support::check_sizing();
    let since = SystemTime::now();
    let mut c = Criterion::default().configure_from_args();
    bench_steps(&mut c);
    c.final_summary();
    table(since);
}
