//! The fiber column's memory and work estimate (`problem::Family::estimate`; cases/README.md,
//! "Budgets"), from the loaded case's numbers before any fiber or matrix exists: for each
//! formulation's mesh (`force_based` with `numerics.elements`, `force_based_fine` with
//! `fine_elements`, the displacement-based meshes of 1 to 8 elements), its dense tangent
//! and factor (`6 n` unknowns for `n` elements: `2 (6n)^2` numbers), its sections (`points`
//! copies per element of the layout's fibers) and its samples; each run at the scene's
//! finest ladder step after its axial prelude (`axial_steps`, which counts against
//! `max_steps`), at [`NEWTON_PER_STEP`] Newton iterations a step, each a dense pass over the
//! tangent and a state determination of every fiber ([`ELEMENT_PER_UPDATE`] times in a
//! force-based element). A static scene's exact reference adds its shooting cross-check at
//! every score time; the pulse's first-period computation (the step search) a dense LU of
//! the tangent.
//!
//! The constants are measurements on this machine (cases/README.md, "Budgets"): they make a unit
//! about a nanosecond. The runtime meter of a run (`column.rs`) counts with the same
//! per-iteration figures ([`Mesh`]).
use super::case::{ColumnCase, ColumnScene, Loading};
use crate::structural::krylov_newton::KRYLOV_DIM;
use super::section::FiberSection;
use crate::case::{Case, Estimate, OrderClass, Scene};

/// Work units per entry of the dense tangent and a Newton iteration (assembly into the zeroed
/// matrix, its copy into the factor, the factor's scans and row-wise trailing checks: the
/// band-limited LU does no more flops than that), as the matrix outgrows the caches: at most
/// 5.6 ns per entry with 40 elements (240 unknowns, 0.5 MB), 12 with 200 (1,200 unknowns,
/// 12 MB), 15 with 400 (46 MB) and 30 with 1,000 (6,000 unknowns, 288 MB: 1.1 s an
/// iteration). Counted as 6 units up to 1 MB, then rising with the logarithm of the size to
/// 30 at 300 MB and beyond (16 at 12 MB, 22 at 46 MB).
pub fn dense_work(dim: f64) -> f64 {
    let mb = 8.0 * dim * dim / 1.0e6;
    let rise = (mb.max(1.0).log10() / 300f64.log10()).min(1.0);
    6.0 + 24.0 * rise
}

/// Work units of one fiber's state determination: 10 ns (Concrete01 and Steel01) to 18 ns
/// (Concrete02 and Steel02) per fiber and iteration on the cyclic scenes' 8-element meshes.
pub const FIBER_WORK: f64 = 20.0;

/// Work units of one section point's own algebra per element iteration (its 3 x 3
/// inverse, its share of the element's 5 x 5 flexibility) and of an element's corotational
/// transformation per point.
pub const POINT_WORK: f64 = 100.0;

/// Newton iterations counted per step: the catalogue's steps take 4 (the pulse) to 8 (the
/// elastica's large loads) state determinations.
pub const NEWTON_PER_STEP: f64 = 8.0;

/// Element iterations counted per force-based element update: 1.5 to 1.7 in the catalogue.
pub const ELEMENT_PER_UPDATE: f64 = 2.0;

/// Bytes a run holds per sample (the observation and its scores', series' and trajectory
/// columns' share: the rigid body's measure 364, `tests/estimates.rs`).
const SAMPLE_BYTES: f64 = 400.0;

/// Bytes of a section point's own state besides its fibers (the section, its trial and
/// committed deformations, forces and flexibility, its interpolation matrix): about 600.
const POINT_BYTES: f64 = 1024.0;

/// Bytes of an element's own state besides its points (the corotational frame, its
/// boxed basic element): about 1 KB.
const ELEMENT_BYTES: f64 = 2048.0;

/// Work units of one score time of a static scene's exact reference: the shooting
/// cross-check integrates 8,192 RK4 steps of the equilibrium ODE.
const EXACT_POINT_WORK: f64 = 8192.0 * 4.0 * 50.0;

/// One formulation's mesh: `count` elements of `points` sections of `fibers` fibers (1 for an
/// elastic section), force-based (element iterations) or displacement-based.
#[derive(Debug, Clone, Copy)]
pub struct Mesh {
    pub count: f64,
    pub points: f64,
    pub fibers: f64,
    pub force: bool,
}

impl Mesh {
    /// Unknowns: six per free node.
    pub fn dim(&self) -> f64 {
        6.0 * self.count
    }

    /// Bytes of the column: (its dense matrices and vectors, its elements: their sections'
    /// fibers and each section point's and element's own state, [`POINT_BYTES`] and
    /// [`ELEMENT_BYTES`]).
    pub fn bytes(&self) -> (f64, f64) {
        let d = self.dim();
        let dense = 8.0 * (2.0 * d * d + (3.0 * KRYLOV_DIM as f64 + 12.0) * d);
        let fiber = FiberSection::bytes_per_fiber() as f64;
        let point = POINT_BYTES + self.fibers * fiber;
        let elements = self.count * (ELEMENT_BYTES + self.points * point);
        (dense, elements)
    }

    /// Work units of one element iteration of one element (a state determination of its
    /// sections).
    pub fn element_iteration_work(&self) -> f64 {
        self.points * (self.fibers * FIBER_WORK + POINT_WORK)
    }

    /// Work units of one Newton iteration: (its dense pass, its elements' state determination
    /// at the nominal element iterations).
    pub fn iteration_work(&self) -> (f64, f64) {
        let d = self.dim();
        let updates = if self.force { ELEMENT_PER_UPDATE } else { 1.0 };
        (
            dense_work(d) * d * d,
            self.count * updates * self.element_iteration_work(),
        )
    }
}

/// The scene's estimate (the family's `estimate`).
pub fn estimate(case: &Case, scene: &Scene) -> Estimate {
    let (Some(c), Some(s)) = (
        case.physics::<ColumnCase>(),
        scene.physics::<ColumnScene>(),
    ) else {
        return Estimate::bounded(0.0, "", 0.0, "");
    };
    let i = scene.index;
    let n = &c.numerics;
    let (fibers, fiber_key) = s.section.fibers();
    let fiber_key = if fiber_key.is_empty() {
        "section".to_string()
    } else {
        fiber_key
    };
    let prelude = super::run::prelude_steps(&s.loading) as f64;
    let (ladder_key, ladder_steps) = OrderClass::ALL
        .into_iter()
        .filter_map(|class| scene.finest(class))
        .max_by_key(|(_, step)| step.steps)
        .map_or((String::new(), 0.0), |(k, step)| (k, step.steps as f64));
    let steps_key = if prelude > ladder_steps {
        format!("scene[{i}].load.axial_steps")
    } else {
        ladder_key
    };
    let samples = scene.n_score as f64 * scene.samples_per_score as f64 + 1.0;
    let layout = fibers * FiberSection::bytes_per_fiber() as f64;
    let mut meshes = vec![(n.elements as f64, "numerics.elements".to_string(), true)];
    if let Some(f) = n.fine_elements {
        meshes.push((f as f64, "numerics.fine_elements".to_string(), true));
    }
    if !matches!(s.loading, Loading::Pulse { .. }) {
        // The displacement-based rivals (the pulse runs force_based only); 8 is the largest.
        meshes.push((8.0, fiber_key.clone(), false));
    }
    let mut e = Estimate::bounded(0.0, "", 0.0, "");
    for (count, count_key, force) in meshes {
        let mesh = Mesh {
            count,
            points: n.points as f64,
            fibers,
            force,
        };
        // The fibers' share grows with the mesh and the section alike: it is named by the
        // mesh when the mesh holds more section points than a section holds fibers.
        let key = |dense: f64, fiber: f64| {
            if dense >= fiber || count * mesh.points >= fibers {
                &count_key
            } else {
                &fiber_key
            }
        };
        let (dense_b, fiber_b) = mesh.bytes();
        let bytes = dense_b + fiber_b + layout + samples * SAMPLE_BYTES;
        let bytes_key = key(dense_b, fiber_b);
        let (dense_w, fiber_w) = mesh.iteration_work();
        let step_key = key(dense_w, fiber_w);
        let step_work = NEWTON_PER_STEP * (dense_w + fiber_w);
        e = e.max(Estimate::run(
            bytes,
            bytes_key,
            ladder_steps + prelude,
            &steps_key,
            step_work,
            step_key,
        ));
        if force && matches!(s.loading, Loading::Pulse { .. }) {
            // The step search's first period: a dense LU of the tangent, once.
            let d = mesh.dim();
            let lu_bytes = bytes + 8.0 * d * d;
            e = e.max(Estimate::bounded(lu_bytes, &count_key, d * d * d / 6.0, &count_key));
        }
    }
    e.prelude_steps = prelude as u64;
    if matches!(s.loading, Loading::TipForce(_) | Loading::TipMoment(_)) {
        let work = (scene.n_score + 1) as f64 * EXACT_POINT_WORK;
        e = e.max(Estimate::bounded(0.0, "", work, &format!("scene[{i}].score_every")));
    }
    e
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::CaseError;
    use crate::catalogue::load_str;

    /// The catalogue file `name` with `old` replaced by `new` (which must occur), loaded.
    fn edited(name: &str, old: &str, new: &str) -> Result<Case, CaseError> {
        let label = format!("cases/{name}.toml");
        let (_, text) = crate::case::embedded_sources()
            .iter()
            .find(|(l, _)| *l == label)
            .expect("a catalogue file");
        assert!(text.contains(old), "{name} lost `{old}`");
        load_str(&label, &text.replacen(old, new, 1))
    }

    /// Every catalogue scene of the column lies well within the default budgets (a tenth of
    /// the memory, a third of the work), its work named by its finest ladder step.
    #[test]
    fn catalogue_scenes_fit_the_defaults() {
        for name in ["fiber_column_static", "fiber_column_cyclic", "fiber_column_dynamic"] {
            let c = edited(name, "schema = 1", "schema = 1").unwrap();
            for s in &c.scenes {
                let e = estimate(&c, s);
                assert!(e.bytes < (crate::case::DEFAULT_MAX_MEMORY_MIB << 20) / 10, "{e:?}");
                assert!(e.work < crate::case::DEFAULT_MAX_WORK / 3, "{e:?}");
                assert!(e.work_key.contains("ladders.order2_4"), "{e:?}");
            }
        }
    }

    /// A mesh of 1,000 elastic elements holds its two dense 6,000 x 6,000 matrices: within
    /// 5 % of the 575 MB measured for the elastica with that mesh (`/usr/bin/time`), over the
    /// default memory budget and refused naming `numerics.elements`.
    #[test]
    fn a_thousand_elements_hold_their_dense_tangent() {
        let mesh = Mesh {
            count: 1000.0,
            points: 3.0,
            fibers: 1.0,
            force: true,
        };
        let (dense, elements) = mesh.bytes();
        let mb = (dense + elements) / 1.0e6;
        assert!((mb / 575.0 - 1.0).abs() < 0.05, "{mb} MB");
        let e = edited("fiber_column_static", "elements = 10\n", "elements = 1000\n").unwrap_err();
        assert_eq!(e.key, "numerics.elements", "{e}");
        assert!(e.message.contains("max_memory_mib = 512"), "{e}");
    }

    /// The axial prelude's steps count against `max_steps`: 1e6 of them are refused naming
    /// `axial_steps`, and the prelude is in a run's steps; a million fibers are refused (by
    /// memory, naming the patch) and a 30-element force-based mesh on the cyclic protocol (by
    /// work, 3.4e10 units: named by the finest ladder step, which the budget affords 4,900
    /// of, the mesh in the message).
    #[test]
    fn preludes_fibers_and_meshes_are_counted() {
        let e = edited(
            "fiber_column_cyclic",
            "axial_steps = 10,",
            "axial_steps = 1.0e6,",
        )
        .unwrap_err();
        assert_eq!(e.key, "scene[0].load.axial_steps", "{e}");
        let text = "reference = \"external\"\nmax_steps = 6000\n";
        let c = edited("fiber_column_cyclic", "reference = \"external\"\n", text).unwrap();
        assert_eq!(estimate(&c, &c.scenes[0]).steps, 5890);
        let e = edited("fiber_column_cyclic", "ny = 16, nz = 2 }", "ny = 1000, nz = 1000 }")
            .unwrap_err();
        assert_eq!(e.key, "section.patches[0].ny", "{e}");
        let e = edited("fiber_column_cyclic", "elements = 1\n", "elements = 30\n").unwrap_err();
        assert_eq!(e.key, "ladders.order2_4[1]", "{e}");
        assert!(e.message.contains("(numerics.elements)"), "{e}");
        assert!(e.message.contains("max_work"), "{e}");
    }
}
