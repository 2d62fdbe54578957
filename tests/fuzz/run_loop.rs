//! The run-loop layer: generated, valid-looking cases with random, extreme physics and small
//! work limits, planned and run in-process with random registered variants. Checks that every
//! run ends with a result or a typed failure within its work limit and its grid, identically
//! twice, scores without panicking, and that the whole suite on such a case writes complete
//! files and leaves no temporary file.
use std::path::PathBuf;
use std::time::Instant;

use mbdbench::integrate::{FailureKind, Limits};
use mbdbench::model::rigid_body::Observation;
use mbdbench::model::rigid_body::plan as rigid_plan;
use mbdbench::model::rigid_body::registry::{self, RigidSetup};
use mbdbench::model::rigid_body::score::{self, ScoreContext};
use mbdbench::run::{Observe, RunOutput};
use mbdbench::selection::VariantFilter;
use mbdbench::suite::{self, RunOptions};
use proptest::prelude::*;
use proptest::sample::Index;

use crate::mutate::{Mutation, apply, lit, value};
use crate::parser::{check_case, check_error};
use crate::{RUN_DEADLINE, common, config, temp_files};

/// A run's output respects its limits and its grid.
fn check_output(out: &RunOutput<Observation>, setup: &RigidSetup, adaptive: bool, what: &str) {
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
fn fingerprint(out: &RunOutput<Observation>) -> String {
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
    setup: &RigidSetup,
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
        let c = match mbdbench::catalogue::load_str(label, &text) {
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
                run_checked(v, &setup, value, plan.energy_scale, &plan.header.primary_metric)
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
        let Ok(c) = mbdbench::catalogue::load_str("cases/fuzz.toml", &p.toml()) else { return Ok(()) };
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
            cases: vec![],
            scenes: vec![],
            base: None,
            skip: true,
            cap_s: mbdbench::suite::skip::DEFAULT_CAP_S,
            cost: mbdbench::cost::CostTable::embedded(),
            catalogue: mbdbench::catalogue::Catalogue::builtin(),
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
        let Ok(problems) = mbdbench::catalogue::problems(std::slice::from_ref(&c), &[], &[]) else { return Ok(()) };
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

/// Limits of the run loop when a case gives none (the work limit of a `--t-end` run).
#[test]
fn default_limits_are_finite() {
    let l = Limits::default();
    assert!(l.max_steps > 0 && l.max_steps < u64::MAX);
    assert!(l.max_rhs_evals > 0 && l.max_rhs_evals < u64::MAX);
}
