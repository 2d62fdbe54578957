//! Dense LU, factor plus one solve, at the orders of the crate's Newton systems: the
//! crate's own `math::lu::DenseLu` (both substitution arithmetics) against nalgebra's
//! `linalg::LU`, dynamic (its matrix taken by value: a copy and an allocation per factor)
//! and fixed-size (stack, for the orders known at compile time here: 6, 12, 18). Orders: 6,
//! 12, 18 (`6 s`, the rigid body's Gauss methods with s = 1, 2, 3), 39 (heavy_top's gauss6),
//! 18, 33, 63, 123, 243 (the beam's tangent, `3 (N + 1)` for N = 5 ... 80 elements) and 66
//! (the fiber column's `6 nodes`, 11 nodes). The matrix is a fixed random one with a
//! dominant diagonal of random sign, so that pivoting swaps rows; each iteration copies it
//! into the factor's buffer first, as a Newton step fills its matrix. Group `lu`, ids
//! `<impl>/<n>`: `cargo bench --bench lu` (about a minute). Where it fails: the timing is of
//! one matrix per order; a matrix with another sparsity (the beam's is banded) factors at
//! the same dense cost here.
mod support;

use criterion::{BenchmarkId, Criterion};
use mbdbench::math::lu::{DenseLu, LinearSolve, Substitution};
use nalgebra::{DMatrix, DVector, SMatrix, SVector};
use std::hint::black_box;
use std::time::Duration;

/// A deterministic matrix with a dominant diagonal of alternating sign (64-bit LCG).
fn matrix(n: usize) -> DMatrix<f64> {
    let mut next = support::uniform();
    DMatrix::from_fn(n, n, |i, j| {
        next()
            + if i == j {
                2.0 * if i % 2 == 0 { 1.0 } else { -1.0 }
            } else {
                0.0
            }
    })
}

/// nalgebra's fixed-size LU at order `$n` (a macro: its generic bounds want a literal).
macro_rules! fixed {
    ($g:expr, $n:literal) => {{
        let a: SMatrix<f64, $n, $n> = SMatrix::from_iterator(matrix($n).iter().copied());
        let b = SVector::<f64, $n>::repeat(1.0);
        $g.bench_function(BenchmarkId::new("nalgebra_fixed", $n), |bch| {
            bch.iter(|| {
                let mut x = b;
                black_box(black_box(a).lu().solve_mut(&mut x));
                x
            })
        });
    }};
}

fn main() {
    let mut c = Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1))
        .sample_size(20)
        .configure_from_args();
    let mut g = c.benchmark_group("lu");
    for n in [6, 12, 18, 33, 39, 63, 66, 123, 243] {
        let a = matrix(n);
        let b = DVector::<f64>::repeat(n, 1.0);
        for (name, sub) in [
            ("divide", Substitution::Divide),
            ("reciprocal", Substitution::Reciprocal),
        ] {
            let mut lu = DenseLu::with_substitution(n, sub);
            let mut x = b.clone();
            g.bench_function(BenchmarkId::new(name, n), |bch| {
                bch.iter(|| {
                    lu.matrix_mut().copy_from(black_box(&a));
                    lu.factor().unwrap();
                    x.copy_from(&b);
                    lu.solve(x.as_mut_slice()).unwrap();
                    black_box(x[0])
                })
            });
        }
        let mut x = b.clone();
        g.bench_function(BenchmarkId::new("nalgebra_dynamic", n), |bch| {
            bch.iter(|| {
                x.copy_from(&b);
                black_box(black_box(&a).clone().lu().solve_mut(&mut x));
                black_box(x[0])
            })
        });
    }
    fixed!(g, 6);
    fixed!(g, 12);
    fixed!(g, 18);
    g.finish();
}
