//! ns/step of every registered variant of every family, per case, run through the `Problem`
//! seam as the suite times it, next to a hand-written fixed-size RK4 loop
//! of the nine-spring model (`mbdbench::model::rigid_body::baseline`). Criterion's
//! throughput is set to the run's step count, so "elem/s" reads as steps per second and the
//! time per element as ns/step. After the benches, a table of ns/step and the ratio of
//! `quat/rk4/body` to the hand loop is printed (target: at most 1.5x).
use criterion::{BenchmarkId, Criterion, Throughput, criterion_group};
use mbdbench::case;
use mbdbench::model::rigid_body::baseline;
use mbdbench::model::rigid_body::plan;
use mbdbench::model::rigid_body::registry::Setup;
use mbdbench::problem::{self, Want};
use std::hint::black_box;
use std::time::Instant;

const T_END: f64 = 1.0;

/// The scene of the hand-written loop and the table: nine_spring/large.
fn nine_spring_large() -> (&'static problem::Family, Box<dyn problem::Problem>) {
    let cases = case::embedded().expect("embedded cases load");
    let c = cases
        .iter()
        .find(|c| c.name == "nine_spring")
        .expect("nine_spring");
    let family = problem::family_of(c);
    let p = (family.compile)(c, c.scene("large").expect("scene large")).expect("compile");
    (family, p)
}

/// The rigid body and initial state of nine_spring/large for the hand-written loop (the one
/// part of this bench that is the rigid family's own: the loop is written for it).
fn setup() -> Setup {
    let cases = case::embedded().expect("embedded cases load");
    let c = cases
        .iter()
        .find(|c| c.name == "nine_spring")
        .expect("nine_spring");
    let s = c.scene("large").expect("scene large");
    plan::scene_plan(c, s).expect("plan").setup
}

/// The step (or tolerance) each variant is tabulated at.
fn value(v: &problem::Variant) -> f64 {
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

/// ns/step of every registered variant of every family on the first scene of every case,
/// through the `Problem` seam as the suite's timing pass runs it (`Want::Timing`: final state
/// only), over 1000 steps of the variant's coarsest ladder step that completes them
/// (adaptive: tolerance 1e-8 over ten score intervals, per accepted step).
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
        let family = problem::family_of(k);
        let mut p = (family.compile)(k, &k.scenes[0]).expect("compile");
        let mut g = c.benchmark_group(format!("step/{}", k.name));
        g.sample_size(10)
            .warm_up_time(std::time::Duration::from_millis(200))
            .measurement_time(std::time::Duration::from_millis(500));
        for v in problem::matrix::registered(family) {
            if p.na_reason(v).is_some() {
                continue;
            }
            // Adaptive: tolerance 1e-8 over ten score intervals; fixed: the coarsest ladder step
            // that completes 1000 steps (a coarser point may fail by design, as the beam's
            // rk4 at 5e-3 s beyond its stability limit).
            let tries: Vec<(f64, f64)> = if v.info.adaptive {
                vec![(1e-8, p.score_every() * 10.0)]
            } else {
                p.ladder(false, &v.info)
                    .iter()
                    .map(|&h| (h, h * 1000.0))
                    .collect()
            };
            let mut chosen = None;
            for (val, t_end) in tries {
                p.set_t_end(t_end);
                if let Ok(o) = p.run(v, v.stepping(val), Want::Timing)
                    && o.failure.is_none()
                {
                    chosen = Some((v.stepping(val), o.stats.steps.max(1)));
                    break;
                }
            }
            let Some((stepping, steps)) = chosen else {
                continue;
            };
            g.throughput(Throughput::Elements(steps));
            let id = format!("{}/{}/{}", v.param, v.integrator, v.formulation);
            let p = &*p;
            g.bench_function(BenchmarkId::from_parameter(id), |b| {
                b.iter(|| black_box(p.run(v, stepping, Want::Timing)))
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
    let (family, mut p) = nine_spring_large();
    p.set_t_end(T_END);
    println!("\nns/step on nine_spring/large (median of {reps}):");
    println!("  {:<40} {:>10.1}", "hand_written_rk4_quat", base);
    let mut quat_rk4 = None;
    for v in problem::matrix::registered(family) {
        let stepping = v.stepping(value(v));
        let ns = ns_per_step(
            || match p.run(v, stepping, Want::Timing) {
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
