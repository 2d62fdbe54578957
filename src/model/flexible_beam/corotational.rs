//! The planar corotational Euler-Bernoulli beam element (Crisfield, *Non-linear Finite Element
//! Analysis of Solids and Structures*, vol. 1, 1991, ch. 7, its simple co-rotational beam
//! element): large rigid motions of each element are
//! filtered out by a frame that follows its chord, and the deformation left in that frame is
//! small and linear (axial: linear; bending: cubic Hermite).
//!
//! Global element coordinates `p = (x1, y1, theta1, x2, y2, theta2)`: node positions in the
//! frame the element lives in and nodal rotations from the reference orientation. With the
//! chord `(dx, dy) = (x2 - x1, y2 - y1)`, `l = |(dx, dy)|`, its rotation `alpha` from the
//! reference chord angle `beta0`, `c = cos(beta0 + alpha)`, `s = sin(beta0 + alpha)`:
//!
//! ```text
//! u_l = l - l0,   theta1_l = theta1 - alpha,   theta2_l = theta2 - alpha       (local)
//! N = EA u_l / l0,   M1 = EI/l0 (4 theta1_l + 2 theta2_l),   M2 = EI/l0 (2 theta1_l + 4 theta2_l)
//! f = B^T (N, M1, M2),   B = [r^T; e3^T - z^T/l; e6^T - z^T/l]
//! K = B^T K_l B + N z z^T / l + (M1 + M2)(r z^T + z r^T) / l^2
//! r = (-c, -s, 0, c, s, 0),   z = (s, -c, 0, -s, c, 0)
//! ```
//!
//! (the tangent's two last terms are the derivative of `B^T`). Invariants: the strain energy
//! `EA u_l^2/(2 l0) + EI/(2 l0) theta_l^T [4 2; 2 4] theta_l` and the internal force are
//! unchanged by rigid translations and rotations of the element; `K` is the exact derivative
//! of `f` (both tested). The local rotations are wrapped to (-pi, pi], so an element may
//! rotate by any amount as a rigid body. Where it fails: the local strains must stay small
//! (the local law is linear); a local rotation beyond pi is read modulo 2 pi; a zero chord
//! length (`l = 0`) has no frame (`force` then returns a non-finite force).
use nalgebra::{SMatrix, SVector};

/// Element coordinates, forces: `(x1, y1, theta1, x2, y2, theta2)`.
pub type Vec6 = SVector<f64, 6>;
/// Element matrices.
pub type Mat6 = SMatrix<f64, 6, 6>;

/// One element: its reference length, chord angle and section stiffnesses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Element {
    /// Reference length (m).
    pub l0: f64,
    /// Reference chord angle (rad).
    pub beta0: f64,
    /// Axial stiffness (N).
    pub ea: f64,
    /// Bending stiffness (N m^2).
    pub ei: f64,
}

/// The element's state in its local frame at one configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Local {
    /// Current chord length.
    pub l: f64,
    /// Cosine and sine of the current chord angle.
    pub c: f64,
    pub s: f64,
    /// Stretch and the two local end rotations.
    pub u: f64,
    pub theta1: f64,
    pub theta2: f64,
}

/// `a` wrapped to (-pi, pi].
fn wrap(a: f64) -> f64 {
    a.sin().atan2(a.cos())
}

impl Element {
    /// The local state at global coordinates `p`.
    pub fn local(&self, p: &Vec6) -> Local {
        let (dx, dy) = (p[3] - p[0], p[4] - p[1]);
        let l = dx.hypot(dy);
        let (s0, c0) = self.beta0.sin_cos();
        // The chord's rotation from its reference direction, in (-pi, pi].
        let alpha = (c0 * dy - s0 * dx).atan2(c0 * dx + s0 * dy);
        Local {
            l,
            c: dx / l,
            s: dy / l,
            u: l - self.l0,
            theta1: wrap(p[2] - alpha),
            theta2: wrap(p[5] - alpha),
        }
    }

    /// The local forces `(N, M1, M2)` of a local state.
    fn local_forces(&self, lo: &Local) -> (f64, f64, f64) {
        let k = self.ei / self.l0;
        (
            self.ea * lo.u / self.l0,
            k * (4.0 * lo.theta1 + 2.0 * lo.theta2),
            k * (2.0 * lo.theta1 + 4.0 * lo.theta2),
        )
    }

    /// The strain energy at `p` (J).
    pub fn energy(&self, p: &Vec6) -> f64 {
        let lo = self.local(p);
        let k = self.ei / self.l0;
        0.5 * self.ea * lo.u * lo.u / self.l0
            + 0.5
                * k
                * (4.0 * lo.theta1 * lo.theta1
                    + 4.0 * lo.theta1 * lo.theta2
                    + 4.0 * lo.theta2 * lo.theta2)
    }

    /// The internal force `f` at `p` and, when `k` is given, its tangent `df/dp`.
    ///
    /// # Example
    ///
    /// ```
    /// use mbdbench::model::flexible_beam::corotational::{Element, Vec6};
    ///
    /// let e = Element { l0: 1.0, beta0: 0.0, ea: 1e6, ei: 1e3 };
    /// // A rigid rotation by 2 rad about node 1 leaves the element unstressed.
    /// let (s, c) = 2.0f64.sin_cos();
    /// let p = Vec6::new(0.0, 0.0, 2.0, c, s, 2.0);
    /// assert!(e.force(&p, None).norm() < 1e-9);
    /// ```
    pub fn force(&self, p: &Vec6, k: Option<&mut Mat6>) -> Vec6 {
        let lo = self.local(p);
        let (n, m1, m2) = self.local_forces(&lo);
        let (c, s, l) = (lo.c, lo.s, lo.l);
        let r = Vec6::new(-c, -s, 0.0, c, s, 0.0);
        let z = Vec6::new(s, -c, 0.0, -s, c, 0.0);
        let mut b1 = -z / l;
        b1[2] += 1.0;
        let mut b2 = -z / l;
        b2[5] += 1.0;
        let f = r * n + b1 * m1 + b2 * m2;
        if let Some(k) = k {
            let (ka, kb) = (self.ea / self.l0, self.ei / self.l0);
            // B^T K_l B with K_l = diag(EA/l0, EI/l0 [4 2; 2 4]).
            *k = r * r.transpose() * ka
                + (b1 * b1.transpose() * 4.0
                    + (b1 * b2.transpose() + b2 * b1.transpose()) * 2.0
                    + b2 * b2.transpose() * 4.0)
                    * kb
                + z * z.transpose() * (n / l)
                + (r * z.transpose() + z * r.transpose()) * ((m1 + m2) / (l * l));
        }
        f
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn element() -> Element {
        Element {
            l0: 0.5,
            beta0: 0.3,
            ea: 2.8e7,
            ei: 1.4e4,
        }
    }

    /// A deformed configuration of `element()`: nodes moved off the reference chord.
    fn deformed() -> Vec6 {
        let (s0, c0) = 0.3f64.sin_cos();
        Vec6::new(0.01, -0.02, 0.05, 0.5 * c0 + 0.013, 0.5 * s0 + 0.04, 0.11)
    }

    /// The tangent is the derivative of the force (central differences, relative 1e-6).
    #[test]
    fn tangent_is_the_derivative_of_the_force() {
        let e = element();
        let p = deformed();
        let mut k = Mat6::zeros();
        e.force(&p, Some(&mut k));
        let h = 1e-7;
        for j in 0..6 {
            let (mut a, mut b) = (p, p);
            a[j] += h;
            b[j] -= h;
            let col = (e.force(&a, None) - e.force(&b, None)) / (2.0 * h);
            let err = (col - k.column(j)).norm();
            assert!(
                err <= 1e-6 * k.norm(),
                "column {j}: {err:e} of {:e}",
                k.norm()
            );
        }
    }

    /// The force is the gradient of the strain energy (central differences).
    #[test]
    fn force_is_the_gradient_of_the_energy() {
        let e = element();
        let p = deformed();
        let f = e.force(&p, None);
        let h = 1e-7;
        for j in 0..6 {
            let (mut a, mut b) = (p, p);
            a[j] += h;
            b[j] -= h;
            let g = (e.energy(&a) - e.energy(&b)) / (2.0 * h);
            assert!(
                (g - f[j]).abs() <= 1e-5 * f.norm(),
                "{j}: {g:e} vs {:e}",
                f[j]
            );
        }
    }

    /// Rigid motions (a translation and any rotation, also past pi) leave the energy and the
    /// force unchanged, the force rotating with the element.
    #[test]
    fn rigid_motions_change_nothing() {
        let e = element();
        let p = deformed();
        let f = e.force(&p, None);
        for angle in [0.7, -2.5, 3.5, 7.0] {
            let (s, c) = f64::sin_cos(angle);
            let rot = |x: f64, y: f64| (c * x - s * y + 1.5, s * x + c * y - 0.25);
            let (x1, y1) = rot(p[0], p[1]);
            let (x2, y2) = rot(p[3], p[4]);
            let q = Vec6::new(x1, y1, p[2] + angle, x2, y2, p[5] + angle);
            assert!((e.energy(&q) - e.energy(&p)).abs() <= 1e-9 * e.energy(&p));
            let g = e.force(&q, None);
            let (fx1, fy1) = (c * f[0] - s * f[1], s * f[0] + c * f[1]);
            assert!((g[0] - fx1).abs() + (g[1] - fy1).abs() <= 1e-6 * f.norm());
            assert!((g[2] - f[2]).abs() + (g[5] - f[5]).abs() <= 1e-6 * f.norm());
        }
    }

    /// At the reference configuration the tangent is the linear Euler-Bernoulli frame element's
    /// stiffness (axis along x): EA/l, 12 EI/l^3, 6 EI/l^2, 4 EI/l, 2 EI/l.
    #[test]
    fn reference_tangent_is_the_linear_stiffness() {
        let e = Element {
            beta0: 0.0,
            ..element()
        };
        let p = Vec6::new(0.0, 0.0, 0.0, e.l0, 0.0, 0.0);
        let mut k = Mat6::zeros();
        assert!(e.force(&p, Some(&mut k)).norm() == 0.0);
        let (l, ea, ei) = (e.l0, e.ea, e.ei);
        let want = Mat6::from_row_slice(&[
            ea / l,
            0.0,
            0.0,
            -ea / l,
            0.0,
            0.0, //
            0.0,
            12.0 * ei / l.powi(3),
            6.0 * ei / l.powi(2),
            0.0,
            -12.0 * ei / l.powi(3),
            6.0 * ei / l.powi(2), //
            0.0,
            6.0 * ei / l.powi(2),
            4.0 * ei / l,
            0.0,
            -6.0 * ei / l.powi(2),
            2.0 * ei / l, //
            -ea / l,
            0.0,
            0.0,
            ea / l,
            0.0,
            0.0, //
            0.0,
            -12.0 * ei / l.powi(3),
            -6.0 * ei / l.powi(2),
            0.0,
            12.0 * ei / l.powi(3),
            -6.0 * ei / l.powi(2), //
            0.0,
            6.0 * ei / l.powi(2),
            2.0 * ei / l,
            0.0,
            -6.0 * ei / l.powi(2),
            4.0 * ei / l, //
        ]);
        assert!((k - want).norm() <= 1e-12 * want.norm(), "{k}\n{want}");
    }
}
