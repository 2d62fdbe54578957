//! Whole-run cost per registered variant of every family at its coarsest ladder step (or
//! loosest tolerance), one scene per case (the first), through the `Problem` seam: what the
//! cheapest point of the work-precision diagram costs, scoring against the stored reference
//! included (`Want::Scored`, as the suite's results pass; its timing pass runs `Want::Timing`).
use criterion::{BenchmarkId, Criterion, criterion_group};
use mbdbench::case;
use mbdbench::problem::{self, Want};
use std::hint::black_box;
use std::time::Duration;

fn whole_runs(c: &mut Criterion) {
    let cases = case::embedded().expect("embedded cases load");
    let references = mbdbench::cli::default_references();
    for k in &cases {
        let scene = &k.scenes[0];
        let family = problem::family_of(k);
        let mut p = (family.compile)(k, scene).expect("compile");
        p.attach_reference(&references).expect("stored reference");
        let mut g = c.benchmark_group(format!("case/{}/{}", k.name, scene.name));
        g.sample_size(10)
            .warm_up_time(Duration::from_millis(200))
            .measurement_time(Duration::from_millis(500));
        for v in problem::matrix::registered(family) {
            if p.na_reason(v).is_some() {
                continue;
            }
            let Some(&value) = p.ladder(false, &v.info).first() else {
                continue;
            };
            let id = format!("{}/{}/{}", v.param, v.integrator, v.formulation);
            let stepping = v.stepping(value);
            g.bench_with_input(BenchmarkId::new(id, value), &value, |b, _| {
                b.iter(|| black_box(p.run(v, stepping, Want::Scored)))
            });
        }
        g.finish();
    }
}

criterion_group!(benches, whole_runs);

fn main() {
    benches();
    criterion::Criterion::default()
        .configure_from_args()
        .final_summary();
}
