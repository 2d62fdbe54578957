//! `lu`: a dense LU factorisation with partial (row) pivoting, `P A = L U`, that factors and
//! solves in buffers sized once, so the Newton iterations of the structural integrators
//! allocate nothing per step.
//!
//! The factorisation is Doolittle's right-looking elimination in the form of LAPACK's
//! `dgetf2` (Golub & Van Loan, "Matrix Computations", 4th ed., Algorithm 3.4.1, Gaussian
//! elimination with partial pivoting): at column `k` the row with the largest `|a_ik|`,
//! `i >= k`, is swapped into place, the multipliers `l_ik = a_ik / a_kk` overwrite the
//! strictly lower part and the trailing block is updated, `a_ij -= l_ik a_kj`. `L` (unit
//! diagonal) and `U` share one `n x n` buffer; the swaps are stored as LAPACK's `ipiv`
//! (`row k was swapped with row ipiv[k]`). A solve applies the swaps to `b`, then forward
//! substitution with `L` and back substitution with `U`, all in `b`.
//!
//! Cost `2 n^3 / 3` flops to factor, `2 n^2` to solve. Invariants: the buffers are sized by
//! `Lu::new(n)` and never reallocated; a failed factorisation leaves the factor unusable
//! (`solve` refuses it) until the next successful `factor`. Partial pivoting is backward
//! stable in practice (growth factor bounded by `2^(n-1)`, small for every matrix met here).
//! Where it fails: a pivot at or below `n eps` times the largest entry of its column of `A`
//! (a numerically singular matrix, for example the mass matrix of a system with a massless
//! coordinate; the threshold is per column so that a saddle-point matrix with blocks of
//! very different size, `[M G^T; G 0]` with a heavy `M`, is not mistaken for singular) is
//! reported as
//! [`LuError::Singular`] with the column, a non-finite entry as [`LuError::NonFinite`]; an
//! ill-conditioned but regular matrix is factored and its solution is as inaccurate as its
//! condition number says.
use nalgebra::{DMatrix, DVector};

/// Why a factorisation failed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LuError {
    /// The largest candidate pivot of `column` was `pivot`, at or below the threshold
    /// `n eps max_i |A_i,column|` (zero for a zero column).
    Singular { column: usize, pivot: f64 },
    /// The matrix holds a NaN or an infinity.
    NonFinite,
    /// `solve_in_place` without a valid factorisation (the last `factor` failed, or the
    /// matrix was changed since).
    NotFactored,
}

impl std::fmt::Display for LuError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LuError::Singular { column, pivot } => {
                write!(f, "singular matrix: pivot {pivot:e} in column {column}")
            }
            LuError::NonFinite => write!(f, "matrix with a non-finite entry"),
            LuError::NotFactored => write!(f, "solve without a valid factorisation"),
        }
    }
}

/// An LU factorisation with partial pivoting in preallocated buffers.
///
/// # Example
///
/// Fill the matrix in place, factor, and solve `A x = b` in `b` (nothing is allocated after
/// `Lu::new`); a singular matrix is an error naming its column:
///
/// ```
/// use mbdbench::structural::lu::{Lu, LuError};
/// use nalgebra::{DMatrix, DVector};
///
/// let mut lu = Lu::new(3);
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
pub struct Lu {
    /// The matrix before `factor`, `L` and `U` after it.
    a: DMatrix<f64>,
    /// LAPACK-style row swaps: row `k` was swapped with row `ipiv[k] >= k`.
    ipiv: Vec<usize>,
    /// The singularity threshold of each column.
    threshold: Vec<f64>,
    /// The buffer holds a valid factorisation.
    factored: bool,
}

impl Lu {
    /// Buffers for `n x n` matrices (the only allocation).
    pub fn new(n: usize) -> Self {
        Lu {
            a: DMatrix::zeros(n, n),
            ipiv: vec![0; n],
            threshold: vec![0.0; n],
            factored: false,
        }
    }

    /// The order `n`.
    pub fn dim(&self) -> usize {
        self.ipiv.len()
    }

    /// The matrix buffer, to be filled before `factor` (it invalidates the factorisation).
    pub fn matrix_mut(&mut self) -> &mut DMatrix<f64> {
        self.factored = false;
        &mut self.a
    }

    /// Copies `m` (`n x n`) into the buffer and factors it.
    ///
    /// # Panics
    ///
    /// If `m` is not `n x n`.
    pub fn factor_from(&mut self, m: &DMatrix<f64>) -> Result<(), LuError> {
        self.matrix_mut().copy_from(m);
        self.factor()
    }

    /// Factors the buffer in place, `P A = L U`.
    pub fn factor(&mut self) -> Result<(), LuError> {
        self.factored = false;
        let n = self.dim();
        let a = &mut self.a;
        for (j, col) in a.column_iter().enumerate() {
            let mut cmax = 0.0_f64;
            for x in col.iter() {
                if !x.is_finite() {
                    return Err(LuError::NonFinite);
                }
                cmax = cmax.max(x.abs());
            }
            self.threshold[j] = n as f64 * f64::EPSILON * cmax;
        }
        for k in 0..n {
            // The pivot: the largest candidate of column k.
            let mut p = k;
            let mut best = a[(k, k)].abs();
            for i in k + 1..n {
                let c = a[(i, k)].abs();
                if c > best {
                    best = c;
                    p = i;
                }
            }
            if best <= self.threshold[k] || best == 0.0 {
                return Err(LuError::Singular {
                    column: k,
                    pivot: best,
                });
            }
            self.ipiv[k] = p;
            if p != k {
                a.swap_rows(k, p);
            }
            let inv = 1.0 / a[(k, k)];
            for i in k + 1..n {
                a[(i, k)] *= inv;
            }
            // Trailing update, column by column (nalgebra stores columns contiguously).
            for j in k + 1..n {
                let akj = a[(k, j)];
                if akj != 0.0 {
                    for i in k + 1..n {
                        let lik = a[(i, k)];
                        a[(i, j)] -= lik * akj;
                    }
                }
            }
        }
        self.factored = true;
        Ok(())
    }

    /// Solves `A x = b` with the last successful factorisation, overwriting `b` with `x`.
    /// An error if there is none (the last `factor` failed or the matrix was changed since).
    ///
    /// # Panics
    ///
    /// If `b` does not have length `n`.
    pub fn solve_in_place(&self, b: &mut DVector<f64>) -> Result<(), LuError> {
        if !self.factored {
            return Err(LuError::NotFactored);
        }
        let n = self.dim();
        assert_eq!(
            b.len(),
            n,
            "right-hand side of length {} for n = {n}",
            b.len()
        );
        let a = &self.a;
        for (k, &p) in self.ipiv.iter().enumerate() {
            if p != k {
                b.swap_rows(k, p);
            }
        }
        // L y = P b (unit diagonal), column-oriented.
        for k in 0..n {
            let bk = b[k];
            if bk != 0.0 {
                for i in k + 1..n {
                    b[i] -= a[(i, k)] * bk;
                }
            }
        }
        // U x = y, column-oriented.
        for k in (0..n).rev() {
            b[k] /= a[(k, k)];
            let bk = b[k];
            if bk != 0.0 {
                for i in 0..k {
                    b[i] -= a[(i, k)] * bk;
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A permutation matrix (every pivot needs a swap) is solved exactly.
    #[test]
    fn permutation_is_solved_exactly() {
        let mut lu = Lu::new(3);
        let m = DMatrix::from_row_slice(3, 3, &[0.0, 0.0, 2.0, 0.0, 3.0, 0.0, 5.0, 0.0, 0.0]);
        lu.factor_from(&m).unwrap();
        let mut b = DVector::from_vec(vec![2.0, 6.0, 15.0]);
        lu.solve_in_place(&mut b).unwrap();
        assert_eq!(b.as_slice(), &[3.0, 2.0, 1.0]);
    }

    /// A zero row, a rank-one matrix and a NaN are errors, and a failed factorisation cannot
    /// be used to solve.
    #[test]
    fn singular_and_non_finite_are_errors() {
        let mut lu = Lu::new(2);
        let zero_row = DMatrix::from_row_slice(2, 2, &[0.0, 0.0, 0.0, 1.0]);
        assert_eq!(
            lu.factor_from(&zero_row),
            Err(LuError::Singular {
                column: 0,
                pivot: 0.0
            })
        );
        let mut b = DVector::from_vec(vec![1.0, 1.0]);
        assert_eq!(lu.solve_in_place(&mut b), Err(LuError::NotFactored));
        let rank_one = DMatrix::from_row_slice(2, 2, &[1.0, 3.0, 1.0 / 3.0, 1.0]);
        assert!(matches!(
            lu.factor_from(&rank_one),
            Err(LuError::Singular { column: 1, .. })
        ));
        let nan = DMatrix::from_row_slice(2, 2, &[1.0, f64::NAN, 0.0, 1.0]);
        assert_eq!(lu.factor_from(&nan), Err(LuError::NonFinite));
    }

    /// Refactoring the same buffers with a new matrix gives that matrix's solution (no state
    /// of the previous factorisation survives).
    #[test]
    fn buffers_are_reused() {
        let mut lu = Lu::new(2);
        lu.factor_from(&DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 1.0, 0.0]))
            .unwrap();
        let mut b = DVector::from_vec(vec![2.0, 4.0]);
        lu.solve_in_place(&mut b).unwrap();
        assert_eq!(b.as_slice(), &[4.0, 2.0]);
        lu.factor_from(&DMatrix::from_row_slice(2, 2, &[2.0, 0.0, 0.0, 4.0]))
            .unwrap();
        let mut b = DVector::from_vec(vec![2.0, 4.0]);
        lu.solve_in_place(&mut b).unwrap();
        assert_eq!(b.as_slice(), &[1.0, 1.0]);
    }

    /// A saddle-point matrix with a heavy mass block, `[1e12 1; 1 0]`, is regular and
    /// solved (its second pivot, `-1e-12`, is small against the matrix but not against its
    /// column).
    #[test]
    fn unbalanced_saddle_point_is_regular() {
        let mut lu = Lu::new(2);
        lu.factor_from(&DMatrix::from_row_slice(2, 2, &[1e12, 1.0, 1.0, 0.0]))
            .unwrap();
        let mut b = DVector::from_vec(vec![1e12 + 2.0, 1.0]);
        lu.solve_in_place(&mut b).unwrap();
        assert!(
            (b[0] - 1.0).abs() < 1e-15 && (b[1] - 2.0).abs() < 1e-3,
            "{b}"
        );
    }

    proptest! {
        /// For a random well-conditioned `A` (a random matrix plus a dominant diagonal, so
        /// its condition number stays below about 10 but pivoting still happens off the
        /// diagonal through the random signs) the solution of `A x = b` matches
        /// `A^{-1} b` from nalgebra's own LU, and its residual is at round-off.
        #[test]
        fn solve_matches_inverse(
            n in 1usize..9,
            entries in proptest::collection::vec(-1.0f64..1.0, 81),
            rhs in proptest::collection::vec(-10.0f64..10.0, 9),
            shift in proptest::collection::vec(prop_oneof![Just(-1.0), Just(1.0)], 9),
        ) {
            let a = DMatrix::from_fn(n, n, |i, j| {
                entries[i * 9 + j] + if i == j { shift[i] * 2.0 * n as f64 } else { 0.0 }
            });
            let b = DVector::from_fn(n, |i, _| rhs[i]);
            let mut lu = Lu::new(n);
            lu.factor_from(&a).unwrap();
            let mut x = b.clone();
            lu.solve_in_place(&mut x).unwrap();
            let expected = a.clone().try_inverse().unwrap() * &b;
            let scale = 1.0 + b.amax();
            prop_assert!((&x - &expected).amax() <= 1e-12 * scale);
            prop_assert!((&a * &x - &b).amax() <= 1e-12 * scale);
        }

        /// A random matrix with no diagonal help (pivots chosen by size alone) is solved to a
        /// residual at round-off relative to `|A| |x|`, the backward stability of partial
        /// pivoting.
        #[test]
        fn residual_is_backward_stable(
            n in 1usize..9,
            entries in proptest::collection::vec(-1.0f64..1.0, 81),
            rhs in proptest::collection::vec(-1.0f64..1.0, 9),
        ) {
            let a = DMatrix::from_fn(n, n, |i, j| entries[i * 9 + j]);
            let b = DVector::from_fn(n, |i, _| rhs[i]);
            let mut lu = Lu::new(n);
            if lu.factor_from(&a).is_ok() {
                let mut x = b.clone();
                lu.solve_in_place(&mut x).unwrap();
                let r = (&a * &x - &b).amax();
                let bound = 1e-13 * n as f64 * (a.abs() * x.abs()).amax().max(b.amax());
                prop_assert!(r <= bound, "residual {r:e} above {bound:e}");
            }
        }
    }
}
