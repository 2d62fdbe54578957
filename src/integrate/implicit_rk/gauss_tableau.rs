//! The Butcher tableaux of the two Gauss methods (Butcher 1964; Hairer, Norsett & Wanner,
//! *Solving ODEs I*, sec. II.7): `implicit_midpoint` (`s = 1`, order 2) and `gauss6`
//! (`s = 3`, `c = 1/2 -+ sqrt(15)/10, 1/2`, order 6), each with the weights `d = b^T A^{-1}`
//! of the update `x_{n+1} = retract(x, sum_i d_i Z_i)` (HW II, sec. IV.8).
//!
//! Invariants: `A` of a Gauss method is invertible (its eigenvalues are the reciprocals of the
//! poles of the Pade stability function, all in `Re > 0`), so `A^T d = b` has a solution, found
//! by `math::lu::DenseLu` once per method; the test `tableau_identities` checks the row sums,
//! `sum b = 1`, and `d` against the collocation polynomial's Lagrange weights at 1.
//!
//! Where it fails: nowhere for these two tableaux (a singular `A` would trip a debug
//! assertion).
use super::GaussScheme;
use crate::math::lu::{DenseLu, LinearSolve, Substitution};

pub(super) const MAX_STAGES: usize = 3;

/// Butcher tableau of a Gauss method, with `d = b^T A^{-1}`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Tableau {
    pub(super) s: usize,
    pub(super) a: [[f64; MAX_STAGES]; MAX_STAGES],
    pub(super) b: [f64; MAX_STAGES],
    pub(super) c: [f64; MAX_STAGES],
    pub(super) d: [f64; MAX_STAGES],
}

impl Tableau {
    pub(super) fn new(scheme: GaussScheme) -> Self {
        let mut t = match scheme {
            GaussScheme::ImplicitMidpoint => Tableau {
                s: 1,
                a: [[0.5, 0.0, 0.0], [0.0; 3], [0.0; 3]],
                b: [1.0, 0.0, 0.0],
                c: [0.5, 0.0, 0.0],
                d: [0.0; 3],
            },
            GaussScheme::Gauss6 => {
                let r = 15.0_f64.sqrt();
                Tableau {
                    s: 3,
                    a: [
                        [5.0 / 36.0, 2.0 / 9.0 - r / 15.0, 5.0 / 36.0 - r / 30.0],
                        [5.0 / 36.0 + r / 24.0, 2.0 / 9.0, 5.0 / 36.0 - r / 24.0],
                        [5.0 / 36.0 + r / 30.0, 2.0 / 9.0 + r / 15.0, 5.0 / 36.0],
                    ],
                    b: [5.0 / 18.0, 4.0 / 9.0, 5.0 / 18.0],
                    c: [0.5 - r / 10.0, 0.5, 0.5 + r / 10.0],
                    d: [0.0; 3],
                }
            }
        };
        // d solves A^T d = b (A of a Gauss method is invertible: its eigenvalues are the
        // reciprocals of the poles of the Pade stability function, all in Re > 0).
        let s = t.s;
        let mut lu = DenseLu::with_substitution(s, Substitution::Reciprocal);
        let at = lu.matrix_mut();
        for i in 0..s {
            for j in 0..s {
                at[(i, j)] = t.a[j][i];
            }
        }
        t.d[..s].copy_from_slice(&t.b[..s]);
        let ok = lu.factor().and_then(|_| lu.solve(&mut t.d[..s]));
        debug_assert!(ok.is_ok(), "Gauss tableau A is invertible");
        t
    }
}
