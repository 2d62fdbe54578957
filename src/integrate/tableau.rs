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
//! Dense output (`DenseOutput`, HNW I, sec. II.6): DOPRI5 carries Shampine's (1986) order-4
//! continuous extension in the form of Hairer's `contd5` (one row `d`, no extra stage);
//! DOP853 the order-7 extension of Hairer's `contd8` (Dormand & Prince 1989 coefficients):
//! stage 13 at the new point, three stages 14..16 used only for interpolation, four rows `d`.
//! The tests check the extensions' order conditions `sum_i b_i(s) Phi_i(t) = s^|t| / gamma(t)`
//! on every tree up to the interpolant's order at several `s` (HNW I, Thm. II.6.1), the row
//! sums of the appended stages, and the end conditions.
//!
//! The DOP853 coefficients are published decimal constants (30 digits) rounded here to the
//! nearest `f64`; the rational ones (DOPRI5, RK4) are written as exact fractions. The tests
//! check `c_i = sum_j a_ij` and the Butcher order conditions on every rooted tree up to the
//! declared order (all 200 trees up to order 8 for DOP853), to the rounding of the sums,
//! and that each error estimator annihilates the trees up to its own order.
/// An explicit Runge-Kutta tableau.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tableau {
    /// Method name (stable snake_case: it appears in case files, records and bench ids).
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
    /// The continuous extension (dense output) of the propagated method.
    pub dense: DenseOutput,
}

/// A continuous extension of an RK method in Hairer's form: with the pair's stages, the stage
/// `E` at the new point (`c_E = 1`, row `b`) and possibly extra stages, the weights are
/// `b_i(s) = s (b_i + (1-s) (u_i + s (v_i + (1-s) (d1_i + s (d2_i + (1-s) (d3_i + ...))))))`
/// with `u = e_1 - b`, `v = 2 b - e_1 - e_E` (`e_j` the unit vectors) and the rows `d`; the
/// interpolant is `y(t + s h) = y + h sum_i b_i(s) K_i`. Whatever the `d`, `b_i(0) = 0`,
/// `b_i(1) = b_i`, `b_i'(0) = e_1`, `b_i'(1) = e_E`: it reproduces both ends and their
/// derivatives (a Hermite interpolant plus corrections that vanish to second order at both
/// ends).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DenseOutput {
    /// Order of the interpolant (local error `O(h^(order + 1))` for every `s` in [0, 1]).
    pub order: u32,
    /// Index of the stage at the new point, `f(t + h, y_n+1)`.
    pub end: usize,
    /// Nodes of the stages appended after the pair's (stage `end` first when the pair is not
    /// first same as last).
    pub c: &'static [f64],
    /// Their rows of `A`: row `i` has as many entries as the stages before it.
    pub a: &'static [&'static [f64]],
    /// The correction rows `d1, d2, ...` over all stages (pair's and appended).
    pub d: &'static [&'static [f64]],
}

impl EmbeddedTableau {
    /// Number of stages the dense output uses (the pair's and the appended ones).
    pub const fn dense_stages(&self) -> usize {
        self.rk.stages() + self.dense.c.len()
    }

    /// The weights `b_i(s)` of the continuous extension at `s` into `w[..dense_stages()]`.
    pub fn dense_weights(&self, s: f64, w: &mut [f64]) {
        let s1 = 1.0 - s;
        let ns = self.rk.stages();
        let d = self.dense.d;
        for (i, wi) in w[..self.dense_stages()].iter_mut().enumerate() {
            let b = if i < ns { self.rk.b[i] } else { 0.0 };
            let e1 = if i == 0 { 1.0 } else { 0.0 };
            let ee = if i == self.dense.end { 1.0 } else { 0.0 };
            // Horner from the innermost coefficient outwards; the factor after the `j`-th
            // coefficient (1-based: b, u, v, d1, ...) is `1-s` for odd `j`, `s` for even `j`.
            let m = 3 + d.len();
            let mut acc = 0.0;
            for j in (1..=m).rev() {
                let cj = match j {
                    1 => b,
                    2 => e1 - b,
                    3 => 2.0 * b - e1 - ee,
                    _ => d[j - 4][i],
                };
                let f = if j % 2 == 1 { s1 } else { s };
                acc = if j == m { cj } else { cj + f * acc };
            }
            *wi = s * acc;
        }
    }
}

/// Upper bound on the stage count of every tableau here (workspace size).
pub const MAX_STAGES: usize = 13;

/// Upper bound on the stage count of every dense output here (pair plus appended stages).
pub const MAX_DENSE_STAGES: usize = 16;

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
    // Shampine's order-4 extension as in Hairer's DOPRI5 (`contd5`): no extra stage, the FSAL
    // stage 7 is `f(t + h, y_n+1)`.
    dense: DenseOutput {
        order: 4,
        end: 6,
        c: &[],
        a: &[],
        d: &[&[
            -12715105075.0 / 11282082432.0,
            0.0,
            87487479700.0 / 32700410799.0,
            -10690763975.0 / 1880347072.0,
            701980252875.0 / 199316789632.0,
            -1453857185.0 / 822651844.0,
            69997945.0 / 29380423.0,
        ]],
    },
};

const DOP853_B: [f64; 12] = [
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
];

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
        b: &DOP853_B,
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
    // Order-7 extension of Hairer's DOP853 (`contd8`): stage 13 is `f(t + h, y_n+1)`, stages
    // 14..16 (c = 1/10, 1/5, 7/9) are evaluated only for interpolation.
    dense: DenseOutput {
        order: 7,
        end: 12,
        c: &[1.0, 0.1, 0.2, 7.0 / 9.0],
        a: &[
            &DOP853_B,
            &[
                0.056167502283047954,
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
                0.25350021021662483,
                -0.2462390374708025,
                -0.12419142326381637,
                0.15329179827876568,
                0.00820105229563469,
                0.007567897660545699,
                -0.008298,
            ],
            &[
                0.03183464816350214,
                0.0,
                0.0,
                0.0,
                0.0,
                0.028300909672366776,
                0.053541988307438566,
                -0.05492374857139099,
                0.0,
                0.0,
                -0.00010834732869724932,
                0.0003825710908356584,
                -0.00034046500868740456,
                0.1413124436746325,
            ],
            &[
                -0.42889630158379194,
                0.0,
                0.0,
                0.0,
                0.0,
                -4.697621415361164,
                7.683421196062599,
                4.06898981839711,
                0.3567271874552811,
                0.0,
                0.0,
                0.0,
                -0.0013990241651590145,
                2.9475147891527724,
                -9.15095847217987,
            ],
        ],
        d: &[
            &[
                -8.428938276109013,
                0.0,
                0.0,
                0.0,
                0.0,
                0.5667149535193777,
                -3.0689499459498917,
                2.38466765651207,
                2.117034582445028,
                -0.871391583777973,
                2.2404374302607883,
                0.6315787787694688,
                -0.08899033645133331,
                18.148505520854727,
                -9.194632392478356,
                -4.436036387594894,
            ],
            &[
                10.427508642579134,
                0.0,
                0.0,
                0.0,
                0.0,
                242.28349177525817,
                165.20045171727028,
                -374.5467547226902,
                -22.113666853125306,
                7.733432668472264,
                -30.674084731089398,
                -9.332130526430229,
                15.697238121770845,
                -31.139403219565178,
                -9.35292435884448,
                35.81684148639408,
            ],
            &[
                19.985053242002433,
                0.0,
                0.0,
                0.0,
                0.0,
                -387.0373087493518,
                -189.17813819516758,
                527.8081592054236,
                -11.57390253995963,
                6.8812326946963,
                -1.0006050966910838,
                0.7777137798053443,
                -2.778205752353508,
                -60.19669523126412,
                84.32040550667716,
                11.99229113618279,
            ],
            &[
                -25.69393346270375,
                0.0,
                0.0,
                0.0,
                0.0,
                -154.18974869023643,
                -231.5293791760455,
                357.6391179106141,
                93.40532418362432,
                -37.45832313645163,
                104.0996495089623,
                29.8402934266605,
                -43.53345659001114,
                96.32455395918828,
                -39.17726167561544,
                -149.72683625798564,
            ],
        ],
    },
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
#[path = "tableau_tests.rs"]
mod tests;
