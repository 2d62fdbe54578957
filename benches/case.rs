//! Whole-run cost per registered variant at its coarsest ladder step (or loosest tolerance),
//! one scene per case (the first): what the cheapest point of the work-precision diagram
//! costs, observation included (the suite's own timing pass runs without observation).
use criterion::{BenchmarkId, Criterion, criterion_group};
use mbdbench::case;
use mbdbench::plan;
use mbdbench::registry;
use std::hint::black_box;
use std::time::Duration;

fn whole_runs(c: &mut Criterion) {
    let cases = case::embedded().expect("embedded cases load");
    for k in &cases {
        let scene = &k.scenes[0];
        let p = plan::scene_plan(k, scene).expect("plan");
        let mut g = c.benchmark_group(format!("case/{}/{}", k.name, scene.name));
        g.sample_size(10)
            .warm_up_time(Duration::from_millis(200))
            .measurement_time(Duration::from_millis(500));
        for v in registry::variants() {
            if registry::scene_na_reason(v, &p.setup.body).is_some() {
                continue;
            }
            let Some(&value) = p.ladders.for_method(&v.info).first() else {
                continue;
            };
            let id = format!("{}/{}/{}", v.param, v.integrator, v.formulation);
            g.bench_with_input(BenchmarkId::new(id, value), &value, |b, &value| {
                b.iter(|| black_box((v.run)(black_box(&p.setup), value)))
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
