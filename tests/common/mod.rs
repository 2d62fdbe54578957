//! Shared helpers of the integration tests: run a slice of the catalogue in-process (one
//! timing repeat, results only) into a temporary folder and index its records.
#![allow(dead_code)]
use std::collections::BTreeMap;
use std::path::PathBuf;

use mbdbench::cli::default_references;
use mbdbench::model::rigid_body::plan::{self as rigid_plan, ScenePlan};
use mbdbench::selection::VariantFilter;
use mbdbench::suite::{self, RunOptions};
use mbdbench::summary::{Record, Summary};

/// A process's standard output and error, in that order (for assertion messages).
pub fn text(o: &std::process::Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// A fresh temporary folder for one test.
pub fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("mbdbench-test-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A copy of the stored references (`references/` of the source tree, its case folders with
/// their subfolders: the fiber column keeps its OpenSees runs in one) in a fresh temporary
/// folder.
pub fn copy_references(tag: &str) -> PathBuf {
    fn copy_tree(from: &std::path::Path, to: &std::path::Path) {
        std::fs::create_dir_all(to).unwrap();
        for f in std::fs::read_dir(from).unwrap() {
            let f = f.unwrap().path();
            let target = to.join(f.file_name().unwrap());
            if f.is_dir() {
                copy_tree(&f, &target);
            } else {
                std::fs::copy(&f, target).unwrap();
            }
        }
    }
    let src = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("references");
    let dir = temp_dir(tag);
    for case in std::fs::read_dir(&src).unwrap() {
        let case = case.unwrap().path();
        if case.is_dir() {
            copy_tree(&case, &dir.join(case.file_name().unwrap()));
        }
    }
    dir
}

/// A cases folder holding one catalogue case file, `file`, edited by `edit`.
pub fn cases_with(tag: &str, file: &str, edit: impl Fn(&str) -> String) -> PathBuf {
    let d = temp_dir(tag);
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("cases").join(file)).unwrap();
    std::fs::write(d.join(file), edit(&text)).unwrap();
    d
}

/// `text` with `old` replaced by `new`; `old` must occur (a fixture that silently stops
/// matching the case file would test nothing).
pub fn replace_once(text: &str, old: &str, new: &str) -> String {
    assert!(
        text.contains(old),
        "the case file no longer contains `{old}`"
    );
    text.replacen(old, new, 1)
}

/// The plans of one case (all its scenes, or the named ones).
pub fn plans(case_name: &str, scenes: &[&str]) -> Vec<ScenePlan> {
    let cases = mbdbench::catalogue::embedded().unwrap();
    let scenes: Vec<String> = scenes.iter().map(|s| s.to_string()).collect();
    rigid_plan::plans(&cases, &[case_name.to_string()], &scenes).unwrap()
}

/// The compiled problems of one case (all its scenes, or the named ones).
pub fn problems(case_name: &str, scenes: &[&str]) -> Vec<Box<dyn mbdbench::problem::Problem>> {
    let cases = mbdbench::catalogue::embedded().unwrap();
    let scenes: Vec<String> = scenes.iter().map(|s| s.to_string()).collect();
    mbdbench::catalogue::problems(&cases, &[case_name.to_string()], &scenes).unwrap()
}

/// Runs the selected scenes and variants with the full ladders (or the quick tier).
pub fn run(
    case_name: &str,
    scenes: &[&str],
    filter: VariantFilter,
    quick: bool,
    t_end: Option<f64>,
    tag: &str,
) -> Summary {
    let out = temp_dir(tag);
    let opts = RunOptions {
        quick,
        jobs: std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1),
        out: out.clone(),
        t_end,
        references: default_references(),
        progress: false,
        repeats: 0,
        serial_timing: false,
        cases: vec![],
        scenes: vec![],
        base: None,
        skip: true,
        cap_s: mbdbench::suite::skip::DEFAULT_CAP_S,
        cost: mbdbench::cost::CostTable::embedded(),
        catalogue: mbdbench::catalogue::Catalogue::builtin(),
    };
    let s = suite::run_catalogue(problems(case_name, scenes), &filter, &opts).unwrap();
    let _ = std::fs::remove_dir_all(&out);
    s
}

/// Filter from lists of names.
pub fn filter(params: &[&str], integrators: &[&str], formulations: &[&str]) -> VariantFilter {
    let v = |l: &[&str]| l.iter().map(|s| s.to_string()).collect();
    VariantFilter {
        param: v(params),
        integrator: v(integrators),
        formulation: v(formulations),
    }
}

/// Records by (scene, param, integrator, formulation, dt-or-tol bits).
pub fn index(s: &Summary) -> BTreeMap<(String, String, String, String, u64), Record> {
    s.records
        .iter()
        .filter(|r| r.dt.is_some() || r.tol.is_some())
        .map(|r| {
            (
                (
                    r.key.scene.clone(),
                    r.key.param.clone(),
                    r.key.integrator.clone(),
                    r.key.formulation.clone(),
                    r.dt.or(r.tol).unwrap().to_bits(),
                ),
                r.clone(),
            )
        })
        .collect()
}

/// One record.
pub fn get<'a>(
    s: &'a Summary,
    scene: &str,
    param: &str,
    integrator: &str,
    formulation: &str,
    value: f64,
) -> &'a Record {
    s.records
        .iter()
        .find(|r| {
            r.key.scene == scene
                && r.key.param == param
                && r.key.integrator == integrator
                && r.key.formulation == formulation
                && r.dt.or(r.tol) == Some(value)
        })
        .unwrap_or_else(|| panic!("no record {scene}/{param}/{integrator}/{formulation}/{value}"))
}

/// A metric value (panics with the record when null or absent).
pub fn metric(r: &Record, name: &str) -> f64 {
    r.metrics
        .get(name)
        .copied()
        .flatten()
        .unwrap_or_else(|| panic!("metric {name} missing in {r:?}"))
}
