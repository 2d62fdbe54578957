//! The fiber column's references: exact for the static scenes, external (OpenSees) for the
//! cyclic and dynamic ones.
//!
//! **Exact** (`references/<case>/<scene>.json`, made by `mbdbench reference`): the tip at
//! every score time `t` (the load factor) from the Bisshopp-Drucker elastica
//! (`elastica.rs`, at `alpha = t F L^2/EI`) or the roll-up's circle (at
//! `lambda = t M L/(2 pi EI)`), as displacements `top_displacement = across L`,
//! `top_axial = (along - 1) L` and `top_rotation`; cross-checked by shooting on the
//! equilibrium ODE (`shooting.rs`, RK4 with 8192 steps, no elliptic integral), whose largest
//! difference is the accuracy claim.
//!
//! **External** (`references/fiber_column/opensees/<scene>.json`): OpenSees' runs of the same
//! column, made by the Python script beside them; `mbdbench` cannot recompute them, so it
//! checks them (`opensees.rs`: the folder's manifest, the record's schema, columns and
//! claims) and compares their model with the case field by field (`opensees_model.rs`).
//! `reference --check` says how to regenerate them.
use serde::{Deserialize, Serialize};

use crate::reference::{self, Stored};

/// The columns a reference holds after `t`, in this order.
pub const COLUMNS: [&str; 5] = [
    "top_displacement",
    "top_axial",
    "top_rotation",
    "base_shear",
    "axial_force",
];

/// A reference track at the score times: `t` and the columns of [`COLUMNS`] (an exact
/// reference has no forces: those columns are empty).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Track {
    pub t: Vec<f64>,
    pub columns: [Vec<f64>; 5],
}

impl Track {
    /// The column named `name` (empty when the reference has none).
    pub fn column(&self, name: &str) -> &[f64] {
        COLUMNS
            .iter()
            .position(|c| *c == name)
            .map_or(&[][..], |i| &self.columns[i])
    }
}

/// The exact reference's cross-check.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CrossCheck {
    pub method: String,
    /// The largest difference over the score times and the three columns (m, rad).
    pub max_diff: f64,
}

/// How the exact reference was made.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Provenance {
    pub command: String,
    pub method: String,
    pub git_commit: String,
    pub created_utc: String,
    pub rustc: String,
    pub cross_check: CrossCheck,
}

/// A static scene's stored exact reference.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExactReference {
    pub case: String,
    pub scene: String,
    pub t: Vec<f64>,
    pub top_displacement: Vec<f64>,
    pub top_axial: Vec<f64>,
    pub top_rotation: Vec<f64>,
    pub provenance: Provenance,
    /// The claim on the tip's position and rotation (m, rad): the cross-check's difference.
    pub accuracy_claim: f64,
    pub inputs_sha256: String,
}

impl Stored for ExactReference {
    fn times(&self) -> &[f64] {
        &self.t
    }
    fn check_columns(&self) -> Result<(), String> {
        reference::columns_fit(
            self.t.len(),
            &[
                self.top_displacement.len(),
                self.top_axial.len(),
                self.top_rotation.len(),
            ],
        )
    }
}

impl ExactReference {
    /// Its track (no force columns).
    pub fn track(&self) -> Track {
        Track {
            t: self.t.clone(),
            columns: [
                self.top_displacement.clone(),
                self.top_axial.clone(),
                self.top_rotation.clone(),
                vec![],
                vec![],
            ],
        }
    }
}
