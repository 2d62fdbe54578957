//! `[[gates]]` of a case file (cases/README.md, "`[[gates]]`"; `mbdbench gate`): a metric, one
//! bound (`max` or `min`), a `where` selecting records by scene, variant names and ladder
//! value, whether the quick tier evaluates it, and the baseline it was set from. Loading only
//! checks their shape (names, finite bounds, scenes that exist, not both `dt` and `tol`); the
//! gate command interprets them against a summary.
use serde::Deserialize;

use super::{Ctx, Res, Scene};

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bound {
    /// The metric must be <= this.
    Max(f64),
    /// The metric must be >= this.
    Min(f64),
}

/// A gate's `where`: each list is a set of accepted values, empty = any.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct GateWhere {
    pub scene: Vec<String>,
    pub param: Vec<String>,
    pub integrator: Vec<String>,
    pub formulation: Vec<String>,
    pub dt: Vec<f64>,
    pub tol: Vec<f64>,
}

/// `[[gates]]` (shape-checked only: the gate command interprets them).
#[derive(Debug, Clone, PartialEq)]
pub struct Gate {
    pub metric: String,
    pub bound: Bound,
    pub filter: GateWhere,
    /// Evaluated by `gate --quick` too.
    pub quick: bool,
    pub baseline: Option<f64>,
    pub margin: Option<f64>,
    pub commit: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawGate {
    metric: String,
    max: Option<f64>,
    min: Option<f64>,
    #[serde(rename = "where", default)]
    filter: RawWhere,
    #[serde(default)]
    quick: bool,
    baseline: Option<f64>,
    margin: Option<f64>,
    commit: Option<String>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawWhere {
    scene: Option<OneOrMany<String>>,
    param: Option<OneOrMany<String>>,
    integrator: Option<OneOrMany<String>>,
    formulation: Option<OneOrMany<String>>,
    dt: Option<OneOrMany<f64>>,
    tol: Option<OneOrMany<f64>>,
}

#[derive(Deserialize)]
#[serde(untagged, expecting = "a value or a list of values")]
enum OneOrMany<T> {
    One(T),
    Many(Vec<T>),
}

impl<T> OneOrMany<T> {
    fn into_vec(self) -> Vec<T> {
        match self {
            OneOrMany::One(x) => vec![x],
            OneOrMany::Many(v) => v,
        }
    }
}

impl Ctx<'_> {
    pub(crate) fn gate(
        &self,
        i: usize,
        g: RawGate,
        scenes: &[Scene],
        formulations: &[&str],
    ) -> Res<Gate> {
        let key = |k: &str| format!("gates[{i}].{k}");
        self.name(
            &key("metric"),
            &g.metric,
            |c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_',
            "a snake_case metric name",
        )?;
        let bound = match (g.max, g.min) {
            (Some(x), None) => Bound::Max(self.finite(&key("max"), x)?),
            (None, Some(x)) => Bound::Min(self.finite(&key("min"), x)?),
            _ => {
                return self.err(format!("gates[{i}]"), "expected exactly one of max, min");
            }
        };
        let baseline = g
            .baseline
            .map(|x| self.finite(&key("baseline"), x))
            .transpose()?;
        let margin = g
            .margin
            .map(|x| self.positive(&key("margin"), x, "a factor"))
            .transpose()?;
        let w = g.filter;
        let strings = |k: &str, v: Option<OneOrMany<String>>| -> Res<Vec<String>> {
            let v = v.map(OneOrMany::into_vec).unwrap_or_default();
            for (j, s) in v.iter().enumerate() {
                let kk = format!("gates[{i}].where.{k}[{j}]");
                match k {
                    "scene" => {
                        if !scenes.iter().any(|sc| &sc.name == s) {
                            return self.err(kk, format!("no scene `{s}` in this case"));
                        }
                    }
                    "formulation" => {
                        if !formulations.contains(&s.as_str()) {
                            return self
                                .err(kk, format!("`{s}`; expected {}", or_list(formulations)));
                        }
                    }
                    _ => self.name(
                        &kk,
                        s,
                        |c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_',
                        "a snake_case variant name",
                    )?,
                }
            }
            Ok(v)
        };
        let numbers = |k: &str, v: Option<OneOrMany<f64>>| -> Res<Vec<f64>> {
            let v = v.map(OneOrMany::into_vec).unwrap_or_default();
            for (j, x) in v.iter().enumerate() {
                self.positive(
                    &format!("gates[{i}].where.{k}[{j}]"),
                    *x,
                    "a step or tolerance",
                )?;
            }
            Ok(v)
        };
        let filter = GateWhere {
            scene: strings("scene", w.scene)?,
            param: strings("param", w.param)?,
            integrator: strings("integrator", w.integrator)?,
            formulation: strings("formulation", w.formulation)?,
            dt: numbers("dt", w.dt)?,
            tol: numbers("tol", w.tol)?,
        };
        if !filter.dt.is_empty() && !filter.tol.is_empty() {
            return self.err(
                key("where"),
                "both dt and tol: no run has both; expected at most one",
            );
        }
        Ok(Gate {
            metric: g.metric,
            bound,
            filter,
            quick: g.quick,
            baseline,
            margin,
            commit: g.commit,
        })
    }
}

/// `a`, `a or b`, `a, b or c`.
fn or_list(names: &[&str]) -> String {
    match names {
        [] => String::new(),
        [a] => a.to_string(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}
