//! The coefficients of the generalized-alpha family, derived once for every method that uses
//! them: the structural `gen_alpha`, `gen_alpha_i3` and `hht` (`structural/`), the Lie-group
//! `lie_gen_alpha` (here) and the fiber column's dynamic schemes.
//!
//! From the spectral radius at infinity `rho_inf` in `[0, 1]` (Chung & Hulbert, "A time
//! integration algorithm for structural dynamics with improved numerical dissipation: the
//! generalized-alpha method", J. Appl. Mech. 60, 1993, eqs. 16, 23, 25):
//! `alpha_m = (2 rho_inf - 1)/(rho_inf + 1)`, `alpha_f = rho_inf/(rho_inf + 1)`,
//! `gamma = 1/2 - alpha_m + alpha_f` (second order), `beta = (1 - alpha_m + alpha_f)^2 / 4`
//! (unconditional stability with the least low-frequency dissipation). HHT-alpha (Hilber,
//! Hughes & Taylor 1977) is the member with `alpha_m = 0`, `alpha_f = -alpha`. A value outside
//! the range is an error naming the method and the value, never a panic.

/// The coefficients of a generalized-alpha method (Chung & Hulbert's family, HHT included), all
/// set by the spectral radius at infinity `rho_inf`.
///
/// # Example
///
/// ```
/// use mbdbench::integrate::gen_alpha_coefficients::Coefficients;
///
/// let c = Coefficients::new(0.9, "gen_alpha").unwrap();
/// assert!((c.gamma - (0.5 - c.alpha_m + c.alpha_f)).abs() < 1e-16);
/// let h = Coefficients::hht(-0.1, "hht").unwrap();
/// assert_eq!((h.alpha_m, h.alpha_f), (0.0, 0.1));
/// assert!(Coefficients::new(1.5, "gen_alpha").unwrap_err().contains("rho_inf = 1.5"));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coefficients {
    pub rho_inf: f64,
    pub alpha_m: f64,
    pub alpha_f: f64,
    pub beta: f64,
    pub gamma: f64,
}

/// The coefficients from `rho_inf` or from HHT's `alpha`, or an error naming the bad value
/// (every generalized-alpha method of the suite builds its coefficients here).
impl Coefficients {
    /// The coefficients for `rho_inf` in `[0, 1]` (Chung & Hulbert); an error names `method`
    /// and the bad value.
    pub fn new(rho_inf: f64, method: &str) -> Result<Coefficients, String> {
        if !(rho_inf.is_finite() && (0.0..=1.0).contains(&rho_inf)) {
            return Err(format!("{method} rho_inf = {rho_inf} must be in [0, 1]"));
        }
        let alpha_m = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
        let alpha_f = rho_inf / (rho_inf + 1.0);
        Ok(Coefficients {
            rho_inf,
            alpha_m,
            alpha_f,
            gamma: 0.5 - alpha_m + alpha_f,
            beta: (1.0 - alpha_m + alpha_f).powi(2) / 4.0,
        })
    }

    /// HHT-alpha as a member of the family (Hilber, Hughes & Taylor 1977): `alpha_m = 0`,
    /// `alpha_f = -alpha`, `beta = (1 - alpha)^2 / 4`, `gamma = 1/2 - alpha`, for `alpha` in
    /// `[-1/3, 0]` (`rho_inf = (1 + alpha) / (1 - alpha)`); an error names `method`.
    pub fn hht(alpha: f64, method: &str) -> Result<Coefficients, String> {
        if !(alpha.is_finite() && (-1.0 / 3.0..=0.0).contains(&alpha)) {
            return Err(format!("{method} alpha = {alpha} must be in [-1/3, 0]"));
        }
        Ok(Coefficients {
            rho_inf: (1.0 + alpha) / (1.0 - alpha),
            alpha_m: 0.0,
            alpha_f: -alpha,
            beta: (1.0 - alpha).powi(2) / 4.0,
            gamma: 0.5 - alpha,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At the ends of the range the family is the trapezoidal rule (`rho_inf = 1`: alpha_m =
    /// alpha_f = 1/2, gamma = 1/2, beta = 1/4) and the asymptotically annihilating method
    /// (`rho_inf = 0`: alpha_m = -1, alpha_f = 0, gamma = 3/2, beta = 1); NaN and values
    /// outside [0, 1] are errors naming the value.
    #[test]
    fn ends_of_the_range_and_bad_values() {
        let c = Coefficients::new(1.0, "m").unwrap();
        assert_eq!(
            (c.alpha_m, c.alpha_f, c.gamma, c.beta),
            (0.5, 0.5, 0.5, 0.25)
        );
        let c = Coefficients::new(0.0, "m").unwrap();
        assert_eq!(
            (c.alpha_m, c.alpha_f, c.gamma, c.beta),
            (-1.0, 0.0, 1.5, 1.0)
        );
        for bad in [f64::NAN, -0.1, 1.1, f64::INFINITY] {
            let e = Coefficients::new(bad, "m").unwrap_err();
            assert!(e.contains(&format!("rho_inf = {bad}")), "{e}");
        }
        assert!(Coefficients::hht(f64::NAN, "hht").is_err());
    }
}
