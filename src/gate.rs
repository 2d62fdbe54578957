//! The gate (design.md, "Command line": `mbdbench gate`): each case's `[[gates]]` thresholds
//! evaluated against a summary, plus the baseline comparison; a table and an exit code.
//! (Types shared with the report; the evaluation lands with issue 3.)
use serde::{Deserialize, Serialize};

/// Outcome of one gate row.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    Pass,
    Fail,
}

/// One evaluated row: a gated (or baseline-compared) record and metric.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GateRow {
    pub case: String,
    pub scene: String,
    pub param: String,
    pub integrator: String,
    pub formulation: String,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub dt: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub tol: Option<f64>,
    /// The metric (or `rhs_evals`, `newton_iters` for baseline rows).
    pub metric: String,
    /// The value found (None: no record, or a null metric).
    pub value: Option<f64>,
    /// The threshold as written, e.g. `<= 3.0e-9` or `<= 3 x baseline 1.2e-8`.
    pub threshold: String,
    pub verdict: Verdict,
    /// Why it failed (stale reference, no record, null metric, regression ...), or empty.
    pub note: String,
}
