//! OpenSees' `Concrete02` (3.7.1, `SRC/material/uniaxial/Concrete02.cpp`, an f2c of FEDEAS'
//! `Concr2` by Mohd Yassin 1994 after Filippou's EERC report): Kent-Scott-Park compression
//! (Kent & Park 1971; Scott, Park & Priestley 1982) with Yassin's damage-modulus unloading and
//! reloading, and a linear tension-softening branch.
//!
//! Envelopes (compression negative, η = ε/ε_c0, E_c0 = 2 f'_c/ε_c0): in compression the
//! parabola f'_c (2η − η²) to ε_c0, the line to (ε_cu, f_cu), then the flat f_cu; in tension
//! E_c0 ε up to ε_t = f_t/E_c0, then f_t − E_ts (ε − ε_t) down to zero at
//! ε_tu = f_t (1/E_ts + 1/E_c0), then zero. Hysteresis (Yassin's EERC report, eqs. 2.31-2.36
//! and 2.42-2.43): the point R = (ε_R, E_c0 ε_R) with ε_R = (f_cu − λ E_c0 ε_cu)/(E_c0 (1 − λ));
//! from the smallest strain reached ε_min (stress σ_m on the envelope) the reloading line of
//! slope E_r = (σ_m − σ_R)/(ε_min − ε_R) meets zero stress at ε_pt = ε_min − σ_m/E_r. Below
//! ε_pt the stress moves from the committed one with slope E_c0 inside the band between the
//! reloading line σ_m + E_r (ε − ε_min) (lower bound, slope E_r) and the unloading line
//! E_r (ε − ε_pt)/2 (upper bound, slope E_r/2). Above ε_pt the tension envelope is shifted by
//! ε_pt; with Δ the largest tension excursion beyond ε_pt so far, reloading runs along the
//! secant to the tension envelope at Δ, then along the shifted envelope.
//!
//! Tangent: the exact slope of the trial branch, E_c0, E_r, E_r/2, the tension secant, or the
//! envelope's; consistent, one-sided at branch points (OpenSees' tension "secant" is the
//! actual slope of that branch, hence consistent too). Deviations from OpenSees, none in a
//! committed stress: (1) on the flat compression branch and past ε_tu in tension OpenSees
//! returns a tangent of 1e-10 Pa to keep stiffness matrices regular; we return 0, the
//! derivative; (2) OpenSees returns, for a trial strain within f64::EPSILON of the committed
//! one, whatever the previous *trial* left in its stress and tangent (a bug invisible when
//! every trial is committed, as in OpenSees' material tester); we return the committed state.
//! Recoverable energy σ²/(2 E_unload): in tension the unloading runs down the secant to ε_pt,
//! E_unload = σ/(ε − ε_pt); in compression it runs with E_c0 to the line E_r (ε − ε_pt)/2,
//! then down that line to ε_pt, and E_unload is the modulus that gives this bilinear path's
//! area, σ²/(2 E_unload) = (σ² − σ_x²)/(2 E_c0) + σ_x²/E_r with σ_x the corner's stress.
//!
//! Invariants: a compressive stress stays inside the band and never beyond the envelope; the
//! section carries tension only beyond ε_pt, at most the shifted tension envelope; the
//! unloading line starts at σ_m/2, so unloading from the envelope first drops with E_c0 to
//! half its stress. Parameters: f'_c < 0, ε_c0 < 0, f'_c ≤ f_cu ≤ 0, ε_cu < ε_c0, 0 ≤ λ < 1,
//! 0 ≤ f_t ≤ |f'_c| (OpenSees takes any f_t; a tensile strength above the compressive one is
//! no concrete), E_ts > 0, all finite (OpenSees flips positive compressive values; we refuse
//! them), and ε_R > 0, i.e. λ > f_cu/(E_c0 ε_cu): OpenSees accepts ε_R ≤ 0, but then E_r changes
//! sign (and divides by zero) once ε_min passes ε_R, which we refuse rather than reproduce.
use super::history::{self, History, Law};
use super::{ParamError, check};

/// Parameters of [`Concrete02`] (SI, OpenSees' names and order; compression negative).
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Concrete02Params {
    /// Compressive strength f'_c (Pa), < 0.
    pub fpc: f64,
    /// Strain at the compressive strength ε_c0, < 0.
    pub epsc0: f64,
    /// Crushing (residual) strength f_cu (Pa), f'_c ≤ f_cu ≤ 0.
    pub fpcu: f64,
    /// Crushing strain ε_cu, < ε_c0 (|ε_cu| > |ε_c0|).
    pub epscu: f64,
    /// λ, the ratio of the unloading slope at ε_cu to E_c0, 0 ≤ λ < 1.
    pub lambda: f64,
    /// Tensile strength f_t (Pa), 0 ≤ f_t ≤ |f'_c|.
    pub ft: f64,
    /// Tension-softening modulus E_ts (Pa, the magnitude of the softening slope), > 0.
    pub ets: f64,
}

/// One state: the point, the smallest strain reached and the largest tension excursion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct State {
    strain: f64,
    stress: f64,
    tangent: f64,
    /// ε_min, the smallest strain reached (≤ 0).
    min_strain: f64,
    /// Δ, the largest tension strain beyond ε_pt reached (OpenSees' `dept`).
    tension_excursion: f64,
}

impl history::State for State {
    fn point(&self) -> (f64, f64, f64) {
        (self.strain, self.stress, self.tangent)
    }
}

/// The reloading geometry of a smallest strain ε_min: its envelope stress σ_m, the
/// reloading slope E_r and the zero-stress strain ε_pt.
struct Reload {
    sig_m: f64,
    e_r: f64,
    eps_pt: f64,
}

/// A Concrete02 fiber: parameters, committed and trial state, committed work.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Concrete02 {
    params: Concrete02Params,
    /// E_c0 = 2 f'_c / ε_c0.
    ec0: f64,
    /// ε_R, the strain of Yassin's focal point R (its stress is E_c0 ε_R).
    eps_r: f64,
    history: History<State>,
}

impl Concrete02 {
    /// A virgin Concrete02 fiber (zero strain and stress, tangent E_c0 = 2 f'_c/ε_c0).
    ///
    /// # Example
    /// ```
    /// use mbdbench::model::fiber_column::material::{Concrete02, Concrete02Params, Uniaxial};
    ///
    /// let p = Concrete02Params {
    ///     fpc: -36e6, epsc0: -0.004, fpcu: -7.2e6, epscu: -0.02,
    ///     lambda: 0.1, ft: 3e6, ets: 1.5e9,
    /// };
    /// let mut c = Concrete02::new(p).unwrap();
    /// // Tension softening: f_t − E_ts (ε − f_t/E_c0) with E_c0 = 18 GPa.
    /// let (stress, tangent) = c.set_trial_strain(1e-3);
    /// assert!((stress - (3e6 - 1.5e9 * (1e-3 - 3e6 / 18e9))).abs() < 1e-6);
    /// assert_eq!(tangent, -1.5e9);
    /// assert!(Concrete02::new(Concrete02Params { ets: 0.0, ..p }).unwrap_err().message.contains("Ets"));
    /// ```
    pub fn new(params: Concrete02Params) -> Result<Self, ParamError> {
        let Concrete02Params {
            fpc,
            epsc0,
            fpcu,
            epscu,
            lambda,
            ft,
            ets,
        } = params;
        let m = "Concrete02";
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
        check(
            m,
            "lambda",
            lambda,
            (0.0..1.0).contains(&lambda),
            "in [0, 1)",
        )?;
        check(m, "ft", ft, ft >= 0.0, ">= 0")?;
        // A tensile strength above the compressive one describes no concrete (typically
        // f_t is a tenth of |f'_c|).
        check(
            m,
            "ft",
            ft,
            ft <= -fpc,
            &format!("at most |fpc| = {:e}", -fpc),
        )?;
        check(m, "ets", ets, ets > 0.0, "positive")?;
        let ec0 = fpc * 2.0 / epsc0;
        let eps_r = (fpcu - lambda * ec0 * epscu) / (ec0 * (1.0 - lambda));
        if eps_r <= 0.0 {
            let floor = fpcu / (ec0 * epscu);
            return Err(ParamError {
                key: "lambda",
                message: format!(
                    "{m}: lambda = {lambda:e} must exceed fpcu/(Ec0 epscu) = {floor:e} \
                     (Yassin's focal point must lie in tension)"
                ),
            });
        }
        let virgin = State {
            strain: 0.0,
            stress: 0.0,
            tangent: ec0,
            min_strain: 0.0,
            tension_excursion: 0.0,
        };
        Ok(Self {
            params,
            ec0,
            eps_r,
            history: History::new(virgin),
        })
    }

    /// The parameters it was built with.
    pub fn params(&self) -> Concrete02Params {
        self.params
    }

    /// The compression envelope (stress, tangent) at `strain` ≤ 0.
    fn compression_envelope(&self, strain: f64) -> (f64, f64) {
        let Concrete02Params {
            fpc,
            epsc0,
            fpcu,
            epscu,
            ..
        } = self.params;
        let eta = strain / epsc0;
        if strain >= epsc0 {
            (fpc * eta * (2.0 - eta), self.ec0 * (1.0 - eta))
        } else if strain > epscu {
            let stress = (fpcu - fpc) * (strain - epsc0) / (epscu - epsc0) + fpc;
            (stress, (fpcu - fpc) / (epscu - epsc0))
        } else {
            // OpenSees: tangent 1e-10.
            (fpcu, 0.0)
        }
    }

    /// The tension envelope (stress, tangent) at `strain` ≥ 0 measured from ε_pt.
    fn tension_envelope(&self, strain: f64) -> (f64, f64) {
        let Concrete02Params { ft, ets, .. } = self.params;
        let cracking = ft / self.ec0;
        let vanishing = ft * (1.0 / ets + 1.0 / self.ec0);
        if strain <= cracking {
            (strain * self.ec0, self.ec0)
        } else if strain <= vanishing {
            (ft - ets * (strain - cracking), -ets)
        } else {
            // OpenSees: tangent 1e-10.
            (0.0, 0.0)
        }
    }

    /// The reloading geometry of the smallest strain `min_strain`.
    fn reload(&self, min_strain: f64) -> Reload {
        let sig_r = self.ec0 * self.eps_r;
        let (sig_m, _) = self.compression_envelope(min_strain);
        let e_r = (sig_m - sig_r) / (min_strain - self.eps_r);
        Reload {
            sig_m,
            e_r,
            eps_pt: min_strain - sig_m / e_r,
        }
    }
}

impl Law for Concrete02 {
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
        let d_strain = strain - c.strain;
        if d_strain.abs() >= f64::EPSILON {
            t.strain = strain;
            if strain < c.min_strain {
                (t.stress, t.tangent) = self.compression_envelope(strain);
                t.min_strain = strain;
            } else {
                let Reload { sig_m, e_r, eps_pt } = self.reload(c.min_strain);
                if strain <= eps_pt {
                    // Inside the band: E_c0 from the committed stress, bounded below by the
                    // reloading line and above by the unloading line.
                    let lower = sig_m + e_r * (strain - c.min_strain);
                    let upper = e_r * 0.5 * (strain - eps_pt);
                    t.stress = c.stress + self.ec0 * d_strain;
                    t.tangent = self.ec0;
                    if t.stress <= lower {
                        t.stress = lower;
                        t.tangent = e_r;
                    }
                    if t.stress >= upper {
                        t.stress = upper;
                        t.tangent = 0.5 * e_r;
                    }
                } else if strain <= eps_pt + c.tension_excursion {
                    // Tension reloading along the secant to the envelope at Δ.
                    let delta = c.tension_excursion;
                    t.tangent = if delta != 0.0 {
                        self.tension_envelope(delta).0 / delta
                    } else {
                        self.ec0
                    };
                    t.stress = t.tangent * (strain - eps_pt);
                } else {
                    // The tension envelope shifted by ε_pt; Δ grows.
                    let excursion = strain - eps_pt;
                    (t.stress, t.tangent) = self.tension_envelope(excursion);
                    t.tension_excursion = excursion;
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
        let s = t.stress;
        if s == 0.0 {
            return 0.0;
        }
        let Reload { e_r, eps_pt, .. } = self.reload(t.min_strain);
        if s > 0.0 {
            // Down the tension secant to ε_pt.
            return 0.5 * s * (t.strain - eps_pt);
        }
        // E_c0 up to the unloading line E_r (ε − ε_pt)/2, then down that line.
        let half = 0.5 * e_r;
        let corner = (s - self.ec0 * t.strain + half * eps_pt) / (half - self.ec0);
        let s_x = (half * (corner - eps_pt)).clamp(s, 0.0);
        (s * s - s_x * s_x) / (2.0 * self.ec0) + s_x * s_x / e_r
    }
}
