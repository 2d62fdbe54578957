//! `account`: where a catalogue run's time went, per model family (the summary's
//! `env.families`, `summary::FamilyTime`): the runs each family made, the ladder points it
//! skipped (`skip`), and the CPU seconds of its runs on their worker threads in the results
//! pass and in the timing pass (`cpu_clock`). The main job prints it at its end and
//! `summary.md` shows it, so a reader sees which family the time goes to before adding to it.
//!
//! Invariant: every job of the run is counted once, under its problem's family, in the family
//! table's order (`catalogue::FAMILIES`); a family with no job has no entry.
use super::{Done, Job};
use crate::problem::Problem;
use crate::summary::{FamilyTime, Status};

/// The per-family account of `jobs` and their results `done` (same order).
pub(super) fn by_family(
    problems: &[Box<dyn Problem>],
    jobs: &[Job],
    done: &[Done],
) -> Vec<FamilyTime> {
    let mut out: Vec<FamilyTime> = crate::catalogue::FAMILIES
        .iter()
        .map(|f| FamilyTime {
            family: f.model.to_string(),
            runs: 0,
            skipped: 0,
            results_cpu_s: 0.0,
            timing_cpu_s: 0.0,
        })
        .collect();
    for (job, d) in jobs.iter().zip(done) {
        let model = problems[job.problem].family().model;
        let Some(f) = out.iter_mut().find(|f| f.family == model) else {
            continue;
        };
        if d.record.status == Status::NotApplicable {
            f.skipped += 1;
        } else {
            f.runs += 1;
        }
        f.results_cpu_s += d.results_cpu_s;
        f.timing_cpu_s += d.timing_cpu_s;
    }
    out.retain(|f| f.runs + f.skipped > 0);
    out
}

/// The account as lines of text (the main job's closing lines): one per family, then the
/// total, with each family's share of the CPU seconds.
pub fn lines(families: &[FamilyTime]) -> Vec<String> {
    let total: f64 = families.iter().map(FamilyTime::cpu_s).sum();
    let share = |x: f64| if total > 0.0 { 100.0 * x / total } else { 0.0 };
    let mut out: Vec<String> = families
        .iter()
        .map(|f| {
            format!(
                "  {:<20} {:>6} runs {:>5} skipped {:>8.1} CPU s ({:>4.1} results + {:>5.1} \
                 timing) {:>5.1} %",
                f.family,
                f.runs,
                f.skipped,
                f.cpu_s(),
                f.results_cpu_s,
                f.timing_cpu_s,
                share(f.cpu_s())
            )
        })
        .collect();
    out.push(format!(
        "  {:<20} {:>6} runs {:>5} skipped {:>8.1} CPU s",
        "all",
        families.iter().map(|f| f.runs).sum::<usize>(),
        families.iter().map(|f| f.skipped).sum::<usize>(),
        total
    ));
    out
}
