//! An OpenSees record's `model` and `settings` against its case, field by field: a reference
//! is only a reference for the column it was run on, so every field of the record either
//! maps to the case quantity it stands for, or is a convention mbdbench's column shares
//! (compared with that convention), or is said here to have no counterpart and why. A field
//! this module does not know is refused (a regenerated record with a new input must be mapped
//! before it is used). The first difference is refused, naming the record's key and the
//! case's, with both values.
//!
//! The record is 2-D (OpenSees `ndm 2`, one fiber across the width), the column 3-D, so the
//! section maps through its projection on the bending direction: fibers at one depth act as
//! one fiber of their summed area under in-plane loads.
//!
//! | record (`model.`, `settings.`) | case |
//! |---|---|
//! | `H`, `nodes.top[1]` | `column.height` (`nodes.base` = `[0, 0]`, `nodes.top[0]` = 0) |
//! | `element.count`, `element.sections` | `numerics.elements`, `numerics.points` |
//! | `element.type`, `.integration`, `.geom_transf` | conventions: forceBeamColumn, Lobatto, Corotational (`force_based`) |
//! | `section.depth`, `section.width` | `section.depth`, `section.width` |
//! | `section.patches[j].mat`, `.y`, `.z`, `.n_depth` | `section.patches[j].material`, `.y`, `.z`, `.ny` |
//! | `section.bars.area`, `.mat` | every `section.layers[j].area`, `.material` |
//! | `section.bars.rows[j].y`, `.count` | `section.layers[j].y`, `.n` |
//! | `materials.NAME.type`, `.args[k]` | `scene[i].materials.NAME`'s model and its parameters in OpenSees' order |
//! | `P`, `axial_steps`, `settings.axial_steps` | `scene[i].load.axial`, `.axial_steps` |
//! | `protocol.drifts_percent[j]`, `.amplitudes_m[j]` | `load.drifts[j]` x 100, `load.drifts[j]` x `column.height` |
//! | `protocol.cycles_per_amplitude`, `settings.increment`, `protocol.steps` | `load.cycles`, `load.increment`, `scene[i].t_end` |
//! | `mass`, `damping.a0` | `load.pulse.mass`, `load.pulse.a0` |
//! | `ground_motion.amplitude`, `.period`, `.duration` | `load.pulse.amplitude`, `.period`, `.duration` (`.start` = 0) |
//! | `t_end` | at least `scene[i].t_end` |
//! | `settings.tol` | at most `numerics.tol` (below) |
//! | `settings.element_tol` | at most `numerics.element_tol` x the first axial step's element work (below) |
//!
//! Conventions compared as text: `section.type` (local y the depth, in the bending plane),
//! `section.bars.displace_concrete` (false: bars do not displace concrete, `layout.rs`),
//! `P_direction`, `protocol.control`, `protocol.cycle`, `mass_dofs`,
//! `ground_motion.direction`, `damping.type`, `settings.test`, `settings.integrator`
//! (cyclic), `settings.element_tol_measures`; `ground_motion.trig_series_max_abs_error` must
//! be 0 (to 1e-12 of the amplitude: OpenSees' excitation is the closed form). No counterpart:
//! `section.cover` (the generator's construction parameter, whose effect, the patches'
//! coordinates, is compared), `patches[j].n_width` and the layers' `z` and the patches'
//! `nz` (out of the bending plane), `materials.NAME.tag` (OpenSees' numbering), `g0` (its
//! products, mass and amplitude, are compared), the descriptions `ground_motion.a_g`,
//! `.opensees`, `protocol.lateral_reference_load`, `settings.t_definition`, the damping's
//! derivation and diagnostics (`zeta`, `omega1`, ...), the solver's choices (algorithm,
//! iteration limits, linear system: records agree across algorithms to 1e-11 of the peaks,
//! and a limit does not loosen a converged step), and the pulse's time discretization
//! (`integrator`, `gamma`, `beta`, `dt`, `record_dt`: its error is the accuracy claim; every
//! score time must be a row, `opensees.rs`). The case's `column.gj` (torsion, unloaded in
//! plane), `numerics.max_iter`, `element_max_iter` and `fine_elements` have no counterpart.
//!
//! **Tolerances.** The case's `numerics.tol` and `element_tol` are the settings of our solver,
//! the record's `tol` and `element_tol` OpenSees'. A reference solved more loosely than the
//! case asks of our solver is refused; a tighter one is fine. The global tolerances are the
//! same measure: OpenSees' `EnergyIncr` test (`CTestEnergyIncr::test`) accepts a step when
//! `|dx . b| / 2 <= tol`, ours (`column.rs`) when `|dx . r| / 2 <= tol`, both half the product
//! of a Newton correction and the residual it solves, in J, so `settings.tol <=
//! numerics.tol` is required. The element tolerances are not the same measure: OpenSees'
//! `forceBeamColumn` (`settings.element_tol_measures`) stops when `|dv . (kv dv)| < tol`, an
//! absolute energy in N m, ours (`basic.rs`) when the same product is below `element_tol`
//! times the element's work scale `|v . q|`, a relative one. So the case's tolerance is taken
//! to an energy at the smallest work scale our element meets, the first axial load step's
//! `W1 = (P/n)^2 (H/elements) / EA0` (`EA0` the section's initial axial stiffness), and
//! `settings.element_tol <= numerics.element_tol W1` is required (catalogue: 1e-20 J against
//! 1e-16 x 2.6 J). Where it fails: a later state whose work `|v . q|` passes near zero asks
//! our element for an absolute accuracy below that bound, which this check does not see.
use serde_json::{Map, Value};
use std::collections::BTreeSet;

use super::case::{ColumnCase, ColumnScene, Loading, RawLoad, RawMaterial};

type Res = Result<(), String>;

/// How OpenSees' element tolerance is measured, as the records state it.
const ELEMENT_TOL_MEASURE: &str = "ForceBeamColumn2d state determination: |dv . (kv dv)| of \
     the basic-deformation residual dv = v_target - integral(b^T vs) (energy, N m) must fall \
     below element_tol";

/// Refuses unless the record's `r` (at `rkey`) is the case's `c` (at `ckey`) to 1e-12
/// relative (the records hold round-trip doubles; a value the case derives, a drift in
/// percent, may differ in its last bit).
fn same(rkey: &str, r: f64, ckey: &str, c: f64) -> Res {
    if (r - c).abs() <= 1e-12 * r.abs().max(c.abs()) {
        Ok(())
    } else {
        Err(format!(
            "stale: key `{rkey}` is {r}, the case's `{ckey}` is {c}"
        ))
    }
}

fn same_text(rkey: &str, r: &str, ckey: &str, c: &str) -> Res {
    if r == c {
        Ok(())
    } else {
        Err(format!(
            "stale: key `{rkey}` is `{r}`, the case's `{ckey}` is `{c}`"
        ))
    }
}

fn differ_in_count(rkey: &str, r: usize, ckey: &str, c: usize) -> String {
    format!("stale: key `{rkey}` has {r} entries, the case's `{ckey}` {c}")
}

/// A JSON object of the record being read: the keys read are remembered, so that
/// [`Obj::done`] refuses one that nothing read.
struct Obj<'a> {
    path: String,
    map: &'a Map<String, Value>,
    read: BTreeSet<String>,
}

impl<'a> Obj<'a> {
    fn new(path: String, v: &'a Value) -> Result<Self, String> {
        match v.as_object() {
            Some(map) => Ok(Obj {
                path,
                map,
                read: BTreeSet::new(),
            }),
            None => Err(format!("key `{path}` is not an object")),
        }
    }

    fn key(&self, k: &str) -> String {
        format!("{}.{k}", self.path)
    }

    fn get(&mut self, k: &str) -> Result<&'a Value, String> {
        self.read.insert(k.to_string());
        self.map
            .get(k)
            .ok_or_else(|| format!("key `{}` is missing", self.key(k)))
    }

    fn num(&mut self, k: &str) -> Result<f64, String> {
        let v = self.get(k)?;
        v.as_f64()
            .filter(|x| x.is_finite())
            .ok_or_else(|| format!("key `{}` is {v}, not a number", self.key(k)))
    }

    fn text(&mut self, k: &str) -> Result<&'a str, String> {
        let v = self.get(k)?;
        v.as_str()
            .ok_or_else(|| format!("key `{}` is {v}, not a string", self.key(k)))
    }

    fn nums(&mut self, k: &str) -> Result<Vec<f64>, String> {
        let v = self.get(k)?;
        let bad = || format!("key `{}` is {v}, not a list of numbers", self.key(k));
        let list = v.as_array().ok_or_else(bad)?;
        list.iter()
            .map(|x| x.as_f64().filter(|x| x.is_finite()).ok_or_else(bad))
            .collect()
    }

    fn obj(&mut self, k: &str) -> Result<Obj<'a>, String> {
        let v = self.get(k)?;
        Obj::new(self.key(k), v)
    }

    fn objs(&mut self, k: &str) -> Result<Vec<Obj<'a>>, String> {
        let v = self.get(k)?;
        let list = v
            .as_array()
            .ok_or_else(|| format!("key `{}` is {v}, not a list", self.key(k)))?;
        let key = self.key(k);
        list.iter()
            .enumerate()
            .map(|(j, x)| Obj::new(format!("{key}[{j}]"), x))
            .collect()
    }

    /// Marks as read keys the comparison leaves out on purpose (each call says why).
    fn skip(&mut self, keys: &[&str]) {
        self.read.extend(keys.iter().map(|k| k.to_string()));
    }

    /// `k`, a number, equals the case's `c` at `ckey`.
    fn same(&mut self, k: &str, ckey: &str, c: f64) -> Res {
        let r = self.num(k)?;
        same(&self.key(k), r, ckey, c)
    }

    fn same_text(&mut self, k: &str, ckey: &str, c: &str) -> Res {
        let r = self.text(k)?;
        same_text(&self.key(k), r, ckey, c)
    }

    /// `k` states the convention `ours`, which mbdbench's column follows.
    fn convention(&mut self, k: &str, ours: &str) -> Res {
        let r = self.text(k)?;
        if r == ours {
            Ok(())
        } else {
            Err(format!(
                "key `{}` is `{r}`; mbdbench's column follows `{ours}`",
                self.key(k)
            ))
        }
    }

    /// Refuses the first key nothing read.
    fn done(self) -> Res {
        match self.map.keys().find(|k| !self.read.contains(*k)) {
            None => Ok(()),
            Some(k) => Err(format!(
                "key `{}.{k}` has no counterpart in the case (mbdbench cannot tell whether \
                 the run matches it)",
                self.path
            )),
        }
    }
}

/// Compares the record's `model` and `settings` with scene `i` of the case, whose horizon is
/// `t_end` (module docs): `Err` names the first difference.
pub fn check(
    c: &ColumnCase,
    s: &ColumnScene,
    i: usize,
    t_end: f64,
    model: &Value,
    settings: &Value,
) -> Res {
    let mut m = Obj::new("model".into(), model)?;
    let mut st = Obj::new("settings".into(), settings)?;
    geometry(&mut m, c)?;
    section(&mut m, c)?;
    materials(&mut m, s, i)?;
    loading(&mut m, &mut st, c, s, (i, t_end))?;
    tolerances(&mut st, c, s)?;
    m.done()?;
    st.done()
}

fn geometry(m: &mut Obj, c: &ColumnCase) -> Res {
    let h = c.height;
    m.same("H", "column.height", h)?;
    let mut nodes = m.obj("nodes")?;
    let base = nodes.nums("base")?;
    if base != [0.0, 0.0] {
        return Err(format!(
            "key `model.nodes.base` is {base:?}; mbdbench's column stands on the origin"
        ));
    }
    let top = nodes.nums("top")?;
    if top.len() != 2 || top[0] != 0.0 {
        return Err(format!(
            "key `model.nodes.top` is {top:?}; mbdbench's column is vertical, its top at \
             [0, column.height]"
        ));
    }
    same("model.nodes.top[1]", top[1], "column.height", h)?;
    nodes.done()?;
    // The record is the force-based element our `force_based` formulation is.
    let mut e = m.obj("element")?;
    e.convention("type", "forceBeamColumn")?;
    e.same("count", "numerics.elements", c.numerics.elements as f64)?;
    e.convention("integration", "Lobatto")?;
    e.same("sections", "numerics.points", c.numerics.points as f64)?;
    e.convention("geom_transf", "Corotational")?;
    e.done()
}

fn section(m: &mut Obj, c: &ColumnCase) -> Res {
    let s = &c.raw_section;
    let mut sec = m.obj("section")?;
    let (Some(depth), Some(width)) = (s.depth, s.width) else {
        return Err("stale: key `model.section` is a fiber section, the case's `section` is \
                    elastic (`section.elastic`)"
            .into());
    };
    sec.convention("type", "Fiber (2-D; local y = depth along global X)")?;
    sec.same("width", "section.width", width)?;
    sec.same("depth", "section.depth", depth)?;
    sec.skip(&["cover"]);
    let patches = sec.objs("patches")?;
    if patches.len() != s.patches.len() {
        let (r, c) = (patches.len(), s.patches.len());
        return Err(differ_in_count("model.section.patches", r, "section.patches", c));
    }
    for (j, (mut p, cp)) in patches.into_iter().zip(&s.patches).enumerate() {
        let ck = format!("section.patches[{j}]");
        p.same_text("mat", &format!("{ck}.material"), &cp.material)?;
        for (k, r, ours) in [("y", "y", cp.y), ("z", "z", cp.z)] {
            let got = p.nums(k)?;
            if got.len() != 2 {
                return Err(format!("key `{}` is {got:?}, not a range", p.key(k)));
            }
            for (e, (g, o)) in got.iter().zip(ours).enumerate() {
                same(&format!("{}[{e}]", p.key(k)), *g, &format!("{ck}.{r}[{e}]"), o)?;
            }
        }
        p.same("n_depth", &format!("{ck}.ny"), cp.ny)?;
        p.skip(&["n_width"]);
        p.done()?;
    }
    let mut bars = sec.obj("bars")?;
    let (area, mat) = (bars.num("area")?, bars.text("mat")?);
    let displaced = bars.get("displace_concrete")?;
    if displaced != &Value::Bool(false) {
        return Err(format!(
            "key `model.section.bars.displace_concrete` is {displaced}; mbdbench's layouts \
             do not displace the concrete under the bars"
        ));
    }
    let rows = bars.objs("rows")?;
    if rows.len() != s.layers.len() {
        let (r, c) = (rows.len(), s.layers.len());
        return Err(differ_in_count("model.section.bars.rows", r, "section.layers", c));
    }
    for (j, (mut r, l)) in rows.into_iter().zip(&s.layers).enumerate() {
        let ck = format!("section.layers[{j}]");
        same("model.section.bars.area", area, &format!("{ck}.area"), l.area)?;
        same_text("model.section.bars.mat", mat, &format!("{ck}.material"), &l.material)?;
        r.same("y", &format!("{ck}.y"), l.y)?;
        r.same("count", &format!("{ck}.n"), l.n)?;
        r.done()?;
    }
    bars.done()?;
    sec.done()
}

/// A scene material's model key in the case, its OpenSees type and its parameters in
/// OpenSees' argument order, each with its case key.
type Args = (&'static str, &'static str, Vec<(&'static str, f64)>);

fn opensees_args(m: &RawMaterial) -> Option<Args> {
    if let Some(p) = m.elastic {
        return Some(("elastic", "Elastic", vec![("e", p.e)]));
    }
    if let Some(p) = m.concrete01 {
        let v = vec![
            ("fpc", p.fpc),
            ("epsc0", p.epsc0),
            ("fpcu", p.fpcu),
            ("epscu", p.epscu),
        ];
        return Some(("concrete01", "Concrete01", v));
    }
    if let Some(p) = m.concrete02 {
        let v = vec![
            ("fpc", p.fpc),
            ("epsc0", p.epsc0),
            ("fpcu", p.fpcu),
            ("epscu", p.epscu),
            ("lambda", p.lambda),
            ("ft", p.ft),
            ("ets", p.ets),
        ];
        return Some(("concrete02", "Concrete02", v));
    }
    if let Some(p) = m.steel01 {
        return Some(("steel01", "Steel01", vec![("fy", p.fy), ("e0", p.e0), ("b", p.b)]));
    }
    let p = m.steel02?;
    let v = vec![
        ("fy", p.fy),
        ("e0", p.e0),
        ("b", p.b),
        ("r0", p.r0),
        ("c_r1", p.c_r1),
        ("c_r2", p.c_r2),
    ];
    Some(("steel02", "Steel02", v))
}

fn materials(m: &mut Obj, s: &ColumnScene, i: usize) -> Res {
    let mut mats = m.obj("materials")?;
    for (name, raw) in &s.raw_materials {
        let ck = format!("scene[{i}].materials.{name}");
        if !mats.map.contains_key(name) {
            return Err(format!(
                "stale: the case's `{ck}` has no counterpart `model.materials.{name}`"
            ));
        }
        let mut rm = mats.obj(name)?;
        let (model, kind, params) = opensees_args(raw).ok_or(format!("{ck}: no model"))?;
        rm.same_text("type", &ck, kind)?;
        let args = rm.nums("args")?;
        if args.len() != params.len() {
            let (r, c) = (args.len(), params.len());
            return Err(differ_in_count(&rm.key("args"), r, &format!("{ck}.{model}"), c));
        }
        for (k, (a, (pk, pv))) in args.iter().zip(&params).enumerate() {
            let rk = format!("{}[{k}]", rm.key("args"));
            same(&rk, *a, &format!("{ck}.{model}.{pk}"), *pv)?;
        }
        rm.skip(&["tag"]);
        rm.done()?;
    }
    mats.done()
}

fn loading(
    m: &mut Obj,
    st: &mut Obj,
    c: &ColumnCase,
    s: &ColumnScene,
    (i, t_end): (usize, f64),
) -> Res {
    let lk = format!("scene[{i}].load");
    let (axial, axial_steps) = match s.loading {
        Loading::Cyclic {
            axial, axial_steps, ..
        }
        | Loading::Pulse {
            axial, axial_steps, ..
        } => (axial, axial_steps as f64),
        _ => {
            return Err(format!(
                "the case's `{lk}` is static; an OpenSees record is a cyclic or pulse run"
            ));
        }
    };
    m.same("P", &format!("{lk}.axial"), axial)?;
    m.convention("P_direction", "-Y at the top node")?;
    m.same("axial_steps", &format!("{lk}.axial_steps"), axial_steps)?;
    st.same("axial_steps", &format!("{lk}.axial_steps"), axial_steps)?;
    match s.loading {
        Loading::Cyclic { ref protocol, .. } => {
            let steps = protocol.len() as f64;
            let increment = protocol.increment();
            cyclic(m, st, (c.height, &s.raw_load, &lk), (i, steps, increment))
        }
        _ => pulse(m, st, s, &lk, (i, t_end)),
    }
}

fn cyclic(
    m: &mut Obj,
    st: &mut Obj,
    (h, load, lk): (f64, &RawLoad, &str),
    (i, steps, increment): (usize, f64, f64),
) -> Res {
    let mut p = m.obj("protocol")?;
    // The top's displacement is prescribed, as our newton_disp integrators prescribe it.
    p.convention("control", "DisplacementControl of node 2, dof 1 (X)")?;
    let drifts = load.drifts.as_deref().unwrap_or_default();
    let (pct, amps) = (p.nums("drifts_percent")?, p.nums("amplitudes_m")?);
    for (k, n) in [("drifts_percent", pct.len()), ("amplitudes_m", amps.len())] {
        if n != drifts.len() {
            let c = drifts.len();
            return Err(differ_in_count(&p.key(k), n, &format!("{lk}.drifts"), c));
        }
    }
    for (j, d) in drifts.iter().enumerate() {
        let ck = format!("{lk}.drifts[{j}]");
        let rk = p.key("drifts_percent");
        same(&format!("{rk}[{j}]"), pct[j], &format!("{ck} x 100"), d * 100.0)?;
        let rk = p.key("amplitudes_m");
        same(&format!("{rk}[{j}]"), amps[j], &format!("{ck} x column.height"), d * h)?;
    }
    let cycles = load.cycles.ok_or(format!("{lk}.cycles is missing"))?;
    p.same("cycles_per_amplitude", &format!("{lk}.cycles"), cycles)?;
    p.convention("cycle", "0 -> +A -> -A -> 0")?;
    st.convention("integrator", "DisplacementControl")?;
    st.same("increment", &format!("{lk}.increment"), increment)?;
    p.same("steps", &format!("scene[{i}].t_end"), steps)?;
    // OpenSees' displacement control scales a 1 N reference load, whose factor the record
    // does not use; `t` counts increments in both (the record says so in words).
    p.skip(&["lateral_reference_load"]);
    st.skip(&["t_definition"]);
    p.done()
}

fn pulse(m: &mut Obj, st: &mut Obj, s: &ColumnScene, lk: &str, (i, t_end): (usize, f64)) -> Res {
    let Loading::Pulse {
        mass,
        a0,
        amplitude,
        period,
        duration,
        ..
    } = s.loading
    else {
        return Err(format!("the case's `{lk}` is not a pulse"));
    };
    let pk = format!("{lk}.pulse");
    m.same("mass", &format!("{pk}.mass"), mass)?;
    m.convention("mass_dofs", "X and Y of the top node; rotation massless")?;
    m.skip(&["g0"]);
    let mut g = m.obj("ground_motion")?;
    g.same("amplitude", &format!("{pk}.amplitude"), amplitude)?;
    g.same("period", &format!("{pk}.period"), period)?;
    let start = g.num("start")?;
    if start != 0.0 {
        return Err(format!(
            "key `model.ground_motion.start` is {start}; the case's pulse starts at t = 0"
        ));
    }
    g.same("duration", &format!("{pk}.duration"), duration)?;
    g.convention("direction", "X")?;
    g.skip(&["a_g", "opensees"]);
    let err = g.num("trig_series_max_abs_error")?;
    if err > 1e-12 * amplitude.abs() {
        return Err(format!(
            "key `model.ground_motion.trig_series_max_abs_error` is {err:e}: OpenSees' \
             excitation is not the closed form of the case's pulse"
        ));
    }
    g.done()?;
    let mut d = m.obj("damping")?;
    d.convention("type", "Rayleigh, mass proportional")?;
    d.same("a0", &format!("{pk}.a0"), a0)?;
    d.skip(&[
        "zeta",
        "omega1",
        "omega1_method",
        "omega1_recomputed",
        "omega2_condensed",
        "omega1_eigen_fullGenLapack",
        "tangent_after_prelude",
        "condensed_tangent",
    ]);
    d.done()?;
    let end = m.num("t_end")?;
    if end < t_end * (1.0 - 1e-12) {
        return Err(format!(
            "stale: key `model.t_end` is {end}, the case's `scene[{i}].t_end` is {t_end}: \
             the run ends before the scene"
        ));
    }
    st.skip(&["integrator", "gamma", "beta", "dt", "record_dt"]);
    Ok(())
}

/// `W1 = (P/n)^2 (H/elements) / EA0`: an element's work `|v . q|` after the first of the
/// `n` axial load steps (module docs).
fn first_step_work(c: &ColumnCase, s: &ColumnScene) -> Result<f64, String> {
    let (axial, steps) = match s.loading {
        Loading::Cyclic {
            axial, axial_steps, ..
        }
        | Loading::Pulse {
            axial, axial_steps, ..
        } => (axial, axial_steps as f64),
        _ => (0.0, 1.0),
    };
    // The section's fibers, made here as a run makes them (the case was checked against its
    // memory budget when it loaded).
    let ea0 = s.section.build()?.initial_tangent()[(0, 0)];
    let p = axial / steps;
    Ok(p * p * (c.height / c.numerics.elements as f64) / ea0)
}

fn tolerances(st: &mut Obj, c: &ColumnCase, s: &ColumnScene) -> Res {
    let n = &c.numerics;
    st.convention("test", "EnergyIncr")?;
    let tol = st.num("tol")?;
    if tol > n.tol {
        return Err(format!(
            "stale: key `settings.tol` is {tol:e} J, looser than the case's `numerics.tol` \
             {:e} J (both bound |dx . r| / 2 of a Newton correction and its residual): the \
             reference was solved less tightly than the case asks",
            n.tol
        ));
    }
    st.convention("element_tol_measures", ELEMENT_TOL_MEASURE)?;
    let etol = st.num("element_tol")?;
    let w1 = first_step_work(c, s)?;
    if etol > n.element_tol * w1 {
        return Err(format!(
            "stale: key `settings.element_tol` is {etol:e} J (absolute), looser than the \
             case's `numerics.element_tol` {:e} (relative to the element's work) at the first \
             axial step's work {w1:.3e} J, {:.3e} J: the reference was solved less tightly \
             than the case asks",
            n.element_tol,
            n.element_tol * w1
        ));
    }
    st.skip(&[
        "algorithm",
        "algorithm_args",
        "algorithm_note",
        "fallback",
        "step_cutting",
        "max_iter",
        "system",
        "numberer",
        "constraints",
        "element_iter",
        "element_subdivide",
    ]);
    Ok(())
}
