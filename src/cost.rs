//! `cost`: the committed cost table (`reports/baseline/cost.json`), a linear model of a run's
//! wall time in its deterministic work, per model family and per scene:
//!
//! ```text
//! t  =  c_step steps + c_rhs rhs_evals + c_newton newton_iters + c_element element_iters
//! ```
//!
//! (`integrate::Stats`; coefficients in nanoseconds, all >= 0), and, where the variant was
//! timed, that variant's own cost per step on the scene (`ns_per_step` by
//! `param/integrator/formulation`: the median over its ladder points of `wall / steps`),
//! which predicts far better (measured on the table's own run: median `|ln(predicted /
//! measured)|` 0.05 over every timed run, against 0.5 to 1.2 for the counters' model, whose
//! per-unit costs differ between charts, formulations and linear solves). A variant without a
//! row (a user's new method) falls back to the scene's model, then the family's.
//! `mbdbench calibrate` fits it
//! to the timing pass of a full run (`wall_s.min` of every timed record) and writes it; it is
//! regenerated with the gate's baseline, on the machine whose times it states. It serves
//! what must know a run's cost before it runs: the ladder's cost cap (`suite::skip`), the
//! main job's time estimate, and the balancing of a split run.
//!
//! The fit (`fit`) minimises the relative error `sum_i (c . x_i / t_i - 1)^2` over the runs
//! (a run of 1 ms weighs as much as one of 1 s), subject to `c >= 0`: the unconstrained
//! least-squares solution of every subset of the four counters (16 normal-equation solves of
//! order <= 4), keeping the best feasible one, which is the non-negative least-squares
//! optimum (the problem is convex; its optimum is the unconstrained optimum on its support).
//! Each row states its fit's quality: the median and the 90th percentile of
//! `|ln(predicted / measured)|` over its runs.
//!
//! Where it fails: a scene or family with no timed run has no row (`predict` then says so
//! and the callers do not skip by cost); a run whose work differs in kind from the runs it
//! was fitted to (a new method with costly per-step work none of the counters sees) is
//! predicted low. Times are this machine's: the table names its CPU.
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

use crate::integrate::Stats;

/// The table as committed (`reports/baseline/cost.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CostTable {
    pub schema: u32,
    /// The commit and machine of the run it was fitted to.
    pub git_commit: String,
    pub cpu: String,
    /// One entry per family (`model` key), in the family table's order.
    pub families: Vec<FamilyCost>,
}

/// A family's coefficients, pooled over its scenes, and each scene's own.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FamilyCost {
    pub family: String,
    pub pooled: Coefficients,
    pub scenes: Vec<SceneCost>,
}

/// One scene's coefficients.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SceneCost {
    pub case: String,
    pub scene: String,
    #[serde(flatten)]
    pub c: Coefficients,
    /// ns per step of each timed variant, by `param/integrator/formulation`.
    pub variants: BTreeMap<String, f64>,
}

/// The key of a variant's row (`SceneCost::variants`).
pub fn variant_key(param: &str, integrator: &str, formulation: &str) -> String {
    format!("{param}/{integrator}/{formulation}")
}

/// The model's coefficients (ns per unit of work) and its fit quality.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Coefficients {
    pub ns_per_step: f64,
    pub ns_per_rhs: f64,
    pub ns_per_newton: f64,
    pub ns_per_element: f64,
    /// Timed runs the fit used.
    pub runs: usize,
    /// Median and 90th percentile of `|ln(predicted / measured)|` over them.
    pub log_error_median: f64,
    pub log_error_p90: f64,
}

/// The work a run does, as the model's regressors.
pub fn work(s: &Stats) -> [f64; 4] {
    [
        s.steps as f64,
        s.rhs_evals as f64,
        s.newton_iters as f64,
        s.element_iters as f64,
    ]
}

impl Coefficients {
    /// Predicted seconds of a run doing `w` (`work`).
    pub fn seconds(&self, w: &[f64; 4]) -> f64 {
        1e-9 * (self.ns_per_step * w[0]
            + self.ns_per_rhs * w[1]
            + self.ns_per_newton * w[2]
            + self.ns_per_element * w[3])
    }
}

/// The table compiled into the binary (`reports/baseline/cost.json` at build time).
pub const EMBEDDED: &str = include_str!("../reports/baseline/cost.json");

impl CostTable {
    /// Parses a table; the error names `origin` and what is wrong.
    pub fn parse(text: &str, origin: &str) -> Result<CostTable, String> {
        let t: CostTable =
            serde_json::from_str(text).map_err(|e| format!("{origin}: not a cost table: {e}"))?;
        if t.schema != 1 {
            return Err(format!(
                "{origin}: schema {} (this build reads 1)",
                t.schema
            ));
        }
        let bad = |c: &Coefficients| {
            [
                c.ns_per_step,
                c.ns_per_rhs,
                c.ns_per_newton,
                c.ns_per_element,
            ]
            .iter()
            .any(|x| !(x.is_finite() && *x >= 0.0))
        };
        for f in &t.families {
            if bad(&f.pooled) {
                return Err(format!(
                    "{origin}: family `{}`: a coefficient is negative or not finite",
                    f.family
                ));
            }
            if let Some(s) = f.scenes.iter().find(|s| bad(&s.c)) {
                return Err(format!(
                    "{origin}: `{}/{}`: a coefficient is negative or not finite",
                    s.case, s.scene
                ));
            }
        }
        Ok(t)
    }

    /// The table compiled into the binary.
    pub fn embedded() -> CostTable {
        CostTable::parse(EMBEDDED, "reports/baseline/cost.json (embedded)")
            .unwrap_or_else(|_| CostTable::empty())
    }

    /// A table with no rows (nothing is predicted).
    pub fn empty() -> CostTable {
        CostTable {
            schema: 1,
            git_commit: String::new(),
            cpu: String::new(),
            families: vec![],
        }
    }

    /// What the table knows of runs of `family` on `case`/`scene` (None: nothing).
    pub fn for_scene(&self, family: &str, case: &str, scene: &str) -> Option<SceneModel<'_>> {
        let f = self.families.iter().find(|f| f.family == family)?;
        Some(SceneModel {
            pooled: &f.pooled,
            scene: f.scenes.iter().find(|s| s.case == case && s.scene == scene),
        })
    }
}

/// The cost model of one scene: its own rows where it has them, else its family's.
#[derive(Debug, Clone, Copy)]
pub struct SceneModel<'a> {
    pooled: &'a Coefficients,
    scene: Option<&'a SceneCost>,
}

impl SceneModel<'_> {
    /// Predicted seconds of a run of the variant `key` (`variant_key`) doing `w` (`work`):
    /// its steps times the variant's cost per step where the table has it, else the scene's
    /// (or the family's) counters' model.
    pub fn seconds(&self, key: &str, w: &[f64; 4]) -> f64 {
        match self.scene {
            Some(s) => match s.variants.get(key) {
                Some(ns) => 1e-9 * ns * w[0],
                None => s.c.seconds(w),
            },
            None => self.pooled.seconds(w),
        }
    }
}

/// One timed run: its work and its measured seconds.
#[derive(Debug, Clone, Copy)]
pub struct Sample {
    pub work: [f64; 4],
    pub seconds: f64,
}

/// The non-negative relative least-squares fit of the model to `samples` (the file's
/// opening); None without a sample of positive time.
pub fn fit(samples: &[Sample]) -> Option<Coefficients> {
    let used: Vec<&Sample> = samples
        .iter()
        .filter(|s| s.seconds > 0.0 && s.seconds.is_finite() && s.work.iter().any(|&w| w > 0.0))
        .collect();
    if used.is_empty() {
        return None;
    }
    // Columns scaled to ns per unit: regressor x_ij / t_i (in ns), target 1.
    let rows: Vec<[f64; 4]> = used
        .iter()
        .map(|s| s.work.map(|w| w / (s.seconds * 1e9)))
        .collect();
    let mut best: Option<([f64; 4], f64)> = None;
    for mask in 1u32..16 {
        let support: Vec<usize> = (0..4).filter(|j| mask & (1 << j) != 0).collect();
        let Some(c) = solve_support(&rows, &support) else {
            continue;
        };
        if c.iter().any(|&x| x < 0.0) {
            continue;
        }
        let sse: f64 = rows
            .iter()
            .map(|r| (r.iter().zip(&c).map(|(a, b)| a * b).sum::<f64>() - 1.0).powi(2))
            .sum();
        if best.is_none_or(|(_, b)| sse < b) {
            best = Some((c, sse));
        }
    }
    let (c, _) = best?;
    let mut coef = Coefficients {
        ns_per_step: c[0],
        ns_per_rhs: c[1],
        ns_per_newton: c[2],
        ns_per_element: c[3],
        runs: used.len(),
        log_error_median: 0.0,
        log_error_p90: 0.0,
    };
    let mut errs: Vec<f64> = used
        .iter()
        .map(|s| (coef.seconds(&s.work).max(1e-12) / s.seconds).ln().abs())
        .collect();
    errs.sort_by(f64::total_cmp);
    coef.log_error_median = errs[errs.len() / 2];
    coef.log_error_p90 = errs[((errs.len() - 1) as f64 * 0.9).round() as usize];
    Some(coef)
}

fn median(v: &[f64]) -> f64 {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// `x` to 3 significant digits (the table's times vary more than that between runs).
fn round3(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let e = 10f64.powi(2 - x.abs().log10().floor() as i32);
    (x * e).round() / e
}

/// The least-squares coefficients on `support` (others 0), by the normal equations; None when
/// they are singular (a counter that is zero in every run).
fn solve_support(rows: &[[f64; 4]], support: &[usize]) -> Option<[f64; 4]> {
    let k = support.len();
    let mut a = nalgebra::DMatrix::<f64>::zeros(k, k);
    let mut b = nalgebra::DVector::<f64>::zeros(k);
    for r in rows {
        for (p, &i) in support.iter().enumerate() {
            b[p] += r[i];
            for (q, &j) in support.iter().enumerate() {
                a[(p, q)] += r[i] * r[j];
            }
        }
    }
    let x = a.lu().solve(&b)?;
    let mut c = [0.0; 4];
    for (p, &i) in support.iter().enumerate() {
        if !x[p].is_finite() {
            return None;
        }
        c[i] = x[p];
    }
    Some(c)
}

/// Fits a table to the timed records of `summary` (every `ok` record with `wall_s`), grouped
/// by `family_of` (a record's family `model` key, None to leave it out), families in the
/// order of `families`.
pub fn calibrate(
    summary: &crate::summary::Summary,
    families: &[&str],
    family_of: impl Fn(&crate::summary::Record) -> Option<&'static str>,
) -> CostTable {
    type Scenes = BTreeMap<(String, String), (Vec<Sample>, BTreeMap<String, Vec<f64>>)>;
    let mut by: BTreeMap<&str, Scenes> = BTreeMap::new();
    for r in &summary.records {
        let (Some(w), Some(f)) = (&r.wall_s, family_of(r)) else {
            continue;
        };
        let (samples, per_step) = by
            .entry(f)
            .or_default()
            .entry((r.key.case.clone(), r.key.scene.clone()))
            .or_default();
        samples.push(Sample {
            work: work(&r.stats),
            seconds: w.min,
        });
        if r.stats.steps > 0 && w.min > 0.0 {
            per_step
                .entry(variant_key(
                    &r.key.param,
                    &r.key.integrator,
                    &r.key.formulation,
                ))
                .or_default()
                .push(1e9 * w.min / r.stats.steps as f64);
        }
    }
    let mut out = CostTable {
        schema: 1,
        git_commit: summary.git_commit.clone(),
        cpu: summary.env.cpu.clone(),
        families: vec![],
    };
    for &f in families {
        let Some(scenes) = by.get(f) else { continue };
        let all: Vec<Sample> = scenes.values().flat_map(|(s, _)| s).copied().collect();
        let Some(pooled) = fit(&all) else { continue };
        out.families.push(FamilyCost {
            family: f.to_string(),
            pooled,
            scenes: scenes
                .iter()
                .filter_map(|((case, scene), (s, per_step))| {
                    fit(s).map(|c| SceneCost {
                        case: case.clone(),
                        scene: scene.clone(),
                        c,
                        variants: per_step
                            .iter()
                            .map(|(k, v)| (k.clone(), round3(median(v))))
                            .collect(),
                    })
                })
                .collect(),
        });
    }
    out
}

/// How well `table` predicts the timed records of `summary` it was fitted to: per family
/// (`family_of`), the median and 90th percentile of `|ln(predicted / measured)|`, each run
/// predicted from its own work as `SceneModel::seconds` does.
pub fn quality(
    table: &CostTable,
    summary: &crate::summary::Summary,
    family_of: impl Fn(&crate::summary::Record) -> Option<&'static str>,
) -> BTreeMap<&'static str, (f64, f64)> {
    let mut errs: BTreeMap<&'static str, Vec<f64>> = BTreeMap::new();
    for r in &summary.records {
        let (Some(w), Some(f)) = (&r.wall_s, family_of(r)) else {
            continue;
        };
        let Some(m) = table.for_scene(f, &r.key.case, &r.key.scene) else {
            continue;
        };
        let key = variant_key(&r.key.param, &r.key.integrator, &r.key.formulation);
        let p = m.seconds(&key, &work(&r.stats));
        if w.min > 0.0 && p > 0.0 {
            errs.entry(f).or_default().push((p / w.min).ln().abs());
        }
    }
    errs.into_iter()
        .map(|(f, mut e)| {
            e.sort_by(f64::total_cmp);
            let p90 = e[((e.len() - 1) as f64 * 0.9).round() as usize];
            (f, (e[e.len() / 2], p90))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fit recovers the coefficients of exact data, and never returns a negative one
    /// (a counter that only adds noise gets 0), with a quality of 0 on exact data.
    #[test]
    fn fit_recovers_exact_coefficients() {
        let truth = [40.0, 120.0, 900.0, 0.0];
        let samples: Vec<Sample> = (1..30)
            .map(|k| {
                let k = k as f64;
                let work = [1e4 * k, 4e4 * k + 3e3 * k * k, 2e3 * (30.0 - k), 0.0];
                let ns: f64 = work.iter().zip(truth).map(|(w, c)| w * c).sum();
                Sample {
                    work,
                    seconds: ns * 1e-9,
                }
            })
            .collect();
        let c = fit(&samples).unwrap();
        for (got, want) in [
            c.ns_per_step,
            c.ns_per_rhs,
            c.ns_per_newton,
            c.ns_per_element,
        ]
        .iter()
        .zip(truth)
        {
            assert!(
                (got - want).abs() <= 1e-6 * want.max(1.0),
                "{got} vs {want}"
            );
        }
        assert!(c.log_error_p90 < 1e-9);
        assert_eq!(c.runs, 29);
    }

    /// Where the unconstrained optimum has a negative coefficient, the fit keeps every
    /// coefficient >= 0 and does at least as well as any single counter alone.
    #[test]
    fn fit_is_non_negative() {
        // Time falls with Newton iterations in this data: least squares would give it a
        // negative coefficient.
        let samples: Vec<Sample> = (1..20)
            .map(|k| {
                let k = k as f64;
                Sample {
                    work: [1e5 * k, 0.0, 1e3 * (20.0 - k), 0.0],
                    seconds: 5e-5 * k * (1.0 + 0.01 * (k % 3.0)),
                }
            })
            .collect();
        let c = fit(&samples).unwrap();
        assert!(c.ns_per_newton >= 0.0 && c.ns_per_step > 0.0);
        assert!(c.log_error_median < 0.05, "{c:?}");
    }

    /// The embedded table parses, and a table with a negative coefficient is refused
    /// naming the file and the row.
    #[test]
    fn parse_checks_the_table() {
        let t = CostTable::parse(EMBEDDED, "embedded").unwrap();
        assert_eq!(t.schema, 1);
        let mut bad = t.clone();
        bad.families.push(FamilyCost {
            family: "x".into(),
            pooled: Coefficients {
                ns_per_step: -1.0,
                ns_per_rhs: 0.0,
                ns_per_newton: 0.0,
                ns_per_element: 0.0,
                runs: 1,
                log_error_median: 0.0,
                log_error_p90: 0.0,
            },
            scenes: vec![],
        });
        let e = CostTable::parse(&serde_json::to_string(&bad).unwrap(), "f.json").unwrap_err();
        assert!(e.contains("f.json") && e.contains("`x`"), "{e}");
    }
}
