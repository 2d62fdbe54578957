//! The budgets through the command line (cases/README.md, "Budgets"): a case file whose
//! numbers ask for more memory, steps or work than its budgets allow is refused by `list`
//! (exit 2, naming the file and the key) before anything large is allocated; a budget key
//! above its hard cap is refused, one raised within it lets the case load; a runaway Newton
//! iteration ends as a typed `work_limit` naming the key; a `--dt` too small for the step
//! budget exits 2 and writes nothing in every model family; a beam reference whose
//! provenance names another mesh than its case's is refused by `reference --check`.
//!
//! Each command runs under a hang guard (killed after 60 s: a guard against a regression
//! that runs for hours, not a timing assertion) with its address space capped, so a
//! regression that allocates gigabytes fails here instead of taking the machine down.
mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// The binary with its address space limited to 2 GiB (`ulimit -v`, through the shell; a
/// system that refuses the limit runs it without).
fn capped(args: &[&str]) -> Command {
    let mut c = Command::new("sh");
    c.arg("-c")
        .arg("ulimit -v 2097152 2>/dev/null; exec \"$0\" \"$@\"")
        .arg(env!("CARGO_BIN_EXE_mbdbench"))
        .args(args);
    c
}

/// Runs `args` under the caps: the exit code (None when killed) and stderr.
fn run_guarded(args: &[&str]) -> (Option<i32>, String) {
    let mut child = capped(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = std::time::Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            let o = child.wait_with_output().unwrap();
            return (
                o.status.code(),
                String::from_utf8_lossy(&o.stderr).into_owned(),
            );
        }
        if t0.elapsed().as_secs() > 60 {
            child.kill().unwrap();
            let _ = child.wait();
            return (None, "killed by the hang guard".into());
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

/// A cases folder holding `file` with each `(old, new)` replaced once.
fn mutated(tag: &str, file: &str, edits: &[(&str, &str)]) -> PathBuf {
    common::cases_with(tag, file, |t| {
        edits.iter().fold(t.to_string(), |t, (old, new)| {
            common::replace_once(&t, old, new)
        })
    })
}

fn list(dir: &Path) -> (Option<i32>, String) {
    run_guarded(&["list", "--cases", dir.to_str().unwrap()])
}

/// A mutation of a case file: a tag, the replacements, the key its refusal names.
type Mutation<'a> = (&'a str, &'a [(&'a str, &'a str)], &'a str);

const CYCLIC: &str = "fiber_column_cyclic.toml";
const DRIFTS: &str = "drifts = [0.0025, 0.005, 0.01, 0.015, 0.02, 0.03, 0.04]";
const EXTERNAL: &str = "reference = \"external\"\n";

/// `list` refuses the mutated fiber column cases that used to abort or run for hours (a
/// 384 GB protocol, 28.8 GB of tangent, a million fibers, an infinite element length, a
/// prelude past `max_steps`, a Newton limit of 1e9), exit 2, naming the file and the key.
#[test]
fn list_refuses_cases_over_their_budgets() {
    let prelude = "reference = \"external\"\nmax_steps = 6000\n";
    let cases: [Mutation; 6] = [
        ("drifts", &[(DRIFTS, "drifts = [1.0e6]")], "scene[0].t_end"),
        (
            "elements",
            &[("elements = 1\n", "elements = 1.0e4\n")],
            "numerics.elements",
        ),
        (
            "fibers",
            &[("ny = 16, nz = 2 }", "ny = 1000, nz = 1000 }")],
            "section.patches[0].ny",
        ),
        (
            "height",
            &[("height = 3.0\n", "height = 1.0e300\n")],
            "column.height",
        ),
        (
            "prelude",
            &[
                ("axial_steps = 10,", "axial_steps = 1.0e6,"),
                (EXTERNAL, prelude),
            ],
            "scene[0].load.axial_steps",
        ),
        (
            "newton",
            &[(
                "tol = 1.0e-20\nmax_iter = 50",
                "tol = 1.0e-300\nmax_iter = 1.0e9",
            )],
            "numerics.max_iter",
        ),
    ];
    for (tag, edits, key) in cases {
        let dir = mutated(&format!("budget-list-{tag}"), CYCLIC, edits);
        let (code, err) = list(&dir);
        assert_eq!(code, Some(2), "{tag}: {err}");
        let file = dir.join(CYCLIC);
        assert!(
            err.contains(&format!("{}: {key}: ", file.display())),
            "{tag}: {err}"
        );
        if tag == "drifts" {
            assert!(err.contains("48000000000 increments"), "{err}");
        }
    }
}

/// A budget key above its hard cap is refused naming it; within the cap, raising
/// `max_work` lets a case its default refuses load (a 30-element force-based column on the
/// cyclic protocol, about 3.4e10 work units), and the beam's former limit of 10,000
/// elements is refused by its memory estimate.
#[test]
fn hard_caps_and_raised_budgets() {
    let over = mutated(
        "budget-cap",
        CYCLIC,
        &[(EXTERNAL, "reference = \"external\"\nmax_steps = 1.0e11\n")],
    );
    let (code, err) = list(&over);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains(": max_steps: ") && err.contains("hard cap"),
        "{err}"
    );
    let mesh = [("elements = 1\n", "elements = 30\n")];
    let (code, err) = list(&mutated("budget-mesh", CYCLIC, &mesh));
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("max_work"), "{err}");
    let raised = [
        mesh[0],
        (EXTERNAL, "reference = \"external\"\nmax_work = 1.0e11\n"),
    ];
    let (code, err) = list(&mutated("budget-raised", CYCLIC, &raised));
    assert_eq!(code, Some(0), "{err}");
    let beam = [("elements = 10\n", "elements = 10000\n")];
    let (code, err) = list(&mutated("budget-beam", "flexible_beam.toml", &beam));
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("numerics.elements") && err.contains("max_memory_mib"),
        "{err}"
    );
}

/// A Newton tolerance no step meets, with a run budget of 300 state determinations and
/// element iterations, ends `trajectory` as a typed `work_limit` naming the key (exit 1, the
/// file holding the failure).
#[test]
fn runaway_newton_ends_as_a_typed_work_limit() {
    let edits = [
        (
            "tol = 1.0e-20\nmax_iter = 50",
            "tol = 1.0e-300\nmax_iter = 1000",
        ),
        (EXTERNAL, "reference = \"external\"\nmax_rhs_evals = 300\n"),
    ];
    let dir = mutated("budget-runaway", CYCLIC, &edits);
    let out = dir.join("t.json");
    let (code, err) = run_guarded(&[
        "trajectory",
        "--cases",
        dir.to_str().unwrap(),
        "--case",
        "fiber_column_cyclic",
        "--scene",
        "rc_cyclic_c01",
        "--param",
        "so3",
        "--integrator",
        "newton_disp_krylov",
        "--dt",
        "5",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(1), "{err}");
    let doc: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(doc["failure"]["kind"], "work_limit", "{doc}");
    assert!(err.contains("max_rhs_evals = 300"), "{err}");
}

/// A `--dt` whose run would take more than `max_steps` steps exits 2 and writes nothing, in
/// every model family (the beam and the rigid body used to start the run and fail it with
/// exit 1, the fiber column to refuse it with exit 2).
#[test]
fn a_too_small_step_is_refused_alike_in_every_family() {
    let dir = common::temp_dir("budget-dt");
    let runs: [&[&str]; 4] = [
        &[
            "--case",
            "flexible_beam",
            "--scene",
            "spinup_w4",
            "--integrator",
            "newmark",
        ],
        &[
            "--case",
            "nine_spring",
            "--scene",
            "two_angles",
            "--param",
            "so3",
            "--integrator",
            "rk4",
        ],
        &[
            "--case",
            "fiber_column_dynamic",
            "--scene",
            "rc_pulse",
            "--param",
            "so3",
            "--integrator",
            "newmark",
        ],
        &[
            "--case",
            "fiber_column_static",
            "--scene",
            "elastica_p1",
            "--param",
            "so3",
            "--integrator",
            "newton_load",
        ],
    ];
    for (i, run) in runs.iter().enumerate() {
        let out = dir.join(format!("t{i}.json"));
        let mut args = vec!["trajectory"];
        args.extend_from_slice(run);
        args.extend(["--dt", "1e-12", "--out", out.to_str().unwrap()]);
        let (code, err) = run_guarded(&args);
        assert_eq!(code, Some(2), "{}: {err}", run[1]);
        assert!(err.contains("more than max_steps = 100000000"), "{err}");
        assert!(!out.exists(), "{}: wrote {}", run[1], out.display());
    }
}

/// Copies the folder `from` to `to`, recursively.
fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let p = entry.unwrap().path();
        let target = to.join(p.file_name().unwrap());
        if p.is_dir() {
            copy_tree(&p, &target);
        } else {
            std::fs::copy(&p, &target).unwrap();
        }
    }
}

/// `reference --check` of a beam reference whose provenance names another mesh than the
/// case's (10,000 elements: the recomputation would have held 21 GB and aborted) is refused
/// before any run, exit 2, naming the file.
#[test]
fn a_reference_naming_another_mesh_is_refused() {
    let dir = common::temp_dir("budget-reference");
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("references");
    copy_tree(&root, &dir);
    let file = dir.join("flexible_beam").join("spinup_w4.json");
    let mut doc: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&file).unwrap()).unwrap();
    doc["provenance"]["elements"] = serde_json::json!(10000);
    std::fs::write(&file, serde_json::to_vec(&doc).unwrap()).unwrap();
    let (code, err) = run_guarded(&[
        "reference",
        "--check",
        "--case",
        "flexible_beam",
        "--scene",
        "spinup_w4",
        "--references",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("spinup_w4.json") && err.contains("10000 elements"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
