//! The parser layer: the real case files, mutated (`mutate.rs`), fed to `catalogue::load_str`.
//! Checks that loading never panics and gives either a case that satisfies the invariants
//! after loading (finite states, symmetric inertia, sane ladders and grids) or an error that
//! names the file and the key (or the line of a syntax error).
use mbdbench::case::{self, Case, CaseError};
use mbdbench::model::rigid_body::plan as rigid_plan;
use proptest::prelude::*;
use proptest::sample::Index;

use crate::config;
use crate::mutate::{apply, mutation};

// ---------------------------------------------------------------------------------------
// Checks

/// A load error names the file, and the key or the line.
pub fn check_error(label: &str, e: &CaseError) {
    assert_eq!(e.file, label, "{e}");
    let shown = e.to_string();
    assert!(shown.starts_with(label), "`{shown}` does not name the file");
    assert!(
        !e.key.is_empty() || e.message.contains("line "),
        "`{shown}` names neither a key nor a line"
    );
    if !e.key.is_empty() {
        assert!(shown.contains(&format!(": {}: ", e.key)), "`{shown}`");
    }
}

/// The invariants of a loaded case (case/mod.rs and each family's case.rs, "Invariants after
/// loading"): the rigid body's state and inertia, the flexible beam's positive physics and
/// breakpoints inside the horizon, the fiber column's loads and protocol.
pub fn check_case(c: &Case) {
    let finite3 = |v: &nalgebra::Vector3<f64>| v.iter().all(|x| x.is_finite());
    assert!(c.energy_scale.is_finite() && c.energy_scale > 0.0);
    assert!(c.max_steps >= 1);
    for s in &c.scenes {
        if let Some(r) = mbdbench::model::rigid_body::case::RigidScene::of(s) {
            assert!(finite3(&r.euler_xyz) && finite3(&r.position) && finite3(&r.velocity));
            assert!(finite3(&r.omega0), "{}: omega0 {:?}", s.name, r.omega0);
            assert!(r.inertia.iter().all(|x| x.is_finite()));
            assert_eq!(r.inertia, r.inertia.transpose());
        } else if let Some(f) = s.physics::<mbdbench::model::fiber_column::case::ColumnScene>() {
            use mbdbench::model::fiber_column::case::Loading;
            let ok = match &f.loading {
                Loading::TipForce(x) | Loading::TipMoment(x) => x.is_finite(),
                Loading::Cyclic {
                    axial, protocol, ..
                } => {
                    *axial > 0.0
                        && protocol.increment() > 0.0
                        && (0..=protocol.len().min(10_000)).all(|i| protocol.at(i).is_finite())
                        && protocol.len() as f64 == s.t_end
                }
                Loading::Pulse {
                    axial,
                    mass,
                    period,
                    ..
                } => *axial > 0.0 && *mass > 0.0 && *period > 0.0,
            };
            assert!(ok, "{}: {:?}", s.name, f.loading);
        } else {
            let b = s
                .physics::<mbdbench::model::flexible_beam::case::BeamScene>()
                .expect("a rigid-body, flexible-beam or fiber-column scene");
            let beam = b.beam;
            for x in [beam.l, beam.ea, beam.ei, beam.rho_a, b.energy_scale] {
                assert!(x.is_finite() && x > 0.0, "{}: {beam:?}", s.name);
            }
            assert!(b.breakpoints.iter().all(|t| *t > 0.0 && *t < s.t_end));
        }
        assert!(s.t_end > 0.0 && s.t_end.is_finite());
        assert!(s.n_score >= 1 && s.samples_per_score >= 1);
        for quick in [false, true] {
            let l = s.ladder(quick);
            for class in case::OrderClass::ALL {
                for f in l.fixed(class) {
                    assert!(f.steps >= 1 && f.steps <= c.max_steps, "{f:?}");
                    assert!(f.h > 0.0 && f.h.is_finite(), "{f:?}");
                }
            }
            assert!(l.tol.iter().all(|t| *t > 0.0 && *t < 1.0));
        }
        assert_eq!(case::inputs_sha256(c, s).len(), 64);
        if c.model() == "rigid_body"
            && let Err(e) = rigid_plan::scene_plan(c, s)
        {
            check_error(&c.file, &e);
        }
    }
}

// ---------------------------------------------------------------------------------------
// Parser

proptest! {
    #![proptest_config(config(1))]

    /// Loading a mutated catalogue file never panics: it gives a valid case or an error that
    /// names the file and the key (or the line of a syntax error).
    #[test]
    fn mutated_case_files_load_or_name_file_and_key(
        which in any::<Index>(),
        muts in prop::collection::vec(mutation(), 1..=4),
    ) {
        let sources = case::embedded_sources();
        let (label, text) = *which.get(sources);
        let mut t = text.to_string();
        for m in &muts {
            t = apply(&t, m);
        }
        match mbdbench::catalogue::load_str(label, &t) {
            Ok(c) => check_case(&c),
            Err(e) => check_error(label, &e),
        }
    }
}
