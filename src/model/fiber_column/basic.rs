//! The beam element in its basic (rigid-body-free) system: from the basic deformations
//! `v = [u, theta_z1, theta_z2, theta_y1, theta_y2, phi]` (elongation, end rotations about
//! the local z and y axes, twist) to the basic forces `q = [N, Mz1, Mz2, My1, My2, T]` and the
//! basic stiffness `dq/dv`, in two formulations:
//!
//! - **force-based** (Spacone, Filippou & Taucer 1996, "Fibre beam-column model for
//!   non-linear analysis of R/C frames", EESD 25; element state determination with element
//!   iterations as in Neuenhofer & Filippou 1997, J. Struct. Eng. 123): the section forces
//!   interpolate the basic forces exactly, `s(x) = b(xi) q` with
//!   `b = [[1,0,0,0,0],[0,xi-1,xi,0,0],[0,0,0,xi-1,xi]]`, `xi = x/L` (equilibrium in the
//!   basic system, no element loads); the element flexibility is
//!   `F = L sum_i w_i b_i^T f_s,i b_i` over the Gauss-Lobatto sections. Given a trial `v`,
//!   each iteration forms the deformations compatible with the current forces,
//!   `v_q = L sum_i w_i b_i^T (e_i + f_s,i (b_i q - s_i))`, corrects `q += F^-1 (v - v_q)`, and
//!   moves every section to `e_i += f_s,i (b_i q - s_i)`; it stops when the energy of the
//!   correction `|dv . dq|` is below `tol` times the element's work scale `|v . q|` (the
//!   first iteration's when larger). Converged, `q` is in equilibrium with every section to
//!   that tolerance and the tangent is `F^-1` (consistent). An elastic section converges in
//!   one iteration and gives the exact stiffness of a prismatic member in the basic system;
//! - **displacement-based**: cubic Hermite transverse and linear axial displacements, so
//!   `e(xi) = a(xi) v` with `a = [[1/L,0,...],[0,(6xi-4)/L,(6xi-2)/L,0,0],[0,0,0,(6xi-4)/L,
//!   (6xi-2)/L]]`, `q = L sum_i w_i a_i^T s_i`, `k = L sum_i w_i a_i^T k_s,i a_i` over
//!   Gauss-Legendre sections: no iterations, but the linear curvature field is exact only
//!   while the section response is linear, so the member needs several elements where it
//!   yields (the mesh dependence the report shows).
//!
//! Torsion is elastic in both, `T = GJ phi / L`. The basic system neglects the axial force's
//! effect on bending inside the element (the corotational frame carries the geometry): its
//! error is second order in the element length. Where it fails: a section whose tangent is
//! singular (every fiber at zero stiffness) makes the force-based element's `f_s` undefined
//! (an `ElementFailure`), and element iterations that do not converge within their limit are
//! reported, not hidden.
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use super::corotational::{Matrix6, Vector6};
use super::quadrature::{legendre_rule, lobatto_rule};
use super::section::Section;

type V5 = SVector<f64, 5>;
type M5 = SMatrix<f64, 5, 5>;
type M35 = SMatrix<f64, 3, 5>;

/// Why an element's state determination failed.
#[derive(Debug, Clone, PartialEq)]
pub enum ElementFailure {
    /// A section's tangent could not be inverted.
    SingularSection { point: usize },
    /// The element flexibility could not be inverted.
    SingularFlexibility,
    /// The element iterations did not converge.
    NoConvergence { iterations: usize, energy: f64 },
    /// A non-finite force or deformation.
    NotFinite,
    /// The run's work budget allows no more element iterations (`meter.rs`).
    WorkLimit,
}

impl std::fmt::Display for ElementFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::SingularSection { point } => {
                write!(f, "singular section tangent at point {point}")
            }
            Self::SingularFlexibility => write!(f, "singular element flexibility"),
            Self::NoConvergence { iterations, energy } => write!(
                f,
                "element iterations did not converge in {iterations} (last correction energy {energy:e})"
            ),
            Self::NotFinite => write!(f, "non-finite element state"),
            Self::WorkLimit => write!(f, "the run's budget allows no more element iterations"),
        }
    }
}

fn b_matrix(xi: f64) -> M35 {
    let mut b = M35::zeros();
    b[(0, 0)] = 1.0;
    b[(1, 1)] = xi - 1.0;
    b[(1, 2)] = xi;
    b[(2, 3)] = xi - 1.0;
    b[(2, 4)] = xi;
    b
}

fn a_matrix(xi: f64, l: f64) -> M35 {
    let mut a = M35::zeros();
    a[(0, 0)] = 1.0 / l;
    a[(1, 1)] = (6.0 * xi - 4.0) / l;
    a[(1, 2)] = (6.0 * xi - 2.0) / l;
    a[(2, 3)] = (6.0 * xi - 4.0) / l;
    a[(2, 4)] = (6.0 * xi - 2.0) / l;
    a
}

fn with_torsion(q: &V5, k: &M5, gj_l: f64, phi: f64) -> (Vector6, Matrix6) {
    let mut q6 = Vector6::zeros();
    q6.fixed_rows_mut::<5>(0).copy_from(q);
    q6[5] = gj_l * phi;
    let mut k6 = Matrix6::zeros();
    k6.fixed_view_mut::<5, 5>(0, 0).copy_from(k);
    k6[(5, 5)] = gj_l;
    (q6, k6)
}

/// The trial or committed state of a force-based element.
#[derive(Debug, Clone)]
struct FbState {
    /// The basic deformations the state is converged to.
    v: V5,
    q: V5,
    e: Vec<Vector3<f64>>,
    s: Vec<Vector3<f64>>,
    fs: Vec<Matrix3<f64>>,
    flex: M5,
    /// `flex^-1` (None: singular), inverted once when `flex` is set: the element iterations
    /// and the tangent of every state determination use it.
    kel: Option<M5>,
}

/// A force-based element in its basic system.
#[derive(Debug, Clone)]
pub struct ForceBased {
    l: f64,
    gj: f64,
    xi: Vec<f64>,
    w: Vec<f64>,
    b: Vec<M35>,
    sections: Vec<Section>,
    tol: f64,
    max_iter: usize,
    trial: FbState,
    committed: FbState,
    /// Element iterations since construction.
    pub iterations: u64,
    /// Subdivided state determinations since construction (see [`ForceBased::update`]).
    pub subdivisions: u64,
    /// The element iterations stop with [`ElementFailure::WorkLimit`] when `iterations`
    /// reaches this ([`ForceBased::allow`]; unlimited by default).
    stop_at: u64,
}

impl ForceBased {
    /// An element of length `l` with torsional stiffness `gj`, `points` Gauss-Lobatto
    /// sections (copies of `section`), element tolerance `tol` (relative energy) and
    /// iteration limit.
    ///
    /// # Example
    ///
    /// An elastic member's basic stiffness is exact: `4EI/L, 2EI/L` for the end rotations.
    ///
    /// ```
    /// use mbdbench::model::fiber_column::basic::ForceBased;
    /// use mbdbench::model::fiber_column::section::{ElasticSection, Section};
    /// use nalgebra::SVector;
    ///
    /// let s = Section::Elastic(ElasticSection::new(100.0, 3.0, 2.0).unwrap());
    /// let mut e = ForceBased::new(2.0, 1.0, &s, 5, 1e-14, 20).unwrap();
    /// let (q, k) = e.update(&SVector::<f64, 6>::new(0.0, 1e-3, 0.0, 0.0, 0.0, 0.0)).unwrap();
    /// assert!((k[(1, 1)] - 4.0 * 3.0 / 2.0).abs() < 1e-12);
    /// assert!((k[(1, 2)] - 2.0 * 3.0 / 2.0).abs() < 1e-12);
    /// assert!((q[1] - 6e-3).abs() < 1e-15);
    /// ```
    pub fn new(
        l: f64,
        gj: f64,
        section: &Section,
        points: usize,
        tol: f64,
        max_iter: usize,
    ) -> Result<Self, String> {
        let (xi, w) = lobatto_rule(points)?;
        let b: Vec<M35> = xi.iter().map(|&x| b_matrix(x)).collect();
        let sections = vec![section.clone(); points];
        let mut fs = Vec::with_capacity(points);
        for (i, s) in sections.iter().enumerate() {
            fs.push(
                s.initial_tangent()
                    .try_inverse()
                    .ok_or(format!("singular initial section tangent at point {i}"))?,
            );
        }
        let mut flex = M5::zeros();
        for i in 0..points {
            flex += b[i].transpose() * fs[i] * b[i] * (w[i] * l);
        }
        let state = FbState {
            v: V5::zeros(),
            q: V5::zeros(),
            e: vec![Vector3::zeros(); points],
            s: vec![Vector3::zeros(); points],
            fs,
            flex,
            kel: flex.try_inverse(),
        };
        Ok(Self {
            l,
            gj,
            xi,
            w,
            b,
            sections,
            tol,
            max_iter,
            trial: state.clone(),
            committed: state,
            iterations: 0,
            subdivisions: 0,
            stop_at: u64::MAX,
        })
    }

    /// Allows `n` more element iterations (the run's budget, `meter.rs`); past them a state
    /// determination fails with [`ElementFailure::WorkLimit`], without subdividing.
    pub fn allow(&mut self, n: u64) {
        self.stop_at = self.iterations.saturating_add(n);
    }

    /// The section positions `xi = x/L` (Gauss-Lobatto).
    pub fn points(&self) -> &[f64] {
        &self.xi
    }

    /// The trial basic forces and tangent for the trial basic deformations `v`: element
    /// iterations from the last trial state; if they fail, the state determination restarts
    /// from the committed state with the deformation increment cut into 4, 16, 64 equal
    /// parts, each iterated to convergence (Neuenhofer & Filippou's remedy; OpenSees' element
    /// does the same by default), counted in `subdivisions`. A converged state satisfies the
    /// same tolerance whichever path reached it.
    pub fn update(&mut self, v: &Vector6) -> Result<(Vector6, Matrix6), ElementFailure> {
        let v5 = v.fixed_rows::<5>(0).into_owned();
        let failure = self.iterate_to(&v5).err();
        if let Some(first) = failure {
            if first == ElementFailure::WorkLimit {
                return Err(first);
            }
            let mut done = false;
            for parts in [4usize, 16, 64] {
                self.subdivisions += 1;
                self.revert();
                let v0 = self.committed.v;
                let mut ok = true;
                for k in 1..=parts {
                    let target = v0 + (v5 - v0) * (k as f64 / parts as f64);
                    match self.iterate_to(&target) {
                        Ok(()) => {}
                        Err(ElementFailure::WorkLimit) => return Err(ElementFailure::WorkLimit),
                        Err(_) => {
                            ok = false;
                            break;
                        }
                    }
                }
                if ok {
                    done = true;
                    break;
                }
            }
            if !done {
                return Err(first);
            }
        }
        let st = &self.trial;
        let kel = st.kel.ok_or(ElementFailure::SingularFlexibility)?;
        Ok(with_torsion(&st.q, &kel, self.gj / self.l, v[5]))
    }

    /// Element iterations from the current trial state to the basic deformations `v5`.
    fn iterate_to(&mut self, v5: &V5) -> Result<(), ElementFailure> {
        let n = self.sections.len();
        let st = &mut self.trial;
        let mut first = 0.0f64;
        let mut last = f64::INFINITY;
        for iter in 0..self.max_iter {
            if self.iterations >= self.stop_at {
                return Err(ElementFailure::WorkLimit);
            }
            self.iterations += 1;
            let mut vq = V5::zeros();
            for i in 0..n {
                let r = st.e[i] + st.fs[i] * (self.b[i] * st.q - st.s[i]);
                vq += self.b[i].transpose() * r * (self.w[i] * self.l);
            }
            let dv = v5 - vq;
            let kel = st.kel.ok_or(ElementFailure::SingularFlexibility)?;
            let dq = kel * dv;
            st.q += dq;
            let energy = dv.dot(&dq).abs();
            if iter == 0 {
                first = energy;
            }
            last = energy;
            let mut flex = M5::zeros();
            for i in 0..n {
                st.e[i] += st.fs[i] * (self.b[i] * st.q - st.s[i]);
                let (s, ks) = self.sections[i].set_trial(&st.e[i]);
                st.s[i] = s;
                st.fs[i] = ks
                    .try_inverse()
                    .ok_or(ElementFailure::SingularSection { point: i })?;
                flex += self.b[i].transpose() * st.fs[i] * self.b[i] * (self.w[i] * self.l);
            }
            st.flex = flex;
            st.kel = flex.try_inverse();
            if !st.q.iter().all(|x| x.is_finite()) {
                return Err(ElementFailure::NotFinite);
            }
            let scale = v5.dot(&st.q).abs().max(first);
            if energy <= self.tol * scale {
                st.v = *v5;
                return Ok(());
            }
        }
        Err(ElementFailure::NoConvergence {
            iterations: self.max_iter,
            energy: last,
        })
    }

    /// Commits the trial state (sections and element).
    pub fn commit(&mut self) {
        for s in &mut self.sections {
            s.commit();
        }
        self.committed.clone_from(&self.trial);
    }

    /// Returns to the last committed state.
    pub fn revert(&mut self) {
        for s in &mut self.sections {
            s.revert();
        }
        self.trial.clone_from(&self.committed);
    }

    /// The sections' work and recoverable energy integrated over the element (J), with the
    /// torsion's elastic energy at twist `phi`.
    pub fn energies(&self, phi: f64) -> (f64, f64) {
        integrate_energies(
            &self.sections,
            &self.w,
            self.l,
            0.5 * self.gj / self.l * phi * phi,
        )
    }
}

fn integrate_energies(sections: &[Section], w: &[f64], l: f64, torsion: f64) -> (f64, f64) {
    let mut work = torsion;
    let mut rec = torsion;
    for (s, w) in sections.iter().zip(w) {
        work += w * l * s.work();
        rec += w * l * s.recoverable();
    }
    (work, rec)
}

/// A displacement-based element in its basic system.
#[derive(Debug, Clone)]
pub struct DispBased {
    l: f64,
    gj: f64,
    w: Vec<f64>,
    a: Vec<M35>,
    sections: Vec<Section>,
}

impl DispBased {
    /// An element of length `l`, torsional stiffness `gj`, `points` Gauss-Legendre sections.
    ///
    /// # Example
    ///
    /// ```
    /// use mbdbench::model::fiber_column::basic::DispBased;
    /// use mbdbench::model::fiber_column::section::{ElasticSection, Section};
    /// use nalgebra::SVector;
    ///
    /// let s = Section::Elastic(ElasticSection::new(100.0, 3.0, 2.0).unwrap());
    /// let mut e = DispBased::new(2.0, 1.0, &s, 2).unwrap();
    /// let (_, k) = e.update(&SVector::<f64, 6>::zeros());
    /// assert!((k[(3, 3)] - 4.0 * 2.0 / 2.0).abs() < 1e-12);
    /// assert!((k[(0, 0)] - 100.0 / 2.0).abs() < 1e-12);
    /// ```
    pub fn new(l: f64, gj: f64, section: &Section, points: usize) -> Result<Self, String> {
        let (xi, w) = legendre_rule(points)?;
        Ok(Self {
            l,
            gj,
            a: xi.iter().map(|&x| a_matrix(x, l)).collect(),
            w,
            sections: vec![section.clone(); points],
        })
    }

    /// The trial basic forces and tangent for the trial basic deformations `v`.
    pub fn update(&mut self, v: &Vector6) -> (Vector6, Matrix6) {
        let v5 = v.fixed_rows::<5>(0).into_owned();
        let mut q = V5::zeros();
        let mut k = M5::zeros();
        for i in 0..self.sections.len() {
            let (s, ks) = self.sections[i].set_trial(&(self.a[i] * v5));
            let wl = self.w[i] * self.l;
            q += self.a[i].transpose() * s * wl;
            k += self.a[i].transpose() * ks * self.a[i] * wl;
        }
        with_torsion(&q, &k, self.gj / self.l, v[5])
    }

    /// Commits the trial state.
    pub fn commit(&mut self) {
        for s in &mut self.sections {
            s.commit();
        }
    }

    /// Returns to the last committed state.
    pub fn revert(&mut self) {
        for s in &mut self.sections {
            s.revert();
        }
    }

    /// See [`ForceBased::energies`].
    pub fn energies(&self, phi: f64) -> (f64, f64) {
        integrate_energies(
            &self.sections,
            &self.w,
            self.l,
            0.5 * self.gj / self.l * phi * phi,
        )
    }
}

/// A basic element of either formulation.
#[derive(Debug, Clone)]
pub enum Basic {
    /// Boxed: its element state is ten times the displacement-based one's.
    Force(Box<ForceBased>),
    Disp(DispBased),
}

impl Basic {
    /// The trial basic forces and tangent.
    pub fn update(&mut self, v: &Vector6) -> Result<(Vector6, Matrix6), ElementFailure> {
        match self {
            Basic::Force(e) => e.update(v),
            Basic::Disp(e) => Ok(e.update(v)),
        }
    }
    /// Commits the trial state.
    pub fn commit(&mut self) {
        match self {
            Basic::Force(e) => e.commit(),
            Basic::Disp(e) => e.commit(),
        }
    }
    /// Returns to the last committed state.
    pub fn revert(&mut self) {
        match self {
            Basic::Force(e) => e.revert(),
            Basic::Disp(e) => e.revert(),
        }
    }
    /// Work and recoverable energy (J) at twist `phi`.
    pub fn energies(&self, phi: f64) -> (f64, f64) {
        match self {
            Basic::Force(e) => e.energies(phi),
            Basic::Disp(e) => e.energies(phi),
        }
    }
    /// Element iterations so far (0 for the displacement-based element).
    pub fn iterations(&self) -> u64 {
        match self {
            Basic::Force(e) => e.iterations,
            Basic::Disp(_) => 0,
        }
    }
    /// Allows `n` more element iterations (a force-based element; nothing for the other).
    pub fn allow(&mut self, n: u64) {
        if let Basic::Force(e) = self {
            e.allow(n);
        }
    }
    /// Subdivided state determinations so far (0 for the displacement-based element).
    pub fn subdivisions(&self) -> u64 {
        match self {
            Basic::Force(e) => e.subdivisions,
            Basic::Disp(_) => 0,
        }
    }
}
