//! Tests of the OpenSees records' comparison with their cases (`opensees_model.rs`), through
//! the library: a case file's text is loaded, its scene compiled, and the stored record of
//! the real references folder attached. The committed cases attach their records; a copy of
//! a case file with one mapped key changed is refused, naming that case key and the record's
//! key it maps to.
use crate::case;
use crate::catalogue::family_of;

/// The catalogue's text of case `name`, without its gates.
fn source(name: &str) -> String {
    let label = format!("cases/{name}.toml");
    let (_, text) = case::embedded_sources()
        .iter()
        .find(|(l, _)| *l == label)
        .expect("embedded");
    case::without_gates(text)
}

/// Loads `text` as case `name`, compiles `scene` and attaches its stored reference.
fn attach(name: &str, text: &str, scene: &str) -> Result<(), String> {
    let c = crate::catalogue::load_str(&format!("cases/{name}.toml"), text).map_err(|e| format!("load: {e}"))?;
    let s = c.scene(scene).expect("scene");
    let mut p = (family_of(&c).compile)(&c, s).map_err(|e| format!("compile: {e}"))?;
    p.attach_reference(&crate::cli::default_references())
}

/// The committed cases' cyclic and pulse scenes attach their OpenSees records: every mapped
/// field of each record is its case's, and its tolerances are no looser than the case's.
#[test]
fn committed_cases_match_their_records() {
    for (name, scene) in [
        ("fiber_column_cyclic", "rc_cyclic_c01"),
        ("fiber_column_cyclic", "rc_cyclic_c02"),
        ("fiber_column_dynamic", "rc_pulse"),
    ] {
        attach(name, &source(name), scene).unwrap_or_else(|e| panic!("{name}/{scene}: {e}"));
    }
}

const CYCLIC: (&str, &str) = ("fiber_column_cyclic", "rc_cyclic_c01");
const DYNAMIC: (&str, &str) = ("fiber_column_dynamic", "rc_pulse");

/// One change of a case file: the case and scene, the edits (each `old` replaced once by
/// `new`; a protocol change also moves `t_end` to its new length), the case key and the
/// record key the refusal must name.
type Change = ((&'static str, &'static str), &'static [(&'static str, &'static str)], &'static str, &'static str);

const CHANGES: &[Change] = &[
    (DYNAMIC, &[("height = 3.0", "height = 3.5")], "column.height", "model.H"),
    (DYNAMIC, &[("axial = 750.0e3", "axial = 700.0e3")], "scene[0].load.axial", "model.P"),
    (
        DYNAMIC,
        &[("axial_steps = 10", "axial_steps = 5")],
        "scene[0].load.axial_steps",
        "model.axial_steps",
    ),
    (
        DYNAMIC,
        &[("mass = 76478.71597334462", "mass = 76000.0")],
        "scene[0].load.pulse.mass",
        "model.mass",
    ),
    (
        DYNAMIC,
        &[("a0 = 0.5928283290934282", "a0 = 0.6")],
        "scene[0].load.pulse.a0",
        "model.damping.a0",
    ),
    (
        DYNAMIC,
        &[("amplitude = 4.903325", "amplitude = 5.0")],
        "scene[0].load.pulse.amplitude",
        "model.ground_motion.amplitude",
    ),
    (
        DYNAMIC,
        &[("period = 0.5", "period = 0.4")],
        "scene[0].load.pulse.period",
        "model.ground_motion.period",
    ),
    (
        DYNAMIC,
        &[("duration = 1.0", "duration = 0.9")],
        "scene[0].load.pulse.duration",
        "model.ground_motion.duration",
    ),
    (DYNAMIC, &[("t_end = 5.0", "t_end = 6.0")], "scene[0].t_end", "model.t_end"),
    (
        CYCLIC,
        &[("fpc = -36.0e6, epsc0 = -0.004, fpcu = -30.0e6", "fpc = -35.0e6, epsc0 = -0.004, fpcu = -30.0e6")],
        "scene[0].materials.core.concrete01.fpc",
        "model.materials.core.args[0]",
    ),
    (
        CYCLIC,
        &[("epsc0 = -0.004, fpcu = -30.0e6", "epsc0 = -0.0035, fpcu = -30.0e6")],
        "scene[0].materials.core.concrete01.epsc0",
        "model.materials.core.args[1]",
    ),
    (
        CYCLIC,
        &[("fy = 420.0e6", "fy = 400.0e6")],
        "scene[0].materials.steel.steel01.fy",
        "model.materials.steel.args[0]",
    ),
    (
        CYCLIC,
        &[("b = 0.01 } } }\nload", "b = 0.02 } } }\nload")],
        "scene[0].materials.steel.steel01.b",
        "model.materials.steel.args[2]",
    ),
    (
        CYCLIC,
        &[(
            "steel01 = { fy = 420.0e6, e0 = 200.0e9, b = 0.01 }",
            "steel02 = { fy = 420.0e6, e0 = 200.0e9, b = 0.01, r0 = 18.0, c_r1 = 0.925, c_r2 = 0.15 }",
        )],
        "scene[0].materials.steel",
        "model.materials.steel.type",
    ),
    (
        CYCLIC,
        &[("y = [-0.21, 0.21], z = [-0.21, 0.21], ny = 16", "y = [-0.2, 0.21], z = [-0.21, 0.21], ny = 16")],
        "section.patches[0].y[0]",
        "model.section.patches[0].y[0]",
    ),
    (
        CYCLIC,
        &[("z = [-0.21, 0.21], ny = 16, nz = 2", "z = [-0.21, 0.21], ny = 8, nz = 2")],
        "section.patches[0].ny",
        "model.section.patches[0].n_depth",
    ),
    (
        CYCLIC,
        &[("y = [0.21, 0.25], z = [-0.25, 0.25]", "y = [0.21, 0.25], z = [-0.24, 0.25]")],
        "section.patches[1].z[0]",
        "model.section.patches[1].z[0]",
    ),
    (
        CYCLIC,
        &[("\"cover_top\", material = \"cover\"", "\"cover_top\", material = \"core\"")],
        "section.patches[1].material",
        "model.section.patches[1].mat",
    ),
    (
        CYCLIC,
        &[("n = 4, area = 4.91e-4 }", "n = 4, area = 5.0e-4 }")],
        "section.layers[0].area",
        "model.section.bars.area",
    ),
    (
        CYCLIC,
        &[("material = \"steel\", y = 0.21,", "material = \"steel\", y = 0.2,")],
        "section.layers[0].y",
        "model.section.bars.rows[0].y",
    ),
    (
        CYCLIC,
        &[("y = 0.21, z = [-0.21, 0.21], n = 4", "y = 0.21, z = [-0.21, 0.21], n = 3")],
        "section.layers[0].n",
        "model.section.bars.rows[0].count",
    ),
    (CYCLIC, &[("depth = 0.5", "depth = 0.6")], "section.depth", "model.section.depth"),
    (CYCLIC, &[("width = 0.5", "width = 0.6")], "section.width", "model.section.width"),
    (CYCLIC, &[("points = 5", "points = 4")], "numerics.points", "model.element.sections"),
    (
        CYCLIC,
        &[("\nelements = 1\n", "\nelements = 2\n")],
        "numerics.elements",
        "model.element.count",
    ),
    (CYCLIC, &[("\ntol = 1.0e-20", "\ntol = 1.0e-22")], "numerics.tol", "settings.tol"),
    (
        CYCLIC,
        &[("element_tol = 1.0e-16", "element_tol = 1.0e-22")],
        "numerics.element_tol",
        "settings.element_tol",
    ),
    (CYCLIC, &[("axial = 750.0e3", "axial = 700.0e3")], "scene[0].load.axial", "model.P"),
    (
        CYCLIC,
        &[("axial_steps = 10", "axial_steps = 5")],
        "scene[0].load.axial_steps",
        "model.axial_steps",
    ),
    (
        CYCLIC,
        &[("drifts = [0.0025, 0.005", "drifts = [0.005, 0.005"), ("t_end = 5880.0", "t_end = 6000.0")],
        "scene[0].load.drifts[0] x 100",
        "model.protocol.drifts_percent[0]",
    ),
    (
        CYCLIC,
        &[("cycles = 2", "cycles = 3"), ("t_end = 5880.0", "t_end = 8820.0")],
        "scene[0].load.cycles",
        "model.protocol.cycles_per_amplitude",
    ),
    (
        CYCLIC,
        &[("increment = 5.0e-4", "increment = 2.5e-4"), ("t_end = 5880.0", "t_end = 11760.0")],
        "scene[0].load.increment",
        "settings.increment",
    ),
    (
        ("fiber_column_cyclic", "rc_cyclic_c02"),
        &[("ft = 3.0e6, ets = 1.5e9 } }, cover", "ft = 2.0e6, ets = 1.5e9 } }, cover")],
        "scene[1].materials.core.concrete02.ft",
        "model.materials.core.args[5]",
    ),
];

/// A one-field change of any mapped case key (geometry, fibers, materials, loading,
/// protocol, pulse, tolerances) on a copy of the case file still loads, but its scene's
/// record is refused as stale, naming the case key and the record's key it maps to.
#[test]
fn a_change_in_any_mapped_key_is_refused_by_name() {
    for ((name, scene), edits, case_key, record_key) in CHANGES {
        let mut text = source(name);
        for (old, new) in *edits {
            assert!(text.contains(old), "{name} lost `{old}`");
            text = text.replacen(old, new, 1);
        }
        let e = match attach(name, &text, scene) {
            Ok(()) => panic!("{name}: {edits:?} was accepted"),
            Err(e) => e,
        };
        assert!(!e.starts_with("load:") && !e.starts_with("compile:"), "{e}");
        assert!(e.contains(&format!("opensees/{scene}.json: ")), "{e}");
        assert!(e.contains(&format!("`{case_key}`")), "{case_key}: {e}");
        assert!(e.contains(&format!("`{record_key}`")), "{record_key}: {e}");
    }
}
