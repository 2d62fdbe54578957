//! Tests of case loading: the embedded catalogue's structure and derived data, the error of
//! every kind of bad input (named by file and key path), ladders and step counts, and the
//! physics hash. The fixtures are the rigid-body catalogue files.
use super::*;
use crate::catalogue::{embedded, load_dir, load_str};
use crate::math::so3;
use crate::model::rigid_body::case::{AngularInit, RigidCase, RigidScene, initial, rigid_body};
use nalgebra::Matrix3;
use nalgebra::Vector3;

const NINE: &str = include_str!("../../cases/nine_spring.toml");

/// The rigid-body data of a catalogue case (every embedded case is one).
fn rc(c: &Case) -> &RigidCase {
    RigidCase::of(c).unwrap()
}

/// The rigid-body data of a catalogue scene.
fn rs(s: &Scene) -> &RigidScene {
    RigidScene::of(s).unwrap()
}
const LABEL: &str = "cases/nine_spring.toml";

/// `NINE` with the first `old` replaced by `new` (which must occur).
fn edited(old: &str, new: &str) -> String {
    assert!(NINE.contains(old), "test fixture lost `{old}`");
    NINE.replacen(old, new, 1)
}

/// The error of loading `text`, checked to name the file and `key` in its Display.
fn error_at(text: &str, key: &str) -> CaseError {
    let e = load_str(LABEL, text).expect_err("bad input must not load");
    let shown = e.to_string();
    assert!(shown.starts_with(LABEL), "`{shown}` does not name the file");
    assert_eq!(e.key, key, "`{shown}`");
    assert!(shown.contains(&format!("{LABEL}: {key}: ")), "`{shown}`");
    e
}

/// Energy of `nine_spring` (cases/README.md, "Equations solved") from the parsed data:
/// `m|v|^2/2 + omega.J.omega/2 + sum k (l - L0)^2/2 + m g0 x_z`.
fn energy0(case: &Case, scene: &Scene) -> f64 {
    let (case, scene) = (rc(case), rs(scene));
    let m = case.body.mass.unwrap();
    let mut e = 0.5 * m * scene.velocity.norm_squared()
        + 0.5 * scene.omega0.dot(&(scene.inertia * scene.omega0))
        + m * case.body.gravity.unwrap_or(0.0) * scene.position.z;
    for s in &case.springs {
        let l = (s.anchor - (scene.position + scene.r0 * s.body_point)).norm();
        e += 0.5 * s.stiffness * (l - s.rest_length).powi(2);
    }
    e
}

// Every embedded catalogue file loads, with the structure cases/README.md describes.
#[test]
fn embedded_files_load() {
    let cases = embedded().unwrap();
    let names: Vec<&str> = cases.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "fiber_column_cyclic",
            "fiber_column_dynamic",
            "fiber_column_static",
            "flexible_beam",
            "free_body",
            "gimbal_lock",
            "heavy_top",
            "nine_spring"
        ]
    );
    for c in &cases {
        assert_eq!(c.file, format!("cases/{}.toml", c.name));
        assert_eq!(c.max_steps, DEFAULT_MAX_STEPS);
        assert_eq!(c.max_rhs_evals, DEFAULT_MAX_RHS_EVALS);
        assert_eq!(c.max_adaptive_rhs_evals, DEFAULT_MAX_ADAPTIVE_RHS_EVALS);
        // Every catalogue case is gated, the quick tier included.
        assert!(
            c.gates.iter().any(|g| g.quick),
            "{} has no quick gate",
            c.name
        );
        // A family without adaptive methods (the fiber column) has no tolerance ladder.
        let adaptive = crate::catalogue::family_of(c)
            .variants()
            .iter()
            .any(|v| v.info.adaptive);
        for s in &c.scenes {
            assert!(!s.ladders.order2_4.is_empty() && (!adaptive || !s.ladders.tol.is_empty()));
            // Every class the full ladders use has one quick point.
            for class in OrderClass::ALL {
                let want = usize::from(!s.ladders.fixed(class).is_empty());
                assert_eq!(s.quick.fixed(class).len(), want, "{}/{}", c.name, s.name);
            }
            assert_eq!(s.quick.tol.len(), usize::from(adaptive));
        }
    }
    let by = |n: &str| cases.iter().find(|c| c.name == n).unwrap();
    let g = by("gimbal_lock");
    let scenes: Vec<&str> = g.scenes.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(
        scenes,
        [
            "spin_d0",
            "spin_d1e-2",
            "spin_d1e-4",
            "spin_d1e-8",
            "spin_zxz_d1e-2",
            "spin_zxz_d1e-4",
            "tumble"
        ]
    );
    assert_eq!(g.reference, ReferenceKind::EXACT);
    assert_eq!(by("free_body").reference, ReferenceKind::EXACT);
    assert_eq!(by("heavy_top").reference, ReferenceKind::NUMERICAL);
    assert_eq!(by("nine_spring").reference, ReferenceKind::NUMERICAL);
    let spin = g.scene("spin_d1e-2").unwrap();
    assert!(spin.ladders.order2_4.iter().any(|f| f.dt == 1.0e-2));
    assert!(spin.ladders.tol.contains(&1.0e-8) && spin.ladders.tol.contains(&1.0e-10));
    assert!(rc(g).translates());
    let f = by("free_body");
    let f = rc(f);
    assert!(f.nonphysical_inertia && f.body.mass.is_none() && !f.translates());
    let h = rc(by("heavy_top"));
    assert_eq!(h.body.pivot_com, Some(Vector3::new(0.0, 1.0, 0.0)));
    assert!(!h.translates() && !h.nonphysical_inertia);
    assert_eq!(h.body.gravity, Some(9.81));
}

// E0 of nine_spring's scenes equals the values cases/README.md prints, to their last digit.
#[test]
fn nine_spring_initial_energies_match_the_spec() {
    let c = load_str(LABEL, NINE).unwrap();
    let large = energy0(&c, c.scene("large").unwrap());
    let two = energy0(&c, c.scene("two_angles").unwrap());
    // Printed as 25035.29 and 6524.2: half a unit of the last printed digit.
    assert!((large - 25035.29).abs() <= 0.005, "large E0 = {large}");
    assert!((two - 6524.2).abs() <= 0.05, "two_angles E0 = {two}");
    // The same energy through the model the runner will build.
    for s in &c.scenes {
        let body = rigid_body(&c, s).unwrap();
        let e = body.energy(&initial(rs(s)));
        assert!((e - energy0(&c, s)).abs() <= 1e-9 * e, "{}: {e}", s.name);
    }
}

// Derived initial data: R0 = Rx Ry Rz, body omega from each of the three inputs.
#[test]
fn derived_initial_state() {
    let cases = embedded().unwrap();
    let g = cases.iter().find(|c| c.name == "gimbal_lock").unwrap();
    let z = rs(g.scene("spin_zxz_d1e-2").unwrap());
    // R0 = Ry(pi/2): body z along world x (to the rounding of cos(pi/2) ~ 6e-17).
    assert!((z.r0 * Vector3::z() - Vector3::x()).amax() <= 1e-15);
    assert!((z.r0 - so3::ry(std::f64::consts::FRAC_PI_2)).amax() == 0.0);
    let w = Vector3::new(0.009999833334166664, 0.9999500004166653, 0.0);
    assert_eq!(z.angular, AngularInit::World(w));
    // omega_body = R0^T w, an orthogonal map: the norm is kept to round-off.
    assert!((z.r0 * z.omega0 - w).amax() <= 1e-15);
    assert!((z.omega0.norm() - 1.0).abs() <= 1e-15);
    let t = rs(g.scene("tumble").unwrap());
    assert!(t.inertia_override);
    assert_eq!(
        t.inertia,
        Matrix3::from_diagonal(&Vector3::new(0.3, 0.35, 0.4))
    );
    assert_eq!(t.omega0, Vector3::new(0.1, 15.0, 0.1));
    assert!((t.r0 - so3::rx(0.5) * so3::rz(0.3)).amax() <= 1e-16);
    assert!((t.q0.to_rotation_matrix().into_inner() - t.r0).amax() <= 1e-15);
    let f = cases.iter().find(|c| c.name == "free_body").unwrap();
    let gni = rs(&f.scenes[0]);
    // J omega0 reproduces L = (cos 1.1, 0, sin 1.1) to round-off.
    let l = Vector3::new(0.4535961214255773, 0.0, 0.8912073600614354);
    assert!((gni.inertia * gni.omega0 - l).amax() <= 1e-15);
    assert_eq!(gni.position, Vector3::zeros());
}

// Ladders resolve per scene: overrides win, step counts follow the divides rule.
#[test]
fn ladders_and_step_counts() {
    let cases = embedded().unwrap();
    let g = cases.iter().find(|c| c.name == "gimbal_lock").unwrap();
    let spin = g.scene("spin_d0").unwrap();
    assert_eq!(spin.n_score, 320);
    assert_eq!(spin.samples_per_score, 1);
    let f = spin.ladders.order2_4[0];
    assert_eq!((f.dt, f.per_score, f.steps), (1.0e-2, 1, 320));
    assert!((f.h - 0.01).abs() <= 1e-17);
    let tumble = g.scene("tumble").unwrap();
    assert_eq!(tumble.ladders.order2_4[0].dt, 2.0e-2);
    assert_eq!(tumble.ladders.order2_4[0].steps, 1000);
    // The override has no tol: the case's applies.
    assert_eq!(tumble.ladders.tol, spin.ladders.tol);
    assert_eq!(tumble.quick.order6[0].dt, 5.0e-2);
    assert_eq!(tumble.quick.tol, vec![1.0e-8]);
    let h = cases.iter().find(|c| c.name == "heavy_top").unwrap();
    let s = &h.scenes[0];
    let last = s.ladders.order1.last().unwrap();
    assert_eq!((last.per_score, last.steps), (2000, 400_000));
    assert_eq!(s.samples_per_score, 10);
    assert_eq!(OrderClass::of_order(4), Some(OrderClass::Order2To4));
    assert_eq!(OrderClass::of_order(6), Some(OrderClass::Order6));
    assert_eq!(OrderClass::of_order(1), Some(OrderClass::Order1));
}

// The divides rule (cases/README.md, "Conventions"): n = round(T/h), |n h - T| <= 1e-9 T.
#[test]
fn steps_dividing_rule() {
    assert_eq!(steps_dividing(0.1, 1.0e-2), Some(10));
    assert_eq!(steps_dividing(3.2, 0.01), Some(320));
    assert_eq!(steps_dividing(0.01, 1.25e-4), Some(80));
    assert_eq!(steps_dividing(0.1, 6.25e-6), Some(16000));
    assert_eq!(steps_dividing(0.1, 0.1), Some(1));
    assert_eq!(steps_dividing(0.1, 3.0e-2), None);
    assert_eq!(steps_dividing(0.1, 0.2), None); // n = round(0.5) would be 0 or 1: off
    // Within 1e-9 relative passes, 1e-8 does not.
    assert_eq!(steps_dividing(1.0, 0.1 * (1.0 + 5e-11)), Some(10));
    assert_eq!(steps_dividing(1.0, 0.1 * (1.0 + 1e-8)), None);
    assert_eq!(steps_dividing(0.0, 0.1), None);
    assert_eq!(steps_dividing(1.0, -0.1), None);
    assert_eq!(steps_dividing(1.0, f64::NAN), None);
    assert_eq!(steps_dividing(f64::INFINITY, 0.1), None);
    // The step count is bounded by 9e15 (every integer up to it is exact in f64), one
    // bound for case loading and the run loop (`run::divides` is this function).
    assert_eq!(steps_dividing(9.0e15, 1.0), Some(9_000_000_000_000_000));
    assert_eq!(steps_dividing(9.0e15 + 2.0, 1.0), None);
    assert_eq!(
        crate::run::divides(1.0e15, 1.0),
        Some(1_000_000_000_000_000)
    );
}

// An unknown key is named with its full path.
#[test]
fn unknown_key() {
    let e = error_at(
        &edited(
            "name = \"large\"\n",
            "name = \"large\"\nomgea = [0.0, 0.0, 1.0]\n",
        ),
        "scene[0].omgea",
    );
    assert!(e.message.contains("unknown field `omgea`"), "{e}");
    error_at(
        &edited("[ladders]\n", "[ladders]\norder3 = [1.0]\n"),
        "ladders.order3",
    );
    error_at(
        &edited("quick = { order1", "quick = { order5 = [1.0], order1"),
        "ladders.quick.order5",
    );
    error_at(
        &edited("schema = 1\n", "schema = 1\nauthor = \"x\"\n"),
        "author",
    );
}

/// A `reference` kind the case's family cannot attach is refused at load, naming the key
/// `reference`: `external` (another program's stored run) on the rigid body and on the
/// flexible beam, `exact` on the beam (its reference is integrated).
#[test]
fn a_reference_kind_the_family_cannot_attach_is_refused() {
    let e = error_at(
        &edited("reference = \"numerical\"", "reference = \"external\""),
        "reference",
    );
    assert!(e.message.contains("`numerical` or `exact`"), "{e}");
    let beam = include_str!("../../cases/flexible_beam.toml");
    let label = "cases/flexible_beam.toml";
    assert!(beam.contains("reference = \"numerical\""));
    for kind in ["external", "exact"] {
        let text = beam.replacen(
            "reference = \"numerical\"",
            &format!("reference = \"{kind}\""),
            1,
        );
        let e = load_str(label, &text).expect_err(kind);
        assert_eq!(
            (e.file.as_str(), e.key.as_str()),
            (label, "reference"),
            "{e}"
        );
        assert!(e.message.starts_with(&format!("`{kind}`")), "{e}");
    }
}

// A wrong type is named with the path of the value, down to an array index.
#[test]
fn wrong_type() {
    let e = error_at(&edited("mass = 1000.0", "mass = \"heavy\""), "body.mass");
    assert!(e.message.contains("expected f64"), "{e}");
    error_at(
        &edited(
            "euler_xyz = [0.0, 0.5, 1.0]",
            "euler_xyz = [0.0, 0.5, \"1\"]",
        ),
        "scene[1].euler_xyz[2]",
    );
    let e = error_at(
        &edited("euler_xyz = [0.0, 0.5, 1.0]", "euler_xyz = [0.0, 0.5]"),
        "scene[1].euler_xyz",
    );
    assert!(e.message.contains("length 3"), "{e}");
    error_at(
        &edited("stiffness = 5.0e3 ", "stiffness = [5.0e3]"),
        "spring[0].stiffness",
    );
    error_at(&edited("schema = 1", "schema = 1.0"), "schema");
    let e = error_at(&edited("\"numerical\"", "\"stored\""), "reference");
    assert!(
        e.message.contains("`stored`") && e.message.contains("`numerical` or `exact`"),
        "{e}"
    );
}

// A missing required key is named, and a TOML syntax error gives file and line.
/// The rigid body's step search needs a rotation bound: a `[stability]` table without
/// `rotation_error_max` is refused at loading with that key named.
#[test]
fn rigid_stability_needs_a_rotation_bound() {
    let e = error_at(
        &edited("rotation_error_max = 0.1\n", ""),
        "stability.rotation_error_max",
    );
    assert!(e.message.contains("missing"), "{e}");
}

#[test]
fn missing_key_and_syntax_error() {
    let text = edited(
        "euler_xyz = [0.0, 0.5, 1.0]\nt_end = 10.0\n",
        "euler_xyz = [0.0, 0.5, 1.0]\n",
    );
    let e = error_at(&text, "scene[1].t_end");
    assert!(e.message.contains("missing field `t_end`"), "{e}");
    let e = error_at(
        &edited("gravity = 9.81", "gravity = 9.81 m/s2"),
        "body.gravity",
    );
    let line_of = |s: &str| NINE.lines().position(|l| l.starts_with(s)).unwrap() + 1;
    assert!(
        e.message.contains(&format!("line {}", line_of("gravity"))),
        "{e}"
    );
    let e = load_str(LABEL, &edited("[body]", "[body")).unwrap_err();
    assert!(
        e.to_string().starts_with(LABEL)
            && e.message.contains(&format!("line {}", line_of("[body]"))),
        "{e}"
    );
}

// Mass must be positive; a zero or negative mass names body.mass.
#[test]
fn non_positive_mass() {
    for m in ["0.0", "-1000.0"] {
        let e = error_at(
            &edited("mass = 1000.0", &format!("mass = {m}")),
            "body.mass",
        );
        assert!(e.message.contains("> 0"), "{e}");
    }
}

// The inertia must be symmetric, positive definite and physical (unless flagged).
#[test]
fn bad_inertia() {
    let j = "[[800.0, -60.0, 40.0], [-60.0, 1000.0, -80.0], [40.0, -80.0, 1200.0]]";
    let with = |m: &str| edited(j, m);
    let e = error_at(
        &with("[[800.0, -60.0, 40.0], [-60.0, 1000.0, -80.0], [40.0, -80.5, 1200.0]]"),
        "body.inertia",
    );
    assert!(e.message.contains("symmetric"), "{e}");
    // Off by 1e-13 relative: symmetric within 1e-12, accepted.
    load_str(
        LABEL,
        &with("[[800.0, -60.0, 40.0], [-60.0, 1000.0, -80.0], [40.0, -80.00000000001, 1200.0]]"),
    )
    .unwrap();
    let e = error_at(
        &with("[[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]]"),
        "body.inertia",
    );
    assert!(e.message.contains("positive definite"), "{e}");
    error_at(
        &with("[[1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]]"),
        "body.inertia",
    );
    // diag(2, 1, 2/3) violates 1 + 2/3 >= 2.
    let gni = "[[2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.6666666666666666]]";
    let e = error_at(&with(gni), "body.inertia");
    assert!(e.message.contains("triangle inequality"), "{e}");
    // The same body loads with the flag.
    let flagged = with(gni).replace(
        "reference = \"numerical\"",
        "reference = \"numerical\"\nnonphysical_inertia = true",
    );
    load_str(LABEL, &flagged).unwrap();
    // Equality is physical (heavy_top's disc): it loads without the flag.
    let disc = "[[0.234375, 0.0, 0.0], [0.0, 0.46875, 0.0], [0.0, 0.0, 0.234375]]";
    let c = load_str(LABEL, &with(disc)).unwrap();
    assert!(!rc(&c).nonphysical_inertia);
    // A per-scene override is checked too, under its own key.
    let e = error_at(
        &edited(
            "name = \"two_angles\"\n",
            &format!("name = \"two_angles\"\ninertia = {gni}\n"),
        ),
        "scene[1].inertia",
    );
    assert!(e.message.contains("triangle"), "{e}");
}

// t_end, sample_every and score_every must be positive and nest by the divides rule.
#[test]
fn bad_times() {
    for t in ["0.0", "-10.0"] {
        let e = error_at(
            &edited(
                "euler_xyz = [0.0, 0.5, 1.0]\nt_end = 10.0",
                &format!("euler_xyz = [0.0, 0.5, 1.0]\nt_end = {t}"),
            ),
            "scene[1].t_end",
        );
        assert!(e.message.contains("> 0"), "{e}");
    }
    error_at(
        &edited("t_end = 10.0", "t_end = 10.05"),
        "scene[0].score_every",
    );
    error_at(
        &edited("sample_every = 0.01", "sample_every = 0.03"),
        "scene[0].sample_every",
    );
}

// A ladder step that does not divide score_every names the step and the scene.
#[test]
fn ladder_step_not_dividing() {
    let e = error_at(
        &edited("order2_4 = [2.0e-2,", "order2_4 = [3.0e-2,"),
        "ladders.order2_4[0]",
    );
    assert!(
        e.message.contains("does not divide") && e.message.contains("`large`"),
        "{e}"
    );
    error_at(
        &edited("quick = { order1 = [1.0e-3]", "quick = { order1 = [7.0e-3]"),
        "ladders.quick.order1[0]",
    );
    error_at(&edited("tol = [1.0e-4,", "tol = [2.0,"), "ladders.tol[0]");
    // A step longer than the score interval does not divide it either.
    error_at(
        &edited("order6 = [5.0e-2,", "order6 = [2.0e-1,"),
        "ladders.order6[0]",
    );
}

// NaN and infinities are rejected wherever a number is read.
#[test]
fn non_finite_numbers() {
    let e = error_at(&edited("t_end = 10.0", "t_end = nan"), "scene[0].t_end");
    assert!(e.message.contains("finite"), "{e}");
    error_at(
        &edited("stiffness = 5.0e3 ", "stiffness = inf "),
        "spring[0].stiffness",
    );
    error_at(
        &edited("[-60.0, 1000.0, -80.0]", "[-60.0, nan, -80.0]"),
        "body.inertia[1][1]",
    );
    error_at(
        &edited(
            "euler_xyz = [0.0, 0.5, 1.0]",
            "euler_xyz = [0.0, -inf, 1.0]",
        ),
        "scene[1].euler_xyz[1]",
    );
}

// Finite inputs whose derived body rate overflows (found by tests/fuzz.rs) are an error
// naming the angular key, not a case whose omega0 is infinite.
#[test]
fn non_finite_body_rate() {
    let scene = |extra: &str| {
        edited(
            "name = \"two_angles\"\n",
            &format!("name = \"two_angles\"\n{extra}\n"),
        )
    };
    let e = error_at(
        &scene(
            "inertia = [[1.0e-300, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]\n\
             angular_momentum_body = [1.0e10, 0.0, 0.0]",
        ),
        "scene[1].angular_momentum_body",
    );
    assert!(e.message.contains("finite"), "{e}");
    let e = error_at(
        &scene("omega_world = [1.7e308, 1.7e308, 1.7e308]"),
        "scene[1].omega_world",
    );
    assert!(e.message.contains("finite"), "{e}");
    // The largest rates that stay finite load.
    load_str(LABEL, &scene("omega = [1.7e308, 1.7e308, 1.7e308]")).unwrap();
}

// Other validations: names, springs, angular inputs, gates' shape.
#[test]
fn other_validations() {
    error_at(&edited("schema = 1", "schema = 2"), "schema");
    error_at(
        &edited("name = \"large\"", "name = \"two_angles\""),
        "scene[1].name",
    );
    error_at(
        &edited("name = \"large\"", "name = \"la rge\""),
        "scene[0].name",
    );
    error_at(
        &edited(
            "primary_metric = \"rotation_error_max\"",
            "primary_metric = \"rot\"",
        ),
        "primary_metric",
    );
    error_at(
        &edited("energy_scale = 1.0e3", "energy_scale = 0.0"),
        "energy_scale",
    );
    error_at(
        &edited(
            "direction = [1.0, 0.0, 0.0]",
            "direction = [1.0, 1.0e-5, 0.0]",
        ),
        "spring[0].direction",
    );
    error_at(
        &edited("rest_length = 1.0 ", "rest_length = 0.0 "),
        "spring[0].rest_length",
    );
    error_at(
        &edited("stiffness = 5.0e3 ", "stiffness = -1.0 "),
        "spring[0].stiffness",
    );
    error_at(
        &edited(
            "name = \"large\"\n",
            "name = \"large\"\nomega = [0.0, 0.0, 1.0]\nomega_world = [0.0, 0.0, 1.0]\n",
        ),
        "scene[0].omega_world",
    );
    error_at(
        &edited("mass = 1000.0", "pivot_com = [0.0, 1.0, 0.0]"),
        "body.gravity",
    );
    let bare = without_gates(NINE);
    assert!(load_str(LABEL, &bare).unwrap().gates.is_empty());
    let gate = |body: &str| format!("{bare}\n[[gates]]\n{body}\n");
    let ok = gate(
        "metric = \"energy_drift_max\"\nmax = 3.0e-9\nwhere = { scene = \"two_angles\", \
         param = \"so3\", integrator = [\"rk4\", \"gauss6\"], dt = 1.0e-3 }\nquick = true\n\
         baseline = 1.0e-9\nmargin = 3.0\ncommit = \"abc1234\"",
    );
    let c = load_str(LABEL, &ok).unwrap();
    assert_eq!(
        c.gates[0].check,
        crate::case::gate::Check::Bound {
            metric: "energy_drift_max".into(),
            bound: Bound::Max(3.0e-9)
        }
    );
    assert_eq!(c.gates[0].filter.integrator, ["rk4", "gauss6"]);
    assert_eq!(c.gates[0].filter.dt, [1.0e-3]);
    error_at(
        &gate("metric = \"energy_drift_max\"\nmax = 1.0\nmin = 0.0"),
        "gates[0]",
    );
    error_at(
        &gate("metric = \"energy_drift_max\"\nmax = 1.0\nwhere = { scene = \"nope\" }"),
        "gates[0].where.scene[0]",
    );
    error_at(
        &gate("metric = \"energy_drift_max\"\nmax = 1.0\nwhere = { colour = \"red\" }"),
        "gates[0].where.colour",
    );
}

/// An expected-failure gate (`expect`) loads as `Check::Expect`; a gate of neither or both
/// forms, a metric-form key beside `expect`, a status other than "failed", an unknown failure
/// kind, a `before` that is not finite and positive, an `after` outside `[0, before)`, or a
/// missing or unknown `expect` key is an error naming that key.
#[test]
fn expect_gate_shape() {
    let bare = without_gates(NINE);
    let gate = |body: &str| format!("{bare}\n[[gates]]\n{body}\n");
    let expect = |inner: &str, extra: &str| {
        gate(&format!(
            "expect = {{ {inner} }}\nwhere = {{ formulation = \"body\" }}\n{extra}"
        ))
    };
    let good = "status = \"failed\", kind = \"diverged\", after = 5.0, before = 20.0";
    let c = load_str(LABEL, &expect(good, "quick = true\ncommit = \"abc1234\"")).unwrap();
    assert_eq!(
        c.gates[0].check,
        crate::case::gate::Check::Expect {
            kind: crate::integrate::FailureKind::Diverged,
            after: 5.0,
            before: 20.0
        }
    );
    assert!(c.gates[0].quick && c.gates[0].check.metric().is_none());
    assert_eq!(c.gates[0].filter.formulation, ["body"]);
    // Every failure kind's name is accepted.
    for k in crate::integrate::FailureKind::ALL {
        let inner = format!(
            "status = \"failed\", kind = \"{}\", after = 0.0, before = 1.0",
            k.name()
        );
        let c = load_str(LABEL, &expect(&inner, "")).unwrap();
        assert!(
            matches!(c.gates[0].check, crate::case::gate::Check::Expect { kind, .. } if kind == k)
        );
    }
    // One form or the other.
    let e = error_at(&gate("quick = true"), "gates[0]");
    assert!(e.message.contains("`expect`"), "{e}");
    for (extra, key) in [
        ("metric = \"energy_drift_max\"", "gates[0].metric"),
        ("max = 1.0", "gates[0].max"),
        ("min = 1.0", "gates[0].min"),
        ("baseline = 1.0", "gates[0].baseline"),
        ("margin = 2.0", "gates[0].margin"),
    ] {
        let e = error_at(&expect(good, extra), key);
        assert!(e.message.contains("not allowed with `expect`"), "{e}");
    }
    let bad = |inner: &str, key: &str| error_at(&expect(inner, ""), key);
    let e = bad(
        "status = \"ok\", kind = \"diverged\", before = 20.0",
        "gates[0].expect.status",
    );
    assert!(e.message.contains("\"failed\" (the only status"), "{e}");
    bad(
        "kind = \"diverged\", before = 20.0",
        "gates[0].expect.status",
    );
    let e = bad(
        "status = \"failed\", kind = \"exploded\", before = 20.0",
        "gates[0].expect.kind",
    );
    assert!(
        e.message.contains("`exploded`")
            && e.message.contains("singular_chart, non_finite")
            && e.message.contains("diverged or bound_exceeded"),
        "{e}"
    );
    bad("status = \"failed\", before = 20.0", "gates[0].expect.kind");
    for before in ["0.0", "-1.0", "inf", "nan"] {
        bad(
            &format!("status = \"failed\", kind = \"diverged\", before = {before}"),
            "gates[0].expect.before",
        );
    }
    bad(
        "status = \"failed\", kind = \"diverged\"",
        "gates[0].expect.before",
    );
    // `after` is required beside `before`, and lies in [0, before).
    let e = bad(
        "status = \"failed\", kind = \"diverged\", before = 20.0",
        "gates[0].expect.after",
    );
    assert!(e.message.contains("missing"), "{e}");
    for after in ["-1.0", "20.0", "25.0", "inf", "nan"] {
        bad(
            &format!("status = \"failed\", kind = \"diverged\", after = {after}, before = 20.0"),
            "gates[0].expect.after",
        );
    }
    bad(&format!("{good}, late = 1.0"), "gates[0].expect.late");
}

// The inputs hash covers the physics only: ladders, gates, title and sample_every do not
// change it; a stiffness, t_end or initial angle does.
#[test]
fn inputs_hash_covers_physics_only() {
    let hash = |text: &str, scene: usize| {
        let c = load_str(LABEL, text).unwrap();
        inputs_sha256(&c, &c.scenes[scene])
    };
    let h0 = hash(NINE, 1);
    assert_eq!(h0.len(), 64);
    assert!(h0.chars().all(|c| c.is_ascii_hexdigit()));
    assert_eq!(h0, hash(NINE, 1));
    assert_ne!(h0, hash(NINE, 0));
    let same = [
        edited("order2_4 = [2.0e-2,", "order2_4 = [5.0e-2, 2.0e-2,"),
        edited("tol = [1.0e-4,", "tol = [1.0e-3, 1.0e-4,"),
        edited("title = \"Rigid", "title = \"A rigid"),
        edited(
            "1.0]\nt_end = 10.0\nsample_every = 0.01",
            "1.0]\nt_end = 10.0\nsample_every = 0.05",
        ),
        format!("{NINE}\n[[gates]]\nmetric = \"energy_drift_max\"\nmax = 1.0\n"),
        edited("mass = 1000.0                 # kg", "mass = 1000.0"),
    ];
    for t in &same {
        assert_eq!(hash(t, 1), h0, "changed by an edit that is not physics");
    }
    let differ = [
        edited("stiffness = 5.0e3 ", "stiffness = 5.1e3 "),
        edited(
            "1.0]\nt_end = 10.0\n",
            "1.0]\nposition = [0.0, 0.0, 1.0e-3]\nt_end = 10.0\n",
        ),
        edited(
            "euler_xyz = [0.0, 0.5, 1.0]\nt_end = 10.0",
            "euler_xyz = [0.0, 0.5, 1.0]\nt_end = 20.0",
        ),
        edited("euler_xyz = [0.0, 0.5, 1.0]", "euler_xyz = [0.0, 0.5, 1.1]"),
        edited("gravity = 9.81", "gravity = 9.80665"),
    ];
    for t in &differ {
        assert_ne!(hash(t, 1), h0, "not changed by a physics edit");
    }
    // The canonical JSON sorts keys at every level.
    let c = load_str(LABEL, NINE).unwrap();
    let json = canonical_json(&inputs_value(&c, &c.scenes[1]));
    assert!(
        json.starts_with("{\"body\":{\"gravity\":9.81,\"inertia\":"),
        "{json}"
    );
    assert!(json.contains("\"score_every\":0.1,\"springs\":["), "{json}");
}

// load_dir reads the source tree's cases/ exactly as the embedded copy, sorted; a file
// whose case name differs from its stem is rejected.
#[test]
fn load_dir_matches_embedded() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases");
    let from_dir = load_dir(&dir).unwrap();
    let emb = embedded().unwrap();
    assert_eq!(from_dir.len(), emb.len());
    for (a, b) in from_dir.iter().zip(&emb) {
        assert_eq!(a.name, b.name);
        assert_eq!(a.scenes, b.scenes);
        assert!(a.file.ends_with(&format!("{}.toml", a.name)));
    }
    let tmp = std::env::temp_dir().join(format!("mbdbench-case-test-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    std::fs::write(tmp.join("other.toml"), NINE).unwrap();
    let e = load_dir(&tmp).unwrap_err();
    std::fs::remove_dir_all(&tmp).unwrap();
    assert_eq!(e.key, "case");
    assert!(e.to_string().contains("other.toml"), "{e}");
}

/// The adaptive RHS budget is a case key outside the physics hash: a count loads, anything
/// else is refused naming the key.
#[test]
fn adaptive_budget_key() {
    let line = NINE
        .lines()
        .find(|l| l.starts_with("energy_scale"))
        .unwrap();
    let with = |v: &str| edited(line, &format!("{line}\nmax_adaptive_rhs_evals = {v}"));
    let c = load_str(LABEL, &with("2e6")).unwrap();
    assert_eq!(c.max_adaptive_rhs_evals, 2_000_000);
    assert_eq!(c.limits().adaptive().max_rhs_evals, 2_000_000);
    let base = load_str(LABEL, NINE).unwrap();
    assert_eq!(
        inputs_sha256(&c, &c.scenes[0]),
        inputs_sha256(&base, &base.scenes[0])
    );
    for bad in ["-1", "0.5", "\"many\""] {
        error_at(&with(bad), "max_adaptive_rhs_evals");
    }
}

/// A `title` holding a control character (a newline that would forge a heading in
/// summary.md, ESC, a tab) is refused naming the key, the title shown escaped; a plain one
/// with non-ASCII text loads.
#[test]
fn title_without_control_characters() {
    let old = "title = \"Rigid body on nine linear springs";
    for bad in ["x\\n## 0 failed", "\\u001b[31mred", "a\\tb", "\\u009b2J"] {
        let e = error_at(&edited(old, &format!("title = \"{bad}")), "title");
        assert!(e.message.contains("control character"), "{e}");
        assert!(!e.to_string().chars().any(|c| c.is_control()), "{e:?}");
    }
    let ok = load_str(LABEL, &edited(old, "title = \"Brüls — ok")).unwrap();
    assert!(ok.title.starts_with("Brüls — ok"));
}
