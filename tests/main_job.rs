//! The main job (`mbdbench` with no command) through the binary, on a catalogue of one case
//! (`free_body`, about 75 s on 2 cores): when `reports/latest` already holds a quick-tier run,
//! which a full run may not replace, the run is written to `reports/latest-full`, and the
//! stability study, the report, the recommendation and the gate all follow it there (they
//! used to keep reading `reports/latest`, whose stale quick summary then stopped the gate with
//! exit 2); the quick run's folder is left as it was. It opens by saying what it will do,
//! and how long the last full run in the folder took.
mod common;

use common::text;

use std::path::PathBuf;
use std::process::Command;

/// The main job's later steps read and write the folder its run wrote.
#[test]
fn main_job_follows_its_run() {
    let root = common::temp_dir("main-job");
    let cases = common::cases_with("main-job-cases", "free_body.toml", |t| t.to_string());
    let refs = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("references");
    let common_args = [
        "--cases",
        cases.to_str().unwrap(),
        "--references",
        refs.to_str().unwrap(),
    ];
    let mbdbench = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_mbdbench"))
            .current_dir(&root)
            .args(common_args)
            .args(args)
            .output()
            .unwrap()
    };
    let o = mbdbench(&["run", "--quick", "--out", "reports/latest"]);
    assert!(o.status.success(), "{}", text(&o));
    let latest = root.join("reports/latest");
    let quick = std::fs::read(latest.join("summary.json")).unwrap();
    let o = mbdbench(&[]);
    assert!(o.status.success(), "the main job failed: {}", text(&o));
    let full = root.join("reports/latest-full");
    for f in ["summary.json", "stability.json", "index.html", "summary.md"] {
        assert!(full.join(f).is_file(), "{f} missing in {}", full.display());
    }
    assert!(
        text(&o).contains("report reports/latest-full/index.html"),
        "{}",
        text(&o)
    );
    // The quick run's folder is untouched: same summary, and no study or report added.
    assert_eq!(std::fs::read(latest.join("summary.json")).unwrap(), quick);
    assert!(!latest.join("stability.json").exists());
    let md = std::fs::read_to_string(full.join("summary.md")).unwrap();
    assert!(md.contains("free_body"), "{md}");
    // It said first what it would do, that an interruption leaves nothing mixed, and the
    // quicker first look; with no full run in reports/latest, no time to go by.
    let said = String::from_utf8_lossy(&o.stdout).to_string();
    let opening: Vec<&str> = said.lines().take(4).collect();
    assert!(
        opening[0].starts_with("mbdbench: the main job: 1 cases (1 scenes)"),
        "{said}"
    );
    assert!(
        opening[1].contains("No full run in reports/latest yet"),
        "{said}"
    );
    assert!(opening[2].contains("Ctrl-C") && opening[3].contains("mbdbench run --quick"));
    assert!(opening[3].contains("--help"), "{said}");
    // With the full run in reports/latest, the next main job says how long it took: its
    // opening is read and the job stopped.
    std::fs::remove_dir_all(&latest).unwrap();
    std::fs::rename(&full, &latest).unwrap();
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(latest.join("summary.json")).unwrap()).unwrap();
    let took = summary["env"]["elapsed_s"].as_f64().expect("elapsed_s");
    let runs = summary["records"].as_array().unwrap().len();
    let mut child = Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .current_dir(&root)
        .args(common_args)
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = std::io::BufRead::lines(std::io::BufReader::new(child.stdout.take().unwrap()));
    let _ = lines.next();
    let second = lines.next().unwrap().unwrap();
    let _ = child.kill();
    let _ = child.wait();
    assert_eq!(
        second,
        format!(
            "  The last full run here: {runs} runs in {took:.0} s (commit {}, {}).",
            summary["git_commit"].as_str().unwrap(),
            summary["created_utc"].as_str().unwrap()
        )
    );
    let _ = std::fs::remove_dir_all(&root);
    let _ = std::fs::remove_dir_all(&cases);
}
