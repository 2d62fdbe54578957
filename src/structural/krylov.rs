//! The Krylov subspace accelerator of Carlson & Miller (1998, "Design and application of a
//! gradient-weighted moving finite element code I: in one dimension", SIAM J. Sci. Comput. 19;
//! the "Krylov-accelerated inexact Newton" of their section on the nonlinear solver), the
//! algorithm of OpenSees' `KrylovNewton`, on the corrections of a Newton iteration whose
//! tangent `K0` is frozen.
//!
//! With the frozen tangent, each iteration's raw correction `s_k = -K0^-1 r(x_k)` is the
//! residual preconditioned by `K0^-1`. After a correction `v_j` has been applied, the change
//! of the raw correction, `a_j = s_j - s_{j+1}`, approximates `K0^-1 K v_j` (`K` the true
//! tangent): the pairs `(v_j, a_j)` are secant information on the preconditioned operator.
//! The accelerated correction is
//!
//! ```text
//! c   = argmin_c | s_k - sum_j c_j a_j |          (least squares over j < k)
//! v_k = s_k + sum_j c_j (v_j - a_j)
//! ```
//!
//! i.e. the part of `s_k` that lies in the span of the `a_j` is replaced by the combination of
//! the `v_j` that the secant model says produces it, and the rest is taken as the plain
//! (modified-Newton) correction. On a linear problem this is GMRES-like on `K0^-1 K`: with
//! `n` unknowns and a subspace of at least `n` it terminates in `n + 1` iterations whatever
//! `K0` is. The subspace holds at most `max_dim` pairs; when an accelerated correction has
//! been made with `max_dim` of them the owner refreshes the tangent and restarts
//! ([`Krylov::full`]), as OpenSees does (`KrylovAccelerator::updateTangent`, default
//! `maxDim` 3).
//!
//! The least-squares problem is solved by modified Gram-Schmidt with one re-orthogonalisation
//! (QR of the `a_j`), in preallocated storage: no allocation per iteration. Where it fails:
//! a secant direction that is (numerically) in the span of the earlier ones is dropped from
//! the fit (its coefficient 0; OpenSees' `dgels` would return unbounded coefficients there).
use nalgebra::DVector;

/// The accelerator's subspace and workspace.
#[derive(Debug, Clone)]
pub struct Krylov {
    max_dim: usize,
    dim: usize,
    v: Vec<DVector<f64>>,
    a: Vec<DVector<f64>>,
    q: Vec<DVector<f64>>,
    r: Vec<f64>,
    kept: Vec<bool>,
    c: Vec<f64>,
}

impl Krylov {
    /// An accelerator for `n` unknowns holding at most `max_dim` secant pairs.
    ///
    /// # Example
    ///
    /// A linear system `A x = b` iterated with a poor frozen tangent `K0 = diag(A)`: the
    /// accelerated corrections solve it in `n + 1 = 3` iterations.
    ///
    /// ```
    /// use mbdbench::structural::krylov::Krylov;
    /// use nalgebra::{DMatrix, DVector};
    ///
    /// let a = DMatrix::from_row_slice(2, 2, &[4.0, 1.0, 2.0, 3.0]);
    /// let b = DVector::from_vec(vec![1.0, 2.0]);
    /// let mut x = DVector::zeros(2);
    /// let mut acc = Krylov::new(2, 3);
    /// for _ in 0..3 {
    ///     let r = &a * &x - &b;
    ///     let mut s = DVector::from_vec(vec![-r[0] / 4.0, -r[1] / 3.0]);
    ///     acc.accelerate(&mut s);
    ///     x += &s;
    /// }
    /// assert!((&a * &x - &b).norm() < 1e-12);
    /// ```
    pub fn new(n: usize, max_dim: usize) -> Self {
        Self {
            max_dim,
            dim: 0,
            v: vec![DVector::zeros(n); max_dim + 1],
            a: vec![DVector::zeros(n); max_dim + 1],
            q: vec![DVector::zeros(n); max_dim],
            r: vec![0.0; max_dim * max_dim],
            kept: vec![false; max_dim],
            c: vec![0.0; max_dim],
        }
    }

    /// Empties the subspace (a new step, or a refreshed tangent).
    pub fn reset(&mut self) {
        self.dim = 0;
    }

    /// The number of unknowns it was made for.
    pub fn unknowns(&self) -> usize {
        self.v[0].len()
    }

    /// The number of pairs the next acceleration will use.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Whether the subspace is exhausted: the owner should refresh its tangent and
    /// [`Krylov::reset`] before the next correction.
    pub fn full(&self) -> bool {
        self.dim > self.max_dim
    }

    /// Turns the raw correction `s = -K0^-1 r` of the current iterate into the accelerated
    /// one (in place) and records it. Must not be called when [`Krylov::full`].
    pub fn accelerate(&mut self, s: &mut DVector<f64>) {
        let k = self.dim;
        assert!(k <= self.max_dim, "Krylov subspace exhausted");
        self.a[k].copy_from(s);
        if k > 0 {
            self.a[k - 1] -= &*s;
            self.least_squares(k, s);
            for j in 0..k {
                let cj = self.c[j];
                if cj != 0.0 {
                    s.axpy(cj, &self.v[j], 1.0);
                    s.axpy(-cj, &self.a[j], 1.0);
                }
            }
        }
        self.v[k].copy_from(s);
        self.dim += 1;
    }

    /// `c = argmin |s - sum_{j<k} c_j a_j|` into `self.c` by modified Gram-Schmidt QR.
    fn least_squares(&mut self, k: usize, s: &DVector<f64>) {
        let m = self.max_dim;
        for j in 0..k {
            self.q[j].copy_from(&self.a[j]);
            let norm0 = self.q[j].norm();
            for pass in 0..2 {
                for i in 0..j {
                    if !self.kept[i] {
                        continue;
                    }
                    let rij = self.q[i].dot(&self.q[j]);
                    if pass == 0 {
                        self.r[i * m + j] = rij;
                    } else {
                        self.r[i * m + j] += rij;
                    }
                    let (qi, qj) = two(&mut self.q, i, j);
                    qj.axpy(-rij, qi, 1.0);
                }
            }
            let rjj = self.q[j].norm();
            self.kept[j] = norm0 > 0.0 && rjj > 1e-12 * norm0;
            if self.kept[j] {
                self.r[j * m + j] = rjj;
                self.q[j] /= rjj;
            }
        }
        // Back substitution R c = Q^T s over the kept columns.
        for j in (0..k).rev() {
            if !self.kept[j] {
                self.c[j] = 0.0;
                continue;
            }
            let mut x = self.q[j].dot(s);
            for i in j + 1..k {
                if self.kept[i] {
                    x -= self.r[j * m + i] * self.c[i];
                }
            }
            self.c[j] = x / self.r[j * m + j];
        }
    }
}

/// Shared access to `q[i]` and mutable access to `q[j]`, `i < j`.
fn two(q: &mut [DVector<f64>], i: usize, j: usize) -> (&DVector<f64>, &mut DVector<f64>) {
    let (lo, hi) = q.split_at_mut(j);
    (&lo[i], &mut hi[0])
}
