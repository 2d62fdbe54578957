//! Outputs that never disagree, through the binary on the quick tier of nine_spring: the
//! report's gate line is the last line of `mbdbench gate --baseline` with the committed
//! baseline on the same files; gates outside the
//! run's selection and stability gates without `stability.json` are skipped and counted
//! (failing under `--require-stability`); `gate --case/--scene` gate a subset and the wrong
//! tier is bad input; a filtered run into a folder holding a broader run merges into it
//! (same commit and tier) and regenerates its report, or writes beside it and leaves it
//! untouched; only drawn runs keep a series file, every other record says why; `summary.md`
//! stays within a pull-request comment.
mod common;

use common::text;

use std::path::Path;
use std::process::{Command, Output};

fn mbdbench(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .args(args)
        .output()
        .unwrap()
}

fn last_line(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .last()
        .unwrap_or("")
        .to_string()
}

/// The page's "Gates:" line (`<p class="gates"><b>Gates:</b> N passed, ...`).
fn page_gate_line(dir: &Path) -> String {
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    let at = html
        .find("<b>Gates:</b> ")
        .expect("the page states the gates")
        + 14;
    let rest = &html[at..];
    rest[..rest.find('.').unwrap()].to_string()
}

/// The agreement of report, gate and folders after quick and filtered runs (one test: the
/// steps build on each other's output).
#[test]
fn report_gate_and_filtered_runs_agree() {
    let root = common::temp_dir("agree");
    let d = root.join("latest");
    let ds = d.to_str().unwrap();
    let summary = d.join("summary.json");
    let ss = summary.to_str().unwrap();
    let o = mbdbench(&["run", "--quick", "--case", "nine_spring", "--out", ds]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        o.stdout.len() < 2000,
        "run prints one line per case:\n{}",
        text(&o)
    );

    // The criterion: the quick nine_spring run passes its quick gates; the two stability
    // gates are skipped (no stability.json) and say so.
    let o = mbdbench(&["gate", "--summary", ss, "--case", "nine_spring", "--quick"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let line = last_line(&o);
    assert!(line.ends_with(" passed, 0 failed, 2 skipped"), "{line}");
    assert!(text(&o).contains("skipped 2: not run: no stability.json beside the summary"));
    let o = mbdbench(&[
        "gate",
        "--summary",
        ss,
        "--case",
        "nine_spring",
        "--quick",
        "--require-stability",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        last_line(&o).ends_with(" 2 failed, 0 skipped"),
        "{}",
        text(&o)
    );

    // Without --case, the other cases' gates lie outside the run's selection: skipped. The
    // report says exactly what the gate says.
    let o = mbdbench(&["gate", "--summary", ss, "--quick"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(text(&o).contains("not run: outside the run's selection (--case nine_spring)"));
    // The report compares a quick summary with the committed baseline, as `gate
    // --baseline` does: its line is that gate's.
    let baseline = Path::new(env!("CARGO_MANIFEST_DIR")).join("reports/baseline/quick.json");
    let b = baseline.to_str().unwrap();
    let o = mbdbench(&["gate", "--summary", ss, "--quick", "--baseline", b]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let gate_line = last_line(&o);
    let r = mbdbench(&["report", "--summary", ss]);
    assert!(r.status.success(), "{}", text(&r));
    assert_eq!(page_gate_line(&d), gate_line);

    // A subset by scene; the wrong tier and unknown names are bad input.
    let o = mbdbench(&["gate", "--summary", ss, "--quick", "--scene", "two_angles"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(!String::from_utf8_lossy(&o.stdout).contains("large/"));
    let o = mbdbench(&["gate", "--summary", ss]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("quick-tier run") && text(&o).contains("--quick"));
    let o = mbdbench(&["gate", "--summary", ss, "--quick", "--case", "nope"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("known: ") && text(&o).contains("nine_spring"));

    // Series: only the drawn runs keep a file; every other record says why; the report
    // found a series for every variant its time-series plots draw.
    let s = mbdbench::gate::load_summary(&summary).unwrap();
    let (mut kept, mut dropped) = (0, 0);
    for r in &s.records {
        match &r.series {
            Some(rel) => {
                kept += 1;
                assert!(d.join(rel).is_file(), "{rel}");
            }
            None if r.status != mbdbench::summary::Status::NotApplicable => {
                dropped += 1;
                assert!(r.series_reason.is_some(), "{:?}", r.key);
            }
            None => {}
        }
    }
    assert!(kept > 0 && dropped > kept, "{kept} kept, {dropped} dropped");
    let html = std::fs::read_to_string(d.join("index.html")).unwrap();
    assert!(!html.contains("(no series file)"));
    let md = std::fs::metadata(d.join("summary.md")).unwrap().len();
    assert!(md < 60_000, "summary.md is {md} bytes");

    // A filtered run of the same commit and tier merges: the other scene's records stay,
    // the report is regenerated and agrees with the gate again.
    let before = s.records.len();
    let o = mbdbench(&[
        "run",
        "--quick",
        "--case",
        "nine_spring",
        "--scene",
        "two_angles",
        "--param",
        "so3",
        "--out",
        ds,
    ]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        text(&o).contains("merged into the broader summary"),
        "{}",
        text(&o)
    );
    let merged = mbdbench::gate::load_summary(&summary).unwrap();
    assert_eq!(merged.records.len(), before);
    assert_eq!(merged.selection, s.selection);
    assert!(merged.records.iter().any(|r| r.key.scene == "large"));
    assert!(d.join("index.html").is_file(), "the report is regenerated");
    let o = mbdbench(&["gate", "--summary", ss, "--quick", "--baseline", b]);
    assert_eq!(page_gate_line(&d), last_line(&o));

    // A full-tier run cannot merge into the quick one: it writes beside it and says where;
    // the quick run's summary is untouched.
    let bytes = std::fs::read(&summary).unwrap();
    let o = mbdbench(&[
        "run",
        "--case",
        "nine_spring",
        "--scene",
        "two_angles",
        "--integrator",
        "rk4",
        "--param",
        "so3",
        "--out",
        ds,
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let elsewhere = root.join("latest-nine_spring-two_angles-so3-rk4-full");
    assert!(
        text(&o).contains(elsewhere.to_str().unwrap()),
        "{}",
        text(&o)
    );
    assert!(elsewhere.join("summary.json").is_file());
    assert_eq!(std::fs::read(&summary).unwrap(), bytes);
    let _ = std::fs::remove_dir_all(&root);
}

/// Every name option's help lists the valid names, and an unknown name is refused with
/// them; every option of every command has help text.
#[test]
fn the_cli_explains_itself() {
    let o = mbdbench(&["run", "--help"]);
    let help = text(&o);
    for name in [
        "dopri5",
        "simo_wong",
        "quat_proj",
        "spatial",
        "nine_spring",
        "spin_d0",
    ] {
        assert!(help.contains(name), "run --help lacks {name}");
    }
    let o = mbdbench(&["run", "--integrator", "rk5"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("valid --integrator names") && text(&o).contains("gauss6"));
    for cmd in [
        "list",
        "run",
        "stability",
        "trajectory",
        "gate",
        "report",
        "advise",
        "reference",
    ] {
        let help = text(&mbdbench(&[cmd, "--help"]));
        // clap prints an option without help text as a bare flag line: every `--x` line must
        // carry words after the flag.
        for l in help.lines().filter(|l| l.trim_start().starts_with("--")) {
            let words = l.split_whitespace().count();
            assert!(words >= 3, "{cmd}: option without help: {l}");
        }
    }
}
