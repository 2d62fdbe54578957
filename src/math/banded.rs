//! `banded`: LU factorisation of a banded matrix with an optional dense border (an
//! "arrow-head" matrix), in buffers sized once from its [`Band`], behind the same
//! [`LinearSolve`] interface as the dense [`DenseLu`]. It serves the structural Newton
//! iterations of systems whose tangent couples only near neighbours (the flexible beam's
//! `fe_exact` elements: `kl = ku = 5`) plus a few coordinates coupled to all (the free hub's
//! angle), in `O(n (kl + ku) kl)` per factorisation and `O(n (2 kl + ku))` per solve instead
//! of the dense `2 n^3 / 3` and `2 n^2`.
//!
//! The matrix, with `B` the band block (lower and upper bandwidths `kl`, `ku`) and the border
//! `nb` rows and columns either first or last ([`Border`]):
//!
//! ```text
//! A = [ B    A12 ]      (border last; border first is the same after a symmetric
//!     [ A21  A22 ]       permutation that moves the border to the end)
//! ```
//!
//! Band block: Gaussian elimination with partial pivoting in LAPACK's band storage and in
//! the order of its `dgbtf2`/`dgbtrs` (Golub & Van Loan, "Matrix Computations", 4th ed.,
//! Sec. 4.3.5, "Banded Gaussian elimination with pivoting": `U` gets upper bandwidth
//! `kl + ku`, `L` keeps `kl`): column `j` holds rows `j - kl - ku ..= j + kl` of `B`, row
//! `i` at offset `kl + ku + i - j`. At column `k` the first largest `|b_ik|`, `k <= i <=
//! k + kl`, is the pivot, the multipliers `l_ik = b_ik (1 / b_kk)` overwrite column `k`
//! below the diagonal, and the columns `k + 1 ..= k + kl + ku` are updated, `b_ij -= l_ik
//! b_kj`, skipping one whose `b_kj` is zero. These are exactly [`DenseLu`]'s operations on
//! the same matrix (the entries outside the band are zero and stay zero; the dense code's
//! updates there subtract `0 * b_kj`), so without a border the factors and the solutions of
//! the two are bit-identical (a test checks it); the row swaps are applied to the
//! right-hand side as they come (`dgbtrs`), not all first, which relabels the same
//! operations. The solve divides by the pivots and skips zero components, as
//! [`crate::math::lu::Substitution::Divide`].
//!
//! Border: block elimination with the Schur complement (Golub & Van Loan, Sec. 3.2.11,
//! block LU): `W = B^-1 A12` (`nb` band solves), `C = A22 - A21 W` factored by a dense LU of
//! order `nb`; a solve is `y = B^-1 b_1`, `x_2 = C^-1 (b_2 - A21 y)`, `x_1 = y - W x_2`.
//! The same structure holds a constrained system's saddle-point matrix `[S G^T; G 0]` (the
//! band `S`, the border the `m` constraint rows and columns, `A22 = 0`): `C = -G S^-1 G^T`.
//!
//! Singularity (as [`DenseLu`], a typed [`LuError`]): a band pivot at or below `n eps` times
//! the largest entry of its column of `A` (band and border rows), or a pivot of `C` at or
//! below `n eps` times the largest entry of its border column of `A` (the threshold of
//! [`DenseLu`] with `n` the full order), is [`LuError::Singular`] naming the column of `A`.
//!
//! Where it fails: eliminating the border last needs a regular band block `B`; a regular
//! `A` with a singular `B` (a saddle point whose `S` is singular on the constraints' null
//! space' complement, e.g. a coordinate that has no mass and is fixed only by a constraint)
//! is reported singular at that column of `B`; such systems keep the dense LU. Partial
//! pivoting within the band is as stable as the dense LU's (the same pivots); the Schur
//! step adds the growth of `W`, small when `B` is well conditioned (the beam's `B` is its
//! prescribed-base iteration matrix, mass-dominated).
//!
//! Why hand-written: it is 2.2 to 2.6x faster than `faer`'s sparse LU on the beam's
//! pattern (measured, [`BandedLu`]'s docs), and `nalgebra-sparse` has no LU (only a
//! Cholesky; the beam's tangent is not symmetric).
use super::lu::{DenseLu, LinearSolve, LuError};

/// Where the border rows and columns sit in the matrix.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Border {
    /// No border: the matrix is the band block.
    None,
    /// The first `k` rows and columns (the beam's free hub angle, coordinate 0).
    First(usize),
    /// The last `k` rows and columns (the multipliers of a saddle-point system).
    Last(usize),
}

impl Border {
    /// The number of border rows and columns.
    pub fn width(&self) -> usize {
        match *self {
            Border::None => 0,
            Border::First(k) | Border::Last(k) => k,
        }
    }
}

/// The shape of a banded matrix with a border: order `n`, the band block's bandwidths.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Band {
    /// Order of the whole matrix.
    pub n: usize,
    /// Lower bandwidth of the band block (`b_ij = 0` for `i > j + kl`).
    pub kl: usize,
    /// Upper bandwidth of the band block (`b_ij = 0` for `j > i + ku`).
    pub ku: usize,
    /// The border rows and columns.
    pub border: Border,
}

impl Band {
    /// The order of the band block.
    pub fn band_order(&self) -> usize {
        self.n.saturating_sub(self.border.width())
    }

    /// The offset of the band block in the matrix (where its row and column 0 sit).
    fn first(&self) -> usize {
        match self.border {
            Border::First(k) => k,
            _ => 0,
        }
    }

    /// The offset of the border in the matrix.
    fn border_start(&self) -> usize {
        match self.border {
            Border::First(_) => 0,
            _ => self.band_order(),
        }
    }

    /// Where `A_ij` lives: the band block's entry, a border block's, or outside the
    /// pattern (None).
    #[inline]
    pub(crate) fn locate(&self, i: usize, j: usize) -> Option<Slot> {
        if i >= self.n || j >= self.n {
            return None;
        }
        let (f, nb) = (self.first(), self.band_order());
        let inb = |x: usize| x >= f && x < f + nb;
        let bs = self.border_start();
        match (inb(i), inb(j)) {
            (true, true) => {
                let (bi, bj) = (i - f, j - f);
                (bi <= bj + self.kl && bj <= bi + self.ku).then_some(Slot::Band(bi, bj))
            }
            (true, false) => Some(Slot::Right(i - f, j - bs)),
            (false, true) => Some(Slot::Below(i - bs, j - f)),
            (false, false) => Some(Slot::Corner(i - bs, j - bs)),
        }
    }
}

/// An entry's place in the blocks of a [`Band`] (band block indices, border indices).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Slot {
    Band(usize, usize),
    Right(usize, usize),
    Below(usize, usize),
    Corner(usize, usize),
}

/// LU factorisation of a banded matrix with a border, in preallocated buffers.
///
/// Measured against `faer` 0.22's sparse LU (scratch crate outside the repository,
/// `taskset -c 1`, 5 rounds, median, on a shared machine under load; faer's low-level
/// `factorize_numeric_lu` into a preallocated numeric factor and scratch, its symbolic
/// analysis done once, then one solve; this type's copy of the matrix, factor and solve) on
/// the beam's pattern, `kl = ku = 5` and one border row and column, `n = 3 N + 1`: this type
/// 4.3, 8.3, 17.3, 35.8 and 72 us at `N` = 10, 20, 40, 80, 160 elements, `faer` 10.2, 18.1,
/// 44.2, 86.2 and 177 us (2.2 to 2.6x slower: its general sparse machinery costs more than
/// the band's few flops), the dense LU 8.4, 40, 305 and 2146 us up to 80. So the
/// hand-written one is kept and no dependency is added.
///
/// # Example
///
/// A tridiagonal matrix with one border row and column first, filled by entry, factored
/// and solved; an entry outside the pattern is refused:
///
/// ```
/// use mbdbench::math::banded::{Band, BandedLu, Border};
/// use mbdbench::math::lu::LinearSolve;
///
/// let band = Band { n: 4, kl: 1, ku: 1, border: Border::First(1) };
/// let mut lu = BandedLu::new(band);
/// let a = [
///     [4.0, 1.0, 1.0, 1.0],
///     [1.0, 3.0, 1.0, 0.0],
///     [1.0, 1.0, 3.0, 1.0],
///     [1.0, 0.0, 1.0, 3.0],
/// ];
/// for i in 0..4 {
///     for j in 0..4 {
///         if a[i][j] != 0.0 {
///             lu.add(i, j, a[i][j]).unwrap();
///         }
///     }
/// }
/// assert!(lu.add(1, 3, 1.0).is_err());
/// lu.factor().unwrap();
/// let x = [1.0, -2.0, 0.5, 3.0];
/// let mut b: Vec<f64> = a.iter().map(|r| r.iter().zip(&x).map(|(p, q)| p * q).sum()).collect();
/// lu.solve(&mut b).unwrap();
/// assert!(b.iter().zip(&x).all(|(p, q)| (p - q).abs() < 1e-14));
/// ```
#[derive(Debug, Clone)]
pub struct BandedLu {
    band: Band,
    /// Leading dimension of the band storage, `2 kl + ku + 1`.
    ldab: usize,
    /// The band block in LAPACK's band storage (column-major, `ldab` rows).
    ab: Vec<f64>,
    /// Row swaps of the band block: row `k` with row `ipiv[k]`, `k <= ipiv[k] <= k + kl`.
    ipiv: Vec<usize>,
    /// Singularity thresholds of the band block's columns.
    threshold: Vec<f64>,
    /// `A12` (band order x nb, column-major); `W = B^-1 A12` after `factor`.
    right: Vec<f64>,
    /// `A21` (nb x band order, column-major).
    below: Vec<f64>,
    /// `A22`, then the Schur complement and its factors.
    corner: DenseLu,
    /// The thresholds of the border columns (floors for the Schur complement's pivots).
    corner_floor: Vec<f64>,
    factored: bool,
}

impl BandedLu {
    /// Buffers for matrices of shape `band` (the only allocation), zero-filled.
    pub fn new(band: Band) -> Self {
        let nb = band.border.width().min(band.n);
        let n1 = band.n - nb;
        let ldab = 2 * band.kl + band.ku + 1;
        BandedLu {
            band,
            ldab,
            ab: vec![0.0; ldab * n1],
            ipiv: vec![0; n1],
            threshold: vec![0.0; n1],
            right: vec![0.0; n1 * nb],
            below: vec![0.0; nb * n1],
            corner: DenseLu::new(nb),
            corner_floor: vec![0.0; nb],
            factored: false,
        }
    }

    /// The shape.
    pub fn band(&self) -> Band {
        self.band
    }

    /// Zeroes the matrix (it invalidates the factorisation).
    pub fn clear(&mut self) {
        self.factored = false;
        self.ab.fill(0.0);
        self.right.fill(0.0);
        self.below.fill(0.0);
        self.corner.matrix_mut().fill(0.0);
    }

    /// A mutable reference to `A_ij`, or a dimension error outside the pattern (the band,
    /// the border).
    #[inline]
    pub fn entry_mut(&mut self, i: usize, j: usize) -> Result<&mut f64, LuError> {
        self.factored = false;
        let n1 = self.band.band_order();
        let kv = self.band.kl + self.band.ku;
        match self.band.locate(i, j) {
            Some(Slot::Band(bi, bj)) => Ok(&mut self.ab[bj * self.ldab + kv + bi - bj]),
            Some(Slot::Right(bi, c)) => Ok(&mut self.right[c * n1 + bi]),
            Some(Slot::Below(r, bj)) => Ok(&mut self.below[bj * self.band.border.width() + r]),
            Some(Slot::Corner(r, c)) => Ok(&mut self.corner.matrix_mut()[(r, c)]),
            None => Err(LuError::OutsidePattern {
                entry: Some((i, j)),
            }),
        }
    }

    /// `A_ij += v`; a dimension error outside the pattern.
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, v: f64) -> Result<(), LuError> {
        *self.entry_mut(i, j)? += v;
        Ok(())
    }

    /// `A_ij` before `factor` (0 outside the pattern).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let n1 = self.band.band_order();
        let kv = self.band.kl + self.band.ku;
        match self.band.locate(i, j) {
            Some(Slot::Band(bi, bj)) => self.ab[bj * self.ldab + kv + bi - bj],
            Some(Slot::Right(bi, c)) => self.right[c * n1 + bi],
            Some(Slot::Below(r, bj)) => self.below[bj * self.band.border.width() + r],
            Some(Slot::Corner(r, c)) => self.corner_entry(r, c),
            None => 0.0,
        }
    }

    fn corner_entry(&self, r: usize, c: usize) -> f64 {
        // DenseLu exposes its buffer mutably only; a copy of the matrix is not kept.
        self.corner_view()[c * self.band.border.width() + r]
    }

    fn corner_view(&self) -> &[f64] {
        self.corner.matrix().as_slice()
    }

    /// The thresholds `n eps max_i |A_ij|` of every column; an error on a non-finite entry.
    fn thresholds(&mut self) -> Result<(), LuError> {
        let n = self.band.n as f64;
        let nb = self.band.border.width();
        let all = self
            .ab
            .iter()
            .chain(&self.right)
            .chain(&self.below)
            .chain(self.corner.matrix().as_slice());
        if !all.into_iter().all(|x| x.is_finite()) {
            return Err(LuError::NonFinite);
        }
        let amax = |s: &[f64]| s.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        for (j, t) in self.threshold.iter_mut().enumerate() {
            let col = &self.ab[j * self.ldab..(j + 1) * self.ldab];
            let border = &self.below[j * nb..(j + 1) * nb];
            *t = n * f64::EPSILON * amax(col).max(amax(border));
        }
        let n1 = self.band.band_order();
        for (c, t) in self.corner_floor.iter_mut().enumerate() {
            let col = &self.right[c * n1..(c + 1) * n1];
            let corner = &self.corner.matrix().as_slice()[c * nb..(c + 1) * nb];
            *t = n * f64::EPSILON * amax(col).max(amax(corner));
        }
        Ok(())
    }

    /// Factors the band block in place (module docs); `column` offsets name `A`'s column.
    fn factor_band(&mut self) -> Result<(), LuError> {
        let n1 = self.band.band_order();
        let (kl, kv, ld) = (self.band.kl, self.band.kl + self.band.ku, self.ldab);
        let ab = &mut self.ab;
        for k in 0..n1 {
            let km = kl.min(n1 - 1 - k);
            let col = &ab[k * ld + kv..=k * ld + kv + km];
            let (mut p, mut best) = (0, col[0].abs());
            for (i, x) in col.iter().enumerate().skip(1) {
                if x.abs() > best {
                    best = x.abs();
                    p = i;
                }
            }
            if best <= self.threshold[k] || best == 0.0 {
                return Err(LuError::Singular {
                    column: k + self.band.first(),
                    pivot: best,
                    threshold: self.threshold[k],
                });
            }
            self.ipiv[k] = k + p;
            let last = (n1 - 1).min(k + kv);
            if p != 0 {
                for j in k..=last {
                    ab.swap(j * ld + kv + k - j, j * ld + kv + k + p - j);
                }
            }
            let inv = 1.0 / ab[k * ld + kv];
            for l in &mut ab[k * ld + kv + 1..=k * ld + kv + km] {
                *l *= inv;
            }
            let (left, right) = ab.split_at_mut((k + 1) * ld);
            let lcol = &left[k * ld + kv + 1..=k * ld + kv + km];
            for (jj, col) in right.chunks_exact_mut(ld).take(last - k).enumerate() {
                // Column j = k + 1 + jj: row k at offset kv + k - j = kv - 1 - jj.
                let top = kv - 1 - jj;
                let akj = col[top];
                if akj != 0.0 {
                    for (x, l) in col[top + 1..=top + km].iter_mut().zip(lcol) {
                        *x -= l * akj;
                    }
                }
            }
        }
        Ok(())
    }

    /// Solves `B x = b` in place with the band block's factors (`b` of the band order).
    fn solve_band(&self, b: &mut [f64]) {
        let n1 = self.band.band_order();
        let (kl, kv, ld) = (self.band.kl, self.band.kl + self.band.ku, self.ldab);
        let ab = &self.ab;
        for k in 0..n1 {
            b.swap(k, self.ipiv[k]);
            let km = kl.min(n1 - 1 - k);
            let bk = b[k];
            if bk != 0.0 {
                let l = &ab[k * ld + kv + 1..=k * ld + kv + km];
                for (bi, l) in b[k + 1..=k + km].iter_mut().zip(l) {
                    *bi -= l * bk;
                }
            }
        }
        for k in (0..n1).rev() {
            b[k] /= ab[k * ld + kv];
            let bk = b[k];
            if bk != 0.0 {
                let i0 = k.saturating_sub(kv);
                let u = &ab[k * ld + kv - (k - i0)..k * ld + kv];
                for (bi, u) in b[i0..k].iter_mut().zip(u) {
                    *bi -= u * bk;
                }
            }
        }
    }

    /// The Schur complement `C = A22 - A21 W` with `W = B^-1 A12` (in `right`), factored.
    fn factor_border(&mut self) -> Result<(), LuError> {
        let (n1, nb) = (self.band.band_order(), self.band.border.width());
        let mut right = std::mem::take(&mut self.right);
        for w in right.chunks_exact_mut(n1) {
            self.solve_band(w);
        }
        self.right = right;
        let c = self.corner.matrix_mut();
        for cc in 0..nb {
            let w = &self.right[cc * n1..(cc + 1) * n1];
            for r in 0..nb {
                let mut s = 0.0;
                for (j, wj) in w.iter().enumerate() {
                    s += self.below[j * nb + r] * wj;
                }
                c[(r, cc)] -= s;
            }
        }
        let start = self.band.border_start();
        self.corner
            .factor_with_floor(&self.corner_floor)
            .map_err(|e| match e {
                LuError::Singular {
                    column,
                    pivot,
                    threshold,
                } => LuError::Singular {
                    column: column + start,
                    pivot,
                    threshold,
                },
                e => e,
            })
    }
}

impl LinearSolve for BandedLu {
    fn dim(&self) -> usize {
        self.band.n
    }

    fn factor(&mut self) -> Result<(), LuError> {
        self.factored = false;
        self.thresholds()?;
        self.factor_band()?;
        if self.band.border.width() > 0 {
            self.factor_border()?;
        }
        self.factored = true;
        Ok(())
    }

    fn solve(&self, b: &mut [f64]) -> Result<(), LuError> {
        if !self.factored {
            return Err(LuError::NotFactored);
        }
        let n = self.band.n;
        if b.len() != n {
            return Err(LuError::Dimension { n, len: b.len() });
        }
        let (n1, nb) = (self.band.band_order(), self.band.border.width());
        let (y, z) = match self.band.border {
            Border::First(_) => {
                let (z, y) = b.split_at_mut(nb);
                (y, z)
            }
            _ => b.split_at_mut(n1),
        };
        self.solve_band(y);
        if nb == 0 {
            return Ok(());
        }
        // z = C^-1 (b_2 - A21 y), then y -= W z.
        for (r, zr) in z.iter_mut().enumerate() {
            let mut s = 0.0;
            for (j, yj) in y.iter().enumerate() {
                s += self.below[j * nb + r] * yj;
            }
            *zr -= s;
        }
        self.corner.solve(z)?;
        for (c, zc) in z.iter().enumerate() {
            let w = &self.right[c * n1..(c + 1) * n1];
            for (yi, wi) in y.iter_mut().zip(w) {
                *yi -= wi * zc;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
#[path = "banded_tests.rs"]
mod tests;
