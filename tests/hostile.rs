//! Bounded behaviour on hostile input and faults, through the command line: a closed
//! stdout (EPIPE) never panics and never changes the exit status or the files written; HTML in
//! a case or scene name is inert in `summary.md` as in `index.html`; summaries with duplicate
//! runs, impossible statuses or negative errors are unusable input naming the record, and so
//! are a malformed `methods` table or `families` list, naming the key.
mod common;

use std::path::Path;
use std::process::{Command, Stdio};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_mbdbench"))
}

/// Runs the binary with its stdout's reader already gone: returns the exit code and stderr.
fn with_closed_stdout(args: &[&str]) -> (Option<i32>, String) {
    let mut child = bin()
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // The parent held the only read end: every write of the child now fails with EPIPE.
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// A small quick run: one scene, one variant, one worker (`--out` to be added).
const SMALL_RUN: &[&str] = &[
    "run",
    "--quick",
    "--case",
    "nine_spring",
    "--scene",
    "two_angles",
    "--param",
    "so3",
    "--integrator",
    "rk4",
    "--formulation",
    "body",
    "--jobs",
    "1",
];

/// Makes the summary in `dir` the user's: the folder's manifest goes, so readers take a
/// hand-edited summary as it is (with the manifest they refuse it, `tests/interrupt.rs`).
fn own_summary(dir: &Path) {
    std::fs::remove_file(dir.join(mbdbench::output::MANIFEST)).unwrap();
}

/// A small quick run (one scene, one variant) into `dir`.
fn small_run(dir: &Path) {
    let o = bin()
        .args(SMALL_RUN)
        .arg("--out")
        .arg(dir)
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// Every command that prints to stdout ends with its normal status when stdout is closed:
/// no panic (exit 101), no exit 2, and its files are still written.
#[test]
fn closed_stdout_is_quiet() {
    let dir = common::temp_dir("epipe");
    let out = dir.join("run");
    let summary = out.join("summary.json");
    for (args, code) in [
        (vec!["list"], 0),
        (vec!["list", "--json"], 0),
        (vec!["reference", "--check", "--case", "nine_spring"], 0),
    ] {
        let (c, err) = with_closed_stdout(&args);
        assert_eq!(c, Some(code), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
    // `run` prints its table after writing the summary.
    let s_out = out.to_str().unwrap();
    let args: Vec<&str> = SMALL_RUN.iter().copied().chain(["--out", s_out]).collect();
    let (c, err) = with_closed_stdout(&args);
    assert_eq!(c, Some(0), "run: {err}");
    assert!(summary.is_file());
    let s = summary.to_str().unwrap();
    let (c, err) = with_closed_stdout(&["report", "--summary", s]);
    assert_eq!(c, Some(0), "report: {err}");
    assert!(out.join("index.html").is_file() && out.join("summary.md").is_file());
    let (c, err) = with_closed_stdout(&["gate", "--summary", s, "--quick"]);
    assert!(matches!(c, Some(0) | Some(1)), "gate: {c:?} {err}");
    assert!(!err.contains("panicked"), "gate: {err}");
}

/// HTML in a summary's case and scene names is escaped in `summary.md`, as in `index.html`:
/// no tag reaches the Markdown renderer.
#[test]
fn summary_md_escapes_names() {
    let dir = common::temp_dir("md-escape");
    small_run(&dir);
    let p = dir.join("summary.json");
    let text = std::fs::read_to_string(&p).unwrap();
    let hostile = text.replace("\"two_angles\"", "\"<img src=x onerror=alert(1)>\"");
    assert_ne!(hostile, text);
    std::fs::write(&p, hostile).unwrap();
    own_summary(&dir);
    let o = bin()
        .args(["report", "--summary"])
        .arg(&p)
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    for f in ["summary.md", "index.html"] {
        let t = std::fs::read_to_string(dir.join(f)).unwrap();
        assert!(!t.contains("<img"), "{f} holds a raw tag");
        assert!(t.contains("&lt;img"), "{f} lost the name");
    }
}

/// An edit of a summary's JSON.
type Edit = Box<dyn Fn(&mut serde_json::Value)>;

/// A summary with a run twice, a failed run without its failure, a failure on an ok run or a
/// negative error is unusable input: `gate` and `report` exit 2 naming the file and the
/// record, and `report` writes nothing.
#[test]
fn impossible_summaries_exit_2() {
    let dir = common::temp_dir("bad-summary");
    small_run(&dir);
    let p = dir.join("summary.json");
    let good: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&p).unwrap()).unwrap();
    let ok_index = good["records"]
        .as_array()
        .unwrap()
        .iter()
        .position(|r| r["status"] == "ok")
        .expect("an ok record");
    let edits: Vec<(&str, Edit)> = vec![
        (
            "is the same run as records[",
            Box::new(|s: &mut serde_json::Value| {
                let r = s["records"][0].clone();
                s["records"].as_array_mut().unwrap().push(r);
            }),
        ),
        (
            "status `failed` without a `failure`",
            Box::new(move |s: &mut serde_json::Value| {
                s["records"][ok_index]["status"] = "failed".into();
            }),
        ),
        (
            "a `failure` on a run that did not fail",
            Box::new(move |s: &mut serde_json::Value| {
                s["records"][ok_index]["failure"] =
                    serde_json::json!({"kind": "non_finite", "t": 0.5, "message": "x"});
            }),
        ),
        (
            "metric `rotation_error_max` is negative",
            Box::new(move |s: &mut serde_json::Value| {
                s["records"][ok_index]["metrics"]["rotation_error_max"] = (-1.0).into();
            }),
        ),
    ];
    refused_edits(&good, edits, &["gate", "report"], "bad-summary-case");
}

/// Each edit of `good`, written as a summary of its own (without a manifest), makes every
/// command of `cmds` exit 2 naming `summary.json` and saying the edit's text; `report`
/// writes nothing.
fn refused_edits(good: &serde_json::Value, edits: Vec<(&str, Edit)>, cmds: &[&str], tag: &str) {
    for (says, edit) in edits {
        let case = common::temp_dir(tag);
        let mut s = good.clone();
        edit(&mut s);
        let f = case.join("summary.json");
        std::fs::write(&f, serde_json::to_string_pretty(&s).unwrap()).unwrap();
        for cmd in cmds {
            let o = bin().args([cmd, "--summary"]).arg(&f).output().unwrap();
            let err = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{cmd} {says}: {err}");
            assert!(
                err.contains("summary.json") && err.contains(says),
                "{cmd}: {err}"
            );
        }
        assert!(!case.join("index.html").exists() && !case.join("summary.md").exists());
    }
}

/// A summary whose `methods` table is malformed (an unknown kind, a missing fact, a fact of
/// the wrong type, a twin of no entry), lacks the integrator of one of its records, or whose
/// `families` list repeats a family is unusable input: `gate`, `report` and `advise` exit 2
/// naming the file and the key. The same summary without the table and the list (as written
/// before they existed, like the committed baseline) is read as before.
#[test]
fn malformed_methods_tables_exit_2() {
    let dir = common::temp_dir("bad-methods");
    small_run(&dir);
    let good: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(good["methods"]["rk4"]["kind"], "explicit");
    assert_eq!(good["methods"]["gauss6_kahan"]["twin_of"], "gauss6");
    assert_eq!(good["families"][0], "rigid_body");
    let edits: Vec<(&str, Edit)> = vec![
        (
            "key `methods.rk4.kind` is \"magic\", expected one of `explicit`",
            Box::new(|s: &mut serde_json::Value| s["methods"]["rk4"]["kind"] = "magic".into()),
        ),
        (
            "key `methods.rk4.order` is missing",
            Box::new(|s: &mut serde_json::Value| {
                s["methods"]["rk4"].as_object_mut().unwrap().remove("order");
            }),
        ),
        (
            "key `methods.rk4.implicit` is \"no\", expected true or false",
            Box::new(|s: &mut serde_json::Value| s["methods"]["rk4"]["implicit"] = "no".into()),
        ),
        (
            "key `methods.gauss6_kahan.twin_of` is \"gauss7\", which has no entry",
            Box::new(|s: &mut serde_json::Value| {
                s["methods"]["gauss6_kahan"]["twin_of"] = "gauss7".into();
            }),
        ),
        (
            "key `integrator` is \"rk4\", which has no entry in `methods`",
            Box::new(|s: &mut serde_json::Value| {
                s["methods"].as_object_mut().unwrap().remove("rk4");
            }),
        ),
        (
            "key `families[1]`: `rigid_body` appears twice",
            Box::new(|s: &mut serde_json::Value| s["families"][1] = "rigid_body".into()),
        ),
    ];
    refused_edits(
        &good,
        edits,
        &["gate", "report", "advise"],
        "bad-methods-case",
    );
    let case = common::temp_dir("old-methods-case");
    let mut old = good.clone();
    let obj = old.as_object_mut().unwrap();
    obj.remove("methods");
    obj.remove("families");
    let f = case.join("summary.json");
    std::fs::write(&f, serde_json::to_string_pretty(&old).unwrap()).unwrap();
    for cmd in ["report", "advise"] {
        let o = bin().args([cmd, "--summary"]).arg(&f).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{cmd} without a table: {err}");
    }
}

/// Loading is at worst O(n log n) in the file size: a ladder of 1e6 distinct tolerances loads
/// (`list` exits 0) within the test's time, and a repeat in it is still found and named.
#[test]
fn huge_ladder_loads() {
    let old = "tol = [1.0e-4, 1.0e-6, 1.0e-8, 1.0e-10, 1.0e-12]";
    let n = 1_000_000;
    let list: Vec<String> = (0..n)
        .map(|k| format!("{:e}", 1e-3 * (1.0 - k as f64 / (2.0 * n as f64))))
        .collect();
    for (tag, values, code) in [
        ("ladder-1e6", list.join(", "), 0),
        ("ladder-1e6-repeat", format!("{}, 1e-3", list.join(", ")), 2),
    ] {
        let dir = common::cases_with(tag, "nine_spring.toml", |t| {
            common::replace_once(t, old, &format!("tol = [{values}]"))
        });
        let o = bin().args(["list", "--cases"]).arg(&dir).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(code), "{tag}: {err}");
        if code == 2 {
            assert!(
                err.contains(&format!("tol[{n}]")) && err.contains("appears twice"),
                "{err}"
            );
        }
    }
}

/// Runs the binary, killing it after `guard_s` (a hang guard, not a timing assertion):
/// returns the exit code (None when killed or signalled) and stderr.
fn run_guarded(args: &[&std::ffi::OsStr], guard_s: u64) -> (Option<i32>, String) {
    let mut child = bin()
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = std::time::Instant::now();
    loop {
        if let Some(_status) = child.try_wait().unwrap() {
            let o = child.wait_with_output().unwrap();
            return (
                o.status.code(),
                String::from_utf8_lossy(&o.stderr).into_owned(),
            );
        }
        if t0.elapsed().as_secs() > guard_s {
            child.kill().unwrap();
            let _ = child.wait();
            return (None, "killed by the hang guard".into());
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
}

/// `report` reads series only from inside the summary's folder: a record whose `series` is
/// `/dev/zero` (an endless file) or leaves the folder (`../..`) is drawn as "no series file",
/// and the report completes.
#[test]
fn report_reads_series_only_inside_its_folder() {
    let dir = common::temp_dir("series-escape");
    small_run(&dir);
    std::fs::remove_dir_all(dir.join("series")).unwrap();
    let p = dir.join("summary.json");
    let mut s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&p).unwrap()).unwrap();
    for (k, r) in s["records"].as_array_mut().unwrap().iter_mut().enumerate() {
        r["series"] = if k % 2 == 0 {
            "/dev/zero"
        } else {
            "../../../../dev/zero"
        }
        .into();
    }
    std::fs::write(&p, serde_json::to_string_pretty(&s).unwrap()).unwrap();
    own_summary(&dir);
    let (code, err) = run_guarded(
        &["report".as_ref(), "--summary".as_ref(), p.as_os_str()],
        120,
    );
    assert_eq!(code, Some(0), "{err}");
    let md = std::fs::read_to_string(dir.join("index.html")).unwrap();
    assert!(
        md.contains("no series file"),
        "the missing series are not named"
    );
}

/// `--jobs 0` means every core and a request far above the core count is clamped with a
/// notice: the run completes and records at most the machine's cores as its threads.
#[test]
fn jobs_are_clamped() {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    for jobs in ["0", "100000"] {
        let dir = common::temp_dir(&format!("jobs-{jobs}"));
        // The small run with its worker count replaced by `jobs`.
        let n = SMALL_RUN.len();
        let tail = [jobs, "--out"];
        let args: Vec<&std::ffi::OsStr> = SMALL_RUN[..n - 1]
            .iter()
            .chain(&tail)
            .map(|s| s.as_ref())
            .chain([dir.as_os_str()])
            .collect();
        let (code, err) = run_guarded(&args, 300);
        assert_eq!(code, Some(0), "--jobs {jobs}: {err}");
        if jobs != "0" {
            assert!(err.contains("more than the"), "{err}");
        }
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(
            s["env"]["threads"].as_u64(),
            Some(cores as u64),
            "--jobs {jobs}"
        );
    }
}

/// A copy of the stored references with `nine_spring/two_angles.json` edited.
fn references_with(tag: &str, edit: &dyn Fn(&mut serde_json::Value)) -> std::path::PathBuf {
    let dir = common::copy_references(tag);
    let p = dir.join("nine_spring/two_angles.json");
    let mut r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&p).unwrap()).unwrap();
    edit(&mut r);
    std::fs::write(&p, serde_json::to_string_pretty(&r).unwrap()).unwrap();
    dir
}

/// A reference that would read as perfect or as another grid is refused on load, by
/// `reference --check` and by `run`, with an error naming the file and the key: zero
/// quaternions, a shifted or short time grid, an absurd accuracy claim.
#[test]
fn hostile_references_are_refused() {
    let cases: Vec<(&str, &str, Edit)> = vec![
        (
            "ref-zero-q",
            "`quaternion[0]` has norm 0",
            Box::new(|r: &mut serde_json::Value| {
                for q in r["quaternion"].as_array_mut().unwrap() {
                    *q = serde_json::json!([0.0, 0.0, 0.0, 0.0]);
                }
            }),
        ),
        (
            "ref-shifted-t",
            "`t[0]` is 0.001",
            Box::new(|r: &mut serde_json::Value| {
                for t in r["t"].as_array_mut().unwrap() {
                    *t = (t.as_f64().unwrap() + 1e-3).into();
                }
            }),
        ),
        (
            "ref-short",
            "key `t` has 100 samples; expected 101",
            Box::new(|r: &mut serde_json::Value| {
                for key in [
                    "t",
                    "position",
                    "quaternion",
                    "velocity",
                    "omega_body",
                    "energy",
                ] {
                    r[key].as_array_mut().unwrap().pop();
                }
            }),
        ),
        (
            "ref-claim",
            "`accuracy_claim.rotation` is 1e308",
            Box::new(|r: &mut serde_json::Value| {
                r["accuracy_claim"]["rotation"] = 1e308.into();
            }),
        ),
    ];
    for (tag, says, edit) in cases {
        let refs = references_with(tag, &*edit);
        let runs = [
            vec![
                "reference",
                "--check",
                "--case",
                "nine_spring",
                "--scene",
                "two_angles",
            ],
            SMALL_RUN.to_vec(),
        ];
        for args in runs {
            let out = common::temp_dir(&format!("{tag}-out"));
            let o = bin()
                .args(&args)
                .arg("--references")
                .arg(&refs)
                .args(if args[0] == "run" {
                    vec!["--out"]
                } else {
                    vec![]
                })
                .args(if args[0] == "run" {
                    vec![out.as_os_str()]
                } else {
                    vec![]
                })
                .output()
                .unwrap();
            let err = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{tag} {}: {err}", args[0]);
            assert!(
                err.contains("two_angles.json") && err.contains(says),
                "{tag}: {err}"
            );
            assert!(
                !out.join("summary.json").exists(),
                "{tag}: output left behind"
            );
        }
    }
}

/// Fixed-length arrays are exactly that length: extra elements of any type, a missing one, a
/// fourth inertia row or a short row are bad input naming the key (they were dropped or
/// truncated silently).
#[test]
fn fixed_arrays_have_their_length() {
    let euler = "euler_xyz = [0.0, 0.5, 1.0]";
    let inertia = "inertia = [[800.0, -60.0, 40.0], [-60.0, 1000.0, -80.0], [40.0, -80.0, 1200.0]]";
    for (tag, old, new, says) in [
        (
            "arr-long",
            euler,
            "euler_xyz = [0.0, 0.5, 1.0, 99.0, \"junk\", [1, 2]]",
            "euler_xyz: invalid length 6",
        ),
        (
            "arr-short",
            euler,
            "euler_xyz = [0.0, 0.5]",
            "euler_xyz: invalid length 2",
        ),
        (
            "arr-rows",
            inertia,
            "inertia = [[800.0, -60.0, 40.0], [-60.0, 1000.0, -80.0], [40.0, -80.0, 1200.0], [1.0, 1.0, 1.0]]",
            "body.inertia: invalid length 4",
        ),
        (
            "arr-row",
            inertia,
            "inertia = [[800.0, -60.0, 40.0], [-60.0, 1000.0], [40.0, -80.0, 1200.0]]",
            "invalid length 2",
        ),
    ] {
        let dir = common::cases_with(tag, "nine_spring.toml", |t| {
            common::replace_once(t, old, new)
        });
        let o = bin().args(["list", "--cases"]).arg(&dir).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{tag}: {err}");
        assert!(
            err.contains("nine_spring.toml") && err.contains(says),
            "{tag}: {err}"
        );
        assert!(o.stdout.is_empty(), "{tag}: output on exit 2");
    }
}

/// An output folder that cannot be written (here: below a regular file, which binds root
/// too) is bad input found before any run (exit 2 naming it, nothing computed), and
/// `reference` into it names the file it could not write.
#[test]
fn unwritable_outputs_are_named_up_front() {
    let dir = common::temp_dir("unwritable");
    let file = dir.join("a_file");
    std::fs::write(&file, b"not a folder").unwrap();
    let out = file.join("out");
    for cmd in ["run", "stability"] {
        let o = bin()
            .args([
                cmd,
                "--quick",
                "--case",
                "nine_spring",
                "--scene",
                "two_angles",
            ])
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{cmd}: {err}");
        assert!(
            err.contains("not writable") && err.contains("a_file/out"),
            "{cmd}: {err}"
        );
        assert!(
            !err.contains("runs") && !err.contains("searches"),
            "{cmd} ran: {err}"
        );
    }
    let o = bin()
        .args([
            "reference",
            "--case",
            "nine_spring",
            "--scene",
            "two_angles",
            "--references",
        ])
        .arg(&file)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "reference: {err}");
    assert!(
        err.contains("a_file/nine_spring/two_angles.json"),
        "reference: {err}"
    );
}

/// Memory is bounded by the sample budget (`case::MAX_SAMPLES`, 1e6 samples a run): a
/// `--t-end` or a case `sample_every` that would keep more is refused before any run, exit 2
/// naming the option or key (`--t-end 1e6` kept 1e8 samples, past 14 GB).
#[test]
fn sample_budget_is_enforced_up_front() {
    let dir = common::temp_dir("budget");
    for cmd in [
        vec![
            "run",
            "--quick",
            "--case",
            "gimbal_lock",
            "--scene",
            "spin_d0",
            "--param",
            "so3",
            "--integrator",
            "rk4",
            "--t-end",
            "1e6",
            "--out",
        ],
        vec![
            "trajectory",
            "--case",
            "gimbal_lock",
            "--scene",
            "spin_d0",
            "--param",
            "so3",
            "--integrator",
            "rk4",
            "--dt",
            "1e-2",
            "--t-end",
            "1e6",
            "--out",
        ],
    ] {
        let out = dir.join(cmd[0]);
        let o = bin().args(&cmd).arg(&out).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{}: {err}", cmd[0]);
        assert!(
            err.contains("--t-end 1000000") && err.contains("at most 1000000"),
            "{err}"
        );
        assert!(!out.exists(), "{}: output left behind", cmd[0]);
    }
    let cases = common::cases_with("budget-case", "nine_spring.toml", |t| {
        common::replace_once(t, "sample_every = 0.01", "sample_every = 1e-7")
    });
    let o = bin()
        .args(["list", "--cases"])
        .arg(&cases)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("sample_every") && err.contains("at most 1000000"),
        "{err}"
    );
}

/// `reference --check` compares the energy column too: an energy column that does not belong
/// to the stored states (here 1 % too large) fails the check (exit 1, `FAIL`).
#[test]
fn reference_check_compares_energy() {
    let refs = references_with("ref-energy", &|r: &mut serde_json::Value| {
        for e in r["energy"].as_array_mut().unwrap() {
            *e = (e.as_f64().unwrap() * 1.01).into();
        }
    });
    let o = bin()
        .args([
            "reference",
            "--check",
            "--case",
            "nine_spring",
            "--scene",
            "two_angles",
        ])
        .arg("--references")
        .arg(&refs)
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        o.status.code(),
        Some(1),
        "{out} {}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        out.contains("FAIL nine_spring/two_angles") && out.contains("energy column"),
        "{out}"
    );
}

/// A diverging adaptive run ends within its RHS budget: `se3_hq/dopri5` at `tol = 0.5` on
/// `nine_spring/two_angles` blows up near t = 6 s and crawled on steps of 1e-7 s to its 1e8-step
/// budget (7.8e8 evaluations, 413 s); it now ends as a typed `work_limit` (or
/// `step_size_underflow`) within the default adaptive budget of 1e6 evaluations, and the
/// timing pass does not run it again (`wall_s` is null).
#[test]
fn diverging_adaptive_run_is_bounded() {
    let cases = common::cases_with("diverging-case", "nine_spring.toml", |t| {
        common::replace_once(t, "tol = [1.0e-6] }", "tol = [0.5] }")
    });
    let out = common::temp_dir("diverging-out");
    let o = bin()
        .args([
            "run",
            "--quick",
            "--case",
            "nine_spring",
            "--scene",
            "two_angles",
        ])
        .args([
            "--param",
            "se3_hq",
            "--integrator",
            "dopri5",
            "--formulation",
            "body",
        ])
        .args(["--jobs", "1", "--verbose", "--cases"])
        .arg(&cases)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    // A typed failure is a result, not a fault of the command: exit 0.
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    let s: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    let recs = s["records"].as_array().unwrap();
    assert_eq!(recs.len(), 1);
    let r = &recs[0];
    let kind = r["failure"]["kind"].as_str().unwrap();
    assert!(kind == "work_limit" || kind == "step_size_underflow", "{r}");
    let evals = r["stats"]["rhs_evals"].as_u64().unwrap();
    assert!(evals <= 1_000_000, "{evals} RHS evaluations");
    assert!(r["wall_s"].is_null(), "a failed run was timed: {r}");
    // The terminal table names the kind as the files do (it printed `WorkLimit`).
    let table = String::from_utf8_lossy(&o.stdout);
    assert!(table.contains(&format!("failed {kind} t=")), "{table}");
    // So does the one line per case.
    assert!(table.contains(&format!("(1 {kind})")), "{table}");
}
