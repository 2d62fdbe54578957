//! The gate's terminal table and exit code: one line per gate row (case, variant, metric,
//! value, threshold, verdict and, for a failure, why), of the baseline rows only the failing
//! ones and a count line, the skipped rows counted by reason, then `N passed, N failed,
//! N skipped` as the last line (every cell on one line: `one_line`). Exit 0 when no row fails (skipped rows do not), 1 when any
//! fails (bad input, exit 2, never gets this far).
use std::io::Write;

use super::{GateRow, Verdict, WORK_METRICS, is_baseline_row};

fn variant(r: &GateRow) -> String {
    let point = match (r.dt, r.tol) {
        (Some(h), _) => format!(" dt={h:e}"),
        (None, Some(t)) => format!(" tol={t:e}"),
        _ => String::new(),
    };
    format!(
        "{}/{}/{}/{}{point}",
        r.key.scene, r.key.param, r.key.integrator, r.key.formulation
    )
}

fn value(r: &GateRow) -> String {
    if let Some(o) = &r.outcome {
        return o.clone();
    }
    match r.value {
        None => "-".into(),
        Some(x) if WORK_METRICS.contains(&r.metric.as_str()) && x.fract() == 0.0 => {
            format!("{x:.0}")
        }
        Some(x) => format!("{x:.3e}"),
    }
}

/// A cell on one line: a control character (a newline or tab in a failure message read from
/// a summary file) becomes a space, so that no text forges a row or the verdict line.
fn one_line(s: String) -> String {
    if s.chars().any(char::is_control) {
        s.replace(char::is_control, " ")
    } else {
        s
    }
}

/// Prints the table; its last line is `N passed, N failed, N skipped` (over all rows,
/// baseline comparisons included).
pub fn print_table(rows: &[GateRow], out: &mut impl Write) -> std::io::Result<()> {
    print_rows(rows, out)?;
    print_tail(rows, out)
}

/// The verdict alone: the failing rows' table (none when every row passes), the skipped
/// rows by reason and the last line (the main job's account of the gate).
pub fn print_verdict(rows: &[GateRow], out: &mut impl Write) -> std::io::Result<()> {
    let failing: Vec<GateRow> = rows
        .iter()
        .filter(|r| r.verdict == Verdict::Fail)
        .cloned()
        .collect();
    print_rows(&failing, out)?;
    print_tail(rows, out)
}

/// The table of the rows shown (every row but the skipped and the passing baseline ones).
fn print_rows(rows: &[GateRow], out: &mut impl Write) -> std::io::Result<()> {
    let shown: Vec<[String; 6]> = rows
        .iter()
        .filter(|r| r.verdict != Verdict::Skip)
        .filter(|r| !is_baseline_row(r) || r.verdict == Verdict::Fail)
        .map(|r| {
            let verdict = match r.verdict {
                Verdict::Pass => "PASS".to_string(),
                Verdict::Fail if r.note.is_empty() => "FAIL".to_string(),
                Verdict::Fail => format!("FAIL  {}", r.note),
                Verdict::Skip => "skip".to_string(),
            };
            [
                r.key.case.clone(),
                variant(r),
                r.metric.clone(),
                value(r),
                r.threshold.clone(),
                verdict,
            ]
            .map(one_line)
        })
        .collect();
    let header = ["case", "variant", "metric", "value", "threshold", "verdict"];
    if !shown.is_empty() {
        let mut w = header.map(str::len);
        for cells in &shown {
            for (k, c) in cells.iter().enumerate() {
                w[k] = w[k].max(c.len());
            }
        }
        let line = |cells: [&str; 6]| {
            format!(
                "{:<a$}  {:<b$}  {:<c$}  {:>d$}  {:<e$}  {}",
                cells[0],
                cells[1],
                cells[2],
                cells[3],
                cells[4],
                cells[5],
                a = w[0],
                b = w[1],
                c = w[2],
                d = w[3],
                e = w[4],
            )
        };
        writeln!(out, "{}", line(header).trim_end())?;
        for cells in &shown {
            writeln!(
                out,
                "{}",
                line(cells.each_ref().map(String::as_str)).trim_end()
            )?;
        }
    }
    Ok(())
}

/// The baseline count, the skipped rows by reason and the verdict line.
fn print_tail(rows: &[GateRow], out: &mut impl Write) -> std::io::Result<()> {
    let baseline: Vec<&GateRow> = rows.iter().filter(|r| is_baseline_row(r)).collect();
    if !baseline.is_empty() {
        let m = baseline
            .iter()
            .filter(|r| r.verdict == Verdict::Fail)
            .count();
        writeln!(
            out,
            "baseline: {} comparisons, {m} regressions",
            baseline.len()
        )?;
    }
    // Skipped rows by reason, one line each (a filtered run skips hundreds).
    for (note, k) in &skipped_by_reason(rows) {
        writeln!(out, "skipped {k}: {}", one_line(note.clone()))?;
    }
    writeln!(out, "{}", verdict_line(rows))
}

/// The skipped rows' reasons with their counts, in first-seen order.
pub fn skipped_by_reason(rows: &[GateRow]) -> Vec<(String, usize)> {
    let mut skipped: Vec<(String, usize)> = vec![];
    for r in rows.iter().filter(|r| r.verdict == Verdict::Skip) {
        match skipped.iter_mut().find(|(n, _)| *n == r.note) {
            Some((_, k)) => *k += 1,
            None => skipped.push((r.note.clone(), 1)),
        }
    }
    skipped
}

/// `N passed, N failed, N skipped`: the gate's last line, and the report's gate summary.
pub fn verdict_line(rows: &[GateRow]) -> String {
    let count = |v: Verdict| rows.iter().filter(|r| r.verdict == v).count();
    format!(
        "{} passed, {} failed, {} skipped",
        count(Verdict::Pass),
        count(Verdict::Fail),
        count(Verdict::Skip)
    )
}

/// 0 when every row passes, 1 when any fails.
pub fn exit_code(rows: &[GateRow]) -> i32 {
    if rows.iter().any(|r| r.verdict == Verdict::Fail) {
        1
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    /// A cell holding a newline, a carriage return or ESC is printed on one line; a plain
    /// cell is unchanged.
    #[test]
    fn cells_stay_on_one_line() {
        assert_eq!(super::one_line("a\nb\r\u{1b}c".into()), "a b  c");
        assert_eq!(super::one_line("plain".into()), "plain");
    }
}
