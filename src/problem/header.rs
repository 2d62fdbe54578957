//! The header of one compiled scene: which family, case and scene it is, the two hashes every
//! record of it is stamped with, and the case's primary metric. Every family's
//! [`Problem`](super::Problem) stores one and hands it out through `Problem::header`; the
//! trait's getters `family`, `case`, `scene`, `inputs_sha256`, `settings_sha256` and
//! `primary_metric` read it, so a family writes none of them.
//!
//! Invariants, as [`SceneHeader::new`] makes it from a loaded case: `case` and `scene` name a
//! scene of a case of `family`; `inputs_sha256` is `case::inputs_sha256` of that scene (its
//! physics and its reference's numerical settings: a stored reference or a baseline record
//! with another hash is stale), `settings_sha256` is the scene's `Scene::settings_sha256`;
//! `primary_metric` is the case's, one of `family.metrics` (the loader refuses any other).
//! Nothing here is read by a run: the header labels the records, never changes a number in
//! them.
//!
//! The scene's grid (`t_end`, `score_every`, `sample_every`) is not here: it is part of what a
//! family's run functions read (its setup's `run::Grid`), and one copy of it, in the setup,
//! is the one the steps are taken on. `Problem::grid` gives it out and `Problem::t_end` and
//! its kin read it there.
use std::path::Path;

use super::Family;
use crate::case::{Case, Scene};
use crate::reference::{self, Stored};
use crate::run::Grid;

/// What names one compiled scene and stamps its records (the module's invariants hold).
///
/// # Example
///
/// ```
/// use mbdbench::problem::SceneHeader;
///
/// let cases = mbdbench::catalogue::embedded().unwrap();
/// let c = cases.iter().find(|c| c.name == "nine_spring").unwrap();
/// let s = c.scene("two_angles").unwrap();
/// let family = mbdbench::catalogue::family_of(c);
/// let h = SceneHeader::new(family, c, s);
/// assert_eq!((h.case.as_str(), h.scene.as_str()), ("nine_spring", "two_angles"));
/// assert_eq!(h.inputs_sha256, mbdbench::case::inputs_sha256(c, s));
/// assert!(family.has_metric(&h.primary_metric));
///
/// // A compiled scene's getters read its header.
/// let p = (family.compile)(c, s).unwrap();
/// assert_eq!(p.header().inputs_sha256, h.inputs_sha256);
/// assert!(std::ptr::eq(p.family(), family));
/// assert_eq!(p.scene(), "two_angles");
/// ```
#[derive(Debug, Clone)]
pub struct SceneHeader {
    /// The family the scene is compiled by.
    pub family: &'static Family,
    /// The case's name.
    pub case: String,
    /// The scene's name within the case.
    pub scene: String,
    /// The SHA-256 of the scene's physics and its reference's numerical settings
    /// (cases/README.md, "Physics hash").
    pub inputs_sha256: String,
    /// The SHA-256 of every other case-file key that can change a result (`case::hash`):
    /// the scene's `Scene::settings_sha256`.
    pub settings_sha256: String,
    /// The case's primary error metric.
    pub primary_metric: String,
    /// The `where` filters of the case's gates that can name this scene's points: a ladder
    /// does not stop early at a point a gate names (`suite::skip`).
    pub gated: Vec<crate::case::GateWhere>,
}

impl SceneHeader {
    /// The header of scene `scene` of the loaded case `case`, compiled by `family`.
    pub fn new(family: &'static Family, case: &Case, scene: &Scene) -> Self {
        SceneHeader {
            family,
            case: case.name.clone(),
            scene: scene.name.clone(),
            inputs_sha256: crate::case::inputs_sha256(case, scene),
            settings_sha256: scene.settings_sha256.clone(),
            primary_metric: case.primary_metric.clone(),
            gated: case
                .gates
                .iter()
                .map(|g| g.filter.clone())
                .filter(|f| f.scene.is_empty() || f.scene.contains(&scene.name))
                .collect(),
        }
    }

    /// The scene's stored reference as a family attaches it: `reference::load_as` under the
    /// header's names and physics hash from `root`, then its times checked against `grid`'s
    /// score times (`reference::check_grid`, the error naming the file); with the SHA-256 of
    /// the file. Every error is one line.
    pub fn load_reference<R: Stored>(
        &self,
        root: &Path,
        grid: &Grid,
    ) -> Result<(R, String), String> {
        let (r, sha): (R, String) =
            reference::load_as(root, &self.case, &self.scene, &self.inputs_sha256)
                .map_err(|e| e.to_string())?;
        reference::check_grid(r.times(), grid.t_end, grid.score_every)
            .map_err(|m| reference::grid_error(root, &self.case, &self.scene, m).to_string())?;
        Ok((r, sha))
    }
}
