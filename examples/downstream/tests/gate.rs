//! The pull-request gate of the crate that owns Heun's method: the method, registered in
//! mbdbench's catalogue, runs the quick tier of the nine_spring case on every chart and
//! formulation, and the gate written for it (below, appended to the case file) must pass. A
//! change that breaks the method fails this test with the gate's row
//! (`MBDBENCH_DOWNSTREAM_BREAK=1 cargo test` shows it).
use clap::Parser;
use mbdbench::catalogue::Catalogue;
use mbdbench::gate::{GateOptions, Verdict};
use mbdbench::methods::{Fixed, Where};
use mbdbench_downstream::Heun;

/// Heun's rotation error on two_angles, so3, body, at 1e-2 s (1.082e-2 rad when written) may
/// grow by half before the gate fails.
const GATE: &str = r#"
[[gates]]
metric = "rotation_error_max"
max = 1.623e-2
baseline = 1.082e-2
margin = 1.5
where = { scene = "two_angles", param = "so3", integrator = "heun", formulation = "body", dt = 1.0e-2 }
quick = true
"#;

#[test]
fn heun_passes_its_gate() {
    // Invariant: the method's gate passes on the suite's own scores (and names the method).
    let dir = std::env::temp_dir().join(format!("mbdbench-downstream-{}", std::process::id()));
    let cases = dir.join("cases");
    std::fs::create_dir_all(&cases).unwrap();
    let (_, text) = mbdbench::case::embedded_sources()
        .iter()
        .find(|(label, _)| label.ends_with("nine_spring.toml"))
        .unwrap();
    // The case without the catalogue's gates (they judge the built-in methods), with ours.
    let physics = text.split("\n[[gates]]").next().unwrap();
    std::fs::write(cases.join("nine_spring.toml"), format!("{physics}\n{GATE}")).unwrap();
    let catalogue = Catalogue::builtin()
        .with_method("heun", Where::Everywhere, Fixed(Heun::from_env()))
        .unwrap()
        .with_cases(&cases);
    let out = dir.join("run");
    let run = ["mbdbench", "run", "--quick", "--integrator", "heun", "--out"];
    let cli = mbdbench::cli::Cli::try_parse_from(run.iter().copied().chain([out.to_str().unwrap()]))
        .unwrap();
    assert_eq!(mbdbench::cli::execute_with(catalogue.clone(), cli), 0, "run");
    let summary = mbdbench::gate::load_summary(&out.join("summary.json")).unwrap();
    let mut opts = GateOptions::new(mbdbench::cli::default_references());
    opts.quick = true;
    opts.catalogue = catalogue.clone();
    let rows = mbdbench::gate::evaluate(&catalogue.cases().unwrap(), &summary, None, &opts).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let line = |r: &mbdbench::gate::GateRow| {
        format!(
            "{}/{}/{}/{} dt={:?} {} = {:?} {} {:?} {}",
            r.key.scene, r.key.param, r.key.integrator, r.key.formulation, r.dt, r.metric,
            r.value, r.threshold, r.verdict, r.note
        )
    };
    assert!(rows.iter().any(|r| r.key.integrator == "heun"), "no row names heun");
    let failed: Vec<String> = rows.iter().filter(|r| r.verdict == Verdict::Fail).map(line).collect();
    assert!(failed.is_empty(), "the gate failed:\n{}", failed.join("\n"));
}
