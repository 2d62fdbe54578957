//! The binary layer: `mbdbench` on mutated case files and hostile arguments. Checks that a bad
//! case file or argument exits 2 naming the file and the key and writes nothing, that other
//! runs exit 0 or 1 with complete output files, and that an output that cannot be put in place
//! leaves neither a partial target nor a temporary file.
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use mbdbench::case;
use proptest::prelude::*;

use crate::mutate::{apply, mutation, value};
use crate::{PROCESS_DEADLINE, all_files, config, fresh_dir, temp_files};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_mbdbench"))
}

/// Runs the binary, killing it (and failing) past `PROCESS_DEADLINE`.
fn run_bin(args: &[&str]) -> Output {
    let mut child = bin()
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        if t0.elapsed() > PROCESS_DEADLINE {
            let _ = child.kill();
            let o = child.wait_with_output().unwrap();
            panic!(
                "mbdbench {args:?} hung ({:?}); stderr: {}",
                PROCESS_DEADLINE,
                String::from_utf8_lossy(&o.stderr)
            );
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

proptest! {
    #![proptest_config(config(32))]

    /// `mbdbench run` on a mutated case file exits 2 naming the file and the key and writes
    /// nothing when the file is bad (as `catalogue::load_dir` reports it); otherwise it runs (or
    /// refuses a stale reference, exit 2, writing nothing) and leaves only complete files.
    #[test]
    fn binary_bad_case_file_exits_2_and_writes_nothing(
        which in 0usize..4,
        muts in prop::collection::vec(mutation(), 1..=3),
    ) {
        let (label, text) = case::embedded_sources()[which];
        let file = Path::new(label).file_name().unwrap().to_str().unwrap();
        let stem = file.trim_end_matches(".toml");
        let mut t = text.to_string();
        for m in &muts {
            t = apply(&t, m);
        }
        let dir = fresh_dir("fuzz-bin");
        std::fs::write(dir.join(file), &t).unwrap();
        let out = dir.join("out");
        let expected = mbdbench::catalogue::load_dir(&dir);
        let o = run_bin(&[
            "run", "--quick", "--cases", dir.to_str().unwrap(), "--out", out.to_str().unwrap(),
            "--case", stem, "--param", "so3", "--integrator", "rk4", "--integrator", "dopri5",
            "--formulation", "body",
        ]);
        let e = stderr(&o);
        match expected {
            Err(err) => {
                prop_assert_eq!(o.status.code(), Some(2), "{}", e);
                // The binary writes control characters escaped (`quiet::terminal_safe`): a
                // mutation can put one into the error's quoted text.
                let want = mbdbench::quiet::terminal_safe(&err.to_string()).into_owned();
                prop_assert!(e.contains(&want), "expected `{}` in `{}`", want, e);
                prop_assert!(all_files(&out).is_empty(), "wrote {:?}", all_files(&out));
            }
            Ok(_) => match o.status.code() {
                Some(0) => {
                    let s = std::fs::read_to_string(out.join("summary.json")).unwrap();
                    let _: mbdbench::summary::Summary = serde_json::from_str(&s).unwrap();
                    prop_assert!(temp_files(&out).is_empty());
                }
                Some(2) => {
                    prop_assert!(e.contains(file) || e.contains("references"), "{}", e);
                    prop_assert!(all_files(&out).is_empty(), "wrote {:?}", all_files(&out));
                }
                c => prop_assert!(false, "exit {:?}: {}", c, e),
            },
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// `mbdbench trajectory` with hostile step, tolerance and horizon arguments exits 2 and
    /// writes nothing, or exits 0 or 1 having written the whole trajectory file; it never
    /// crashes or hangs.
    #[test]
    fn binary_trajectory_hostile_arguments(
        integ in prop::sample::select(&["rk4", "euler", "gauss6", "dop853", "simo_wong"][..]),
        value in prop_oneof![
            Just("0.01".to_string()), Just("0.001".to_string()), Just("1e-8".to_string()),
            value(),
        ],
        t_end in prop::option::of(prop_oneof![
            prop::sample::select(&["3.2", "0.01", "1e-9", "1e9", "1e13", "1e300", "nan",
                "-1", "0", "inf"][..]).prop_map(str::to_string),
            value(),
        ]),
    ) {
        let dir = fresh_dir("fuzz-traj");
        let f = dir.join("t.json");
        let flag = if integ.starts_with("dop") { "--tol" } else { "--dt" };
        let mut args = vec![
            "trajectory", "--case", "gimbal_lock", "--scene", "spin_d1e-2", "--param", "so3",
            "--integrator", integ, flag, value.as_str(), "--out", f.to_str().unwrap(),
        ];
        if let Some(t) = &t_end {
            args.extend(["--t-end", t.as_str()]);
        }
        let o = run_bin(&args);
        let e = stderr(&o);
        match o.status.code() {
            Some(2) => prop_assert!(all_files(&dir).is_empty(), "{}: wrote {:?}", e,
                all_files(&dir)),
            Some(c @ (0 | 1)) => {
                let doc: serde_json::Value =
                    serde_json::from_slice(&std::fs::read(&f).unwrap()).unwrap();
                prop_assert_eq!(doc["status"] == "failed", c == 1, "{}", doc["status"]);
                prop_assert!(temp_files(&dir).is_empty());
            }
            c => prop_assert!(false, "exit {:?}: {}", c, e),
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// An output whose final rename fails (the target is a folder) leaves neither a partial
/// target nor the temporary file, and a completed write leaves exactly the target.
#[test]
fn write_atomic_is_all_or_nothing() {
    let dir = fresh_dir("fuzz-atomic");
    let target = dir.join("summary.json");
    std::fs::create_dir_all(&target).unwrap();
    assert!(mbdbench::reference::write_atomic(&target, b"{}").is_err());
    assert!(target.is_dir());
    assert_eq!(all_files(&dir), Vec::<PathBuf>::new());
    let ok = dir.join("sub").join("x.json");
    mbdbench::reference::write_atomic(&ok, b"[1]").unwrap();
    assert_eq!(std::fs::read(&ok).unwrap(), b"[1]");
    assert_eq!(all_files(&dir), vec![ok]);
    // A parent that is a file: an error, nothing written.
    let blocked = dir.join("sub").join("x.json").join("y.json");
    assert!(mbdbench::reference::write_atomic(&blocked, b"{}").is_err());
    assert_eq!(all_files(&dir).len(), 1);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `mbdbench run` whose summary cannot be put in place (its path is a folder) fails with
/// exit 2 naming the path and leaves no temporary file; no `summary.json` appears.
#[test]
fn binary_unwritable_summary_leaves_no_partial_file() {
    let dir = fresh_dir("fuzz-unwritable");
    let out = dir.join("out");
    std::fs::create_dir_all(out.join("summary.json")).unwrap();
    let o = run_bin(&[
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
        "--formulation",
        "body",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("summary.json"), "{}", stderr(&o));
    assert!(out.join("summary.json").is_dir());
    assert!(temp_files(&out).is_empty(), "{:?}", temp_files(&out));
    let _ = std::fs::remove_dir_all(&dir);
}
