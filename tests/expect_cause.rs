//! An expected-failure gate holds a cause, not just a kind (cases/README.md, `expect`), through the
//! binary: with the column's Newton budget cut to 3 iterations every plain-Newton run on c02
//! fails at the first step, and the gate expecting OpenSees' cycling at step 4154 fails those
//! rows instead of passing them.
mod common;

use std::process::Command;

/// c02's plain-Newton runs at the quick point stop at the cycling step with the case as
/// written (the gate passes) and at t <= 5 with `max_iter = 3` (the gate fails, saying the
/// failure came too early).
#[test]
fn a_newton_budget_failure_is_not_the_expected_cycling() {
    let bin = env!("CARGO_BIN_EXE_mbdbench");
    for (tag, edit, want) in [
        ("as-written", None, 0),
        ("max-iter-3", Some(("max_iter = 50", "max_iter = 3")), 1),
    ] {
        let cases =
            common::cases_with(
                &format!("expect-{tag}"),
                "fiber_column_cyclic.toml",
                |t| match edit {
                    Some((a, b)) => common::replace_once(t, a, b),
                    None => t.to_string(),
                },
            );
        let out = common::temp_dir(&format!("expect-out-{tag}"));
        let run = Command::new(bin)
            .args([
                "run",
                "--quick",
                "--case",
                "fiber_column_cyclic",
                "--scene",
                "rc_cyclic_c02",
            ])
            .args([
                "--formulation",
                "force_based",
                "--integrator",
                "newton_disp",
            ])
            .args(["--integrator", "newton_disp_ls", "--jobs", "1", "--cases"])
            .arg(&cases)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert!(
            run.status.code().is_some_and(|c| c <= 1),
            "{}",
            common::text(&run)
        );
        let gate = Command::new(bin)
            .args([
                "gate",
                "--quick",
                "--case",
                "fiber_column_cyclic",
                "--scene",
                "rc_cyclic_c02",
            ])
            .arg("--cases")
            .arg(&cases)
            .arg("--summary")
            .arg(out.join("summary.json"))
            .output()
            .unwrap();
        let text = common::text(&gate);
        let expect_rows: Vec<&str> = text
            .lines()
            .filter(|l| l.contains("expect failed (newton_failure)"))
            .collect();
        assert!(!expect_rows.is_empty(), "{text}");
        if want == 0 {
            assert!(expect_rows.iter().all(|l| l.contains("PASS")), "{text}");
        } else {
            assert_eq!(gate.status.code(), Some(1), "{text}");
            assert!(
                expect_rows
                    .iter()
                    .all(|l| l.contains("FAIL") && l.contains("too early (another cause)")),
                "{text}"
            );
        }
        let _ = std::fs::remove_dir_all(&out);
        let _ = std::fs::remove_dir_all(&cases);
    }
}
