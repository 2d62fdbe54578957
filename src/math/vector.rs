//! `Vector`: the small linear-algebra interface the integrators need of a tangent
//! (increment) type, so that one Runge-Kutta code serves every state space.
//!
//! A tangent is a fixed-size element of R^n: an `SVector<f64, N>` or a pair of tangents
//! (pose increment, velocity increment). Nothing here allocates; `DIM` is known at compile
//! time, and `write_to`/`read_from` flatten a tangent for the dense Newton solves of the
//! implicit methods. Pairs compose, so no type-level dimension arithmetic is needed.
use nalgebra::SVector;
use std::fmt::Debug;

/// A finite-dimensional real vector space with a flat coordinate view.
pub trait Vector: Copy + Debug + Send + Sync + 'static {
    /// Number of real components.
    const DIM: usize;
    /// The zero vector.
    fn zero() -> Self;
    /// `self += a * x`.
    fn axpy(&mut self, a: f64, x: &Self);
    /// `a * self`.
    #[inline(always)]
    fn scaled(&self, a: f64) -> Self {
        let mut out = Self::zero();
        out.axpy(a, self);
        out
    }
    /// Writes the components into `out[..DIM]`.
    fn write_to(&self, out: &mut [f64]);
    /// Reads the components from `s[..DIM]`.
    fn read_from(s: &[f64]) -> Self;
    /// Largest absolute component.
    fn norm_inf(&self) -> f64;
    /// Whether every component is finite.
    fn is_finite(&self) -> bool;
    /// `self - x`.
    #[inline(always)]
    fn minus(&self, x: &Self) -> Self {
        let mut out = *self;
        out.axpy(-1.0, x);
        out
    }
}

impl<const N: usize> Vector for SVector<f64, N> {
    const DIM: usize = N;
    #[inline(always)]
    fn zero() -> Self {
        SVector::<f64, N>::zeros()
    }
    #[inline(always)]
    fn axpy(&mut self, a: f64, x: &Self) {
        for i in 0..N {
            self[i] += a * x[i];
        }
    }
    #[inline(always)]
    fn write_to(&self, out: &mut [f64]) {
        out[..N].copy_from_slice(self.as_slice());
    }
    #[inline(always)]
    fn read_from(s: &[f64]) -> Self {
        SVector::<f64, N>::from_column_slice(&s[..N])
    }
    #[inline(always)]
    fn norm_inf(&self) -> f64 {
        self.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        self.iter().all(|v| v.is_finite())
    }
}

impl<A: Vector, B: Vector> Vector for (A, B) {
    const DIM: usize = A::DIM + B::DIM;
    #[inline(always)]
    fn zero() -> Self {
        (A::zero(), B::zero())
    }
    #[inline(always)]
    fn axpy(&mut self, a: f64, x: &Self) {
        self.0.axpy(a, &x.0);
        self.1.axpy(a, &x.1);
    }
    #[inline(always)]
    fn write_to(&self, out: &mut [f64]) {
        self.0.write_to(&mut out[..A::DIM]);
        self.1.write_to(&mut out[A::DIM..]);
    }
    #[inline(always)]
    fn read_from(s: &[f64]) -> Self {
        (A::read_from(&s[..A::DIM]), B::read_from(&s[A::DIM..]))
    }
    #[inline(always)]
    fn norm_inf(&self) -> f64 {
        self.0.norm_inf().max(self.1.norm_inf())
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        self.0.is_finite() && self.1.is_finite()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Vector3, Vector6};

    /// Flattening a pair and reading it back is the identity, and axpy acts componentwise.
    #[test]
    fn pair_round_trip_and_axpy() {
        let a: (Vector3<f64>, Vector6<f64>) = (
            Vector3::new(1.0, 2.0, 3.0),
            Vector6::new(4.0, 5.0, 6.0, 7.0, 8.0, 9.0),
        );
        assert_eq!(<(Vector3<f64>, Vector6<f64>)>::DIM, 9);
        let mut buf = [0.0; 9];
        a.write_to(&mut buf);
        assert_eq!(buf, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
        let b = <(Vector3<f64>, Vector6<f64>)>::read_from(&buf);
        assert_eq!(a.0, b.0);
        assert_eq!(a.1, b.1);
        let mut c = a;
        c.axpy(-2.0, &b);
        assert_eq!(c.norm_inf(), 9.0);
        assert!(c.is_finite());
        assert_eq!(a.minus(&a).norm_inf(), 0.0);
    }
}
