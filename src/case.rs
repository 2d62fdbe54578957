//! Case files (`cases/*.toml`, design.md "Case file") to typed, validated structs.
//!
//! A file is read in two passes. First serde, with `deny_unknown_fields` everywhere, turns
//! the TOML into raw structs; a syntax error, an unknown key or a wrong type comes back from
//! the `toml` crate with a byte span, which is mapped to a dotted key path (`scene[1].t_end`,
//! `body.inertia`) by walking the spanned document tree (`toml::de::DeTable`). Second, the
//! raw structs are checked against the physics and the conventions of `spec/cases.md` and
//! the derived data a run needs is computed once: the initial rotation
//! `R0 = Rx(a) Ry(b) Rz(c)`, the body angular velocity (`omega`, `R0^T w` for `omega_world`,
//! `J^-1 L` for `angular_momentum_body`), each scene's effective inertia and ladders, and
//! every step count.
//!
//! Invariants after loading: every number is finite; the inertia of every scene is symmetric
//! (to 1e-12 relative, then symmetrised), positive definite and, unless
//! `nonphysical_inertia = true`, its principal moments satisfy the triangle inequality
//! (equality allowed: a flat disc); `score_every` divides `t_end`, `sample_every` divides
//! `score_every` and every fixed step divides `score_every` by the rule of `spec/cases.md`
//! (`n = round(T/h)`, `|n h - T| <= 1e-9 T`; the run then takes `n` steps of `T/n`).
//! Errors are values naming the file, the key and what was expected; loading never panics.
//!
//! `inputs_sha256` hashes the physics of one scene only (canonical JSON, sorted keys,
//! shortest round-trip floats), so editing a ladder, a gate, a title or `sample_every` does
//! not make a stored reference stale.
use std::fmt;
use std::ops::Range;
use std::path::Path;

use nalgebra::{Matrix3, SymmetricEigen, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use sha2::{Digest, Sha256};

use crate::math::so3;
use crate::model::rigid_body::{Observation, RigidBody, Spring};

/// The only schema version this loader reads.
pub const SCHEMA: i64 = 1;
/// `max_steps` when a case does not set it.
pub const DEFAULT_MAX_STEPS: u64 = 100_000_000;
/// Relative slack of the step-divides-span rule.
pub const DIVIDES_REL_TOL: f64 = 1e-9;
/// Metric names of rigid-body cases (design.md "Files"); `primary_metric` is one of them.
pub const RIGID_BODY_METRICS: &[&str] = &[
    "position_error_max",
    "rotation_error_max",
    "velocity_error_max",
    "omega_error_max",
    "energy_drift_max",
    "energy_drift_final",
    "momentum_drift_max",
    "constraint_error_max",
    "conditioning_min",
];

/// The four catalogue files compiled into the binary, sorted by name.
const EMBEDDED: [(&str, &str); 4] = [
    (
        "cases/free_body.toml",
        include_str!("../cases/free_body.toml"),
    ),
    (
        "cases/gimbal_lock.toml",
        include_str!("../cases/gimbal_lock.toml"),
    ),
    (
        "cases/heavy_top.toml",
        include_str!("../cases/heavy_top.toml"),
    ),
    (
        "cases/nine_spring.toml",
        include_str!("../cases/nine_spring.toml"),
    ),
];

// ---------------------------------------------------------------------------------------
// Errors

/// A bad case file: which file, which key (dotted path, `scene[1].t_end`; empty when the
/// problem is the whole file), and what was expected.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CaseError {
    pub file: String,
    pub key: String,
    pub message: String,
}

impl fmt::Display for CaseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.key.is_empty() {
            write!(f, "{}: {}", self.file, self.message)
        } else {
            write!(f, "{}: {}: {}", self.file, self.key, self.message)
        }
    }
}

impl std::error::Error for CaseError {}

// ---------------------------------------------------------------------------------------
// Typed, validated case

/// The physical model a case uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Model {
    RigidBody,
}

impl Model {
    pub fn name(self) -> &'static str {
        match self {
            Model::RigidBody => "rigid_body",
        }
    }
}

/// How a case's references are made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ReferenceKind {
    /// Integrated and stored under `references/` (design.md "References").
    Numerical,
    /// A closed-form solution computed at scoring time.
    Exact,
}

/// One validated case file.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// The label it was loaded from (`cases/nine_spring.toml`).
    pub file: String,
    /// `case`: snake_case, equal to the file stem.
    pub name: String,
    pub title: String,
    pub model: Model,
    /// One of `RIGID_BODY_METRICS`.
    pub primary_metric: String,
    /// J; relative energy drifts divide by `max(|E0|, energy_scale)`.
    pub energy_scale: f64,
    /// The inertia may violate the triangle inequality (a mathematical test body).
    pub nonphysical_inertia: bool,
    pub reference: ReferenceKind,
    /// Per-run step budget (default `DEFAULT_MAX_STEPS`).
    pub max_steps: u64,
    /// Per-run RHS-evaluation budget (None: the runner's default).
    pub max_rhs_evals: Option<u64>,
    pub body: BodySpec,
    pub springs: Vec<SpringSpec>,
    pub scenes: Vec<Scene>,
    pub gates: Vec<Gate>,
    /// `[stability]`: the stability study's settings (None: the case is not in the study).
    pub stability: Option<StabilitySpec>,
}

/// `[stability]` (issue 4, `mbdbench stability`).
#[derive(Debug, Clone, PartialEq)]
pub struct StabilitySpec {
    /// The horizon `t_h` in periods of the scene's fastest linearised mode
    /// (`model::linear_modes`).
    pub periods: f64,
    /// rad: the accuracy bound of `largest_accurate_dt` (max geodesic rotation error over the
    /// score times of the horizon).
    pub rotation_error_max: f64,
    /// Scenes of the quick tier (each names a scene of the case).
    pub quick: Vec<String>,
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

/// Fixed-step integrator classes, each with its own ladder.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum OrderClass {
    /// Order 1 (`order1`).
    Order1,
    /// Orders 2 to 4 (`order2_4`).
    Order2To4,
    /// Order 5 and above (`order6`).
    Order6,
}

impl OrderClass {
    pub const ALL: [OrderClass; 3] = [
        OrderClass::Order1,
        OrderClass::Order2To4,
        OrderClass::Order6,
    ];

    /// The class of a method of order `order` (None for 0).
    pub fn of_order(order: u32) -> Option<Self> {
        match order {
            0 => None,
            1 => Some(OrderClass::Order1),
            2..=4 => Some(OrderClass::Order2To4),
            _ => Some(OrderClass::Order6),
        }
    }

    /// Its key in `[ladders]`.
    pub fn key(self) -> &'static str {
        match self {
            OrderClass::Order1 => "order1",
            OrderClass::Order2To4 => "order2_4",
            OrderClass::Order6 => "order6",
        }
    }
}

/// One point of a fixed-step ladder, resolved against its scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedStep {
    /// The step as written in the file (s); records and gates name the run by it.
    pub dt: f64,
    /// Steps per `score_every`: `round(score_every / dt)`.
    pub per_score: u64,
    /// Steps over the whole scene: `per_score * Scene::n_score`.
    pub steps: u64,
    /// The step actually taken: `t_end / steps` (`t_k = k h`, the run ends at `t_end`).
    pub h: f64,
}

/// A scene's effective ladders (the scene's override where given, else the case's).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Ladder {
    pub order1: Vec<FixedStep>,
    pub order2_4: Vec<FixedStep>,
    pub order6: Vec<FixedStep>,
    /// Adaptive tolerances, each in (0, 1).
    pub tol: Vec<f64>,
}

impl Ladder {
    /// The fixed steps of one class.
    pub fn fixed(&self, class: OrderClass) -> &[FixedStep] {
        match class {
            OrderClass::Order1 => &self.order1,
            OrderClass::Order2To4 => &self.order2_4,
            OrderClass::Order6 => &self.order6,
        }
    }
}

/// `[[scene]]`: an initial state, a horizon and the scoring grid.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// `[A-Za-z0-9_-]+`, unique in its case.
    pub name: String,
    /// Position in the file (0-based), as in error keys `scene[i]`.
    pub index: usize,
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
    pub t_end: f64,
    pub sample_every: f64,
    pub score_every: f64,
    /// Score intervals over the run: `round(t_end / score_every)`.
    pub n_score: u64,
    /// Sample intervals per score interval: `round(score_every / sample_every)`.
    pub samples_per_score: u64,
    /// The full tier.
    pub ladders: Ladder,
    /// The quick tier (a class absent from every `quick` table is empty: not run quick).
    pub quick: Ladder,
}

impl Scene {
    /// The ladder of a tier.
    pub fn ladder(&self, quick: bool) -> &Ladder {
        if quick { &self.quick } else { &self.ladders }
    }
}

/// A gate's threshold.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bound {
    /// The metric must be <= this.
    Max(f64),
    /// The metric must be >= this.
    Min(f64),
}

/// A gate's `where`: each list is a set of accepted values, empty = any.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct GateWhere {
    pub scene: Vec<String>,
    pub param: Vec<String>,
    pub integrator: Vec<String>,
    pub formulation: Vec<String>,
    pub dt: Vec<f64>,
    pub tol: Vec<f64>,
}

/// `[[gates]]` (shape-checked only: the gate command interprets them).
#[derive(Debug, Clone, PartialEq)]
pub struct Gate {
    pub metric: String,
    pub bound: Bound,
    pub filter: GateWhere,
    /// Evaluated by `gate --quick` too.
    pub quick: bool,
    pub baseline: Option<f64>,
    pub margin: Option<f64>,
    pub commit: Option<String>,
}

impl Case {
    /// The scene named `name`.
    pub fn scene(&self, name: &str) -> Option<&Scene> {
        self.scenes.iter().find(|s| s.name == name)
    }

    /// Whether the body translates (has a mass and no pivot); position and velocity errors
    /// are absent otherwise.
    pub fn translates(&self) -> bool {
        self.body.mass.is_some() && self.body.pivot_com.is_none()
    }

    /// The model of `scene` (its effective inertia). A body without mass gets the placeholder
    /// mass 1 kg: validation guarantees it has no force and no velocity that could use it.
    pub fn rigid_body(&self, scene: &Scene) -> Result<RigidBody, CaseError> {
        let springs = self
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
            self.body.mass.unwrap_or(1.0),
            scene.inertia,
            springs,
            self.body.gravity,
            self.body.pivot_com,
        )
        .map(|b| {
            if self.body.mass.is_some() {
                b
            } else {
                b.without_translation()
            }
        })
        .ok_or_else(|| CaseError {
            file: self.file.clone(),
            key: format!("scene[{}]", scene.index),
            message: "the inertia about the reference point is singular".into(),
        })
    }

    /// The physical initial state of `scene`.
    pub fn initial(&self, scene: &Scene) -> Observation {
        Observation {
            q: scene.q0,
            x: scene.position,
            v: scene.velocity,
            omega: scene.omega0,
        }
    }
}

// ---------------------------------------------------------------------------------------
// Loading

/// Loads one case from its text; `file_label` names it in errors (`cases/<name>.toml`).
pub fn load_str(file_label: &str, text: &str) -> Result<Case, CaseError> {
    let raw: RawCase = toml::from_str(text).map_err(|e| toml_error(file_label, text, &e))?;
    Ctx { file: file_label }.case(raw)
}

/// Loads every `*.toml` of `dir`, sorted by file name; each file's `case` must equal its stem.
pub fn load_dir(dir: &Path) -> Result<Vec<Case>, CaseError> {
    let dir_label = dir.display().to_string();
    let io = |e: std::io::Error| CaseError {
        file: dir_label.clone(),
        key: String::new(),
        message: format!("cannot read the case directory: {e}"),
    };
    let mut paths = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(io)? {
        let path = entry.map_err(io)?.path();
        if path.extension().is_some_and(|x| x == "toml") && path.is_file() {
            paths.push(path);
        }
    }
    paths.sort();
    if paths.is_empty() {
        return Err(CaseError {
            file: dir_label,
            key: String::new(),
            message: "no *.toml case files here".into(),
        });
    }
    let mut cases = Vec::with_capacity(paths.len());
    for path in paths {
        let label = path.display().to_string();
        let text = std::fs::read_to_string(&path).map_err(|e| CaseError {
            file: label.clone(),
            key: String::new(),
            message: format!("cannot read: {e}"),
        })?;
        let case = load_str(&label, &text)?;
        check_stem(&case, &path)?;
        cases.push(case);
    }
    Ok(cases)
}

/// The catalogue compiled into the binary (`cases/` of the source tree), sorted by name.
pub fn embedded() -> Result<Vec<Case>, CaseError> {
    EMBEDDED
        .iter()
        .map(|(label, text)| {
            let case = load_str(label, text)?;
            check_stem(&case, Path::new(label))?;
            Ok(case)
        })
        .collect()
}

/// `text` with every `[[gates]]` table removed (a gate table runs to the next table header):
/// test fixtures append gates of their own to the real case files, whose gate indices would
/// otherwise shift whenever the catalogue's gates change.
#[cfg(test)]
pub(crate) fn without_gates(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut in_gate = false;
    for line in text.split_inclusive('\n') {
        let head = line.trim_start();
        if head.starts_with('[') {
            in_gate = head.starts_with("[[gates]]");
        }
        if !in_gate {
            out.push_str(line);
        }
    }
    out
}

/// The embedded files as `(label, text)`.
pub fn embedded_sources() -> &'static [(&'static str, &'static str)] {
    &EMBEDDED
}

fn check_stem(case: &Case, path: &Path) -> Result<(), CaseError> {
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
    if stem != case.name {
        return Err(CaseError {
            file: case.file.clone(),
            key: "case".into(),
            message: format!(
                "`{}` differs from the file name; expected `{stem}`",
                case.name
            ),
        });
    }
    Ok(())
}

/// The number of steps `n = round(span / h)` when `h` divides `span` by the rule of
/// `spec/cases.md` (`|n h - span| <= 1e-9 span`, `n >= 1`); None otherwise, and for a
/// non-finite or non-positive argument.
pub fn steps_dividing(span: f64, h: f64) -> Option<u64> {
    if !(span.is_finite() && h.is_finite() && span > 0.0 && h > 0.0) {
        return None;
    }
    let n = (span / h).round();
    if !(1.0..=9.0e15).contains(&n) {
        return None;
    }
    if (n * h - span).abs() <= DIVIDES_REL_TOL * span {
        Some(n as u64)
    } else {
        None
    }
}

// ---------------------------------------------------------------------------------------
// Canonical inputs hash

/// Hex SHA-256 of the canonical JSON of the physics of `scene` (design.md "Case file"):
/// case name and model, body (mass, the scene's effective inertia, gravity, pivot), springs,
/// the initial state as given, `t_end` and `score_every`. Ladders, gates, the title and
/// `sample_every` are not part of it.
pub fn inputs_sha256(case: &Case, scene: &Scene) -> String {
    let json = canonical_json(&inputs_value(case, scene));
    let digest = Sha256::digest(json.as_bytes());
    digest.iter().map(|b| format!("{b:02x}")).collect()
}

/// The value `inputs_sha256` hashes (exposed for provenance and debugging).
pub fn inputs_value(case: &Case, scene: &Scene) -> Value {
    let num = |x: f64| Value::from(x + 0.0); // + 0.0 maps -0.0 to 0.0
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
        "mass": opt(case.body.mass),
        "inertia": m3(&scene.inertia),
        "gravity": opt(case.body.gravity),
        "pivot_com": case.body.pivot_com.as_ref().map_or(Value::Null, v3),
    });
    let springs: Vec<Value> = case
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
    let (akey, aval) = match &scene.angular {
        AngularInit::Body(w) => ("omega", v3(w)),
        AngularInit::World(w) => ("omega_world", v3(w)),
        AngularInit::MomentumBody(l) => ("angular_momentum_body", v3(l)),
    };
    let mut initial = serde_json::Map::new();
    initial.insert("euler_xyz".into(), v3(&scene.euler_xyz));
    initial.insert("position".into(), v3(&scene.position));
    initial.insert("velocity".into(), v3(&scene.velocity));
    initial.insert(akey.into(), aval);
    serde_json::json!({
        "case": case.name,
        "model": case.model.name(),
        "body": body,
        "springs": springs,
        "initial": Value::Object(initial),
        "t_end": num(scene.t_end),
        "score_every": num(scene.score_every),
    })
}

/// Compact JSON with object keys sorted at every level, whatever map type serde_json was
/// built with; numbers as serde_json prints them (shortest round-trip).
pub fn canonical_json(v: &Value) -> String {
    let mut out = String::new();
    write_canonical(v, &mut out);
    out
}

fn write_canonical(v: &Value, out: &mut String) {
    match v {
        Value::Object(m) => {
            let mut keys: Vec<&String> = m.keys().collect();
            keys.sort();
            out.push('{');
            for (i, k) in keys.into_iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                out.push_str(&Value::String(k.clone()).to_string());
                out.push(':');
                write_canonical(&m[k], out);
            }
            out.push('}');
        }
        Value::Array(a) => {
            out.push('[');
            for (i, x) in a.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                write_canonical(x, out);
            }
            out.push(']');
        }
        other => out.push_str(&other.to_string()),
    }
}

// ---------------------------------------------------------------------------------------
// Raw (serde) layer

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCase {
    schema: i64,
    case: String,
    title: String,
    model: Model,
    primary_metric: String,
    energy_scale: f64,
    #[serde(default)]
    nonphysical_inertia: bool,
    reference: ReferenceKind,
    max_steps: Option<f64>,
    max_rhs_evals: Option<f64>,
    body: RawBody,
    #[serde(default)]
    spring: Vec<RawSpring>,
    scene: Vec<RawScene>,
    ladders: RawLadders,
    #[serde(default)]
    gates: Vec<RawGate>,
    stability: Option<RawStability>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStability {
    periods: f64,
    rotation_error_max: f64,
    #[serde(default)]
    quick: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBody {
    mass: Option<f64>,
    inertia: [[f64; 3]; 3],
    gravity: Option<f64>,
    pivot_com: Option<[f64; 3]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSpring {
    body_point: [f64; 3],
    direction: [f64; 3],
    stiffness: f64,
    rest_length: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    name: String,
    euler_xyz: [f64; 3],
    position: Option<[f64; 3]>,
    velocity: Option<[f64; 3]>,
    omega: Option<[f64; 3]>,
    omega_world: Option<[f64; 3]>,
    angular_momentum_body: Option<[f64; 3]>,
    inertia: Option<[[f64; 3]; 3]>,
    t_end: f64,
    sample_every: f64,
    score_every: f64,
    ladders: Option<RawLadders>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawLadders {
    order1: Option<Vec<f64>>,
    order2_4: Option<Vec<f64>>,
    order6: Option<Vec<f64>>,
    tol: Option<Vec<f64>>,
    quick: Option<RawQuick>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawQuick {
    order1: Option<Vec<f64>>,
    order2_4: Option<Vec<f64>>,
    order6: Option<Vec<f64>>,
    tol: Option<Vec<f64>>,
}

impl RawLadders {
    fn get(&self, key: &str) -> Option<&Vec<f64>> {
        match key {
            "order1" => self.order1.as_ref(),
            "order2_4" => self.order2_4.as_ref(),
            "order6" => self.order6.as_ref(),
            _ => self.tol.as_ref(),
        }
    }
}

fn quick_list<'a>(l: &'a RawLadders, key: &str) -> Option<&'a Vec<f64>> {
    l.quick.as_ref().and_then(|q| q.get(key))
}

impl RawQuick {
    fn get(&self, key: &str) -> Option<&Vec<f64>> {
        match key {
            "order1" => self.order1.as_ref(),
            "order2_4" => self.order2_4.as_ref(),
            "order6" => self.order6.as_ref(),
            _ => self.tol.as_ref(),
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGate {
    metric: String,
    max: Option<f64>,
    min: Option<f64>,
    #[serde(rename = "where", default)]
    filter: RawWhere,
    #[serde(default)]
    quick: bool,
    baseline: Option<f64>,
    margin: Option<f64>,
    commit: Option<String>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawWhere {
    scene: Option<OneOrMany<String>>,
    param: Option<OneOrMany<String>>,
    integrator: Option<OneOrMany<String>>,
    formulation: Option<OneOrMany<String>>,
    dt: Option<OneOrMany<f64>>,
    tol: Option<OneOrMany<f64>>,
}

#[derive(Deserialize)]
#[serde(untagged, expecting = "a value or a list of values")]
enum OneOrMany<T> {
    One(T),
    Many(Vec<T>),
}

impl<T> OneOrMany<T> {
    fn into_vec(self) -> Vec<T> {
        match self {
            OneOrMany::One(x) => vec![x],
            OneOrMany::Many(v) => v,
        }
    }
}

// ---------------------------------------------------------------------------------------
// TOML error -> key path

/// Maps a `toml` error to the key path at its span (found in the spanned document tree,
/// parsed with recovery so that a syntax error still has the keys before it).
fn toml_error(file: &str, text: &str, e: &toml::de::Error) -> CaseError {
    let mut message = e.message().trim().to_string();
    let mut key = String::new();
    if let Some(span) = e.span() {
        let (doc, syntax_errors) = toml::de::DeTable::parse_recoverable(text);
        let mut path = Vec::new();
        let last = table_path(doc.get_ref(), span.start, &mut path);
        let (line, col) = line_col(text, span.start);
        // After a syntax error the recovered tree is only trusted for a key on the same line.
        let trusted =
            syntax_errors.is_empty() || last.is_some_and(|k| line_col(text, k.start).0 == line);
        if trusted {
            key = join_path(&path);
        }
        message = format!("{message} (line {line}, column {col})");
    }
    // serde reports a missing field on its table: name the field itself.
    if let Some(field) = e
        .message()
        .strip_prefix("missing field `")
        .and_then(|s| s.split('`').next())
    {
        key = if key.is_empty() {
            field.to_string()
        } else {
            format!("{key}.{field}")
        };
    }
    CaseError {
        file: file.to_string(),
        key,
        message,
    }
}

enum Seg {
    Key(String),
    Index(usize),
}

fn join_path(path: &[Seg]) -> String {
    let mut s = String::new();
    for seg in path {
        match seg {
            Seg::Key(k) => {
                if !s.is_empty() {
                    s.push('.');
                }
                s.push_str(k);
            }
            Seg::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

/// Appends to `path` the key (and array index) whose entry holds byte `pos`. A table opened
/// by a `[header]` has the header as its span, so containment is tested on the extent of an
/// entry: its key, its value and everything below it.
/// Returns the span of the last key pushed.
fn table_path(
    table: &toml::de::DeTable<'_>,
    pos: usize,
    path: &mut Vec<Seg>,
) -> Option<Range<usize>> {
    for (k, v) in table.iter() {
        if k.span().contains(&pos) {
            path.push(Seg::Key(k.get_ref().to_string()));
            return Some(k.span());
        }
        if extent(v).contains(&pos) {
            path.push(Seg::Key(k.get_ref().to_string()));
            return value_path(v, pos, path).or(Some(k.span()));
        }
    }
    None
}

fn value_path(
    v: &toml::Spanned<toml::de::DeValue<'_>>,
    pos: usize,
    path: &mut Vec<Seg>,
) -> Option<Range<usize>> {
    match v.get_ref() {
        toml::de::DeValue::Table(t) => table_path(t, pos, path),
        toml::de::DeValue::Array(a) => {
            let i = a.iter().position(|x| extent(x).contains(&pos))?;
            path.push(Seg::Index(i));
            value_path(&a[i], pos, path)
        }
        _ => None,
    }
}

/// The byte range covered by a value and all its descendants (with their keys).
fn extent(v: &toml::Spanned<toml::de::DeValue<'_>>) -> Range<usize> {
    let mut r = v.span();
    let mut grow = |s: Range<usize>| {
        r.start = r.start.min(s.start);
        r.end = r.end.max(s.end);
    };
    match v.get_ref() {
        toml::de::DeValue::Table(t) => {
            for (k, x) in t.iter() {
                grow(k.span());
                grow(extent(x));
            }
        }
        toml::de::DeValue::Array(a) => a.iter().for_each(|x| grow(extent(x))),
        _ => {}
    }
    r
}

/// 1-based line and column (in characters) of byte offset `pos`.
fn line_col(text: &str, pos: usize) -> (usize, usize) {
    let pos = pos.min(text.len());
    let before = text.get(..pos).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

// ---------------------------------------------------------------------------------------
// Validation

struct Ctx<'a> {
    file: &'a str,
}

type Res<T> = Result<T, CaseError>;

/// The part of a scene the ladders are resolved against.
struct Span {
    index: usize,
    name: String,
    t_end: f64,
    score_every: f64,
    n_score: u64,
}

impl Ctx<'_> {
    fn err<T>(&self, key: impl Into<String>, message: impl Into<String>) -> Res<T> {
        Err(CaseError {
            file: self.file.to_string(),
            key: key.into(),
            message: message.into(),
        })
    }

    fn finite(&self, key: &str, x: f64) -> Res<f64> {
        if x.is_finite() {
            Ok(x)
        } else {
            self.err(key, format!("{x} is not a finite number"))
        }
    }

    fn positive(&self, key: &str, x: f64, what: &str) -> Res<f64> {
        let x = self.finite(key, x)?;
        if x > 0.0 {
            Ok(x)
        } else {
            self.err(key, format!("{x} is not positive; expected {what} > 0"))
        }
    }

    fn vec3(&self, key: &str, a: [f64; 3]) -> Res<Vector3<f64>> {
        for (i, x) in a.iter().enumerate() {
            self.finite(&format!("{key}[{i}]"), *x)?;
        }
        Ok(Vector3::from(a))
    }

    fn count(&self, key: &str, x: f64) -> Res<u64> {
        let x = self.finite(key, x)?;
        if x >= 1.0 && x.fract() == 0.0 && x <= 9.0e15 {
            Ok(x as u64)
        } else {
            self.err(key, format!("{x}; expected a positive integer"))
        }
    }

    fn name(&self, key: &str, s: &str, allow: impl Fn(char) -> bool, what: &str) -> Res<()> {
        if !s.is_empty() && s.chars().all(allow) {
            Ok(())
        } else {
            self.err(key, format!("`{s}`; expected {what}"))
        }
    }

    /// A validated inertia (symmetrised): symmetric, positive definite, and physical unless
    /// `nonphysical`.
    fn inertia(&self, key: &str, a: [[f64; 3]; 3], nonphysical: bool) -> Res<Matrix3<f64>> {
        for (i, row) in a.iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                self.finite(&format!("{key}[{i}][{j}]"), *x)?;
            }
        }
        let m = Matrix3::from_fn(|i, j| a[i][j]);
        let scale = m.amax();
        for i in 0..3 {
            for j in (i + 1)..3 {
                if (m[(i, j)] - m[(j, i)]).abs() > 1e-12 * scale {
                    return self.err(
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
            return self.err(
                key,
                format!(
                    "not positive definite: principal moments {}, {}, {}; expected all > 0",
                    l[0], l[1], l[2]
                ),
            );
        }
        if !nonphysical && l[2] > l[0] + l[1] + 1e-12 * (l[0] + l[1] + l[2]) {
            return self.err(
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

    fn case(&self, raw: RawCase) -> Res<Case> {
        if raw.schema != SCHEMA {
            return self.err("schema", format!("{}; expected {SCHEMA}", raw.schema));
        }
        self.name(
            "case",
            &raw.case,
            |c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_',
            "a snake_case name ([a-z0-9_]+)",
        )?;
        if !RIGID_BODY_METRICS.contains(&raw.primary_metric.as_str()) {
            return self.err(
                "primary_metric",
                format!(
                    "unknown metric `{}`; expected one of {}",
                    raw.primary_metric,
                    RIGID_BODY_METRICS.join(", ")
                ),
            );
        }
        let energy_scale = self.positive("energy_scale", raw.energy_scale, "an energy in J")?;
        let max_steps = match raw.max_steps {
            Some(x) => self.count("max_steps", x)?,
            None => DEFAULT_MAX_STEPS,
        };
        let max_rhs_evals = raw
            .max_rhs_evals
            .map(|x| self.count("max_rhs_evals", x))
            .transpose()?;
        let body = self.body(&raw.body, raw.nonphysical_inertia)?;
        let springs = raw
            .spring
            .iter()
            .enumerate()
            .map(|(i, s)| self.spring(i, s, &body))
            .collect::<Res<Vec<_>>>()?;
        self.ladders_shape("ladders", &raw.ladders, true)?;
        if raw.scene.is_empty() {
            return self.err("scene", "no [[scene]]; expected at least one");
        }
        let mut scenes: Vec<Scene> = Vec::with_capacity(raw.scene.len());
        for (i, s) in raw.scene.iter().enumerate() {
            let scene = self.scene(
                i,
                s,
                &body,
                raw.nonphysical_inertia,
                &raw.ladders,
                max_steps,
            )?;
            if scenes.iter().any(|o| o.name == scene.name) {
                return self.err(
                    format!("scene[{i}].name"),
                    format!(
                        "`{}` is used twice; expected unique scene names",
                        scene.name
                    ),
                );
            }
            scenes.push(scene);
        }
        let gates = raw
            .gates
            .into_iter()
            .enumerate()
            .map(|(i, g)| self.gate(i, g, &scenes))
            .collect::<Res<Vec<_>>>()?;
        let stability = raw
            .stability
            .map(|st| self.stability(st, &scenes))
            .transpose()?;
        Ok(Case {
            file: self.file.to_string(),
            name: raw.case,
            title: raw.title,
            model: raw.model,
            primary_metric: raw.primary_metric,
            energy_scale,
            nonphysical_inertia: raw.nonphysical_inertia,
            reference: raw.reference,
            max_steps,
            max_rhs_evals,
            body,
            springs,
            scenes,
            gates,
            stability,
        })
    }

    fn stability(&self, st: RawStability, scenes: &[Scene]) -> Res<StabilitySpec> {
        let periods = self.positive("stability.periods", st.periods, "a number of periods")?;
        let rotation_error_max = self.positive(
            "stability.rotation_error_max",
            st.rotation_error_max,
            "a rotation error bound in rad",
        )?;
        for (i, name) in st.quick.iter().enumerate() {
            if !scenes.iter().any(|s| &s.name == name) {
                return self.err(
                    format!("stability.quick[{i}]"),
                    format!("`{name}` is no scene of this case"),
                );
            }
        }
        Ok(StabilitySpec {
            periods,
            rotation_error_max,
            quick: st.quick,
        })
    }

    fn body(&self, b: &RawBody, nonphysical: bool) -> Res<BodySpec> {
        let mass = b
            .mass
            .map(|m| self.positive("body.mass", m, "a mass in kg"))
            .transpose()?;
        let inertia = self.inertia("body.inertia", b.inertia, nonphysical)?;
        let gravity = match b.gravity {
            Some(g) => {
                let g = self.finite("body.gravity", g)?;
                if g < 0.0 {
                    return self.err(
                        "body.gravity",
                        format!("{g}; expected g0 >= 0 (it acts along -z)"),
                    );
                }
                (g > 0.0).then_some(g)
            }
            None => None,
        };
        if gravity.is_some() && mass.is_none() {
            return self.err("body.gravity", "gravity needs body.mass");
        }
        let pivot_com = b
            .pivot_com
            .map(|p| self.vec3("body.pivot_com", p))
            .transpose()?;
        if pivot_com.is_some() && mass.is_none() {
            return self.err("body.pivot_com", "a pivot needs body.mass");
        }
        Ok(BodySpec {
            mass,
            inertia,
            gravity,
            pivot_com,
        })
    }

    fn spring(&self, i: usize, s: &RawSpring, body: &BodySpec) -> Res<SpringSpec> {
        let key = |k: &str| format!("spring[{i}].{k}");
        if body.mass.is_none() || body.pivot_com.is_some() {
            return self.err(
                format!("spring[{i}]"),
                "springs need a free, translating body (body.mass and no body.pivot_com)",
            );
        }
        let body_point = self.vec3(&key("body_point"), s.body_point)?;
        let direction = self.vec3(&key("direction"), s.direction)?;
        if (direction.norm() - 1.0).abs() > 1e-12 {
            return self.err(
                key("direction"),
                format!(
                    "length {}; expected a unit vector (to 1e-12)",
                    direction.norm()
                ),
            );
        }
        let stiffness = self.finite(&key("stiffness"), s.stiffness)?;
        if stiffness < 0.0 {
            return self.err(
                key("stiffness"),
                format!("{stiffness}; expected a stiffness >= 0 in N/m"),
            );
        }
        let rest_length = self.positive(&key("rest_length"), s.rest_length, "a length in m")?;
        Ok(SpringSpec {
            body_point,
            direction,
            stiffness,
            rest_length,
            anchor: body_point + direction * rest_length,
        })
    }

    /// Values of a ladder table that do not depend on a scene: finite, positive, tols in
    /// (0, 1), no duplicates; the case-level table must give all four lists.
    fn ladders_shape(&self, prefix: &str, l: &RawLadders, complete: bool) -> Res<()> {
        for key in ["order1", "order2_4", "order6", "tol"] {
            match l.get(key) {
                Some(v) => self.list_shape(&format!("{prefix}.{key}"), key, v)?,
                None if complete => {
                    return self.err(
                        format!("{prefix}.{key}"),
                        "missing; expected a list (it may be empty)",
                    );
                }
                None => {}
            }
            if let Some(v) = l.quick.as_ref().and_then(|q| q.get(key)) {
                self.list_shape(&format!("{prefix}.quick.{key}"), key, v)?;
            }
        }
        Ok(())
    }

    fn list_shape(&self, path: &str, key: &str, v: &[f64]) -> Res<()> {
        for (j, x) in v.iter().enumerate() {
            let k = format!("{path}[{j}]");
            if key == "tol" {
                let x = self.finite(&k, *x)?;
                if !(x > 0.0 && x < 1.0) {
                    return self.err(k, format!("{x}; expected a tolerance in (0, 1)"));
                }
            } else {
                self.positive(&k, *x, "a step in s")?;
            }
            if v[..j].contains(x) {
                return self.err(k, format!("{x} appears twice; expected distinct values"));
            }
        }
        Ok(())
    }

    /// One tier of a scene's effective ladder.
    fn tier(
        &self,
        case_l: &RawLadders,
        scene_l: Option<&RawLadders>,
        quick: bool,
        span: &Span,
        max_steps: u64,
    ) -> Res<Ladder> {
        let pick = |key: &str| -> Option<(String, &Vec<f64>)> {
            if quick {
                if let Some(v) = scene_l.and_then(|l| quick_list(l, key)) {
                    return Some((format!("scene[{}].ladders.quick.{key}", span.index), v));
                }
                quick_list(case_l, key).map(|v| (format!("ladders.quick.{key}"), v))
            } else {
                if let Some(v) = scene_l.and_then(|l| l.get(key)) {
                    return Some((format!("scene[{}].ladders.{key}", span.index), v));
                }
                case_l.get(key).map(|v| (format!("ladders.{key}"), v))
            }
        };
        let mut out = Ladder::default();
        for class in OrderClass::ALL {
            let steps = match pick(class.key()) {
                Some((path, v)) => v
                    .iter()
                    .enumerate()
                    .map(|(j, h)| self.fixed_step(&format!("{path}[{j}]"), *h, span, max_steps))
                    .collect::<Res<Vec<_>>>()?,
                None => Vec::new(),
            };
            match class {
                OrderClass::Order1 => out.order1 = steps,
                OrderClass::Order2To4 => out.order2_4 = steps,
                OrderClass::Order6 => out.order6 = steps,
            }
        }
        out.tol = pick("tol").map(|(_, v)| v.clone()).unwrap_or_default();
        Ok(out)
    }

    fn fixed_step(&self, key: &str, dt: f64, span: &Span, max_steps: u64) -> Res<FixedStep> {
        let Some(per_score) = steps_dividing(span.score_every, dt) else {
            return self.err(
                key,
                format!(
                    "step {dt} s does not divide score_every = {} s of scene `{}`; expected \
                     score_every / step to be an integer (to 1e-9 relative)",
                    span.score_every, span.name
                ),
            );
        };
        let steps = per_score.saturating_mul(span.n_score);
        if steps > max_steps {
            return self.err(
                key,
                format!(
                    "step {dt} s needs {steps} steps over t_end = {} s of scene `{}`, more \
                     than max_steps = {max_steps}",
                    span.t_end, span.name
                ),
            );
        }
        Ok(FixedStep {
            dt,
            per_score,
            steps,
            h: span.t_end / steps as f64,
        })
    }

    fn scene(
        &self,
        i: usize,
        s: &RawScene,
        body: &BodySpec,
        nonphysical: bool,
        case_l: &RawLadders,
        max_steps: u64,
    ) -> Res<Scene> {
        let key = |k: &str| format!("scene[{i}].{k}");
        self.name(
            &key("name"),
            &s.name,
            |c| c.is_ascii_alphanumeric() || c == '_' || c == '-',
            "a scene name matching [A-Za-z0-9_-]+",
        )?;
        let euler_xyz = self.vec3(&key("euler_xyz"), s.euler_xyz)?;
        let r0 = so3::rx(euler_xyz.x) * so3::ry(euler_xyz.y) * so3::rz(euler_xyz.z);
        let q0 = so3::quat_from_matrix(&r0);
        let translates = body.mass.is_some() && body.pivot_com.is_none();
        let mut state = [Vector3::zeros(); 2];
        for (slot, (k, v)) in state
            .iter_mut()
            .zip([("position", s.position), ("velocity", s.velocity)])
        {
            if let Some(v) = v {
                *slot = self.vec3(&key(k), v)?;
                if !translates && *slot != Vector3::zeros() {
                    return self.err(
                        key(k),
                        "must be zero: the body does not translate (no body.mass, or a pivot)",
                    );
                }
            }
        }
        let [position, velocity] = state;
        let inertia = match s.inertia {
            Some(m) => self.inertia(&key("inertia"), m, nonphysical)?,
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
            return self.err(
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
                let w = self.vec3(&key("omega"), *v)?;
                (AngularInit::Body(w), w)
            }
            Some(("omega_world", v)) => {
                let w = self.vec3(&key("omega_world"), *v)?;
                (AngularInit::World(w), r0.transpose() * w)
            }
            Some((_, v)) => {
                let l = self.vec3(&key("angular_momentum_body"), *v)?;
                let j = match body.pivot_com {
                    Some(x) => {
                        inertia
                            + (Matrix3::identity() * x.norm_squared() - x * x.transpose())
                                * body.mass.unwrap_or(0.0)
                    }
                    None => inertia,
                };
                let Some(w) = j.cholesky().map(|c| c.solve(&l)) else {
                    return self.err(key("angular_momentum_body"), "singular inertia");
                };
                (AngularInit::MomentumBody(l), w)
            }
        };
        // Finite inputs can still give a non-finite body rate (`J^-1 L` with a near-singular
        // inertia, `R0^T w` near the largest double): name the key it came from.
        if !omega0.iter().all(|x| x.is_finite()) {
            return self.err(
                key(given.first().map_or("omega", |g| g.0)),
                format!(
                    "gives the body angular velocity {:?}; expected one that is finite",
                    omega0.as_slice()
                ),
            );
        }
        let t_end = self.positive(&key("t_end"), s.t_end, "a horizon in s")?;
        let sample_every = self.positive(&key("sample_every"), s.sample_every, "a time in s")?;
        let score_every = self.positive(&key("score_every"), s.score_every, "a time in s")?;
        let Some(n_score) = steps_dividing(t_end, score_every) else {
            return self.err(
                key("score_every"),
                format!(
                    "{score_every} s does not divide t_end = {t_end} s; expected t_end / \
                     score_every to be an integer (to 1e-9 relative)"
                ),
            );
        };
        let Some(samples_per_score) = steps_dividing(score_every, sample_every) else {
            return self.err(
                key("sample_every"),
                format!(
                    "{sample_every} s does not divide score_every = {score_every} s; expected \
                     score_every / sample_every to be an integer (to 1e-9 relative)"
                ),
            );
        };
        if let Some(l) = &s.ladders {
            self.ladders_shape(&key("ladders"), l, false)?;
        }
        let span = Span {
            index: i,
            name: s.name.clone(),
            t_end,
            score_every,
            n_score,
        };
        let ladders = self.tier(case_l, s.ladders.as_ref(), false, &span, max_steps)?;
        let quick = self.tier(case_l, s.ladders.as_ref(), true, &span, max_steps)?;
        Ok(Scene {
            name: s.name.clone(),
            index: i,
            euler_xyz,
            r0,
            q0,
            position,
            velocity,
            angular,
            omega0,
            inertia,
            inertia_override: s.inertia.is_some(),
            t_end,
            sample_every,
            score_every,
            n_score,
            samples_per_score,
            ladders,
            quick,
        })
    }

    fn gate(&self, i: usize, g: RawGate, scenes: &[Scene]) -> Res<Gate> {
        let key = |k: &str| format!("gates[{i}].{k}");
        self.name(
            &key("metric"),
            &g.metric,
            |c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_',
            "a snake_case metric name",
        )?;
        let bound = match (g.max, g.min) {
            (Some(x), None) => Bound::Max(self.finite(&key("max"), x)?),
            (None, Some(x)) => Bound::Min(self.finite(&key("min"), x)?),
            _ => {
                return self.err(format!("gates[{i}]"), "expected exactly one of max, min");
            }
        };
        let baseline = g
            .baseline
            .map(|x| self.finite(&key("baseline"), x))
            .transpose()?;
        let margin = g
            .margin
            .map(|x| self.positive(&key("margin"), x, "a factor"))
            .transpose()?;
        let w = g.filter;
        let strings = |k: &str, v: Option<OneOrMany<String>>| -> Res<Vec<String>> {
            let v = v.map(OneOrMany::into_vec).unwrap_or_default();
            for (j, s) in v.iter().enumerate() {
                let kk = format!("gates[{i}].where.{k}[{j}]");
                match k {
                    "scene" => {
                        if !scenes.iter().any(|sc| &sc.name == s) {
                            return self.err(kk, format!("no scene `{s}` in this case"));
                        }
                    }
                    "formulation" => {
                        if s != "body" && s != "spatial" {
                            return self.err(kk, format!("`{s}`; expected body or spatial"));
                        }
                    }
                    _ => self.name(
                        &kk,
                        s,
                        |c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_',
                        "a snake_case variant name",
                    )?,
                }
            }
            Ok(v)
        };
        let numbers = |k: &str, v: Option<OneOrMany<f64>>| -> Res<Vec<f64>> {
            let v = v.map(OneOrMany::into_vec).unwrap_or_default();
            for (j, x) in v.iter().enumerate() {
                self.positive(
                    &format!("gates[{i}].where.{k}[{j}]"),
                    *x,
                    "a step or tolerance",
                )?;
            }
            Ok(v)
        };
        let filter = GateWhere {
            scene: strings("scene", w.scene)?,
            param: strings("param", w.param)?,
            integrator: strings("integrator", w.integrator)?,
            formulation: strings("formulation", w.formulation)?,
            dt: numbers("dt", w.dt)?,
            tol: numbers("tol", w.tol)?,
        };
        if !filter.dt.is_empty() && !filter.tol.is_empty() {
            return self.err(
                key("where"),
                "both dt and tol: no run has both; expected at most one",
            );
        }
        Ok(Gate {
            metric: g.metric,
            bound,
            filter,
            quick: g.quick,
            baseline,
            margin,
            commit: g.commit,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const NINE: &str = include_str!("../cases/nine_spring.toml");
    const LABEL: &str = "cases/nine_spring.toml";

    /// `NINE` with the first `old` replaced by `new` (which must occur).
    fn edited(old: &str, new: &str) -> String {
        assert!(NINE.contains(old), "test fixture lost `{old}`");
        NINE.replacen(old, new, 1)
    }

    /// The error of loading `text`, checked to name the file and `key` in its Display.
    fn error_at(text: &str, key: &str) -> CaseError {
        let e = load_str(LABEL, text).expect_err("bad input must not load");
        let shown = e.to_string();
        assert!(shown.starts_with(LABEL), "`{shown}` does not name the file");
        assert_eq!(e.key, key, "`{shown}`");
        assert!(shown.contains(&format!("{LABEL}: {key}: ")), "`{shown}`");
        e
    }

    /// Energy of spec/cases.md sec. 1 from the parsed data:
    /// `m|v|^2/2 + omega.J.omega/2 + sum k (l - L0)^2/2 + m g0 x_z`.
    fn energy0(case: &Case, scene: &Scene) -> f64 {
        let m = case.body.mass.unwrap();
        let mut e = 0.5 * m * scene.velocity.norm_squared()
            + 0.5 * scene.omega0.dot(&(scene.inertia * scene.omega0))
            + m * case.body.gravity.unwrap_or(0.0) * scene.position.z;
        for s in &case.springs {
            let l = (s.anchor - (scene.position + scene.r0 * s.body_point)).norm();
            e += 0.5 * s.stiffness * (l - s.rest_length).powi(2);
        }
        e
    }

    // Every embedded catalogue file loads, with the structure spec/cases.md prescribes.
    #[test]
    fn embedded_files_load() {
        let cases = embedded().unwrap();
        let names: Vec<&str> = cases.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(
            names,
            ["free_body", "gimbal_lock", "heavy_top", "nine_spring"]
        );
        for c in &cases {
            assert_eq!(c.file, format!("cases/{}.toml", c.name));
            assert_eq!(c.max_steps, DEFAULT_MAX_STEPS);
            // Every catalogue case is gated, the quick tier included.
            assert!(
                c.gates.iter().any(|g| g.quick),
                "{} has no quick gate",
                c.name
            );
            for s in &c.scenes {
                assert!(!s.ladders.order2_4.is_empty() && !s.ladders.tol.is_empty());
                for class in OrderClass::ALL {
                    assert_eq!(s.quick.fixed(class).len(), 1, "{}/{}", c.name, s.name);
                }
                assert_eq!(s.quick.tol.len(), 1);
            }
        }
        let by = |n: &str| cases.iter().find(|c| c.name == n).unwrap();
        let g = by("gimbal_lock");
        let scenes: Vec<&str> = g.scenes.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(
            scenes,
            [
                "spin_d0",
                "spin_d1e-2",
                "spin_d1e-4",
                "spin_d1e-8",
                "spin_zxz_d1e-2",
                "spin_zxz_d1e-4",
                "tumble"
            ]
        );
        assert_eq!(g.reference, ReferenceKind::Exact);
        assert_eq!(by("free_body").reference, ReferenceKind::Exact);
        assert_eq!(by("heavy_top").reference, ReferenceKind::Numerical);
        assert_eq!(by("nine_spring").reference, ReferenceKind::Numerical);
        let spin = g.scene("spin_d1e-2").unwrap();
        assert!(spin.ladders.order2_4.iter().any(|f| f.dt == 1.0e-2));
        assert!(spin.ladders.tol.contains(&1.0e-8) && spin.ladders.tol.contains(&1.0e-10));
        assert!(g.translates());
        let f = by("free_body");
        assert!(f.nonphysical_inertia && f.body.mass.is_none() && !f.translates());
        let h = by("heavy_top");
        assert_eq!(h.body.pivot_com, Some(Vector3::new(0.0, 1.0, 0.0)));
        assert!(!h.translates() && !h.nonphysical_inertia);
        assert_eq!(h.body.gravity, Some(9.81));
    }

    // E0 of nine_spring's scenes equals spec/cases.md's printed values to their last digit.
    #[test]
    fn nine_spring_initial_energies_match_the_spec() {
        let c = load_str(LABEL, NINE).unwrap();
        let large = energy0(&c, c.scene("large").unwrap());
        let two = energy0(&c, c.scene("two_angles").unwrap());
        // Printed as 25035.29 and 6524.2: half a unit of the last printed digit.
        assert!((large - 25035.29).abs() <= 0.005, "large E0 = {large}");
        assert!((two - 6524.2).abs() <= 0.05, "two_angles E0 = {two}");
        // The same energy through the model the runner will build.
        for s in &c.scenes {
            let body = c.rigid_body(s).unwrap();
            let e = body.energy(&c.initial(s));
            assert!((e - energy0(&c, s)).abs() <= 1e-9 * e, "{}: {e}", s.name);
        }
    }

    // Derived initial data: R0 = Rx Ry Rz, body omega from each of the three inputs.
    #[test]
    fn derived_initial_state() {
        let cases = embedded().unwrap();
        let g = cases.iter().find(|c| c.name == "gimbal_lock").unwrap();
        let z = g.scene("spin_zxz_d1e-2").unwrap();
        // R0 = Ry(pi/2): body z along world x (to the rounding of cos(pi/2) ~ 6e-17).
        assert!((z.r0 * Vector3::z() - Vector3::x()).amax() <= 1e-15);
        assert!((z.r0 - so3::ry(std::f64::consts::FRAC_PI_2)).amax() == 0.0);
        let w = Vector3::new(0.009999833334166664, 0.9999500004166653, 0.0);
        assert_eq!(z.angular, AngularInit::World(w));
        // omega_body = R0^T w, an orthogonal map: the norm is kept to round-off.
        assert!((z.r0 * z.omega0 - w).amax() <= 1e-15);
        assert!((z.omega0.norm() - 1.0).abs() <= 1e-15);
        let t = g.scene("tumble").unwrap();
        assert!(t.inertia_override);
        assert_eq!(
            t.inertia,
            Matrix3::from_diagonal(&Vector3::new(0.3, 0.35, 0.4))
        );
        assert_eq!(t.omega0, Vector3::new(0.1, 15.0, 0.1));
        assert!((t.r0 - so3::rx(0.5) * so3::rz(0.3)).amax() <= 1e-16);
        assert!((t.q0.to_rotation_matrix().into_inner() - t.r0).amax() <= 1e-15);
        let f = cases.iter().find(|c| c.name == "free_body").unwrap();
        let gni = &f.scenes[0];
        // J omega0 reproduces L = (cos 1.1, 0, sin 1.1) to round-off.
        let l = Vector3::new(0.4535961214255773, 0.0, 0.8912073600614354);
        assert!((gni.inertia * gni.omega0 - l).amax() <= 1e-15);
        assert_eq!(gni.position, Vector3::zeros());
    }

    // Ladders resolve per scene: overrides win, step counts follow the divides rule.
    #[test]
    fn ladders_and_step_counts() {
        let cases = embedded().unwrap();
        let g = cases.iter().find(|c| c.name == "gimbal_lock").unwrap();
        let spin = g.scene("spin_d0").unwrap();
        assert_eq!(spin.n_score, 320);
        assert_eq!(spin.samples_per_score, 1);
        let f = spin.ladders.order2_4[0];
        assert_eq!((f.dt, f.per_score, f.steps), (1.0e-2, 1, 320));
        assert!((f.h - 0.01).abs() <= 1e-17);
        let tumble = g.scene("tumble").unwrap();
        assert_eq!(tumble.ladders.order2_4[0].dt, 2.0e-2);
        assert_eq!(tumble.ladders.order2_4[0].steps, 1000);
        // The override has no tol: the case's applies.
        assert_eq!(tumble.ladders.tol, spin.ladders.tol);
        assert_eq!(tumble.quick.order6[0].dt, 5.0e-2);
        assert_eq!(tumble.quick.tol, vec![1.0e-8]);
        let h = cases.iter().find(|c| c.name == "heavy_top").unwrap();
        let s = &h.scenes[0];
        let last = s.ladders.order1.last().unwrap();
        assert_eq!((last.per_score, last.steps), (2000, 400_000));
        assert_eq!(s.samples_per_score, 10);
        assert_eq!(OrderClass::of_order(4), Some(OrderClass::Order2To4));
        assert_eq!(OrderClass::of_order(6), Some(OrderClass::Order6));
        assert_eq!(OrderClass::of_order(1), Some(OrderClass::Order1));
    }

    // The divides rule of spec/cases.md: n = round(T/h), |n h - T| <= 1e-9 T.
    #[test]
    fn steps_dividing_rule() {
        assert_eq!(steps_dividing(0.1, 1.0e-2), Some(10));
        assert_eq!(steps_dividing(3.2, 0.01), Some(320));
        assert_eq!(steps_dividing(0.01, 1.25e-4), Some(80));
        assert_eq!(steps_dividing(0.1, 6.25e-6), Some(16000));
        assert_eq!(steps_dividing(0.1, 0.1), Some(1));
        assert_eq!(steps_dividing(0.1, 3.0e-2), None);
        assert_eq!(steps_dividing(0.1, 0.2), None); // n = round(0.5) would be 0 or 1: off
        // Within 1e-9 relative passes, 1e-8 does not.
        assert_eq!(steps_dividing(1.0, 0.1 * (1.0 + 5e-11)), Some(10));
        assert_eq!(steps_dividing(1.0, 0.1 * (1.0 + 1e-8)), None);
        assert_eq!(steps_dividing(0.0, 0.1), None);
        assert_eq!(steps_dividing(1.0, -0.1), None);
        assert_eq!(steps_dividing(1.0, f64::NAN), None);
        assert_eq!(steps_dividing(f64::INFINITY, 0.1), None);
    }

    // An unknown key is named with its full path.
    #[test]
    fn unknown_key() {
        let e = error_at(
            &edited(
                "name = \"large\"\n",
                "name = \"large\"\nomgea = [0.0, 0.0, 1.0]\n",
            ),
            "scene[0].omgea",
        );
        assert!(e.message.contains("unknown field `omgea`"), "{e}");
        error_at(
            &edited("[ladders]\n", "[ladders]\norder3 = [1.0]\n"),
            "ladders.order3",
        );
        error_at(
            &edited("quick = { order1", "quick = { order5 = [1.0], order1"),
            "ladders.quick.order5",
        );
        error_at(
            &edited("schema = 1\n", "schema = 1\nauthor = \"x\"\n"),
            "author",
        );
    }

    // A wrong type is named with the path of the value, down to an array index.
    #[test]
    fn wrong_type() {
        let e = error_at(&edited("mass = 1000.0", "mass = \"heavy\""), "body.mass");
        assert!(e.message.contains("expected f64"), "{e}");
        error_at(
            &edited(
                "euler_xyz = [0.0, 0.5, 1.0]",
                "euler_xyz = [0.0, 0.5, \"1\"]",
            ),
            "scene[1].euler_xyz[2]",
        );
        let e = error_at(
            &edited("euler_xyz = [0.0, 0.5, 1.0]", "euler_xyz = [0.0, 0.5]"),
            "scene[1].euler_xyz",
        );
        assert!(e.message.contains("length 3"), "{e}");
        error_at(
            &edited("stiffness = 5.0e3 ", "stiffness = [5.0e3]"),
            "spring[0].stiffness",
        );
        error_at(&edited("schema = 1", "schema = 1.0"), "schema");
        let e = error_at(&edited("\"numerical\"", "\"stored\""), "reference");
        assert!(e.message.contains("`numerical` or `exact`"), "{e}");
    }

    // A missing required key is named, and a TOML syntax error gives file and line.
    #[test]
    fn missing_key_and_syntax_error() {
        let text = edited(
            "euler_xyz = [0.0, 0.5, 1.0]\nt_end = 10.0\n",
            "euler_xyz = [0.0, 0.5, 1.0]\n",
        );
        let e = error_at(&text, "scene[1].t_end");
        assert!(e.message.contains("missing field `t_end`"), "{e}");
        let e = error_at(
            &edited("gravity = 9.81", "gravity = 9.81 m/s2"),
            "body.gravity",
        );
        let line_of = |s: &str| NINE.lines().position(|l| l.starts_with(s)).unwrap() + 1;
        assert!(
            e.message.contains(&format!("line {}", line_of("gravity"))),
            "{e}"
        );
        let e = load_str(LABEL, &edited("[body]", "[body")).unwrap_err();
        assert!(
            e.to_string().starts_with(LABEL)
                && e.message.contains(&format!("line {}", line_of("[body]"))),
            "{e}"
        );
    }

    // Mass must be positive; a zero or negative mass names body.mass.
    #[test]
    fn non_positive_mass() {
        for m in ["0.0", "-1000.0"] {
            let e = error_at(
                &edited("mass = 1000.0", &format!("mass = {m}")),
                "body.mass",
            );
            assert!(e.message.contains("> 0"), "{e}");
        }
    }

    // The inertia must be symmetric, positive definite and physical (unless flagged).
    #[test]
    fn bad_inertia() {
        let j = "[[800.0, -60.0, 40.0], [-60.0, 1000.0, -80.0], [40.0, -80.0, 1200.0]]";
        let with = |m: &str| edited(j, m);
        let e = error_at(
            &with("[[800.0, -60.0, 40.0], [-60.0, 1000.0, -80.0], [40.0, -80.5, 1200.0]]"),
            "body.inertia",
        );
        assert!(e.message.contains("symmetric"), "{e}");
        // Off by 1e-13 relative: symmetric within 1e-12, accepted.
        load_str(
            LABEL,
            &with(
                "[[800.0, -60.0, 40.0], [-60.0, 1000.0, -80.0], [40.0, -80.00000000001, 1200.0]]",
            ),
        )
        .unwrap();
        let e = error_at(
            &with("[[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]]"),
            "body.inertia",
        );
        assert!(e.message.contains("positive definite"), "{e}");
        error_at(
            &with("[[1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]]"),
            "body.inertia",
        );
        // diag(2, 1, 2/3) violates 1 + 2/3 >= 2.
        let gni = "[[2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.6666666666666666]]";
        let e = error_at(&with(gni), "body.inertia");
        assert!(e.message.contains("triangle inequality"), "{e}");
        // The same body loads with the flag.
        let flagged = with(gni).replace(
            "reference = \"numerical\"",
            "reference = \"numerical\"\nnonphysical_inertia = true",
        );
        load_str(LABEL, &flagged).unwrap();
        // Equality is physical (heavy_top's disc): it loads without the flag.
        let disc = "[[0.234375, 0.0, 0.0], [0.0, 0.46875, 0.0], [0.0, 0.0, 0.234375]]";
        let c = load_str(LABEL, &with(disc)).unwrap();
        assert!(!c.nonphysical_inertia);
        // A per-scene override is checked too, under its own key.
        let e = error_at(
            &edited(
                "name = \"two_angles\"\n",
                &format!("name = \"two_angles\"\ninertia = {gni}\n"),
            ),
            "scene[1].inertia",
        );
        assert!(e.message.contains("triangle"), "{e}");
    }

    // t_end, sample_every and score_every must be positive and nest by the divides rule.
    #[test]
    fn bad_times() {
        for t in ["0.0", "-10.0"] {
            let e = error_at(
                &edited(
                    "euler_xyz = [0.0, 0.5, 1.0]\nt_end = 10.0",
                    &format!("euler_xyz = [0.0, 0.5, 1.0]\nt_end = {t}"),
                ),
                "scene[1].t_end",
            );
            assert!(e.message.contains("> 0"), "{e}");
        }
        error_at(
            &edited("t_end = 10.0", "t_end = 10.05"),
            "scene[0].score_every",
        );
        error_at(
            &edited("sample_every = 0.01", "sample_every = 0.03"),
            "scene[0].sample_every",
        );
    }

    // A ladder step that does not divide score_every names the step and the scene.
    #[test]
    fn ladder_step_not_dividing() {
        let e = error_at(
            &edited("order2_4 = [2.0e-2,", "order2_4 = [3.0e-2,"),
            "ladders.order2_4[0]",
        );
        assert!(
            e.message.contains("does not divide") && e.message.contains("`large`"),
            "{e}"
        );
        error_at(
            &edited("quick = { order1 = [1.0e-3]", "quick = { order1 = [7.0e-3]"),
            "ladders.quick.order1[0]",
        );
        error_at(&edited("tol = [1.0e-4,", "tol = [2.0,"), "ladders.tol[0]");
        // A step longer than the score interval does not divide it either.
        error_at(
            &edited("order6 = [5.0e-2,", "order6 = [2.0e-1,"),
            "ladders.order6[0]",
        );
    }

    // NaN and infinities are rejected wherever a number is read.
    #[test]
    fn non_finite_numbers() {
        let e = error_at(&edited("t_end = 10.0", "t_end = nan"), "scene[0].t_end");
        assert!(e.message.contains("finite"), "{e}");
        error_at(
            &edited("stiffness = 5.0e3 ", "stiffness = inf "),
            "spring[0].stiffness",
        );
        error_at(
            &edited("[-60.0, 1000.0, -80.0]", "[-60.0, nan, -80.0]"),
            "body.inertia[1][1]",
        );
        error_at(
            &edited(
                "euler_xyz = [0.0, 0.5, 1.0]",
                "euler_xyz = [0.0, -inf, 1.0]",
            ),
            "scene[1].euler_xyz[1]",
        );
    }

    // Finite inputs whose derived body rate overflows (found by tests/fuzz.rs) are an error
    // naming the angular key, not a case whose omega0 is infinite.
    #[test]
    fn non_finite_body_rate() {
        let scene = |extra: &str| {
            edited(
                "name = \"two_angles\"\n",
                &format!("name = \"two_angles\"\n{extra}\n"),
            )
        };
        let e = error_at(
            &scene(
                "inertia = [[1.0e-300, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]\n\
                 angular_momentum_body = [1.0e10, 0.0, 0.0]",
            ),
            "scene[1].angular_momentum_body",
        );
        assert!(e.message.contains("finite"), "{e}");
        let e = error_at(
            &scene("omega_world = [1.7e308, 1.7e308, 1.7e308]"),
            "scene[1].omega_world",
        );
        assert!(e.message.contains("finite"), "{e}");
        // The largest rates that stay finite load.
        load_str(LABEL, &scene("omega = [1.7e308, 1.7e308, 1.7e308]")).unwrap();
    }

    // Other validations: names, springs, angular inputs, gates' shape.
    #[test]
    fn other_validations() {
        error_at(&edited("schema = 1", "schema = 2"), "schema");
        error_at(
            &edited("name = \"large\"", "name = \"two_angles\""),
            "scene[1].name",
        );
        error_at(
            &edited("name = \"large\"", "name = \"la rge\""),
            "scene[0].name",
        );
        error_at(
            &edited(
                "primary_metric = \"rotation_error_max\"",
                "primary_metric = \"rot\"",
            ),
            "primary_metric",
        );
        error_at(
            &edited("energy_scale = 1.0e3", "energy_scale = 0.0"),
            "energy_scale",
        );
        error_at(
            &edited(
                "direction = [1.0, 0.0, 0.0]",
                "direction = [1.0, 1.0e-5, 0.0]",
            ),
            "spring[0].direction",
        );
        error_at(
            &edited("rest_length = 1.0 ", "rest_length = 0.0 "),
            "spring[0].rest_length",
        );
        error_at(
            &edited("stiffness = 5.0e3 ", "stiffness = -1.0 "),
            "spring[0].stiffness",
        );
        error_at(
            &edited(
                "name = \"large\"\n",
                "name = \"large\"\nomega = [0.0, 0.0, 1.0]\nomega_world = [0.0, 0.0, 1.0]\n",
            ),
            "scene[0].omega_world",
        );
        error_at(
            &edited("mass = 1000.0", "pivot_com = [0.0, 1.0, 0.0]"),
            "body.gravity",
        );
        let bare = without_gates(NINE);
        assert!(load_str(LABEL, &bare).unwrap().gates.is_empty());
        let gate = |body: &str| format!("{bare}\n[[gates]]\n{body}\n");
        let ok = gate(
            "metric = \"energy_drift_max\"\nmax = 3.0e-9\nwhere = { scene = \"two_angles\", \
             param = \"so3\", integrator = [\"rk4\", \"gauss6\"], dt = 1.0e-3 }\nquick = true\n\
             baseline = 1.0e-9\nmargin = 3.0\ncommit = \"abc1234\"",
        );
        let c = load_str(LABEL, &ok).unwrap();
        assert_eq!(c.gates[0].bound, Bound::Max(3.0e-9));
        assert_eq!(c.gates[0].filter.integrator, ["rk4", "gauss6"]);
        assert_eq!(c.gates[0].filter.dt, [1.0e-3]);
        error_at(
            &gate("metric = \"energy_drift_max\"\nmax = 1.0\nmin = 0.0"),
            "gates[0]",
        );
        error_at(
            &gate("metric = \"energy_drift_max\"\nmax = 1.0\nwhere = { scene = \"nope\" }"),
            "gates[0].where.scene[0]",
        );
        error_at(
            &gate("metric = \"energy_drift_max\"\nmax = 1.0\nwhere = { colour = \"red\" }"),
            "gates[0].where.colour",
        );
    }

    // The inputs hash covers the physics only: ladders, gates, title and sample_every do not
    // change it; a stiffness, t_end or initial angle does.
    #[test]
    fn inputs_hash_covers_physics_only() {
        let hash = |text: &str, scene: usize| {
            let c = load_str(LABEL, text).unwrap();
            inputs_sha256(&c, &c.scenes[scene])
        };
        let h0 = hash(NINE, 1);
        assert_eq!(h0.len(), 64);
        assert!(h0.chars().all(|c| c.is_ascii_hexdigit()));
        assert_eq!(h0, hash(NINE, 1));
        assert_ne!(h0, hash(NINE, 0));
        let same = [
            edited("order2_4 = [2.0e-2,", "order2_4 = [5.0e-2, 2.0e-2,"),
            edited("tol = [1.0e-4,", "tol = [1.0e-3, 1.0e-4,"),
            edited("title = \"Rigid", "title = \"A rigid"),
            edited(
                "1.0]\nt_end = 10.0\nsample_every = 0.01",
                "1.0]\nt_end = 10.0\nsample_every = 0.05",
            ),
            format!("{NINE}\n[[gates]]\nmetric = \"energy_drift_max\"\nmax = 1.0\n"),
            edited("mass = 1000.0                 # kg", "mass = 1000.0"),
        ];
        for t in &same {
            assert_eq!(hash(t, 1), h0, "changed by an edit that is not physics");
        }
        let differ = [
            edited("stiffness = 5.0e3 ", "stiffness = 5.1e3 "),
            edited(
                "1.0]\nt_end = 10.0\n",
                "1.0]\nposition = [0.0, 0.0, 1.0e-3]\nt_end = 10.0\n",
            ),
            edited(
                "euler_xyz = [0.0, 0.5, 1.0]\nt_end = 10.0",
                "euler_xyz = [0.0, 0.5, 1.0]\nt_end = 20.0",
            ),
            edited("euler_xyz = [0.0, 0.5, 1.0]", "euler_xyz = [0.0, 0.5, 1.1]"),
            edited("gravity = 9.81", "gravity = 9.80665"),
        ];
        for t in &differ {
            assert_ne!(hash(t, 1), h0, "not changed by a physics edit");
        }
        // The canonical JSON sorts keys at every level.
        let c = load_str(LABEL, NINE).unwrap();
        let json = canonical_json(&inputs_value(&c, &c.scenes[1]));
        assert!(
            json.starts_with("{\"body\":{\"gravity\":9.81,\"inertia\":"),
            "{json}"
        );
        assert!(json.contains("\"score_every\":0.1,\"springs\":["), "{json}");
    }

    // load_dir reads the source tree's cases/ exactly as the embedded copy, sorted; a file
    // whose case name differs from its stem is rejected.
    #[test]
    fn load_dir_matches_embedded() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases");
        let from_dir = load_dir(&dir).unwrap();
        let emb = embedded().unwrap();
        assert_eq!(from_dir.len(), emb.len());
        for (a, b) in from_dir.iter().zip(&emb) {
            assert_eq!(a.name, b.name);
            assert_eq!(a.scenes, b.scenes);
            assert!(a.file.ends_with(&format!("{}.toml", a.name)));
        }
        let tmp = std::env::temp_dir().join(format!("mbdbench-case-test-{}", std::process::id()));
        std::fs::create_dir_all(&tmp).unwrap();
        std::fs::write(tmp.join("other.toml"), NINE).unwrap();
        let e = load_dir(&tmp).unwrap_err();
        std::fs::remove_dir_all(&tmp).unwrap();
        assert_eq!(e.key, "case");
        assert!(e.to_string().contains("other.toml"), "{e}");
    }
}
