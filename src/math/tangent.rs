//! `tangent`: where a Newton iteration's matrix is written and factored, chosen once from
//! the pattern its system declares. A system writes its tangent entry by entry through
//! [`Entries`] (`clear`, `add`, `set`), the same code for a dense `DMatrix` and for a
//! [`Tangent`]; the integrator sizes one [`Tangent`] from the system's [`Pattern`] before
//! the first step (the only allocation) and factors and solves it through [`LinearSolve`].
//!
//! The choice ([`Tangent::new`]): a dense pattern, or a banded one below the measured
//! crossover, is held and factored densely ([`DenseLu`], `2 n^3 / 3` flops); a larger banded
//! pattern by [`BandedLu`] (`O(n kl (kl + ku))`). Crossover, measured with
//! `benches/structural.rs`'s `structural_lu` group (factor plus one solve, `taskset -c 1`,
//! 5 rounds, criterion estimates, median; a shared, loaded machine) on the beam's band
//! `kl = ku = 5` with one border row and column: dense vs banded 0.48 vs 0.93 us at `n = 7`,
//! 1.48 vs 1.91 at 13, 2.32 vs 2.26 at 16, 3.37 vs 2.56 at 19, 4.51 vs 2.98 at 22 and 9.22
//! vs 4.23 at 31; so banded from `n >= 3 (kl + ku) / 2 + 1` (16 for the beam: 5 elements
//! with a free hub, 6 on a prescribed base). Measured for this band only.
//! The beam's modal models and every small system keep the dense path.
//!
//! The pattern a system declares must hold every entry it writes: a write outside it is
//! remembered and makes the next `factor` fail with [`LuError::OutsidePattern`] (a `newton_failure`
//! of the step, not a panic), so a wrong declaration shows at once in any test that steps.
//!
//! Later users, by design (not wired yet): a constrained system's saddle-point matrix
//! `[S G^T; G 0]` is a [`Band`] with the `m` multipliers as a border last
//! ([`Border::Last`]); the fiber column's multi-element meshes are banded by their node
//! numbering (6 coordinates a node: `kl = ku = 11`).
use nalgebra::DMatrix;

use super::banded::{Band, BandedLu, Border};
use super::lu::{DenseLu, LinearSolve, LuError};

/// The nonzero pattern of a system's tangent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pattern {
    /// Any entry may be nonzero.
    Dense,
    /// Nonzero only in a band and its border ([`Band`]; its `n` is the system's order).
    Banded(Band),
}

/// The smallest order at which a band of `kl`, `ku` is factored banded (module docs).
pub fn crossover(kl: usize, ku: usize) -> usize {
    3 * (kl + ku) / 2 + 1
}

/// A matrix written entry by entry: a tangent's writer is generic over it.
pub trait Entries {
    /// Sets every entry to zero.
    fn clear(&mut self);
    /// `A_ij += v`.
    fn add(&mut self, i: usize, j: usize, v: f64);
    /// `A_ij = v`.
    fn set(&mut self, i: usize, j: usize, v: f64);
}

impl Entries for DMatrix<f64> {
    #[inline]
    fn clear(&mut self) {
        self.fill(0.0);
    }
    #[inline]
    fn add(&mut self, i: usize, j: usize, v: f64) {
        self[(i, j)] += v;
    }
    #[inline]
    fn set(&mut self, i: usize, j: usize, v: f64) {
        self[(i, j)] = v;
    }
}

#[derive(Debug, Clone)]
enum Storage {
    Dense(DenseLu),
    Banded(BandedLu),
}

/// An iteration matrix's storage and factorisation, dense or banded by its pattern.
///
/// # Example
///
/// A tridiagonal pattern of order 40 is held banded, written through [`Entries`],
/// factored and solved; a write outside the pattern makes `factor` fail:
///
/// ```
/// use mbdbench::math::banded::{Band, Border};
/// use mbdbench::math::lu::{LinearSolve, LuError};
/// use mbdbench::math::tangent::{Entries, Pattern, Tangent};
///
/// let n = 40;
/// let mut s = Tangent::new(n, Pattern::Banded(Band { n, kl: 1, ku: 1, border: Border::None }));
/// assert!(s.is_banded());
/// for i in 0..n {
///     s.set(i, i, 2.0);
///     if i > 0 {
///         s.set(i, i - 1, -1.0);
///         s.set(i - 1, i, -1.0);
///     }
/// }
/// s.factor().unwrap();
/// let mut b = vec![0.0; n];
/// b[0] = 1.0;
/// b[n - 1] = 1.0;
/// s.solve(&mut b).unwrap();
/// assert!(b.iter().all(|x| (x - 1.0).abs() < 1e-12));
///
/// s.add(0, 5, 1.0);
/// s.add(0, 6, 1.0);
/// // The first stray entry is named, and clearing forgets it.
/// assert_eq!(s.factor(), Err(LuError::OutsidePattern { entry: Some((0, 5)) }));
/// s.clear();
/// assert!(s.factor().is_err_and(|e| matches!(e, LuError::Singular { .. })));
/// ```
#[derive(Debug, Clone)]
pub struct Tangent {
    storage: Storage,
    /// The first write outside the pattern since the last `clear`.
    stray: Option<LuError>,
}

impl Tangent {
    /// Storage for an order-`n` matrix of `pattern` (a banded pattern's own `n` is replaced
    /// by `n`): dense below the crossover, else banded.
    pub fn new(n: usize, pattern: Pattern) -> Self {
        let storage = match pattern {
            Pattern::Banded(band) if n >= crossover(band.kl, band.ku) => {
                Storage::Banded(BandedLu::new(Band { n, ..band }))
            }
            _ => Storage::Dense(DenseLu::new(n)),
        };
        Tangent {
            storage,
            stray: None,
        }
    }

    /// Whether the matrix is held banded.
    pub fn is_banded(&self) -> bool {
        matches!(self.storage, Storage::Banded(_))
    }

    /// The dense matrix buffer, when held densely (it invalidates the factorisation).
    pub fn dense_mut(&mut self) -> Option<&mut DMatrix<f64>> {
        match &mut self.storage {
            Storage::Dense(lu) => Some(lu.matrix_mut()),
            Storage::Banded(_) => None,
        }
    }

    /// Marks the matrix as written outside its pattern (the next `factor` fails).
    pub fn mark_stray(&mut self) {
        self.stray
            .get_or_insert(LuError::OutsidePattern { entry: None });
    }

    /// `A_ij` before `factor` (0 outside a banded pattern).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        match &self.storage {
            Storage::Dense(lu) => lu.matrix()[(i, j)],
            Storage::Banded(lu) => lu.get(i, j),
        }
    }

    /// Solves `A x = b` in place, `b` a vector.
    pub fn solve_in_place(&self, b: &mut nalgebra::DVector<f64>) -> Result<(), LuError> {
        self.solve(b.as_mut_slice())
    }
}

impl Entries for Tangent {
    fn clear(&mut self) {
        self.stray = None;
        match &mut self.storage {
            Storage::Dense(lu) => lu.matrix_mut().fill(0.0),
            Storage::Banded(lu) => lu.clear(),
        }
    }

    #[inline]
    fn add(&mut self, i: usize, j: usize, v: f64) {
        match &mut self.storage {
            Storage::Dense(lu) => lu.matrix_mut()[(i, j)] += v,
            Storage::Banded(lu) => match lu.entry_mut(i, j) {
                Ok(x) => *x += v,
                Err(e) => {
                    self.stray.get_or_insert(e);
                }
            },
        }
    }

    #[inline]
    fn set(&mut self, i: usize, j: usize, v: f64) {
        match &mut self.storage {
            Storage::Dense(lu) => lu.matrix_mut()[(i, j)] = v,
            Storage::Banded(lu) => match lu.entry_mut(i, j) {
                Ok(x) => *x = v,
                Err(e) => {
                    self.stray.get_or_insert(e);
                }
            },
        }
    }
}

impl LinearSolve for Tangent {
    fn dim(&self) -> usize {
        match &self.storage {
            Storage::Dense(lu) => lu.dim(),
            Storage::Banded(lu) => lu.dim(),
        }
    }

    fn factor(&mut self) -> Result<(), LuError> {
        if let Some(e) = self.stray {
            return Err(e);
        }
        match &mut self.storage {
            Storage::Dense(lu) => lu.factor(),
            Storage::Banded(lu) => lu.factor(),
        }
    }

    fn solve(&self, b: &mut [f64]) -> Result<(), LuError> {
        match &self.storage {
            Storage::Dense(lu) => lu.solve(b),
            Storage::Banded(lu) => lu.solve(b),
        }
    }
}

/// The band of a border-free pattern, for tests and benches: `Pattern::Banded` of order
/// `n` with bandwidths `kl`, `ku` and `border`.
pub fn banded(n: usize, kl: usize, ku: usize, border: Border) -> Pattern {
    Pattern::Banded(Band { n, kl, ku, border })
}
