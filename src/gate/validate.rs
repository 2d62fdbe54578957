//! Validation of the `[[gates]]` of the case files against what exists: the metric names a
//! summary can hold (`KNOWN_METRIC_LISTS` and every name in the records), the registered
//! parameterizations, integrators and formulations, the ladder points of the selected scenes
//! (either tier), and the consistency of a bound with its `baseline x margin` (the metric and
//! bound checks apply to bound gates only; an expected-failure gate has neither). Every failure is
//! a `GateError` naming the case file, the gate (`gates[i]`), the key and the value.
use std::collections::BTreeSet;

use super::{BOUND_REL_TOL, GateError, KNOWN_METRIC_LISTS, all_records, same_value};
use crate::case::gate::Check;
use crate::case::{self, Bound, Case, Gate, GateWhere, OrderClass};
use crate::problem::Variant;
use crate::summary::Summary;

/// Metric names a gate may use: every family's metrics, the static lists and every name in
/// the records.
pub fn known_metrics(summary: &Summary, stability: Option<&Summary>) -> BTreeSet<String> {
    let mut known: BTreeSet<String> = KNOWN_METRIC_LISTS
        .iter()
        .flat_map(|l| l.iter())
        .map(|s| s.to_string())
        .collect();
    known.extend(
        crate::catalogue::FAMILIES
            .iter()
            .flat_map(|f| f.metrics.iter().map(|m| m.name.to_string())),
    );
    for r in all_records(summary, stability) {
        known.extend(r.metrics.keys().cloned());
    }
    known
}

pub(super) fn check_threshold(c: &Case, index: usize, g: &Gate) -> Result<(), GateError> {
    let err = |key: &str, message: String| GateError::Threshold {
        file: c.file.clone(),
        index,
        key: key.into(),
        message,
    };
    // An expected-failure gate has no bound (loading refuses a baseline or margin on it).
    let (key, t) = match g.check {
        Check::Bound {
            bound: Bound::Max(t),
            ..
        } => ("max", t),
        Check::Bound {
            bound: Bound::Min(t),
            ..
        } => ("min", t),
        Check::Expect { .. } => return Ok(()),
    };
    match (g.baseline, g.margin) {
        (None, None) => Ok(()),
        (Some(_), None) => Err(err(
            "margin",
            "missing: `baseline` is given and the threshold is baseline x margin".into(),
        )),
        (None, Some(_)) => Err(err(
            "baseline",
            "missing: `margin` is given and the threshold is baseline x margin".into(),
        )),
        (Some(b), Some(m)) => {
            let product = b * m;
            if (t - product).abs() <= BOUND_REL_TOL * t.abs().max(product.abs()) {
                Ok(())
            } else {
                Err(err(
                    key,
                    format!("{t:e} differs from baseline x margin = {b:e} x {m} = {product:.4e}"),
                ))
            }
        }
    }
}

/// Each `where` value must name something that exists: a registered parameterization,
/// integrator or formulation, a step on some fixed-step ladder (either tier) of the selected
/// scenes, a tolerance on some tolerance ladder.
pub(super) fn check_where_values(
    c: &Case,
    index: usize,
    g: &Gate,
    catalogue: &crate::catalogue::Catalogue,
) -> Result<(), GateError> {
    let f = &g.filter;
    let err = |key: String, message: String| GateError::Where {
        file: c.file.clone(),
        index,
        key,
        message,
    };
    let vs = catalogue.family_or_builtin(c).variants();
    let names = |pick: fn(&Variant) -> &'static str| {
        let mut n: Vec<&str> = vs.iter().map(pick).collect();
        n.sort_unstable();
        n.dedup();
        n
    };
    let lists: [(&str, &Vec<String>, Vec<&str>); 3] = [
        ("param", &f.param, names(|v| v.param)),
        ("integrator", &f.integrator, names(|v| v.integrator)),
        ("formulation", &f.formulation, names(|v| v.formulation)),
    ];
    for (key, asked, known) in &lists {
        for (j, name) in asked.iter().enumerate() {
            if !known.contains(&name.as_str()) {
                return Err(err(
                    format!("where.{key}[{j}]"),
                    format!(
                        "\"{name}\" is no registered {key} (registered: {})",
                        known.join(", ")
                    ),
                ));
            }
        }
    }
    let scenes: Vec<&case::Scene> = c
        .scenes
        .iter()
        .filter(|s| keep(&f.scene, &s.name))
        .collect();
    let mut steps = vec![];
    let mut tols = vec![];
    for s in &scenes {
        for l in [&s.ladders, &s.quick] {
            for class in OrderClass::ALL {
                steps.extend(l.fixed(class).iter().map(|p| p.dt));
            }
            tols.extend(l.tol.iter().copied());
        }
    }
    for (key, asked, ladder) in [("dt", &f.dt, &steps), ("tol", &f.tol, &tols)] {
        for (j, x) in asked.iter().enumerate() {
            if !ladder.iter().any(|y| same_value(*x, *y)) {
                return Err(err(
                    format!("where.{key}[{j}]"),
                    format!(
                        "{x:e} is on no {} ladder (full or quick) of the selected scenes",
                        if key == "dt" {
                            "fixed-step"
                        } else {
                            "tolerance"
                        }
                    ),
                ));
            }
        }
    }
    Ok(())
}

pub(super) fn keep(list: &[String], v: &str) -> bool {
    list.is_empty() || list.iter().any(|x| x == v)
}

/// `scene = two_angles, integrator = [rk4, gauss6], dt = 1e-3` (the keys given).
pub(super) fn describe(f: &GateWhere) -> String {
    fn list<T>(v: &[T], show: impl Fn(&T) -> String) -> String {
        if v.len() == 1 {
            show(&v[0])
        } else {
            format!("[{}]", v.iter().map(show).collect::<Vec<_>>().join(", "))
        }
    }
    let mut parts = vec![];
    for (k, v) in [
        ("scene", &f.scene),
        ("param", &f.param),
        ("integrator", &f.integrator),
        ("formulation", &f.formulation),
    ] {
        if !v.is_empty() {
            parts.push(format!("{k} = {}", list(v, |s| s.clone())));
        }
    }
    for (k, v) in [("dt", &f.dt), ("tol", &f.tol)] {
        if !v.is_empty() {
            parts.push(format!("{k} = {}", list(v, |x| format!("{x:e}"))));
        }
    }
    if parts.is_empty() {
        "any run".into()
    } else {
        parts.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::super::fixture::{self, opts, passing};
    use super::super::{Verdict, evaluate};
    use super::*;

    /// An unknown metric is bad input naming the file, the gate and the metric.
    #[test]
    fn unknown_metric_is_bad_input() {
        let c = fixture::with_gates(
            "nine_spring",
            &format!(
                "{}\n[[gates]]\nmetric = \"foo\"\nmax = 1.0\n",
                fixture::GATES
            ),
        );
        let e = evaluate(std::slice::from_ref(&c), &passing(&c), None, &opts(true)).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("cases/nine_spring.toml: gates[3].metric: unknown metric \"foo\""),
            "{e}"
        );
        // Work counters are known metrics.
        let c = fixture::with_gates(
            "nine_spring",
            "[[gates]]\nmetric = \"rhs_evals\"\nmax = 4000.0\nwhere = { scene = \"two_angles\", \
             param = \"so3\", integrator = \"rk4\", formulation = \"body\", dt = 1.0e-2 }\n",
        );
        let rows = evaluate(std::slice::from_ref(&c), &passing(&c), None, &opts(false)).unwrap();
        assert_eq!(
            (rows[0].verdict, rows[0].value),
            (Verdict::Pass, Some(4000.0))
        );
    }

    /// A `where` that names nothing registered, or expands to no point of the gated tier,
    /// is bad input naming the gate and what it asked for.
    #[test]
    fn where_matching_nothing_is_bad_input() {
        let s = fixture::summary(vec![]);
        let err = |case: &str, gate: &str, quick: bool| {
            let c = fixture::with_gates(case, &format!("[[gates]]\n{gate}\nquick = true\n"));
            let e = evaluate(&[c], &s, None, &opts(quick)).unwrap_err();
            assert!(matches!(e, GateError::Where { .. }), "{e}");
            e.to_string()
        };
        let m = err(
            "nine_spring",
            "metric = \"energy_drift_max\"\nmax = 1.0\nwhere = { integrator = [\"rk4\", \"rk5\"] }",
            false,
        );
        assert!(
            m.starts_with("cases/nine_spring.toml: gates[0].where.integrator[1]: \"rk5\""),
            "{m}"
        );
        let m = err(
            "nine_spring",
            "metric = \"energy_drift_max\"\nmax = 1.0\nwhere = { dt = 3.0e-3 }",
            false,
        );
        assert!(m.contains("gates[0].where.dt[0]: 3e-3 is on no"), "{m}");
        // rk4 never runs 1e-3 (an order-1 quick step): the expansion is empty.
        let m = err(
            "nine_spring",
            "metric = \"energy_drift_max\"\nmax = 1.0\nwhere = { integrator = \"rk4\", dt = 1.0e-3 }",
            false,
        );
        assert!(
            m.starts_with("cases/nine_spring.toml: gates[0].where: integrator = rk4, dt = 1e-3")
                && m.contains("no point of their full ladders"),
            "{m}"
        );
        // 5e-3 is on the full ladder but not the quick one.
        let m = err(
            "nine_spring",
            "metric = \"energy_drift_max\"\nmax = 1.0\nwhere = { integrator = \"rk4\", dt = 5.0e-3 }",
            true,
        );
        assert!(m.contains("quick ladders (values there: 1e-2)"), "{m}");
        // Every SE(3) variant is n/a on a pivoted body.
        let m = err(
            "heavy_top",
            "metric = \"energy_drift_max\"\nmax = 1.0\nwhere = { param = \"se3_hq\" }",
            false,
        );
        assert!(
            m.contains("param = se3_hq matches no registered variant that applies")
                && m.contains("a fixed pivot"),
            "{m}"
        );
    }

    /// A bound that is not baseline x margin (relative 1e-9), or half of that pair, is bad
    /// input.
    #[test]
    fn bound_must_be_baseline_times_margin() {
        let s = fixture::summary(vec![]);
        let gate = |extra: &str| {
            fixture::with_gates(
                "nine_spring",
                &format!("[[gates]]\nmetric = \"energy_drift_max\"\n{extra}\n"),
            )
        };
        let c = gate("max = 3.0000000001e-9\nbaseline = 1.0e-9\nmargin = 3.0");
        assert!(check_threshold(&c, 0, &c.gates[0]).is_ok());
        let c = gate("max = 4.0e-9\nbaseline = 1.0e-9\nmargin = 3.0");
        let e = evaluate(&[c], &s, None, &opts(false)).unwrap_err();
        assert!(matches!(e, GateError::Threshold { .. }));
        assert_eq!(
            e.to_string(),
            "cases/nine_spring.toml: gates[0].max: 4e-9 differs from baseline x margin = \
             1e-9 x 3 = 3.0000e-9"
        );
        let c = gate("min = 0.5\nbaseline = 1.0");
        let e = evaluate(&[c], &s, None, &opts(false)).unwrap_err();
        assert!(e.to_string().contains("gates[0].margin: missing"), "{e}");
    }
}
