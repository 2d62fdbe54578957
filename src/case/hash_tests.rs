//! Tests of the two hashes (`case::hash`): every key of every embedded case file is changed
//! on its own, the file reloaded, and the scenes' hashes compared with the original's, so
//! that no key that changes a result can be left out of both hashes, no rival's setting can
//! make a reference stale, and no presentation key can make a record new.
use std::collections::BTreeSet;

use super::*;
use crate::case::embedded_sources;
use crate::catalogue::{FAMILIES, load_str};
use crate::problem::Family;

/// Which hash a key must move.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Class {
    /// Neither (the presentation keys).
    Presentation,
    /// `settings_sha256`, not `inputs_sha256`.
    Setting,
    /// `inputs_sha256` (and, as every non-presentation key, `settings_sha256`).
    Physics,
    /// The file's identity or a permission flag: not mutated (a changed name is another case).
    Identity,
}

/// Keys whose change makes another case, or only widens what the loader accepts.
const IDENTITY: [&str; 4] = ["case", "model", "scene.name", "nonphysical_inertia"];

/// Whether the dotted key `path` lies under one of the dotted `prefixes`.
fn under(path: &str, prefixes: &[&str]) -> bool {
    prefixes
        .iter()
        .any(|p| path == *p || path.starts_with(&format!("{p}.")))
}

/// The class of a key path (array indices dropped) of a file of `family`.
fn class(family: &Family, path: &str) -> Class {
    let top = path.split('.').next().unwrap_or("");
    let scene_key = path
        .strip_prefix("scene.")
        .and_then(|p| p.split('.').next())
        .unwrap_or("");
    if under(path, &IDENTITY) {
        Class::Identity
    } else if (top != "scene" && PRESENTATION_KEYS.contains(&top))
        || (top == "scene" && PRESENTATION_SCENE_KEYS.contains(&scene_key))
    {
        Class::Presentation
    } else if under(path, &SHARED_SETTINGS) || under(path, family.settings) {
        Class::Setting
    } else {
        Class::Physics
    }
}

/// One leaf of the file: its place (for the edit), its dotted path without indices, and
/// the scene it belongs to (None for a case-level key).
struct Leaf {
    place: Vec<Step>,
    path: String,
    scene: Option<usize>,
}

#[derive(Clone)]
enum Step {
    Key(String),
    Index(usize),
}

fn leaves(v: &toml::Value, place: &mut Vec<Step>, path: &str, scene: Option<usize>) -> Vec<Leaf> {
    let mut out = vec![];
    match v {
        toml::Value::Table(t) => {
            for (k, x) in t {
                place.push(Step::Key(k.clone()));
                let p = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                out.extend(leaves(x, place, &p, scene));
                place.pop();
            }
        }
        toml::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                place.push(Step::Index(i));
                let s = if path == "scene" { Some(i) } else { scene };
                out.extend(leaves(x, place, path, s));
                place.pop();
            }
        }
        _ => out.push(Leaf {
            place: place.clone(),
            path: path.to_string(),
            scene,
        }),
    }
    out
}

fn at<'a>(v: &'a mut toml::Value, place: &[Step]) -> &'a mut toml::Value {
    place.iter().fold(v, |v, s| match (s, v) {
        (Step::Key(k), toml::Value::Table(t)) => t.get_mut(k).unwrap(),
        (Step::Index(i), toml::Value::Array(a)) => &mut a[*i],
        _ => unreachable!("a leaf's place walks the value it came from"),
    })
}

/// The changed values to try for a leaf, in order (the first that loads is used).
fn mutations(v: &toml::Value, family: &Family) -> Vec<toml::Value> {
    use toml::Value as V;
    match v {
        V::Float(x) if *x == 0.0 => vec![V::Float(0.125), V::Float(-0.125)],
        V::Float(x) => [1.25, 0.8, 2.0, 0.5, 1.0 + 1e-6]
            .iter()
            .map(|f| V::Float(x * f))
            .collect(),
        V::Integer(i) => vec![V::Integer(i + 1), V::Integer(i - 1), V::Integer(i * 2)],
        V::Boolean(b) => vec![V::Boolean(!b)],
        V::String(s) if s.contains(' ') => vec![V::from(format!("{s} (edited)"))],
        V::String(s) => family
            .metrics
            .iter()
            .map(|m| m.name)
            .chain(["numerical", "exact", "external"])
            .filter(|n| n != s)
            .map(V::from)
            .collect(),
        _ => vec![],
    }
}

/// The hashes of every scene of a case text, or the load error.
fn hashes(label: &str, text: &str) -> Result<Vec<(String, String)>, String> {
    let c = load_str(label, text).map_err(|e| e.to_string())?;
    Ok(c.scenes
        .iter()
        .map(|s| (inputs_sha256(&c, s), s.settings_sha256.clone()))
        .collect())
}

/// The edits to try for a leaf, each a list of (place, new value), in order: the leaf alone;
/// the leaf with every leaf of its scene (or of the case level) that holds the same number
/// (a breakpoint and the torque's end, moved together); the numbers of its array, then of
/// the array around that, scaled together (a symmetric inertia) or rotated (a unit vector).
fn edits(
    original: &toml::Value,
    leaf: &Leaf,
    all: &[Leaf],
    family: &Family,
) -> Vec<Vec<(Vec<Step>, toml::Value)>> {
    let value = at(&mut original.clone(), &leaf.place).clone();
    let mut out: Vec<Vec<(Vec<Step>, toml::Value)>> = mutations(&value, family)
        .into_iter()
        .map(|m| vec![(leaf.place.clone(), m)])
        .collect();
    let number = |v: &toml::Value| v.as_float().or(v.as_integer().map(|i| i as f64));
    if let Some(x) = number(&value) {
        let twins: Vec<&Leaf> = all
            .iter()
            .filter(|l| {
                l.scene == leaf.scene
                    && matches!(class(family, &l.path), Class::Physics | Class::Setting)
                    && number(&at(&mut original.clone(), &l.place).clone()) == Some(x)
            })
            .collect();
        for m in mutations(&value, family) {
            out.push(twins.iter().map(|l| (l.place.clone(), m.clone())).collect());
        }
    }
    for up in 1..=2 {
        // Only arrays: the steps dropped must be indices (a row, then the matrix).
        if leaf.place.len() < up
            || !leaf.place[leaf.place.len() - up..]
                .iter()
                .all(|s| matches!(s, Step::Index(_)))
        {
            break;
        }
        let prefix = &leaf.place[..leaf.place.len() - up];
        let group: Vec<&Leaf> = all
            .iter()
            .filter(|l| l.place.len() > prefix.len() && l.place.starts_with_steps(prefix))
            .collect();
        let values: Vec<Option<f64>> = group
            .iter()
            .map(|l| number(&at(&mut original.clone(), &l.place).clone()))
            .collect();
        if values.iter().any(Option::is_none) {
            continue;
        }
        let values: Vec<f64> = values.into_iter().flatten().collect();
        for f in [1.25, 0.8, 0.99] {
            out.push(
                group
                    .iter()
                    .zip(&values)
                    .map(|(l, x)| (l.place.clone(), toml::Value::Float(x * f)))
                    .collect(),
            );
        }
        out.push(
            group
                .iter()
                .enumerate()
                .map(|(i, l)| {
                    let x = values[(i + 1) % values.len()];
                    (l.place.clone(), toml::Value::Float(x))
                })
                .collect(),
        );
    }
    out
}

/// Whether two places are the same step by step.
trait StartsWith {
    fn starts_with_steps(&self, prefix: &[Step]) -> bool;
}

impl StartsWith for Vec<Step> {
    fn starts_with_steps(&self, prefix: &[Step]) -> bool {
        self.len() >= prefix.len()
            && self.iter().zip(prefix).all(|(a, b)| match (a, b) {
                (Step::Key(x), Step::Key(y)) => x == y,
                (Step::Index(x), Step::Index(y)) => x == y,
                _ => false,
            })
    }
}

/// What a mutation of one leaf did to each scene's two hashes, judged against its class:
/// a violation's text, or None.
fn judge(
    class: Class,
    leaf: &Leaf,
    before: &[(String, String)],
    after: &[(String, String)],
) -> Option<String> {
    let moved: Vec<(bool, bool)> = before
        .iter()
        .zip(after)
        .map(|(b, a)| (b.0 != a.0, b.1 != a.1))
        .collect();
    let any_inputs = moved.iter().any(|m| m.0);
    let any_settings = moved.iter().any(|m| m.1);
    let elsewhere = leaf.scene.is_some_and(|i| {
        moved
            .iter()
            .enumerate()
            .any(|(j, m)| j != i && (m.0 || m.1))
    });
    let bad = match class {
        Class::Presentation => (any_inputs || any_settings).then_some("moved a hash"),
        Class::Setting => {
            if any_inputs {
                Some("moved inputs_sha256 (a setting would make the reference stale)")
            } else if !any_settings {
                Some("moved neither hash")
            } else {
                None
            }
        }
        Class::Physics => (!any_inputs).then_some("did not move inputs_sha256"),
        Class::Identity => None,
    };
    let bad = bad.or(elsewhere.then_some("moved another scene's hash"));
    bad.map(|b| format!("{}: {b}", leaf.path))
}

/// A joint edit: the file, the key it checks, the text replacements.
type Joint = (
    &'static str,
    &'static str,
    &'static [(&'static str, &'static str)],
);

/// Keys that a load-time rule ties to others, so that none can change alone: each is
/// changed together with what the rule ties it to, by text replacements of every
/// occurrence, and judged as the class of `key` over the whole file.
const JOINT: [Joint; 8] = [
    // The protocol's drifts are whole increments of H: H and the increment double together.
    (
        "fiber_column_cyclic.toml",
        "column.height",
        &[
            ("height = 3.0", "height = 6.0"),
            ("increment = 5.0e-4", "increment = 1.0e-3"),
        ],
    ),
    // t_end is the protocol's length in increments.
    (
        "fiber_column_cyclic.toml",
        "scene.load.cycles",
        &[
            ("cycles = 2", "cycles = 1"),
            ("t_end = 5880.0", "t_end = 2940.0"),
        ],
    ),
    (
        "fiber_column_cyclic.toml",
        "scene.load.increment",
        &[
            ("increment = 5.0e-4", "increment = 2.5e-4"),
            ("t_end = 5880.0", "t_end = 11760.0"),
        ],
    ),
    // A material's name is how patches and layers point at it: renamed in both places.
    (
        "fiber_column_cyclic.toml",
        "section.layers.material",
        &[
            ("material = \"steel\"", "material = \"rebar\""),
            ("steel = {", "rebar = {"),
        ],
    ),
    (
        "fiber_column_dynamic.toml",
        "section.layers.material",
        &[
            ("material = \"steel\"", "material = \"rebar\""),
            ("steel = {", "rebar = {"),
        ],
    ),
    (
        "fiber_column_cyclic.toml",
        "section.patches.material",
        &[
            ("material = \"core\"", "material = \"confined\""),
            ("core = {", "confined = {"),
        ],
    ),
    (
        "fiber_column_dynamic.toml",
        "section.patches.material",
        &[
            ("material = \"core\"", "material = \"confined\""),
            ("core = {", "confined = {"),
        ],
    ),
    // Only some coordinate counts are compiled in: one bending mode becomes an axial one.
    (
        "flexible_beam.toml",
        "numerics.cb_bending_modes",
        &[
            ("cb_bending_modes = 8", "cb_bending_modes = 7"),
            ("cb_axial_modes = 1", "cb_axial_modes = 2"),
        ],
    ),
];

/// The keys `JOINT` covers beside its own (each checked there, not alone), and the modal
/// formulations' mode counts, which no edit can change in this build (`modal_linear` takes
/// exactly the compiled coordinate counts): `modal_counts_are_physics` checks them.
const JOINT_COVERS: [(&str, &str); 5] = [
    ("fiber_column_cyclic.toml", "scene.t_end"),
    ("fiber_column_dynamic.toml", "section.patches.material"),
    ("flexible_beam.toml", "numerics.axial_modes"),
    ("flexible_beam.toml", "numerics.cb_axial_modes"),
    ("flexible_beam.toml", "numerics.bending_modes"),
];

/// Keys whose value the loader fixes: each family's scenes admit one reference kind (the
/// beam's are numerical, a static column's exact, a cyclic or dynamic column's external), so
/// no other value loads; the value is a shared setting, in the settings hash by construction.
const FIXED_BY_LOADER: [(&str, &str); 4] = [
    ("fiber_column_cyclic.toml", "reference"),
    ("fiber_column_dynamic.toml", "reference"),
    ("fiber_column_static.toml", "reference"),
    ("flexible_beam.toml", "reference"),
];

/// The beam's mode counts, which no loadable edit can change alone, are in its physics hash
/// as written (its reference's self-convergence tracks depend on them).
#[test]
fn modal_counts_are_physics() {
    let cases = crate::catalogue::embedded().unwrap();
    let c = cases.iter().find(|c| c.model() == "flexible_beam").unwrap();
    let (_, text) = embedded_sources()
        .iter()
        .find(|(l, _)| l.ends_with("flexible_beam.toml"))
        .unwrap();
    let raw: toml::Value = toml::from_str(text).unwrap();
    let n = |k: &str| raw["numerics"][k].as_integer().unwrap();
    let want = serde_json::json!([
        n("bending_modes"),
        n("axial_modes"),
        n("cb_bending_modes"),
        n("cb_axial_modes")
    ]);
    for s in &c.scenes {
        assert_eq!(inputs_value(c, s)["modes"], want, "{}", s.name);
    }
}

/// The joint edits load, and each moves the hash of its key's class (the physics hash for
/// all of them) in every scene it touches.
#[test]
fn joint_edits_move_the_physics_hash() {
    for (file, key, replacements) in JOINT {
        let (label, text) = embedded_sources()
            .iter()
            .find(|(l, _)| l.ends_with(file))
            .unwrap();
        let model = if file.starts_with("fiber") {
            "fiber_column"
        } else {
            "flexible_beam"
        };
        let family = FAMILIES.iter().find(|f| f.model == model).unwrap();
        let mut edited = text.to_string();
        for (a, b) in replacements.iter() {
            assert!(edited.contains(a), "{file}: `{a}` not found");
            edited = edited.replace(a, b);
        }
        let before = hashes(label, text).unwrap();
        let after = hashes(label, &edited).unwrap_or_else(|e| panic!("{file} {key}: {e}"));
        let leaf = Leaf {
            place: vec![],
            path: key.to_string(),
            scene: None,
        };
        assert_eq!(class(family, key), Class::Physics, "{key}");
        assert_eq!(
            judge(Class::Physics, &leaf, &before, &after),
            None,
            "{file} {key}"
        );
    }
}

/// Every key of every embedded case file moves the hash its class says and no other: a
/// presentation key (title, advice, gates, ladders, the stability study's selection, a
/// scene's name and control flag) neither; a setting (shared, or declared by the family)
/// the settings hash only; every other key the physics hash; a scene's key only that
/// scene's hashes. Each key must find a change that still loads, so none goes unchecked.
#[test]
fn every_key_moves_the_right_hash() {
    let mut violations = vec![];
    let mut unchecked = BTreeSet::new();
    let mut checked = 0usize;
    for (label, text) in embedded_sources() {
        let original: toml::Value = toml::from_str(text).unwrap();
        let model = original["model"].as_str().unwrap();
        let family = FAMILIES.iter().find(|f| f.model == model).unwrap();
        let before = hashes(label, text).unwrap();
        let all = leaves(&original, &mut vec![], "", None);
        for leaf in &all {
            let class = class(family, &leaf.path);
            if matches!(class, Class::Identity | Class::Presentation) && leaf.path != "title" {
                // Presentation keys are outside both hashes by construction (`case::hash`);
                // the title stands for them below.
                continue;
            }
            let mut last = String::from("no change to try");
            let mut loaded = None;
            for edit in edits(&original, leaf, &all, family) {
                let mut v = original.clone();
                for (place, x) in edit {
                    *at(&mut v, &place) = x;
                }
                match hashes(label, &toml::to_string(&v).unwrap()) {
                    Ok(h) => {
                        loaded = Some(h);
                        break;
                    }
                    Err(e) => last = e,
                }
            }
            let Some(after) = loaded else {
                let joint = JOINT_COVERS
                    .iter()
                    .copied()
                    .chain(FIXED_BY_LOADER.iter().copied())
                    .chain(JOINT.iter().map(|(f, k, _)| (*f, *k)))
                    .any(|(f, k)| label.ends_with(f) && leaf.path == k);
                if !joint {
                    unchecked.insert(format!("{label}: {} ({last})", leaf.path));
                }
                continue;
            };
            checked += 1;
            violations.extend(judge(class, leaf, &before, &after).map(|v| format!("{label}: {v}")));
        }
    }
    assert!(checked > 300, "only {checked} keys checked");
    assert!(violations.is_empty(), "{}", violations.join("\n"));
    assert!(
        unchecked.is_empty(),
        "keys no change of which loads (cannot be checked):\n{}",
        unchecked.into_iter().collect::<Vec<_>>().join("\n")
    );
}

/// A family whose physics map uses a key the hash adds itself is refused when its cases
/// load, naming the family and the key, so two physics cannot hash alike through an
/// overwritten key.
#[test]
fn a_family_using_a_reserved_key_is_refused() {
    fn overwriting(
        case: &crate::case::Case,
        scene: &crate::case::Scene,
    ) -> serde_json::Map<String, serde_json::Value> {
        let mut m = (crate::model::rigid_body::family::FAMILY.inputs)(case, scene);
        m.insert(
            "case".into(),
            serde_json::Value::from("the family's own physics"),
        );
        m
    }
    let bad: &'static Family = Box::leak(Box::new(Family {
        inputs: overwriting,
        ..crate::model::rigid_body::family::FAMILY
    }));
    let cases = crate::catalogue::embedded().unwrap();
    let mut c = cases
        .iter()
        .find(|c| c.name == "nine_spring")
        .unwrap()
        .clone();
    c.family = bad;
    let e = check_family_inputs(&c).unwrap_err();
    assert_eq!(e.key, "model");
    assert!(
        e.message.contains("reserved key `case`") && e.message.contains("rigid_body"),
        "{e}"
    );
    // Every built-in family passes on every embedded case of its own.
    for c in &cases {
        assert!(FAMILIES.iter().any(|f| f.model == c.family.model()));
        check_family_inputs(c).unwrap();
    }
}

/// The settings hash depends on values, not on how they are written: a float written as an
/// integer, in another exponent form, with comments or reordered keys hashes alike.
#[test]
fn settings_hash_ignores_spelling() {
    let (label, text) = embedded_sources()
        .iter()
        .find(|(l, _)| l.ends_with("fiber_column_cyclic.toml"))
        .unwrap();
    let base = settings_sha256s(label, text).unwrap();
    let respelled = text
        .replace("elements = 1\n", "elements = 1.0 # one element\n")
        .replace("tol = 1.0e-20", "tol = 1e-20");
    assert_ne!(respelled.as_str(), *text);
    assert_eq!(settings_sha256s(label, &respelled).unwrap(), base);
}
