//! ns/step of every registered variant, per case, next to a hand-written fixed-size RK4 loop
//! of the nine-spring model (`mbdbench::baseline`). Criterion's
//! throughput is set to the run's step count, so "elem/s" reads as steps per second and the
//! time per element as ns/step. After the benches, a table of ns/step and the ratio of
//! `quat/rk4/body` to the hand loop is printed (target: at most 1.5x).
use criterion::{BenchmarkId, Criterion, Throughput, criterion_group};
use mbdbench::baseline;
use mbdbench::case;
use mbdbench::plan;
use mbdbench::registry::{self, Setup};
use mbdbench::run::Grid;
use std::hint::black_box;
use std::time::Instant;

const T_END: f64 = 1.0;

fn setup() -> Setup {
    let cases = case::embedded().expect("embedded cases load");
    let c = cases
        .iter()
        .find(|c| c.name == "nine_spring")
        .expect("nine_spring");
    let s = c.scene("large").expect("scene large");
    let mut p = plan::scene_plan(c, s).expect("plan");
    p.setup.grid = Grid {
        t_end: T_END,
        sample_every: 0.1,
        score_every: 0.1,
    };
    p.setup
}

/// The step (or tolerance) each variant is benchmarked at.
fn value(v: &registry::Variant) -> f64 {
    if v.info.adaptive { 1e-8 } else { 1e-3 }
}

fn baseline_run(setup: &Setup, n: usize) -> baseline::Y {
    let o = &setup.initial;
    let mut y = baseline::Y::zeros();
    y[0] = o.q.w;
    y[1] = o.q.i;
    y[2] = o.q.j;
    y[3] = o.q.k;
    y.fixed_rows_mut::<3>(4).copy_from(&o.x);
    y.fixed_rows_mut::<3>(7).copy_from(&o.v);
    y.fixed_rows_mut::<3>(10).copy_from(&o.omega);
    let h = T_END / n as f64;
    for _ in 0..n {
        baseline::step(&setup.body, &mut y, h);
    }
    y
}

/// ns/step of every registered variant on the first scene of every case, over 1000 steps of
/// the variant's coarsest ladder step (adaptive: tolerance 1e-8, per accepted step).
fn bench_steps(c: &mut Criterion) {
    let setup = setup();
    let n = (T_END / 1e-3).round() as usize;
    let mut g = c.benchmark_group("step/baseline");
    g.sample_size(10);
    g.throughput(Throughput::Elements(n as u64));
    g.bench_function("hand_written_rk4_quat_nine_spring", |b| {
        b.iter(|| black_box(baseline_run(black_box(&setup), n)))
    });
    g.finish();
    let cases = case::embedded().expect("embedded cases load");
    for k in &cases {
        let scene = &k.scenes[0];
        let p = plan::scene_plan(k, scene).expect("plan");
        let mut g = c.benchmark_group(format!("step/{}", k.name));
        g.sample_size(10)
            .warm_up_time(std::time::Duration::from_millis(200))
            .measurement_time(std::time::Duration::from_millis(500));
        for v in registry::variants() {
            if registry::scene_na_reason(v, &p.setup.body).is_some() {
                continue;
            }
            let (val, t_end) = if v.info.adaptive {
                (1e-8, p.setup.grid.score_every * 10.0)
            } else {
                match p.ladders.for_method(&v.info).first() {
                    Some(&h) => (h, h * 1000.0),
                    None => continue,
                }
            };
            let mut s = p.setup.clone();
            s.observe = mbdbench::run::Observe::Final;
            s.grid = Grid {
                t_end,
                sample_every: t_end,
                score_every: t_end,
            };
            let steps = match (v.run)(&s, val) {
                Ok(o) if o.failure.is_none() => o.stats.steps.max(1),
                _ => continue,
            };
            g.throughput(Throughput::Elements(steps));
            let id = format!("{}/{}/{}", v.param, v.integrator, v.formulation);
            g.bench_with_input(BenchmarkId::from_parameter(id), &val, |b, &val| {
                b.iter(|| black_box((v.run)(black_box(&s), val)))
            });
        }
        g.finish();
    }
}

/// Median ns/step over a few repeats (for the printed table).
fn ns_per_step(f: impl Fn() -> u64, reps: usize) -> f64 {
    let mut t = Vec::with_capacity(reps);
    for _ in 0..reps {
        let t0 = Instant::now();
        let steps = f();
        t.push(t0.elapsed().as_secs_f64() * 1e9 / steps as f64);
    }
    t.sort_by(f64::total_cmp);
    t[reps / 2]
}

fn table(_: &mut Criterion) {
    let setup = setup();
    let n = (T_END / 1e-3).round() as usize;
    let reps = if std::env::args().any(|a| a == "--bench") {
        21
    } else {
        1
    };
    let base = ns_per_step(
        || {
            black_box(baseline_run(&setup, n));
            n as u64
        },
        reps,
    );
    println!("\nns/step on nine_spring/large (median of {reps}):");
    println!("  {:<40} {:>10.1}", "hand_written_rk4_quat", base);
    let mut quat_rk4 = None;
    for v in registry::variants() {
        let val = value(v);
        let ns = ns_per_step(
            || match (v.run)(&setup, val) {
                Ok(o) => o.stats.steps.max(1),
                Err(_) => 1,
            },
            reps,
        );
        let id = format!("{}/{}/{}", v.param, v.integrator, v.formulation);
        if id == "quat/rk4/body" {
            quat_rk4 = Some(ns);
        }
        println!("  {id:<40} {ns:>10.1}");
    }
    if let Some(q) = quat_rk4 {
        println!(
            "quat/rk4/body vs hand-written loop: {:.2}x (target <= 1.5x)",
            q / base
        );
    }
}

criterion_group!(benches, bench_steps, table);

fn main() {
    benches();
    criterion::Criterion::default()
        .configure_from_args()
        .final_summary();
}
