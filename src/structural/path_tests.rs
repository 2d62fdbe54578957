//! Tests of the path-dependent kind of structural system (`path.rs`, `equilibrium.rs`,
//! `krylov_newton.rs`, `path_step.rs`, `midpoint.rs`) on a chain of masses joined by links,
//! each link an elastic spring beside an elastic-perfectly-plastic one (so the tangent stays
//! positive when the plastic spring yields): the three solution algorithms reach one
//! equilibrium, a failed step reverts, Newmark on a linear chain is the same scheme on both
//! kinds of system, the midpoint rule closes the energy balance of a yielding chain, and the
//! four methods converge at order 2.
use nalgebra::{DMatrix, DVector};

use super::SecondOrder;
use super::equilibrium::{Equilibrium, Newton, NewtonLineSearch};
use super::gen_alpha::GenAlpha;
use super::hht::Hht;
use super::krylov_newton::KrylovNewton;
use super::method::Method;
use super::midpoint::Midpoint;
use super::newmark::Newmark;
use super::newton::NewtonOptions;
use super::path::{PathDependent, PathFailure, Prescribed};
use super::path_step::Path;
use super::state::State;
use crate::integrate::Stats;

/// A chain of `n` nodes on a line, link `i` joining node `i - 1` (the ground for `i = 0`) to
/// node `i`: an elastic spring `k_e` beside an elastic-perfectly-plastic one (`k_p`, yield
/// force `f_y`), whose plastic elongations are the path's memory.
#[derive(Clone)]
struct Chain {
    k_e: f64,
    k_p: f64,
    f_y: f64,
    u: DVector<f64>,
    u_c: DVector<f64>,
    u_mark: DVector<f64>,
    /// Plastic elongations (trial, committed) and the work done on each link.
    plastic: DVector<f64>,
    plastic_c: DVector<f64>,
    force_c: DVector<f64>,
    work_c: f64,
    f: DVector<f64>,
    k: DMatrix<f64>,
    fresh: bool,
}

impl Chain {
    fn new(n: usize, k_e: f64, k_p: f64, f_y: f64) -> Self {
        let z = DVector::zeros(n);
        Chain {
            k_e,
            k_p,
            f_y,
            u: z.clone(),
            u_c: z.clone(),
            u_mark: z.clone(),
            plastic: z.clone(),
            plastic_c: z.clone(),
            force_c: z.clone(),
            work_c: 0.0,
            f: z,
            k: DMatrix::zeros(n, n),
            fresh: false,
        }
    }

    fn elongation(u: &DVector<f64>, i: usize) -> f64 {
        u[i] - if i == 0 { 0.0 } else { u[i - 1] }
    }

    /// Link `i`'s force at the trial configuration, its plastic elongation and tangent.
    fn link(&self, i: usize) -> (f64, f64, f64) {
        let e = Self::elongation(&self.u, i);
        let trial = self.k_p * (e - self.plastic_c[i]);
        let (fp, ep, kp) = if trial.abs() > self.f_y {
            let fp = self.f_y * trial.signum();
            (fp, e - fp / self.k_p, 0.0)
        } else {
            (trial, self.plastic_c[i], self.k_p)
        };
        (self.k_e * e + fp, ep, self.k_e + kp)
    }
}

impl PathDependent for Chain {
    fn dim(&self) -> usize {
        self.u.len()
    }
    fn assemble(&mut self) -> Result<(), PathFailure> {
        self.f.fill(0.0);
        self.k.fill(0.0);
        for i in 0..self.dim() {
            let (f, ep, k) = self.link(i);
            self.plastic[i] = ep;
            self.f[i] += f;
            self.k[(i, i)] += k;
            if i > 0 {
                self.f[i - 1] -= f;
                self.k[(i - 1, i - 1)] += k;
                self.k[(i, i - 1)] -= k;
                self.k[(i - 1, i)] -= k;
            }
        }
        self.fresh = true;
        Ok(())
    }
    fn assembled(&self) -> bool {
        self.fresh
    }
    fn internal_force(&self) -> &DVector<f64> {
        &self.f
    }
    fn stiffness(&self) -> &DMatrix<f64> {
        &self.k
    }
    fn apply(&mut self, dx: &DVector<f64>, eta: f64) {
        self.u.axpy(eta, dx, 1.0);
        self.fresh = false;
    }
    fn mark(&mut self) {
        self.u_mark.copy_from(&self.u);
    }
    fn return_to_mark(&mut self) {
        self.u.copy_from(&self.u_mark);
        self.fresh = false;
    }
    fn commit(&mut self) {
        self.work_c = self.work();
        for i in 0..self.dim() {
            self.force_c[i] = self.link(i).0;
        }
        self.u_c.copy_from(&self.u);
        self.plastic_c.copy_from(&self.plastic);
        self.fresh = false;
    }
    fn revert(&mut self) {
        self.u.copy_from(&self.u_c);
        self.plastic.copy_from(&self.plastic_c);
        self.fresh = false;
    }
    fn additive(&self, _: usize) -> bool {
        true
    }
    fn displacement(&self, i: usize) -> f64 {
        self.u[i]
    }
    fn committed_displacement(&self, i: usize) -> f64 {
        self.u_c[i]
    }
    /// The links' work by the trapezoid of their forces over the step's elongation.
    fn work(&self) -> f64 {
        let mut w = self.work_c;
        for i in 0..self.dim() {
            let de = Self::elongation(&self.u, i) - Self::elongation(&self.u_c, i);
            w += 0.5 * (self.force_c[i] + self.link(i).0) * de;
        }
        w
    }
}

/// The chain `M a + K q = -M 1 s(t)` of an elastic chain as a second-order system.
struct LinearChain {
    m: DVector<f64>,
    k: DMatrix<f64>,
    series: fn(f64) -> f64,
}

impl SecondOrder for LinearChain {
    fn dim(&self) -> usize {
        self.m.len()
    }
    fn residual(
        &self,
        t: f64,
        q: &DVector<f64>,
        _v: &DVector<f64>,
        a: &DVector<f64>,
        r: &mut DVector<f64>,
    ) {
        r.copy_from(&(&self.k * q));
        for i in 0..self.m.len() {
            r[i] += self.m[i] * (a[i] + (self.series)(t));
        }
    }
    #[allow(clippy::too_many_arguments)]
    fn tangent(
        &self,
        _t: f64,
        _q: &DVector<f64>,
        _v: &DVector<f64>,
        _a: &DVector<f64>,
        c_m: f64,
        _c_c: f64,
        c_k: f64,
        s: &mut DMatrix<f64>,
    ) {
        s.copy_from(&(&self.k * c_k));
        for i in 0..self.m.len() {
            s[(i, i)] += c_m * self.m[i];
        }
    }
}

fn ground(t: f64) -> f64 {
    3.0 * (2.0 * t).sin()
}

type Shaken = Path<Chain, Newton, fn(f64) -> f64>;

/// The chain of 3 nodes, masses 1, 2, 1, under the ground motion, solved by Newton.
fn shaken(chain: Chain, a0: f64) -> Shaken {
    let mass = DVector::from_vec(vec![1.0, 2.0, 1.0]);
    let pattern = -&mass;
    let newton = Newton::new(1e-24, 30).unwrap();
    let series: fn(f64) -> f64 = ground;
    Path::new(chain, newton, mass, a0, DVector::zeros(3), pattern, series).unwrap()
}

/// Runs `method` on `p` to `t_end` at step `h`; the displacements after every step.
fn run<M: Method<Shaken>>(mut method: M, mut p: Shaken, h: f64, t_end: f64) -> Vec<DVector<f64>> {
    let mut stats = Stats::default();
    let mut st = method.new_state(&p);
    method.init(&mut p, 0.0, &mut st, &mut stats).unwrap();
    let n = (t_end / h).round() as usize;
    let mut out = vec![st.q.clone()];
    for k in 0..n {
        method
            .step(&mut p, k as f64 * h, h, &mut st, &mut stats)
            .unwrap();
        out.push(st.q.clone());
    }
    out
}

/// Newton, the line search and Krylov-accelerated Newton bring a yielding chain under a
/// load past its yield to one equilibrium (within 1e-10 of the displacement), each step
/// committed; Newton on the elastic chain needs two iterations (one solves, one confirms).
#[test]
fn the_three_algorithms_reach_one_equilibrium() {
    let f = DVector::from_vec(vec![0.0, 0.0, 2.5]);
    fn solve<E: Equilibrium<Chain>>(mut e: E, f: &DVector<f64>) -> (DVector<f64>, usize) {
        let mut c = Chain::new(3, 1.0, 10.0, 1.0);
        let mut iterations = 0;
        for j in 1..=5 {
            iterations += e.step(&mut c, &(f * (j as f64 / 5.0)), None, None).unwrap();
        }
        (c.u.clone(), iterations)
    }
    let (a, ia) = solve(Newton::new(1e-24, 30).unwrap(), &f);
    let (b, ib) = solve(NewtonLineSearch::new(1e-24, 30).unwrap(), &f);
    let (k, ik) = solve(KrylovNewton::new(1e-24, 60).unwrap(), &f);
    eprintln!(
        "yielding chain: u {:?}; iterations newton {ia}, line search {ib}, krylov {ik}",
        a.as_slice()
    );
    assert!(
        (&a - &b).amax() < 1e-10 && (&a - &k).amax() < 1e-10,
        "{a} {b} {k}"
    );
    // Every link carries 2.5 N, above its plastic spring's 1 N: all yield.
    assert!(a[0] > 1.5 - 1e-9 && a[0] < 1.5 + 1e-9, "{}", a[0]);
    let mut elastic = Chain::new(3, 1.0, 10.0, 1e9);
    let its = Newton::new(1e-24, 30)
        .unwrap()
        .step(&mut elastic, &f, None, None)
        .unwrap();
    assert_eq!(its, 2);
}

/// Displacement control: the prescribed unknown reaches its value exactly and the load that
/// holds it is the chain's internal force there; a step that cannot converge within its
/// limit is a typed failure that leaves the committed state.
#[test]
fn prescribed_steps_and_failures() {
    let mut c = Chain::new(2, 1.0, 10.0, 1.0);
    let zero = DVector::zeros(2);
    let mut newton = Newton::new(1e-24, 30).unwrap();
    newton
        .step(&mut c, &zero, Some(Prescribed { dof: 1, value: 0.5 }), None)
        .unwrap();
    assert_eq!(c.displacement(1), 0.5);
    assert!(
        c.internal_force()[0].abs() < 1e-10,
        "{}",
        c.internal_force()[0]
    );
    let before = c.u.clone();
    let mut capped = Newton::new(1e-24, 1).unwrap();
    let f = DVector::from_vec(vec![0.0, 5.0]);
    let e = capped.step(&mut c, &f, None, None).unwrap_err();
    assert!(
        matches!(e, PathFailure::NoConvergence { iterations: 1, .. }),
        "{e}"
    );
    assert_eq!(c.u, before);
    assert!(Newton::new(0.0, 3).is_err() && KrylovNewton::new(1e-9, 0).is_err());
}

/// Newmark on the elastic chain as a path-dependent structure (iterating on displacements)
/// and on the same chain as a second-order system (iterating on accelerations) is one
/// scheme: the displacements agree within 1e-10 of their peak over 400 steps.
#[test]
fn newmark_is_one_scheme_on_both_kinds() {
    let h = 0.02;
    let path = run(
        Newmark::new(NewtonOptions::default()).unwrap(),
        shaken(Chain::new(3, 1.0, 10.0, 1e9), 0.0),
        h,
        8.0,
    );
    let mut p = shaken(Chain::new(3, 1.0, 10.0, 1e9), 0.0);
    p.system.assemble().unwrap();
    let mut lin = LinearChain {
        m: DVector::from_vec(vec![1.0, 2.0, 1.0]),
        k: p.system.stiffness().clone(),
        series: ground,
    };
    let mut m = Newmark::new(NewtonOptions {
        tol: 1e-13,
        max_iters: 25,
    })
    .unwrap();
    let (mut st, mut stats) = (State::for_system(&lin), Stats::default());
    m.init(&mut lin, 0.0, &mut st, &mut stats).unwrap();
    let mut worst = 0.0f64;
    let peak = path.iter().fold(0.0f64, |p, q| p.max(q.amax()));
    for (k, q) in path.iter().enumerate().skip(1) {
        m.step(&mut lin, (k - 1) as f64 * h, h, &mut st, &mut stats)
            .unwrap();
        worst = worst.max((&st.q - q).amax());
    }
    eprintln!(
        "newmark, path against second-order: {:.3e} of the peak {peak:.4}",
        worst / peak
    );
    assert!(worst < 1e-10 * peak);
}

/// The midpoint rule closes the energy balance of the damped, yielding chain: kinetic +
/// links' work + damping = input, within 1e-9 of the input at every step of 400.
#[test]
fn midpoint_closes_the_energy_balance_while_yielding() {
    let mut p = shaken(Chain::new(3, 1.0, 10.0, 0.5), 0.1);
    let (mut m, mut stats) = (Midpoint, Stats::default());
    let mut st = Method::new_state(&m, &p);
    m.init(&mut p, 0.0, &mut st, &mut stats).unwrap();
    let mut worst = 0.0f64;
    for k in 0..400 {
        m.step(&mut p, k as f64 * 0.02, 0.02, &mut st, &mut stats)
            .unwrap();
        let balance = p.kinetic() + p.system.work_c + p.damping() - p.input();
        worst = worst.max(balance.abs() / p.input().abs().max(1e-300));
    }
    let yielded = p.system.plastic_c.amax();
    eprintln!("midpoint: balance {worst:.3e} of the input; plastic elongation {yielded:.3}");
    assert!(yielded > 0.1, "the chain must yield: {yielded}");
    assert!(worst < 1e-9, "{worst:e}");
}

/// Each of the four methods converges at second order on the yielding chain: the
/// differences of successive halvings (h = 0.04 .. 0.005) of the displacement at t = 2 fall
/// by 16 over two halvings (the observed order within 0.35 of 2).
#[test]
fn the_four_methods_are_second_order_on_paths() {
    fn ladder<M: Method<Shaken>>(make: impl Fn() -> M) -> f64 {
        let ends: Vec<DVector<f64>> = [0.04, 0.02, 0.01, 0.005]
            .iter()
            .map(|&h| {
                run(make(), shaken(Chain::new(3, 1.0, 10.0, 0.5), 0.1), h, 2.0)
                    .pop()
                    .unwrap()
            })
            .collect();
        let d: Vec<f64> = (0..3).map(|i| (&ends[i] - &ends[i + 1]).amax()).collect();
        (d[0] / d[2]).log2() / 2.0
    }
    let o = NewtonOptions::default;
    let orders = [
        ("newmark", ladder(|| Newmark::new(o()).unwrap())),
        ("hht", ladder(|| Hht::new(-0.05, o()).unwrap())),
        ("gen_alpha", ladder(|| GenAlpha::new(0.9, o()).unwrap())),
        ("midpoint", ladder(|| Midpoint)),
    ];
    eprintln!("orders on the yielding chain: {orders:.3?}");
    for (name, p) in orders {
        assert!((p - 2.0).abs() < 0.35, "{name}: {p}");
    }
}
