//! OpenSees' `Steel02` (3.7.1, `SRC/material/uniaxial/Steel02.cpp`, after Filippou's FEDEAS
//! `Steel02`): the Giuffre-Menegotto-Pinto steel (Menegotto & Pinto 1973) with Filippou,
//! Popov & Bertero's (1983) curvature degradation, isotropic hardening off (a1 = 0, a2 = 1,
//! a3 = 0, a4 = 1, the shifts are exactly 1) and no initial stress.
//!
//! Equations: each branch runs from its reversal point (ε_r, σ_r) toward the intersection
//! (ε_0, σ_0) of the elastic line through it (slope E0) with the hardening asymptote of the
//! loading direction (slope E_sh = b E0 through (±ε_y, ±f_y)); with ε* = (ε − ε_r)/(ε_0 − ε_r)
//! and R = R0 (1 − cR1 ξ / (cR2 + ξ)),
//!
//! σ = σ_r + (σ_0 − σ_r) [b ε* + (1 − b) ε* / (1 + |ε*|^R)^{1/R}]      (Menegotto-Pinto),
//!
//! ξ = |(ε_pl − ε_0)/ε_y| where ε_pl is the largest previous strain excursion on the side the
//! branch heads to (OpenSees' `epspl`, the committed `epsmax` or `epsmin`). The first loading
//! (OpenSees' `kon` 0) is set up as OpenSees does: the reversal point is the origin, the
//! target (±ε_y, ±f_y) and ε_pl = ±ε_y, so ξ = 0 and R = R0; the strain memory starts at
//! ε_max = ε_y, ε_min = −ε_y, so reversals inside the first elastic range still take ξ from
//! ±ε_y. A trial strain within 10 f64::EPSILON of a virgin committed strain returns (0, E0)
//! and leaves the material virgin (OpenSees' `kon` 3, which we fold into the virgin state:
//! both start the first loading the same way). A reversal is detected from the sign of the
//! trial increment against the committed strain, so a trial is always computed from the
//! committed state.
//!
//! Tangent: E = (σ_0 − σ_r)/(ε_0 − ε_r) [b + (1 − b) / (1 + |ε*|^R)^{1+1/R}], the exact
//! derivative along the trial branch (consistent; identical to OpenSees). Recoverable energy:
//! σ²/(2 E0), E_unload = E0, the initial slope of every unloading branch. The branch softens
//! as it unloads, so it reaches zero stress later and gives back more than this: σ²/(2 E0) is
//! a lower bound (by 7 % after first loading to 0.01 with the case's parameters), and the
//! dissipated energy it implies an upper bound.
//! Parameters: f_y > 0, E0 > 0, 0 ≤ b < 1, R0 > 0, 0 < cR1 < 1 (so R stays positive however
//! large ξ grows), cR2 > 0, all finite. The model is rate-free; it fails (ε_0 = ε_r, a zero
//! division) only for parameters the constructor refuses.
use super::history::{self, History, Law};
use super::{ParamError, check};

/// Parameters of [`Steel02`] (SI, OpenSees' names and order).
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Steel02Params {
    /// Yield stress f_y (Pa), > 0.
    pub fy: f64,
    /// Initial elastic modulus E0 (Pa), > 0.
    pub e0: f64,
    /// Strain-hardening ratio b = E_sh / E0, 0 ≤ b < 1.
    pub b: f64,
    /// Initial curvature parameter R0 of the elastic-plastic transition, > 0 (10–20 typical).
    pub r0: f64,
    /// Curvature degradation cR1, 0 < cR1 < 1 (0.925 typical).
    pub c_r1: f64,
    /// Curvature degradation cR2, > 0 (0.15 typical).
    pub c_r2: f64,
}

/// Which way the current branch heads (OpenSees' `kon`: 0 and 3 virgin, 1 up, 2 down).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Heading {
    Virgin,
    Up,
    Down,
}

/// One state: the point and the current branch with its strain memory.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct State {
    strain: f64,
    stress: f64,
    tangent: f64,
    heading: Heading,
    /// Largest and smallest strain reached at a reversal (starting at ±ε_y).
    eps_max: f64,
    eps_min: f64,
    /// The strain memory the branch's ξ is measured from.
    eps_pl: f64,
    /// The branch's asymptote intersection (ε_0, σ_0).
    eps_0: f64,
    sig_0: f64,
    /// The branch's reversal point (ε_r, σ_r).
    eps_r: f64,
    sig_r: f64,
}

impl history::State for State {
    fn point(&self) -> (f64, f64, f64) {
        (self.strain, self.stress, self.tangent)
    }
}

/// A Steel02 fiber: parameters, committed and trial state, committed work.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Steel02 {
    params: Steel02Params,
    history: History<State>,
}

impl Steel02 {
    /// A virgin Steel02 fiber (zero strain and stress, tangent E0).
    ///
    /// # Example
    /// ```
    /// use mbdbench::model::fiber_column::material::{Steel02, Steel02Params, Uniaxial};
    ///
    /// let p = Steel02Params { fy: 420e6, e0: 200e9, b: 0.01, r0: 18.0, c_r1: 0.925, c_r2: 0.15 };
    /// let mut s = Steel02::new(p).unwrap();
    /// // At the first yield strain the curve sits 2^(-1/R0) of the way to f_y (b aside).
    /// let (stress, _) = s.set_trial_strain(420e6 / 200e9);
    /// let expected = 420e6 * (0.01 + 0.99 * 2f64.powf(-1.0 / 18.0));
    /// assert!((stress - expected).abs() < 1e-3);
    /// assert!(Steel02::new(Steel02Params { c_r1: 1.5, ..p }).unwrap_err().message.contains("cR1"));
    /// ```
    pub fn new(params: Steel02Params) -> Result<Self, ParamError> {
        let Steel02Params {
            fy,
            e0,
            b,
            r0,
            c_r1,
            c_r2,
        } = params;
        check("Steel02", "fy", fy, fy > 0.0, "positive")?;
        check("Steel02", "e0", e0, e0 > 0.0, "positive")?;
        check("Steel02", "b", b, (0.0..1.0).contains(&b), "in [0, 1)")?;
        check("Steel02", "r0", r0, r0 > 0.0, "positive")?;
        check(
            "Steel02",
            "c_r1",
            c_r1,
            c_r1 > 0.0 && c_r1 < 1.0,
            "in (0, 1)",
        )?;
        check("Steel02", "c_r2", c_r2, c_r2 > 0.0, "positive")?;
        let eps_y = fy / e0;
        let virgin = State {
            strain: 0.0,
            stress: 0.0,
            tangent: e0,
            heading: Heading::Virgin,
            eps_max: eps_y,
            eps_min: -eps_y,
            eps_pl: 0.0,
            eps_0: 0.0,
            sig_0: 0.0,
            eps_r: 0.0,
            sig_r: 0.0,
        };
        Ok(Self {
            params,
            history: History::new(virgin),
        })
    }

    /// The parameters it was built with.
    pub fn params(&self) -> Steel02Params {
        self.params
    }
}

impl Law for Steel02 {
    type State = State;
    fn history(&self) -> &History<State> {
        &self.history
    }
    fn history_mut(&mut self) -> &mut History<State> {
        &mut self.history
    }
    #[inline]
    fn trial_state(&self, c: State, strain: f64) -> State {
        let Steel02Params {
            fy,
            e0,
            b,
            r0,
            c_r1,
            c_r2,
        } = self.params;
        let e_sh = b * e0;
        let eps_y = fy / e0;
        let mut t = c;
        t.strain = strain;
        let d_strain = strain - c.strain;

        if c.heading == Heading::Virgin {
            if d_strain.abs() < 10.0 * f64::EPSILON {
                t.stress = 0.0;
                t.tangent = e0;
                return t;
            }
            // First loading: from the origin toward (±ε_y, ±f_y), ξ = 0.
            t.eps_max = eps_y;
            t.eps_min = -eps_y;
            if d_strain < 0.0 {
                t.heading = Heading::Down;
                t.eps_0 = t.eps_min;
                t.sig_0 = -fy;
                t.eps_pl = t.eps_min;
            } else {
                t.heading = Heading::Up;
                t.eps_0 = t.eps_max;
                t.sig_0 = fy;
                t.eps_pl = t.eps_max;
            }
        }

        if t.heading == Heading::Down && d_strain > 0.0 {
            // Reversal to loading: new branch from the committed point toward the upper
            // asymptote, ξ measured from the largest strain so far.
            t.heading = Heading::Up;
            t.eps_r = c.strain;
            t.sig_r = c.stress;
            if c.strain < t.eps_min {
                t.eps_min = c.strain;
            }
            t.eps_0 = (fy - e_sh * eps_y - t.sig_r + e0 * t.eps_r) / (e0 - e_sh);
            t.sig_0 = fy + e_sh * (t.eps_0 - eps_y);
            t.eps_pl = t.eps_max;
        } else if t.heading == Heading::Up && d_strain < 0.0 {
            // Reversal to unloading: toward the lower asymptote, ξ from the smallest strain.
            t.heading = Heading::Down;
            t.eps_r = c.strain;
            t.sig_r = c.stress;
            if c.strain > t.eps_max {
                t.eps_max = c.strain;
            }
            t.eps_0 = (-fy + e_sh * eps_y - t.sig_r + e0 * t.eps_r) / (e0 - e_sh);
            t.sig_0 = -fy + e_sh * (t.eps_0 + eps_y);
            t.eps_pl = t.eps_min;
        }

        let xi = ((t.eps_pl - t.eps_0) / eps_y).abs();
        let r = r0 * (1.0 - (c_r1 * xi) / (c_r2 + xi));
        let eps_star = (strain - t.eps_r) / (t.eps_0 - t.eps_r);
        let base = 1.0 + eps_star.abs().powf(r);
        let root = base.powf(1.0 / r);
        let normalized = b * eps_star + (1.0 - b) * eps_star / root;
        t.stress = normalized * (t.sig_0 - t.sig_r) + t.sig_r;
        let slope = b + (1.0 - b) / (base * root);
        t.tangent = slope * (t.sig_0 - t.sig_r) / (t.eps_0 - t.eps_r);
        t
    }
    fn initial_tangent(&self) -> f64 {
        self.params.e0
    }
    fn recoverable_energy(&self) -> f64 {
        let s = self.history.trial().stress;
        s * s / (2.0 * self.params.e0)
    }
}
