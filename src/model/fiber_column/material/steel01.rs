//! OpenSees' `Steel01` (3.7.1, `SRC/material/uniaxial/Steel01.cpp`): the bilinear steel with
//! kinematic hardening, isotropic hardening off (OpenSees' defaults a1 = 0, a2 = 1, a3 = 0,
//! a4 = 1, which make its asymptote shifts identically 1).
//!
//! Equations: with E_sh = b E0 and the trial elastic predictor σ_e = σ_c + E0 (ε − ε_c)
//! from the committed point, the stress is σ_e clipped between the two hardening asymptotes
//! σ = E_sh ε ± f_y (1 − b), i.e. σ = max(E_sh ε − f_y(1−b), min(E_sh ε + f_y(1−b), σ_e)),
//! which is OpenSees' `determineTrialState` with both shifts 1 (the same comparisons in the
//! same order, so the clipping ties resolve as there). On monotonic loading this is the
//! bilinear σ = E0 ε for |ε| ≤ f_y/E0 and ±f_y + E_sh (ε ∓ f_y/E0) beyond; every elastic
//! branch has slope E0 and the two asymptotes stay 2 f_y (1 − b) apart in stress (pure
//! kinematic hardening, no Bauschinger rounding). Since the shifts stay 1, OpenSees' reversal
//! bookkeeping (loading index, min/max strains) cannot change a stress and is left out.
//!
//! Tangent: E0 on the elastic branch, E_sh on an asymptote, chosen as OpenSees does
//! (E0 when |σ − σ_e| < f64::EPSILON, else E_sh); this is the exact derivative along the
//! trial branch (consistent), one-sided at the branch points. Like OpenSees, a trial strain
//! within f64::EPSILON of the committed one returns the committed state. Recoverable energy:
//! σ²/(2 E0), E_unload = E0, exact since unloading is elastic until the opposite asymptote.
//! Parameters: f_y > 0, E0 > 0, 0 ≤ b < 1, all finite. With isotropic hardening off the
//! state needs no history variable: it is the bare point (strain, stress, tangent).
use super::history::{History, Law, Point};
use super::{ParamError, check};

/// Parameters of [`Steel01`] (SI, OpenSees' names): yield stress, initial modulus and
/// hardening ratio.
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Steel01Params {
    /// Yield stress f_y (Pa), > 0.
    pub fy: f64,
    /// Initial elastic modulus E0 (Pa), > 0.
    pub e0: f64,
    /// Strain-hardening ratio b = E_sh / E0, 0 ≤ b < 1.
    pub b: f64,
}

/// A Steel01 fiber: parameters, committed and trial point, committed work.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Steel01 {
    params: Steel01Params,
    history: History<Point>,
}

impl Steel01 {
    /// A virgin Steel01 fiber (zero strain and stress, tangent E0).
    ///
    /// # Example
    /// ```
    /// use mbdbench::model::fiber_column::material::{Steel01, Steel01Params, Uniaxial};
    ///
    /// let mut s = Steel01::new(Steel01Params { fy: 420e6, e0: 200e9, b: 0.01 }).unwrap();
    /// let (stress, tangent) = s.set_trial_strain(0.0121);
    /// assert!((stress - (420e6 + 2e9 * 0.01)).abs() < 1e-3 && tangent == 2e9);
    /// let bad = Steel01Params { fy: -420e6, e0: 200e9, b: 0.01 };
    /// assert!(Steel01::new(bad).unwrap_err().message.starts_with("Steel01: fy = -4.2e8"));
    /// ```
    pub fn new(params: Steel01Params) -> Result<Self, ParamError> {
        let Steel01Params { fy, e0, b } = params;
        check("Steel01", "fy", fy, fy > 0.0, "positive")?;
        check("Steel01", "e0", e0, e0 > 0.0, "positive")?;
        check("Steel01", "b", b, (0.0..1.0).contains(&b), "in [0, 1)")?;
        let virgin = Point {
            strain: 0.0,
            stress: 0.0,
            tangent: e0,
        };
        Ok(Self {
            params,
            history: History::new(virgin),
        })
    }

    /// The parameters it was built with.
    pub fn params(&self) -> Steel01Params {
        self.params
    }
}

impl Law for Steel01 {
    type State = Point;
    fn history(&self) -> &History<Point> {
        &self.history
    }
    fn history_mut(&mut self) -> &mut History<Point> {
        &mut self.history
    }
    #[inline]
    fn trial_state(&self, c: Point, strain: f64) -> Point {
        let Steel01Params { fy, e0, b } = self.params;
        let d_strain = strain - c.strain;
        if d_strain.abs() > f64::EPSILON {
            let e_sh = b * e0;
            let hardening = e_sh * strain;
            let half_band = fy * (1.0 - b);
            let elastic = c.stress + e0 * d_strain;
            // Clip the elastic predictor to the upper, then the lower asymptote.
            let upper = hardening + half_band;
            let mut stress = if upper < elastic { upper } else { elastic };
            let lower = hardening - half_band;
            if lower > stress {
                stress = lower;
            }
            let tangent = if (stress - elastic).abs() < f64::EPSILON {
                e0
            } else {
                e_sh
            };
            Point {
                strain,
                stress,
                tangent,
            }
        } else {
            c
        }
    }
    fn initial_tangent(&self) -> f64 {
        self.params.e0
    }
    fn recoverable_energy(&self) -> f64 {
        let s = self.history.trial().stress;
        s * s / (2.0 * self.params.e0)
    }
}
