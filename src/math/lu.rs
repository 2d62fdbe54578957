//! `lu`: the one dense LU factorisation of the crate, `P A = L U` with partial (row)
//! pivoting, in buffers sized once, behind the small interface [`LinearSolve`] (fill the
//! matrix, `factor`, `solve` any number of times) that a banded or sparse factorisation can
//! implement later. It serves the Newton solves of the implicit Runge-Kutta methods
//! (`integrate::implicit_rk`, order `s n`) and of the structural integrators and models
//! (`structural`, the beam's and the fiber column's tangents); nothing is allocated after
//! [`DenseLu::new`].
//!
//! Factorisation: Doolittle's right-looking elimination in the form of LAPACK's `dgetf2`
//! (Golub & Van Loan, "Matrix Computations", 4th ed., Algorithm 3.4.1): at column `k` the
//! first row of largest `|a_ik|`, `i >= k`, is swapped into place, the multipliers
//! `l_ik = a_ik (1 / a_kk)` overwrite the strictly lower part, and the trailing block is
//! updated column by column (contiguous in the column-major buffer), `a_ij -= l_ik a_kj`,
//! skipping a column whose `a_kj` is zero. `L` (unit diagonal) and `U` share the buffer;
//! the swaps are LAPACK's `ipiv` (row `k` was swapped with row `ipiv[k] >= k`). Cost
//! `2 n^3 / 3` flops; `2 n^2` per solve. Every element sees the same operations, in the same
//! order, as in nalgebra's `LU` (which has no skip, is faster and allocates: the
//! measurements of `benches/lu.rs` and why this one is kept are in [`DenseLu`]'s docs).
//!
//! Substitution (Golub & Van Loan, Alg. 3.1.3-4, column-oriented "saxpy" forms: once a
//! component is final it is eliminated from every row it enters, so the row updates are
//! independent and vectorize): forward with `L`, then back with `U`, in one of two
//! arithmetics fixed at construction ([`Substitution`]): [`Substitution::Divide`] divides by
//! `u_jj` and skips a zero component (nalgebra's operations; the structural integrators),
//! [`Substitution::Reciprocal`] multiplies by the stored `1 / u_jj` and skips nothing (the
//! implicit Runge-Kutta methods: a division's latency sat on the chain from one component to
//! the next, measured 3402 vs 4656 ns/step on heavy_top, gauss6, n = 39; one rounding more
//! per component, within the same backward-error bound's order). Both exist so that every
//! stored result stays bit-identical to the two factorisations this module replaced.
//!
//! Backward stability: `P (A + E) = L U` with `|E| <= 2 n eps |L| |U|`; the growth factor of
//! partial pivoting is at most `2^(n-1)`, small for every matrix met here.
//!
//! Where it fails, as a value, never a panic ([`LuError`]): a buffer of the wrong length; a
//! non-finite entry; a pivot at or below `n eps` times the largest entry of its column of
//! `A` (numerically singular, e.g. the mass matrix of a system with a massless coordinate;
//! the threshold is per column so that a saddle-point matrix `[M G^T; G 0]` with a heavy `M`
//! is not mistaken for singular); a solve without a valid factorisation. An ill-conditioned
//! but regular matrix is factored, and its solution is as inaccurate as its condition says.
use nalgebra::{DMatrix, DVector};

/// Why a factorisation or solve failed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LuError {
    /// A buffer's length does not match the order `n`.
    Dimension { n: usize, len: usize },
    /// The matrix holds a NaN or an infinity.
    NonFinite,
    /// The largest candidate pivot of `column` was `pivot`, at or below `threshold`,
    /// `n eps max_i |A_i,column|` (zero for a zero column).
    Singular {
        column: usize,
        pivot: f64,
        threshold: f64,
    },
    /// A solve without a valid factorisation (the last `factor` failed, or the matrix was
    /// changed since).
    NotFactored,
    /// An entry written outside the pattern the matrix was sized for (a banded store): the
    /// first stray entry `(row, column)`, or None when the system wrote its tangent densely
    /// only (no banded writer) into a banded store. The system's declared pattern is wrong.
    OutsidePattern { entry: Option<(usize, usize)> },
}

impl std::fmt::Display for LuError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LuError::Dimension { n, len } => {
                write!(f, "buffer of length {len} does not fit order {n}")
            }
            LuError::NonFinite => write!(f, "matrix with a non-finite entry"),
            LuError::Singular {
                column,
                pivot,
                threshold,
            } => write!(
                f,
                "numerically singular: pivot {pivot:.3e} of column {column} <= {threshold:.3e}"
            ),
            LuError::NotFactored => write!(f, "solve without a valid factorisation"),
            LuError::OutsidePattern {
                entry: Some((row, column)),
            } => write!(
                f,
                "entry ({row}, {column}) written outside the declared pattern"
            ),
            LuError::OutsidePattern { entry: None } => write!(
                f,
                "a banded pattern declared, but the tangent written only densely"
            ),
        }
    }
}

/// A factorisation of a square matrix held in its own buffer: fill it (the implementor's
/// own accessor), `factor`, then `solve` as often as needed. A banded or sparse
/// factorisation implements the same three calls.
pub trait LinearSolve {
    /// The order `n`.
    fn dim(&self) -> usize;
    /// Factors the buffer in place; on error the factorisation is unusable until the next
    /// successful call.
    fn factor(&mut self) -> Result<(), LuError>;
    /// Solves `A x = b` in place (`b` becomes `x`, length `n`).
    fn solve(&self, b: &mut [f64]) -> Result<(), LuError>;
}

/// The arithmetic of the substitutions (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Substitution {
    /// Divide by each pivot, skip zero components (nalgebra's operations).
    Divide,
    /// Multiply by each pivot's stored reciprocal, skip nothing.
    Reciprocal,
}

/// A dense LU factorisation with partial pivoting in preallocated column-major buffers.
///
/// Why hand-written rather than `nalgebra::linalg::LU` (`benches/lu.rs`, factor and one
/// solve, median of criterion on a shared 2-core machine, so about +-20 %): nalgebra's
/// dynamic LU is faster, 338 vs 369 ns at n = 6, 2.3 vs 3.7 us at 18, 11.9 vs 15.7 us at 39,
/// 45 vs 51 us at 66, 1.95 vs 2.09 ms at 243 (this type with division; with reciprocals
/// 342 ns, 3.8 us, 20 us, 58 us, 2.5 ms), and its fixed-size LU faster still (248 ns at 6,
/// 1.9 us at 18). It is not used because its dynamic LU takes its matrix by value and
/// allocates its permutation, so every Newton factorisation would allocate (the hot loops
/// must not: `tests/no_alloc*.rs`), and its fixed-size LU needs the order at compile time
/// while the Newton systems' orders are run-time (`6 s`, `3 (N + 1)`, `6 nodes`). Division
/// is bit-identical to nalgebra's LU (a test checks it), so calling nalgebra's public
/// elimination kernels (`linalg::gauss_step_swap`) on this buffer would be a way to its
/// speed without its allocation; not done yet.
///
/// # Example
///
/// Fill the matrix in place, factor, and solve `A x = b` in `b`; a singular matrix is an
/// error naming its column:
///
/// ```
/// use mbdbench::math::lu::{DenseLu, LinearSolve, LuError};
/// use nalgebra::{DMatrix, DVector};
///
/// let mut lu = DenseLu::new(3);
/// lu.matrix_mut().copy_from(&DMatrix::from_row_slice(3, 3, &[
///     0.0, 2.0, 1.0,
///     1.0, 1.0, 0.0,
///     4.0, 0.0, 3.0,
/// ]));
/// lu.factor().unwrap();
/// let mut b = DVector::from_vec(vec![7.0, 3.0, 13.0]);
/// lu.solve_in_place(&mut b).unwrap();
/// assert!((b - DVector::from_vec(vec![1.0, 2.0, 3.0])).amax() < 1e-14);
///
/// lu.matrix_mut().copy_from(&DMatrix::from_row_slice(3, 3, &[
///     1.0, 2.0, 3.0,
///     2.0, 4.0, 6.0,
///     0.0, 0.0, 1.0,
/// ]));
/// assert!(matches!(lu.factor(), Err(LuError::Singular { column: 1, .. })));
/// ```
#[derive(Debug, Clone)]
pub struct DenseLu {
    /// The matrix before `factor`, `L` and `U` after it.
    a: DMatrix<f64>,
    /// LAPACK-style row swaps: row `k` was swapped with row `ipiv[k] >= k`.
    ipiv: Vec<usize>,
    /// The singularity threshold of each column.
    threshold: Vec<f64>,
    /// `1 / u_jj` ([`Substitution::Reciprocal`] only).
    inv_diag: Vec<f64>,
    substitution: Substitution,
    /// The buffer holds a valid factorisation.
    factored: bool,
}

impl DenseLu {
    /// Buffers for `n x n` matrices (the only allocation), solving with
    /// [`Substitution::Divide`].
    pub fn new(n: usize) -> Self {
        Self::with_substitution(n, Substitution::Divide)
    }

    /// Buffers for `n x n` matrices, solving with `substitution`.
    pub fn with_substitution(n: usize, substitution: Substitution) -> Self {
        DenseLu {
            a: DMatrix::zeros(n, n),
            ipiv: vec![0; n],
            threshold: vec![0.0; n],
            inv_diag: vec![0.0; n],
            substitution,
            factored: false,
        }
    }

    /// The matrix buffer, to be filled before `factor` (it invalidates the factorisation).
    pub fn matrix_mut(&mut self) -> &mut DMatrix<f64> {
        self.factored = false;
        &mut self.a
    }

    /// The matrix buffer (the factors after a successful `factor`).
    pub fn matrix(&self) -> &DMatrix<f64> {
        &self.a
    }

    /// [`LinearSolve::factor`] with each column's singularity threshold raised to at least
    /// `floor[j]` (a floor of the wrong length is a dimension error). The Schur complement
    /// of a bordered banded matrix (`banded`) takes its border columns' thresholds from
    /// the whole matrix: its own entries can be round-off of a cancellation.
    pub fn factor_with_floor(&mut self, floor: &[f64]) -> Result<(), LuError> {
        self.factored = false;
        if floor.len() != self.dim() {
            return Err(LuError::Dimension {
                n: self.dim(),
                len: floor.len(),
            });
        }
        self.thresholds()?;
        for (t, f) in self.threshold.iter_mut().zip(floor) {
            *t = t.max(*f);
        }
        self.eliminate()
    }

    /// Whether a valid factorisation is held.
    pub fn is_factored(&self) -> bool {
        self.factored
    }

    /// Copies `m` into the buffer and factors it; a dimension error if `m` is not `n x n`.
    pub fn factor_from(&mut self, m: &DMatrix<f64>) -> Result<(), LuError> {
        if m.shape() != self.a.shape() {
            self.factored = false;
            return Err(LuError::Dimension {
                n: self.dim(),
                len: m.len(),
            });
        }
        self.matrix_mut().copy_from(m);
        self.factor()
    }

    /// [`LinearSolve::solve`] on a vector.
    pub fn solve_in_place(&self, b: &mut DVector<f64>) -> Result<(), LuError> {
        self.solve(b.as_mut_slice())
    }

    /// The per-column thresholds; an error on a non-finite entry.
    fn thresholds(&mut self) -> Result<(), LuError> {
        let n = self.dim();
        for (j, col) in self.a.column_iter().enumerate() {
            let mut cmax = 0.0_f64;
            for x in col.iter() {
                if !x.is_finite() {
                    return Err(LuError::NonFinite);
                }
                cmax = cmax.max(x.abs());
            }
            self.threshold[j] = n as f64 * f64::EPSILON * cmax;
        }
        Ok(())
    }
}

impl LinearSolve for DenseLu {
    fn dim(&self) -> usize {
        self.ipiv.len()
    }

    fn factor(&mut self) -> Result<(), LuError> {
        self.factored = false;
        self.thresholds()?;
        self.eliminate()
    }

    fn solve(&self, b: &mut [f64]) -> Result<(), LuError> {
        self.substitute(b)
    }
}

impl DenseLu {
    /// The elimination of `factor` with the thresholds in place.
    fn eliminate(&mut self) -> Result<(), LuError> {
        let n = self.dim();
        let a = self.a.as_mut_slice();
        for k in 0..n {
            // The pivot: the first largest candidate of column k.
            let col = &a[k * n..(k + 1) * n];
            let (mut p, mut best) = (k, col[k].abs());
            for (i, x) in col.iter().enumerate().skip(k + 1) {
                if x.abs() > best {
                    best = x.abs();
                    p = i;
                }
            }
            if best <= self.threshold[k] || best == 0.0 {
                return Err(LuError::Singular {
                    column: k,
                    pivot: best,
                    threshold: self.threshold[k],
                });
            }
            self.ipiv[k] = p;
            if p != k {
                for j in 0..n {
                    a.swap(j * n + k, j * n + p);
                }
            }
            let inv = 1.0 / a[k * n + k];
            for l in &mut a[k * n + k + 1..(k + 1) * n] {
                *l *= inv;
            }
            // Trailing update, column by column.
            let (left, right) = a.split_at_mut((k + 1) * n);
            let lcol = &left[k * n + k + 1..];
            for col in right.chunks_exact_mut(n) {
                let akj = col[k];
                if akj != 0.0 {
                    for (x, l) in col[k + 1..].iter_mut().zip(lcol) {
                        *x -= l * akj;
                    }
                }
            }
        }
        if self.substitution == Substitution::Reciprocal {
            for j in 0..n {
                self.inv_diag[j] = 1.0 / a[j * n + j];
            }
        }
        self.factored = true;
        Ok(())
    }

    /// The substitutions of `solve`.
    fn substitute(&self, b: &mut [f64]) -> Result<(), LuError> {
        if !self.factored {
            return Err(LuError::NotFactored);
        }
        let n = self.dim();
        if b.len() != n {
            return Err(LuError::Dimension { n, len: b.len() });
        }
        for (k, &p) in self.ipiv.iter().enumerate() {
            b.swap(k, p);
        }
        let a = self.a.as_slice();
        match self.substitution {
            Substitution::Divide => {
                // L y = P b (unit diagonal), then U x = y.
                for k in 0..n {
                    let bk = b[k];
                    if bk != 0.0 {
                        for (bi, l) in b[k + 1..].iter_mut().zip(&a[k * n + k + 1..(k + 1) * n]) {
                            *bi -= l * bk;
                        }
                    }
                }
                for k in (0..n).rev() {
                    b[k] /= a[k * n + k];
                    let bk = b[k];
                    if bk != 0.0 {
                        for (bi, u) in b[..k].iter_mut().zip(&a[k * n..k * n + k]) {
                            *bi -= u * bk;
                        }
                    }
                }
            }
            Substitution::Reciprocal => {
                for k in 0..n {
                    let yk = b[k];
                    for (bi, l) in b[k + 1..].iter_mut().zip(&a[k * n + k + 1..(k + 1) * n]) {
                        *bi -= l * yk;
                    }
                }
                for k in (0..n).rev() {
                    b[k] *= self.inv_diag[k];
                    let xk = b[k];
                    for (bi, u) in b[..k].iter_mut().zip(&a[k * n..k * n + k]) {
                        *bi -= u * xk;
                    }
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
#[path = "lu_tests.rs"]
mod tests;
