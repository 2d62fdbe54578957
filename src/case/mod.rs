//! Case files (`cases/*.toml`, cases/README.md "Case-file keys") to typed, validated structs: the
//! part every model family shares (the family's own part is parsed by the family, which the
//! catalogue's loader, `catalogue::load_str`, picks by the file's `model` key), so that unknown
//! keys and key paths in errors work for every family. `case` knows a family only through
//! [`CaseFamily`], so it sits below the seam (`problem`) in the crate's layers.
//!
//! A file is read in two passes. First serde, with `deny_unknown_fields` everywhere, turns
//! the TOML into the family's raw structs (declared with [`case_schema!`], which adds the
//! shared keys); a syntax error, an unknown key or a wrong type comes back with a dotted key
//! path (`keypath`). Second, the raw structs are checked against the physics and the
//! conventions of the case-file specification, and the data a run needs is computed once:
//! the shared part here ([`Ctx::assemble`]: name, primary metric among the family's metrics,
//! budgets, each scene's grid and ladders, gates, `[stability]`), the family's physics by the
//! family (held as a [`Payload`] of the case and of each scene).
//!
//! Invariants after loading: every number is finite; `score_every` divides `t_end`,
//! `sample_every` divides `score_every` and every fixed step divides `score_every` by the
//! rule of `ladder` (`n = round(T/h)`, `|n h - T| <= 1e-9 T`; the run then takes `n` steps
//! of `T/n`). Errors are values naming the file, the key and what was expected; loading
//! never panics.
//!
//! # Example
//!
//! ```
//! let cases = mbdbench::catalogue::embedded().unwrap();
//! let c = cases.iter().find(|c| c.name == "nine_spring").unwrap();
//! assert_eq!(c.model(), "rigid_body");
//! let s = c.scene("two_angles").unwrap();
//! assert!(s.t_end > 0.0 && s.n_score >= 1);
//! // Bad input is an error naming the file and the key.
//! let source = mbdbench::case::embedded_sources()
//!     .iter()
//!     .find(|(label, _)| label.ends_with("nine_spring.toml"))
//!     .unwrap();
//! let text = source.1.replace("t_end = 10.0", "t_end = -1.0");
//! let e = mbdbench::catalogue::load_str("cases/nine_spring.toml", &text).unwrap_err();
//! assert!(e.key.ends_with(".t_end"), "{e}");
//! ```
use std::any::Any;
use std::fmt;
use std::path::{Path, PathBuf};

use serde::Deserialize;

pub mod budget;
mod ctx;
pub mod exact;
mod family;
pub mod gate;
pub mod hash;
mod keypath;
pub mod ladder;
mod schema;

pub use budget::{
    DEFAULT_ADVISE_MAX_ENERGY_DRIFT, DEFAULT_MAX_ADAPTIVE_RHS_EVALS, DEFAULT_MAX_MEMORY_MIB,
    DEFAULT_MAX_RHS_EVALS, DEFAULT_MAX_STEPS, DEFAULT_MAX_WORK, Estimate, HARD_CAPS, MAX_SAMPLES,
    OdeCosts, hard_cap, ode_estimate, over_sample_budget,
};
pub use ctx::{Ctx, Res};
pub use family::CaseFamily;
pub use gate::{Bound, Gate, GateWhere, RawGate, VALUE_REL_TOL, same_value};
pub use hash::{canonical_json, inputs_sha256, inputs_value};
pub use ladder::{
    DIVIDES_REL_TOL, Ladder, LadderStep, Ladders, OrderClass, RawLadders, steps_dividing,
};
pub use schema::{RawGrid, RawShared, RawStability};

/// The only schema version this loader reads.
pub const SCHEMA: i64 = 1;

/// The shortest and longest length (m) that sets a model's size ([`Ctx::length`]: a
/// column's height, a section's outline, a beam's length; cases/README.md, "Conventions"):
/// outside, the squares and cubes the models form leave the floating-point range
/// (`height = 1.0e300` made elements of infinite length).
pub const MIN_LENGTH: f64 = 1e-6;
pub const MAX_LENGTH: f64 = 1e6;
/// The catalogue files compiled into the binary, sorted by name.
const EMBEDDED: [(&str, &str); 8] = [
    (
        "cases/fiber_column_cyclic.toml",
        include_str!("../../cases/fiber_column_cyclic.toml"),
    ),
    (
        "cases/fiber_column_dynamic.toml",
        include_str!("../../cases/fiber_column_dynamic.toml"),
    ),
    (
        "cases/fiber_column_static.toml",
        include_str!("../../cases/fiber_column_static.toml"),
    ),
    (
        "cases/flexible_beam.toml",
        include_str!("../../cases/flexible_beam.toml"),
    ),
    (
        "cases/free_body.toml",
        include_str!("../../cases/free_body.toml"),
    ),
    (
        "cases/gimbal_lock.toml",
        include_str!("../../cases/gimbal_lock.toml"),
    ),
    (
        "cases/heavy_top.toml",
        include_str!("../../cases/heavy_top.toml"),
    ),
    (
        "cases/nine_spring.toml",
        include_str!("../../cases/nine_spring.toml"),
    ),
];

// Errors

/// A bad case file: which file, which key (dotted path, `scene[1].t_end`; empty when the
/// problem is the whole file), and what was expected.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CaseError {
    pub file: String,
    pub key: String,
    pub message: String,
}

impl CaseError {
    /// An error on the `model` key of `case`: a case of another family handed to a family's
    /// code.
    pub fn model(case: &Case, message: impl Into<String>) -> Self {
        CaseError {
            file: case.file.clone(),
            key: "model".into(),
            message: message.into(),
        }
    }
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

/// How a case's references are made: the case file's `reference` key. The kinds are open: the
/// three below serve the built-in families, and a family may declare a kind of its own
/// (`ReferenceKind::new("converged")` in its `problem::Family::references`); a case file may
/// name only a kind its family declares (refused at load, by the key `reference`, with the
/// family's kinds).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ReferenceKind(&'static str);

impl ReferenceKind {
    /// Integrated and stored under `references/` (cases/README.md, "References and how they are
    /// checked").
    pub const NUMERICAL: ReferenceKind = ReferenceKind("numerical");
    /// A closed-form solution, evaluated at the score times by `mbdbench reference` and stored
    /// under `references/` like a numerical one.
    pub const EXACT: ReferenceKind = ReferenceKind("exact");
    /// A stored run of another program (OpenSees), made by a script kept beside it: `mbdbench
    /// reference` verifies it (hash, schema, model) and says how to regenerate it.
    pub const EXTERNAL: ReferenceKind = ReferenceKind("external");

    /// A family's own kind, spelled `name` in its case files (snake_case).
    pub const fn new(name: &'static str) -> ReferenceKind {
        ReferenceKind(name)
    }

    /// Its spelling in a case file.
    pub fn name(self) -> &'static str {
        self.0
    }
}

/// A family's own data of a case or of a scene, held without the shared code naming its
/// type; the family reads it back with [`Case::physics`] / [`Scene::physics`].
pub trait Payload: Any + fmt::Debug + Send + Sync {
    fn as_any(&self) -> &dyn Any;
    fn as_any_mut(&mut self) -> &mut dyn Any;
    fn clone_box(&self) -> Box<dyn Payload>;
    fn eq_dyn(&self, other: &dyn Payload) -> bool;
}

impl<T: Any + fmt::Debug + Clone + PartialEq + Send + Sync> Payload for T {
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
    fn clone_box(&self) -> Box<dyn Payload> {
        Box::new(self.clone())
    }
    fn eq_dyn(&self, other: &dyn Payload) -> bool {
        other.as_any().downcast_ref::<T>() == Some(self)
    }
}

/// A family's data, owned by a case or a scene (cloned and compared through [`Payload`]).
#[derive(Debug)]
pub struct Physics(Box<dyn Payload>);

impl Physics {
    pub fn new(p: impl Payload) -> Self {
        Physics(Box::new(p))
    }
    /// The data, if it is a `T`.
    pub fn get<T: Payload>(&self) -> Option<&T> {
        self.0.as_any().downcast_ref()
    }
    /// The data, mutable, if it is a `T`.
    pub fn get_mut<T: Payload>(&mut self) -> Option<&mut T> {
        self.0.as_any_mut().downcast_mut()
    }
}

impl Clone for Physics {
    fn clone(&self) -> Self {
        Physics(self.0.clone_box())
    }
}

impl PartialEq for Physics {
    fn eq(&self, other: &Self) -> bool {
        self.0.eq_dyn(&*other.0)
    }
}

/// One validated case file.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// The label it was loaded from (`cases/nine_spring.toml`).
    pub file: String,
    /// `case`: snake_case, equal to the file stem.
    pub name: String,
    pub title: String,
    /// The family that loaded it (its `model` key: [`Case::model`]).
    pub family: &'static dyn CaseFamily,
    /// One of the family's metrics.
    pub primary_metric: String,
    /// Relative energy drifts divide by `max(|E0|, energy_scale)` (the energy's unit).
    pub energy_scale: f64,
    pub reference: ReferenceKind,
    /// Per-run step budget (default `DEFAULT_MAX_STEPS`).
    pub max_steps: u64,
    /// Per-run RHS-evaluation budget (default `DEFAULT_MAX_RHS_EVALS`).
    pub max_rhs_evals: u64,
    /// RHS-evaluation budget of an adaptive run (default `DEFAULT_MAX_ADAPTIVE_RHS_EVALS`).
    pub max_adaptive_rhs_evals: u64,
    /// The memory (MiB) one run may hold by its family's estimate (default
    /// `DEFAULT_MAX_MEMORY_MIB`).
    pub max_memory_mib: u64,
    /// The work units one run may need by its family's estimate (default `DEFAULT_MAX_WORK`).
    pub max_work: u64,
    /// The recommendation's target errors in the primary metric (None: `advise`'s defaults).
    pub advise_targets: Option<Vec<f64>>,
    /// Above this relative energy drift a variant is listed to avoid (default 1e-3).
    pub advise_max_energy_drift: f64,
    pub scenes: Vec<Scene>,
    pub gates: Vec<Gate>,
    /// `[stability]`: the stability study's settings (None: the case is not in the study).
    pub stability: Option<StabilitySpec>,
    /// The family's own data of the case (a rigid body's body and springs).
    pub physics: Physics,
}

/// `[stability]` (`mbdbench stability`; cases/README.md, "`[stability]`").
#[derive(Debug, Clone, PartialEq)]
pub struct StabilitySpec {
    /// The horizon `t_h` in periods of the scene's fastest linearised mode
    /// (`model::rigid_body::linear_modes`) or first elastic mode (the seam's search); required for scenes
    /// stepped in time, unused by load paths (a static scene's search spans its whole path).
    pub periods: Option<f64>,
    /// rad: the accuracy bound of `largest_accurate_dt` (max geodesic rotation error over the
    /// score times of the horizon); the rigid body's files must give it (its loader checks),
    /// families without a rotation have none.
    pub rotation_error_max: Option<f64>,
    /// Scenes of the quick tier (each names a scene of the case).
    pub quick: Vec<String>,
}

/// `[[scene]]`: the family's initial state, a horizon and the scoring grid.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// `[A-Za-z0-9_-]+`, unique in its case.
    pub name: String,
    /// Position in the file (0-based), as in error keys `scene[i]`.
    pub index: usize,
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
    /// A control scene: its result is known by construction (a chart exact on it); the
    /// recommendation leaves it out of "cheapest" (outside the physics hash).
    pub control: bool,
    /// The family's own data of the scene (a rigid body's initial state).
    pub physics: Physics,
    /// The hash of every key of the file that can change this scene's results (`case::hash`),
    /// set by [`load_str`] from the file's text; empty for a scene built another way.
    pub settings_sha256: String,
}

impl Scene {
    /// The ladder of a tier.
    pub fn ladder(&self, quick: bool) -> &Ladder {
        if quick { &self.quick } else { &self.ladders }
    }

    /// The step of one order class that takes the most steps in either tier, with its key
    /// path (`ladders.quick.order1[0]`); None when neither tier has the class.
    pub fn finest(&self, class: OrderClass) -> Option<(String, LadderStep)> {
        [&self.ladders, &self.quick]
            .into_iter()
            .filter_map(|l| l.finest(class))
            .max_by_key(|(_, s)| s.steps)
    }

    /// The family's data of the scene, if it is a `T`.
    pub fn physics<T: Payload>(&self) -> Option<&T> {
        self.physics.get()
    }

    /// The same, mutable (studies that vary a scene's physics).
    pub fn physics_mut<T: Payload>(&mut self) -> Option<&mut T> {
        self.physics.get_mut()
    }
}

impl Case {
    /// The case's work budgets, for every run of its scenes.
    pub fn limits(&self) -> crate::integrate::Limits {
        crate::integrate::Limits {
            max_steps: self.max_steps,
            max_rhs_evals: self.max_rhs_evals,
            max_adaptive_rhs_evals: self.max_adaptive_rhs_evals,
        }
    }

    /// The family's `model` key (`catalogue::FAMILIES`).
    pub fn model(&self) -> &'static str {
        self.family.model()
    }

    /// The scene named `name`.
    pub fn scene(&self, name: &str) -> Option<&Scene> {
        self.scenes.iter().find(|s| s.name == name)
    }

    /// The family's data of the case, if it is a `T`.
    pub fn physics<T: Payload>(&self) -> Option<&T> {
        self.physics.get()
    }

    /// The same, mutable.
    pub fn physics_mut<T: Payload>(&mut self) -> Option<&mut T> {
        self.physics.get_mut()
    }
}

// ---------------------------------------------------------------------------------------
// Loading

/// The one key read before the family's schema: which family parses the file (its `model`).
pub fn model_key(file_label: &str, text: &str) -> Result<String, CaseError> {
    #[derive(Deserialize)]
    struct ModelKey {
        model: String,
    }
    let m: ModelKey = parse(file_label, text)?;
    Ok(m.model)
}

/// Parses `text` into a family's raw (serde) case, errors with key paths.
pub fn parse<T: serde::de::DeserializeOwned>(file_label: &str, text: &str) -> Result<T, CaseError> {
    toml::from_str(text).map_err(|e| keypath::toml_error(file_label, text, &e))
}

/// The case files of `dir` as `(label, text)`: every `*.toml`, sorted by file name, each read
/// as a regular file of at most `read_limited::CASE` bytes and as UTF-8 text. The family
/// table's loader (`catalogue::load_dir`) parses them.
pub fn read_dir(dir: &Path) -> Result<Vec<(PathBuf, String)>, CaseError> {
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
    let mut out = Vec::with_capacity(paths.len());
    for path in paths {
        let label = path.display().to_string();
        let bytes =
            crate::read_limited::read(&path, crate::read_limited::CASE).map_err(|e| CaseError {
                file: label.clone(),
                key: String::new(),
                message: e.why.to_string(),
            })?;
        let text = String::from_utf8(bytes).map_err(|e| CaseError {
            file: label.clone(),
            key: String::new(),
            message: format!("cannot read: not UTF-8 text: {e}"),
        })?;
        out.push((path, text));
    }
    Ok(out)
}

/// The selected cases and scenes (empty filter lists select all), in file order. A name in
/// a filter that matches nothing is an error.
pub fn select<'c>(
    cases: &'c [Case],
    case_filter: &[String],
    scene_filter: &[String],
) -> Result<Vec<(&'c Case, &'c Scene)>, String> {
    for c in case_filter {
        if !cases.iter().any(|k| &k.name == c) {
            return Err(format!(
                "--case {c}: no such case (known: {})",
                cases
                    .iter()
                    .map(|k| k.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
    }
    let mut out = vec![];
    for c in cases {
        if !case_filter.is_empty() && !case_filter.contains(&c.name) {
            continue;
        }
        for s in &c.scenes {
            if !scene_filter.is_empty() && !scene_filter.contains(&s.name) {
                continue;
            }
            out.push((c, s));
        }
    }
    for s in scene_filter {
        if !out.iter().any(|(_, sc)| &sc.name == s) {
            return Err(format!("--scene {s}: no such scene in the selected cases"));
        }
    }
    Ok(out)
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

/// Refuses a case whose `case` key differs from its file's stem.
pub fn check_stem(case: &Case, path: &Path) -> Result<(), CaseError> {
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

#[cfg(test)]
mod tests;
