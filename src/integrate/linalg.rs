//! Dense LU factorization with partial (row) pivoting, in place on caller-provided buffers,
//! for the Newton solves of the implicit integrators.
//!
//! Algorithm: right-looking Doolittle elimination `P A = L U` (Golub & Van Loan, *Matrix
//! Computations*, 4th ed., Alg. 3.4.1, "Gaussian elimination with partial pivoting"), row-major
//! storage, `L` unit lower triangular stored below the diagonal, `U` on and above it, and the
//! row interchanges recorded LAPACK-style (`piv[k]` is the row swapped with row `k` at step
//! `k`). Solving applies the interchanges, then forward and back substitution (Alg. 3.1.3-4)
//! on a column-major copy of the factors that `DenseLu::factor` keeps, with the reciprocals of
//! the pivots (the back substitution multiplies by `1 / u_jj` instead of dividing: one rounding
//! more per component, within the same backward-error bound's order).
//! Cost: `n^3/3` multiply-adds to factor, `n^2` to solve; nothing is allocated after
//! `DenseLu::new` (`lu_factor` allocates nothing at all).
//!
//! Backward stability: the computed factors satisfy `P (A + E) = L U` with
//! `|E| <= 2 n eps |L| |U|`, and the growth factor of partial pivoting is small in practice
//! (at most `2^(n-1)` in theory), so the solution of a well-conditioned system has a relative
//! error of a few `n eps cond(A)`.
//!
//! Failure, as a value rather than a panic: buffers of the wrong length, a non-finite entry,
//! or a pivot with `|u_kk| <= n eps max_ij |a_ij|` (numerically singular: below the size of the
//! rounding errors of the elimination itself, so the factors carry no information in that
//! direction) give an `LuError`. A matrix that passes this test may still be badly conditioned;
//! the check is a guard against garbage, not a condition estimate.

/// Why a factorization or solve failed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LuError {
    /// A buffer's length does not match the order `n`.
    Dimension { n: usize, len: usize },
    /// The matrix has a NaN or infinite entry.
    NonFinite,
    /// The pivot of column `col` is at most `threshold` in magnitude.
    Singular {
        col: usize,
        pivot: f64,
        threshold: f64,
    },
    /// `solve` was called before a successful `factor`.
    NotFactored,
}

impl std::fmt::Display for LuError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LuError::Dimension { n, len } => {
                write!(f, "buffer of length {len} does not fit order {n}")
            }
            LuError::NonFinite => write!(f, "matrix has a non-finite entry"),
            LuError::Singular {
                col,
                pivot,
                threshold,
            } => write!(
                f,
                "numerically singular: pivot {pivot:.3e} of column {col} <= {threshold:.3e}"
            ),
            LuError::NotFactored => write!(f, "solve before factor"),
        }
    }
}

/// Factors the row-major `n x n` matrix `a` in place into `P A = L U`, writing the
/// interchanges to `piv[..n]`.
pub fn lu_factor(a: &mut [f64], n: usize, piv: &mut [usize]) -> Result<(), LuError> {
    if a.len() != n * n {
        return Err(LuError::Dimension { n, len: a.len() });
    }
    if piv.len() < n {
        return Err(LuError::Dimension { n, len: piv.len() });
    }
    let mut amax = 0.0_f64;
    for v in a.iter() {
        if !v.is_finite() {
            return Err(LuError::NonFinite);
        }
        amax = amax.max(v.abs());
    }
    let threshold = n as f64 * f64::EPSILON * amax;
    for k in 0..n {
        // Pivot: the largest magnitude in column k on or below the diagonal.
        let mut p = k;
        let mut pmax = a[k * n + k].abs();
        for i in k + 1..n {
            let v = a[i * n + k].abs();
            if v > pmax {
                pmax = v;
                p = i;
            }
        }
        piv[k] = p;
        // `!(pmax > threshold)` also catches the all-zero matrix (threshold 0).
        if pmax <= threshold || amax == 0.0 {
            return Err(LuError::Singular {
                col: k,
                pivot: pmax,
                threshold,
            });
        }
        if p != k {
            for j in 0..n {
                a.swap(k * n + j, p * n + j);
            }
        }
        let inv = 1.0 / a[k * n + k];
        for i in k + 1..n {
            let l = a[i * n + k] * inv;
            a[i * n + k] = l;
            if l != 0.0 {
                let (top, bottom) = a.split_at_mut(i * n);
                let urow = &top[k * n + k + 1..k * n + n];
                let row = &mut bottom[k + 1..n];
                for (r, u) in row.iter_mut().zip(urow) {
                    *r -= l * u;
                }
            }
        }
    }
    Ok(())
}

/// Solves `A x = b` in place (`b` becomes `x`) with the factors from `lu_factor` stored
/// column by column (`cols[j * n + i]` is entry `(i, j)` of `L \ U`) and the reciprocals
/// `1 / u_jj` of the pivots (`DenseLu::factor` keeps both).
fn lu_solve_cols(
    cols: &[f64],
    inv_diag: &[f64],
    n: usize,
    piv: &[usize],
    b: &mut [f64],
) -> Result<(), LuError> {
    if cols.len() != n * n || inv_diag.len() != n {
        return Err(LuError::Dimension { n, len: cols.len() });
    }
    if piv.len() < n || piv[..n].iter().any(|&p| p >= n) {
        return Err(LuError::Dimension { n, len: piv.len() });
    }
    if b.len() != n {
        return Err(LuError::Dimension { n, len: b.len() });
    }
    for (k, &p) in piv[..n].iter().enumerate() {
        b.swap(k, p);
    }
    // Column-oriented substitutions (Golub & Van Loan, Alg. 3.1.3-4, "saxpy" forms): once a
    // component is final it is eliminated from all the rows it enters, so the updates of
    // different rows are independent. (The row-oriented "dot product" forms chain every
    // addition of a row's sum through one accumulator; at the n = 6..42 of the Newton solves
    // that latency chain, not the n^2 arithmetic, was the cost: 3x slower, measured.) The
    // factors are read column by column from contiguous memory, so the updates vectorize
    // (heavy_top, gauss6, n = 39: 4656 -> 3402 ns/step, quat/body).
    // L y = P b (unit diagonal).
    for j in 0..n {
        let yj = b[j];
        let col = &cols[j * n + j + 1..(j + 1) * n];
        for (bi, l) in b[j + 1..].iter_mut().zip(col) {
            *bi -= l * yj;
        }
    }
    // U x = y, multiplying by the stored reciprocals of the pivots: a division's latency
    // (~4x a multiplication's) sat on the chain from one component to the next.
    for j in (0..n).rev() {
        b[j] *= inv_diag[j];
        let xj = b[j];
        let col = &cols[j * n..j * n + j];
        for (bi, u) in b[..j].iter_mut().zip(col) {
            *bi -= u * xj;
        }
    }
    Ok(())
}

/// An `n x n` LU workspace: fill `matrix_mut`, `factor` once, `solve` any number of times.
#[derive(Debug, Clone)]
pub struct DenseLu {
    n: usize,
    a: Vec<f64>,
    /// The factors column by column, for the solves.
    cols: Vec<f64>,
    /// `1 / u_jj`.
    inv_diag: Vec<f64>,
    piv: Vec<usize>,
    factored: bool,
}

impl DenseLu {
    /// Allocates the workspace (the only allocation).
    pub fn new(n: usize) -> Self {
        DenseLu {
            n,
            a: vec![0.0; n * n],
            cols: vec![0.0; n * n],
            inv_diag: vec![0.0; n],
            piv: vec![0; n],
            factored: false,
        }
    }

    /// The order.
    pub fn n(&self) -> usize {
        self.n
    }

    /// The row-major matrix to fill; invalidates a previous factorization.
    pub fn matrix_mut(&mut self) -> &mut [f64] {
        self.factored = false;
        &mut self.a
    }

    /// Factors the matrix in place.
    pub fn factor(&mut self) -> Result<(), LuError> {
        self.factored = false;
        lu_factor(&mut self.a, self.n, &mut self.piv)?;
        let n = self.n;
        for (j, col) in self.cols.chunks_exact_mut(n).enumerate() {
            for (i, c) in col.iter_mut().enumerate() {
                *c = self.a[i * n + j];
            }
            self.inv_diag[j] = 1.0 / self.a[j * n + j];
        }
        self.factored = true;
        Ok(())
    }

    /// Whether a factorization is available.
    pub fn is_factored(&self) -> bool {
        self.factored
    }

    /// Solves `A x = b` in place.
    pub fn solve(&self, b: &mut [f64]) -> Result<(), LuError> {
        if !self.factored {
            return Err(LuError::NotFactored);
        }
        lu_solve_cols(&self.cols, &self.inv_diag, self.n, &self.piv, b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic uniform numbers in [-1, 1) (64-bit LCG, Knuth's MMIX constants).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        }
    }

    fn matvec(a: &[f64], n: usize, x: &[f64], out: &mut [f64]) {
        for i in 0..n {
            out[i] = (0..n).map(|j| a[i * n + j] * x[j]).sum();
        }
    }

    /// A 3x3 system with a zero leading entry (needs a row interchange) and an integer
    /// solution is solved to round-off.
    #[test]
    fn known_solution_with_pivoting() {
        // x = (1, -2, 3).
        let a0 = [0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0, -1.0];
        let x = [1.0, -2.0, 3.0];
        let mut b = [0.0; 3];
        matvec(&a0, 3, &x, &mut b);
        let mut lu = DenseLu::new(3);
        lu.matrix_mut().copy_from_slice(&a0);
        lu.factor().unwrap();
        lu.solve(&mut b).unwrap();
        for i in 0..3 {
            // cond(A) ~ 10: a few eps relative.
            assert!((b[i] - x[i]).abs() < 1e-14, "{b:?}");
        }
    }

    /// Hand-computed factors of a 2x2 matrix: P swaps the rows, L = [1 0; 1/3 1],
    /// U = [3 4; 0 2 - 4/3].
    #[test]
    fn known_factors_2x2() {
        let mut a = [1.0, 2.0, 3.0, 4.0];
        let mut piv = [0; 2];
        lu_factor(&mut a, 2, &mut piv).unwrap();
        assert_eq!(piv, [1, 1]);
        assert_eq!(a[0], 3.0);
        assert_eq!(a[1], 4.0);
        assert!((a[2] - 1.0 / 3.0).abs() < 1e-16);
        assert!((a[3] - (2.0 - 4.0 / 3.0)).abs() < 1e-15);
    }

    /// Random well-conditioned (diagonally dominant) systems of order 1..=40 are solved with a
    /// normwise backward error of a few n eps, and a forward error of a few n eps cond (cond
    /// is below 3 for these matrices), against a known solution; one factorization serves
    /// several right-hand sides.
    #[test]
    fn random_well_conditioned_systems() {
        let mut rng = Lcg(12345);
        let mut worst_fwd = 0.0_f64;
        for n in 1..=40 {
            let mut lu = DenseLu::new(n);
            let mut a0 = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..n {
                    a0[i * n + j] = rng.next() / n as f64;
                }
                a0[i * n + i] += 2.0 * rng.next().signum();
            }
            lu.matrix_mut().copy_from_slice(&a0);
            lu.factor().unwrap();
            for _rhs in 0..3 {
                let x: Vec<f64> = (0..n).map(|_| rng.next() * 10.0).collect();
                let mut b = vec![0.0; n];
                matvec(&a0, n, &x, &mut b);
                let b0 = b.clone();
                lu.solve(&mut b).unwrap();
                // Backward error |b - A x^| / (|A| |x^| + |b|), infinity norms.
                let mut r = vec![0.0; n];
                matvec(&a0, n, &b, &mut r);
                let res = r
                    .iter()
                    .zip(&b0)
                    .fold(0.0_f64, |m, (u, v)| m.max((u - v).abs()));
                let anorm = (0..n)
                    .map(|i| (0..n).map(|j| a0[i * n + j].abs()).sum::<f64>())
                    .fold(0.0_f64, f64::max);
                let xnorm = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                let bnorm = b0.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                let backward = res / (anorm * xnorm + bnorm);
                assert!(
                    backward < 4.0 * n as f64 * f64::EPSILON,
                    "n={n} {backward:e}"
                );
                let xmax = x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                let fwd = b
                    .iter()
                    .zip(&x)
                    .fold(0.0_f64, |m, (u, v)| m.max((u - v).abs()))
                    / xmax;
                worst_fwd = worst_fwd.max(fwd / (n as f64 * f64::EPSILON));
                assert!(fwd < 12.0 * n as f64 * f64::EPSILON, "n={n} {fwd:e}");
            }
        }
        eprintln!("worst forward error / (n eps) = {worst_fwd:.3}");
    }

    /// An exactly singular matrix, a rank-one matrix whose elimination leaves only rounding
    /// noise, and the zero matrix are reported as singular, not factored.
    #[test]
    fn singular_matrices_are_errors() {
        let mut a = [1.0, 2.0, 2.0, 4.0];
        let mut piv = [0; 2];
        assert!(matches!(
            lu_factor(&mut a, 2, &mut piv),
            Err(LuError::Singular { col: 1, .. })
        ));
        // u v^T with entries that do not cancel exactly in binary.
        let u = [0.1, 0.7, 0.3];
        let v = [0.3, 0.9, 0.11];
        let mut r1 = [0.0; 9];
        for i in 0..3 {
            for j in 0..3 {
                r1[i * 3 + j] = u[i] * v[j];
            }
        }
        let mut piv3 = [0; 3];
        assert!(matches!(
            lu_factor(&mut r1, 3, &mut piv3),
            Err(LuError::Singular { .. })
        ));
        let mut z = DenseLu::new(4);
        assert!(matches!(z.factor(), Err(LuError::Singular { col: 0, .. })));
        let mut b = [1.0; 4];
        assert_eq!(z.solve(&mut b), Err(LuError::NotFactored));
    }

    /// Non-finite entries and mismatched buffers are errors, never panics.
    #[test]
    fn bad_input_is_an_error() {
        let mut a = [1.0, f64::NAN, 0.0, 1.0];
        let mut piv = [0; 2];
        assert_eq!(lu_factor(&mut a, 2, &mut piv), Err(LuError::NonFinite));
        let mut a3 = [1.0; 3];
        assert!(matches!(
            lu_factor(&mut a3, 2, &mut piv),
            Err(LuError::Dimension { .. })
        ));
        let mut lu = DenseLu::new(2);
        lu.matrix_mut().copy_from_slice(&[2.0, 0.0, 0.0, 2.0]);
        lu.factor().unwrap();
        let mut b = [1.0; 3];
        assert!(matches!(lu.solve(&mut b), Err(LuError::Dimension { .. })));
        let mut b2 = [1.0, 4.0];
        lu.solve(&mut b2).unwrap();
        assert_eq!(b2, [0.5, 2.0]);
    }
}
