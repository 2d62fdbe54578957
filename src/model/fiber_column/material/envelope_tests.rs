//! Tests of the materials' shapes: monotonic envelopes and first unloading branches against
//! their closed forms (Kent-Scott-Park, Karsan-Jirsa, Yassin, bilinear, Menegotto-Pinto),
//! and the returned tangent against one-sided differences of the stress inside each branch.
use super::test_support::*;
use super::*;

/// Asserts |a − b| ≤ tol with a message naming the point.
fn close(a: f64, b: f64, tol: f64, what: &str) {
    assert!((a - b).abs() <= tol, "{what}: {a:e} vs {b:e} (tol {tol:e})");
}

/// Kent-Scott-Park envelope of Concrete01 / Concrete02 in closed form.
fn ksp(strain: f64, fpc: f64, epsc0: f64, fpcu: f64, epscu: f64) -> f64 {
    let eta = strain / epsc0;
    if strain >= epsc0 {
        fpc * (2.0 * eta - eta * eta)
    } else if strain >= epscu {
        fpc + (fpcu - fpc) * (strain - epsc0) / (epscu - epsc0)
    } else {
        fpcu
    }
}

#[test]
fn concrete01_monotonic_compression_is_kent_scott_park() {
    // Invariant: monotonic compression follows 2η − η², the line to f_cu at ε_cu, then flat.
    for p in [CORE_C01, COVER_C01] {
        let mut m = Material::from(Concrete01::new(p).unwrap());
        for (e, s) in drive(&mut m, &path(&[-0.03], 600)) {
            let want = ksp(e, p.fpc, p.epsc0, p.fpcu, p.epscu);
            close(s, want, 1e-9 * p.fpc.abs(), &format!("ε = {e}"));
        }
    }
}

#[test]
fn concrete01_tension_and_unloading_follow_karsan_jirsa() {
    // Invariant: no tension; unloading from ε_min is the line to ε_p = ε_c0(0.145η² + 0.13η).
    let p = CORE_C01;
    let mut m = Material::from(Concrete01::new(p).unwrap());
    for (e, s) in drive(&mut m, &path(&[0.002], 20)) {
        assert_eq!(s, 0.0, "tension at ε = {e}");
    }
    let mut m = Material::from(Concrete01::new(p).unwrap());
    drive(&mut m, &path(&[-0.006], 60));
    let sig_m = ksp(-0.006, p.fpc, p.epsc0, p.fpcu, p.epscu);
    let eta = 1.5;
    let eps_p = p.epsc0 * (0.145 * eta * eta + 0.13 * eta);
    let slope = sig_m / (-0.006 - eps_p);
    assert!(slope < 2.0 * p.fpc / p.epsc0, "secant below E_c0 here");
    for k in 1..=40 {
        let e = -0.006 + k as f64 * 1e-4;
        let (s, t) = m.set_trial_strain(e);
        let want = if e < eps_p { slope * (e - eps_p) } else { 0.0 };
        close(s, want, 1e-6, &format!("unloading at ε = {e}"));
        if e < eps_p - 1e-12 {
            close(t, slope, 1e-3, "unloading slope");
        }
    }
    // Reloading runs back up the same line (no separate reloading curve).
    m.set_trial_strain(-0.003);
    m.commit();
    let (s, _) = m.set_trial_strain(-0.005);
    close(
        s,
        slope * (-0.005 - eps_p),
        1e-6,
        "reloading on the unloading line",
    );
}

#[test]
fn concrete02_monotonic_envelopes_in_closed_form() {
    // Invariant: compression is Kent-Scott-Park, tension E_c ε then f_t − E_ts(ε − f_t/E_c), then 0.
    for p in [CORE_C02, COVER_C02] {
        let ec = 2.0 * p.fpc / p.epsc0;
        let mut m = Material::from(Concrete02::new(p).unwrap());
        for (e, s) in drive(&mut m, &path(&[-0.03], 600)) {
            let want = ksp(e, p.fpc, p.epsc0, p.fpcu, p.epscu);
            close(s, want, 1e-9 * p.fpc.abs(), &format!("compression ε = {e}"));
        }
        let mut m = Material::from(Concrete02::new(p).unwrap());
        let e_t = p.ft / ec;
        let e_tu = p.ft / p.ets + e_t;
        for (e, s) in drive(&mut m, &path(&[0.003], 600)) {
            let want = if e <= e_t {
                ec * e
            } else if e <= e_tu {
                p.ft - p.ets * (e - e_t)
            } else {
                0.0
            };
            close(s, want, 1e-9 * p.ft, &format!("tension ε = {e}"));
        }
    }
}

#[test]
fn concrete02_unloading_follows_yassins_lines() {
    // Invariant: from the envelope the stress drops with E_c0 to E_r(ε − ε_pt)/2, then follows it.
    let p = CORE_C02;
    let ec = 2.0 * p.fpc / p.epsc0;
    let mut m = Material::from(Concrete02::new(p).unwrap());
    let e_min = -0.003;
    drive(&mut m, &path(&[e_min], 30));
    let sig_m = ksp(e_min, p.fpc, p.epsc0, p.fpcu, p.epscu);
    let eps_r = (p.fpcu - p.lambda * ec * p.epscu) / (ec * (1.0 - p.lambda));
    let e_r = (sig_m - ec * eps_r) / (e_min - eps_r);
    let eps_pt = e_min - sig_m / e_r;
    for k in 1..=40 {
        let e = e_min + k as f64 * 1e-4;
        let (s, _) = m.set_trial_strain(e);
        let want = if e <= eps_pt {
            (sig_m + ec * (e - e_min)).min(0.5 * e_r * (e - eps_pt))
        } else {
            let (ft, ets) = (p.ft, p.ets);
            let x = e - eps_pt;
            if x <= ft / ec {
                ec * x
            } else {
                (ft - ets * (x - ft / ec)).max(0.0)
            }
        };
        close(s, want, 1e-6, &format!("unloading (one trial) at ε = {e}"));
    }
    // Reloading from ε_pt in one step runs along E_r back to the envelope point.
    m.set_trial_strain(eps_pt);
    m.commit();
    let (s, t) = m.set_trial_strain(0.5 * (eps_pt + e_min));
    close(
        s,
        sig_m + e_r * (0.5 * (eps_pt + e_min) - e_min),
        1e-6,
        "reload",
    );
    close(t, e_r, 1e-3, "reload slope");
}

#[test]
fn steel01_monotonic_is_bilinear_and_unloads_elastically() {
    // Invariant: σ = E0 ε up to f_y, then f_y + b E0 (ε − ε_y); unloading elastic to the
    // opposite asymptote −f_y + b E0 (ε + ε_y).
    let p = STEEL01;
    let ey = p.fy / p.e0;
    let esh = p.b * p.e0;
    for sign in [1.0, -1.0] {
        let mut m = Material::from(Steel01::new(p).unwrap());
        for (e, s) in drive(&mut m, &path(&[sign * 0.03], 300)) {
            let want = if e.abs() <= ey {
                p.e0 * e
            } else {
                sign * p.fy + esh * (e - sign * ey)
            };
            close(s, want, 1e-9 * p.fy, &format!("ε = {e}"));
        }
    }
    let mut m = Material::from(Steel01::new(p).unwrap());
    drive(&mut m, &path(&[0.01], 100));
    let s1 = p.fy + esh * (0.01 - ey);
    let down: Vec<f64> = (1..=200).map(|k| 0.01 - k as f64 * 1e-4).collect();
    for (e, s) in drive(&mut m, &down) {
        let want = (s1 + p.e0 * (e - 0.01)).max(-p.fy + esh * (e + ey));
        close(s, want, 1e-9 * p.fy, &format!("reversal ε = {e}"));
    }
}

#[test]
fn steel02_first_loading_is_menegotto_pinto() {
    // Invariant: first loading is σ/f_y = b ε* + (1 − b) ε*/(1 + |ε*|^R0)^(1/R0), ε* = ε/ε_y.
    let p = STEEL02;
    let ey = p.fy / p.e0;
    for sign in [1.0, -1.0] {
        let mut m = Material::from(Steel02::new(p).unwrap());
        for (e, s) in drive(&mut m, &path(&[sign * 0.03], 600)) {
            let x = e / ey;
            let curve = p.b * x + (1.0 - p.b) * x / (1.0 + x.abs().powf(p.r0)).powf(1.0 / p.r0);
            close(s, p.fy * curve, 1e-9 * p.fy, &format!("ε = {e}"));
        }
    }
}

#[test]
fn steel02_first_reversal_is_menegotto_pinto_with_degraded_r() {
    // Invariant: after a reversal at (ε_r, σ_r) the branch is the Menegotto-Pinto curve toward
    // the elastic/asymptote intersection, with R = R0 (1 − cR1 ξ/(cR2 + ξ)).
    let p = STEEL02;
    let (ey, esh) = (p.fy / p.e0, p.b * p.e0);
    let mut m = Material::from(Steel02::new(p).unwrap());
    let pts = drive(&mut m, &path(&[0.01], 100));
    let (er, sr) = *pts.last().unwrap();
    let e0 = (-p.fy + esh * ey - sr + p.e0 * er) / (p.e0 - esh);
    let s0 = -p.fy + esh * (e0 + ey);
    let xi = ((-ey - e0) / ey).abs();
    let r = p.r0 * (1.0 - p.c_r1 * xi / (p.c_r2 + xi));
    for k in 1..=60 {
        let e = er - k as f64 * 4e-4;
        let (s, _) = m.set_trial_strain(e);
        let x = (e - er) / (e0 - er);
        let curve = p.b * x + (1.0 - p.b) * x / (1.0 + x.abs().powf(r)).powf(1.0 / r);
        close(s, sr + (s0 - sr) * curve, 1e-9 * p.fy, &format!("ε = {e}"));
    }
}

#[test]
fn elastic_is_linear() {
    // Invariant: σ = E ε with tangent E, whatever the history.
    let mut m = Material::from(Elastic::new(ElasticParams { e: 30e9 }).unwrap());
    for (e, s) in drive(&mut m, &path(&[0.01, -0.02, 0.005], 50)) {
        assert_eq!(s, 30e9 * e);
        assert_eq!(m.tangent(), 30e9);
    }
}

#[test]
fn tangents_are_consistent_inside_branches() {
    // Invariant: the returned tangent is d stress / d strain along the trial branch: it equals
    // both one-sided differences where they agree and one of them at a branch point.
    for (name, mut m, history) in case_histories() {
        let scale = m.initial_tangent();
        let tol = 1e-6 * scale;
        let h = 1e-10;
        let (mut checked, mut at_kinks) = (0, 0);
        for &committed in &history {
            m.set_trial_strain(committed);
            m.commit();
            for offset in [-7e-4, -2.3e-4, -3.1e-5, 2.9e-5, 2.1e-4, 6.7e-4] {
                let x = committed + offset;
                let (s, t) = m.set_trial_strain(x);
                let ahead = (m.set_trial_strain(x + h).0 - s) / h;
                let behind = (s - m.set_trial_strain(x - h).0) / h;
                let what = format!("{name}: committed ε = {committed}, trial ε = {x}");
                if (ahead - behind).abs() <= tol {
                    close(t, 0.5 * (ahead + behind), tol, &what);
                    checked += 1;
                } else {
                    let gap = (t - ahead).abs().min((t - behind).abs());
                    assert!(gap <= tol, "{what}: {t:e} vs {ahead:e} / {behind:e}");
                    at_kinks += 1;
                }
            }
            m.revert_to_last_commit();
        }
        assert!(
            checked > 500,
            "{name}: only {checked} smooth points checked"
        );
        assert!(
            at_kinks * 20 < checked,
            "{name}: {at_kinks} kinks, {checked} smooth"
        );
    }
}
