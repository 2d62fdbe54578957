//! OpenSees' `Concrete01` (3.7.1, `SRC/material/uniaxial/Concrete01.cpp`): the uniaxial
//! Kent-Scott-Park concrete (Kent & Park 1971; Scott, Park & Priestley 1982) with degraded
//! linear unloading and reloading after Karsan & Jirsa (1969), and no tensile strength.
//!
//! Envelope (compression negative, η = ε/ε_c0, E_c0 = 2 f'_c/ε_c0): the parabola
//! σ = f'_c (2η − η²) down to ε_c0, the line from (ε_c0, f'_c) to (ε_cu, f_cu), then the flat
//! σ = f_cu. Unloading from the smallest strain reached ε_min goes down a straight line to
//! zero stress at the plastic strain ε_p = ε_c0 (0.145 η_m² + 0.13 η_m) for η_m < 2, else
//! ε_c0 (0.707 (η_m − 2) + 0.834) (Karsan & Jirsa's fit, η_m = max(ε_min, ε_cu)/ε_c0), with
//! the slope E_u = σ(ε_min)/(ε_min − ε_p) capped at E_c0 (if the secant would be steeper,
//! E_u = E_c0 and ε_p moves to ε_min − σ(ε_min)/E_c0). Stress is zero for ε > ε_p and for any
//! ε > 0.
//!
//! OpenSees' quirks, kept: (1) reloading after a partial unloading climbs the unloading line
//! itself, elastic, back to (ε_min, σ(ε_min)), with no separate reloading curve; (2) the
//! Karsan-Jirsa strain ratio stops growing at ε_cu (η_m is clamped) while ε_min keeps going, so
//! past ε_cu the unloading line gets flatter as ε_min grows; with f_cu = 0 its slope is 0;
//! (3) any ε > 0 returns (0, 0) at once, leaving the history untouched; (4) a trial strain
//! within f64::EPSILON of the committed one returns the committed state; (5) going further into
//! compression, OpenSees replaces the branch stress by the elastic predictor
//! σ_c + E_u,c (ε − ε_c) whenever the predictor is the larger (less compressive). From every
//! reachable state the predictor is at least as compressive as the branch (E_u is never below
//! the envelope's tangent and no committed point is more compressive than its unloading
//! line), so that clamp does not bind (it never fired along the test histories); it is kept,
//! evaluated as OpenSees evaluates it.
//!
//! Tangent: the exact slope of the trial branch (parabola, descending line, 0 on the flat and
//! in the zero-stress gap, E_u on the line), consistent, one-sided at branch points, and equal
//! to OpenSees' bit for bit on the reference histories. One deviation written in, unreachable
//! per (5): were the predictor clamp to bind while ε_min moves, OpenSees would return the new
//! E_u; we return the committed E_u, the predictor's slope (consistent).
//! Recoverable energy: σ²/(2 E_u) with E_u the trial unloading slope (exact: unloading runs
//! down that line to zero stress); 0 at zero stress.
//! Parameters: f'_c < 0, ε_c0 < 0, f'_c ≤ f_cu ≤ 0, ε_cu < ε_c0, all finite (OpenSees flips
//! positive values to negative; we refuse them instead, so that a sign slip is loud).
use super::history::{self, History, Law};
use super::{ParamError, check};

/// Parameters of [`Concrete01`] (SI, OpenSees' names and order; compression negative).
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Concrete01Params {
    /// Compressive strength f'_c (Pa), < 0.
    pub fpc: f64,
    /// Strain at the compressive strength ε_c0, < 0.
    pub epsc0: f64,
    /// Crushing (residual) strength f_cu (Pa), f'_c ≤ f_cu ≤ 0.
    pub fpcu: f64,
    /// Crushing strain ε_cu, < ε_c0 (|ε_cu| > |ε_c0|).
    pub epscu: f64,
}

/// One state: the point and the unloading line (smallest strain, zero-stress strain, slope).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct State {
    strain: f64,
    stress: f64,
    tangent: f64,
    min_strain: f64,
    end_strain: f64,
    unload_slope: f64,
}

impl history::State for State {
    fn point(&self) -> (f64, f64, f64) {
        (self.strain, self.stress, self.tangent)
    }
}

/// A Concrete01 fiber: parameters, committed and trial state, committed work.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Concrete01 {
    params: Concrete01Params,
    /// E_c0 = 2 f'_c / ε_c0.
    ec0: f64,
    history: History<State>,
}

impl Concrete01 {
    /// A virgin Concrete01 fiber (zero strain and stress, tangent E_c0 = 2 f'_c/ε_c0).
    ///
    /// # Example
    /// ```
    /// use mbdbench::model::fiber_column::material::{Concrete01, Concrete01Params, Uniaxial};
    ///
    /// let p = Concrete01Params { fpc: -36e6, epsc0: -0.004, fpcu: -30e6, epscu: -0.014 };
    /// let mut c = Concrete01::new(p).unwrap();
    /// let (stress, tangent) = c.set_trial_strain(-0.002); // η = 1/2 on the parabola
    /// assert!((stress + 27e6).abs() < 1e-6 && (tangent - 9e9).abs() < 1e-3);
    /// assert_eq!(c.set_trial_strain(0.001), (0.0, 0.0)); // no tension
    /// let err = Concrete01::new(Concrete01Params { fpc: 36e6, ..p }).unwrap_err();
    /// assert_eq!(err.key, "fpc");
    /// assert!(err.message.contains("fpc = 3.6e7"));
    /// ```
    pub fn new(params: Concrete01Params) -> Result<Self, ParamError> {
        let Concrete01Params {
            fpc,
            epsc0,
            fpcu,
            epscu,
        } = params;
        let m = "Concrete01";
        check(m, "fpc", fpc, fpc < 0.0, "negative (compression)")?;
        check(m, "epsc0", epsc0, epsc0 < 0.0, "negative (compression)")?;
        check(m, "fpcu", fpcu, fpcu <= 0.0, "<= 0 (compression)")?;
        check(m, "fpcu", fpcu, fpcu >= fpc, "no stronger than fpc")?;
        check(
            m,
            "epscu",
            epscu,
            epscu < epsc0,
            "beyond epsc0 (|epscu| > |epsc0|)",
        )?;
        let ec0 = 2.0 * fpc / epsc0;
        let virgin = State {
            strain: 0.0,
            stress: 0.0,
            tangent: ec0,
            min_strain: 0.0,
            end_strain: 0.0,
            unload_slope: ec0,
        };
        Ok(Self {
            params,
            ec0,
            history: History::new(virgin),
        })
    }

    /// The parameters it was built with.
    pub fn params(&self) -> Concrete01Params {
        self.params
    }

    /// The trial unloading slope E_u (what OpenSees returns as the tangent on the predictor
    /// branch, see the module doc).
    #[cfg(test)]
    pub(super) fn trial_unload_slope(&self) -> f64 {
        self.history.trial().unload_slope
    }

    /// The monotonic envelope (stress, tangent) at `strain` ≤ 0.
    fn envelope(&self, strain: f64) -> (f64, f64) {
        let Concrete01Params {
            fpc,
            epsc0,
            fpcu,
            epscu,
        } = self.params;
        if strain > epsc0 {
            let eta = strain / epsc0;
            (fpc * (2.0 * eta - eta * eta), self.ec0 * (1.0 - eta))
        } else if strain > epscu {
            let slope = (fpc - fpcu) / (epsc0 - epscu);
            (fpc + slope * (strain - epsc0), slope)
        } else {
            (fpcu, 0.0)
        }
    }

    /// The unloading line from a new envelope point (t.min_strain, t.stress): sets
    /// t.end_strain and t.unload_slope (Karsan & Jirsa's plastic strain, slope ≤ E_c0).
    fn unloading_line(&self, t: &mut State) {
        let Concrete01Params { epsc0, epscu, .. } = self.params;
        let eta = t.min_strain.max(epscu) / epsc0;
        let ratio = if eta < 2.0 {
            0.145 * eta * eta + 0.13 * eta
        } else {
            0.707 * (eta - 2.0) + 0.834
        };
        t.end_strain = ratio * epsc0;
        let secant_run = t.min_strain - t.end_strain; // < 0 but at tiny strains
        let elastic_run = t.stress / self.ec0;
        if secant_run > -f64::EPSILON {
            t.unload_slope = self.ec0;
        } else if secant_run <= elastic_run {
            t.end_strain = t.min_strain - secant_run;
            t.unload_slope = t.stress / secant_run;
        } else {
            t.end_strain = t.min_strain - elastic_run;
            t.unload_slope = self.ec0;
        }
    }
}

impl Law for Concrete01 {
    type State = State;
    fn history(&self) -> &History<State> {
        &self.history
    }
    fn history_mut(&mut self) -> &mut History<State> {
        &mut self.history
    }
    #[inline]
    fn trial_state(&self, c: State, strain: f64) -> State {
        let mut t = c;
        if (strain - c.strain).abs() >= f64::EPSILON {
            t.strain = strain;
            if strain > 0.0 {
                t.stress = 0.0;
                t.tangent = 0.0;
            } else {
                // The elastic predictor from the committed point, as OpenSees evaluates it.
                let predictor = c.stress + c.unload_slope * strain - c.unload_slope * c.strain;
                if strain < c.strain {
                    if strain <= c.min_strain {
                        // New envelope point and its unloading line.
                        t.min_strain = strain;
                        (t.stress, t.tangent) = self.envelope(strain);
                        self.unloading_line(&mut t);
                    } else if strain <= c.end_strain {
                        t.tangent = c.unload_slope;
                        t.stress = t.tangent * (strain - c.end_strain);
                    } else {
                        t.stress = 0.0;
                        t.tangent = 0.0;
                    }
                    if predictor > t.stress {
                        // OpenSees' tangent here is t.unload_slope; the predictor's is
                        // the committed slope.
                        t.stress = predictor;
                        t.tangent = c.unload_slope;
                    }
                } else if predictor <= 0.0 {
                    t.stress = predictor;
                    t.tangent = c.unload_slope;
                } else {
                    t.stress = 0.0;
                    t.tangent = 0.0;
                }
            }
        }
        t
    }
    fn initial_tangent(&self) -> f64 {
        self.ec0
    }
    fn recoverable_energy(&self) -> f64 {
        let t = self.history.trial();
        if t.stress == 0.0 || t.unload_slope <= 0.0 {
            0.0
        } else {
            t.stress * t.stress / (2.0 * t.unload_slope)
        }
    }
}
