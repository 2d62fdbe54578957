//! The linear elastic uniaxial material, σ = E ε (OpenSees' `Elastic` without damping or
//! separate compression modulus): the fiber column's elastic reference and the baseline of
//! the energy tests. Its tangent is E everywhere (exactly consistent), its recoverable energy
//! is σ²/(2E) = E ε²/2 (E_unload = E) so that, up to the trapezoid rule's rounding, the
//! dissipated energy is zero on every path. It has no failure mode beyond its parameter
//! check (E finite and positive).
use super::{ParamError, Uniaxial, check, trapezoid};

/// Parameters of [`Elastic`] (SI): `e` the Young's modulus (Pa), finite and positive.
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct ElasticParams {
    /// Young's modulus E (Pa), > 0.
    pub e: f64,
}

/// A linear elastic fiber: its committed and trial strain and the committed work.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Elastic {
    params: ElasticParams,
    committed_strain: f64,
    trial_strain: f64,
    committed_work: f64,
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
        Ok(Self {
            params,
            committed_strain: 0.0,
            trial_strain: 0.0,
            committed_work: 0.0,
        })
    }

    /// The parameters it was built with.
    pub fn params(&self) -> ElasticParams {
        self.params
    }
}

impl Uniaxial for Elastic {
    fn set_trial_strain(&mut self, strain: f64) -> (f64, f64) {
        self.trial_strain = strain;
        (self.stress(), self.params.e)
    }
    fn strain(&self) -> f64 {
        self.trial_strain
    }
    fn stress(&self) -> f64 {
        self.params.e * self.trial_strain
    }
    fn tangent(&self) -> f64 {
        self.params.e
    }
    fn initial_tangent(&self) -> f64 {
        self.params.e
    }
    fn commit(&mut self) {
        self.committed_work = self.work();
        self.committed_strain = self.trial_strain;
    }
    fn revert_to_last_commit(&mut self) {
        self.trial_strain = self.committed_strain;
    }
    fn work(&self) -> f64 {
        let c = self.committed_strain;
        let e = self.params.e;
        self.committed_work + trapezoid(c, e * c, self.trial_strain, self.stress())
    }
    fn recoverable_energy(&self) -> f64 {
        let s = self.stress();
        s * s / (2.0 * self.params.e)
    }
}
