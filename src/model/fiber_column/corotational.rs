//! The 3-D corotational transformation of a two-node beam element: from the nodes' positions
//! and rotations to the six basic deformations of the element's rigid-body-free (basic)
//! system, their first variation `B` and the element's global force and tangent.
//!
//! Following the element-independent corotational frame of Crisfield (1990, "A consistent
//! co-rotational formulation for non-linear three-dimensional beam elements", CMAME 81) and
//! Battini & Pacoste (2002, CMAME 191, section 3), derived here in our own notation. With the
//! initial element frame `E0 = [e1 e2 e3]` (e1 along the axis), the node rotations `R_a`
//! (a = 1, 2) and positions `x_a`:
//!
//! ```text
//! (1) d = x2 - x1,  l = |d|,  r1 = d / l
//! (2) T_a = R_a E0 (the nodes' triads),  q_a = T_a e2-column,  q = (q1 + q2)/2
//! (3) r3 = r1 x q / |r1 x q|,  r2 = r3 x r1,  Rr = [r1 r2 r3] (the corotated frame)
//! (4) theta_a = log(Rr^T T_a) (local rotation vectors, components along r1, r2, r3)
//! (5) v = [l - l0, theta_1z, theta_2z, theta_1y, theta_2y, theta_2x - theta_1x]
//! ```
//!
//! The basic forces `q_b = [N, Mz1, Mz2, My1, My2, T]` are conjugate to (5). Variations: with
//! the virtual spins `dw_a` (`dT_a = [dw_a]x T_a`), the frame's spin `dw_r` has the components
//!
//! ```text
//! (6) dw_r.r3 = r2.dd / l,   dw_r.r2 = -r3.dd / l,
//!     dw_r.r1 = ((q.r1)(dw_r.r2) + (1/2) sum_a dw_a.(q_a x r3)) / (q.r2)
//! ```
//!
//! (the last from `r3.q = 0` held along the variation), the local rotations' left spins are
//! `da_a = Rr^T (dw_a - dw_r)` and `dtheta_a = dexp_inv(theta_a) da_a`, which gives the rows
//! of `B = dv/d(x1, w1, x2, w2)`. The global internal force is `f = B^T q_b` and the tangent
//! `K = B^T k_b B + K_g`, whose geometric part `K_g = d(B^T q_b)/d(config)` at fixed `q_b`
//! is derived in closed form (eqs. 7-9 at [`Corotational::global`]; tested against central
//! differences of the force). The tangent is that of the update `R <- exp([dw]x) R` (not
//! symmetric away from equilibrium).
//!
//! Cost: an element whose first node is clamped (the column's base element) needs only the
//! reaction on that node's translations, the force on node 2 and node 2's 6 x 6 block of the
//! tangent ([`Corotational::global_free_end`]). `B` and its pieces are formed column by column
//! over a list of the 12 columns, each column by the same operations as in the full matrix, so
//! the block's entries are the full tangent's bit for bit (tested); for one clamped element the
//! full 12 x 12 tangent took 13 % of a cyclic run.
//!
//! Where it fails: `|r1 x q| -> 0` (the nodes' e2 axes turned onto the chord: a local
//! rotation of 90 degrees within one element) and `q.r2 -> 0` make the frame undefined; the
//! local rotations must stay below `pi` (the `log`'s branch), which an element with a
//! sensible mesh does by far.
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use crate::math::so3;

/// The variation of the basic deformations, 6 x 12 (columns: `x1, w1, x2, w2`).
pub type BMatrix = SMatrix<f64, 6, 12>;
/// A 12 x 12 element matrix in global components.
pub type Matrix12 = SMatrix<f64, 12, 12>;
/// A 12-vector in global components.
pub type Vector12 = SVector<f64, 12>;
/// Basic deformations or forces.
pub type Vector6 = SVector<f64, 6>;
/// A basic stiffness.
pub type Matrix6 = SMatrix<f64, 6, 6>;

/// The fixed data of an element: initial end positions and frame.
///
/// # Example
///
/// A straight element turned rigidly by a rotation `Q` (both nodes moved by `Q`, their
/// rotations set to `Q`) has zero basic deformations:
///
/// ```
/// use mbdbench::model::fiber_column::corotational::Corotational;
/// use mbdbench::math::so3;
/// use nalgebra::{Matrix3, Vector3};
///
/// let e = Corotational::new(Vector3::zeros(), Vector3::new(0.0, 0.0, 2.0), Vector3::x())
///     .unwrap();
/// let q = so3::exp(&Vector3::new(0.3, -1.2, 0.7));
/// let (v, _) = e.deformations(&Vector3::zeros(), &(q * Vector3::new(0.0, 0.0, 2.0)), &q, &q);
/// assert!(v.norm() < 1e-14);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Corotational {
    x1: Vector3<f64>,
    x2: Vector3<f64>,
    /// Initial frame: columns e1 (axis), e2, e3.
    e0: Matrix3<f64>,
    l0: f64,
}

/// The kinematic quantities of one configuration that `B` is made of.
struct Frame {
    l: f64,
    rr: Matrix3<f64>,
    q: [Vector3<f64>; 2],
    theta: [Vector3<f64>; 2],
}

impl Corotational {
    /// An element from `x1` to `x2` whose local e2 axis is `e2_hint` made orthogonal to the
    /// axis. Errors for a zero length or a hint along the axis.
    pub fn new(x1: Vector3<f64>, x2: Vector3<f64>, e2_hint: Vector3<f64>) -> Result<Self, String> {
        let d = x2 - x1;
        let l0 = d.norm();
        if !(l0 > 0.0 && l0.is_finite()) {
            return Err(format!("element of length {l0}"));
        }
        let e1 = d / l0;
        let e2 = e2_hint - e1 * e1.dot(&e2_hint);
        if e2.norm() < 1e-8 * e2_hint.norm().max(1e-300) {
            return Err("the local y axis hint lies along the element".into());
        }
        let e2 = e2.normalize();
        let e3 = e1.cross(&e2);
        Ok(Self {
            x1,
            x2,
            e0: Matrix3::from_columns(&[e1, e2, e3]),
            l0,
        })
    }

    /// The initial length.
    pub fn l0(&self) -> f64 {
        self.l0
    }

    /// The initial frame (columns: axis, local y, local z).
    pub fn e0(&self) -> &Matrix3<f64> {
        &self.e0
    }

    /// The initial end positions.
    pub fn ends(&self) -> (Vector3<f64>, Vector3<f64>) {
        (self.x1, self.x2)
    }

    fn frame(
        &self,
        x1: &Vector3<f64>,
        x2: &Vector3<f64>,
        r1m: &Matrix3<f64>,
        r2m: &Matrix3<f64>,
    ) -> Frame {
        let d = x2 - x1;
        let l = d.norm();
        let r1 = d / l;
        let t1 = r1m * self.e0;
        let t2 = r2m * self.e0;
        let q1 = t1.column(1).into_owned();
        let q2 = t2.column(1).into_owned();
        let q = (q1 + q2) * 0.5;
        let r3 = r1.cross(&q).normalize();
        let r2 = r3.cross(&r1);
        let rr = Matrix3::from_columns(&[r1, r2, r3]);
        let theta = [
            so3::log(&(rr.transpose() * t1)),
            so3::log(&(rr.transpose() * t2)),
        ];
        Frame {
            l,
            rr,
            q: [q1, q2],
            theta,
        }
    }

    /// The basic deformations (5) and their variation `B` at the configuration: current end
    /// positions and node rotation matrices (rotations from the initial configuration).
    pub fn deformations(
        &self,
        x1: &Vector3<f64>,
        x2: &Vector3<f64>,
        r1m: &Matrix3<f64>,
        r2m: &Matrix3<f64>,
    ) -> (Vector6, BMatrix) {
        let f = self.frame(x1, x2, r1m, r2m);
        let [t1, t2] = f.theta;
        let v = Vector6::new(f.l - self.l0, t1.z, t2.z, t1.y, t2.y, t2.x - t1.x);
        (v, self.variation(&f))
    }

    fn variation(&self, f: &Frame) -> BMatrix {
        self.variations(f, &ALL).b
    }

    /// `B` with the frame spin and the local rotations' variations it is made of, in the
    /// columns `cols` of the 12 (each block column `c` is the full column `cols[c]`, computed
    /// by the same operations as in the full matrix, so the entries are the same bits).
    fn variations<const C: usize>(&self, f: &Frame, cols: &[usize; C]) -> Variations<C> {
        let r1 = f.rr.column(0).into_owned();
        let r2 = f.rr.column(1).into_owned();
        let r3 = f.rr.column(2).into_owned();
        let q = (f.q[0] + f.q[1]) * 0.5;
        let (q1p, q2p) = (q.dot(&r1), q.dot(&r2));
        let g = [f.q[0].cross(&r3) * 0.5, f.q[1].cross(&r3) * 0.5];
        // Rows (1 x C) of the frame spin's components, eq. (6), and B's first row.
        let mut om = SMatrix::<f64, 3, C>::zeros();
        let mut b = SMatrix::<f64, 6, C>::zeros();
        for (c, &j) in cols.iter().enumerate() {
            let k = j % 3;
            match j / 3 {
                0 => {
                    om[(2, c)] = -r2[k] / f.l;
                    om[(1, c)] = r3[k] / f.l;
                    b[(0, c)] = -r1[k];
                }
                2 => {
                    om[(2, c)] = r2[k] / f.l;
                    om[(1, c)] = -r3[k] / f.l;
                    b[(0, c)] = r1[k];
                }
                _ => {}
            }
            om[(0, c)] = q1p * om[(1, c)];
            match j / 3 {
                1 => om[(0, c)] += g[0][k],
                3 => om[(0, c)] += g[1][k],
                _ => {}
            }
            om[(0, c)] /= q2p;
        }
        // The frame spin in global components, 3 x C: Rr * om.
        let spin = f.rr * om;
        let mut dth = [SMatrix::<f64, 3, C>::zeros(); 2];
        let mut jac = [Matrix3::zeros(); 2];
        for (a, out) in dth.iter_mut().enumerate() {
            // da_a = Rr^T (S_a - spin), then dexp_inv.
            let mut s = -spin;
            for (c, &j) in cols.iter().enumerate() {
                if j / 3 == 1 + 2 * a {
                    s[(j % 3, c)] += 1.0;
                }
            }
            jac[a] = so3::dexp_inv(&f.theta[a]);
            *out = jac[a] * (f.rr.transpose() * s);
        }
        for c in 0..C {
            b[(1, c)] = dth[0][(2, c)];
            b[(2, c)] = dth[1][(2, c)];
            b[(3, c)] = dth[0][(1, c)];
            b[(4, c)] = dth[1][(1, c)];
            b[(5, c)] = dth[1][(0, c)] - dth[0][(0, c)];
        }
        Variations { b, spin, dth, jac }
    }

    /// The basic deformations at a configuration, with what [`Corotational::global_at`]
    /// and [`Corotational::global_free_end`] need to form the global force and tangent there
    /// without recomputing the frame.
    pub fn at(
        &self,
        x1: &Vector3<f64>,
        x2: &Vector3<f64>,
        r1m: &Matrix3<f64>,
        r2m: &Matrix3<f64>,
    ) -> (Vector6, Kinematics) {
        let frame = self.frame(x1, x2, r1m, r2m);
        let [t1, t2] = frame.theta;
        let v = Vector6::new(frame.l - self.l0, t1.z, t2.z, t1.y, t2.y, t2.x - t1.x);
        (v, Kinematics { frame })
    }

    /// The basic deformations (5) alone, without `B`.
    pub fn basic_deformations(
        &self,
        x1: &Vector3<f64>,
        x2: &Vector3<f64>,
        r1m: &Matrix3<f64>,
        r2m: &Matrix3<f64>,
    ) -> Vector6 {
        self.at(x1, x2, r1m, r2m).0
    }

    /// [`Corotational::global`] at the configuration of [`Corotational::at`].
    pub fn global_at(&self, kin: &Kinematics, qb: &Vector6, kb: &Matrix6) -> (Vector12, Matrix12) {
        let var = self.variations(&kin.frame, &ALL);
        let b = &var.b;
        let force = b.transpose() * qb;
        let mut k = b.transpose() * kb * b;
        k += self.geometric(&kin.frame, &var, &ALL, qb);
        (force, k)
    }

    /// What a clamped first node leaves of [`Corotational::global_at`]: the force on node 1's
    /// translations (its support's reaction), the force on node 2 (6) and node 2's block of
    /// the tangent (6 x 6), each entry the same bits as in the full force and tangent. The
    /// full tangent's other three blocks and node 1's moments are not formed: a third of `B`,
    /// three quarters of `B^T k_b B` and half of `K_g`.
    ///
    /// # Example
    ///
    /// ```
    /// use mbdbench::model::fiber_column::corotational::{Corotational, Matrix6, Vector6};
    /// use mbdbench::math::so3;
    /// use nalgebra::Vector3;
    ///
    /// let e = Corotational::new(Vector3::zeros(), Vector3::new(0.0, 0.0, 2.0), Vector3::x())
    ///     .unwrap();
    /// let r2 = so3::exp(&Vector3::new(0.0, 0.1, 0.0));
    /// let (x1, x2) = (Vector3::zeros(), Vector3::new(0.05, 0.0, 2.0));
    /// let (_, kin) = e.at(&x1, &x2, &nalgebra::Matrix3::identity(), &r2);
    /// let (qb, kb) = (Vector6::new(-1.0, 0.2, 0.3, 0.0, 0.0, 0.0), Matrix6::identity());
    /// let (f, k) = e.global_at(&kin, &qb, &kb);
    /// let (reaction, f2, k22) = e.global_free_end(&kin, &qb, &kb);
    /// assert_eq!(reaction, f.fixed_rows::<3>(0).into_owned());
    /// assert_eq!(f2, f.fixed_rows::<6>(6).into_owned());
    /// assert_eq!(k22, k.fixed_view::<6, 6>(6, 6).into_owned());
    /// ```
    pub fn global_free_end(
        &self,
        kin: &Kinematics,
        qb: &Vector6,
        kb: &Matrix6,
    ) -> (Vector3<f64>, Vector6, Matrix6) {
        let var = self.variations(&kin.frame, &BASE_AND_FREE);
        let force = var.b.transpose() * qb;
        let free = var.columns::<6>(3);
        let b = &free.b;
        let mut k = b.transpose() * kb * b;
        k += self.geometric(&kin.frame, &free, &FREE, qb);
        (
            force.fixed_rows::<3>(0).into_owned(),
            force.fixed_rows::<6>(3).into_owned(),
            k,
        )
    }

    /// The element's global internal force `B^T q_b` and tangent `B^T k_b B + K_g` at the
    /// configuration, for basic forces `q_b` and basic stiffness `k_b`.
    ///
    /// The geometric part (eqs. 7-9, our derivation): with the end moments in local
    /// components `m_1 = (-T, My1, Mz1)`, `m_2 = (T, My2, Mz2)`, their global pull-backs
    /// `mu_a = Rr J_a^T m_a` (`J_a = dexp_inv(theta_a)`), `M = mu_1 + mu_2` with local
    /// components `M_i`, `eta = (q.r1)/(q.r2)`, the internal force is
    ///
    /// ```text
    /// (7) f_x2 = -f_x1 = N r1 + ((M_1 eta + M_2) r3 - M_3 r2) / l,
    ///     f_wa = mu_a - M_1 / (2 q.r2) (q_a x r3),
    /// ```
    ///
    /// and `K_g` is its derivative at fixed `q_b` along `x_a + e`, `exp([e]x) R_a`, using
    /// `dr_i = dw_r x r_i`, `dq_a = dw_a x q_a`, `dtheta_a` from `B`, `dM_i` = the local
    /// components of `sum_a D_a dtheta_a` (the frame's own spin drops out of them) with
    ///
    /// ```text
    /// (8) D(theta, m) = d(J(theta)^T m)/dtheta = -[m]x / 2 + (c'(t)/t) g theta^T
    ///                   + c ((theta.m) I + theta m^T - 2 m theta^T),
    /// (9) g = theta (theta.m) - t^2 m,  c(t) = (1 - (t/2) cot(t/2)) / t^2,  t = |theta|.
    /// ```
    pub fn global(
        &self,
        x1: &Vector3<f64>,
        x2: &Vector3<f64>,
        r1m: &Matrix3<f64>,
        r2m: &Matrix3<f64>,
        qb: &Vector6,
        kb: &Matrix6,
    ) -> (Vector12, Matrix12) {
        let (_, kin) = self.at(x1, x2, r1m, r2m);
        self.global_at(&kin, qb, kb)
    }

    /// `K_g` in the rows and columns `cols` of the 12 (block entry `(r, c)` is the full
    /// entry `(cols[r], cols[c])`), from the variations in those columns.
    fn geometric<const C: usize>(
        &self,
        f: &Frame,
        var: &Variations<C>,
        cols: &[usize; C],
        qb: &Vector6,
    ) -> SMatrix<f64, C, C> {
        let rr = &f.rr;
        let r = [
            rr.column(0).into_owned(),
            rr.column(1).into_owned(),
            rr.column(2).into_owned(),
        ];
        let l = f.l;
        let n = qb[0];
        let m = [
            Vector3::new(-qb[5], qb[3], qb[1]),
            Vector3::new(qb[5], qb[4], qb[2]),
        ];
        let jtm = [var.jac[0].transpose() * m[0], var.jac[1].transpose() * m[1]];
        let mu = [rr * jtm[0], rr * jtm[1]];
        let ml = jtm[0] + jtm[1];
        let q = (f.q[0] + f.q[1]) * 0.5;
        let (q1p, q2p) = (q.dot(&r[0]), q.dot(&r[1]));
        let eta = q1p / q2p;
        let spin = &var.spin;
        // Variations as 1 x C rows or 3 x C blocks.
        let mut dl = SMatrix::<f64, 1, C>::zeros();
        let mut sel = [SMatrix::<f64, 3, C>::zeros(); 2];
        for (c, &j) in cols.iter().enumerate() {
            match j / 3 {
                0 => dl[c] = -r[0][j % 3],
                1 => sel[0][(j % 3, c)] = 1.0,
                2 => dl[c] = r[0][j % 3],
                _ => sel[1][(j % 3, c)] = 1.0,
            }
        }
        let dr = [
            -so3::hat(&r[0]) * spin,
            -so3::hat(&r[1]) * spin,
            -so3::hat(&r[2]) * spin,
        ];
        let dqa = [-so3::hat(&f.q[0]) * sel[0], -so3::hat(&f.q[1]) * sel[1]];
        let dq = (dqa[0] + dqa[1]) * 0.5;
        let dq1p = r[0].transpose() * dq + q.transpose() * dr[0];
        let dq2p = r[1].transpose() * dq + q.transpose() * dr[1];
        let deta = (dq1p - dq2p * eta) / q2p;
        let djm = [d_jt_m(&f.theta[0], &m[0]), d_jt_m(&f.theta[1], &m[1])];
        let dm = djm[0] * var.dth[0] + djm[1] * var.dth[1];
        let (dm1, dm2, dm3) = (dm.row(0), dm.row(1), dm.row(2));
        // (7), differentiated: the chord force f_d.
        let a = (ml[0] * eta + ml[1]) / l;
        let da = (dm1 * eta + deta * ml[0] + dm2) / l - dl * (a / l);
        let c3 = ml[2] / l;
        let dc3 = dm3 / l - dl * (c3 / l);
        let dfd = dr[0] * n + r[2] * da + dr[2] * a - r[1] * dc3 - dr[1] * c3;
        // The rotation forces f_wa, of the sides whose rotations are among the rows.
        let h = ml[0] / (2.0 * q2p);
        let dh = dm1 / (2.0 * q2p) - dq2p * (ml[0] / (2.0 * q2p * q2p));
        let mut dfw = [None, None];
        for (side, out) in dfw.iter_mut().enumerate() {
            if !cols.contains(&(3 + 6 * side)) {
                continue;
            }
            let dmu = -so3::hat(&mu[side]) * spin + rr * djm[side] * var.dth[side];
            let qa_r3 = f.q[side].cross(&r[2]);
            *out = Some(
                dmu - qa_r3 * dh
                    - (-so3::hat(&r[2]) * dqa[side] + so3::hat(&f.q[side]) * dr[2]) * h,
            );
        }
        let mut kg = SMatrix::<f64, C, C>::zeros();
        for (row, &j) in cols.iter().enumerate() {
            let k = j % 3;
            let from = match (j / 3, &dfw) {
                (0, _) => -dfd.row(k),
                (2, _) => dfd.row(k).into_owned(),
                (1, [Some(w), _]) | (3, [_, Some(w)]) => w.row(k).into_owned(),
                _ => continue,
            };
            kg.row_mut(row).copy_from(&from);
        }
        kg
    }
}

/// The kinematic state of an element at one configuration (its frame).
pub struct Kinematics {
    frame: Frame,
}

/// `B` and the pieces of it the geometric stiffness reuses, in `C` of the 12 columns.
struct Variations<const C: usize> {
    b: SMatrix<f64, 6, C>,
    /// The frame spin `dw_r`, 3 x C.
    spin: SMatrix<f64, 3, C>,
    /// The local rotations' variations `dtheta_a`, 3 x C each.
    dth: [SMatrix<f64, 3, C>; 2],
    /// `dexp_inv(theta_a)`.
    jac: [Matrix3<f64>; 2],
}

impl<const C: usize> Variations<C> {
    /// The `N` columns from `first` on.
    fn columns<const N: usize>(&self, first: usize) -> Variations<N> {
        Variations {
            b: self.b.fixed_columns::<N>(first).into_owned(),
            spin: self.spin.fixed_columns::<N>(first).into_owned(),
            dth: self.dth.map(|d| d.fixed_columns::<N>(first).into_owned()),
            jac: self.jac,
        }
    }
}

/// The 12 columns `x1, w1, x2, w2`.
const ALL: [usize; 12] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11];
/// Node 1's translations (its reaction) and node 2's six unknowns.
const BASE_AND_FREE: [usize; 9] = [0, 1, 2, 6, 7, 8, 9, 10, 11];
/// Node 2's six unknowns.
const FREE: [usize; 6] = [6, 7, 8, 9, 10, 11];

/// Eq. (8): `d(dexp_inv(theta)^T m)/dtheta`.
fn d_jt_m(theta: &Vector3<f64>, m: &Vector3<f64>) -> Matrix3<f64> {
    let t2 = theta.norm_squared();
    // c and c'/t: series below t = 0.2 (truncation < 1e-9 relative), closed form above.
    let (c, dc_t) = if t2 < 0.04 {
        (
            1.0 / 12.0 + t2 * (1.0 / 720.0 + t2 * (1.0 / 30240.0 + t2 / 1209600.0)),
            1.0 / 360.0 + t2 * (1.0 / 7560.0 + t2 / 201600.0),
        )
    } else {
        let t = t2.sqrt();
        let h = 0.5 * t;
        let cot = h.cos() / h.sin();
        let c = (1.0 - h * cot) / t2;
        let dc = -0.5 * (cot - h / (h.sin() * h.sin())) / t2 - 2.0 * c / t;
        (c, dc / t)
    };
    let tm = theta.dot(m);
    let g = theta * tm - m * t2;
    so3::hat(m) * -0.5
        + g * theta.transpose() * dc_t
        + (Matrix3::identity() * tm + theta * m.transpose() - m * theta.transpose() * 2.0) * c
}

#[cfg(test)]
mod tests {
    use super::*;

    fn element() -> Corotational {
        Corotational::new(
            Vector3::new(0.1, -0.2, 0.0),
            Vector3::new(0.3, 0.1, 1.2),
            Vector3::new(1.0, 0.2, 0.0),
        )
        .unwrap()
    }

    /// A deformed configuration: moved ends and rotated nodes.
    fn config() -> (Vector3<f64>, Vector3<f64>, Matrix3<f64>, Matrix3<f64>) {
        (
            Vector3::new(0.12, -0.25, 0.03),
            Vector3::new(0.5, 0.0, 1.1),
            so3::exp(&Vector3::new(0.2, -0.4, 0.3)),
            so3::exp(&Vector3::new(-0.1, -0.5, 0.6)),
        )
    }

    fn perturbed(
        c: &(Vector3<f64>, Vector3<f64>, Matrix3<f64>, Matrix3<f64>),
        d: &Vector12,
    ) -> (Vector3<f64>, Vector3<f64>, Matrix3<f64>, Matrix3<f64>) {
        let s = |i: usize| Vector3::new(d[i], d[i + 1], d[i + 2]);
        (
            c.0 + s(0),
            c.1 + s(6),
            so3::exp(&s(3)) * c.2,
            so3::exp(&s(9)) * c.3,
        )
    }

    // B is the derivative of the basic deformations along x_a + e, exp([e]x) R_a: each column
    // against a central difference of v (step 1e-6), to 1e-8.
    #[test]
    fn b_is_the_derivative_of_v() {
        let e = element();
        let c = config();
        let (_, b) = e.deformations(&c.0, &c.1, &c.2, &c.3);
        for j in 0..12 {
            let mut d = Vector12::zeros();
            d[j] = 1e-6;
            let p = perturbed(&c, &d);
            let m = perturbed(&c, &(-d));
            let (vp, _) = e.deformations(&p.0, &p.1, &p.2, &p.3);
            let (vm, _) = e.deformations(&m.0, &m.1, &m.2, &m.3);
            let fd = (vp - vm) / 2e-6;
            let err = (fd - b.column(j)).norm();
            assert!(err < 1e-8, "column {j}: {err:e}");
        }
    }

    // The tangent is the derivative of the global force at fixed basic stiffness: with
    // q_b = q0 + k_b (v - v0) (a linear elastic basic element), K against a central
    // difference of B^T q_b (step 1e-6), to 1e-8 relative.
    #[test]
    fn tangent_is_the_derivative_of_the_force() {
        let e = element();
        let c = config();
        let (v0, _) = e.deformations(&c.0, &c.1, &c.2, &c.3);
        let q0 = Vector6::new(3.0, -1.0, 2.0, 0.5, -0.7, 0.4);
        let mut kb = Matrix6::identity() * 2.0;
        kb[(1, 2)] = 0.5;
        kb[(2, 1)] = 0.5;
        let force_at = |p: &(Vector3<f64>, Vector3<f64>, Matrix3<f64>, Matrix3<f64>)| {
            let (v, b) = e.deformations(&p.0, &p.1, &p.2, &p.3);
            b.transpose() * (q0 + kb * (v - v0))
        };
        let (_, k) = e.global(&c.0, &c.1, &c.2, &c.3, &q0, &kb);
        let scale = k.norm();
        for j in 0..12 {
            let mut d = Vector12::zeros();
            d[j] = 1e-6;
            let fd = (force_at(&perturbed(&c, &d)) - force_at(&perturbed(&c, &(-d)))) / 2e-6;
            let err = (fd - k.column(j)).norm() / scale;
            assert!(err < 1e-8, "column {j}: {err:e}");
        }
    }

    // A clamped first node's force and tangent are the full ones' entries bit for bit: the
    // reaction is f[0..3], the free node's force f[6..12] and its block K[6..12, 6..12]
    // (exact equality, at a deformed configuration with a coupled basic stiffness).
    #[test]
    fn free_end_is_the_full_block_bit_for_bit() {
        let e = element();
        let c = config();
        let qb = Vector6::new(3.0, -1.0, 2.0, 0.5, -0.7, 0.4);
        let mut kb = Matrix6::identity() * 2.0;
        kb[(1, 2)] = 0.5;
        kb[(2, 1)] = 0.5;
        kb[(0, 3)] = -0.25;
        kb[(4, 0)] = 0.125;
        let (v, kin) = e.at(&c.0, &c.1, &c.2, &c.3);
        let (f, k) = e.global_at(&kin, &qb, &kb);
        let (reaction, f2, k22) = e.global_free_end(&kin, &qb, &kb);
        assert_eq!(v, e.basic_deformations(&c.0, &c.1, &c.2, &c.3));
        assert_eq!(reaction, f.fixed_rows::<3>(0).into_owned());
        assert_eq!(f2, f.fixed_rows::<6>(6).into_owned());
        assert_eq!(k22, k.fixed_view::<6, 6>(6, 6).into_owned());
        assert!(k22.norm() > 1.0, "a real tangent: {k22}");
    }

    // A rigid motion (translation plus rotation of the whole element) leaves v at zero, and
    // B annihilates the six rigid-body velocities (translations and the spin of everything).
    #[test]
    fn rigid_motions_are_free() {
        let e = element();
        let rot = so3::exp(&Vector3::new(1.0, 2.0, -0.5));
        let t = Vector3::new(0.3, -2.0, 5.0);
        let (x1, x2) = e.ends();
        let (v, b) = e.deformations(&(rot * x1 + t), &(rot * x2 + t), &rot, &rot);
        assert!(v.norm() < 1e-14, "{v}");
        let (p1, p2) = (rot * x1 + t, rot * x2 + t);
        for k in 0..3 {
            let mut tr = Vector12::zeros();
            tr[k] = 1.0;
            tr[6 + k] = 1.0;
            assert!((b * tr).norm() < 1e-13);
            let mut w = Vector3::zeros();
            w[k] = 1.0;
            let mut sp = Vector12::zeros();
            sp.fixed_rows_mut::<3>(0).copy_from(&w.cross(&p1));
            sp.fixed_rows_mut::<3>(3).copy_from(&w);
            sp.fixed_rows_mut::<3>(6).copy_from(&w.cross(&p2));
            sp.fixed_rows_mut::<3>(9).copy_from(&w);
            assert!((b * sp).norm() < 1e-13, "{}", (b * sp).norm());
        }
    }
}
