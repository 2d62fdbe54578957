//! `fe_exact`: the beam as `n` corotational Euler-Bernoulli elements (`corotational.rs`) in the
//! frame of its base, the family's reference model.
//!
//! Coordinates: per node `k = 1..n` its displacement `(u_k, v_k)` from the reference position
//! `(k L/n, 0)` and its rotation `theta_k`, in the base frame (node 0 is clamped to the hub
//! on the axis: all zero); a free hub adds its angle `phi` first. Kinetic energy: the
//! material point at `r = N(X) d` (`d` the nodal positions and rotations; axial position
//! linear, lateral position cubic Hermite in the nodal positions and rotations, as the
//! element's own interpolation) moves in the inertial frame with `R(phi) (r' + phi' J r)`,
//! `J` the quarter turn, so with the constant consistent matrices `M = int rhoA N^T N` and
//! `G = int rhoA N^T J N` (skew)
//!
//! ```text
//! T = 1/2 d'^T M d' + phi' d'^T G d + 1/2 phi'^2 d^T M d (+ 1/2 J_hub phi'^2),
//! ```
//!
//! and Lagrange's equations in residual form (`structural::SecondOrder`) are
//!
//! ```text
//! r_d   = M d'' + 2 phi' G d' + (phi'' G - phi'^2 M) d + f_int(d),
//! r_phi = (J_hub + d^T M d) phi'' + (G d)^T d'' + 2 phi' d^T M d' - tau(t)   (free hub),
//! ```
//!
//! with `phi(t)` given for a prescribed base (then there is no `r_phi`). Every inertial term
//! of the moving frame is kept: Coriolis, the centrifugal load and softening `-phi'^2 M d`,
//! the Euler term `phi'' G d`; the geometric stiffening comes from the corotational
//! internal force. The angular momentum about the axis is `H = J_hub phi' + d'^T G d +
//! phi' d^T M d` (`dT/dphi'`).
//!
//! The tangent is banded: a node's coordinates couple with its neighbours' only, so with
//! the coordinates numbered node by node `|i - j| <= 5` (`kl = ku = 5`), and a free hub's
//! angle couples with every coordinate (one border row and column, first). The model declares
//! it (`SecondOrder::pattern`) and writes its tangent through `math::tangent::Entries`, the
//! same operations into a dense matrix or the banded one (tested: equal entry for entry), so
//! the structural integrators' Newton iterations cost `O(n)` instead of `O(n^3)`.
//!
//! Invariants (tested): `M` is symmetric positive definite, `G` skew; the residual is the
//! derivative of the Lagrangian (its tangent is checked against differences); a static
//! cantilever under a small tip load bends by `P L^3 / (3 EI)`; the in-plane frequencies of the
//! rotating cantilever follow the known centrifugal stiffening. Where it fails: the lateral
//! interpolation of the kinetic energy takes the nodal rotations as slopes, exact for small
//! rotations relative to the base and converging with the mesh otherwise (the deformation of
//! these scenes stays small relative to the base frame); the elements' local strains must stay
//! small.
use nalgebra::{DMatrix, DVector};

use super::base::Base;
use super::corotational::{Element, Mat6, Vec6};
use crate::math::banded::{Band, Border};
use crate::math::tangent::{Entries, Pattern, Tangent};
use crate::structural::SecondOrder;

/// The beam's section and length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Beam {
    /// Length (m).
    pub l: f64,
    /// Axial stiffness (N).
    pub ea: f64,
    /// Bending stiffness (N m^2).
    pub ei: f64,
    /// Mass per length (kg/m).
    pub rho_a: f64,
}

/// The finite-element model of the beam on its base.
#[derive(Debug, Clone)]
pub struct Fe {
    pub beam: Beam,
    pub base: Base,
    /// Number of elements.
    pub n_el: usize,
    elem: Element,
    /// One element's consistent matrices (all elements are alike).
    m_e: Mat6,
    g_e: Mat6,
    /// 1 with a free hub (its angle is coordinate 0), else 0.
    off: usize,
}

/// The two-point Hermite and linear shape functions at `xi` in [0, 1] for an element of
/// length `l`: rows (axial, lateral) of `N` over `(x1, y1, theta1, x2, y2, theta2)`.
fn shape(xi: f64, l: f64) -> [[f64; 6]; 2] {
    let (x2, x3) = (xi * xi, xi * xi * xi);
    [
        [1.0 - xi, 0.0, 0.0, xi, 0.0, 0.0],
        [
            0.0,
            1.0 - 3.0 * x2 + 2.0 * x3,
            l * (xi - 2.0 * x2 + x3),
            0.0,
            3.0 * x2 - 2.0 * x3,
            l * (x3 - x2),
        ],
    ]
}

/// Four-point Gauss-Legendre on [0, 1] (exact to degree 7: `N^T N` has degree 6).
const GAUSS4: [(f64, f64); 4] = [
    (0.069_431_844_202_973_71, 0.173_927_422_568_726_93),
    (0.330_009_478_207_571_9, 0.326_072_577_431_273_07),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_07),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_93),
];

impl Fe {
    /// The model of `beam` in `n_el` elements on `base`.
    ///
    /// # Example
    ///
    /// ```
    /// use mbdbench::model::flexible_beam::base::Base;
    /// use mbdbench::model::flexible_beam::fe::{Beam, Fe};
    /// use mbdbench::structural::SecondOrder;
    ///
    /// let beam = Beam { l: 10.0, ea: 2.8e7, ei: 1.4e4, rho_a: 1.2 };
    /// let fe = Fe::new(beam, 8, Base::SpinUp { w: 4.0, t_up: 15.0 }).unwrap();
    /// assert_eq!(fe.dim(), 24);
    /// assert!((fe.mass_total() - 12.0).abs() < 1e-12);
    /// ```
    pub fn new(beam: Beam, n_el: usize, base: Base) -> Result<Fe, String> {
        if n_el == 0 {
            return Err("the element count must be at least 1".into());
        }
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
        let l0 = beam.l / n_el as f64;
        let (mut m_e, mut g_e) = (Mat6::zeros(), Mat6::zeros());
        for (xi, w) in GAUSS4 {
            let [nx, ny] = shape(xi, l0);
            let k = w * l0 * beam.rho_a;
            for i in 0..6 {
                for j in 0..6 {
                    m_e[(i, j)] += k * (nx[i] * nx[j] + ny[i] * ny[j]);
                    // N^T J N with J (x, y) = (-y, x): x-row^T (-y-row) + y-row^T x-row.
                    g_e[(i, j)] += k * (ny[i] * nx[j] - nx[i] * ny[j]);
                }
            }
        }
        let off = usize::from(matches!(base, Base::Free { .. }));
        Ok(Fe {
            beam,
            base,
            n_el,
            elem: Element {
                l0,
                beta0: 0.0,
                ea: beam.ea,
                ei: beam.ei,
            },
            m_e,
            g_e,
            off,
        })
    }

    /// The total beam mass `rhoA L` as the model's mass matrix sees it.
    pub fn mass_total(&self) -> f64 {
        // Sum of the axial translation entries: 1^T M 1 over x-slots of every element.
        let mut s = 0.0;
        for i in [0, 3] {
            for j in [0, 3] {
                s += self.m_e[(i, j)];
            }
        }
        s * self.n_el as f64
    }

    /// The global index of local coordinate `j` (0..6) of element `e`, None when clamped.
    #[inline]
    fn index(&self, e: usize, j: usize) -> Option<usize> {
        let node = e + j / 3;
        (node > 0).then(|| self.off + 3 * (node - 1) + j % 3)
    }

    /// Gathers element `e`'s slice of `x` (zeros at the clamp).
    #[inline]
    fn gather(&self, e: usize, x: &DVector<f64>) -> Vec6 {
        Vec6::from_fn(|j, _| self.index(e, j).map_or(0.0, |i| x[i]))
    }

    /// Element `e`'s nodal positions and rotations `d_e` (reference plus displacement).
    #[inline]
    fn positions(&self, e: usize, q: &DVector<f64>) -> Vec6 {
        let mut d = self.gather(e, q);
        d[0] += e as f64 * self.elem.l0;
        d[3] += (e + 1) as f64 * self.elem.l0;
        d
    }

    /// The base angle, rate and acceleration: prescribed, or the hub coordinate's.
    #[inline]
    fn frame(&self, t: f64, q: &DVector<f64>, v: &DVector<f64>, a: &DVector<f64>) -> [f64; 3] {
        match self.base.motion(t) {
            Some(m) => [m.theta, m.rate, m.accel],
            None => [q[0], v[0], a[0]],
        }
    }

    /// The lateral displacement of the tip in the base frame (m).
    pub fn tip_deflection(&self, q: &DVector<f64>) -> f64 {
        q[self.off + 3 * (self.n_el - 1) + 1]
    }

    /// The axial displacement of the tip in the base frame (m).
    pub fn tip_axial(&self, q: &DVector<f64>) -> f64 {
        q[self.off + 3 * (self.n_el - 1)]
    }

    /// Kinetic and strain energy at `(t, q, v)` (J).
    pub fn energy(&self, t: f64, q: &DVector<f64>, v: &DVector<f64>) -> (f64, f64) {
        let w = self.frame(t, q, v, v)[1];
        let (mut kin, mut strain) = (0.0, 0.0);
        for e in 0..self.n_el {
            let (d, dv) = (self.positions(e, q), self.gather(e, v));
            kin += 0.5 * dv.dot(&(self.m_e * dv))
                + w * dv.dot(&(self.g_e * d))
                + 0.5 * w * w * d.dot(&(self.m_e * d));
            strain += self.elem.energy(&self.local_coords(e, q));
        }
        if let Base::Free { j_hub, .. } = self.base {
            kin += 0.5 * j_hub * w * w;
        }
        (kin, strain)
    }

    /// The angular momentum about the axis, `dT/dphi'` (N m s).
    pub fn momentum(&self, t: f64, q: &DVector<f64>, v: &DVector<f64>) -> f64 {
        let w = self.frame(t, q, v, v)[1];
        let mut h = match self.base {
            Base::Free { j_hub, .. } => j_hub * w,
            Base::SpinUp { .. } => 0.0,
        };
        for e in 0..self.n_el {
            let (d, dv) = (self.positions(e, q), self.gather(e, v));
            h += dv.dot(&(self.g_e * d)) + w * d.dot(&(self.m_e * d));
        }
        h
    }

    /// The element's coordinates for its corotational law: its displacements on its
    /// reference placed at the origin (the law is translation-invariant; the chord is then
    /// exactly `l0` at rest, with no round-off from the node's distance to the hub).
    #[inline]
    fn local_coords(&self, e: usize, q: &DVector<f64>) -> Vec6 {
        let mut p = self.gather(e, q);
        p[3] += self.elem.l0;
        p
    }
}

impl SecondOrder for Fe {
    fn dim(&self) -> usize {
        self.off + 3 * self.n_el
    }

    /// The beam's length: the nodes' distance from the hub sets the round-off of the
    /// element lengths, so of the displacements.
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
        r.fill(0.0);
        let [_, w, wd] = self.frame(t, q, v, a);
        let (mut dmd, mut hub_coupling, mut dmv) = (0.0, 0.0, 0.0);
        for e in 0..self.n_el {
            let d = self.positions(e, q);
            let (dv, da) = (self.gather(e, v), self.gather(e, a));
            let (md, gd) = (self.m_e * d, self.g_e * d);
            let f = self.elem.force(&self.local_coords(e, q), None);
            let re = self.m_e * da + self.g_e * dv * (2.0 * w) + gd * wd - md * (w * w) + f;
            for j in 0..6 {
                if let Some(i) = self.index(e, j) {
                    r[i] += re[j];
                }
            }
            if self.off == 1 {
                dmd += d.dot(&md);
                hub_coupling += gd.dot(&da);
                dmv += md.dot(&dv);
            }
        }
        if let Base::Free { j_hub, .. } = self.base {
            r[0] = (j_hub + dmd) * wd + hub_coupling + 2.0 * w * dmv - self.base.torque(t);
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
        self.fill_tangent(t, q, v, a, [c_m, c_c, c_k], s);
    }

    /// Banded: node `k`'s coordinates couple with nodes `k - 1 ..= k + 1` only, `|i - j|
    /// <= 5` among the nodal coordinates; a free hub's angle couples with all (a border
    /// row and column first).
    fn pattern(&self) -> Pattern {
        Pattern::Banded(Band {
            n: self.dim(),
            kl: 5,
            ku: 5,
            border: if self.off == 1 {
                Border::First(1)
            } else {
                Border::None
            },
        })
    }

    fn tangent_into(
        &self,
        t: f64,
        q: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
        c_m: f64,
        c_c: f64,
        c_k: f64,
        s: &mut Tangent,
    ) {
        self.fill_tangent(t, q, v, a, [c_m, c_c, c_k], s);
    }
}

impl Fe {
    /// Writes `c_m dr/da + c_c dr/dv + c_k dr/dq` (`c = [c_m, c_c, c_k]`) into `s`, dense
    /// or banded: the same operations on every entry either way.
    fn fill_tangent<T: Entries>(
        &self,
        t: f64,
        q: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
        [c_m, c_c, c_k]: [f64; 3],
        s: &mut T,
    ) {
        s.clear();
        let [_, w, wd] = self.frame(t, q, v, a);
        let mut k_e = Mat6::zeros();
        let free = self.off == 1;
        let mut s00 = 0.0;
        for e in 0..self.n_el {
            let d = self.positions(e, q);
            let (dv, da) = (self.gather(e, v), self.gather(e, a));
            self.elem.force(&self.local_coords(e, q), Some(&mut k_e));
            let se = self.m_e * c_m
                + self.g_e * (2.0 * w * c_c)
                + (self.g_e * wd - self.m_e * (w * w) + k_e) * c_k;
            for j in 0..6 {
                let Some(i) = self.index(e, j) else { continue };
                for k in 0..6 {
                    if let Some(ik) = self.index(e, k) {
                        s.add(i, ik, se[(j, k)]);
                    }
                }
            }
            if !free {
                continue;
            }
            // Free hub: the hub column of r_d and the hub row r_phi.
            let (md, gd, mv) = (self.m_e * d, self.g_e * d, self.m_e * dv);
            let col = gd * c_m + (self.g_e * dv * 2.0 - md * (2.0 * w)) * c_c;
            // d r_phi / d d: 2 phi'' M d + G^T d'' ... as a row: 2 phi'' (M d)^T + d''^T G
            // + 2 phi' (M d')^T; d r_phi / d d' = 2 phi' (M d)^T; d r_phi / d d'' = (G d)^T.
            let row = (md * (2.0 * wd) - self.g_e * da + mv * (2.0 * w)) * c_k
                + md * (2.0 * w * c_c)
                + gd * c_m;
            for j in 0..6 {
                if let Some(i) = self.index(e, j) {
                    s.add(i, 0, col[j]);
                    s.add(0, i, row[j]);
                }
            }
            s00 += d.dot(&md) * c_m + 2.0 * d.dot(&mv) * c_c;
        }
        if let Base::Free { j_hub, .. } = self.base {
            s.set(0, 0, j_hub * c_m + s00);
        }
    }
}

impl super::observe::Beamlike for Fe {
    fn base(&self) -> Base {
        self.base
    }
    fn tip_deflection(&self, q: &DVector<f64>) -> f64 {
        Fe::tip_deflection(self, q)
    }
    fn tip_axial(&self, q: &DVector<f64>) -> f64 {
        Fe::tip_axial(self, q)
    }
    fn hub(&self, t: f64, q: &DVector<f64>, v: &DVector<f64>) -> [f64; 2] {
        let f = self.frame(t, q, v, v);
        [f[0], f[1]]
    }
    fn energy(&self, t: f64, q: &DVector<f64>, v: &DVector<f64>) -> (f64, f64) {
        Fe::energy(self, t, q, v)
    }
    fn momentum(&self, t: f64, q: &DVector<f64>, v: &DVector<f64>) -> f64 {
        Fe::momentum(self, t, q, v)
    }
}
