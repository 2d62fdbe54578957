//! Gauss-Lobatto and Gauss-Legendre rules on `[0, 1]`, the integration points of the beam
//! elements (the force-based element's sections sit at Lobatto points so that the ends, where
//! the moments peak, are sampled; the displacement-based element uses Legendre points).
//!
//! Lobatto with `n` points (`n >= 2`) integrates polynomials up to degree `2n - 3` exactly;
//! its interior points are the roots of `P'_{n-1}`, weights `2 / (n (n - 1) P_{n-1}(x)^2)` on
//! `[-1, 1]` (Abramowitz & Stegun 25.4.32). Legendre with `n` points (`n >= 1`) is exact up to
//! degree `2n - 1`; points the roots of `P_n`, weights `2 / ((1 - x^2) P'_n(x)^2)` (A&S
//! 25.4.29). Roots by Newton's method from Chebyshev-like guesses, to round-off; tested for
//! `n <= 10` (the elements accept at most 10 points).
use std::f64::consts::PI;

/// `P_n(x)` and `P'_n(x)` by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
        p0 = p1;
        p1 = p2;
    }
    let dp = if (1.0 - x * x).abs() < 1e-300 {
        0.5 * (n * (n + 1)) as f64 * x.powi(n as i32 + 1)
    } else {
        n as f64 * (p0 - x * p1) / (1.0 - x * x)
    };
    (p1, dp)
}

/// The `n`-point Gauss-Legendre rule on `[0, 1]`: `(points, weights)`, points increasing.
///
/// # Example
///
/// ```
/// use mbdbench::model::fiber_column::quadrature::legendre_rule;
/// let (x, w) = legendre_rule(3).unwrap();
/// let integral: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(5)).sum();
/// assert!((integral - 1.0 / 6.0).abs() < 1e-15);
/// ```
pub fn legendre_rule(n: usize) -> Result<(Vec<f64>, Vec<f64>), String> {
    if !(1..=10).contains(&n) {
        return Err(format!("{n} Gauss-Legendre points: 1 to 10 are supported"));
    }
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    for i in 0..n {
        let mut t = -(PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        for _ in 0..100 {
            let (p, dp) = legendre(n, t);
            let dt = p / dp;
            t -= dt;
            if dt.abs() < 1e-16 {
                break;
            }
        }
        let (_, dp) = legendre(n, t);
        x[i] = 0.5 * (t + 1.0);
        w[i] = 1.0 / ((1.0 - t * t) * dp * dp);
    }
    Ok((x, w))
}

/// The `n`-point Gauss-Lobatto rule on `[0, 1]` (ends included): `(points, weights)`.
///
/// # Example
///
/// ```
/// use mbdbench::model::fiber_column::quadrature::lobatto_rule;
/// let (x, w) = lobatto_rule(5).unwrap();
/// assert_eq!((x[0], x[4]), (0.0, 1.0));
/// let integral: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(7)).sum();
/// assert!((integral - 1.0 / 8.0).abs() < 1e-15);
/// ```
pub fn lobatto_rule(n: usize) -> Result<(Vec<f64>, Vec<f64>), String> {
    if !(2..=10).contains(&n) {
        return Err(format!("{n} Gauss-Lobatto points: 2 to 10 are supported"));
    }
    let m = n - 1;
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    let end_w = 1.0 / (n * m) as f64;
    x[n - 1] = 1.0;
    w[0] = end_w;
    w[n - 1] = end_w;
    for i in 1..m {
        // Roots of P'_m: Newton on P'_m with P''_m from the Legendre equation.
        let mut t = -(PI * i as f64 / m as f64).cos();
        for _ in 0..100 {
            let (p, dp) = legendre(m, t);
            let d2p = (2.0 * t * dp - (m * (m + 1)) as f64 * p) / (1.0 - t * t);
            let dt = dp / d2p;
            t -= dt;
            if dt.abs() < 1e-16 {
                break;
            }
        }
        let (p, _) = legendre(m, t);
        x[i] = 0.5 * (t + 1.0);
        w[i] = end_w / (p * p);
    }
    Ok((x, w))
}

#[cfg(test)]
mod tests {
    use super::*;

    // Each rule integrates every monomial up to its degree of exactness on [0, 1] to 1e-14,
    // its weights sum to 1, and the points are symmetric about 1/2.
    #[test]
    fn rules_are_exact_to_their_degree() {
        for n in 1..=10 {
            let (x, w) = legendre_rule(n).unwrap();
            for d in 0..=(2 * n - 1) {
                let got: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(d as i32)).sum();
                assert!(
                    (got - 1.0 / (d + 1) as f64).abs() < 1e-14,
                    "Legendre n={n} d={d}"
                );
            }
            for i in 0..n {
                assert!((x[i] + x[n - 1 - i] - 1.0).abs() < 1e-15);
            }
        }
        for n in 2..=10 {
            let (x, w) = lobatto_rule(n).unwrap();
            for d in 0..=(2 * n - 3) {
                let got: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(d as i32)).sum();
                assert!(
                    (got - 1.0 / (d + 1) as f64).abs() < 1e-14,
                    "Lobatto n={n} d={d}"
                );
            }
            for i in 0..n {
                assert!((x[i] + x[n - 1 - i] - 1.0).abs() < 1e-15);
            }
        }
        assert!(lobatto_rule(1).is_err() && legendre_rule(0).is_err());
        assert!(lobatto_rule(11).is_err() && legendre_rule(11).is_err());
    }
}
