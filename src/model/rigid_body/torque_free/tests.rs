//! Tests of the exact torque-free motion (`mod.rs`) and of `spin_exact`: conservation of
//! `|L|`, `T` and world `L`; agreement with a 30-digit mpmath Taylor integration and with an
//! order-12 Gragg-Bulirsch-Stoer integration (HNW I, sec. II.9); independence of `R0` and of
//! the order of the axes (both sides of the separatrix); the regular precession of
//! axisymmetric bodies; steady spins; the rejected inputs.
use super::*;
use crate::math::so3::{geodesic_quat, rx, rz};
use nalgebra::Quaternion;

const EPS: f64 = f64::EPSILON;

fn gni_inertia() -> Vector3<f64> {
    Vector3::new(2.0, 1.0, 0.6666666666666666)
}

/// `free_body/gni`: `J omega(0) = (cos 1.1, 0, sin 1.1)`, `R0 = I`.
fn gni() -> (Vector3<f64>, Vector3<f64>, Matrix3<f64>) {
    let j = gni_inertia();
    let l = Vector3::new(0.4535961214255773, 0.0, 0.8912073600614354);
    (j, l.component_div(&j), Matrix3::identity())
}

/// `gimbal_lock/tumble`: `J = diag(0.3, 0.35, 0.4)`, `omega(0) = (0.1, 15, 0.1)`,
/// `R0 = Rx(0.5) Rz(0.3)`.
fn tumble() -> (Vector3<f64>, Vector3<f64>, Matrix3<f64>) {
    (
        Vector3::new(0.3, 0.35, 0.4),
        Vector3::new(0.1, 15.0, 0.1),
        rx(0.5) * rz(0.3),
    )
}

fn exact((j, w, r): (Vector3<f64>, Vector3<f64>, Matrix3<f64>)) -> TorqueFreeExact {
    TorqueFreeExact::new(j, w, r).unwrap()
}

/// Euler's equations `J omega' = J omega x omega` and quaternion kinematics
/// `q' = q (0, omega)/2`, state
/// `(q_w, q_x, q_y, q_z, omega)`.
fn rhs(j: &Vector3<f64>, y: &[f64; 7]) -> [f64; 7] {
    let (q0, q1, q2, q3) = (y[0], y[1], y[2], y[3]);
    let (w1, w2, w3) = (y[4], y[5], y[6]);
    let l = Vector3::new(j.x * w1, j.y * w2, j.z * w3);
    [
        -0.5 * (q1 * w1 + q2 * w2 + q3 * w3),
        0.5 * (q0 * w1 + q2 * w3 - q3 * w2),
        0.5 * (q0 * w2 + q3 * w1 - q1 * w3),
        0.5 * (q0 * w3 + q1 * w2 - q2 * w1),
        (l.y * w3 - l.z * w2) / j.x,
        (l.z * w1 - l.x * w3) / j.y,
        (l.x * w2 - l.y * w1) / j.z,
    ]
}

/// Gragg-Bulirsch-Stoer (Hairer, Norsett & Wanner I, sec. II.9): the explicit midpoint
/// rule with `n = 2, 4, 8, ..., 64` substeps, written for the increment (so its rounding
/// is relative to the increment), extrapolated in `h^2` by Aitken-Neville (order 12),
/// added to the state with Kahan compensation. Powers of two make every `H/n` exact: with
/// the harmonic sequence `2, 4, 6, ...` the rows end at times differing by an ulp of `H`
/// and the extrapolation amplifies that systematic offset into a measured 5e-13 rad drift
/// over 100 s (`gni`), whatever `H`.
struct Gbs {
    j: Vector3<f64>,
    y: [f64; 7],
    comp: [f64; 7],
}

const ROWS: usize = 6;

impl Gbs {
    fn new(j: Vector3<f64>, q: UnitQuaternion<f64>, w: Vector3<f64>) -> Self {
        Gbs {
            j,
            y: [q.w, q.i, q.j, q.k, w.x, w.y, w.z],
            comp: [0.0; 7],
        }
    }

    fn step(&mut self, big_h: f64) {
        let y = self.y;
        let f0 = rhs(&self.j, &y);
        let mut prev = [[0.0; 7]; ROWS];
        for row in 0..ROWS {
            let n = 2usize << row;
            let h = big_h / n as f64;
            let mut d_prev = [0.0; 7];
            let mut d_cur: [f64; 7] = std::array::from_fn(|i| h * f0[i]);
            for _ in 1..n {
                let z: [f64; 7] = std::array::from_fn(|i| y[i] + d_cur[i]);
                let f = rhs(&self.j, &z);
                let d_next: [f64; 7] = std::array::from_fn(|i| d_prev[i] + 2.0 * h * f[i]);
                d_prev = d_cur;
                d_cur = d_next;
            }
            let mut cur = [[0.0; 7]; ROWS];
            cur[0] = d_cur;
            for k in 1..=row {
                let ratio = ((1u64 << (2 * k)) - 1) as f64;
                cur[k] = std::array::from_fn(|i| {
                    cur[k - 1][i] + (cur[k - 1][i] - prev[k - 1][i]) / ratio
                });
            }
            prev = cur;
        }
        let delta = prev[ROWS - 1];
        for ((y, c), d) in self.y.iter_mut().zip(self.comp.iter_mut()).zip(delta) {
            let yk = d - *c;
            let sum = *y + yk;
            *c = (sum - *y) - yk;
            *y = sum;
        }
    }

    fn q(&self) -> UnitQuaternion<f64> {
        UnitQuaternion::new_normalize(Quaternion::new(self.y[0], self.y[1], self.y[2], self.y[3]))
    }

    fn omega(&self) -> Vector3<f64> {
        Vector3::new(self.y[4], self.y[5], self.y[6])
    }
}

/// Max over `[t_a, t_b)` of the rotation (rad) and angular-velocity differences between
/// the exact solution and GBS with macro step `big_h`, sampled every `every` steps;
/// returns one `(rot, omega)` pair per window of `windows` (window ends, ascending).
fn cross_check(
    scene: (Vector3<f64>, Vector3<f64>, Matrix3<f64>),
    big_h: f64,
    t_end: f64,
    every: usize,
    windows: &[f64],
) -> Vec<(f64, f64)> {
    let ex = exact(scene);
    let (q0, w0) = ex.at(0.0);
    let mut gbs = Gbs::new(scene.0, so3::quat_from_matrix(&scene.2), scene.1);
    // The exact solution starts where the integration does (to round-off).
    assert!(geodesic_quat(&q0, &gbs.q()) <= 4.0 * EPS);
    assert!((w0 - scene.1).norm() <= 8.0 * EPS * scene.1.norm());
    let n = (t_end / big_h).round() as usize;
    let mut out = vec![(0.0_f64, 0.0_f64); windows.len()];
    for i in 1..=n {
        gbs.step(big_h);
        if i % every == 0 {
            let t = i as f64 * big_h;
            let (q, w) = ex.at(t);
            let dr = geodesic_quat(&q, &gbs.q());
            let dw = (w - gbs.omega()).norm();
            let k = windows.iter().position(|&e| t <= e + 1e-9).unwrap();
            out[k].0 = out[k].0.max(dr);
            out[k].1 = out[k].1.max(dw);
        }
    }
    out
}

/// `|L|`, `T` and the world angular momentum `R L` are constant along the exact motion
/// to a few ulps (sampled every 0.01 s over the whole horizon of both scenes).
#[test]
fn conservation() {
    for (name, scene, t_end) in [("gni", gni(), 100.0), ("tumble", tumble(), 20.0)] {
        let ex = exact(scene);
        let j = scene.0;
        let (q, w) = ex.at(0.0);
        let l0 = q * j.component_mul(&w);
        let t0 = 0.5 * w.dot(&j.component_mul(&w));
        let (mut e_l, mut e_t, mut e_lw) = (0.0_f64, 0.0_f64, 0.0_f64);
        let n = (t_end / 0.01_f64).round() as usize;
        for i in 0..=n {
            let (q, w) = ex.at(i as f64 * 0.01);
            let lb = j.component_mul(&w);
            e_l = e_l.max((lb.norm() - l0.norm()).abs() / l0.norm());
            e_t = e_t.max((0.5 * w.dot(&lb) - t0).abs() / t0);
            e_lw = e_lw.max((q * lb - l0).norm() / l0.norm());
        }
        eprintln!("{name}: rel drift |L| {e_l:.1e}, T {e_t:.1e}, world L {e_lw:.1e}");
        // A handful of roundings in the elliptic identities, the sums and the rotation.
        let tol = 16.0 * EPS;
        assert!(e_l <= tol && e_t <= tol && e_lw <= tol, "{name}");
    }
}

/// 30-digit references `(t, [q_w, q_x, q_y, q_z, omega])` from `R = I`, produced by
/// `python3` with mpmath 1.3.0: `mp.dps = 30`, `J` and `omega0` the exact values of the
/// doubles of `gni()` / `tumble()` (`mpf(x)` of each double), `f` = `rhs` above in mpf
/// (Euler's equations in the form `(J_2 - J_3) w_2 w_3 / J_1`, ...),
/// `sol = mp.odefun(f, 0, [1, 0, 0, 0] + omega0)` (Taylor series), printing
/// `mp.nstr(sol(t), 22)`. A rerun at `mp.dps = 36` agreed in all 22 printed digits.
#[allow(clippy::excessive_precision)]
const MPMATH_GNI: [(f64, [f64; 7]); 3] = [
    (
        10.0,
        [
            0.7651110308293112478978,
            0.3743195514832238050484,
            0.1028541314550417155802,
            0.5137226990540089954283,
            0.2035330682940204980895,
            0.2830074268128432959136,
            1.302673751492342772792,
        ],
    ),
    (
        50.0,
        [
            -0.8783337070892959190564,
            -0.2932280271328520217821,
            -0.3735652240469649883842,
            -0.05473798020836327397432,
            -0.1159747348131203983678,
            0.5512692353332129572568,
            1.2021558825124513458,
        ],
    ),
    (
        100.0,
        [
            0.8870943102642880091261,
            -0.2616786950327902976967,
            0.2258391074277559543065,
            0.30591607152762922054,
            -0.08867415693748930910821,
            -0.5904185243334242323656,
            1.181056928687901425073,
        ],
    ),
];
/// As above for `tumble` (`R(t) = R0 R_I(t)` is checked separately).
#[allow(clippy::excessive_precision)]
const MPMATH_TUMBLE: [(f64, [f64; 7]); 5] = [
    (
        2.5,
        [
            0.9923209552086094861052,
            -0.04843550765968744740891,
            -0.09792282413518711165635,
            -0.05800210310851168712051,
            -1.724410852752569734026,
            14.82968493322435396473,
            1.49422039599857252107,
        ],
    ),
    (
        5.0,
        [
            0.05772320534705826185885,
            -0.6115707793390380765724,
            -0.006806552523961433213769,
            -0.7890518894634506205462,
            -1.3441791624812634645,
            -14.89697087402006051957,
            1.165166604240192572144,
        ],
    ),
    (
        10.0,
        [
            -0.2008007924029351348193,
            -0.2676858497702969942117,
            -0.7766277681436769552984,
            -0.5337346132220379857709,
            10.9462397699298257959,
            4.428447305941123668893,
            9.479853576168511480825,
        ],
    ),
    (
        15.0,
        [
            -0.4320216966797523269781,
            0.09455781201320340641157,
            -0.8957680886048704012515,
            -0.04489549222807132530762,
            -2.450924472962575676195,
            14.65330596893214736047,
            2.123151685378403221713,
        ],
    ),
    (
        20.0,
        [
            -0.01200293644109398382599,
            0.9778300044640415520219,
            0.002021792097288618920056,
            -0.209046225135396496168,
            0.1937706234559685040139,
            -14.9984257999956487977,
            0.1751008020709386241594,
        ],
    ),
];

/// The exact solution agrees with a 30-digit Taylor integration: `gni` over 100 s and
/// `tumble` over 20 s (two flips) to about 1e-14 relative. The bound: the phases
/// `lambda t + tau0` (up to ~100 rad) and `phi` (up to ~150 rad) carry a few ulps of
/// their size (1e-14 rad), scaled in `omega` by `|d omega/d tau| <= |omega|`.
#[test]
fn against_mpmath() {
    let (j, w, _) = tumble();
    let sets = [
        ("gni", exact(gni()), &MPMATH_GNI[..]),
        (
            "tumble",
            exact((j, w, Matrix3::identity())),
            &MPMATH_TUMBLE[..],
        ),
    ];
    for (name, ex, refs) in sets {
        for &(t, y) in refs {
            let (q, w) = ex.at(t);
            let q_ref = UnitQuaternion::new_normalize(Quaternion::new(y[0], y[1], y[2], y[3]));
            let w_ref = Vector3::new(y[4], y[5], y[6]);
            let dr = geodesic_quat(&q, &q_ref);
            let dw = (w - w_ref).norm() / w_ref.norm();
            eprintln!("{name} t = {t}: rotation {dr:.1e} rad, omega {dw:.1e} relative");
            let tol = 64.0 * EPS * (1.0 + t);
            assert!(
                dr <= tol && dw <= tol,
                "{name} t {t}: {dr:e} {dw:e} > {tol:e}"
            );
        }
    }
}

/// `R(t) = R0 R_I(t)` and `omega` does not depend on `R0` (cases/README.md, `gimbal_lock`).
#[test]
fn initial_attitude_factors_out() {
    let (j, w, r0) = tumble();
    let (a, b) = (exact((j, w, r0)), exact((j, w, Matrix3::identity())));
    let q0 = so3::quat_from_matrix(&r0);
    for t in [0.0, 0.7, 3.3, 6.2, 12.9, 20.0] {
        let ((qa, wa), (qb, wb)) = (a.at(t), b.at(t));
        assert!(geodesic_quat(&qa, &(q0 * qb)) <= 8.0 * EPS, "t {t}");
        assert!((wa - wb).norm() <= 4.0 * EPS * wa.norm(), "t {t}");
    }
}

/// Cross-check against the order-12 GBS integration of `(q, omega)` (macro step 0.05 s)
/// for `gni` over 100 s (the project needs agreement to ~2e-12). GBS truncation per step
/// is ~(|omega| H)^13 / (4 4^2 ... 4^5) < 1e-20, and its round-off is a random walk of
/// ulps of the increments, so the difference measures both solutions' rounding:
/// measured 2.8e-14 rad and 4.9e-15 rad/s, the same for H = 0.2 ... 0.0125 (so no
/// truncation is left); the exact solution alone is 1.3e-14 from mpmath at t = 100.
#[test]
fn gni_against_gbs() {
    let out = cross_check(gni(), 0.05, 100.0, 2, &[100.0]);
    let (dr, dw) = out[0];
    eprintln!("gni vs GBS over [0, 100]: rotation {dr:.1e} rad, omega {dw:.1e} rad/s");
    // ~100 ulps of the accumulated phase (|omega| t ~ 130 rad): 64 eps (1 + t).
    let tol = 64.0 * EPS * 101.0;
    assert!(dr <= tol && dw <= tol, "{dr:e} {dw:e} > {tol:e}");
}

/// Cross-check against GBS for `tumble` (`R0 = Rx(0.5) Rz(0.3)`, macro step 0.005 s,
/// `|omega| H ~ 0.075`): tight over `[0, 5]` (one flip); after the flips the double-
/// precision integration itself drifts (the state is 2e-6 from the separatrix, where the
/// period is `~ln(1/m1)` sensitive), so `[5, 20]` is only reported and loosely bounded.
#[test]
fn tumble_against_gbs() {
    let out = cross_check(tumble(), 0.005, 20.0, 20, &[5.0, 20.0]);
    let ((dr5, dw5), (dr20, dw20)) = (out[0], out[1]);
    eprintln!("tumble vs GBS over [0, 5]: rotation {dr5:.1e} rad, omega {dw5:.1e} rad/s");
    eprintln!("tumble vs GBS over [5, 20]: rotation {dr20:.1e} rad, omega {dw20:.1e} rad/s");
    // [0, 5]: a few ulps of the phases (|omega| t ~ 75 rad), as for gni: 64 eps (1 + t) in
    // rotation, times |omega| = 15 rad/s in omega. Measured 1.3e-14 rad, 9.1e-14 rad/s.
    assert!(
        dr5 <= 64.0 * EPS * 6.0 && dw5 <= 64.0 * EPS * 6.0 * 15.0,
        "{dr5:e} {dw5:e}"
    );
    // [5, 20]: GBS's own drift (exact vs mpmath stays ~1e-13 here); measured 1.9e-12 rad,
    // 2.9e-11 rad/s. Bounded by the limit cases/README.md (`gimbal_lock`, `tumble`) states for
    // double precision.
    assert!(dr20 <= 3e-11 && dw20 <= 1e-9, "{dr20:e} {dw20:e}");
}

/// The 24 proper signed permutations of the body axes (`x' = Q x`: `J' = Q J Q^T`,
/// `omega0' = Q omega0`, `R0' = R0 Q^T`) give the same motion `R' = R Q^T`,
/// `omega' = Q omega`: the internal sorting and role assignment are right for every order,
/// on both sides of the separatrix (`gni` rotates about its min axis, `tumble` its max).
#[test]
fn any_axis_order() {
    let mut qs = Vec::new();
    for p in [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ] {
        for signs in 0..8 {
            let mut q = Matrix3::zeros();
            for (i, &pi) in p.iter().enumerate() {
                q[(i, pi)] = if signs & (1 << i) != 0 { -1.0 } else { 1.0 };
            }
            if q.determinant() > 0.0 {
                qs.push(q);
            }
        }
    }
    assert_eq!(qs.len(), 24);
    for (scene, times) in [(gni(), [0.5, 37.0, 99.9]), (tumble(), [0.5, 6.1, 19.9])] {
        let base = exact(scene);
        let (j, w, r0) = scene;
        for q in &qs {
            let jp = q.abs() * j;
            let ex = TorqueFreeExact::new(jp, q * w, r0 * q.transpose()).unwrap();
            let qq = so3::quat_from_matrix(q);
            for t in times {
                let ((qa, wa), (qb, wb)) = (base.at(t), ex.at(t));
                let dr = geodesic_quat(&(qa * qq.inverse()), &qb);
                let dw = (q * wa - wb).norm() / wa.norm();
                // Only the order of a few sums differs: ulps of the phases (<= 130 rad).
                let tol = 64.0 * EPS * (1.0 + t);
                assert!(dr <= tol && dw <= tol, "Q {q} t {t}: {dr:e} {dw:e}");
            }
        }
    }
}

/// Axisymmetric bodies (`m = 0`, `nu = 0` in the elliptic path) follow the regular
/// precession `R = exp(t [L_w / J_p]x) R0 exp(t (1/J_e - 1/J_p) L_e [e]x)`,
/// `omega = exp(-t (1/J_e - 1/J_p) L_e [e]x) omega0`, prolate and oblate, any axis.
#[test]
fn axisymmetric_regular_precession() {
    let r0 = rx(0.5) * rz(0.3);
    let cases = [
        (Vector3::new(1.0, 1.0, 2.0), Vector3::new(0.3, -0.2, 1.1), 2),
        (Vector3::new(3.0, 2.0, 3.0), Vector3::new(0.4, 1.0, -0.7), 1),
        (Vector3::new(0.5, 0.8, 0.8), Vector3::new(-2.0, 0.3, 0.1), 0),
    ];
    for (j, w, axis) in cases {
        let ex = TorqueFreeExact::new(j, w, r0).unwrap();
        let jp = j[(axis + 1) % 3];
        let e = Vector3::ith(axis, 1.0);
        let lw = r0 * j.component_mul(&w);
        let spin = (1.0 / j[axis] - 1.0 / jp) * j[axis] * w[axis];
        let q0 = so3::quat_from_matrix(&r0);
        for t in [0.0, 0.3, 4.0, 17.0, 50.0] {
            let q_ref = so3::exp_quat(&(lw * (t / jp))) * q0 * so3::exp_quat(&(e * spin * t));
            let w_ref = so3::exp_quat(&(e * (-spin * t))) * w;
            let (q, wt) = ex.at(t);
            let dr = geodesic_quat(&q, &q_ref);
            let dw = (wt - w_ref).norm() / w.norm();
            // Both sides accumulate ulps of phases up to |omega| t ~ 120 rad.
            let tol = 64.0 * EPS * (1.0 + 2.5 * t);
            assert!(
                dr <= tol && dw <= tol,
                "J {j} t {t}: {dr:e} {dw:e} > {tol:e}"
            );
        }
    }
}

/// Steady spins (omega0 an eigenvector of J, including the unstable intermediate axis and
/// any omega0 of a spherical body) stay exactly steady: `R = R0 exp(t [omega0]x)`; a
/// spherical body agrees with `spin_exact` for `w = R0 omega0`.
#[test]
fn steady_spins() {
    let r0 = rx(0.5) * rz(0.3);
    let q0 = so3::quat_from_matrix(&r0);
    let cases = [
        (Vector3::new(0.3, 0.35, 0.4), Vector3::new(0.0, 15.0, 0.0)),
        (Vector3::new(0.3, 0.35, 0.4), Vector3::new(-2.0, 0.0, 0.0)),
        (Vector3::new(1.0, 2.0, 2.0), Vector3::new(0.0, 0.6, -0.8)),
        (Vector3::new(2.0, 2.0, 2.0), Vector3::new(0.1, 0.2, 0.3)),
        (Vector3::new(0.3, 0.35, 0.4), Vector3::zeros()),
    ];
    for (j, w) in cases {
        let ex = TorqueFreeExact::new(j, w, r0).unwrap();
        for t in [0.0, 1.0, 3.2, 20.0] {
            let (q, wt) = ex.at(t);
            assert_eq!(wt, w, "J {j}");
            let q_ref = q0 * so3::exp_quat(&(w * t));
            assert!(
                geodesic_quat(&q, &q_ref) <= 4.0 * EPS * (1.0 + t),
                "J {j} t {t}"
            );
            if j.x == j.y && j.y == j.z {
                let (qs, ws) = spin_exact(r0 * w, r0, t);
                assert!(geodesic_quat(&q, &qs) <= 8.0 * EPS * (1.0 + t), "t {t}");
                assert!((ws - w).norm() <= 4.0 * EPS * w.norm());
            }
        }
    }
}

/// `spin_exact` is the flow of `R' = [w]x R`, `R' = R [omega]x` with constant
/// `omega = R0^T w` (central differences, `h = 1e-5`: error `h^2 |w|^3/6 + eps/h`), keeps
/// the spin axis fixed (`R^T w = omega`), and is sign-canonical (`q_w >= 0`).
#[test]
fn spin_exact_kinematics() {
    let d: f64 = 1e-2;
    let w = Vector3::new(d.sin(), d.cos(), 0.0);
    for r0 in [
        Matrix3::identity(),
        crate::math::so3::ry(std::f64::consts::FRAC_PI_2),
    ] {
        for t in [0.0, 1.0, std::f64::consts::FRAC_PI_2, 3.2] {
            let (q, om) = spin_exact(w, r0, t);
            assert!(q.w >= 0.0);
            assert!((om - r0.transpose() * w).norm() <= EPS);
            let r = q.to_rotation_matrix().into_inner();
            let h = 1e-5;
            let rp = spin_exact(w, r0, t + h).0.to_rotation_matrix().into_inner();
            let rm = spin_exact(w, r0, t - h).0.to_rotation_matrix().into_inner();
            let rdot = (rp - rm) / (2.0 * h);
            assert!((rdot - so3::hat(&w) * r).abs().max() <= 1e-9, "t {t}");
            assert!((rdot - r * so3::hat(&om)).abs().max() <= 1e-9, "t {t}");
            // The spin axis, seen in the body at t, is omega (R^T w = omega).
            assert!((r.transpose() * w - om).norm() <= 4.0 * EPS);
        }
    }
}

/// A nearly steady spin about the min axis (tiny cone: `theta ~ 1e-6`, Landau's Euler
/// angles nearly singular) still agrees with GBS over 10 s to round-off.
#[test]
fn small_cone_against_gbs() {
    let scene = (
        Vector3::new(1.0, 2.0, 3.0),
        Vector3::new(1.5, 1e-6, -2e-6),
        rx(0.2),
    );
    let out = cross_check(scene, 0.02, 10.0, 5, &[10.0]);
    let (dr, dw) = out[0];
    eprintln!("small cone vs GBS over [0, 10]: rotation {dr:.1e} rad, omega {dw:.1e} rad/s");
    let tol = 64.0 * EPS * 16.0;
    assert!(dr <= tol && dw <= tol, "{dr:e} {dw:e}");
}

/// Bad inputs and the exact separatrix are rejected with an `Err`, never a panic.
#[test]
fn rejects() {
    let (j, w, r0) = tumble();
    assert!(TorqueFreeExact::new(Vector3::new(0.3, -0.35, 0.4), w, r0).is_err());
    assert!(TorqueFreeExact::new(Vector3::new(0.3, f64::NAN, 0.4), w, r0).is_err());
    assert!(TorqueFreeExact::new(j, Vector3::new(0.1, f64::INFINITY, 0.0), r0).is_err());
    let reflect = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, -1.0));
    assert!(TorqueFreeExact::new(j, w, reflect).is_err());
    assert!(TorqueFreeExact::new(j, w, r0 * 1.01).is_err());
    // J (2, 3, 6), omega (3, 0.7, 1): S = 2 (2 - 3) 9 + 6 (6 - 3) 1 = 0 exactly.
    let err = TorqueFreeExact::new(Vector3::new(2.0, 3.0, 6.0), Vector3::new(3.0, 0.7, 1.0), r0);
    assert!(err.unwrap_err().contains("separatrix"));
}
