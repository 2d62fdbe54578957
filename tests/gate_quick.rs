//! The real quick tier (catalogue and stability study) passes the quick gates and the
//! committed baseline (so CI fails on a crossed threshold or a regression), and the gate
//! command's exit codes:
//! 0 on the real quick tier, 2 on a truncated summary.
mod common;

use mbdbench::gate::{self, GateOptions, Verdict};

/// Every quick gate of every case passes on a fresh quick run of the whole catalogue and of
/// the stability study, and the fresh run shows no regression against
/// reports/baseline/quick.json.
#[test]
fn real_quick_tier_passes_gates_and_baseline() {
    let mut rows = vec![];
    let cases = mbdbench::catalogue::embedded().unwrap();
    let out = common::temp_dir("gate-quick");
    let opts = mbdbench::suite::RunOptions {
        quick: true,
        jobs: 2,
        out: out.clone(),
        t_end: None,
        references: mbdbench::cli::default_references(),
        progress: false,
        repeats: 0,
        serial_timing: false,
        cases: vec![],
        scenes: vec![],
        base: None,
        skip: true,
        cap_s: mbdbench::suite::skip::DEFAULT_CAP_S,
        cost: mbdbench::cost::CostTable::embedded(),
        catalogue: mbdbench::catalogue::Catalogue::builtin(),
    };
    let problems = mbdbench::catalogue::problems(&cases, &[], &[]).unwrap();
    let summary = mbdbench::suite::run_catalogue(
        problems,
        &mbdbench::selection::VariantFilter::default(),
        &opts,
    )
    .unwrap();
    let baseline =
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("reports/baseline/quick.json");
    let gopts = GateOptions {
        quick: true,
        baseline: Some(baseline),
        factor: gate::DEFAULT_FACTOR,
        references: mbdbench::cli::default_references(),
        cases: vec![],
        scenes: vec![],
        require_stability: true,
        catalogue: mbdbench::catalogue::Catalogue::builtin(),
    };
    let sopts = mbdbench::stability::StudyOptions {
        quick: true,
        jobs: 2,
        out: out.clone(),
        references: mbdbench::cli::default_references(),
        progress: false,
    };
    let stability = mbdbench::study::run_study(
        &cases,
        &[],
        &[],
        &mbdbench::selection::VariantFilter::default(),
        &sopts,
    )
    .unwrap();
    rows.extend(gate::evaluate(&cases, &summary, Some(&stability), &gopts).unwrap());
    // The stability gates were evaluated on stability.json records.
    assert!(
        rows.iter()
            .any(|r| r.metric == "largest_stable_dt" && r.verdict == Verdict::Pass),
        "no passing stability gate row"
    );
    let failed: Vec<_> = rows.iter().filter(|r| r.verdict == Verdict::Fail).collect();
    assert!(
        failed.is_empty(),
        "{} failing rows: {:?}",
        failed.len(),
        &failed[..failed.len().min(5)]
    );
    assert!(rows.len() > 100, "{} rows", rows.len());
    assert_eq!(gate::exit_code(&rows), 0);
    let _ = std::fs::remove_dir_all(&out);
}

/// `mbdbench gate` on a truncated summary exits 2 naming the file, and writes nothing.
#[test]
fn truncated_summary_exits_2() {
    let d = common::temp_dir("gate-trunc");
    let text = std::fs::read_to_string(
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("reports/baseline/quick.json"),
    )
    .unwrap();
    let f = d.join("summary.json");
    std::fs::write(&f, &text[..text.len() / 3]).unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .args(["gate", "--quick", "--summary", f.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("summary.json"));
    let _ = std::fs::remove_dir_all(&d);
}
