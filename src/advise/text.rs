//! The recommendation as text, for the terminal (`mbdbench advise`, the end of the main job):
//! per case one line per target (winner, its settings and cost, the runner-up and the gap, or
//! "tie" and every variant within `TIE_REL` of the winner's cost, the wall-time winner or why
//! there is none), after the scenes whose reference is itself one of the variants say so
//! (`reference.rs`), the skipped targets, the robustness ranking
//! (at most `ROBUST_LINES` lines), and the avoid list
//! grouped by reason (at most `AVOID_LINES` lines per case, with the count of the rest).
use std::fmt::Write;

use super::{Advice, CaseAdvice, Pick, Setting, TIE_REL, TargetAdvice};

/// Avoid lines shown per case (the JSON holds them all).
pub const AVOID_LINES: usize = 8;

/// Robustness lines shown per case (the JSON holds them all).
pub const ROBUST_LINES: usize = 6;

fn settings(p: &Pick) -> String {
    p.settings
        .iter()
        .map(|(scene, s)| match s {
            Setting::Dt(dt) => format!("{scene} dt={dt:e}"),
            Setting::Tol(tol) => format!("{scene} tol={tol:e}"),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The variants tied with the winner, each with its ranking cost relative to the winner's
/// (work, or median wall time when `by_time`).
fn tied(t: &TargetAdvice, w: &Pick, by_time: bool) -> String {
    let rank = |p: &Pick| {
        if by_time {
            p.wall_s.unwrap_or(f64::INFINITY)
        } else {
            p.cost as f64
        }
    };
    t.tie
        .iter()
        .map(|p| {
            let r = if rank(w) > 0.0 {
                rank(p) / rank(w)
            } else {
                1.0
            };
            format!("{} (cost {}, x{r:.2})", p.name(), p.cost)
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The recommendation as lines of text.
pub fn render(a: &Advice) -> String {
    let mut out = String::new();
    let cost = if a.by == "time" {
        "median wall time"
    } else {
        "RHS evaluations + Newton iterations"
    };
    let _ = writeln!(
        out,
        "Recommendation (cheapest by {cost}; every non-control scene):"
    );
    for c in &a.cases {
        let _ = writeln!(
            out,
            "\n{} ({} in {}; scenes: {}{})",
            c.case,
            c.metric,
            if c.unit.is_empty() { "-" } else { &c.unit },
            c.scenes.join(", "),
            if c.controls.is_empty() {
                String::new()
            } else {
                format!("; controls left out: {}", c.controls.join(", "))
            }
        );
        for n in &c.references {
            let _ = writeln!(out, "  reference = a variant: {}", n.text);
        }
        for t in &c.targets {
            target_line(&mut out, t, a.by == "time");
        }
        for s in &c.skipped_targets {
            let _ = writeln!(out, "  <= {:e}: not offered: {}", s.target, s.reason);
        }
        robustness_lines(&mut out, c);
        avoid_lines(&mut out, c);
    }
    out
}

/// A target's line: its winner with settings and cost, the tie or runner-up, the wall-time
/// winner (ranked by wall time when `by_time`), or none and why.
fn target_line(out: &mut String, t: &TargetAdvice, by_time: bool) {
    match &t.winner {
        Some(w) => {
            let mut line = format!(
                "  <= {:e}: {}{} (cost {}{}; {})",
                t.target,
                if t.tie.is_empty() { "" } else { "tie: " },
                w.name(),
                w.cost,
                w.wall_s.map_or(String::new(), |s| format!(", {s:.3} s")),
                settings(w)
            );
            if !t.tie.is_empty() {
                let within = TIE_REL * 1e2;
                let _ = write!(line, "; tied within {within:.0} %: {}", tied(t, w, by_time));
            } else if let (Some(r), Some(g)) = (&t.runner_up, t.gap) {
                let _ = write!(line, "; runner-up {} x{g:.2}", r.name());
            }
            if let Some(b) = &t.by_time {
                let _ = write!(line, "; fastest by wall time {}", b.name());
            }
            let _ = writeln!(out, "{line}");
            if let Some(n) = &t.note {
                let _ = writeln!(out, "      ({n})");
            }
        }
        None => {
            let _ = writeln!(
                out,
                "  <= {:e}: none ({})",
                t.target,
                t.note.as_deref().unwrap_or("-")
            );
        }
    }
}

/// The robustness ranking (at most `ROBUST_LINES` lines, then the count of the rest).
fn robustness_lines(out: &mut String, c: &CaseAdvice) {
    if !c.robustness.is_empty() {
        let _ = writeln!(
            out,
            "  at what step (stability study; largest accurate, then stable):"
        );
        let step = |s: &Option<Setting>| match s {
            Some(Setting::Dt(x)) => format!("dt {x:.3e}"),
            Some(Setting::Tol(x)) => format!("tol {x:.3e}"),
            None => "none".into(),
        };
        for r in c.robustness.iter().take(ROBUST_LINES) {
            let _ = writeln!(
                out,
                "    {}/{}/{} on {}: accurate {}, stable {}{}",
                r.param,
                r.integrator,
                r.formulation,
                r.scene,
                if r.accuracy_searched {
                    step(&r.accurate)
                } else {
                    "not searched".into()
                },
                step(&r.stable),
                r.limited_by
                    .as_ref()
                    .map_or(String::new(), |l| format!(" (limited by {l})"))
            );
        }
        if c.robustness.len() > ROBUST_LINES {
            let _ = writeln!(
                out,
                "    ... {} more (advise --json lists them all)",
                c.robustness.len() - ROBUST_LINES
            );
        }
    }
}

/// The avoid list (at most `AVOID_LINES` lines, then the count of the rest).
fn avoid_lines(out: &mut String, c: &CaseAdvice) {
    if !c.avoid.is_empty() {
        let _ = writeln!(out, "  avoid ({}):", c.avoid.len());
        for v in c.avoid.iter().take(AVOID_LINES) {
            let who = match (&v.integrator, &v.formulation) {
                (Some(i), Some(f)) => format!("{}/{i}/{f}", v.param),
                _ => format!("{} (chart)", v.param),
            };
            let _ = writeln!(out, "    {who} on {}: {}", v.scene, v.reason);
        }
        if c.avoid.len() > AVOID_LINES {
            let _ = writeln!(
                out,
                "    ... {} more (advise --json lists them all)",
                c.avoid.len() - AVOID_LINES
            );
        }
    }
}
