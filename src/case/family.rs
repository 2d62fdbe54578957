//! What the shared case schema needs to know of the family that loads a file: its `model`
//! key, its metrics (a case's `primary_metric` is one of them), the reference kinds it can
//! attach, the physics a scene's hash covers and the estimate its budgets are checked
//! against. `problem::Family` implements it; a loaded [`Case`] keeps the family it was
//! loaded by, so the physics hash (`hash::inputs_value`) and the step budget
//! (`budget::over_step_budget`) ask that family without a table lookup. The trait is what
//! lets `case` sit below `problem` (the seam) and the catalogue (the table) in the crate's
//! layers (docs/architecture.md).
use super::{Case, Estimate, ReferenceKind, Scene};

/// A model family as the case loader sees it.
pub trait CaseFamily: Sync {
    /// The case file's `model` key.
    fn model(&self) -> &'static str;
    /// The names of every metric the family reports, in its order.
    fn metric_names(&self) -> Vec<&'static str>;
    /// Its formulations' names (a gate may name one).
    fn formulations(&self) -> &'static [&'static str];
    /// The reference kinds its problems can attach.
    fn references(&self) -> &'static [ReferenceKind];
    /// The family's physics of a scene in the physics hash (`problem::Family::inputs`).
    fn inputs(&self, case: &Case, scene: &Scene) -> serde_json::Map<String, serde_json::Value>;
    /// What one run of a scene needs (`problem::Family::estimate`).
    fn estimate(&self, case: &Case, scene: &Scene) -> Estimate;
}

impl std::fmt::Debug for dyn CaseFamily {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "CaseFamily({})", self.model())
    }
}

/// Two families are the same family when their `model` keys are (the table holds each key
/// once).
impl PartialEq for dyn CaseFamily {
    fn eq(&self, other: &Self) -> bool {
        self.model() == other.model()
    }
}
