//! Tests of the fiber column's case files: the catalogue's files load, and bad input is
//! refused with an error naming the file and the key, or ends a run in a typed failure.
use crate::case::{self, CaseError};
use crate::integrate::FailureKind;
use crate::catalogue::family_of;
use crate::problem::{Stepping, Want};

fn source(name: &str) -> String {
    let label = format!("cases/{name}.toml");
    let (_, text) = case::embedded_sources()
        .iter()
        .find(|(l, _)| *l == label)
        .expect("embedded");
    case::without_gates(text)
}

/// Loads `name`'s file with `old` replaced by `new` (which must occur).
fn edited(name: &str, old: &str, new: &str) -> Result<case::Case, CaseError> {
    let text = source(name);
    assert!(text.contains(old), "{old} not in {name}");
    crate::catalogue::load_str(&format!("cases/{name}.toml"), &text.replacen(old, new, 1))
}

fn refused(name: &str, old: &str, new: &str) -> CaseError {
    match edited(name, old, new) {
        Ok(_) => panic!("{name}: `{new}` was accepted"),
        Err(e) => e,
    }
}

// The catalogue's three fiber-column files load, and their scenes compile.
#[test]
fn catalogue_files_load() {
    for name in [
        "fiber_column_static",
        "fiber_column_cyclic",
        "fiber_column_dynamic",
    ] {
        let (label, text) = case::embedded_sources()
            .iter()
            .find(|(l, _)| *l == format!("cases/{name}.toml"))
            .unwrap_or_else(|| panic!("{name} is not in the catalogue"));
        let c = crate::catalogue::load_str(label, text).unwrap_or_else(|e| panic!("{e}"));
        for s in &c.scenes {
            (family_of(&c).compile)(&c, s).unwrap_or_else(|e| panic!("{e}"));
        }
    }
}

// A negative strength where the model needs a positive one is refused, naming the scene's
// material key and the parameter.
#[test]
fn negative_strength_names_the_key() {
    let e = refused("fiber_column_cyclic", "fy = 420.0e6", "fy = -420.0e6");
    assert_eq!(e.file, "cases/fiber_column_cyclic.toml");
    assert!(e.key.starts_with("scene[0].materials.steel"), "{e}");
    assert!(e.message.contains("fy"), "{e}");
    let e = refused("fiber_column_cyclic", "fpc = -36.0e6", "fpc = 36.0e6");
    assert!(e.key.starts_with("scene[0].materials.core"), "{e}");
}

// A fiber outside the section's outline, a section with no fibers, and a patch naming a
// material the scene does not give are refused by key.
#[test]
fn bad_layouts_are_refused() {
    let e = refused(
        "fiber_column_cyclic",
        "y = [0.21, 0.25], z = [-0.25, 0.25], ny = 2",
        "y = [0.21, 0.35], z = [-0.25, 0.25], ny = 2",
    );
    assert_eq!(e.key, "section", "{e}");
    assert!(e.message.contains("cover_top"), "{e}");
    let text = source("fiber_column_cyclic");
    let start = text.find("patches = [").unwrap();
    let end = text[start..].find("\n]\n").unwrap() + start + 3;
    let l_start = text.find("layers = [").unwrap();
    let l_end = text[l_start..].find("\n]\n").unwrap() + l_start + 3;
    let mut empty = text.clone();
    empty.replace_range(l_start..l_end, "");
    empty.replace_range(start..end, "");
    let e = crate::catalogue::load_str("cases/fiber_column_cyclic.toml", &empty).unwrap_err();
    assert_eq!(e.key, "section", "{e}");
    let e = refused(
        "fiber_column_cyclic",
        "material = \"core\"",
        "material = \"kore\"",
    );
    assert_eq!(e.key, "section.patches[0].material", "{e}");
    assert!(e.message.contains("kore"), "{e}");
}

// A loading must be exactly one kind, and a cyclic scene's horizon must be its protocol's
// length.
#[test]
fn loadings_are_checked() {
    let e = refused(
        "fiber_column_static",
        "load = { tip_force = 1.0 }",
        "load = { tip_force = 1.0, tip_moment = 1.0 }",
    );
    assert_eq!(e.key, "scene[0].load", "{e}");
    let e = refused("fiber_column_cyclic", "t_end = 5880.0", "t_end = 5000.0");
    assert_eq!(e.key, "scene[0].t_end", "{e}");
    assert!(e.message.contains("5880"), "{e}");
    let e = refused("fiber_column_cyclic", "0.0025, 0.005", "0.0026, 0.005");
    assert!(e.key.starts_with("scene[0].load.drifts[0]"), "{e}");
    let e = refused("fiber_column_static", "points = 3", "points = 2");
    assert_eq!(e.key, "numerics.points", "{e}");
}

// A load step that never converges (the first tenth of the elastica's largest load with two
// Newton iterations allowed, where it takes five) ends the run with a typed newton_failure at that step's t, not a
// panic or a silent result.
#[test]
fn a_step_that_never_converges_is_a_typed_failure() {
    let c = edited("fiber_column_static", "max_iter = 40", "max_iter = 2").unwrap();
    let s = c.scene("elastica_p10").unwrap();
    let p = (family_of(&c).compile)(&c, s).unwrap();
    let v = family_of(&c)
        .find("so3", "newton_load", "force_based")
        .unwrap();
    let out = p.run(v, Stepping::Dt(0.1), Want::Scored).unwrap();
    let f = out.failure.expect("a failure");
    assert_eq!(f.kind, FailureKind::NewtonFailure);
    assert_eq!(f.t, 0.1);
    assert!(out.scores.get("tip_error").is_none());
}

/// A material parameter outside its model's meaning is refused at load with the parameter's
/// full key: Concrete02's tensile strength above `|fpc|`, a compressive strength or strain
/// given positive, Steel01's hardening ratio outside [0, 1), Steel02's `c_r1` outside (0, 1).
#[test]
fn material_parameters_out_of_meaning_name_their_key() {
    for (old, new, key) in [
        (
            "ft = 3.0e6, ets = 1.5e9 } }, cover",
            "ft = 40.0e6, ets = 1.5e9 } }, cover",
            "scene[1].materials.core.concrete02.ft",
        ),
        (
            "fpc = -36.0e6, epsc0 = -0.004, fpcu = -30.0e6",
            "fpc = 36.0e6, epsc0 = -0.004, fpcu = -30.0e6",
            "scene[0].materials.core.concrete01.fpc",
        ),
        (
            "epsc0 = -0.002, fpcu = 0.0",
            "epsc0 = 0.002, fpcu = 0.0",
            "scene[0].materials.cover.concrete01.epsc0",
        ),
        (
            "b = 0.01 } } }\nload",
            "b = 1.0 } } }\nload",
            "scene[0].materials.steel.steel01.b",
        ),
        (
            "c_r1 = 0.925",
            "c_r1 = 1.5",
            "scene[1].materials.steel.steel02.c_r1",
        ),
    ] {
        let e = refused("fiber_column_cyclic", old, new);
        assert_eq!(e.file, "cases/fiber_column_cyclic.toml");
        assert_eq!(e.key, key, "{e}");
    }
    let e = refused(
        "fiber_column_cyclic",
        "ft = 3.0e6, ets = 1.5e9 } }, cover",
        "ft = 40.0e6, ets = 1.5e9 } }, cover",
    );
    assert!(e.message.contains("at most |fpc| = 3.6e7"), "{e}");
}

/// A key the loading's kind needs and the file leaves out (the axial load of a pulse or a
/// cyclic scene, its step count, the protocol's increment and cycles) is named as missing,
/// not reported as a NaN value.
#[test]
fn a_missing_loading_key_is_named() {
    for (name, old, new, key) in [
        (
            "fiber_column_dynamic",
            "load = { axial = 750.0e3, axial_steps = 10, pulse",
            "load = { axial_steps = 10, pulse",
            "scene[0].load.axial",
        ),
        (
            "fiber_column_cyclic",
            "load = { axial = 750.0e3, axial_steps = 10, drifts",
            "load = { axial_steps = 10, drifts",
            "scene[0].load.axial",
        ),
        (
            "fiber_column_cyclic",
            "axial = 750.0e3, axial_steps = 10, drifts",
            "axial = 750.0e3, drifts",
            "scene[0].load.axial_steps",
        ),
        (
            "fiber_column_cyclic",
            ", cycles = 2, increment = 5.0e-4 }",
            ", cycles = 2 }",
            "scene[0].load.increment",
        ),
        (
            "fiber_column_cyclic",
            ", cycles = 2, increment",
            ", increment",
            "scene[0].load.cycles",
        ),
    ] {
        let e = refused(name, old, new);
        assert_eq!(e.key, key, "{e}");
        assert!(e.message.starts_with("missing"), "{e}");
        assert!(!e.message.contains("NaN"), "{e}");
    }
}

/// The case's `reference` must be the one its scenes are scored against: `exact` for the
/// static scenes (the elastica), `external` for the cyclic and pulse scenes (OpenSees' runs);
/// a kind the family has not (`numerical`) is refused before the scenes are read.
#[test]
fn the_reference_kind_fits_the_scenes() {
    let e = refused(
        "fiber_column_static",
        "reference = \"exact\"",
        "reference = \"external\"",
    );
    assert_eq!(e.key, "reference", "{e}");
    assert!(e.message.contains("scene[0] is static"), "{e}");
    let e = refused(
        "fiber_column_dynamic",
        "reference = \"external\"",
        "reference = \"exact\"",
    );
    assert_eq!(e.key, "reference", "{e}");
    assert!(e.message.contains("whose reference is `external`"), "{e}");
    let e = refused(
        "fiber_column_cyclic",
        "reference = \"external\"",
        "reference = \"numerical\"",
    );
    assert_eq!(e.key, "reference", "{e}");
    assert!(e.message.contains("`exact` or `external`"), "{e}");
}

/// A length outside 1e-6 to 1e6 m (the height of `1e300` that made elements of infinite
/// length, and a cyclic protocol of 5e300 increments) is refused naming its key.
#[test]
fn non_physical_lengths_are_refused() {
    let e = refused("fiber_column_static", "height = 1.0\n", "height = 1.0e300\n");
    assert_eq!(e.key, "column.height", "{e}");
    assert!(e.message.contains("1000000"), "{e}");
    let e = refused("fiber_column_cyclic", "height = 3.0\n", "height = 1.0e300\n");
    assert_eq!(e.key, "column.height", "{e}");
    let e = refused("fiber_column_cyclic", "depth = 0.5\n", "depth = 1.0e-9\n");
    assert_eq!(e.key, "section.depth", "{e}");
    assert!(edited("fiber_column_static", "height = 1.0\n", "height = 1.0e6\n").is_ok());
}

/// Iteration limits above their hard cap (1000) are refused naming the key: `max_iter = 1e9`
/// with a tolerance no step meets used to run for hours.
#[test]
fn iteration_limits_have_a_hard_cap() {
    let runaway = "tol = 1.0e-300\nmax_iter = 1.0e9";
    let e = refused("fiber_column_cyclic", "tol = 1.0e-20\nmax_iter = 50", runaway);
    assert_eq!(e.key, "numerics.max_iter", "{e}");
    assert!(e.message.contains("1000"), "{e}");
    let e = refused(
        "fiber_column_cyclic",
        "element_max_iter = 50",
        "element_max_iter = 1.0e9",
    );
    assert_eq!(e.key, "numerics.element_max_iter", "{e}");
}

/// Newton iterations, state determinations and element iterations count against
/// `max_rhs_evals`: a tolerance no step meets, with a budget of 300, ends the run as a typed
/// `work_limit` naming the key during the axial prelude (t = 0), where the iteration limit
/// alone would have allowed 1000 iterations a step.
#[test]
fn iterations_count_against_the_run_budget() {
    let text = source("fiber_column_cyclic")
        .replacen("tol = 1.0e-20\nmax_iter = 50", "tol = 1.0e-300\nmax_iter = 1000", 1)
        .replacen(
            "reference = \"external\"\n",
            "reference = \"external\"\nmax_rhs_evals = 300\n",
            1,
        );
    let c = crate::catalogue::load_str("cases/fiber_column_cyclic.toml", &text).unwrap();
    let p = (family_of(&c).compile)(&c, &c.scenes[0]).unwrap();
    let v = family_of(&c)
        .find("so3", "newton_disp_krylov", "force_based")
        .unwrap();
    let out = p.run(v, Stepping::Dt(5.0), Want::Scored).unwrap();
    let f = out.failure.expect("a failure");
    assert_eq!(f.kind, FailureKind::WorkLimit, "{f:?}");
    assert_eq!(f.t, 0.0);
    assert!(f.message.contains("max_rhs_evals = 300"), "{f:?}");
}

/// The axial prelude's steps count against `max_steps` in a run too: with 5,885 steps
/// allowed, the 10 prelude steps and 1,176 steps of 5 increments run, the 5,880 steps of 1
/// increment are refused before the run starts.
#[test]
fn the_prelude_counts_against_max_steps() {
    let text = source("fiber_column_cyclic")
        .replacen("order2_4 = [5.0, 1.0]", "order2_4 = [5.0]", 1)
        .replacen(
            "reference = \"external\"\n",
            "reference = \"external\"\nmax_steps = 5885\n",
            1,
        );
    let c = crate::catalogue::load_str("cases/fiber_column_cyclic.toml", &text).unwrap();
    let p = (family_of(&c).compile)(&c, &c.scenes[0]).unwrap();
    let v = family_of(&c)
        .find("so3", "newton_disp_krylov", "force_based")
        .unwrap();
    let e = p.run(v, Stepping::Dt(1.0), Want::Timing).unwrap_err();
    assert!(e.contains("10 prelude steps") && e.contains("5885"), "{e}");
}
