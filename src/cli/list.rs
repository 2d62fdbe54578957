//! `mbdbench list`: the cases and scenes, the registered variants of every family and the
//! `n/a` combinations with their reasons; `--json` for tools (scenes with their variant matrix).
use super::*;

pub(super) fn cmd_list(common: &Common, json: bool) -> Result<i32, String> {
    let cases = load_cases(common)?;
    let catalogue = common.catalogue();
    let problems = catalogue.problems(&cases, &[], &[])?;
    // The families the cases use, in family-table order (the catalogue's copies, with the
    // methods it registered).
    let families: Vec<&'static Family> = catalogue
        .families()
        .iter()
        .copied()
        .filter(|f| problems.iter().any(|p| std::ptr::eq(p.family(), *f)))
        .collect();
    let registered: usize = families.iter().map(|f| f.variants().len()).sum();
    let mut scenes = vec![];
    for p in &problems {
        let variants: Vec<_> = problem::matrix(p.family())
            .map(|cell| {
                let (status, reason) = match cell.entry {
                    Entry::NotApplicable(why) => ("n/a", Some(why)),
                    Entry::Registered(v) => match p.na_reason(v) {
                        Some(r) => ("n/a", Some(r)),
                        None => ("run", None),
                    },
                };
                serde_json::json!({
                    "param": cell.param, "integrator": cell.integrator,
                    "formulation": cell.formulation, "status": status, "reason": reason,
                })
            })
            .collect();
        scenes.push(serde_json::json!({
            "case": p.case(), "scene": p.scene(), "t_end": p.t_end(),
            "variants": variants,
        }));
    }
    if json {
        let v = serde_json::json!({ "scenes": scenes, "registered": registered });
        crate::say!(
            "{}",
            serde_json::to_string_pretty(&v).map_err(|e| e.to_string())?
        );
        return Ok(EXIT_OK);
    }
    for c in &cases {
        crate::say!("{} — {}", c.name, c.title);
        for s in &c.scenes {
            crate::say!("  scene {} (t_end {} s)", s.name, s.t_end);
        }
    }
    crate::say!("\nregistered variants: {registered}");
    for v in families.iter().flat_map(|f| f.variants()) {
        crate::say!(
            "  {:<12} {:<18} {:<8} order {} {}{}{}",
            v.param,
            v.integrator,
            v.formulation,
            v.info.order,
            if v.info.adaptive { "adaptive " } else { "" },
            if v.info.implicit {
                "implicit "
            } else {
                "explicit "
            },
            if v.info.lie_group { "lie-group" } else { "" }
        );
    }
    crate::say!("\nnot applicable:");
    let mut seen = BTreeMap::new();
    for cell in families.iter().flat_map(|f| problem::matrix(f)) {
        if let Entry::NotApplicable(why) = cell.entry {
            seen.entry(why).or_insert_with(Vec::new).push(format!(
                "{}/{}/{}",
                cell.param, cell.integrator, cell.formulation
            ));
        }
    }
    for (reason, list) in seen {
        crate::say!("  {} combinations: {reason}", list.len());
    }
    for p in &problems {
        for v in p.family().variants() {
            if let Some(r) = p.na_reason(v) {
                crate::say!(
                    "  {}/{}: {}/{}/{}: {r}",
                    p.case(),
                    p.scene(),
                    v.param,
                    v.integrator,
                    v.formulation
                );
            }
        }
    }
    Ok(EXIT_OK)
}
