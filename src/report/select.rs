//! Which variants a plot draws. A scene has up to ~150 variants; one plot with all of them is
//! unreadable, so every plot draws one panel of one of its family's named selections
//! (`problem::figures::Selection`, declared with the family's figures, split into panels by
//! its `Split`) and its caption names it. This file applies a selection and its panels to the
//! report's variant views.
//!
//! Invariants: the panels of a selection partition the variants it admits (each admitted
//! variant is in exactly one panel); a twin that differs from another method only in its
//! summation (`MethodInfo::twin_of`, the Kahan-compensated methods) is admitted by no
//! selection, as the plots here are the short-horizon ones. A method's kind and twin are the
//! summary's facts (`Summary::methods`, carried by each `VariantRuns`; the compiled-in
//! catalogue's for a summary written before the table existed), never looked up by name in
//! this build's table. A family whose declared split leaves more than `MAX_LINES` variants in
//! a panel fails the unit test below, not the report.
use super::data::VariantRuns;
use crate::integrate::MethodKind;
use crate::problem::Family;
use crate::problem::figures::{ParamGroup, Split};
use crate::summary::methods::Methods;

pub use crate::problem::figures::{MAX_LINES, Selection};

/// A selection applied to the report's variants.
pub trait Admits {
    /// Whether a variant is drawn.
    fn admits(&self, v: &VariantRuns) -> bool;
}

/// Whether an integrator is, by the facts of `methods` (`catalogue::methods_of` a summary), a
/// long-horizon twin of another (left out of every selection).
pub fn is_twin(methods: &Methods, integrator: &str) -> bool {
    methods.get(integrator).is_some_and(|f| f.twin_of.is_some())
}

/// The kind of an integrator by the facts of `methods` (explicit for a name it lacks: a
/// summary whose table is present has every name, `Summary::check`).
pub fn kind_of(methods: &Methods, integrator: &str) -> MethodKind {
    methods
        .get(integrator)
        .map_or(MethodKind::Explicit, |f| f.kind)
}

impl Admits for Selection {
    fn admits(&self, v: &VariantRuns) -> bool {
        self.admit
            .admits(&v.key.param, &v.key.integrator, v.adaptive)
            && !v.twin
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
        self.sel.admits(v) && self.admits_key(&v.key.param, v.kind, &v.key.formulation)
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

    /// The caption's sentences on what the panel draws: as lines (with what the family's line
    /// styles mean) or as dots (a variant's formulations side by side, in registry order).
    pub fn drawn(&self, family: &Family, dots: bool) -> String {
        if dots {
            format!(
                "Dots: {} A variant's formulations sit side by side, in registry order.",
                self.describe
            )
        } else if self.formulation.is_some() || family.figures.line_styles.is_empty() {
            format!("Lines: {}", self.describe)
        } else {
            format!(
                "Lines: {} Line style: {}.",
                self.describe, family.figures.line_styles
            )
        }
    }

    /// Whether the panel's own filter (the method's kind, parameterizations, formulation)
    /// passes.
    pub fn admits_key(&self, param: &str, kind: MethodKind, formulation: &str) -> bool {
        self.kind.is_none_or(|k| kind == k)
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
        Split::Formulation => family
            .axes
            .formulations
            .iter()
            .map(|&f| Panel {
                formulation: Some(f),
                ..Panel::part(sel, f, &format!("{f} formulation"))
            })
            .collect(),
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

/// A plot cut into plots of at most `MAX_LINES` lines, for plots whose lines are not chosen
/// by a selection (the stability study's, whose variants depend on the run's filter): unchanged
/// when it is small enough; else one plot per integrator kind, and a kind with more lines in
/// consecutive parts of at most `MAX_LINES`, the kinds by the facts of `methods` (the
/// summary's). Ids and titles name the part; each failure mark goes with its variant's line
/// (to the kind's first part when the variant has no line).
pub fn split_crowded(methods: &Methods, p: super::chart::Plot) -> Vec<super::chart::Plot> {
    if p.lines.len() <= MAX_LINES {
        return vec![p];
    }
    let mut out = vec![];
    for kind in MethodKind::ALL {
        let lines: Vec<_> = p
            .lines
            .iter()
            .filter(|l| kind_of(methods, &l.key.integrator) == kind)
            .cloned()
            .collect();
        let fails: Vec<_> = p
            .fails
            .iter()
            .filter(|f| kind_of(methods, &f.key.integrator) == kind)
            .collect();
        if lines.is_empty() && fails.is_empty() {
            continue;
        }
        let chunks: Vec<Vec<_>> = if lines.is_empty() {
            vec![vec![]]
        } else {
            lines.chunks(MAX_LINES).map(<[_]>::to_vec).collect()
        };
        let n = chunks.len();
        for (i, chunk) in chunks.into_iter().enumerate() {
            let part = if n == 1 {
                String::new()
            } else {
                format!("_{}", i + 1)
            };
            let mine = |k: &super::data::VariantKey| chunk.iter().any(|l| &l.key == k);
            let fails = fails
                .iter()
                .filter(|f| mine(&f.key) || (i == 0 && !p.lines.iter().any(|l| l.key == f.key)))
                .map(|f| (*f).clone())
                .collect();
            out.push(super::chart::Plot {
                id: format!("{}_{}{part}", p.id, kind.name()),
                title: if n == 1 {
                    format!("{} ({} methods)", p.title, kind.name())
                } else {
                    format!(
                        "{} ({} methods, part {} of {n})",
                        p.title,
                        kind.name(),
                        i + 1
                    )
                },
                caption: format!(
                    "{} This panel: the {} methods{}; the plots beside it draw the rest.",
                    p.caption,
                    kind.name(),
                    if n == 1 {
                        String::new()
                    } else {
                        format!(", part {} of {n}", i + 1)
                    }
                ),
                lines: chunk,
                fails,
                ..p.clone()
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::catalogue::FAMILIES;
    use crate::problem::matrix::registered;

    /// Every declared selection's panels hold at most `MAX_LINES` registered variants each
    /// (every scene draws a subset of them), and together they hold each variant the selection
    /// admits exactly once.
    #[test]
    fn panels_partition_and_stay_small() {
        for family in FAMILIES {
            for &sel in family.figures.selections() {
                let ps = panels(sel, family);
                for v in registered(family) {
                    let admitted = sel.admit.admits(v.param, v.integrator, v.info.adaptive)
                        && v.info.twin_of.is_none();
                    let n = ps
                        .iter()
                        .filter(|p| p.admits_key(v.param, v.info.kind, v.formulation))
                        .count();
                    if admitted {
                        assert_eq!(n, 1, "{} in {}: {n} panels", v.integrator, sel.id);
                    }
                }
                for p in &ps {
                    let lines = registered(family)
                        .filter(|v| {
                            sel.admit.admits(v.param, v.integrator, v.info.adaptive)
                                && v.info.twin_of.is_none()
                                && p.admits_key(v.param, v.info.kind, v.formulation)
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

    /// A crowded plot is cut into plots of at most `MAX_LINES` lines that together hold
    /// every line once, each with its own id; a small plot is left as it is.
    #[test]
    fn crowded_plots_are_split() {
        use super::super::chart::{Legend, Line, Plot};
        use super::super::data::VariantKey;
        let line = |p: &str, i: &str| Line {
            key: VariantKey {
                param: p.into(),
                integrator: i.into(),
                formulation: "body".into(),
            },
            points: vec![(1.0, 1.0)],
            label: None,
            marker_every: 1,
        };
        let params = crate::catalogue::axis_names(crate::problem::Axis::Param);
        let mut lines: Vec<Line> = params.iter().map(|p| line(p, "rk4")).collect();
        lines.push(line("so3", "lgvi"));
        let p = Plot {
            id: "x".into(),
            title: "t".into(),
            x_label: String::new(),
            y_label: String::new(),
            x: super::super::axes::Scale::Log,
            y: super::super::axes::Scale::Log,
            lines,
            fails: vec![],
            legend: Legend::PerLine,
            caption: String::new(),
            footer: String::new(),
            round_off: None,
        };
        let total = p.lines.len();
        assert!(total > MAX_LINES);
        let methods = crate::catalogue::methods();
        let parts = split_crowded(&methods, p.clone());
        assert!(parts.iter().all(|q| q.lines.len() <= MAX_LINES));
        assert_eq!(parts.iter().map(|q| q.lines.len()).sum::<usize>(), total);
        let mut ids: Vec<&str> = parts.iter().map(|q| q.id.as_str()).collect();
        ids.dedup();
        assert_eq!(ids.len(), parts.len(), "{ids:?}");
        let small = Plot {
            lines: p.lines[..3].to_vec(),
            ..p
        };
        assert_eq!(split_crowded(&methods, small.clone())[0].id, small.id);
    }

    /// The Kahan twins are left out and the kinds come from the integrators' facts.
    #[test]
    fn twins_and_kinds() {
        let m = crate::catalogue::methods();
        assert!(is_twin(&m, "gauss6_kahan") && is_twin(&m, "simo_wong_kahan"));
        assert!(!is_twin(&m, "gauss6"));
        assert_eq!(kind_of(&m, "rk4"), MethodKind::Explicit);
        assert_eq!(kind_of(&m, "gauss6"), MethodKind::Implicit);
        assert_eq!(kind_of(&m, "lgvi"), MethodKind::Geometric);
    }

    /// The report takes a method's kind and twin from the summary's `methods` table, not from
    /// this build's catalogue: an integrator no family registers, stated `implicit` there, is
    /// drawn in the implicit methods' panel of a kind-split selection, its stated twin in
    /// none; and a built-in name restated `geometric` there is drawn as geometric.
    #[test]
    fn the_summary_table_decides_kind_and_twin() {
        use crate::integrate::MethodInfo;
        use crate::summary::methods::MethodFacts;
        use crate::summary::{Record, RunKey, Status};
        let mut table = crate::catalogue::methods();
        let mine = MethodInfo::new("my_method", MethodKind::Implicit, 3).with_implicit(true);
        table.insert("my_method", MethodFacts::of(&mine, "so3"));
        table.insert(
            "my_method_kahan",
            MethodFacts::of(&mine.with_twin_of("my_method"), "so3"),
        );
        let mut rk4 = table.get("rk4").unwrap().clone();
        rk4.kind = MethodKind::Geometric;
        table.insert("rk4", rk4);
        let run = |integrator: &str| {
            let mut r = Record::new(RunKey::new("c", "s", "so3", integrator, "body"), "h");
            r.dt = Some(0.01);
            r.status = Status::Ok;
            r
        };
        let records = ["my_method", "my_method_kahan", "rk4"].map(run).to_vec();
        let mut summary = super::super::fixture::summary_from("c", "t", records, vec![]);
        summary.methods = Some(table);
        assert!(summary.check().is_ok());
        let views = super::super::data::case_views(&summary, &[]);
        let vs = &views[0].scenes[0].variants;
        let family = crate::catalogue::find_family("rigid_body").unwrap();
        let sel = Selection {
            id: "all",
            short: "all",
            describe: "All.",
            admit: crate::problem::figures::Admit::All,
            legend_axes: &[],
            split: Split::Kind,
        };
        let ps = panels(sel, family);
        let panel_of = |name: &str| {
            let v = vs.iter().find(|v| v.key.integrator == name).unwrap();
            ps.iter()
                .filter(|p| p.admits(v))
                .map(|p| p.id.clone())
                .collect::<Vec<_>>()
        };
        assert_eq!(panel_of("my_method"), ["all_implicit"]);
        assert!(panel_of("my_method_kahan").is_empty());
        assert_eq!(panel_of("rk4"), ["all_geometric"]);
        // Without the table (a summary written before it), the catalogue's facts: rk4 is
        // explicit, and the unknown name falls back to explicit.
        summary.methods = None;
        let views = super::super::data::case_views(&summary, &[]);
        let vs = &views[0].scenes[0].variants;
        let rk4 = vs.iter().find(|v| v.key.integrator == "rk4").unwrap();
        assert_eq!(rk4.kind, MethodKind::Explicit);
    }
}
