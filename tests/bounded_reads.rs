//! Input files are read with limits, through the command line (`src/read_limited.rs`):
//! references and their manifest only as regular files inside the references folder, summaries,
//! baselines, `stability.json` and output manifests only as regular files, each of at most its
//! kind's cap. A link to `/dev/zero`, a FIFO, a link out of the folder and an oversize (sparse)
//! file are each refused at once, the file named; before, `/dev/zero` was read to 1 GB and a
//! FIFO blocked forever. Every run has a hang guard, so a regression fails instead of hanging.
#![cfg(unix)]
mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Runs the binary with `args`, killing it after 60 s (a hang guard, not a timing assertion):
/// the exit code (None when killed) and its stdout and stderr.
fn run_guarded(args: &[&std::ffi::OsStr]) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if t0.elapsed() > Duration::from_secs(60) {
            child.kill().unwrap();
            let _ = child.wait();
            return (None, "killed by the hang guard".into());
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let o = child.wait_with_output().unwrap();
    (o.status.code(), common::text(&o))
}

/// Makes a FIFO at `p`.
fn mkfifo(p: &Path) {
    let ok = Command::new("mkfifo").arg(p).status().unwrap();
    assert!(ok.success(), "mkfifo {}", p.display());
}

/// The four ways a file can be hostile: what to put at `p`, and what the refusal says.
fn tamper(p: &Path, how: &str, outside: &Path) -> &'static str {
    let _ = std::fs::remove_file(p);
    match how {
        "dev-zero" => {
            // Outside the references folder, so refused for that before its type is looked at.
            std::os::unix::fs::symlink("/dev/zero", p).unwrap();
            "resolves to /dev/zero"
        }
        "fifo" => {
            mkfifo(p);
            "FIFO"
        }
        "escape" => {
            std::os::unix::fs::symlink(outside, p).unwrap();
            "outside the folder"
        }
        "oversize" => {
            let f = std::fs::File::create(p).unwrap();
            // Past both caps (a reference's and a manifest's): the error names the cap's constant.
            f.set_len(mbdbench::read_limited::REFERENCE.cap + 1)
                .unwrap();
            "read_limited::"
        }
        _ => unreachable!(),
    }
}

/// `reference --check` on a copy of the references whose OpenSees reference, or its
/// `MANIFEST.json`, is a link to `/dev/zero`, a FIFO, a link to a copy outside the folder or
/// a sparse file past the cap: FAIL (exit 1) naming the file and why, within the guard.
#[test]
fn reference_check_refuses_hostile_files() {
    let refs = common::copy_references("bounded-opensees");
    let dir = refs.join("fiber_column/opensees");
    let outside = common::temp_dir("bounded-outside");
    for name in ["rc_cyclic_c01.json", "MANIFEST.json"] {
        let p = dir.join(name);
        let keep = outside.join(name);
        std::fs::copy(&p, &keep).unwrap();
        for how in ["dev-zero", "fifo", "escape", "oversize"] {
            let says = tamper(&p, how, &keep);
            let (code, out) = run_guarded(&[
                "reference".as_ref(),
                "--check".as_ref(),
                "--case".as_ref(),
                "fiber_column_cyclic".as_ref(),
                "--scene".as_ref(),
                "rc_cyclic_c01".as_ref(),
                "--references".as_ref(),
                refs.as_os_str(),
            ]);
            assert_eq!(code, Some(1), "{name} {how}: {out}");
            assert!(out.contains("FAIL"), "{name} {how}: {out}");
            assert!(
                out.contains(&p.display().to_string()) && out.contains(says),
                "{name} {how}: {out}"
            );
        }
        std::fs::remove_file(&p).unwrap();
        std::fs::copy(&keep, &p).unwrap();
    }
    let _ = std::fs::remove_dir_all(&refs);
    let _ = std::fs::remove_dir_all(&outside);
}

/// A stored reference that is a FIFO or a link out of the references folder is bad input to
/// `run` (exit 2 naming it, no summary written), and `reference --check` names it too.
#[test]
fn run_refuses_hostile_stored_reference() {
    let refs = common::copy_references("bounded-stored");
    let out = common::temp_dir("bounded-stored-out").join("run");
    let p = refs.join("nine_spring/two_angles.json");
    let keep = common::temp_dir("bounded-stored-keep").join("two_angles.json");
    std::fs::copy(&p, &keep).unwrap();
    for how in ["fifo", "escape"] {
        let says = tamper(&p, how, &keep);
        let (code, text) = run_guarded(&[
            "run".as_ref(),
            "--quick".as_ref(),
            "--case".as_ref(),
            "nine_spring".as_ref(),
            "--scene".as_ref(),
            "two_angles".as_ref(),
            "--integrator".as_ref(),
            "rk4".as_ref(),
            "--references".as_ref(),
            refs.as_os_str(),
            "--out".as_ref(),
            out.as_os_str(),
        ]);
        assert_eq!(code, Some(2), "run {how}: {text}");
        assert!(
            text.contains("two_angles.json") && text.contains(says),
            "run {how}: {text}"
        );
        assert!(!out.join("summary.json").exists(), "run {how}: output left");
        let (code, text) = run_guarded(&[
            "reference".as_ref(),
            "--check".as_ref(),
            "--case".as_ref(),
            "nine_spring".as_ref(),
            "--scene".as_ref(),
            "two_angles".as_ref(),
            "--references".as_ref(),
            refs.as_os_str(),
        ]);
        assert!(matches!(code, Some(1) | Some(2)), "check {how}: {text}");
        assert!(
            text.contains("two_angles.json") && text.contains(says),
            "check {how}: {text}"
        );
    }
    let _ = std::fs::remove_dir_all(&refs);
}

/// A scratch folder holding a copy of the quick baseline as `summary.json`.
fn summary_copy(tag: &str) -> PathBuf {
    let d = common::temp_dir(tag);
    let src = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("reports/baseline/quick.json");
    std::fs::copy(src, d.join("summary.json")).unwrap();
    d
}

/// `gate` refuses, exit 2 naming the file, a `--summary` that links to `/dev/zero` or is a
/// sparse file past `read_limited::SUMMARY`, a `--baseline` that is a FIFO, and a
/// `stability.json` or output manifest beside the summary that is a FIFO.
#[test]
fn gate_refuses_hostile_summaries() {
    let d = summary_copy("bounded-gate");
    let summary = d.join("summary.json");
    let zero = d.join("zero.json");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let big = d.join("big.json");
    std::fs::File::create(&big)
        .unwrap()
        .set_len(mbdbench::read_limited::SUMMARY.cap + 1)
        .unwrap();
    let fifo = d.join("baseline.json");
    mkfifo(&fifo);
    let gate = |summary: &Path, extra: &[&Path]| {
        let mut args: Vec<&std::ffi::OsStr> =
            vec!["gate".as_ref(), "--quick".as_ref(), "--summary".as_ref()];
        args.push(summary.as_os_str());
        if let Some(b) = extra.first() {
            args.extend(["--baseline".as_ref(), b.as_os_str()]);
        }
        run_guarded(&args)
    };
    for (args, file, says) in [
        ((zero.as_path(), vec![]), &zero, "character device"),
        ((big.as_path(), vec![]), &big, "read_limited::SUMMARY"),
        ((summary.as_path(), vec![fifo.as_path()]), &fifo, "FIFO"),
    ] {
        let (code, text) = gate(args.0, &args.1);
        assert_eq!(code, Some(2), "{}: {text}", file.display());
        assert!(
            text.contains(&file.display().to_string()) && text.contains(says),
            "{text}"
        );
    }
    for beside in ["stability.json", mbdbench::output::MANIFEST] {
        let p = d.join(beside);
        mkfifo(&p);
        let (code, text) = gate(&summary, &[]);
        assert_eq!(code, Some(2), "{beside}: {text}");
        assert!(text.contains(beside) && text.contains("FIFO"), "{text}");
        std::fs::remove_file(&p).unwrap();
    }
    let _ = std::fs::remove_dir_all(&d);
}
