//! The rigid body's plan of one scene: the compiled body, the initial state, the grid, the
//! work limits, the ladders and the scene's header (names, hashes, primary metric), as
//! `RigidProblem`, the stability study and the benches use them (cases/README.md, "Case-file
//! keys"; the shared parts come from `case` and `catalogue`). Fails with a `CaseError` naming
//! the scene when the scene is not a rigid-body scene.
use crate::case::{self, Case, Scene};
use crate::problem::SceneHeader;
use crate::case::Ladders;

use super::case as rigid_case;
use super::registry::RigidSetup;

/// Everything the suite needs of one scene.
#[derive(Debug, Clone)]
pub struct ScenePlan {
    /// The scene's family, names, hashes and primary metric (`RigidProblem::header`).
    pub header: SceneHeader,
    pub setup: RigidSetup,
    pub energy_scale: f64,
    pub ladders: Ladders,
    pub quick: Ladders,
}

/// The plan of one scene.
pub fn scene_plan(c: &Case, s: &Scene) -> Result<ScenePlan, case::CaseError> {
    let body = rigid_case::rigid_body(c, s)?;
    let initial = rigid_case::RigidScene::of(s)
        .map(rigid_case::initial)
        .ok_or_else(|| case::CaseError {
            file: c.file.clone(),
            key: format!("scene[{}]", s.index),
            message: "not a rigid-body scene".into(),
        })?;
    let limits = c.limits();
    Ok(ScenePlan {
        header: SceneHeader::new(&super::family::FAMILY, c, s),
        setup: RigidSetup {
            body,
            initial,
            grid: crate::run::Grid::of_scene(s),
            limits,
            observe: crate::run::Observe::Grid,
        },
        energy_scale: c.energy_scale,
        ladders: s.ladder(false).values(),
        quick: s.ladder(true).values(),
    })
}

/// The plans of the selected cases and scenes (empty filter lists select all). A name in a
/// filter that matches nothing is an error.
pub fn plans(
    cases: &[Case],
    case_filter: &[String],
    scene_filter: &[String],
) -> Result<Vec<ScenePlan>, String> {
    case::select(cases, case_filter, scene_filter)?
        .into_iter()
        .map(|(c, s)| scene_plan(c, s).map_err(|e| e.to_string()))
        .collect()
}
