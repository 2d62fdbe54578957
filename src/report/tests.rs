//! Tests of the report page: self-contained and complete, failed and n/a records, gate tables
//! and colours (both gate forms), path components.
use super::*;
use crate::gate::{GateRow, Verdict};

/// The plots the page holds for a case (each scene's and the across-scene ones).
fn plots_of(c: &CaseSection) -> usize {
    c.across.len()
        + c.scenes
            .iter()
            .map(|s| s.work_precision.len() + s.convergence.len() + s.timeseries.len())
            .sum::<usize>()
}

/// The page is self-contained (no src/href attribute, no script), holds one inline SVG per
/// expected plot of the case, the tables and the environment line; every SVG is also a
/// file; the markdown has the same tables.
#[test]
fn page_is_self_contained_and_complete() {
    let s = fixture::summary();
    let dir = fixture::temp_dir("complete");
    fixture::write_series(&dir.join("series"), &s, |_| false);
    let cases = crate::catalogue::embedded().unwrap();
    let out = dir.join("report");
    let extras = Extras {
        svg_files: true,
        ..Default::default()
    };
    let files = write_report(&s, &dir.join("series"), &cases, extras, &out).unwrap();
    let html = std::fs::read_to_string(&files.index_html).unwrap();
    assert_eq!(render_check(&html), Vec::<String>::new());
    for t in html::start_tags(&html) {
        for (n, _) in &t.attrs {
            assert!(
                n != "src" && n != "href" && !n.ends_with(":href"),
                "<{}> {n}",
                t.name
            );
        }
    }
    assert!(!html.contains(" src=") && !html.contains(" href="));
    let sec = fixture::case_section(&html, fixture::CASE);
    let page = build_page(&s, &dir.join("series"), &cases, None, None);
    let expected = plots_of(&page.cases[0]);
    // Plots at round-off are one sentence instead of an SVG.
    let c = &page.cases[0];
    let bodies: Vec<&chart::Rendered> = c
        .across
        .iter()
        .chain(c.scenes.iter().flat_map(|s| {
            s.work_precision
                .iter()
                .chain(&s.convergence)
                .chain(&s.timeseries)
        }))
        .map(|f| &f.body)
        .collect();
    let svgs = bodies
        .iter()
        .filter(|b| matches!(b, chart::Rendered::Svg(_)))
        .count();
    let notes = bodies
        .iter()
        .filter(|b| matches!(b, chart::Rendered::Note(_)))
        .count();
    assert!(
        notes > 0,
        "the fixture's constraint residuals are at round-off"
    );
    assert_eq!(sec.matches("<p class=\"nodata roundoff\">").count(), notes);
    assert_eq!(sec.matches("<figure").count(), expected);
    assert_eq!(sec.matches("<svg").count(), svgs);
    assert_eq!(sec.matches("<svg data-lines=\"").count(), svgs);
    assert_eq!(files.svgs.len(), svgs);
    assert!(files.svgs.iter().all(|p| p.is_file()));
    // rk4 on so3 is in the Lie-group charts' panel, lgvi in the geometric methods' one.
    for f in [
        "wp_wall_rk4_group",
        "wp_rhs_so3_geometric",
        "conv_so3_explicit",
    ] {
        assert!(
            out.join(format!("svg/nine_spring/large/{f}.svg")).is_file(),
            "{f}: {:?}",
            files.svgs
        );
    }
    // No panel draws more than MAX_LINES lines, and the page says how many it draws.
    let figs = page.cases[0].scenes.iter().flat_map(|s| {
        s.work_precision
            .iter()
            .chain(&s.convergence)
            .chain(&s.timeseries)
    });
    for f in figs {
        if let chart::Rendered::Svg(d) = &f.body {
            assert!(d.lines <= select::MAX_LINES, "{}: {}", f.kind, d.lines);
            assert!(sec.contains(&format!("<svg data-lines=\"{}\"", d.lines)));
        }
    }
    // No literal markdown reaches the page.
    for md in ["**", "`", "]("] {
        assert!(!html.contains(md), "{md} in the page");
    }
    for kind in html::REQUIRED_SECTIONS
        .iter()
        .chain(&["na", "across-scenes"])
    {
        assert!(sec.contains(&format!("data-section=\"{kind}\"")), "{kind}");
    }
    let env = env_line(&s);
    let md = std::fs::read_to_string(&files.summary_md).unwrap();
    assert!(md.contains(&env));
    for title in [
        "nine_spring: failed runs",
        "nine_spring: largest completed ladder step",
        "nine_spring / two_angles: heat map of variants x metrics",
        "nine_spring / large: heat map of variants x metrics",
        "nine_spring: not applicable",
    ] {
        assert!(html.contains(title), "{title}");
    }
    // summary.md has a line per case (its failures by kind) and points to the page.
    assert!(
        md.contains("39 runs (3 with a typed failure: 3 singular_chart)"),
        "{md}"
    );
    assert!(md.contains("index.html#case-nine_spring"), "{md}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Failed and n/a records, missing series files and a case file that was not given still
/// give a complete page: the time series say "no data" in place.
#[test]
fn failed_na_and_missing_series_render() {
    let s = fixture::summary();
    let dir = fixture::temp_dir("missing");
    let out = dir.join("report");
    // No series at all, and no case files.
    let files = write_report(&s, &dir.join("nowhere"), &[], Extras::default(), &out).unwrap();
    let html = std::fs::read_to_string(&files.index_html).unwrap();
    assert_eq!(render_check(&html), Vec::<String>::new());
    let sec = fixture::case_section(&html, fixture::CASE);
    let page = build_page(&s, &dir.join("nowhere"), &[], None, None);
    let timeseries: usize = page.cases[0]
        .scenes
        .iter()
        .map(|s| s.timeseries.len())
        .sum();
    assert!(
        timeseries >= 2 * fixture::SCENES.len(),
        "energy and constraint per scene"
    );
    assert_eq!(sec.matches("<figure").count(), plots_of(&page.cases[0]));
    assert_eq!(sec.matches("<p class=\"nodata\">").count(), timeseries);
    assert_eq!(
        sec.matches("<svg").count(),
        plots_of(&page.cases[0]) - timeseries
    );
    assert!(sec.contains("no series file"));
    assert!(sec.contains("written on SO(3) x R^3 (chart so3) only"));
    // Only one scene's series present: that scene's time series are drawn.
    fixture::write_series(&dir.join("series"), &s, |r| r.key.scene == "large");
    let files = write_report(&s, &dir.join("series"), &[], Extras::default(), &out).unwrap();
    let html = std::fs::read_to_string(&files.index_html).unwrap();
    let page = build_page(&s, &dir.join("series"), &[], None, None);
    // The predicate names the records whose series are left out: those of `large`.
    let large = page.cases[0]
        .scenes
        .iter()
        .find(|s| s.name == "large")
        .unwrap();
    let nodata = |f: &Figure| matches!(f.body, chart::Rendered::NoData(_));
    assert!(
        large.timeseries.iter().all(nodata),
        "{:?}",
        large
            .timeseries
            .iter()
            .map(|f| (&f.kind, &f.body))
            .filter(|(_, b)| !matches!(b, chart::Rendered::Svg(_)))
            .collect::<Vec<_>>()
    );
    let all_nodata = page.cases[0]
        .scenes
        .iter()
        .flat_map(|s| {
            s.work_precision
                .iter()
                .chain(&s.convergence)
                .chain(&s.timeseries)
        })
        .filter(|f| nodata(f))
        .count();
    assert_eq!(
        fixture::case_section(&html, fixture::CASE)
            .matches("<p class=\"nodata\">")
            .count(),
        all_nodata
    );
    // An empty summary.
    let mut empty = s.clone();
    empty.records.clear();
    empty.fits.clear();
    let files = write_report(&empty, &dir.join("series"), &[], Extras::default(), &out).unwrap();
    let html = std::fs::read_to_string(&files.index_html).unwrap();
    assert_eq!(render_check(&html), Vec::<String>::new());
    assert!(html.contains("none (no data)"));
    let _ = std::fs::remove_dir_all(&dir);
}

fn gate(scene: &str, dt: f64, metric: &str, verdict: Verdict) -> GateRow {
    GateRow {
        key: crate::summary::RunKey::new(fixture::CASE, scene, "so3", "rk4", "body"),
        dt: Some(dt),
        tol: None,
        metric: metric.into(),
        value: Some(1.0),
        outcome: None,
        threshold: "<= 1".into(),
        verdict,
        note: String::new(),
        ratio: Some(1.0),
    }
}

/// An expected-failure gate row shows in the case's gate table (HTML and markdown) as
/// its label, outcome and bound, and colours the gated run's status cell.
#[test]
fn expect_gate_renders() {
    let s = fixture::summary();
    let dir = fixture::temp_dir("expect-gates");
    let expect = |dt: f64, outcome: &str, verdict: Verdict| GateRow {
        key: crate::summary::RunKey::new(fixture::CASE, "large", "euler_zxz", "rk4", "body"),
        dt: Some(dt),
        tol: None,
        metric: "expect failed (singular_chart)".into(),
        value: None,
        outcome: Some(outcome.into()),
        threshold: "before 0.55 s".into(),
        verdict,
        note: String::new(),
        ratio: None,
    };
    let mut late = expect(1e-2, "singular_chart at t = 0.6", Verdict::Fail);
    late.note = "singular_chart at t = 0.6, too late: expected singular_chart before 0.55 s".into();
    let rows = vec![
        expect(2e-2, "singular_chart at t = 0.5", Verdict::Pass),
        late,
    ];
    let page = build_page(&s, &dir, &[], Some(&rows), None);
    let c = &page.cases[0];
    let g = c.gates.as_ref().unwrap();
    let col = |name: &str| g.header.iter().position(|h| h == name).unwrap();
    assert_eq!(g.rows.len(), 2);
    assert_eq!(
        g.rows[0][col("metric")].text,
        "expect failed (singular_chart)"
    );
    assert_eq!(g.rows[0][col("value")].text, "singular_chart at t = 0.5");
    assert_eq!(g.rows[0][col("threshold")].text, "before 0.55 s");
    let large = c.scenes.iter().find(|sc| sc.name == "large").unwrap();
    let m = &large.matrix;
    let status = m.header.iter().position(|h| h == "status").unwrap();
    let tone = |step: &str| {
        m.rows
            .iter()
            .find(|r| r[0].text == "euler_zxz" && r[3].text == step)
            .map(|r| r[status].tone)
    };
    assert_eq!(tone("dt 2e-2"), Some(tables::Tone::Pass));
    assert_eq!(tone("dt 1e-2"), Some(tables::Tone::Fail));
    let html = html::render(&page);
    for part in [
        "expect failed (singular_chart)",
        "singular_chart at t = 0.5",
        "before 0.55 s",
    ] {
        assert!(html.contains(part), "{part} not in the page");
    }
    let md = markdown::render(&page);
    assert!(
        md.contains("singular_chart at t = 0.6") && md.contains("Gates: 1 passed, 1 failed"),
        "{md}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Gated cells are coloured by verdict (a gated run at a coarser step gets its own row),
/// other cells neutral; the gate table and the markdown marks agree.
#[test]
fn gate_colours() {
    let s = fixture::summary();
    let dir = fixture::temp_dir("gates");
    let rows = vec![
        gate("two_angles", 5e-3, fixture::PRIMARY, Verdict::Pass),
        gate("two_angles", 2e-2, "energy_drift_max", Verdict::Fail),
    ];
    let page = build_page(&s, &dir, &[], Some(&rows), None);
    let c = &page.cases[0];
    // Without the case file, scenes sort by name: large, two_angles.
    assert_eq!(c.scenes[1].name, "two_angles");
    let m = &c.scenes[1].matrix;
    let so3_rk4_body: Vec<&Vec<tables::Cell>> = m
        .rows
        .iter()
        .filter(|r| r[0].text == "so3" && r[1].text == "rk4" && r[2].text == "body")
        .collect();
    assert_eq!(
        so3_rk4_body.len(),
        2,
        "finest row plus the gated coarse row"
    );
    let col = |name: &str| m.header.iter().position(|h| h == name).unwrap();
    assert_eq!(so3_rk4_body[0][3].text, "dt 5e-3");
    assert_eq!(
        so3_rk4_body[0][col(fixture::PRIMARY)].tone,
        tables::Tone::Pass
    );
    assert_eq!(
        so3_rk4_body[0][col("energy_drift_max")].tone,
        tables::Tone::Neutral
    );
    assert_eq!(so3_rk4_body[1][3].text, "dt 2e-2");
    assert_eq!(
        so3_rk4_body[1][col("energy_drift_max")].tone,
        tables::Tone::Fail
    );
    let g = page.gate_summary.as_ref().unwrap();
    assert_eq!(g.line, "1 passed, 1 failed, 0 skipped");
    assert_eq!(g.failed, 1);
    let g = c.gates.as_ref().unwrap();
    assert_eq!(g.rows.len(), 2);
    let html = html::render(&page);
    assert!(html.contains("<td class=\"pass\">") && html.contains("<td class=\"fail\">"));
    let md = markdown::render(&page);
    // summary.md lists the failing rows only, in the gate's own Markdown block.
    assert!(
        md.contains("| energy_drift_max | 1.000 | &lt;= 1 |"),
        "{md}"
    );
    assert!(!md.contains("dt=0.005000"), "{md}");
    assert!(md.contains(&crate::gate::markdown::verdict(&rows)), "{md}");
    assert!(md.contains("Gates: 1 passed, 1 failed, 0 skipped."));
    // Without gate rows nothing is coloured.
    let plain = build_page(&s, &dir, &[], None, None);
    assert!(
        plain.cases[0].scenes[0]
            .matrix
            .rows
            .iter()
            .flatten()
            .all(|c| c.tone == tables::Tone::Plain)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Path components are plain and short: a 300-byte case name becomes 64 characters and a
/// hash (two such names stay distinct), so the report of a summary naming it is written.
#[test]
fn long_names_are_shortened() {
    let (a, b) = ("x".repeat(300), format!("{}y", "x".repeat(299)));
    assert!(safe(&a).len() <= MAX_COMPONENT && safe(&a) != safe(&b));
    assert_eq!(safe("two_angles"), "two_angles");
    assert_eq!(safe(".."), "_");
    let dir = std::env::temp_dir().join(format!("mbdbench-long-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let mut s = fixture::summary();
    for r in &mut s.records {
        r.key.case = a.clone();
    }
    let out = dir.join("out");
    let extras = Extras {
        svg_files: true,
        ..Default::default()
    };
    let files = write_report(&s, &dir.join("series"), &[], extras, &out).unwrap();
    assert!(!files.svgs.is_empty());
    assert!(files.svgs.iter().all(|p| p.exists()));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The plot files are written only on request (`Extras::svg_files`): by default the page
/// alone holds the plots, and a later report without them leaves no file of the earlier one.
#[test]
fn svg_files_only_on_request() {
    let s = fixture::summary();
    let dir = fixture::temp_dir("svg-files");
    fixture::write_series(&dir.join("series"), &s, |_| false);
    let out = dir.join("report");
    let on = Extras {
        svg_files: true,
        ..Default::default()
    };
    let files = write_report(&s, &dir.join("series"), &[], on, &out).unwrap();
    assert!(!files.svgs.is_empty() && out.join("svg").is_dir());
    let files = write_report(&s, &dir.join("series"), &[], Extras::default(), &out).unwrap();
    assert!(files.svgs.is_empty());
    assert!(
        !out.join("svg").exists(),
        "the earlier report's plot files are gone"
    );
    let html = std::fs::read_to_string(&files.index_html).unwrap();
    assert!(
        html.matches("<svg").count() > 0,
        "the page still inlines its plots"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Pseudo-time is labelled as what it is: a static scene's `t` is the load factor and a
/// cyclic scene's the protocol's increments (never seconds), a dynamic scene's `t` is in
/// seconds; an RMS metric is not captioned as a max.
#[test]
fn stepped_parameter_and_aggregate_labels() {
    let cases = crate::catalogue::embedded().unwrap();
    let mut seen = std::collections::BTreeMap::new();
    for c in &cases {
        let f = crate::catalogue::family_of(c);
        for s in &c.scenes {
            let (t, step) = (f.figures.t_axis)(s);
            seen.insert((c.name.clone(), s.name.clone()), (t, step));
        }
    }
    let of = |case: &str| {
        seen.iter()
            .filter(|((c, _), _)| c == case)
            .map(|(_, v)| *v)
            .collect::<Vec<_>>()
    };
    assert!(of("fiber_column_static").iter().all(|(t, s)| {
        t.starts_with("load factor") && s.contains("load factor") && !t.contains("(s)")
    }));
    assert!(of("fiber_column_cyclic").iter().all(|(t, s)| {
        t.starts_with("protocol increment") && s.contains("protocol") && !s.contains("(s)")
    }));
    for case in ["fiber_column_dynamic", "nine_spring", "flexible_beam"] {
        assert!(!of(case).is_empty(), "{case}");
        assert!(
            of(case)
                .iter()
                .all(|(t, s)| *t == "t (s)" && *s == "step dt (s)")
        );
    }
    assert_eq!(
        data::aggregate("base_shear_error_rms"),
        " (RMS over the run)"
    );
    assert_eq!(data::aggregate("rotation_error_max"), " (max over the run)");
    assert_eq!(data::aggregate("tip_error"), "");
}

/// Every part of a case but its narrative is folded and none opens by itself (the heat maps,
/// one per scene, each scene's plots, the tables), and the case states the environment.
#[test]
fn case_parts_are_folded() {
    let s = fixture::summary();
    let cases = crate::catalogue::embedded().unwrap();
    let page = build_page(&s, std::path::Path::new("/nonexistent"), &cases, None, None);
    let html = html::render(&page);
    let sec = fixture::case_section(&html, fixture::CASE);
    // Every part of the case but its narrative is folded and none opens by itself: the heat
    // maps (one per scene), each scene's plots, the tables.
    let heat = sec.find("data-section=\"heatmaps\"").expect("heat maps");
    assert!(
        sec[..heat].ends_with("<details class=\"part\" "),
        "{}",
        &sec[..heat]
    );
    let narrative = sec.find("data-section=\"narrative\"").unwrap();
    assert!(!sec[..narrative].contains("<details"));
    for t in html::start_tags(sec).iter().filter(|t| t.name == "details") {
        assert!(!t.attrs.iter().any(|(n, _)| n == "open"), "{t:?}");
    }
    assert_eq!(
        sec.matches("<details class=\"scene\"").count(),
        fixture::SCENES.len()
    );
    assert_eq!(
        sec.matches("<table class=\"heatmap\">").count(),
        fixture::SCENES.len()
    );
    let env = env_line(&s);
    for part in [
        "abc1234",
        "2026-01-02T03:04:05Z",
        "rustc 1.95.0",
        "Test CPU",
        "Test OS",
    ] {
        assert!(env.contains(part), "{part}");
    }
    assert!(
        sec.contains(&html::esc(&env)),
        "env line in the case section"
    );
}
