//! The registry: the explicit table of valid (parameterization, integrator, formulation)
//! variants of the rigid-body model, each pointing to a monomorphised run function, and the
//! reasons every other combination is `n/a`. The table is the documentation of what is
//! compared (`mbdbench list` prints it).
//!
//! Rules: the generic integrators (`euler`, `rk4`, `dopri5`, `dop853`, `implicit_midpoint`,
//! `gauss6`) run on every chart in both formulations (classical RK on additive charts, RKMK on
//! Lie-group charts); the Crouch-Grossman methods (`lie_euler`, `cg3`) need a Lie-group chart;
//! the geometric rigid-body methods (`splitting`, `lgvi`, `simo_wong`) are written on
//! SO(3) x R^3 in the body formulation, and `lie_gen_alpha` (generic over
//! `integrate::LieSecondOrder`) runs where the body implements that trait: `so3`, body. Per scene, the SE(3) charts (`se3_hq`,
//! `dual_quat`) are `n/a` when the body does not translate (a pivot, or no mass).
use crate::integrate::adaptive_rk::AdaptiveRk;
use super::methods::compensated::GaussKahan;
use crate::integrate::crouch_grossman::CrouchGrossman;
use crate::integrate::explicit_rk::ExplicitRk;
use crate::integrate::implicit_rk::ImplicitRk;
use crate::integrate::lie_gen_alpha::LieGenAlpha;
use super::methods::lgvi::Lgvi;
use super::methods::simo_wong::SimoWong;
use super::methods::simo_wong_kahan::SimoWongKahan;
use super::methods::splitting::Splitting;
use crate::integrate::{Adaptive, FixedStep, Limits, MethodInfo};
use crate::model::rigid_body::{Observation, RigidBody, RigidSystem};
use crate::rotation::{
    Body, DualQuat, EulerXyz, EulerZxz, EulerZyx, Formulation, Matrix, MatrixProj, PoseChart, Quat,
    QuatProj, RotVec, Se3Hq, So3, Spatial,
};
use crate::run::{Grid, Observe, RunOutput, Watched, run_adaptive, run_fixed};

/// What a run function needs of a scene.
#[derive(Debug, Clone)]
pub struct RigidSetup {
    pub body: RigidBody,
    pub initial: Observation,
    pub grid: Grid,
    pub limits: Limits,
    /// When to observe (`Final`: the timing pass, which keeps only the final state; adaptive
    /// methods take the same steps either way, as their output is interpolated).
    pub observe: Observe,
}

/// A monomorphised run: fixed step (`dt`) or tolerance (`tol`).
pub type RunFn = fn(&RigidSetup, f64) -> Result<RunOutput<Observation>, String>;

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
    "implicit_midpoint_kahan",
    "gauss6_kahan",
    "simo_wong_kahan",
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
        "implicit_midpoint_kahan" | "gauss6_kahan"
            if !(["quat", "so3"].contains(&param) && formulation == "body") =>
        {
            "compensated summation is registered on quat and so3 in the body formulation only \
             (the long-horizon study's charts)"
                .into()
        }
        "splitting" | "lgvi" | "simo_wong" | "lie_gen_alpha" | "simo_wong_kahan"
            if param != "so3" =>
        {
            "written on SO(3) x R^3 (chart so3) only".into()
        }
        "splitting" | "lgvi" | "simo_wong" | "lie_gen_alpha" | "simo_wong_kahan"
            if formulation != "body" =>
        {
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

/// A fixed-step variant of chart `$chart` and formulation `$form` built by `$ctor`.
macro_rules! fixed {
    ($chart:ty, $form:ty, $name:literal, $ctor:expr) => {
        Variant {
            param: <$chart as PoseChart>::NAME,
            integrator: $name,
            formulation: <$form as Formulation>::NAME,
            info: FixedStep::<RigidSystem<$chart, $form>>::info(&$ctor),
            se3: <$chart as PoseChart>::SE3,
            run: |setup: &RigidSetup, dt: f64| {
                let sys = RigidSystem::<$chart, $form>::new(setup.body.clone());
                let x0 = sys.state_from(&setup.initial);
                let mut m = $ctor;
                run_fixed(
                    &sys,
                    &mut m,
                    x0,
                    dt,
                    &setup.grid,
                    &setup.limits,
                    &setup.observe,
                )
            },
        }
    };
}

/// An adaptive variant.
macro_rules! adaptive {
    ($chart:ty, $form:ty, $name:literal, $ctor:ident) => {
        Variant {
            param: <$chart as PoseChart>::NAME,
            integrator: $name,
            formulation: <$form as Formulation>::NAME,
            info: Adaptive::<Watched<RigidSystem<$chart, $form>>>::info(&AdaptiveRk::$ctor(1e-6)),
            se3: <$chart as PoseChart>::SE3,
            run: |setup: &RigidSetup, tol: f64| {
                let sys = RigidSystem::<$chart, $form>::new(setup.body.clone());
                let x0 = sys.state_from(&setup.initial);
                let mut m = AdaptiveRk::$ctor(tol);
                run_adaptive(&sys, &mut m, x0, &setup.grid, &setup.limits, &setup.observe)
            },
        }
    };
}

/// The generic integrators on one chart and formulation.
macro_rules! generic {
    ($v:ident, $chart:ty, $form:ty) => {
        $v.push(fixed!($chart, $form, "euler", ExplicitRk::euler()));
        $v.push(fixed!($chart, $form, "rk4", ExplicitRk::rk4()));
        $v.push(adaptive!($chart, $form, "dopri5", dopri5));
        $v.push(adaptive!($chart, $form, "dop853", dop853));
        $v.push(fixed!(
            $chart,
            $form,
            "implicit_midpoint",
            ImplicitRk::implicit_midpoint()
        ));
        $v.push(fixed!($chart, $form, "gauss6", ImplicitRk::gauss6()));
    };
}

/// The Crouch-Grossman methods on a Lie-group chart and formulation.
macro_rules! crouch_grossman {
    ($v:ident, $chart:ty, $form:ty) => {
        $v.push(fixed!(
            $chart,
            $form,
            "lie_euler",
            CrouchGrossman::lie_euler()
        ));
        $v.push(fixed!($chart, $form, "cg3", CrouchGrossman::cg3()));
    };
}

fn build() -> Vec<Variant> {
    let mut v = Vec::new();
    macro_rules! both_formulations {
        ($chart:ident) => {
            generic!(v, $chart, Body);
            generic!(v, $chart, Spatial);
        };
    }
    crate::for_each_chart!(both_formulations);
    for_lie_charts(&mut v);
    v.push(fixed!(So3, Body, "splitting", Splitting::new()));
    v.push(fixed!(So3, Body, "lgvi", Lgvi::new()));
    v.push(fixed!(So3, Body, "simo_wong", SimoWong::new()));
    v.push(fixed!(So3, Body, "lie_gen_alpha", LieGenAlpha::<6, _>::default()));
    // Compensated summation, for the long-horizon study (stability::long_horizon).
    for_kahan(&mut v);
    for x in &v {
        debug_assert_eq!(x.info.name, x.integrator, "{x:?}");
    }
    v
}

/// The compensated-summation variants (methods::compensated), on the long-horizon study's
/// charts only.
fn for_kahan(v: &mut Vec<Variant>) {
    v.push(fixed!(
        Quat,
        Body,
        "implicit_midpoint_kahan",
        GaussKahan::implicit_midpoint()
    ));
    v.push(fixed!(
        So3,
        Body,
        "implicit_midpoint_kahan",
        GaussKahan::implicit_midpoint()
    ));
    v.push(fixed!(Quat, Body, "gauss6_kahan", GaussKahan::gauss6()));
    v.push(fixed!(So3, Body, "gauss6_kahan", GaussKahan::gauss6()));
    v.push(fixed!(So3, Body, "simo_wong_kahan", SimoWongKahan::new()));
}

/// The Crouch-Grossman methods on the three Lie-group charts.
fn for_lie_charts(v: &mut Vec<Variant>) {
    crouch_grossman!(v, So3, Body);
    crouch_grossman!(v, So3, Spatial);
    crouch_grossman!(v, Se3Hq, Body);
    crouch_grossman!(v, Se3Hq, Spatial);
    crouch_grossman!(v, DualQuat, Body);
    crouch_grossman!(v, DualQuat, Spatial);
}

/// The table of registered variants.
pub fn variants() -> &'static [Variant] {
    static TABLE: std::sync::OnceLock<Vec<Variant>> = std::sync::OnceLock::new();
    TABLE.get_or_init(build)
}
