//! Tests of `chart`: rendering to the file and inline SVGs, end labels, no-data, the
//! round-off sentence and the dots of a category axis (kept apart so `chart.rs` stays one
//! screenful of drawing code under the project's file-size limit).
use super::*;
use crate::report::axes::Scale;

fn key(p: &str, i: &str, f: &str) -> VariantKey {
    VariantKey {
        param: p.into(),
        integrator: i.into(),
        formulation: f.into(),
    }
}

fn plot(lines: Vec<Line>, fails: Vec<FailMark>) -> Plot {
    Plot {
        id: "t".into(),
        title: "title".into(),
        x_label: "x".into(),
        y_label: "y".into(),
        x: Scale::Log,
        y: Scale::Log,
        lines,
        fails,
        legend: Legend::Factored,
        caption: String::new(),
        footer: "footer".into(),
        round_off: None,
    }
}

/// A plot renders to one SVG element with the end labels of both log axes, the legend's
/// names and the failed band.
#[test]
fn renders_svg_with_end_labels() {
    let p = plot(
        vec![Line {
            key: key("so3", "rk4", "spatial"),
            points: vec![(1e-3, 2e-8), (1e-1, 3e-4)],
            label: None,
            marker_every: 1,
        }],
        vec![FailMark {
            key: key("euler_zxz", "rk4", "body"),
            x: 0.0,
        }],
    );
    let Rendered::Svg(d) = render(&p).unwrap() else {
        panic!("no svg")
    };
    assert_eq!(d.lines, 1);
    assert!(d.inline.starts_with("<svg") && !d.inline.contains("\neuler_zxz\n"));
    let s = d.file;
    assert!(s.starts_with("<svg"), "{}", &s[..40]);
    assert_eq!(s.matches("<svg").count(), 1);
    // plotters writes each text on its own line inside <text>.
    for t in [
        "1e-3",
        "1e-1",
        "1e-8",
        "failed",
        "rk4",
        "so3",
        "euler_zxz",
        "spatial",
        "footer",
    ] {
        assert!(s.contains(&format!("\n{t}\n")), "missing {t}");
    }
    assert!(!s.contains("href") && !s.contains(" src="));
}

/// A relative quantity whose every value is below `ROUND_OFF` becomes one sentence with
/// a bound computed from the data (strictly above the largest value); one value above
/// round-off brings the plot back.
#[test]
fn round_off_is_one_sentence() {
    assert_eq!(bound_above(2.2e-16), "3e-16");
    assert_eq!(bound_above(9.5e-15), "1e-14");
    let mut p = plot(
        vec![Line {
            key: key("so3", "rk4", "body"),
            points: vec![(1.0, 2.2e-16), (2.0, 1e-16)],
            label: None,
            marker_every: 1,
        }],
        vec![],
    );
    p.round_off = Some("constraint residual (so3)".into());
    match render(&p).unwrap() {
        Rendered::Note(s) => assert!(
            s.starts_with("constraint residual (so3) stays below 3e-16"),
            "{s}"
        ),
        other => panic!("{other:?}"),
    }
    p.lines[0].points.push((3.0, 1e-9));
    assert!(matches!(render(&p).unwrap(), Rendered::Svg(_)));
}

/// On a category axis the points are dots: no polyline joins them, but each series is
/// still counted.
#[test]
fn categories_are_not_joined() {
    let mut p = plot(
        vec![Line {
            key: key("so3", "rk4", "body"),
            points: vec![(0.0, 1e-3), (1.0, 1e-4), (2.0, 1e-5)],
            label: None,
            marker_every: 1,
        }],
        vec![],
    );
    p.x = Scale::Category(vec!["a".into(), "b".into(), "c".into()]);
    let Rendered::Svg(d) = render(&p).unwrap() else {
        panic!("no svg")
    };
    assert_eq!(d.lines, 1);
    assert_eq!(d.inline.matches("<g class=\"series\"").count(), 1);
    // The series group holds no line (plotters' own axes are polylines too).
    assert!(
        d.inline
            .contains("<g class=\"series\" data-variant=\"so3 / rk4 / body\">\n</g>"),
        "{}",
        d.inline
    );
    p.x = Scale::Linear;
    let Rendered::Svg(d) = render(&p).unwrap() else {
        panic!("no svg")
    };
    // The file keeps its polyline; the page's copy draws it as a path (`svg_page`).
    assert!(
        d.file
            .contains("<g class=\"series\" data-variant=\"so3 / rk4 / body\">\n<polyline")
    );
    assert!(
        d.inline.contains(
            "<g class=\"series\" data-variant=\"so3 / rk4 / body\">\n<path fill=\"none\""
        ),
        "{}",
        d.inline
    );
}

/// Lines without representable values and no failures give "no data".
#[test]
fn no_data() {
    let p = plot(
        vec![Line {
            key: key("so3", "rk4", "body"),
            points: vec![(0.0, 1.0), (1.0, f64::NAN)],
            label: None,
            marker_every: 1,
        }],
        vec![],
    );
    assert!(matches!(render(&p).unwrap(), Rendered::NoData(_)));
}

/// Two lines of one integrator and formulation on two charts get different line patterns
/// (no two lines of a panel share colour and pattern), and the legend names each chart and
/// formulation with its pattern in place of the formulation rows.
#[test]
fn one_integrator_on_two_charts_has_two_patterns() {
    let line = |p: &str| Line {
        key: key(p, "rk4", "body"),
        points: vec![(1e-3, 2e-8), (1e-1, 3e-4)],
        label: None,
        marker_every: 1,
    };
    let p = plot(vec![line("quat"), line("so3")], vec![]);
    let Rendered::Svg(d) = render(&p).unwrap() else {
        panic!("no svg")
    };
    // The inline chart writes each series as a group holding its line (a path there).
    let dashes: Vec<&str> = d
        .inline
        .split("<g class=\"series\"")
        .skip(1)
        .map(|s| {
            let group = s.split("</g>").next().unwrap();
            group
                .split("stroke-dasharray=\"")
                .nth(1)
                .map_or("solid", |r| r.split('"').next().unwrap())
        })
        .collect();
    assert_eq!(dashes.len(), 2, "{dashes:?}");
    assert_ne!(dashes[0], dashes[1]);
    let texts: Vec<String> = legend_entries(&p)
        .iter()
        .map(|e| match e {
            Entry::Heading(t) => t.clone(),
            Entry::Sample { text, pattern, .. } => format!("{text}:{pattern}"),
        })
        .collect();
    assert!(texts.contains(&"quat/body:0".to_string()), "{texts:?}");
    assert!(texts.contains(&"so3/body:1".to_string()), "{texts:?}");
    assert!(
        !texts.iter().any(|t| t.starts_with("formulation")),
        "{texts:?}"
    );
}
