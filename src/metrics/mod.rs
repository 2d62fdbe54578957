//! Metrics every family shares: what a run is scored on (docs/schemas.md, "summary.json"; metric
//! names in cases/README.md), the energy drift, the chart diagnostics and the order fit; a family's
//! own metrics (the rigid body's trajectory errors and momentum drift) live in its folder. One file
//! per metric family; each declares what it needs (a reference, a conserved quantity, a constrained
//! chart) and is absent from the record where that does not apply (never 0), or `null` with a
//! reason where it applies but cannot be computed (e.g. the run failed before `t_end`).
use std::collections::BTreeMap;

pub mod chart;
pub mod energy_drift;
pub mod order;

/// Metric values by name (`None` = null) and, for each null, the reason.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Scores {
    pub values: BTreeMap<String, Option<f64>>,
    pub reasons: BTreeMap<String, String>,
}

impl Scores {
    pub fn set(&mut self, name: &str, v: f64) {
        self.values.insert(name.to_string(), Some(v));
    }
    pub fn null(&mut self, name: &str, reason: impl Into<String>) {
        self.values.insert(name.to_string(), None);
        self.reasons.insert(name.to_string(), reason.into());
    }
    pub fn get(&self, name: &str) -> Option<f64> {
        self.values.get(name).copied().flatten()
    }
}
