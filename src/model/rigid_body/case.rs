//! The rigid-body case schema (cases/README.md, "Rigid-body keys"; the physics of each case in
//! its section there): `[body]` (mass, inertia about the centre of mass, gravity, a fixed pivot),
//! `[[spring]]` (linear springs to fixed anchors), `nonphysical_inertia`, and each scene's
//! initial state (`euler_xyz` with `R0 = Rx(a) Ry(b) Rz(c)`, position, velocity, one of
//! `omega`, `omega_world` (`omega = R0^T w`), `angular_momentum_body` (`omega = J^-1 L`, `J`
//! about the reference point), an optional inertia override). The shared keys are checked by
//! `case::Ctx::assemble`.
//!
//! Invariants after loading: every number is finite; the inertia of every scene is symmetric
//! (to 1e-12 relative, then symmetrised), positive definite and, unless
//! `nonphysical_inertia = true`, its principal moments satisfy the triangle inequality
//! (equality allowed: a flat disc); spring directions are unit vectors (to 1e-12); a body
//! that does not translate (no mass, or a pivot) has zero position and velocity and no
//! springs; the body angular velocity is finite.
use nalgebra::{Matrix3, SymmetricEigen, UnitQuaternion, Vector3};
use serde::Deserialize;
use serde_json::Value;

use super::{Observation, RigidBody, Spring};
use crate::case::hash::num;
use crate::case::{Case, CaseError, Ctx, Res, Scene};
use crate::math::so3;

crate::case_schema! {
    case RawCase / CaseOwn {
        #[serde(default)]
        nonphysical_inertia: bool,
        body: RawBody,
        #[serde(default)]
        spring: Vec<RawSpring>,
    }
    scene RawScene / SceneOwn {
        #[serde(deserialize_with = "crate::case::exact::array")]
        euler_xyz: [f64; 3],
        #[serde(default, deserialize_with = "crate::case::exact::option_array")]
        position: Option<[f64; 3]>,
        #[serde(default, deserialize_with = "crate::case::exact::option_array")]
        velocity: Option<[f64; 3]>,
        #[serde(default, deserialize_with = "crate::case::exact::option_array")]
        omega: Option<[f64; 3]>,
        #[serde(default, deserialize_with = "crate::case::exact::option_array")]
        omega_world: Option<[f64; 3]>,
        #[serde(default, deserialize_with = "crate::case::exact::option_array")]
        angular_momentum_body: Option<[f64; 3]>,
        #[serde(default, deserialize_with = "crate::case::exact::option_matrix")]
        inertia: Option<[[f64; 3]; 3]>,
    }
}

/// The rigid-body data of a case.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidCase {
    /// The inertia may violate the triangle inequality (a mathematical test body).
    pub nonphysical_inertia: bool,
    pub body: BodySpec,
    pub springs: Vec<SpringSpec>,
}

/// The rigid-body data of a scene: its initial state and effective inertia.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidScene {
    /// rad, as given: `R0 = Rx(a) Ry(b) Rz(c)`.
    pub euler_xyz: Vector3<f64>,
    /// `R0`.
    pub r0: Matrix3<f64>,
    /// `R0` as a sign-canonical unit quaternion.
    pub q0: UnitQuaternion<f64>,
    /// World position of the centre of mass, m (zero unless the body translates).
    pub position: Vector3<f64>,
    /// World velocity of the centre of mass, m/s (zero unless the body translates).
    pub velocity: Vector3<f64>,
    /// The angular initial condition as given.
    pub angular: AngularInit,
    /// Body angular velocity at `t = 0`, rad/s.
    pub omega0: Vector3<f64>,
    /// Effective inertia about the centre of mass (the scene's override, else the body's).
    pub inertia: Matrix3<f64>,
    /// The scene overrides the body's inertia.
    pub inertia_override: bool,
}

/// `[body]`.
#[derive(Debug, Clone, PartialEq)]
pub struct BodySpec {
    /// kg; None: the body does not translate (its centre of mass stays at the origin).
    pub mass: Option<f64>,
    /// Inertia about the centre of mass, body frame, kg m^2 (symmetrised); a scene may
    /// override it (`Scene::inertia` is the one to use).
    pub inertia: Matrix3<f64>,
    /// `g0` along `-z`, m/s^2; None when absent or 0.
    pub gravity: Option<f64>,
    /// Body-frame centre of mass relative to a fixed pivot at the world origin (m).
    pub pivot_com: Option<Vector3<f64>>,
}

/// `[[spring]]`: from a body point (relative to the centre of mass) to a fixed anchor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringSpec {
    pub body_point: Vector3<f64>,
    /// Unit vector (to 1e-12).
    pub direction: Vector3<f64>,
    /// N/m, >= 0.
    pub stiffness: f64,
    /// m, > 0.
    pub rest_length: f64,
    /// World anchor `body_point + rest_length * direction` (at `R = I`, `x = 0`).
    pub anchor: Vector3<f64>,
}

/// The initial angular velocity as the file gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AngularInit {
    /// `omega`: body frame (also used when none is given: zero).
    Body(Vector3<f64>),
    /// `omega_world`: world frame; body `omega = R0^T w`.
    World(Vector3<f64>),
    /// `angular_momentum_body`: `L = J omega` in the body frame, `J` about the reference point
    /// (the centre of mass, or the pivot for a pinned body).
    MomentumBody(Vector3<f64>),
}

impl RigidCase {
    /// The rigid-body data of `case` (None for a case of another family).
    pub fn of(case: &Case) -> Option<&RigidCase> {
        case.physics()
    }

    /// Whether the body translates (has a mass and no pivot); position and velocity errors
    /// are absent otherwise.
    pub fn translates(&self) -> bool {
        self.body.mass.is_some() && self.body.pivot_com.is_none()
    }
}

impl RigidScene {
    /// The rigid-body data of `scene` (None for a scene of another family).
    pub fn of(scene: &Scene) -> Option<&RigidScene> {
        scene.physics()
    }
}

/// The rigid data of a scene of a rigid case, or the error naming it (a case of another
/// family handed to rigid code).
fn parts<'a>(case: &'a Case, scene: &'a Scene) -> Res<(&'a RigidCase, &'a RigidScene)> {
    match (RigidCase::of(case), RigidScene::of(scene)) {
        (Some(c), Some(s)) => Ok((c, s)),
        _ => Err(CaseError::model(
            case,
            format!("`{}` is not a rigid-body case", case.model()),
        )),
    }
}

/// The model of `scene` (its effective inertia). A body without mass gets the placeholder
/// mass 1 kg: validation guarantees it has no force and no velocity that could use it.
pub fn rigid_body(case: &Case, scene: &Scene) -> Res<RigidBody> {
    let (c, s) = parts(case, scene)?;
    let springs = c
        .springs
        .iter()
        .map(|s| Spring {
            body_point: s.body_point,
            anchor: s.anchor,
            stiffness: s.stiffness,
            rest_length: s.rest_length,
        })
        .collect();
    RigidBody::new(
        c.body.mass.unwrap_or(1.0),
        s.inertia,
        springs,
        c.body.gravity,
        c.body.pivot_com,
    )
    .map(|b| {
        if c.body.mass.is_some() {
            b
        } else {
            b.without_translation()
        }
    })
    .ok_or_else(|| CaseError {
        file: case.file.clone(),
        key: format!("scene[{}]", scene.index),
        message: "the inertia about the reference point is singular".into(),
    })
}

/// The physical initial state of `scene`.
pub fn initial(scene: &RigidScene) -> Observation {
    Observation {
        q: scene.q0,
        x: scene.position,
        v: scene.velocity,
        omega: scene.omega0,
    }
}

/// Loads a rigid-body case file (the family's `load`).
pub fn load(file: &str, text: &str) -> Result<Case, CaseError> {
    let raw: RawCase = crate::case::parse(file, text)?;
    let (shared, own, scenes) = raw.split();
    let cx = Ctx { file };
    if shared
        .stability
        .as_ref()
        .is_some_and(|st| st.rotation_error_max().is_none())
    {
        return cx.err(
            "stability.rotation_error_max",
            "missing; the rigid body's accurate-step search needs a rotation error bound in rad",
        );
    }
    cx.assemble(
        &super::family::FAMILY,
        shared,
        |cx| {
            let body = body(cx, &own.body, own.nonphysical_inertia)?;
            let springs = own
                .spring
                .iter()
                .enumerate()
                .map(|(i, s)| spring(cx, i, s, &body))
                .collect::<Res<Vec<_>>>()?;
            Ok(RigidCase {
                nonphysical_inertia: own.nonphysical_inertia,
                body,
                springs,
            })
        },
        scenes,
        scene,
    )
}

/// The rigid physics of a scene in the physics hash (`case::hash`): the body (mass, the
/// scene's effective inertia, gravity, pivot), the springs, the initial state as given.
pub fn inputs(case: &Case, scene: &Scene) -> serde_json::Map<String, Value> {
    let mut m = serde_json::Map::new();
    let Ok((c, s)) = parts(case, scene) else {
        return m;
    };
    let v3 = |v: &Vector3<f64>| Value::Array(v.iter().map(|x| num(*x)).collect());
    let m3 = |m: &Matrix3<f64>| {
        Value::Array(
            (0..3)
                .map(|i| Value::Array((0..3).map(|j| num(m[(i, j)])).collect()))
                .collect(),
        )
    };
    let opt = |x: Option<f64>| x.map_or(Value::Null, num);
    let body = serde_json::json!({
        "mass": opt(c.body.mass),
        "inertia": m3(&s.inertia),
        "gravity": opt(c.body.gravity),
        "pivot_com": c.body.pivot_com.as_ref().map_or(Value::Null, v3),
    });
    let springs: Vec<Value> = c
        .springs
        .iter()
        .map(|s| {
            serde_json::json!({
                "body_point": v3(&s.body_point),
                "direction": v3(&s.direction),
                "stiffness": num(s.stiffness),
                "rest_length": num(s.rest_length),
            })
        })
        .collect();
    let (akey, aval) = match &s.angular {
        AngularInit::Body(w) => ("omega", v3(w)),
        AngularInit::World(w) => ("omega_world", v3(w)),
        AngularInit::MomentumBody(l) => ("angular_momentum_body", v3(l)),
    };
    let mut initial = serde_json::Map::new();
    initial.insert("euler_xyz".into(), v3(&s.euler_xyz));
    initial.insert("position".into(), v3(&s.position));
    initial.insert("velocity".into(), v3(&s.velocity));
    initial.insert(akey.into(), aval);
    m.insert("body".into(), body);
    m.insert("springs".into(), Value::Array(springs));
    m.insert("initial".into(), Value::Object(initial));
    m
}

// ---------------------------------------------------------------------------------------
// Raw (serde) layer and validation

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawBody {
    mass: Option<f64>,
    #[serde(deserialize_with = "crate::case::exact::matrix")]
    inertia: [[f64; 3]; 3],
    gravity: Option<f64>,
    #[serde(default, deserialize_with = "crate::case::exact::option_array")]
    pivot_com: Option<[f64; 3]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSpring {
    #[serde(deserialize_with = "crate::case::exact::array")]
    body_point: [f64; 3],
    #[serde(deserialize_with = "crate::case::exact::array")]
    direction: [f64; 3],
    stiffness: f64,
    rest_length: f64,
}

/// A validated inertia (symmetrised): symmetric, positive definite, and physical unless
/// `nonphysical`.
fn inertia(cx: &Ctx, key: &str, a: [[f64; 3]; 3], nonphysical: bool) -> Res<Matrix3<f64>> {
    for (i, row) in a.iter().enumerate() {
        for (j, x) in row.iter().enumerate() {
            cx.finite(&format!("{key}[{i}][{j}]"), *x)?;
        }
    }
    let m = Matrix3::from_fn(|i, j| a[i][j]);
    let scale = m.amax();
    for i in 0..3 {
        for j in (i + 1)..3 {
            if (m[(i, j)] - m[(j, i)]).abs() > 1e-12 * scale {
                return cx.err(
                    key,
                    format!(
                        "not symmetric: [{i}][{j}] = {} but [{j}][{i}] = {}; expected a \
                         symmetric matrix",
                        m[(i, j)],
                        m[(j, i)]
                    ),
                );
            }
        }
    }
    let m = (m + m.transpose()) * 0.5;
    let mut l = SymmetricEigen::new(m).eigenvalues;
    l.as_mut_slice().sort_by(f64::total_cmp);
    if l[0].is_nan() || l[0] <= 0.0 {
        return cx.err(
            key,
            format!(
                "not positive definite: principal moments {}, {}, {}; expected all > 0",
                l[0], l[1], l[2]
            ),
        );
    }
    if !nonphysical && l[2] > l[0] + l[1] + 1e-12 * (l[0] + l[1] + l[2]) {
        return cx.err(
            key,
            format!(
                "principal moments {}, {}, {} violate the triangle inequality \
                 ({} > {} + {}); expected each <= the sum of the other two, or \
                 nonphysical_inertia = true for a mathematical test body",
                l[0], l[1], l[2], l[2], l[0], l[1]
            ),
        );
    }
    Ok(m)
}

fn body(cx: &Ctx, b: &RawBody, nonphysical: bool) -> Res<BodySpec> {
    let mass = b
        .mass
        .map(|m| cx.positive("body.mass", m, "a mass in kg"))
        .transpose()?;
    let inertia = inertia(cx, "body.inertia", b.inertia, nonphysical)?;
    let gravity = match b.gravity {
        Some(g) => {
            let g = cx.finite("body.gravity", g)?;
            if g < 0.0 {
                return cx.err(
                    "body.gravity",
                    format!("{g}; expected g0 >= 0 (it acts along -z)"),
                );
            }
            (g > 0.0).then_some(g)
        }
        None => None,
    };
    if gravity.is_some() && mass.is_none() {
        return cx.err("body.gravity", "gravity needs body.mass");
    }
    let pivot_com = b
        .pivot_com
        .map(|p| cx.vec3("body.pivot_com", p))
        .transpose()?;
    if pivot_com.is_some() && mass.is_none() {
        return cx.err("body.pivot_com", "a pivot needs body.mass");
    }
    Ok(BodySpec {
        mass,
        inertia,
        gravity,
        pivot_com,
    })
}

fn spring(cx: &Ctx, i: usize, s: &RawSpring, body: &BodySpec) -> Res<SpringSpec> {
    let key = |k: &str| format!("spring[{i}].{k}");
    if body.mass.is_none() || body.pivot_com.is_some() {
        return cx.err(
            format!("spring[{i}]"),
            "springs need a free, translating body (body.mass and no body.pivot_com)",
        );
    }
    let body_point = cx.vec3(&key("body_point"), s.body_point)?;
    let direction = cx.vec3(&key("direction"), s.direction)?;
    if (direction.norm() - 1.0).abs() > 1e-12 {
        return cx.err(
            key("direction"),
            format!(
                "length {}; expected a unit vector (to 1e-12)",
                direction.norm()
            ),
        );
    }
    let stiffness = cx.finite(&key("stiffness"), s.stiffness)?;
    if stiffness < 0.0 {
        return cx.err(
            key("stiffness"),
            format!("{stiffness}; expected a stiffness >= 0 in N/m"),
        );
    }
    let rest_length = cx.positive(&key("rest_length"), s.rest_length, "a length in m")?;
    Ok(SpringSpec {
        body_point,
        direction,
        stiffness,
        rest_length,
        anchor: body_point + direction * rest_length,
    })
}

/// A scene's rigid-body part: the initial rotation `R0 = Rx(a) Ry(b) Rz(c)`, position and
/// velocity (zero unless the body translates), the effective inertia, and the body angular
/// velocity from whichever of `omega`, `omega_world`, `angular_momentum_body` is given.
fn scene(cx: &Ctx, i: usize, s: &SceneOwn, c: &RigidCase) -> Res<RigidScene> {
    let body = &c.body;
    let nonphysical = c.nonphysical_inertia;
    let key = |k: &str| format!("scene[{i}].{k}");
    let euler_xyz = cx.vec3(&key("euler_xyz"), s.euler_xyz)?;
    let r0 = so3::rx(euler_xyz.x) * so3::ry(euler_xyz.y) * so3::rz(euler_xyz.z);
    let q0 = so3::quat_from_matrix(&r0);
    let translates = body.mass.is_some() && body.pivot_com.is_none();
    let mut state = [Vector3::zeros(); 2];
    for (slot, (k, v)) in state
        .iter_mut()
        .zip([("position", s.position), ("velocity", s.velocity)])
    {
        if let Some(v) = v {
            *slot = cx.vec3(&key(k), v)?;
            if !translates && *slot != Vector3::zeros() {
                return cx.err(
                    key(k),
                    "must be zero: the body does not translate (no body.mass, or a pivot)",
                );
            }
        }
    }
    let [position, velocity] = state;
    let inertia = match s.inertia {
        Some(m) => inertia(cx, &key("inertia"), m, nonphysical)?,
        None => body.inertia,
    };
    let given: Vec<(&str, [f64; 3])> = [
        ("omega", s.omega),
        ("omega_world", s.omega_world),
        ("angular_momentum_body", s.angular_momentum_body),
    ]
    .into_iter()
    .filter_map(|(k, v)| v.map(|v| (k, v)))
    .collect();
    if given.len() > 1 {
        return cx.err(
            key(given[1].0),
            format!(
                "given together with `{}`; expected at most one of omega, omega_world, \
                 angular_momentum_body",
                given[0].0
            ),
        );
    }
    let (angular, omega0) = match given.first() {
        None => (AngularInit::Body(Vector3::zeros()), Vector3::zeros()),
        Some(("omega", v)) => {
            let w = cx.vec3(&key("omega"), *v)?;
            (AngularInit::Body(w), w)
        }
        Some(("omega_world", v)) => {
            let w = cx.vec3(&key("omega_world"), *v)?;
            (AngularInit::World(w), r0.transpose() * w)
        }
        Some((_, v)) => {
            let l = cx.vec3(&key("angular_momentum_body"), *v)?;
            let j = match body.pivot_com {
                Some(x) => {
                    inertia
                        + (Matrix3::identity() * x.norm_squared() - x * x.transpose())
                            * body.mass.unwrap_or(0.0)
                }
                None => inertia,
            };
            let Some(w) = j.cholesky().map(|c| c.solve(&l)) else {
                return cx.err(key("angular_momentum_body"), "singular inertia");
            };
            (AngularInit::MomentumBody(l), w)
        }
    };
    // Finite inputs can still give a non-finite body rate (`J^-1 L` with a near-singular
    // inertia, `R0^T w` near the largest double): name the key it came from.
    if !omega0.iter().all(|x| x.is_finite()) {
        return cx.err(
            key(given.first().map_or("omega", |g| g.0)),
            format!(
                "gives the body angular velocity {:?}; expected one that is finite",
                omega0.as_slice()
            ),
        );
    }
    Ok(RigidScene {
        euler_xyz,
        r0,
        q0,
        position,
        velocity,
        angular,
        omega0,
        inertia,
        inertia_override: s.inertia.is_some(),
    })
}
