//! Tests of the recommendation on small hand-made summaries: the ranking rules (cheapest on
//! every non-control scene, ties in the family's order, the gap, the accuracy-claim floor of
//! the targets, the wall-time ranking's 10 ms rule) and the avoid list.
use super::*;
use crate::integrate::{Failure, FailureKind, Stats};
use crate::summary::{Env, FitRecord, Record, RunKey, Status, Wall};

/// A run of `param/integrator/body` on `scene` at step `dt` with primary error `err` (None:
/// failed with `singular_chart`), `rhs` evaluations and median wall time `wall` s.
fn rec(
    scene: &str,
    param: &str,
    integ: &str,
    dt: f64,
    err: Option<f64>,
    rhs: u64,
    wall: f64,
) -> Record {
    let key = RunKey {
        case: "c".into(),
        scene: scene.into(),
        param: param.into(),
        integrator: integ.into(),
        formulation: "body".into(),
    };
    let mut r = Record::new(key, "-");
    r.dt = Some(dt);
    let failure = err
        .is_none()
        .then(|| Failure::new(FailureKind::SingularChart, 1.0, "x"));
    r.take_run(
        Stats {
            rhs_evals: rhs,
            steps: rhs,
            ..Stats::default()
        },
        failure,
    );
    if let Some(e) = err {
        r.metrics.insert("rotation_error_max".into(), Some(e));
        r.metrics.insert("energy_drift_max".into(), Some(1e-6));
        r.metrics.insert("conditioning_min".into(), Some(1.0));
        r.wall_s = Some(Wall {
            min: wall,
            median: wall,
        });
    }
    r
}

fn summary(records: Vec<Record>) -> Summary {
    Summary {
        schema: 1,
        git_commit: "-".into(),
        created_utc: "-".into(),
        env: Env::current(1, None),
        records,
        fits: vec![],
        selection: None,
        methods: None,
        families: None,
    }
}

fn spec(claim: f64) -> CaseSpec {
    let scene = |name: &str, control: bool| SceneSpec {
        name: name.into(),
        control,
        claim: Some(claim),
        reference_variant: None,
    };
    CaseSpec {
        case: "c".into(),
        metric: "rotation_error_max".into(),
        unit: "rad".into(),
        targets: vec![1e-3, 1e-6, 1e-9],
        max_energy_drift: 1e-3,
        claim_margin: super::CLAIM_MARGIN,
        claim_name: "accuracy claim",
        scenes: vec![scene("a", false), scene("b", false), scene("ctl", true)],
    }
}

/// The winner is the variant whose cheapest points reaching the target on every non-control
/// scene cost least in sum; a variant that fails on one scene is out however cheap it is
/// elsewhere; the control scene neither helps nor hurts; runner-up and gap follow.
#[test]
fn cheapest_on_every_scene() {
    let s = summary(vec![
        // so3/rk4: 1e-3 at 100 + 100; 1e-6 at 1000 + 1000.
        rec("a", "so3", "rk4", 1e-2, Some(1e-4), 100, 0.02),
        rec("a", "so3", "rk4", 1e-3, Some(1e-7), 1000, 0.2),
        rec("b", "so3", "rk4", 1e-2, Some(5e-4), 100, 0.02),
        rec("b", "so3", "rk4", 1e-3, Some(5e-7), 1000, 0.2),
        // quat/rk4: cheaper on a, dearer on b (1e-3: 50 + 300 = 350).
        rec("a", "quat", "rk4", 1e-2, Some(1e-4), 50, 0.01),
        rec("b", "quat", "rk4", 1e-2, Some(2e-3), 100, 0.02),
        rec("b", "quat", "rk4", 5e-3, Some(1e-4), 300, 0.05),
        // euler_xyz/rk4: cheapest on a and the control, fails on b.
        rec("a", "euler_xyz", "rk4", 1e-2, Some(1e-9), 10, 0.001),
        rec("b", "euler_xyz", "rk4", 1e-2, None, 5, 0.0),
        rec("ctl", "euler_xyz", "rk4", 1e-2, Some(0.0), 1, 0.0),
    ]);
    let a = advise(&s, &[spec(1e-12)], &Options::default());
    let c = &a.cases[0];
    assert_eq!(c.scenes, ["a", "b"]);
    assert_eq!(c.controls, ["ctl"]);
    let t3 = &c.targets[0];
    let w = t3.winner.as_ref().unwrap();
    assert_eq!(w.name(), "so3/rk4/body");
    assert_eq!(w.cost, 200);
    assert_eq!(w.settings["a"], Setting::Dt(1e-2));
    assert_eq!(t3.runner_up.as_ref().unwrap().name(), "quat/rk4/body");
    assert_eq!(t3.gap, Some(350.0 / 200.0));
    // Every chosen run of the winner took 20 ms: ranked by wall time too (quat: 0.06 s).
    assert_eq!(t3.by_time.as_ref().unwrap().name(), "so3/rk4/body");
    // 1e-6: only so3 reaches it on both scenes (quat never does on a, euler fails on b).
    let t6 = &c.targets[1];
    assert_eq!(t6.winner.as_ref().unwrap().cost, 2000);
    assert!(t6.runner_up.is_none() && t6.gap.is_none());
    // 1e-9: nobody.
    assert!(c.targets[2].winner.is_none());
    assert!(
        c.targets[2]
            .note
            .as_ref()
            .unwrap()
            .contains("no variant reaches")
    );
    // The failure is listed to avoid, with its scene and kind.
    assert!(c.avoid.iter().any(|v| v.param == "euler_xyz"
        && v.scene == "b"
        && v.reason.starts_with("singular_chart at 1 of its 1")));
}

/// Ties go to the earlier variant in the family's order, whatever the records' order.
#[test]
fn ties_follow_the_family_order() {
    let s = summary(vec![
        rec("a", "quat", "rk4", 1e-2, Some(1e-4), 100, 0.02),
        rec("b", "quat", "rk4", 1e-2, Some(1e-4), 100, 0.02),
        rec("a", "so3", "rk4", 1e-2, Some(1e-4), 100, 0.02),
        rec("b", "so3", "rk4", 1e-2, Some(1e-4), 100, 0.02),
    ]);
    let a = advise(&s, &[spec(0.0)], &Options::default());
    let t = &a.cases[0].targets[0];
    let order = |p: &str| crate::catalogue::variant_order(p, "rk4", "body");
    let first = if order("quat") < order("so3") {
        "quat"
    } else {
        "so3"
    };
    assert_eq!(t.winner.as_ref().unwrap().param, first);
    assert_eq!(t.gap, Some(1.0));
}

/// A target below 100x a scene's accuracy claim is not offered (and says why); a run of the
/// winner at or under 10 ms leaves out the wall-time ranking, saying so.
#[test]
fn claim_floor_and_short_runs() {
    let s = summary(vec![
        rec("a", "so3", "rk4", 1e-2, Some(1e-10), 100, 0.005),
        rec("b", "so3", "rk4", 1e-2, Some(1e-10), 100, 0.02),
    ]);
    let a = advise(&s, &[spec(1e-10)], &Options::default());
    let c = &a.cases[0];
    assert_eq!(c.targets.len(), 2);
    assert_eq!(c.skipped_targets.len(), 1);
    assert_eq!(c.skipped_targets[0].target, 1e-9);
    assert!(c.skipped_targets[0].reason.contains("accuracy claim"));
    assert!(c.targets[0].by_time.is_none());
    assert!(c.targets[0].note.as_ref().unwrap().contains("wall time"));
}

/// Conditioning below 1e-3 lists the chart (once per scene, at its lowest); an energy drift
/// above the case's bound at the finest completed point lists the variant.
#[test]
fn avoid_conditioning_and_drift() {
    let mut r1 = rec("a", "euler_xyz", "rk4", 1e-2, Some(1e-4), 100, 0.02);
    r1.metrics.insert("conditioning_min".into(), Some(1e-5));
    let mut r2 = rec("a", "euler_xyz", "dopri5", 1e-2, Some(1e-4), 100, 0.02);
    r2.metrics.insert("conditioning_min".into(), Some(1e-7));
    let mut r3 = rec("b", "so3", "euler", 1e-2, Some(1e-2), 100, 0.02);
    r3.metrics.insert("energy_drift_max".into(), Some(0.5));
    let mut r4 = rec("b", "so3", "euler", 1e-3, Some(1e-3), 1000, 0.2);
    r4.metrics.insert("energy_drift_max".into(), Some(2e-3));
    let a = advise(
        &summary(vec![r1, r2, r3, r4]),
        &[spec(0.0)],
        &Options::default(),
    );
    let avoid = &a.cases[0].avoid;
    let chart: Vec<&Avoid> = avoid.iter().filter(|v| v.integrator.is_none()).collect();
    assert_eq!(chart.len(), 1);
    assert!(chart[0].reason.contains("1.0e-7"), "{}", chart[0].reason);
    let drift: Vec<&Avoid> = avoid
        .iter()
        .filter(|v| v.reason.contains("drift"))
        .collect();
    assert_eq!(drift.len(), 1);
    assert!(drift[0].reason.contains("2.0e-3") && drift[0].reason.contains("dt = 1e-3"));
}

/// The failure kinds' names are those the files write.
#[test]
fn failure_kind_names_match_the_files() {
    for k in FailureKind::ALL {
        assert_eq!(serde_json::to_value(k).unwrap(), k.name());
    }
}

/// A status other than ok never wins: an `n/a` record with a small error is ignored.
#[test]
fn only_completed_runs_count() {
    let mut na = rec("a", "quat", "rk4", 1e-2, Some(1e-9), 1, 0.02);
    na.status = Status::NotApplicable;
    let s = summary(vec![
        na,
        rec("b", "quat", "rk4", 1e-2, Some(1e-9), 1, 0.02),
        rec("a", "so3", "rk4", 1e-2, Some(1e-4), 100, 0.02),
        rec("b", "so3", "rk4", 1e-2, Some(1e-4), 100, 0.02),
    ]);
    let a = advise(&s, &[spec(0.0)], &Options::default());
    assert_eq!(a.cases[0].targets[0].winner.as_ref().unwrap().param, "so3");
}

/// An order fit whose local slopes spread by more than 1 lists its variant ("not
/// asymptotic"); a clean fit, a fit without an order and a fit on a control scene do not.
#[test]
fn avoid_non_asymptotic_fits() {
    let fit = |scene: &str, integ: &str, order: Option<f64>, pts: Vec<[f64; 2]>| FitRecord {
        key: RunKey::new("c", scene, "so3", integ, "body"),
        metric: "rotation_error_max".into(),
        order,
        reason: None,
        points: pts,
    };
    let mut s = summary(vec![
        rec("a", "so3", "rk4", 1e-2, Some(1e-4), 100, 0.02),
        rec("b", "so3", "rk4", 1e-2, Some(1e-4), 100, 0.02),
    ]);
    s.fits = vec![
        // Slopes 4 and 1: straddles a change of regime.
        fit(
            "a",
            "rk4",
            Some(2.4),
            vec![[1e-3, 1e-12], [1e-2, 1e-8], [1e-1, 1e-7]],
        ),
        // Slopes 4.0 and 4.0.
        fit(
            "a",
            "gauss6",
            Some(4.0),
            vec![[1e-3, 1e-12], [1e-2, 1e-8], [1e-1, 1e-4]],
        ),
        fit(
            "a",
            "dopri5",
            None,
            vec![[1e-3, 1e-12], [1e-2, 1e-8], [1e-1, 1e-7]],
        ),
        fit(
            "ctl",
            "rk4",
            Some(2.4),
            vec![[1e-3, 1e-12], [1e-2, 1e-8], [1e-1, 1e-7]],
        ),
    ];
    let a = advise(&s, &[spec(0.0)], &Options::default());
    let fits: Vec<&Avoid> = a.cases[0]
        .avoid
        .iter()
        .filter(|v| v.reason.contains("not asymptotic"))
        .collect();
    assert_eq!(fits.len(), 1, "{fits:?}");
    assert_eq!(fits[0].integrator.as_deref(), Some("rk4"));
    assert_eq!(fits[0].scene, "a");
    assert!(
        fits[0].reason.contains("1.00 to 4.00"),
        "{}",
        fits[0].reason
    );
}

/// Variants whose ranking cost lies within `TIE_REL` of the winner's are a tie with it, in
/// cost order, and the text says "tie" and names them all; one just outside is the
/// runner-up only; with `--by time` the tie is decided by wall time, not work.
#[test]
fn close_costs_are_a_tie() {
    let s = summary(vec![
        // so3: 200; quat: 208 (4 % dearer); euler_xyz: 211 (5.5 % dearer).
        rec("a", "so3", "rk4", 1e-2, Some(1e-4), 100, 0.10),
        rec("b", "so3", "rk4", 1e-2, Some(1e-4), 100, 0.10),
        rec("a", "quat", "rk4", 1e-2, Some(1e-4), 104, 0.30),
        rec("b", "quat", "rk4", 1e-2, Some(1e-4), 104, 0.30),
        rec("a", "euler_xyz", "rk4", 1e-2, Some(1e-4), 105, 0.20),
        rec("b", "euler_xyz", "rk4", 1e-2, Some(1e-4), 106, 0.20),
    ]);
    let a = advise(&s, &[spec(1e-12)], &Options::default());
    let t = &a.cases[0].targets[0];
    assert_eq!(t.winner.as_ref().unwrap().name(), "so3/rk4/body");
    let tied: Vec<String> = t.tie.iter().map(|p| p.name()).collect();
    assert_eq!(tied, ["quat/rk4/body"]);
    assert_eq!(t.runner_up.as_ref().unwrap().name(), "quat/rk4/body");
    let text = text::render(&a);
    assert!(text.contains("tie: so3/rk4/body"), "{text}");
    assert!(
        text.contains("tied within 5 %: quat/rk4/body (cost 208, x1.04)"),
        "{text}"
    );
    assert!(!text.contains("runner-up"), "{text}");
    let json = serde_json::to_value(&a).unwrap();
    assert_eq!(json["cases"][0]["targets"][0]["tie"][0]["param"], "quat");
    // By wall time (0.2 s, 0.4 s, 0.6 s): so3 stands alone.
    let by_time = Options {
        by: By::Time,
        ..Options::default()
    };
    let a = advise(&s, &[spec(1e-12)], &by_time);
    let t = &a.cases[0].targets[0];
    assert!(t.tie.is_empty(), "{:?}", t.tie);
    assert!(text::render(&a).contains("runner-up euler_xyz/rk4/body x2.00"));
}
