//! The uniaxial fiber materials of the fiber column: the [`Uniaxial`] interface (trial,
//! committed and reverted state, work and recoverable energy) and the static-dispatch
//! [`Material`] enum over the five models, [`Elastic`], [`Concrete01`], [`Concrete02`],
//! [`Steel01`] and [`Steel02`].
//!
//! The four hysteretic models follow OpenSees 3.7.1's classes of the same names branch for
//! branch, with the same floating-point expressions
//! (`SRC/material/uniaxial/{Concrete01,Concrete02,Steel01,Steel02}.cpp`), so that an OpenSees
//! run is a fair reference; each file's `//!` names the equations (Kent & Park 1971 / Scott,
//! Park & Priestley 1982, Karsan & Jirsa 1969, Yassin 1994, Menegotto & Pinto 1973 with
//! Filippou, Popov & Bertero 1983) and every place it departs from OpenSees: only in tangents,
//! in the trial-from-committed rule and in refusing a few parameter sets OpenSees accepts,
//! never in a committed stress. `opensees_tests.rs` replays OpenSees' own responses, stored
//! with the script that produced them in `references/fiber_column/materials/`;
//! `envelope_tests.rs` checks closed forms and tangents, `state_tests.rs` the state machinery,
//! energies and constructors, on the fixtures of `test_support.rs`.
//!
//! Invariants of every model: strain is measured from the unstressed state, tension positive,
//! SI units (Pa, m/m); compressive parameters of the concretes are negative as in OpenSees. A
//! trial is always computed from the last committed state, whatever trials were set since, so
//! `set_trial_strain(x)` is a pure function of (committed state, x) and
//! `revert_to_last_commit` restores the committed strain, stress and tangent bit for bit. The
//! state of one fiber lives inside its value (`Copy`, no allocation), so a section is a plain
//! array of [`Material`]. [`Uniaxial::work`] is the trapezoid rule over the committed strain
//! increments, exact for the piecewise-linear branches and second-order accurate on the
//! curved ones; [`Uniaxial::recoverable_energy`] is `σ²/(2 E_unload)` with `E_unload` named by
//! each model. A model fails where its source does: the constructors refuse parameters outside
//! the ranges listed on each parameter struct (and every non-finite value) with a
//! [`ParamError`] naming the parameter (its struct field, the case file's key), and the models
//! assume strains of engineering size (|ε| ≪ 1).
//!
//! The bookkeeping behind these invariants is written once, in `history.rs`: a fiber's trial
//! state, committed state and committed work, and the [`Uniaxial`] methods that set, read,
//! commit and revert them or sum the work. Each model's file holds only what is its own: its
//! parameters, its state's history variables and its constitutive law (the trial state as a
//! function of the committed state and the strain, the initial tangent, the recoverable
//! energy).
mod concrete01;
mod concrete02;
mod elastic;
mod history;
mod steel01;
mod steel02;

#[cfg(test)]
mod envelope_tests;
#[cfg(test)]
mod opensees_tests;
#[cfg(test)]
mod state_tests;
#[cfg(test)]
mod test_support;

pub use concrete01::{Concrete01, Concrete01Params};
pub use concrete02::{Concrete02, Concrete02Params};
pub use elastic::{Elastic, ElasticParams};
pub use steel01::{Steel01, Steel01Params};
pub use steel02::{Steel02, Steel02Params};

/// A uniaxial material with trial, committed and reverted state (strain measured from the unstressed state, tension positive).
pub trait Uniaxial {
    /// Sets the trial strain, starting from the last committed state whatever trial strains were set since; returns the trial (stress, tangent).
    fn set_trial_strain(&mut self, strain: f64) -> (f64, f64);
    /// The trial strain.
    fn strain(&self) -> f64;
    /// The trial stress.
    fn stress(&self) -> f64;
    /// The trial tangent, consistent with stress (d stress / d strain along the trial branch).
    fn tangent(&self) -> f64;
    /// The tangent of the virgin material at zero strain.
    fn initial_tangent(&self) -> f64;
    /// Makes the trial state the committed one.
    fn commit(&mut self);
    /// Makes the committed state the trial one again.
    fn revert_to_last_commit(&mut self);
    /// Work density ∫ σ dε (J/m^3) along the committed path by the trapezoid rule over committed strain increments, plus the trial increment's trapezoid: W_c + (σ_c + σ)(ε − ε_c)/2.
    fn work(&self) -> f64;
    /// Recoverable strain energy density (J/m^3) of the trial state: the energy returned by unloading to zero stress along the material's unloading branch, σ²/(2 E_unload) with E_unload documented per material (E0 for the steels; the degraded unloading slope for the concretes as OpenSees defines it). dissipated = work − recoverable.
    fn recoverable_energy(&self) -> f64;
    /// Dissipated energy density (J/m^3) of the trial state: `work() − recoverable_energy()`.
    fn dissipated(&self) -> f64 {
        self.work() - self.recoverable_energy()
    }
}

/// One fiber's material: any of the five models, dispatched by `match` (no allocation).
///
/// # Example
/// ```
/// use mbdbench::model::fiber_column::material::{Material, Steel01, Steel01Params, Uniaxial};
///
/// let steel = Steel01::new(Steel01Params { fy: 420e6, e0: 200e9, b: 0.01 }).unwrap();
/// let mut fibers = [Material::from(steel); 4];
/// for f in &mut fibers {
///     f.set_trial_strain(0.001);
///     f.commit();
/// }
/// assert!((fibers[3].stress() - 200e6).abs() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Material {
    /// Linear elastic.
    Elastic(Elastic),
    /// OpenSees' Concrete01 (Kent-Scott-Park, no tension).
    Concrete01(Concrete01),
    /// OpenSees' Concrete02 (Yassin's concrete with linear tension softening).
    Concrete02(Concrete02),
    /// OpenSees' Steel01 (bilinear, kinematic hardening).
    Steel01(Steel01),
    /// OpenSees' Steel02 (Giuffre-Menegotto-Pinto).
    Steel02(Steel02),
}

impl Material {
    /// The model's name as OpenSees spells it (`"Elastic"` for the linear one).
    pub fn model_name(&self) -> &'static str {
        match self {
            Material::Elastic(_) => "Elastic",
            Material::Concrete01(_) => "Concrete01",
            Material::Concrete02(_) => "Concrete02",
            Material::Steel01(_) => "Steel01",
            Material::Steel02(_) => "Steel02",
        }
    }
}

/// Forwards one `Uniaxial` method to the variant inside.
macro_rules! dispatch {
    ($self:expr, $m:ident => $body:expr) => {
        match $self {
            Material::Elastic($m) => $body,
            Material::Concrete01($m) => $body,
            Material::Concrete02($m) => $body,
            Material::Steel01($m) => $body,
            Material::Steel02($m) => $body,
        }
    };
}

impl Uniaxial for Material {
    fn set_trial_strain(&mut self, strain: f64) -> (f64, f64) {
        dispatch!(self, m => m.set_trial_strain(strain))
    }
    fn strain(&self) -> f64 {
        dispatch!(self, m => m.strain())
    }
    fn stress(&self) -> f64 {
        dispatch!(self, m => m.stress())
    }
    fn tangent(&self) -> f64 {
        dispatch!(self, m => m.tangent())
    }
    fn initial_tangent(&self) -> f64 {
        dispatch!(self, m => m.initial_tangent())
    }
    fn commit(&mut self) {
        dispatch!(self, m => m.commit())
    }
    fn revert_to_last_commit(&mut self) {
        dispatch!(self, m => m.revert_to_last_commit())
    }
    fn work(&self) -> f64 {
        dispatch!(self, m => m.work())
    }
    fn recoverable_energy(&self) -> f64 {
        dispatch!(self, m => m.recoverable_energy())
    }
}

macro_rules! from_model {
    ($($model:ident),*) => {
        $(impl From<$model> for Material {
            fn from(m: $model) -> Self {
                Material::$model(m)
            }
        })*
    };
}
from_model!(Elastic, Concrete01, Concrete02, Steel01, Steel02);

/// A parameter a constructor refuses: `key`, the field of the parameter struct (the case
/// file's key, `c_r1`), and the message, which names the model and the parameter as
/// OpenSees spells it (`Steel02: cR1 = 1.5e0 must be in (0, 1)`).
#[derive(Debug, Clone, PartialEq)]
pub struct ParamError {
    pub key: &'static str,
    pub message: String,
}

impl From<ParamError> for String {
    fn from(e: ParamError) -> String {
        e.message
    }
}

/// A parameter's name as OpenSees' manual spells it (the messages keep that spelling; the
/// struct fields, which the case files use, are lower snake case).
fn opensees_name(key: &'static str) -> &'static str {
    match key {
        "e" => "E",
        "e0" => "E0",
        "ets" => "Ets",
        "r0" => "R0",
        "c_r1" => "cR1",
        "c_r2" => "cR2",
        other => other,
    }
}

/// Checks one parameter of a constructor, `key` its struct field: refuses a non-finite value,
/// then one for which `ok` is false, with "`model`: `name` = `value` must be `rule`" (`name`
/// OpenSees' spelling of `key`).
fn check(model: &str, key: &'static str, value: f64, ok: bool, rule: &str) -> Result<(), ParamError> {
    let name = opensees_name(key);
    let message = if !value.is_finite() {
        format!("{model}: {name} = {value} must be finite")
    } else if !ok {
        format!("{model}: {name} = {value:e} must be {rule}")
    } else {
        return Ok(());
    };
    Err(ParamError { key, message })
}
