//! `terminal`: `run`'s account of a summary on the terminal: one line per case by default
//! ([`print_brief`]: scenes, variants, runs, typed failures by kind, `n/a`), the full table with
//! `--verbose` ([`print_table`]: per scene, one row per variant at its finest ladder point, with
//! its primary error, energy drift, conditioning, fitted order, work and status). The same
//! tables, with plots, are in `index.html`.
use std::collections::BTreeMap;

use crate::case::Case;
use crate::catalogue::Ordered;
use crate::summary::{Record, Status, Summary};

/// Formats a number for the terminal table.
fn num(v: Option<f64>) -> String {
    match v {
        Some(x) => format!("{x:9.2e}"),
        None => format!("{:>9}", "-"),
    }
}

/// One line per case (scenes, variants, runs, typed failures by kind): `run`'s account
/// without `--verbose` (the full table is in `index.html` and behind `run --verbose`).
pub fn print_brief(s: &Summary, out: &mut impl std::io::Write) -> std::io::Result<()> {
    #[derive(Default)]
    struct Count<'a> {
        scenes: std::collections::BTreeSet<&'a str>,
        variants: std::collections::BTreeSet<[usize; 3]>,
        runs: usize,
        na: usize,
        failed: BTreeMap<&'static str, usize>,
    }
    let mut by_case: BTreeMap<&str, Count> = BTreeMap::new();
    for r in &s.records {
        let c = by_case.entry(r.key.case.as_str()).or_default();
        c.scenes.insert(&r.key.scene);
        if r.status == Status::NotApplicable {
            c.na += 1;
            continue;
        }
        c.variants.insert(r.variant_order());
        c.runs += 1;
        if let Some(f) = &r.failure {
            *c.failed.entry(f.kind.name()).or_default() += 1;
        }
    }
    for (case, c) in by_case {
        let failed: usize = c.failed.values().sum();
        let kinds: Vec<String> = c.failed.iter().map(|(k, n)| format!("{n} {k}")).collect();
        writeln!(
            out,
            "{case}: {}, {} variants, {} runs, {failed} with a typed failure{}, {} n/a",
            crate::summary::count(c.scenes.len(), "scene"),
            c.variants.len(),
            c.runs,
            if kinds.is_empty() {
                String::new()
            } else {
                format!(" ({})", kinds.join(", "))
            },
            c.na
        )?;
    }
    Ok(())
}

/// A readable table: per scene, one row per variant (finest ladder point).
pub fn print_table(
    s: &Summary,
    cases: &[Case],
    out: &mut impl std::io::Write,
) -> std::io::Result<()> {
    let mut by_scene: BTreeMap<(String, String), Vec<&Record>> = BTreeMap::new();
    for r in &s.records {
        by_scene
            .entry((r.key.case.clone(), r.key.scene.clone()))
            .or_default()
            .push(r);
    }
    let fits: BTreeMap<(&str, &str, &str, &str, &str), Option<f64>> = s
        .fits
        .iter()
        .map(|f| {
            (
                (
                    f.key.case.as_str(),
                    f.key.scene.as_str(),
                    f.key.param.as_str(),
                    f.key.integrator.as_str(),
                    f.key.formulation.as_str(),
                ),
                f.order,
            )
        })
        .collect();
    for ((case, scene), rs) in by_scene {
        writeln!(out, "\n{case}/{scene}")?;
        writeln!(
            out,
            "  {:<12} {:<18} {:<8} {:>9} {:>9} {:>9} {:>9} {:>6} {:>10}  status",
            "param",
            "integrator",
            "form",
            "dt|tol",
            "primary",
            "E drift",
            "cond min",
            "order",
            "rhs evals"
        )?;
        let mut last: BTreeMap<(&str, &str, &str), &Record> = BTreeMap::new();
        let mut failures: BTreeMap<(&str, &str, &str), usize> = BTreeMap::new();
        for r in &rs {
            if r.status == Status::NotApplicable {
                continue;
            }
            let k = (
                r.key.param.as_str(),
                r.key.integrator.as_str(),
                r.key.formulation.as_str(),
            );
            last.insert(k, r);
            if r.status == Status::Failed {
                *failures.entry(k).or_default() += 1;
            }
        }
        let case_file = cases.iter().find(|c| c.name == case);
        let primary = case_file
            .map(|c| c.primary_metric.clone())
            .unwrap_or_else(|| {
                let family = crate::catalogue::family_of_case(case_file, last.values().copied());
                family.default_primary().to_string()
            });
        let mut keys: Vec<_> = last.keys().copied().collect();
        keys.sort_by_key(|(p, i, f)| crate::catalogue::variant_order(p, i, f));
        for k in keys {
            let r = last[&k];
            let order = fits
                .get(&(case.as_str(), scene.as_str(), k.0, k.1, k.2))
                .copied()
                .flatten()
                .map(|o| format!("{o:6.2}"))
                .unwrap_or_else(|| format!("{:>6}", "-"));
            let status = match (&r.failure, failures.get(&k)) {
                (Some(f), _) => format!("failed {} t={:.3}", f.kind.name(), f.t),
                (None, Some(n)) => format!("ok ({n} coarser failed)"),
                (None, None) => "ok".into(),
            };
            writeln!(
                out,
                "  {:<12} {:<18} {:<8} {} {} {} {} {} {:>10}  {}",
                k.0,
                k.1,
                k.2,
                num(r.dt.or(r.tol)),
                num(r.metrics.get(&primary).copied().flatten()),
                num(r.metrics.get("energy_drift_max").copied().flatten()),
                num(r.metrics.get("conditioning_min").copied().flatten()),
                order,
                r.stats.rhs_evals,
                status
            )?;
        }
    }
    Ok(())
}
