//! Structural dynamics: the second-order systems of the flexible families (the flexible beam,
//! the fiber column, later the constrained mechanisms) and their integrators.
//!
//! Two kinds of system: [`SecondOrder`] (and [`Constraints`]) below, a residual of vectors
//! `q`, `v`, `a` that a method may evaluate anywhere; and a path-dependent structure
//! ([`path::PathDependent`]: hysteretic elements with committed histories, nodal rotations in
//! a chart), solved in increments from its committed state by a solution algorithm of
//! [`equilibrium`] (Newton, Newton with the energy line search, Krylov-accelerated Newton in
//! [`krylov_newton`]), which are the static methods; with mass, damping and a load history
//! ([`path_step::Path`]) it is stepped by the same Newmark, HHT and generalized-alpha methods
//! and by the energy-consistent [`midpoint::Midpoint`].
//!
//! A system is written in residual form, with run-time sizes (its size comes from the case
//! file: a mode or element count):
//!
//! ```text
//! r(t, q, v, a) + G(q)^T lambda = 0,        r = M(q) a + f(t, q, v),
//! g(t, q) = 0                                (constrained systems only),
//! ```
//!
//! where `q` are the coordinates, `v = q'`, `a = q''`, `M` the (possibly singular) mass
//! matrix, `f` every other force (internal, gyroscopic, inertial terms of a moving frame,
//! minus the applied loads) and `G = dg/dq` the constraint Jacobian with multipliers `lambda`.
//! Newton's method needs the combination `S = c_m dr/da + c_c dr/dv + c_k dr/dq` that each
//! integrator forms from its own coefficients (Newmark iterating on the acceleration:
//! `c_m = 1`, `c_c = gamma h`, `c_k = beta h^2`), so a system never knows which integrator
//! runs it.
//!
//! Invariants: every method writes into caller-owned buffers sized once (`dim`,
//! `n_constraints`), so a time loop built on these traits allocates nothing per step.
//! Where it fails: a system whose `S` is singular for every step (a massless, unloaded
//! coordinate with no stiffness) makes every implicit method report a `newton_failure`.
//!
//! The integrators (one file each; every one a struct with a validating constructor and its
//! parameters, and there its implementation of the one interface [`method::Method`]: its
//! `step(sys, t, h, state, stats)` on the preallocated [`state::State`], while `init` for
//! consistent initial accelerations, `info()` and `new_state` are the trait's, written once,
//! where the methods agree):
//!
//! - [`newmark::Newmark`]: average acceleration (`beta = 1/4`, `gamma = 1/2`), order 2, no
//!   numerical dissipation, conserves the energy of linear systems;
//! - [`hht::Hht`]: Hilber-Hughes-Taylor, `alpha` in `[-1/3, 0]`, order 2, spectral radius
//!   `(1 + alpha)/(1 - alpha)` at infinity;
//! - [`gen_alpha::GenAlpha`]: Chung & Hulbert's generalized-alpha in Arnold & Brüls' form,
//!   `rho_inf` in `[0, 1]`, order 2 for nonlinear systems, spectral radius `rho_inf`;
//! - [`gen_alpha_i3::GenAlphaI3`]: the same for [`Constraints`] systems in index-3 form,
//!   with a scaled iteration matrix, order 2 in `q` and `v`.
//!
//! Their Newton iterations on the acceleration ask the system for `S` with `c_m = 1`,
//! `c_c = gamma h`, `c_k = beta h^2` (Newmark's matrix above times `beta h^2`, bounded as
//! `h -> 0`); the index-3 form uses `c_m = (1 - alpha_m)/(1 - alpha_f)` and the same
//! `c_c`, `c_k`. They share [`crate::math::tangent::Tangent`] (the iteration matrix, sized once
//! from the system's [`SecondOrder::pattern`]: a dense LU with partial pivoting, or a banded
//! one with a border for a system that declares its band, such as the beam's `fe_exact`),
//! [`newton`] (the Newton iteration on the acceleration and its options) and `init` (consistent initial
//! accelerations, also for a singular mass matrix).
use nalgebra::{DMatrix, DVector};

use crate::math::tangent::{Pattern, Tangent};

pub mod equilibrium;
pub mod gen_alpha;
pub mod gen_alpha_i3;
pub mod hht;
mod init;
pub mod krylov;
pub mod krylov_newton;
pub mod method;
pub mod midpoint;
pub mod newmark;
pub mod newton;
pub mod path;
pub mod path_step;
#[cfg(test)]
mod path_tests;
pub mod state;
#[cfg(test)]
mod test_support;

/// A second-order system `M(q) a + f(t, q, v) = 0` in residual form.
pub trait SecondOrder: Send + Sync {
    /// The number of coordinates `n`.
    fn dim(&self) -> usize;

    /// Writes `r = M(q) a + f(t, q, v)` into `r` (length `n`).
    fn residual(
        &self,
        t: f64,
        q: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
        r: &mut DVector<f64>,
    );

    /// The size of the coordinates' round-off (e.g. a structure's length when the
    /// coordinates are displacements of nodes placed that far apart): Newton's convergence
    /// test accepts updates below its tolerance times this, even when the state is near 0.
    /// 0 by default (a purely relative test).
    fn length_scale(&self) -> f64 {
        0.0
    }

    /// Overwrites `s` (`n x n`) with `c_m dr/da + c_c dr/dv + c_k dr/dq` at `(t, q, v, a)`.
    #[allow(clippy::too_many_arguments)]
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
    );

    /// The nonzero pattern of the tangent, which sizes the Newton iterations' matrix once
    /// ([`Tangent::new`]: dense, or banded with a border above the measured crossover).
    /// Dense by default; a system that declares another writes [`SecondOrder::tangent_into`].
    fn pattern(&self) -> Pattern {
        Pattern::Dense
    }

    /// Overwrites `s` with the tangent of [`SecondOrder::tangent`], in the storage its
    /// [`SecondOrder::pattern`] chose. By default through the dense buffer; on a banded
    /// storage (a system that declared a band without writing this) it marks `s` so that its
    /// factorisation fails.
    #[allow(clippy::too_many_arguments)]
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
        match s.dense_mut() {
            Some(m) => self.tangent(t, q, v, a, c_m, c_c, c_k, m),
            None => s.mark_stray(),
        }
    }
}

/// A shared reference to a second-order system is one (its methods read the system only),
/// so a method, whose `step` takes the system mutably for the path-dependent kind, runs on
/// a system that is borrowed.
impl<S: SecondOrder + ?Sized> SecondOrder for &S {
    fn dim(&self) -> usize {
        (**self).dim()
    }

    fn residual(
        &self,
        t: f64,
        q: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
        r: &mut DVector<f64>,
    ) {
        (**self).residual(t, q, v, a, r)
    }

    fn length_scale(&self) -> f64 {
        (**self).length_scale()
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
        (**self).tangent(t, q, v, a, c_m, c_c, c_k, s)
    }

    fn pattern(&self) -> Pattern {
        (**self).pattern()
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
        (**self).tangent_into(t, q, v, a, c_m, c_c, c_k, s)
    }
}

/// Holonomic constraints `g(t, q) = 0` (length `m`) on a second-order system, with the
/// multipliers `lambda` entering its equations as `G(q)^T lambda`.
pub trait Constraints: SecondOrder {
    /// The number of constraints `m`.
    fn n_constraints(&self) -> usize;

    /// Writes `g(t, q)` into `out` (length `m`).
    fn g(&self, t: f64, q: &DVector<f64>, out: &mut DVector<f64>);

    /// Overwrites `out` (`m x n`) with `G = dg/dq` at `(t, q)`.
    fn jacobian(&self, t: f64, q: &DVector<f64>, out: &mut DMatrix<f64>);

    /// Adds `c_k d(G(q)^T lambda)/dq` into `s` (`n x n`); nothing for constraints linear in
    /// `q` (the default).
    fn add_lambda_tangent(
        &self,
        t: f64,
        q: &DVector<f64>,
        lambda: &DVector<f64>,
        c_k: f64,
        s: &mut DMatrix<f64>,
    ) {
        let _ = (t, q, lambda, c_k, s);
    }

    /// Writes `dg/dt` and `d2g/dt2` at fixed `q` into `g_t` and `g_tt` (Baumgarte's
    /// stabilisation of rheonomic constraints); zero for scleronomic ones (the default).
    fn g_time(&self, t: f64, q: &DVector<f64>, g_t: &mut DVector<f64>, g_tt: &mut DVector<f64>) {
        let _ = (t, q);
        g_t.fill(0.0);
        g_tt.fill(0.0);
    }
}
