//! The cantilever column as a structure: `n` two-node corotational elements along the global
//! z axis from a clamped base, six unknowns per free node (the displacement and the spatial
//! rotation increment `dw`), the nodes' rotations held in a [`RotationChart`], and the static
//! Newton step under load control with, optionally, one prescribed displacement (the
//! displacement control of the cyclic scenes: the prescribed degree of freedom leaves the
//! unknowns and its residual is the force that holds it, the base shear's counterpart).
//!
//! Newton's step solves `K dx = -(f_int - f_ext)` on the free unknowns (the first iteration
//! of a step also carries the prescribed increment, `K_ff dx_f = -(r_f + K_fp dx_p)`),
//! moves the nodes by `dx` and turns their rotations with each chart's retraction; the
//! element states are trial states until the step converges and are then committed (or
//! reverted, on failure). With [`Algorithm::Krylov`] the step's first tangent is reused and
//! the corrections are accelerated over the subspace of the previous ones (`krylov.rs`,
//! Carlson & Miller; the tangent refreshed after `KRYLOV_DIM + 1` corrections, as OpenSees).
//! A dynamic step adds the inertia and damping of [`Inertia`] (the schemes in `dynamic.rs`).
//! Convergence: the energy of the correction `|dx . r| / 2` at or below
//! the step's tolerance (J), as OpenSees' `EnergyIncr`. The in-plane rotation of the top,
//! `top_turn`, is the sum of the increments' components about global y (unwrapped: it
//! passes `pi` and `2 pi` without jumping, whatever the chart).
//!
//! Invariants: the base node never moves; between steps every element is committed; the
//! tangent is that of the update `R <- exp([dw]x) R` (`corotational.rs`), assembled densely
//! (the columns here have at most a few hundred unknowns). Where it fails: a load beyond the
//! column's limit point under load control (no equilibrium nearby) ends in a typed
//! `NewtonFailure`.
use nalgebra::{DMatrix, DVector, Vector3};

use super::basic::{Basic, ElementFailure};
use super::meter::Meter;
use crate::rotation::RotationChart;
use super::corotational::Corotational;
use super::krylov::Krylov;
use crate::math::lu::{DenseLu as Lu, LinearSolve};

/// Why a static step failed.
#[derive(Debug, Clone, PartialEq)]
pub enum NewtonFailure {
    /// No convergence within the iteration limit.
    NoConvergence { iterations: usize, energy: f64 },
    /// An element's state determination failed.
    Element {
        element: usize,
        failure: ElementFailure,
    },
    /// The tangent is singular.
    SingularTangent,
    /// The run's budget is spent (`meter.rs`; the message names the key).
    WorkLimit(String),
}

impl std::fmt::Display for NewtonFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NoConvergence { iterations, energy } => write!(
                f,
                "Newton did not converge in {iterations} iterations (last energy {energy:e} J)"
            ),
            Self::Element { element, failure } => write!(f, "element {element}: {failure}"),
            Self::SingularTangent => write!(f, "singular tangent"),
            Self::WorkLimit(why) => write!(f, "{why}"),
        }
    }
}

/// One prescribed displacement: free-node unknown index and its target value.
#[derive(Debug, Clone, Copy)]
pub struct Prescribed {
    pub dof: usize,
    pub value: f64,
}

/// The inertia and damping of a dynamic step (Newmark's family, iterating on the
/// displacement): a lumped mass per unknown (0 for the massless ones), mass-proportional
/// damping `C = a0 M`, and the step's predictors, so that at the trial displacement `u`
/// the (effective) acceleration is `a = c_a (u - u_pred)` and the (effective) velocity
/// `v = v_pred + c_v a` (Newmark: `c_a = 1/(beta h^2)`, `c_v = gamma h`). The residual is
/// `w_int f_int(u) + (1 - w_int) f_old - f_ext + M (a + a0 v)` and the tangent
/// `w_int K + M c_a (1 + a0 c_v)`: `w_int = 1` is Newmark's end-point equilibrium, `w_int < 1`
/// the weighted internal force of HHT, the generalized-alpha method and the midpoint rule
/// (`dynamic.rs`), with `f_old` the internal force of the last converged state.
///
/// `work_consistent = Some(W_n)` (the elements' work at the last converged state) adds the
/// energy-consistent correction of the midpoint rule: with `du = u - u_n` on the
/// translations and `e = (W(u) - W_n) - du . f_bar` (`f_bar` the weighted internal force), the
/// residual gains `e M du / (du . M du)`, so that the structural work of the corrected force
/// over the step, `du . f_bar + e`, equals the elements' own (fiber-trapezoid) work exactly.
/// The correction is `O(h^2)` and its derivative is left out of the tangent; it is applied
/// only when `e` exceeds 64 ulps of the work sums (below that it is round-off), and `e` is
/// held once the iteration is close (`FREEZE`), so the closure is to the fibres' work as
/// evaluated a few corrections before convergence.
#[derive(Debug, Clone, Copy)]
pub struct Inertia<'a> {
    pub mass: &'a DVector<f64>,
    pub a0: f64,
    pub c_a: f64,
    pub c_v: f64,
    pub u_pred: &'a DVector<f64>,
    pub v_pred: &'a DVector<f64>,
    /// The weight of the trial internal force (1: Newmark).
    pub w_int: f64,
    /// The internal force of the last converged state (used when `w_int != 1`).
    pub f_old: Option<&'a DVector<f64>>,
    /// The elements' work at the last converged state, for the energy-consistent correction.
    pub work_consistent: Option<f64>,
}

impl<'a> Inertia<'a> {
    /// Newmark's end-point form (`w_int = 1`, no correction).
    pub fn newmark(
        mass: &'a DVector<f64>,
        a0: f64,
        c_a: f64,
        c_v: f64,
        u_pred: &'a DVector<f64>,
        v_pred: &'a DVector<f64>,
    ) -> Self {
        Self {
            mass,
            a0,
            c_a,
            c_v,
            u_pred,
            v_pred,
            w_int: 1.0,
            f_old: None,
            work_consistent: None,
        }
    }
}

/// How the Newton step moves toward equilibrium (the `newton_*` integrators' variants).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Algorithm {
    /// Full Newton: the tangent of the current configuration every iteration.
    Newton,
    /// Newton with the energy line search (`search_line`).
    LineSearch,
    /// Krylov-accelerated Newton (Carlson & Miller): the step's first tangent, its
    /// corrections accelerated in the subspace of the previous ones.
    Krylov,
}

/// The Krylov subspace's largest dimension (OpenSees' `KrylovNewton` default `maxDim`).
pub const KRYLOV_DIM: usize = 3;

/// The energy-consistent correction's `e` is re-evaluated while the last correction's energy
/// exceeds `FREEZE` times the tolerance and then held: the fibres' work carries the element
/// iterations' own tolerance as noise, which, divided by `|du|`, would otherwise keep the
/// residual from settling (measured without the hold: Newton stalled at 1e-19 J against
/// 1e-20 J at step 2433 of the pulse).
const FREEZE: f64 = 1e4;

/// The counts of one converged step.
#[derive(Debug, Clone, Copy, Default)]
pub struct StepCount {
    pub iterations: usize,
    pub element_iterations: u64,
    pub element_subdivisions: u64,
}

/// The column: elements, node states and the Newton workspace.
pub struct Column<C: RotationChart> {
    elements: Vec<(Corotational, Basic)>,
    x0: Vec<Vector3<f64>>,
    /// Node displacements from `x0` (kept apart from the positions, so increments far below
    /// the positions' rounding, 4e-16 m at 3 m, are not lost).
    u: Vec<Vector3<f64>>,
    rot: Vec<C::Rot>,
    u_c: Vec<Vector3<f64>>,
    rot_c: Vec<C::Rot>,
    top_turn: f64,
    top_turn_c: f64,
    f_int: DVector<f64>,
    k: DMatrix<f64>,
    lu: Lu,
    dx: DVector<f64>,
    /// The residual `f_int - f_ext` of the current iteration (a buffer).
    r: DVector<f64>,
    /// `f_int`, `k` and `base` are those of the current configuration and element states.
    assembled: bool,
    base: Vector3<f64>,
    u_ls: Vec<Vector3<f64>>,
    rot_ls: Vec<C::Rot>,
    /// Trial evaluations of the line search since construction.
    pub line_evaluations: u64,
    krylov: Krylov,
    /// The energy-consistent correction's `e` in use (see [`Inertia`]).
    work_e: f64,
    /// The run's budgets as the iterations spend them (unlimited unless set).
    meter: Meter,
}

impl<C: RotationChart> Column<C> {
    /// A column of height `h` along global z in `elements.len()` equal elements (their basic
    /// elements given bottom first), local y along global x (the plane of bending x-z).
    pub fn new(h: f64, elements: Vec<Basic>) -> Result<Self, String> {
        let n = elements.len();
        if n == 0 {
            return Err("a column needs at least one element".into());
        }
        let x0: Vec<Vector3<f64>> = (0..=n)
            .map(|i| Vector3::new(0.0, 0.0, h * i as f64 / n as f64))
            .collect();
        let mut els = Vec::with_capacity(n);
        for (i, b) in elements.into_iter().enumerate() {
            els.push((Corotational::new(x0[i], x0[i + 1], Vector3::x())?, b));
        }
        let dim = 6 * n;
        Ok(Self {
            elements: els,
            u: vec![Vector3::zeros(); n + 1],
            u_c: vec![Vector3::zeros(); n + 1],
            x0,
            rot: vec![C::identity(); n + 1],
            rot_c: vec![C::identity(); n + 1],
            top_turn: 0.0,
            top_turn_c: 0.0,
            f_int: DVector::zeros(dim),
            k: DMatrix::zeros(dim, dim),
            lu: Lu::new(dim),
            dx: DVector::zeros(dim),
            r: DVector::zeros(dim),
            assembled: false,
            base: Vector3::zeros(),
            u_ls: vec![Vector3::zeros(); n + 1],
            rot_ls: vec![C::identity(); n + 1],
            line_evaluations: 0,
            krylov: Krylov::new(dim, KRYLOV_DIM),
            work_e: 0.0,
            meter: Meter::unlimited(),
        })
    }

    /// Meters the iterations against a run's budgets from now on.
    pub fn set_meter(&mut self, meter: Meter) {
        self.meter = meter;
    }

    /// The number of unknowns (6 per free node).
    pub fn dim(&self) -> usize {
        6 * self.elements.len()
    }

    /// The unknown index of component `c` (0..6: ux, uy, uz, wx, wy, wz) of the top node.
    pub fn top_dof(&self, c: usize) -> usize {
        self.dim() - 6 + c
    }

    /// The top node's displacement from its initial position.
    pub fn top_displacement(&self) -> Vector3<f64> {
        let n = self.elements.len();
        self.u[n]
    }

    /// The top's accumulated in-plane rotation (about global y), unwrapped.
    pub fn top_turn(&self) -> f64 {
        self.top_turn
    }

    /// The top node's rotation matrix.
    pub fn top_rotation_matrix(&self) -> nalgebra::Matrix3<f64> {
        C::matrix(&self.rot[self.elements.len()])
    }

    /// The elements (corotational frame and basic element).
    pub fn elements(&self) -> &[(Corotational, Basic)] {
        &self.elements
    }

    /// Assembles the internal force and tangent of the trial state; returns the base node's
    /// internal force, which equals the support's reaction on the column.
    fn assemble(&mut self) -> Result<Vector3<f64>, NewtonFailure> {
        self.assembled = false;
        self.f_int.fill(0.0);
        self.k.fill(0.0);
        let mut base = Vector3::zeros();
        self.meter.assembly()?;
        for (e, (cr, basic)) in self.elements.iter_mut().enumerate() {
            let (r1, r2) = (C::matrix(&self.rot[e]), C::matrix(&self.rot[e + 1]));
            let (x1, x2) = (self.x0[e] + self.u[e], self.x0[e + 1] + self.u[e + 1]);
            let (v, kin) = cr.at(&x1, &x2, &r1, &r2);
            let before = basic.iterations();
            basic.allow(self.meter.element_allowance());
            let updated = basic.update(&v);
            let force = matches!(basic, Basic::Force(_));
            let spent = if force { basic.iterations() - before } else { 1 };
            self.meter.elements(spent, force)?;
            let (qb, kb) = updated.map_err(|failure| match failure {
                ElementFailure::WorkLimit => self.meter.spent(),
                failure => NewtonFailure::Element {
                    element: e,
                    failure,
                },
            })?;
            let (f, k) = cr.global_at(&kin, &qb, &kb);
            if e == 0 {
                base = f.fixed_rows::<3>(0).into_owned();
            }
            // Global unknowns of the element's 12: node e (absent for the base) then e + 1.
            let map = |i: usize| -> Option<usize> {
                let node = e + i / 6;
                (node > 0).then(|| 6 * (node - 1) + i % 6)
            };
            for i in 0..12 {
                let Some(gi) = map(i) else { continue };
                self.f_int[gi] += f[i];
                for j in 0..12 {
                    if let Some(gj) = map(j) {
                        self.k[(gi, gj)] += k[(i, j)];
                    }
                }
            }
        }
        self.base = base;
        self.assembled = true;
        Ok(base)
    }

    fn apply(&mut self, dx: &DVector<f64>) {
        self.apply_scaled(dx, 1.0);
    }

    fn apply_scaled(&mut self, dx: &DVector<f64>, eta: f64) {
        let top = self.u.len() - 1;
        let before = C::matrix(&self.rot[top]);
        for node in 1..self.u.len() {
            let o = 6 * (node - 1);
            self.u[node] += Vector3::new(dx[o], dx[o + 1], dx[o + 2]) * eta;
            let dw = Vector3::new(dx[o + 3], dx[o + 4], dx[o + 5]) * eta;
            self.rot[node] = C::rotate(&self.rot[node], &dw);
        }
        // The rotation the chart actually applied (a first-order retraction turns by less
        // than |dw|), about global y.
        let turned = crate::math::so3::log(&(C::matrix(&self.rot[top]) * before.transpose()));
        self.top_turn += turned.y;
    }

    /// One static step to equilibrium with the external loads `f_ext` (length `dim`) and an
    /// optional prescribed displacement; commits on success, reverts on failure. Returns the
    /// counts and the support's reaction on the column at the base (the column's internal
    /// force there): the base shear is `-R.x`, the axial force `-R.z`.
    pub fn step(
        &mut self,
        f_ext: &DVector<f64>,
        prescribed: Option<Prescribed>,
        tol: f64,
        max_iter: usize,
        algorithm: Algorithm,
    ) -> Result<(StepCount, Vector3<f64>), NewtonFailure> {
        self.step_dynamic(f_ext, prescribed, None, tol, max_iter, algorithm)
    }

    /// [`Column::step`] with inertia (a dynamic step; `None`: static).
    pub fn step_dynamic(
        &mut self,
        f_ext: &DVector<f64>,
        prescribed: Option<Prescribed>,
        inertia: Option<Inertia<'_>>,
        tol: f64,
        max_iter: usize,
        algorithm: Algorithm,
    ) -> Result<(StepCount, Vector3<f64>), NewtonFailure> {
        let count = |c: &Self| -> (u64, u64) {
            c.elements.iter().fold((0, 0), |(i, s), (_, b)| {
                (i + b.iterations(), s + b.subdivisions())
            })
        };
        let before = count(self);
        let out = self.iterate(f_ext, prescribed, inertia, tol, max_iter, algorithm);
        let after = count(self);
        match out {
            Ok((iterations, base)) => {
                for (_, b) in &mut self.elements {
                    b.commit();
                }
                self.u_c.clone_from(&self.u);
                self.rot_c.clone_from(&self.rot);
                self.top_turn_c = self.top_turn;
                let count = StepCount {
                    iterations,
                    element_iterations: after.0 - before.0,
                    element_subdivisions: after.1 - before.1,
                };
                Ok((count, base))
            }
            Err(e) => {
                self.revert();
                Err(e)
            }
        }
    }

    /// Returns every element and node to the last committed state.
    pub fn revert(&mut self) {
        self.assembled = false;
        for (_, b) in &mut self.elements {
            b.revert();
        }
        self.u.clone_from(&self.u_c);
        self.rot.clone_from(&self.rot_c);
        self.top_turn = self.top_turn_c;
    }

    fn iterate(
        &mut self,
        f_ext: &DVector<f64>,
        prescribed: Option<Prescribed>,
        inertia: Option<Inertia<'_>>,
        tol: f64,
        max_iter: usize,
        algorithm: Algorithm,
    ) -> Result<(usize, Vector3<f64>), NewtonFailure> {
        if algorithm == Algorithm::Krylov {
            return self.iterate_krylov(f_ext, prescribed, inertia, tol, max_iter);
        }
        let line_search = algorithm == Algorithm::LineSearch;
        let mut energy = f64::INFINITY;
        for iter in 1..=max_iter {
            self.meter.newton()?;
            // The first iteration of a step starts where the last step converged: its
            // assembly is still valid (same configuration, committed element states).
            if !(iter == 1 && self.assembled) {
                self.assemble()?;
            }
            let mut r = self.take_residual();
            self.form_residual(f_ext, inertia, &mut r, energy > FREEZE * tol);
            let dx_p = self.prescribed_increment(prescribed, iter);
            self.factor_tangent(inertia, prescribed, dx_p, &mut r)?;
            self.dx.copy_from(&r);
            self.dx.neg_mut();
            self.lu
                .solve_in_place(&mut self.dx)
                .map_err(|_| NewtonFailure::SingularTangent)?;
            if let Some(p) = prescribed {
                self.dx[p.dof] = dx_p;
            }
            energy = 0.5 * self.dx.dot(&r).abs();
            if !energy.is_finite() {
                break;
            }
            let dx = std::mem::replace(&mut self.dx, DVector::zeros(0));
            if line_search && inertia.is_none() && dx_p == 0.0 && energy > tol {
                self.search_line(&dx, &r, f_ext, prescribed)?;
            } else {
                self.apply(&dx);
            }
            self.dx = dx;
            self.r = r;
            if energy <= tol && dx_p == 0.0 {
                // Leave the element states consistent with the final configuration.
                let base = self.assemble()?;
                return Ok((iter, base));
            }
        }
        Err(NewtonFailure::NoConvergence {
            iterations: max_iter,
            energy,
        })
    }

    /// Krylov-accelerated Newton (`krylov.rs`): the tangent is formed and factored at the
    /// step's first iteration and reused; each raw correction `-K0^-1 r` is accelerated over
    /// the subspace of the previous corrections; once [`KRYLOV_DIM`] + 1 corrections have
    /// been made with one tangent, the tangent of the current configuration is formed and
    /// the subspace restarts (OpenSees' `KrylovNewton`, `-iterate current -increment
    /// current`). A prescribed increment is carried by the first iteration exactly as in
    /// Newton's path; that correction moves the prescribed unknown, so it is not a secant
    /// pair of the free unknowns' problem and is kept out of the subspace. Convergence: the
    /// energy of the applied (accelerated) correction with the residual it was made from,
    /// `|dx . r| / 2 <= tol`, never at an iteration that carries a prescribed increment.
    fn iterate_krylov(
        &mut self,
        f_ext: &DVector<f64>,
        prescribed: Option<Prescribed>,
        inertia: Option<Inertia<'_>>,
        tol: f64,
        max_iter: usize,
    ) -> Result<(usize, Vector3<f64>), NewtonFailure> {
        let mut energy = f64::INFINITY;
        let mut refresh = true;
        self.krylov.reset();
        for iter in 1..=max_iter {
            self.meter.newton()?;
            if !(iter == 1 && self.assembled) {
                self.assemble()?;
            }
            let mut r = self.take_residual();
            self.form_residual(f_ext, inertia, &mut r, energy > FREEZE * tol);
            let dx_p = self.prescribed_increment(prescribed, iter);
            if refresh {
                self.factor_tangent(inertia, prescribed, dx_p, &mut r)?;
                self.krylov.reset();
            } else if let Some(p) = prescribed {
                r[p.dof] = 0.0;
            }
            self.dx.copy_from(&r);
            self.dx.neg_mut();
            self.lu
                .solve_in_place(&mut self.dx)
                .map_err(|_| NewtonFailure::SingularTangent)?;
            if let Some(p) = prescribed {
                self.dx[p.dof] = dx_p;
            }
            if dx_p == 0.0 {
                self.krylov.accelerate(&mut self.dx);
            }
            energy = 0.5 * self.dx.dot(&r).abs();
            if !energy.is_finite() {
                break;
            }
            let dx = std::mem::replace(&mut self.dx, DVector::zeros(0));
            self.apply(&dx);
            self.dx = dx;
            self.r = r;
            if energy <= tol && dx_p == 0.0 {
                let base = self.assemble()?;
                return Ok((iter, base));
            }
            refresh = self.krylov.full();
        }
        Err(NewtonFailure::NoConvergence {
            iterations: max_iter,
            energy,
        })
    }

    /// The residual buffer, taken for an iteration and put back at its end; an early exit (a
    /// failure, after which the step reverts) leaves it empty, so it is remade then.
    fn take_residual(&mut self) -> DVector<f64> {
        let r = std::mem::replace(&mut self.r, DVector::zeros(0));
        if r.len() == self.dim() {
            r
        } else {
            DVector::zeros(self.dim())
        }
    }

    /// The prescribed unknown's increment carried by iteration `iter` (the first only).
    fn prescribed_increment(&self, prescribed: Option<Prescribed>, iter: usize) -> f64 {
        match prescribed {
            Some(p) if iter == 1 => p.value - self.dof_value(p.dof),
            _ => 0.0,
        }
    }

    /// `r = w f_int + (1 - w) f_old - f_ext`, the energy-consistent correction if asked for,
    /// and the inertia and damping forces, at the current configuration.
    fn form_residual(
        &mut self,
        f_ext: &DVector<f64>,
        inertia: Option<Inertia<'_>>,
        r: &mut DVector<f64>,
        update_e: bool,
    ) {
        r.copy_from(&self.f_int);
        let Some(m) = inertia else {
            *r -= f_ext;
            return;
        };
        if m.w_int != 1.0 {
            *r *= m.w_int;
            if let Some(f_old) = m.f_old {
                r.axpy(1.0 - m.w_int, f_old, 1.0);
            }
        }
        if let Some(w_n) = m.work_consistent {
            // e = (W(u) - W_n) - du . f_bar over the translations, spread along M du.
            let du = |c: &Self, i: usize| c.u[i / 6 + 1][i % 6] - c.u_c[i / 6 + 1][i % 6];
            let (mut fdu, mut mdu2) = (0.0, 0.0);
            for i in (0..r.len()).filter(|i| i % 6 < 3) {
                fdu += du(self, i) * r[i];
                mdu2 += m.mass[i] * du(self, i) * du(self, i);
            }
            if update_e {
                let w = self.energies().0;
                let e = (w - w_n) - fdu;
                // Only where `e` is resolved above the round-off of the work sums (64 ulps).
                let resolved = e.abs() > 64.0 * f64::EPSILON * (w.abs() + w_n.abs());
                self.work_e = if resolved && mdu2 > 0.0 { e } else { 0.0 };
            }
            if self.work_e != 0.0 {
                for i in (0..r.len()).filter(|i| i % 6 < 3 && m.mass[*i] != 0.0) {
                    r[i] += self.work_e * m.mass[i] * du(self, i) / mdu2;
                }
            }
        }
        *r -= f_ext;
        for i in 0..r.len() {
            if m.mass[i] != 0.0 && i % 6 < 3 {
                let u = self.u[i / 6 + 1][i % 6];
                let a = m.c_a * (u - m.u_pred[i]);
                let v = m.v_pred[i] + m.c_v * a;
                r[i] += m.mass[i] * (a + m.a0 * v);
            }
        }
    }

    /// Forms `w K + M c_a (1 + a0 c_v)` in the factorization's storage, moves a prescribed
    /// increment `dx_p` to the right side (`r += K_:p dx_p`) and decouples its row and
    /// column, and factors.
    fn factor_tangent(
        &mut self,
        inertia: Option<Inertia<'_>>,
        prescribed: Option<Prescribed>,
        dx_p: f64,
        r: &mut DVector<f64>,
    ) -> Result<(), NewtonFailure> {
        let dim = self.dim();
        let k = self.lu.matrix_mut();
        k.copy_from(&self.k);
        if let Some(m) = inertia {
            if m.w_int != 1.0 {
                *k *= m.w_int;
            }
            for i in 0..dim {
                if m.mass[i] != 0.0 && i % 6 < 3 {
                    k[(i, i)] += m.mass[i] * m.c_a * (1.0 + m.a0 * m.c_v);
                }
            }
        }
        if let Some(p) = prescribed {
            for i in 0..dim {
                r[i] += k[(i, p.dof)] * dx_p;
            }
            for j in 0..dim {
                k[(p.dof, j)] = 0.0;
                k[(j, p.dof)] = 0.0;
            }
            k[(p.dof, p.dof)] = 1.0;
            r[p.dof] = 0.0;
        }
        self.lu.factor().map_err(|_| NewtonFailure::SingularTangent)
    }

    /// The tangent stiffness of the current configuration and element states (assembled
    /// if it is not current), without inertia.
    pub fn tangent(&mut self) -> Result<&DMatrix<f64>, NewtonFailure> {
        if !self.assembled {
            self.assemble()?;
        }
        Ok(&self.k)
    }

    /// The current value of unknown `dof` as a displacement (translations only: a
    /// prescribed rotation component reads 0).
    fn dof_value(&self, dof: usize) -> f64 {
        let node = dof / 6 + 1;
        let c = dof % 6;
        if c < 3 { self.u[node][c] } else { 0.0 }
    }

    /// The energy line search (the `_ls` variants): moves by `eta dx` from the current
    /// configuration with `eta` chosen by regula falsi on `s(eta) = dx . r(x + eta dx)` until
    /// `|s(eta)| <= 0.8 |s(0)|` (at most 10 trials, `eta` kept in [0.1, 1]); the full step
    /// when it already satisfies that. Counts its trial evaluations.
    fn search_line(
        &mut self,
        dx: &DVector<f64>,
        r0: &DVector<f64>,
        f_ext: &DVector<f64>,
        prescribed: Option<Prescribed>,
    ) -> Result<(), NewtonFailure> {
        self.u_ls.clone_from(&self.u);
        self.rot_ls.clone_from(&self.rot);
        let turn = self.top_turn;
        let s0 = dx.dot(r0);
        let eval = |c: &mut Self, eta: f64| -> Result<f64, NewtonFailure> {
            c.u.clone_from(&c.u_ls);
            c.rot.clone_from(&c.rot_ls);
            c.top_turn = turn;
            c.apply_scaled(dx, eta);
            c.assemble()?;
            c.line_evaluations += 1;
            let mut s = 0.0;
            for i in 0..dx.len() {
                if prescribed.is_some_and(|p| p.dof == i) {
                    continue;
                }
                s += dx[i] * (c.f_int[i] - f_ext[i]);
            }
            Ok(s)
        };
        let (mut a, mut sa) = (0.0, s0);
        let (mut b, mut sb) = (1.0, eval(self, 1.0)?);
        for _ in 0..10 {
            if sb.abs() <= 0.8 * s0.abs() || !sb.is_finite() || sb == sa {
                break;
            }
            let eta = (b - sb * (b - a) / (sb - sa)).clamp(0.1, 1.0);
            let s = eval(self, eta)?;
            if s * sa < 0.0 {
                (b, sb) = (eta, s);
            } else {
                (a, sa) = (b, sb);
                (b, sb) = (eta, s);
            }
        }
        Ok(())
    }

    /// The internal force of the committed (or trial) state at the free unknowns.
    pub fn internal_force(&self) -> &DVector<f64> {
        &self.f_int
    }

    /// The largest out-of-balance force `|f_int - f_ext|` over the free unknowns (the
    /// prescribed one, if any, left out: its residual is the reaction), recomputed by a
    /// fresh state determination of every element at the current configuration (the
    /// equilibrium check after convergence).
    pub fn residual_max(
        &mut self,
        f_ext: &DVector<f64>,
        prescribed: Option<usize>,
    ) -> Result<f64, NewtonFailure> {
        self.assemble()?;
        let mut worst = 0.0f64;
        for i in 0..self.dim() {
            if prescribed != Some(i) {
                worst = worst.max((self.f_int[i] - f_ext[i]).abs());
            }
        }
        Ok(worst)
    }

    /// Work done on the elements and their recoverable energy (J), summed over the column.
    pub fn energies(&self) -> (f64, f64) {
        let mut out = (0.0, 0.0);
        for (e, (cr, b)) in self.elements.iter().enumerate() {
            let (r1, r2) = (C::matrix(&self.rot[e]), C::matrix(&self.rot[e + 1]));
            let (x1, x2) = (self.x0[e] + self.u[e], self.x0[e + 1] + self.u[e + 1]);
            let (v, _) = cr.deformations(&x1, &x2, &r1, &r2);
            let (w, r) = b.energies(v[5]);
            out.0 += w;
            out.1 += r;
        }
        out
    }
}
