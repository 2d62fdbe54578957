//! The gate's verdict through the binary, as a pull request meets it: `--case` and
//! `--scene` filter the baseline comparison as they filter the gates; the report and
//! `summary.md` give the verdict of `gate --baseline`, in `gate --markdown`'s words; a summary and a
//! `stability.json` of different selections are never judged together (the gate and
//! `advise` refuse the pair naming both stamps, the report leaves the study out, a `run`
//! into the folder removes the stale study and says so); and a `stability` into a folder
//! says which report files it removes.
mod common;

use std::path::Path;
use std::process::{Command, Output};

fn mbdbench(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .args(args)
        .output()
        .unwrap()
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// With `--case` (and `--scene`), every row of the gate's table, those of the baseline
/// comparison included, is of the selected case (and scene): against a baseline in which
/// every run of `free_body` and of the scene `large` took half the RHS evaluations (each a
/// regression row), the unfiltered gate prints rows of both, `--case nine_spring` none of
/// `free_body`, and `--scene two_angles` none of `large`. `report --baseline` gives the
/// same verdict on the page and in `summary.md`, whose gate block is `gate --markdown`'s.
#[test]
fn case_and_scene_filter_the_baseline_comparison() {
    let out = common::temp_dir("verdict-filter");
    let o = mbdbench(&[
        "run",
        "--quick",
        "--case",
        "nine_spring",
        "--case",
        "free_body",
        "--param",
        "so3",
        "--integrator",
        "rk4",
        "--out",
        s(&out),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", common::text(&o));
    let summary = out.join("summary.json");
    let mut base: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&summary).unwrap()).unwrap();
    for r in base["records"].as_array_mut().unwrap() {
        if r["case"] == "free_body" || r["scene"] == "large" {
            let n = r["stats"]["rhs_evals"].as_u64().unwrap();
            r["stats"]["rhs_evals"] = serde_json::json!(n / 2);
        }
    }
    let b = out.with_extension("baseline.json");
    std::fs::write(&b, serde_json::to_vec(&base).unwrap()).unwrap();
    let gate = |extra: &[&str]| {
        let mut a = vec![
            "gate",
            "--summary",
            s(&summary),
            "--quick",
            "--baseline",
            s(&b),
        ];
        a.extend(extra);
        let o = mbdbench(&a);
        (o.status.code(), common::text(&o))
    };
    // A row of case `c` (and of scene `sc`) in a table: its first column and its variant.
    let has = |t: &str, c: &str, sc: &str| {
        t.lines()
            .any(|l| l.starts_with(&format!("{c} ")) && l.contains(&format!(" {sc}/")))
    };
    let (code, all) = gate(&[]);
    assert_eq!(code, Some(1), "{all}");
    assert!(
        has(&all, "free_body", "gni") && has(&all, "nine_spring", "large"),
        "{all}"
    );
    let (code, case) = gate(&["--case", "nine_spring"]);
    assert_eq!(code, Some(1), "{case}");
    assert!(
        !has(&case, "free_body", "gni") && has(&case, "nine_spring", "large"),
        "{case}"
    );
    // Its regressions are all on `large`: the scene's verdict passes.
    let (code, scene) = gate(&["--case", "nine_spring", "--scene", "two_angles"]);
    assert_eq!(code, Some(0), "{scene}");
    assert!(!has(&scene, "nine_spring", "large"), "{scene}");
    assert!(has(&scene, "nine_spring", "two_angles"), "{scene}");
    // The report with the same baseline gives the gate's verdict on the page and in
    // summary.md, whose gate block is `gate --markdown`'s, byte for byte.
    let last = all.lines().last().unwrap().to_string();
    assert!(last.contains("4 failed"), "{all}");
    let o = mbdbench(&["report", "--summary", s(&summary), "--baseline", s(&b)]);
    assert_eq!(o.status.code(), Some(0), "{}", common::text(&o));
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(page.contains(&format!("<b>Gates:</b> {last}.")), "{last}");
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    let o = mbdbench(&[
        "gate",
        "--summary",
        s(&summary),
        "--quick",
        "--baseline",
        s(&b),
        "--markdown",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let block = String::from_utf8(o.stdout).unwrap();
    assert!(block.starts_with(&format!("**Gates: {last}.**")), "{block}");
    assert!(
        block.contains("| integrator | rk4 | 4 | x2.000 |"),
        "{block}"
    );
    assert!(
        md.contains(&block),
        "summary.md:\n{md}\ngate --markdown:\n{block}"
    );
    let _ = std::fs::remove_dir_all(&out);
    let _ = std::fs::remove_file(&b);
}

/// A `stability.json` of another selection than the summary's: `gate --require-stability`
/// and `advise` exit 2 naming both stamps, `report` writes the page without the study and
/// says why; a `run` into the folder whose selection holds the old one removes the stale
/// study and says so; a `stability` into a folder with a report says it removes the report.
#[test]
fn a_stale_stability_study_is_never_judged_beside_the_run() {
    let out = common::temp_dir("verdict-stale");
    let dir = s(&out);
    let run = |param: &[&str]| {
        let mut a = vec![
            "run",
            "--quick",
            "--case",
            "nine_spring",
            "--integrator",
            "rk4",
        ];
        a.extend(param);
        a.extend(["--out", dir]);
        mbdbench(&a)
    };
    let study = |param: &str| {
        mbdbench(&[
            "stability",
            "--quick",
            "--case",
            "nine_spring",
            "--integrator",
            "rk4",
            "--param",
            param,
            "--out",
            dir,
        ])
    };
    assert_eq!(run(&["--param", "so3"]).status.code(), Some(0));
    assert_eq!(study("quat").status.code(), Some(0));
    let summary = out.join("summary.json");
    let sum = s(&summary);
    for args in [
        vec!["gate", "--summary", sum, "--quick", "--require-stability"],
        vec!["advise", "--summary", sum],
    ] {
        let o = mbdbench(&args);
        let t = common::text(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {t}");
        assert!(
            t.contains("stability.json (commit")
                && t.contains("--param quat")
                && t.contains("is not of the run of summary.json (commit")
                && t.contains("--param so3"),
            "{args:?}: {t}"
        );
    }
    let o = mbdbench(&["report", "--summary", sum]);
    let t = common::text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("written without the stability study"), "{t}");
    // The study of the run's own selection pairs; it replaces the report made before it.
    let o = study("so3");
    let t = common::text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("removed index.html, summary.md"), "{t}");
    let o = mbdbench(&["gate", "--summary", sum, "--quick", "--require-stability"]);
    assert!(
        matches!(o.status.code(), Some(0 | 1)),
        "{}",
        common::text(&o)
    );
    // A run of a wider selection (every chart) into the folder: the study is stale now.
    let o = run(&[]);
    let t = common::text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(
        t.contains("stability.json (not of this run's build and selection"),
        "{t}"
    );
    assert!(!out.join("stability.json").exists());
    let _ = std::fs::remove_dir_all(&out);
}
