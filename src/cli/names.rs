//! The valid names of the command line's name options, per model family, from the family
//! table (`catalogue::FAMILIES`) and the embedded case files: the help texts of `--case`,
//! `--param`, `--integrator` and `--formulation` list them, and an unknown name is refused
//! with the valid ones (a new family or integrator shows up here without an edit).
use crate::catalogue::FAMILIES;
use crate::problem::Family;
use crate::selection::VariantFilter;

/// The integrators a family registers, in its table order, without repeats.
fn integrators_of(f: &Family) -> Vec<&'static str> {
    let mut out: Vec<&'static str> = vec![];
    for v in f.variants() {
        if !out.contains(&v.integrator) {
            out.push(v.integrator);
        }
    }
    out
}

/// The names of one axis, per family: `rigid_body: a, b, c; other: d`.
fn per_family(names: impl Fn(&Family) -> Vec<&'static str>) -> String {
    FAMILIES
        .iter()
        .map(|f| format!("{}: {}", f.model, names(f).join(", ")))
        .collect::<Vec<_>>()
        .join("; ")
}

/// The parameterizations per family.
pub fn params() -> String {
    per_family(|f| f.axes.params.to_vec())
}

/// The integrators per family.
pub fn integrators() -> String {
    per_family(integrators_of)
}

/// The formulations per family.
pub fn formulations() -> String {
    per_family(|f| f.axes.formulations.to_vec())
}

/// Help of `--param`.
pub fn param_help() -> String {
    format!(
        "Only these parameterizations (repeatable; default: all). Per model family: {}",
        params()
    )
}

/// Help of `--integrator`.
pub fn integrator_help() -> String {
    format!(
        "Only these integrators (repeatable; default: all). Per model family: {}",
        integrators()
    )
}

/// Help of `--formulation`.
pub fn formulation_help() -> String {
    format!(
        "Only these formulations (repeatable; default: all). Per model family: {}",
        formulations()
    )
}

/// The embedded catalogue's case names.
fn case_names() -> Vec<String> {
    crate::catalogue::embedded()
        .map(|cs| cs.into_iter().map(|c| c.name).collect())
        .unwrap_or_default()
}

/// Help of `--case`.
pub fn case_help() -> String {
    format!(
        "Only these cases (repeatable; default: all). The embedded catalogue: {}",
        case_names().join(", ")
    )
}

/// Help of `--scene`.
pub fn scene_help() -> String {
    let scenes: Vec<String> = crate::catalogue::embedded()
        .map(|cs| {
            cs.iter()
                .map(|c| {
                    let names: Vec<&str> = c.scenes.iter().map(|s| s.name.as_str()).collect();
                    format!("{}: {}", c.name, names.join(", "))
                })
                .collect()
        })
        .unwrap_or_default();
    format!(
        "Only these scenes (repeatable; default: all). The embedded catalogue's: {}",
        scenes.join("; ")
    )
}

/// Bad input when a variant filter names nothing any family registers: each unknown name
/// with the valid names of its axis.
pub fn check_variant_names(
    filter: &VariantFilter,
    catalogue: &crate::catalogue::Catalogue,
) -> Result<(), String> {
    let bad = catalogue.unknown_names(filter);
    if bad.is_empty() {
        return Ok(());
    }
    let mut msg = format!("unknown variant name(s): {}", bad.join(", "));
    let mut valid = |flag: &str, list: String| {
        if bad.iter().any(|b| b.starts_with(flag)) {
            msg.push_str(&format!("\n  valid {flag} names, per model family: {list}"));
        }
    };
    valid("--param", params());
    valid("--integrator", integrators());
    valid("--formulation", formulations());
    Err(msg)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every registered integrator, parameterization and formulation of every family is in
    /// its help text, and an unknown name's error lists the valid ones of its axis only.
    #[test]
    fn help_and_errors_list_the_valid_names() {
        let (p, i, f) = (param_help(), integrator_help(), formulation_help());
        for fam in FAMILIES {
            for v in fam.variants() {
                assert!(i.contains(v.integrator), "{}", v.integrator);
                assert!(p.contains(v.param), "{}", v.param);
                assert!(f.contains(v.formulation), "{}", v.formulation);
            }
        }
        let bad = VariantFilter {
            param: vec![],
            integrator: vec!["rk5".into()],
            formulation: vec![],
        };
        let e = check_variant_names(&bad, &crate::catalogue::Catalogue::builtin()).unwrap_err();
        assert!(e.contains("--integrator rk5"), "{e}");
        assert!(
            e.contains("valid --integrator names") && e.contains("dopri5"),
            "{e}"
        );
        assert!(!e.contains("valid --param"), "{e}");
        assert!(
            check_variant_names(
                &VariantFilter::default(),
                &crate::catalogue::Catalogue::builtin()
            )
            .is_ok()
        );
        assert!(case_help().contains("nine_spring") && scene_help().contains("spin_d0"));
    }
}
