//! `summary.md`: the report's answer for a CI log or a pull-request comment
//! (GitHub-flavoured Markdown, kept well under a comment's 65,536 characters): the
//! environment line, the gate verdict (the gate's own last line, the skipped rows' reasons,
//! the failing rows), the recommendation, and one line per case (scenes, variants, runs,
//! typed failures by kind, its gates) pointing to its section of `index.html`, which holds
//! every table and plot. Long tables fold in `<details>` blocks; a shortened cell is written
//! in full; gate colours become `[pass]` / `[FAIL]` after the value.
use super::Page;
use super::tables::{Table, Tone};

/// Makes text inert for a Markdown renderer, as `index.html` escapes it: a `<` that would open
/// a tag, a comment, a declaration or an autolink (followed by a letter, `/`, `!` or `?`) and an
/// `&` that would start an entity (followed by a letter or `#`) are written as entities; every
/// control character (a newline, a carriage return, ESC) becomes a space, so that text from a
/// case or summary file stays on its line and cannot start one (a name holding
/// `"\n## 0 failed"` would otherwise be a heading); the rest (`<=`, `a & b`) stays as it reads.
pub(super) fn text(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut it = s.chars().peekable();
    while let Some(c) = it.next() {
        let next = it.peek().copied();
        match c {
            '<' if next.is_some_and(|n| n.is_ascii_alphabetic() || "/!?".contains(n)) => {
                out.push_str("&lt;")
            }
            '&' if next.is_some_and(|n| n.is_ascii_alphabetic() || n == '#') => {
                out.push_str("&amp;")
            }
            c if c.is_control() => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// Escapes a table cell: inert text (`text`, newlines folded to spaces) and pipes.
fn cell(s: &str) -> String {
    text(s).replace('|', "\\|")
}

/// Renders a table (folded when longer than `open_below` rows).
pub fn table(t: &Table, open_below: usize) -> String {
    let mut s = format!("#### {}\n\n{}\n\n", text(&t.title), text(&t.note));
    if t.rows.is_empty() {
        s.push_str("_no rows_\n\n");
        return s;
    }
    let fold = t.rows.len() > open_below;
    if fold {
        s.push_str(&format!(
            "<details><summary>{} rows</summary>\n\n",
            t.rows.len()
        ));
    }
    s.push_str(&format!(
        "| {} |\n",
        t.header
            .iter()
            .map(|h| cell(h))
            .collect::<Vec<_>>()
            .join(" | ")
    ));
    s.push_str(&format!("|{}\n", "---|".repeat(t.header.len())));
    for row in &t.rows {
        let cells: Vec<String> = row
            .iter()
            .map(|c| {
                let mark = match c.tone {
                    Tone::Pass => " [pass]",
                    Tone::Fail => " [FAIL]",
                    Tone::Plain | Tone::Neutral => "",
                };
                // A shortened cell is written in full (no hover text in a CI log).
                let text = c.full.as_deref().unwrap_or(&c.text);
                // The gate table's verdict column already says pass/FAIL.
                if !mark.is_empty() && (text == "pass" || text == "FAIL") {
                    cell(text)
                } else {
                    format!("{}{mark}", cell(text))
                }
            })
            .collect();
        s.push_str(&format!("| {} |\n", cells.join(" | ")));
    }
    s.push('\n');
    if fold {
        s.push_str("</details>\n\n");
    }
    s
}

/// The whole document: the environment, the gate verdict (`gate::markdown`: the roll-up and
/// the failing rows), the recommendation, and one line per case pointing to its section of `index.html`.
pub fn render(page: &Page) -> String {
    // The environment comes from the summary (a hand-edited one too): kept on its line and
    // inside its code span.
    let env = page
        .env_line
        .replace(|c: char| c.is_control() || c == '`', " ");
    let mut s = format!("# mbdbench report\n\n`{env}`\n\n");
    if let Some(g) = &page.gate_summary {
        s.push_str(&g.markdown);
        s.push('\n');
    }
    if let Some(a) = &page.advice {
        s.push_str(&super::advice::markdown(a));
    }
    s.push_str("## Cases\n\n");
    if page.cases.is_empty() {
        s.push_str("No cases (no data).\n");
    }
    for c in &page.cases {
        s.push_str(&format!("- **{}**", text(&c.name)));
        if !c.title.is_empty() {
            s.push_str(&format!(" ({})", text(&c.title)));
        }
        s.push_str(&format!(
            ": {}. Plots and tables: `index.html#{}`.\n",
            text(&c.line),
            text(&super::advice::anchor(&c.name))
        ));
    }
    if let Some((families, elapsed)) = &page.time {
        s.push_str(&time_section(families, *elapsed));
    }
    s.push_str(
        "\nThe plots, every table (the variants x metrics matrices, failures, largest steps, \
         n/a) and the stability study are in `index.html` beside this file.\n",
    );
    s
}

/// The run's time per family (`env.families`): runs, skipped ladder points, CPU seconds in
/// the results and timing passes, and each family's share.
fn time_section(families: &[crate::summary::FamilyTime], elapsed: Option<f64>) -> String {
    let total: f64 = families.iter().map(|f| f.cpu_s()).sum();
    let mut s = format!(
        "\n## Time per family\n\nThe run took {} on its workers: {total:.1} CPU s in all, \
         by family (CPU seconds of the runs on their worker threads; skipped: ladder points \
         not run, `n/a` with the reason).\n\n| family | runs | skipped | CPU s | results | \
         timing | share |\n|---|---:|---:|---:|---:|---:|---:|\n",
        elapsed.map_or("an unrecorded time".into(), |t| format!("{t:.0} s wall"))
    );
    for f in families {
        s.push_str(&format!(
            "| {} | {} | {} | {:.1} | {:.1} | {:.1} | {:.1} % |\n",
            cell(&f.family),
            f.runs,
            f.skipped,
            f.cpu_s(),
            f.results_cpu_s,
            f.timing_cpu_s,
            if total > 0.0 {
                100.0 * f.cpu_s() / total
            } else {
                0.0
            }
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::tables::Cell;

    /// Text is inert for a Markdown renderer: tags, comments, declarations and entities are
    /// escaped, control characters (a newline that would start a heading) become spaces,
    /// comparisons and lone ampersands read as written.
    #[test]
    fn text_is_inert() {
        assert_eq!(text("<img src=x>"), "&lt;img src=x>");
        assert_eq!(text("</b><!-- x --><?p"), "&lt;/b>&lt;!-- x -->&lt;?p");
        assert_eq!(text("&amp; &#60;"), "&amp;amp; &amp;#60;");
        assert_eq!(
            text("error <= 1e-6 & drift < 2"),
            "error <= 1e-6 & drift < 2"
        );
        assert_eq!(cell("a|<i>"), "a\\|&lt;i>");
        assert_eq!(text("t\n## 0 failed\r\u{1b}[2J"), "t ## 0 failed  [2J");
    }

    /// Cells escape pipes, gated cells carry their verdict, long tables fold.
    #[test]
    fn table_format() {
        let t = Table {
            kind: "matrix",
            title: "T".into(),
            note: "n".into(),
            header: vec!["a".into(), "b".into()],
            rows: vec![vec![
                Cell::plain("x|y"),
                Cell {
                    text: "1e-9".into(),
                    tone: Tone::Fail,
                    full: None,
                },
            ]],
        };
        let s = table(&t, 5);
        assert!(s.contains("| x\\|y | 1e-9 [FAIL] |"), "{s}");
        assert!(s.contains("|---|---|"));
        assert!(!s.contains("<details>"));
        assert!(table(&t, 0).contains("<details><summary>1 rows</summary>"));
    }

    /// The time section lists every family of the account with its runs, skipped points and
    /// CPU seconds, and shares that add up to 100 %.
    #[test]
    fn time_section_lists_every_family() {
        let f = |family: &str, runs, skipped, r, t| crate::summary::FamilyTime {
            family: family.into(),
            runs,
            skipped,
            results_cpu_s: r,
            timing_cpu_s: t,
        };
        let s = time_section(
            &[
                f("rigid_body", 10, 2, 30.0, 45.0),
                f("fiber_column", 3, 0, 5.0, 20.0),
            ],
            Some(61.4),
        );
        assert!(
            s.contains("61 s wall") && s.contains("100.0 CPU s in all"),
            "{s}"
        );
        assert!(
            s.contains("| rigid_body | 10 | 2 | 75.0 | 30.0 | 45.0 | 75.0 % |"),
            "{s}"
        );
        assert!(
            s.contains("| fiber_column | 3 | 0 | 25.0 | 5.0 | 20.0 | 25.0 % |"),
            "{s}"
        );
    }
}
