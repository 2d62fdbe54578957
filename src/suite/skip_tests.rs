//! The ladder's stopping rules on a real scene (`gimbal_lock/tumble`, whose exact reference
//! claims 7.9e-10 in rotation) with records made up to put each rule on either side of its
//! line.
use super::*;
use crate::problem::Variant;
use crate::summary::{Record, RunKey};

fn scene() -> Box<dyn Problem> {
    let cases = crate::catalogue::embedded().unwrap();
    let c = cases.iter().find(|c| c.name == "gimbal_lock").unwrap();
    let family = crate::catalogue::family_of(c);
    let mut p = (family.compile)(c, c.scene("tumble").unwrap()).unwrap();
    p.attach_reference(&crate::cli::default_references())
        .unwrap();
    p
}

fn variant(p: &dyn Problem, integrator: &str) -> &'static Variant {
    p.family().find("quat", integrator, "body").unwrap()
}

/// An `ok` record at step `dt` with primary error `e` and `steps` steps.
fn point(p: &dyn Problem, v: &Variant, dt: f64, e: f64) -> Record {
    let mut r = Record::new(
        RunKey::new(p.case(), p.scene(), v.param, v.integrator, v.formulation),
        "",
    );
    r.status = Status::Ok;
    r.set_stepping(v.stepping(dt));
    r.metrics.insert(p.primary_metric().to_string(), Some(e));
    r.stats.steps = crate::case::steps_dividing(p.t_end(), dt).unwrap();
    r.stats.rhs_evals = 4 * r.stats.steps;
    r
}

const NO_COST: Rules = Rules {
    cap_s: f64::INFINITY,
    cost: None,
};

fn refs(rs: &[Record]) -> Vec<&Record> {
    rs.iter().collect()
}

/// Rule 1: a coarser point at or below the reference's claim stops the ladder; one just above
/// it does not.
#[test]
fn the_reference_floor_stops_a_ladder() {
    let p = scene();
    let p = &*p;
    let v = variant(p, "rk4");
    let claim = p
        .accuracy_claim_for(p.primary_metric(), v.formulation)
        .unwrap();
    assert!(claim > 1e-12 && claim < 1e-8, "{claim}");
    let below = point(p, v, 1e-2, claim);
    let why = reason(p, v, 5e-3, &[&below], &NO_COST).expect("stopped at the floor");
    assert!(
        why.contains("accuracy claim") && why.contains("dt = 1e-2"),
        "{why}"
    );
    let above = point(p, v, 1e-2, 1.5 * claim);
    assert_eq!(reason(p, v, 5e-3, &[&above], &NO_COST), None);
}

/// Rule 2: three points of a first-order method inside the fit window whose error halves with
/// the step stop the ladder; a slope off by more than the slack, a point outside the window,
/// a failed point or a method of higher order do not.
#[test]
fn an_established_first_order_stops_a_ladder() {
    let p = scene();
    let p = &*p;
    let euler = variant(p, "euler");
    assert_eq!(euler.info.order, 1);
    let mk = |errs: [f64; 3], v: &Variant| -> Vec<Record> {
        [1e-3, 5e-4, 2.5e-4]
            .iter()
            .zip(errs)
            .map(|(&dt, e)| point(p, v, dt, e))
            .collect()
    };
    let halving = mk([4e-3, 2e-3, 1e-3], euler);
    let why = reason(p, euler, 1.25e-4, &refs(&halving), &NO_COST).expect("order 1 shown");
    assert!(why.contains("order 1 is established"), "{why}");
    // Local slope log2(4e-3 / 1.8e-3) = 1.15: not as predicted.
    let off = mk([4e-3, 1.8e-3, 0.9e-3], euler);
    assert_eq!(reason(p, euler, 1.25e-4, &refs(&off), &NO_COST), None);
    let outside = mk([4e-2, 2e-2, 1e-2], euler);
    assert_eq!(reason(p, euler, 1.25e-4, &refs(&outside), &NO_COST), None);
    let mut failed = mk([4e-3, 2e-3, 1e-3], euler);
    failed[2].status = Status::Failed;
    assert_eq!(reason(p, euler, 1.25e-4, &refs(&failed), &NO_COST), None);
    let rk4 = variant(p, "rk4");
    let halving4 = mk([4e-3, 2e-3, 1e-3], rk4);
    assert_eq!(reason(p, rk4, 1.25e-4, &refs(&halving4), &NO_COST), None);
}

/// Rule 3: the point's time predicted from the previous point's work (its steps scaled to
/// the point's `T / dt`) over the cap stops the ladder, under it does not; a ladder's first
/// point is never stopped by cost.
#[test]
fn the_cost_cap_stops_a_ladder() {
    let p = scene();
    let p = &*p;
    let v = variant(p, "rk4");
    let key = crate::cost::variant_key(v.param, v.integrator, v.formulation);
    let coef = crate::cost::Coefficients {
        ns_per_step: 0.0,
        ns_per_rhs: 0.0,
        ns_per_newton: 0.0,
        ns_per_element: 0.0,
        runs: 1,
        log_error_median: 0.0,
        log_error_p90: 0.0,
    };
    let table = crate::cost::CostTable {
        schema: 1,
        git_commit: String::new(),
        cpu: String::new(),
        families: vec![crate::cost::FamilyCost {
            family: p.family().model.into(),
            pooled: coef,
            scenes: vec![crate::cost::SceneCost {
                case: p.case().into(),
                scene: p.scene().into(),
                c: coef,
                // 1 ms a step.
                variants: [(key, 1e6)].into_iter().collect(),
            }],
        }],
    };
    let model = table.for_scene(p.family().model, p.case(), p.scene());
    let rules = |cap_s| Rules { cap_s, cost: model };
    let prev = point(p, v, 1e-3, 1e-3);
    // 1 ms a step over the point's T / dt steps.
    let predicted = 1e-3 * crate::case::steps_dividing(p.t_end(), 5e-4).unwrap() as f64;
    let why = reason(p, v, 5e-4, &[&prev], &rules(0.9 * predicted)).expect("over the cap");
    assert!(
        why.contains(&format!("predicted {predicted:.1} s")),
        "{why}"
    );
    assert_eq!(reason(p, v, 5e-4, &[&prev], &rules(1.1 * predicted)), None);
    assert_eq!(reason(p, v, 1e-3, &[], &rules(1e-9)), None);
}

/// A gate's `where` names exactly the points the gate expands to: the flexible beam's
/// flexsat gates name `gauss6` at 5e-2 s but not at 2.5e-2 s, and the spin-up's name
/// `modal_stiffened` at 2.5e-2 s but not at 5e-2 s (while every point of `modal_linear` there).
#[test]
fn gated_points_are_the_gates_points() {
    let cases = crate::catalogue::embedded().unwrap();
    let c = cases.iter().find(|c| c.name == "flexible_beam").unwrap();
    let family = crate::catalogue::family_of(c);
    let flexsat = (family.compile)(c, c.scene("flexsat").unwrap()).unwrap();
    let spinup = (family.compile)(c, c.scene("spinup_w4").unwrap()).unwrap();
    let v = family.find("none", "gauss6", "modal_linear").unwrap();
    assert!(flexsat.gated(v, 5e-2));
    assert!(!flexsat.gated(v, 2.5e-2));
    assert!(spinup.gated(v, 5e-2) && spinup.gated(v, 1.234e-3));
    let stiffened = family.find("none", "gauss6", "modal_stiffened").unwrap();
    assert!(spinup.gated(stiffened, 2.5e-2));
    assert!(!spinup.gated(stiffened, 5e-2));
}
