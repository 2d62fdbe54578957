//! A closed stdout or stderr never panics, on any command (`src/quiet.rs`): each command runs
//! once with both streams open for its normal exit status, then with stdout closed, with
//! stderr closed and with both closed (`run ... 2>&1 | head -1`), and must end with that same
//! status: never 101 (a panic), never a panic message, its files still written. The runs are
//! narrow (one case, one scene or variant) to keep this fast; the main job (no command) runs
//! these commands' own code (`cli::main_job`), so it is covered by them.
mod common;

use std::path::Path;
use std::process::{Command, Output, Stdio};

/// Which of the child's streams has no reader left.
#[derive(Debug, Clone, Copy)]
enum Closed {
    Stdout,
    Stderr,
    Both,
}

/// The write end of a pipe whose read end is already gone: every write to it fails with EPIPE
/// (made before the child starts, so no write can slip in while a reader still exists).
fn closed_pipe() -> Stdio {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    writer.into()
}

fn spawn(args: &[&str], closed: Option<Closed>) -> Output {
    let (out, err) = match closed {
        None => (Stdio::piped(), Stdio::piped()),
        Some(Closed::Stdout) => (closed_pipe(), Stdio::piped()),
        Some(Closed::Stderr) => (Stdio::piped(), closed_pipe()),
        Some(Closed::Both) => (closed_pipe(), closed_pipe()),
    };
    Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(out)
        .stderr(err)
        .output()
        .unwrap()
}

/// Runs `args` with open streams and returns its exit status, then checks that it ends with
/// that status, and without a panic message where one could be read, with each stream closed.
fn same_status_when_closed(args: &[&str]) -> i32 {
    let normal = spawn(args, None);
    let code = normal.status.code().expect("ended by a signal");
    assert!(code != 101, "{args:?} panicked: {}", common::text(&normal));
    for closed in [Closed::Stdout, Closed::Stderr, Closed::Both] {
        let o = spawn(args, Some(closed));
        let text = common::text(&o);
        assert_eq!(
            o.status.code(),
            Some(code),
            "{args:?} with {closed:?} closed: {text}"
        );
        assert!(!text.contains("panicked"), "{args:?} {closed:?}: {text}");
    }
    code
}

/// `list`, `list --json`, `reference --check`, a failing `trajectory` (its message goes to
/// stderr), a bad-input error, a usage error and `--help` end with their normal status with
/// either stream closed.
#[test]
fn small_commands_tolerate_closed_streams() {
    let dir = common::temp_dir("closed-small");
    let traj = dir.join("t.json");
    let traj = traj.to_str().unwrap();
    let missing = dir.join("no-such-folder");
    for (args, want) in [
        (vec!["list"], 0),
        (vec!["list", "--json"], 0),
        (
            vec![
                "reference",
                "--check",
                "--case",
                "nine_spring",
                "--scene",
                "two_angles",
            ],
            0,
        ),
        (
            // euler at 0.1 s diverges (non_finite at 3.5 s): exit 1, the failure on stderr.
            vec![
                "trajectory",
                "--case",
                "nine_spring",
                "--scene",
                "two_angles",
                "--param",
                "so3",
                "--integrator",
                "euler",
                "--dt",
                "0.1",
                "--out",
                traj,
            ],
            1,
        ),
        (vec!["list", "--cases", missing.to_str().unwrap()], 2),
        (vec!["run", "--no-such-option"], 2),
        (vec!["--help"], 0),
    ] {
        assert_eq!(same_status_when_closed(&args), want, "{args:?}");
    }
    assert!(Path::new(traj).is_file(), "trajectory wrote nothing");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `run`, `stability`, `report`, `advise` and `gate` on one small run end with their normal
/// status with either stream closed, and write their files: the progress lines and notes on
/// stderr and the tables on stdout are dropped, the work is not.
#[test]
fn folder_commands_tolerate_closed_streams() {
    let dir = common::temp_dir("closed-run");
    let out = dir.join("run");
    let o = out.to_str().unwrap();
    let summary = out.join("summary.json");
    let s = summary.to_str().unwrap();
    let run = [
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
        "--jobs",
        "1",
        "--out",
        o,
    ];
    assert_eq!(same_status_when_closed(&run), 0);
    assert!(summary.is_file());
    // The study of the run's own selection: advise and gate judge only such a pair.
    let stability = [
        "stability",
        "--quick",
        "--case",
        "nine_spring",
        "--scene",
        "two_angles",
        "--param",
        "so3",
        "--integrator",
        "rk4",
        "--jobs",
        "1",
        "--out",
        o,
    ];
    assert_eq!(same_status_when_closed(&stability), 0);
    assert!(out.join("stability.json").is_file());
    assert_eq!(same_status_when_closed(&["report", "--summary", s]), 0);
    assert!(out.join("index.html").is_file() && out.join("summary.md").is_file());
    assert_eq!(same_status_when_closed(&["advise", "--summary", s]), 0);
    assert_eq!(
        same_status_when_closed(&["advise", "--summary", s, "--json"]),
        0
    );
    let gate = same_status_when_closed(&["gate", "--summary", s, "--quick"]);
    assert!(gate == 0 || gate == 1, "gate: {gate}");
    let _ = std::fs::remove_dir_all(&dir);
}
