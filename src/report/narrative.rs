//! "What this shows": a paragraph per case generated only from the summary's numbers, never
//! from hand-written claims. Each sentence comes from a computed fact:
//!
//! - per scene, the cheapest completed run whose primary error is at most the tightest target
//!   the recommendation offers for the case (`paragraph_with`: `advise`'s offered targets;
//!   `TARGET`, 1e-6, when there is no recommendation), by RHS
//!   evaluations (deterministic) and by wall time (`wall_s.min`), or the smallest error reached
//!   when none gets there; a control scene (`control = true`) is marked as such;
//! - the failures, counted by kind, with the parameterizations and integrators involved;
//! - for the family's chart group (`problem::figures::ChartGroup`; the rigid body's Euler-angle
//!   charts): their lowest minimum conditioning, their failure rate against the other charts',
//!   and the largest RHS-evaluation ratio of an adaptive method on a chart of the group to the
//!   same method, formulation, tolerance and scene on the group's comparison chart (`so3`: the
//!   cost of adapting the step near a singular set);
//! - the fitted orders: per integrator, the median observed order over its fits;
//! - how many combinations are `n/a`.
//!
//! Ties are broken by registry order (the first variant in the ordering of `data`), then by
//! coarser ladder value, so the text is deterministic.
use std::collections::BTreeMap;

use super::data::{CaseView, SceneView, VariantKey, num, step_label};
use super::tables::kind_name;
use crate::catalogue::axis_names;
use crate::problem::Axis;
use crate::summary::{Record, Status};

/// The accuracy a "cheapest" run must reach (primary metric, its own units).
pub const TARGET: f64 = 1e-6;

/// The cheapest runs of a scene reaching the target.
#[derive(Debug, Clone, Copy)]
pub struct Cheapest<'a> {
    pub by_rhs: Option<&'a Record>,
    pub by_wall: Option<&'a Record>,
    /// The smallest primary error of any completed run, with its run.
    pub best: Option<(&'a Record, f64)>,
}

fn error(r: &Record, primary: &str) -> Option<f64> {
    r.metrics
        .get(primary)
        .copied()
        .flatten()
        .filter(|e| e.is_finite())
}

/// Finds the cheapest runs of a scene reaching `target` on `primary`.
pub fn cheapest<'a>(sv: &SceneView<'a>, primary: &str, target: f64) -> Cheapest<'a> {
    let ok: Vec<&'a Record> = sv.runs().filter(|r| r.status == Status::Ok).collect();
    let reaching: Vec<&'a Record> = ok
        .iter()
        .copied()
        .filter(|r| error(r, primary).is_some_and(|e| e <= target))
        .collect();
    // `runs()` is in registry order, coarse to fine: `min_by` keeps the first of equals.
    let by_rhs = reaching
        .iter()
        .copied()
        .min_by(|a, b| a.stats.rhs_evals.cmp(&b.stats.rhs_evals));
    let by_wall = reaching
        .iter()
        .copied()
        .filter(|r| r.wall_s.is_some())
        .min_by(|a, b| {
            let (x, y) = (a.wall_s.map(|w| w.min), b.wall_s.map(|w| w.min));
            x.unwrap_or(f64::INFINITY)
                .total_cmp(&y.unwrap_or(f64::INFINITY))
        });
    let best = ok
        .iter()
        .filter_map(|r| error(r, primary).map(|e| (*r, e)))
        .min_by(|a, b| a.1.total_cmp(&b.1));
    Cheapest {
        by_rhs,
        by_wall,
        best,
    }
}

/// `so3 / rk4 / body at dt 1e-2`.
pub fn run_name(r: &Record) -> String {
    format!(
        "{} / {} / {} at {}",
        r.key.param,
        r.key.integrator,
        r.key.formulation,
        step_label(r)
    )
}

/// The largest RHS-evaluation ratio of an adaptive method on an Euler chart to the same
/// method on so3 (same scene, formulation, tolerance, both completed).
#[derive(Debug, Clone, Copy)]
pub struct EulerCost<'a> {
    pub euler: &'a Record,
    pub so3: &'a Record,
    pub ratio: f64,
}

/// Finds the largest cost ratio of the case's adaptive runs on a chart of the family's chart
/// group (Euler) to the same method on the group's comparison chart (so3).
pub fn euler_cost<'a>(cv: &CaseView<'a>) -> Option<EulerCost<'a>> {
    let group = cv.family.figures.chart_group?;
    let mut best: Option<EulerCost<'a>> = None;
    for s in &cv.scenes {
        for v in s
            .variants
            .iter()
            .filter(|v| v.adaptive && group.contains(&v.key.param))
        {
            let Some(g) = s.variant(group.compare_with, &v.key.integrator, &v.key.formulation)
            else {
                continue;
            };
            for r in v.ok() {
                let Some(tol) = r.tol else { continue };
                let Some(q) = g.at(tol).filter(|q| q.status == Status::Ok) else {
                    continue;
                };
                if q.stats.rhs_evals == 0 {
                    continue;
                }
                let ratio = r.stats.rhs_evals as f64 / q.stats.rhs_evals as f64;
                if best.is_none_or(|b| ratio > b.ratio) {
                    best = Some(EulerCost {
                        euler: r,
                        so3: q,
                        ratio,
                    });
                }
            }
        }
    }
    best
}

/// The run on a chart of the family's chart group (Euler) with the lowest `conditioning_min`.
pub fn min_conditioning<'a>(cv: &CaseView<'a>) -> Option<(&'a Record, f64)> {
    let group = cv.family.figures.chart_group?;
    cv.runs()
        .filter(|r| group.contains(&r.key.param))
        .filter_map(|r| {
            r.metrics
                .get("conditioning_min")
                .copied()
                .flatten()
                .map(|c| (r, c))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// A ratio with 3 significant digits, never in exponent form (`2740`, `35.2`, `1.07`).
pub fn ratio(x: f64) -> String {
    if x >= 100.0 {
        format!("{x:.0}")
    } else if x >= 10.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.2}")
    }
}

fn join_names(mut names: Vec<String>) -> String {
    names.dedup();
    names.join(", ")
}

fn scene_sentence(cv: &CaseView, sv: &SceneView, target: Target) -> String {
    let control = cv
        .case
        .and_then(|c| c.scene(&sv.name))
        .is_some_and(|s| s.control);
    let sentence = match target {
        Target::At(t, offered) => scene_facts(cv, sv, t, offered),
        Target::NoneOffered => no_target_facts(cv, sv),
    };
    if control {
        format!(
            "(Control scene, left out of the recommendation: a result known by construction.) \
             {sentence}"
        )
    } else {
        sentence
    }
}

/// The error a scene sentence names the cheapest run reaching.
#[derive(Debug, Clone, Copy)]
enum Target {
    /// A target; `true` when it is the tightest the recommendation offers.
    At(f64, bool),
    /// The recommendation offers no target for the case (all below its references' claims).
    NoneOffered,
}

/// A scene's sentence when no target is offered: the smallest error reached, and why no
/// cheapest run is named.
fn no_target_facts(cv: &CaseView, sv: &SceneView) -> String {
    let p = &cv.primary;
    match cheapest(sv, p, f64::NEG_INFINITY).best {
        Some((r, e)) => format!(
            "Scene {}: the recommendation offers no target error for this case (each lies \
             below 100x its references' accuracy claim); the smallest {p} was {} by {}.",
            sv.name,
            num(e),
            run_name(r)
        ),
        None => format!(
            "Scene {}: no completed run has a value of {p} (no data).",
            sv.name
        ),
    }
}

fn scene_facts(cv: &CaseView, sv: &SceneView, target: f64, offered: bool) -> String {
    let which = if offered {
        " (the tightest target the recommendation offers)"
    } else {
        ""
    };
    let c = cheapest(sv, &cv.primary, target);
    let p = &cv.primary;
    let ties = c.by_rhs.map_or(0, |a| {
        sv.runs()
            .filter(|r| {
                r.status == Status::Ok
                    && r.stats.rhs_evals == a.stats.rhs_evals
                    && error(r, p).is_some_and(|e| e <= target)
            })
            .count()
    });
    let tie = if ties > 1 {
        format!("; {ties} runs tie at this cost, the first in registry order is named")
    } else {
        String::new()
    };
    match (c.by_rhs, c.by_wall, c.best) {
        (Some(a), Some(b), _) => format!(
            "Scene {}: the cheapest run reaching {p} <= {}{which} is {} with {} RHS evaluations \
             ({p} {}{tie}); by wall time, {} in {} s ({p} {}).",
            sv.name,
            num(target),
            run_name(a),
            a.stats.rhs_evals,
            num(error(a, p).unwrap_or(f64::NAN)),
            run_name(b),
            num(b.wall_s.map(|w| w.min).unwrap_or(f64::NAN)),
            num(error(b, p).unwrap_or(f64::NAN)),
        ),
        (Some(a), None, _) => format!(
            "Scene {}: the cheapest run reaching {p} <= {}{which} is {} with {} RHS \
             evaluations ({p} {}{tie}); no wall time was recorded.",
            sv.name,
            num(target),
            run_name(a),
            a.stats.rhs_evals,
            num(error(a, p).unwrap_or(f64::NAN)),
        ),
        (None, _, Some((r, e))) => format!(
            "Scene {}: no run reached {p} <= {}{which}; the smallest was {} by {}.",
            sv.name,
            num(target),
            num(e),
            run_name(r)
        ),
        (None, _, None) => format!(
            "Scene {}: no completed run has a value of {p} (no data).",
            sv.name
        ),
    }
}

fn failure_sentence(cv: &CaseView) -> String {
    let total = cv.runs().count();
    let mut by_kind: BTreeMap<String, (usize, Vec<String>, Vec<String>)> = BTreeMap::new();
    for r in cv.runs().filter(|r| r.status == Status::Failed) {
        let kind = r
            .failure
            .as_ref()
            .map(|f| kind_name(f.kind))
            .unwrap_or_else(|| "unknown".into());
        let e = by_kind.entry(kind).or_default();
        e.0 += 1;
        e.1.push(r.key.param.clone());
        e.2.push(r.key.integrator.clone());
    }
    let failed: usize = by_kind.values().map(|e| e.0).sum();
    if failed == 0 {
        return format!("All {total} runs completed without a typed failure.");
    }
    let order = |list: &[&str], mut v: Vec<String>| {
        v.sort_by_key(|x| list.iter().position(|y| y == x).unwrap_or(usize::MAX));
        join_names(v)
    };
    let parts: Vec<String> = by_kind
        .into_iter()
        .map(|(kind, (n, ps, is))| {
            format!(
                "{kind} {n} ({} with {})",
                order(axis_names(Axis::Param), ps),
                order(axis_names(Axis::Integrator), is)
            )
        })
        .collect();
    format!(
        "{failed} of {total} runs ended with a typed failure: {}.",
        parts.join("; ")
    )
}

fn euler_sentences(cv: &CaseView) -> Vec<String> {
    let mut out = vec![];
    let Some(group) = cv.family.figures.chart_group else {
        return out;
    };
    let euler: Vec<&Record> = cv.runs().filter(|r| group.contains(&r.key.param)).collect();
    if euler.is_empty() {
        return out;
    }
    let other: Vec<&Record> = cv
        .runs()
        .filter(|r| !group.contains(&r.key.param))
        .collect();
    let ef = euler.iter().filter(|r| r.status == Status::Failed).count();
    let of = other.iter().filter(|r| r.status == Status::Failed).count();
    let mut s = format!(
        "{}: {ef} of {} runs failed, against {of} of {} runs of the other charts",
        group.label,
        euler.len(),
        other.len()
    );
    if let Some((r, c)) = min_conditioning(cv) {
        s.push_str(&format!(
            "; their lowest conditioning was {} ({} on scene {})",
            num(c),
            run_name(r),
            r.key.scene
        ));
    }
    s.push('.');
    out.push(s);
    if let Some(e) = euler_cost(cv) {
        out.push(format!(
            "At equal tolerance an adaptive method on {} needed up to {}x the RHS evaluations \
             of the same method on {}: {} on scene {} took {} against {}.",
            group.one,
            ratio(e.ratio),
            group.compare_with,
            run_name(e.euler),
            e.euler.key.scene,
            e.euler.stats.rhs_evals,
            e.so3.stats.rhs_evals
        ));
    }
    out
}

/// Whether a fit's local slopes agree (`metrics::order::ASYMPTOTIC_SPREAD`; a fit with
/// fewer than two local slopes has nothing to disagree with).
pub fn asymptotic(f: &crate::summary::FitRecord) -> bool {
    crate::metrics::order::slope_spread(&f.points)
        .is_none_or(|(spread, _, _)| spread <= crate::metrics::order::ASYMPTOTIC_SPREAD)
}

/// Median observed order per integrator over the case's asymptotic fits (fits without an
/// order, and fits that are not asymptotic, are counted apart: `without`,
/// `not_asymptotic`).
pub fn median_orders(cv: &CaseView) -> (Vec<(String, f64, usize)>, usize, usize, usize) {
    let mut by: BTreeMap<VariantKey, Vec<f64>> = BTreeMap::new();
    let (mut with, mut without, mut not_asymptotic) = (0, 0, 0);
    for s in &cv.scenes {
        for v in &s.variants {
            let Some(f) = v.fit else { continue };
            match f.order {
                Some(p) if p.is_finite() && !asymptotic(f) => not_asymptotic += 1,
                Some(p) if p.is_finite() => {
                    with += 1;
                    // Keyed by integrator only (param/formulation blanked) to keep registry order.
                    let k = VariantKey {
                        param: String::new(),
                        integrator: v.key.integrator.clone(),
                        formulation: String::new(),
                    };
                    by.entry(k).or_default().push(p);
                }
                _ => without += 1,
            }
        }
    }
    let list = by
        .into_iter()
        .map(|(k, mut ps)| {
            ps.sort_by(f64::total_cmp);
            let n = ps.len();
            let med = if n % 2 == 1 {
                ps[n / 2]
            } else {
                0.5 * (ps[n / 2 - 1] + ps[n / 2])
            };
            (k.integrator, med, n)
        })
        .collect();
    (list, with, without, not_asymptotic)
}

fn order_sentence(cv: &CaseView) -> Option<String> {
    let (list, with, without, not_asymptotic) = median_orders(cv);
    let total = with + without + not_asymptotic;
    if total == 0 {
        return None;
    }
    let apart = if not_asymptotic > 0 {
        format!(
            "; {not_asymptotic} of {total} fits were not asymptotic (local slopes differing \
             by more than {}), their slopes are not counted as orders",
            crate::metrics::order::ASYMPTOTIC_SPREAD
        )
    } else {
        String::new()
    };
    if list.is_empty() {
        return Some(format!(
            "None of the {total} order fits gave an observed order: {without} had fewer than 3 \
             ladder points in range{apart}."
        ));
    }
    let parts: Vec<String> = list
        .iter()
        .map(|(i, p, n)| format!("{i} {p:.2} ({n})"))
        .collect();
    Some(format!(
        "Observed order of {} (median over variants and scenes, number of fits): {}; {without} \
         of {total} fits had fewer than 3 ladder points in range{apart}.",
        cv.primary,
        parts.join(", "),
    ))
}

/// The paragraph of a case, as sentences.
pub fn paragraph(cv: &CaseView) -> Vec<String> {
    paragraph_with(cv, None)
}

/// The paragraph of a case whose recommendation offers the targets `offered` (`advise`'s,
/// largest first or in any order): its scene sentences name the cheapest run reaching the
/// tightest of them, or, when none is offered, the smallest error reached. Without a
/// recommendation (`None`), they use `TARGET`.
pub fn paragraph_with(cv: &CaseView, offered: Option<&[f64]>) -> Vec<String> {
    let target = match offered {
        None => Target::At(TARGET, false),
        Some(list) => list
            .iter()
            .copied()
            .fold(None, |m: Option<f64>, t| Some(m.map_or(t, |m| m.min(t))))
            .map_or(Target::NoneOffered, |t| Target::At(t, true)),
    };
    let mut out: Vec<String> = cv
        .scenes
        .iter()
        .map(|s| scene_sentence(cv, s, target))
        .collect();
    out.push(failure_sentence(cv));
    out.extend(euler_sentences(cv));
    out.extend(order_sentence(cv));
    let na: usize = cv.scenes.iter().map(|s| s.na.len()).sum();
    if na > 0 {
        out.push(format!(
            "{na} combinations are n/a over the case's scenes (reasons in the n/a table)."
        ));
    }
    if cv.scenes.is_empty() {
        out.push("No data for this case.".into());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::{data, fixture};

    /// The cheapest runs named in the text are the cheapest of all qualifying runs (checked
    /// by brute force over the summary), with their numbers.
    #[test]
    fn cheapest_matches_brute_force() {
        let s = fixture::summary();
        let views = data::case_views(&s, &[]);
        let cv = &views[0];
        assert_eq!(cv.primary, fixture::PRIMARY);
        let text = paragraph(cv);
        for scene in fixture::SCENES {
            let qualifying: Vec<&Record> = s
                .records
                .iter()
                .filter(|r| r.key.scene == scene && r.status == Status::Ok)
                .filter(|r| r.metrics[fixture::PRIMARY].is_some_and(|e| e <= TARGET))
                .collect();
            let by_rhs = qualifying.iter().min_by_key(|r| r.stats.rhs_evals).unwrap();
            let by_wall = qualifying
                .iter()
                .min_by(|a, b| a.wall_s.unwrap().min.total_cmp(&b.wall_s.unwrap().min))
                .unwrap();
            // The fixture's intended answers.
            assert_eq!(run_name(by_rhs), "quat / dopri5 / body at tol 1e-6");
            assert_eq!(run_name(by_wall), "so3 / lgvi / body at dt 1e-2");
            let sentence = text
                .iter()
                .find(|t| t.starts_with(&format!("Scene {scene}:")))
                .unwrap();
            assert!(
                sentence.contains(&format!(
                    "is {} with {} RHS evaluations",
                    run_name(by_rhs),
                    by_rhs.stats.rhs_evals
                )),
                "{sentence}"
            );
            assert!(
                sentence.contains(&format!(
                    "by wall time, {} in {} s",
                    run_name(by_wall),
                    num(by_wall.wall_s.unwrap().min)
                )),
                "{sentence}"
            );
            assert!(sentence.contains("1500") && sentence.contains("4e-4 s"));
        }
    }

    /// The failure count, the Euler conditioning and the Euler/so3 cost ratio are the
    /// summary's numbers.
    #[test]
    fn failures_and_euler_facts() {
        let s = fixture::summary();
        let views = data::case_views(&s, &[]);
        let text = paragraph(&views[0]).join(" ");
        let failed = s
            .records
            .iter()
            .filter(|r| r.status == Status::Failed)
            .count();
        let runs = s
            .records
            .iter()
            .filter(|r| r.status != Status::NotApplicable)
            .count();
        assert_eq!((failed, runs), (3, 39));
        assert!(
            text.contains(
                "3 of 39 runs ended with a typed failure: singular_chart 3 (euler_zxz with rk4)."
            ),
            "{text}"
        );
        // euler_zxz: 3 failed of 9 runs (6 rk4 + 3 dopri5); others 0 of 30.
        assert!(
            text.contains("Euler-angle charts: 3 of 9 runs failed, against 0 of 30"),
            "{text}"
        );
        assert!(
            text.contains(
                "their lowest conditioning was 0 (euler_zxz / rk4 / body at dt 2e-2 on scene large)"
            ),
            "{text}"
        );
        let e = euler_cost(&views[0]).unwrap();
        assert_eq!(e.ratio, 20.0);
        assert_eq!(e.euler.tol, Some(1e-8));
        assert!(
            text.contains("up to 20.0x the RHS evaluations of the same method on so3: euler_zxz / dopri5 / body at tol 1e-8 on scene two_angles took 96000 against 4800."),
            "{text}"
        );
        assert!(
            text.contains("rk4 4.00 (4)") && text.contains("lgvi 2.00 (2)"),
            "{text}"
        );
        assert!(text.contains("4 combinations are n/a"), "{text}");
    }

    /// A scene where nothing reaches the target says so, with the best error.
    #[test]
    fn nothing_reaches_target() {
        let mut s = fixture::summary();
        for r in &mut s.records {
            if let Some(Some(e)) = r.metrics.get_mut(fixture::PRIMARY) {
                *e += 1e-5;
            }
        }
        let views = data::case_views(&s, &[]);
        let text = paragraph(&views[0]);
        // Smallest error: quat dopri5 at 1e-8 (3e-9 + 1e-5 for so3 dopri5 is the minimum).
        assert!(
            text[0].contains("no run reached rotation_error_max <= 1e-6; the smallest was 1e-5 by so3 / dopri5 / body at tol 1e-8"),
            "{}",
            text[0]
        );
    }

    /// With a recommendation, the scene sentences use its tightest offered target, never one
    /// it refuses; with none offered they name no cheapest run.
    #[test]
    fn offered_targets() {
        let s = fixture::summary();
        let views = data::case_views(&s, &[]);
        let text = paragraph_with(&views[0], Some(&[1e-2, 1e-4])).join(" ");
        assert!(
            text.contains("<= 1e-4 (the tightest target the recommendation offers)"),
            "{text}"
        );
        assert!(!text.contains("<= 1e-6"), "{text}");
        let none = paragraph_with(&views[0], Some(&[])).join(" ");
        assert!(none.contains("offers no target error"), "{none}");
        assert!(!none.contains("the cheapest run reaching"), "{none}");
    }
}
