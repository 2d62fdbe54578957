//! `[[gates]]` of a case file (cases/README.md, "`[[gates]]`"; `mbdbench gate`): what a gate
//! checks (`Check`: a metric and one bound, `max` or `min`, or an expected typed failure,
//! `expect`), a `where` selecting records by scene, variant names and ladder value, whether the
//! quick tier evaluates it, and the baseline a bound was set from. Loading only checks their
//! shape (names, finite bounds, one form per gate, known failure kinds, scenes that exist, not
//! both `dt` and `tol`); the gate command interprets them against a summary.
use serde::Deserialize;

use super::{Ctx, Res, Scene};
use crate::integrate::FailureKind;

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bound {
    /// The metric must be <= this.
    Max(f64),
    /// The metric must be >= this.
    Min(f64),
}

/// What a gate checks of each record its `where` selects.
#[derive(Debug, Clone, PartialEq)]
pub enum Check {
    /// `metric` with `max` or `min`: the record's metric lies within the bound.
    Bound { metric: String, bound: Bound },
    /// `expect = { status = "failed", kind, after, before }`: the run ended in a typed
    /// failure of `kind` at `after < t <= before` (a variant known to fail, e.g. a model that
    /// diverges). The lower bound names the cause: a failure that comes before the mechanism
    /// the gate expects (a Newton failure at the first step from a budget set too small) is
    /// another failure, whatever its kind.
    Expect {
        kind: FailureKind,
        after: f64,
        before: f64,
    },
}

impl Check {
    /// The gated metric (None for an expected failure).
    pub fn metric(&self) -> Option<&str> {
        match self {
            Check::Bound { metric, .. } => Some(metric),
            Check::Expect { .. } => None,
        }
    }
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

/// Relative slack when a `where` step or tolerance is matched with a ladder value or a record.
pub const VALUE_REL_TOL: f64 = 1e-12;

/// Whether two steps or tolerances are the same ladder value.
pub fn same_value(a: f64, b: f64) -> bool {
    (a - b).abs() <= VALUE_REL_TOL * a.abs().max(b.abs())
}

impl GateWhere {
    /// Whether the filter names the ladder point `value` of a variant on `scene`, as the
    /// gate expands it (`gate`): every given list holds the name, and the point's step (a
    /// fixed-step method) or tolerance (an adaptive one) is one of those given, or none is
    /// given; a filter with steps names no adaptive method's point, and one with tolerances
    /// no fixed-step method's. The ladder's early stop (`suite::skip`) runs every point a
    /// gate names.
    pub fn names_point(&self, scene: &str, variant: [&str; 3], adaptive: bool, value: f64) -> bool {
        let keep = |list: &[String], v: &str| list.is_empty() || list.iter().any(|x| x == v);
        let [param, integrator, formulation] = variant;
        let (wanted, other) = if adaptive {
            (&self.tol, &self.dt)
        } else {
            (&self.dt, &self.tol)
        };
        keep(&self.scene, scene)
            && keep(&self.param, param)
            && keep(&self.integrator, integrator)
            && keep(&self.formulation, formulation)
            && other.is_empty()
            && (wanted.is_empty() || wanted.iter().any(|w| same_value(*w, value)))
    }
}

/// `[[gates]]` (shape-checked only: the gate command interprets them).
#[derive(Debug, Clone, PartialEq)]
pub struct Gate {
    pub check: Check,
    pub filter: GateWhere,
    /// Evaluated by `gate --quick` too.
    pub quick: bool,
    /// The measured value a bound was set from (always None for `Check::Expect`), and the
    /// factor between it and the bound.
    pub baseline: Option<f64>,
    pub margin: Option<f64>,
    pub commit: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawGate {
    metric: Option<String>,
    max: Option<f64>,
    min: Option<f64>,
    expect: Option<RawExpect>,
    #[serde(rename = "where", default)]
    filter: RawWhere,
    #[serde(default)]
    quick: bool,
    baseline: Option<f64>,
    margin: Option<f64>,
    commit: Option<String>,
}

/// `expect = { status, kind, after, before }`: every key required, checked in `Ctx::gate` (so
/// a missing one is named like a bad one).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawExpect {
    status: Option<String>,
    kind: Option<String>,
    after: Option<f64>,
    before: Option<f64>,
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
        let metric_given = g.metric.is_some();
        let check = match (g.metric, g.expect) {
            (_, Some(e)) => {
                let present = [
                    ("metric", metric_given),
                    ("max", g.max.is_some()),
                    ("min", g.min.is_some()),
                    ("baseline", g.baseline.is_some()),
                    ("margin", g.margin.is_some()),
                ];
                if let Some((k, _)) = present.iter().find(|(_, p)| *p) {
                    return self.err(
                        key(k),
                        "not allowed with `expect`: an expected-failure gate has no metric, \
                         bound, baseline or margin",
                    );
                }
                self.expect(i, e)?
            }
            (Some(metric), None) => {
                self.name(
                    &key("metric"),
                    &metric,
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
                Check::Bound { metric, bound }
            }
            (None, None) => {
                return self.err(
                    format!("gates[{i}]"),
                    "expected `metric` with `max` or `min`, or `expect`",
                );
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
            check,
            filter,
            quick: g.quick,
            baseline,
            margin,
            commit: g.commit,
        })
    }
}

impl Ctx<'_> {
    /// `gates[i].expect`: status `"failed"`, a failure kind's name, a finite positive `before`
    /// and a finite `after` with `0 <= after < before`.
    fn expect(&self, i: usize, e: RawExpect) -> Res<Check> {
        let key = |k: &str| format!("gates[{i}].expect.{k}");
        match e.status.as_deref() {
            Some("failed") => {}
            Some(s) => {
                return self.err(
                    key("status"),
                    format!("`{s}`; expected \"failed\" (the only status a gate can expect)"),
                );
            }
            None => {
                return self.err(
                    key("status"),
                    "missing; expected \"failed\" (the only status a gate can expect)",
                );
            }
        }
        let names: Vec<&str> = FailureKind::ALL.iter().map(|k| k.name()).collect();
        let kind = match e.kind.as_deref() {
            Some(s) => match FailureKind::from_name(s) {
                Some(k) => k,
                None => {
                    return self.err(
                        key("kind"),
                        format!("`{s}`; expected a failure kind: {}", or_list(&names)),
                    );
                }
            },
            None => {
                return self.err(
                    key("kind"),
                    format!("missing; expected a failure kind: {}", or_list(&names)),
                );
            }
        };
        let before = match e.before {
            Some(x) => self.positive(&key("before"), x, "a time (or load parameter)")?,
            None => {
                return self.err(
                    key("before"),
                    "missing; expected the latest time (or load parameter) of the failure",
                );
            }
        };
        let after = match e.after {
            Some(x) if x.is_finite() && x >= 0.0 && x < before => x,
            Some(x) => {
                return self.err(
                    key("after"),
                    format!(
                        "{x}; expected a time (or load parameter) from 0 up to `before` = \
                         {before}, exclusive: the earliest the expected failure can come"
                    ),
                );
            }
            None => {
                return self.err(
                    key("after"),
                    "missing; expected the time (or load parameter) after which the expected \
                     failure comes (its cause: a failure before it is another failure)",
                );
            }
        };
        Ok(Check::Expect {
            kind,
            after,
            before,
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
