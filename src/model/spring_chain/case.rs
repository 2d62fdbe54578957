//! The spring chain's case schema: `[chain]` with `masses` (kg) and `stiffness` (N/m; wall to
//! mass 1, mass 1 to 2, mass 2 to 3), and per scene the initial `displacement` (m) and
//! `velocity` (m/s) of the three masses. Every mass and stiffness must be finite and positive
//! (a positive `k1` keeps every modal frequency positive); the shared keys are checked by
//! `case::Ctx::assemble`.
use serde::Deserialize;
use serde_json::Value;

use super::{Chain, ChainObs};
use crate::case::hash::num;
use crate::case::{Case, CaseError, Ctx, Res, Scene};

crate::case_schema! {
    case RawCase / CaseOwn {
        chain: RawChain,
    }
    scene RawScene / SceneOwn {
        #[serde(deserialize_with = "crate::case::exact::array")]
        displacement: [f64; 3],
        #[serde(deserialize_with = "crate::case::exact::array")]
        velocity: [f64; 3],
    }
}

/// `[chain]` as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawChain {
    #[serde(deserialize_with = "crate::case::exact::array")]
    masses: [f64; 3],
    #[serde(deserialize_with = "crate::case::exact::array")]
    stiffness: [f64; 3],
}

/// The chain of a case.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainCase {
    pub masses: [f64; 3],
    pub stiffness: [f64; 3],
}

/// The initial state of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainScene {
    pub initial: ChainObs,
}

impl ChainCase {
    pub fn chain(&self) -> Chain {
        Chain::new(self.masses, self.stiffness)
    }
}

fn positive3(cx: &Ctx, key: &str, a: [f64; 3], what: &str) -> Res<[f64; 3]> {
    for (i, x) in a.iter().enumerate() {
        cx.positive(&format!("{key}[{i}]"), *x, what)?;
    }
    Ok(a)
}

/// Loads a spring-chain case file (the family's `load`).
pub fn load(file: &str, text: &str) -> Result<Case, CaseError> {
    let raw: RawCase = crate::case::parse(file, text)?;
    let (shared, own, scenes) = raw.split();
    Ctx { file }.assemble(
        &super::family::FAMILY,
        shared,
        |cx| {
            Ok(ChainCase {
                masses: positive3(cx, "chain.masses", own.chain.masses, "a mass in kg")?,
                stiffness: positive3(
                    cx,
                    "chain.stiffness",
                    own.chain.stiffness,
                    "a stiffness in N/m",
                )?,
            })
        },
        scenes,
        |cx, i, s: &SceneOwn, _c: &ChainCase| {
            let x = cx.vec3(&format!("scene[{i}].displacement"), s.displacement)?;
            let v = cx.vec3(&format!("scene[{i}].velocity"), s.velocity)?;
            Ok(ChainScene {
                initial: ChainObs { x, v },
            })
        },
    )
}

/// The chain's physics of a scene in the physics hash: masses, stiffnesses, initial state.
pub fn inputs(case: &Case, scene: &Scene) -> serde_json::Map<String, Value> {
    let mut m = serde_json::Map::new();
    let (Some(c), Some(s)) = (case.physics::<ChainCase>(), scene.physics::<ChainScene>()) else {
        return m;
    };
    let arr = |a: &[f64]| Value::Array(a.iter().map(|x| num(*x)).collect());
    m.insert("masses".into(), arr(&c.masses));
    m.insert("stiffness".into(), arr(&c.stiffness));
    m.insert("displacement".into(), arr(s.initial.x.as_slice()));
    m.insert("velocity".into(), arr(s.initial.v.as_slice()));
    m
}
