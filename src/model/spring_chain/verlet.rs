//! Stormer-Verlet (velocity Verlet, kick-drift-kick) for the spring chain's second-order
//! equations `y'' = a(y)` (Hairer, Lubich & Wanner, Geometric Numerical Integration, sec.
//! I.3.1, eq. (3.4)): `v+ = v + h/2 a(y)`, `y' = y + h v+`, `v' = v+ + h/2 a(y')`. Order 2,
//! symplectic and time-reversible; on a linear oscillator it is stable for `w h < 2` and its
//! energy error stays bounded (no drift). One acceleration per step after the first (the last
//! one is reused), counted as one RHS evaluation; no allocation.
use nalgebra::{Vector3, Vector6};

use super::{ChainSystem, Coordinates};
use crate::integrate::{Failure, FixedStep, MethodInfo, MethodKind, Stats};

/// The method, with the acceleration at the current state cached between steps.
#[derive(Debug, Clone, Default)]
pub struct StormerVerlet {
    /// `(y, a(y))` of the last step's end.
    last: Option<(Vector3<f64>, Vector3<f64>)>,
}

impl StormerVerlet {
    pub fn new() -> Self {
        StormerVerlet { last: None }
    }
}

impl<C: Coordinates> FixedStep<ChainSystem<C>> for StormerVerlet {
    fn info(&self) -> MethodInfo {
        MethodInfo::new("stormer_verlet", MethodKind::Geometric, 2).with_symplectic(true)
    }

    fn step(
        &mut self,
        sys: &ChainSystem<C>,
        _t: f64,
        h: f64,
        x: &mut Vector6<f64>,
        stats: &mut Stats,
    ) -> Result<(), Failure> {
        let y: Vector3<f64> = x.fixed_rows::<3>(0).into_owned();
        let a0 = match self.last {
            Some((yl, al)) if yl == y => al,
            _ => {
                stats.rhs_evals += 1;
                C::accel(&sys.chain, &y)
            }
        };
        let v_half = x.fixed_rows::<3>(3) + a0 * (0.5 * h);
        let y1 = y + v_half * h;
        let a1 = C::accel(&sys.chain, &y1);
        stats.rhs_evals += 1;
        let v1 = v_half + a1 * (0.5 * h);
        *x = Vector6::new(y1[0], y1[1], y1[2], v1[0], v1[1], v1[2]);
        self.last = Some((y1, a1));
        Ok(())
    }
}
