//! The recommendation at the top of the report (`crate::advise`): the page's first screen.
//!
//! On the page (`html`): a table of contents linking every case's section, grouped by family
//! in the family table's order (`catalogue::FAMILIES`, rigid bodies first), then one compact
//! block per case in the same order (`data-rec=<case>`): per offered target, the winner with
//! its step or tolerance per scene, its work and wall time, the runner-up with the cost ratio
//! (or "none" / "not offered" and why), then what to avoid, grouped by reason. Where the
//! family's formulations differ in physics (`problem::figures::PhysicalView`, the flexible
//! beam), the block ranks against the physical reference first and the primary metric's
//! time-error view second. Every number is `advise`'s: this module only lays it out. The
//! blocks sit in a grid that reflows, so the page needs no horizontal scroll at 1280 px.
//!
//! In `summary.md` (`markdown`): rows = target errors (largest first), columns = cases, a
//! cell = the winner, its cost and its runner-up with the cost ratio.
use super::data::num;
use super::html::esc;
use crate::advise::{Advice, Avoid, CaseAdvice, CaseSpec, Pick, Setting, TargetAdvice};
use crate::case::Case;

/// Reasons of the avoid list shown per case on the first screen (the case's section lists
/// every entry).
pub const AVOID_GROUPS: usize = 3;

/// Variants named per avoid reason on the first screen.
pub const AVOID_NAMES: usize = 3;

/// The specs of the cases whose family declares a physical view, with that view's metric,
/// unit and targets in place of the primary metric's; `reference(case, scene)` is what the
/// advice needs of the scene's reference for that metric.
pub fn physical_specs(
    cases: &[Case],
    reference: &dyn Fn(&Case, &str) -> crate::advise::SceneReference,
) -> Vec<CaseSpec> {
    let mut specs = crate::advise::specs(cases, reference);
    specs.retain_mut(|spec| {
        let Some(case) = cases.iter().find(|c| c.name == spec.case) else {
            return false;
        };
        let family = crate::catalogue::family_of(case);
        let Some(view) = family.figures.physical else {
            return false;
        };
        spec.metric = view.metric.to_string();
        spec.unit = family
            .metrics
            .iter()
            .find(|m| m.name == view.metric)
            .map_or("", |m| m.unit)
            .to_string();
        spec.targets = view.targets.to_vec();
        spec.claim_margin = view.claim_margin;
        spec.claim_name = "own error";
        true
    });
    specs
}

/// A ladder value: `dt 1e-2` or `tol 1e-8`.
fn setting_text(s: &Setting) -> String {
    match s {
        Setting::Dt(h) => format!("dt {}", num(*h)),
        Setting::Tol(t) => format!("tol {}", num(*t)),
    }
}

/// A pick's settings, scenes sharing one value named together (`tol 1e-8 on every scene`).
pub fn settings(p: &Pick, scenes: usize) -> String {
    let mut by: Vec<(String, Vec<&str>)> = vec![];
    for (scene, s) in &p.settings {
        let t = setting_text(s);
        match by.iter_mut().find(|(v, _)| *v == t) {
            Some((_, names)) => names.push(scene),
            None => by.push((t, vec![scene])),
        }
    }
    match by.as_slice() {
        [(t, names)] if names.len() == scenes && scenes > 1 => format!("{t} on every scene"),
        [(t, _)] if scenes <= 1 => t.clone(),
        _ => by
            .iter()
            .map(|(t, names)| format!("{t} on {}", names.join(", ")))
            .collect::<Vec<_>>()
            .join("; "),
    }
}

/// A wall time in seconds, in the unit that reads best (`0.42 ms`, `1.52 s`).
pub fn wall(s: f64) -> String {
    if s >= 1.0 {
        format!("{s:.2} s")
    } else if s >= 1e-3 {
        format!("{:.1} ms", s * 1e3)
    } else {
        format!("{:.0} \u{b5}s", s * 1e6)
    }
}

/// One line for consecutive targets with the same answer (`targets`, largest first): the
/// winner with its settings, work and time, the runner-up; "none" or the note when nothing
/// reaches them.
fn target_line(targets: &[f64], t: &TargetAdvice, scenes: usize, unit: &str) -> String {
    let values: Vec<String> = targets.iter().map(|x| num(*x)).collect();
    let target = format!("&le; {}{}", values.join(", "), unit_suffix(unit));
    let Some(w) = &t.winner else {
        return format!(
            "<li class=\"none\"><b>{target}</b> none: {}</li>",
            esc(t
                .note
                .as_deref()
                .unwrap_or("no variant reaches it on every scene"))
        );
    };
    let time = w.wall_s.map_or("not timed".to_string(), wall);
    let mut s = format!(
        "<li><b>{target}</b> {}<b class=\"win\">{}</b> at {}; work {} ({time})",
        if t.tie.is_empty() { "" } else { "tie: " },
        esc(&w.name()),
        esc(&settings(w, scenes)),
        w.cost
    );
    if !t.tie.is_empty() {
        let tied: Vec<String> = t
            .tie
            .iter()
            .map(|p| format!("{} (work {})", esc(&p.name()), p.cost))
            .collect();
        s.push_str(&format!(
            "; tied within {:.0} %: {}",
            crate::advise::TIE_REL * 1e2,
            tied.join(", ")
        ));
    } else if let (Some(r), Some(g)) = (&t.runner_up, t.gap) {
        s.push_str(&format!("; runner-up {} &times;{g:.2}", esc(&r.name())));
    }
    if let Some(b) = t.by_time.as_ref().filter(|b| b.name() != w.name()) {
        s.push_str(&format!("; fastest by wall time {}", esc(&b.name())));
    }
    s.push_str("</li>");
    s
}

fn unit_suffix(unit: &str) -> String {
    if unit.is_empty() || unit == "1" {
        String::new()
    } else {
        format!(" {unit}")
    }
}

/// The reason an avoid entry is grouped under: its text before the first number
/// (`singular_chart`, `energy drift`, `the chart's conditioning fell`).
fn reason_group(reason: &str) -> String {
    let mut words = vec![];
    for w in reason.split(' ') {
        if w.chars().next().is_some_and(|c| c.is_ascii_digit()) {
            break;
        }
        words.push(w);
    }
    while words.last().is_some_and(|w| ["at", "to", "of"].contains(w)) {
        words.pop();
    }
    let g = words.join(" ");
    g.trim_end_matches(':').to_string()
}

/// Who an avoid entry names: the variant, or the chart (`euler_zxz (chart)`).
fn avoid_who(v: &Avoid) -> String {
    match (&v.integrator, &v.formulation) {
        (Some(i), Some(f)) => format!("{}/{i}/{f}", v.param),
        _ => format!("{} (chart)", v.param),
    }
}

/// The avoid list in a few lines: per reason (at most `AVOID_GROUPS`, the most frequent
/// first), how many entries and the first `AVOID_NAMES` variants it names.
fn avoid_summary(list: &[Avoid]) -> String {
    let mut groups: Vec<(String, usize, Vec<String>)> = vec![];
    for v in list {
        let g = reason_group(&v.reason);
        let who = avoid_who(v);
        let at = match groups.iter().position(|(k, _, _)| *k == g) {
            Some(i) => i,
            None => {
                groups.push((g, 0, vec![]));
                groups.len() - 1
            }
        };
        let e = &mut groups[at];
        e.1 += 1;
        if !e.2.contains(&who) {
            e.2.push(who);
        }
    }
    groups.sort_by_key(|g| std::cmp::Reverse(g.1));
    let mut parts = vec![];
    for (g, n, names) in groups.iter().take(AVOID_GROUPS) {
        let more = names.len().saturating_sub(AVOID_NAMES);
        let shown: Vec<&str> = names.iter().take(AVOID_NAMES).map(|s| s.as_str()).collect();
        parts.push(format!(
            "<i>{}</i> ({n}): {}{}",
            esc(g),
            esc(&shown.join(", ")),
            if more > 0 {
                format!(" +{more}")
            } else {
                String::new()
            }
        ));
    }
    if groups.len() > AVOID_GROUPS {
        parts.push(format!("{} more reasons", groups.len() - AVOID_GROUPS));
    }
    parts.join("; ")
}

/// The lines of one ranking (offered targets, then the skipped ones); consecutive targets
/// with the same answer (winner, settings, runner-up, ties: a target the winner's run beats
/// by far) share one line.
fn ranking(c: &CaseAdvice) -> String {
    let mut s = String::from("<ul>\n");
    let same = |a: &TargetAdvice, b: &TargetAdvice| {
        TargetAdvice {
            target: 0.0,
            ..a.clone()
        } == TargetAdvice {
            target: 0.0,
            ..b.clone()
        }
    };
    let mut i = 0;
    while i < c.targets.len() {
        let t = &c.targets[i];
        let mut j = i + 1;
        while j < c.targets.len() && same(t, &c.targets[j]) {
            j += 1;
        }
        let values: Vec<f64> = c.targets[i..j].iter().map(|t| t.target).collect();
        s.push_str(&target_line(&values, t, c.scenes.len(), &c.unit));
        s.push('\n');
        i = j;
    }
    for k in &c.skipped_targets {
        s.push_str(&format!(
            "<li class=\"none\"><b>&le; {}{}</b> not offered: {}</li>\n",
            num(k.target),
            unit_suffix(&c.unit),
            esc(&k.reason)
        ));
    }
    s.push_str("</ul>\n");
    s
}

/// The block of one case: its heading (a link to its section), the physical ranking when the
/// family declares one, the primary metric's ranking, what to avoid.
fn block(c: &CaseAdvice, physical: Option<(&CaseAdvice, &str)>) -> String {
    let mut s = format!(
        "<div class=\"rec\" data-rec=\"{}\">\n<h3><a href=\"#{}\">{}</a></h3>\n",
        esc(&c.case),
        esc(&anchor(&c.case)),
        esc(&c.case)
    );
    let scenes = if c.scenes.is_empty() {
        String::new()
    } else {
        format!("; scenes {}", c.scenes.join(", "))
    };
    if let Some((p, what)) = physical {
        s.push_str(&format!(
            "<p><b>Against the physical reference</b> ({}: {}){}</p>\n",
            esc(&p.metric),
            esc(what),
            esc(&scenes)
        ));
        s.push_str(&ranking(p));
        s.push_str(&format!(
            "<p><b>Time-discretisation error</b> ({}, against each formulation's own \
             converged run)</p>\n",
            esc(&c.metric)
        ));
    } else {
        s.push_str(&format!("<p>{}{}</p>\n", esc(&c.metric), esc(&scenes)));
    }
    s.push_str(&ranking(c));
    if !c.references.is_empty() {
        s.push_str(&format!(
            "<p class=\"refvar\"><b>Reference = a variant</b> (errors are distances to its \
             scheme, not to the exact solution; the scene's section says more): {}</p>\n",
            esc(&reference_short(&c.references))
        ));
    }
    if !c.avoid.is_empty() {
        s.push_str(&format!(
            "<p class=\"avoid\"><b>Avoid</b> {}</p>\n",
            avoid_summary(&c.avoid)
        ));
    }
    s.push_str("</div>\n");
    s
}

/// The references that are variants, one clause per scene: `rc_pulse: OpenSees 3.7.1's
/// newmark/force_based run at 5e-4 s, ours agrees to 1.9e-12`.
fn reference_short(notes: &[crate::advise::reference::ReferenceNote]) -> String {
    notes
        .iter()
        .map(|n| {
            let agrees = n
                .agreement
                .map_or(String::new(), |e| format!(", ours agrees to {}", num(e)));
            format!("{}: {}{agrees}", n.scene, n.reference.label())
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// The recommendation as HTML (a `<section>`): the table of contents over `order` (case,
/// family model name, in page order), then a block per case of `a` in that order (cases of
/// `a` not in `order` after); nothing without cases. `physical` holds the physical rankings.
pub fn html(a: &Advice, physical: Option<&Advice>, order: &[(String, &str)]) -> String {
    if a.cases.is_empty() && order.is_empty() {
        return String::new();
    }
    let mut s = String::from(
        "<section class=\"advice\" data-section=\"advice\" id=\"recommendation\">\n\
         <h2>Recommendation</h2>\n<p>Per case and target error of its metric: the cheapest \
         variant (work = RHS evaluations + Newton iterations) reaching it on every scene that \
         is not a control, at its step (dt) or tolerance (tol) per scene, its median wall \
         time, and the runner-up with its cost ratio; then what to avoid. \
         <code>mbdbench advise</code> prints the same.</p>\n",
    );
    s.push_str(&toc(order));
    s.push_str("<div class=\"recs\">\n");
    let mut shown: Vec<&str> = vec![];
    let ordered = order
        .iter()
        .filter_map(|(name, _)| a.cases.iter().find(|c| &c.case == name));
    let rest = a
        .cases
        .iter()
        .filter(|c| !order.iter().any(|(n, _)| *n == c.case));
    for c in ordered.chain(rest) {
        if shown.contains(&c.case.as_str()) {
            continue;
        }
        shown.push(&c.case);
        let phys = physical
            .and_then(|p| p.cases.iter().find(|x| x.case == c.case))
            .and_then(|p| physical_what(&c.case, order).map(|w| (p, w)));
        s.push_str(&block(c, phys));
    }
    s.push_str("</div>\n</section>\n");
    s
}

/// The physical view's sentence of a case's family (found by the family name in `order`).
fn physical_what(case: &str, order: &[(String, &str)]) -> Option<&'static str> {
    let model = order.iter().find(|(n, _)| n == case)?.1;
    crate::catalogue::FAMILIES
        .iter()
        .find(|f| f.model == model)?
        .figures
        .physical
        .map(|v| v.what)
}

/// The table of contents: per family (in `order`'s order), links to its cases' sections.
fn toc(order: &[(String, &str)]) -> String {
    if order.is_empty() {
        return String::new();
    }
    let mut families: Vec<(&str, Vec<&str>)> = vec![];
    for (case, family) in order {
        match families.iter_mut().find(|(f, _)| f == family) {
            Some((_, cases)) => cases.push(case),
            None => families.push((family, vec![case])),
        }
    }
    let mut s = String::from("<nav class=\"toc\" data-section=\"toc\"><b>Contents</b>");
    for (family, cases) in families {
        let links: Vec<String> = cases
            .iter()
            .map(|c| format!("<a href=\"#{}\">{}</a>", esc(&anchor(c)), esc(c)))
            .collect();
        s.push_str(&format!(
            " <span class=\"fam\">{}: {}</span>",
            esc(family),
            links.join(" ")
        ));
    }
    s.push_str("</nav>\n");
    s
}

/// The target errors of every case, largest first, without repeats.
fn rows(a: &Advice) -> Vec<f64> {
    let mut t: Vec<f64> = a
        .cases
        .iter()
        .flat_map(|c| {
            c.targets
                .iter()
                .map(|t| t.target)
                .chain(c.skipped_targets.iter().map(|s| s.target))
        })
        .collect();
    t.sort_by(|a, b| b.total_cmp(a));
    t.dedup();
    t
}

/// One cell: (the winner, the rest of the line).
fn cell(c: &CaseAdvice, target: f64) -> (String, String) {
    if let Some(t) = c.targets.iter().find(|t| t.target == target) {
        return match &t.winner {
            Some(w) => {
                let runner = match (&t.runner_up, t.gap) {
                    _ if !t.tie.is_empty() => format!(
                        "; tie with {}",
                        t.tie
                            .iter()
                            .map(|p| p.name())
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                    (Some(r), Some(g)) => format!("; runner-up {} x{g:.2}", r.name()),
                    _ => "; no runner-up".into(),
                };
                (w.name(), format!("cost {}{runner}", w.cost))
            }
            None => ("none".into(), "no variant reaches it on every scene".into()),
        };
    }
    if c.skipped_targets.iter().any(|s| s.target == target) {
        return (
            "not offered".into(),
            "below 100x the references' accuracy claim".into(),
        );
    }
    ("-".into(), String::new())
}

/// The anchor of a case's section.
pub fn anchor(case: &str) -> String {
    format!("case-{case}")
}

/// The table as Markdown, or nothing without cases.
pub fn markdown(a: &Advice) -> String {
    use super::markdown::text;
    if a.cases.is_empty() {
        return String::new();
    }
    let mut s = String::from("## Recommendation\n\n| error <= |");
    for c in &a.cases {
        s.push_str(&format!(" {} ({}) |", text(&c.case), text(&c.metric)));
    }
    s.push_str("\n|---|");
    s.push_str(&"---|".repeat(a.cases.len()));
    s.push('\n');
    for t in rows(a) {
        s.push_str(&format!("| {t:e} |"));
        for c in &a.cases {
            let (w, rest) = cell(c, t);
            s.push_str(&format!(" **{}** {} |", text(&w), text(&rest)));
        }
        s.push('\n');
    }
    s.push('\n');
    for c in &a.cases {
        for n in &c.references {
            s.push_str(&format!(
                "> **{}**, reference = a variant: {}\n",
                text(&c.case),
                text(&n.text)
            ));
        }
    }
    if a.cases.iter().any(|c| !c.references.is_empty()) {
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::advise::{Pick, Skipped, TargetAdvice};

    fn pick(p: &str, cost: u64) -> Pick {
        Pick {
            param: p.into(),
            integrator: "rk4".into(),
            formulation: "body".into(),
            settings: Default::default(),
            cost,
            rhs_evals: cost,
            newton_iters: 0,
            wall_s: None,
        }
    }

    fn case(name: &str, targets: Vec<TargetAdvice>, skipped: Vec<Skipped>) -> CaseAdvice {
        CaseAdvice {
            case: name.into(),
            metric: "rotation_error_max".into(),
            unit: "rad".into(),
            scenes: vec!["a".into(), "b".into()],
            controls: vec![],
            targets,
            skipped_targets: skipped,
            avoid: vec![],
            robustness: vec![],
            references: vec![],
        }
    }

    fn target(t: f64, winner: Option<Pick>, runner: Option<Pick>) -> TargetAdvice {
        TargetAdvice {
            target: t,
            gap: runner.as_ref().map(|_| 1.5),
            tie: vec![],
            winner,
            runner_up: runner,
            by_time: None,
            note: None,
        }
    }

    /// The first screen has a block per case in the page's order (families first, whatever the
    /// advice's order), a table of contents linking each case under its family, per target the
    /// winner with its settings per scene, work and time and the runner-up with its ratio,
    /// "none" and "not offered" where they apply, and the avoid list grouped by reason; a case
    /// with a physical ranking shows it before its time-error ranking. The page with it passes
    /// the self-containment check and puts it before the first case; summary.md keeps its
    /// table.
    #[test]
    fn blocks_and_page() {
        let mut so3 = pick("so3", 200);
        so3.settings.insert("a".into(), Setting::Dt(1e-2));
        so3.settings.insert("b".into(), Setting::Dt(1e-2));
        so3.wall_s = Some(0.0123);
        let c = case(
            "c",
            vec![
                target(1e-3, Some(so3.clone()), Some(pick("quat", 300))),
                target(1e-6, None, None),
            ],
            vec![Skipped {
                target: 1e-9,
                reason: "below the claim".into(),
            }],
        );
        let mut beam = case("beam", vec![target(1e-3, Some(so3.clone()), None)], vec![]);
        beam.avoid = (0..4)
            .map(|k| Avoid {
                param: format!("p{k}"),
                integrator: Some("rk4".into()),
                formulation: Some("body".into()),
                scene: "a".into(),
                reason: format!("diverged at {k} of its 4 ladder points"),
            })
            .collect();
        let a = Advice {
            schema: 1,
            by: "work",
            cases: vec![beam.clone(), c.clone()],
        };
        let mut phys = beam.clone();
        phys.metric = "tip_deflection_error_max".into();
        let physical = Advice {
            cases: vec![phys],
            ..a.clone()
        };
        let order = vec![
            ("c".to_string(), "rigid_body"),
            ("beam".to_string(), "flexible_beam"),
        ];
        let h = html(&a, Some(&physical), &order);
        let (bc, bb) = (
            h.find("data-rec=\"c\"").unwrap(),
            h.find("data-rec=\"beam\"").unwrap(),
        );
        assert!(bc < bb, "blocks follow the page's order");
        let toc = &h[h.find("class=\"toc\"").unwrap()..bc];
        assert!(
            toc.contains("rigid_body: <a href=\"#case-c\">c</a>"),
            "{toc}"
        );
        assert!(
            toc.contains("flexible_beam: <a href=\"#case-beam\">beam</a>"),
            "{toc}"
        );
        let block_c = &h[bc..bb];
        assert!(
            block_c.contains(
                "<b>&le; 1e-3 rad</b> <b class=\"win\">so3/rk4/body</b> at dt 1e-2 on every \
                 scene; work 200 (12.3 ms); runner-up quat/rk4/body &times;1.50"
            ),
            "{block_c}"
        );
        assert!(block_c.contains("<b>&le; 1e-6 rad</b> none: no variant reaches it"));
        assert!(block_c.contains("<b>&le; 1e-9 rad</b> not offered: below the claim"));
        let block_b = &h[bb..];
        let p = block_b.find("tip_deflection_error_max").unwrap();
        let t = block_b.find("Time-discretisation error").unwrap();
        assert!(p < t, "the physical ranking comes first");
        assert!(
            block_b.contains("<i>diverged</i> (4): p0/rk4/body, p1/rk4/body, p2/rk4/body +1"),
            "{block_b}"
        );
        let mut page = crate::report::fixture::page();
        page.advice = Some(a.clone());
        let rendered = crate::report::html::render(&page);
        assert_eq!(crate::report::render_check(&rendered), Vec::<String>::new());
        let first_case = rendered.find("<section class=\"case\"").unwrap();
        assert!(rendered.find("data-section=\"advice\"").unwrap() < first_case);
        let md = markdown(&Advice {
            cases: vec![c],
            ..a.clone()
        });
        assert!(md.contains("| 1e-3 | **so3/rk4/body** cost 200; runner-up quat/rk4/body x1.50 |"));
        assert!(html(&Advice { cases: vec![], ..a }, None, &[]).is_empty());
    }

    /// Scenes sharing a setting are named together; different settings list their scenes.
    #[test]
    fn settings_grouped() {
        let mut p = pick("so3", 1);
        p.settings.insert("a".into(), Setting::Tol(1e-8));
        assert_eq!(settings(&p, 1), "tol 1e-8");
        p.settings.insert("b".into(), Setting::Tol(1e-8));
        assert_eq!(settings(&p, 2), "tol 1e-8 on every scene");
        p.settings.insert("c".into(), Setting::Dt(2.5e-3));
        assert_eq!(settings(&p, 3), "tol 1e-8 on a, b; dt 2.5e-3 on c");
        assert_eq!(wall(2.0), "2.00 s");
        assert_eq!(wall(2e-4), "200 \u{b5}s");
    }
}
