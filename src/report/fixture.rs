//! Test fixture: a small synthetic summary with known answers (cheapest runs, failures, a cost
//! ratio, n/a records) and its series files, for the report's tests. The numbers are chosen
//! by hand so that each narrative fact has one right answer:
//!
//! - the cheapest run reaching 1e-6 by RHS evaluations is `quat / dopri5 / body` at tol 1e-6
//!   (1500 evaluations), by wall time `so3 / lgvi / body` at dt 1e-2 (4e-4 s);
//! - `euler_zxz / rk4 / body` fails at every step in scene `large` (singular chart);
//! - `euler_zxz / dopri5 / body` costs 10, 8.75 and 20 times `so3 / dopri5 / body`: the
//!   largest ratio is 20 at tol 1e-8 in scene `two_angles`.
use std::path::{Path, PathBuf};

use crate::integrate::{Failure, FailureKind, Stats};
use crate::summary::{Env, FitRecord, Record, Series, Status, Summary, Wall, run_id};

pub const CASE: &str = "nine_spring";
pub const PRIMARY: &str = "rotation_error_max";
pub const SCENES: [&str; 2] = ["two_angles", "large"];

/// (param, integrator, formulation, ladder, errors, rhs evals, wall) of the completed variants.
type Spec = (
    &'static str,
    &'static str,
    &'static str,
    [f64; 3],
    [f64; 3],
    [u64; 3],
    [f64; 3],
);

const DT: [f64; 3] = [2e-2, 1e-2, 5e-3];
const TOL: [f64; 3] = [1e-4, 1e-6, 1e-8];

const OK_RUNS: [Spec; 5] = [
    (
        "so3",
        "rk4",
        "body",
        DT,
        [1.6e-5, 1.0e-6, 6.25e-8],
        [2000, 4000, 8000],
        [1e-3, 2e-3, 4e-3],
    ),
    (
        "so3",
        "rk4",
        "spatial",
        DT,
        [1.76e-5, 1.1e-6, 6.9e-8],
        [2000, 4000, 8000],
        [1.05e-3, 2.1e-3, 4.2e-3],
    ),
    (
        "so3",
        "lgvi",
        "body",
        DT,
        [4e-6, 9.9e-7, 2.5e-7],
        [1000, 2000, 4000],
        [2e-4, 4e-4, 8e-4],
    ),
    (
        "quat",
        "dopri5",
        "body",
        TOL,
        [3e-4, 5e-7, 4e-9],
        [600, 1500, 5000],
        [3e-4, 9e-4, 2.5e-3],
    ),
    (
        "so3",
        "dopri5",
        "body",
        TOL,
        [2e-4, 4e-7, 3e-9],
        [500, 1600, 4800],
        [2.8e-4, 8.5e-4, 2.4e-3],
    ),
];

fn record(
    scene: &str,
    param: &str,
    integ: &str,
    form: &str,
    value: Option<f64>,
    tol: bool,
) -> Record {
    let (dt, tl) = if tol { (None, value) } else { (value, None) };
    let key = crate::summary::RunKey::new(CASE, scene, param, integ, form);
    let mut r = Record::new(key, &"0".repeat(64));
    (r.dt, r.tol) = (dt, tl);
    r
}

fn ok(scene: &str, s: &Spec, i: usize) -> Record {
    let tol = s.1 == "dopri5";
    let mut r = record(scene, s.0, s.1, s.2, Some(s.3[i]), tol);
    r.status = Status::Ok;
    r.metrics.insert(PRIMARY.into(), Some(s.4[i]));
    r.metrics
        .insert("energy_drift_max".into(), Some(s.4[i] * 10.0));
    r.metrics.insert("conditioning_min".into(), Some(1.0));
    r.metrics.insert(
        "constraint_error_max".into(),
        if s.0 == "so3" || s.0 == "quat" {
            Some(1e-15)
        } else {
            None
        },
    );
    r.stats = Stats {
        steps: s.5[i] / 4,
        rhs_evals: s.5[i],
        ..Stats::default()
    };
    r.wall_s = Some(Wall {
        min: s.6[i],
        median: s.6[i] * 1.1,
    });
    let id = run_id(
        &r.key.param,
        &r.key.integrator,
        &r.key.formulation,
        r.dt,
        r.tol,
    );
    r.series = Some(format!("series/{CASE}/{scene}/{id}.json"));
    r
}

/// The synthetic summary.
pub fn summary() -> Summary {
    let mut records = vec![];
    let mut fits = vec![];
    for scene in SCENES {
        for s in &OK_RUNS {
            for i in 0..3 {
                records.push(ok(scene, s, i));
            }
            if s.1 != "dopri5" {
                fits.push(FitRecord {
                    key: crate::summary::RunKey::new(CASE, scene, s.0, s.1, s.2),
                    metric: PRIMARY.into(),
                    order: Some(if s.1 == "rk4" { 4.0 } else { 2.0 }),
                    reason: None,
                    points: vec![],
                });
            }
        }
        // euler_zxz with rk4: fails everywhere in `large`, completes (badly) in `two_angles`.
        for (i, dt) in DT.iter().enumerate() {
            let mut r = record(scene, "euler_zxz", "rk4", "body", Some(*dt), false);
            if scene == "large" {
                r.status = Status::Failed;
                r.failure = Some(Failure::new(
                    FailureKind::SingularChart,
                    0.5 + 0.1 * i as f64,
                    "euler_zxz chart conditioning 0.000e0 <= 1e-12",
                ));
                r.metrics.insert(PRIMARY.into(), None);
                r.metrics.insert("conditioning_min".into(), Some(0.0));
                r.metric_reasons
                    .insert(PRIMARY.into(), "run failed (SingularChart)".into());
                r.stats.rhs_evals = 100 * (i as u64 + 1);
                r.wall_s = Some(Wall {
                    min: 1e-5,
                    median: 1e-5,
                });
            } else {
                r.status = Status::Ok;
                r.metrics
                    .insert(PRIMARY.into(), Some(1e-3 / (i as f64 + 1.0)));
                r.metrics.insert("conditioning_min".into(), Some(1e-3));
                r.stats.rhs_evals = 2000 * (1 << i);
                r.wall_s = Some(Wall {
                    min: 1e-3 * f64::from(1 << i),
                    median: 1e-3,
                });
            }
            records.push(r);
        }
        fits.push(FitRecord {
            key: crate::summary::RunKey::new(CASE, scene, "euler_zxz", "rk4", "body"),
            metric: PRIMARY.into(),
            order: None,
            reason: Some("0 of 3 ladder points lie in range".into()),
            points: vec![],
        });
        // euler_zxz with dopri5 in two_angles: 10, 8.75, 20 x the so3 cost.
        if scene == "two_angles" {
            for (i, (tol, rhs)) in TOL.iter().zip([5000u64, 14000, 96000]).enumerate() {
                let mut r = record(scene, "euler_zxz", "dopri5", "body", Some(*tol), true);
                r.status = Status::Ok;
                r.metrics
                    .insert(PRIMARY.into(), Some(1e-3 / (i as f64 + 1.0)));
                r.metrics.insert("conditioning_min".into(), Some(2e-3));
                r.stats.rhs_evals = rhs;
                r.wall_s = Some(Wall {
                    min: 1e-2,
                    median: 1e-2,
                });
                records.push(r);
            }
        }
        let mut na = record(scene, "quat", "splitting", "body", None, false);
        na.reason = Some("written on SO(3) x R^3 (chart so3) only".into());
        records.push(na);
        let mut na = record(scene, "se3_hq", "rk4", "body", None, false);
        na.reason = Some("the case has no translational degrees of freedom".into());
        records.push(na);
    }
    summary_from("abc1234", "2026-01-02T03:04:05Z", records, fits)
}

/// A summary of `records` and `fits` made at `git_commit` and `created_utc`, with the fixed
/// test environment (2 threads, a release profile, no timing).
pub fn summary_from(
    git_commit: &str,
    created_utc: &str,
    records: Vec<Record>,
    fits: Vec<FitRecord>,
) -> Summary {
    Summary {
        schema: 1,
        git_commit: git_commit.into(),
        created_utc: created_utc.into(),
        env: Env {
            rustc: "rustc 1.95.0".into(),
            cpu: "Test CPU".into(),
            os: "Test OS".into(),
            profile: "release".into(),
            threads: 2,
            timing: None,
            elapsed_s: None,
            families: None,
        },
        records,
        fits,
        selection: None,
        methods: None,
        families: None,
    }
}

/// The page of the synthetic summary alone (no series files, no cases' figures, no advice).
pub fn page() -> crate::report::Page {
    crate::report::build_page(&summary(), Path::new("/nonexistent"), &[], None, None)
}

/// The `<section>` of case `case` in a rendered page.
pub fn case_section<'a>(html: &'a str, case: &str) -> &'a str {
    let start = html
        .find(&format!("<section class=\"case\" data-case=\"{case}\""))
        .expect("case section");
    let end = html[start..].find("</section>").unwrap() + start;
    &html[start..end]
}

/// A fresh temporary directory for one test.
pub fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("mbdbench-report-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Writes a series file for every completed run under `root` (the summary's `series/`
/// directory), except the runs for which `skip` is true.
pub fn write_series(root: &Path, s: &Summary, skip: impl Fn(&Record) -> bool) {
    for r in s
        .records
        .iter()
        .filter(|r| r.status == Status::Ok && !skip(r))
    {
        let n = 11;
        let t: Vec<f64> = (0..n).map(|k| k as f64).collect();
        let scale = r.metrics[PRIMARY].unwrap_or(1e-6);
        let series = Series {
            energy: t.iter().map(|x| 1000.0 + scale * x).collect(),
            constraint: t
                .iter()
                .map(|x| (r.key.param != "euler_zxz").then_some(1e-16 * (1.0 + x)))
                .collect(),
            conditioning: vec![1.0; n],
            primary_error: Some(t.iter().map(|x| scale * x / 10.0).collect()),
            primary_metric: PRIMARY.into(),
            tracks: Default::default(),
            t,
        };
        let id = run_id(
            &r.key.param,
            &r.key.integrator,
            &r.key.formulation,
            r.dt,
            r.tol,
        );
        let p = root
            .join(&r.key.case)
            .join(&r.key.scene)
            .join(format!("{id}.json"));
        crate::reference::write_atomic(&p, serde_json::to_string(&series).unwrap().as_bytes())
            .unwrap();
    }
}
