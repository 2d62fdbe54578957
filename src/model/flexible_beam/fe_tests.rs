//! Tests of the finite-element model (`fe.rs`).
use nalgebra::{DMatrix, DVector};

use super::base::Base;
use super::fe::{Beam, Fe};
use crate::structural::SecondOrder;

const KANE: Beam = Beam {
    l: 10.0,
    ea: 2.8e7,
    ei: 1.4e4,
    rho_a: 1.2,
};

fn free_hub() -> Base {
    Base::Free {
        j_hub: 130.0,
        torque: 0.1,
        t_off: 5.0,
    }
}

/// A smooth, non-trivial state of `fe` (displacements ~1e-2, rates ~1e-1).
fn state(fe: &Fe, scale: f64) -> DVector<f64> {
    DVector::from_fn(fe.dim(), |i, _| scale * (0.37 * i as f64 + 0.2).sin())
}

/// Newton on the static residual at constant rate (v = a = 0, t after the spin-up), until the
/// correction is below 1e-13 m (the residual itself stalls at the round-off of EA times a
/// strain).
fn equilibrium(fe: &Fe, t: f64) -> DVector<f64> {
    let n = fe.dim();
    let (mut q, zero) = (DVector::zeros(n), DVector::zeros(n));
    let (mut r, mut s) = (DVector::zeros(n), DMatrix::zeros(n, n));
    for _ in 0..30 {
        fe.residual(t, &q, &zero, &zero, &mut r);
        fe.tangent(t, &q, &zero, &zero, 0.0, 0.0, 1.0, &mut s);
        let dq = s.clone().lu().solve(&r).unwrap();
        q -= &dq;
        if dq.norm() < 1e-13 {
            return q;
        }
    }
    panic!("no static equilibrium: |r| = {:e}", r.norm());
}

/// The tangent is the derivative of the residual in a, v and q, for a prescribed base during
/// the spin-up and for a free hub (central differences, relative 1e-6).
#[test]
fn tangent_is_the_derivative_of_the_residual() {
    for base in [Base::SpinUp { w: 6.0, t_up: 15.0 }, free_hub()] {
        let fe = Fe::new(KANE, 5, base).unwrap();
        let n = fe.dim();
        let (q, v, a) = (state(&fe, 0.02), state(&fe, 0.3), state(&fe, 0.5));
        let t = 7.0;
        for (which, c) in [
            (0, [1.0, 0.0, 0.0]),
            (1, [0.0, 1.0, 0.0]),
            (2, [0.0, 0.0, 1.0]),
        ] {
            let mut s = DMatrix::zeros(n, n);
            fe.tangent(t, &q, &v, &a, c[0], c[1], c[2], &mut s);
            // The residual is linear in a and quadratic in v (exact central differences with a
            // large step); in q the step balances truncation and round-off.
            let h = if which == 2 { 1e-6 } else { 1e-2 };
            for j in 0..n {
                let mut args = [a.clone(), v.clone(), q.clone()];
                let mut back = args.clone();
                args[which][j] += h;
                back[which][j] -= h;
                let (mut rp, mut rm) = (DVector::zeros(n), DVector::zeros(n));
                fe.residual(t, &args[2], &args[1], &args[0], &mut rp);
                fe.residual(t, &back[2], &back[1], &back[0], &mut rm);
                // Round-off of the residual's evaluation, amplified by the difference.
                let noise = 1e-14 * rp.norm().max(rm.norm()) / h;
                let col = (rp - rm) / (2.0 * h);
                let err = (&col - s.column(j)).norm();
                assert!(
                    err <= 1e-6 * s.norm().max(1.0) + noise,
                    "{base:?} d/d{} column {j}: {err:e} of {:e}",
                    ["a", "v", "q"][which],
                    s.norm()
                );
            }
        }
    }
}

/// The consistent mass matrix is symmetric positive definite and G is skew (assembled from
/// the residual's derivatives).
#[test]
fn mass_is_spd_and_gyroscopic_is_skew() {
    let fe = Fe::new(KANE, 6, Base::SpinUp { w: 4.0, t_up: 15.0 }).unwrap();
    let n = fe.dim();
    let z = DVector::zeros(n);
    let mut m = DMatrix::zeros(n, n);
    fe.tangent(0.0, &z, &z, &z, 1.0, 0.0, 0.0, &mut m);
    assert!((&m - m.transpose()).norm() <= 1e-14 * m.norm());
    assert!(m.clone().cholesky().is_some());
    // At t >= T the rate is W: d r / d v = 2 W G.
    let mut g = DMatrix::zeros(n, n);
    fe.tangent(20.0, &z, &z, &z, 0.0, 1.0, 0.0, &mut g);
    assert!((&g + g.transpose()).norm() <= 1e-14 * g.norm());
    assert!(g.norm() > 0.0);
}

/// A small static tip load bends the cantilever by P L^3 / (3 EI) (cubic elements are exact
/// at the nodes of a linear cantilever; the load keeps the geometric nonlinearity below 1e-9).
#[test]
fn static_tip_load_matches_beam_theory() {
    let fe = Fe::new(KANE, 4, Base::SpinUp { w: 4.0, t_up: 15.0 }).unwrap();
    let n = fe.dim();
    let p = 1e-3;
    let tip = n - 2;
    let (mut q, zero) = (DVector::zeros(n), DVector::zeros(n));
    let (mut r, mut s) = (DVector::zeros(n), DMatrix::zeros(n, n));
    for _ in 0..10 {
        fe.residual(0.0, &q, &zero, &zero, &mut r);
        r[tip] -= p;
        fe.tangent(0.0, &q, &zero, &zero, 0.0, 0.0, 1.0, &mut s);
        q -= s.clone().lu().solve(&r).unwrap();
    }
    let want = p * KANE.l.powi(3) / (3.0 * KANE.ei);
    let got = fe.tip_deflection(&q);
    assert!(
        (got / want - 1.0).abs() < 1e-6,
        "tip {got:e}, beam theory {want:e}"
    );
}

/// The in-plane frequencies of the rotating cantilever (hub radius 0): the lowest
/// eigenfrequency of the model linearised about its steady rotating equilibrium (Coriolis
/// included) against the flapwise values of the rotating uniform cantilever (Wright, Smith,
/// Thompson & Green 1982; Banerjee 2000: omega L^2 sqrt(rhoA/EI) = 3.6816, 4.1373, 5.5850,
/// 11.2023 at eta = Omega L^2 sqrt(rhoA/EI) = 1, 2, 4, 10), lowered by the in-plane softening
/// to sqrt(omega_flap^2 - Omega^2): within 0.3 % with 40 elements. The model converges to it
/// like h^2 at high rates (piecewise-constant element tension; measured at eta = 10: 1.09 %,
/// 0.31 %, 0.11 % low with 10, 20, 40 elements); Coriolis coupling moves it by 4e-4.
#[test]
fn rotating_frequencies_follow_centrifugal_stiffening() {
    let unit = (KANE.ei / (KANE.rho_a * KANE.l.powi(4))).sqrt();
    for (eta, flap) in [
        (0.0, 3.5160),
        (1.0, 3.6816),
        (2.0, 4.1373),
        (4.0, 5.5850),
        (10.0, 11.2023),
    ] {
        let w = eta * unit;
        let fe = Fe::new(KANE, 40, Base::SpinUp { w, t_up: 1.0 }).unwrap();
        let n = fe.dim();
        let t = 2.0;
        let q = equilibrium(&fe, t);
        let z = DVector::zeros(n);
        let (mut m, mut c, mut k) = (
            DMatrix::zeros(n, n),
            DMatrix::zeros(n, n),
            DMatrix::zeros(n, n),
        );
        fe.tangent(t, &q, &z, &z, 1.0, 0.0, 0.0, &mut m);
        fe.tangent(t, &q, &z, &z, 0.0, 1.0, 0.0, &mut c);
        fe.tangent(t, &q, &z, &z, 0.0, 0.0, 1.0, &mut k);
        let minv = m.try_inverse().unwrap();
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        a.view_mut((0, n), (n, n)).fill_with_identity();
        a.view_mut((n, 0), (n, n)).copy_from(&(-&minv * &k));
        a.view_mut((n, n), (n, n)).copy_from(&(-&minv * &c));
        let lowest = a
            .complex_eigenvalues()
            .iter()
            .map(|l| l.im.abs())
            .filter(|x| *x > 1e-6)
            .fold(f64::INFINITY, f64::min);
        let want = (flap * flap - eta * eta).sqrt() * unit;
        assert!(
            (lowest / want - 1.0).abs() < 3e-3,
            "eta {eta}: model {lowest:.5} rad/s, theory {want:.5} rad/s"
        );
    }
}

/// The energy and momentum of a state are those of its Lagrangian: T = 1/2 v^T (dr/da) v
/// for a base at rest, and the momentum of a rigid spin is J_total omega.
#[test]
fn energy_and_momentum_of_simple_states() {
    let fe = Fe::new(KANE, 4, free_hub()).unwrap();
    let n = fe.dim();
    let z = DVector::zeros(n);
    // A rigid spin at 0.01 rad/s of the undeformed beam: H = (J_hub + rhoA L^3/3) omega.
    let mut v = DVector::zeros(n);
    v[0] = 0.01;
    let h = fe.momentum(10.0, &z, &v);
    let want = (130.0 + KANE.rho_a * KANE.l.powi(3) / 3.0) * 0.01;
    assert!((h / want - 1.0).abs() < 1e-12, "{h} vs {want}");
    let (kin, strain) = fe.energy(10.0, &z, &v);
    assert!((kin / (0.5 * want * 0.01) - 1.0).abs() < 1e-12);
    assert_eq!(strain, 0.0);
}

/// The tip deflection of `fe` over the spin-up with `step`, sampled every `every` steps.
fn spin_up_tip(
    fe: &Fe,
    h: f64,
    t_end: f64,
    mut step: impl FnMut(
        &Fe,
        f64,
        f64,
        &mut crate::structural::state::State,
        &mut crate::integrate::Stats,
    ) -> Result<(), crate::integrate::Failure>,
) -> (Vec<f64>, crate::integrate::Stats) {
    use crate::structural::state::State;
    let mut st = State::for_system(fe);
    let mut stats = crate::integrate::Stats::default();
    let n = (t_end / h).round() as usize;
    let mut tip = vec![0.0];
    for k in 0..n {
        step(fe, k as f64 * h, h, &mut st, &mut stats).unwrap();
        tip.push(fe.tip_deflection(&st.q));
    }
    (tip, stats)
}

/// The corotational model on Kane's spin-up to W = 4 rad/s (above the first bending
/// frequency) stays bounded with the structural integrators, Newmark and generalized-alpha
/// agree with each other and with Newmark at half the step within 1 % of the peak tip
/// deflection, and the deflection lags the rotation (negative) during the spin-up.
#[test]
fn spin_up_stays_bounded_and_integrators_agree() {
    use crate::structural::gen_alpha::GenAlpha;
    use crate::structural::method::Method;
    use crate::structural::newmark::Newmark;
    use crate::structural::newton::NewtonOptions;
    let fe = Fe::new(KANE, 10, Base::SpinUp { w: 4.0, t_up: 15.0 }).unwrap();
    let t_end = 20.0;
    let run_newmark = |h: f64| {
        let mut m = Newmark::new(NewtonOptions::default()).unwrap();
        spin_up_tip(&fe, h, t_end, |mut s, t, h, st, stats| {
            m.step(&mut s, t, h, st, stats)
        })
    };
    let (a, stats) = run_newmark(1e-2);
    let (b, _) = run_newmark(5e-3);
    let mut g = GenAlpha::new(0.9, NewtonOptions::default()).unwrap();
    let (c, _) = spin_up_tip(&fe, 1e-2, t_end, |mut s, t, h, st, stats| {
        g.step(&mut s, t, h, st, stats)
    });
    let peak = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = |x: &[f64], y: &[f64], stride: usize| {
        x.iter()
            .enumerate()
            .map(|(i, v)| (v - y[i * stride]).abs())
            .fold(0.0f64, f64::max)
    };
    let (d_half, d_ga) = (diff(&a, &b, 2), diff(&a, &c, 1));
    eprintln!(
        "spin-up W=4, 10 elements: peak |v_tip| {peak:.4e} m, min {:.4e} m; newmark 1e-2 vs 5e-3: {d_half:.2e} m; vs gen_alpha: {d_ga:.2e} m; {} newton iterations in {} steps",
        a.iter().cloned().fold(f64::INFINITY, f64::min),
        stats.newton_iters,
        stats.steps
    );
    assert!(peak < 1.0 && peak > 1e-3, "peak {peak}");
    assert!(a[750] < 0.0, "the tip lags during the spin-up: {}", a[750]);
    assert!(d_half < 0.01 * peak && d_ga < 0.01 * peak);
}

/// The tangent written into the banded iteration matrix (the pattern the model declares,
/// with the free hub's border) equals the dense tangent entry for entry, bit for bit, for a
/// prescribed base and a free hub at several element counts, and nothing falls outside the
/// pattern (the matrix factors).
#[test]
fn banded_tangent_equals_the_dense_one() {
    use crate::math::lu::LinearSolve;
    use crate::math::tangent::Tangent;
    for base in [Base::SpinUp { w: 6.0, t_up: 15.0 }, free_hub()] {
        for n_el in [8, 13, 30] {
            let fe = Fe::new(KANE, n_el, base).unwrap();
            let n = fe.dim();
            let (q, v, a) = (state(&fe, 0.02), state(&fe, 0.3), state(&fe, 0.5));
            let c = [1.0, 0.5e-2, 0.25e-4];
            let mut dense = DMatrix::zeros(n, n);
            fe.tangent(7.0, &q, &v, &a, c[0], c[1], c[2], &mut dense);
            let mut s = Tangent::new(n, fe.pattern());
            assert!(s.is_banded(), "{n_el} elements");
            fe.tangent_into(7.0, &q, &v, &a, c[0], c[1], c[2], &mut s);
            for i in 0..n {
                for j in 0..n {
                    assert_eq!(s.get(i, j), dense[(i, j)], "({i}, {j}), {n_el} elements");
                }
            }
            s.factor().unwrap();
        }
    }
}
