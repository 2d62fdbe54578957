//! The gate's verdict as Markdown: the one renderer of every Markdown account of a gate
//! (`summary.md`, the pull-request comment, and `mbdbench gate --markdown`), so that they
//! cannot disagree with each other or with the terminal's last line.
//!
//! The block: the verdict line `N passed, N failed, N skipped` (the terminal's,
//! `table::verdict_line`), the skipped rows counted by reason, then, when something failed,
//! the failures rolled up by integrator, chart, case and metric (count, and the range of
//! `GateRow::ratio`: value over the bound or the baseline), then the failing rows themselves
//! until the block reaches [`MAX_BYTES`], with the count of the rows left out. Numbers carry 4
//! significant digits. Text read from files (failure messages, names) is kept on one line and
//! cannot open a heading, a table cell or an HTML tag.
//!
//! Where it fails: a verdict of many thousand failing rows lists only the first few hundred
//! rows; the roll-up and the counts are complete.
//!
//! # Example
//!
//! ```
//! use mbdbench::gate::markdown;
//!
//! let md = markdown::verdict(&[]);
//! assert!(md.starts_with("**Gates: 0 passed, 0 failed, 0 skipped.**"));
//! ```
use std::collections::BTreeMap;
use std::fmt::Write;

use super::table::{skipped_by_reason, verdict_line};
use super::{GateRow, Verdict};

/// The most bytes of the block, however many rows fail (a pull-request comment stays
/// readable and within the forges' limits).
pub const MAX_BYTES: usize = 60_000;

/// Roll-up lines shown per dimension (the rest are counted).
const ROLLUP_LINES: usize = 12;

/// `x` with 4 significant digits.
fn sig(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x != 0.0 && !(1e-3..1e5).contains(&x.abs()) {
        return format!("{x:.3e}");
    }
    let digits = if x == 0.0 {
        3
    } else {
        (3 - x.abs().log10().floor() as i32).max(0) as usize
    };
    format!("{x:.digits$}")
}

/// Text on one line, safe inside a table cell and outside code (a `|` escaped, `<`, `>` and
/// `&` as entities, which Markdown renders as the characters).
fn cell(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            c if c.is_control() => out.push(' '),
            '|' => out.push_str("\\|"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '&' => out.push_str("&amp;"),
            '`' => out.push('\''),
            c => out.push(c),
        }
    }
    out
}

/// The part of a row's key a roll-up groups by.
type Part = fn(&GateRow) -> &str;

/// The ratio range of a group of rows: (smallest, largest), None without a ratio.
type Range = Option<(f64, f64)>;

/// The failing rows sharing one part of their key.
struct Group {
    name: String,
    failed: usize,
    range: Range,
}

/// The failing rows grouped by one part of their key, most failures first.
fn group(failing: &[&GateRow], part: Part) -> Vec<Group> {
    let mut by: BTreeMap<&str, (usize, Range)> = BTreeMap::new();
    for r in failing {
        let e = by.entry(part(r)).or_insert((0, None));
        e.0 += 1;
        if let Some(x) = r.ratio.filter(|x| x.is_finite()) {
            e.1 = Some(e.1.map_or((x, x), |(lo, hi)| (lo.min(x), hi.max(x))));
        }
    }
    let mut out: Vec<Group> = by
        .into_iter()
        .map(|(k, (failed, range))| Group {
            name: k.to_string(),
            failed,
            range,
        })
        .collect();
    out.sort_by(|a, b| b.failed.cmp(&a.failed).then_with(|| a.name.cmp(&b.name)));
    out
}

fn rollup(failing: &[&GateRow], s: &mut String) {
    let dims: [(&str, Part); 4] = [
        ("integrator", |r| &r.key.integrator),
        ("chart", |r| &r.key.param),
        ("case", |r| &r.key.case),
        ("metric", |r| &r.metric),
    ];
    s.push_str(
        "\n| failures by | name | failed | ratio to bound or baseline |\n|---|---|---|---|\n",
    );
    for (dim, part) in dims {
        let g = group(failing, part);
        for Group {
            name,
            failed: n,
            range,
        } in g.iter().take(ROLLUP_LINES)
        {
            let range = match range {
                Some((lo, hi)) if lo == hi => format!("x{}", sig(*lo)),
                Some((lo, hi)) => format!("x{} to x{}", sig(*lo), sig(*hi)),
                None => "-".into(),
            };
            let _ = writeln!(s, "| {dim} | {} | {n} | {range} |", cell(name));
        }
        if g.len() > ROLLUP_LINES {
            let rest: usize = g.iter().skip(ROLLUP_LINES).map(|x| x.failed).sum();
            let _ = writeln!(s, "| {dim} | {} more | {rest} | |", g.len() - ROLLUP_LINES);
        }
    }
}

fn row_line(r: &GateRow) -> String {
    let point = match (r.dt, r.tol) {
        (Some(h), _) => format!(" dt={}", sig(h)),
        (None, Some(t)) => format!(" tol={}", sig(t)),
        _ => String::new(),
    };
    let value = match (&r.outcome, r.value) {
        (Some(o), _) => cell(o),
        (None, Some(x)) => sig(x),
        (None, None) => "-".into(),
    };
    format!(
        "| {} | {}/{}/{}/{}{point} | {} | {value} | {} | {} |\n",
        cell(&r.key.case),
        cell(&r.key.scene),
        cell(&r.key.param),
        cell(&r.key.integrator),
        cell(&r.key.formulation),
        cell(&r.metric),
        cell(&r.threshold),
        cell(&r.note)
    )
}

/// The verdict block (module docs), at most [`MAX_BYTES`] bytes.
pub fn verdict(rows: &[GateRow]) -> String {
    let mut s = format!("**Gates: {}.**", verdict_line(rows));
    for (why, k) in skipped_by_reason(rows) {
        let _ = write!(s, " Skipped {k}: {}.", cell(&why));
    }
    s.push('\n');
    let failing: Vec<&GateRow> = rows.iter().filter(|r| r.verdict == Verdict::Fail).collect();
    if failing.is_empty() {
        return s;
    }
    rollup(&failing, &mut s);
    s.push_str(
        "\n| case | variant | metric | value | threshold | why |\n|---|---|---|---|---|---|\n",
    );
    let tail = |left: usize| {
        format!(
            "\n{left} more failing rows not shown (the full table: `mbdbench gate` on the same \
             files).\n"
        )
    };
    for (i, r) in failing.iter().enumerate() {
        let line = row_line(r);
        let left = failing.len() - i;
        if s.len() + line.len() + tail(left).len() > MAX_BYTES {
            s.push_str(&tail(left));
            return s;
        }
        s.push_str(&line);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::summary::RunKey;

    fn row(case: &str, param: &str, ratio: f64, note: &str) -> GateRow {
        GateRow {
            key: RunKey::new(case, "s", param, "rk4", "body"),
            dt: Some(0.01),
            tol: None,
            metric: "rotation_error_max".into(),
            value: Some(1.234567e-6 * ratio),
            outcome: None,
            threshold: "<= 1.234567e-6".into(),
            verdict: if ratio > 1.0 {
                Verdict::Fail
            } else {
                Verdict::Pass
            },
            note: note.into(),
            ratio: Some(ratio),
        }
    }

    /// The block opens with the terminal's verdict line, rolls the failures up by
    /// integrator, chart, case and metric with their counts and ratio ranges (4 significant
    /// digits), and lists the failing rows, never a passing one.
    #[test]
    fn rolls_up_then_lists_the_failures() {
        let rows = vec![
            row("a", "so3", 2.0, "2x the maximum"),
            row("a", "quat", 345.678, "346x"),
            row("b", "so3", 0.5, ""),
        ];
        let md = verdict(&rows);
        assert!(
            md.starts_with("**Gates: 1 passed, 2 failed, 0 skipped.**"),
            "{md}"
        );
        assert!(
            md.contains("| integrator | rk4 | 2 | x2.000 to x345.7 |"),
            "{md}"
        );
        assert!(md.contains("| chart | quat | 1 | x345.7 |"), "{md}");
        assert!(md.contains("| case | a | 2 |"), "{md}");
        assert!(md.contains("| a | s/so3/rk4/body dt=0.01000 | rotation_error_max | 2.469e-6"));
        assert!(!md.contains("| b | s/so3"), "{md}");
    }

    /// However many rows fail, the block stays within `MAX_BYTES` and counts what it left
    /// out; the roll-up still counts every failure; text from files cannot break a cell.
    #[test]
    fn stays_within_its_bytes_when_everything_fails() {
        let rows: Vec<GateRow> = (0..20_000)
            .map(|i| {
                row(
                    &format!("case{}", i % 7),
                    "so3",
                    10.0,
                    "line\n## 0 failed | <b>",
                )
            })
            .collect();
        let md = verdict(&rows);
        assert!(md.len() <= MAX_BYTES, "{}", md.len());
        assert!(md.contains("| case | case0 | 2858 | x10.00 |"), "{md}");
        assert!(md.contains("more failing rows not shown"), "{md}");
        assert!(!md.contains("\n## 0 failed") && !md.contains("<b>"), "{md}");
    }
}
