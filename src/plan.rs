//! From validated case files to the suite's scene plans: the compiled model, the initial
//! state, the grid, the work limits, the ladders and the physics hash of each scene.
use crate::case::{Case, Ladder, OrderClass, Scene};
use crate::suite::Ladders;

/// The ladder values of a scene's tier (steps per order class, tolerances).
pub fn ladders(l: &Ladder) -> Ladders {
    let dts = |c: OrderClass| l.fixed(c).iter().map(|s| s.dt).collect::<Vec<_>>();
    Ladders {
        order1: dts(OrderClass::Order1),
        order2_4: dts(OrderClass::Order2To4),
        order6: dts(OrderClass::Order6),
        tol: l.tol.clone(),
    }
}

/// The selected cases and scenes (empty filter lists select all), in file order. A name in
/// a filter that matches nothing is an error.
pub fn select<'c>(
    cases: &'c [Case],
    case_filter: &[String],
    scene_filter: &[String],
) -> Result<Vec<(&'c Case, &'c Scene)>, String> {
    for c in case_filter {
        if !cases.iter().any(|k| &k.name == c) {
            return Err(format!(
                "--case {c}: no such case (known: {})",
                cases
                    .iter()
                    .map(|k| k.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
    }
    let mut out = vec![];
    for c in cases {
        if !case_filter.is_empty() && !case_filter.contains(&c.name) {
            continue;
        }
        for s in &c.scenes {
            if !scene_filter.is_empty() && !scene_filter.contains(&s.name) {
                continue;
            }
            out.push((c, s));
        }
    }
    for s in scene_filter {
        if !out.iter().any(|(_, sc)| &sc.name == s) {
            return Err(format!("--scene {s}: no such scene in the selected cases"));
        }
    }
    Ok(out)
}

/// The compiled problems of the selected cases and scenes, each by its case's family.
pub fn problems(
    cases: &[Case],
    case_filter: &[String],
    scene_filter: &[String],
) -> Result<Vec<Box<dyn crate::problem::Problem>>, String> {
    select(cases, case_filter, scene_filter)?
        .into_iter()
        .map(|(c, s)| (crate::problem::family_of(c).compile)(c, s).map_err(|e| e.to_string()))
        .collect()
}
