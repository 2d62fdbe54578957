//! The flexible beam's case schema (cases/README.md, "Flexible-beam keys"): `[numerics]` (the
//! numerical settings every scene shares: `fe_exact`'s element count, the reference's, the
//! modal models' mode counts, the divergence bound) and per scene the `beam` (`length`, `ea`,
//! `ei`, `rho_a`), exactly one base (`spin_up = { w, t_up }`, prescribed; or
//! `hub = { inertia, torque, t_off }`, free), its `breakpoints` (times where the motion is
//! not smooth: the spin-up's end, the torque's end) and an optional `energy_scale` (J; the
//! case's by default), which the energy balance divides by since the beam starts at rest.
//!
//! Invariants after loading: every number is finite and every physical one positive; counts
//! are integers of at least 1 (the modal counts at most [`MAX_MODES`]); the base's own
//! breakpoint is listed when it falls before `t_end`; each breakpoint lies in `(0, t_end)`
//! and is divided by `sample_every`, `score_every` and every fixed step of the scene's
//! ladders (`check_breakpoints`, after the ladders are resolved), so every fixed-step run
//! lands on it and every sample grid holds it. Where it fails: nothing here checks that the
//! chosen counts converge; the case file's comments and the note give the evidence.
use serde::Deserialize;
use serde_json::Value;

use super::base::Base;
use super::fe::Beam;
use crate::case::hash::num;
use crate::case::{Case, CaseError, Ctx, Res, Scene, steps_dividing};

/// The largest mode count of a modal model (its state is a fixed-size vector per
/// registered size; `family.rs`).
pub const MAX_MODES: u64 = 8;

crate::case_schema! {
    case RawCase / CaseOwn {
        numerics: RawNumerics,
    }
    scene RawScene / SceneOwn {
        beam: RawBeam,
        spin_up: Option<RawSpinUp>,
        hub: Option<RawHub>,
        #[serde(default)]
        breakpoints: Vec<f64>,
        energy_scale: Option<f64>,
        reference_dt: Option<f64>,
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawNumerics {
    elements: f64,
    reference_elements: f64,
    reference_dt: f64,
    bending_modes: f64,
    axial_modes: f64,
    cb_bending_modes: f64,
    cb_axial_modes: f64,
    baumgarte: RawBaumgarte,
    baumgarte_soft: RawBaumgarte,
    baumgarte_stiff: RawBaumgarte,
    divergence_bound: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawBaumgarte {
    alpha: f64,
    beta: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawBeam {
    length: f64,
    ea: f64,
    ei: f64,
    rho_a: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSpinUp {
    w: f64,
    t_up: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawHub {
    inertia: f64,
    torque: f64,
    t_off: f64,
}

/// The numerical settings of a case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Numerics {
    /// `fe_exact`'s element count.
    pub elements: usize,
    /// The reference's element count.
    pub reference_elements: usize,
    /// The reference's Newmark step (s); it must divide every scene's score grid.
    pub reference_dt: f64,
    /// Clamped-free bending modes of `modal_linear` and `modal_stiffened`.
    pub bending_modes: usize,
    /// Clamped-free rod modes of `modal_stiffened`.
    pub axial_modes: usize,
    /// Clamped-clamped beam modes of the AIGC lateral set (plus four static modes).
    pub cb_bending_modes: usize,
    /// Clamped-clamped rod modes of the AIGC stretch set (plus two static modes).
    pub cb_axial_modes: usize,
    /// Baumgarte's `(alpha, beta)` (1/s) of `aigc_baumgarte`, `_soft` and `_stiff`.
    pub baumgarte: [(f64, f64); 3],
    /// A run ends as `diverged` when `|v_tip| > divergence_bound L`.
    pub divergence_bound: f64,
}

/// A scene's physics.
#[derive(Debug, Clone, PartialEq)]
pub struct BeamScene {
    pub beam: Beam,
    pub base: Base,
    pub breakpoints: Vec<f64>,
    /// The energy balance's scale (J).
    pub energy_scale: f64,
    /// The scene's own reference step (s), else the case's `numerics.reference_dt`.
    pub reference_dt: Option<f64>,
}

fn count(cx: &Ctx, key: &str, x: f64, max: Option<u64>) -> Res<usize> {
    let n = cx.count(key, x)?;
    match max {
        Some(m) if n > m => cx.err(key, format!("{n}; at most {m} are registered")),
        _ => Ok(n as usize),
    }
}

/// Baumgarte's constraint dynamics `g'' + 2 alpha g' + beta^2 g = 0` are asymptotically
/// stable only for `alpha > 0` and `beta > 0` (both roots then have negative real parts).
fn baumgarte(cx: &Ctx, key: &str, b: &RawBaumgarte) -> Res<(f64, f64)> {
    let what = "a rate in 1/s: the constraint dynamics g'' + 2 alpha g' + beta^2 g = 0 are \
                stable only for alpha > 0 and beta > 0";
    Ok((
        cx.positive(&format!("{key}.alpha"), b.alpha, what)?,
        cx.positive(&format!("{key}.beta"), b.beta, what)?,
    ))
}

/// Loads a flexible-beam case file (the family's `load`).
pub fn load(file: &str, text: &str) -> Result<Case, CaseError> {
    let raw: RawCase = crate::case::parse(file, text)?;
    let (shared, own, scenes) = raw.split();
    let case_scale = shared.energy_scale;
    if shared
        .stability
        .as_ref()
        .is_some_and(|st| st.rotation_error_max().is_some())
    {
        return Ctx { file }.err(
            "stability.rotation_error_max",
            "the beam has no rotation error; its step search judges boundedness only (remove the key)",
        );
    }
    let case = Ctx { file }.assemble(
        &super::family::FAMILY,
        shared,
        |cx| {
            let n = &own.numerics;
            Ok(Numerics {
                // The element counts are bounded by the family's estimate (`estimate.rs`):
                // the dense matrices of 10,000 elements would hold 21 GB.
                elements: count(cx, "numerics.elements", n.elements, None)?,
                reference_elements: count(
                    cx,
                    "numerics.reference_elements",
                    n.reference_elements,
                    None,
                )?,
                reference_dt: cx.positive(
                    "numerics.reference_dt",
                    n.reference_dt,
                    "a time step in s",
                )?,
                bending_modes: count(
                    cx,
                    "numerics.bending_modes",
                    n.bending_modes,
                    Some(MAX_MODES),
                )?,
                axial_modes: count(cx, "numerics.axial_modes", n.axial_modes, Some(MAX_MODES))?,
                cb_bending_modes: count(
                    cx,
                    "numerics.cb_bending_modes",
                    n.cb_bending_modes,
                    Some(MAX_MODES),
                )?,
                cb_axial_modes: count(
                    cx,
                    "numerics.cb_axial_modes",
                    n.cb_axial_modes,
                    Some(MAX_MODES),
                )?,
                baumgarte: [
                    baumgarte(cx, "numerics.baumgarte", &n.baumgarte)?,
                    baumgarte(cx, "numerics.baumgarte_soft", &n.baumgarte_soft)?,
                    baumgarte(cx, "numerics.baumgarte_stiff", &n.baumgarte_stiff)?,
                ],
                divergence_bound: cx.positive(
                    "numerics.divergence_bound",
                    n.divergence_bound,
                    "a multiple of the beam's length",
                )?,
            })
        },
        scenes,
        |cx, i, s: &SceneOwn, _c: &Numerics| scene(cx, i, s, case_scale),
    )?;
    check_breakpoints(&case)?;
    if let Some(n) = case.physics::<Numerics>() {
        super::formulations::check_sizes(n).map_err(|(key, message)| CaseError {
            file: file.to_string(),
            key: format!("numerics.{key}"),
            message,
        })?;
    }
    Ok(case)
}

fn scene(cx: &Ctx, i: usize, s: &SceneOwn, case_scale: f64) -> Res<BeamScene> {
    let k = |name: &str| format!("scene[{i}].{name}");
    let b = &s.beam;
    let beam = Beam {
        l: cx.length(&k("beam.length"), b.length, "a beam length")?,
        ea: cx.positive(&k("beam.ea"), b.ea, "an axial stiffness in N")?,
        ei: cx.positive(&k("beam.ei"), b.ei, "a bending stiffness in N m^2")?,
        rho_a: cx.positive(&k("beam.rho_a"), b.rho_a, "a mass per length in kg/m")?,
    };
    let base = match (&s.spin_up, &s.hub) {
        (Some(u), None) => Base::SpinUp {
            w: cx.positive(&k("spin_up.w"), u.w, "a final rate in rad/s")?,
            t_up: cx.positive(&k("spin_up.t_up"), u.t_up, "a spin-up time in s")?,
        },
        (None, Some(h)) => Base::Free {
            j_hub: cx.positive(&k("hub.inertia"), h.inertia, "a hub inertia in kg m^2")?,
            torque: cx.finite(&k("hub.torque"), h.torque)?,
            t_off: cx.positive(&k("hub.t_off"), h.t_off, "a time in s")?,
        },
        _ => {
            return cx.err(
                k("spin_up"),
                "a scene has exactly one base: `spin_up` (prescribed) or `hub` (free)",
            );
        }
    };
    for (j, t) in s.breakpoints.iter().enumerate() {
        cx.positive(&k(&format!("breakpoints[{j}]")), *t, "a time in s")?;
    }
    if s.breakpoints.windows(2).any(|w| w[0] >= w[1]) {
        return cx.err(k("breakpoints"), "not strictly ascending");
    }
    let energy_scale = match s.energy_scale {
        Some(e) => cx.positive(&k("energy_scale"), e, "an energy in J")?,
        None => case_scale,
    };
    let reference_dt = match s.reference_dt {
        Some(h) => Some(cx.positive(&k("reference_dt"), h, "a time step in s")?),
        None => None,
    };
    Ok(BeamScene {
        beam,
        base,
        breakpoints: s.breakpoints.clone(),
        energy_scale,
        reference_dt,
    })
}

/// Every breakpoint lies inside the horizon and is divided by the sample and score grids and
/// by every fixed step of the scene's ladders; the base's own breakpoint is listed.
fn check_breakpoints(case: &Case) -> Res<()> {
    let cx = Ctx { file: &case.file };
    for sc in &case.scenes {
        let Some(p) = sc.physics::<BeamScene>() else {
            continue;
        };
        let i = sc.index;
        if let Some(n) = case.physics::<Numerics>() {
            let (h, key) = match p.reference_dt {
                Some(h) => (h, format!("scene[{i}].reference_dt")),
                None => (n.reference_dt, "numerics.reference_dt".to_string()),
            };
            // The time estimate runs at twice the step, the self-convergence track down to
            // a quarter of it.
            if steps_dividing(sc.score_every, 2.0 * h).is_none() {
                return cx.err(
                    key,
                    format!(
                        "twice the reference step {h} s does not divide score_every = {}",
                        sc.score_every
                    ),
                );
            }
        }
        let own = p.base.breakpoint();
        if own < sc.t_end && !p.breakpoints.iter().any(|b| (b - own).abs() <= 1e-9 * own) {
            return cx.err(
                format!("scene[{i}].breakpoints"),
                format!("the base's motion is not smooth at t = {own} s; list it"),
            );
        }
        for (j, &b) in p.breakpoints.iter().enumerate() {
            let key = format!("scene[{i}].breakpoints[{j}]");
            if b >= sc.t_end {
                return cx.err(key, format!("{b} is not before t_end = {}", sc.t_end));
            }
            for (what, h) in [
                ("sample_every", sc.sample_every),
                ("score_every", sc.score_every),
            ] {
                if steps_dividing(b, h).is_none() {
                    return cx.err(key, format!("{b} s is not a multiple of {what} = {h}"));
                }
            }
            for tier in [&sc.ladders, &sc.quick] {
                for s in tier.order1.iter().chain(&tier.order2_4).chain(&tier.order6) {
                    if steps_dividing(b, s.dt).is_none() {
                        return cx.err(
                            key,
                            format!("{b} s is not a multiple of the ladder step {}", s.dt),
                        );
                    }
                }
            }
        }
    }
    Ok(())
}

/// The beam's physics of a scene in the physics hash: the beam, the base, the reference's
/// element count and step (the numerics that shape the reference).
pub fn inputs(case: &Case, scene: &Scene) -> serde_json::Map<String, Value> {
    let mut m = serde_json::Map::new();
    let (Some(c), Some(s)) = (case.physics::<Numerics>(), scene.physics::<BeamScene>()) else {
        return m;
    };
    let b = &s.beam;
    m.insert(
        "beam".into(),
        serde_json::json!({"length": num(b.l), "ea": num(b.ea), "ei": num(b.ei), "rho_a": num(b.rho_a)}),
    );
    let base = match s.base {
        Base::SpinUp { w, t_up } => serde_json::json!({"spin_up": {"w": num(w), "t_up": num(t_up)}}),
        Base::Free {
            j_hub,
            torque,
            t_off,
        } => serde_json::json!({"hub": {"inertia": num(j_hub), "torque": num(torque), "t_off": num(t_off)}}),
    };
    m.insert("base".into(), base);
    m.insert(
        "reference_elements".into(),
        Value::from(c.reference_elements as u64),
    );
    m.insert(
        "reference_dt".into(),
        num(s.reference_dt.unwrap_or(c.reference_dt)),
    );
    // The self-convergence tracks of the reference depend on every formulation's mesh or
    // modes.
    m.insert("elements".into(), Value::from(c.elements as u64));
    m.insert(
        "modes".into(),
        serde_json::json!([c.bending_modes, c.axial_modes, c.cb_bending_modes, c.cb_axial_modes]),
    );
    m
}
