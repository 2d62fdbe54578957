//! The registry: the explicit table of valid (parameterization, integrator, formulation)
//! variants of the rigid-body model, each pointing to a monomorphised run function, and the
//! reasons every other combination is `n/a`. The table is the documentation of what is
//! compared (design.md, "Core ideas").
//!
//! Rules: the generic integrators (`euler`, `rk4`, `dopri5`, `dop853`, `implicit_midpoint`,
//! `gauss6`) run on every chart in both formulations (classical RK on additive charts, RKMK on
//! Lie-group charts); the Crouch-Grossman methods (`lie_euler`, `cg3`) need a Lie-group chart;
//! the geometric rigid-body methods (`splitting`, `lgvi`, `simo_wong`, `lie_gen_alpha`) are
//! written on SO(3) x R^3 in the body formulation. Per scene, the SE(3) charts (`se3_hq`,
//! `dual_quat`) are `n/a` when the body does not translate (a pivot, or no mass).
use crate::integrate::{Limits, MethodInfo};
use crate::model::rigid_body::{Observation, RigidBody};
use crate::run::{Grid, RunOutput};

/// What a run function needs of a scene.
#[derive(Debug, Clone)]
pub struct Setup {
    pub body: RigidBody,
    pub initial: Observation,
    pub grid: Grid,
    pub limits: Limits,
}

/// A monomorphised run: fixed step (`dt`) or tolerance (`tol`).
pub type RunFn = fn(&Setup, f64) -> Result<RunOutput, String>;

/// One valid combination.
#[derive(Clone, Copy)]
pub struct Variant {
    pub param: &'static str,
    pub integrator: &'static str,
    pub formulation: &'static str,
    pub info: MethodInfo,
    /// Whether the chart moves rotation and translation together on SE(3).
    pub se3: bool,
    pub run: RunFn,
}

impl std::fmt::Debug for Variant {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}/{}", self.param, self.integrator, self.formulation)
    }
}

/// The parameterization names, in report order.
pub const PARAMS: &[&str] = &[
    "euler_xyz",
    "euler_zyx",
    "euler_zxz",
    "rotvec",
    "quat",
    "quat_proj",
    "matrix",
    "matrix_proj",
    "so3",
    "se3_hq",
    "dual_quat",
];

/// The integrator names of the rigid core, in report order.
pub const INTEGRATORS: &[&str] = &[
    "euler",
    "rk4",
    "dopri5",
    "dop853",
    "implicit_midpoint",
    "gauss6",
    "lie_euler",
    "cg3",
    "splitting",
    "lgvi",
    "simo_wong",
    "lie_gen_alpha",
];

/// The formulations.
pub const FORMULATIONS: &[&str] = &["body", "spatial"];

/// The Lie-group charts.
pub const LIE_PARAMS: &[&str] = &["so3", "se3_hq", "dual_quat"];

/// Why a combination absent from the table is not applicable.
pub fn static_na_reason(param: &str, integrator: &str, formulation: &str) -> String {
    match integrator {
        "lie_euler" | "cg3" if !LIE_PARAMS.contains(&param) => {
            "Crouch-Grossman methods need a Lie-group chart (so3, se3_hq, dual_quat)".into()
        }
        "splitting" | "lgvi" | "simo_wong" | "lie_gen_alpha" if param != "so3" => {
            "written on SO(3) x R^3 (chart so3) only".into()
        }
        "splitting" | "lgvi" | "simo_wong" | "lie_gen_alpha" if formulation != "body" => {
            "written in the body formulation only".into()
        }
        _ => "not registered".into(),
    }
}

/// Why a registered variant does not apply to a scene, if it does not.
pub fn scene_na_reason(v: &Variant, body: &RigidBody) -> Option<String> {
    if v.se3 && !body.translates() {
        return Some(if body.pivot_com.is_some() {
            "a fixed pivot: the translation is not a degree of freedom, no SE(3) motion".into()
        } else {
            "the case has no translational degrees of freedom".into()
        });
    }
    None
}

/// Finds a registered variant.
pub fn find(param: &str, integrator: &str, formulation: &str) -> Option<&'static Variant> {
    variants()
        .iter()
        .find(|v| v.param == param && v.integrator == integrator && v.formulation == formulation)
}

/// The table (filled in `table.rs`).
pub fn variants() -> &'static [Variant] {
    &[]
}
