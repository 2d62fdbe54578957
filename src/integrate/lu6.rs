//! The 6 x 6 Newton solve of `simo_wong`: nalgebra's partial-pivoting LU factors (`P A = L U`,
//! Golub & Van Loan, *Matrix Computations*, 4th ed., Alg. 3.4.1) kept packed, and forward and
//! back substitution (Alg. 3.1.3-4) written here with exactly the operations of
//! `nalgebra::linalg::LU::solve` in the same order (`x_r <- x_r + (-c) u_ri`, one division by
//! the pivot per row), so the solution is bit-identical to nalgebra's.
//!
//! Why it exists: the optimiser stopped inlining nalgebra's generic triangular solve into
//! `LU::solve` after an unrelated change in the run loop, and `simo_wong` (about 2
//! solves a step) slowed down by 4 % with every instruction unchanged. Owning the
//! substitution fixes the code the step runs, measured in `benches/step.rs`.
//!
//! Fails (`None`) exactly where nalgebra's does: on an exactly zero pivot of `U`. A nearly
//! singular matrix gives a large, inaccurate solution; the Newton iteration's own stop test
//! judges it.
//!
//! # Example
//!
//! ```
//! use mbdbench::integrate::lu6::Lu6;
//! use nalgebra::{Matrix6, Vector6};
//!
//! let a = Matrix6::from_fn(|i, j| if i == j { 4.0 } else { 1.0 / (1.0 + (i + 2 * j) as f64) });
//! let b = Vector6::new(1.0, -2.0, 0.5, 3.0, 0.0, 1.5);
//! let x = Lu6::new(a).solve(&b).unwrap();
//! assert_eq!(x, a.lu().solve(&b).unwrap()); // bit for bit
//! assert!((a * x - b).amax() < 1e-14);
//! ```
use nalgebra::{Matrix6, Vector6, linalg::PermutationSequence};

type Perm = PermutationSequence<nalgebra::U6>;

/// LU factors of a 6 x 6 matrix: `L` (unit diagonal, not stored) below the diagonal of
/// `packed`, `U` on and above it, and the row interchanges.
#[derive(Debug, Clone)]
pub struct Lu6 {
    packed: Matrix6<f64>,
    p: Perm,
}

impl Lu6 {
    /// Factors `a` with nalgebra's partial-pivoting LU.
    pub fn new(a: Matrix6<f64>) -> Lu6 {
        let (p, l, u) = a.lu().unpack();
        let packed = Matrix6::from_fn(|i, j| if i > j { l[(i, j)] } else { u[(i, j)] });
        Lu6 { packed, p }
    }

    /// Solves `A x = b`; None when a pivot of `U` is exactly zero.
    #[inline]
    pub fn solve(&self, b: &Vector6<f64>) -> Option<Vector6<f64>> {
        let m = &self.packed;
        let mut x = *b;
        self.p.permute_rows(&mut x);
        // Forward substitution with the unit lower factor (nalgebra divides by the unit
        // diagonal, which is exact, so it is left out).
        for i in 0..5 {
            let c = x[i];
            for r in i + 1..6 {
                x[r] += -c * m[(r, i)];
            }
        }
        for i in (0..6).rev() {
            let d = m[(i, i)];
            if d == 0.0 {
                return None;
            }
            let c = x[i] / d;
            x[i] = c;
            for r in 0..i {
                x[r] += -c * m[(r, i)];
            }
        }
        Some(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The solution is bit-identical to nalgebra's `LU::solve` on any matrix and right-hand
        /// side, singular ones included (both give None, or the same numbers).
        #[test]
        fn bit_identical_to_nalgebra(
            a in proptest::collection::vec(-10.0f64..10.0, 36),
            b in proptest::collection::vec(-10.0f64..10.0, 6),
            zero_col in 0usize..12,
        ) {
            let mut a = Matrix6::from_column_slice(&a);
            if zero_col < 6 {
                a.column_mut(zero_col).fill(0.0);
            }
            let b = Vector6::from_column_slice(&b);
            let ours = Lu6::new(a).solve(&b);
            let theirs = a.lu().solve(&b);
            match (ours, theirs) {
                (Some(x), Some(y)) => {
                    for k in 0..6 {
                        prop_assert_eq!(x[k].to_bits(), y[k].to_bits());
                    }
                }
                (None, None) => {}
                (x, y) => prop_assert!(false, "ours {:?}, nalgebra {:?}", x, y),
            }
        }
    }

    /// A singular matrix (a zero column) has no solution.
    #[test]
    fn zero_pivot_is_none() {
        let mut a = Matrix6::<f64>::identity();
        a[(3, 3)] = 0.0;
        assert!(Lu6::new(a).solve(&Vector6::repeat(1.0)).is_none());
    }
}
