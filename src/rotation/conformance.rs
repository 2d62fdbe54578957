//! Conformance suite: every pose chart (`for_each_chart!`) against the same invariants.
//!
//! Checked per chart, with `spatial = false` and `true` where it matters:
//! 1. `R -> chart -> R` within 1e-14 (geodesic) for random rotations (unit quaternions drawn
//!    uniformly), rotations near angle pi and near identity, and rotations within 1e-6 of each
//!    Euler chart's singular set (module `special_rotations`); the translation to 8 eps.
//! 2. `chart -> R -> chart` for chart-specific coordinates (`Probe::samples`: other branches,
//!    near-singular coordinates, the rotation vector beyond pi and near 2 pi), compared as
//!    rotations (1e-14).
//! 3. The kinematic map `velocity` agrees with a central difference (h = 1e-6) of the pose
//!    along `retract(c, t v)` (additive: `c + t rates`; Lie: the group action): `R' = R [omega]x`
//!    and `x' = xdot`, to 1e-8 (truncation `h^2 |v|^3 / 6 < 2e-9` for `|v| < 20`, round-off
//!    `eps/h ~ 2e-10`), where the conditioning is at least 0.1. Nearer the singular set the
//!    rates grow like `1/conditioning` and a directional difference is meaningless (the curve
//!    turns by O(1) within h); there the derivative is superposed from the partials along each
//!    tangent basis direction (each accurate to ~1e-10), so the check is relative:
//!    `|sum v_i dR_i - R [omega]x| <= 1e-9 max(1, sum |v_i|)`.
//! 4. `retract(c, 0)` returns `c` exactly.
//! 5. `normalize` is idempotent to 4 eps per stored number, keeps an on-manifold rotation to
//!    1e-14, and returns `false` for charts that do not normalize.
//! 6. `dexp_inv(0, v) = v` exactly; for Lie charts the RKMK identity: along
//!    `g(t) = retract(c, theta0 + t u)`, `dexp_inv(theta0, xi) = u` with `xi` the trivialised
//!    velocity of `g` obtained by a central difference (1e-8).
//! 7. proptest: (1) and (3) over random rotations, positions and velocities.
//!
//! "Within 1e-6 of the singular set" per chart: for the Euler charts, `b` at distance `d` from
//! `+-pi/2` (`xyz`, `zyx`) or from `0, pi` (`zxz`), `d in {1e-6, 1e-9, 1e-12, 0}`; the
//! conditioning is then `sin d ~ d` and `d` is also the rotation's geodesic distance to the
//! singular set. The angles themselves are ill-conditioned there (the undetermined
//! combination `a -+ c` moves by `~eps/d`), but the rotation must and does round-trip to 1e-14.
//! For `rotvec` the singular set is the sphere `|phi| = 2 pi`: conditioning 1e-6 is
//! `|phi| = 2 pi (1 - 1e-6)`, which `from_pose` never returns (`|phi| <= pi`) but a run can
//! reach before re-charting: those coordinates are in `Probe::samples`. The other charts have
//! no singular set (conditioning 1).
//!
//! Last, one test integrates `RigidSystem<C, F>` for every chart and both formulations with
//! RK4/RKMK4 (torque-free body, `J = diag(1, 2, 3)`, 2 s at h = 1e-3) and checks that the final
//! states agree to 1e-9: the charts plug into the model consistently.
use nalgebra::{DualQuaternion, Matrix3, Quaternion, UnitQuaternion, Vector3};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

use super::*;
use crate::integrate::System;
use crate::math::so3;
use crate::math::vector::Vector;
use crate::model::rigid_body::{Observation, RigidBody, RigidSystem};

const EPS: f64 = f64::EPSILON;
const H: f64 = 1e-6;

/// Deterministic SplitMix64, uniform in `[-1, 1)`.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    fn vec3(&mut self, s: f64) -> Vector3<f64> {
        Vector3::new(self.next() * s, self.next() * s, self.next() * s)
    }
    /// Uniform on the unit sphere of quaternions (rejection from the 4-cube).
    fn quat(&mut self) -> UnitQuaternion<f64> {
        loop {
            let q = Quaternion::new(self.next(), self.next(), self.next(), self.next());
            let n = q.norm();
            if n > 0.1 && n <= 1.0 {
                return UnitQuaternion::from_quaternion(q);
            }
        }
    }
}

fn to_matrix(q: &UnitQuaternion<f64>) -> Matrix3<f64> {
    q.to_rotation_matrix().into_inner()
}

/// `d` values for "near the singular set" (module docs).
const NEAR: [f64; 4] = [1e-6, 1e-9, 1e-12, 0.0];

/// Rotations near every Euler chart's singular set (both sides), near angle pi and near the
/// identity, each also with generic rounding (`euler::tests::generic`): a matrix built from
/// elementary rotations (or through its quaternion) has its small entries accurate *relative*
/// to their size, which would hide a naive `atan2` of small entries.
fn special_rotations() -> Vec<Matrix3<f64>> {
    let exact = special_rotations_exact();
    let generic: Vec<Matrix3<f64>> = exact.iter().map(euler::tests::generic).collect();
    exact.into_iter().chain(generic).collect()
}

fn special_rotations_exact() -> Vec<Matrix3<f64>> {
    let mut out = Vec::new();
    for d in NEAR {
        for (a, c) in [(0.3, -1.1), (2.9, 2.8), (-3.0, 0.2)] {
            for s in [1.0, -1.0] {
                let b = s * (FRAC_PI_2 - d);
                out.push(euler::xyz_rotation(&Vector3::new(a, b, c)));
                out.push(euler::zyx_rotation(&Vector3::new(a, b, c)));
            }
            out.push(euler::zxz_rotation(&Vector3::new(a, d, c)));
            out.push(euler::zxz_rotation(&Vector3::new(a, PI - d, c)));
        }
    }
    let axis = Vector3::new(0.48, -0.6, 0.64);
    for t in [PI, PI - 1e-6, PI - 1e-9, PI - 1e-12, 1e-6, 1e-12, 0.0] {
        out.push(so3::exp(&(axis * t)));
    }
    for e in [Vector3::x(), Vector3::y(), Vector3::z()] {
        out.push(so3::exp(&(e * PI)));
    }
    out
}

fn random_rotations(n: usize, seed: u64) -> Vec<Matrix3<f64>> {
    let mut rng = Rng(seed);
    (0..n).map(|_| to_matrix(&rng.quat())).collect()
}

/// The stored numbers of a chart's coordinates, flat.
trait Flat {
    fn flat(&self) -> Vec<f64>;
}
impl Flat for Pose<Vector3<f64>> {
    fn flat(&self) -> Vec<f64> {
        self.rot.iter().chain(self.x.iter()).copied().collect()
    }
}
impl Flat for Pose<Quaternion<f64>> {
    fn flat(&self) -> Vec<f64> {
        self.rot
            .coords
            .iter()
            .chain(self.x.iter())
            .copied()
            .collect()
    }
}
impl Flat for Pose<UnitQuaternion<f64>> {
    fn flat(&self) -> Vec<f64> {
        self.rot
            .coords
            .iter()
            .chain(self.x.iter())
            .copied()
            .collect()
    }
}
impl Flat for Pose<Matrix3<f64>> {
    fn flat(&self) -> Vec<f64> {
        self.rot.iter().chain(self.x.iter()).copied().collect()
    }
}
impl Flat for DualQuaternion<f64> {
    fn flat(&self) -> Vec<f64> {
        self.real
            .coords
            .iter()
            .chain(self.dual.coords.iter())
            .copied()
            .collect()
    }
}

/// Chart-specific coordinates that `from_pose` does not produce.
trait Probe: PoseChart<Coords: Flat> {
    /// Other branches, near-singular coordinates, points off the constraint manifold.
    fn samples() -> Vec<Self::Coords>;
}

fn x0() -> Vector3<f64> {
    Vector3::new(1.0, -2.0, 0.5)
}

fn euler_samples(singular: [f64; 2]) -> Vec<Pose<Vector3<f64>>> {
    let mut v = vec![
        Vector3::new(4.0, 2.0, -4.0),
        Vector3::new(-3.5, -0.5, 7.0),
        Vector3::new(0.1, 3.5, -0.2),
    ];
    for b in singular {
        for d in [1e-6, -1e-6, 1e-9] {
            v.push(Vector3::new(0.7, b + d, -2.2));
        }
    }
    v.into_iter().map(|rot| Pose { rot, x: x0() }).collect()
}

impl Probe for EulerXyz {
    fn samples() -> Vec<Self::Coords> {
        euler_samples([FRAC_PI_2, -FRAC_PI_2])
    }
}
impl Probe for EulerZyx {
    fn samples() -> Vec<Self::Coords> {
        euler_samples([FRAC_PI_2, -FRAC_PI_2])
    }
}
impl Probe for EulerZxz {
    fn samples() -> Vec<Self::Coords> {
        euler_samples([0.0, PI])
    }
}
impl Probe for RotVec {
    fn samples() -> Vec<Self::Coords> {
        let axis = Vector3::new(-0.36, 0.48, 0.8);
        [
            0.0,
            1e-9,
            PI - 1e-9,
            PI + 1e-9,
            4.5,
            TAU * (1.0 - 1e-6),
            TAU - 1e-9,
            TAU + 1e-3,
            7.0,
        ]
        .into_iter()
        .map(|t| Pose {
            rot: axis * t,
            x: x0(),
        })
        .collect()
    }
}
fn quat_samples() -> Vec<Pose<Quaternion<f64>>> {
    let q = Quaternion::new(-0.5, 0.5, -0.5, 0.5);
    [
        q,
        q * (1.0 + 1e-8),
        Quaternion::new(0.0, 1.0, 0.0, 0.0),
        q * 1.5,
    ]
    .into_iter()
    .map(|rot| Pose { rot, x: x0() })
    .collect()
}
impl Probe for Quat {
    fn samples() -> Vec<Self::Coords> {
        quat_samples()
    }
}
impl Probe for QuatProj {
    fn samples() -> Vec<Self::Coords> {
        quat_samples()
    }
}
fn matrix_samples() -> Vec<Pose<Matrix3<f64>>> {
    let r = so3::exp(&Vector3::new(0.4, -2.0, 1.0));
    let p = Matrix3::new(0.3, -0.1, 0.2, 0.05, -0.4, 0.1, 0.2, 0.3, 0.25);
    [r, r + p * 1e-8, r + p * 0.3, so3::rx(PI)]
        .into_iter()
        .map(|rot| Pose { rot, x: x0() })
        .collect()
}
impl Probe for Matrix {
    fn samples() -> Vec<Self::Coords> {
        matrix_samples()
    }
}
impl Probe for MatrixProj {
    fn samples() -> Vec<Self::Coords> {
        matrix_samples()
    }
}
fn unit_quat_samples() -> Vec<Pose<UnitQuaternion<f64>>> {
    let q = UnitQuaternion::from_quaternion(Quaternion::new(-0.3, 0.5, 0.7, -0.2));
    let drifted = UnitQuaternion::new_unchecked(q.into_inner() * (1.0 + 1e-9));
    [q, UnitQuaternion::identity(), drifted]
        .into_iter()
        .map(|rot| Pose { rot, x: x0() })
        .collect()
}
impl Probe for So3 {
    fn samples() -> Vec<Self::Coords> {
        unit_quat_samples()
    }
}
impl Probe for Se3Hq {
    fn samples() -> Vec<Self::Coords> {
        unit_quat_samples()
    }
}
impl Probe for DualQuat {
    fn samples() -> Vec<Self::Coords> {
        let p = Quaternion::new(-0.3, 0.5, 0.7, -0.2).normalize();
        let g = dual_quat::from_parts(&p, &x0());
        let drifted = DualQuaternion::from_real_and_dual(g.real * (1.0 + 1e-9), g.dual + p * 1e-9);
        vec![
            g,
            dual_quat::from_parts(&Quaternion::identity(), &x0()),
            drifted,
        ]
    }
}

/// Whether `c` lies on its chart's constraint manifold (to round-off).
fn on_manifold<C: PoseChart>(c: &C::Coords) -> bool {
    C::residual(c).is_none_or(|r| r < 1e-14)
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

/// Test 1; returns the largest rotation and translation errors.
fn round_trip_rotations<C: PoseChart>(rs: &[Matrix3<f64>], x: &Vector3<f64>) -> (f64, f64) {
    let (mut er, mut ex) = (0.0_f64, 0.0_f64);
    for r in rs {
        let c = C::from_pose(r, x);
        let g = so3::geodesic(r, &C::rotation(&c));
        let gq = so3::geodesic_quat(&so3::quat_from_matrix(r), &C::quaternion(&c));
        let dx = (C::position(&c) - x).amax();
        assert!(
            g <= 1e-14 && gq <= 1e-14,
            "{}: geodesic {g:e} / {gq:e} for {r}",
            C::NAME
        );
        assert!(dx <= 8.0 * EPS * (1.0 + x.amax()), "{}: dx {dx:e}", C::NAME);
        assert!(C::is_finite(&c));
        assert!(C::conditioning(&c) >= 0.0);
        match C::residual(&c) {
            // The input's own defect (a few eps for the generically rounded ones) is kept
            // by the matrix charts.
            Some(res) => assert!(
                C::CONSTRAINED && res <= 8.0 * EPS + matrix::orthogonality_defect(r),
                "{}: {res:e}",
                C::NAME
            ),
            None => assert!(!C::CONSTRAINED),
        }
        er = er.max(g);
        ex = ex.max(dx);
    }
    (er, ex)
}

/// Test 3 at one point: the directional difference (`directional`) or the superposed
/// partials; returns the error of `R'` and of `x'`, relative as documented.
fn kinematic_error<C: PoseChart>(
    c: &C::Coords,
    omega: &Vector3<f64>,
    xdot: &Vector3<f64>,
    spatial: bool,
    directional: bool,
) -> (f64, f64) {
    let r = C::rotation(c);
    let v = C::velocity(c, &r, omega, xdot, spatial);
    let expected = r * so3::hat(omega);
    let along = |d: &C::Tangent| {
        let p = C::retract(c, &d.scaled(H), spatial);
        let m = C::retract(c, &d.scaled(-H), spatial);
        (
            (C::rotation(&p) - C::rotation(&m)) / (2.0 * H),
            (C::position(&p) - C::position(&m)) / (2.0 * H),
        )
    };
    if directional {
        let (dr, dx) = along(&v);
        ((dr - expected).amax(), (dx - xdot).amax())
    } else {
        let n = <C::Tangent as Vector>::DIM;
        let mut flat = vec![0.0; n];
        v.write_to(&mut flat);
        let mut dr = Matrix3::zeros();
        let mut dx = Vector3::zeros();
        let mut basis = vec![0.0; n];
        for i in 0..n {
            basis.iter_mut().for_each(|b| *b = 0.0);
            basis[i] = 1.0;
            let (pr, px) = along(&C::Tangent::read_from(&basis));
            dr += pr * flat[i];
            dx += px * flat[i];
        }
        let scale = flat.iter().map(|f| f.abs()).sum::<f64>().max(1.0);
        ((dr - expected).amax() / scale, (dx - xdot).amax() / scale)
    }
}

/// Test 6 (RKMK identity) at one point; returns `|dexp_inv(theta0, xi) - u|`.
fn rkmk_error<C: PoseChart>(
    c: &C::Coords,
    theta0: &C::Tangent,
    u: &C::Tangent,
    spatial: bool,
) -> f64 {
    let at = |s: f64| {
        let mut th = *theta0;
        th.axpy(s, u);
        C::retract(c, &th, spatial)
    };
    let g0 = at(0.0);
    let (p, m) = (at(H), at(-H));
    let r = C::rotation(&g0);
    let rd = (C::rotation(&p) - C::rotation(&m)) / (2.0 * H);
    let xd = (C::position(&p) - C::position(&m)) / (2.0 * H);
    let omega = so3::vee(&(r.transpose() * rd));
    let xi = C::velocity(&g0, &r, &omega, &xd, spatial);
    C::dexp_inv(theta0, &xi, spatial).minus(u).norm_inf()
}

fn random_tangent<T: Vector>(rng: &mut Rng, s: f64) -> T {
    let v: Vec<f64> = (0..T::DIM).map(|_| rng.next() * s).collect();
    T::read_from(&v)
}

/// All seven checks for chart `C`, printing the measured errors (`--nocapture`).
fn check_chart<C: Probe>() {
    let mut rng = Rng(0x5EED ^ C::NAME.len() as u64);
    let x = rng.vec3(2.0);
    let (e_rand, dx_rand, e_spec, dx_spec, min_cond) = check_rotation_round_trip::<C>(&x);
    let e_back = check_chart_round_trip::<C>();
    // The points of the remaining checks: random and special rotations at `x`, and the
    // chart's own on-manifold samples.
    let mut points: Vec<C::Coords> = random_rotations(40, 11)
        .iter()
        .chain(special_rotations().iter())
        .map(|r| C::from_pose(r, &x))
        .collect();
    points.extend(C::samples().into_iter().filter(|c| on_manifold::<C>(c)));
    let (e_dir, e_sup, n_sup) = check_kinematic_map::<C>(&points, &mut rng);
    check_zero_retract::<C>(&points);
    let e_norm = check_normalize::<C>(&points, &mut rng);
    let e_rkmk = check_dexp_inv::<C>(&points, &mut rng);
    println!(
        "{:12} R->c->R rand {e_rand:.1e} special {e_spec:.1e} (x {:.1e}) | c->R->c {e_back:.1e} | \
         kin dir {e_dir:.1e} sup {e_sup:.1e} ({n_sup} near-sing) | normalize {e_norm:.1e} | \
         rkmk {e_rkmk:.1e} | min cond {min_cond:.1e}",
        C::NAME,
        dx_rand.max(dx_spec)
    );
}

/// Check 1: R -> chart -> R over random and special rotations (errors of R and of the position),
/// and the smallest conditioning over the special ones: below 1e-15 for the Euler charts
/// (they reach their singularity), at least 1/2 for the others.
fn check_rotation_round_trip<C: Probe>(x: &Vector3<f64>) -> (f64, f64, f64, f64, f64) {
    let (e_rand, dx_rand) = round_trip_rotations::<C>(&random_rotations(500, 7), x);
    let (e_spec, dx_spec) = round_trip_rotations::<C>(&special_rotations(), x);
    let min_cond = special_rotations()
        .iter()
        .map(|r| C::conditioning(&C::from_pose(r, x)))
        .fold(f64::INFINITY, f64::min);
    match C::NAME {
        "euler_xyz" | "euler_zyx" | "euler_zxz" => assert!(min_cond < 1e-15, "{min_cond}"),
        _ => assert!(min_cond >= 0.5 - 1e-15, "{}: {min_cond}", C::NAME),
    }
    (e_rand, dx_rand, e_spec, dx_spec, min_cond)
}

/// Check 2: chart -> R -> chart, compared as rotations (on-manifold samples; the others' R is not
/// a rotation); returns the largest geodesic error.
fn check_chart_round_trip<C: Probe>() -> f64 {
    let mut e_back = 0.0_f64;
    for c in C::samples() {
        if !on_manifold::<C>(&c) {
            continue;
        }
        let r = C::rotation(&c);
        let c2 = C::from_pose(&r, &C::position(&c));
        let g = so3::geodesic(&r, &C::rotation(&c2));
        assert!(g <= 1e-14, "{}: {c:?} -> {c2:?}: {g:e}", C::NAME);
        assert!((C::position(&c2) - C::position(&c)).amax() <= 8.0 * EPS * 3.0);
        e_back = e_back.max(g);
    }
    e_back
}

/// Check 3: The kinematic map against central differences, direct (conditioning at least 0.1) and
/// superposed (at least 1e-7; an Euler chart must reach a near-singular point); returns the
/// largest errors and the near-singular points reached.
fn check_kinematic_map<C: Probe>(points: &[C::Coords], rng: &mut Rng) -> (f64, f64, usize) {
    let (mut e_dir, mut e_sup, mut n_sup) = (0.0_f64, 0.0_f64, 0);
    for c in points {
        let cond = C::conditioning(c);
        for spatial in [false, true] {
            let omega = rng.vec3(1.0);
            let xdot = rng.vec3(1.0);
            if cond >= 0.1 {
                let (er, ex) = kinematic_error::<C>(c, &omega, &xdot, spatial, true);
                assert!(
                    er <= 1e-8 && ex <= 1e-8,
                    "{} {spatial}: {er:e} {ex:e} at {c:?}",
                    C::NAME
                );
                e_dir = e_dir.max(er.max(ex));
            }
            if cond >= 1e-7 {
                let (er, ex) = kinematic_error::<C>(c, &omega, &xdot, spatial, false);
                assert!(
                    er <= 1e-9 && ex <= 1e-9,
                    "{} {spatial}: {er:e} {ex:e} at {c:?}",
                    C::NAME
                );
                e_sup = e_sup.max(er.max(ex));
                n_sup += (cond < 1e-3) as usize;
            }
        }
    }
    if C::NAME.starts_with("euler") {
        assert!(
            n_sup > 0,
            "no near-singular point reached the superposed check"
        );
    }
    (e_dir, e_sup, n_sup)
}

/// Check 4: Retract by zero is the identity, exactly.
fn check_zero_retract<C: Probe>(points: &[C::Coords]) {
    for c in points {
        for spatial in [false, true] {
            let c2 = C::retract(c, &C::Tangent::zero(), spatial);
            assert_eq!(max_abs_diff(&c.flat(), &c2.flat()), 0.0, "{}", C::NAME);
        }
    }
}

/// Check 5: normalize: idempotent to 4 eps, keeps an on-manifold rotation, reports itself;
/// returns the largest rotation it moved.
fn check_normalize<C: Probe>(points: &[C::Coords], rng: &mut Rng) -> f64 {
    let mut e_norm = 0.0_f64;
    let mut candidates = C::samples();
    for c in points.iter().take(20) {
        candidates.push(C::retract(c, &random_tangent(rng, 0.3), false));
        candidates.push(C::retract(c, &random_tangent(rng, 3.0), true));
    }
    for c in candidates {
        let mut c1 = c;
        let applied = C::normalize(&mut c1);
        if !C::NORMALIZES {
            assert!(!applied);
            assert_eq!(max_abs_diff(&c.flat(), &c1.flat()), 0.0);
        }
        if on_manifold::<C>(&c) {
            let g = so3::geodesic(&C::rotation(&c), &C::rotation(&c1));
            assert!(g <= 1e-14, "{}: normalize moved R by {g:e}", C::NAME);
            e_norm = e_norm.max(g);
        }
        if C::NORMALIZES && C::CONSTRAINED {
            assert!(C::residual(&c1).unwrap() <= 8.0 * EPS, "{}", C::NAME);
        }
        let mut c2 = c1;
        C::normalize(&mut c2);
        let (f1, f2) = (c1.flat(), c2.flat());
        let scale = f1.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        let d = max_abs_diff(&f1, &f2);
        assert!(d <= 4.0 * EPS * scale, "{}: not idempotent, {d:e}", C::NAME);
    }
    e_norm
}

/// Check 6: dexp_inv(0, v) = v; the RKMK identity on Lie charts; returns its largest error.
fn check_dexp_inv<C: Probe>(points: &[C::Coords], rng: &mut Rng) -> f64 {
    let mut e_rkmk = 0.0_f64;
    for spatial in [false, true] {
        let v: C::Tangent = random_tangent(rng, 1.0);
        let w = C::dexp_inv(&C::Tangent::zero(), &v, spatial);
        assert_eq!(w.minus(&v).norm_inf(), 0.0);
        if C::LIE {
            for c in points.iter().take(20) {
                let theta0: C::Tangent = random_tangent(rng, 1.5);
                let u: C::Tangent = random_tangent(rng, 1.0);
                let e = rkmk_error::<C>(c, &theta0, &u, spatial);
                assert!(
                    e <= 1e-8,
                    "{} {spatial}: RKMK identity off by {e:e}",
                    C::NAME
                );
                e_rkmk = e_rkmk.max(e);
            }
        }
    }
    e_rkmk
}

/// proptest strategy: a unit quaternion from four uniform numbers (norm above 0.1).
fn quat_strategy() -> impl Strategy<Value = UnitQuaternion<f64>> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)
        .prop_filter("norm above 0.1", |(a, b, c, d)| {
            a * a + b * b + c * c + d * d > 0.01
        })
        .prop_map(|(a, b, c, d)| UnitQuaternion::from_quaternion(Quaternion::new(a, b, c, d)))
}

fn vec3_strategy(s: f64) -> impl Strategy<Value = Vector3<f64>> {
    (-s..s, -s..s, -s..s).prop_map(|(a, b, c)| Vector3::new(a, b, c))
}

macro_rules! conformance_tests {
    ($t:ident) => {
        #[allow(non_snake_case)]
        mod $t {
            use super::*;
            type C = crate::rotation::$t;

            /// Tests 1-6 of the module docs for this chart.
            #[test]
            fn invariants() {
                check_chart::<C>();
            }

            proptest! {
                /// Test 7: round trip (1e-14) and kinematic map (1e-8, where conditioning
                /// >= 0.1) at random poses and velocities, both formulations.
                #[test]
                fn random_poses(
                    q in quat_strategy(),
                    x in vec3_strategy(3.0),
                    omega in vec3_strategy(2.0),
                    xdot in vec3_strategy(2.0),
                ) {
                    let r = to_matrix(&q);
                    let c = C::from_pose(&r, &x);
                    let g = so3::geodesic(&r, &<C as PoseChart>::rotation(&c));
                    prop_assert!(g <= 1e-14, "geodesic {:e}", g);
                    prop_assert!((<C as PoseChart>::position(&c) - x).amax() <= 8.0 * EPS * 4.0);
                    for spatial in [false, true] {
                        let directional = C::conditioning(&c) >= 0.1;
                        let (er, ex) = kinematic_error::<C>(&c, &omega, &xdot, spatial, directional);
                        let tol = if directional { 1e-8 } else { 1e-9 };
                        prop_assert!(er <= tol && ex <= tol, "{} {:e} {:e}", spatial, er, ex);
                    }
                }
            }
        }
    };
}

/// One test module per chart (nested, so the module names do not shadow the chart types).
mod charts {
    use super::*;
    crate::for_each_chart!(conformance_tests);
}

/// Final state of a torque-free body (`J = diag(1, 2, 3)`, `omega0 = (0.3, 1, 0.2)`, moving
/// with constant velocity) after 2 s of RK4 (RKMK4 on Lie charts) at h = 1e-3, and the
/// smallest conditioning met and the final constraint residual (0 for minimal charts).
fn integrate<C: PoseChart, F: Formulation>() -> (Observation, f64, f64) {
    let body = RigidBody::new(
        1.0,
        Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 3.0)),
        vec![],
        None,
        None,
    )
    .unwrap();
    let sys = RigidSystem::<C, F>::new(body);
    let o = Observation {
        q: so3::quat_from_matrix(&euler::xyz_rotation(&Vector3::new(0.3, -0.4, 0.6))),
        x: Vector3::new(0.1, -0.2, 0.3),
        v: Vector3::new(0.5, 0.0, -0.2),
        omega: Vector3::new(0.3, 1.0, 0.2),
    };
    let mut s = sys.state_from(&o);
    let h = 1e-3;
    let mut min_cond = C::conditioning(&s.pose);
    for k in 0..2000 {
        let t = k as f64 * h;
        // RKMK4: k_i = dexp_inv(theta_i, f(y (+) theta_i)), theta_i = h a_i k_{i-1}.
        let k1 = sys.rhs(t, &s);
        let th2 = k1.scaled(0.5 * h);
        let k2 = sys.dexp_inv(&th2, &sys.rhs(t + 0.5 * h, &sys.retract(&s, &th2)));
        let th3 = k2.scaled(0.5 * h);
        let k3 = sys.dexp_inv(&th3, &sys.rhs(t + 0.5 * h, &sys.retract(&s, &th3)));
        let th4 = k3.scaled(h);
        let k4 = sys.dexp_inv(&th4, &sys.rhs(t + h, &sys.retract(&s, &th4)));
        let mut inc = k1.scaled(h / 6.0);
        inc.axpy(h / 3.0, &k2);
        inc.axpy(h / 3.0, &k3);
        inc.axpy(h / 6.0, &k4);
        s = sys.retract(&s, &inc);
        sys.normalize(&mut s);
        sys.check(t + h, &s).unwrap();
        min_cond = min_cond.min(C::conditioning(&s.pose));
    }
    (
        sys.observe(&s),
        min_cond,
        C::residual(&s.pose).unwrap_or(0.0),
    )
}

/// Every chart in both formulations, integrated by RK4/RKMK4, reaches the same final state as
/// `so3`/body to 1e-9 (RK4's global error at h = 1e-3 over 2 s is ~1e-12 times the chart's
/// error constant), and the free translation is exact (x = x0 + v0 t to 1e-12).
#[test]
fn rk4_agrees_across_charts() {
    let (reference, _, _) = integrate::<So3, Body>();
    let x_exact = Vector3::new(0.1, -0.2, 0.3) + Vector3::new(0.5, 0.0, -0.2) * 2.0;
    assert!((reference.x - x_exact).amax() < 1e-12);
    let mut worst = 0.0_f64;
    macro_rules! compare {
        ($t:ident) => {
            for (spatial, (o, cond, res)) in [
                (false, integrate::<crate::rotation::$t, Body>()),
                (true, integrate::<crate::rotation::$t, Spatial>()),
            ] {
                let g = so3::geodesic_quat(&o.q, &reference.q);
                let dw = (o.omega - reference.omega).amax();
                let dx = (o.x - reference.x).amax().max((o.v - reference.v).amax());
                println!(
                    "{:12} spatial={spatial:5} rotation {g:.1e} omega {dw:.1e} x,v {dx:.1e} min cond {cond:.2} residual {res:.1e}",
                    <crate::rotation::$t as PoseChart>::NAME
                );
                assert!(g <= 1e-9 && dw <= 1e-9 && dx <= 1e-9, "{}", <crate::rotation::$t as PoseChart>::NAME);
                worst = worst.max(g).max(dw);
            }
        };
    }
    crate::for_each_chart!(compare);
    println!("worst rotation/omega disagreement {worst:.1e}");
}
