//! Tests of the stability section: tables, plots and facts of each part from fixture records.
use super::*;
use crate::report::{Extras, fixture, html, markdown, render_check, write_report};
use crate::summary::{FitRecord, Summary, run_id};

fn rec(case: &str, scene: &str, p: &str, i: &str, metrics: &[(&str, Option<f64>)]) -> Record {
    let mut r = fixture::summary().records[0].clone();
    r.key.case = case.into();
    r.key.scene = scene.into();
    r.key.param = p.into();
    r.key.integrator = i.into();
    r.key.formulation = "body".into();
    r.dt = None;
    r.tol = None;
    r.status = Status::Ok;
    r.series = None;
    r.metrics = metrics.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    r.metric_reasons.clear();
    r
}

const LIMITED: &str = "limited by bound_exceeded at t = 30.135874 with dt = 9.287436e-4 (n = \
    33280): energy error |E - E0| / max(|E0|, energy_scale) = 1.000e0 >= 1";
const CAP: &str = "bounded up to the cap (dt = t_h / 20, tol = 1e0; t_h = 30.910000 s)";

/// A search record with its reasons.
fn search(scene: &str, p: &str, i: &str, stable: Option<f64>, why: &str) -> Record {
    let m = if i == "dopri5" { "tol" } else { "dt" };
    let sm = format!("largest_stable_{m}");
    let am = format!("largest_accurate_{m}");
    let mut r = rec(
        fixture::CASE,
        scene,
        p,
        i,
        &[
            (&sm, stable),
            (&am, stable.map(|x| x / 10.0)),
            ("stability_horizon", Some(30.91)),
            ("fastest_period", Some(1.5455)),
        ],
    );
    r.metric_reasons.insert(sm, why.into());
    r.metric_reasons.insert(
        am,
        "limited by bound_exceeded at t = 30.58077 with dt = 2.34156e-2 (n = 1320): \
         rotation error 1.046e-1 rad >= 0.1 rad"
            .into(),
    );
    r
}

/// A small stability summary: step searches (one capped), a stiffness ladder, a
/// long-horizon run, a record of a later kind and a case found only here.
pub fn stability_summary() -> Summary {
    let mut records = vec![
        search("two_angles", "so3", "euler", Some(8.94e-4), LIMITED),
        search("two_angles", "so3", "rk4", Some(0.187), LIMITED),
        search("two_angles", "so3", "simo_wong", Some(1.5455), CAP),
        search("two_angles", "quat", "dopri5", Some(1e-3), LIMITED),
    ];
    for (j, dt) in [(0, 0.187), (2, 0.0187), (4, 0.00187)] {
        records.push(search(
            &format!("two_angles_k1e{j}"),
            "so3",
            "rk4",
            Some(dt),
            LIMITED,
        ));
        let simo = if j == 0 { CAP } else { LIMITED };
        records.push(search(
            &format!("two_angles_k1e{j}"),
            "so3",
            "simo_wong",
            Some(dt * 2.0),
            simo,
        ));
    }
    let mut long = rec(
        "free_body",
        "gni",
        "so3",
        "rk4",
        &[
            ("long_horizon_steps", Some(1e4)),
            ("energy_growth_exponent", Some(0.98)),
            ("momentum_growth_exponent", None),
            ("energy_error_final", Some(1e-9)),
            ("momentum_error_final", Some(2e-9)),
        ],
    );
    long.dt = Some(1e-2);
    long.metric_reasons.insert(
        "momentum_growth_exponent".into(),
        "the error is exactly 0 at every sample".into(),
    );
    let id = run_id("so3", "rk4", "body", Some(1e-2), None);
    long.series = Some(format!("series/long_horizon/free_body/gni/{id}.json"));
    records.push(long);
    records.push(rec(
        fixture::CASE,
        "two_angles",
        "so3",
        "rk4",
        &[("sensitivity_growth_max", Some(3.5e-2))],
    ));
    records.push(rec(
        "gimbal_lock",
        "approach",
        "euler_zyx",
        "rk4",
        &[("approach_distance", Some(1e-3))],
    ));
    let fit = |i: &str, order: Option<f64>, points: Vec<[f64; 2]>| FitRecord {
        key: crate::summary::RunKey::new(fixture::CASE, "two_angles_stiffness", "so3", i, "body"),
        metric: "largest_stable_dt_vs_stiffness".into(),
        order,
        reason: order.is_none().then(|| "2 of 3 stiffness factors".into()),
        points,
    };
    let fits = vec![
        fit(
            "rk4",
            Some(-0.5),
            vec![[1.0, 0.187], [1e2, 0.0187], [1e4, 0.00187]],
        ),
        fit("simo_wong", None, vec![[1e2, 0.0374], [1e4, 0.00374]]),
    ];
    fixture::summary_from("def5678", "2026-01-02T04:00:00Z", records, fits)
}

fn write_long_series(dir: &Path) {
    let id = run_id("so3", "rk4", "body", Some(1e-2), None);
    let p = dir.join(format!("series/long_horizon/free_body/gni/{id}.json"));
    std::fs::create_dir_all(p.parent().unwrap()).unwrap();
    let t: Vec<f64> = (0..50)
        .map(|k| 10f64.powf(k as f64 / 12.0) * 1e-2)
        .collect();
    let e: Vec<f64> = t.iter().map(|x| 1e-13 * x).collect();
    let v = serde_json::json!({"t": t, "energy_error": e, "momentum_error": e});
    std::fs::write(p, v.to_string()).unwrap();
}

/// The stability fixture renders, per case, its step tables (the cap visible as such, the
/// Euler sentence, short reasons with the full text on hover and in the markdown), the
/// stiffness-ladder plot with slopes and the unmeasured points in its caption, the
/// long-horizon plots and table, the generic table of other records, and a section for a
/// case found only in stability.json; the page stays self-contained and passes its check.
#[test]
fn stability_fixture_renders_tables_and_plots() {
    let s = fixture::summary();
    let st = stability_summary();
    let dir = fixture::temp_dir("stability");
    fixture::write_series(&dir.join("series"), &s, |_| false);
    write_long_series(&dir);
    let out = dir.join("report");
    let src = Source {
        summary: &st,
        dir: &dir,
    };
    let files = write_report(
        &s,
        &dir.join("series"),
        &[],
        Extras {
            stability: Some(src),
            svg_files: true,
            ..Default::default()
        },
        &out,
    )
    .unwrap();
    let page = std::fs::read_to_string(&files.index_html).unwrap();
    assert_eq!(render_check(&page), Vec::<String>::new());
    for t in html::start_tags(&page) {
        for (n, _) in &t.attrs {
            assert!(n != "src" && n != "href" && !n.ends_with(":href"), "{n}");
        }
    }
    let nine = fixture::case_section(&page, fixture::CASE);
    assert!(nine.contains("data-section=\"stability\""));
    assert!(nine.contains(&html::esc(EULER_NOTE)));
    assert_eq!(page.matches(&html::esc(EULER_NOTE)).count(), 1);
    assert!(nine.contains("nine_spring / two_angles: largest stable and accurate step"));
    assert!(nine.contains("nine_spring / two_angles_k1e2: largest stable and accurate step"));
    assert!(nine.contains("<td>dt 1.55e0 (cap)</td>"), "capped value");
    assert!(nine.contains(">bounded up to the cap</td>"));
    assert!(nine.contains("<td>tol 1e-3</td>"), "adaptive row");
    assert!(nine.contains(&format!(
        "<td title=\"{}\">energy error &gt;= 1 at t = 30.14 s</td>",
        html::esc(LIMITED)
    )));
    // The ladder: one plot (stable dt), the slopes in the legend, capped point in the caption.
    let ladder = files
        .svgs
        .iter()
        .find(|p| p.ends_with("stability/two_angles_stiffness_largest_stable_dt.svg"))
        .expect("ladder svg");
    let svg = std::fs::read_to_string(ladder).unwrap();
    assert!(
        svg.contains("so3 / rk4: slope -0.50"),
        "slope in the legend"
    );
    assert!(svg.contains("so3 / simo_wong: slope - (too few points)"));
    assert!(
        svg.contains("\n1e4\n") && svg.contains("\n1\n"),
        "end labels"
    );
    assert!(nine.contains("so3 / simo_wong / body at k x 1: bounded up to the cap"));
    assert!(
        nine.contains("<td>3.5e-2</td>"),
        "other records: sensitivity"
    );
    // Long horizon: both plots drawn from the series file, and the table.
    let fb = fixture::case_section(&page, "free_body");
    assert_eq!(fb.matches("<svg").count(), 2, "energy and momentum plots");
    assert!(fb.contains("so3 / rk4: p = 0.98"));
    assert!(fb.contains("free_body: long horizon"));
    assert!(fb.contains("<td>0.980</td>"));
    assert!(
        out.join("svg/free_body/stability/long_gni_energy_explicit.svg")
            .is_file()
    );
    // A case only in stability.json gets a section with its record.
    let gl = fixture::case_section(&page, "gimbal_lock");
    assert!(gl.contains("approach_distance") && gl.contains("<td>1e-3</td>"));
    // The stability tables are in the page; summary.md keeps the answer only.
    let md = std::fs::read_to_string(&files.summary_md).unwrap();
    assert!(!md.contains("### Stability"));
    assert!(page.contains("nine_spring / two_angles: largest stable and accurate step"));
    assert!(page.contains("free_body: long horizon"));
    assert!(page.contains("nine_spring: other stability records"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A singularity-ladder record: chart, setting, distance, error, conditioning, RHS count,
/// and optionally a failure.
fn sing(p: &str, i: &str, step: (Option<f64>, Option<f64>), d: f64, e: f64) -> Record {
    let mut r = rec(
        "gimbal_lock",
        &format!("ladder_d{d:e}"),
        p,
        i,
        &[
            ("approach_distance", Some(d)),
            ("rotation_error_max", Some(e)),
            ("conditioning_min", Some(d.max(1e-3))),
        ],
    );
    (r.dt, r.tol) = step;
    r.stats.rhs_evals = (1e3 * e.max(1e-9).log10().abs()) as u64;
    r
}

/// The singularity ladder gives, per setting, error and conditioning plots (and work for
/// an adaptive setting), one line per chart sorted by d, a failed chart in the red band and
/// named with its failure in the caption, the regime-change step in the caption; its
/// sentence names where each Euler chart's error peaks.
#[test]
fn singularity_plots_per_setting() {
    let fixed = (Some(1e-2), None);
    let tol = (None, Some(1e-8));
    let mut rs = vec![];
    for (d, e) in [(1e-2, 1e-4), (1e-10, 1e-11), (1e-6, 1e-2)] {
        rs.push(sing("euler_xyz", "rk4", fixed, d, e));
        rs.push(sing("so3", "rk4", fixed, d, 1e-15));
        rs.push(sing("euler_xyz", "dop853", tol, d, e / 10.0));
        let mut z = sing("euler_zxz", "rk4", fixed, d, 0.0);
        z.status = Status::Failed;
        z.metrics.insert("rotation_error_max".into(), None);
        z.failure = Some(crate::integrate::Failure::new(
            crate::integrate::FailureKind::SingularChart,
            0.0,
            "conditioning 0",
        ));
        rs.push(z);
    }
    let refs: Vec<&Record> = rs.iter().collect();
    let plots = singularity_plots("gimbal_lock", &refs, "footer");
    let ids: Vec<&str> = plots.iter().map(|p| p.id.as_str()).collect();
    assert_eq!(
        ids,
        [
            "stability/singularity_rk4_dt_1e-2_rotation_error",
            "stability/singularity_rk4_dt_1e-2_conditioning",
            "stability/singularity_dop853_tol_1e-8_rotation_error",
            "stability/singularity_dop853_tol_1e-8_rhs_evals",
            "stability/singularity_dop853_tol_1e-8_conditioning",
        ]
    );
    let err = &plots[0];
    let params: Vec<&str> = err.lines.iter().map(|l| l.key.param.as_str()).collect();
    assert_eq!(params, ["euler_xyz", "so3"]);
    assert_eq!(
        err.lines[0].points,
        vec![(1e-10, 1e-11), (1e-6, 1e-2), (1e-2, 1e-4)]
    );
    assert_eq!(err.fails.len(), 3);
    assert!(err.caption.contains("Omega h = 1e-2"), "{}", err.caption);
    assert!(
        err.caption
            .contains("Failed (red band): euler_zxz (singular_chart at t = 0)"),
        "{}",
        err.caption
    );
    assert_eq!(plots[3].lines[0].points[0], (1e-10, 9000.0));
    let facts = singularity_facts(&refs);
    assert_eq!(
        facts[0],
        "Singularity ladder, rk4 at dt 1e-2, max rotation error: euler_xyz peaks at 1e-2 \
         (d = 1e-6), 1e-11 at d = 1e-10."
    );
}

/// The sensitivity plot draws each scene's growth series from its file, names the
/// predictable horizon in the legend, and names a scene whose file is missing.
#[test]
fn sensitivity_plot_from_series() {
    let dir = fixture::temp_dir("sensitivity");
    let mut a = rec(
        "nine_spring",
        "large",
        "so3",
        "dop853",
        &[
            ("sensitivity_growth_max", Some(945.0)),
            ("predictable_horizon", Some(10.0)),
        ],
    );
    a.series = Some("series/sensitivity/nine_spring/large.json".into());
    let p = dir.join(a.series.as_ref().unwrap());
    std::fs::create_dir_all(p.parent().unwrap()).unwrap();
    let v = serde_json::json!({"t": [0.0, 5.0, 10.0], "growth": [1.0, 30.0, 597.0]});
    std::fs::write(&p, v.to_string()).unwrap();
    let mut b = a.clone();
    b.key.scene = "two_angles".into();
    b.series = Some("series/sensitivity/nine_spring/two_angles.json".into());
    let plot = sensitivity_plot("nine_spring", &[&a, &b], &dir, "f").unwrap();
    assert_eq!(plot.lines.len(), 1);
    assert_eq!(
        plot.lines[0].points,
        vec![(0.0, 1.0), (5.0, 30.0), (10.0, 597.0)]
    );
    assert_eq!(
        plot.lines[0].label.as_deref(),
        Some("large (predictable to t = 10)")
    );
    assert!(plot.caption.contains("No series file for: two_angles."));
    assert!(sensitivity_plot("nine_spring", &[], &dir, "f").is_none());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Without stability.json the page and the markdown have no stability part; with one whose
/// series files are missing the long-horizon plots say "no data" in place.
#[test]
fn no_stability_no_part() {
    let s = fixture::summary();
    let dir = fixture::temp_dir("no-stability");
    let page = html::render(&crate::report::build_page(&s, &dir, &[], None, None));
    assert!(!page.contains("data-section=\"stability"));
    assert!(!page.contains(EULER_NOTE));
    let md = markdown::render(&crate::report::build_page(&s, &dir, &[], None, None));
    assert!(!md.contains("Stability"));
    let st = stability_summary();
    let src = Source {
        summary: &st,
        dir: &dir,
    };
    let page = html::render(&crate::report::build_page(&s, &dir, &[], None, Some(src)));
    assert_eq!(render_check(&page), Vec::<String>::new());
    let fb = fixture::case_section(&page, "free_body");
    assert!(fb.contains("no series file"));
    assert!(fb.contains("<p class=\"nodata\">"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A corrupt stability.json is a warning naming the file and the report is written without
/// the part; an absent one is silently no part.
#[test]
fn corrupt_stability_json_warns_and_report_goes_on() {
    let s = fixture::summary();
    let dir = fixture::temp_dir("corrupt-stability");
    let summary_path = dir.join("summary.json");
    std::fs::write(&summary_path, serde_json::to_string(&s).unwrap()).unwrap();
    assert_eq!(load_beside(&summary_path), (None, None));
    std::fs::write(dir.join("stability.json"), "{\"schema\": 1, \"records\": [").unwrap();
    let (st, warning) = load_beside(&summary_path);
    assert!(st.is_none());
    let w = warning.expect("a warning");
    assert!(
        w.starts_with("warning:") && w.contains("stability.json"),
        "{w}"
    );
    let files = write_report(
        &s,
        &dir.join("series"),
        &[],
        Extras {
            stability: st.as_ref().map(|s| Source {
                summary: s,
                dir: &dir,
            }),
            ..Default::default()
        },
        &dir.join("report"),
    )
    .unwrap();
    let page = std::fs::read_to_string(&files.index_html).unwrap();
    assert_eq!(render_check(&page), Vec::<String>::new());
    assert!(page.contains("data-case=\"nine_spring\""));
    assert!(!page.contains("data-section=\"stability"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Reasons shorten to the failure kind or the bound and its time; the cap stays "bounded up
/// to the cap"; unknown texts are cut with an ellipsis.
#[test]
fn short_reasons() {
    assert_eq!(short_reason(LIMITED), "energy error >= 1 at t = 30.14 s");
    assert_eq!(short_reason(CAP), "bounded up to the cap");
    assert_eq!(
        short_reason(
            "nothing passed: bound_exceeded at t = 18.854163 with n = 327680 steps: \
             rotation error 1.388e-1 rad >= 0.1 rad"
        ),
        "nothing passed: rotation error >= 0.1 rad at t = 18.85 s"
    );
    assert_eq!(
        short_reason(
            "limited by newton_failure at t = 28.055488 with dt = 4.7e-1 (n = 65): \
             simo_wong: Newton diverges"
        ),
        "newton_failure at t = 28.06 s"
    );
    assert_eq!(short_reason("nothing passed"), "nothing passed");
    assert_eq!(
        short_reason("search not completed: x"),
        "search not completed"
    );
    assert!(short_reason(&"x".repeat(80)).ends_with("..."));
    assert_eq!(short_reason(""), "-");
    assert_eq!(decimals(-0.0004, 3), "0.000");
    assert_eq!(decimals(-0.5, 2), "-0.50");
}
