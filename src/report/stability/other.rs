//! Everything the other parts do not draw (n/a records, metrics and fits of later parts):
//! generic tables of their values, so nothing in stability.json is dropped.
use super::*;

/// Records of kinds this part does not know: a generic table of their metrics.
pub(super) fn other_table(case: &str, rs: &[&Record]) -> Table {
    let metrics: BTreeSet<&str> = rs
        .iter()
        .flat_map(|r| r.metrics.keys().map(String::as_str))
        .collect();
    let rows = rs
        .iter()
        .map(|r| {
            let mut row = vec![Cell::plain(&r.key.scene)];
            row.extend(variant_cells(&VariantKey::of(&r.key)));
            row.push(Cell::plain(crate::report::data::step_label(r)));
            row.push(status_cell(r));
            row.extend(metrics.iter().map(|m| metric_text(r, m)));
            row
        })
        .collect();
    let mut header: Vec<String> = [
        "scene",
        "param",
        "integrator",
        "formulation",
        "step",
        "status",
    ]
    .map(String::from)
    .to_vec();
    header.extend(metrics.iter().map(|m| m.to_string()));
    Table {
        kind: "stability-other",
        title: format!("{case}: other stability records"),
        note: "Records of stability.json that are neither step searches nor long-horizon runs \
               (later parts of the study, n/a combinations), with every metric they carry; \
               `-`: absent, `null`: not computed (hover, or the markdown, for why)."
            .into(),
        header,
        rows,
    }
}

/// Fits of kinds this part does not draw.
pub(super) fn other_fits_table(case: &str, fs: &[&FitRecord]) -> Table {
    let rows = fs
        .iter()
        .map(|f| {
            let mut row = vec![Cell::plain(&f.key.scene)];
            row.extend(variant_cells(&VariantKey::of(&f.key)));
            row.push(Cell::plain(&f.metric));
            row.push(Cell::plain(
                f.order.map(|p| decimals(p, 3)).unwrap_or("null".into()),
            ));
            row.push(Cell::abridged(
                abbreviate(f.reason.as_deref().unwrap_or(""), 48),
                f.reason.clone().unwrap_or_default(),
            ));
            row.push(Cell::plain(f.points.len().to_string()));
            row
        })
        .collect();
    Table {
        kind: "stability-other",
        title: format!("{case}: other stability fits"),
        note: "Fits of stability.json not drawn above, with their fitted value.".into(),
        header: [
            "scene",
            "param",
            "integrator",
            "formulation",
            "metric",
            "value",
            "reason",
            "points",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    }
}
