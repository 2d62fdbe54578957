//! The static scenes' independent check: the cantilever's equilibrium ODE integrated by
//! shooting, with no elliptic integral. In units of `L` and `EI`, for a dead tip force
//! `alpha = P L^2/EI` across the undeformed axis and a tip moment `m = M L/EI`,
//!
//! `theta'' = -alpha cos theta`, `x' = cos theta`, `y' = sin theta`, `theta(0) = 0`,
//! `theta'(1) = m`
//!
//! (the bending moment at `s` is the tip force's about `(x(s), y(s))` plus the tip moment:
//! `theta'(s) = alpha (x(1) - x(s)) + m`). Classical RK4 with `n` steps integrates it from a
//! guessed root curvature `theta'(0)`, and bisection finds the curvature for which
//! `theta'(1) = m`: `theta'(1)` increases with `theta'(0)` on the bracket
//! `[m, m + alpha]` (at `theta'(0) = m`, `theta'' <= 0` makes `theta'(1) <= m`; at
//! `m + alpha` the integral of `cos theta` is below 1, so `theta'(1) >= m`). Its error is
//! that of RK4, `O(n^-4)`: about 1e-14 with `n = 8192` for loads up to `alpha = 20`.
//! Where it fails: the bracket assumes the branch where the tip rotation stays below pi
//! under the force (the elastica's `alpha` of the cases); with a moment alone
//! (`alpha = 0`) the ODE is the circle, for any `m`.
use super::elastica::ElasticaTip;

/// Integrates the ODE with `n` RK4 steps from `theta'(0) = kappa0`: `(x, y, theta,
/// theta')` at `s = 1`.
fn integrate(alpha: f64, kappa0: f64, n: usize) -> [f64; 4] {
    let rhs = |u: [f64; 4]| {
        let (s, c) = u[0].sin_cos();
        [u[1], -alpha * c, c, s]
    };
    let h = 1.0 / n as f64;
    // State (theta, theta', x, y).
    let mut u = [0.0, kappa0, 0.0, 0.0];
    let add = |u: [f64; 4], k: [f64; 4], w: f64| std::array::from_fn(|i| u[i] + w * k[i]);
    for _ in 0..n {
        let k1 = rhs(u);
        let k2 = rhs(add(u, k1, 0.5 * h));
        let k3 = rhs(add(u, k2, 0.5 * h));
        let k4 = rhs(add(u, k3, h));
        u = std::array::from_fn(|i| u[i] + h / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]));
    }
    [u[2], u[3], u[0], u[1]]
}

/// The tip under the force `alpha` and the moment `m` by shooting with `n` RK4 steps.
///
/// # Example
///
/// ```
/// use mbdbench::model::fiber_column::elastica::{elastica_tip, rollup_tip};
/// use mbdbench::model::fiber_column::shooting::shooting_tip;
///
/// let s = shooting_tip(2.0, 0.0, 4096);
/// let e = elastica_tip(2.0).unwrap();
/// assert!((s.across - e.across).abs() < 1e-12);
/// let r = shooting_tip(0.0, std::f64::consts::PI, 4096);
/// assert!((r.along - rollup_tip(0.5).along).abs() < 1e-12);
/// ```
pub fn shooting_tip(alpha: f64, m: f64, n: usize) -> ElasticaTip {
    let (mut lo, mut hi) = (m, m + alpha);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if integrate(alpha, mid, n)[3] < m {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let [x, y, theta, _] = integrate(alpha, 0.5 * (lo + hi), n);
    ElasticaTip {
        along: x,
        across: y,
        rotation: theta,
    }
}
