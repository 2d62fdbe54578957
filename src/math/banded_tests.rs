//! Tests of the banded LU with a border (`banded.rs`): against the dense LU on random
//! banded and bordered matrices (bit-identical without a border, a backward error of a few
//! `n eps` with one), the same typed errors on singular, non-finite and unfactored input,
//! and the pattern's refusal of entries outside it.
use super::*;
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

/// A deterministic generator of numbers in [-1, 1] (64-bit LCG).
fn lcg(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
    move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

/// A random matrix of `band`'s pattern, every entry of the pattern nonzero, with a
/// diagonal of size `diag` (small: pivoting swaps rows).
fn random(band: Band, seed: u64, diag: f64) -> DMatrix<f64> {
    let mut next = lcg(seed);
    DMatrix::from_fn(band.n, band.n, |i, j| match band.locate(i, j) {
        Some(_) => next() + if i == j { diag } else { 0.0 },
        None => 0.0,
    })
}

fn filled(band: Band, a: &DMatrix<f64>) -> BandedLu {
    let mut lu = BandedLu::new(band);
    for j in 0..band.n {
        for i in 0..band.n {
            if a[(i, j)] != 0.0 {
                lu.add(i, j, a[(i, j)]).unwrap();
            }
        }
    }
    lu
}

/// The backward error `|A x - b|_inf / (|A|_inf |x|_inf + |b|_inf)`.
fn backward_error(a: &DMatrix<f64>, x: &[f64], b: &DVector<f64>) -> f64 {
    let x = DVector::from_column_slice(x);
    let r = a * &x - b;
    let norm_a = (0..a.nrows())
        .map(|i| a.row(i).iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    r.amax() / (norm_a * x.amax() + b.amax())
}

fn border_of(kind: u8, k: usize) -> Border {
    match kind % 3 {
        0 => Border::None,
        1 => Border::First(k),
        _ => Border::Last(k),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Without a border the banded LU makes the dense LU's operations: the same solution,
    /// bit for bit, also where pivoting swaps rows (a small random diagonal); with one, a
    /// backward error within 8 n eps, as the dense one's, when the band block is well
    /// conditioned (the method's precondition, module docs: here diagonally dominant).
    #[test]
    fn solves_equal_the_dense_lu(
        n1 in 1usize..40, kl in 0usize..6, ku in 0usize..6, kind in 0u8..3, k in 1usize..4,
        seed in any::<u64>(), diag in 0.0f64..3.0,
    ) {
        let border = border_of(kind, k);
        let band = Band { n: n1 + border.width(), kl, ku, border };
        let diag = if border == Border::None { diag } else { (kl + ku + 1) as f64 + diag };
        let a = random(band, seed, diag);
        let mut dense = DenseLu::new(band.n);
        let mut lu = filled(band, &a);
        let (rd, rb) = (dense.factor_from(&a), lu.factor());
        if border == Border::None {
            prop_assert_eq!(rd, rb);
        }
        prop_assume!(rd.is_ok() && rb.is_ok());
        let mut next = lcg(seed ^ 0x55);
        let b = DVector::from_fn(band.n, |_, _| next());
        let (mut xd, mut xb) = (b.clone(), b.clone());
        dense.solve_in_place(&mut xd).unwrap();
        lu.solve(xb.as_mut_slice()).unwrap();
        let (ed, eb) = (backward_error(&a, xd.as_slice(), &b), backward_error(&a, xb.as_slice(), &b));
        let bound = 8.0 * band.n as f64 * f64::EPSILON;
        prop_assert!(eb <= bound, "banded backward error {eb:e} > {bound:e} (dense {ed:e})");
        if border == Border::None {
            prop_assert_eq!(xd, xb);
        }
    }
}

/// A matrix whose band block has two equal columns is singular for both factorisations,
/// with the same typed error; without a border at the same column, pivot and threshold.
#[test]
fn singular_band_is_the_same_error() {
    for border in [Border::None, Border::First(1), Border::Last(2)] {
        let band = Band {
            n: 12 + border.width(),
            kl: 2,
            ku: 1,
            border,
        };
        let first = match border {
            Border::First(k) => k,
            _ => 0,
        };
        let mut a = random(band, 7, 2.0);
        // Rows 5 and 6 of the band block: row 6 := row 5 where the pattern allows,
        // with row 5 kept inside row 6's band (the band block is then singular).
        let (r5, r6) = (first + 5, first + 6);
        for j in 0..band.n {
            a[(r5, j)] = 0.0;
            a[(r6, j)] = 0.0;
        }
        for j in [first + 5, first + 6] {
            a[(r5, j)] = 1.0 + j as f64;
            a[(r6, j)] = 1.0 + j as f64;
        }
        let mut dense = DenseLu::new(band.n);
        let rd = dense.factor_from(&a);
        let rb = filled(band, &a).factor();
        assert!(
            matches!(rd, Err(LuError::Singular { .. })),
            "{border:?}: {rd:?}"
        );
        assert!(
            matches!(rb, Err(LuError::Singular { .. })),
            "{border:?}: {rb:?}"
        );
        if border == Border::None {
            assert_eq!(rd, rb);
        }
    }
}

/// A singular Schur complement (a border column equal to a combination of the band's
/// columns) is a `Singular` error naming a border column, as the dense LU's error.
#[test]
fn singular_border_is_the_same_error() {
    for border in [Border::First(1), Border::Last(1)] {
        let band = Band {
            n: 10,
            kl: 1,
            ku: 1,
            border,
        };
        let mut a = random(band, 3, 3.0);
        let (bc, b0) = match border {
            Border::First(_) => (0, 1),
            _ => (9, 0),
        };
        // The border column and row := the sum of two band columns and rows: rank 9.
        for i in 0..10 {
            a[(i, bc)] = 0.0;
        }
        for i in 0..10 {
            if i != bc {
                a[(i, bc)] = a[(i, b0)] + a[(i, b0 + 1)];
            }
        }
        for j in 0..10 {
            a[(bc, j)] = a[(b0, j)] + a[(b0 + 1, j)];
        }
        a[(bc, bc)] = a[(b0, bc)] + a[(b0 + 1, bc)];
        let rd = DenseLu::new(10).factor_from(&a);
        let rb = filled(band, &a).factor();
        assert!(matches!(rd, Err(LuError::Singular { .. })), "{rd:?}");
        assert!(
            matches!(rb, Err(LuError::Singular { column, .. }) if column == bc),
            "{border:?}: {rb:?}"
        );
    }
}

/// A zero matrix, a NaN and a solve before a factorisation are the dense LU's errors.
#[test]
fn errors_are_the_dense_ones() {
    let band = Band {
        n: 6,
        kl: 1,
        ku: 2,
        border: Border::Last(1),
    };
    let mut lu = BandedLu::new(band);
    assert_eq!(lu.solve(&mut [0.0; 6]), Err(LuError::NotFactored));
    assert!(matches!(
        lu.factor(),
        Err(LuError::Singular { column: 0, .. })
    ));
    assert!(matches!(
        DenseLu::new(6).factor(),
        Err(LuError::Singular { column: 0, .. })
    ));
    let a = random(band, 1, 3.0);
    let mut lu = filled(band, &a);
    lu.add(5, 5, f64::NAN).unwrap();
    assert_eq!(lu.factor(), Err(LuError::NonFinite));
    let mut lu = filled(band, &a);
    lu.factor().unwrap();
    assert_eq!(
        lu.solve(&mut [0.0; 5]),
        Err(LuError::Dimension { n: 6, len: 5 })
    );
    lu.add(0, 0, 1.0).unwrap();
    assert_eq!(lu.solve(&mut [0.0; 6]), Err(LuError::NotFactored));
}

/// Entries outside the band are refused; inside they are read back where they were put,
/// in every block, and `clear` zeroes them all.
#[test]
fn pattern_is_kept() {
    let band = Band {
        n: 8,
        kl: 1,
        ku: 2,
        border: Border::First(2),
    };
    let mut lu = BandedLu::new(band);
    let a = random(band, 11, 1.0);
    for i in 0..8 {
        for j in 0..8 {
            let inside = lu.add(i, j, a[(i, j)]).is_ok();
            // Band block rows/columns 2..8: i - 2 <= j - 2 + 1 and j - 2 <= i - 2 + 2.
            let want = i < 2 || j < 2 || (i <= j + 1 && j <= i + 2);
            assert_eq!(inside, want, "({i}, {j})");
        }
    }
    for i in 0..8 {
        for j in 0..8 {
            assert_eq!(lu.get(i, j), a[(i, j)], "({i}, {j})");
        }
    }
    assert!(lu.add(8, 0, 1.0).is_err());
    lu.clear();
    assert!((0..8).all(|i| (0..8).all(|j| lu.get(i, j) == 0.0)));
}
