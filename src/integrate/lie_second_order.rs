//! `LieSecondOrder`: a second-order system on a Lie group, the kind of system the Lie-group
//! generalized-alpha method (`lie_gen_alpha`) advances.
//!
//! The configuration `q` lies on a Lie group `G` of dimension `N` (SO(3) x R^3 for a rigid
//! body, SE(2) for a planar link, a product of them for a mechanism); the velocity `w` is an
//! element of its Lie algebra written in `N` coordinates, in the trivialisation the system
//! chooses (`q' = q w^` for the right one); the equations of motion are solved for the
//! acceleration, `w' = f(t, q, w)`. The system supplies what a Lie-group method needs:
//! - `acceleration`: `f(t, q, w)`;
//! - `advance`: the retraction `q exp(dq^)` of the configuration by an algebra increment `dq`,
//!   with a new velocity (the exponential map of `G`, so that `advance` keeps `q` on the group
//!   exactly, up to rounding);
//! - `solve_iteration`: the Newton step `(I - c df/dw) d = -r` of an implicit method, with the
//!   tangent Jacobian `df/dw` of the acceleration in velocity (the configuration part `df/dq`
//!   may be left out: a simplified Newton that converges where `h^2 |df/dq|` is small).
//!
//! On a vector space (`G = R^N`, `advance` the sum) the methods over this trait are the
//! classical ones of the same coefficients. Invariant: `advance` and `solve_iteration` do not
//! allocate; `solve_iteration` returns `None` for a singular iteration matrix, never panics.
use super::System;
use nalgebra::SVector;

/// A second-order system on an `N`-dimensional Lie group, in acceleration form.
///
/// # Example
///
/// The pendulum `theta'' = -sin theta` on the circle group, its configuration stored as a unit
/// complex number `(cos theta, sin theta)` and its velocity as the one coordinate of the
/// algebra; `advance` multiplies by `exp(i dq)`, so the configuration stays on the circle.
///
/// ```
/// use mbdbench::integrate::lie_second_order::LieSecondOrder;
/// use mbdbench::integrate::{Failure, FailureKind, System};
/// use nalgebra::{SVector, Vector1, Vector2, Vector3};
///
/// struct Pendulum;
/// impl System for Pendulum {
///     /// `(cos theta, sin theta, w)`.
///     type State = Vector3<f64>;
///     /// `(theta increment, w increment)`.
///     type Tangent = Vector2<f64>;
///     const LIE: bool = true;
///     fn rhs(&self, t: f64, x: &Vector3<f64>) -> Vector2<f64> {
///         Vector2::new(x[2], self.acceleration(t, x)[0])
///     }
///     fn retract(&self, x: &Vector3<f64>, d: &Vector2<f64>) -> Vector3<f64> {
///         self.advance(x, &Vector1::new(d[0]), &Vector1::new(x[2] + d[1]))
///     }
///     fn check(&self, t: f64, x: &Vector3<f64>) -> Result<(), Failure> {
///         if x.iter().all(|v| v.is_finite()) { Ok(()) }
///         else { Err(Failure::new(FailureKind::NonFinite, t, "non-finite")) }
///     }
/// }
/// impl LieSecondOrder<1> for Pendulum {
///     fn velocity(&self, x: &Vector3<f64>) -> Vector1<f64> { Vector1::new(x[2]) }
///     fn acceleration(&self, _t: f64, x: &Vector3<f64>) -> Vector1<f64> { Vector1::new(-x[1]) }
///     fn advance(&self, x: &Vector3<f64>, dq: &Vector1<f64>, w: &Vector1<f64>) -> Vector3<f64> {
///         let (s, c) = dq[0].sin_cos();
///         Vector3::new(x[0] * c - x[1] * s, x[0] * s + x[1] * c, w[0])
///     }
///     fn solve_iteration(&self, _x: &Vector3<f64>, _c: f64, r: &Vector1<f64>)
///         -> Option<Vector1<f64>> {
///         Some(-r) // f does not depend on w: the iteration matrix is the identity
///     }
/// }
/// let x = Pendulum.advance(&Vector3::new(1.0, 0.0, 0.5), &Vector1::new(0.3), &Vector1::new(0.5));
/// assert!((x[0] * x[0] + x[1] * x[1] - 1.0).abs() < 1e-15);
/// assert!((x[1] - 0.3_f64.sin()).abs() < 1e-15);
/// ```
pub trait LieSecondOrder<const N: usize>: System {
    /// The velocity `w` of a state, in the algebra's coordinates.
    fn velocity(&self, x: &Self::State) -> SVector<f64, N>;

    /// The acceleration `f(t, q, w)` at a state.
    fn acceleration(&self, t: f64, x: &Self::State) -> SVector<f64, N>;

    /// The state with configuration `q exp(dq^)` (the group's retraction of the algebra
    /// increment `dq`) and velocity `w`.
    fn advance(&self, x: &Self::State, dq: &SVector<f64, N>, w: &SVector<f64, N>) -> Self::State;

    /// The Newton update `d` of `(I - c df/dw(x)) d = -r`, `None` if the matrix is singular.
    fn solve_iteration(
        &self,
        x: &Self::State,
        c: f64,
        r: &SVector<f64, N>,
    ) -> Option<SVector<f64, N>>;
}
