//! `state`: the state a structural integrator advances and the workspace its Newton
//! iteration works in, both sized once from the system (`n` coordinates, `m` constraints) so
//! that a step allocates nothing.
//!
//! The state is `(q, v, a, aux, lambda)`: coordinates, velocities, the true acceleration
//! `a = v'` (for Newmark and generalized-alpha it satisfies the equations of motion
//! `M(q) a + f(t, q, v) + G^T lambda = 0` at the state's time; for HHT it is HHT's
//! acceleration, which satisfies them at the alpha-weighted point), the auxiliary acceleration `aux` of the generalized-alpha method
//! (Chung & Hulbert 1993; Arnold & Brüls 2007, where it is the `a_n` of the update
//! `q_{n+1} = q_n + h v_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1}`; it approximates
//! `q''(t_n + (alpha_m - alpha_f) h)`, not `q''(t_n)`) and the constraint multipliers
//! `lambda` (length `m`, empty for unconstrained systems). Newmark and HHT keep
//! `aux = a` (HHT's `a_n` approximates `q''(t_n + alpha h)` and is stored in both).
//!
//! Invariants: the vectors keep their lengths; a step writes its trial values into the
//! workspace and swaps them into the state only when it succeeds, so a failed step leaves
//! the state at `t_n`. Where it fails: a state built for one system and handed with another
//! of a different size makes the integrators panic (a programming error, not a numerical
//! failure).
use nalgebra::{DMatrix, DVector};

use super::{Constraints, SecondOrder};
use crate::math::lu::DenseLu as Lu;
use crate::math::tangent::{Pattern, Tangent};

/// The state of a structural integrator and its workspace.
///
/// # Example
///
/// A state for a 2-coordinate, 1-constraint system, set to its initial values; the
/// accelerations and multipliers stay zero until an integrator's `init` computes them:
///
/// ```
/// use mbdbench::structural::state::State;
///
/// let mut s = State::new(2, 1);
/// s.set(&[1.0, 0.0], &[0.0, 2.0]);
/// assert_eq!((s.dim(), s.n_constraints()), (2, 1));
/// assert_eq!(s.v[1], 2.0);
/// assert_eq!(s.a.amax() + s.aux.amax() + s.lambda.amax(), 0.0);
/// assert!(s.is_finite());
/// ```
#[derive(Debug, Clone)]
pub struct State {
    /// Coordinates `q`.
    pub q: DVector<f64>,
    /// Velocities `v = q'`.
    pub v: DVector<f64>,
    /// The true acceleration `a = v'` at the state's time.
    pub a: DVector<f64>,
    /// The generalized-alpha auxiliary acceleration (equal to `a` for Newmark and HHT).
    pub aux: DVector<f64>,
    /// Constraint multipliers (length `m`).
    pub lambda: DVector<f64>,
    pub(crate) work: Work,
}

/// The Newton buffers and trial values of one step.
#[derive(Debug, Clone)]
pub(crate) struct Work {
    /// Trial values at `t_{n+1}` (or, inside HHT's Newton, its evaluation point).
    pub q1: DVector<f64>,
    pub v1: DVector<f64>,
    pub a1: DVector<f64>,
    pub aux1: DVector<f64>,
    pub lambda1: DVector<f64>,
    /// The parts of the evaluation point that do not depend on the unknown.
    pub qe: DVector<f64>,
    pub ve: DVector<f64>,
    /// Residual (length `n`).
    pub r: DVector<f64>,
    /// Tangent (`n x n`).
    pub s: DMatrix<f64>,
    /// Constraint values (length `m`) and Jacobian (`m x n`).
    pub g: DVector<f64>,
    pub jac: DMatrix<f64>,
    /// Right-hand side and increment of the constrained Newton system (length `n + m`).
    pub rhs: DVector<f64>,
    /// LU of `n x n` dense matrices (the mass matrix of the consistent start).
    pub lu_n: Lu,
    /// The unconstrained Newton iteration matrix and its factorisation, in the storage of
    /// the system's pattern.
    pub iter: Tangent,
    /// LU of the `(n + m) x (n + m)` constrained systems.
    pub lu_c: Lu,
    /// The constrained start's finite differences: a displaced `q`, its Jacobian, and
    /// `m`-vectors for `g_t`, `g_tt`.
    pub qt: DVector<f64>,
    pub jac_t: DMatrix<f64>,
    pub gt_p: DVector<f64>,
    pub gt_m: DVector<f64>,
    pub gtt: DVector<f64>,
}

impl Work {
    fn new(n: usize, m: usize, pattern: Pattern) -> Self {
        Work {
            q1: DVector::zeros(n),
            v1: DVector::zeros(n),
            a1: DVector::zeros(n),
            aux1: DVector::zeros(n),
            lambda1: DVector::zeros(m),
            qe: DVector::zeros(n),
            ve: DVector::zeros(n),
            r: DVector::zeros(n),
            s: DMatrix::zeros(n, n),
            g: DVector::zeros(m),
            jac: DMatrix::zeros(m, n),
            rhs: DVector::zeros(n + m),
            lu_n: Lu::new(n),
            iter: Tangent::new(n, pattern),
            lu_c: Lu::new(n + m),
            qt: DVector::zeros(n),
            jac_t: DMatrix::zeros(m, n),
            gt_p: DVector::zeros(m),
            gt_m: DVector::zeros(m),
            gtt: DVector::zeros(m),
        }
    }
}

impl State {
    /// A zero state for `n` coordinates and `m` constraints, with its workspace (the only
    /// allocation).
    pub fn new(n: usize, m: usize) -> Self {
        Self::with_pattern(n, m, Pattern::Dense)
    }

    /// A zero state whose unconstrained iteration matrix has `pattern`.
    pub fn with_pattern(n: usize, m: usize, pattern: Pattern) -> Self {
        State {
            q: DVector::zeros(n),
            v: DVector::zeros(n),
            a: DVector::zeros(n),
            aux: DVector::zeros(n),
            lambda: DVector::zeros(m),
            work: Work::new(n, m, pattern),
        }
    }

    /// A zero state sized for an unconstrained system.
    pub fn for_system<S: SecondOrder + ?Sized>(sys: &S) -> Self {
        State::with_pattern(sys.dim(), 0, sys.pattern())
    }

    /// A zero state sized for a constrained system.
    pub fn for_constrained<S: Constraints + ?Sized>(sys: &S) -> Self {
        State::new(sys.dim(), sys.n_constraints())
    }

    /// Sets `q` and `v`, and zeroes `a`, `aux` and `lambda` (an integrator's `init` computes
    /// consistent ones).
    ///
    /// # Panics
    ///
    /// If `q0` or `v0` do not have length `n`.
    pub fn set(&mut self, q0: &[f64], v0: &[f64]) {
        self.q.copy_from_slice(q0);
        self.v.copy_from_slice(v0);
        self.a.fill(0.0);
        self.aux.fill(0.0);
        self.lambda.fill(0.0);
    }

    /// The number of coordinates `n`.
    pub fn dim(&self) -> usize {
        self.q.len()
    }

    /// The number of constraints `m`.
    pub fn n_constraints(&self) -> usize {
        self.lambda.len()
    }

    /// Every component of `q`, `v`, `a`, `aux` and `lambda` is finite.
    pub fn is_finite(&self) -> bool {
        [&self.q, &self.v, &self.a, &self.aux, &self.lambda]
            .iter()
            .all(|x| x.iter().all(|c| c.is_finite()))
    }

    /// Moves the trial values of the workspace into the state (swaps, no copies). `lambda`
    /// only when `with_lambda`.
    pub(crate) fn commit(&mut self, with_lambda: bool) {
        let w = &mut self.work;
        std::mem::swap(&mut self.q, &mut w.q1);
        std::mem::swap(&mut self.v, &mut w.v1);
        std::mem::swap(&mut self.a, &mut w.a1);
        std::mem::swap(&mut self.aux, &mut w.aux1);
        if with_lambda {
            std::mem::swap(&mut self.lambda, &mut w.lambda1);
        }
    }

    /// Panics unless the state is sized for `n` coordinates and `m` constraints.
    pub(crate) fn assert_sizes(&self, n: usize, m: usize) {
        assert!(
            self.dim() == n && self.n_constraints() == m,
            "state for n = {}, m = {} used with a system of n = {n}, m = {m}",
            self.dim(),
            self.n_constraints()
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::lu::LinearSolve;

    /// `commit` swaps the trial values in (the workspace keeps the old ones, same lengths)
    /// and leaves `lambda` alone unless asked.
    #[test]
    fn commit_swaps_without_reallocating() {
        let mut s = State::new(2, 1);
        s.set(&[1.0, 2.0], &[3.0, 4.0]);
        s.work.q1.fill(5.0);
        s.work.lambda1.fill(7.0);
        s.commit(false);
        assert_eq!(s.q.as_slice(), &[5.0, 5.0]);
        assert_eq!(s.work.q1.as_slice(), &[1.0, 2.0]);
        assert_eq!(s.lambda[0], 0.0);
        s.commit(true);
        assert_eq!(s.lambda[0], 7.0);
        assert_eq!((s.work.rhs.len(), s.work.lu_c.dim()), (3, 3));
    }

    /// A NaN anywhere in the state is seen by `is_finite`.
    #[test]
    fn non_finite_is_seen() {
        let mut s = State::new(1, 1);
        assert!(s.is_finite());
        s.lambda[0] = f64::NAN;
        assert!(!s.is_finite());
    }

    /// A size mismatch between state and system is a panic naming both sizes.
    #[test]
    #[should_panic(expected = "state for n = 2")]
    fn size_mismatch_panics() {
        State::new(2, 0).assert_sizes(3, 0);
    }
}
