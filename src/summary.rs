//! `summary.json` (docs/schemas.md, "summary.json"; its fields are a contract): one record per run
//! with its metrics, work counters and timing, the order fits, and the environment that produced
//! them; plus the per-run series files. Written atomically. Also the build/environment facts
//! (`Env`) and a UTC timestamp without a date library. The facts of the methods a run was made
//! with travel in the summary (`methods`, the table of `methods.rs`), beside the families'
//! `model` keys, so that readers need no table of their own (older summaries have neither).
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

use crate::integrate::{Failure, Stats};

pub mod methods;

/// A run's status.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Status {
    #[serde(rename = "ok")]
    Ok,
    #[serde(rename = "failed")]
    Failed,
    #[serde(rename = "n/a")]
    NotApplicable,
}

/// Wall time of a run (s): min and median over its repeats.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Wall {
    pub min: f64,
    pub median: f64,
}

/// Which run a record is about, up to its ladder point: the case, the scene and the names of
/// the variant on the family's three axes. The one key type of every record (runs, order fits,
/// gate rows); `#[serde(flatten)]` keeps its five fields at the top level of each JSON object,
/// as docs/schemas.md documents them.
#[derive(Debug, Clone, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct RunKey {
    pub case: String,
    pub scene: String,
    pub param: String,
    pub integrator: String,
    pub formulation: String,
}

impl RunKey {
    /// The key of `variant` run on scene `scene` of case `case`.
    pub fn new(case: &str, scene: &str, param: &str, integrator: &str, formulation: &str) -> Self {
        RunKey {
            case: case.into(),
            scene: scene.into(),
            param: param.into(),
            integrator: integrator.into(),
            formulation: formulation.into(),
        }
    }

    /// Whether both keys name the same variant (on any case and scene).
    pub fn same_variant(&self, o: &RunKey) -> bool {
        self.param == o.param
            && self.integrator == o.integrator
            && self.formulation == o.formulation
    }
}

impl crate::selection::RunNames for RunKey {
    fn run_names(&self) -> [&str; 5] {
        [
            &self.case,
            &self.scene,
            &self.param,
            &self.integrator,
            &self.formulation,
        ]
    }
}

/// One run (or one `n/a` combination).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Record {
    #[serde(flatten)]
    pub key: RunKey,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub dt: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub tol: Option<f64>,
    pub status: Status,
    pub failure: Option<Failure>,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub reason: Option<String>,
    pub metrics: BTreeMap<String, Option<f64>>,
    /// Why a null metric is null.
    #[serde(skip_serializing_if = "BTreeMap::is_empty", default)]
    pub metric_reasons: BTreeMap<String, String>,
    pub stats: Stats,
    /// The timing pass's wall times; null for a failed or `n/a` run (never timed) and when
    /// the timing pass was skipped.
    pub wall_s: Option<Wall>,
    pub inputs_sha256: String,
    /// The hash of the case-file keys outside the physics that change a result
    /// (`case::hash`); a record whose settings differ from the baseline's is a new record
    /// there. Absent in summaries written before it existed.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub settings_sha256: Option<String>,
    pub reference_sha256: Option<String>,
    /// The series file (relative to the summary's folder); null when none was written, with
    /// the reason in `series_reason`.
    pub series: Option<String>,
    /// Why `series` is null: only the runs a figure draws keep their series (each variant's
    /// coarsest completed ladder point, for the variants the time-series plots draw), so the
    /// output stays small; `mbdbench trajectory` gives any run's samples.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub series_reason: Option<String>,
}

impl Record {
    /// The record of a run not made yet: `n/a`, no step, no metrics, no work.
    pub fn new(key: RunKey, inputs_sha256: &str) -> Record {
        Record {
            key,
            dt: None,
            tol: None,
            status: Status::NotApplicable,
            failure: None,
            reason: None,
            metrics: BTreeMap::new(),
            metric_reasons: BTreeMap::new(),
            stats: Stats::default(),
            wall_s: None,
            inputs_sha256: inputs_sha256.into(),
            settings_sha256: None,
            reference_sha256: None,
            series: None,
            series_reason: None,
        }
    }

    /// Sets the ladder point: a fixed step (`dt`) or a tolerance (`tol`).
    pub fn set_stepping(&mut self, s: crate::run::Stepping) {
        match s {
            crate::run::Stepping::Dt(h) => self.dt = Some(h),
            crate::run::Stepping::Tol(t) => self.tol = Some(t),
        }
    }

    /// Takes the outcome of a run that was made: its work, and `ok` or `failed` with the
    /// typed failure.
    pub fn take_run(&mut self, stats: Stats, failure: Option<Failure>) {
        self.stats = stats;
        self.status = if failure.is_some() {
            Status::Failed
        } else {
            Status::Ok
        };
        self.failure = failure;
    }

    /// A run the family refused to start (its message, e.g. a work budget): `failed` with a
    /// `work_limit` failure at t = 0.
    pub fn refuse(&mut self, message: String) {
        self.status = Status::Failed;
        self.failure = Some(Failure::new(
            crate::integrate::FailureKind::WorkLimit,
            0.0,
            message,
        ));
    }
}

/// An observed order over a ladder.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FitRecord {
    #[serde(flatten)]
    pub key: RunKey,
    pub metric: String,
    pub order: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub reason: Option<String>,
    pub points: Vec<[f64; 2]>,
}

/// Where and how the numbers were made.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Env {
    pub rustc: String,
    pub cpu: String,
    pub os: String,
    pub profile: String,
    pub threads: usize,
    /// How the wall times were taken: `parallel (N workers)`, `serial` (`--serial-timing`,
    /// or one worker) or `none` (no timing pass). Absent in summaries written before it.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub timing: Option<String>,
    /// s: the wall time of the whole command that wrote the file (its runs, timing pass and
    /// writing). Absent in files written before it.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub elapsed_s: Option<f64>,
    /// Where the run's time went, one entry per model family in the family table's order
    /// (`FamilyTime`). Absent in files written before it and where nothing ran.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub families: Option<Vec<FamilyTime>>,
}

/// One family's share of a run (`env.families`): its runs, the ladder points it skipped
/// (`n/a` records with the reason, `suite::skip`), and the CPU seconds its runs took on
/// their worker threads (`cpu_clock`) in the results pass (observed and scored) and in the
/// timing pass (the repeats without observation). The CPU seconds of the families add up to
/// the runs' share of the command's `elapsed_s` times the workers that ran them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FamilyTime {
    pub family: String,
    pub runs: usize,
    pub skipped: usize,
    pub results_cpu_s: f64,
    pub timing_cpu_s: f64,
}

impl FamilyTime {
    /// The family's CPU seconds in both passes.
    pub fn cpu_s(&self) -> f64 {
        self.results_cpu_s + self.timing_cpu_s
    }
}

/// The whole summary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    pub schema: u32,
    pub git_commit: String,
    pub created_utc: String,
    pub env: Env,
    pub records: Vec<Record>,
    pub fits: Vec<FitRecord>,
    /// What the run was asked to compute (`crate::selection`); absent in summaries written
    /// before it (readers then take every case of the tier the ladder points show).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub selection: Option<crate::selection::Selection>,
    /// The facts of every method registered in the catalogue the run was made with, by
    /// integrator name (`catalogue::methods`); absent in summaries written before it
    /// (readers then take the compiled-in catalogue's, `catalogue::methods_of`).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub methods: Option<methods::Methods>,
    /// The `model` keys of the catalogue's families, in table order; absent in summaries
    /// written before it.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub families: Option<Vec<String>>,
}

impl Summary {
    /// Whether `stability` (a `stability.json`) belongs with this summary: made by the same
    /// build (`git_commit`) for the same selection's filters (cases, scenes, variants,
    /// `--t-end`). The tiers may differ: a study's tier is its own search depth (the main
    /// job pairs the full run with the quick study). Otherwise the pair would judge one
    /// build's stability study beside another build's results or another subset: an error
    /// naming both stamps.
    pub fn pairs_with(&self, stability: &Summary) -> Result<(), String> {
        let stamp = |s: &Summary| {
            let sel = match &s.selection {
                Some(sel) => {
                    let f = sel.flags();
                    format!(
                        "{} tier{}",
                        sel.tier.name(),
                        if f.is_empty() {
                            String::new()
                        } else {
                            format!(", {f}")
                        }
                    )
                }
                None => "no selection".into(),
            };
            format!("commit {}, {sel}", s.git_commit)
        };
        let filters = |s: &Summary| {
            s.selection.as_ref().map(|sel| crate::selection::Selection {
                tier: crate::selection::Tier::Full,
                ..sel.clone()
            })
        };
        if self.git_commit == stability.git_commit && filters(self) == filters(stability) {
            return Ok(());
        }
        Err(format!(
            "stability.json ({}) is not of the run of summary.json ({}): a stability study is \
             judged only beside the run of the same build and selection; run `mbdbench \
             stability` with the run's options into the same folder, or remove stability.json",
            stamp(stability),
            stamp(self)
        ))
    }

    /// The summary as JSON with one record (and one fit) per line: the header fields
    /// indented, each record compact on a line of its own, so a run is one `grep` away and a
    /// diff shows the runs that changed; a quarter smaller than two-space indentation
    /// (9.7 MB for the full run before, 7.5 MB after). Any JSON reader reads it.
    pub fn to_json_lines(&self) -> Result<String, serde_json::Error> {
        let mut head = serde_json::to_value(self)?;
        let obj = head
            .as_object_mut()
            .expect("a summary serializes to an object");
        obj.remove("records");
        obj.remove("fits");
        let mut out = String::from("{\n");
        for (k, v) in obj.iter() {
            // The methods table one method a line, like the records.
            let value = match &self.methods {
                Some(m) if k == "methods" => m.to_json_lines(2)?,
                _ => serde_json::to_string(v)?,
            };
            out.push_str(&format!("  {}: {value},\n", serde_json::to_string(k)?));
        }
        let list = |name: &str, items: Vec<String>, last: bool, out: &mut String| {
            out.push_str(&format!("  \"{name}\": ["));
            if !items.is_empty() {
                out.push_str("\n    ");
                out.push_str(&items.join(",\n    "));
                out.push_str("\n  ");
            }
            out.push_str(if last { "]\n" } else { "],\n" });
        };
        let records = self
            .records
            .iter()
            .map(serde_json::to_string)
            .collect::<Result<Vec<_>, _>>()?;
        let fits = self
            .fits
            .iter()
            .map(serde_json::to_string)
            .collect::<Result<Vec<_>, _>>()?;
        list("records", records, false, &mut out);
        list("fits", fits, true, &mut out);
        out.push_str("}\n");
        Ok(out)
    }

    /// What the schema cannot check, for a summary read from a file: every run appears once
    /// (its run key and ladder point), its names hold no control character, a `failed` record
    /// carries its failure and an `ok` or `n/a` one none, and no error or drift metric (a name
    /// containing `error` or `drift`) is negative; and the `methods` table and `families`
    /// list hold together (`methods::check_summary`). The message names the record by its index and
    /// key.
    pub fn check(&self) -> Result<(), String> {
        if let Some(sel) = &self.selection {
            sel.check()?;
        }
        let mut seen: BTreeMap<(&RunKey, u64, u64), usize> = BTreeMap::new();
        for (i, r) in self.records.iter().enumerate() {
            let k = &r.key;
            // Names reach the terminal, summary.md and the page: a control character (a
            // newline, ESC) could forge a line or a heading, or drive the terminal.
            for (key, n) in [
                ("case", &k.case),
                ("scene", &k.scene),
                ("param", &k.param),
                ("integrator", &k.integrator),
                ("formulation", &k.formulation),
            ] {
                if n.chars().any(char::is_control) {
                    return Err(format!(
                        "records[{i}]: key `{key}` is {n:?}: a control character in a name"
                    ));
                }
            }
            let name = || {
                format!(
                    "records[{i}] ({}/{} {}/{}/{}{})",
                    k.case,
                    k.scene,
                    k.param,
                    k.integrator,
                    k.formulation,
                    match (r.dt, r.tol) {
                        (Some(h), _) => format!(" dt {h:e}"),
                        (None, Some(t)) => format!(" tol {t:e}"),
                        _ => String::new(),
                    }
                )
            };
            let point = (
                k,
                r.dt.map_or(0, f64::to_bits),
                r.tol.map_or(0, f64::to_bits),
            );
            if let Some(j) = seen.insert(point, i) {
                return Err(format!("{} is the same run as records[{j}]", name()));
            }
            match (r.status, &r.failure) {
                (Status::Failed, None) => {
                    return Err(format!("{}: status `failed` without a `failure`", name()));
                }
                (Status::Ok | Status::NotApplicable, Some(_)) => {
                    return Err(format!(
                        "{}: a `failure` on a run that did not fail",
                        name()
                    ));
                }
                _ => {}
            }
            for (m, v) in &r.metrics {
                if let Some(v) = v
                    && *v < 0.0
                    && (m.contains("error") || m.contains("drift"))
                {
                    return Err(format!("{}: metric `{m}` is negative ({v:e})", name()));
                }
            }
        }
        // After the names' check: its messages print names.
        methods::check_summary(self)
    }
}

/// The commit this binary was built from.
pub fn git_commit() -> &'static str {
    env!("MBDBENCH_GIT_COMMIT")
}

/// The compiler this binary was built with.
pub fn rustc_version() -> &'static str {
    env!("MBDBENCH_RUSTC")
}

impl Env {
    /// The current machine and build; `timing` says how the wall times were taken.
    pub fn current(threads: usize, timing: Option<String>) -> Env {
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|s| {
                s.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split(':').nth(1))
                    .map(|v| v.trim().to_string())
            })
            .unwrap_or_else(|| std::env::consts::ARCH.to_string());
        let os = std::fs::read_to_string("/etc/os-release")
            .ok()
            .and_then(|s| {
                s.lines().find(|l| l.starts_with("PRETTY_NAME=")).map(|l| {
                    l.trim_start_matches("PRETTY_NAME=")
                        .trim_matches('"')
                        .to_string()
                })
            })
            .unwrap_or_else(|| std::env::consts::OS.to_string());
        Env {
            rustc: rustc_version().to_string(),
            cpu,
            os,
            profile: if cfg!(debug_assertions) {
                "debug".into()
            } else {
                "release".into()
            },
            threads,
            timing,
            elapsed_s: None,
            families: None,
        }
    }
}

/// Current UTC time as `YYYY-MM-DDThh:mm:ssZ`.
pub fn now_utc() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    format_utc(secs)
}

/// Formats Unix seconds as an ISO-8601 UTC time (proleptic Gregorian calendar).
pub fn format_utc(secs: u64) -> String {
    let days = (secs / 86400) as i64;
    let rem = secs % 86400;
    // Civil-from-days (Howard Hinnant's algorithm, public domain description).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + if m <= 2 { 1 } else { 0 };
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        (rem % 3600) / 60,
        rem % 60
    )
}

/// A per-run time series at the score times (docs/schemas.md, "Series files"). JSON has no NaN or
/// infinity: serde_json writes a non-finite value (an overflowed energy, say) as `null`, and
/// the lists read `null` back as NaN, so that every series file written reads back (found by
/// tests/fuzz.rs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Series {
    pub t: Vec<f64>,
    #[serde(deserialize_with = "nullable_f64s")]
    pub energy: Vec<f64>,
    pub constraint: Vec<Option<f64>>,
    #[serde(deserialize_with = "nullable_f64s")]
    pub conditioning: Vec<f64>,
    /// The case's primary error metric at each score time (absent without a reference).
    #[serde(
        skip_serializing_if = "Option::is_none",
        default,
        deserialize_with = "nullable_f64s_opt"
    )]
    pub primary_error: Option<Vec<f64>>,
    pub primary_metric: String,
    /// A family's own quantities at the score times, by name (the flexible beam's
    /// `tip_deflection` and the reference's `tip_deflection_reference`, which its
    /// tip-over-time figure draws); null where a run has no value. Absent when empty.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub tracks: BTreeMap<String, Vec<Option<f64>>>,
}

/// `n` and a noun, plural past one: `1 scene`, `7 scenes`.
pub fn count(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

/// `x` rounded to `digits` significant digits (non-finite values unchanged).
pub fn round_sig(x: f64, digits: usize) -> f64 {
    if !x.is_finite() || x == 0.0 {
        return x;
    }
    format!("{x:.*e}", digits.saturating_sub(1))
        .parse()
        .unwrap_or(x)
}

impl Series {
    /// The series with every number rounded to `digits` significant digits (`round_sig`):
    /// what series files hold (plot data; the summary's metrics keep full precision).
    pub fn rounded(&self, digits: usize) -> Series {
        let r = |v: &[f64]| v.iter().map(|&x| round_sig(x, digits)).collect::<Vec<_>>();
        Series {
            t: r(&self.t),
            energy: r(&self.energy),
            constraint: self
                .constraint
                .iter()
                .map(|c| c.map(|x| round_sig(x, digits)))
                .collect(),
            conditioning: r(&self.conditioning),
            primary_error: self.primary_error.as_deref().map(r),
            primary_metric: self.primary_metric.clone(),
            tracks: self
                .tracks
                .iter()
                .map(|(k, v)| {
                    let v = v.iter().map(|c| c.map(|x| round_sig(x, digits))).collect();
                    (k.clone(), v)
                })
                .collect(),
        }
    }
}

/// A list of numbers in which `null` stands for a non-finite value, read as NaN.
fn nullable_f64s<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
    let v: Vec<Option<f64>> = Deserialize::deserialize(d)?;
    Ok(v.into_iter().map(|x| x.unwrap_or(f64::NAN)).collect())
}

/// `nullable_f64s` for an optional list.
fn nullable_f64s_opt<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<Vec<f64>>, D::Error> {
    let v: Option<Vec<Option<f64>>> = Deserialize::deserialize(d)?;
    Ok(v.map(|v| v.into_iter().map(|x| x.unwrap_or(f64::NAN)).collect()))
}

/// A file-name-safe id for a run.
pub fn run_id(
    param: &str,
    integrator: &str,
    formulation: &str,
    dt: Option<f64>,
    tol: Option<f64>,
) -> String {
    let step = match (dt, tol) {
        (Some(h), _) => format!("dt{h:e}"),
        (None, Some(t)) => format!("tol{t:e}"),
        _ => "na".into(),
    };
    format!("{param}.{integrator}.{formulation}.{step}")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The calendar conversion matches known instants (epoch, a leap day, a recent date).
    #[test]
    fn utc_formatting() {
        assert_eq!(format_utc(0), "1970-01-01T00:00:00Z");
        assert_eq!(format_utc(951_782_400), "2000-02-29T00:00:00Z");
        assert_eq!(format_utc(1_795_267_139), "2026-11-21T13:18:59Z");
    }

    /// A series with non-finite values (written as `null`) reads back, with NaN in their
    /// place (before, reading it failed: `invalid type: null, expected f64`).
    #[test]
    fn series_with_non_finite_values_round_trip() {
        let s = Series {
            t: vec![0.0, 0.1],
            energy: vec![1.0, f64::INFINITY],
            constraint: vec![None, Some(1e-16)],
            conditioning: vec![f64::NAN, 0.5],
            primary_error: Some(vec![0.0, f64::NEG_INFINITY]),
            primary_metric: "rotation_error_max".into(),
            tracks: Default::default(),
        };
        let text = serde_json::to_string(&s).unwrap();
        let back: Series = serde_json::from_str(&text).unwrap();
        assert_eq!(back.energy[0], 1.0);
        assert!(back.energy[1].is_nan() && back.conditioning[0].is_nan());
        assert_eq!(back.conditioning[1], 0.5);
        let e = back.primary_error.unwrap();
        assert!(e[0] == 0.0 && e[1].is_nan());
        // An absent primary error stays absent.
        let none = Series {
            primary_error: None,
            ..s
        };
        let back: Series = serde_json::from_str(&serde_json::to_string(&none).unwrap()).unwrap();
        assert_eq!(back.primary_error, None);
    }

    /// `to_json_lines` reads back to the same summary (empty lists included), puts each
    /// record and fit on a line of its own, and rounds a number series rounded once more to
    /// itself (`round_sig` is idempotent, to 6 significant digits).
    #[test]
    fn json_lines_round_trip_and_rounding() {
        let mut s = Summary {
            schema: 1,
            git_commit: "c".into(),
            created_utc: "t".into(),
            env: Env::current(1, None),
            records: vec![],
            fits: vec![],
            selection: Some(crate::selection::Selection::everything(
                crate::selection::Tier::Quick,
            )),
            methods: None,
            families: None,
        };
        let back: Summary = serde_json::from_str(&s.to_json_lines().unwrap()).unwrap();
        assert_eq!(back, s);
        let mut r = Record::new(RunKey::new("a", "b", "so3", "rk4", "body"), "h");
        r.metrics
            .insert("rotation_error_max".into(), Some(1.0 / 3.0));
        r.series_reason = Some("not written".into());
        s.records = vec![r.clone(), r];
        s.records[1].dt = Some(0.01);
        let mut table = methods::Methods::default();
        let rk4 =
            crate::integrate::MethodInfo::new("rk4", crate::integrate::MethodKind::Explicit, 4);
        table.insert("rk4", methods::MethodFacts::of(&rk4, "quat"));
        s.methods = Some(table);
        s.families = Some(vec!["rigid_body".into()]);
        let text = s.to_json_lines().unwrap();
        let back: Summary = serde_json::from_str(&text).unwrap();
        assert_eq!(back, s);
        assert_eq!(
            text.lines()
                .filter(|l| l.contains("\"case\":\"a\""))
                .count(),
            2
        );
        assert!(
            text.contains("\n    \"rk4\": {\"kind\":\"explicit\""),
            "{text}"
        );
        assert_eq!(round_sig(1.0 / 3.0, 6), 0.333333);
        assert_eq!(round_sig(0.7000000000000001, 6), 0.7);
        assert_eq!(round_sig(-f64::EPSILON, 6), -2.22045e-16);
        for x in [1.0 / 3.0, 123456.789, 9.999995e-9, f64::NAN, 0.0] {
            let once = round_sig(x, 6);
            assert!(round_sig(once, 6) == once || once.is_nan());
        }
    }

    /// Statuses serialize to the contract's strings.
    #[test]
    fn status_strings() {
        assert_eq!(
            serde_json::to_string(&Status::NotApplicable).unwrap(),
            "\"n/a\""
        );
        assert_eq!(serde_json::to_string(&Status::Ok).unwrap(), "\"ok\"");
    }
}
