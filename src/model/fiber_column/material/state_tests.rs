//! Tests of the state machinery and the energies: trial / commit / revert, work and
//! recoverable energy (closed elastic cycles, steel hysteresis loops against their areas
//! computed independently, non-negative dissipation), and the constructors' refusals.
use super::test_support::*;
use super::*;

#[test]
fn material_is_plain_data() {
    // Invariant: a fiber's material is Copy, Send and Sync (a section is a plain array).
    fn plain<T: Copy + Send + Sync + std::fmt::Debug + 'static>() {}
    plain::<Material>();
    assert!(std::mem::size_of::<Material>() <= 256);
}

#[test]
fn revert_restores_the_committed_state_exactly() {
    // Invariant: after any trials, revert_to_last_commit gives back the committed strain,
    // stress, tangent and work bit for bit.
    for (name, mut m, history) in case_histories() {
        for &e in &history {
            m.set_trial_strain(e);
            m.commit();
            let (strain, stress, tangent, work) = (m.strain(), m.stress(), m.tangent(), m.work());
            let energy = m.recoverable_energy();
            for trial in [e + 3e-3, e - 5e-3, 0.0, e + 1e-5, -0.02] {
                m.set_trial_strain(trial);
            }
            m.revert_to_last_commit();
            let what = format!("{name} at ε = {e}");
            assert_eq!(m.strain().to_bits(), strain.to_bits(), "{what}");
            assert_eq!(m.stress().to_bits(), stress.to_bits(), "{what}");
            assert_eq!(m.tangent().to_bits(), tangent.to_bits(), "{what}");
            assert_eq!(m.work().to_bits(), work.to_bits(), "{what}");
            assert_eq!(m.recoverable_energy().to_bits(), energy.to_bits(), "{what}");
        }
    }
}

#[test]
fn a_trial_depends_only_on_the_committed_state() {
    // Invariant: set_trial_strain(x) after other trials equals set_trial_strain(x) on a fresh
    // copy of the committed material, including a trial back at the committed strain.
    for (name, mut m, history) in case_histories() {
        for &e in &history {
            m.set_trial_strain(e);
            m.commit();
            let fresh = m;
            for x in [e - 4e-3, e + 2e-3, e, e + 1e-4, e - 1e-4] {
                let mut reference = fresh;
                let want = reference.set_trial_strain(x);
                for noise in [e + 0.01, e - 0.01, e + 1e-6] {
                    m.set_trial_strain(noise);
                }
                let got = m.set_trial_strain(x);
                let what = format!("{name}: committed {e}, trial {x}");
                assert_eq!(got.0.to_bits(), want.0.to_bits(), "{what}");
                assert_eq!(got.1.to_bits(), want.1.to_bits(), "{what}");
                assert_eq!(m, reference, "{what}");
            }
            m.set_trial_strain(e);
            assert_eq!(
                m.stress().to_bits(),
                fresh.stress().to_bits(),
                "{name} at {e}"
            );
        }
    }
}

#[test]
fn work_is_the_trapezoid_sum_and_matches_an_uncommitted_trial() {
    // Invariant: work() = committed trapezoid sum + the trial increment's trapezoid.
    for (name, mut m, history) in case_histories() {
        let (mut sum, mut prev) = (0.0, (0.0, 0.0));
        for &e in &history {
            let (s, _) = m.set_trial_strain(e);
            let expected = sum + 0.5 * (prev.1 + s) * (e - prev.0);
            let tol = 1e-12 * (1.0 + expected.abs());
            assert!((m.work() - expected).abs() <= tol, "{name} trial at {e}");
            m.commit();
            sum = expected;
            prev = (e, s);
        }
    }
}

#[test]
fn closed_elastic_cycles_dissipate_nothing() {
    // Invariant: a closed cycle inside an elastic range returns all the work: dissipated ≈ 0
    // at every point of it and work ≈ 0 at its end.
    let elastic = Material::from(Elastic::new(ElasticParams { e: 200e9 }).unwrap());
    let steel01 = Material::from(Steel01::new(STEEL01).unwrap());
    let c02 = Material::from(Concrete02::new(CORE_C02).unwrap());
    let cases = [
        (elastic, path(&[0.01, -0.01, 0.0], 100)),
        (steel01, path(&[0.002, -0.002, 0.0], 100)),
        (c02, path(&[1.5e-4, 0.0], 50)),
    ];
    for (mut m, strains) in cases {
        let scale = 0.5 * m.initial_tangent() * 0.01f64.powi(2);
        for &e in &strains {
            m.set_trial_strain(e);
            m.commit();
            assert!(m.dissipated().abs() <= 1e-12 * scale, "{m:?} at {e}");
        }
        assert!(m.work().abs() <= 1e-12 * scale);
    }
}

#[test]
fn dissipation_never_decreases_below_zero() {
    // Invariant: along every case history dissipated = work − recoverable stays ≥ 0 (up to the
    // trapezoid rule's error on curved branches, bounded here by 1e-3 of the peak work).
    for (name, mut m, history) in case_histories() {
        let mut peak = 0.0f64;
        let mut lowest = 0.0f64;
        for &e in &history {
            m.set_trial_strain(e);
            m.commit();
            peak = peak.max(m.work().abs());
            lowest = lowest.min(m.dissipated());
        }
        assert!(
            lowest >= -1e-3 * peak,
            "{name}: dissipated down to {lowest:e} of {peak:e}"
        );
    }
}

/// Unloads `m` from its committed state in committed steps of `h` toward zero stress and
/// returns the work given back until the stress reaches zero (the last step's zero crossing
/// located by linear interpolation).
fn unload_to_zero(m: &mut Material, h: f64) -> f64 {
    let start = m.work();
    let step = -h * m.stress().signum();
    let (mut e, mut s, mut w) = (m.strain(), m.stress(), m.work());
    loop {
        let (s_next, _) = m.set_trial_strain(e + step);
        if s_next == 0.0 || s_next.signum() != s.signum() {
            let e_zero = e + step * s / (s - s_next);
            return start - (w + 0.5 * s * (e_zero - e));
        }
        m.commit();
        (e, s, w) = (e + step, s_next, m.work());
    }
}

#[test]
fn recoverable_energy_is_the_work_returned_by_unloading() {
    // Invariant: unloading to zero stress gives back recoverable_energy() (exactly on the
    // piecewise-linear unloading branches; Steel02's σ²/(2 E0) is a lower bound of the work
    // its softening Menegotto-Pinto unloading returns).
    let elastic = Material::from(Elastic::new(ElasticParams { e: 200e9 }).unwrap());
    let c01 = Material::from(Concrete01::new(CORE_C01).unwrap());
    let c02 = Material::from(Concrete02::new(CORE_C02).unwrap());
    let cover02 = Material::from(Concrete02::new(COVER_C02).unwrap());
    let s01 = Material::from(Steel01::new(STEEL01).unwrap());
    let s02 = Material::from(Steel02::new(STEEL02).unwrap());
    let cases = [
        (elastic, vec![0.002]),
        (s01, vec![0.01]),
        (s01, vec![0.01, -0.004]),
        (c01, vec![-0.003]),
        (c01, vec![-0.006]),
        (c01, vec![-0.02, -0.01]),
        (c02, vec![-0.003]),
        (c02, vec![-0.01]),
        (c02, vec![-0.003, -0.0028]),
        (c02, vec![-0.003, 0.0, -0.001]),
        (c02, vec![0.0005]),
        (cover02, vec![-0.004, 0.0006]),
    ];
    for (mut m, targets) in cases {
        drive(&mut m, &path(&targets, 400));
        let (name, recoverable) = (format!("{m:?}"), m.recoverable_energy());
        assert!(recoverable > 0.0, "{name}");
        let returned = unload_to_zero(&mut m, 1e-8);
        assert!(
            (returned - recoverable).abs() <= 1e-8 * recoverable,
            "{name}: returned {returned:e} vs recoverable {recoverable:e}"
        );
    }
    let mut m = s02;
    drive(&mut m, &path(&[0.01], 400));
    let recoverable = m.recoverable_energy();
    let returned = unload_to_zero(&mut m, 1e-8);
    assert!(
        recoverable <= returned && returned < 1.2 * recoverable,
        "{returned:e} vs {recoverable:e}"
    );
}

/// Shoelace area of a closed polygon.
fn polygon_area(pts: &[(f64, f64)]) -> f64 {
    let n = pts.len();
    (0..n)
        .map(|i| {
            let (a, b) = (pts[i], pts[(i + 1) % n]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum::<f64>()
        .abs()
        / 2.0
}

#[test]
fn steel01_loop_dissipates_the_parallelogram_area() {
    // Invariant: a symmetric cycle ±ε_a of Steel01 dissipates the area of its parallelogram
    // (elastic sides E0, hardening sides b E0), computed here from the vertices.
    let p = STEEL01;
    let (ey, esh) = (p.fy / p.e0, p.b * p.e0);
    let ea = 0.012;
    let sa = p.fy + esh * (ea - ey);
    // Elastic unloading from (ea, sa) meets −f_y + E_sh (ε + ε_y) at ε_b.
    let eb = (sa - p.e0 * ea + p.fy - esh * ey) / (esh - p.e0);
    let sb = sa + p.e0 * (eb - ea);
    let area = polygon_area(&[(ea, sa), (eb, sb), (-ea, -sa), (-eb, -sb)]);
    let mut m = Material::from(Steel01::new(p).unwrap());
    drive(&mut m, &path(&[ea], 100));
    let (w0, r0) = (m.work(), m.recoverable_energy());
    let n = 2000;
    let cycle: Vec<f64> = (1..=2 * n)
        .map(|k| ea * (std::f64::consts::PI * k as f64 / n as f64).cos())
        .collect();
    drive(&mut m, &cycle);
    assert!((m.stress() - sa).abs() < 1e-6 * p.fy, "the loop closes");
    let dissipated = (m.work() - w0) - (m.recoverable_energy() - r0);
    assert!(
        (dissipated - area).abs() <= 1e-5 * area,
        "{dissipated:e} vs {area:e}"
    );
}

/// Menegotto-Pinto branch from (er, sr) toward the asymptote intersection, as a closure
/// of ε, with the degraded R of ξ = |(ε_pl − ε_0)/ε_y|.
fn mp_branch(p: Steel02Params, er: f64, sr: f64, up: bool, eps_pl: f64) -> impl Fn(f64) -> f64 {
    let (ey, esh) = (p.fy / p.e0, p.b * p.e0);
    let sign = if up { 1.0 } else { -1.0 };
    let e0 = (sign * p.fy - sign * esh * ey - sr + p.e0 * er) / (p.e0 - esh);
    let s0 = sign * p.fy + esh * (e0 - sign * ey);
    let xi = ((eps_pl - e0) / ey).abs();
    let r = p.r0 * (1.0 - p.c_r1 * xi / (p.c_r2 + xi));
    move |e: f64| {
        let x = (e - er) / (e0 - er);
        sr + (s0 - sr) * (p.b * x + (1.0 - p.b) * x / (1.0 + x.abs().powf(r)).powf(1.0 / r))
    }
}

/// Composite Simpson integral of f over [a, b] with n (even) panels.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let inner: f64 = (1..n)
        .map(|i| f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    (f(a) + f(b) + inner) * h / 3.0
}

#[test]
fn steel02_loop_dissipates_the_area_between_its_branches() {
    // Invariant: over a cycle between reversal points the work equals the area between the
    // two Menegotto-Pinto branches (their closed form integrated by Simpson's rule), and the
    // dissipated energy equals that area once the loop has settled (it closes to 1e-3 f_y).
    let p = STEEL02;
    let ea = 0.015;
    let n = 1000;
    let to = |a: f64, b: f64| -> Vec<f64> {
        (1..=n).map(|k| a + (b - a) * k as f64 / n as f64).collect()
    };
    let mut m = Material::from(Steel02::new(p).unwrap());
    // Two cycles to settle the branches, then measure the third.
    drive(&mut m, &path(&[ea, -ea, ea, -ea], 200));
    let sa = m.stress();
    let (w0, r0) = (m.work(), m.recoverable_energy());
    drive(&mut m, &to(-ea, ea));
    let sb = m.stress();
    drive(&mut m, &to(ea, -ea));
    let sc = m.stress();
    let work = m.work() - w0;
    let dissipated = work - (m.recoverable_energy() - r0);
    // The strain memory after the first cycle: ε_max = ε_a, ε_min = −ε_a.
    let up = mp_branch(p, -ea, sa, true, ea);
    let down = mp_branch(p, ea, sb, false, -ea);
    assert!(
        (up(ea) - sb).abs() < 1e-6 * p.fy,
        "the up branch ends at the material's point"
    );
    assert!(
        (down(-ea) - sc).abs() < 1e-6 * p.fy,
        "so does the down branch"
    );
    assert!(
        (sc - sa).abs() < 1e-3 * p.fy,
        "the loop has settled: {sa:e} vs {sc:e}"
    );
    let area = simpson(&up, -ea, ea, 20000) - simpson(&down, -ea, ea, 20000);
    assert!(
        (work - area).abs() <= 1e-5 * area,
        "work {work:e} vs {area:e}"
    );
    assert!(
        (dissipated - area).abs() <= 1e-4 * area,
        "dissipated {dissipated:e} vs {area:e}"
    );
}

/// Checks that `r` is refused with a message containing `needle`, and that the error's key
/// is the parameter the message names (its struct field).
fn bad(r: Result<Material, ParamError>, needle: &str) {
    let e = r.expect_err(needle);
    assert!(e.message.contains(needle), "{e:?} should name {needle}");
    let named = super::opensees_name(e.key);
    assert!(e.message.contains(&format!(" {named} = ")), "{e:?}: key {}", e.key);
}

/// Every out-of-range or non-finite parameter of the concretes is refused with its name and
/// value, and the error's key is the parameter's struct field (the case file's key).
#[test]
fn concrete_constructors_refuse_bad_parameters_by_name() {
    let c01 = |p| Concrete01::new(p).map(Material::from);
    bad(
        c01(Concrete01Params {
            fpc: 36e6,
            ..CORE_C01
        }),
        "fpc = 3.6e7",
    );
    bad(
        c01(Concrete01Params {
            epsc0: 0.004,
            ..CORE_C01
        }),
        "epsc0",
    );
    bad(
        c01(Concrete01Params {
            fpcu: 1e6,
            ..CORE_C01
        }),
        "fpcu",
    );
    bad(
        c01(Concrete01Params {
            fpcu: -40e6,
            ..CORE_C01
        }),
        "fpcu",
    );
    bad(
        c01(Concrete01Params {
            epscu: -0.003,
            ..CORE_C01
        }),
        "epscu",
    );
    bad(
        c01(Concrete01Params {
            epscu: f64::NAN,
            ..CORE_C01
        }),
        "epscu = NaN",
    );
    let c02 = |p| Concrete02::new(p).map(Material::from);
    bad(
        c02(Concrete02Params {
            fpc: 0.0,
            ..CORE_C02
        }),
        "fpc",
    );
    bad(
        c02(Concrete02Params {
            epsc0: f64::INFINITY,
            ..CORE_C02
        }),
        "epsc0 = inf",
    );
    bad(
        c02(Concrete02Params {
            fpcu: 2e6,
            ..CORE_C02
        }),
        "fpcu",
    );
    bad(
        c02(Concrete02Params {
            epscu: -0.004,
            ..CORE_C02
        }),
        "epscu",
    );
    bad(
        c02(Concrete02Params {
            lambda: 1.0,
            ..CORE_C02
        }),
        "lambda",
    );
    bad(
        c02(Concrete02Params {
            lambda: -0.1,
            ..CORE_C02
        }),
        "lambda",
    );
    bad(
        c02(Concrete02Params {
            ft: -3e6,
            ..CORE_C02
        }),
        "ft = -3e6",
    );
    bad(
        c02(Concrete02Params {
            ft: 40e6,
            ..CORE_C02
        }),
        "ft = 4e7 must be at most |fpc| = 3.6e7",
    );
    bad(
        c02(Concrete02Params {
            ets: 0.0,
            ..CORE_C02
        }),
        "Ets",
    );
    let strong_residual = Concrete02Params {
        fpcu: -30e6,
        epscu: -0.014,
        ..CORE_C02
    };
    bad(c02(strong_residual), "lambda = 1e-1 must exceed");
}

/// Every out-of-range or non-finite parameter of the steels and of the elastic material is
/// refused with its name and value, and the error's key is the parameter's struct field.
#[test]
fn steel_and_elastic_constructors_refuse_bad_parameters_by_name() {
    let s01 = |p| Steel01::new(p).map(Material::from);
    bad(
        s01(Steel01Params {
            fy: -420e6,
            ..STEEL01
        }),
        "Steel01: fy = -4.2e8",
    );
    bad(s01(Steel01Params { e0: 0.0, ..STEEL01 }), "E0");
    bad(s01(Steel01Params { b: 1.0, ..STEEL01 }), "b = 1e0");
    bad(
        s01(Steel01Params {
            b: -0.01,
            ..STEEL01
        }),
        "b",
    );
    let s02 = |p| Steel02::new(p).map(Material::from);
    bad(
        s02(Steel02Params {
            fy: f64::NAN,
            ..STEEL02
        }),
        "fy = NaN",
    );
    bad(
        s02(Steel02Params {
            e0: -1.0,
            ..STEEL02
        }),
        "E0",
    );
    bad(s02(Steel02Params { b: 2.0, ..STEEL02 }), "b");
    bad(s02(Steel02Params { r0: 0.0, ..STEEL02 }), "R0");
    bad(
        s02(Steel02Params {
            c_r1: 0.0,
            ..STEEL02
        }),
        "cR1",
    );
    bad(
        s02(Steel02Params {
            c_r1: 1.0,
            ..STEEL02
        }),
        "cR1",
    );
    bad(
        s02(Steel02Params {
            c_r2: -0.15,
            ..STEEL02
        }),
        "cR2",
    );
    bad(
        Elastic::new(ElasticParams { e: 0.0 }).map(Material::from),
        "E = 0e0",
    );
    bad(
        Elastic::new(ElasticParams { e: f64::NAN }).map(Material::from),
        "E = NaN",
    );
}
