//! Fixtures shared by the material tests: the six materials of the fiber-column case (core
//! and cover `Concrete01` and `Concrete02`, `Steel01`, `Steel02`) plus an elastic one, and
//! the OpenSees reference file `references/fiber_column/materials/materials.json` (written by
//! `generate.py` next to it) with its strain histories, which visit every branch of every
//! model and so also serve the tangent and trial/commit/revert tests.
use super::*;
use serde::Deserialize;
use std::collections::BTreeMap;

/// The reference file, relative to the crate root.
pub(super) const REFERENCE: &str = "references/fiber_column/materials/materials.json";

/// The header of the reference file.
#[derive(Debug, Deserialize)]
pub(super) struct Header {
    pub opensees_version: String,
    pub openseespy_version: String,
    pub script_sha256: String,
    pub regenerate: String,
}

/// One material's OpenSees response: parameters (OpenSees' names), the committed strain
/// history and OpenSees' stress and tangent after each commit.
#[derive(Debug, Deserialize)]
pub(super) struct Response {
    pub name: String,
    pub model: String,
    pub params: BTreeMap<String, f64>,
    pub strain: Vec<f64>,
    pub stress: Vec<f64>,
    pub tangent: Vec<f64>,
}

/// Where the reference comes from and what checks it.
#[derive(Debug, Deserialize)]
pub(super) struct Provenance {
    pub tool: String,
    pub command: String,
    pub script_sha256: String,
    pub cross_check: String,
    pub accuracy_claim: String,
}

/// The whole reference file.
#[derive(Debug, Deserialize)]
pub(super) struct Reference {
    pub header: Header,
    pub provenance: Provenance,
    pub materials: Vec<Response>,
}

/// Reads and parses the reference file.
pub(super) fn load_reference() -> Reference {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(REFERENCE);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("cannot parse {}: {e}", path.display()))
}

/// Builds a material from OpenSees' model name and parameter names.
pub(super) fn build(model: &str, p: &BTreeMap<String, f64>) -> Result<Material, String> {
    let get = |k: &str| {
        p.get(k)
            .copied()
            .ok_or_else(|| format!("{model}: missing parameter {k}"))
    };
    Ok(match model {
        "Concrete01" => Concrete01::new(Concrete01Params {
            fpc: get("fpc")?,
            epsc0: get("epsc0")?,
            fpcu: get("fpcu")?,
            epscu: get("epscu")?,
        })?
        .into(),
        "Concrete02" => Concrete02::new(Concrete02Params {
            fpc: get("fpc")?,
            epsc0: get("epsc0")?,
            fpcu: get("fpcu")?,
            epscu: get("epscu")?,
            lambda: get("lambda")?,
            ft: get("ft")?,
            ets: get("Ets")?,
        })?
        .into(),
        "Steel01" => Steel01::new(Steel01Params {
            fy: get("fy")?,
            e0: get("E0")?,
            b: get("b")?,
        })?
        .into(),
        "Steel02" => Steel02::new(Steel02Params {
            fy: get("fy")?,
            e0: get("E0")?,
            b: get("b")?,
            r0: get("R0")?,
            c_r1: get("cR1")?,
            c_r2: get("cR2")?,
        })?
        .into(),
        other => return Err(format!("unknown model {other}")),
    })
}

pub(super) const CORE_C01: Concrete01Params = Concrete01Params {
    fpc: -36e6,
    epsc0: -0.004,
    fpcu: -30e6,
    epscu: -0.014,
};
pub(super) const COVER_C01: Concrete01Params = Concrete01Params {
    fpc: -30e6,
    epsc0: -0.002,
    fpcu: 0.0,
    epscu: -0.006,
};
pub(super) const CORE_C02: Concrete02Params = Concrete02Params {
    fpc: -36e6,
    epsc0: -0.004,
    fpcu: -7.2e6,
    epscu: -0.02,
    lambda: 0.1,
    ft: 3e6,
    ets: 1.5e9,
};
pub(super) const COVER_C02: Concrete02Params = Concrete02Params {
    fpc: -30e6,
    epsc0: -0.002,
    fpcu: -6e6,
    epscu: -0.006,
    lambda: 0.1,
    ft: 3e6,
    ets: 1.5e9,
};
pub(super) const STEEL01: Steel01Params = Steel01Params {
    fy: 420e6,
    e0: 200e9,
    b: 0.01,
};
pub(super) const STEEL02: Steel02Params = Steel02Params {
    fy: 420e6,
    e0: 200e9,
    b: 0.01,
    r0: 18.0,
    c_r1: 0.925,
    c_r2: 0.15,
};

/// The six case materials and an elastic one, each with a cyclic strain history that visits
/// all its branches (the OpenSees histories; the steel's for the elastic one).
pub(super) fn case_histories() -> Vec<(String, Material, Vec<f64>)> {
    let reference = load_reference();
    let mut out: Vec<_> = reference
        .materials
        .iter()
        .map(|r| {
            let m = build(&r.model, &r.params).expect("reference parameters");
            (r.name.clone(), m, r.strain.clone())
        })
        .collect();
    let steel = out
        .iter()
        .find(|(n, _, _)| n == "steel02")
        .map(|(_, _, h)| h.clone())
        .expect("steel02 history");
    let elastic = Elastic::new(ElasticParams { e: 200e9 }).unwrap();
    out.push(("elastic".into(), elastic.into(), steel));
    out
}

/// Strains from 0 along straight segments to each target in `n` equal steps.
pub(super) fn path(targets: &[f64], n: usize) -> Vec<f64> {
    let mut out = vec![0.0];
    for &target in targets {
        let start = *out.last().unwrap();
        out.extend((1..=n).map(|k| start + (target - start) * k as f64 / n as f64));
    }
    out
}

/// Sets and commits each strain in turn; returns the committed (strain, stress) points.
pub(super) fn drive(m: &mut Material, strains: &[f64]) -> Vec<(f64, f64)> {
    strains
        .iter()
        .map(|&e| {
            let (s, _) = m.set_trial_strain(e);
            m.commit();
            (e, s)
        })
        .collect()
}
