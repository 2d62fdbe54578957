//! Tests of the rigid body's step search (`search.rs`): the score indices, the step and
//! tolerance searches on synthetic verdicts, and the on-the-fly reference against the stored one.
use super::*;
use crate::integrate::FailureKind;
use crate::stability::steps::RESOLUTION;
use crate::math::so3;

fn fail(n: f64) -> Verdict {
    Verdict::Fail(Limit {
        kind: FailureKind::NonFinite,
        t: n,
        message: "synthetic".into(),
    })
}

/// The score indices are strictly ascending inside (0, n), one per score time (every step
/// below `SCORE_POINTS` steps).
#[test]
fn score_indices_cover_the_horizon() {
    for n in [1u64, 2, 20, 199, 200, 201, 1000, 20_971_520] {
        let at = score_indices(n);
        assert!(at.windows(2).all(|w| w[0] < w[1]), "n = {n}");
        assert!(at.iter().all(|&k| k > 0 && k < n), "n = {n}");
        assert_eq!(at.len() as u64, SCORE_POINTS.min(n) - 1, "n = {n}");
    }
}

/// The step search finds the boundary of a monotone verdict to 5 % from the passing side,
/// reports the failure just beyond it, flags a passing cap, and gives None when nothing
/// passes within the budget.
#[test]
fn step_search_brackets_the_boundary() {
    let f = search_steps(
        CAP_STEPS,
        CAP_STEPS,
        1 << 20,
        |n| {
            if n >= 1377 {
                Verdict::Pass
            } else {
                fail(n as f64)
            }
        },
        10.0,
    );
    let n = f.n.unwrap();
    assert!(
        (1377..(1377.0 * RESOLUTION) as u64 + 1).contains(&n),
        "{f:?}"
    );
    assert_eq!(f.value, Some(10.0 / n as f64));
    let (_, limit) = f.limit.clone().unwrap();
    assert!(
        limit.t < 1377.0 && limit.t * RESOLUTION >= n as f64,
        "{f:?}"
    );
    assert!(f.reason(10.0).starts_with("limited by non_finite"));
    let capped = search_steps(CAP_STEPS, CAP_STEPS, 1 << 20, |_| Verdict::Pass, 10.0);
    assert!(capped.capped && capped.n == Some(CAP_STEPS));
    assert!(capped.reason(10.0).starts_with("bounded up to the cap"));
    let none = search_steps(CAP_STEPS, CAP_STEPS, 640, |n| fail(n as f64), 10.0);
    assert_eq!(none.value, None);
    assert!(
        none.reason(10.0).contains("nothing passed"),
        "{}",
        none.reason(10.0)
    );
    let err = search_steps(
        CAP_STEPS,
        CAP_STEPS,
        640,
        |_| Verdict::Error("broken".into()),
        10.0,
    );
    assert_eq!(err.value, None);
    assert!(err.reason(10.0).contains("broken"));
}

/// The tolerance search finds the largest passing tolerance to 5 %.
#[test]
fn tol_search_brackets_the_boundary() {
    let f = search_tol(TOL_CAP, |tol| {
        if tol <= 3e-5 {
            Verdict::Pass
        } else {
            fail(tol)
        }
    });
    let tol = f.value.unwrap();
    assert!(tol <= 3e-5 && tol * RESOLUTION > 3e-5, "{f:?}");
    let capped = search_tol(TOL_CAP, |_| Verdict::Pass);
    assert!(capped.capped && capped.value == Some(TOL_CAP));
}

/// The on-the-fly reference (dop853/so3/body at 1e-12, Hermite-interpolated) agrees with
/// the stored, cross-checked reference of nine_spring/two_angles over its 10 s to 1e-8 rad,
/// far below the 0.1 rad bound it judges.
#[test]
fn on_the_fly_reference_matches_the_stored_one() {
    let cases = crate::catalogue::embedded().unwrap();
    let c = cases.iter().find(|c| c.name == "nine_spring").unwrap();
    let plan =
        crate::model::rigid_body::plan::scene_plan(c, c.scene("two_angles").unwrap()).unwrap();
    let scene = StudyScene::new(c, &plan).unwrap().unwrap();
    assert!(scene.horizon > 10.0);
    let stored = crate::model::rigid_body::reference::load(
        &crate::cli::default_references(),
        "nine_spring",
        "two_angles",
        &plan.header.inputs_sha256,
    )
    .unwrap()
    .reference;
    let otf = OnTheFly::default();
    let mut worst = 0.0_f64;
    for (k, t) in stored.t.iter().enumerate() {
        let q = stored.quaternion[k];
        let qr = nalgebra::UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(
            q[0], q[1], q[2], q[3],
        ));
        worst = worst.max(so3::geodesic_quat(
            &otf.rotation_at(&scene, *t).unwrap(),
            &qr,
        ));
    }
    assert!(worst < 1e-8, "on-the-fly vs stored: {worst:e} rad");
}

/// Between two reference points the Hermite interpolant of a uniform spin is exact to
/// the interpolation order: error below 1e-10 at w dt = 1e-2.
#[test]
fn hermite_interpolates_a_spin() {
    use crate::model::rigid_body::Observation;
    let w = nalgebra::Vector3::new(0.3, -0.5, 0.8);
    let at = |t: f64| Sample {
        t,
        obs: Observation {
            q: crate::math::so3::exp_quat(&(w * t)),
            x: nalgebra::Vector3::zeros(),
            v: nalgebra::Vector3::zeros(),
            omega: w,
        },
        conditioning: 1.0,
        residual: None,
    };
    let h = 1e-2 / w.norm();
    let (a, b) = (at(0.0), at(h));
    for s in [0.1, 0.37, 0.5, 0.9] {
        let got = hermite(&a, &b, s * h);
        let e = so3::geodesic_quat(&got, &at(s * h).obs.q);
        assert!(e < 1e-10, "s = {s}: {e:e}");
    }
}
