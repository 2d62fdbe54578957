//! Tests of the catalogue value: a method registered from outside takes the built-ins' path
//! (the same variants, bit-identical runs), extends only the families that offer its kind of
//! system, and a name that is taken or malformed is refused.
use super::*;
use crate::methods::Fixed;
use crate::methods::builtin::{Cg3, Rk4};
use crate::problem::{Stepping, Want};

/// The built-in catalogue with RK4 registered again under `rk4_twin`.
fn with_twin() -> Catalogue {
    Catalogue::builtin()
        .with_method("rk4_twin", Where::Everywhere, Fixed(Rk4))
        .unwrap()
}

#[test]
fn a_registered_method_runs_as_the_builtin_it_copies() {
    // Invariant: RK4 registered from outside gives, on every chart and formulation of a
    // scene, the outcome of the built-in rk4 bit for bit (scores, work, failure): one path.
    let cat = with_twin();
    let cases = cat.cases().unwrap();
    let p = cat
        .problems(&cases, &["nine_spring".into()], &["two_angles".into()])
        .unwrap()
        .pop()
        .unwrap();
    let mut p = p;
    p.attach_reference(&std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("references"))
        .unwrap();
    let family = p.family();
    let mut compared = 0;
    for twin in family
        .variants()
        .iter()
        .filter(|v| v.integrator == "rk4_twin")
    {
        let rk4 = family.find(twin.param, "rk4", twin.formulation).unwrap();
        assert_eq!(twin.info.order, rk4.info.order);
        assert_eq!(twin.info.lie_group, rk4.info.lie_group);
        let a = p.run(twin, Stepping::Dt(1e-2), Want::Scored).unwrap();
        let b = p.run(rk4, Stepping::Dt(1e-2), Want::Scored).unwrap();
        assert_eq!(a.stats, b.stats, "{}/{}", twin.param, twin.formulation);
        assert_eq!(format!("{:?}", a.scores), format!("{:?}", b.scores));
        compared += 1;
    }
    assert_eq!(compared, 22, "every chart in both formulations");
}

#[test]
fn a_registration_extends_the_families_that_offer_its_systems() {
    // Invariant: a generic method reaches the rigid body's 22 chart x formulation systems and
    // the beam's six ODE forms, numbered after the family's own table, and appears on the
    // integrator axis; the other families and the built-in table are untouched.
    let cat = with_twin();
    let builtin = Catalogue::builtin();
    for (model, added) in [
        ("rigid_body", 22),
        ("flexible_beam", 6),
        ("fiber_column", 0),
    ] {
        let ext = cat.find_family(model).unwrap();
        let base = builtin.find_family(model).unwrap();
        assert_eq!(
            ext.variants().len(),
            base.variants().len() + added,
            "{model}"
        );
        let mut idx: Vec<usize> = ext.variants().iter().map(|v| v.index).collect();
        idx.sort_unstable();
        idx.dedup();
        assert_eq!(idx.len(), ext.variants().len(), "{model}: indices unique");
        assert_eq!(
            ext.axes.integrators.contains(&"rk4_twin"),
            added > 0,
            "{model}"
        );
        assert!(!base.variants().iter().any(|v| v.integrator == "rk4_twin"));
    }
    // A Lie-group method only reaches the Lie-group charts, and no beam form.
    let cat = Catalogue::builtin()
        .with_method("cg3_twin", Where::LieGroup, Fixed(Cg3))
        .unwrap();
    let rigid = cat.find_family("rigid_body").unwrap();
    let on: Vec<_> = rigid
        .variants()
        .iter()
        .filter(|v| v.integrator == "cg3_twin")
        .collect();
    assert_eq!(on.len(), 6);
    assert!(
        on.iter()
            .all(|v| crate::model::rigid_body::registry::LIE_PARAMS.contains(&v.param))
    );
    let beam = cat.find_family("flexible_beam").unwrap();
    assert!(!beam.axes.integrators.contains(&"cg3_twin"));
}

#[test]
fn taken_and_malformed_names_are_refused() {
    // Invariant: a built-in name, an earlier registration's name and a name that is not a
    // lower-case identifier are refused with an error naming the method and why.
    for (name, why) in [
        ("rk4", "a built-in integrator"),
        ("newmark", "a built-in integrator"),
        ("Rk4", "lower-case identifier"),
        ("my rk4", "lower-case identifier"),
        ("", "lower-case identifier"),
    ] {
        let e = Catalogue::builtin()
            .with_method(name, Where::Everywhere, Fixed(Rk4))
            .unwrap_err();
        assert!(e.to_string().contains(why), "{name}: {e}");
        assert_eq!(e.name, name);
    }
    let e = with_twin()
        .with_method("rk4_twin", Where::Everywhere, Fixed(Rk4))
        .unwrap_err();
    assert!(e.to_string().contains("earlier registration"), "{e}");
}

#[test]
fn a_registered_structural_method_runs_as_the_builtin_it_copies() {
    // Invariant: Newmark registered from outside as a structural method reaches the beam's
    // three second-order forms only, and on each gives the built-in newmark's outcome bit for
    // bit on a spin-up scene at its quick step.
    let cat = Catalogue::builtin()
        .with_structural_method(
            "newmark_twin",
            crate::structural::newmark::Newmark::new(Default::default()).unwrap(),
        )
        .unwrap();
    assert!(
        !cat.find_family("rigid_body")
            .unwrap()
            .axes
            .integrators
            .contains(&"newmark_twin")
    );
    let cases = cat.cases().unwrap();
    let mut p = cat
        .problems(&cases, &["flexible_beam".into()], &["spinup_w4".into()])
        .unwrap()
        .pop()
        .unwrap();
    p.attach_reference(&std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("references"))
        .unwrap();
    let family = p.family();
    let twins: Vec<_> = family
        .variants()
        .iter()
        .filter(|v| v.integrator == "newmark_twin")
        .collect();
    let forms: Vec<&str> = twins.iter().map(|v| v.formulation).collect();
    assert_eq!(forms, ["fe_exact", "modal_stiffened", "modal_linear"]);
    for twin in twins {
        let newmark = family.find("none", "newmark", twin.formulation).unwrap();
        let dt = p.ladder(true, &twin.info)[0];
        let a = p.run(twin, Stepping::Dt(dt), Want::Scored).unwrap();
        let b = p.run(newmark, Stepping::Dt(dt), Want::Scored).unwrap();
        assert_eq!(a.stats, b.stats, "{}", twin.formulation);
        assert_eq!(format!("{:?}", a.scores), format!("{:?}", b.scores));
        assert_eq!(a.failure.is_some(), b.failure.is_some());
    }
}
