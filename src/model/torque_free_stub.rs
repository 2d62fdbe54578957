//! Temporary stand-in until the exact Euler-Poinsot solution lands.
use nalgebra::{Matrix3, UnitQuaternion, Vector3};
pub struct TorqueFreeExact;
impl TorqueFreeExact {
    pub fn new(_: Vector3<f64>, _: Vector3<f64>, _: Matrix3<f64>) -> Result<Self, String> {
        Err("exact torque-free solution not available yet".into())
    }
    pub fn at(&self, _t: f64) -> (UnitQuaternion<f64>, Vector3<f64>) {
        (UnitQuaternion::identity(), Vector3::zeros())
    }
}
