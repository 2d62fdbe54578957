//! A test-only model family, the proof of the family seam (`problem`): a chain of three masses
//! on linear springs, fixed to a wall at its left end (`k1` wall-mass 1, `k2` mass 1-2, `k3`
//! mass 2-3), `M x'' + K x = 0` with
//! `K = [[k1 + k2, -k2, 0], [-k2, k2 + k3, -k3], [0, -k3, k3]]`, `M = diag(m)`, energy
//! `E = v^T M v / 2 + x^T K x / 2`. It has an exact modal solution: with
//! `M^{-1/2} K M^{-1/2} = U diag(w^2) U^T` and the mass-normalised modes `Phi = M^{-1/2} U`,
//! the modal coordinates `q = Phi^T M x` oscillate independently,
//! `q_i(t) = q_i(0) cos(w_i t) + q_i'(0) sin(w_i t) / w_i`, and `x = Phi q`.
//!
//! Its record axes: `param` = `none` (no rotations); `formulation` = `chain_nodal` (the
//! nodal displacements and velocities) or `chain_modal` (the modal coordinates); integrator =
//! `rk4`, `dopri5` or `stormer_verlet` (`verlet.rs`, kick-drift-kick, order 2, symplectic).
//! It exists to show that a family is one folder plus one line in the family table: it
//! compiles only for the crate's own tests and with the `seam-test` feature, its case file
//! and references live under `tests/fixtures/`, and nothing outside this folder names it.
//!
//! Where it fails: stiffnesses whose modal frequencies differ by many orders of magnitude make
//! the explicit methods' step limit `w_max h < 2.8` (rk4) or `< 2` (Stormer-Verlet) the only
//! thing measured; a zero frequency (a free chain) is refused at loading (`k1 > 0`).
use nalgebra::{Matrix3, SVector, SymmetricEigen, Vector3, Vector6};

use crate::integrate::{Failure, FailureKind, System};

pub mod case;
pub mod family;
pub mod problem;
#[cfg(test)]
mod tests;
pub mod verlet;

/// The chain's matrices and its modal decomposition.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    pub masses: Vector3<f64>,
    pub k: Matrix3<f64>,
    /// `M^{-1} K`.
    pub minv_k: Matrix3<f64>,
    /// Mass-normalised modes (columns), `Phi^T M Phi = I`.
    pub phi: Matrix3<f64>,
    /// Modal frequencies (rad/s), ascending.
    pub omega: Vector3<f64>,
}

impl Chain {
    /// The chain of masses `m` (kg) and stiffnesses `k` (N/m), all positive (checked at
    /// loading).
    pub fn new(m: [f64; 3], k: [f64; 3]) -> Chain {
        let kk = Matrix3::new(
            k[0] + k[1],
            -k[1],
            0.0,
            -k[1],
            k[1] + k[2],
            -k[2],
            0.0,
            -k[2],
            k[2],
        );
        let masses = Vector3::from(m);
        let s = masses.map(|x| 1.0 / x.sqrt());
        let a = Matrix3::from_fn(|i, j| s[i] * kk[(i, j)] * s[j]);
        let eig = SymmetricEigen::new(a);
        let mut order = [0usize, 1, 2];
        order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
        let omega = Vector3::from_fn(|i, _| eig.eigenvalues[order[i]].max(0.0).sqrt());
        let phi = Matrix3::from_fn(|i, j| s[i] * eig.eigenvectors[(i, order[j])]);
        let minv_k = Matrix3::from_fn(|i, j| kk[(i, j)] / masses[i]);
        Chain {
            masses,
            k: kk,
            minv_k,
            phi,
            omega,
        }
    }

    /// `E = v^T M v / 2 + x^T K x / 2`.
    pub fn energy(&self, o: &ChainObs) -> f64 {
        0.5 * o.v.component_mul(&self.masses).dot(&o.v) + 0.5 * o.x.dot(&(self.k * o.x))
    }

    /// Modal coordinates and rates of a nodal state: `q = Phi^T M x`.
    pub fn to_modal(&self, o: &ChainObs) -> (Vector3<f64>, Vector3<f64>) {
        let pm = self.phi.transpose();
        (
            pm * o.x.component_mul(&self.masses),
            pm * o.v.component_mul(&self.masses),
        )
    }

    /// The exact state at `t` from the initial state `o0`.
    pub fn exact(&self, o0: &ChainObs, t: f64) -> ChainObs {
        let (q0, qd0) = self.to_modal(o0);
        let mut q = Vector3::zeros();
        let mut qd = Vector3::zeros();
        for i in 0..3 {
            let w = self.omega[i];
            let (s, c) = (w * t).sin_cos();
            q[i] = q0[i] * c + qd0[i] * s / w;
            qd[i] = -q0[i] * w * s + qd0[i] * c;
        }
        ChainObs {
            x: self.phi * q,
            v: self.phi * qd,
        }
    }
}

/// What a run observes: nodal displacements (m) and velocities (m/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChainObs {
    pub x: Vector3<f64>,
    pub v: Vector3<f64>,
}

/// How the equations are written.
pub trait Coordinates: Send + Sync + Clone + 'static {
    /// The `formulation` name.
    const NAME: &'static str;
    /// The state `[coordinates; rates]` of a nodal observation.
    fn state(chain: &Chain, o: &ChainObs) -> Vector6<f64>;
    /// The nodal observation of a state.
    fn observe(chain: &Chain, x: &Vector6<f64>) -> ChainObs;
    /// The acceleration of the coordinates `y`.
    fn accel(chain: &Chain, y: &Vector3<f64>) -> Vector3<f64>;
}

/// Nodal coordinates: `x'' = -M^{-1} K x`.
#[derive(Debug, Clone, Copy)]
pub struct Nodal;

/// Modal coordinates: `q'' = -w^2 q`.
#[derive(Debug, Clone, Copy)]
pub struct Modal;

impl Coordinates for Nodal {
    const NAME: &'static str = "chain_nodal";
    fn state(_: &Chain, o: &ChainObs) -> Vector6<f64> {
        Vector6::new(o.x[0], o.x[1], o.x[2], o.v[0], o.v[1], o.v[2])
    }
    fn observe(_: &Chain, x: &Vector6<f64>) -> ChainObs {
        ChainObs {
            x: x.fixed_rows::<3>(0).into_owned(),
            v: x.fixed_rows::<3>(3).into_owned(),
        }
    }
    #[inline(always)]
    fn accel(chain: &Chain, y: &Vector3<f64>) -> Vector3<f64> {
        -(chain.minv_k * y)
    }
}

impl Coordinates for Modal {
    const NAME: &'static str = "chain_modal";
    fn state(chain: &Chain, o: &ChainObs) -> Vector6<f64> {
        let (q, qd) = chain.to_modal(o);
        Vector6::new(q[0], q[1], q[2], qd[0], qd[1], qd[2])
    }
    fn observe(chain: &Chain, x: &Vector6<f64>) -> ChainObs {
        ChainObs {
            x: chain.phi * x.fixed_rows::<3>(0),
            v: chain.phi * x.fixed_rows::<3>(3),
        }
    }
    #[inline(always)]
    fn accel(chain: &Chain, y: &Vector3<f64>) -> Vector3<f64> {
        -y.component_mul(&chain.omega.component_mul(&chain.omega))
    }
}

/// The chain's equations in coordinates `C`, as a first-order `System` on `[y; y']`.
#[derive(Debug, Clone)]
pub struct ChainSystem<C: Coordinates> {
    pub chain: Chain,
    _c: std::marker::PhantomData<C>,
}

impl<C: Coordinates> ChainSystem<C> {
    pub fn new(chain: Chain) -> Self {
        ChainSystem {
            chain,
            _c: std::marker::PhantomData,
        }
    }
}

impl<C: Coordinates> System for ChainSystem<C> {
    type State = Vector6<f64>;
    type Tangent = SVector<f64, 6>;
    const LIE: bool = false;
    #[inline(always)]
    fn rhs(&self, _t: f64, x: &Vector6<f64>) -> Vector6<f64> {
        let a = C::accel(&self.chain, &x.fixed_rows::<3>(0).into_owned());
        Vector6::new(x[3], x[4], x[5], a[0], a[1], a[2])
    }
    #[inline(always)]
    fn retract(&self, x: &Vector6<f64>, dx: &Vector6<f64>) -> Vector6<f64> {
        x + dx
    }
    fn check(&self, t: f64, x: &Vector6<f64>) -> Result<(), Failure> {
        if x.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(Failure::new(FailureKind::NonFinite, t, "non-finite chain state"))
        }
    }
}

impl<C: Coordinates> crate::run::Observable for ChainSystem<C> {
    type Obs = ChainObs;
    fn observe(&self, x: &Vector6<f64>) -> ChainObs {
        C::observe(&self.chain, x)
    }
    fn residual(&self, _x: &Vector6<f64>) -> Option<f64> {
        None
    }
    fn energy(&self, o: &ChainObs) -> f64 {
        self.chain.energy(o)
    }
}

/// Hairer's componentwise scale: every component is additive.
impl<C: Coordinates> crate::integrate::adaptive_rk::ErrorScale for ChainSystem<C> {
    #[inline(always)]
    fn coords(&self, x: &Vector6<f64>) -> Vector6<f64> {
        *x
    }
}
