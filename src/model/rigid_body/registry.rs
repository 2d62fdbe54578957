//! The registry: the explicit table of valid (parameterization, integrator, formulation)
//! variants of the rigid-body model, each pointing to a run monomorphised on its chart,
//! formulation and method, and the reasons every other combination is `n/a`. The table is the
//! documentation of what is compared (`mbdbench list` prints it).
//!
//! How it is built: the generic methods reach it through the method face (`crate::methods`),
//! the path a method written outside the crate takes as well: `methods::builtin::each` hands
//! each method to [`EveryChart`], which instantiates it on every chart in both formulations
//! where it applies (`Where`: RK, Gauss and Dormand-Prince everywhere, classical on additive
//! charts and RKMK on Lie-group charts; the Crouch-Grossman methods `lie_euler`, `cg3` on the
//! Lie-group charts). The body's own methods, written for one system only, are added by
//! [`on_system`]: the geometric methods (`splitting`, `lgvi`, `simo_wong`) on SO(3) x R^3 in
//! the body formulation, `lie_gen_alpha` (generic over `integrate::LieSecondOrder`) where the
//! body implements that trait (`so3`, body), and the compensated-summation variants on the
//! long-horizon study's charts. Per scene, the SE(3) charts (`se3_hq`, `dual_quat`) are `n/a`
//! when the body does not translate (a pivot, or no mass).
use super::methods::compensated::GaussKahan;
use super::methods::lgvi::Lgvi;
use super::methods::simo_wong::SimoWong;
use super::methods::simo_wong_kahan::SimoWongKahan;
use super::methods::splitting::Splitting;
use crate::integrate::lie_gen_alpha::LieGenAlpha;
use crate::integrate::{FixedStep, Limits, MethodInfo, System};
use crate::methods::{OdeMethod, Visit, Where};
use crate::model::rigid_body::{Observation, RigidBody, RigidSystem};
use crate::rotation::{
    Body, DualQuat, EulerXyz, EulerZxz, EulerZyx, Formulation, Matrix, MatrixProj, PoseChart, Quat,
    QuatProj, RotVec, Se3Hq, So3, Spatial,
};
use crate::run::{Grid, Observe, RunOutput, run_fixed};
use std::sync::Arc;

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
pub type RunFn =
    Arc<dyn Fn(&RigidSetup, f64) -> Result<RunOutput<Observation>, String> + Send + Sync>;

/// One valid combination.
#[derive(Clone)]
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

/// Builds the variant of method `m` (listed as `name`) on chart `C` in formulation `F`: its
/// facts on that system and its run, monomorphised on the system and the method.
fn on_chart<C: PoseChart, F: Formulation, M: OdeMethod>(name: &'static str, m: &Arc<M>) -> Variant {
    let run_m = Arc::clone(m);
    Variant {
        param: C::NAME,
        integrator: name,
        formulation: F::NAME,
        info: m.info::<RigidSystem<C, F>>(),
        se3: C::SE3,
        run: Arc::new(move |setup: &RigidSetup, value: f64| {
            let sys = RigidSystem::<C, F>::new(setup.body.clone());
            let x0 = sys.state_from(&setup.initial);
            let stepping = run_m.stepping(value);
            run_m.run(
                &sys,
                x0,
                stepping,
                &setup.grid,
                &setup.limits,
                &setup.observe,
            )
        }),
    }
}

/// Builds the variant of a method written for one system only, `RigidSystem<C, F>`: `make`
/// gives a fresh stepper for each run.
fn on_system<C: PoseChart, F: Formulation, M>(name: &'static str, make: fn() -> M) -> Variant
where
    M: FixedStep<RigidSystem<C, F>> + 'static,
{
    Variant {
        param: C::NAME,
        integrator: name,
        formulation: F::NAME,
        info: FixedStep::<RigidSystem<C, F>>::info(&make()),
        se3: C::SE3,
        run: Arc::new(move |setup: &RigidSetup, dt: f64| {
            let sys = RigidSystem::<C, F>::new(setup.body.clone());
            let x0 = sys.state_from(&setup.initial);
            let mut m = make();
            run_fixed(
                &sys,
                &mut m,
                x0,
                dt,
                &setup.grid,
                &setup.limits,
                &setup.observe,
            )
        }),
    }
}

/// Instantiates each method it is handed on every chart, in both formulations, where the
/// method applies (`Where`), keeping where it applies beside each variant.
struct EveryChart(Vec<(Where, Variant)>);

impl Visit for EveryChart {
    fn method<M: OdeMethod>(&mut self, name: &'static str, at: Where, m: M) {
        let m = Arc::new(m);
        let out = &mut self.0;
        macro_rules! both_formulations {
            ($chart:ident) => {
                if at.admits::<RigidSystem<$chart, Body>>() {
                    out.push((at, on_chart::<$chart, Body, M>(name, &m)));
                    out.push((at, on_chart::<$chart, Spatial, M>(name, &m)));
                }
            };
        }
        crate::for_each_chart!(both_formulations);
    }
}

/// The variants of one method on every chart, in both formulations, where it applies
/// (chart-major): how a method registered from outside the crate reaches the rigid body
/// (`catalogue::Catalogue::with_method`, through `family::ode_variants`).
pub fn instantiate<M: OdeMethod>(name: &'static str, at: Where, m: M) -> Vec<Variant> {
    let mut every = EveryChart(vec![]);
    every.method(name, at, m);
    every.0.into_iter().map(|(_, v)| v).collect()
}

/// The rigid body's own methods, each written for SO(3) x R^3 in the body formulation (or,
/// compensated, on the long-horizon study's charts).
fn own_methods(v: &mut Vec<Variant>) {
    type So3Body = RigidSystem<So3, Body>;
    v.push(on_system::<So3, Body, _>("splitting", Splitting::new));
    v.push(on_system::<So3, Body, _>("lgvi", Lgvi::new));
    v.push(on_system::<So3, Body, _>("simo_wong", SimoWong::new));
    v.push(on_system::<So3, Body, _>(
        "lie_gen_alpha",
        LieGenAlpha::<6, <So3Body as System>::State>::default,
    ));
    // Compensated summation, for the long-horizon study (stability::long_horizon).
    v.push(
        on_system::<Quat, Body, GaussKahan<RigidSystem<Quat, Body>>>(
            "implicit_midpoint_kahan",
            GaussKahan::implicit_midpoint,
        ),
    );
    v.push(on_system::<So3, Body, GaussKahan<So3Body>>(
        "implicit_midpoint_kahan",
        GaussKahan::implicit_midpoint,
    ));
    v.push(
        on_system::<Quat, Body, GaussKahan<RigidSystem<Quat, Body>>>(
            "gauss6_kahan",
            GaussKahan::gauss6,
        ),
    );
    v.push(on_system::<So3, Body, GaussKahan<So3Body>>(
        "gauss6_kahan",
        GaussKahan::gauss6,
    ));
    v.push(on_system::<So3, Body, _>(
        "simo_wong_kahan",
        SimoWongKahan::new,
    ));
}

/// The table: every built-in generic method (`methods::builtin::each`, the path a method
/// written outside the crate takes too) on every chart where it applies, then the rigid
/// body's own methods.
/// The table is chart-major (what `list` and the gate's rows follow): the methods that apply
/// everywhere chart by chart, each chart in both formulations, then the Lie-group methods
/// likewise, then the body's own methods; the methods of a chart and formulation in the
/// order they were handed.
fn build() -> Vec<Variant> {
    let mut every = EveryChart(vec![]);
    crate::methods::builtin::each(&mut every);
    let place = |n: &str, names: &[&str]| names.iter().position(|x| *x == n);
    every.0.sort_by_key(|(at, v)| {
        let block = usize::from(*at == Where::LieGroup);
        (
            block,
            place(v.param, PARAMS),
            place(v.formulation, FORMULATIONS),
        )
    });
    let mut v: Vec<Variant> = every.0.into_iter().map(|(_, v)| v).collect();
    own_methods(&mut v);
    for x in &v {
        debug_assert_eq!(x.info.name, x.integrator, "{x:?}");
    }
    v
}

/// The table of registered variants.
pub fn variants() -> &'static [Variant] {
    static TABLE: std::sync::OnceLock<Vec<Variant>> = std::sync::OnceLock::new();
    TABLE.get_or_init(build)
}
