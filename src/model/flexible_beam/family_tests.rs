//! Tests of the flexible-beam family behind the seam: bad case files are refused with the
//! file and key named, the registered variants run through `Problem`, the trajectory columns
//! are the documented ones, `modal_linear` diverges with a typed failure, and the momentum
//! form conserves the free hub's angular momentum to round-off.
use crate::case::Case;
use crate::catalogue::load_str;
use crate::problem::{Problem, Stepping, Want};

const TEXT: &str = include_str!("../../../cases/flexible_beam.toml");

fn load(text: &str) -> Result<Case, crate::case::CaseError> {
    load_str("cases/flexible_beam.toml", text)
}

fn problem(scene: &str, t_end: Option<f64>) -> Box<dyn Problem> {
    let c = load(TEXT).unwrap();
    let mut p = (super::family::FAMILY.compile)(&c, c.scene(scene).unwrap()).unwrap();
    match t_end {
        Some(t) => p.set_t_end(t),
        None => p
            .attach_reference(&crate::cli::default_references())
            .unwrap(),
    }
    p
}

/// Each kind of bad input is refused at loading with the key that holds it: a non-positive
/// stiffness or mass per length, an element count of 0, a mode count of 0 or one whose state
/// size is not registered, Baumgarte settings whose constraint dynamics are not stable, a base
/// breakpoint left out, a breakpoint off the score grid, and a rotation bound in the step
/// search's `[stability]` (the beam has no rotation error to bound).
#[test]
fn bad_input_names_the_key() {
    let cases: [(&str, &str, &str); 10] = [
        ("ei = 1.4e4", "ei = -1.4e4", "scene[0].beam.ei"),
        ("rho_a = 1.2 }", "rho_a = 0.0 }", "scene[0].beam.rho_a"),
        ("elements = 10", "elements = 0", "numerics.elements"),
        ("cb_bending_modes = 8", "cb_bending_modes = 0", "numerics.cb_bending_modes"),
        ("bending_modes = 4", "bending_modes = 7", "numerics.bending_modes"),
        (
            "baumgarte = { alpha = 20.0",
            "baumgarte = { alpha = -1.0",
            "numerics.baumgarte.alpha",
        ),
        (
            "baumgarte_soft = { alpha = 2.0, beta = 2.0 }",
            "baumgarte_soft = { alpha = 2.0, beta = 0.0 }",
            "numerics.baumgarte_soft.beta",
        ),
        (
            "breakpoints = [15.0]\nenergy_scale = 3200.0",
            "breakpoints = []\nenergy_scale = 3200.0",
            "scene[0].breakpoints",
        ),
        (
            "breakpoints = [15.0]\nenergy_scale = 3200.0",
            "breakpoints = [15.0, 15.05]\nenergy_scale = 3200.0",
            "scene[0].breakpoints[1]",
        ),
        (
            "periods = 20.0\n",
            "periods = 20.0\nrotation_error_max = 0.1\n",
            "stability.rotation_error_max",
        ),
    ];
    for (from, to, key) in cases {
        assert!(TEXT.contains(from), "{from}");
        let e = load(&TEXT.replacen(from, to, 1)).unwrap_err();
        assert_eq!(e.file, "cases/flexible_beam.toml");
        assert!(e.key.contains(key), "{to}: key {} ({})", e.key, e.message);
    }
}

/// `trajectory` writes the documented columns for `fe_exact` under `gen_alpha` (no `param`
/// beyond `none`), one value per sample, starting at rest.
#[test]
fn trajectory_has_the_documented_columns() {
    let p = problem("spinup_w6", Some(1.0));
    let v = super::family::FAMILY
        .find("none", "gen_alpha", "fe_exact")
        .unwrap();
    let out = p.run(v, Stepping::Dt(1.0e-3), Want::Trajectory).unwrap();
    assert!(out.failure.is_none());
    let c = out.columns.unwrap();
    let names: Vec<&str> = c.columns.iter().map(|x| x.0).collect();
    let family: Vec<&str> = super::family::FAMILY.columns.iter().map(|x| x.name).collect();
    assert_eq!(names, family);
    assert_eq!(c.t.len(), 21);
    for (_, w, data) in &c.columns {
        assert_eq!(data.len(), w * c.t.len());
    }
    assert_eq!(c.columns[0].2[0], 0.0);
    assert!(c.columns[0].2[20].abs() > 1e-6, "the tip moves");
}

/// `modal_linear` (no geometric stiffening) diverges on the slowest spin-up with a typed
/// `diverged` failure before t_end, while `modal_stiffened` stays within 2 % of the
/// reference's peak tip deflection.
#[test]
fn conventional_model_diverges_and_stiffened_one_does_not() {
    let p = problem("spinup_w4", None);
    let f = &super::family::FAMILY;
    let lin = p
        .run(
            f.find("none", "rk4", "modal_linear").unwrap(),
            Stepping::Dt(2.5e-3),
            Want::Scored,
        )
        .unwrap();
    let fail = lin.failure.expect("modal_linear diverges");
    assert_eq!(fail.kind, crate::integrate::FailureKind::Diverged);
    assert!(fail.t > 10.0 && fail.t < 20.0, "{}", fail.t);
    // The samples before the failing step already lie far beyond the bounded models' 0.4 m
    // (the crossing itself is in the failure's message, not a sample).
    let tip = lin.scores.get("tip_deflection_max").unwrap();
    assert!(tip > 5.0 && tip <= 10.0, "{tip}");
    assert!(fail.message.contains("divergence bound"), "{}", fail.message);
    let st = p
        .run(
            f.find("none", "rk4", "modal_stiffened").unwrap(),
            Stepping::Dt(2.5e-3),
            Want::Scored,
        )
        .unwrap();
    assert!(st.failure.is_none());
    let e = st.scores.get("tip_deflection_error_max").unwrap();
    assert!(e < 0.02 * 0.4001 && e > 0.0, "{e:e}");
}

/// On the free hub, the momentum form keeps H = tau t_off after the torque ends to
/// round-off under rk4 (a linear invariant), for the modal and the constrained AIGC forms,
/// and the AIGC constraints stay at round-off.
#[test]
fn free_hub_momentum_is_a_linear_invariant() {
    let p = problem("flexsat", Some(10.0));
    for form in ["modal_stiffened", "aigc_baumgarte", "aigc_projection"] {
        let v = super::family::FAMILY.find("none", "rk4", form).unwrap();
        let out = p.run(v, Stepping::Dt(1.0e-2), Want::Scored).unwrap();
        assert!(out.failure.is_none(), "{form}");
        let h = out.scores.get("momentum_error_max").unwrap();
        assert!(h < 1e-12, "{form}: {h:e}");
        if form.starts_with("aigc") {
            let g = out.scores.get("constraint_error_max").unwrap();
            assert!(g < 1e-12, "{form}: {g:e}");
        }
    }
}

/// The report's tip-over-time figure has what it draws: through the real command line
/// (`run --quick` on `spinup_w4`, then `report`), the completed run's series holds the tip
/// deflection and the reference's at every score time (the reference's own values), the
/// diverged `modal_linear` run keeps its series up to the failure (the family draws failed
/// runs), and the page has the tip panels, `modal_linear`'s naming its failed run.
#[test]
fn tip_figure_draws_every_formulation_against_the_reference() {
    use clap::Parser;
    let out = std::env::temp_dir().join(format!("mbdbench-beam-tip-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let o = out.display().to_string();
    let cli = |args: &[&str]| {
        let mut all = vec!["mbdbench"];
        all.extend_from_slice(args);
        crate::cli::execute(crate::cli::Cli::parse_from(all))
    };
    let run = [
        "run",
        "--quick",
        "--case",
        "flexible_beam",
        "--scene",
        "spinup_w4",
        "--integrator",
        "newmark",
        "--formulation",
        "modal_linear",
        "--formulation",
        "modal_stiffened",
        "--out",
        &o,
    ];
    assert_eq!(cli(&run), 0, "a typed failure is a result, not an error");
    let summary: crate::summary::Summary =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
            .unwrap();
    let series = |form: &str| {
        let r = summary
            .records
            .iter()
            .find(|r| r.key.formulation == form)
            .unwrap();
        let rel = r.series.clone().expect("a drawn run keeps its series");
        let text = std::fs::read_to_string(out.join(rel)).unwrap();
        (r.status, serde_json::from_str::<crate::summary::Series>(&text).unwrap())
    };
    let (status, s) = series("modal_stiffened");
    assert_eq!(status, crate::summary::Status::Ok);
    let tip = &s.tracks["tip_deflection"];
    let reference = &s.tracks["tip_deflection_reference"];
    assert_eq!((tip.len(), reference.len()), (s.t.len(), s.t.len()));
    assert_eq!(s.t.len(), 201);
    let peak = reference.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
    assert!((peak - 0.4001).abs() < 1e-3, "reference peak {peak}");
    let worst = tip
        .iter()
        .zip(reference)
        .map(|(a, b)| (a.unwrap() - b.unwrap()).abs())
        .fold(0.0, f64::max);
    assert!(worst < 0.02 * peak, "tip vs reference {worst}");
    let (status, s) = series("modal_linear");
    assert_eq!(status, crate::summary::Status::Failed);
    assert!(s.t.len() > 100 && s.t.len() < 201, "{}", s.t.len());
    let last = s.tracks["tip_deflection"].last().unwrap().unwrap();
    assert!(last.abs() > 1.0, "diverging: {last}");
    let summary_path = out.join("summary.json").display().to_string();
    assert_eq!(cli(&["report", "--summary", &summary_path]), 0);
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(
        page.contains("spinup_w4: tip_deflection over time (linear modes)")
            && page.contains("spinup_w4: tip_deflection over time (FE and stiffened modes)"),
        "no tip figure"
    );
    assert!(
        page.contains("modal_linear: newmark at dt 2.5e-3, failed at t = "),
        "the failed run is not named"
    );
    let _ = std::fs::remove_dir_all(&out);
}
