//! The fiber column's part of the report, through the binary on the quick tier of its
//! dynamic and cyclic cases (the so3 chart): the energy balance over time is drawn for the
//! pulse, with a line for each of the four schemes, and for no scene that keeps no energy
//! books; the hysteresis loop is drawn for the cyclic scenes.
mod common;

use std::process::Command;

fn mbdbench(args: &[&str]) {
    let o = Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "mbdbench {args:?}: {}",
        common::text(&o)
    );
}

/// The balance panel exists exactly where the scene keeps energy books (the pulse), names
/// the four schemes it draws, and the page has no plot files beside it unless asked.
#[test]
fn balance_drawn_for_the_pulse_only() {
    let dir = common::temp_dir("fiber-report");
    let out = dir.join("out");
    let out_s = out.to_str().unwrap();
    mbdbench(&[
        "run",
        "--quick",
        "--case",
        "fiber_column_dynamic",
        "--case",
        "fiber_column_cyclic",
        "--param",
        "so3",
        "--out",
        out_s,
    ]);
    let summary = out.join("summary.json");
    mbdbench(&["report", "--summary", summary.to_str().unwrap()]);
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let figure = |id: &str| {
        let at = html.find(&format!("<figure data-plot=\"{id}\""))?;
        let end = at + html[at..].find("</figure>").unwrap();
        Some(html[at..end].to_string())
    };
    let balance = figure("rc_pulse/balance_so3_force_based").expect("the pulse's balance panel");
    assert!(
        balance.contains("dt 1e-3 (newmark, hht, gen_alpha, midpoint)"),
        "the four schemes at the quick step: {balance}"
    );
    assert!(balance.contains("<svg"), "a drawn plot, not a note");
    for scene in ["rc_cyclic_c01", "rc_cyclic_c02"] {
        assert!(
            !html.contains(&format!("data-plot=\"{scene}/balance_")),
            "{scene} keeps no energy books"
        );
        assert!(
            figure(&format!("{scene}/shear_db")).is_some(),
            "{scene}: hysteresis loop"
        );
    }
    assert!(!out.join("svg").exists(), "plot files only with --svg");
    let _ = std::fs::remove_dir_all(&dir);
}
