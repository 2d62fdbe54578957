//! Tests of the dense LU (`lu.rs`): known factors and solutions, pivoting, both substitution
//! arithmetics against nalgebra's LU and a known solution (backward and forward error of a
//! few `n eps`), the per-column singularity threshold, and every error as a value.
use super::*;
use proptest::prelude::*;

fn both(n: usize) -> [DenseLu; 2] {
    [
        DenseLu::new(n),
        DenseLu::with_substitution(n, Substitution::Reciprocal),
    ]
}

/// Hand-computed factors of a 2x2 matrix: P swaps the rows, L = [1 0; 1/3 1],
/// U = [3 4; 0 2 - 4/3].
#[test]
fn known_factors_2x2() {
    let mut lu = DenseLu::new(2);
    lu.factor_from(&DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 3.0, 4.0]))
        .unwrap();
    assert_eq!(lu.ipiv, [1, 1]);
    let a = &lu.a;
    assert_eq!((a[(0, 0)], a[(0, 1)]), (3.0, 4.0));
    assert!((a[(1, 0)] - 1.0 / 3.0).abs() < 1e-16);
    assert!((a[(1, 1)] - (2.0 - 4.0 / 3.0)).abs() < 1e-15);
}

/// A permutation matrix (every pivot needs a swap) is solved exactly by both arithmetics,
/// and refactoring the buffers with a new matrix leaves nothing of the previous one.
#[test]
fn permutation_is_solved_exactly_and_buffers_are_reused() {
    for mut lu in both(3) {
        let m = DMatrix::from_row_slice(3, 3, &[0.0, 0.0, 2.0, 0.0, 3.0, 0.0, 5.0, 0.0, 0.0]);
        lu.factor_from(&m).unwrap();
        let mut b = DVector::from_vec(vec![2.0, 6.0, 15.0]);
        lu.solve_in_place(&mut b).unwrap();
        assert_eq!(b.as_slice(), &[3.0, 2.0, 1.0]);
        lu.factor_from(&DMatrix::from_diagonal_element(3, 3, 2.0))
            .unwrap();
        let mut b = [2.0, 4.0, 8.0];
        lu.solve(&mut b).unwrap();
        assert_eq!(b, [1.0, 2.0, 4.0]);
    }
}

/// A zero row, a rank-one matrix whose elimination leaves only rounding noise, the zero
/// matrix and a NaN are errors; a failed factorisation cannot be used to solve; buffers of
/// the wrong length are errors, never panics.
#[test]
fn errors_are_values() {
    let mut lu = DenseLu::new(2);
    let zero_row = DMatrix::from_row_slice(2, 2, &[0.0, 0.0, 0.0, 1.0]);
    assert_eq!(
        lu.factor_from(&zero_row),
        Err(LuError::Singular {
            column: 0,
            pivot: 0.0,
            threshold: 0.0
        })
    );
    assert_eq!(lu.solve(&mut [1.0, 1.0]), Err(LuError::NotFactored));
    let rank_one = DMatrix::from_row_slice(2, 2, &[1.0, 3.0, 1.0 / 3.0, 1.0]);
    assert!(matches!(
        lu.factor_from(&rank_one),
        Err(LuError::Singular { column: 1, .. })
    ));
    let (u, v) = ([0.1, 0.7, 0.3], [0.3, 0.9, 0.11]);
    let mut lu3 = DenseLu::new(3);
    let r1 = DMatrix::from_fn(3, 3, |i, j| u[i] * v[j]);
    assert!(matches!(
        lu3.factor_from(&r1),
        Err(LuError::Singular { .. })
    ));
    let mut z = DenseLu::new(4);
    assert!(matches!(
        z.factor(),
        Err(LuError::Singular { column: 0, .. })
    ));
    let nan = DMatrix::from_row_slice(2, 2, &[1.0, f64::NAN, 0.0, 1.0]);
    assert_eq!(lu.factor_from(&nan), Err(LuError::NonFinite));
    assert!(matches!(
        lu.factor_from(&DMatrix::zeros(3, 3)),
        Err(LuError::Dimension { n: 2, len: 9 })
    ));
    lu.factor_from(&DMatrix::from_diagonal_element(2, 2, 2.0))
        .unwrap();
    assert_eq!(
        lu.solve(&mut [1.0; 3]),
        Err(LuError::Dimension { n: 2, len: 3 })
    );
    let mut b = [1.0, 4.0];
    lu.solve(&mut b).unwrap();
    assert_eq!(b, [0.5, 2.0]);
}

/// A saddle-point matrix with a heavy mass block, `[1e12 1; 1 0]`, is regular and solved
/// (its second pivot, `-1e-12`, is small against the matrix but not against its column).
#[test]
fn unbalanced_saddle_point_is_regular() {
    let mut lu = DenseLu::new(2);
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
    /// With division, the factors and the solution are bit-identical to nalgebra's LU on a
    /// random regular matrix (every element sees the same operations in the same order);
    /// with reciprocals the solution agrees to round-off.
    #[test]
    fn divide_is_nalgebra_bit_for_bit(
        n in 1usize..13,
        entries in proptest::collection::vec(-1.0f64..1.0, 144),
        rhs in proptest::collection::vec(-10.0f64..10.0, 12),
    ) {
        let a = DMatrix::from_fn(n, n, |i, j| entries[i * 12 + j] + if i == j { 0.5 } else { 0.0 });
        let b = DVector::from_fn(n, |i, _| rhs[i]);
        let mut lu = DenseLu::new(n);
        prop_assume!(lu.factor_from(&a).is_ok());
        let mut x = b.clone();
        lu.solve_in_place(&mut x).unwrap();
        let theirs = a.clone().lu();
        let Some(y) = theirs.solve(&b) else { return Ok(()) };
        for k in 0..n {
            prop_assert_eq!(x[k].to_bits(), y[k].to_bits());
        }
        let mut r = DenseLu::with_substitution(n, Substitution::Reciprocal);
        r.factor_from(&a).unwrap();
        let mut z = b.clone();
        r.solve_in_place(&mut z).unwrap();
        let bound = 1e-13 * n as f64 * (a.abs() * z.abs()).amax().max(b.amax());
        prop_assert!((&a * &z - &b).amax() <= bound);
    }

    /// For a random well-conditioned `A` (a dominant diagonal of random sign, so pivoting
    /// still happens off the diagonal) both arithmetics solve `A x = b` against a known `x`
    /// with a forward error of a few `n eps`, and a random matrix with no diagonal help with
    /// a residual at round-off relative to `|A| |x|` (partial pivoting's backward stability).
    #[test]
    fn solutions_are_accurate(
        n in 1usize..41,
        entries in proptest::collection::vec(-1.0f64..1.0, 1600),
        sol in proptest::collection::vec(-10.0f64..10.0, 40),
        shift in proptest::collection::vec(prop_oneof![Just(-1.0), Just(1.0)], 40),
    ) {
        let dominant = DMatrix::from_fn(n, n, |i, j| {
            entries[i * 40 + j] / n as f64 + if i == j { 2.0 * shift[i] } else { 0.0 }
        });
        let plain = DMatrix::from_fn(n, n, |i, j| entries[i * 40 + j]);
        let x = DVector::from_fn(n, |i, _| sol[i]);
        for mut lu in both(n) {
            lu.factor_from(&dominant).unwrap();
            let mut y = &dominant * &x;
            lu.solve_in_place(&mut y).unwrap();
            prop_assert!((&y - &x).amax() <= 12.0 * n as f64 * f64::EPSILON * x.amax());
            if lu.factor_from(&plain).is_ok() {
                let b = &plain * &x;
                let mut y = b.clone();
                lu.solve_in_place(&mut y).unwrap();
                let r = (&plain * &y - &b).amax();
                let bound = 1e-13 * n as f64 * (plain.abs() * y.abs()).amax().max(b.amax());
                prop_assert!(r <= bound, "residual {r:e} above {bound:e}");
            }
        }
    }
}
