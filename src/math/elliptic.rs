//! Jacobi elliptic functions `sn, cn, dn (u | m)` for `0 <= m <= 1`, the complete integral
//! `K(m)`, and the incomplete integrals `F` and `Pi` written through Carlson's `R_F`, `R_J`.
//!
//! Algorithm: the descending Landen (Gauss) transformation, Abramowitz & Stegun 16.12.1-3
//! (equivalently the AGM, A&S 16.4). With `k' = sqrt(m1)`, `m1 = 1 - m`, one step maps
//! `m -> mu = s^2`, `s = (1 - k')/(1 + k') = m/(1 + k')^2`, `mu1 = 1 - mu = 4 k'/(1 + k')^2`,
//! `v = u/(1 + s)`, and
//! `sn(u|m) = (1 + s) sn(v|mu) / D`, `cn(u|m) = cn(v|mu) dn(v|mu) / D`,
//! `dn(u|m) = ((1 - s) + s cn^2(v|mu)) / D`, `D = 1 + s sn^2(v|mu)`
//! (the `dn` numerator is A&S's `1 - s sn^2` rewritten with `sn^2 + cn^2 = 1`). The upward
//! pass does not carry `sn, cn` themselves (a relative error in `cn ~ 1` doubles per level
//! where `s ~ 1` and is not a backward error in `u`; measured: 256 ulps at `m1 = 1e-300`)
//! but the ratio `t = |tan am| = |sn/cn|` while `t <= 1`, else `r = 1/t`, in which, using
//! `(1 - s) + s = 1` exactly, `t <- (1 + s) t / dn(v|mu)`, `r <- r dn(v|mu) / (1 + s)`,
//! `dn <- (1 + (1 - s) t^2) / (1 + (1 + s) t^2) = ((1 - s) + r^2) / ((1 + s) + r^2)`:
//! sums of positive terms only, so each level's rounding is a small backward error of its
//! own argument (the idea of Bulirsch's 1965 `sncndn`). The signs of `sn` and `cn` are
//! those of `sin v`, `cos v` at the bottom (all denominators are positive). Every
//! quantity of the parameter chain is formed from `k'`
//! without a subtraction (`1 - s = 2 k'/(1 + k')`), so the complementary parameter `m1` may
//! be given directly down to the underflow limit: near `m = 1` (`m1 ~ 1e-11`) nothing is
//! lost. The chain converges quadratically (`s_{i+1} ~ s_i^2/4`); it stops when
//! `mu < 1e-17`, where `sn(v|mu) = sin v` to `mu pi/4 < 1e-17` for `|v| <= pi` (A&S 16.13.1),
//! so the bottom is `sin v, cos v, 1 - mu sin^2 v / 2`: 7 levels at `m1 = 1e-11`, 12 at
//! `m1 = 1e-300`. `K(m) = (1 + s_1) K(mu)` (Landen's transformation, A&S sec. 17.5), so
//! `K = (pi/2) prod(1 + s_i)` on the same chain, which makes the reduction below consistent
//! with the functions.
//!
//! Argument reduction: `u` is reduced to `[-2K, 2K]` modulo the period `4K` with a fused
//! multiply-add (one rounding), so the bottom argument stays in `[-pi, pi]`. The result is
//! backward stable in `u`: the error equals that of a relative perturbation of `u` of a few
//! ulps (plus `|u|/K` ulps of `K`), which is the conditioning of `sn(u)` for a double `u`
//! itself. Near the zeros of `cn` (and of `dn` at `m = 1`) the results keep *absolute*
//! accuracy ~1e-16, with relative accuracy limited by the same backward error.
//!
//! `m1 = 0` (`m = 1`) is the limit `tanh, sech, sech` (no period); `m = 0` gives
//! `sin, cos, 1`. Inputs outside `[0, 1]`, non-finite, or with `m + m1` not 1 to a few ulps
//! are rejected with `Err`; a non-finite `u` gives NaNs.
//!
//! Incomplete integrals, given the amplitude by `(sin phi, cos phi)` for `|phi| <= pi/2`
//! (DLMF 19.25.5 and 19.25.14, `Delta^2 = 1 - m sin^2 = cos^2 + m1 sin^2`, cancellation-free):
//! `F(phi|m) = s R_F(c^2, Delta^2, 1)`,
//! `Pi(phi, nu|m) = s R_F(c^2, Delta^2, 1) + (nu/3) s^3 R_J(c^2, Delta^2, 1, 1 - nu s^2)`.
//! `R_F`, `R_J` come from the `ellip` crate (Carlson's duplication, Boost's implementation).
use std::f64::consts::FRAC_PI_2;

/// Bottom of the Landen chain: below this parameter `sn = sin` to `< 1e-17`.
const MU_BOTTOM: f64 = 1e-17;
/// Enough levels for any `m1 >= 1e-300` (each level at least squares the small parameter).
const MAX_LEVELS: usize = 16;

/// The Jacobi elliptic functions of one parameter `m` (with its complement `m1 = 1 - m`),
/// with the Landen chain precomputed so that each evaluation costs a `sin_cos` and a few
/// multiplications per level.
#[derive(Clone, Copy, Debug)]
pub struct Jacobi {
    m: f64,
    m1: f64,
    /// `s_i` of the chain, top (level 0) first.
    s: [f64; MAX_LEVELS],
    /// `1 - s_i`, formed without cancellation.
    c: [f64; MAX_LEVELS],
    levels: usize,
    /// The bottom parameter `mu < MU_BOTTOM`.
    mu: f64,
    /// `prod (1 + s_i)`, so that `v = u / scale` at the bottom.
    scale: f64,
    /// The quarter period `K(m)` (`inf` at `m = 1`).
    k: f64,
}

impl Jacobi {
    /// From the parameter and its complement, both given (`m + m1 = 1` to a few ulps).
    pub fn new(m: f64, m1: f64) -> Result<Self, String> {
        let in_unit = |x: f64| (0.0..=1.0).contains(&x);
        if !(in_unit(m) && in_unit(m1)) {
            return Err(format!(
                "Jacobi: parameter m = {m}, m1 = {m1} outside [0, 1]"
            ));
        }
        if ((m + m1) - 1.0).abs() > 4.0 * f64::EPSILON {
            return Err(format!("Jacobi: m = {m} and m1 = {m1} do not add up to 1"));
        }
        let mut s = [0.0; MAX_LEVELS];
        let mut c = [0.0; MAX_LEVELS];
        if m1 == 0.0 {
            return Ok(Jacobi {
                m,
                m1,
                s,
                c,
                levels: 0,
                mu: 1.0,
                scale: f64::INFINITY,
                k: f64::INFINITY,
            });
        }
        let (mut mi, mut m1i) = (m, m1);
        let mut levels = 0;
        let mut scale = 1.0;
        while mi >= MU_BOTTOM {
            if levels == MAX_LEVELS {
                return Err(format!(
                    "Jacobi: Landen chain did not converge for m1 = {m1}"
                ));
            }
            let kp = m1i.sqrt();
            let d = 1.0 + kp;
            let si = mi / (d * d);
            s[levels] = si;
            c[levels] = 2.0 * kp / d;
            scale *= 1.0 + si;
            levels += 1;
            mi = si * si;
            m1i = 4.0 * kp / (d * d);
        }
        Ok(Jacobi {
            m,
            m1,
            s,
            c,
            levels,
            mu: mi,
            scale,
            k: FRAC_PI_2 * scale * (1.0 + 0.25 * mi),
        })
    }

    /// From the complementary parameter alone (`m = 1 - m1`); use this near `m = 1`.
    pub fn from_m1(m1: f64) -> Result<Self, String> {
        Self::new(1.0 - m1, m1)
    }

    /// From the parameter alone (`m1 = 1 - m`); use this near `m = 0`.
    pub fn from_m(m: f64) -> Result<Self, String> {
        Self::new(m, 1.0 - m)
    }

    /// The parameter `m`.
    pub fn m(&self) -> f64 {
        self.m
    }

    /// The complementary parameter `m1 = 1 - m`.
    pub fn m1(&self) -> f64 {
        self.m1
    }

    /// The quarter period `K(m)` (`inf` at `m = 1`).
    pub fn k(&self) -> f64 {
        self.k
    }

    /// `(sn, cn, dn)(u | m)`.
    #[inline]
    pub fn sn_cn_dn(&self, u: f64) -> (f64, f64, f64) {
        if !u.is_finite() {
            return (f64::NAN, f64::NAN, f64::NAN);
        }
        if self.m1 == 0.0 {
            let sech = 1.0 / u.cosh();
            return (u.tanh(), sech, sech);
        }
        let period = 4.0 * self.k;
        let turns = (u / period).round();
        let ur = (-turns).mul_add(period, u);
        let v = ur / self.scale;
        let (sv, cv) = v.sin_cos();
        // The signs of sn and cn are the same at every level (the denominators are
        // positive), so the chain carries |tan am| (`t`, while <= 1) or |cot am| (`r`).
        let mut dn = 1.0 - 0.5 * self.mu * sv * sv;
        let mut small_tan = sv.abs() <= cv.abs();
        let mut x = if small_tan {
            (sv / cv).abs()
        } else {
            (cv / sv).abs()
        };
        for i in (0..self.levels).rev() {
            let (s, c) = (self.s[i], self.c[i]);
            let x2 = x * x;
            if small_tan {
                let dn_up = (1.0 + c * x2) / (1.0 + (1.0 + s) * x2);
                x *= (1.0 + s) / dn;
                dn = dn_up;
                if x > 1.0 {
                    x = 1.0 / x;
                    small_tan = false;
                }
            } else {
                let dn_up = (c + x2) / ((1.0 + s) + x2);
                x *= dn / (1.0 + s);
                dn = dn_up;
            }
        }
        let h = 1.0 / x.hypot(1.0);
        let (sn_abs, cn_abs) = if small_tan { (x * h, h) } else { (h, x * h) };
        (sn_abs.copysign(sv), cn_abs.copysign(cv), dn)
    }
}

/// `(sn, cn, dn)(u | m)` with the parameter given by `m` and its complement `m1`.
pub fn sn_cn_dn(u: f64, m: f64, m1: f64) -> Result<(f64, f64, f64), String> {
    Ok(Jacobi::new(m, m1)?.sn_cn_dn(u))
}

/// Complete integral of the first kind `K(m)` from `m` and `m1 = 1 - m`.
pub fn complete_k(m: f64, m1: f64) -> Result<f64, String> {
    Ok(Jacobi::new(m, m1)?.k())
}

/// Carlson `R_F` with the error as a `String`.
pub fn carlson_rf(x: f64, y: f64, z: f64) -> Result<f64, String> {
    ellip::elliprf(x, y, z).map_err(|e| format!("R_F({x}, {y}, {z}): {e}"))
}

/// Carlson `R_J` with the error as a `String`.
pub fn carlson_rj(x: f64, y: f64, z: f64, p: f64) -> Result<f64, String> {
    ellip::elliprj(x, y, z, p).map_err(|e| format!("R_J({x}, {y}, {z}, {p}): {e}"))
}

/// `F(phi | m)` for `|phi| <= pi/2` given `s = sin phi`, `c = cos phi >= 0` and `m1`.
pub fn incomplete_f_sc(s: f64, c: f64, m1: f64) -> Result<f64, String> {
    if s == 0.0 {
        return Ok(0.0);
    }
    let c2 = c * c;
    Ok(s * carlson_rf(c2, c2 + m1 * s * s, 1.0)?)
}

/// `Pi(phi, nu | m)` (`∫_0^phi dθ / ((1 - nu sin^2 θ) sqrt(1 - m sin^2 θ))`) for
/// `|phi| <= pi/2` given `s = sin phi`, `c = cos phi >= 0`, `m1`, and `nu < 1` (here only
/// `nu s^2 < 1` is used, so no principal value is taken).
pub fn incomplete_pi_sc(s: f64, c: f64, m1: f64, nu: f64) -> Result<f64, String> {
    if s == 0.0 {
        return Ok(0.0);
    }
    let c2 = c * c;
    let d2 = c2 + m1 * s * s;
    let s2 = s * s;
    let p = 1.0 - nu * s2;
    if p <= 0.0 {
        return Err(format!(
            "Pi: characteristic nu = {nu} reaches the pole at sin^2 = {s2}"
        ));
    }
    Ok(s * carlson_rf(c2, d2, 1.0)? + nu / 3.0 * s * s2 * carlson_rj(c2, d2, 1.0, p)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// High-precision values `(m1, u, sn, cn, dn)` with `m = 1 - m1` exact, produced by
    /// `python3` with mpmath 1.3.0, `mp.dps = 40`, `mp.ellipfun('sn'|'cn'|'dn', mpf(u),
    /// m = 1 - mpf(m1))` (inputs are the doubles written here).
    // 20 significant digits on purpose: the compiler rounds them to the nearest double.
    #[allow(clippy::excessive_precision)]
    const MPMATH: [(f64, f64, f64, f64, f64); 15] = [
        (
            0.5,
            0.7,
            0.6243400909662173451,
            0.78115264245363431444,
            0.89727349532132493796,
        ),
        (
            0.5,
            -2.2,
            -0.96964460170058955145,
            -0.24451860132289536378,
            0.72793864658805725698,
        ),
        (
            0.5,
            3.0,
            0.63002899824203316449,
            -0.77657160737058895625,
            0.89528304501262062372,
        ),
        (
            0.1,
            1.3,
            0.8746262090428203778,
            0.48479789031655724563,
            0.5581452275258171612,
        ),
        (
            0.001,
            2.5,
            0.9868433222515610334,
            0.16167948950779645558,
            0.16466364829607706261,
        ),
        (
            0.001,
            -6.0,
            -0.99896935040451338735,
            -0.045389833138981118994,
            0.055300784039940736215,
        ),
        (
            1e-11,
            0.5,
            0.46211715726018199173,
            0.88681888396998415873,
            0.88681888397118819414,
        ),
        (
            1e-11,
            5.0,
            0.99990920426509263441,
            0.013475282035981799934,
            0.013475282406964166144,
        ),
        (
            1e-11,
            13.0,
            0.99999999999212890819,
            3.9676420740974725902e-6,
            5.0736755540723208264e-6,
        ),
        (
            1e-11,
            14.0,
            0.99999999999998723165,
            1.5980208310446853768e-7,
            3.1663127934182800028e-6,
        ),
        (
            1e-11,
            20.0,
            0.99999981610777719981,
            -0.00060645231616676483721,
            0.0006064605607789807921,
        ),
        (
            1e-11,
            -27.0,
            -0.8008668097723904623,
            -0.59884251102021285002,
            0.5988425110255680781,
        ),
        (
            0.99999,
            0.9,
            0.78332626769648050779,
            0.62161077720443502467,
            0.99999693199508537039,
        ),
        (
            0.3,
            1000.25,
            0.07491175373020891033,
            -0.99719016699577645374,
            0.9980339475224002479,
        ),
        (
            0.3,
            -12345.5,
            -0.88047079080208293841,
            0.47410039711474056358,
            0.67626905191724416448,
        ),
    ];

    /// `(m1, K(1 - m1))` from mpmath (same command, `mp.ellipk(1 - mpf(m1))`).
    #[allow(clippy::excessive_precision)]
    const MPMATH_K: [(f64, f64); 5] = [
        (0.5, 1.8540746773013719184),
        (0.001, 4.8411325605502970199),
        (1e-11, 14.050512372619768192),
        (0.3, 2.0753631352924691602),
        (0.99999, 1.5708002538078030653),
    ];

    const EPS: f64 = f64::EPSILON;

    fn params() -> Vec<f64> {
        vec![1.0, 0.9, 0.5, 0.1, 1e-3, 1e-6, 1e-11, 1e-15, 1e-30, 1e-300]
    }

    fn args() -> Vec<f64> {
        vec![
            0.0, 1e-9, 0.3, -0.8, 1.7, 3.3, -5.1, 9.0, 14.0, 17.5, -40.0, 123.4,
        ]
    }

    /// sn, cn, dn agree with 40-digit mpmath values to the backward error of `u`: a few ulps
    /// times `(1 + |u|)` (the derivatives are bounded by 1), across the whole parameter range.
    #[test]
    fn against_mpmath() {
        let mut worst: f64 = 0.0;
        for &(m1, u, sn, cn, dn) in &MPMATH {
            let j = Jacobi::from_m1(m1).unwrap();
            let (s, c, d) = j.sn_cn_dn(u);
            let err = (s - sn).abs().max((c - cn).abs()).max((d - dn).abs());
            let tol = 4.0 * EPS * (1.0 + u.abs());
            assert!(err <= tol, "m1 {m1} u {u}: err {err:e} > {tol:e}");
            worst = worst.max(err / (EPS * (1.0 + u.abs())));
        }
        eprintln!("worst sn/cn/dn error vs mpmath: {worst:.2} eps (1 + |u|)");
    }

    /// Near `m = 1` the tiny `cn` and `dn` keep their relative accuracy up to the backward
    /// error of `u` (a few ulps of `u`) times their log-derivatives `sn dn / cn`,
    /// `m sn cn / dn` (e.g. `cn(14 | 1 - 1e-11) ~ 1.6e-7` has log-derivative ~20).
    #[test]
    fn relative_accuracy_near_separatrix() {
        for &(m1, u, sn, cn, dn) in MPMATH.iter().filter(|p| p.0 == 1e-11 && p.1 > 10.0) {
            let (_, c, d) = Jacobi::from_m1(m1).unwrap().sn_cn_dn(u);
            let (rc, rd) = ((c - cn).abs() / cn.abs(), (d - dn).abs() / dn.abs());
            let back = 4.0 * EPS * u.abs();
            let tol_c = 8.0 * EPS + back * (sn * dn / cn).abs();
            let tol_d = 8.0 * EPS + back * (sn * cn / dn).abs();
            assert!(rc <= tol_c, "u {u}: rel cn {rc:e} > {tol_c:e}");
            assert!(rd <= tol_d, "u {u}: rel dn {rd:e} > {tol_d:e}");
            eprintln!("u {u}: rel err cn {rc:.1e} (tol {tol_c:.1e}), dn {rd:.1e} ({tol_d:.1e})");
        }
    }

    /// `K(m)` agrees with mpmath to a few ulps, and with `ellip`'s `R_F(0, m1, 1)`.
    #[test]
    fn complete_k_against_mpmath_and_carlson() {
        for &(m1, k) in &MPMATH_K {
            let j = Jacobi::from_m1(m1).unwrap();
            assert!(
                (j.k() - k).abs() <= 4.0 * EPS * k,
                "m1 {m1}: K {} vs {k}",
                j.k()
            );
            let rf = carlson_rf(0.0, m1, 1.0).unwrap();
            assert!(
                (j.k() - rf).abs() <= 8.0 * EPS * k,
                "m1 {m1}: R_F {rf} vs {}",
                j.k()
            );
        }
        assert!((complete_k(0.0, 1.0).unwrap() - FRAC_PI_2).abs() <= EPS);
        assert!(complete_k(1.0, 0.0).unwrap().is_infinite());
    }

    /// `sn^2 + cn^2 = 1` and `dn^2 + m sn^2 = 1` (also `dn^2 = m1 + m cn^2`) to a few ulps.
    #[test]
    fn identities() {
        for m1 in params() {
            let j = Jacobi::from_m1(m1).unwrap();
            let m = j.m();
            for u in args() {
                let (s, c, d) = j.sn_cn_dn(u);
                assert!((s * s + c * c - 1.0).abs() <= 8.0 * EPS, "m1 {m1} u {u}");
                assert!(
                    (d * d + m * s * s - 1.0).abs() <= 8.0 * EPS,
                    "m1 {m1} u {u}"
                );
                // The cancellation-free form agrees relative to dn itself (dn >= sqrt(m1)).
                let d2 = (m1 + m * c * c).sqrt();
                assert!(
                    (d - d2).abs() <= 8.0 * EPS * d,
                    "m1 {m1} u {u}: {d} vs {d2}"
                );
            }
        }
    }

    /// `d sn/du = cn dn`, `d cn/du = -sn dn`, `d dn/du = -m sn cn` by central differences
    /// (`h = 1e-5`: truncation `h^2/6 |f'''| <= 1e-10 (1 + 4m)`, round-off `eps/h ~ 2e-11`).
    #[test]
    fn derivatives() {
        let h = 1e-5;
        for m1 in params() {
            let j = Jacobi::from_m1(m1).unwrap();
            let m = j.m();
            for u in args() {
                let (sp, cp, dp) = j.sn_cn_dn(u + h);
                let (sm, cm, dm) = j.sn_cn_dn(u - h);
                let (s, c, d) = j.sn_cn_dn(u);
                let tol = 1e-9;
                assert!(
                    ((sp - sm) / (2.0 * h) - c * d).abs() <= tol,
                    "sn' m1 {m1} u {u}"
                );
                assert!(
                    ((cp - cm) / (2.0 * h) + s * d).abs() <= tol,
                    "cn' m1 {m1} u {u}"
                );
                assert!(
                    ((dp - dm) / (2.0 * h) + m * s * c).abs() <= tol,
                    "dn' m1 {m1} u {u}"
                );
            }
        }
    }

    /// `m = 0` gives `sin, cos, 1` and `m = 1` gives `tanh, sech, sech` to round-off; a tiny
    /// `m1` approaches the `m = 1` limit well inside a quarter period (error `O(m1 cosh^2 u)`).
    #[test]
    fn limits() {
        let j0 = Jacobi::from_m(0.0).unwrap();
        let j1 = Jacobi::from_m1(0.0).unwrap();
        let jt = Jacobi::from_m1(1e-30).unwrap();
        for u in args() {
            let (s, c, d) = j0.sn_cn_dn(u);
            let tol = 2.0 * EPS * (1.0 + u.abs());
            assert!((s - u.sin()).abs() <= tol && (c - u.cos()).abs() <= tol && d == 1.0);
            let (s, c, d) = j1.sn_cn_dn(u);
            let sech = 1.0 / u.cosh();
            assert!((s - u.tanh()).abs() <= EPS && (c - sech).abs() <= EPS * sech);
            assert!((d - sech).abs() <= EPS * sech);
            if u.abs() < 20.0 {
                let (s, c, d) = jt.sn_cn_dn(u);
                let tol = 4.0 * EPS * (1.0 + u.abs());
                assert!((s - u.tanh()).abs() <= tol, "u {u}: {s} vs {}", u.tanh());
                assert!((c - sech).abs() <= tol && (d - sech).abs() <= tol, "u {u}");
            }
        }
    }

    /// Period `4K` (sn, cn) and `2K` (dn); quarter-period values `sn(K) = 1`, `cn(K) = 0`,
    /// `dn(K) = sqrt(m1)`. Far arguments (`u ~ 1e3 K`) keep the backward accuracy: the
    /// difference is the rounding of `u + 4 n K`, i.e. `~ eps (|u| + 4 n K)`.
    #[test]
    fn periodicity() {
        for m1 in params().into_iter().filter(|&m1| m1 > 0.0) {
            let j = Jacobi::from_m1(m1).unwrap();
            let k = j.k();
            let (s, c, d) = j.sn_cn_dn(k);
            assert!((s - 1.0).abs() <= 4.0 * EPS, "m1 {m1}: sn(K) = {s}");
            assert!(c.abs() <= 4.0 * EPS * k.max(1.0), "m1 {m1}: cn(K) = {c}");
            assert!(
                (d - m1.sqrt()).abs() <= 4.0 * EPS * k.max(1.0),
                "m1 {m1}: dn(K) = {d}"
            );
            for u in [0.37, -1.2, 2.9] {
                let (s0, c0, d0) = j.sn_cn_dn(u);
                for n in [1.0, -3.0, 250.0, 1000.0] {
                    let un = u + 4.0 * n * k;
                    let (s1, c1, d1) = j.sn_cn_dn(un);
                    let tol = 4.0 * EPS * un.abs();
                    assert!(
                        (s1 - s0).abs() <= tol && (c1 - c0).abs() <= tol,
                        "m1 {m1} n {n}"
                    );
                    assert!((d1 - d0).abs() <= tol, "m1 {m1} n {n}");
                    let (_, _, d2) = j.sn_cn_dn(u + 2.0 * n * k);
                    assert!((d2 - d0).abs() <= tol, "dn half period m1 {m1} n {n}");
                }
            }
        }
    }

    /// `F(am u | m) = u` for `|u| <= K` and `Pi(phi, 0 | m) = F`; `Pi` with `nu < 0` against
    /// a Simpson quadrature of its defining integral in the amplitude (smooth integrand).
    #[test]
    fn incomplete_integrals() {
        for m1 in [0.5, 1e-3, 1e-11] {
            let j = Jacobi::from_m1(m1).unwrap();
            for frac in [0.1, 0.5, 0.9, 0.999, -0.7] {
                let u = frac * j.k();
                let (s, c, _) = j.sn_cn_dn(u);
                let f = incomplete_f_sc(s, c, m1).unwrap();
                assert!((f - u).abs() <= 8.0 * EPS * j.k(), "m1 {m1} u {u}: F {f}");
                let p0 = incomplete_pi_sc(s, c, m1, 0.0).unwrap();
                assert!((p0 - f).abs() <= 4.0 * EPS * f.abs());
            }
        }
        // Pi(phi, nu | m) with phi = 1.2, m = 0.5, nu = -4/3 by composite Simpson (N = 2000,
        // error ~ N^-4 |f''''| ~ 1e-13).
        let (phi, m, nu) = (1.2_f64, 0.5_f64, -4.0 / 3.0);
        let f = |t: f64| 1.0 / ((1.0 - nu * t.sin().powi(2)) * (1.0 - m * t.sin().powi(2)).sqrt());
        let n = 2000;
        let h = phi / n as f64;
        let mut sum = f(0.0) + f(phi);
        for i in 1..n {
            sum += if i % 2 == 1 { 4.0 } else { 2.0 } * f(i as f64 * h);
        }
        let quad = sum * h / 3.0;
        let p = incomplete_pi_sc(phi.sin(), phi.cos(), 1.0 - m, nu).unwrap();
        assert!((p - quad).abs() <= 1e-12, "Pi {p} vs Simpson {quad}");
    }

    /// Bad parameters are rejected, bad arguments give NaN (never a panic).
    #[test]
    fn rejects() {
        assert!(Jacobi::new(1.2, -0.2).is_err());
        assert!(Jacobi::new(0.5, 0.6).is_err());
        assert!(Jacobi::from_m1(f64::NAN).is_err());
        let (s, _, _) = Jacobi::from_m1(0.5).unwrap().sn_cn_dn(f64::INFINITY);
        assert!(s.is_nan());
    }
}
