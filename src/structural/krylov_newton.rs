//! `krylov_newton`: Krylov-accelerated Newton (OpenSees' `KrylovNewton`, `-iterate current
//! -increment current`), the third [`Equilibrium`] algorithm beside those of
//! `equilibrium.rs`: the tangent is formed and factored at the step's first iteration and
//! reused; each raw correction `-K0^-1 r` is accelerated over the subspace of the previous
//! corrections (`krylov.rs`, Carlson & Miller 1998); once [`KRYLOV_DIM`] + 1 corrections have
//! been made with one tangent, the tangent of the current configuration is formed and the
//! subspace restarts.
//!
//! A prescribed increment is carried by the first iteration exactly as in Newton's loop;
//! that correction moves the prescribed unknown, so it is not a secant pair of the free
//! unknowns' problem and is kept out of the subspace. Convergence: the energy of the applied
//! (accelerated) correction with the residual it was made from, `|dx . r| / 2 <= tol`, never
//! at an iteration that carries a prescribed increment.
//!
//! Invariants and failures: those of `equilibrium.rs`; fewer factorisations than Newton per
//! step, usually more iterations (measured on the fiber column's c02 cycling: 1.41x more
//! solves than OpenSees' own KrylovNewton, whose convergence test differs in its details).
use nalgebra::DVector;

use super::equilibrium::{Equilibrium, FREEZE, Inertia, Workspace, validate};
use super::krylov::Krylov;
use super::path::{PathDependent, PathFailure, Prescribed};

/// The Krylov subspace's largest dimension (OpenSees' `KrylovNewton` default `maxDim`).
pub const KRYLOV_DIM: usize = 3;

/// Krylov-accelerated Newton (module docs).
#[derive(Debug, Clone)]
pub struct KrylovNewton {
    tol: f64,
    max_iter: usize,
    ws: Workspace,
    krylov: Krylov,
}

impl KrylovNewton {
    /// The algorithm with the energy tolerance `tol` (J) and at most `max_iter` iterations.
    pub fn new(tol: f64, max_iter: usize) -> Result<Self, String> {
        validate(tol, max_iter)?;
        Ok(KrylovNewton {
            tol,
            max_iter,
            ws: Workspace::new(),
            krylov: Krylov::new(0, KRYLOV_DIM),
        })
    }
}

impl<S: PathDependent + ?Sized> Equilibrium<S> for KrylovNewton {
    const NAME: &'static str = "krylov_newton";

    fn solve(
        &mut self,
        sys: &mut S,
        f_ext: &DVector<f64>,
        prescribed: Option<Prescribed>,
        inertia: Option<Inertia<'_>>,
    ) -> Result<usize, PathFailure> {
        let (tol, ws) = (self.tol, &mut self.ws);
        ws.size(sys.dim());
        if self.krylov.unknowns() != sys.dim() {
            self.krylov = Krylov::new(sys.dim(), KRYLOV_DIM);
        }
        let mut energy = f64::INFINITY;
        let mut refresh = true;
        self.krylov.reset();
        for iter in 1..=self.max_iter {
            sys.iteration()?;
            if !(iter == 1 && sys.assembled()) {
                sys.assemble()?;
            }
            ws.form_residual(sys, f_ext, inertia, energy > FREEZE * tol);
            let dx_p = Workspace::prescribed_increment(sys, prescribed, iter);
            if refresh {
                ws.factor_tangent(sys, inertia, prescribed, dx_p)?;
                self.krylov.reset();
            } else if let Some(p) = prescribed {
                ws.r[p.dof] = 0.0;
            }
            ws.correction(prescribed, dx_p)?;
            if dx_p == 0.0 {
                self.krylov.accelerate(&mut ws.dx);
            }
            energy = ws.energy();
            if !energy.is_finite() {
                break;
            }
            sys.apply(&ws.dx, 1.0);
            if energy <= tol && dx_p == 0.0 {
                sys.assemble()?;
                return Ok(iter);
            }
            refresh = self.krylov.full();
        }
        Err(PathFailure::NoConvergence {
            iterations: self.max_iter,
            energy,
        })
    }
}
