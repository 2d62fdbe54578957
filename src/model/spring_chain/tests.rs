//! The proof of the family seam: the spring chain goes through `list`, `run`, `trajectory`,
//! `reference --check`, `report` and `gate` of the real command line (in process), with its
//! case file and references under `tests/fixtures/`; its exact solution is checked against
//! the equations; and no file outside this folder names the family or its variants, except
//! its line in the family table and its fixtures.
use std::path::{Path, PathBuf};

use clap::Parser;

use super::{Chain, ChainObs};
use crate::cli::{Cli, execute};
use crate::summary::{Status, Summary};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn fixtures() -> (String, String) {
    let f = root().join("tests/fixtures");
    (
        f.join("cases").display().to_string(),
        f.join("references").display().to_string(),
    )
}

/// Runs the command line in process; returns its exit code.
fn cli(args: &[&str]) -> i32 {
    let (cases, refs) = fixtures();
    let mut all = vec!["mbdbench", "--cases", &cases, "--references", &refs];
    all.extend_from_slice(args);
    execute(Cli::parse_from(all))
}

fn temp(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("mbdbench-seam-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The modal solution solves `M x'' + K x = 0`: its second difference in time matches
/// `-M^{-1} K x` to the difference's truncation, and it keeps the energy to round-off.
#[test]
fn exact_solution_solves_the_equations() {
    let chain = Chain::new([1.0, 2.0, 1.5], [100.0, 50.0, 80.0]);
    let o0 = ChainObs {
        x: [0.01, -0.02, 0.1].into(),
        v: [0.5, 0.0, -0.3].into(),
    };
    let e0 = chain.energy(&o0);
    let h = 1e-4;
    for t in [0.3, 1.7, 5.0] {
        let (a, b, c) = (
            chain.exact(&o0, t - h),
            chain.exact(&o0, t),
            chain.exact(&o0, t + h),
        );
        let xdd = (a.x - 2.0 * b.x + c.x) / (h * h);
        let rhs = -(chain.minv_k * b.x);
        assert!(
            (xdd - rhs).amax() <= 1e-5 * rhs.amax().max(1.0),
            "{xdd} vs {rhs}"
        );
        assert!((chain.energy(&b) - e0).abs() <= 1e-13 * e0);
    }
    // At t = 0 the modal round trip x = Phi Phi^T M x0 returns x0 to round-off.
    assert!((chain.exact(&o0, 0.0).x - o0.x).amax() <= 1e-15);
}

/// Every command of the suite runs the family end to end: the matrix lists its six variants,
/// the stored references pass their check, the full run converges at the methods' orders
/// (rk4 4, Stormer-Verlet 2), the trajectory carries the family's columns without `--param`,
/// the stability study (the rigid body's parts) leaves it alone, the report has the case, and
/// the gates pass.
#[test]
fn end_to_end_through_the_command_line() {
    let out = temp("e2e");
    let o = out.display().to_string();
    assert_eq!(cli(&["list"]), 0);
    let cases = crate::catalogue::load_dir(&root().join("tests/fixtures/cases")).unwrap();
    let problems = crate::catalogue::problems(&cases, &[], &[]).unwrap();
    assert_eq!(problems.len(), 2);
    let cells: Vec<_> = crate::problem::matrix(problems[0].family()).collect();
    assert_eq!(cells.len(), 6);
    assert_eq!(cli(&["reference", "--case", "spring_chain", "--check"]), 0);
    assert_eq!(cli(&["run", "--jobs", "2", "--out", &o]), 0);
    let s: Summary =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s.records.len(), 2 * (4 * 2 + 4 * 2 + 3 * 2));
    assert!(s.records.iter().all(|r| r.status == Status::Ok));
    for f in &s.fits {
        let want = if f.key.integrator == "rk4" { 4.0 } else { 2.0 };
        let order = f.order.unwrap_or(f64::NAN);
        assert!((order - want).abs() <= 0.1, "{f:?}");
    }
    assert_eq!(s.fits.len(), 2 * 4, "{:?}", s.fits);
    for r in &s.records {
        assert!(r.metrics["displacement_error_max"].unwrap() < 0.05, "{r:?}");
        // Only the runs a figure draws keep a series file; the others say why.
        match &r.series {
            Some(rel) => assert!(out.join(rel).is_file()),
            None => assert!(r.series_reason.is_some(), "{r:?}"),
        }
    }
    let traj = out.join("kick.json");
    let t = traj.display().to_string();
    let args = [
        "trajectory",
        "--case",
        "spring_chain",
        "--scene",
        "kick",
        "--integrator",
        "stormer_verlet",
        "--dt",
        "0.0125",
        "--out",
        &t,
    ];
    assert_eq!(cli(&args), 0);
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&traj).unwrap()).unwrap();
    assert_eq!(doc["formulation"], "chain_nodal");
    assert_eq!(doc["param"], "none");
    assert_eq!(doc["t"].as_array().unwrap().len(), 201);
    assert_eq!(doc["displacement"][0].as_array().unwrap().len(), 3);
    assert_eq!(doc["energy"].as_array().unwrap().len(), 201);
    // The stability study's parts are the rigid body's: nothing of this family runs there.
    assert_eq!(cli(&["stability", "--quick", "--out", &o]), 0);
    let st: Summary =
        serde_json::from_str(&std::fs::read_to_string(out.join("stability.json")).unwrap())
            .unwrap();
    assert!(st.records.is_empty() && st.fits.is_empty());
    let summary = out.join("summary.json").display().to_string();
    assert_eq!(cli(&["report", "--summary", &summary]), 0);
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("spring_chain") && html.contains("stormer_verlet"));
    assert_eq!(cli(&["gate", "--summary", &summary]), 0);
    let _ = std::fs::remove_dir_all(&out);
}

/// Files a reader of the rest of the crate sees (sources, tests, benches, cases, references,
/// docs, CI), relative to the crate root.
fn visible_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            visible_files(&p, out);
        } else {
            out.push(p);
        }
    }
}

/// Nothing outside `src/model/spring_chain/` names the family or its own variants, except its
/// line in the family table (`src/model/mod.rs`) and its fixtures under `tests/fixtures/`.
#[test]
fn no_file_outside_the_folder_names_the_family() {
    let names = [
        "spring_chain",
        "stormer_verlet",
        "chain_nodal",
        "chain_modal",
    ];
    let r = root();
    let mut files = vec![];
    for d in ["src", "tests", "benches", "cases", "references", ".ci"] {
        visible_files(&r.join(d), &mut files);
    }
    for f in ["README.md", "Cargo.toml", "build.rs"] {
        files.push(r.join(f));
    }
    let own = r.join("src/model/spring_chain");
    let fixtures = [
        r.join("tests/fixtures/cases/spring_chain.toml"),
        r.join("tests/fixtures/references/spring_chain"),
    ];
    let mut offenders = vec![];
    for f in files {
        if f.starts_with(&own) || fixtures.iter().any(|x| f.starts_with(x)) {
            continue;
        }
        let Ok(text) = std::fs::read_to_string(&f) else {
            continue;
        };
        let table = f == r.join("src/model/mod.rs");
        for (i, line) in text.lines().enumerate() {
            if table && line.trim() == "spring_chain," {
                continue;
            }
            if names.iter().any(|n| line.contains(n)) {
                offenders.push(format!("{}:{}: {line}", f.display(), i + 1));
            }
        }
    }
    assert!(offenders.is_empty(), "{}", offenders.join("\n"));
}
