//! The assumed-mode ("modal") models of the beam on its base: the deformation as a sum of
//! shape functions (`shapes.rs`) with the kinetic energy kept to second order in it (Kane,
//! Ryan & Banerjee, J. Guidance 10(2), 1987), with or without the foreshortening that gives
//! the geometric stiffening, and optional linear constraints on the shapes' end values.
//!
//! Kinematics: the stretch `s(x, t) = psi(x)^T p` (the `stretch` shapes), the lateral
//! displacement `u2(x, t) = phi(x)^T q` (the `lateral` shapes), the axial displacement
//! `u1 = s - 1/2 int_0^x u2'^2` with `stiffening` (`u1 = s` without), the point at
//! `r = (x + u1, u2)` in the base frame, which turns at `Om = theta'`. With `Mpp = int rhoA psi
//! psi^T`, `Mqq = int rhoA phi phi^T`, `C = int rhoA psi phi^T`, `ap = int rhoA x psi`,
//! `aq = int rhoA x phi`, `I0 = int rhoA x^2`, `Kpp = int EA psi' psi'^T`, `Kqq = int EI phi''
//! phi''^T`, `Kg = int rhoA (L^2 - x^2)/2 phi' phi'^T` (from `int_0^L rhoA x int_0^x u2'^2`;
//! 0 without stiffening) and `D = Mqq - Kg`, the energies to second order are
//!
//! ```text
//! T2 = 1/2 p'^T Mpp p' + 1/2 q'^T Mqq q' - Om p'^T C q + Om q'^T (C^T p + aq)
//!      + 1/2 Om^2 Jtot,   Jtot = J_hub + I0 + q^T D q + p^T Mpp p + 2 ap^T p,
//! V  = 1/2 p^T Kpp p + 1/2 q^T Kqq q,
//! ```
//!
//! (`J_hub` for a free hub only) and Lagrange's equations in residual form are
//!
//! ```text
//! r_p  = Mpp p'' - 2 Om C q' - Om' C q + (Kpp - Om^2 Mpp) p - Om^2 ap,
//! r_q  = Mqq q'' + 2 Om C^T p' + Om' (C^T p + aq) + (Kqq - Om^2 D) q,
//! r_th = Jtot Om' - (C q)^T p'' + (C^T p + aq)^T q'' + 2 Om (q^T D q' + p^T Mpp p' + ap^T p')
//!        - tau(t)                                                     (free hub only),
//! ```
//!
//! coordinates `[theta, p, q]` for a free hub (`Om = theta'`), `[p, q]` for a prescribed base
//! (`Om`, `Om'` from `base.motion(t)`). The angular momentum is `H = dT2/dOm = -p'^T C q +
//! q'^T (C^T p + aq) + Om Jtot`, and `r_th = dH/dt - tau`. Since `T2` is homogeneous of degree
//! 2 in `(Om, p', q')`, the energy `E = T2 + V` of a prescribed base obeys `dE/dt = Om dH/dt`
//! (the Jacobi integral `E - Om H` changes by `-Om' H`), and a free hub's `dH/dt = tau`.
//! The matrices are integrated by 8-point Gauss-Legendre on 32 equal subintervals: exact for
//! the Hermite and linear shapes, and for the modes to round-off while `beta L` stays below
//! about 50 (the error bound is `1.7e-23 (2 beta h)^16` relative, `h = L/32`: 1e-12 at
//! `beta L = 80`, the 25th mode).
//!
//! Invariants (tested in `modal_tests.rs`): the tangent is the exact derivative of the residual;
//! the mass matrix is symmetric positive definite and the gyroscopic one skew; `T2 = 1/2 v^T
//! M v` and `H = (M v)_theta` for a free hub; the two energy identities hold along Newmark
//! solutions to its accuracy. Where it fails: the second-order energy drops the terms cubic in
//! the deformation, so deflections must stay small against the length; the modal stretch of a
//! stiff rod makes the system stiff (axial frequency `pi/2 sqrt(EA/rhoA)/L`); shapes that are
//! linearly dependent are refused (singular mass), but nearly dependent ones (a Hermite basis
//! with many modes) make the mass ill-conditioned; constraints are linear and scleronomic, and
//! their rows must be independent for the constrained integrators (not checked here).
use nalgebra::{DMatrix, DVector};

use super::base::Base;
use super::fe::Beam;
use super::shapes::{Shape, composite_rule};
use crate::structural::{Constraints, SecondOrder};

/// Which deformation a constraint restrains.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Field {
    /// The stretch `s = psi^T p`.
    Stretch,
    /// The lateral displacement `u2 = phi^T q`.
    Lateral,
}

/// A linear constraint: the `derivative`-th x-derivative (0..=3) of `field` at the root
/// (`at_tip` false) or the tip vanishes, the row `psi^(k)(x)^T p = 0` or `phi^(k)(x)^T q = 0`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Bc {
    pub field: Field,
    pub at_tip: bool,
    pub derivative: usize,
}

/// The shapes of a modal model.
#[derive(Debug, Clone, PartialEq)]
pub struct Basis {
    /// The shapes `psi` of the stretch (may be empty: an inextensible beam).
    pub stretch: Vec<Shape>,
    /// The shapes `phi` of the lateral displacement (at least one).
    pub lateral: Vec<Shape>,
    /// Keep the foreshortening `-1/2 int u2'^2` in the axial displacement (the centrifugal
    /// stiffening).
    pub stiffening: bool,
    /// Linear constraints on the shapes' end values.
    pub constraints: Vec<Bc>,
}

/// The assumed-mode model of the beam on its base.
#[derive(Debug, Clone)]
pub struct Modal {
    pub beam: Beam,
    pub base: Base,
    basis: Basis,
    /// 1 with a free hub (its angle is coordinate 0), else 0.
    off: usize,
    np: usize,
    nq: usize,
    mpp: DMatrix<f64>,
    kpp: DMatrix<f64>,
    mqq: DMatrix<f64>,
    kqq: DMatrix<f64>,
    /// `D = Mqq - Kg` (`Mqq` without stiffening).
    d: DMatrix<f64>,
    /// `C` (`np x nq`).
    c: DMatrix<f64>,
    ap: DVector<f64>,
    aq: DVector<f64>,
    i0: f64,
    /// `psi(L)` and `phi(L)`.
    psi_tip: DVector<f64>,
    phi_tip: DVector<f64>,
    /// The constraint rows (`m x n`).
    rows: DMatrix<f64>,
    /// The transposes of `sqq`, `mpp`, `kpp`, `c`, `mqq`, `kqq`, `d`: the residual and the
    /// quadratic forms read their rows
    /// as contiguous columns (the matrices are symmetric only to round-off, and the residual
    /// keeps the row-wise sums).
    rows_of: RowsOf,
}

/// Row-major copies (transposes) of the matrices the residual sums over rows.
#[derive(Debug, Clone)]
struct RowsOf {
    /// `int phi' phi'^T` (the tip's foreshortening is `1/2 q^T Sqq q`; symmetric).
    sqq: DMatrix<f64>,
    mpp: DMatrix<f64>,
    kpp: DMatrix<f64>,
    c: DMatrix<f64>,
    mqq: DMatrix<f64>,
    kqq: DMatrix<f64>,
    d: DMatrix<f64>,
}

/// Subintervals and points per subinterval of the composite Gauss-Legendre rule.
const N_SUB: usize = 32;
const N_PT: usize = 8;

/// `x[xo..]^T m y[yo..]` over `m`'s rows and columns, from `mt` = `m^T` (row `i` of `m` is
/// the contiguous column `i` of `mt`): the row sums first, in the index order.
fn bilinear(mt: &DMatrix<f64>, x: &DVector<f64>, xo: usize, y: &DVector<f64>, yo: usize) -> f64 {
    let (nr, nc) = (mt.ncols(), mt.nrows());
    let (x, y) = (&x.as_slice()[xo..xo + nr], &y.as_slice()[yo..yo + nc]);
    let mut s = 0.0;
    for (i, xi) in x.iter().enumerate() {
        let mut row = 0.0;
        for (m, yj) in col(mt, i).iter().zip(y) {
            row += m * yj;
        }
        s += xi * row;
    }
    s
}

/// Column `j` of `m` as a slice (nalgebra stores columns contiguously).
fn col(m: &DMatrix<f64>, j: usize) -> &[f64] {
    let n = m.nrows();
    &m.as_slice()[j * n..(j + 1) * n]
}

/// `a^T x[xo..]`.
fn dot_at(a: &DVector<f64>, x: &DVector<f64>, xo: usize) -> f64 {
    a.iter().enumerate().map(|(i, ai)| ai * x[xo + i]).sum()
}

/// Refuses non-positive or non-finite beam data, a bad hub, no lateral shape, and a shape
/// `Shape::validate` refuses.
fn check_data(beam: &Beam, base: &Base, basis: &Basis) -> Result<(), String> {
    for (name, x) in [
        ("length", beam.l),
        ("EA", beam.ea),
        ("EI", beam.ei),
        ("rhoA", beam.rho_a),
    ] {
        if !(x.is_finite() && x > 0.0) {
            return Err(format!("{name} must be finite and positive, not {x}"));
        }
    }
    if let Base::Free {
        j_hub,
        torque,
        t_off,
    } = *base
        && !(j_hub.is_finite() && j_hub >= 0.0 && torque.is_finite() && !t_off.is_nan())
    {
        return Err(format!(
            "the hub needs a finite inertia >= 0 and a finite torque, not {base:?}"
        ));
    }
    if basis.lateral.is_empty() {
        return Err("a modal model needs at least one lateral shape".into());
    }
    for s in basis.stretch.iter().chain(&basis.lateral) {
        s.validate()?;
    }
    Ok(())
}

/// Refuses as many constraints as shape coordinates, a derivative above 3, and a constraint
/// on the stretch without stretch shapes.
fn check_constraints(constraints: &[Bc], np: usize, nq: usize) -> Result<(), String> {
    if constraints.len() >= np + nq {
        return Err(format!(
            "{} constraints on {} shape coordinates leave no motion",
            constraints.len(),
            np + nq
        ));
    }
    for bc in constraints {
        if bc.derivative > 3 {
            return Err(format!("{bc:?}: derivatives 0..=3 only"));
        }
        if bc.field == Field::Stretch && np == 0 {
            return Err(format!("{bc:?}: there are no stretch shapes"));
        }
    }
    Ok(())
}

/// The integrals over the beam of the module's notation (`Kg` 0 without stiffening).
struct Integrals {
    mpp: DMatrix<f64>,
    kpp: DMatrix<f64>,
    c: DMatrix<f64>,
    mqq: DMatrix<f64>,
    kqq: DMatrix<f64>,
    kg: DMatrix<f64>,
    /// `int phi' phi'^T`.
    sqq: DMatrix<f64>,
    ap: DVector<f64>,
    aq: DVector<f64>,
    i0: f64,
}

/// The matrices, vectors and `I0` by the composite Gauss-Legendre rule, summed point by point.
fn integrals(beam: &Beam, basis: &Basis) -> Integrals {
    let (np, nq) = (basis.stretch.len(), basis.lateral.len());
    let l = beam.l;
    let (mut mpp, mut kpp, mut c) = (
        DMatrix::zeros(np, np),
        DMatrix::zeros(np, np),
        DMatrix::zeros(np, nq),
    );
    let (mut mqq, mut kqq, mut kg, mut sqq) = (
        DMatrix::zeros(nq, nq),
        DMatrix::zeros(nq, nq),
        DMatrix::zeros(nq, nq),
        DMatrix::zeros(nq, nq),
    );
    let (mut ap, mut aq) = (DVector::zeros(np), DVector::zeros(nq));
    let mut i0 = 0.0;
    let (mut psi, mut phi) = (vec![[0.0; 4]; np], vec![[0.0; 4]; nq]);
    for (x, w) in composite_rule(l, N_SUB, N_PT) {
        for (e, s) in psi.iter_mut().zip(&basis.stretch) {
            *e = s.eval(x, l);
        }
        for (e, s) in phi.iter_mut().zip(&basis.lateral) {
            *e = s.eval(x, l);
        }
        let wm = w * beam.rho_a;
        i0 += wm * x * x;
        for i in 0..np {
            ap[i] += wm * x * psi[i][0];
            for j in 0..np {
                mpp[(i, j)] += wm * psi[i][0] * psi[j][0];
                kpp[(i, j)] += w * beam.ea * psi[i][1] * psi[j][1];
            }
            for k in 0..nq {
                c[(i, k)] += wm * psi[i][0] * phi[k][0];
            }
        }
        for k in 0..nq {
            aq[k] += wm * x * phi[k][0];
            for j in 0..nq {
                mqq[(k, j)] += wm * phi[k][0] * phi[j][0];
                kqq[(k, j)] += w * beam.ei * phi[k][2] * phi[j][2];
                kg[(k, j)] += wm * 0.5 * (l * l - x * x) * phi[k][1] * phi[j][1];
                sqq[(k, j)] += w * phi[k][1] * phi[j][1];
            }
        }
    }
    if !basis.stiffening {
        kg.fill(0.0);
    }
    Integrals {
        mpp,
        kpp,
        c,
        mqq,
        kqq,
        kg,
        sqq,
        ap,
        aq,
        i0,
    }
}

/// Refuses linearly dependent stretch or lateral shapes (a mass block without a Cholesky
/// factor).
fn check_independent(mpp: &DMatrix<f64>, mqq: &DMatrix<f64>) -> Result<(), String> {
    for (m, what) in [(mpp, "stretch"), (mqq, "lateral")] {
        if m.nrows() > 0 && m.clone().cholesky().is_none() {
            return Err(format!("the {what} shapes are linearly dependent"));
        }
    }
    Ok(())
}

/// The constraint rows (`m x n`): each constraint's shape values at its end, in its field's
/// columns.
fn constraint_rows(basis: &Basis, l: f64, n: usize, off: usize, np: usize) -> DMatrix<f64> {
    let mut rows = DMatrix::zeros(basis.constraints.len(), n);
    for (r, bc) in basis.constraints.iter().enumerate() {
        let x = if bc.at_tip { l } else { 0.0 };
        let (shapes, start) = match bc.field {
            Field::Stretch => (&basis.stretch, off),
            Field::Lateral => (&basis.lateral, off + np),
        };
        for (j, s) in shapes.iter().enumerate() {
            rows[(r, start + j)] = s.eval(x, l)[bc.derivative];
        }
    }
    rows
}

impl Modal {
    /// The model of `beam` on `base` in `basis`; an error names bad data (non-positive or
    /// non-finite beam data or hub inertia, no lateral shape, a shape index out of range, a
    /// derivative above 3, a constraint on the stretch without stretch shapes, as many
    /// constraints as coordinates, linearly dependent shapes).
    ///
    /// # Example
    ///
    /// ```
    /// use mbdbench::model::flexible_beam::base::Base;
    /// use mbdbench::model::flexible_beam::fe::Beam;
    /// use mbdbench::model::flexible_beam::modal::{Basis, Modal};
    /// use mbdbench::model::flexible_beam::shapes::Shape;
    /// use mbdbench::structural::SecondOrder;
    ///
    /// let beam = Beam { l: 10.0, ea: 2.8e7, ei: 1.4e4, rho_a: 1.2 };
    /// let basis = Basis {
    ///     stretch: vec![Shape::ClampedFreeRod(1)],
    ///     lateral: (1..=4).map(Shape::ClampedFreeBending).collect(),
    ///     stiffening: true,
    ///     constraints: vec![],
    /// };
    /// let m = Modal::new(beam, Base::SpinUp { w: 4.0, t_up: 15.0 }, basis).unwrap();
    /// assert_eq!(m.dim(), 5);
    /// ```
    pub fn new(beam: Beam, base: Base, basis: Basis) -> Result<Modal, String> {
        check_data(&beam, &base, &basis)?;
        let (np, nq) = (basis.stretch.len(), basis.lateral.len());
        let off = usize::from(matches!(base, Base::Free { .. }));
        let n = off + np + nq;
        check_constraints(&basis.constraints, np, nq)?;
        let l = beam.l;
        let Integrals {
            mpp,
            kpp,
            c,
            mqq,
            kqq,
            kg,
            sqq,
            ap,
            aq,
            i0,
        } = integrals(&beam, &basis);
        check_independent(&mpp, &mqq)?;
        let d = &mqq - &kg;
        let psi_tip = DVector::from_iterator(np, basis.stretch.iter().map(|s| s.eval(l, l)[0]));
        let phi_tip = DVector::from_iterator(nq, basis.lateral.iter().map(|s| s.eval(l, l)[0]));
        let rows = constraint_rows(&basis, l, n, off, np);
        let rows_of = RowsOf {
            sqq: sqq.transpose(),
            mpp: mpp.transpose(),
            kpp: kpp.transpose(),
            c: c.transpose(),
            mqq: mqq.transpose(),
            kqq: kqq.transpose(),
            d: d.transpose(),
        };
        Ok(Modal {
            rows_of,
            beam,
            base,
            basis,
            off,
            np,
            nq,
            mpp,
            kpp,
            mqq,
            kqq,
            d,
            c,
            ap,
            aq,
            i0,
            psi_tip,
            phi_tip,
            rows,
        })
    }

    /// The model's shapes.
    pub fn basis(&self) -> &Basis {
        &self.basis
    }

    /// The hub's inertia (0 for a prescribed base, which has no hub coordinate).
    fn j_hub(&self) -> f64 {
        match self.base {
            Base::Free { j_hub, .. } => j_hub,
            Base::SpinUp { .. } => 0.0,
        }
    }

    /// The base rate and acceleration: prescribed, or the hub coordinate's.
    #[inline]
    fn rates(&self, t: f64, v: &DVector<f64>, a: &DVector<f64>) -> (f64, f64) {
        match self.base.motion(t) {
            Some(m) => (m.rate, m.accel),
            None => (v[0], a[0]),
        }
    }

    /// The lateral displacement of the tip in the base frame, `u2(L)` (m).
    pub fn tip_deflection(&self, q: &DVector<f64>) -> f64 {
        dot_at(&self.phi_tip, q, self.off + self.np)
    }

    /// The axial displacement of the tip in the base frame, `u1(L) = s(L) - 1/2 q^T (int phi'
    /// phi'^T) q` with stiffening, `s(L)` without (the model's own kinematics; `s = 0` without
    /// stretch shapes) (m).
    pub fn tip_axial(&self, q: &DVector<f64>) -> f64 {
        let s = dot_at(&self.psi_tip, q, self.off);
        if self.basis.stiffening {
            let iq = self.off + self.np;
            s - 0.5 * bilinear(&self.rows_of.sqq, q, iq, q, iq)
        } else {
            s
        }
    }

    /// The hub's angle and rate at `(t, q, v)`: prescribed, or the hub coordinate's.
    pub fn hub(&self, t: f64, q: &DVector<f64>, v: &DVector<f64>) -> [f64; 2] {
        match self.base.motion(t) {
            Some(m) => [m.theta, m.rate],
            None => [q[0], v[0]],
        }
    }

    /// `Jtot = J_hub + I0 + q^T D q + p^T Mpp p + 2 ap^T p` (`J_hub` with a free hub).
    fn j_total(&self, q: &DVector<f64>) -> f64 {
        let (o, iq) = (self.off, self.off + self.np);
        self.j_hub()
            + self.i0
            + bilinear(&self.rows_of.d, q, iq, q, iq)
            + bilinear(&self.rows_of.mpp, q, o, q, o)
            + 2.0 * dot_at(&self.ap, q, o)
    }

    /// A free hub's column of the mass matrix into `col` (length `dim`): `(Jtot, -C q,
    /// C^T p + aq)`, the only part that changes with the state (`ode.rs` uses it instead of
    /// the whole tangent). Nothing for a prescribed base.
    pub fn hub_column(&self, q: &DVector<f64>, col: &mut DVector<f64>) {
        if self.off == 0 {
            return;
        }
        let (o, np, nq) = (self.off, self.np, self.nq);
        let iq = o + np;
        col[0] = self.j_total(q);
        for i in 0..np {
            col[o + i] = -(0..nq).map(|k| self.c[(i, k)] * q[iq + k]).sum::<f64>();
        }
        for k in 0..nq {
            col[iq + k] = self.aq[k] + (0..np).map(|i| self.c[(i, k)] * q[o + i]).sum::<f64>();
        }
    }

    /// The part of `H` from the deformation rates: `-p'^T C q + q'^T (C^T p + aq)`.
    fn h_relative(&self, q: &DVector<f64>, v: &DVector<f64>) -> f64 {
        let (o, iq) = (self.off, self.off + self.np);
        -bilinear(&self.rows_of.c, v, o, q, iq) + bilinear(&self.rows_of.c, q, o, v, iq) + dot_at(&self.aq, v, iq)
    }

    /// Kinetic energy `T2` (the rigid rotation and a free hub included) and strain energy `V`
    /// at `(t, q, v)` (J).
    pub fn energy(&self, t: f64, q: &DVector<f64>, v: &DVector<f64>) -> (f64, f64) {
        let (o, iq) = (self.off, self.off + self.np);
        let om = self.hub(t, q, v)[1];
        let kin = 0.5 * bilinear(&self.rows_of.mpp, v, o, v, o)
            + 0.5 * bilinear(&self.rows_of.mqq, v, iq, v, iq)
            + om * self.h_relative(q, v)
            + 0.5 * om * om * self.j_total(q);
        let strain =
            0.5 * bilinear(&self.rows_of.kpp, q, o, q, o) + 0.5 * bilinear(&self.rows_of.kqq, q, iq, q, iq);
        (kin, strain)
    }

    /// The angular momentum about the axis, `H = dT2/dOm` (N m s).
    pub fn momentum(&self, t: f64, q: &DVector<f64>, v: &DVector<f64>) -> f64 {
        let om = self.hub(t, q, v)[1];
        self.h_relative(q, v) + om * self.j_total(q)
    }

    /// The constraint rows (`m x n`; the hub's column is zero).
    pub fn constraint_rows(&self) -> &DMatrix<f64> {
        &self.rows
    }
}

impl SecondOrder for Modal {
    fn dim(&self) -> usize {
        self.off + self.np + self.nq
    }

    /// The beam's length (the stretch and deflection amplitudes are lengths).
    fn length_scale(&self) -> f64 {
        self.beam.l
    }

    fn residual(
        &self,
        t: f64,
        q: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
        r: &mut DVector<f64>,
    ) {
        let (om, omd) = self.rates(t, v, a);
        let (o, np, nq) = (self.off, self.np, self.nq);
        let iq = o + np;
        let free = o == 1;
        let om2 = om * om;
        let t_of = &self.rows_of;
        let (q, v, a) = (q.as_slice(), v.as_slice(), a.as_slice());
        let (qp, vp, ap_) = (&q[o..iq], &v[o..iq], &a[o..iq]);
        let (qq, vq, aq_) = (&q[iq..iq + nq], &v[iq..iq + nq], &a[iq..iq + nq]);
        let r = r.as_mut_slice();
        // The hub row's sums: Jtot, q^T D q' + p^T Mpp p' + ap^T p', the coupling to p'', q''.
        // Each row sum runs over a contiguous column of the transpose, in the index order.
        let (mut jtot, mut dot, mut coupling) = (self.j_hub() + self.i0, 0.0, 0.0);
        for i in 0..np {
            let (mrow, krow, crow) = (col(&t_of.mpp, i), col(&t_of.kpp, i), col(&t_of.c, i));
            let (mut ma, mut mq, mut mv, mut kq) = (0.0, 0.0, 0.0, 0.0);
            for j in 0..np {
                let m = mrow[j];
                ma += m * ap_[j];
                mq += m * qp[j];
                mv += m * vp[j];
                kq += krow[j] * qp[j];
            }
            let (mut cq, mut cv) = (0.0, 0.0);
            for k in 0..nq {
                cq += crow[k] * qq[k];
                cv += crow[k] * vq[k];
            }
            r[o + i] = ma - 2.0 * om * cv - omd * cq + kq - om2 * (mq + self.ap[i]);
            if free {
                jtot += qp[i] * (mq + 2.0 * self.ap[i]);
                dot += qp[i] * mv + self.ap[i] * vp[i];
                coupling -= cq * ap_[i];
            }
        }
        for k in 0..nq {
            let (mrow, drow, krow) = (col(&t_of.mqq, k), col(&t_of.d, k), col(&t_of.kqq, k));
            let ccol = col(&self.c, k);
            let (mut ma, mut dq, mut dv, mut kq) = (0.0, 0.0, 0.0, 0.0);
            for l in 0..nq {
                ma += mrow[l] * aq_[l];
                let d = drow[l];
                dq += d * qq[l];
                dv += d * vq[l];
                kq += krow[l] * qq[l];
            }
            let (mut ctp, mut ctv) = (self.aq[k], 0.0);
            for i in 0..np {
                ctp += ccol[i] * qp[i];
                ctv += ccol[i] * vp[i];
            }
            r[iq + k] = ma + 2.0 * om * ctv + omd * ctp + kq - om2 * dq;
            if free {
                jtot += qq[k] * dq;
                dot += qq[k] * dv;
                coupling += ctp * aq_[k];
            }
        }
        if free {
            r[0] = jtot * omd + coupling + 2.0 * om * dot - self.base.torque(t);
        }
    }

    fn tangent(
        &self,
        t: f64,
        q: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
        c_m: f64,
        c_c: f64,
        c_k: f64,
        s: &mut DMatrix<f64>,
    ) {
        s.fill(0.0);
        let (om, omd) = self.rates(t, v, a);
        let (o, np, nq) = (self.off, self.np, self.nq);
        let iq = o + np;
        let om2 = om * om;
        // At fixed base motion: mass blockdiag(Mpp, Mqq), gyroscopic 2 Om [[0, -C], [C^T, 0]],
        // stiffness [[Kpp - Om^2 Mpp, -Om' C], [Om' C^T, Kqq - Om^2 D]].
        for i in 0..np {
            for j in 0..np {
                let m = self.mpp[(i, j)];
                s[(o + i, o + j)] = c_m * m + c_k * (self.kpp[(i, j)] - om2 * m);
            }
            for k in 0..nq {
                let c = self.c[(i, k)];
                let x = 2.0 * om * c_c * c + omd * c_k * c;
                s[(o + i, iq + k)] = -x;
                s[(iq + k, o + i)] = x;
            }
        }
        for k in 0..nq {
            for l in 0..nq {
                s[(iq + k, iq + l)] =
                    c_m * self.mqq[(k, l)] + c_k * (self.kqq[(k, l)] - om2 * self.d[(k, l)]);
            }
        }
        if o == 0 {
            return;
        }
        // Free hub: the rows' derivatives in Om = v0 and Om' = a0 (the hub column), and the
        // hub row's in (p, q) and their rates; nothing depends on theta itself.
        //   dr_p/dOm' = -C q,          dr_p/dOm = -2 C q' - 2 Om (Mpp p + ap),
        //   dr_q/dOm' = C^T p + aq,    dr_q/dOm = 2 C^T p' - 2 Om D q,
        //   dr_th/dp'' = -(C q)^T,     dr_th/dp' = 2 Om (Mpp p + ap)^T,
        //   dr_th/dp = (2 Om' (Mpp p + ap) + C q'' + 2 Om Mpp p')^T,
        //   dr_th/dq'' = (C^T p + aq)^T,  dr_th/dq' = 2 Om (D q)^T,
        //   dr_th/dq = (2 Om' D q - C^T p'' + 2 Om D q')^T,
        //   dr_th/dOm' = Jtot,         dr_th/dOm = 2 (q^T D q' + p^T Mpp p' + ap^T p').
        let (mut jtot, mut dot) = (self.j_hub() + self.i0, 0.0);
        for i in 0..np {
            let (mut mq, mut mv) = (0.0, 0.0);
            for j in 0..np {
                let m = self.mpp[(i, j)];
                mq += m * q[o + j];
                mv += m * v[o + j];
            }
            let (mut cq, mut cv, mut ca) = (0.0, 0.0, 0.0);
            for k in 0..nq {
                let c = self.c[(i, k)];
                cq += c * q[iq + k];
                cv += c * v[iq + k];
                ca += c * a[iq + k];
            }
            let mqa = mq + self.ap[i];
            s[(o + i, 0)] = -c_m * cq - c_c * 2.0 * (cv + om * mqa);
            s[(0, o + i)] =
                -c_m * cq + c_c * 2.0 * om * mqa + c_k * (2.0 * omd * mqa + ca + 2.0 * om * mv);
            jtot += q[o + i] * (mq + 2.0 * self.ap[i]);
            dot += q[o + i] * mv + self.ap[i] * v[o + i];
        }
        for k in 0..nq {
            let (mut dq, mut dv) = (0.0, 0.0);
            for l in 0..nq {
                let d = self.d[(k, l)];
                dq += d * q[iq + l];
                dv += d * v[iq + l];
            }
            let (mut ctp, mut ctv, mut cta) = (self.aq[k], 0.0, 0.0);
            for i in 0..np {
                let c = self.c[(i, k)];
                ctp += c * q[o + i];
                ctv += c * v[o + i];
                cta += c * a[o + i];
            }
            s[(iq + k, 0)] = c_m * ctp + c_c * 2.0 * (ctv - om * dq);
            s[(0, iq + k)] =
                c_m * ctp + c_c * 2.0 * om * dq + c_k * (2.0 * omd * dq - cta + 2.0 * om * dv);
            jtot += q[iq + k] * dq;
            dot += q[iq + k] * dv;
        }
        s[(0, 0)] = c_m * jtot + c_c * 2.0 * dot;
    }
}

impl Constraints for Modal {
    fn n_constraints(&self) -> usize {
        self.rows.nrows()
    }

    /// `g = rows q` (linear, scleronomic).
    fn g(&self, _t: f64, q: &DVector<f64>, out: &mut DVector<f64>) {
        for r in 0..self.rows.nrows() {
            let mut g = 0.0;
            for j in 0..self.rows.ncols() {
                g += self.rows[(r, j)] * q[j];
            }
            out[r] = g;
        }
    }

    fn jacobian(&self, _t: f64, _q: &DVector<f64>, out: &mut DMatrix<f64>) {
        out.copy_from(&self.rows);
    }
}
