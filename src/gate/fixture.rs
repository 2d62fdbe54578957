//! Test fixture of the gate: `nine_spring` with the fixture's gates in place of the real
//! case file's own (so the tests do not depend on the catalogue's gates), and a synthetic
//! summary whose records carry the real current physics and reference hashes.
use std::collections::BTreeMap;
use std::path::PathBuf;

use super::GateOptions;
use crate::case::{self, Case};
use crate::integrate::Stats;
use crate::summary::{Env, Record, Status, Summary};

/// Three gates: a quick accuracy gate at the quick step 1e-2 (its bound is baseline x margin),
/// a full-only energy gate at 5e-3 (not on the quick ladder), and a quick conditioning gate on
/// two adaptive variants at tol 1e-6 (on both ladders).
pub const GATES: &str = r#"
[[gates]]
metric = "rotation_error_max"
max = 1.0e-5
where = { scene = "two_angles", param = "so3", integrator = "rk4", formulation = "body", dt = 1.0e-2 }
quick = true
baseline = 5.0e-6
margin = 2.0
commit = "abc1234"

[[gates]]
metric = "energy_drift_max"
max = 1.0e-6
where = { scene = "two_angles", param = "so3", integrator = "rk4", formulation = "body", dt = 5.0e-3 }

[[gates]]
metric = "conditioning_min"
min = 0.5
where = { scene = "two_angles", param = ["so3", "quat"], integrator = "dopri5", formulation = "body", tol = 1.0e-6 }
quick = true
"#;

/// The text of an embedded case file.
pub fn source(name: &str) -> &'static str {
    let label = format!("cases/{name}.toml");
    case::embedded_sources()
        .iter()
        .find(|(l, _)| *l == label)
        .map(|(_, t)| *t)
        .unwrap()
}

/// An embedded case with its own gates replaced by `gates`.
pub fn with_gates(name: &str, gates: &str) -> Case {
    let label = format!("cases/{name}.toml");
    let bare = case::without_gates(source(name));
    crate::catalogue::load_str(&label, &format!("{bare}\n{gates}")).unwrap()
}

/// `nine_spring` with `GATES`.
pub fn nine() -> Case {
    with_gates("nine_spring", GATES)
}

pub fn references() -> PathBuf {
    crate::cli::default_references()
}

/// Options of the full gate (or the quick one) on the real references.
pub fn opts(quick: bool) -> GateOptions {
    GateOptions {
        quick,
        ..GateOptions::new(references())
    }
}

/// An `ok` record with the current hashes of its scene.
pub fn record(
    c: &Case,
    scene: &str,
    variant: (&str, &str, &str),
    dt: Option<f64>,
    tol: Option<f64>,
    metrics: &[(&str, f64)],
    rhs_evals: u64,
) -> Record {
    let s = c.scene(scene).unwrap();
    let inputs = case::inputs_sha256(c, s);
    let loaded =
        crate::model::rigid_body::reference::load(&references(), &c.name, scene, &inputs).unwrap();
    Record {
        key: crate::summary::RunKey::new(&c.name, scene, variant.0, variant.1, variant.2),
        dt,
        tol,
        status: Status::Ok,
        failure: None,
        reason: None,
        metrics: metrics
            .iter()
            .map(|(k, v)| (k.to_string(), Some(*v)))
            .collect(),
        metric_reasons: BTreeMap::new(),
        stats: Stats {
            steps: rhs_evals / 4,
            rhs_evals,
            newton_iters: 0,
            rejected: 0,
            normalizations: 0,
            element_iters: 0,
        },
        wall_s: None,
        inputs_sha256: inputs,
        settings_sha256: Some(s.settings_sha256.clone()),
        reference_sha256: Some(loaded.file_sha256),
        series: None,
        series_reason: None,
    }
}

pub fn summary(records: Vec<Record>) -> Summary {
    Summary {
        schema: 1,
        git_commit: "test".into(),
        created_utc: "2026-01-01T00:00:00Z".into(),
        env: Env {
            rustc: "rustc".into(),
            cpu: "cpu".into(),
            os: "os".into(),
            profile: "test".into(),
            threads: 1,
            timing: None,
            elapsed_s: None,
            families: None,
        },
        records,
        fits: vec![],
        selection: None,
        methods: Some(crate::catalogue::methods()),
        families: Some(crate::catalogue::family_models()),
    }
}

/// Records for every point `GATES` expands to (either tier), each within its bounds.
pub fn passing(c: &Case) -> Summary {
    let so3_rk4 = ("so3", "rk4", "body");
    let errors = |rot: f64| {
        vec![
            ("position_error_max", rot * 0.5),
            ("rotation_error_max", rot),
            ("velocity_error_max", rot * 2.0),
            ("omega_error_max", rot * 3.0),
            ("energy_drift_max", 1.0e-7),
            ("conditioning_min", 1.0),
        ]
    };
    summary(vec![
        record(
            c,
            "two_angles",
            so3_rk4,
            Some(1.0e-2),
            None,
            &errors(4.0e-6),
            4000,
        ),
        record(
            c,
            "two_angles",
            so3_rk4,
            Some(5.0e-3),
            None,
            &errors(2.5e-7),
            8000,
        ),
        record(
            c,
            "two_angles",
            ("so3", "dopri5", "body"),
            None,
            Some(1.0e-6),
            &errors(3.0e-6),
            2100,
        ),
        record(
            c,
            "two_angles",
            ("quat", "dopri5", "body"),
            None,
            Some(1.0e-6),
            &[
                ("rotation_error_max", 3.1e-6),
                ("conditioning_min", 0.99),
                ("constraint_error_max", 1.0e-9),
            ],
            2200,
        ),
    ])
}

/// A fresh scratch folder for one test.
pub fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("mbdbench-gate-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}
