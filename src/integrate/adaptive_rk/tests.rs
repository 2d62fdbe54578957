//! Tests of the adaptive pairs (`mod.rs`): error proportional to the tolerance, exact work
//! counts, the continuation rule, landing on sample times, typed failures (blow-up, NaN field,
//! work limits, tolerance below round-off), RKMK on SO(3), and the dense output's order, end
//! conditions, work and bitwise reproducibility.
use super::*;
use crate::integrate::explicit_rk::{combine, rkmk_stages};
use crate::integrate::test_support::*;
use nalgebra::{Vector1, Vector2, Vector4};

/// Integrates over `[0, t_end]` in `m` equal sample intervals.
fn sampled<S: ErrorScale>(
    ad: &mut AdaptiveRk<S>,
    sys: &S,
    x: &mut S::State,
    t_end: f64,
    m: usize,
    st: &mut Stats,
) -> Result<(), Failure> {
    for k in 0..m {
        let ta = t_end * k as f64 / m as f64;
        let tb = t_end * (k + 1) as f64 / m as f64;
        ad.advance(sys, ta, tb, x, st, &Limits::default())?;
        assert_eq!(ad.time(), Some(tb), "lands exactly on the sample time");
    }
    Ok(())
}

/// On Kepler (e = 0.5, five periods sampled once per period; exact solution at each
/// sample = the initial state) the global error of both pairs falls with the tolerance
/// about proportionally: log-log slope in [0.8, 1.2] over 6 decades (local error per
/// step ~ tol with local extrapolation, hence global error ~ tol; measured 1.11 and 0.92).
/// The constant grows with the span (the phase error grows linearly): error <= 1e4 tol
/// (measured 2e2 .. 9e3).
#[test]
fn error_proportional_to_tol() {
    let sys = Kepler::new(0.5);
    let tols = [1e-6, 1e-8, 1e-10, 1e-12];
    for dop853 in [false, true] {
        let mut errs = Vec::new();
        for &tol in &tols {
            let mut ad = if dop853 {
                AdaptiveRk::dop853(tol)
            } else {
                AdaptiveRk::dopri5(tol)
            };
            let mut x = sys.initial();
            let mut st = Stats::default();
            sampled(&mut ad, &sys, &mut x, 5.0 * sys.period(), 5, &mut st).unwrap();
            let e = (x - sys.initial()).norm();
            eprintln!("{} tol {tol:e}: error {e:.3e}, {st:?}", ad.tab.rk.name);
            assert!(e < 1e4 * tol);
            errs.push(e);
        }
        let slope = (errs[0] / errs[3]).log10() / 6.0;
        eprintln!("log-log slope {slope:.3}");
        assert!((0.8..=1.2).contains(&slope), "slope {slope}");
    }
}

/// RHS evaluations are counted exactly: a fresh dopri5 run costs 2 + 6 (accepted +
/// rejected), dop853 2 + 11 (accepted + rejected) + accepted; an eccentric orbit
/// (e = 0.9) forces rejections, which are counted.
#[test]
fn counts_and_rejections() {
    let sys = Kepler::new(0.9);
    for dop853 in [false, true] {
        let mut ad = if dop853 {
            AdaptiveRk::dop853(1e-6)
        } else {
            AdaptiveRk::dopri5(1e-6)
        };
        let mut x = sys.initial();
        let mut st = Stats::default();
        ad.advance(&sys, 0.0, sys.period(), &mut x, &mut st, &Limits::default())
            .unwrap();
        eprintln!("{}: {st:?}", ad.tab.rk.name);
        assert!(st.rejected > 0);
        let expect = if dop853 {
            2 + 11 * (st.steps + st.rejected) + st.steps
        } else {
            2 + 6 * (st.steps + st.rejected)
        };
        assert_eq!(st.rhs_evals, expect);
        assert_eq!(st.normalizations, 0);
    }
}

/// A contiguous second call keeps the step size and first stage (no restart cost); a
/// call from another time restarts; the landing time is exactly `t1`.
#[test]
fn state_kept_across_calls() {
    let sys = Oscillator;
    let mut ad = AdaptiveRk::dopri5(1e-8);
    let mut x = sys.initial();
    let mut st = Stats::default();
    let lim = Limits::default();
    ad.advance(&sys, 0.0, 1.0, &mut x, &mut st, &lim).unwrap();
    let h = ad.step_size();
    assert!(h > 0.01);
    let mut st2 = Stats::default();
    ad.advance(&sys, 1.0, 1.0 + 0.5 * h, &mut x, &mut st2, &lim)
        .unwrap();
    assert_eq!((st2.steps, st2.rejected, st2.rhs_evals), (1, 0, 6));
    assert_eq!(
        ad.step_size(),
        h,
        "the clipped step does not shrink the stored one"
    );
    assert!((x - sys.exact(1.0 + 0.5 * h)).norm() < 1e-7);
    let mut st3 = Stats::default();
    let mut y = sys.initial();
    ad.advance(&sys, 0.0, 0.3, &mut y, &mut st3, &lim).unwrap();
    assert_eq!(st3.rhs_evals, 2 + 6 * (st3.steps + st3.rejected));
    assert_eq!(ad.time(), Some(0.3));
}

/// Sampling a run at 100 times gives the same accuracy as the exact solution requires
/// (error <= 100 tol at each sample on the oscillator) and lands on every sample time.
#[test]
fn sampled_run_lands_on_samples() {
    let sys = Oscillator;
    let mut ad = AdaptiveRk::dop853(1e-9);
    let mut x = sys.initial();
    let mut st = Stats::default();
    let lim = Limits::default();
    for k in 0..100 {
        let (ta, tb) = (0.07 * k as f64, 0.07 * (k + 1) as f64);
        ad.advance(&sys, ta, tb, &mut x, &mut st, &lim).unwrap();
        assert_eq!(ad.time(), Some(tb));
        assert!((x - sys.exact(tb)).norm() < 100.0 * 1e-9, "t = {tb}");
    }
    // Backward integration returns to the start.
    let mut ad = AdaptiveRk::dopri5(1e-10);
    ad.advance(&sys, 7.0, 0.0, &mut x, &mut st, &lim).unwrap();
    assert!((x - sys.initial()).norm() < 1e-7);
}

/// `y' = y^2`, `y(0) = 1` blows up at t = 1: the run ends with `step_size_underflow`
/// near t = 1 with a huge y (the step shrinks like the distance to the numerical
/// blow-up time, which differs from 1 by about the accumulated relative error, ~ tol).
#[test]
fn blowup_gives_underflow() {
    let sys = Blowup { nan: false };
    for mut ad in [AdaptiveRk::dopri5(1e-6), AdaptiveRk::dop853(1e-6)] {
        let mut x = Vector1::new(1.0);
        let mut st = Stats::default();
        let e = ad
            .advance(&sys, 0.0, 2.0, &mut x, &mut st, &Limits::default())
            .unwrap_err();
        eprintln!("{}: {e:?} y = {:e} {st:?}", ad.tab.rk.name, x[0]);
        assert_eq!(e.kind, FailureKind::StepSizeUnderflow);
        assert!((e.t - 1.0).abs() < 1e-5 && x[0] > 1e12);
        assert_eq!(ad.time(), None);
    }
}

/// A tolerance below round-off fails at once with `step_size_underflow` (before, a
/// spinning body at tol 1e-73 crawled on ~1e-20 s steps towards its work limit).
#[test]
fn tolerance_below_round_off_is_refused() {
    let cases = crate::catalogue::embedded().unwrap();
    let c = cases.iter().find(|c| c.name == "gimbal_lock").unwrap();
    let p = crate::model::rigid_body::plan::scene_plan(c, c.scene("spin_d1e-2").unwrap()).unwrap();
    for integrator in ["dopri5", "dop853"] {
        let v = crate::model::rigid_body::registry::find("so3", integrator, "body").unwrap();
        let out = (v.run)(&p.setup, 1.7e-73).unwrap();
        let f = out.failure.unwrap();
        assert_eq!(out.stats.steps, 0, "refused before any step");
        assert_eq!(
            (f.kind, f.t),
            (FailureKind::StepSizeUnderflow, 0.0),
            "{f:?}"
        );
        assert!(f.message.contains("round-off"), "{f:?}");
        // At the floor itself the run goes ahead.
        let out = (v.run)(&p.setup, MIN_TOL).unwrap();
        assert!(
            out.failure.as_ref().is_none_or(|f| f.t > 0.0),
            "{:?}",
            out.failure
        );
    }
}

/// A NaN vector field is rejected until the step underflows (never accepted).
#[test]
fn nan_field_never_accepted() {
    let sys = Blowup { nan: true };
    let mut x = Vector1::new(1.0);
    let mut st = Stats::default();
    let mut ad = AdaptiveRk::dopri5(1e-6);
    let e = ad
        .advance(&sys, 1.0, 2.0, &mut x, &mut st, &Limits::default())
        .unwrap_err();
    assert_eq!(e.kind, FailureKind::StepSizeUnderflow);
    assert_eq!(st.steps, 0);
    assert_eq!(x[0], 1.0);
}

/// Tiny budgets give `work_limit` failures (steps, then RHS evaluations, never passed).
#[test]
fn work_limits() {
    let sys = Kepler::new(0.5);
    let mut x = sys.initial();
    let mut st = Stats::default();
    let lim = Limits {
        max_steps: 5,
        max_rhs_evals: u64::MAX,
        max_adaptive_rhs_evals: u64::MAX,
    };
    let e = AdaptiveRk::dopri5(1e-8)
        .advance(&sys, 0.0, 6.0, &mut x, &mut st, &lim)
        .unwrap_err();
    assert_eq!(e.kind, FailureKind::WorkLimit);
    assert_eq!(st.steps, 6);
    let mut st = Stats::default();
    let lim = Limits {
        max_steps: u64::MAX,
        max_rhs_evals: 100,
        max_adaptive_rhs_evals: u64::MAX,
    };
    let e = AdaptiveRk::dop853(1e-8)
        .advance(&sys, 0.0, 6.0, &mut sys.initial(), &mut st, &lim)
        .unwrap_err();
    assert_eq!(e.kind, FailureKind::WorkLimit);
    // Stopped before an attempt that could pass the budget (dop853: 17 at most).
    assert!(
        st.rhs_evals <= 100 && st.rhs_evals > 100 - 17,
        "{}",
        st.rhs_evals
    );
}

/// RKMK dopri5/dop853 on SO(3) (free rotor, 10 s in one call): the error against the
/// independent reference falls with the tolerance (slope in [0.8, 1.2] over 6 decades;
/// measured 0.99 and 1.04) and stays below 10 tol (measured 1 .. 4.3 tol); every
/// accepted step is normalized.
#[test]
fn rotor_rkmk_adaptive() {
    let sys = rotor_system();
    let t_end = 10.0;
    let reference = rotor_reference(&sys, t_end);
    let tols = [1e-5, 1e-7, 1e-9, 1e-11];
    for dop853 in [false, true] {
        let mut errs = Vec::new();
        for &tol in &tols {
            let mut ad = if dop853 {
                AdaptiveRk::dop853(tol)
            } else {
                AdaptiveRk::dopri5(tol)
            };
            let mut x = rotor_initial(&sys);
            let mut st = Stats::default();
            ad.advance(&sys, 0.0, t_end, &mut x, &mut st, &Limits::default())
                .unwrap();
            let e = rotor_distance(&x, &reference);
            eprintln!("rotor {} tol {tol:e}: error {e:.3e} {st:?}", ad.tab.rk.name);
            assert_eq!(st.normalizations, st.steps);
            assert!(e < 10.0 * tol);
            errs.push(e);
        }
        let slope = (errs[0] / errs[3]).log10() / 6.0;
        eprintln!("rotor slope {slope:.3}");
        assert!((0.8..=1.2).contains(&slope));
    }
}

/// At tol 1e-13 dop853 on SO(3) agrees with the independent reference to 10 tol.
#[test]
fn rotor_tight_tolerance() {
    let sys = rotor_system();
    let reference = rotor_reference(&sys, 2.0);
    let mut ad = AdaptiveRk::dop853(1e-13);
    let mut x = rotor_initial(&sys);
    let mut st = Stats::default();
    ad.advance(&sys, 0.0, 2.0, &mut x, &mut st, &Limits::default())
        .unwrap();
    let e = rotor_distance(&x, &reference);
    eprintln!("rotor dop853 tol 1e-13: error {e:.3e} {st:?}");
    assert!(e < 1e-12);
}

/// One step of signed size `dh` from `(t, x)` without error control, followed by all the
/// dense output's appended stages; returns the new state (unnormalized).
fn one_step<S: ErrorScale>(
    ad: &mut AdaptiveRk<S>,
    sys: &S,
    t: f64,
    dh: f64,
    x: &S::State,
) -> S::State {
    let mut st = Stats::default();
    let s = ad.tab.rk.stages();
    ad.k[0] = sys.rhs(t, x);
    let (y_last, f_last) = rkmk_stages(sys, &ad.tab.rk, t, dh, x, &mut ad.k[..s], &mut st);
    let delta = combine(dh, ad.tab.rk.b, &ad.k[..s]);
    let y = if ad.tab.fsal {
        y_last
    } else {
        sys.retract(x, &delta)
    };
    ad.f0 = if ad.tab.fsal {
        f_last
    } else {
        sys.rhs(t + dh, &y)
    };
    ad.dense_stages(sys, t, dh, x, &delta, &mut st);
    y
}

/// The exact Kepler state (semi-major axis 1, eccentricity `e`, pericentre at t = 0) at
/// `t`, from Kepler's equation `E - e sin E = t` solved by Newton's method to round-off.
fn kepler_exact(e: f64, t: f64) -> nalgebra::Vector4<f64> {
    let mut ea = t;
    for _ in 0..50 {
        ea -= (ea - e * ea.sin() - t) / (1.0 - e * ea.cos());
    }
    let (s, c) = ea.sin_cos();
    let w = (1.0 - e * e).sqrt();
    let r = 1.0 - e * c;
    nalgebra::Vector4::new(c - e, w * s, -s / r, w * c / r)
}

/// Observed orders of the dense output at s = 0.37 over one step of sizes `hs` from
/// `(t, x)`, against `exact(t + 0.37 h)` with the distance `dist`; also returns the errors.
fn interpolant_orders<S: ErrorScale>(
    make: impl Fn() -> AdaptiveRk<S>,
    sys: &S,
    t: f64,
    x: &S::State,
    hs: &[f64],
    exact: impl Fn(f64) -> S::State,
    dist: impl Fn(&S::State, &S::State) -> f64,
) -> (Vec<f64>, Vec<f64>) {
    let s = 0.37;
    let mut errs = Vec::new();
    for &h in hs {
        let mut ad = make();
        one_step(&mut ad, sys, t, h, x);
        let mut y = ad.interpolate(sys, x, h, s).unwrap();
        sys.normalize(&mut y);
        errs.push(dist(&y, &exact(t + s * h)));
    }
    (observed_orders(&errs), errs)
}

/// On Kepler (e = 0.5, additive: the classical dense output) the interpolant at s = 0.37
/// has local error O(h^5) for dopri5 (order 4) and O(h^8) for dop853 (order 7): observed
/// orders under halving of h (dopri5 h = 0.1 .. 0.00625: measured 4.65, 4.78, 4.88, 4.94;
/// dop853 h = 0.4 .. 0.05: 7.23, 7.73, 7.89; both tending to p + 1 from below, the
/// coarsest pairs pre-asymptotic) in [p + 0.2, p + 1.5] with p the interpolant's order,
/// the finest within 0.25 of p + 1.
/// The errors stay far above round-off (smallest 1e-12). It reproduces both ends exactly
/// (s = 0 gives `x_n`, s = 1 the step's new state, bitwise) and its time derivative at
/// both ends is `f` (4th-order central differences in s, step 1e-3: truncation
/// ~ (1e-3)^4 |y^(5)| ~ 1e-12, rounding ~ 1e-16 / 1e-3 / h ~ 1e-12; bound 1e-9).
#[test]
fn interpolant_order_kepler() {
    let e = 0.5;
    let sys = Kepler::new(e);
    let t = 0.3;
    let x = kepler_exact(e, t);
    let exact = |t| kepler_exact(e, t);
    let dist = |a: &Vector4<f64>, b: &Vector4<f64>| (a - b).norm();
    for dop853 in [false, true] {
        let make = || {
            if dop853 {
                AdaptiveRk::dop853(1e-6)
            } else {
                AdaptiveRk::dopri5(1e-6)
            }
        };
        let (h0, p) = if dop853 { (0.4, 7.0) } else { (0.1, 4.0) };
        let m = if dop853 { 4 } else { 5 };
        let hs: Vec<f64> = (0..m).map(|j| h0 / 2f64.powi(j)).collect();
        let (orders, errs) = interpolant_orders(make, &sys, t, &x, &hs, exact, dist);
        eprintln!(
            "kepler {}: errors {} orders {}",
            make().tab.rk.name,
            sci(&errs),
            fixed(&orders)
        );
        assert!(orders.iter().all(|o| (p + 0.2..=p + 1.5).contains(o)));
        assert!((orders[orders.len() - 1] - (p + 1.0)).abs() < 0.25);
        assert!(errs[errs.len() - 1] > 1e-13);

        let h = 0.2;
        let mut ad = make();
        let y1 = one_step(&mut ad, &sys, t, h, &x);
        assert_eq!(ad.interpolate(&sys, &x, h, 0.0).unwrap(), x);
        assert_eq!(ad.interpolate(&sys, &x, h, 1.0).unwrap(), y1);
        let d = 1e-3;
        for (s, y) in [(0.0, x), (1.0, y1)] {
            let mut at = |k: f64| ad.interpolate(&sys, &x, h, s + k * d).unwrap();
            let dy = (at(-2.0) - 8.0 * at(-1.0) + 8.0 * at(1.0) - at(2.0)) / (12.0 * d * h);
            let f = sys.rhs(t + s * h, &y);
            assert!(
                (dy - f).norm() < 1e-9,
                "y'({s}) - f = {:e}",
                (dy - f).norm()
            );
        }
    }
}

/// The RKMK interpolant on SO(3) (free rotor, `x_n (+) theta(s)`, normalized) has the
/// same orders as on vectors: at s = 0.37, for h = 0.8 .. 0.1 (dopri5, measured 5.06,
/// 5.27, 5.20) and h = 1.6 .. 0.2 (dop853, measured 8.37, 8.27, 8.17, approaching 8 from
/// above), observed orders in [p + 0.5, p + 1.5] against the independent reference (whose
/// error over 0.6 s is ~1e-15, below the smallest error measured, 1.2e-11).
#[test]
fn interpolant_order_rotor() {
    let sys = rotor_system();
    let x = rotor_initial(&sys);
    for dop853 in [false, true] {
        let make = || {
            if dop853 {
                AdaptiveRk::dop853(1e-6)
            } else {
                AdaptiveRk::dopri5(1e-6)
            }
        };
        let (h0, p) = if dop853 { (1.6, 7.0) } else { (0.8, 4.0) };
        let hs: Vec<f64> = (0..4).map(|j| h0 / 2f64.powi(j)).collect();
        let (orders, errs) = interpolant_orders(
            make,
            &sys,
            0.0,
            &x,
            &hs,
            |t| rotor_reference(&sys, t),
            rotor_distance,
        );
        eprintln!(
            "rotor {}: errors {} orders {}",
            make().tab.rk.name,
            sci(&errs),
            fixed(&orders)
        );
        assert!(orders.iter().all(|o| (p + 0.5..=p + 1.5).contains(o)));
    }
}

/// The state's bit patterns (for bitwise comparisons).
fn rotor_bits(s: &RotorState) -> Vec<u64> {
    let q = s.pose.rot.coords;
    q.iter()
        .chain(s.pose.x.iter())
        .chain(s.vel.iter())
        .map(|v| v.to_bits())
        .collect()
}

/// Dense output on the free rotor, 320 outputs over 3.2 s: every output is within 10 tol
/// of the reference (dop853 at tol 1e-13 landing on each output time, itself checked
/// against the independent reference at 3.2 s to 1e-12; measured worst 1.3 .. 3.3 tol at
/// tol 1e-6 .. 1e-10), every output is a unit quaternion, outputs come in order
/// k = 1..=320. At tol 1e-8 both pairs take far fewer steps than outputs (< 80; measured
/// dopri5 30, dop853 9). The final state is the last accepted step's, equal (bitwise, with
/// the same step counts) to a single `advance` over the span, and to the last output; a
/// second run gives bitwise the same outputs.
#[test]
fn integrate_dense_rotor() {
    let sys = rotor_system();
    let (dt, n) = (0.01, 320);
    let lim = Limits::default();
    let mut r = AdaptiveRk::dop853(1e-13);
    let mut xr = rotor_initial(&sys);
    let mut st = Stats::default();
    let mut refs = Vec::new();
    for k in 1..=n {
        let (ta, tb) = ((k - 1) as f64 * dt, k as f64 * dt);
        r.advance(&sys, ta, tb, &mut xr, &mut st, &lim).unwrap();
        refs.push(xr);
    }
    assert!(rotor_distance(&xr, &rotor_reference(&sys, 3.2)) < 1e-12);
    let make = |dop853: bool, tol: f64| {
        if dop853 {
            AdaptiveRk::dop853(tol)
        } else {
            AdaptiveRk::dopri5(tol)
        }
    };
    let run = |dop853: bool, tol: f64| {
        let mut ad = make(dop853, tol);
        let mut x = rotor_initial(&sys);
        let mut st = Stats::default();
        let mut outs = Vec::new();
        let mut push = |k: u64, y: &RotorState| {
            outs.push((k, *y));
            Ok(())
        };
        ad.integrate_dense(&sys, 0.0, &mut x, dt, n, &mut push, &mut st, &lim)
            .unwrap();
        assert_eq!(ad.time(), Some(n as f64 * dt));
        (outs, x, st)
    };
    for dop853 in [false, true] {
        for tol in [1e-6, 1e-8, 1e-10] {
            let (outs, x, st) = run(dop853, tol);
            let name = make(dop853, tol).tab.rk.name;
            assert_eq!(outs.len(), n as usize);
            let mut worst: f64 = 0.0;
            for (i, (k, y)) in outs.iter().enumerate() {
                assert_eq!(*k, i as u64 + 1);
                assert!((y.pose.rot.coords.norm() - 1.0).abs() <= 4.0 * f64::EPSILON);
                worst = worst.max(rotor_distance(y, &refs[i]));
            }
            eprintln!(
                "dense rotor {name} tol {tol:e}: worst {:.2} tol, {st:?}",
                worst / tol
            );
            assert!(worst < 10.0 * tol);
            if tol == 1e-8 {
                assert!(st.steps < n / 4, "{name}: {} steps", st.steps);
            }
            assert_eq!(rotor_bits(&outs[n as usize - 1].1), rotor_bits(&x));
            let mut ad = make(dop853, tol);
            let mut xa = rotor_initial(&sys);
            let mut sa = Stats::default();
            ad.advance(&sys, 0.0, n as f64 * dt, &mut xa, &mut sa, &lim)
                .unwrap();
            assert_eq!(rotor_bits(&xa), rotor_bits(&x));
            assert_eq!((sa.steps, sa.rejected), (st.steps, st.rejected));
            let (outs2, x2, st2) = run(dop853, tol);
            assert_eq!(st2, st);
            assert_eq!(rotor_bits(&x2), rotor_bits(&x));
            for ((_, a), (_, b)) in outs.iter().zip(&outs2) {
                assert_eq!(rotor_bits(a), rotor_bits(b));
            }
        }
    }
}

/// A system that records the times of `check` (called once per accepted step).
struct Recorder<S> {
    inner: S,
    times: std::sync::Mutex<Vec<f64>>,
}

impl<S: System> System for Recorder<S> {
    type State = S::State;
    type Tangent = S::Tangent;
    const LIE: bool = S::LIE;
    fn rhs(&self, t: f64, x: &S::State) -> S::Tangent {
        self.inner.rhs(t, x)
    }
    fn retract(&self, x: &S::State, dx: &S::Tangent) -> S::State {
        self.inner.retract(x, dx)
    }
    fn check(&self, t: f64, x: &S::State) -> Result<(), Failure> {
        self.times.lock().unwrap().push(t);
        self.inner.check(t, x)
    }
}

impl<S: ErrorScale> ErrorScale for Recorder<S> {
    fn coords(&self, x: &S::State) -> S::Tangent {
        self.inner.coords(x)
    }
}

/// Work of `integrate_dense` is counted exactly: dopri5 costs what `advance` costs
/// (2 + 6 per attempt; its dense output needs no evaluation), dop853 that plus 3 per
/// accepted step with an output time strictly inside it (the lazily evaluated stages
/// 14..16; an output on a step's end needs none). Kepler e = 0.9 over one period
/// (rejections occur): with 200 outputs most steps contain one, with 3 outputs few do,
/// with 1 output none does.
#[test]
fn dense_counts_kepler() {
    let e = 0.9;
    let rec = Recorder {
        inner: Kepler::new(e),
        times: std::sync::Mutex::new(Vec::new()),
    };
    let period = rec.inner.period();
    for dop853 in [false, true] {
        for n in [200u64, 3, 1] {
            let mut ad = if dop853 {
                AdaptiveRk::dop853(1e-8)
            } else {
                AdaptiveRk::dopri5(1e-8)
            };
            rec.times.lock().unwrap().clear();
            let dt = period / n as f64;
            let mut x = rec.inner.initial();
            let mut st = Stats::default();
            let mut check = |_: u64, _: &Vector4<f64>| Ok(());
            ad.integrate_dense(
                &rec,
                0.0,
                &mut x,
                dt,
                n,
                &mut check,
                &mut st,
                &Limits::default(),
            )
            .unwrap();
            let mut bounds = vec![0.0];
            bounds.extend(rec.times.lock().unwrap().iter());
            assert_eq!(bounds.len() as u64, st.steps + 1);
            let inside = bounds
                .windows(2)
                .filter(|w| (1..=n).any(|k| w[0] < k as f64 * dt && (k as f64 * dt) < w[1]))
                .count() as u64;
            let attempts = st.steps + st.rejected;
            let expect = if dop853 {
                2 + 11 * attempts + st.steps + 3 * inside
            } else {
                2 + 6 * attempts
            };
            eprintln!(
                "{} n = {n}: {st:?}, {inside} steps with outputs inside",
                ad.tab.rk.name
            );
            assert!(st.rejected > 0);
            assert_eq!(st.rhs_evals, expect);
            match n {
                200 => assert!(inside > st.steps / 2),
                3 => assert!(inside <= 2),
                _ => assert_eq!(inside, 0),
            }
        }
    }
}

/// Backward dense output (dt_out < 0) on the oscillator lands on `t0 + n dt_out` and
/// follows the exact solution (<= 100 tol, as for sampled `advance`); an error returned by
/// the output callback ends the run with that error.
#[test]
fn dense_backward_and_callback_error() {
    let sys = Oscillator;
    let tol = 1e-9;
    let mut ad = AdaptiveRk::dop853(tol);
    let mut x = sys.initial();
    let mut st = Stats::default();
    let lim = Limits::default();
    let mut check = |k: u64, y: &Vector2<f64>| {
        assert!((y - sys.exact(-0.07 * k as f64)).norm() < 100.0 * tol);
        Ok(())
    };
    ad.integrate_dense(&sys, 0.0, &mut x, -0.07, 100, &mut check, &mut st, &lim)
        .unwrap();
    let t_end = 100.0 * -0.07;
    assert_eq!(ad.time(), Some(t_end));
    assert!((x - sys.exact(t_end)).norm() < 100.0 * tol);
    let mut stop = |k: u64, _: &Vector2<f64>| {
        if k == 3 {
            Err(Failure::new(FailureKind::BoundExceeded, 0.3, "stop"))
        } else {
            Ok(())
        }
    };
    let e = ad
        .integrate_dense(
            &sys,
            0.0,
            &mut sys.initial(),
            0.1,
            10,
            &mut stop,
            &mut st,
            &lim,
        )
        .unwrap_err();
    assert_eq!(e.kind, FailureKind::BoundExceeded);
    assert_eq!(ad.time(), None);
}

/// `info()` of both pairs.
#[test]
fn method_info() {
    let i = Adaptive::<RotorSys>::info(&AdaptiveRk::<RotorSys>::dop853(1e-6));
    assert_eq!((i.name, i.order, i.stages), ("dop853", 8, 12));
    assert!(i.adaptive && i.lie_group && !i.implicit);
    let i = Adaptive::<Kepler>::info(&AdaptiveRk::<Kepler>::dopri5(1e-6));
    assert_eq!((i.name, i.order, i.stages), ("dopri5", 5, 7));
    assert!(!i.lie_group);
}
