//! Tests of `tableau`: the Butcher tableaux's row sums and order conditions through the
//! rooted trees of `tableau::trees` (every tree up to each method's order, and one of the next
//! order failing, so the declared order is exact), the embedded estimators, and the dense
//! outputs' structure and order (kept apart so `tableau.rs` stays under the project's
//! 800-line file limit).
use super::trees::*;
use super::*;

/// Rounding allowance of an order condition, in units of `eps * |b|.|g|`: each of the at
/// most ~12 stages x 8 levels of products and sums contributes O(eps) relative to the
/// absolute sum (plus the coefficients' own rounding to f64).
const UNITS: f64 = 64.0;

fn check_row_sums(tab: &Tableau) {
    assert_eq!(tab.c.len(), tab.stages());
    assert_eq!(tab.a.len(), tab.stages());
    for i in 0..tab.stages() {
        assert_eq!(tab.a[i].len(), i, "{} row {i}", tab.name);
        let s: f64 = tab.a[i].iter().sum();
        let sa: f64 = tab.a[i].iter().map(|a| a.abs()).sum();
        assert!(
            (s - tab.c[i]).abs() <= 8.0 * f64::EPSILON * sa.max(1.0),
            "{} row {i}: sum a = {s}, c = {}",
            tab.name,
            tab.c[i]
        );
    }
}

/// The extended tableau of a dense output: the pair's stages then the appended ones,
/// with weights `w` (leaked: test-only, a few small tableaux).
fn extended(tab: &EmbeddedTableau, w: Vec<f64>) -> Tableau {
    let c: Vec<f64> = tab.rk.c.iter().chain(tab.dense.c).copied().collect();
    let a: Vec<&'static [f64]> = tab.rk.a.iter().chain(tab.dense.a).copied().collect();
    Tableau {
        name: tab.rk.name,
        order: tab.dense.order,
        c: Box::leak(c.into_boxed_slice()),
        a: Box::leak(a.into_boxed_slice()),
        b: Box::leak(w.into_boxed_slice()),
    }
}

fn dense_weights_at(tab: &EmbeddedTableau, s: f64) -> Vec<f64> {
    let mut w = vec![f64::NAN; MAX_DENSE_STAGES];
    tab.dense_weights(s, &mut w);
    w.truncate(tab.dense_stages());
    w
}

/// Dense outputs: the appended stages are consistent (`c_i = sum_j a_ij`; the stage at
/// the new point has row `b`, `c = 1`), every `d` row spans all stages, and the weights
/// satisfy `b_i(0) = 0`, `b_i(1) = b_i` exactly and `b_i'(0) = e_1`, `b_i'(1) = e_end`
/// (derivatives by 4th-order central differences, step 1e-3: truncation
/// ~ 1e-12 |b^(5)| <~ 1e-8 for coefficients of size <~ 1e3, rounding ~ 1e-16 * 1e3 / 1e-3).
#[test]
fn dense_output_structure() {
    for tab in [&DOPRI5, &DOP853] {
        let n = tab.dense_stages();
        assert!(n <= MAX_DENSE_STAGES);
        let ext = extended(tab, vec![0.0; n]);
        check_row_sums(&ext);
        let end = tab.dense.end;
        assert_eq!(ext.a[end], tab.rk.b.split_at(end).0.to_vec().as_slice());
        assert!(tab.rk.b[end..].iter().all(|&b| b == 0.0));
        assert_eq!(ext.c[end], 1.0);
        for d in tab.dense.d {
            assert_eq!(d.len(), n);
        }
        assert!(dense_weights_at(tab, 0.0).iter().all(|&w| w == 0.0));
        let w1 = dense_weights_at(tab, 1.0);
        for (i, w) in w1.iter().enumerate() {
            let b = if i < tab.rk.stages() {
                tab.rk.b[i]
            } else {
                0.0
            };
            assert_eq!(*w, b, "{} b_{i}(1)", tab.rk.name);
        }
        let dh = 1e-3;
        for (s, unit) in [(0.0, 0), (1.0, end)] {
            let wp = |k: f64| dense_weights_at(tab, s + k * dh);
            let (m2, m1, p1, p2) = (wp(-2.0), wp(-1.0), wp(1.0), wp(2.0));
            for i in 0..n {
                let der = (m2[i] - 8.0 * m1[i] + 8.0 * p1[i] - p2[i]) / (12.0 * dh);
                let want = if i == unit { 1.0 } else { 0.0 };
                assert!(
                    (der - want).abs() < 1e-7,
                    "{} b_{i}'({s}) = {der}",
                    tab.rk.name
                );
            }
        }
    }
}

/// Dense outputs have their declared order: at s = 0.1, 0.37, 0.5, 0.8, 1 the weights
/// `b_i(s)` satisfy `sum b_i(s) Phi_i(t) = s^|t| / gamma(t)` on every tree up to the order
/// (4 for dopri5: 8 trees; 7 for dop853: 85 trees) to rounding, and at s = 0.37 violate
/// one of the next order by far more than rounding (> 1e4 units; the order is exact
/// there). Measured: <= 1 unit up to the order; order 5 (dopri5) 3.1e-4, order 8
/// (dop853) 3.9e-7 (small: the order-8 targets are `0.37^8 / gamma <= 4e-5`).
#[test]
fn dense_output_order_conditions() {
    for tab in [&DOPRI5, &DOP853] {
        let p = tab.dense.order as usize;
        for s in [0.1, 0.37, 0.5, 0.8, 1.0] {
            let ext = extended(tab, dense_weights_at(tab, s));
            let target = |t: &str| s.powi(order(t) as i32) / gamma(t);
            let (u, r, t) = worst(&ext, ext.b, 1..=p, target);
            eprintln!("{} s = {s}: worst {u:.1} units ({r:.1e}, {t})", tab.rk.name);
            assert!(
                u <= UNITS,
                "{} s = {s}: tree {t} residual {r:e}",
                tab.rk.name
            );
            if s == 0.37 {
                let (u, r, _) = worst(&ext, ext.b, p + 1..=p + 1, target);
                eprintln!(
                    "{} s = {s}: order {} residual {r:.2e} ({u:.1e} units)",
                    tab.rk.name,
                    p + 1
                );
                assert!(u > 1e4, "{} has order > {p} at s = {s}", tab.rk.name);
            }
        }
    }
}

/// Tree counts 1, 1, 2, 4, 9, 20, 48, 115 (OEIS A000081) and gamma of the bushy trees.
#[test]
fn tree_enumeration_is_complete() {
    let t = trees(8);
    let n: Vec<usize> = t.iter().map(|v| v.len()).collect();
    assert_eq!(n, vec![1, 1, 2, 4, 9, 20, 48, 115]);
    assert_eq!(gamma("[[][][]]"), 4.0);
    assert_eq!(gamma("[[[[]]]]"), 24.0);
    assert_eq!(gamma("[[[]][]]"), 8.0);
}

/// Row sums `c_i = sum_j a_ij` for every tableau, `A` strictly lower-triangular.
#[test]
fn row_sums() {
    for tab in [&EULER, &RK4, &DOPRI5.rk, &DOP853.rk] {
        check_row_sums(tab);
    }
}

/// Euler and RK4 satisfy all order conditions up to their order, and RK4 fails one of
/// order 5 (so the declared order is exact).
#[test]
fn euler_rk4_order_conditions() {
    for tab in [&EULER, &RK4] {
        let (u, r, t) = worst(tab, tab.b, 1..=tab.order as usize, |t| 1.0 / gamma(t));
        assert!(u <= UNITS, "{}: tree {t} residual {r:e}", tab.name);
        let p = tab.order as usize + 1;
        let (_, r, _) = worst(tab, tab.b, p..=p, |t| 1.0 / gamma(t));
        assert!(r > 1e-3, "{} satisfies all order-{p} conditions", tab.name);
    }
}

/// DOPRI5: order 5 on all 17 trees up to order 5, FSAL row equals `b`, the estimator
/// `e = b - b_hat` annihilates all trees up to order 4 and not all of order 5.
#[test]
fn dopri5_order_conditions() {
    let tab = &DOPRI5.rk;
    let (u, r, t) = worst(tab, tab.b, 1..=5, |t| 1.0 / gamma(t));
    assert!(u <= UNITS, "tree {t} residual {r:e} ({u} units)");
    let (_, r, _) = worst(tab, tab.b, 6..=6, |t| 1.0 / gamma(t));
    assert!(r > 1e-4, "dopri5 satisfies every order-6 condition");
    assert_eq!(tab.a[6], &tab.b[..6]);
    assert_eq!(tab.b[6], 0.0);
    assert_eq!(tab.c[6], 1.0);
    let (u, r, t) = worst(tab, DOPRI5.e, 1..=4, |_| 0.0);
    assert!(u <= UNITS, "estimator, tree {t} residual {r:e}");
    let (_, r, _) = worst(tab, DOPRI5.e, 5..=5, |_| 0.0);
    assert!(r > 1e-5, "estimator is of order > 4");
}

/// DOP853: order 8 on all 200 trees up to order 8 (this includes the quadrature
/// conditions `sum b_i c_i^(k-1) = 1/k`, k <= 8), not order 9; the 5th-order estimator
/// annihilates the trees up to order 5, the 3rd-order one those up to order 3.
#[test]
fn dop853_order_conditions() {
    let tab = &DOP853.rk;
    for k in 1..=8 {
        let q: f64 = (0..12).map(|i| tab.b[i] * tab.c[i].powi(k - 1)).sum();
        assert!(
            (q - 1.0 / k as f64).abs() < 1e-14,
            "quadrature k = {k}: {q}"
        );
    }
    let (u, r, t) = worst(tab, tab.b, 1..=8, |t| 1.0 / gamma(t));
    assert!(u <= UNITS, "tree {t} residual {r:e} ({u} units)");
    let (_, r, _) = worst(tab, tab.b, 9..=9, |t| 1.0 / gamma(t));
    assert!(r > 1e-6, "dop853 satisfies every order-9 condition");
    let (u, r, t) = worst(tab, DOP853.e, 1..=5, |_| 0.0);
    assert!(u <= UNITS, "5th-order estimator, tree {t} residual {r:e}");
    let (_, r, _) = worst(tab, DOP853.e, 6..=6, |_| 0.0);
    assert!(r > 1e-6, "5th-order estimator is of order > 5");
    let (e3, o3) = DOP853.e_low.unwrap();
    assert_eq!(o3, 3);
    let (u, r, t) = worst(tab, e3, 1..=3, |_| 0.0);
    assert!(u <= UNITS, "3rd-order estimator, tree {t} residual {r:e}");
    let (_, r, _) = worst(tab, e3, 4..=4, |_| 0.0);
    assert!(r > 1e-4, "3rd-order estimator is of order > 3");
}
