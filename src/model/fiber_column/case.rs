//! The fiber column's case schema (cases/README.md, "Fiber-column keys"): `[numerics]` (the
//! Newton and element tolerances, the integration points, the element counts of
//! `force_based` and `force_based_fine`), `[column]` (height, torsional stiffness), `[section]`
//! (an elastic section `elastic = { ea, ei }`, or a fiber layout of `patches` and bar `layers`
//! inside a `depth x width` outline whose materials each scene names) and per scene its
//! `materials` (fiber sections only) and its `load`, one of four kinds:
//! `{ tip_force }` and `{ tip_moment }` (static, load factor `t` from 0 to 1), the cyclic
//! `{ axial, axial_steps, drifts, cycles, increment }` (the axial load in `axial_steps`
//! steps before `t = 0`, then the top displacement `increment` per unit of `t` through
//! `cycles` full cycles `0 -> +d -> -d -> 0` of each drift `d H`) and the dynamic
//! `{ axial, axial_steps, pulse = { mass, a0, amplitude, period, duration } }` (a lumped top
//! mass in both translations, damping `C = a0 M`, ground acceleration
//! `amplitude sin(2 pi t / period)` for `t <= duration`, along the bending plane).
//!
//! Invariants after loading: the case's `reference` is `exact` when its scenes are static
//! and `external` when they are cyclic or dynamic; every number finite, every length,
//! stiffness, strength magnitude and count positive; the materials' own checks (`material/`) name the parameter
//! they refuse; the fiber layout lies inside its outline and has fibers (`layout.rs`); a
//! cyclic scene's `t_end` is its protocol's length in increments and every drift amplitude
//! is a whole number of increments (so every ladder step that divides the score grid lands
//! on the reversals). A loaded case holds nothing that grows with its counts: the protocol
//! is kept by its amplitudes (`protocol.rs`) and the fiber layout unexpanded (a run makes
//! the fibers), so the family's memory and work estimate (`estimate.rs`) is checked before
//! anything large exists. Where it fails: nothing here checks that the chosen counts
//! converge; the case file's comments give the evidence.
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::collections::BTreeMap;

use super::layout::{Layer, Patch, SectionSpec, check_layout};
use super::material::{
    Concrete01, Concrete01Params, Concrete02, Concrete02Params, Elastic, ElasticParams, Material,
    ParamError, Steel01, Steel01Params, Steel02, Steel02Params,
};
use super::protocol::Protocol;
use super::section::ElasticSection;
use crate::case::{Case, CaseError, Ctx, ReferenceKind, Res, Scene};

crate::case_schema! {
    case RawCase / CaseOwn {
        numerics: RawNumerics,
        column: RawColumn,
        section: RawSection,
    }
    scene RawScene / SceneOwn {
        #[serde(default)]
        materials: BTreeMap<String, RawMaterial>,
        load: RawLoad,
    }
}

#[derive(Deserialize, Serialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawNumerics {
    tol: f64,
    max_iter: f64,
    element_tol: f64,
    element_max_iter: f64,
    points: f64,
    elements: f64,
    fine_elements: Option<f64>,
}

#[derive(Deserialize, Serialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawColumn {
    height: f64,
    gj: f64,
}

#[derive(Deserialize, Serialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawElasticSection {
    ea: f64,
    ei: f64,
}

#[derive(Deserialize, Serialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawPatch {
    pub(super) name: String,
    pub(super) material: String,
    #[serde(deserialize_with = "crate::case::exact::array")]
    pub(super) y: [f64; 2],
    #[serde(deserialize_with = "crate::case::exact::array")]
    pub(super) z: [f64; 2],
    pub(super) ny: f64,
    pub(super) nz: f64,
}

#[derive(Deserialize, Serialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawLayer {
    pub(super) name: String,
    pub(super) material: String,
    pub(super) y: f64,
    #[serde(deserialize_with = "crate::case::exact::array")]
    pub(super) z: [f64; 2],
    pub(super) n: f64,
    pub(super) area: f64,
}

#[derive(Deserialize, Serialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSection {
    pub(super) elastic: Option<RawElasticSection>,
    pub(super) depth: Option<f64>,
    pub(super) width: Option<f64>,
    #[serde(default)]
    pub(super) patches: Vec<RawPatch>,
    #[serde(default)]
    pub(super) layers: Vec<RawLayer>,
}

#[derive(Deserialize, Serialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMaterial {
    pub(super) elastic: Option<ElasticParams>,
    pub(super) concrete01: Option<Concrete01Params>,
    pub(super) concrete02: Option<Concrete02Params>,
    pub(super) steel01: Option<Steel01Params>,
    pub(super) steel02: Option<Steel02Params>,
}

#[derive(Deserialize, Serialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawPulse {
    pub(super) mass: f64,
    pub(super) a0: f64,
    pub(super) amplitude: f64,
    pub(super) period: f64,
    pub(super) duration: f64,
}

#[derive(Deserialize, Serialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawLoad {
    pub(super) tip_force: Option<f64>,
    pub(super) tip_moment: Option<f64>,
    pub(super) axial: Option<f64>,
    pub(super) axial_steps: Option<f64>,
    pub(super) drifts: Option<Vec<f64>>,
    pub(super) cycles: Option<f64>,
    pub(super) increment: Option<f64>,
    pub(super) pulse: Option<RawPulse>,
}

/// The numerical settings of a case.
#[derive(Debug, Clone, PartialEq)]
pub struct Numerics {
    /// Newton's energy-increment tolerance `|dx . r| / 2` (J).
    pub tol: f64,
    pub max_iter: usize,
    /// The force-based element's tolerance and iteration limit: its iterations stop when
    /// the energy of a correction `|dv . dq|` is below `element_tol` times the element's
    /// work `|v . q|` (`basic.rs`), so the tolerance is relative, not in J.
    pub element_tol: f64,
    pub element_max_iter: usize,
    /// Integration points per element (Gauss-Lobatto, force-based; Gauss-Legendre, rivals).
    pub points: usize,
    /// `force_based`'s element count.
    pub elements: usize,
    /// `force_based_fine`'s element count (None: the formulation does not apply).
    pub fine_elements: Option<usize>,
}

/// The case's column: its height, torsional stiffness and section layout (the materials
/// are the scene's).
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnCase {
    pub numerics: Numerics,
    pub height: f64,
    pub gj: f64,
    /// `Some((ea, ei))` for an elastic section.
    pub elastic: Option<(f64, f64)>,
    /// The raw layout (fiber sections), built per scene with its materials.
    pub(super) raw_section: RawSection,
    /// The case's own keys as written (the physics hash).
    inputs: Value,
}

/// How a scene loads the column.
#[derive(Debug, Clone, PartialEq)]
pub enum Loading {
    /// A dead tip force across the axis (N, along global x), times the load factor `t`.
    TipForce(f64),
    /// A tip moment about global y (N m, bending in x-z), times `t`.
    TipMoment(f64),
    /// The axial load, then the top displacement protocol.
    Cyclic {
        axial: f64,
        axial_steps: usize,
        /// The top displacement (m) at every integer `t` from 0 to `t_end`.
        protocol: Protocol,
    },
    /// The axial load, then the ground-acceleration pulse.
    Pulse {
        axial: f64,
        axial_steps: usize,
        mass: f64,
        a0: f64,
        amplitude: f64,
        period: f64,
        duration: f64,
    },
}

impl Loading {
    /// The scene's kind: `static`, `cyclic` or `dynamic`.
    pub fn kind(&self) -> &'static str {
        match self {
            Loading::TipForce(_) | Loading::TipMoment(_) => "static",
            Loading::Cyclic { .. } => "cyclic",
            Loading::Pulse { .. } => "dynamic",
        }
    }

    /// The ground acceleration (m/s^2) of a pulse at `t` (0 for other loadings).
    pub fn ground(&self, t: f64) -> f64 {
        match *self {
            Loading::Pulse {
                amplitude,
                period,
                duration,
                ..
            } if t <= duration => amplitude * (std::f64::consts::TAU * t / period).sin(),
            _ => 0.0,
        }
    }
}

/// A scene's physics: the section with its materials (its fibers are made per run) and the
/// loading.
#[derive(Debug, Clone)]
pub struct ColumnScene {
    pub section: SectionSpec,
    pub loading: Loading,
    /// The scene's materials and load as written (what an external reference's model is
    /// compared with, key by key: `opensees_model.rs`).
    pub(super) raw_materials: BTreeMap<String, RawMaterial>,
    pub(super) raw_load: RawLoad,
    inputs: Value,
}

/// Two scenes are equal when they were written alike (the section follows from the case's
/// layout and the scene's materials).
impl PartialEq for ColumnScene {
    fn eq(&self, other: &Self) -> bool {
        self.inputs == other.inputs && self.loading == other.loading
    }
}

fn count(cx: &Ctx, key: &str, x: f64) -> Res<usize> {
    Ok(cx.count(key, x)? as usize)
}

/// The most Newton iterations of a step and element iterations of a state determination a
/// case may allow (`numerics.max_iter`, `element_max_iter`; the catalogue's take 20 to 50):
/// a limit of 1e9 with a tolerance no step meets ran for hours. The run's budgets bound the
/// iterations of a whole run (`meter.rs`).
pub const MAX_ITER_CAP: u64 = 1000;

/// An iteration limit: a count up to [`MAX_ITER_CAP`].
fn iteration_limit(cx: &Ctx, key: &str, x: f64) -> Res<usize> {
    let n = cx.count(key, x)?;
    if n > MAX_ITER_CAP {
        return cx.err(
            key,
            format!(
                "{n} is above its hard cap {MAX_ITER_CAP} (cases/README.md, \"Fiber-column \
                 keys\")"
            ),
        );
    }
    Ok(n as usize)
}

fn numerics(cx: &Ctx, n: &RawNumerics) -> Res<Numerics> {
    let points = count(cx, "numerics.points", n.points)?;
    if !(3..=10).contains(&points) {
        return cx.err(
            "numerics.points",
            format!("{points}; expected 3 to 10 integration points"),
        );
    }
    Ok(Numerics {
        tol: cx.positive("numerics.tol", n.tol, "an energy in J")?,
        max_iter: iteration_limit(cx, "numerics.max_iter", n.max_iter)?,
        element_tol: cx.positive("numerics.element_tol", n.element_tol, "a relative energy")?,
        element_max_iter: iteration_limit(cx, "numerics.element_max_iter", n.element_max_iter)?,
        points,
        elements: count(cx, "numerics.elements", n.elements)?,
        fine_elements: n
            .fine_elements
            .map(|x| count(cx, "numerics.fine_elements", x))
            .transpose()?,
    })
}

fn case_physics(cx: &Ctx, own: &CaseOwn) -> Res<ColumnCase> {
    let s = &own.section;
    let elastic = match (&s.elastic, s.depth, s.width) {
        (Some(e), None, None) if s.patches.is_empty() && s.layers.is_empty() => Some((
            cx.positive("section.elastic.ea", e.ea, "an axial stiffness in N")?,
            cx.positive("section.elastic.ei", e.ei, "a bending stiffness in N m^2")?,
        )),
        (None, Some(d), Some(w)) => {
            cx.length("section.depth", d, "a depth")?;
            cx.length("section.width", w, "a width")?;
            None
        }
        _ => {
            return cx.err(
                "section",
                "expected either `elastic = { ea, ei }` alone or `depth`, `width` with \
                 `patches` and `layers`",
            );
        }
    };
    // The physics hash's part of the case: the column and its section as written. The
    // numerics are the column's own solver settings (`Family::settings`): no reference uses
    // them.
    let inputs = serde_json::json!({
        "column": own.column,
        "section": own.section,
    });
    Ok(ColumnCase {
        numerics: numerics(cx, &own.numerics)?,
        height: cx.length("column.height", own.column.height, "a height")?,
        gj: cx.positive("column.gj", own.column.gj, "a torsional stiffness in N m^2")?,
        elastic,
        raw_section: own.section.clone(),
        inputs,
    })
}

fn material(cx: &Ctx, key: &str, m: &RawMaterial) -> Res<Material> {
    let given = [
        m.elastic.is_some(),
        m.concrete01.is_some(),
        m.concrete02.is_some(),
        m.steel01.is_some(),
        m.steel02.is_some(),
    ];
    if given.iter().filter(|x| **x).count() != 1 {
        return cx.err(
            key,
            "expected exactly one of elastic, concrete01, concrete02, steel01, steel02",
        );
    }
    let named = |model: &str, r: Result<Material, ParamError>| match r {
        Ok(m) => Ok(m),
        Err(e) => cx.err(format!("{key}.{model}.{}", e.key), e.message),
    };
    if let Some(p) = m.elastic {
        named("elastic", Elastic::new(p).map(Material::from))
    } else if let Some(p) = m.concrete01 {
        named("concrete01", Concrete01::new(p).map(Material::from))
    } else if let Some(p) = m.concrete02 {
        named("concrete02", Concrete02::new(p).map(Material::from))
    } else if let Some(p) = m.steel01 {
        named("steel01", Steel01::new(p).map(Material::from))
    } else if let Some(p) = m.steel02 {
        named("steel02", Steel02::new(p).map(Material::from))
    } else {
        unreachable!("one material model is given")
    }
}

fn fiber_layout(
    cx: &Ctx,
    i: usize,
    s: &RawSection,
    materials: &BTreeMap<String, Material>,
) -> Res<SectionSpec> {
    let pick = |key: String, name: &str| -> Res<Material> {
        match materials.get(name) {
            Some(m) => Ok(*m),
            None => cx.err(
                key,
                format!(
                    "material `{name}` is not among scene[{i}].materials ({})",
                    materials.keys().cloned().collect::<Vec<_>>().join(", ")
                ),
            ),
        }
    };
    let mut patches = vec![];
    for (j, p) in s.patches.iter().enumerate() {
        let k = format!("section.patches[{j}]");
        patches.push(Patch {
            name: p.name.clone(),
            material: pick(format!("{k}.material"), &p.material)?,
            y: p.y,
            z: p.z,
            ny: count(cx, &format!("{k}.ny"), p.ny)?,
            nz: count(cx, &format!("{k}.nz"), p.nz)?,
        });
    }
    let mut layers = vec![];
    for (j, l) in s.layers.iter().enumerate() {
        let k = format!("section.layers[{j}]");
        layers.push(Layer {
            name: l.name.clone(),
            material: pick(format!("{k}.material"), &l.material)?,
            y: [l.y, l.y],
            z: l.z,
            n: count(cx, &format!("{k}.n"), l.n)?,
            area: cx.positive(&format!("{k}.area"), l.area, "a bar area in m^2")?,
        });
    }
    let (depth, width) = (s.depth.unwrap_or(0.0), s.width.unwrap_or(0.0));
    check_layout(depth, width, &patches, &layers).or_else(|e| cx.err("section", e))?;
    Ok(SectionSpec::Fiber {
        depth,
        width,
        patches,
        layers,
    })
}

/// The protocol of `cycles` full cycles `0 -> +d -> -d -> 0` of each amplitude `d = drift H`,
/// `increment` per unit of `t`, held by its amplitudes in increments (nothing is expanded).
fn protocol(
    cx: &Ctx,
    key: &str,
    drifts: &[f64],
    cycles: u64,
    increment: f64,
    h: f64,
) -> Res<Protocol> {
    if drifts.is_empty() {
        return cx.err(format!("{key}.drifts"), "empty; expected drift ratios");
    }
    let mut amplitudes = Vec::with_capacity(drifts.len());
    for (j, &d) in drifts.iter().enumerate() {
        let k = format!("{key}.drifts[{j}]");
        let d = cx.positive(&k, d, "a drift ratio")?;
        let n = d * h / increment;
        if (n - n.round()).abs() > 1e-9 * n.max(1.0) || n.round() < 1.0 {
            return cx.err(
                k,
                format!(
                    "{d} H = {} m is not a whole number of increments of {increment} m",
                    d * h
                ),
            );
        }
        if n.round() > super::protocol::MAX_INCREMENTS as f64 {
            return cx.err(
                k,
                format!(
                    "{d} H = {:e} m is {n:e} increments of {increment} m, more than a \
                     protocol can hold (2^53)",
                    d * h
                ),
            );
        }
        amplitudes.push(n.round() as u64);
    }
    Protocol::new(amplitudes, cycles, increment).or_else(|e| {
        cx.err(
            key,
            format!("drifts, cycles and increment: {e}; expected fewer or smaller cycles"),
        )
    })
}

/// The value of a key the loading's kind needs (optional in the schema, which takes every
/// kind's keys), or an error naming it as missing.
fn needed(cx: &Ctx, key: &str, x: Option<f64>, what: &str) -> Res<f64> {
    match x {
        Some(x) => Ok(x),
        None => cx.err(key, format!("missing; this loading needs {what}")),
    }
}

fn loading(cx: &Ctx, i: usize, l: &RawLoad, h: f64) -> Res<Loading> {
    let key = format!("scene[{i}].load");
    let axial = |cx: &Ctx| -> Res<(f64, usize)> {
        let k = format!("{key}.axial");
        let what = "a compressive axial load in N";
        let a = cx.positive(&k, needed(cx, &k, l.axial, what)?, what)?;
        let k = format!("{key}.axial_steps");
        let what = "the axial load's step count";
        let s = count(cx, &k, needed(cx, &k, l.axial_steps, what)?)?;
        Ok((a, s))
    };
    match (l.tip_force, l.tip_moment, &l.drifts, &l.pulse) {
        (Some(f), None, None, None) if l.axial.is_none() => Ok(Loading::TipForce(
            cx.finite(&format!("{key}.tip_force"), f)?,
        )),
        (None, Some(m), None, None) if l.axial.is_none() => Ok(Loading::TipMoment(
            cx.finite(&format!("{key}.tip_moment"), m)?,
        )),
        (None, None, Some(drifts), None) => {
            let (axial, axial_steps) = axial(cx)?;
            let (k, what) = (format!("{key}.increment"), "a displacement increment in m");
            let increment = cx.positive(&k, needed(cx, &k, l.increment, what)?, what)?;
            let k = format!("{key}.cycles");
            let cycles = cx.count(&k, needed(cx, &k, l.cycles, "a cycle count")?)?;
            Ok(Loading::Cyclic {
                axial,
                axial_steps,
                protocol: protocol(cx, &key, drifts, cycles, increment, h)?,
            })
        }
        (None, None, None, Some(p)) => {
            let (axial, axial_steps) = axial(cx)?;
            let k = format!("{key}.pulse");
            Ok(Loading::Pulse {
                axial,
                axial_steps,
                mass: cx.positive(&format!("{k}.mass"), p.mass, "a mass in kg")?,
                a0: {
                    let a0 = cx.finite(&format!("{k}.a0"), p.a0)?;
                    if a0 < 0.0 {
                        return cx.err(format!("{k}.a0"), format!("{a0}; expected a0 >= 0 (1/s)"));
                    }
                    a0
                },
                amplitude: cx.finite(&format!("{k}.amplitude"), p.amplitude)?,
                period: cx.positive(&format!("{k}.period"), p.period, "a period in s")?,
                duration: cx.positive(&format!("{k}.duration"), p.duration, "a time in s")?,
            })
        }
        _ => cx.err(
            key,
            "expected exactly one loading: { tip_force }, { tip_moment }, { axial, \
             axial_steps, drifts, cycles, increment } or { axial, axial_steps, pulse }",
        ),
    }
}

fn scene_physics(
    cx: &Ctx,
    (i, grid_t_end, reference): (usize, f64, &str),
    s: &SceneOwn,
    c: &ColumnCase,
) -> Res<ColumnScene> {
    let loading = loading(cx, i, &s.load, c.height)?;
    // A static scene is scored against the exact elastica, a cyclic or pulse scene against
    // OpenSees' run: the case's `reference` must say which.
    let wanted = match loading.kind() {
        "static" => ReferenceKind::EXACT,
        _ => ReferenceKind::EXTERNAL,
    };
    if reference != wanted.name() {
        return cx.err(
            "reference",
            format!(
                "`{}`, but scene[{i}] is {} ({} loading), whose reference is `{}`",
                reference,
                loading.kind(),
                loading.kind(),
                wanted.name()
            ),
        );
    }
    let section = match c.elastic {
        Some((ea, ei)) => {
            if !s.materials.is_empty() {
                return cx.err(
                    format!("scene[{i}].materials"),
                    "an elastic section takes no materials",
                );
            }
            SectionSpec::Elastic(
                ElasticSection::new(ea, ei, ei).or_else(|e| cx.err("section", e))?,
            )
        }
        None => {
            let mut materials = BTreeMap::new();
            for (name, m) in &s.materials {
                let k = format!("scene[{i}].materials.{name}");
                materials.insert(name.clone(), material(cx, &k, m)?);
            }
            fiber_layout(cx, i, &c.raw_section, &materials)?
        }
    };
    if let Loading::Cyclic { protocol, .. } = &loading {
        let n = protocol.len() as f64;
        if grid_t_end != n {
            return cx.err(
                format!("scene[{i}].t_end"),
                format!(
                    "{grid_t_end}; the protocol of scene[{i}].load (drifts, cycles, increment) \
                     has {n} increments, so t_end = {n}"
                ),
            );
        }
    }
    let inputs = serde_json::json!({ "materials": s.materials, "load": s.load });
    Ok(ColumnScene {
        section,
        loading,
        raw_materials: s.materials.clone(),
        raw_load: s.load.clone(),
        inputs,
    })
}

/// Loads a fiber-column case file (the family's `load`).
pub fn load(file: &str, text: &str) -> Result<Case, CaseError> {
    let raw: RawCase = crate::case::parse(file, text)?;
    let (shared, own, scenes) = raw.split();
    let t_ends: Vec<f64> = scenes.iter().map(|(g, _)| g.t_end).collect();
    let reference = shared.reference.clone();
    Ctx { file }.assemble(
        &super::family::FAMILY,
        shared,
        |cx| case_physics(cx, &own),
        scenes,
        |cx, i, s: &SceneOwn, c: &ColumnCase| {
            scene_physics(cx, (i, t_ends[i], &reference), s, c)
        },
    )
}

/// The column's physics of a scene in the physics hash: the column and its section (the
/// case's keys) and the scene's materials and load, as written. Not the numerics: they are
/// settings (`Family::settings`), in every record's `settings_sha256`.
pub fn inputs(case: &Case, scene: &Scene) -> serde_json::Map<String, Value> {
    let mut m = serde_json::Map::new();
    let (Some(c), Some(s)) = (case.physics::<ColumnCase>(), scene.physics::<ColumnScene>())
    else {
        return m;
    };
    for part in [&c.inputs, &s.inputs] {
        if let Value::Object(o) = part {
            m.extend(o.iter().map(|(k, v)| (k.clone(), v.clone())));
        }
    }
    m
}
