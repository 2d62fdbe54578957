//! The long-horizon part: energy and momentum error against t (log-log, from the series
//! files beside stability.json) with the growth exponent in the legend, one panel per
//! integrator kind (`integrate::MethodKind`; each method beside its Kahan-compensated twin, at
//! most eight lines; the kinds are the study's facts, its `methods` table), and a table of
//! exponents and final errors.
use super::*;
use crate::integrate::MethodKind;
use crate::report::select::kind_of;

/// The columns of a long-horizon series file: `t`, energy error, momentum error (None when the
/// body conserves no momentum component).
pub(super) type LongSeries = (Vec<f64>, Vec<f64>, Option<Vec<f64>>);

pub(super) fn load_long_series(dir: &Path, r: &Record) -> Option<LongSeries> {
    let id = crate::summary::run_id(
        &r.key.param,
        &r.key.integrator,
        &r.key.formulation,
        r.dt,
        r.tol,
    );
    let mut candidates = vec![];
    if let Some(rel) = &r.series {
        candidates.push(std::path::PathBuf::from(rel));
    }
    candidates.push(
        Path::new("series/long_horizon")
            .join(&r.key.case)
            .join(&r.key.scene)
            .join(format!("{id}.json")),
    );
    let v = candidates
        .iter()
        .find_map(|rel| crate::report::data::load_json_inside(dir, rel))?;
    Some((
        column(&v, "t")?,
        column(&v, "energy_error")?,
        column(&v, "momentum_error"),
    ))
}

/// Column `name` of a series file's JSON (a non-number, e.g. `null`, reads as NaN).
pub(super) fn column(v: &serde_json::Value, name: &str) -> Option<Vec<f64>> {
    v.get(name)?
        .as_array()?
        .iter()
        .map(|x| x.as_f64().or(Some(f64::NAN)))
        .collect()
}

/// The long-horizon plots of one scene (energy, and momentum when any record has it).
pub(super) fn long_plots(
    methods: &Methods,
    case: &str,
    scene: &str,
    rs: &[&Record],
    dir: &Path,
    footer: &str,
) -> Vec<Plot> {
    let loaded: Vec<(&Record, Option<LongSeries>)> =
        rs.iter().map(|r| (*r, load_long_series(dir, r))).collect();
    let mut out = vec![];
    let kinds: Vec<MethodKind> = MethodKind::ALL
        .into_iter()
        .filter(|k| rs.iter().any(|r| kind_of(methods, &r.key.integrator) == *k))
        .collect();
    for (momentum, kind) in [false, true]
        .into_iter()
        .flat_map(|m| kinds.iter().map(move |k| (m, *k)))
    {
        let metric = if momentum {
            "momentum_growth_exponent"
        } else {
            "energy_growth_exponent"
        };
        if !rs.iter().any(|r| r.metrics.contains_key(metric)) {
            continue;
        }
        let mut lines = vec![];
        let mut missing = vec![];
        let mut steps: BTreeSet<String> = BTreeSet::new();
        for (r, s) in loaded
            .iter()
            .filter(|(r, _)| kind_of(methods, &r.key.integrator) == kind)
        {
            let key = VariantKey::of(&r.key);
            if (!momentum || r.metrics.contains_key(metric))
                && let Some(n) = r.metrics.get("long_horizon_steps").copied().flatten()
            {
                steps.insert(num(n));
            }
            let Some((t, e, m)) = s else {
                missing.push(format!("{} (no series file)", key.label()));
                continue;
            };
            let ys = if momentum {
                match m {
                    Some(m) => m,
                    None => continue,
                }
            } else {
                e
            };
            let points: Vec<(f64, f64)> = t.iter().copied().zip(ys.iter().copied()).collect();
            let p = match r.metrics.get(metric).copied().flatten() {
                Some(p) => format!("p = {}", decimals(p, 2)),
                None => "p -".into(),
            };
            let n = points.len();
            lines.push(Line {
                key: key.clone(),
                points,
                label: Some(format!("{} / {}: {p}", key.param, key.integrator)),
                marker_every: (n / 8).max(1),
            });
        }
        let (name, y) = if momentum {
            ("momentum error", "max |L_i - L_i(0)| / |L(0)|")
        } else {
            ("energy error", "|E - E0| / max(|E0|, E_scale)")
        };
        let mut caption = format!(
            "The relative {name} of each variant against t (log-log) over {} steps of the \
             dt in the table below, at 200 log-spaced times; p in the legend is the fitted \
             growth exponent of its running maximum over the last two decades (error ~ t^p: 1 \
             drift, 0 bounded, 1/2 round-off random walk). Exact zeros are not drawn.",
            if steps.is_empty() {
                "-".to_string()
            } else {
                steps.into_iter().collect::<Vec<_>>().join(" or ")
            }
        );
        if !missing.is_empty() {
            caption.push_str(&format!(" No data: {}.", missing.join("; ")));
        }
        caption.push_str(&format!(
            " This panel: the {} methods; the other kinds are in the panels beside it.",
            kind.name()
        ));
        out.push(Plot {
            id: format!(
                "stability/long_{scene}_{}_{}",
                if momentum { "momentum" } else { "energy" },
                kind.name()
            ),
            title: format!(
                "{case}/{scene}: {name} over a long horizon ({} methods)",
                kind.name()
            ),
            x_label: "t (s)".into(),
            y_label: y.into(),
            x: Scale::Log,
            y: Scale::Log,
            ..Plot::per_line(lines, caption, footer)
        });
    }
    out
}

/// The long-horizon table of a case.
pub(super) fn long_table(case: &str, rs: &[&Record]) -> Table {
    let rows = rs
        .iter()
        .map(|r| {
            let mut row = variant_cells(&VariantKey::of(&r.key)).to_vec();
            row.insert(0, Cell::plain(&r.key.scene));
            row.push(Cell::plain(r.dt.map(num).unwrap_or_else(|| "-".into())));
            row.push(
                match r.metrics.get("long_horizon_steps").copied().flatten() {
                    Some(n) => Cell::plain(format!("{n:.0}")),
                    None => Cell::plain("-"),
                },
            );
            row.push(status_cell(r));
            for m in [
                "energy_growth_exponent",
                "momentum_growth_exponent",
                "energy_error_final",
                "momentum_error_final",
            ] {
                let mut c = metric_text(r, m);
                if m.ends_with("_exponent")
                    && let Some(Some(p)) = r.metrics.get(m)
                {
                    c.text = decimals(*p, 3);
                }
                row.push(c);
            }
            row
        })
        .collect();
    Table {
        kind: "stability-long-horizon",
        title: format!("{case}: long horizon"),
        note: "Growth exponents p of the energy and momentum errors (fitted on their running \
               maximum over the last two decades of t: ~1 truncation drift, ~0 bounded, ~1/2 \
               round-off random walk) and the errors at the end. `-`: the body conserves no \
               momentum component; `null`: no exponent (hover, or the markdown, for why)."
            .into(),
        header: [
            "scene",
            "param",
            "integrator",
            "formulation",
            "dt",
            "steps",
            "status",
            "energy exponent",
            "momentum exponent",
            "final energy error",
            "final momentum error",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    }
}
