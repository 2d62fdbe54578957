//! The catalogue: the family table and what needs all of it. It sits above the families
//! (`model/`) and the seam they implement (`problem/`), so that neither imports the other's
//! table: a family implements [`problem::Family`](crate::problem::Family), the table
//! ([`FAMILIES`], one line per family in `model::families!`) lists them, and everything that
//! dispatches on a family or looks at every family's names comes here:
//! - a case file's loader, dispatching on its `model` key to the family that parses it
//!   ([`load_str`], [`load_dir`], [`embedded`]; `case` holds the shared schema and reading);
//! - the family of a case, of a variant, of a summary's records ([`family_of`],
//!   [`family_of_variant`], [`family_of_case`], [`find_family`]);
//! - the names of each record axis over every family and the report order they define
//!   ([`axis_names`], [`axis_position`], [`variant_order`], [`Ordered`] for the summary's keys
//!   and records);
//! - the facts of every registered method, the table a summary carries ([`methods`]), and
//!   the table a reader of a summary goes by ([`methods_of`]: the summary's, or the
//!   compiled-in one for a summary written before the table existed);
//! - a variant filter's names checked against every family ([`unknown_names`]).
//!
//! Layers (docs/architecture.md, `tests/layers.rs`): `catalogue` imports `model`, `problem`,
//! `case` and `summary`; only the commands above it (`plan`, `suite`, `stability`, `gate`,
//! `report`, `advise`, `cli`) import it.
//!
//! # Example
//!
//! ```
//! let cases = mbdbench::catalogue::embedded().unwrap();
//! let c = cases.iter().find(|c| c.name == "nine_spring").unwrap();
//! let family = mbdbench::catalogue::family_of(c);
//! assert_eq!(family.model, "rigid_body");
//! assert!(family.find("so3", "rk4", "body").is_some());
//! // A case file naming no family is refused by its `model` key.
//! let e = mbdbench::catalogue::load_str("x.toml", "model = \"none\"").unwrap_err();
//! assert_eq!(e.key, "model");
//! ```
use std::path::Path;

mod value;
pub use value::{Catalogue, RegisterError};

use std::borrow::Cow;
use std::collections::BTreeMap;

use crate::case::{self, Case, CaseError};
use crate::problem::{Axes, Axis, Family, Variant};
use crate::selection::VariantFilter;
use crate::summary::methods::{MethodFacts, Methods};
use crate::summary::{Record, RunKey, Summary};

/// Loads one case from its text; `file_label` names it in errors (`cases/<name>.toml`). Every
/// scene's estimate (`problem::Family::estimate`) is checked against the case's budgets
/// (`budget::check`): a case whose run would pass one is refused here, before anything that
/// grows with its numbers exists.
pub fn load_str(file_label: &str, text: &str) -> Result<Case, CaseError> {
    let model = case::model_key(file_label, text)?;
    let Some(family) = find_family(&model) else {
        return Err(CaseError {
            file: file_label.to_string(),
            key: "model".into(),
            message: format!(
                "unknown model `{}`; expected one of {}",
                model,
                FAMILIES
                    .iter()
                    .map(|f| format!("`{}`", f.model))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        });
    };
    let mut case = (family.load)(file_label, text)?;
    case::hash::check_family_inputs(&case)?;
    case::hash::stamp_settings(&mut case, family.model, file_label, text)?;
    for scene in &case.scenes {
        case::budget::check(&case, scene, &(family.estimate)(&case, scene))?;
    }
    Ok(case)
}

/// Loads every `*.toml` of `dir`, sorted by file name; each file's `case` must equal its stem.
/// Each is read as a regular file of at most `read_limited::CASE` bytes.
pub fn load_dir(dir: &Path) -> Result<Vec<Case>, CaseError> {
    let mut cases = vec![];
    for (path, text) in case::read_dir(dir)? {
        let case = load_str(&path.display().to_string(), &text)?;
        case::check_stem(&case, &path)?;
        cases.push(case);
    }
    Ok(cases)
}

/// The catalogue compiled into the binary (`cases/` of the source tree), sorted by name.
pub fn embedded() -> Result<Vec<Case>, CaseError> {
    case::embedded_sources()
        .iter()
        .map(|(label, text)| {
            let case = load_str(label, text)?;
            case::check_stem(&case, Path::new(label))?;
            Ok(case)
        })
        .collect()
}

/// The families, in report order. Adding a family is its folder under `src/model/` plus one
/// line in `model::families!`.
pub use crate::model::FAMILIES;

/// The family a case belongs to (its `model` key, checked when the case was loaded).
pub fn family_of(case: &Case) -> &'static Family {
    find_family(case.model()).unwrap_or(FAMILIES[0])
}

/// The family whose axes name the variant `(param, integrator, formulation)` (the report of a
/// summary whose case file was not given); the first family when none does.
pub fn family_of_variant(param: &str, integrator: &str, formulation: &str) -> &'static Family {
    FAMILIES
        .iter()
        .copied()
        .find(|f| {
            f.axes.params.contains(&param)
                && f.axes.integrators.contains(&integrator)
                && f.axes.formulations.contains(&formulation)
        })
        .unwrap_or(FAMILIES[0])
}

/// The family of a case in a summary: its case file's when given, else the family naming the
/// variant of its first record, else the first family.
pub fn family_of_case<'a>(
    case: Option<&Case>,
    mut records: impl Iterator<Item = &'a Record>,
) -> &'static Family {
    match (case, records.next()) {
        (Some(c), _) => family_of(c),
        (None, Some(r)) => family_of_variant(&r.key.param, &r.key.integrator, &r.key.formulation),
        (None, None) => FAMILIES[0],
    }
}

/// The family with TOML `model` key `model`.
pub fn find_family(model: &str) -> Option<&'static Family> {
    FAMILIES.iter().copied().find(|f| f.model == model)
}

/// The names of one axis over every family: the families in table order, each in its own
/// order, each name once. The report's colours, markers and orders follow it, so a family's
/// names look the same in every plot and a name shared by two families looks the same in both.
pub fn axis_names(axis: Axis) -> &'static [&'static str] {
    use std::sync::OnceLock;
    static NAMES: [OnceLock<Vec<&'static str>>; 3] =
        [OnceLock::new(), OnceLock::new(), OnceLock::new()];
    let (slot, pick): (usize, fn(&Axes) -> &'static [&'static str]) = match axis {
        Axis::Param => (0, |a| a.params),
        Axis::Integrator => (1, |a| a.integrators),
        Axis::Formulation => (2, |a| a.formulations),
    };
    NAMES[slot].get_or_init(|| {
        let mut out: Vec<&'static str> = vec![];
        for f in FAMILIES {
            for n in pick(&f.axes) {
                if !out.contains(n) {
                    out.push(n);
                }
            }
        }
        out
    })
}

/// The facts of every method the families register, by integrator name: the table a summary
/// carries (`Summary::methods`, docs/schemas.md "Methods and families"). The one place that
/// gathers it: a catalogue other than the compiled-in one changes this function only.
///
/// A name registered more than once (on several charts, by several families) has one entry:
/// its facts are those of its first registration in table order, except the facts that depend
/// on the chart (`summary::methods::CHART_FACTS`: RK4 is RKMK4 on a Lie-group chart, Gauss is
/// symplectic on a vector space and not on a group), which hold when any registration has
/// them, with those parameterizations listed (`lie_group_params`, `symplectic_params`). Two
/// registrations of one name that state other facts differently are a bug of the table
/// ([`method_conflicts`], asserted empty by a test); the table keeps the first.
///
/// # Example
///
/// ```
/// use mbdbench::integrate::MethodKind;
///
/// let table = mbdbench::catalogue::methods();
/// let rk4 = table.get("rk4").unwrap();
/// assert_eq!((rk4.kind, rk4.order, rk4.implicit), (MethodKind::Explicit, 4, false));
/// assert!(rk4.lie_group && rk4.lie_group_params.iter().any(|p| p == "so3"));
/// let gauss6 = table.get("gauss6").unwrap();
/// assert!(gauss6.symplectic_params.iter().any(|p| p == "quat"));
/// assert!(!gauss6.symplectic_params.iter().any(|p| p == "so3"));
/// assert_eq!(table.get("gauss6_kahan").unwrap().twin_of.as_deref(), Some("gauss6"));
/// ```
pub fn methods() -> Methods {
    methods_in(FAMILIES)
}

/// The facts of every method `families` register (as [`methods`] for the family table): the
/// table of a run made with a catalogue's families (`Catalogue::families`).
pub fn methods_in(families: &[&'static Family]) -> Methods {
    gather(families.iter().flat_map(|f| f.variants().iter())).0
}

/// The registrations of one name whose facts (the chart-dependent ones aside) differ from its
/// first registration's, one sentence each naming both; empty for a sound table.
pub fn method_conflicts() -> Vec<String> {
    gather(FAMILIES.iter().flat_map(|f| f.variants().iter())).1
}

/// The table of `variants` and the conflicts found building it (see [`methods`]).
fn gather<'a>(variants: impl Iterator<Item = &'a Variant>) -> (Methods, Vec<String>) {
    let mut table = Methods::default();
    let mut first: BTreeMap<&str, (&str, &str)> = BTreeMap::new();
    let mut conflicts = vec![];
    for v in variants {
        let facts = match table.get(v.integrator) {
            None => {
                first.insert(v.integrator, (v.param, v.formulation));
                MethodFacts::of(&v.info, v.param)
            }
            Some(f) => {
                let mut f = f.clone();
                if !f.add(&v.info, v.param) {
                    let (p, form) = first.get(v.integrator).copied().unwrap_or_default();
                    conflicts.push(format!(
                        "{} on {}/{} states other facts than on {p}/{form}",
                        v.integrator, v.param, v.formulation
                    ));
                }
                f
            }
        };
        table.insert(v.integrator, facts);
    }
    (table, conflicts)
}

/// The `model` keys of the families, in table order: the list a summary carries
/// (`Summary::families`).
pub fn family_models() -> Vec<String> {
    FAMILIES.iter().map(|f| f.model.to_string()).collect()
}

/// The method facts a reader of `summary` goes by: the summary's own table when it has one,
/// else (a summary written before the table existed) the compiled-in catalogue's
/// ([`methods`]).
pub fn methods_of(summary: &Summary) -> Cow<'_, Methods> {
    match &summary.methods {
        Some(m) => Cow::Borrowed(m),
        None => Cow::Owned(methods()),
    }
}

/// The place of `name` in [`axis_names`] (`usize::MAX` for a name no family has).
pub fn axis_position(axis: Axis, name: &str) -> usize {
    axis_names(axis)
        .iter()
        .position(|x| *x == name)
        .unwrap_or(usize::MAX)
}

/// A variant's place in the families' axis order: (param, integrator, formulation).
pub fn variant_order(param: &str, integrator: &str, formulation: &str) -> [usize; 3] {
    [
        axis_position(Axis::Param, param),
        axis_position(Axis::Integrator, integrator),
        axis_position(Axis::Formulation, formulation),
    ]
}

/// The names in a variant filter that are not a name of any family's axes (bad input), in
/// the built-in catalogue ([`Catalogue::unknown_names`]).
pub fn unknown_names(filter: &VariantFilter) -> Vec<String> {
    Catalogue::builtin().unknown_names(filter)
}

/// The compiled problems of the selected cases and scenes, each by its case's family (the
/// built-in catalogue's [`Catalogue::problems`]).
pub fn problems(
    cases: &[Case],
    case_filter: &[String],
    scene_filter: &[String],
) -> Result<Vec<Box<dyn crate::problem::Problem>>, String> {
    Catalogue::builtin().problems(cases, case_filter, scene_filter)
}

/// The report order of the summary's keys and records, which needs every family's axis
/// names (so it is here, not in `summary`).
pub trait Ordered {
    /// The variant's place in the families' axis order ([`axis_names`]).
    fn variant_order(&self) -> [usize; 3];
}

impl Ordered for RunKey {
    fn variant_order(&self) -> [usize; 3] {
        variant_order(&self.param, &self.integrator, &self.formulation)
    }
}

impl Ordered for Record {
    fn variant_order(&self) -> [usize; 3] {
        self.key.variant_order()
    }
}

/// The report order of records: case, scene, variant, then coarse steps (loose tolerances)
/// first, so the finest ladder point of a variant is its last record.
pub fn report_order(r: &Record) -> (String, String, [usize; 3], u64, u64) {
    (
        r.key.case.clone(),
        r.key.scene.clone(),
        r.variant_order(),
        r.dt.map_or(0, |x| u64::MAX - x.to_bits()),
        r.tol.map_or(0, |x| u64::MAX - x.to_bits()),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::{MethodInfo, MethodKind};

    /// No two registrations of one integrator name, in any family or on any chart, state
    /// different facts (`lie_group` aside, which the table keeps per parameterization): the
    /// table keyed by name loses nothing.
    #[test]
    fn registrations_of_a_name_agree() {
        assert_eq!(method_conflicts(), Vec::<String>::new());
    }

    /// The table has every registered integrator, with the facts of each of its
    /// registrations, and lists a parameterization under `lie_group_params` (and
    /// `symplectic_params`) exactly when a registration of the method on it runs on a Lie
    /// group (is symplectic), and then every registration on it does: the lists are facts of
    /// the name and the chart.
    #[test]
    fn the_table_holds_every_registration() {
        let table = methods();
        let all: Vec<&Variant> = FAMILIES.iter().flat_map(|f| f.variants().iter()).collect();
        for v in &all {
            let f = table.get(v.integrator).expect("a registered name");
            assert!(f.agrees_with(&v.info), "{}", v.integrator);
            for (fact, params, holds) in [
                ("lie_group", &f.lie_group_params, v.info.lie_group),
                ("symplectic", &f.symplectic_params, v.info.symplectic),
            ] {
                let listed = params.iter().any(|p| p == v.param);
                assert_eq!(listed, holds, "{fact}: {} on {}", v.integrator, v.param);
            }
        }
        let names: std::collections::BTreeSet<&str> = all.iter().map(|v| v.integrator).collect();
        assert_eq!(table.len(), names.len());
        assert!(table.check().is_ok());
        // The chart-dependent fact: rk4 runs as RKMK4 on so3 and as RK4 on the Euler charts.
        let rk4 = table.get("rk4").unwrap();
        assert!(rk4.lie_group_params.iter().any(|p| p == "so3"));
        assert!(!rk4.lie_group_params.iter().any(|p| p == "euler_zyx"));
        assert_eq!(
            family_models().first().map(String::as_str),
            Some(FAMILIES[0].model)
        );
    }

    /// Two registrations of one name with different facts are a conflict naming both; the
    /// table keeps the first one's facts.
    #[test]
    fn a_conflict_is_found_and_the_first_wins() {
        let variant = |param, info| Variant {
            param,
            integrator: "m",
            formulation: "body",
            info,
            index: 0,
            runner: crate::problem::Runner::new(()),
        };
        let explicit = MethodInfo::new("m", MethodKind::Explicit, 2);
        let implicit = explicit.with_implicit(true).with_lie_group(true);
        let vs = [variant("so3", explicit), variant("quat", implicit)];
        let (table, conflicts) = gather(vs.iter());
        let m = table.get("m").unwrap();
        assert!(!m.implicit && m.lie_group_params == ["quat"]);
        assert_eq!(conflicts.len(), 1);
        assert!(
            conflicts[0].contains("m on quat/body") && conflicts[0].contains("so3/body"),
            "{conflicts:?}"
        );
    }
}
