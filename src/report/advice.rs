//! The recommendation at the top of the report (`crate::advise`): one table, rows = target
//! errors (largest first), columns = cases (each heading a link to the case's section), a
//! cell = the cheapest variant reaching the target on every non-control scene, its cost and
//! its runner-up with the cost ratio; "not offered" where the target is below 100x the
//! references' accuracy claims, "none" where no variant reaches it. The same table in
//! `summary.md`, without links.
use super::html::esc;
use crate::advise::{Advice, CaseAdvice};

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

/// The table as HTML (a `<section>`), or nothing without cases.
pub fn html(a: &Advice) -> String {
    if a.cases.is_empty() {
        return String::new();
    }
    let mut s = String::from(
        "<section class=\"advice\" data-section=\"advice\">\n<h2>Recommendation</h2>\n<p>The \
         cheapest variant (RHS evaluations + Newton iterations) reaching each error in the \
         case's primary metric on every scene that is not a control; its runner-up and the \
         cost ratio. <code>mbdbench advise</code> prints it with the step per scene and what \
         to avoid.</p>\n<table class=\"advice\">\n<tr><th>error &le;</th>",
    );
    for c in &a.cases {
        s.push_str(&format!(
            "<th><a href=\"#{}\">{}</a><br><small>{}</small></th>",
            esc(&anchor(&c.case)),
            esc(&c.case),
            esc(&c.metric)
        ));
    }
    s.push_str("</tr>\n");
    for t in rows(a) {
        s.push_str(&format!("<tr><th>{t:e}</th>"));
        for c in &a.cases {
            let (w, rest) = cell(c, t);
            s.push_str(&format!(
                "<td><b>{}</b><br><small>{}</small></td>",
                esc(&w),
                esc(&rest)
            ));
        }
        s.push_str("</tr>\n");
    }
    s.push_str("</table>\n</section>\n");
    s
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

    /// The table has a row per target (largest first), a column per case linking to its
    /// section, the winner with cost and runner-up, "none" and "not offered" where they
    /// apply; the page with it passes the self-containment check (in-page links only) and
    /// puts it before the first case; summary.md holds the same cells.
    #[test]
    fn table_and_page() {
        let a = Advice {
            schema: 1,
            by: "work",
            cases: vec![CaseAdvice {
                case: "c".into(),
                metric: "rotation_error_max".into(),
                unit: "rad".into(),
                scenes: vec!["a".into()],
                controls: vec![],
                targets: vec![
                    TargetAdvice {
                        target: 1e-6,
                        winner: None,
                        runner_up: None,
                        gap: None,
                        tie: vec![],
                        by_time: None,
                        note: None,
                    },
                    TargetAdvice {
                        target: 1e-3,
                        winner: Some(pick("so3", 200)),
                        runner_up: Some(pick("quat", 300)),
                        gap: Some(1.5),
                        tie: vec![],
                        by_time: None,
                        note: None,
                    },
                ],
                skipped_targets: vec![Skipped {
                    target: 1e-9,
                    reason: "-".into(),
                }],
                avoid: vec![],
                robustness: vec![],
            }],
        };
        let h = html(&a);
        let r3 = h.find("<th>1e-3</th>").unwrap();
        let r6 = h.find("<th>1e-6</th>").unwrap();
        let r9 = h.find("<th>1e-9</th>").unwrap();
        assert!(r3 < r6 && r6 < r9);
        assert!(h.contains("<a href=\"#case-c\">c</a>"));
        assert!(
            h.contains("<b>so3/rk4/body</b><br><small>cost 200; runner-up quat/rk4/body x1.50")
        );
        assert!(h[r6..r9].contains("<b>none</b>") && h[r9..].contains("not offered"));
        let mut page = crate::report::build_page(
            &crate::report::fixture::summary(),
            std::path::Path::new("/nonexistent"),
            &[],
            None,
            None,
        );
        page.advice = Some(a.clone());
        let p = crate::report::html::render(&page);
        assert_eq!(crate::report::render_check(&p), Vec::<String>::new());
        let first_case = p.find("<section class=\"case\"").unwrap();
        assert!(p.find("data-section=\"advice\"").unwrap() < first_case);
        let md = markdown(&a);
        assert!(md.contains("| 1e-3 | **so3/rk4/body** cost 200; runner-up quat/rk4/body x1.50 |"));
        assert!(html(&Advice { cases: vec![], ..a }).is_empty());
    }
}
