//! Butcher tableaux of the explicit Runge-Kutta methods, as constant data.
//!
//! A tableau `(c, A, b)` with strictly lower-triangular `A` defines the stages
//! `K_i = f(t + c_i h, y + h sum_{j<i} a_ij K_j)` and the step `y + h sum_i b_i K_i`
//! (Hairer, Norsett & Wanner, *Solving ODEs I*, 2nd ed., sec. II.1, eq. (1.8)). Row `i` of `a`
//! holds the `i` entries `a_i0 .. a_i,i-1` (row 0 is empty). The same data drives classical RK
//! on vector spaces and Runge-Kutta-Munthe-Kaas on Lie groups (`explicit_rk.rs`); the
//! Crouch-Grossman methods reuse the `Tableau` type with their own coefficients
//! (`crouch_grossman.rs`).
//!
//! Methods here:
//! - `EULER`: explicit Euler, order 1, 1 stage;
//! - `RK4`: the classical Runge-Kutta method, order 4, 4 stages (HNW I, Table 1.2, left);
//! - `DOPRI5`: Dormand & Prince (1980) 5(4), 7 stages, first-same-as-last (row 7 of `A` is
//!   `b`), propagates the 5th-order solution (HNW I, Table 5.2, p. 178);
//! - `DOP853`: Dormand & Prince 8(5,3) as in Hairer's DOP853 (Prince & Dormand 1981; HNW I,
//!   sec. II.10): 12 stages, the 8th-order solution, and two error estimators, of orders 5
//!   and 3 (`e = b - b_hat`), combined by the caller as `err5^2 / sqrt(err5^2 + 0.01 err3^2)`.
//!   Its `c_12 = 1` stage is not at the new point (`a_12 != b`): the next step's first stage
//!   costs one more evaluation.
//!
//! The DOP853 coefficients are published decimal constants (30 digits) rounded here to the
//! nearest `f64`; the rational ones (DOPRI5, RK4) are written as exact fractions. The tests
//! check `c_i = sum_j a_ij` and the Butcher order conditions on every rooted tree up to the
//! declared order (all 200 trees up to order 8 for DOP853), to the rounding of the sums,
//! and that each error estimator annihilates the trees up to its own order.
/// An explicit Runge-Kutta tableau.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tableau {
    /// Method name (design.md, "Variant names").
    pub name: &'static str,
    /// Classical order.
    pub order: u32,
    /// Nodes `c_i`.
    pub c: &'static [f64],
    /// Strictly lower-triangular `A`: row `i` has `i` entries.
    pub a: &'static [&'static [f64]],
    /// Weights `b_i`.
    pub b: &'static [f64],
}

impl Tableau {
    /// Number of stages.
    pub const fn stages(&self) -> usize {
        self.b.len()
    }
}

/// An embedded pair: the propagated solution and its error estimators.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EmbeddedTableau {
    /// The propagated (higher-order) method.
    pub rk: Tableau,
    /// Error weights `e = b - b_hat` of the main estimator (`err = h sum e_i K_i`).
    pub e: &'static [f64],
    /// Order of the main estimator's `b_hat`.
    pub e_order: u32,
    /// DOP853's second, low-order estimator (`b - b_hhat`) and its order.
    pub e_low: Option<(&'static [f64], u32)>,
    /// The last stage is evaluated at the new point (`a_s = b`, `c_s = 1`): its value is the
    /// next step's first stage (first same as last).
    pub fsal: bool,
}

/// Upper bound on the stage count of every tableau here (workspace size).
pub const MAX_STAGES: usize = 13;

/// Explicit Euler.
pub const EULER: Tableau = Tableau {
    name: "euler",
    order: 1,
    c: &[0.0],
    a: &[&[]],
    b: &[1.0],
};

/// The classical fourth-order Runge-Kutta method.
pub const RK4: Tableau = Tableau {
    name: "rk4",
    order: 4,
    c: &[0.0, 0.5, 0.5, 1.0],
    a: &[&[], &[0.5], &[0.0, 0.5], &[0.0, 0.0, 1.0]],
    b: &[1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
};

const DOPRI5_B: [f64; 7] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
    0.0,
];

/// Dormand-Prince 5(4), first same as last.
pub const DOPRI5: EmbeddedTableau = EmbeddedTableau {
    rk: Tableau {
        name: "dopri5",
        order: 5,
        c: &[0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0],
        a: &[
            &[],
            &[1.0 / 5.0],
            &[3.0 / 40.0, 9.0 / 40.0],
            &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
            &[
                19372.0 / 6561.0,
                -25360.0 / 2187.0,
                64448.0 / 6561.0,
                -212.0 / 729.0,
            ],
            &[
                9017.0 / 3168.0,
                -355.0 / 33.0,
                46732.0 / 5247.0,
                49.0 / 176.0,
                -5103.0 / 18656.0,
            ],
            &[
                DOPRI5_B[0],
                DOPRI5_B[1],
                DOPRI5_B[2],
                DOPRI5_B[3],
                DOPRI5_B[4],
                DOPRI5_B[5],
            ],
        ],
        b: &DOPRI5_B,
    },
    // b - b_hat, b_hat = (5179/57600, 0, 7571/16695, 393/640, -92097/339200, 187/2100, 1/40).
    e: &[
        71.0 / 57600.0,
        0.0,
        -71.0 / 16695.0,
        71.0 / 1920.0,
        -17253.0 / 339200.0,
        22.0 / 525.0,
        -1.0 / 40.0,
    ],
    e_order: 4,
    e_low: None,
    fsal: true,
};

/// Dormand-Prince 8(5,3) (Hairer's DOP853).
pub const DOP853: EmbeddedTableau = EmbeddedTableau {
    rk: Tableau {
        name: "dop853",
        order: 8,
        c: &[
            0.0,
            0.05260015195876773,
            0.0789002279381516,
            0.1183503419072274,
            0.2816496580927726,
            1.0 / 3.0,
            0.25,
            4.0 / 13.0,
            127.0 / 195.0,
            0.6,
            6.0 / 7.0,
            1.0,
        ],
        a: &[
            &[],
            &[0.05260015195876773],
            &[0.0197250569845379, 0.0591751709536137],
            &[0.02958758547680685, 0.0, 0.08876275643042054],
            &[
                0.2413651341592667,
                0.0,
                -0.8845494793282861,
                0.924834003261792,
            ],
            &[
                0.037037037037037035,
                0.0,
                0.0,
                0.17082860872947386,
                0.12546768756682242,
            ],
            &[
                0.037109375,
                0.0,
                0.0,
                0.17025221101954405,
                0.06021653898045596,
                -0.017578125,
            ],
            &[
                0.03709200011850479,
                0.0,
                0.0,
                0.17038392571223998,
                0.10726203044637328,
                -0.015319437748624402,
                0.008273789163814023,
            ],
            &[
                0.6241109587160757,
                0.0,
                0.0,
                -3.3608926294469414,
                -0.868219346841726,
                27.59209969944671,
                20.154067550477894,
                -43.48988418106996,
            ],
            &[
                0.47766253643826434,
                0.0,
                0.0,
                -2.4881146199716677,
                -0.590290826836843,
                21.230051448181193,
                15.279233632882423,
                -33.28821096898486,
                -0.020331201708508627,
            ],
            &[
                -0.9371424300859873,
                0.0,
                0.0,
                5.186372428844064,
                1.0914373489967295,
                -8.149787010746927,
                -18.52006565999696,
                22.739487099350505,
                2.4936055526796523,
                -3.0467644718982196,
            ],
            &[
                2.273310147516538,
                0.0,
                0.0,
                -10.53449546673725,
                -2.0008720582248625,
                -17.9589318631188,
                27.94888452941996,
                -2.8589982771350235,
                -8.87285693353063,
                12.360567175794303,
                0.6433927460157636,
            ],
        ],
        b: &[
            0.054293734116568765,
            0.0,
            0.0,
            0.0,
            0.0,
            4.450312892752409,
            1.8915178993145003,
            -5.801203960010585,
            0.3111643669578199,
            -0.1521609496625161,
            0.20136540080403034,
            0.04471061572777259,
        ],
    },
    e: &[
        0.01312004499419488,
        0.0,
        0.0,
        0.0,
        0.0,
        -1.2251564463762044,
        -0.4957589496572502,
        1.6643771824549864,
        -0.35032884874997366,
        0.3341791187130175,
        0.08192320648511571,
        -0.022355307863886294,
    ],
    e_order: 5,
    // b - b_hhat with b_hhat = (0.2440944881889764 at stage 1, 0.7338466882816119 at stage 9,
    // 0.022058823529411766 at stage 12), computed in 40-digit decimal then rounded.
    e_low: Some((
        &[
            -0.18980075407240762,
            0.0,
            0.0,
            0.0,
            0.0,
            4.450312892752409,
            1.8915178993145003,
            -5.801203960010585,
            -0.42268232132379197,
            -0.1521609496625161,
            0.20136540080403034,
            0.022651792198360825,
        ],
        3,
    )),
    fsal: false,
};

#[cfg(test)]
pub(crate) mod trees {
    //! Rooted trees and elementary weights for the order-condition tests.
    //!
    //! A tree is its canonical string: `"[]"` is the single node, and a node with children
    //! `t1..tm` is `"[" + sorted(t1..tm) + "]"`. Elementary weight of a tableau on tree `t`:
    //! the stage vector `g(t)_i = prod_k (A g(t_k))_i` (1 for a leaf), condition
    //! `b . g(t) = 1/gamma(t)`, `gamma(t) = |t| prod_k gamma(t_k)` (HNW I, Thm. II.2.13).
    use super::Tableau;
    use std::collections::BTreeSet;

    /// Splits a canonical tree string into its children's strings.
    fn children(t: &str) -> Vec<&str> {
        let inner = &t[1..t.len() - 1];
        let mut out = Vec::new();
        let mut depth = 0;
        let mut start = 0;
        for (i, ch) in inner.char_indices() {
            match ch {
                '[' => {
                    if depth == 0 {
                        start = i;
                    }
                    depth += 1;
                }
                ']' => {
                    depth -= 1;
                    if depth == 0 {
                        out.push(&inner[start..=i]);
                    }
                }
                _ => {}
            }
        }
        out
    }

    fn canon(children: &mut [String]) -> String {
        children.sort();
        format!("[{}]", children.concat())
    }

    /// All trees obtained by attaching one leaf to some node of `t`.
    fn grow(t: &str, out: &mut BTreeSet<String>) {
        let ch: Vec<String> = children(t).iter().map(|s| s.to_string()).collect();
        let mut with_leaf = ch.clone();
        with_leaf.push("[]".to_string());
        out.insert(canon(&mut with_leaf));
        for k in 0..ch.len() {
            let mut sub = BTreeSet::new();
            grow(&ch[k], &mut sub);
            for s in sub {
                let mut c2 = ch.clone();
                c2[k] = s;
                out.insert(canon(&mut c2));
            }
        }
    }

    /// All rooted trees with `1..=max_order` nodes, grouped by order.
    pub fn trees(max_order: usize) -> Vec<Vec<String>> {
        let mut all = vec![vec!["[]".to_string()]];
        for _ in 1..max_order {
            let mut next = BTreeSet::new();
            for t in all.last().unwrap() {
                grow(t, &mut next);
            }
            all.push(next.into_iter().collect());
        }
        all
    }

    /// Number of nodes.
    pub fn order(t: &str) -> usize {
        t.len() / 2
    }

    /// `gamma(t)`.
    pub fn gamma(t: &str) -> f64 {
        children(t)
            .iter()
            .fold(order(t) as f64, |g, c| g * gamma(c))
    }

    /// Stage vector `g(t)`, with `A` replaced by `|A|` when `abs` (for the rounding bound).
    pub fn stage_weights(tab: &Tableau, t: &str, abs: bool) -> Vec<f64> {
        let mut g = vec![1.0; tab.stages()];
        for c in children(t) {
            let gc = stage_weights(tab, c, abs);
            for (gi, row) in g.iter_mut().zip(tab.a) {
                let ag: f64 = row
                    .iter()
                    .zip(&gc)
                    .map(|(a, gj)| if abs { a.abs() } else { *a } * gj)
                    .sum();
                *gi *= ag;
            }
        }
        g
    }

    /// `(w . g(t), |w| . |g|(t))`: the weighted elementary weight and its rounding scale.
    pub fn weight(tab: &Tableau, w: &[f64], t: &str) -> (f64, f64) {
        let g = stage_weights(tab, t, false);
        let ga = stage_weights(tab, t, true);
        let v = w.iter().zip(&g).map(|(w, g)| w * g).sum();
        let a = w.iter().zip(&ga).map(|(w, g)| w.abs() * g).sum();
        (v, a)
    }

    /// Largest violation of `w . g(t) = target(t)` over the trees of orders `orders`, in
    /// units of the rounding scale `eps * |w| . |g|(t)`; also returns the absolute residual.
    pub fn worst(
        tab: &Tableau,
        w: &[f64],
        orders: std::ops::RangeInclusive<usize>,
        target: impl Fn(&str) -> f64,
    ) -> (f64, f64, String) {
        let all = trees(*orders.end());
        let mut worst = (0.0, 0.0, String::new());
        for n in orders {
            for t in &all[n - 1] {
                let (v, a) = weight(tab, w, t);
                let r = (v - target(t)).abs();
                let units = r / (f64::EPSILON * a.max(1.0));
                if units > worst.0 {
                    worst = (units, r, t.clone());
                }
            }
        }
        worst
    }
}

#[cfg(test)]
mod tests {
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
}
