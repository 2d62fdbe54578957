//! A hand-written, fixed-size classical RK4 for the nine-spring rigid body with an additive
//! quaternion in the body formulation: the cost baseline the generic machinery is measured
//! against (`benches/step.rs`: the registry's `quat` + `rk4` + `body` should cost no more than
//! 1.5x this loop). State `y = (q[4], x[3], v[3], omega[3])` in one `SVector<f64, 13>`;
//! `q' = q (x) (0, omega)/2`, `x' = v`, `v' = f/m`, `omega' = J^{-1}(R^T tau - omega x J omega)`.
//! It is deliberately independent of `RigidSystem` (only the spring data is shared), so a test
//! also uses it to cross-check the generic code path.
use nalgebra::{Matrix3, Quaternion, SVector, UnitQuaternion, Vector3};

use crate::model::rigid_body::RigidBody;

/// The 13-number state.
pub type Y = SVector<f64, 13>;

/// Right-hand side of the rigid body with springs and gravity (free body).
#[inline(always)]
pub fn rhs(b: &RigidBody, y: &Y) -> Y {
    let q = Quaternion::new(y[0], y[1], y[2], y[3]);
    let x = Vector3::new(y[4], y[5], y[6]);
    let v = Vector3::new(y[7], y[8], y[9]);
    let w = Vector3::new(y[10], y[11], y[12]);
    // Rotation matrix of the (not necessarily unit) quaternion, as the additive chart uses it.
    let r: Matrix3<f64> = UnitQuaternion::new_unchecked(q)
        .to_rotation_matrix()
        .into_inner();
    let mut f = Vector3::zeros();
    let mut tau = Vector3::zeros();
    for s in &b.springs {
        let rb = r * s.body_point;
        let d = s.anchor - (x + rb);
        let l = d.norm();
        let fi = d * (s.stiffness * (l - s.rest_length) / l);
        f += fi;
        tau += rb.cross(&fi);
    }
    if let Some(g) = b.gravity {
        f.z -= b.mass * g;
    }
    let qd = q * Quaternion::new(0.0, w.x, w.y, w.z) * 0.5;
    let a = f / b.mass;
    let wd = b.inertia_inv * (r.transpose() * tau - w.cross(&(b.inertia * w)));
    let mut out = Y::zeros();
    out[0] = qd.w;
    out[1] = qd.i;
    out[2] = qd.j;
    out[3] = qd.k;
    out.fixed_rows_mut::<3>(4).copy_from(&v);
    out.fixed_rows_mut::<3>(7).copy_from(&a);
    out.fixed_rows_mut::<3>(10).copy_from(&wd);
    out
}

/// One classical RK4 step.
#[inline(always)]
pub fn step(b: &RigidBody, y: &mut Y, h: f64) {
    let k1 = rhs(b, y);
    let k2 = rhs(b, &(*y + k1 * (0.5 * h)));
    let k3 = rhs(b, &(*y + k2 * (0.5 * h)));
    let k4 = rhs(b, &(*y + k3 * h));
    *y += (k1 + (k2 + k3) * 2.0 + k4) * (h / 6.0);
}
