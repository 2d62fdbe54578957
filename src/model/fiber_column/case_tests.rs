//! Tests of the fiber column's case files: the catalogue's files load, and bad input is
//! refused with an error naming the file and the key, or ends a run in a typed failure.
use crate::case::{self, CaseError};
use crate::integrate::FailureKind;
use crate::problem::{Stepping, Want, family_of};

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
    case::load_str(&format!("cases/{name}.toml"), &text.replacen(old, new, 1))
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
        let c = case::load_str(label, text).unwrap_or_else(|e| panic!("{e}"));
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
    let e = case::load_str("cases/fiber_column_cyclic.toml", &empty).unwrap_err();
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
    let c = case::load_str("cases/fiber_column_cyclic.toml", &text).unwrap();
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
    let c = case::load_str("cases/fiber_column_cyclic.toml", &text).unwrap();
    let p = (family_of(&c).compile)(&c, &c.scenes[0]).unwrap();
    let v = family_of(&c)
        .find("so3", "newton_disp_krylov", "force_based")
        .unwrap();
    let e = p.run(v, Stepping::Dt(1.0), Want::Timing).unwrap_err();
    assert!(e.contains("10 prelude steps") && e.contains("5885"), "{e}");
}
