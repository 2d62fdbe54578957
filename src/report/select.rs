//! Which variants a plot draws. A scene has up to ~150 variants; one plot with all of them is
//! unreadable, so every plot draws one panel of one of its family's named selections
//! (`problem::figures::Selection`, declared with the family's figures, split into panels by
//! its `Split`) and its caption names it. This file applies a selection and its panels to the
//! report's variant views.
//!
//! Invariants: the panels of a selection partition the variants it admits (each admitted
//! variant is in exactly one panel); a twin that differs from another method only in its
//! summation (`MethodInfo::twin_of`, the Kahan-compensated methods) is admitted by no
//! selection, as the plots here are the short-horizon ones. A family whose declared split
//! leaves more than `MAX_LINES` variants in a panel fails the unit test below, not the report.
use super::data::VariantRuns;
use crate::integrate::MethodKind;
use crate::problem::Family;
use crate::problem::figures::{ParamGroup, Split};

pub use crate::problem::figures::{MAX_LINES, Selection};

/// A selection applied to the report's variants.
pub trait Admits {
    /// Whether a variant is drawn.
    fn admits(&self, v: &VariantRuns) -> bool;
}

/// Whether an integrator is a long-horizon twin of another (left out of every selection).
pub fn is_twin(integrator: &str) -> bool {
    crate::problem::integrator_info(integrator).is_some_and(|i| i.twin_of.is_some())
}

/// The kind of an integrator (explicit for a name no family registers).
pub fn kind_of(integrator: &str) -> MethodKind {
    crate::problem::integrator_info(integrator).map_or(MethodKind::Explicit, |i| i.kind)
}

impl Admits for Selection {
    fn admits(&self, v: &VariantRuns) -> bool {
        self.admit
            .admits(&v.key.param, &v.key.integrator, v.adaptive)
            && !is_twin(&v.key.integrator)
    }
}

/// Which parameterizations a panel draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Params {
    Any,
    In(&'static [&'static str]),
    /// Those in none of the groups.
    NotIn(&'static [ParamGroup]),
}

/// One panel of a selection.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Panel {
    pub sel: Selection,
    /// File-name id (`<selection id>` or `<selection id>_<part>`).
    pub id: String,
    /// Title fragment.
    pub short: String,
    /// The caption sentences naming the lines.
    pub describe: String,
    kind: Option<MethodKind>,
    params: Params,
    formulation: Option<&'static str>,
}

impl Admits for Panel {
    fn admits(&self, v: &VariantRuns) -> bool {
        self.sel.admits(v) && self.admits_key(&v.key.param, &v.key.integrator, &v.key.formulation)
    }
}

impl Panel {
    fn whole(sel: Selection) -> Panel {
        Panel {
            sel,
            id: sel.id.into(),
            short: sel.short.into(),
            describe: sel.describe.into(),
            kind: None,
            params: Params::Any,
            formulation: None,
        }
    }

    fn part(sel: Selection, id: &str, part: &str) -> Panel {
        Panel {
            id: format!("{}_{id}", sel.id),
            short: format!("{}, {part}", sel.short),
            describe: format!(
                "{} This panel: {part}; the selection's other panels draw the rest.",
                sel.describe
            ),
            ..Panel::whole(sel)
        }
    }

    /// Whether the panel's own filter (kind, parameterizations, formulation) passes.
    pub fn admits_key(&self, param: &str, integrator: &str, formulation: &str) -> bool {
        self.kind.is_none_or(|k| kind_of(integrator) == k)
            && self.formulation.is_none_or(|f| f == formulation)
            && match self.params {
                Params::Any => true,
                Params::In(ps) => ps.contains(&param),
                Params::NotIn(gs) => !gs.iter().any(|g| g.params.contains(&param)),
            }
    }
}

/// The panels of a selection in `family`, in report order (some may draw nothing in a given
/// scene; the callers leave those out).
pub fn panels(sel: Selection, family: &Family) -> Vec<Panel> {
    let groups = family.figures.param_groups;
    let by_group = || {
        let mut out: Vec<Panel> = groups
            .iter()
            .map(|g| Panel {
                params: Params::In(g.params),
                ..Panel::part(sel, g.id, g.label)
            })
            .collect();
        out.push(Panel {
            params: Params::NotIn(groups),
            ..Panel::part(sel, "other", "other charts")
        });
        out
    };
    match sel.split {
        Split::Whole => vec![Panel::whole(sel)],
        Split::Kind => MethodKind::ALL
            .iter()
            .map(|&k| Panel {
                kind: Some(k),
                ..Panel::part(sel, k.name(), &format!("{} methods", k.name()))
            })
            .collect(),
        Split::ParamGroup => by_group(),
        Split::ParamGroupFormulation => by_group()
            .into_iter()
            .flat_map(|p| {
                family.axes.formulations.iter().map(move |&f| Panel {
                    id: format!("{}_{f}", p.id),
                    short: format!("{}, {f}", p.short),
                    describe: p.describe.replace(
                        "; the selection's",
                        &format!(", {f} formulation; the selection's"),
                    ),
                    formulation: Some(f),
                    ..p.clone()
                })
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::problem::{FAMILIES, matrix::registered};

    /// Every declared selection's panels hold at most `MAX_LINES` registered variants each
    /// (every scene draws a subset of them), and together they hold each variant the selection
    /// admits exactly once.
    #[test]
    fn panels_partition_and_stay_small() {
        for family in FAMILIES {
            let f = family.figures;
            let sels = f
                .work_precision
                .iter()
                .chain(f.convergence)
                .chain(f.timeseries.iter().map(|(_, s)| s))
                .chain(f.across_scenes.iter().map(|(s, _)| s));
            for &sel in sels {
                let ps = panels(sel, family);
                for v in registered(family) {
                    let admitted = sel.admit.admits(v.param, v.integrator, v.info.adaptive)
                        && !is_twin(v.integrator);
                    let n = ps
                        .iter()
                        .filter(|p| p.admits_key(v.param, v.integrator, v.formulation))
                        .count();
                    if admitted {
                        assert_eq!(n, 1, "{} in {}: {n} panels", v.integrator, sel.id);
                    }
                }
                for p in &ps {
                    let lines = registered(family)
                        .filter(|v| {
                            sel.admit.admits(v.param, v.integrator, v.info.adaptive)
                                && !is_twin(v.integrator)
                                && p.admits_key(v.param, v.integrator, v.formulation)
                        })
                        .count();
                    assert!(
                        lines <= MAX_LINES,
                        "{} panel {}: {lines} lines",
                        family.model,
                        p.id
                    );
                }
            }
        }
    }

    /// The Kahan twins are left out and the kinds come from the integrators' facts.
    #[test]
    fn twins_and_kinds() {
        assert!(is_twin("gauss6_kahan") && is_twin("simo_wong_kahan") && !is_twin("gauss6"));
        assert_eq!(kind_of("rk4"), MethodKind::Explicit);
        assert_eq!(kind_of("gauss6"), MethodKind::Implicit);
        assert_eq!(kind_of("lgvi"), MethodKind::Geometric);
    }
}
