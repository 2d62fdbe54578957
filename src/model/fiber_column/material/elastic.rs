//! The linear elastic uniaxial material, σ = E ε (OpenSees' `Elastic` without damping or
//! separate compression modulus): the fiber column's elastic reference and the baseline of
//! the energy tests. Its tangent is E everywhere (exactly consistent), its recoverable energy
//! is σ²/(2E) = E ε²/2 (E_unload = E) so that, up to the trapezoid rule's rounding, the
//! dissipated energy is zero on every path. It has no failure mode beyond its parameter
//! check (E finite and positive). Its state is the bare point (ε, E ε, E): the trial's
//! stress is evaluated once, when the trial is set.
use super::history::{History, Law, Point};
use super::{ParamError, check};

/// Parameters of [`Elastic`] (SI): `e` the Young's modulus (Pa), finite and positive.
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct ElasticParams {
    /// Young's modulus E (Pa), > 0.
    pub e: f64,
}

/// A linear elastic fiber: parameters, committed and trial point, committed work.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Elastic {
    params: ElasticParams,
    history: History<Point>,
}

impl Elastic {
    /// A virgin elastic fiber (zero strain and stress).
    ///
    /// # Example
    /// ```
    /// use mbdbench::model::fiber_column::material::{Elastic, ElasticParams, Uniaxial};
    ///
    /// let mut m = Elastic::new(ElasticParams { e: 200e9 }).unwrap();
    /// assert_eq!(m.set_trial_strain(1e-3), (200e6, 200e9));
    /// assert!(Elastic::new(ElasticParams { e: -1.0 }).unwrap_err().message.contains("E = "));
    /// ```
    pub fn new(params: ElasticParams) -> Result<Self, ParamError> {
        check("Elastic", "e", params.e, params.e > 0.0, "positive")?;
        let virgin = Point {
            strain: 0.0,
            stress: 0.0,
            tangent: params.e,
        };
        Ok(Self {
            params,
            history: History::new(virgin),
        })
    }

    /// The parameters it was built with.
    pub fn params(&self) -> ElasticParams {
        self.params
    }
}

impl Law for Elastic {
    type State = Point;
    fn history(&self) -> &History<Point> {
        &self.history
    }
    fn history_mut(&mut self) -> &mut History<Point> {
        &mut self.history
    }
    #[inline]
    fn trial_state(&self, _committed: Point, strain: f64) -> Point {
        let e = self.params.e;
        Point {
            strain,
            stress: e * strain,
            tangent: e,
        }
    }
    fn initial_tangent(&self) -> f64 {
        self.params.e
    }
    fn recoverable_energy(&self) -> f64 {
        let s = self.history.trial().stress;
        s * s / (2.0 * self.params.e)
    }
}
