//! The initial guess of the stage increments of an implicit Gauss step (`ImplicitRk`,
//! `mod.rs`; used by the Newton iteration in `newton.rs`).
//!
//! Initial guess: the previous step's collocation polynomial extrapolated (HW II, sec. IV.8,
//! "starting values"; error `O(h^(s+1))` on additive charts, `O(h^3)` on a Lie group, where
//! the change of base point adds a dropped commutator term of the BCH formula), when the step
//! continues the previous one (`t` equals the previous `t + h`); otherwise the explicit
//! predictor `Z_i = c_i h f(t, x)`.
//!
//! The extrapolation evaluates the previous collocation polynomial `Theta` through the Lagrange
//! basis on the nodes `{0} U c`: `Z_i = Theta(1 + r c_i) - Theta(1)`, `r = h / h_prev`.
//!
//! Where it fails: the extrapolated guess is poor when `h` changes much or the solution turns
//! sharply; Newton then needs more iterations or fails and is retried from the predictor.

/// `L_j(theta)`: the Lagrange polynomial on the nodes `{0} U c` that is 1 at `c_j` and 0 at the
/// other nodes (including 0).
pub(super) fn lagrange(c: &[f64], j: usize, theta: f64) -> f64 {
    let mut l = theta / c[j];
    for (k, ck) in c.iter().enumerate() {
        if k != j {
            l *= (theta - ck) / (c[j] - ck);
        }
    }
    l
}

/// The initial guess of a Newton attempt.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Guess {
    Extrapolated,
    Predictor,
}
