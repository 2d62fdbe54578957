//! The cost of one Newton iteration of the structural integrators on the flexible beam's
//! `fe_exact` model, as `structural::newton` makes it: one residual, the tangent written
//! into the iteration matrix the state sizes from the model's pattern
//! (`SecondOrder::tangent_into` into `math::tangent::Tangent`), its factorisation and one
//! solve. Group `structural`, ids `newton_iteration/<base>/<N>` for `N` = 10, 20, 40, 80 and
//! 160 elements, on the prescribed spin-up (band only, `n = 3 N`) and on the free hub (band
//! plus one border row and column, `n = 3 N + 1`); the model is Kane, Ryan & Banerjee's
//! beam (10 m, EA 2.8e7 N, EI 1.4e4 N m^2, 1.2 kg/m) at a deformed, moving state (t = 7 s,
//! h = 1e-3 s, Newmark's coefficients). A second group, `structural_lu`, times factor plus
//! one solve of the beam's free-hub pattern (`kl = ku = 5`, one border) dense
//! (`math::lu::DenseLu`) and banded (`math::banded::BandedLu`) at small orders, the
//! measurement behind `math::tangent`'s crossover.
//!
//! After the benches, a table of the free hub's and spin-up's time per iteration at each
//! `N` from criterion's own estimates (as `benches/step.rs`'s table), with the ratio of
//! `N = 80` to `N = 10` (target: at most 10x; linear cost gives 8x). `cargo test --benches`
//! runs each benchmark once, untimed. `cargo bench --bench structural` takes about 10 s.
//! Where it fails: the times are of one state; the dense path's cost grows as `n^3` and
//! would dominate a run of the suite at 160 elements, the banded one's as `n`.
mod support;

use criterion::{BenchmarkId, Criterion};
use mbdbench::math::banded::{Band, BandedLu, Border};
use mbdbench::math::lu::{DenseLu, LinearSolve};
use mbdbench::math::tangent::Tangent;
use mbdbench::model::flexible_beam::base::Base;
use mbdbench::model::flexible_beam::fe::{Beam, Fe};
use mbdbench::structural::SecondOrder;
use nalgebra::{DMatrix, DVector};
use std::hint::black_box;
use std::path::Path;
use std::time::SystemTime;
use support::{Sizing, timed};

const GROUP: &str = "structural";
const LU_GROUP: &str = "structural_lu";
const ELEMENTS: [usize; 5] = [10, 20, 40, 80, 160];
/// Orders of the crossover group: the free hub's `3 N + 1` for N = 2 ... 10.
const LU_ORDERS: [usize; 9] = [7, 10, 13, 16, 19, 22, 25, 28, 31];
const KANE: Beam = Beam {
    l: 10.0,
    ea: 2.8e7,
    ei: 1.4e4,
    rho_a: 1.2,
};
const H: f64 = 1e-3;

/// One Newton iteration's data: the model, a state, its residual and iteration matrix.
struct Iteration {
    fe: Fe,
    q: DVector<f64>,
    v: DVector<f64>,
    a: DVector<f64>,
    r: DVector<f64>,
    s: Tangent,
}

/// A smooth deformed state of amplitude `amp` (a bent, stretched beam).
fn state(fe: &Fe, amp: f64) -> DVector<f64> {
    DVector::from_fn(fe.dim(), |i, _| {
        amp * (0.3 * i as f64).sin() / (1.0 + i as f64)
    })
}

impl Iteration {
    fn new(n_el: usize, base: Base) -> Iteration {
        let fe = Fe::new(KANE, n_el, base).expect("model");
        let (q, v, a) = (state(&fe, 1e-3), state(&fe, 1e-2), state(&fe, 1e-1));
        let s = Tangent::new(fe.dim(), fe.pattern());
        let r = DVector::zeros(fe.dim());
        Iteration { fe, q, v, a, r, s }
    }

    /// What `structural::newton::solve_acceleration` does in one iteration.
    fn run(&mut self) -> f64 {
        let t = 7.0;
        let it = self;
        it.fe.residual(t, &it.q, &it.v, &it.a, &mut it.r);
        it.fe.tangent_into(
            t,
            &it.q,
            &it.v,
            &it.a,
            1.0,
            0.5 * H,
            0.25 * H * H,
            &mut it.s,
        );
        it.s.factor().expect("regular iteration matrix");
        it.r.neg_mut();
        it.s.solve_in_place(&mut it.r).expect("solve");
        it.r[0]
    }
}

fn bases() -> [(&'static str, Base); 2] {
    [
        ("spin_up", Base::SpinUp { w: 4.0, t_up: 15.0 }),
        (
            "free_hub",
            Base::Free {
                j_hub: 10.0,
                torque: 5.0,
                t_off: 10.0,
            },
        ),
    ]
}

fn bench_newton(c: &mut Criterion) {
    let mut g = c.benchmark_group(GROUP);
    for (name, base) in bases() {
        for n_el in ELEMENTS {
            let mut it = Iteration::new(n_el, base);
            if support::measuring() {
                let (_, first) = timed(|| black_box(it.run()));
                let secs = support::calibrate(first, || {
                    black_box(it.run());
                });
                Sizing::for_cost(secs).apply(&mut g);
            }
            let id = BenchmarkId::new(format!("newton_iteration/{name}"), n_el);
            g.bench_function(id, |b| b.iter(|| black_box(it.run())));
        }
    }
    g.finish();
}

/// The free hub's pattern at order `n` with random entries and a dominant diagonal.
fn hub_matrix(n: usize) -> DMatrix<f64> {
    let mut next = support::uniform();
    DMatrix::from_fn(n, n, |i, j| {
        let inside = i == 0 || j == 0 || i.abs_diff(j) <= 5;
        if inside {
            next() + if i == j { 4.0 } else { 0.0 }
        } else {
            0.0
        }
    })
}

fn bench_lu(c: &mut Criterion) {
    let mut g = c.benchmark_group(LU_GROUP);
    for n in LU_ORDERS {
        let m = hub_matrix(n);
        let b0 = DVector::from_fn(n, |i, _| 1.0 + i as f64);
        let mut dense = DenseLu::new(n);
        let band = Band {
            n,
            kl: 5,
            ku: 5,
            border: Border::First(1),
        };
        let mut banded = BandedLu::new(band);
        for j in 0..n {
            for i in 0..n {
                if m[(i, j)] != 0.0 {
                    banded.add(i, j, m[(i, j)]).expect("in the pattern");
                }
            }
        }
        let template = banded.clone();
        let mut x = b0.clone();
        let mut run_dense = || {
            dense.matrix_mut().copy_from(&m);
            dense.factor().expect("regular");
            x.copy_from(&b0);
            dense.solve_in_place(&mut x).expect("solve");
            x[0]
        };
        if support::measuring() {
            Sizing::for_cost(1e-6).apply(&mut g);
        }
        g.bench_function(BenchmarkId::new("dense", n), |b| {
            b.iter(|| black_box(run_dense()))
        });
        let mut y = b0.clone();
        g.bench_function(BenchmarkId::new("banded", n), |b| {
            b.iter(|| {
                banded.clone_from(&template);
                banded.factor().expect("regular");
                y.copy_from(&b0);
                banded.solve(y.as_mut_slice()).expect("solve");
                black_box(y[0])
            })
        });
    }
    g.finish();
}

/// Criterion's estimate (ns: the slope when sampled linearly, else the mean) of
/// `newton_iteration/<name>/<n_el>` if this run wrote it (its folder:
/// `<home>/structural/newton_iteration_<name>/<n_el>/new/`).
fn estimate_ns(home: &Path, name: &str, n_el: usize, since: SystemTime) -> Result<f64, String> {
    let path = home
        .join(GROUP)
        .join(format!("newton_iteration_{name}"))
        .join(n_el.to_string())
        .join("new")
        .join("estimates.json");
    let modified = std::fs::metadata(&path)
        .and_then(|m| m.modified())
        .map_err(|_| "not measured".to_string())?;
    if modified < since {
        return Err("not run by this process".into());
    }
    let text = std::fs::read_to_string(&path).map_err(|e| e.to_string())?;
    let v: serde_json::Value = serde_json::from_str(&text).map_err(|e| e.to_string())?;
    let e = match v.get("slope") {
        Some(s) if !s.is_null() => s,
        _ => &v["mean"],
    };
    e["point_estimate"]
        .as_f64()
        .ok_or_else(|| "no point estimate".into())
}

/// The closing table: us per iteration and the ratio of 80 to 10 elements, per base.
fn table(since: SystemTime) {
    if !support::measuring() {
        return;
    }
    let home = support::criterion_home();
    for (name, _) in bases() {
        let mut line = format!("{name}:");
        let mut us = Vec::new();
        for n_el in ELEMENTS {
            match estimate_ns(&home, name, n_el, since) {
                Ok(ns) => {
                    line += &format!(" {n_el}: {:.2} us", ns / 1e3);
                    us.push((n_el, ns / 1e3));
                }
                Err(why) => line += &format!(" {n_el}: ({why})"),
            }
        }
        let at = |k| us.iter().find(|(n, _)| *n == k).map(|(_, t)| *t);
        if let (Some(a), Some(b)) = (at(10), at(80)) {
            line += &format!("; 80/10 = {:.1}x (target <= 10x)", b / a);
        }
        println!("{line}");
    }
}

fn main() {
    support::check_sizing();
    let since = SystemTime::now();
    let mut c = Criterion::default().configure_from_args();
    bench_newton(&mut c);
    bench_lu(&mut c);
    c.final_summary();
    table(since);
}
