//! Rotation parameterizations ("charts") of a rigid body's pose, behind one trait, and the
//! rotation-only part of the charts that keep the translation apart (`RotationChart`,
//! `rotation_chart.rs`: a node's rotation in a structure).
//!
//! A `PoseChart` stores the rotation (and, for the SE(3) charts, the translation together
//! with it) in its own numbers and knows: the map to and from a rotation matrix, its
//! kinematic map (body angular velocity -> coordinate rates, or the trivialised velocity on a
//! Lie group), `retract`, `dexp_inv`, its own constraint residual, a conditioning number that
//! is 0 on its singular set, and an optional `normalize` (projection or re-charting).
//! For the charts that keep the translation separately, `x` is an additive R^3 inside the
//! chart's coordinates, so every chart describes the whole pose `(R, x)`.
//!
//! Lie-group charts use the right (body) trivialisation `g exp(theta)` with the body formulation
//! and the left (spatial) one `exp(theta) g` with the spatial formulation (`spatial = true`);
//! additive charts ignore `spatial`.
use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use std::fmt::Debug;

use crate::math::so3;
use crate::math::vector::Vector;

/// A parameterization of a rigid body's pose.
///
/// # Example
///
/// The Lie-group chart `so3`: a body-frame increment (rotation, then translation) retracts as
/// `R exp(w)`, `x + v`; the stored unit quaternion satisfies its constraint to round-off, and
/// the chart has no singular set.
///
/// ```
/// use mbdbench::rotation::{PoseChart, So3};
/// use nalgebra::{UnitQuaternion, Vector3, Vector6};
///
/// let r = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -0.2, 0.1));
/// let c = So3::from_pose(r.to_rotation_matrix().matrix(), &Vector3::new(1.0, 2.0, 3.0));
/// let d = Vector6::new(0.0, 0.0, 0.5, 0.1, 0.0, 0.0);
/// let c1 = So3::retract(&c, &d, false);
/// let want = r * UnitQuaternion::from_scaled_axis(Vector3::new(0.0, 0.0, 0.5));
/// assert!(So3::quaternion(&c1).angle_to(&want) < 1e-14);
/// assert_eq!(So3::position(&c1), Vector3::new(1.1, 2.0, 3.0));
/// assert!(So3::residual(&c1).unwrap() < 1e-15);
/// assert_eq!(So3::conditioning(&c1), 1.0);
/// ```
pub trait PoseChart: Send + Sync + 'static {
    /// The variant name (stable snake_case: it appears in case files, records and bench ids).
    const NAME: &'static str;
    /// The stored numbers.
    type Coords: Copy + Debug + Send + Sync + Translation;
    /// The increment of the pose.
    type Tangent: Vector;
    /// Retract is a group action and `dexp_inv` is not the identity (RKMK applies).
    const LIE: bool;
    /// Rotation and translation move together on SE(3) (not applicable with a fixed pivot).
    const SE3: bool;
    /// The chart has a constraint (redundant coordinates): `residual` is `Some`.
    const CONSTRAINED: bool;
    /// The chart normalizes (projects or re-charts) after each step.
    const NORMALIZES: bool;

    /// Coordinates of the pose `(R, x)` (principal branch for multi-valued charts).
    fn from_pose(r: &Matrix3<f64>, x: &Vector3<f64>) -> Self::Coords;
    /// The rotation matrix.
    fn rotation(c: &Self::Coords) -> Matrix3<f64>;
    /// The rotation as a unit quaternion.
    fn quaternion(c: &Self::Coords) -> UnitQuaternion<f64> {
        so3::quat_from_matrix(&Self::rotation(c))
    }
    /// The translation.
    #[inline(always)]
    fn position(c: &Self::Coords) -> Vector3<f64> {
        c.translation()
    }
    /// The pose velocity: coordinate rates (additive charts) or the trivialised velocity (Lie
    /// charts: body twist when `!spatial`, spatial twist when `spatial`), from the body angular
    /// velocity `omega_body` and the world velocity `xdot` of the translation. `r` is
    /// `rotation(c)`, passed in because the caller has it.
    fn velocity(
        c: &Self::Coords,
        r: &Matrix3<f64>,
        omega_body: &Vector3<f64>,
        xdot: &Vector3<f64>,
        spatial: bool,
    ) -> Self::Tangent;
    /// `c (+) d`.
    fn retract(c: &Self::Coords, d: &Self::Tangent, spatial: bool) -> Self::Coords;
    /// The RKMK correction: rate of the increment `theta` whose velocity is `v` (identity for
    /// additive charts).
    fn dexp_inv(theta: &Self::Tangent, v: &Self::Tangent, spatial: bool) -> Self::Tangent;
    /// Whether `retract_dexp_inv` shares work (else a caller is better off calling `retract`
    /// and `dexp_inv` apart: the default's closure is not always inlined, measured on
    /// `se3_hq`).
    const FUSED_RETRACT_DEXP_INV: bool = false;
    /// `retract(c, d, spatial)` and the map `v -> dexp_inv(d, v, spatial)` together, for an
    /// RKMK stage, which needs both at the same increment: a chart may share their work
    /// (`so3`: one `sin_cos` of `|theta|/2`), and must return the same numbers as the two
    /// apart. Default: the two apart.
    #[inline(always)]
    fn retract_dexp_inv(
        c: &Self::Coords,
        d: &Self::Tangent,
        spatial: bool,
    ) -> (Self::Coords, impl Fn(&Self::Tangent) -> Self::Tangent) {
        (Self::retract(c, d, spatial), move |v: &Self::Tangent| {
            Self::dexp_inv(d, v, spatial)
        })
    }
    /// The chart's own constraint residual (`||q|^2 - 1|`, `|R^T R - I|`, ...), `None` for
    /// minimal charts.
    fn residual(c: &Self::Coords) -> Option<f64>;
    /// Distance-like number that is 0 on the chart's singular set (1 where it has none).
    fn conditioning(c: &Self::Coords) -> f64;
    /// Projection or re-charting; returns whether it was applied.
    fn normalize(c: &mut Self::Coords) -> bool;
    /// Whether all stored numbers are finite.
    fn is_finite(c: &Self::Coords) -> bool;
}

/// Newton-Euler formulation (cases/README.md, "Equations solved"): equations and velocities in the
/// body frame, or the twist and equations in the world frame (Bongardt & Kirchner,
/// general-coordinates Newton-Euler).
pub trait Formulation: Send + Sync + 'static {
    const SPATIAL: bool;
    const NAME: &'static str;
}

/// Body formulation: velocity state `(v, omega)` = (world velocity of the reference point,
/// body angular velocity); Euler's equations in the body frame.
#[derive(Debug, Clone, Copy, Default)]
pub struct Body;
/// Spatial formulation: velocity state = the spatial twist `(v_s, w)`, `w = R omega`,
/// `v_s = xdot - w x x`; equations in the world frame.
#[derive(Debug, Clone, Copy, Default)]
pub struct Spatial;

impl Formulation for Body {
    const SPATIAL: bool = false;
    const NAME: &'static str = "body";
}
impl Formulation for Spatial {
    const SPATIAL: bool = true;
    const NAME: &'static str = "spatial";
}

mod so3_chart;
pub use so3_chart::So3;

mod rotation_chart;
pub use rotation_chart::RotationChart;

pub mod dual_quat;
pub mod euler;
pub mod matrix;
pub mod quat;
pub mod rotvec;
pub mod se3_hq;
pub use dual_quat::DualQuat;
pub use euler::{EulerXyz, EulerZxz, EulerZyx};
pub use matrix::{Matrix, MatrixProj};
pub use quat::{Quat, QuatProj};
pub use rotvec::RotVec;
pub use se3_hq::Se3Hq;

/// Invokes `$m!(T)` once for each of the eleven chart types `T` (by their bare names, in the
/// order of the parameterization list in README.md, "What it answers"), so a table of charts is
/// written once: the conformance suite and the registry use it. The caller brings the names into
/// scope (`use crate::rotation::*`).
#[macro_export]
macro_rules! for_each_chart {
    ($m:ident) => {
        $m!(EulerXyz);
        $m!(EulerZyx);
        $m!(EulerZxz);
        $m!(RotVec);
        $m!(Quat);
        $m!(QuatProj);
        $m!(Matrix);
        $m!(MatrixProj);
        $m!(So3);
        $m!(Se3Hq);
        $m!(DualQuat);
    };
}

#[cfg(test)]
mod conformance;
#[cfg(test)]
mod conformance_rotation;

/// Coordinates that carry a translation: every chart's, so `PoseChart::position` is written
/// once (a `Pose` keeps it beside the rotation's numbers; a dual quaternion encodes it).
pub trait Translation {
    /// The translation (m, world).
    fn translation(&self) -> Vector3<f64>;
}

impl<Q: Copy> Translation for Pose<Q> {
    #[inline(always)]
    fn translation(&self) -> Vector3<f64> {
        self.x
    }
}

/// Coordinates of a chart that keeps the translation as a separate additive R^3.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose<Q: Copy> {
    /// The rotation's coordinates.
    pub rot: Q,
    /// The translation (m, world).
    pub x: Vector3<f64>,
}
