//! Observed orders of convergence: every fixed-step integrator, every
//! parameterization and both formulations, on `nine_spring/two_angles` and `free_body/gni`,
//! fitted over the ladder points between 100x the reference's accuracy claim and 1e-2.
mod common;

use mbdbench::model::rigid_body::registry;
use mbdbench::summary::{Status, Summary};

fn declared(integrator: &str) -> f64 {
    registry::variants()
        .iter()
        .find(|v| v.integrator == integrator)
        .map(|v| v.info.order as f64)
        .unwrap()
}

/// Checks every fit of a scene; returns the variants checked.
fn check_scene(s: &Summary, scene: &str, exempt: &[(&str, &str)]) -> usize {
    let mut checked = 0;
    let mut bad = vec![];
    for f in s.fits.iter().filter(|f| f.key.scene == scene) {
        let failed = s.records.iter().any(|r| {
            r.key.scene == scene
                && r.key.param == f.key.param
                && r.key.integrator == f.key.integrator
                && r.key.formulation == f.key.formulation
                && r.status == Status::Failed
        });
        if failed {
            continue; // asserted separately (the order claim is for runs that reach t_end)
        }
        if exempt.contains(&(f.key.param.as_str(), f.key.integrator.as_str()))
            || exempt.contains(&("*", f.key.integrator.as_str()))
        {
            continue;
        }
        let p = declared(&f.key.integrator);
        match f.order {
            Some(o) if (o - p).abs() <= 0.25 => checked += 1,
            _ => bad.push(format!(
                "{}/{}/{}: order {:?} (declared {p}), reason {:?}, points {:?}",
                f.key.param, f.key.integrator, f.key.formulation, f.order, f.reason, f.points
            )),
        }
    }
    assert!(
        bad.is_empty(),
        "{scene}: {} fits off:\n{}",
        bad.len(),
        bad.join("\n")
    );
    checked
}

/// On nine_spring/two_angles every fixed-step variant's observed order is within 0.25 of its
/// declared order (RKMK rk4 on so3 included: 4, not the 2 it drops to without dexp_inv).
#[test]
fn orders_on_nine_spring_two_angles() {
    let fixed: Vec<&str> = registry::INTEGRATORS
        .iter()
        .copied()
        .filter(|i| !matches!(*i, "dopri5" | "dop853"))
        .collect();
    let s = common::run(
        "nine_spring",
        &["two_angles"],
        common::filter(&[], &fixed, &[]),
        false,
        None,
        "conv-ns",
    );
    let n = check_scene(&s, "two_angles", &[]);
    // 11 charts x 2 formulations x 4 generic + 3 Lie charts x 2 x 2 Crouch-Grossman + 4 geometric
    // + 5 compensated (implicit_midpoint_kahan, gauss6_kahan on quat and so3; simo_wong_kahan)
    assert_eq!(n, 88 + 12 + 4 + 5, "every fixed-step variant has a fit");
    let rk4_so3 = s
        .fits
        .iter()
        .find(|f| f.key.param == "so3" && f.key.integrator == "rk4" && f.key.formulation == "body")
        .unwrap();
    assert!((rk4_so3.order.unwrap() - 4.0).abs() <= 0.25);
}

/// On free_body/gni every fixed-step variant that reaches t_end has its declared order, except
/// gauss6 (and its compensated twin), which at every step dividing score_every has at most two errors above the
/// reference floor (100x the claim), whose ratio shows order >= 5.75; euler_zxz starts in its
/// singular set and fails with singular_chart at t = 0 for every method.
#[test]
fn orders_on_free_body_gni() {
    let fixed: Vec<&str> = registry::INTEGRATORS
        .iter()
        .copied()
        .filter(|i| !matches!(*i, "dopri5" | "dop853"))
        .collect();
    let s = common::run(
        "free_body",
        &["gni"],
        common::filter(&[], &fixed, &[]),
        false,
        None,
        "conv-gni",
    );
    let n = check_scene(
        &s,
        "gni",
        &[
            ("*", "gauss6"),
            ("*", "gauss6_kahan"),
            ("quat", "euler"),
            ("matrix", "euler"),
        ],
    );
    // quat and matrix with euler: in the spatial formulation their errors stay above 1e-2
    // on the ladder (3e8 steps a run would be needed to enter the window), in the body one
    // they fit normally. Their order is checked from the ratios of successive ladder errors,
    // `log(e_k / e_k+1) / log(h_k / h_k+1)`.
    let plan = &common::plans("free_body", &["gni"])[0];
    let ladder = &plan.ladders.order1;
    assert!(ladder.len() >= 3, "order-1 ladder {ladder:?}");
    for p in ["quat", "matrix"] {
        for form in ["body", "spatial"] {
            let e: Vec<f64> = ladder
                .iter()
                .map(|h| {
                    common::metric(
                        common::get(&s, "gni", p, "euler", form, *h),
                        "rotation_error_max",
                    )
                })
                .collect();
            for (we, wh) in e.windows(2).zip(ladder.windows(2)) {
                let local = (we[0] / we[1]).ln() / (wh[0] / wh[1]).ln();
                assert!(
                    (local - 1.0).abs() <= 0.25,
                    "{p}/euler/{form}: errors {e:?} at {ladder:?}"
                );
            }
        }
    }
    // 9 charts (se3_hq and dual_quat are n/a without translation, euler_zxz fails) x 2 x 3
    // (euler, rk4, implicit_midpoint) + so3 x 2 x 2 Crouch-Grossman + 4 geometric + the
    // compensated implicit_midpoint_kahan (quat, so3) and simo_wong_kahan (gauss6_kahan is
    // exempt like gauss6)
    assert_eq!(n, 8 * 2 * 3 - 4 + 4 + 4 + 3, "fits checked");
    let stored = mbdbench::model::rigid_body::reference::load(
        &mbdbench::cli::default_references(),
        "free_body",
        "gni",
        &plan.header.inputs_sha256,
    )
    .unwrap();
    let floor = 100.0
        * mbdbench::model::rigid_body::reference::claim_for(
            &stored.reference,
            "rotation_error_max",
        );
    // gauss6: at most two ladder points lie above the floor; where two do, their error ratio
    // shows at least order 6 - 0.25, and the fit is null for the stated reason.
    for f in s
        .fits
        .iter()
        .filter(|f| f.key.integrator == "gauss6" && f.key.param != "euler_zxz")
    {
        let e: Vec<f64> = [0.1, 0.05, 0.025]
            .iter()
            .map(|h| {
                common::metric(
                    common::get(&s, "gni", &f.key.param, "gauss6", &f.key.formulation, *h),
                    "rotation_error_max",
                )
            })
            .collect();
        assert!(e.iter().filter(|x| **x >= floor).count() < 3, "{f:?}");
        assert!(f.order.is_none() && f.reason.as_deref().unwrap().contains("lie between"));
        if e[1] >= floor {
            let local = (e[0] / e[1]).log2();
            assert!(
                local >= 5.75,
                "{}/{}: errors {e:?}",
                f.key.param,
                f.key.formulation
            );
        }
    }
    for r in s
        .records
        .iter()
        .filter(|r| r.key.param == "euler_zxz" && r.status != Status::NotApplicable)
    {
        let f = r.failure.as_ref().expect("euler_zxz fails on gni");
        assert_eq!(
            serde_json::to_value(f.kind).unwrap(),
            serde_json::json!("singular_chart")
        );
        assert_eq!(f.t, 0.0);
        assert_eq!(r.stats.rhs_evals, 0, "no garbage integrated");
    }
}

/// Adaptive methods have no step ladder: their error falls as the tolerance tightens while the
/// RHS evaluations grow (error against work, recorded for the work-precision view).
#[test]
fn adaptive_error_against_work() {
    let s = common::run(
        "nine_spring",
        &["two_angles"],
        common::filter(&["so3", "quat_proj"], &["dopri5", "dop853"], &["body"]),
        false,
        None,
        "conv-adaptive",
    );
    for p in ["so3", "quat_proj"] {
        for i in ["dopri5", "dop853"] {
            let e6 = common::get(&s, "two_angles", p, i, "body", 1e-6);
            let e10 = common::get(&s, "two_angles", p, i, "body", 1e-10);
            let (a, b) = (
                common::metric(e6, "rotation_error_max"),
                common::metric(e10, "rotation_error_max"),
            );
            assert!(b < a / 100.0, "{p}/{i}: {a:e} -> {b:e}");
            assert!(e10.stats.rhs_evals > e6.stats.rhs_evals);
        }
    }
}
