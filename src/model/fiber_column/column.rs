//! The cantilever column as a structure: `n` two-node corotational elements along the global
//! z axis from a clamped base, six unknowns per free node (the displacement and the spatial
//! rotation increment `dw`), the nodes' rotations held in a [`RotationChart`], and the static
//! Newton step under load control with, optionally, one prescribed displacement (the
//! displacement control of the cyclic scenes: the prescribed degree of freedom leaves the
//! unknowns and its residual is the force that holds it, the base shear's counterpart).
//!
//! The column is a path-dependent structure of the structural module
//! ([`crate::structural::path::PathDependent`]): a solution algorithm of
//! `structural::equilibrium` (Newton, Newton with the energy line search, Krylov-accelerated
//! Newton) moves the nodes by its corrections `dx` and turns their rotations with each
//! chart's retraction; the element states are trial states until the step converges and are
//! then committed (or reverted, on failure). A dynamic step is a structural method's on
//! `structural::path_step::Path` (mass, damping, the ground motion). The in-plane rotation of the top,
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
use super::corotational::Corotational;
use super::meter::Meter;
use crate::rotation::RotationChart;
use crate::structural::equilibrium::Equilibrium;
use crate::structural::path::{PathDependent, PathFailure, Prescribed};

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
    /// `f_int`, `k` and `base` are those of the current configuration and element states.
    assembled: bool,
    base: Vector3<f64>,
    /// The configuration a line search returns to (`mark`).
    u_ls: Vec<Vector3<f64>>,
    rot_ls: Vec<C::Rot>,
    turn_ls: f64,
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
            assembled: false,
            base: Vector3::zeros(),
            u_ls: vec![Vector3::zeros(); n + 1],
            rot_ls: vec![C::identity(); n + 1],
            turn_ls: 0.0,
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

    /// Assembles the internal force and tangent of the trial state, and the base node's
    /// internal force, which equals the support's reaction on the column.
    fn determine(&mut self) -> Result<(), PathFailure> {
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
            let spent = if force {
                basic.iterations() - before
            } else {
                1
            };
            self.meter.elements(spent, force)?;
            let (qb, kb) = updated.map_err(|failure| match failure {
                ElementFailure::WorkLimit => self.meter.spent(),
                failure => PathFailure::Element {
                    element: e,
                    failure: failure.to_string(),
                },
            })?;
            if e == 0 {
                // The clamped base node: only the free node's block is assembled.
                let (reaction, f, k) = cr.global_free_end(&kin, &qb, &kb);
                base = reaction;
                for i in 0..6 {
                    self.f_int[i] += f[i];
                    for j in 0..6 {
                        self.k[(i, j)] += k[(i, j)];
                    }
                }
                continue;
            }
            let (f, k) = cr.global_at(&kin, &qb, &kb);
            // Global unknowns of the element's 12: node e, then e + 1 (e > 0: both free).
            let map = |i: usize| 6 * (e + i / 6 - 1) + i % 6;
            for i in 0..12 {
                self.f_int[map(i)] += f[i];
                for j in 0..12 {
                    self.k[(map(i), map(j))] += k[(i, j)];
                }
            }
        }
        self.base = base;
        self.assembled = true;
        Ok(())
    }

    /// The support's reaction on the column at the last assembly (N): the base shear is
    /// `-x`, the axial force `-z` (zero before the first).
    pub fn base_reaction(&self) -> Vector3<f64> {
        self.base
    }

    fn move_by(&mut self, dx: &DVector<f64>, eta: f64) {
        self.assembled = false;
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
    /// optional prescribed displacement, by `solver`; commits on success, reverts on failure.
    /// Returns the counts and the support's reaction on the column at the base (the column's
    /// internal force there): the base shear is `-R.x`, the axial force `-R.z`.
    pub fn step<E: Equilibrium<Self>>(
        &mut self,
        solver: &mut E,
        f_ext: &DVector<f64>,
        prescribed: Option<Prescribed>,
    ) -> Result<(StepCount, Vector3<f64>), PathFailure> {
        let before = self.element_counts();
        let iterations = solver.step(self, f_ext, prescribed, None)?;
        let after = self.element_counts();
        let count = StepCount {
            iterations,
            element_iterations: after.0 - before.0,
            element_subdivisions: after.1 - before.1,
        };
        Ok((count, self.base))
    }

    /// The elements' iterations and subdivisions so far.
    fn element_counts(&self) -> (u64, u64) {
        self.elements.iter().fold((0, 0), |(i, s), (_, b)| {
            (i + b.iterations(), s + b.subdivisions())
        })
    }

    /// The tangent stiffness of the current configuration and element states (assembled
    /// if it is not current), without inertia.
    pub fn tangent(&mut self) -> Result<&DMatrix<f64>, PathFailure> {
        if !self.assembled {
            self.determine()?;
        }
        Ok(&self.k)
    }

    /// The largest out-of-balance force `|f_int - f_ext|` over the free unknowns (the
    /// prescribed one, if any, left out: its residual is the reaction), recomputed by a
    /// fresh state determination of every element at the current configuration (the
    /// equilibrium check after convergence).
    pub fn residual_max(
        &mut self,
        f_ext: &DVector<f64>,
        prescribed: Option<usize>,
    ) -> Result<f64, PathFailure> {
        self.determine()?;
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
            let v = cr.basic_deformations(&x1, &x2, &r1, &r2);
            let (w, r) = b.energies(v[5]);
            out.0 += w;
            out.1 += r;
        }
        out
    }
}

/// The column as a path-dependent structure: six unknowns per free node, the translations
/// additive, the rotations retracted by the chart.
impl<C: RotationChart> PathDependent for Column<C> {
    fn dim(&self) -> usize {
        Column::dim(self)
    }

    fn assemble(&mut self) -> Result<(), PathFailure> {
        self.determine()
    }

    fn assembled(&self) -> bool {
        self.assembled
    }

    fn internal_force(&self) -> &DVector<f64> {
        &self.f_int
    }

    fn stiffness(&self) -> &DMatrix<f64> {
        &self.k
    }

    fn apply(&mut self, dx: &DVector<f64>, eta: f64) {
        self.move_by(dx, eta);
    }

    fn mark(&mut self) {
        self.u_ls.clone_from(&self.u);
        self.rot_ls.clone_from(&self.rot);
        self.turn_ls = self.top_turn;
    }

    fn return_to_mark(&mut self) {
        self.u.clone_from(&self.u_ls);
        self.rot.clone_from(&self.rot_ls);
        self.top_turn = self.turn_ls;
        self.assembled = false;
    }

    fn commit(&mut self) {
        for (_, b) in &mut self.elements {
            b.commit();
        }
        self.u_c.clone_from(&self.u);
        self.rot_c.clone_from(&self.rot);
        self.top_turn_c = self.top_turn;
    }

    fn revert(&mut self) {
        self.assembled = false;
        for (_, b) in &mut self.elements {
            b.revert();
        }
        self.u.clone_from(&self.u_c);
        self.rot.clone_from(&self.rot_c);
        self.top_turn = self.top_turn_c;
    }

    fn additive(&self, i: usize) -> bool {
        i % 6 < 3
    }

    fn displacement(&self, i: usize) -> f64 {
        self.u[i / 6 + 1][i % 6]
    }

    fn committed_displacement(&self, i: usize) -> f64 {
        self.u_c[i / 6 + 1][i % 6]
    }

    fn work(&self) -> f64 {
        self.energies().0
    }

    fn iteration(&mut self) -> Result<(), PathFailure> {
        self.meter.newton()
    }

    fn inner_iterations(&self) -> u64 {
        self.element_counts().0
    }
}
