//! The flexible beam's memory and work estimate (`problem::Family::estimate`; cases/README.md,
//! "Budgets"), from the loaded case's numbers. The costly model is `fe_exact`: `3 n + 1`
//! unknowns for `n` elements (the hub angle of a free hub), whose structural integrators
//! hold three dense `n x n` matrices (the tangent and two LU buffers, `structural/state.rs`)
//! and factor the tangent at every Newton iteration, a dense LU (the free hub's angle couples
//! every unknown). The runs counted are `fe_exact` at the scene's finest ladder step with the
//! case's `elements` (the modal forms are small: at most 16 coordinates, `MAX_MODES`), the
//! reference's (`reference_elements` at the reference step; `reference --check` runs at twice
//! it), its self-convergence track (`elements` at a quarter of `min(reference_dt, 1e-3 s)`)
//! and an adaptive run of a modal form at its whole RHS budget.
//!
//! The constants are measurements on this machine (cases/README.md, "Budgets"): a unit is about a
//! nanosecond.
use super::case::{BeamScene, Numerics};
use crate::case::{Case, Estimate, OrderClass, Scene};

/// Work units of a Newton iteration of `fe_exact` per cubed unknown: its dense LU, measured
/// at 4.6 ms with 301 unknowns and 0.30 s with 1,201 (`n^3 / 6` ns), 0.15 ms with 121 (the
/// reference's 40 elements: `n^3 / 12`).
const LU_WORK: f64 = 1.0 / 6.0;

/// Work units per squared unknown and per element of a Newton iteration (the residual and
/// tangent's assembly, the solves).
const SQUARE_WORK: f64 = 10.0;
const ELEMENT_WORK: f64 = 500.0;

/// Newton iterations counted per step: the catalogue's `fe_exact` steps take 1 to 1.9.
const NEWTON_PER_STEP: f64 = 2.0;

/// Work units of one evaluation of a modal form's equations (the 16-coordinate AIGC set:
/// 1.8 us measured under `dop853`).
const MODAL_RHS_WORK: f64 = 2000.0;

/// Bytes a run holds per sample (the observation and its scores', series' and trajectory
/// columns' share: the rigid body's measure 364, `tests/estimates.rs`).
const SAMPLE_BYTES: f64 = 400.0;

/// `fe_exact` with `elements` elements: (bytes of its matrices, work units of one step).
fn fe(elements: f64) -> (f64, f64) {
    let n = 3.0 * elements + 1.0;
    let bytes = 8.0 * (3.0 * n * n + 20.0 * n);
    let iteration = LU_WORK * n * n * n + SQUARE_WORK * n * n + ELEMENT_WORK * elements;
    (bytes, NEWTON_PER_STEP * iteration)
}

/// The scene's estimate (the family's `estimate`).
pub fn estimate(case: &Case, scene: &Scene) -> Estimate {
    let (Some(c), Some(s)) = (case.physics::<Numerics>(), scene.physics::<BeamScene>()) else {
        return Estimate::bounded(0.0, "", 0.0, "");
    };
    let i = scene.index;
    let samples = scene.n_score as f64 * scene.samples_per_score as f64 + 1.0;
    let sample_bytes = samples * SAMPLE_BYTES;
    let (ref_dt, ref_dt_key) = match s.reference_dt {
        Some(h) => (h, format!("scene[{i}].reference_dt")),
        None => (c.reference_dt, "numerics.reference_dt".to_string()),
    };
    let (fe_bytes, fe_step) = fe(c.elements as f64);
    let (ref_bytes, ref_step) = fe(c.reference_elements as f64);
    let elements = "numerics.elements";
    let reference = "numerics.reference_elements";
    let mut e = Estimate::bounded(
        fe_bytes + sample_bytes,
        elements,
        case.max_rhs_evals.min(case.max_adaptive_rhs_evals) as f64 * MODAL_RHS_WORK,
        "max_adaptive_rhs_evals",
    );
    if let Some((key, step)) = OrderClass::ALL
        .into_iter()
        .filter_map(|class| scene.finest(class))
        .max_by_key(|(_, step)| step.steps)
    {
        e = e.max(Estimate::run(
            fe_bytes + sample_bytes,
            elements,
            step.steps as f64,
            &key,
            fe_step,
            elements,
        ));
    }
    let ref_bytes = ref_bytes + (scene.n_score + 1) as f64 * SAMPLE_BYTES;
    e = e.max(Estimate::run(
        ref_bytes,
        reference,
        scene.t_end / ref_dt,
        &ref_dt_key,
        ref_step,
        reference,
    ));
    // The self-convergence track's finest step follows the reference step below 1 ms.
    let quarter = ref_dt.min(1.0e-3) / 4.0;
    let quarter_key = if ref_dt < 1.0e-3 {
        ref_dt_key
    } else {
        format!("scene[{i}].t_end")
    };
    e.max(Estimate::run(
        fe_bytes,
        elements,
        scene.t_end / quarter,
        &quarter_key,
        fe_step,
        elements,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::CaseError;
    use crate::catalogue::load_str;

    fn edited(old: &str, new: &str) -> Result<Case, CaseError> {
        let (label, text) = crate::case::embedded_sources()
            .iter()
            .find(|(l, _)| l.ends_with("flexible_beam.toml"))
            .expect("the beam's file");
        assert!(text.contains(old), "the beam's file lost `{old}`");
        load_str(label, &text.replacen(old, new, 1))
    }

    /// The catalogue's beam scenes fit the default budgets, their costliest run the
    /// reference's (40 elements at the reference step); 10,000 elements (the loader's old
    /// limit) would hold three dense 30,001 x 30,001 matrices, 21.6 GB, and are refused naming
    /// `numerics.elements`, as is a reference step that needs more than `max_steps` steps.
    #[test]
    fn beam_estimates_name_their_keys() {
        let c = edited("schema = 1", "schema = 1").unwrap();
        for s in &c.scenes {
            let e = estimate(&c, s);
            assert!(e.work < crate::case::DEFAULT_MAX_WORK, "{e:?}");
            assert!(e.work_key.contains("reference"), "{e:?}");
        }
        let (bytes, _) = fe(10_000.0);
        assert!((bytes / 21.6e9 - 1.0).abs() < 0.01, "{bytes}");
        let e = edited("elements = 10\n", "elements = 10000\n").unwrap_err();
        assert_eq!(e.key, "numerics.elements", "{e}");
        let e = edited("reference_dt = 1.0e-3", "reference_dt = 1.0e-8").unwrap_err();
        assert_eq!(e.key, "numerics.reference_dt", "{e}");
    }
}
