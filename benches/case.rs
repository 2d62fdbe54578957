//! Whole-run cost per registered variant of every family at its coarsest ladder step (or
//! loosest tolerance), one scene per case (the first), through the `Problem` seam: what the
//! cheapest point of the work-precision diagram costs, scoring against the stored reference
//! included (`Want::Scored`, as the suite's results pass; its timing pass runs `Want::Timing`).
//!
//! Under `cargo bench` each variant is run first (three times when a run takes under 0.1 s,
//! for the median) and its benchmark sampled as `support` sizes it from that cost; each
//! group's first line gives its expected time. A variant whose run takes over 0.3 s is not
//! sampled, and the group's second line names it with its cost: criterion needs at least 10
//! samples of two runs each (one run a sample draws its warning) after three warm-up runs,
//! so each would take over 7 s, and the dozen dearest together about 2 of the 10 minutes
//! `cargo bench` may take on two cores. In the run measured for the README those were 12 of
//! the 603: explicit Euler and Lie-Euler on free_body/gni, whose coarsest step, 1.6e-5 s over
//! 100 s, is 6.25 million steps (0.31 to 0.70 s a run): `euler` of `euler_xyz`, `euler_zyx`,
//! `rotvec` and `matrix_proj` in both formulations, `so3/euler/spatial` and `so3/lie_euler`
//! in both; and `so3/newton_disp/disp_based_n8` on the cyclic fiber column (0.47 s). Which
//! runs cross 0.3 s moves with the machine's load (another run also dropped
//! `matrix/euler/spatial` and `so3/euler/body`, 0.35 s). The `step` bench still measures
//! their ns/step, and `cargo test --benches` runs every variant once, untimed.
mod support;

use criterion::{BenchmarkId, Criterion};
use mbdbench::problem::{self, Want};
use std::hint::black_box;
use support::{Sizing, timed};

/// The longest whole run that is sampled, in seconds (see the file's opening).
const RUN_LIMIT: f64 = 0.3;

fn id(v: &problem::Variant) -> String {
    format!("{}/{}/{}", v.param, v.integrator, v.formulation)
}

fn whole_runs(c: &mut Criterion) {
    let cases = mbdbench::catalogue::embedded().expect("embedded cases load");
    let references = mbdbench::cli::default_references();
    let measuring = support::measuring();
    for k in &cases {
        let scene = &k.scenes[0];
        let family = mbdbench::catalogue::family_of(k);
        let mut p = (family.compile)(k, scene).expect("compile");
        p.attach_reference(&references).expect("stored reference");
        let mut skipped = Vec::new();
        let mut benches = Vec::new();
        for v in problem::matrix::registered(family).filter(|v| p.na_reason(v).is_none()) {
            let Some(&value) = p.ladder(false, &v.info).first() else {
                continue;
            };
            let stepping = v.stepping(value);
            let run = || {
                black_box(p.run(v, stepping, Want::Scored)).ok();
            };
            // The calibration (measuring only: a test runs each benchmark once anyway).
            let secs = if measuring {
                support::calibrate(timed(run).1, run)
            } else {
                0.0
            };
            if secs > RUN_LIMIT {
                skipped.push(format!("{} ({secs:.2} s)", id(v)));
            } else {
                benches.push((v, value, secs));
            }
        }
        let name = format!("case/{}/{}", k.name, scene.name);
        if measuring {
            let expected: f64 = benches
                .iter()
                .map(|&(.., secs)| Sizing::for_cost(secs).expected(secs))
                .sum();
            println!(
                "{name}: {} benchmarks, about {expected:.0} s",
                benches.len()
            );
            if !skipped.is_empty() {
                println!(
                    "{name}: not sampled, one run over {RUN_LIMIT} s: {}",
                    skipped.join(", ")
                );
            }
        }
        let mut g = c.benchmark_group(name);
        for &(v, value, secs) in &benches {
            if measuring {
                Sizing::for_cost(secs).apply(&mut g);
            }
            let stepping = v.stepping(value);
            let p = &*p;
            g.bench_with_input(BenchmarkId::new(id(v), value), &value, |b, _| {
                b.iter(|| black_box(p.run(v, stepping, Want::Scored)))
            });
        }
        g.finish();
    }
}

fn main() {
    support::check_sizing();
    let mut c = Criterion::default().configure_from_args();
    whole_runs(&mut c);
    c.final_summary();
}
