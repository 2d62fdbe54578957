//! Tests of the column's static Newton steps against the exact elastica and roll-up, for
//! every nodal rotation chart.
use nalgebra::DVector;

use super::basic::{Basic, DispBased, ForceBased};
use crate::rotation::{MatrixProj, QuatProj, RotVec, RotationChart, So3};
use super::column::Column;
use crate::structural::equilibrium::Newton;
use super::elastica::{elastica_tip, rollup_tip};
use super::section::{ElasticSection, Section};

/// The elastica's column: L = 1, EI = 1, EA = 1e6, GJ = 1, `n` force-based elements with 3
/// Lobatto points (exact for an elastic section).
fn elastic_column<C: RotationChart>(n: usize, force_based: bool) -> Column<C> {
    let s = Section::Elastic(ElasticSection::new(1e6, 1.0, 1.0).unwrap());
    let h = 1.0 / n as f64;
    let els = (0..n)
        .map(|_| {
            if force_based {
                Basic::Force(Box::new(ForceBased::new(h, 1.0, &s, 3, 1e-16, 20).unwrap()))
            } else {
                Basic::Disp(DispBased::new(h, 1.0, &s, 2).unwrap())
            }
        })
        .collect();
    Column::new(1.0, els).unwrap()
}

/// Runs the elastica at `alpha` in `steps` load steps; returns the tip error (|tip - exact|
/// in units of L) at the end and the Newton iterations.
fn elastica_error<C: RotationChart>(n: usize, alpha: f64, steps: usize) -> (f64, usize) {
    let mut col = elastic_column::<C>(n, true);
    let mut f = DVector::zeros(col.dim());
    let mut iterations = 0;
    for k in 1..=steps {
        f[col.top_dof(0)] = alpha * k as f64 / steps as f64;
        let (c, _) = col.step(&mut Newton::new(1e-20, 30).unwrap(), &f, None).unwrap();
        iterations += c.iterations;
    }
    let exact = elastica_tip(alpha).unwrap();
    let u = col.top_displacement();
    let err = ((u.x - exact.across).powi(2) + (1.0 + u.z - exact.along).powi(2)).sqrt();
    (err, iterations)
}

// The elastica's tip with 10 and 40 force-based elements lies within 1.5e-3 L and 1e-4 L of
// the exact Bisshopp-Drucker tip for P L^2/EI = 1, 2, 5, 10 (10 load steps), and the error
// falls with the mesh at order 2 (the basic system's neglected axial-bending coupling).
#[test]
fn elastica_matches_the_exact_tip() {
    for alpha in [1.0, 2.0, 5.0, 10.0] {
        let (e10, _) = elastica_error::<So3>(10, alpha, 10);
        let (e40, _) = elastica_error::<So3>(40, alpha, 10);
        let order = (e10 / e40).ln() / 4f64.ln();
        eprintln!("alpha {alpha}: error 10 el {e10:.3e}, 40 el {e40:.3e}, order {order:.3}");
        assert!(e10 < 1.5e-3 && e40 < 1e-4, "alpha {alpha}: {e10:e} {e40:e}");
        assert!((order - 2.0).abs() < 0.2, "alpha {alpha}: order {order}");
    }
}

// Every chart gives the same elastica (their retractions differ, the equilibrium does not),
// to Newton's tolerance.
#[test]
fn charts_agree_on_the_elastica() {
    let (r, _) = elastica_error::<So3>(10, 5.0, 10);
    for (name, e) in [
        ("quat_proj", elastica_error::<QuatProj>(10, 5.0, 10)),
        ("rotvec", elastica_error::<RotVec>(10, 5.0, 10)),
        ("matrix_proj", elastica_error::<MatrixProj>(10, 5.0, 10)),
    ] {
        assert!((e.0 - r).abs() < 1e-12, "{name}: {} vs {r}", e.0);
    }
}

/// The roll-up with chart `C`: `n` elements, `steps` load steps of the tip moment
/// `lambda 2 pi EI/L`; the largest tip error over the steps (units of L), the final tip's
/// distance from the root and the final unwrapped rotation.
fn rollup<C: RotationChart>(n: usize, steps: usize) -> (f64, f64, f64, usize) {
    let mut col = elastic_column::<C>(n, true);
    let mut f = DVector::zeros(col.dim());
    let mut worst = 0.0f64;
    let mut iterations = 0;
    for k in 1..=steps {
        let lambda = k as f64 / steps as f64;
        f[col.top_dof(4)] = lambda * std::f64::consts::TAU;
        iterations += col
            .step(&mut Newton::new(1e-20, 40).unwrap(), &f, None)
            .unwrap()
            .0
            .iterations;
        let exact = rollup_tip(lambda);
        let u = col.top_displacement();
        let err = ((u.x - exact.across).powi(2) + (1.0 + u.z - exact.along).powi(2)).sqrt();
        worst = worst.max(err);
    }
    let u = col.top_displacement();
    let closed = (u + nalgebra::Vector3::new(0.0, 0.0, 1.0)).norm();
    (worst, closed, col.top_turn(), iterations)
}

// The roll-up closes the column into a circle with every chart: at lambda = 1 the tip is back
// at the root within 1e-8 L and the unwrapped rotation is 2 pi; along the way the tip follows
// the exact arc to O(h^2).
#[test]
fn rollup_closes_with_every_chart() {
    fn check<C: RotationChart>() {
        let (worst, closed, turn, iterations) = rollup::<C>(20, 10);
        eprintln!("{}: {iterations} Newton iterations in 10 steps", C::NAME);
        eprintln!(
            "{}: max tip error {worst:.3e}, closure {closed:.3e}, turn {turn}",
            C::NAME
        );
        assert!(closed < 1e-8, "{}: closure {closed:e}", C::NAME);
        assert!(
            (turn - std::f64::consts::TAU).abs() < 1e-10,
            "{}: {turn}",
            C::NAME
        );
        assert!(worst < 5e-3, "{}: {worst:e}", C::NAME);
    }
    check::<So3>();
    check::<QuatProj>();
    check::<RotVec>();
    check::<MatrixProj>();
}

// A displacement-based element with an elastic section has the same basic stiffness as the
// force-based one, so both give the same elastica.
#[test]
fn disp_based_equals_force_based_when_elastic() {
    let run = |fb: bool| {
        let mut col = elastic_column::<So3>(10, fb);
        let mut f = DVector::zeros(col.dim());
        for k in 1..=10 {
            f[col.top_dof(0)] = 2.0 * k as f64 / 10.0;
            col.step(&mut Newton::new(1e-20, 30).unwrap(), &f, None).unwrap();
        }
        col.top_displacement()
    };
    assert!((run(true) - run(false)).norm() < 1e-12);
}

// The roll-up's largest tip error along the arc (tip_error_max) falls at order 2 with the
// mesh (10 and 40 elements, so3): the nodes of a corotational mesh under a constant moment
// form a regular polygon whose sides are the elements' undeformed length, a chord error of
// O(h^2).
#[test]
fn rollup_tip_error_is_second_order() {
    let (e10, ..) = rollup::<So3>(10, 10);
    let (e40, ..) = rollup::<So3>(40, 10);
    let order = (e10 / e40).ln() / 4f64.ln();
    eprintln!("roll-up tip_error_max: 10 el {e10:.3e}, 40 el {e40:.3e}, order {order:.3}");
    assert!((order - 2.0).abs() < 0.1, "order {order}");
}
