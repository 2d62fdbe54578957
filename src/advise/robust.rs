//! The "at what step" part of the recommendation, from the stability study (`stability.json`
//! beside the summary): per scene of a case, each searched variant's largest stable step and
//! largest accurate step (`model::rigid_body::stability::search`: the largest `dt`, or loosest `tol`, whose run
//! stays within the energy bound, resp. the accuracy bound, over the study's horizon), ranked
//! by the largest accurate step, then the largest stable one; what limits the stable step
//! (the study's reason, e.g. `newton_failure` or `bound_exceeded`) is kept. Fixed-step
//! variants come first, adaptive ones (tolerances, not comparable with steps) after.
//!
//! Where it fails: the quick tier searches only a few variants (the gated pair and explicit
//! Euler) on one scene per case; the full study (`mbdbench stability`, or the main job with
//! `--full-stability`) ranks every registered variant. A variant the study did not search is
//! simply absent.
use serde::Serialize;

use super::Setting;
use crate::summary::{Record, Summary};

/// One variant's largest steps on one scene.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Robust {
    pub scene: String,
    pub param: String,
    pub integrator: String,
    pub formulation: String,
    /// The largest stable step (or loosest stable tolerance); None: nothing passed.
    pub stable: Option<Setting>,
    /// The largest accurate step (or loosest accurate tolerance); None: nothing passed, or
    /// not searched (`accuracy_searched`).
    pub accurate: Option<Setting>,
    /// False for a search that has no accurate step (the seam's step search: the beam has
    /// no reference beyond its scenes' horizon); written only then.
    #[serde(skip_serializing_if = "is_true")]
    pub accuracy_searched: bool,
    /// What stops the stable step from growing (the failure kind of the next larger try).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limited_by: Option<String>,
}

fn is_true(b: &bool) -> bool {
    *b
}

fn value(r: &Record, metric: &str) -> Option<f64> {
    r.metrics.get(metric).copied().flatten()
}

/// The study's reason for a metric, shortened to its failure kind: `limited by X at t = ...`
/// gives `X`.
fn limit(r: &Record, metric: &str) -> Option<String> {
    let why = r.metric_reasons.get(metric)?;
    let rest = why.strip_prefix("limited by ")?;
    Some(rest.split(" at t").next().unwrap_or(rest).to_string())
}

/// The ranking of `case`'s searched variants in `stability` (empty without step searches).
pub fn robustness(case: &str, stability: &Summary) -> Vec<Robust> {
    let mut rows: Vec<(bool, Robust)> = vec![];
    for r in stability
        .records
        .iter()
        .filter(|r| r.key.case == case && r.dt.is_none() && r.tol.is_none())
    {
        let (adaptive, stable, accurate) = if r.metrics.contains_key("largest_stable_dt") {
            (
                false,
                value(r, "largest_stable_dt").map(Setting::Dt),
                value(r, "largest_accurate_dt").map(Setting::Dt),
            )
        } else if r.metrics.contains_key("largest_stable_tol") {
            (
                true,
                value(r, "largest_stable_tol").map(Setting::Tol),
                value(r, "largest_accurate_tol").map(Setting::Tol),
            )
        } else {
            continue;
        };
        let stable_metric = if adaptive {
            "largest_stable_tol"
        } else {
            "largest_stable_dt"
        };
        rows.push((
            adaptive,
            Robust {
                scene: r.key.scene.clone(),
                param: r.key.param.clone(),
                integrator: r.key.integrator.clone(),
                formulation: r.key.formulation.clone(),
                stable,
                accurate,
                accuracy_searched: r.metrics.contains_key(if adaptive {
                    "largest_accurate_tol"
                } else {
                    "largest_accurate_dt"
                }),
                limited_by: limit(r, stable_metric),
            },
        ));
    }
    let x = |s: &Option<Setting>| match s {
        Some(Setting::Dt(v) | Setting::Tol(v)) => *v,
        None => 0.0,
    };
    rows.sort_by(|(a_adapt, a), (b_adapt, b)| {
        (&a.scene, a_adapt)
            .cmp(&(&b.scene, b_adapt))
            .then(x(&b.accurate).total_cmp(&x(&a.accurate)))
            .then(x(&b.stable).total_cmp(&x(&a.stable)))
    });
    rows.into_iter().map(|(_, r)| r).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::summary::RunKey;

    fn search(i: &str, stable: Option<f64>, accurate: Option<f64>) -> Record {
        let mut r = Record::new(RunKey::new("c", "s", "so3", i, "body"), "h");
        r.status = crate::summary::Status::Ok;
        r.metrics.insert("largest_stable_dt".into(), stable);
        r.metrics.insert("largest_accurate_dt".into(), accurate);
        r.metric_reasons.insert(
            "largest_stable_dt".into(),
            "limited by newton_failure at t = 2 with dt = 0.5".into(),
        );
        r
    }

    /// Variants rank by their largest accurate step, then their largest stable one; a
    /// variant with no accurate step ranks last; the limit is the failure kind; ladder
    /// records and other cases are ignored.
    #[test]
    fn ranks_by_accurate_then_stable_step() {
        let mut ladder = search("euler", Some(9.0), Some(9.0));
        ladder.dt = Some(0.1);
        let mut other = search("rk4", Some(9.0), Some(9.0));
        other.key.case = "d".into();
        let s = Summary {
            schema: 1,
            git_commit: "-".into(),
            created_utc: "-".into(),
            env: crate::summary::Env::current(1, None),
            records: vec![
                search("euler", Some(1e-3), None),
                search("rk4", Some(0.19), Some(0.023)),
                search("simo_wong", Some(0.46), Some(0.023)),
                ladder,
                other,
            ],
            fits: vec![],
            selection: None,
            methods: None,
            families: None,
        };
        let r = robustness("c", &s);
        let names: Vec<&str> = r.iter().map(|x| x.integrator.as_str()).collect();
        assert_eq!(names, ["simo_wong", "rk4", "euler"]);
        assert_eq!(r[0].stable, Some(Setting::Dt(0.46)));
        assert_eq!(r[0].limited_by.as_deref(), Some("newton_failure"));
        assert_eq!(r[2].accurate, None);
        assert!(r.iter().all(|x| x.accuracy_searched));
    }

    /// A search without an accurate step (the seam's) says so, in the entry and in its JSON;
    /// a searched one writes nothing extra.
    #[test]
    fn unsearched_accuracy_is_said() {
        let mut seam = search("newmark", Some(0.05), None);
        seam.metrics.remove("largest_accurate_dt");
        let s = Summary {
            schema: 1,
            git_commit: "-".into(),
            created_utc: "-".into(),
            env: crate::summary::Env::current(1, None),
            records: vec![seam, search("rk4", Some(0.19), Some(0.023))],
            fits: vec![],
            selection: None,
            methods: None,
            families: None,
        };
        let r = robustness("c", &s);
        let seam = r.iter().find(|x| x.integrator == "newmark").unwrap();
        assert!(!seam.accuracy_searched && seam.accurate.is_none());
        let json = serde_json::to_string(&r).unwrap();
        assert_eq!(
            json.matches("\"accuracy_searched\":false").count(),
            1,
            "{json}"
        );
        assert!(!json.contains("\"accuracy_searched\":true"), "{json}");
    }
}
