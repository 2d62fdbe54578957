//! The command line against bad input and failing runs (exit codes: docs/schemas.md, "Exit
//! codes"): bad case files and missing or stale references exit 2 with an error naming the
//! file and the key and write nothing; a diverging run and a run past its work limit are
//! recorded as typed failures while the other runs complete; `reference --check` passes.
mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_mbdbench"))
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn run(args: &[&str]) -> Output {
    bin().args(args).output().unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

use common::{cases_with, replace_once};

fn expect_bad_input(dir: &Path, key: &str, what: &str) {
    let out = dir.join("out");
    let o = run(&[
        "run",
        "--quick",
        "--cases",
        dir.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{what}: {e}");
    assert!(e.contains("nine_spring.toml"), "{what}: no file in {e}");
    assert!(e.contains(key), "{what}: no key {key} in {e}");
    assert!(
        !out.join("summary.json").exists(),
        "{what}: wrote a summary"
    );
}

/// Each class of bad case file exits 2 naming the file and the key.
#[test]
fn bad_case_files_exit_2_naming_file_and_key() {
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            "unknown key",
            "energy_scale = 1.0e3",
            "energy_scale = 1.0e3\nenergy_scael = 1.0",
            "energy_scael",
        ),
        (
            "wrong type",
            "mass = 1000.0",
            "mass = \"heavy\"",
            "body.mass",
        ),
        ("negative mass", "mass = 1000.0", "mass = -1.0", "body.mass"),
        ("zero mass", "mass = 1000.0", "mass = 0.0", "body.mass"),
        (
            "not symmetric",
            "inertia = [[800.0, -60.0, 40.0], [-60.0, 1000.0",
            "inertia = [[800.0, -60.0, 40.0], [-61.0, 1000.0",
            "body.inertia",
        ),
        (
            "not positive definite",
            "inertia = [[800.0, -60.0, 40.0], [-60.0, 1000.0, -80.0], [40.0, -80.0, 1200.0]]",
            "inertia = [[800.0, -60.0, 40.0], [-60.0, -1000.0, -80.0], [40.0, -80.0, 1200.0]]",
            "body.inertia",
        ),
        (
            "triangle inequality",
            "inertia = [[800.0, -60.0, 40.0], [-60.0, 1000.0, -80.0], [40.0, -80.0, 1200.0]]",
            "inertia = [[100.0, 0.0, 0.0], [0.0, 100.0, 0.0], [0.0, 0.0, 1200.0]]",
            "body.inertia",
        ),
        ("t_end <= 0", "t_end = 10.0", "t_end = -10.0", "t_end"),
        (
            "ladder step",
            "order1 = [2.0e-5",
            "order1 = [3.0e-2, 2.0e-5",
            "ladders.order1",
        ),
    ];
    for (i, (what, from, to, key)) in cases.iter().enumerate() {
        let dir = cases_with(&format!("bad{i}"), "nine_spring.toml", |t| {
            replace_once(t, from, to)
        });
        expect_bad_input(&dir, key, what);
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// A missing reference and a stale one (its inputs_sha256 differs) exit 2, naming the file
/// (and, when stale, the key), before any run.
#[test]
fn missing_and_stale_references_exit_2() {
    let empty = common::temp_dir("refs-empty");
    let out = empty.join("out");
    let o = run(&[
        "run",
        "--quick",
        "--case",
        "free_body",
        "--references",
        empty.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("gni.json") && stderr(&o).contains("missing"),
        "{}",
        stderr(&o)
    );
    assert!(!out.join("summary.json").exists());

    let stale = common::temp_dir("refs-stale");
    std::fs::create_dir_all(stale.join("free_body")).unwrap();
    let text = std::fs::read_to_string(repo().join("references/free_body/gni.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let old = v["inputs_sha256"].as_str().unwrap().to_string();
    std::fs::write(
        stale.join("free_body/gni.json"),
        text.replace(&old, &"0".repeat(64)),
    )
    .unwrap();
    let o = run(&[
        "run",
        "--quick",
        "--case",
        "free_body",
        "--references",
        stale.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(
        e.contains("gni.json") && e.contains("inputs_sha256") && e.contains("stale"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&empty);
    let _ = std::fs::remove_dir_all(&stale);
}

/// A diverging run (euler on nine_spring at 0.1 s: the state overflows within 3.5 s) ends as
/// `failed` with its kind (`non_finite`) and time while every other run of the same command
/// completes; a ladder run past its step budget (a `--t-end`) fails with `work_limit`, and a
/// `trajectory --dt` past it is refused before the run (exit 2, nothing written).
#[test]
fn diverging_and_over_budget_runs_are_typed_failures() {
    let dir = cases_with("diverge", "nine_spring.toml", |t| {
        // The case-wide order-1 ladder and the `large` scene's own override.
        let t = replace_once(
            t,
            "order1 = [2.0e-5, 1.25e-5, 7.8125e-6]",
            "order1 = [1.0e-1]",
        );
        replace_once(&t, "ladders = { order1 = [4.0e-5, 2.0e-5] }", "")
    });
    let out = dir.join("out");
    let o = run(&[
        "run",
        "--cases",
        dir.to_str().unwrap(),
        "--param",
        "so3",
        "--param",
        "quat_proj",
        "--integrator",
        "euler",
        "--integrator",
        "rk4",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    let recs = s["records"].as_array().unwrap();
    let euler: Vec<_> = recs.iter().filter(|r| r["integrator"] == "euler").collect();
    assert!(!euler.is_empty());
    for r in &euler {
        assert_eq!(r["status"], "failed", "{r}");
        let kind = r["failure"]["kind"].as_str().unwrap();
        assert!(kind == "non_finite", "{r}");
        assert!(r["failure"]["t"].as_f64().unwrap() > 0.0);
    }
    let rk4_ok = recs
        .iter()
        .filter(|r| r["integrator"] == "rk4" && r["status"] == "ok")
        .count();
    assert_eq!(rk4_ok, 48, "the other runs completed");

    let dir2 = cases_with("budget", "nine_spring.toml", |t| {
        replace_once(
            t,
            "reference = \"numerical\"",
            "reference = \"numerical\"\nmax_steps = 2000000",
        )
    });
    let o = run(&[
        "trajectory",
        "--cases",
        dir2.to_str().unwrap(),
        "--case",
        "nine_spring",
        "--scene",
        "large",
        "--param",
        "so3",
        "--integrator",
        "euler",
        "--dt",
        "1e-6",
        "--out",
        dir2.join("t.json").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("max_steps = 2000000"), "{}", stderr(&o));
    assert!(!dir2.join("t.json").exists());
    let out2 = dir2.join("out");
    let o = run(&[
        "run",
        "--quick",
        "--cases",
        dir2.to_str().unwrap(),
        "--scene",
        "large",
        "--param",
        "so3",
        "--integrator",
        "euler",
        "--t-end",
        "3000",
        "--out",
        out2.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out2.join("summary.json")).unwrap()).unwrap();
    let r = &s["records"][0];
    assert_eq!(r["status"], "failed", "{r}");
    assert_eq!(r["failure"]["kind"], "work_limit", "{r}");
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&dir2);
}

/// Usage errors exit 2 and write nothing; `trajectory` names the valid names of a wrong one,
/// and on success says what it wrote.
#[test]
fn usage_errors_exit_2() {
    let d = common::temp_dir("usage");
    let f = d.join("t.json");
    for args in [
        vec!["run", "--param", "quaternion"],
        vec!["run", "--case", "no_such_case"],
        vec![
            "trajectory",
            "--case",
            "free_body",
            "--scene",
            "gni",
            "--param",
            "so3",
            "--integrator",
            "rk4",
            "--dt",
            "0.03",
            "--out",
            f.to_str().unwrap(),
        ],
        vec![
            "trajectory",
            "--case",
            "free_body",
            "--scene",
            "gni",
            "--param",
            "euler_xyz",
            "--integrator",
            "lgvi",
            "--dt",
            "0.01",
            "--out",
            f.to_str().unwrap(),
        ],
        vec!["frobnicate"],
    ] {
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(!f.exists());
    }
    // `trajectory` refuses an unknown name listing the valid ones of its family and axis.
    let traj = |scene: &str, param: &str, integ: &str| {
        run(&[
            "trajectory",
            "--case",
            "free_body",
            "--scene",
            scene,
            "--param",
            param,
            "--integrator",
            integ,
            "--dt",
            "0.01",
            "--out",
            f.to_str().unwrap(),
        ])
    };
    for (o, says) in [
        (
            traj("gnii", "so3", "rk4"),
            "--scene gnii: not a scene of case free_body (its scenes: gni",
        ),
        (
            traj("gni", "so4", "rk4"),
            "--param so4: not a name of the rigid_body family (valid: euler_xyz",
        ),
        (
            traj("gni", "so3", "rk5"),
            "--integrator rk5: not a name of the rigid_body family (valid: euler, rk4",
        ),
    ] {
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(stderr(&o).contains(says), "{}", stderr(&o));
        assert!(!f.exists());
    }
    // On success it says what it wrote, and the file records the step, the units and the
    // commit.
    let o = traj("gni", "so3", "rk4");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let said = String::from_utf8_lossy(&o.stdout);
    assert!(
        said.starts_with(&format!("trajectory: {} (", f.display())),
        "{said}"
    );
    let doc: serde_json::Value = serde_json::from_slice(&std::fs::read(&f).unwrap()).unwrap();
    assert_eq!(doc["dt"], 0.01);
    assert_eq!(doc["units"]["omega_body"], "rad/s");
    assert_eq!(doc["git_commit"], mbdbench::summary::git_commit());
}

/// `reference --check` recomputes every stored reference and passes within its claim.
#[test]
fn stored_references_check() {
    for case in ["nine_spring", "gimbal_lock", "free_body", "heavy_top"] {
        let o = run(&["reference", "--case", case, "--check"]);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{case}: {}{}",
            String::from_utf8_lossy(&o.stdout),
            stderr(&o)
        );
    }
}

/// `mbdbench report` with a corrupt stability.json beside the summary warns on stderr (naming
/// the file), still writes the whole report without a stability part and exits 0.
#[test]
fn report_with_corrupt_stability_json_warns_and_goes_on() {
    let d = common::temp_dir("report-corrupt-stability");
    let summary = mbdbench::summary::Summary {
        schema: 1,
        git_commit: "abc1234".into(),
        created_utc: "2026-01-02T03:04:05Z".into(),
        env: mbdbench::summary::Env::current(1, None),
        records: vec![],
        fits: vec![],
        selection: None,
        methods: None,
        families: None,
    };
    let path = d.join("summary.json");
    std::fs::write(&path, serde_json::to_string(&summary).unwrap()).unwrap();
    std::fs::write(d.join("stability.json"), "{\"schema\": 1, \"records\": [").unwrap();
    let out = d.join("report");
    let o = run(&[
        "report",
        "--summary",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{e}");
    assert!(e.contains("warning") && e.contains("stability.json"), "{e}");
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(!page.contains("data-section=\"stability"));
    assert!(out.join("summary.md").is_file());
}

/// `mbdbench --help` says what running without a command does (the main job).
#[test]
fn help_names_the_main_job() {
    let o = run(&["--help"]);
    assert_eq!(o.status.code(), Some(0));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("Without a command, mbdbench runs the main job"),
        "{text}"
    );
}
