//! The step search's part of the stability section: one table per scene of each variant's
//! largest stable and accurate step or tolerance with what limits it, and the facts sentence
//! (variants bounded only by the cap, the most restrictive stable step).
use super::*;

/// The step-search table of one scene.
pub(super) fn step_table(case: &str, scene: &str, records: &[&Record]) -> Table {
    let mut rows = vec![];
    let mut rs: Vec<&Record> = records.to_vec();
    rs.sort_by_key(|r| VariantKey::of(&r.key));
    let mut horizons: Vec<f64> = vec![];
    for r in rs {
        let Some(sm) = stable_metric(r) else { continue };
        let am = sm.replace("stable", "accurate");
        let adaptive = sm.ends_with("_tol");
        let mut row: Vec<Cell> = variant_cells(&VariantKey::of(&r.key)).to_vec();
        for m in [sm, am.as_str()] {
            let why = r.metric_reasons.get(m).map(String::as_str).unwrap_or("");
            row.push(step_cell(
                r.metrics.get(m).copied().flatten(),
                adaptive,
                why,
            ));
            row.push(Cell::abridged(short_reason(why), why));
        }
        let th = r.metrics.get("stability_horizon").copied().flatten();
        if let Some(h) = th
            && !horizons.iter().any(|x| (x - h).abs() <= 1e-12 * h.abs())
        {
            horizons.push(h);
        }
        row.push(Cell::plain(th.map(time).unwrap_or_else(|| "-".into())));
        rows.push(row);
    }
    let capped_n = rows.iter().filter(|r| r[3].text.ends_with("(cap)")).count();
    let horizon = match horizons.as_slice() {
        [h] => format!("t_h = {} s", time(*h)),
        _ => "t_h per row".to_string(),
    };
    Table {
        kind: "stability-steps",
        title: format!("{case} / {scene}: largest stable and accurate step"),
        note: format!(
            "{horizon}; {} variant{}, {capped_n} stable up to the cap (the coarsest step tried).",
            rows.len(),
            if rows.len() == 1 { "" } else { "s" }
        ),
        header: [
            "param",
            "integrator",
            "formulation",
            "largest stable dt / tol",
            "what limits it",
            "largest accurate dt / tol",
            "what limits it",
            "t_h (s)",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    }
}

/// Sentences computed from the step searches of the case file's scenes: the variants bounded
/// up to the cap everywhere, and the most restrictive stable step.
pub(super) fn search_facts(search: &[&Record], case: Option<&Case>) -> Vec<String> {
    let own: Vec<&Record> = search
        .iter()
        .copied()
        .filter(|r| case.is_none() || in_case_file(case, &r.key.scene))
        .collect();
    let mut out = vec![];
    let mut by_variant: BTreeMap<VariantKey, Vec<bool>> = BTreeMap::new();
    for r in &own {
        let Some(sm) = stable_metric(r) else { continue };
        let why = r.metric_reasons.get(sm).map(String::as_str).unwrap_or("");
        by_variant
            .entry(VariantKey::of(&r.key))
            .or_default()
            .push(capped(why));
    }
    let always: Vec<String> = by_variant
        .iter()
        .filter(|(_, c)| c.iter().all(|x| *x))
        .map(|(k, _)| k.label())
        .collect();
    if !always.is_empty() {
        out.push(format!(
            "Stable up to the cap (the coarsest step tried) in every searched scene, i.e. no stability limit \
             found: {}.",
            always.join(", ")
        ));
    }
    let smallest = own
        .iter()
        .filter_map(|r| {
            let sm = stable_metric(r)?;
            let v = r.metrics.get(sm).copied().flatten()?;
            Some((sm.ends_with("_dt"), v, *r, sm))
        })
        .filter(|x| x.0)
        .min_by(|a, b| a.1.total_cmp(&b.1));
    if let Some((_, v, r, sm)) = smallest {
        out.push(format!(
            "The most restrictive stable step is {} in {} at dt {} ({}).",
            VariantKey::of(&r.key).label(),
            r.key.scene,
            num(v),
            short_reason(r.metric_reasons.get(sm).map(String::as_str).unwrap_or(""))
        ));
    }
    out
}
