//! The bring-your-own-integrator example end to end: Ralston's method, registered from outside
//! the crate's tables (`examples/byo_integrator.rs`, compiled into this test as a module), runs
//! on the nine_spring case through the suite's own commands, and appears in what each command
//! writes: the summary's records, the report, `advise --json` and the gate's rows, where the gate
//! written for it in the example's case overlay passes.
#[allow(dead_code)]
#[path = "../examples/byo_integrator.rs"]
mod byo;

mod common;

#[test]
fn a_registered_method_goes_through_run_report_advise_and_gate() {
    // Invariant: a method registered in a catalogue is scored, reported, advised on and gated
    // exactly where a built-in would be: its records run, and its name is in every output.
    let cases = byo::overlay().expect("the overlay is written");
    let out = common::temp_dir("byo_integrator");
    let out_s = out.to_str().unwrap();
    let summary = format!("{out_s}/summary.json");
    let code = byo::command(
        &cases,
        &[
            "run",
            "--quick",
            "--case",
            "nine_spring",
            "--case",
            "flexible_beam",
            "--out",
            out_s,
        ],
    );
    assert_eq!(code, 0, "run");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&summary).unwrap()).unwrap();
    let ralston = |case: &str| -> Vec<serde_json::Value> {
        s["records"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|r| r["integrator"] == "ralston3" && r["case"] == case)
            .cloned()
            .collect()
    };
    // Every chart in both formulations on both scenes, each at the quick tier's one step.
    let nine = ralston("nine_spring");
    assert_eq!(nine.len(), 2 * 11 * 2, "ralston3 records on nine_spring");
    assert!(nine.iter().all(|r| r["status"] == "ok"));
    // Every ODE form of the beam (six of its eight formulations) on its four scenes.
    let beam = ralston("flexible_beam");
    let ran = beam.iter().filter(|r| r["status"] != "n/a").count();
    assert_eq!(ran, 4 * 6, "ralston3 runs on the beam");
    assert_eq!(byo::command(&cases, &["report", "--summary", &summary]), 0);
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(page.contains("ralston3"), "the report names the method");
    let advise = std::process::Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .args([
            "advise",
            "--json",
            "--case",
            "flexible_beam",
            "--summary",
            &summary,
        ])
        .output()
        .unwrap();
    // Advice reads the records as data: on the beam's quick ladder (2.5e-3 s) Ralston's
    // method diverges where RK4 does not (a shorter stability interval on the imaginary
    // axis), and advise names it among the variants to avoid.
    assert!(advise.status.success(), "{}", common::text(&advise));
    let a: serde_json::Value = serde_json::from_slice(&advise.stdout).unwrap();
    let avoid = a["cases"][0]["avoid"].as_array().unwrap();
    assert!(
        avoid.iter().any(|x| x["integrator"] == "ralston3"),
        "advise weighs the method: {avoid:?}"
    );
    let gate = std::process::Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .args([
            "gate",
            "--quick",
            "--case",
            "nine_spring",
            "--summary",
            &summary,
        ])
        .args(["--cases", &cases])
        .output()
        .unwrap();
    // The built-in catalogue does not know the method the overlay's gate names: refused.
    assert_eq!(gate.status.code(), Some(2), "{}", common::text(&gate));
    assert!(common::text(&gate).contains("\"ralston3\" is no registered integrator"));
    let code = byo::command(
        &cases,
        &[
            "gate",
            "--quick",
            "--case",
            "nine_spring",
            "--summary",
            &summary,
        ],
    );
    assert_eq!(code, 0, "the gate written for the method passes");
}

#[test]
fn the_registered_method_keeps_its_order_against_the_stored_reference() {
    // Invariant: Ralston's method, written once and registered from outside, is third order
    // against nine_spring's stored reference (two_angles, rotation error) on an additive chart
    // (quat) and, through the Munthe-Kaas stages, on the Lie-group chart so3, in both
    // formulations: each halving of the step divides the error by 8 (local orders within 0.2
    // of 3).
    let cat = mbdbench::catalogue::Catalogue::builtin()
        .with_method(
            "ralston3",
            mbdbench::methods::Where::Everywhere,
            mbdbench::methods::Fixed(byo::Ralston3),
        )
        .unwrap();
    let cases = cat.cases().unwrap();
    let mut p = cat
        .problems(&cases, &["nine_spring".into()], &["two_angles".into()])
        .unwrap()
        .pop()
        .unwrap();
    p.attach_reference(&mbdbench::cli::default_references())
        .unwrap();
    for (param, formulation) in [("quat", "body"), ("so3", "body"), ("so3", "spatial")] {
        let v = p.family().find(param, "ralston3", formulation).unwrap();
        let errs: Vec<f64> = [1.0e-2, 5.0e-3, 2.5e-3]
            .iter()
            .map(|&dt| {
                let out = p
                    .run(
                        v,
                        mbdbench::problem::Stepping::Dt(dt),
                        mbdbench::problem::Want::Scored,
                    )
                    .unwrap();
                assert!(out.failure.is_none(), "{param}/{formulation} at {dt}");
                out.scores.get("rotation_error_max").unwrap()
            })
            .collect();
        eprintln!("ralston3 {param}/{formulation}: rotation errors {errs:?}");
        for w in errs.windows(2) {
            let order = (w[0] / w[1]).log2();
            assert!(
                (order - 3.0).abs() < 0.2,
                "{param}/{formulation}: {errs:?}, order {order}"
            );
        }
    }
}
