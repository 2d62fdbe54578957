//! Exact tips of the cantilever column's static scenes, in units of the length `L`: the
//! elastica under a perpendicular dead tip force (Bisshopp & Drucker 1945) and the roll-up
//! under a tip moment (a circular arc). The rod is inextensible and unshearable, of
//! constant bending stiffness `EI`, clamped at `s = 0` along `x`; `s, x, y` are in units
//! of `L`, `θ(s)` is the tangent's angle from `x`, counter-clockwise.
//!
//! **The elastica.** A dead force `P` in `+y` at the tip, `α = P L²/EI ≥ 0`. The bending
//! moment at `s` is that of the tip force about the point `(x(s), y(s))`:
//!
//! (E1) `θ'(s) = α (x(1) − x(s))`, so `θ'' = −α cos θ`, `θ(0) = 0`, `θ'(1) = 0`,
//! `x' = cos θ`, `y' = sin θ`.
//!
//! With `θ0 = θ(1)` (the tip rotation, `0 ≤ θ0 < π/2`), the first integral is
//!
//! (E2) `θ'² = 2α (sin θ0 − sin θ)`,
//!
//! and at `s = 0` (E1) and (E2) give the tip's `x` with no integral:
//!
//! (E3) `x_tip = θ'(0)/α = √(2 sin θ0 / α)`.
//!
//! The substitution `1 + sin θ = 2p² sin²φ` with `p = sin(π/4 + θ0/2)`,
//! `p² = (1 + sin θ0)/2` (so `θ = θ0` at `φ = π/2`, `θ = 0` at `sin φ1 = 1/(√2 p)`) gives
//! `sin θ0 − sin θ = 2p² cos²φ`, `cos θ = 2p sin φ Δ` with `Δ = √(1 − p² sin²φ)`, and
//! `dθ/√(sin θ0 − sin θ) = √2 dφ/Δ`. Then `∫ ds = 1` becomes Bisshopp and Drucker's
//! length condition, and `∫ sin θ ds` (with `sin θ = 1 − 2Δ²`) the deflection:
//!
//! (E4) `√α = K(p) − F(φ1, p)`, `sin φ1 = 1/(√2 p)`,
//!
//! (E5) `y_tip = 1 − (2/√α) [E(p) − E(φ1, p)]`,
//!
//! Legendre's integrals with modulus `p` (parameter `m = p²`, the `ellip` crate's and
//! mpmath's argument). (E5) loses `log10(1/α)` digits as `α → 0` (`y_tip ≈ α/3` is a
//! difference of two terms near 1), and (E4) needs `K − F` of nearly equal terms. So the
//! integrals are taken over the complementary amplitude `χ = π/2 − φ ∈ [0, χ1]`, with
//! `q = cos(π/4 + θ0/2) = √(1 − p²)`, `Δ² = q² + p² sin²χ`, `sin²χ1 = sin θ0/(2p²)`,
//! `cos²χ1 = 1/(2p²)`, `Δ²(χ1) = 1/2` exactly, and `sin θ = sin θ0 − 2p² sin²χ`. Carlson's
//! forms `∫_0^χ1 dχ/√(1 − k² sin²χ) = s1 R_F(c1², 1 − k² s1², 1)` and
//! `∫_0^χ1 sin²χ dχ/√(1 − k² sin²χ) = (s1³/3) R_D(c1², 1 − k² s1², 1)` (DLMF §19.25(i),
//! `s1 = sin χ1`, `c1 = cos χ1`), taken at `k² = −p²/q²` and rescaled by the homogeneity
//! `R_F(λ·) = λ^(−1/2) R_F`, `R_D(λ·) = λ^(−3/2) R_D` with `λ = q²`, give
//!
//! (E6) `√α = I1 := ∫_0^χ1 dχ/Δ = s1 R_F(q² c1², 1/2, q²)`,
//!
//! (E7) `I2 := ∫_0^χ1 sin²χ dχ/Δ = (q²/3) s1³ R_D(q² c1², 1/2, q²)`, and
//! `y_tip = (sin θ0 I1 − 2p² I2)/√α = sin θ0 (1 − q² R_D / (3 R_F))`,
//!
//! the last form by `I1 = √α` and `2p² s1² = sin θ0` (`R_F`, `R_D` of the arguments of
//! (E6), (E7)). The same two relations turn (E3) into
//!
//! (E3') `x_tip = 2p / R_F(q² c1², 1/2, q²)`, and `sin θ0 = α x_tip²/2` in (E7),
//!
//! which, unlike `√(2 sin θ0/α)`, do not inherit the root's last-ulp error in `θ0` (the
//! arguments vary slowly with `θ0`). `R_F` and `R_D` are sums of positive terms, and the
//! subtraction in (E7) removes a third at most (`q² R_D/(3 R_F)` is `1/3` at `α = 0` and
//! tends to 0), so no digits are lost at either end and nothing underflows as `α → 0`.
//!
//! The solve: `p` and `q` are `cos(δ/2)`, `sin(δ/2)` of the complement `δ = π/2 − θ0`; the
//! unknown is `θ0` while `θ0 ≤ π/4` (`α ≤ α_* = I1(π/4)² ≈ 2.0145`) and `δ` beyond, so
//! that `sin θ0`, `q` and `δ` all keep their relative accuracy from `α → 0` to `δ → 0`.
//! `I1` increases strictly with `θ0`, and Brent's method (bracketing, inverse quadratic
//! and secant steps, bisection safeguard; Brent 1973, ch. 4) solves (E6) to a few ulps: on
//! `θ0 ∈ [0, π/4]` for `I1² = α` (analytic in `θ0` at 0, unlike `I1`), on `δ` for
//! `I1 = √α` in a bracket around the estimate (E9). `R_F`, `R_D` are the `ellip` crate's
//! (Carlson's duplication, Boost's implementation).
//!
//! (E8) Small loads: `θ0 = α/2 − 11α³/240 + O(α⁵)`, `y_tip = α/3 − 4α³/105 + O(α⁵)`,
//! `x_tip = 1 − α²/15 + 4α⁴/315 + O(α⁶)` (regular perturbation of (E1) in powers of `α`:
//! `θ = α θ1 + α³ θ3`, `θ1 = s − s²/2`, `θ3'' = θ1²/2`).
//!
//! (E9) Large loads: `K(p) ≈ ln(4/q)` and `F(φ1, 1) = artanh(1/√2) = ln(1 + √2)` give
//! `δ ≈ 8(√2 − 1) e^{−√α}`, and `x_tip → √(2/α)`, `y_tip → 1 − (2 − √2)/√α`,
//! `θ0 → π/2`. Past `√α = 40` (`α > 1600`, `δ < 1.5e-17`) these limits *are* the answer
//! in doubles (the neglected terms are below 1e-17: `θ0` rounds to `π/2`, `x_tip` differs
//! by `O(δ²)`, `y_tip` by `5e-18` at `α = 1600`, measured with mpmath), and they are
//! returned: so every finite `α ≥ 0` has an answer, and nothing underflows.
//!
//! **Accuracy.** Against 40-digit mpmath values of (E3)-(E5) (tests) the three numbers
//! agree to 5e-16 relative (two ulps) at `α` = 0.5, 1, 2, 5, 10, 20, 50, 200; a shooting
//! solution of (E1) with 8192 RK4 steps (tests) agrees to about 1e-14 for `α` from 0.5 to
//! 20; the series (E8) hold, with the next coefficients as measured by mpmath, at
//! `α = 0.05`, and their two terms to a few ulps from `α = 1e-4` down to `1e-300`; a sweep
//! over `α ∈ [1e-8, 1e6]` is monotone and inside the reach `x² + y² ≤ 1` (to rounding).
//!
//! **Where it fails.** Nowhere on finite `α ≥ 0`: the solve is tested up to `α = 1600`,
//! the limits (E9) beyond, up to `f64::MAX`. What is lost past `α ≈ 1600` is only the
//! relative accuracy of `δ = π/2 − θ0` (not returned; `θ0` is `π/2` in doubles there). The
//! inextensible model itself, of course, leaves the physics long before: a real column
//! yields well below `α ~ 100`. Negative, NaN or infinite `α` are refused.
//!
//! **The roll-up.** A tip moment `M = λ 2π EI/L` bends the whole rod to the curvature
//! `κ = 2πλ` (in `1/L`), an arc of angle `ψ = κ = 2πλ`:
//!
//! (R1) `x_tip = sin ψ / ψ = sin(ψ/2) cos(ψ/2)/(ψ/2)`,
//! `y_tip = (1 − cos ψ)/ψ = sin²(ψ/2)/(ψ/2)`, `θ_tip = ψ`,
//!
//! the half-angle forms having no cancellation as `ψ → 0` (`(1, 0, 0)` at `ψ = 0`). At
//! `λ = 1` the rod closes into a circle: the tip is back at the root to rounding (`1e-16`).
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI, SQRT_2};

/// Tip of the cantilever under a static tip load, in units of the length `L`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElasticaTip {
    /// `x_tip / L`, along the undeformed axis.
    pub along: f64,
    /// `y_tip / L`, across the axis in the direction of the load (the deflection).
    pub across: f64,
    /// The tip's rotation `θ0` in radians, counter-clockwise from the undeformed axis.
    pub rotation: f64,
}

/// Above `√α = 40` the large-load limits (E9) are exact in doubles.
const SQRT_ALPHA_LIMIT: f64 = 40.0;
/// `8 (√2 − 1)`, the constant of the large-load estimate (E9) of `δ = π/2 − θ0`.
const DELTA_SCALE: f64 = 8.0 * (SQRT_2 - 1.0);
/// Brent iterations allowed (a few ulps are reached in about 10).
const MAX_ITERATIONS: usize = 200;

/// The integrands' parameters at a trial tip rotation: `sin θ0`, `p`, `p²`, `q²`.
#[derive(Clone, Copy, Debug)]
struct Trial {
    sin_t0: f64,
    p: f64,
    p2: f64,
    q2: f64,
}

impl Trial {
    /// From `θ0` and its complement `δ = π/2 − θ0`, each given to its own relative
    /// accuracy (`sin θ0` is taken from whichever is the smaller).
    fn new(theta0: f64, delta: f64) -> Self {
        let sin_t0 = if theta0 <= delta {
            theta0.sin()
        } else {
            delta.cos()
        };
        let (q, p) = (0.5 * delta).sin_cos();
        Trial {
            sin_t0,
            p,
            p2: p * p,
            q2: q * q,
        }
    }

    /// `(sin χ1, q² cos²χ1)`, the amplitude's sine and the first Carlson argument.
    fn amplitude(&self) -> (f64, f64) {
        let half_over_p2 = 0.5 / self.p2;
        ((self.sin_t0 * half_over_p2).sqrt(), self.q2 * half_over_p2)
    }

    /// `I1` of (E6), which equals `√α` at the solution.
    fn i1(&self) -> Result<f64, String> {
        let (s1, x) = self.amplitude();
        if s1 == 0.0 {
            return Ok(0.0);
        }
        let rf = ellip::elliprf(x, 0.5, self.q2)
            .map_err(|e| format!("elastica: R_F({x}, 0.5, {}): {e}", self.q2))?;
        Ok(s1 * rf)
    }

    /// `(x_tip, y_tip)` by (E3') and (E7) at the solution of (E6).
    fn along_across(&self, alpha: f64) -> Result<(f64, f64), String> {
        let (_, x) = self.amplitude();
        let rf = ellip::elliprf(x, 0.5, self.q2)
            .map_err(|e| format!("elastica: R_F({x}, 0.5, {}): {e}", self.q2))?;
        let rd = ellip::elliprd(x, 0.5, self.q2)
            .map_err(|e| format!("elastica: R_D({x}, 0.5, {}): {e}", self.q2))?;
        // The rod cannot reach beyond 1, which rounding could suggest as α → 0.
        let along = (2.0 * self.p / rf).min(1.0);
        let sin_t0 = 0.5 * alpha * along * along;
        Ok((along, sin_t0 * (1.0 - self.q2 * rd / (3.0 * rf))))
    }
}

/// Tip of the cantilever elastica under a perpendicular dead tip load, `α = P L²/EI`:
/// (E3'), (E6), (E7) of the module doc, and the limits (E9) past `α = 1600`.
///
/// `Err` for a negative, NaN or infinite `α`; `α = 0` gives the straight rod `(1, 0, 0)`.
///
/// # Example
/// ```
/// use mbdbench::model::fiber_column::elastica::elastica_tip;
///
/// let tip = elastica_tip(1.0).unwrap();
/// // Mattiasson (1981): u/L = 0.05643, w/L = 0.30172, θ0 = 0.46135 at PL²/EI = 1.
/// assert!((1.0 - tip.along - 0.05643).abs() < 5e-6);
/// assert!((tip.across - 0.30172).abs() < 5e-6);
/// assert!((tip.rotation - 0.46135).abs() < 5e-6);
/// assert!(elastica_tip(-1.0).is_err());
/// ```
pub fn elastica_tip(alpha: f64) -> Result<ElasticaTip, String> {
    if !alpha.is_finite() || alpha < 0.0 {
        return Err(format!(
            "elastica: the load parameter alpha = {alpha} must be finite and >= 0"
        ));
    }
    if alpha == 0.0 {
        return Ok(ElasticaTip {
            along: 1.0,
            across: 0.0,
            rotation: 0.0,
        });
    }
    let root_alpha = alpha.sqrt();
    if root_alpha > SQRT_ALPHA_LIMIT {
        return Ok(ElasticaTip {
            along: (2.0 / alpha).sqrt(),
            across: 1.0 - (2.0 - SQRT_2) / root_alpha,
            rotation: FRAC_PI_2,
        });
    }
    let at_quarter = Trial::new(FRAC_PI_4, FRAC_PI_2 - FRAC_PI_4).i1()?;
    let (theta0, trial) = if alpha <= at_quarter * at_quarter {
        // θ0 in [0, π/4]: the residual I1² − α is analytic at θ0 = 0.
        let residual = |t: f64| -> Result<f64, String> {
            let i1 = Trial::new(t, FRAC_PI_2 - t).i1()?;
            Ok(i1 * i1 - alpha)
        };
        let hi = FRAC_PI_4;
        let t = brent(residual, 0.0, -alpha, hi, at_quarter * at_quarter - alpha)?;
        (t, Trial::new(t, FRAC_PI_2 - t))
    } else {
        // δ = π/2 − θ0 in (0, π/4): bracket around the estimate (E9).
        let residual =
            |d: f64| -> Result<f64, String> { Ok(Trial::new(FRAC_PI_2 - d, d).i1()? - root_alpha) };
        let estimate = DELTA_SCALE * (-root_alpha).exp();
        let mut lo = (0.25 * estimate).min(0.5 * FRAC_PI_4);
        let mut f_lo = residual(lo)?;
        while f_lo <= 0.0 {
            lo *= 0.25;
            f_lo = residual(lo)?;
        }
        let mut hi = (4.0 * estimate).min(FRAC_PI_4);
        let mut f_hi = residual(hi)?;
        if f_hi > 0.0 {
            hi = FRAC_PI_4;
            f_hi = at_quarter - root_alpha;
        }
        let d = brent(residual, lo, f_lo, hi, f_hi)?;
        (FRAC_PI_2 - d, Trial::new(FRAC_PI_2 - d, d))
    };
    let (along, across) = trial.along_across(alpha)?;
    Ok(ElasticaTip {
        along,
        across,
        rotation: theta0,
    })
}

/// Tip of the cantilever rolled up by the tip moment `M = λ 2π EI/L`: the arc (R1) of the
/// module doc, of angle `2πλ`. Defined for every finite `λ` (negative rolls the other way;
/// `λ = 1` closes the circle).
///
/// # Example
/// ```
/// use mbdbench::model::fiber_column::elastica::rollup_tip;
/// use std::f64::consts::{FRAC_PI_2, PI};
///
/// let quarter = rollup_tip(0.25); // a quarter circle of radius 2/π
/// assert!((quarter.along - 2.0 / PI).abs() < 1e-15);
/// assert!((quarter.across - 2.0 / PI).abs() < 1e-15);
/// assert_eq!(quarter.rotation, FRAC_PI_2);
/// let full = rollup_tip(1.0);
/// assert!(full.along.abs() < 1e-15 && full.across.abs() < 1e-15);
/// ```
pub fn rollup_tip(lambda: f64) -> ElasticaTip {
    let half = PI * lambda;
    if half == 0.0 {
        return ElasticaTip {
            along: 1.0,
            across: 0.0,
            rotation: 0.0,
        };
    }
    let (s, c) = half.sin_cos();
    let sinc = s / half;
    ElasticaTip {
        along: sinc * c,
        across: sinc * s,
        rotation: 2.0 * half,
    }
}

/// Brent's zero finder on a bracket `[a, b]` with `f(a) f(b) ≤ 0`, to a few ulps of the
/// root: inverse quadratic interpolation or secant steps, each accepted only if it falls
/// well inside the bracket and shrinks it fast enough, else bisection (Brent 1973, ch. 4).
fn brent<F>(mut f: F, mut a: f64, mut fa: f64, mut b: f64, mut fb: f64) -> Result<f64, String>
where
    F: FnMut(f64) -> Result<f64, String>,
{
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 {
        return Ok(b);
    }
    if fa.signum() == fb.signum() || fa.is_nan() || fb.is_nan() {
        return Err(format!(
            "elastica: no sign change on [{a}, {b}] (residuals {fa}, {fb})"
        ));
    }
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..MAX_ITERATIONS {
        if fb.signum() == fc.signum() {
            (c, fc) = (a, fa);
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            (a, fa) = (b, fb);
            (b, fb) = (c, fc);
            (c, fc) = (a, fa);
        }
        let tol = 2.0 * f64::EPSILON * b.abs() + f64::MIN_POSITIVE;
        let xm = 0.5 * (c - b);
        if xm.abs() <= tol || fb == 0.0 {
            return Ok(b);
        }
        if e.abs() >= tol && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            }
            p = p.abs();
            let bound = (3.0 * xm * q - (tol * q).abs()).min((e * q).abs());
            if 2.0 * p < bound {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        (a, fa) = (b, fb);
        b += if d.abs() > tol { d } else { tol.copysign(xm) };
        fb = f(b)?;
        if fb.is_nan() {
            return Err(format!("elastica: residual NaN at {b}"));
        }
    }
    Err(format!(
        "elastica: no convergence in {MAX_ITERATIONS} iterations"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `(α, x_tip, y_tip, θ0)` from the classical forms (E3)-(E5) in 40-digit arithmetic:
    /// `python3` with mpmath 1.3.0, `mp.dps = 40`, `θ0` by 200 bisections of
    /// `ellipk(m) − ellipf(φ1, m) − √α` (`m = p²`), then `ellipe`; printed to 20 digits.
    // 20 significant digits on purpose: the compiler rounds them to the nearest double.
    #[allow(clippy::excessive_precision)]
    const MPMATH: [(f64, f64, f64, f64); 8] = [
        (
            0.5,
            0.98408103752916250338,
            0.16214357565836960515,
            0.24453364713321830851,
        ),
        (
            1.0,
            0.94356676371662311691,
            0.30172077379981352954,
            0.46135194971187896071,
        ),
        (
            2.0,
            0.83935827917483276379,
            0.49345748039671182041,
            0.78174983155654304442,
        ),
        (
            5.0,
            0.61237163927557012814,
            0.71379152361191272809,
            1.2153681176116810959,
        ),
        (
            10.0,
            0.44500440224624873043,
            0.81060902488029645323,
            1.430285538803857529,
        ),
        (
            20.0,
            0.31611443243352486436,
            0.86869589828543780326,
            1.5329349562970412372,
        ),
        (
            50.0,
            0.19999960395040236465,
            0.91715544730358746325,
            1.5679819015714367048,
        ),
        (
            200.0,
            0.099999999999857154789,
            0.95857864376131254642,
            1.5707939364375100396,
        ),
    ];

    fn tip(alpha: f64) -> ElasticaTip {
        elastica_tip(alpha).unwrap()
    }

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    // The three tip numbers agree with 40-digit values of the classical forms to two ulps.
    #[test]
    fn matches_high_precision_values() {
        for (alpha, x, y, t) in MPMATH {
            let got = tip(alpha);
            let errs = [rel(got.along, x), rel(got.across, y), rel(got.rotation, t)];
            for err in errs {
                assert!(
                    err < 1e-15,
                    "alpha = {alpha}: {got:?}, relative errors {errs:?}"
                );
            }
        }
    }

    // Shooting on the ODE (E1) with RK4 (`shooting.rs`: bisection on the root curvature for
    // θ'(1) = 0) gives the same tip as the elliptic solution, independently of (E2)-(E7).
    #[test]
    fn agrees_with_shooting() {
        for alpha in [0.5, 1.0, 2.0, 5.0, 10.0, 20.0] {
            let s = super::super::shooting::shooting_tip(alpha, 0.0, 1 << 13);
            let got = tip(alpha);
            let errs = [got.along - s.along, got.across - s.across, got.rotation - s.rotation];
            for err in errs {
                assert!(err.abs() < 1e-12, "alpha = {alpha}: differences {errs:?}");
            }
        }
    }

    // The classical Legendre forms (E4), (E5) through the `ellip` crate's own incomplete
    // integrals (argument: parameter m = p^2) hold at the solution.
    #[test]
    fn satisfies_the_legendre_forms() {
        for alpha in [1.0, 2.0, 5.0, 10.0] {
            let got = tip(alpha);
            let m = 0.5 * (1.0 + got.rotation.sin());
            let phi1 = (1.0 / (2.0 * m).sqrt()).asin();
            let k_minus_f = ellip::ellipk(m).unwrap() - ellip::ellipf(phi1, m).unwrap();
            let e_minus_e = ellip::ellipe(m).unwrap() - ellip::ellipeinc(phi1, m).unwrap();
            assert!(
                rel(k_minus_f, alpha.sqrt()) < 1e-13,
                "alpha = {alpha}: (E4)"
            );
            let across = 1.0 - 2.0 * e_minus_e / alpha.sqrt();
            assert!(rel(across, got.across) < 1e-13, "alpha = {alpha}: (E5)");
        }
    }

    // The tips at PL^2/EI = 1, 2, 5, 10 match Mattiasson's printed five decimals (1981,
    // IJNME 17, 145-153, Table 1, as transcribed by two public third-party test suites;
    // the rotation only at PL^2/EI = 1).
    #[test]
    fn matches_mattiasson_table() {
        // (α, u/L = 1 − x_tip, w/L = y_tip)
        let table = [
            (1.0, 0.05643, 0.30172),
            (2.0, 0.16064, 0.49346),
            (5.0, 0.38763, 0.71379),
            (10.0, 0.55500, 0.81061),
        ];
        for (alpha, u, w) in table {
            let got = tip(alpha);
            assert!(
                (1.0 - got.along - u).abs() <= 5e-6,
                "alpha = {alpha}: {got:?}"
            );
            assert!((got.across - w).abs() <= 5e-6, "alpha = {alpha}: {got:?}");
        }
        assert!((tip(1.0).rotation - 0.46135).abs() <= 5e-6);
    }

    // Small loads follow the perturbation series (E8): the remainders are O(α^5) for the
    // deflection and rotation and O(α^6) for the axis, with the measured coefficients.
    #[test]
    fn small_load_series() {
        let a: f64 = 0.05;
        let got = tip(a);
        let r_rot = (got.rotation - (a / 2.0 - 11.0 * a.powi(3) / 240.0)) / a.powi(5);
        let r_across = (got.across - (a / 3.0 - 4.0 * a.powi(3) / 105.0)) / a.powi(5);
        let r_along = (got.along - (1.0 - a * a / 15.0 + 4.0 * a.powi(4) / 315.0)) / a.powi(6);
        // mpmath at α = 0.001: 0.0089310, 0.0081385, −0.0031465.
        assert!(rel(r_rot, 0.0089310) < 1e-2, "{r_rot}");
        assert!(rel(r_across, 0.0081385) < 1e-2, "{r_across}");
        assert!(rel(r_along, -0.0031465) < 1e-2, "{r_along}");
        // Below α = 1e-4 the two-term series are exact in doubles, down to the least loads.
        for a in [1e-4, 1e-8, 1e-100, 1e-300] {
            let got = tip(a);
            let (across, rotation) = (
                a / 3.0 - 4.0 * a * a * a / 105.0,
                a / 2.0 - 11.0 * a * a * a / 240.0,
            );
            assert!(rel(got.across, across) < 4e-15, "{a}: {got:?}");
            assert!(rel(got.rotation, rotation) < 4e-15, "{a}: {got:?}");
            assert!(
                (got.along - (1.0 - a * a / 15.0)).abs() < 3e-16,
                "{a}: {got:?}"
            );
        }
        assert_eq!(
            tip(0.0),
            ElasticaTip {
                along: 1.0,
                across: 0.0,
                rotation: 0.0
            }
        );
    }

    // Large loads approach the limits (E9), and the switch to them at √α = 40 is seamless.
    #[test]
    fn large_load_limit() {
        let limit = |a: f64| (2.0 / a).sqrt();
        for a in [1000.0, 1599.0, 1600.0, 1601.0, 1e4, 1e12, f64::MAX] {
            let got = tip(a);
            assert!(rel(got.along, limit(a)) < 1e-11, "{a}: {got:?}");
            let y = 1.0 - (2.0 - SQRT_2) / a.sqrt();
            assert!((got.across - y).abs() < 1e-12, "{a}: {got:?}");
            assert!(
                FRAC_PI_2 - got.rotation < 1e-8 && got.rotation <= FRAC_PI_2,
                "{a}"
            );
        }
        // Either side of the switch, the solved answer equals the limit to rounding.
        let (below, above) = (tip(1599.999), tip(1600.001));
        let lim = |a: f64| 1.0 - (2.0 - SQRT_2) / a.sqrt();
        assert!((below.across - lim(1599.999)).abs() < 3e-16);
        assert!((above.across - lim(1600.001)).abs() < 3e-16);
        assert!(rel(below.along, limit(1599.999)) < 3e-16);
        assert!((below.rotation - FRAC_PI_2).abs() < 3e-16);
    }

    // Over a fine sweep of load steps the tip is finite, stays within reach of the
    // inextensible rod, and moves monotonically: deflection and rotation up, axis down.
    #[test]
    fn sweep_is_monotone_and_within_reach() {
        let mut prev = tip(0.0);
        let n = 4000;
        for i in 1..=n {
            // α from 1e-8 to 1e6, log-spaced, crossing α_* and √α = 40.
            let a = 10f64.powf(-8.0 + 14.0 * i as f64 / n as f64);
            let got = tip(a);
            assert!(got.along.hypot(got.across) <= 1.0 + 2.3e-16, "{a}: {got:?}");
            assert!(got.across > prev.across, "{a}: {got:?} after {prev:?}");
            // (to rounding: `along` is 1 − α²/15, to a few ulps, near α = 1e-8)
            assert!(
                got.along <= prev.along + 4.5e-16,
                "{a}: {got:?} after {prev:?}"
            );
            assert!(
                got.rotation >= prev.rotation && got.rotation <= FRAC_PI_2,
                "{a}"
            );
            prev = got;
        }
        // Every load step λα, λ in (0, 1], of the cases' loads.
        for alpha in [1.0, 2.0, 5.0, 10.0] {
            for k in 1..=100 {
                let got = tip(alpha * k as f64 / 100.0);
                assert!(got.along.is_finite() && got.across.is_finite());
            }
        }
    }

    // Negative, NaN and infinite loads are refused.
    #[test]
    fn refuses_bad_loads() {
        for a in [-1.0, -1e-300, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(elastica_tip(a).is_err(), "{a}");
        }
        assert!(elastica_tip(-0.0).is_ok());
    }

    // At λ = 1 the roll-up closes the circle: tip at the root to 1e-15, rotation 2π.
    #[test]
    fn rollup_closes_the_circle() {
        let full = rollup_tip(1.0);
        assert!(
            full.along.abs() < 1e-15 && full.across.abs() < 1e-15,
            "{full:?}"
        );
        assert_eq!(full.rotation, 2.0 * PI);
        let half = rollup_tip(0.5);
        assert!(half.along.abs() < 1e-16 && rel(half.across, 2.0 / PI) < 1e-15);
        assert_eq!(half.rotation, PI);
    }

    // As λ → 0 the roll-up tends continuously to the straight rod, with the arc's series
    // x = 1 − ψ²/6, y = ψ/2 (ψ = 2πλ) and no cancellation.
    #[test]
    fn rollup_is_continuous_at_zero() {
        assert_eq!(
            rollup_tip(0.0),
            ElasticaTip {
                along: 1.0,
                across: 0.0,
                rotation: 0.0
            }
        );
        for lambda in [1e-3, 1e-6, 1e-12, 1e-200, 1e-300] {
            let got = rollup_tip(lambda);
            let psi = 2.0 * PI * lambda;
            let along = 1.0 - psi * psi / 6.0;
            assert!(
                (got.along - along).abs() < psi.powi(4) / 100.0 + 1.2e-16,
                "{got:?}"
            );
            assert!(
                rel(got.across, psi / 2.0) < psi * psi / 10.0 + 1e-15,
                "{got:?}"
            );
            assert_eq!(got.rotation, psi);
        }
        // The tip lies on the arc: the chord from the root has length 2 sin(ψ/2)/ψ.
        for k in 1..100 {
            let got = rollup_tip(k as f64 / 100.0);
            let half = 0.5 * got.rotation;
            let chord = got.along.hypot(got.across);
            assert!(
                (chord - half.sin().abs() / half).abs() < 1e-15,
                "{k}: {got:?}"
            );
        }
    }
}
