//! Hostile input (issue 4): property-based fuzzing of the case parser, of the run loop and of
//! the command line. Every input either runs or gives a typed error within its work limit;
//! nothing panics, hangs, or leaves a half-written file that looks complete.
//!
//! Three layers:
//! - the parser: the real case files, mutated (lines deleted, duplicated, swapped; keys
//!   renamed; values retyped; numbers replaced by extremes; huge and deeply nested arrays;
//!   junk; truncation), fed to `case::load_str`;
//! - the run loop: generated, valid-looking cases with random physics (tiny and huge masses,
//!   near-singular inertias, random springs and initial states, tiny and huge horizons, fine
//!   sample grids) and small work limits, planned and run with random registered variants at
//!   their ladder steps, at steps longer than the horizon, and with horizon overrides;
//! - the binary: bad case files and hostile arguments exit 2 naming the file and the key and
//!   write nothing; output files are written whole or not at all.
//!
//! The number of cases per property is `MBDBENCH_FUZZ_CASES` (default 256 for the in-process
//! parser property, a fraction of it for the slower ones; see `cases`). CI runs the defaults;
//! a long run is `MBDBENCH_FUZZ_CASES=20000 cargo test --release --test fuzz`.
mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use mbdbench::case::{self, Case, CaseError};
use mbdbench::integrate::{FailureKind, Limits};
use mbdbench::model::rigid_body::plan as rigid_plan;
use mbdbench::model::rigid_body::registry::{self, Setup};
use mbdbench::model::rigid_body::score::{self, ScoreContext};
use mbdbench::plan;
use mbdbench::run::{Observe, RunOutput};
use mbdbench::suite::{self, RunOptions, VariantFilter};
use proptest::prelude::*;
use proptest::sample::Index;
use proptest::test_runner::Config;

// ---------------------------------------------------------------------------------------
// Configuration

/// Cases for a property: `MBDBENCH_FUZZ_CASES` (or `base`) divided by `divisor` (the cost of
/// one case relative to the parser property's), at least 4.
fn cases(divisor: u32) -> u32 {
    let base = std::env::var("MBDBENCH_FUZZ_CASES")
        .ok()
        .and_then(|s| s.trim().parse::<u32>().ok())
        .unwrap_or(256);
    (base / divisor).max(4)
}

fn config(divisor: u32) -> Config {
    Config {
        cases: cases(divisor),
        // Shrinking a slow failing case can take long; the failing input is printed anyway.
        max_shrink_iters: 256,
        failure_persistence: None,
        ..Config::default()
    }
}

/// The slowest one run may take before it counts as a hang (its work limit is small).
const RUN_DEADLINE: Duration = Duration::from_secs(20);
/// The slowest one binary invocation may take before it counts as a hang.
const PROCESS_DEADLINE: Duration = Duration::from_secs(60);

// ---------------------------------------------------------------------------------------
// Values

/// A TOML literal for `x` (`nan`, `inf`, `-inf`, or the round-trip decimal).
fn lit(x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf".into() } else { "-inf".into() }
    } else {
        format!("{x:?}")
    }
}

/// Extreme numbers and wrong types, as TOML value text.
const EXTREMES: &[&str] = &[
    "0",
    "0.0",
    "-0.0",
    "-1",
    "-1.0",
    "1",
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "1e-308",
    "5e-324",
    "-5e-324",
    "nan",
    "-nan",
    "+nan",
    "inf",
    "-inf",
    "+inf",
    "9007199254740993",
    "9223372036854775807",
    "-9223372036854775808",
    "1e15",
    "9.0e15",
    "1e16",
    "0x7fffffff",
    "0o777",
    "0b101",
    "1_000.5",
    "\"junk\"",
    "\"\"",
    "'1.0'",
    "\"\"\"multi\nline\"\"\"",
    "true",
    "false",
    "[]",
    "[[]]",
    "[1.0]",
    "[1.0, 2.0]",
    "[0.0, nan, inf]",
    "[1.0, \"a\", true]",
    "[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]",
    "{}",
    "{ x = 1.0 }",
    "{ order1 = [1.0] }",
    "1979-05-27T07:32:00Z",
    "07:32:00",
    "1979-05-27",
];

/// A replacement value: an extreme, any double (NaN, infinities, subnormals included), a
/// plain number, or a junk string.
fn value() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => prop::sample::select(EXTREMES).prop_map(str::to_string),
        3 => any::<f64>().prop_map(lit),
        2 => (-1.0e3..1.0e3f64).prop_map(lit),
        1 => (0u32..12).prop_map(|e| format!("1.0e-{e}")),
        1 => "[ -~]{0,12}".prop_map(|s| format!("{s:?}")),
        1 => "[ -~\n]{0,16}",
    ]
}

// ---------------------------------------------------------------------------------------
// Text mutations

#[derive(Debug, Clone)]
enum Mutation {
    DeleteLine(Index),
    DuplicateLine(Index),
    SwapLines(Index, Index),
    /// Replace one numeric literal.
    Number(Index, String),
    /// Replace the value of one `key = value` line.
    Value(Index, String),
    /// Rename the key of one `key = value` line.
    RenameKey(Index, String),
    /// Cut the text at a character boundary.
    Truncate(Index),
    /// Insert text at a character boundary.
    Insert(Index, String),
    /// The value of one `key = value` line becomes an array of this many numbers.
    HugeArray(Index, usize),
    /// The value of one `key = value` line becomes this many nested arrays.
    Nested(Index, usize),
    /// A top-level key (a work limit) with this value, before the first table.
    TopKey(&'static str, String),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        2 => any::<Index>().prop_map(Mutation::DeleteLine),
        1 => any::<Index>().prop_map(Mutation::DuplicateLine),
        1 => (any::<Index>(), any::<Index>()).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        6 => (any::<Index>(), value()).prop_map(|(i, v)| Mutation::Number(i, v)),
        3 => (any::<Index>(), value()).prop_map(|(i, v)| Mutation::Value(i, v)),
        1 => (any::<Index>(), "[a-z_]{1,12}|\"[ -~]{0,8}\"|[ -~]{0,6}")
            .prop_map(|(i, k)| Mutation::RenameKey(i, k)),
        1 => any::<Index>().prop_map(Mutation::Truncate),
        2 => (any::<Index>(), "[\\[\\]{}=\",.#'\n a-z0-9]{1,8}|.{1,4}")
            .prop_map(|(i, s)| Mutation::Insert(i, s)),
        1 => (any::<Index>(), prop_oneof![0usize..8, 1000usize..20_000])
            .prop_map(|(i, n)| Mutation::HugeArray(i, n)),
        1 => (any::<Index>(), prop_oneof![1usize..8, 100usize..5_000])
            .prop_map(|(i, n)| Mutation::Nested(i, n)),
        1 => (
            prop::sample::select(&["max_steps", "max_rhs_evals"][..]),
            value()
        )
            .prop_map(|(k, v)| Mutation::TopKey(k, v)),
    ]
}

/// Byte ranges of the numeric literals of `text` (a run of `[0-9.eE+-_]` holding a digit,
/// after a space, `[`, `,` or `=`; names such as `order2_4` or `spin_d1e-2` are skipped).
fn numbers(text: &str) -> Vec<std::ops::Range<usize>> {
    let b = text.as_bytes();
    let num = |c: u8| c.is_ascii_digit() || b".eE+-_".contains(&c);
    let mut out = vec![];
    let mut i = 0;
    while i < b.len() {
        let starts = num(b[i]) && (i == 0 || b" [,=".contains(&b[i - 1]));
        if starts {
            let mut j = i;
            while j < b.len() && num(b[j]) {
                j += 1;
            }
            if b[i..j].iter().any(u8::is_ascii_digit) {
                out.push(i..j);
            }
            i = j;
        } else {
            i += 1;
        }
    }
    out
}

/// Byte ranges of the lines of `text` (with their newline).
fn lines(text: &str) -> Vec<std::ops::Range<usize>> {
    let mut out = vec![];
    let mut start = 0;
    for l in text.split_inclusive('\n') {
        out.push(start..start + l.len());
        start += l.len();
    }
    out
}

/// `(key range, value range)` of every `key = value` line that is not a comment.
fn assignments(text: &str) -> Vec<(std::ops::Range<usize>, std::ops::Range<usize>)> {
    lines(text)
        .into_iter()
        .filter_map(|r| {
            let l = &text[r.clone()];
            let head = l.trim_start();
            if head.starts_with('#') || head.starts_with('[') {
                return None;
            }
            let eq = l.find('=')?;
            let end = r.start + l.trim_end_matches(['\n', '\r']).len();
            Some((r.start..r.start + eq, r.start + eq + 1..end))
        })
        .collect()
}

fn floor_char(text: &str, mut i: usize) -> usize {
    i = i.min(text.len());
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn splice(text: &str, r: std::ops::Range<usize>, with: &str) -> String {
    format!("{}{with}{}", &text[..r.start], &text[r.end..])
}

fn apply(text: &str, m: &Mutation) -> String {
    let ls = lines(text);
    let asg = assignments(text);
    match m {
        Mutation::DeleteLine(i) if !ls.is_empty() => splice(text, i.get(&ls).clone(), ""),
        Mutation::DuplicateLine(i) if !ls.is_empty() => {
            let r = i.get(&ls).clone();
            let l = text[r.clone()].to_string();
            splice(text, r.start..r.start, &l)
        }
        Mutation::SwapLines(a, b) if !ls.is_empty() => {
            let (mut ra, mut rb) = (a.get(&ls).clone(), b.get(&ls).clone());
            if ra.start > rb.start {
                std::mem::swap(&mut ra, &mut rb);
            }
            if ra == rb {
                return text.to_string();
            }
            format!(
                "{}{}{}{}{}",
                &text[..ra.start],
                &text[rb.clone()],
                &text[ra.end..rb.start],
                &text[ra.clone()],
                &text[rb.end..]
            )
        }
        Mutation::Number(i, v) => {
            let ns = numbers(text);
            if ns.is_empty() {
                return text.to_string();
            }
            splice(text, i.get(&ns).clone(), v)
        }
        Mutation::Value(i, v) if !asg.is_empty() => {
            splice(text, i.get(&asg).1.clone(), &format!(" {v}"))
        }
        Mutation::RenameKey(i, k) if !asg.is_empty() => {
            splice(text, i.get(&asg).0.clone(), &format!("{k} "))
        }
        Mutation::Truncate(i) => text[..floor_char(text, i.index(text.len() + 1))].to_string(),
        Mutation::Insert(i, s) => {
            let at = floor_char(text, i.index(text.len() + 1));
            splice(text, at..at, s)
        }
        Mutation::HugeArray(i, n) if !asg.is_empty() => {
            let arr = format!("[{}]", vec!["1.0"; *n].join(", "));
            splice(text, i.get(&asg).1.clone(), &format!(" {arr}"))
        }
        Mutation::Nested(i, n) if !asg.is_empty() => {
            let arr = format!("{}1.0{}", "[".repeat(*n), "]".repeat(*n));
            splice(text, i.get(&asg).1.clone(), &format!(" {arr}"))
        }
        Mutation::TopKey(k, v) => {
            let line = format!("{k} = {v}\n");
            match text.find("\n[") {
                Some(p) => splice(text, p + 1..p + 1, &line),
                None => format!("{line}{text}"),
            }
        }
        _ => text.to_string(),
    }
}

// ---------------------------------------------------------------------------------------
// Checks

/// A load error names the file, and the key or the line.
fn check_error(label: &str, e: &CaseError) {
    assert_eq!(e.file, label, "{e}");
    let shown = e.to_string();
    assert!(shown.starts_with(label), "`{shown}` does not name the file");
    assert!(
        !e.key.is_empty() || e.message.contains("line "),
        "`{shown}` names neither a key nor a line"
    );
    if !e.key.is_empty() {
        assert!(shown.contains(&format!(": {}: ", e.key)), "`{shown}`");
    }
}

/// The invariants of a loaded case (case/mod.rs and the rigid family's case.rs, "Invariants after loading").
fn check_case(c: &Case) {
    let finite3 = |v: &nalgebra::Vector3<f64>| v.iter().all(|x| x.is_finite());
    assert!(c.energy_scale.is_finite() && c.energy_scale > 0.0);
    assert!(c.max_steps >= 1);
    for s in &c.scenes {
        let r = mbdbench::model::rigid_body::case::RigidScene::of(s).unwrap();
        assert!(finite3(&r.euler_xyz) && finite3(&r.position) && finite3(&r.velocity));
        assert!(finite3(&r.omega0), "{}: omega0 {:?}", s.name, r.omega0);
        assert!(r.inertia.iter().all(|x| x.is_finite()));
        assert_eq!(r.inertia, r.inertia.transpose());
        assert!(s.t_end > 0.0 && s.t_end.is_finite());
        assert!(s.n_score >= 1 && s.samples_per_score >= 1);
        for quick in [false, true] {
            let l = s.ladder(quick);
            for class in case::OrderClass::ALL {
                for f in l.fixed(class) {
                    assert!(f.steps >= 1 && f.steps <= c.max_steps, "{f:?}");
                    assert!(f.h > 0.0 && f.h.is_finite(), "{f:?}");
                }
            }
            assert!(l.tol.iter().all(|t| *t > 0.0 && *t < 1.0));
        }
        assert_eq!(case::inputs_sha256(c, s).len(), 64);
        if let Err(e) = rigid_plan::scene_plan(c, s) {
            check_error(&c.file, &e);
        }
    }
}

/// A run's output respects its limits and its grid.
fn check_output(out: &RunOutput, setup: &Setup, adaptive: bool, what: &str) {
    let l = &setup.limits;
    assert!(
        out.stats.steps <= l.max_steps.saturating_add(1),
        "{what}: {} steps, max_steps {}",
        out.stats.steps,
        l.max_steps
    );
    // Budgets are checked after each step (a step's own evaluations may overshoot); an
    // implicit step's Newton iterations are bounded by the method.
    let slack = if adaptive { 20_000 } else { 5_000 };
    assert!(
        out.stats.rhs_evals <= l.max_rhs_evals.saturating_add(slack),
        "{what}: {} RHS evaluations, max_rhs_evals {}",
        out.stats.rhs_evals,
        l.max_rhs_evals
    );
    let t_end = setup.grid.t_end;
    let mut last = f64::NEG_INFINITY;
    for s in &out.samples {
        assert!(
            s.t.is_finite() && s.t >= last,
            "{what}: sample time {}",
            s.t
        );
        assert!(s.t <= t_end * (1.0 + 1e-12), "{what}: sample past t_end");
        last = s.t;
    }
    if out.failure.is_none() {
        assert!(!out.samples.is_empty(), "{what}: ok without samples");
        let t = out.samples.last().unwrap().t;
        assert!((t - t_end).abs() <= 1e-9 * t_end, "{what}: ends at {t}");
    }
    if let Some(f) = &out.failure {
        assert!(!f.message.is_empty(), "{what}: {f:?}");
        assert!(
            !matches!(f.kind, FailureKind::BoundExceeded | FailureKind::Diverged),
            "{what}: {f:?}"
        );
    }
}

/// Everything of a run that must be bit-identical across repeats.
fn fingerprint(out: &RunOutput) -> String {
    format!(
        "{:?} {:?} {} {:?}",
        out.stats,
        out.failure,
        out.conditioning_min.to_bits(),
        out.samples
            .iter()
            .map(|s| format!("{:?}", s))
            .collect::<Vec<_>>()
    )
}

/// Runs `f` and fails the property if it takes longer than `RUN_DEADLINE`.
fn timed<T>(what: &str, f: impl FnOnce() -> T) -> T {
    let t0 = Instant::now();
    let r = f();
    let dt = t0.elapsed();
    assert!(dt < RUN_DEADLINE, "{what}: took {dt:?}");
    r
}

// ---------------------------------------------------------------------------------------
// Parser

proptest! {
    #![proptest_config(config(1))]

    /// Loading a mutated catalogue file never panics: it gives a valid case or an error that
    /// names the file and the key (or the line of a syntax error).
    #[test]
    fn mutated_case_files_load_or_name_file_and_key(
        which in any::<Index>(),
        muts in prop::collection::vec(mutation(), 1..=4),
    ) {
        let sources = case::embedded_sources();
        let (label, text) = *which.get(sources);
        let mut t = text.to_string();
        for m in &muts {
            t = apply(&t, m);
        }
        match case::load_str(label, &t) {
            Ok(c) => check_case(&c),
            Err(e) => check_error(label, &e),
        }
    }
}

// ---------------------------------------------------------------------------------------
// Random physics

/// A positive magnitude: ordinary, tiny, huge, or the extremes of the doubles.
fn magnitude() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => 0.01f64..100.0,
        1 => (-300i32..=-6).prop_map(|e| 10f64.powi(e)),
        1 => (6i32..=300).prop_map(|e| 10f64.powi(e)),
        1 => Just(f64::MIN_POSITIVE),
        1 => Just(f64::MAX),
    ]
}

/// A signed number, zero included.
fn signed() -> impl Strategy<Value = f64> {
    prop_oneof![
        1 => Just(0.0),
        6 => (magnitude(), any::<bool>()).prop_map(|(x, neg)| if neg { -x } else { x }),
    ]
}

fn vec3() -> impl Strategy<Value = [f64; 3]> {
    [signed(), signed(), signed()]
}

/// A small vector (an ordinary state), or a hostile one.
fn state3() -> impl Strategy<Value = [f64; 3]> {
    prop_oneof![
        4 => [-5.0..5.0f64, -5.0..5.0f64, -5.0..5.0f64],
        1 => vec3(),
    ]
}

/// Principal moments: ordinary, near singular (one or two tiny), or spread over decades.
fn moments() -> impl Strategy<Value = [f64; 3]> {
    prop_oneof![
        4 => [0.1..10.0f64, 0.1..10.0f64, 0.1..10.0f64],
        1 => (0.1..10.0f64, 1i32..300).prop_map(|(a, e)| [10f64.powi(-e), a, a]),
        1 => (0.1..10.0f64, 1i32..300).prop_map(|(a, e)| [10f64.powi(-e), 10f64.powi(-e), a]),
        1 => [magnitude(), magnitude(), magnitude()],
    ]
}

/// The inertia `Q diag(m) Q^T` for `Q = Rx(a) Ry(b) Rz(c)`, exactly symmetric.
fn inertia(m: [f64; 3], angles: [f64; 3]) -> [[f64; 3]; 3] {
    let q = nalgebra::Rotation3::from_euler_angles(angles[0], angles[1], angles[2]).into_inner();
    let j = q * nalgebra::Matrix3::from_diagonal(&nalgebra::Vector3::from(m)) * q.transpose();
    let mut a = [[0.0; 3]; 3];
    for (i, row) in a.iter_mut().enumerate() {
        for (k, x) in row.iter_mut().enumerate() {
            *x = if k < i { j[(k, i)] } else { j[(i, k)] };
        }
    }
    a
}

#[derive(Debug, Clone)]
struct PhysSpring {
    body_point: [f64; 3],
    direction: [f64; 3],
    stiffness: f64,
    rest_length: f64,
}

#[derive(Debug, Clone)]
struct PhysScene {
    euler: [f64; 3],
    position: [f64; 3],
    velocity: [f64; 3],
    /// 0: none, 1: omega, 2: omega_world, 3: angular_momentum_body.
    angular: (u8, [f64; 3]),
    inertia: Option<([f64; 3], [f64; 3])>,
    score_every: f64,
    n_score: u64,
    samples_per_score: f64,
    /// Own ladders: steps as divisors of score_every, and tolerances.
    ladders: Option<(Vec<u64>, Vec<f64>)>,
}

#[derive(Debug, Clone)]
struct Phys {
    mass: Option<f64>,
    moments: [f64; 3],
    axes: [f64; 3],
    nonphysical: bool,
    gravity: Option<f64>,
    pivot: Option<[f64; 3]>,
    springs: Vec<PhysSpring>,
    scenes: Vec<PhysScene>,
    energy_scale: f64,
    max_steps: u64,
    max_rhs_evals: Option<u64>,
    /// Divisors of score_every of the three fixed classes, and tolerances.
    ladders: [Vec<u64>; 3],
    tol: Vec<f64>,
    /// Numbers of the generated text replaced by a hostile value.
    poison: Vec<(Index, String)>,
}

fn spring() -> impl Strategy<Value = PhysSpring> {
    (
        state3(),
        prop_oneof![
            3 => prop::sample::select(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]][..]),
            1 => [-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64],
        ],
        prop_oneof![3 => 1.0..1.0e4f64, 1 => Just(0.0), 1 => magnitude()],
        prop_oneof![3 => 0.1..2.0f64, 1 => magnitude()],
    )
        .prop_map(|(body_point, d, stiffness, rest_length)| {
            let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let direction = if n > 1e-3 {
                [d[0] / n, d[1] / n, d[2] / n]
            } else {
                [0.0, 0.0, 1.0]
            };
            PhysSpring {
                body_point,
                direction,
                stiffness,
                rest_length,
            }
        })
}

fn tolerances() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(
        prop_oneof![
            3 => (1i32..=12).prop_map(|e| 10f64.powi(-e)),
            1 => (13i32..=300).prop_map(|e| 10f64.powi(-e)),
            1 => 0.01..0.99f64,
        ],
        0..=2,
    )
    .prop_map(|mut v| {
        v.dedup();
        v
    })
}

fn divisors() -> impl Strategy<Value = Vec<u64>> {
    prop::collection::btree_set(1u64..=8, 0..=2).prop_map(|s| s.into_iter().collect())
}

fn scene() -> impl Strategy<Value = PhysScene> {
    (
        prop_oneof![4 => [-4.0..4.0f64, -4.0..4.0f64, -4.0..4.0f64], 1 => vec3()],
        state3(),
        state3(),
        (0u8..4, prop_oneof![4 => state3(), 1 => vec3()]),
        prop::option::weighted(0.2, (moments(), [-3.0..3.0f64, -3.0..3.0f64, -3.0..3.0f64])),
        prop_oneof![
            4 => prop::sample::select(&[1.0e-3, 1.0e-2, 0.1, 1.0, 10.0][..]),
            1 => magnitude(),
        ],
        prop_oneof![4 => 1u64..=20, 1 => Just(1u64)],
        prop_oneof![
            4 => prop::sample::select(&[1.0, 2.0, 10.0][..]),
            1 => prop::sample::select(&[1.0e3, 1.0e6, 1.0e9, 1.0e12][..]),
        ],
        prop::option::weighted(0.3, (divisors(), tolerances())),
    )
        .prop_map(
            |(euler, position, velocity, angular, inertia, score_every, n_score, sps, ladders)| {
                PhysScene {
                    euler,
                    position,
                    velocity,
                    angular,
                    inertia,
                    score_every,
                    n_score,
                    samples_per_score: sps,
                    ladders,
                }
            },
        )
}

fn phys() -> impl Strategy<Value = Phys> {
    (
        (
            prop::option::weighted(0.8, magnitude()),
            moments(),
            prop_oneof![
                1 => Just([0.0; 3]),
                1 => [-3.0..3.0f64, -3.0..3.0f64, -3.0..3.0f64],
            ],
            any::<bool>(),
            prop::option::weighted(0.5, prop_oneof![4 => Just(9.81), 1 => magnitude()]),
            prop::option::weighted(0.2, state3()),
            prop::collection::vec(spring(), 0..=4),
        ),
        (
            prop::collection::vec(scene(), 1..=2),
            prop_oneof![4 => Just(1.0), 1 => magnitude()],
            prop_oneof![4 => 100u64..=3000, 1 => 1u64..=10],
            prop::option::weighted(0.7, 1u64..=60_000),
            [divisors(), divisors(), divisors()],
            tolerances(),
            prop_oneof![
                5 => Just(vec![]),
                1 => prop::collection::vec((any::<Index>(), value()), 1..=2),
            ],
        ),
    )
        .prop_map(
            |(
                (mass, moments, axes, nonphysical, gravity, pivot, springs),
                (scenes, energy_scale, max_steps, max_rhs_evals, ladders, tol, poison),
            )| {
                // Keep the generated file consistent (gravity and a pivot need a mass,
                // springs a free body); the poison and the extremes make it hostile.
                let pivot = pivot.filter(|_| mass.is_some());
                Phys {
                    mass,
                    moments,
                    axes,
                    nonphysical,
                    gravity: gravity.filter(|_| mass.is_some()),
                    springs: if mass.is_some() && pivot.is_none() {
                        springs
                    } else {
                        vec![]
                    },
                    pivot,
                    scenes,
                    energy_scale,
                    max_steps,
                    max_rhs_evals,
                    ladders,
                    tol,
                    poison,
                }
            },
        )
}

fn arr3(a: &[f64; 3]) -> String {
    format!("[{}, {}, {}]", lit(a[0]), lit(a[1]), lit(a[2]))
}

fn mat3(m: &[[f64; 3]; 3]) -> String {
    format!("[{}, {}, {}]", arr3(&m[0]), arr3(&m[1]), arr3(&m[2]))
}

fn steps_list(score_every: f64, ks: &[u64]) -> String {
    let v: Vec<String> = ks.iter().map(|k| lit(score_every / *k as f64)).collect();
    format!("[{}]", v.join(", "))
}

fn tol_list(t: &[f64]) -> String {
    format!(
        "[{}]",
        t.iter().map(|x| lit(*x)).collect::<Vec<_>>().join(", ")
    )
}

impl Phys {
    /// The case file. The case-level ladders are expressed in the first scene's
    /// `score_every`; other scenes whose grid they do not divide get their own or fail to
    /// load (a typed error, itself checked).
    fn toml(&self) -> String {
        use std::fmt::Write;
        let mut t = String::new();
        let _ = writeln!(
            t,
            "schema = 1\ncase = \"fuzz\"\ntitle = \"fuzz\"\nmodel = \"rigid_body\"\n\
             primary_metric = \"rotation_error_max\"\nenergy_scale = {}\nreference = \"exact\"\n\
             nonphysical_inertia = {}\nmax_steps = {}",
            lit(self.energy_scale),
            self.nonphysical,
            self.max_steps
        );
        if let Some(r) = self.max_rhs_evals {
            let _ = writeln!(t, "max_rhs_evals = {r}");
        }
        let _ = writeln!(t, "\n[body]");
        if let Some(m) = self.mass {
            let _ = writeln!(t, "mass = {}", lit(m));
        }
        let _ = writeln!(t, "inertia = {}", mat3(&inertia(self.moments, self.axes)));
        if let Some(g) = self.gravity {
            let _ = writeln!(t, "gravity = {}", lit(g));
        }
        if let Some(p) = &self.pivot {
            let _ = writeln!(t, "pivot_com = {}", arr3(p));
        }
        for s in &self.springs {
            let _ = writeln!(
                t,
                "\n[[spring]]\nbody_point = {}\ndirection = {}\nstiffness = {}\nrest_length = {}",
                arr3(&s.body_point),
                arr3(&s.direction),
                lit(s.stiffness),
                lit(s.rest_length)
            );
        }
        let translates = self.mass.is_some() && self.pivot.is_none();
        for (i, s) in self.scenes.iter().enumerate() {
            let _ = writeln!(
                t,
                "\n[[scene]]\nname = \"s{i}\"\neuler_xyz = {}",
                arr3(&s.euler)
            );
            if translates {
                let _ = writeln!(
                    t,
                    "position = {}\nvelocity = {}",
                    arr3(&s.position),
                    arr3(&s.velocity)
                );
            }
            let key = ["", "omega", "omega_world", "angular_momentum_body"][s.angular.0 as usize];
            if !key.is_empty() {
                let _ = writeln!(t, "{key} = {}", arr3(&s.angular.1));
            }
            if let Some((m, a)) = &s.inertia {
                let _ = writeln!(t, "inertia = {}", mat3(&inertia(*m, *a)));
            }
            let _ = writeln!(
                t,
                "t_end = {}\nsample_every = {}\nscore_every = {}",
                lit(s.score_every * s.n_score as f64),
                lit(s.score_every / s.samples_per_score),
                lit(s.score_every)
            );
            if let Some((ks, tol)) = &s.ladders {
                let l = steps_list(s.score_every, ks);
                let _ = writeln!(
                    t,
                    "ladders = {{ order1 = {l}, order2_4 = {l}, order6 = {l}, tol = {}, \
                     quick = {{ order2_4 = {l} }} }}",
                    tol_list(tol)
                );
            }
        }
        let h = self.scenes[0].score_every;
        let _ = writeln!(
            t,
            "\n[ladders]\norder1 = {}\norder2_4 = {}\norder6 = {}\ntol = {}\n\
             quick = {{ order2_4 = {}, tol = {} }}",
            steps_list(h, &self.ladders[0]),
            steps_list(h, &self.ladders[1]),
            steps_list(h, &self.ladders[2]),
            tol_list(&self.tol),
            steps_list(h, &self.ladders[1][..self.ladders[1].len().min(1)]),
            tol_list(&self.tol[..self.tol.len().min(1)]),
        );
        for (i, v) in &self.poison {
            t = apply(&t, &Mutation::Number(*i, v.clone()));
        }
        t
    }
}

/// How one variant is run on a scene.
#[derive(Debug, Clone)]
enum Pick {
    /// The first value of its ladder (full tier).
    Ladder,
    /// A fixed step or tolerance given directly: `t_end` times this factor for fixed
    /// steps (a step as long as the horizon or longer), the value itself for tolerances.
    Direct(f64),
    /// Its ladder value with the horizon replaced (as `run --t-end` does).
    Horizon(f64),
    /// Its ladder value, observing the final state only (the timing pass).
    Final,
}

fn pick() -> impl Strategy<Value = Pick> {
    prop_oneof![
        4 => Just(Pick::Ladder),
        2 => prop::sample::select(&[1.0, 2.0, 0.5, 1.0e10, 1.0e-3, 1.0e-300, 1.0e300][..])
            .prop_map(Pick::Direct),
        2 => prop::sample::select(&[1.0e-9, 1.0e3, 1.0e6, 1.0e9, 1.0e13, 1.0e300][..])
            .prop_map(Pick::Horizon),
        1 => Just(Pick::Final),
    ]
}

/// Runs `v` on `setup` at `value` twice, checks the output and that both runs agree bit
/// for bit, and scores it (no reference).
fn run_checked(
    v: &registry::Variant,
    setup: &Setup,
    value: f64,
    energy_scale: f64,
    primary: &str,
) -> Result<(), String> {
    let what = format!("{v:?} at {value:e}, t_end {:e}", setup.grid.t_end);
    let first = timed(&what, || (v.run)(setup, value));
    let second = timed(&what, || (v.run)(setup, value));
    match (&first, &second) {
        (Ok(a), Ok(b)) => {
            check_output(a, setup, v.info.adaptive, &what);
            assert_eq!(fingerprint(a), fingerprint(b), "{what}: not deterministic");
            let cx = ScoreContext {
                body: &setup.body,
                energy_scale,
                primary_metric: primary,
                reference: None,
            };
            let (scores, series) = score::score(a, &cx);
            serde_json::to_string(&series).map_err(|e| format!("{what}: series: {e}"))?;
            serde_json::to_string(&scores.values).map_err(|e| format!("{what}: {e}"))?;
            Ok(())
        }
        (Err(a), Err(b)) => {
            assert_eq!(a, b, "{what}: not deterministic");
            assert!(!a.is_empty(), "{what}: empty error");
            Ok(())
        }
        _ => panic!("{what}: Ok once, Err once"),
    }
}

proptest! {
    #![proptest_config(config(8))]

    /// A valid-looking case with random, extreme physics and small work limits either fails
    /// to load with an error naming the file and the key, or every registered variant run on
    /// it ends with a result or a typed failure within its work limit, identically twice, and
    /// scores without panicking.
    #[test]
    fn random_physics_runs_or_fails_typed(
        p in phys(),
        variants in prop::collection::vec((any::<Index>(), pick()), 1..=5),
    ) {
        let text = p.toml();
        let label = "cases/fuzz.toml";
        let c = match case::load_str(label, &text) {
            Ok(c) => c,
            Err(e) => {
                check_error(label, &e);
                return Ok(());
            }
        };
        check_case(&c);
        let table = registry::variants();
        for s in &c.scenes {
            let Ok(plan) = rigid_plan::scene_plan(&c, s) else { continue };
            for (i, how) in &variants {
                let v = i.get(table);
                if registry::scene_na_reason(v, &plan.setup.body).is_some() {
                    continue;
                }
                let ladder = plan.ladders.for_method(&v.info);
                let mut setup = plan.setup.clone();
                let value = match how {
                    Pick::Ladder => ladder.first().copied(),
                    Pick::Direct(f) if v.info.adaptive => Some(f.min(0.5)),
                    Pick::Direct(f) => Some(setup.grid.t_end * f),
                    Pick::Horizon(t) => {
                        // As `run --t-end` does: only a horizon the score grid divides.
                        if mbdbench::run::divides(*t, setup.grid.score_every).is_none() {
                            continue;
                        }
                        setup.grid.t_end = *t;
                        ladder.first().copied()
                    }
                    Pick::Final => {
                        setup.observe = Observe::Final;
                        ladder.first().copied()
                    }
                };
                let Some(value) = value else { continue };
                run_checked(v, &setup, value, plan.energy_scale, &plan.primary_metric)
                    .map_err(TestCaseError::fail)?;
            }
        }
    }

    /// The whole suite on a random case (a few variants, `--t-end` mode so that no
    /// reference is needed) writes a summary and series files that read back whole, and
    /// leaves no temporary file behind.
    #[test]
    fn suite_on_random_physics_writes_complete_files(
        p in phys(),
        param in prop::sample::select(registry::PARAMS),
        integrators in prop::collection::vec(prop::sample::select(registry::INTEGRATORS), 1..=2),
        quick in any::<bool>(),
        jobs in 1usize..=2,
    ) {
        let Ok(c) = case::load_str("cases/fuzz.toml", &p.toml()) else { return Ok(()) };
        let Ok(plans) = rigid_plan::plans(std::slice::from_ref(&c), &[], &[]) else { return Ok(()) };
        let out = common::temp_dir("fuzz-suite");
        let opts = RunOptions {
            quick,
            jobs,
            out: out.clone(),
            t_end: Some(c.scenes[0].t_end),
            references: PathBuf::from("/nonexistent"),
            progress: false,
            repeats: 0,
            serial_timing: false,
        };
        let filter = VariantFilter {
            param: vec![param.to_string()],
            integrator: integrators.iter().map(|s| s.to_string()).collect(),
            formulation: vec![],
        };
        // A horizon the other scenes' grids do not divide is refused by the CLI.
        if plans
            .iter()
            .any(|p| mbdbench::run::divides(c.scenes[0].t_end, p.setup.grid.score_every).is_none())
        {
            return Ok(());
        }
        let Ok(problems) = plan::problems(std::slice::from_ref(&c), &[], &[]) else { return Ok(()) };
        let s = timed("suite", || suite::run_catalogue(problems, &filter, &opts))
            .map_err(TestCaseError::fail)?;
        let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
        let back: mbdbench::summary::Summary = serde_json::from_str(&text).unwrap();
        prop_assert_eq!(back.records.len(), s.records.len());
        for r in &back.records {
            if let Some(rel) = &r.series {
                let t = std::fs::read_to_string(out.join(rel)).unwrap();
                let _: mbdbench::summary::Series = serde_json::from_str(&t).unwrap();
            }
        }
        prop_assert!(temp_files(&out).is_empty(), "{:?}", temp_files(&out));
        let _ = std::fs::remove_dir_all(&out);
    }
}

/// Files under `dir` that look like leftovers of an interrupted atomic write.
fn temp_files(dir: &Path) -> Vec<PathBuf> {
    all_files(dir)
        .into_iter()
        .filter(|p| {
            p.extension()
                .and_then(|x| x.to_str())
                .is_some_and(|x| x.starts_with("tmp"))
        })
        .collect()
}

/// Every file under `dir`.
fn all_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = vec![];
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(rd) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in rd.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else {
                out.push(p);
            }
        }
    }
    out
}

/// Limits of the run loop when a case gives none (the work limit of a `--t-end` run).
#[test]
fn default_limits_are_finite() {
    let l = Limits::default();
    assert!(l.max_steps > 0 && l.max_steps < u64::MAX);
    assert!(l.max_rhs_evals > 0 && l.max_rhs_evals < u64::MAX);
}

// ---------------------------------------------------------------------------------------
// The binary

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_mbdbench"))
}

/// Runs the binary, killing it (and failing) past `PROCESS_DEADLINE`.
fn run_bin(args: &[&str]) -> Output {
    let mut child = bin()
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        if t0.elapsed() > PROCESS_DEADLINE {
            let _ = child.kill();
            let o = child.wait_with_output().unwrap();
            panic!(
                "mbdbench {args:?} hung ({:?}); stderr: {}",
                PROCESS_DEADLINE,
                String::from_utf8_lossy(&o.stderr)
            );
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A fresh, unique temporary folder (proptest runs many cases per test process).
fn fresh_dir(tag: &str) -> PathBuf {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static N: AtomicUsize = AtomicUsize::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    common::temp_dir(&format!("{tag}-{n}"))
}

proptest! {
    #![proptest_config(config(32))]

    /// `mbdbench run` on a mutated case file exits 2 naming the file and the key and writes
    /// nothing when the file is bad (as `case::load_dir` reports it); otherwise it runs (or
    /// refuses a stale reference, exit 2, writing nothing) and leaves only complete files.
    #[test]
    fn binary_bad_case_file_exits_2_and_writes_nothing(
        which in 0usize..4,
        muts in prop::collection::vec(mutation(), 1..=3),
    ) {
        let (label, text) = case::embedded_sources()[which];
        let file = Path::new(label).file_name().unwrap().to_str().unwrap();
        let stem = file.trim_end_matches(".toml");
        let mut t = text.to_string();
        for m in &muts {
            t = apply(&t, m);
        }
        let dir = fresh_dir("fuzz-bin");
        std::fs::write(dir.join(file), &t).unwrap();
        let out = dir.join("out");
        let expected = case::load_dir(&dir);
        let o = run_bin(&[
            "run", "--quick", "--cases", dir.to_str().unwrap(), "--out", out.to_str().unwrap(),
            "--case", stem, "--param", "so3", "--integrator", "rk4", "--integrator", "dopri5",
            "--formulation", "body",
        ]);
        let e = stderr(&o);
        match expected {
            Err(err) => {
                prop_assert_eq!(o.status.code(), Some(2), "{}", e);
                prop_assert!(e.contains(&err.to_string()), "expected `{}` in `{}`", err, e);
                prop_assert!(all_files(&out).is_empty(), "wrote {:?}", all_files(&out));
            }
            Ok(_) => match o.status.code() {
                Some(0) => {
                    let s = std::fs::read_to_string(out.join("summary.json")).unwrap();
                    let _: mbdbench::summary::Summary = serde_json::from_str(&s).unwrap();
                    prop_assert!(temp_files(&out).is_empty());
                }
                Some(2) => {
                    prop_assert!(e.contains(file) || e.contains("references"), "{}", e);
                    prop_assert!(all_files(&out).is_empty(), "wrote {:?}", all_files(&out));
                }
                c => prop_assert!(false, "exit {:?}: {}", c, e),
            },
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// `mbdbench trajectory` with hostile step, tolerance and horizon arguments exits 2 and
    /// writes nothing, or exits 0 or 1 having written the whole trajectory file; it never
    /// crashes or hangs.
    #[test]
    fn binary_trajectory_hostile_arguments(
        integ in prop::sample::select(&["rk4", "euler", "gauss6", "dop853", "simo_wong"][..]),
        value in prop_oneof![
            Just("0.01".to_string()), Just("0.001".to_string()), Just("1e-8".to_string()),
            value(),
        ],
        t_end in prop::option::of(prop_oneof![
            prop::sample::select(&["3.2", "0.01", "1e-9", "1e9", "1e13", "1e300", "nan",
                "-1", "0", "inf"][..]).prop_map(str::to_string),
            value(),
        ]),
    ) {
        let dir = fresh_dir("fuzz-traj");
        let f = dir.join("t.json");
        let flag = if integ.starts_with("dop") { "--tol" } else { "--dt" };
        let mut args = vec![
            "trajectory", "--case", "gimbal_lock", "--scene", "spin_d1e-2", "--param", "so3",
            "--integrator", integ, flag, value.as_str(), "--out", f.to_str().unwrap(),
        ];
        if let Some(t) = &t_end {
            args.extend(["--t-end", t.as_str()]);
        }
        let o = run_bin(&args);
        let e = stderr(&o);
        match o.status.code() {
            Some(2) => prop_assert!(all_files(&dir).is_empty(), "{}: wrote {:?}", e,
                all_files(&dir)),
            Some(c @ (0 | 1)) => {
                let doc: serde_json::Value =
                    serde_json::from_slice(&std::fs::read(&f).unwrap()).unwrap();
                prop_assert_eq!(doc["status"] == "failed", c == 1, "{}", doc["status"]);
                prop_assert!(temp_files(&dir).is_empty());
            }
            c => prop_assert!(false, "exit {:?}: {}", c, e),
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// An output whose final rename fails (the target is a folder) leaves neither a partial
/// target nor the temporary file, and a completed write leaves exactly the target.
#[test]
fn write_atomic_is_all_or_nothing() {
    let dir = fresh_dir("fuzz-atomic");
    let target = dir.join("summary.json");
    std::fs::create_dir_all(&target).unwrap();
    assert!(mbdbench::reference::write_atomic(&target, b"{}").is_err());
    assert!(target.is_dir());
    assert_eq!(all_files(&dir), Vec::<PathBuf>::new());
    let ok = dir.join("sub").join("x.json");
    mbdbench::reference::write_atomic(&ok, b"[1]").unwrap();
    assert_eq!(std::fs::read(&ok).unwrap(), b"[1]");
    assert_eq!(all_files(&dir), vec![ok]);
    // A parent that is a file: an error, nothing written.
    let blocked = dir.join("sub").join("x.json").join("y.json");
    assert!(mbdbench::reference::write_atomic(&blocked, b"{}").is_err());
    assert_eq!(all_files(&dir).len(), 1);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `mbdbench run` whose summary cannot be put in place (its path is a folder) fails with
/// exit 2 naming the path and leaves no temporary file; no `summary.json` appears.
#[test]
fn binary_unwritable_summary_leaves_no_partial_file() {
    let dir = fresh_dir("fuzz-unwritable");
    let out = dir.join("out");
    std::fs::create_dir_all(out.join("summary.json")).unwrap();
    let o = run_bin(&[
        "run",
        "--quick",
        "--case",
        "gimbal_lock",
        "--scene",
        "spin_d0",
        "--param",
        "so3",
        "--integrator",
        "rk4",
        "--formulation",
        "body",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("summary.json"), "{}", stderr(&o));
    assert!(out.join("summary.json").is_dir());
    assert!(temp_files(&out).is_empty(), "{:?}", temp_files(&out));
    let _ = std::fs::remove_dir_all(&dir);
}
