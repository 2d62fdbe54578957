//! `equilibrium`: the solution algorithms that bring a [`PathDependent`] structure to the
//! equation (P1) of `path.rs` in one load or time step, from its committed state: full
//! Newton ([`Newton`]), Newton with the energy line search ([`NewtonLineSearch`]) and the
//! Krylov-accelerated Newton of `krylov_newton.rs`, one interface, [`Equilibrium`]. They are
//! the static methods of the suite (a static scene is a sequence of their steps) and the
//! inner solver of the structural time integrators on path-dependent systems
//! ([`super::path_step`]).
//!
//! One iteration: the residual of (P1) at the trial configuration, `r = w f_int + (1 - w)
//! f_old - F + M (a + a0 v)`, the iteration matrix `w K + M c_a (1 + a0 c_v)` (the inertia's
//! part diagonal: the mass is lumped), the correction `dx = -S^-1 r`, applied. With one
//! prescribed unknown (displacement control) its increment is carried by the first
//! iteration (`S_ff dx_f = -(r_f + S_fp dx_p)`), its row and column decoupled in every
//! iteration, and its residual, the force that holds it, left out. Convergence: the energy of
//! the correction `|dx . r| / 2` at or below the tolerance (J), as OpenSees' `EnergyIncr`,
//! never at an iteration that carries a prescribed increment; the step then assembles once
//! more, so the element states are those of the final configuration.
//!
//! The energy-consistent correction of the midpoint rule (`Inertia::work_consistent`): with
//! `du = u - u_n` on the additive unknowns and `e = (W(u) - W_n) - du . f_bar` (`W` the
//! elements' own work, `f_bar` the weighted internal force), the residual gains
//! `e M du / (du . M du)`, so that the structural work of the corrected force over the step
//! equals the elements' work exactly. It is `O(h^2)`, left out of the tangent, applied only
//! where `e` exceeds 64 ulps of the work sums, and held once the iteration is close
//! ([`FREEZE`]).
//!
//! Invariants: one assembly and one factorisation per iteration, in a workspace sized once
//! (no allocation per iteration once sized). Where it fails: no convergence within
//! `max_iter` iterations, a singular iteration matrix, or the system's own failures
//! (`PathFailure`); `step` then reverts the system.
use nalgebra::DVector;

use super::path::{PathDependent, PathFailure, Prescribed};
use crate::integrate::{MethodInfo, MethodKind};
use crate::math::lu::{DenseLu as Lu, LinearSolve};

/// The inertia and damping of a dynamic step (Newmark's family, iterating on the
/// displacement): a lumped mass per unknown (0 for the massless ones), mass-proportional
/// damping `C = a0 M`, and the step's predictors, so that at the trial displacement `u`
/// the (effective) acceleration is `a = c_a (u - u_pred)` and the (effective) velocity
/// `v = v_pred + c_v a`. `w_int` weighs the trial internal force against `f_old`, that of the
/// last converged state; `work_consistent = Some(W_n)` (the elements' work at the last
/// converged state) adds the midpoint rule's correction (module docs).
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

/// The energy-consistent correction's `e` is re-evaluated while the last correction's energy
/// exceeds `FREEZE` times the tolerance and then held: the fibres' work carries the element
/// iterations' own tolerance as noise, which, divided by `|du|`, would otherwise keep the
/// residual from settling (measured on the fiber column without the hold: Newton stalled at
/// 1e-19 J against 1e-20 J at step 2433 of its pulse).
pub const FREEZE: f64 = 1e4;

/// A solution algorithm for one step of a path-dependent system.
pub trait Equilibrium<S: PathDependent + ?Sized> {
    /// The algorithm's name.
    const NAME: &'static str;

    /// Iterates the trial state of `sys` to (P1) under the load `f_ext`, the prescribed
    /// unknown and the inertia given; returns the iterations made. Does not commit.
    fn solve(
        &mut self,
        sys: &mut S,
        f_ext: &DVector<f64>,
        prescribed: Option<Prescribed>,
        inertia: Option<Inertia<'_>>,
    ) -> Result<usize, PathFailure>;

    /// [`Equilibrium::solve`], then the trial state committed on success, reverted on failure.
    fn step(
        &mut self,
        sys: &mut S,
        f_ext: &DVector<f64>,
        prescribed: Option<Prescribed>,
        inertia: Option<Inertia<'_>>,
    ) -> Result<usize, PathFailure> {
        match self.solve(sys, f_ext, prescribed, inertia) {
            Ok(iterations) => {
                sys.commit();
                Ok(iterations)
            }
            Err(e) => {
                sys.revert();
                Err(e)
            }
        }
    }

    /// What the algorithm is, as a static method of the suite: implicit, of kind
    /// `structural`, order 2 (the class of the step ladders: a static path has no
    /// time-discretisation order).
    fn info(&self) -> MethodInfo {
        MethodInfo::new(Self::NAME, MethodKind::Structural, 2).with_implicit(true)
    }
}

/// The tolerance (J) and iteration limit of an algorithm; an error names a bad one.
pub(crate) fn validate(tol: f64, max_iter: usize) -> Result<(), String> {
    if !(tol.is_finite() && tol > 0.0) {
        return Err(format!("tol = {tol} must be finite and positive (J)"));
    }
    if max_iter == 0 {
        return Err("max_iter = 0 must be at least 1".into());
    }
    Ok(())
}

/// What every algorithm iterates in: the factorisation, the correction, the residual and the
/// energy-consistent correction in use, sized to the system on first use.
#[derive(Debug, Clone)]
pub(crate) struct Workspace {
    pub lu: Lu,
    pub dx: DVector<f64>,
    pub r: DVector<f64>,
    work_e: f64,
}

impl Workspace {
    pub fn new() -> Self {
        Self::sized(0)
    }

    fn sized(n: usize) -> Self {
        Workspace {
            lu: Lu::new(n),
            dx: DVector::zeros(n),
            r: DVector::zeros(n),
            work_e: 0.0,
        }
    }

    /// Sizes the buffers for `n` unknowns (allocates only when `n` changes).
    pub fn size(&mut self, n: usize) {
        if self.r.len() != n {
            *self = Self::sized(n);
        }
    }

    /// The prescribed unknown's increment carried by iteration `iter` (the first only).
    pub fn prescribed_increment<S: PathDependent + ?Sized>(
        sys: &S,
        prescribed: Option<Prescribed>,
        iter: usize,
    ) -> f64 {
        match prescribed {
            Some(p) if iter == 1 => {
                let now = if sys.additive(p.dof) {
                    sys.displacement(p.dof)
                } else {
                    0.0
                };
                p.value - now
            }
            _ => 0.0,
        }
    }

    /// `r = w f_int + (1 - w) f_old - f_ext`, the energy-consistent correction if asked for
    /// (re-evaluated when `update_e`), and the inertia and damping forces, at the trial
    /// configuration.
    pub fn form_residual<S: PathDependent + ?Sized>(
        &mut self,
        sys: &S,
        f_ext: &DVector<f64>,
        inertia: Option<Inertia<'_>>,
        update_e: bool,
    ) {
        let r = &mut self.r;
        r.copy_from(sys.internal_force());
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
            let du = |i: usize| sys.displacement(i) - sys.committed_displacement(i);
            let (mut fdu, mut mdu2) = (0.0, 0.0);
            for i in (0..r.len()).filter(|&i| sys.additive(i)) {
                fdu += du(i) * r[i];
                mdu2 += m.mass[i] * du(i) * du(i);
            }
            if update_e {
                let w = sys.work();
                let e = (w - w_n) - fdu;
                let resolved = e.abs() > 64.0 * f64::EPSILON * (w.abs() + w_n.abs());
                self.work_e = if resolved && mdu2 > 0.0 { e } else { 0.0 };
            }
            if self.work_e != 0.0 {
                for i in (0..r.len()).filter(|&i| sys.additive(i) && m.mass[i] != 0.0) {
                    r[i] += self.work_e * m.mass[i] * du(i) / mdu2;
                }
            }
        }
        *r -= f_ext;
        for i in 0..r.len() {
            if m.mass[i] != 0.0 && sys.additive(i) {
                let u = sys.displacement(i);
                let a = m.c_a * (u - m.u_pred[i]);
                let v = m.v_pred[i] + m.c_v * a;
                r[i] += m.mass[i] * (a + m.a0 * v);
            }
        }
    }

    /// Forms `w K + M c_a (1 + a0 c_v)` in the factorisation's storage, moves a prescribed
    /// increment `dx_p` to the right side (`r += S_:p dx_p`) and decouples its row and
    /// column, and factors.
    pub fn factor_tangent<S: PathDependent + ?Sized>(
        &mut self,
        sys: &S,
        inertia: Option<Inertia<'_>>,
        prescribed: Option<Prescribed>,
        dx_p: f64,
    ) -> Result<(), PathFailure> {
        let dim = sys.dim();
        let r = &mut self.r;
        let k = self.lu.matrix_mut();
        k.copy_from(sys.stiffness());
        if let Some(m) = inertia {
            if m.w_int != 1.0 {
                *k *= m.w_int;
            }
            for i in 0..dim {
                if m.mass[i] != 0.0 && sys.additive(i) {
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
        self.lu.factor().map_err(|_| PathFailure::SingularTangent)
    }

    /// The correction `dx = -S^-1 r` with the factored matrix, the prescribed increment in
    /// its place.
    pub fn correction(
        &mut self,
        prescribed: Option<Prescribed>,
        dx_p: f64,
    ) -> Result<(), PathFailure> {
        self.dx.copy_from(&self.r);
        self.dx.neg_mut();
        self.lu
            .solve_in_place(&mut self.dx)
            .map_err(|_| PathFailure::SingularTangent)?;
        if let Some(p) = prescribed {
            self.dx[p.dof] = dx_p;
        }
        Ok(())
    }

    /// `|dx . r| / 2`.
    pub fn energy(&self) -> f64 {
        0.5 * self.dx.dot(&self.r).abs()
    }
}

/// Full Newton: the tangent of the current configuration every iteration; with
/// `LINE_SEARCH` ([`NewtonLineSearch`]) each correction `dx` of a static step without a
/// prescribed increment, whose energy is above the tolerance, is scaled by `eta`, chosen by
/// regula falsi on `s(eta) = dx . r(x + eta dx)` until `|s(eta)| <= 0.8 |s(0)|` (at most 10
/// trials, `eta` kept in `[0.1, 1]`); the full step when it already satisfies that.
///
/// # Example
///
/// See [`PathDependent`]'s.
#[derive(Debug, Clone)]
pub struct NewtonIteration<const LINE_SEARCH: bool> {
    tol: f64,
    max_iter: usize,
    ws: Workspace,
    /// Trial evaluations of the line search so far (0 without it).
    pub evaluations: u64,
}

/// Full Newton.
pub type Newton = NewtonIteration<false>;

/// Newton with the energy line search.
pub type NewtonLineSearch = NewtonIteration<true>;

impl<const LINE_SEARCH: bool> NewtonIteration<LINE_SEARCH> {
    /// The algorithm with the energy tolerance `tol` (J) and at most `max_iter` iterations a
    /// step.
    pub fn new(tol: f64, max_iter: usize) -> Result<Self, String> {
        validate(tol, max_iter)?;
        Ok(NewtonIteration {
            tol,
            max_iter,
            ws: Workspace::new(),
            evaluations: 0,
        })
    }
}

impl<S: PathDependent + ?Sized, const LINE_SEARCH: bool> Equilibrium<S>
    for NewtonIteration<LINE_SEARCH>
{
    const NAME: &'static str = if LINE_SEARCH {
        "newton_line_search"
    } else {
        "newton"
    };

    fn solve(
        &mut self,
        sys: &mut S,
        f_ext: &DVector<f64>,
        prescribed: Option<Prescribed>,
        inertia: Option<Inertia<'_>>,
    ) -> Result<usize, PathFailure> {
        let limits = (self.tol, self.max_iter);
        let search = LINE_SEARCH.then_some(&mut self.evaluations);
        iterate(
            &mut self.ws,
            sys,
            f_ext,
            prescribed,
            inertia,
            limits,
            search,
        )
    }
}

/// Newton's loop (module docs); with `search` (the line search's evaluation counter) the
/// corrections of a static step are line-searched.
fn iterate<S: PathDependent + ?Sized>(
    ws: &mut Workspace,
    sys: &mut S,
    f_ext: &DVector<f64>,
    prescribed: Option<Prescribed>,
    inertia: Option<Inertia<'_>>,
    (tol, max_iter): (f64, usize),
    mut search: Option<&mut u64>,
) -> Result<usize, PathFailure> {
    ws.size(sys.dim());
    let mut energy = f64::INFINITY;
    for iter in 1..=max_iter {
        sys.iteration()?;
        // The first iteration of a step starts where the last step converged: its assembly
        // is still valid (same configuration, committed element states).
        if !(iter == 1 && sys.assembled()) {
            sys.assemble()?;
        }
        ws.form_residual(sys, f_ext, inertia, energy > FREEZE * tol);
        let dx_p = Workspace::prescribed_increment(sys, prescribed, iter);
        ws.factor_tangent(sys, inertia, prescribed, dx_p)?;
        ws.correction(prescribed, dx_p)?;
        energy = ws.energy();
        if !energy.is_finite() {
            break;
        }
        match search.as_deref_mut() {
            Some(count) if inertia.is_none() && dx_p == 0.0 && energy > tol => {
                search_line(sys, &ws.dx, &ws.r, f_ext, prescribed, count)?;
            }
            _ => sys.apply(&ws.dx, 1.0),
        }
        if energy <= tol && dx_p == 0.0 {
            // Leave the element states consistent with the final configuration.
            sys.assemble()?;
            return Ok(iter);
        }
    }
    Err(PathFailure::NoConvergence {
        iterations: max_iter,
        energy,
    })
}

/// The energy line search along `dx` from the trial configuration (see [`NewtonLineSearch`]);
/// counts its trial evaluations.
fn search_line<S: PathDependent + ?Sized>(
    sys: &mut S,
    dx: &DVector<f64>,
    r0: &DVector<f64>,
    f_ext: &DVector<f64>,
    prescribed: Option<Prescribed>,
    count: &mut u64,
) -> Result<(), PathFailure> {
    sys.mark();
    let s0 = dx.dot(r0);
    let mut eval = |sys: &mut S, eta: f64| -> Result<f64, PathFailure> {
        sys.return_to_mark();
        sys.apply(dx, eta);
        sys.assemble()?;
        *count += 1;
        let f_int = sys.internal_force();
        let mut s = 0.0;
        for i in 0..dx.len() {
            if prescribed.is_some_and(|p| p.dof == i) {
                continue;
            }
            s += dx[i] * (f_int[i] - f_ext[i]);
        }
        Ok(s)
    };
    let (mut a, mut sa) = (0.0, s0);
    let (mut b, mut sb) = (1.0, eval(sys, 1.0)?);
    for _ in 0..10 {
        if sb.abs() <= 0.8 * s0.abs() || !sb.is_finite() || sb == sa {
            break;
        }
        let eta = (b - sb * (b - a) / (sb - sa)).clamp(0.1, 1.0);
        let s = eval(sys, eta)?;
        if s * sa < 0.0 {
            (b, sb) = (eta, s);
        } else {
            (a, sa) = (b, sb);
            (b, sb) = (eta, s);
        }
    }
    Ok(())
}
