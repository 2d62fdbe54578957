//! The fastest linearised mode of a rigid-body scene: the time scale the stability study
//! measures its horizon in (`t_h` = `[stability].periods`, 20 in the catalogue, periods of the
//! fastest mode).
//!
//! Two candidates, the larger frequency wins:
//! - the elastic modes of the force field linearised about the reference configuration
//!   `x = 0, R = I` (where `nine_spring`'s springs are exactly at rest, cases/README.md,
//!   `nine_spring`): with generalised displacements `q = (dx, dtheta)` (world translation, small
//!   world rotation `R = exp([dtheta]x)`), the tangent stiffness `K = -d(f, tau)/dq` is taken by
//!   central differences of `RigidBody::wrench` (step 1e-6: relative error ~1e-10, far below what a
//!   horizon needs), symmetrised, and the modes solve `K v = w^2 M v`, `M = diag(m I, J)` (`J`
//!   about the reference point; the translational block only when the body translates), via
//!   `L^-1 K L^-T` with `M = L L^T` (Cholesky) and a symmetric eigen-decomposition; negative
//!   eigenvalues (an unstable equilibrium, e.g. an inverted pendulum) carry no period and are
//!   ignored;
//! - the initial body rotation rate `|omega(0)|` (a free or spinning body: one turn is the
//!   fastest motion a torque-free rigid body has; the heavy top's spin).
//!
//! Where it fails: a body with neither springs at rest nor rotation (no time scale) gets
//! `None`; a preloaded spring field is linearised with its preload (geometric stiffness) at
//! `x = 0, R = I`, which need not be an equilibrium.
use nalgebra::{Matrix3, Matrix6, SymmetricEigen, Vector3, Vector6};

use super::{Observation, RigidBody};
use crate::math::so3;

/// Central-difference step of the tangent stiffness (m, rad).
const H: f64 = 1e-6;

/// The angular frequencies (rad/s) of the linearised elastic modes about `x = 0, R = I`,
/// ascending; empty when the body has no springs and no configuration-dependent gravity
/// torque.
pub fn elastic_frequencies(body: &RigidBody) -> Vec<f64> {
    let translates = body.translates();
    let gravity_torque = body.gravity.is_some() && body.pivot_com.is_some();
    if body.springs.is_empty() && !gravity_torque {
        return vec![];
    }
    let wrench_at = |q: &Vector6<f64>| {
        let x = Vector3::new(q[0], q[1], q[2]);
        let r = so3::exp(&Vector3::new(q[3], q[4], q[5]));
        let (f, tau) = body.wrench(&r, &x);
        Vector6::new(f[0], f[1], f[2], tau[0], tau[1], tau[2])
    };
    let mut k = Matrix6::zeros();
    for j in 0..6 {
        let mut qp = Vector6::zeros();
        qp[j] = H;
        let df = (wrench_at(&qp) - wrench_at(&-qp)) / (2.0 * H);
        k.set_column(j, &-df);
    }
    let k = (k + k.transpose()) * 0.5;
    let mut m = Matrix6::zeros();
    m.fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&(Matrix3::identity() * body.mass));
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(&body.inertia);
    // Without translation the translational rows and columns drop out: keep the rotational
    // block only (the translational one is given unit mass and zero stiffness, frequency 0).
    let (k, m) = if translates {
        (k, m)
    } else {
        let mut kr = Matrix6::zeros();
        let mut mr = Matrix6::identity();
        kr.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&k.fixed_view::<3, 3>(3, 3));
        mr.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&m.fixed_view::<3, 3>(3, 3));
        (kr, mr)
    };
    let Some(chol) = m.cholesky() else {
        return vec![];
    };
    let l_inv = match chol.l().try_inverse() {
        Some(x) => x,
        None => return vec![],
    };
    let a = l_inv * k * l_inv.transpose();
    let eig = SymmetricEigen::new((a + a.transpose()) * 0.5);
    let mut w: Vec<f64> = eig
        .eigenvalues
        .iter()
        .filter(|l| **l > 0.0 && l.is_finite())
        .map(|l| l.sqrt())
        .collect();
    w.sort_by(f64::total_cmp);
    w
}

/// The fastest angular frequency of a scene (rad/s): the larger of the fastest elastic mode
/// and `|omega(0)|`; None when neither exists.
pub fn fastest_frequency(body: &RigidBody, initial: &Observation) -> Option<f64> {
    let elastic = elastic_frequencies(body).last().copied().unwrap_or(0.0);
    let spin = initial.omega.norm();
    let w = elastic.max(spin);
    (w > 0.0 && w.is_finite()).then_some(w)
}

/// The period of the fastest mode (s).
pub fn fastest_period(body: &RigidBody, initial: &Observation) -> Option<f64> {
    fastest_frequency(body, initial).map(|w| std::f64::consts::TAU / w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::rigid_body::Spring;
    use nalgebra::UnitQuaternion;

    fn at_rest() -> Observation {
        Observation {
            q: UnitQuaternion::identity(),
            x: Vector3::zeros(),
            v: Vector3::zeros(),
            omega: Vector3::zeros(),
        }
    }

    fn spring(b: [f64; 3], d: [f64; 3], k: f64) -> Spring {
        let b = Vector3::from(b);
        Spring {
            body_point: b,
            anchor: b + Vector3::from(d),
            stiffness: k,
            rest_length: 1.0,
        }
    }

    /// A point mass on three orthogonal springs through its centre: three translational modes
    /// at sqrt(k/m) and no rotational stiffness.
    #[test]
    fn translational_oscillator() {
        let springs = vec![
            spring([0.0; 3], [1.0, 0.0, 0.0], 400.0),
            spring([0.0; 3], [0.0, 1.0, 0.0], 400.0),
            spring([0.0; 3], [0.0, 0.0, 1.0], 900.0),
        ];
        let body = RigidBody::new(4.0, Matrix3::identity(), springs, None, None).unwrap();
        let w = elastic_frequencies(&body);
        assert_eq!(w.len(), 3);
        for (got, want) in w.iter().zip([10.0, 10.0, 15.0]) {
            assert!((got - want).abs() < 1e-6 * want, "{w:?}");
        }
        let p = fastest_period(&body, &at_rest()).unwrap();
        assert!((p - std::f64::consts::TAU / 15.0).abs() < 1e-9);
    }

    /// A torsional pair: two springs along y at body points +-a x form a couple about z, whose
    /// rotational frequency is sqrt(2 k a^2 / J_zz); the translational y mode is sqrt(2k/m).
    #[test]
    fn rotational_couple() {
        let (k, a, m, jz) = (50.0, 0.5, 2.0, 0.25);
        let springs = vec![
            spring([a, 0.0, 0.0], [0.0, 1.0, 0.0], k),
            spring([-a, 0.0, 0.0], [0.0, 1.0, 0.0], k),
        ];
        let body = RigidBody::new(
            m,
            Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, jz)),
            springs,
            None,
            None,
        )
        .unwrap();
        let w = elastic_frequencies(&body);
        let rot = (2.0 * k * a * a / jz).sqrt();
        let tr = (2.0 * k / m).sqrt();
        for want in [rot, tr] {
            assert!(
                w.iter().any(|x| (x - want).abs() < 1e-6 * want),
                "{want} not in {w:?}"
            );
        }
    }

    /// A free body without springs has no elastic mode: its time scale is its rotation rate,
    /// and a body at rest has none at all.
    #[test]
    fn spin_only_and_none() {
        let body = RigidBody::new(1.0, Matrix3::identity() * 2.0, vec![], None, None).unwrap();
        assert!(elastic_frequencies(&body).is_empty());
        assert_eq!(fastest_frequency(&body, &at_rest()), None);
        let spinning = Observation {
            omega: Vector3::new(3.0, 0.0, 4.0),
            ..at_rest()
        };
        assert_eq!(fastest_frequency(&body, &spinning), Some(5.0));
    }

    /// A pendulum hanging below its pivot has the small-oscillation frequency sqrt(m g l / J_O)
    /// about both horizontal axes (`J_O` the inertia about the pivot).
    #[test]
    fn hanging_pendulum() {
        let (m, g, l) = (3.0, 9.81, 0.8);
        let jc = Matrix3::from_diagonal(&Vector3::new(0.1, 0.1, 0.05));
        let body =
            RigidBody::new(m, jc, vec![], Some(g), Some(Vector3::new(0.0, 0.0, -l))).unwrap();
        let w = elastic_frequencies(&body);
        let want = (m * g * l / (0.1 + m * l * l)).sqrt();
        assert_eq!(w.len(), 2, "{w:?}");
        for x in &w {
            assert!((x - want).abs() < 1e-6 * want, "{w:?} vs {want}");
        }
    }
}
