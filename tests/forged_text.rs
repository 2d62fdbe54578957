//! Text from case and summary files cannot forge structure, through the command line: a
//! `title` holding a newline and `## 0 failed`, or ESC, is refused at load naming the file and
//! the key; a record name with a control character makes a summary unusable input naming
//! `records[i]` and the key; free text that does get through (the summary's environment) stays
//! on its line in `summary.md`; and no ESC byte reaches the terminal, the user's text being
//! shown as `\u001b` instead.
mod common;

use std::path::Path;
use std::process::{Command, Output};

fn bin(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .args(args)
        .output()
        .unwrap()
}

/// Whether a process printed an ESC byte on either stream.
fn printed_esc(o: &Output) -> bool {
    o.stdout.contains(&0x1b) || o.stderr.contains(&0x1b)
}

/// A `title` with a newline and a forged heading, or a terminal escape, is refused by `list`
/// and by `run` (exit 2 naming the file and `title`; `run` writes no summary or summary.md),
/// and the refusal prints no ESC byte.
#[test]
fn hostile_title_is_refused() {
    for (tag, title) in [
        ("forge-heading", "Torque-free\\n## 0 failed"),
        ("forge-esc", "Torque-free\\u001b[2J\\u001b]0;owned\\u0007"),
    ] {
        let dir = common::cases_with(tag, "free_body.toml", |t| {
            common::replace_once(t, "title = \"Torque-free", &format!("title = \"{title}"))
        });
        let d = dir.to_str().unwrap();
        let o = bin(&["list", "--cases", d]);
        let text = common::text(&o);
        assert_eq!(o.status.code(), Some(2), "{tag}: {text}");
        assert!(
            text.contains("free_body.toml: title:") && text.contains("control character"),
            "{tag}: {text}"
        );
        assert!(!printed_esc(&o), "{tag}: ESC printed raw");
        let out = dir.join("out");
        let o = bin(&[
            "run",
            "--quick",
            "--cases",
            d,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2), "{tag}: {}", common::text(&o));
        assert!(!out.join("summary.json").exists() && !out.join("summary.md").exists());
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// A scene name holding ESC is refused naming the key, and the error quotes it as the visible
/// text `\u001b`: the terminal never receives the escape the case file holds.
#[test]
fn quoted_input_is_printed_escaped() {
    let dir = common::cases_with("forge-scene", "free_body.toml", |t| {
        common::replace_once(t, "name = \"gni\"", "name = \"gni\\u001b[31m\"")
    });
    let o = bin(&["list", "--cases", dir.to_str().unwrap()]);
    let text = common::text(&o);
    assert_eq!(o.status.code(), Some(2), "{text}");
    assert!(text.contains("scene[0].name"), "{text}");
    assert!(text.contains("gni\\u001b[31m"), "{text}");
    assert!(!printed_esc(&o), "ESC printed raw: {text}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A small quick run (one scene, one variant) into `dir`, its manifest removed so that the
/// summary can be edited by hand (`tests/hostile.rs`, `own_summary`).
fn small_run(dir: &Path) {
    let o = bin(&[
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
        dir.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", common::text(&o));
    std::fs::remove_file(dir.join(mbdbench::output::MANIFEST)).unwrap();
}

/// A summary whose record names hold ESC and a newline is unusable input to `report`,
/// `advise` and `gate` (exit 2 naming `records[i]` and the key, printed without ESC); free
/// text in its environment lands in `summary.md` on the environment's own line: no line of
/// the file starts with the forged `## 0 failed`, and no ESC is written.
#[test]
fn summary_text_cannot_forge_structure() {
    let dir = common::temp_dir("forge-summary");
    small_run(&dir);
    let p = dir.join("summary.json");
    let s = p.to_str().unwrap();
    let good = std::fs::read_to_string(&p).unwrap();
    let forged = good.replace(
        "\"scene\":\"two_angles\"",
        "\"scene\":\"two_angles\\u001b[31m\\n## 0 failed\"",
    );
    assert_ne!(forged, good, "the summary's format changed");
    std::fs::write(&p, &forged).unwrap();
    for args in [
        vec!["report", "--summary", s],
        vec!["advise", "--summary", s],
        vec!["gate", "--summary", s, "--quick"],
    ] {
        let o = bin(&args);
        let text = common::text(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {text}");
        assert!(
            text.contains("records[") && text.contains("key `scene`"),
            "{args:?}: {text}"
        );
        assert!(!printed_esc(&o), "{args:?}: ESC printed raw");
    }
    assert!(!dir.join("summary.md").exists(), "a report was written");
    let mut v: serde_json::Value = serde_json::from_str(&good).unwrap();
    v["env"]["os"] = "Linux\n## 0 failed\u{1b}[2J`".into();
    std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
    let o = bin(&["report", "--summary", s]);
    assert_eq!(o.status.code(), Some(0), "{}", common::text(&o));
    let md = std::fs::read_to_string(dir.join("summary.md")).unwrap();
    assert!(md.contains("0 failed"), "the environment was dropped");
    assert!(!md.contains('\u{1b}'), "ESC in summary.md");
    for line in md.lines() {
        assert!(!line.starts_with("## 0 failed"), "forged heading: {line}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
