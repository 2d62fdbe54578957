//! The recommendation on a real run (the quick tier of gimbal_lock and nine_spring): every
//! winner actually reaches its target on every non-control scene (checked against the
//! summary's records), no Euler chart wins gimbal_lock as a whole, and `mbdbench advise
//! --json` says exactly what the library computes.
mod common;

use std::process::Command;

use mbdbench::advise::{self, Options, Setting};
use mbdbench::cli::default_references;
use mbdbench::summary::Status;

/// Every winner and runner-up reaches its target at its settings on every scene it lists,
/// which are all the case's non-control scenes; gimbal_lock's winners are not Euler charts;
/// the binary's JSON equals the library's advice, and the report's table names the same
/// winners.
#[test]
fn advice_holds_against_the_summary() {
    let dir = common::temp_dir("advise");
    let out = dir.join("q");
    let o = Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .args([
            "run",
            "--quick",
            "--case",
            "gimbal_lock",
            "--case",
            "nine_spring",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary = mbdbench::gate::load_summary(&out.join("summary.json")).unwrap();
    let cases = mbdbench::catalogue::embedded().unwrap();
    let root = default_references();
    let reference = |c: &mbdbench::case::Case, scene: &str| {
        advise::stored_reference(&root, c, scene, &c.primary_metric, advise::Claim::Accuracy)
    };
    let advice = advise::advise(
        &summary,
        &advise::specs(&cases, &reference),
        &Options::default(),
    );
    assert_eq!(advice.cases.len(), 2);
    let mut winners = 0;
    for c in &advice.cases {
        let case = cases.iter().find(|k| k.name == c.case).unwrap();
        let wanted: Vec<&str> = case
            .scenes
            .iter()
            .filter(|s| !s.control)
            .map(|s| s.name.as_str())
            .collect();
        assert_eq!(c.scenes, wanted, "{}", c.case);
        for t in &c.targets {
            for p in [&t.winner, &t.runner_up].into_iter().flatten() {
                let scenes: Vec<&str> = p.settings.keys().map(String::as_str).collect();
                let mut sorted = wanted.clone();
                sorted.sort();
                assert_eq!(scenes, sorted);
                for (scene, s) in &p.settings {
                    let r = summary
                        .records
                        .iter()
                        .find(|r| {
                            r.key.case == c.case
                                && &r.key.scene == scene
                                && r.key.param == p.param
                                && r.key.integrator == p.integrator
                                && r.key.formulation == p.formulation
                                && match s {
                                    Setting::Dt(dt) => r.dt == Some(*dt),
                                    Setting::Tol(tol) => r.tol == Some(*tol),
                                }
                        })
                        .unwrap();
                    assert_eq!(r.status, Status::Ok);
                    let e = r.metrics[&c.metric].unwrap();
                    assert!(
                        e <= t.target,
                        "{} {scene}: {e:e} > {:e}",
                        p.name(),
                        t.target
                    );
                }
            }
            if let Some(w) = &t.winner {
                winners += 1;
                if c.case == "gimbal_lock" {
                    assert!(
                        !w.param.starts_with("euler"),
                        "{} wins gimbal_lock",
                        w.name()
                    );
                }
                assert!(t.runner_up.is_some(), "{}: no runner-up", c.case);
            }
        }
    }
    assert!(winners >= 3, "only {winners} winners on the quick tier");
    let o = Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .args(["advise", "--json", "--summary"])
        .arg(out.join("summary.json"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let cli: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(cli, serde_json::to_value(&advice).unwrap());
    // The report opens with the same winners, and marks the control scene in its text.
    let o = Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .args(["report", "--summary"])
        .arg(out.join("summary.json"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    let table = &md[md.find("## Recommendation").unwrap()..md.find("\n## Cases").unwrap()];
    for c in &advice.cases {
        for t in &c.targets {
            if let Some(w) = &t.winner {
                assert!(table.contains(&format!("**{}** cost {}", w.name(), w.cost)));
            }
        }
    }
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains(
        "left out of the recommendation: a result known by construction.) Scene spin_d0"
    ));
    let _ = std::fs::remove_dir_all(&dir);
}
