//! The rigid-body model: a body with full inertia, optional geometrically exact linear
//! springs to fixed anchors, optional uniform gravity, and an optional fixed pivot; and
//! `RigidSystem<C, F>`, its Newton-Euler equations in a chosen pose chart `C` and
//! formulation `F`, as a `System` for the integrators.
//!
//! Equations (cases/README.md, "Equations solved"; Bongardt & Kirchner for the two formulations):
//! - body:    `xddot = f/m`, `J omega' = R^T tau - omega x J omega`, `R' = R [omega]x`,
//!   velocity state `(v, omega)` = (world velocity of the centre of mass, body angular velocity);
//! - spatial: `w' = J_w^{-1} (tau - w x J_w w)`, `J_w = R J R^T`, `v_s' = xddot - w' x x - w x xdot`,
//!   `R' = [w]x R`, `x' = v_s + w x x`, velocity state `(v_s, w)`, the spatial twist.
//!
//! Here `f` is the world force on the centre of mass and `tau` the world torque about the
//! reference point: the centre of mass for a free body, the pivot (world origin) for a pinned
//! one, whose `J` is then the inertia about the pivot (`J_O = J_C + m (|X|^2 I - X X^T)`) and
//! whose translation is frozen at zero. Spring `i`: `p_i = x + R b_i`, `l_i = |a_i - p_i|`,
//! `f_i = k (l_i - L0) (a_i - p_i) / l_i`; gravity `-m g0 e_z`, potential `m g0 z_com`.
//! Terms a scene does not have are absent (no springs loop, no gravity branch does work).
//! A spring of zero current length has an undefined direction: its force is then taken as 0
//! (the energy is still continuous there); no case comes near it.
pub mod baseline;
pub mod case;
pub mod family;
pub mod figures;
pub mod linear_modes;
pub mod methods;
pub mod momentum_drift;
pub mod plan;
pub mod problem;
pub mod reference;
pub mod refgen;
pub mod registry;
pub mod score;
pub mod stability;
pub mod torque_free;
pub mod trajectory_error;

use nalgebra::{Matrix3, UnitQuaternion, Vector3, Vector6};
use std::marker::PhantomData;

use crate::integrate::{Failure, FailureKind, System};
use crate::rotation::{Formulation, PoseChart};

/// A linear spring from a body point to a fixed world anchor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spring {
    /// Body-frame point, relative to the centre of mass (m).
    pub body_point: Vector3<f64>,
    /// World-frame anchor (m).
    pub anchor: Vector3<f64>,
    /// N/m.
    pub stiffness: f64,
    /// m.
    pub rest_length: f64,
}

/// A rigid body and the force elements acting on it.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidBody {
    /// kg.
    pub mass: f64,
    /// Inertia about the reference point (centre of mass, or pivot), body frame (kg m^2).
    pub inertia: Matrix3<f64>,
    /// Its inverse.
    pub inertia_inv: Matrix3<f64>,
    /// Springs (empty: no spring term).
    pub springs: Vec<Spring>,
    /// `g0` along `-z` (None: no gravity term).
    pub gravity: Option<f64>,
    /// Body-frame position of the centre of mass relative to a fixed pivot at the world origin
    /// (None: the body is free and translates).
    pub pivot_com: Option<Vector3<f64>>,
    /// False when the case gives the body no translational degrees of freedom (no mass):
    /// the translation is then frozen like a pinned body's.
    pub free_translation: bool,
}

/// The physical state of a rigid body, independent of any chart.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observation {
    pub q: UnitQuaternion<f64>,
    /// World position of the reference point (0 for a pinned body).
    pub x: Vector3<f64>,
    /// World velocity of the reference point.
    pub v: Vector3<f64>,
    /// Body angular velocity.
    pub omega: Vector3<f64>,
}

impl RigidBody {
    /// A body with inertia `inertia_com` about its centre of mass; with `pivot_com`, the
    /// stored inertia is moved to the pivot by the parallel-axis theorem.
    pub fn new(
        mass: f64,
        inertia_com: Matrix3<f64>,
        springs: Vec<Spring>,
        gravity: Option<f64>,
        pivot_com: Option<Vector3<f64>>,
    ) -> Option<Self> {
        let inertia = match pivot_com {
            Some(x) => {
                inertia_com + (Matrix3::identity() * x.norm_squared() - x * x.transpose()) * mass
            }
            None => inertia_com,
        };
        let inertia_inv = inertia.try_inverse()?;
        Some(RigidBody {
            mass,
            inertia,
            inertia_inv,
            springs,
            gravity: gravity.filter(|g| *g != 0.0),
            pivot_com,
            free_translation: true,
        })
    }

    /// The same body with its translation frozen (a case that gives it no mass).
    pub fn without_translation(mut self) -> Self {
        self.free_translation = false;
        self
    }

    /// Whether the body translates (no pivot).
    #[inline(always)]
    pub fn translates(&self) -> bool {
        self.free_translation && self.pivot_com.is_none()
    }

    /// Whether any force element acts (springs or gravity); without one the wrench is zero.
    #[inline(always)]
    pub fn loaded(&self) -> bool {
        !self.springs.is_empty() || self.gravity.is_some()
    }

    /// World force on the centre of mass and world torque about the reference point.
    ///
    /// The springs are taken in chunks of `SPRING_CHUNK`, in two passes per chunk: arms,
    /// offsets and force scales, then the sums in spring order. The `sqrt -> div` chain of one
    /// spring then no longer waits for the previous spring's sums, so the chains of a chunk
    /// overlap (and vectorize): 9 springs, quat/euler/body, 111 -> ~101 ns/step. Each number is
    /// the same expression as in a one-pass loop, and so is the order of the sums (a spring of
    /// zero length gets scale 0 and adds an exact zero).
    #[inline(always)]
    pub fn wrench(&self, r: &Matrix3<f64>, x: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        const SPRING_CHUNK: usize = 16;
        let mut f = Vector3::zeros();
        let mut tau = Vector3::zeros();
        for springs in self.springs.chunks(SPRING_CHUNK) {
            let mut rb = [Vector3::zeros(); SPRING_CHUNK];
            let mut d = [Vector3::zeros(); SPRING_CHUNK];
            let mut scale = [0.0; SPRING_CHUNK];
            for (i, s) in springs.iter().enumerate() {
                rb[i] = r * s.body_point;
                d[i] = s.anchor - (x + rb[i]);
                let l = d[i].norm();
                scale[i] = if l > 0.0 {
                    s.stiffness * (l - s.rest_length) / l
                } else {
                    0.0
                };
            }
            for i in 0..springs.len() {
                let fi = d[i] * scale[i];
                f += fi;
                tau += rb[i].cross(&fi);
            }
        }
        if let Some(g) = self.gravity {
            let fg = Vector3::new(0.0, 0.0, -self.mass * g);
            f += fg;
            if let Some(c) = self.pivot_com {
                tau += (r * c).cross(&fg);
            }
        }
        (f, tau)
    }

    /// Potential energy of the springs and of gravity.
    #[inline]
    pub fn potential(&self, r: &Matrix3<f64>, x: &Vector3<f64>) -> f64 {
        let mut e = 0.0;
        for s in &self.springs {
            let l = (s.anchor - (x + r * s.body_point)).norm();
            e += 0.5 * s.stiffness * (l - s.rest_length).powi(2);
        }
        if let Some(g) = self.gravity {
            let z = match self.pivot_com {
                Some(c) => (r * c).z,
                None => x.z,
            };
            e += self.mass * g * z;
        }
        e
    }

    /// Kinetic energy (translation only for a free body).
    #[inline]
    pub fn kinetic(&self, v: &Vector3<f64>, omega: &Vector3<f64>) -> f64 {
        let rot = 0.5 * omega.dot(&(self.inertia * omega));
        if self.translates() {
            rot + 0.5 * self.mass * v.norm_squared()
        } else {
            rot
        }
    }

    /// Total energy of an observed state.
    pub fn energy(&self, o: &Observation) -> f64 {
        let r = o.q.to_rotation_matrix().into_inner();
        self.kinetic(&o.v, &o.omega) + self.potential(&r, &o.x)
    }

    /// World angular momentum about the reference point (centre of mass, or pivot).
    pub fn angular_momentum(&self, o: &Observation) -> Vector3<f64> {
        o.q * (self.inertia * o.omega)
    }
}

/// The rigid body's equations in chart `C` and formulation `F`.
#[derive(Debug)]
pub struct RigidSystem<C: PoseChart, F: Formulation> {
    pub body: RigidBody,
    _m: PhantomData<(C, F)>,
}

// By hand: a derive would ask the chart and formulation markers to be `Clone` too.
impl<C: PoseChart, F: Formulation> Clone for RigidSystem<C, F> {
    fn clone(&self) -> Self {
        RigidSystem {
            body: self.body.clone(),
            _m: PhantomData,
        }
    }
}

/// State: the chart's pose coordinates and the velocity 6-vector `(v, omega)` (body
/// formulation: world velocity of the reference point and body angular velocity; spatial:
/// the spatial twist `(v_s, w)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidState<P: Copy> {
    pub pose: P,
    pub vel: Vector6<f64>,
}

impl<C: PoseChart, F: Formulation> RigidSystem<C, F> {
    pub fn new(body: RigidBody) -> Self {
        RigidSystem {
            body,
            _m: PhantomData,
        }
    }

    /// The state of the physical pose `(q, x)` and velocities `(v world, omega body)`.
    pub fn state_from(&self, o: &Observation) -> RigidState<C::Coords> {
        let r = o.q.to_rotation_matrix().into_inner();
        let pose = C::from_pose(&r, &o.x);
        let vel = if F::SPATIAL {
            let w = r * o.omega;
            let vs = o.v - w.cross(&o.x);
            Vector6::new(vs.x, vs.y, vs.z, w.x, w.y, w.z)
        } else {
            Vector6::new(o.v.x, o.v.y, o.v.z, o.omega.x, o.omega.y, o.omega.z)
        };
        RigidState { pose, vel }
    }

    /// The physical state of `s`.
    pub fn observe(&self, s: &RigidState<C::Coords>) -> Observation {
        let r = C::rotation(&s.pose);
        let x = C::position(&s.pose);
        let (omega, v) = self.body_velocities(&r, &x, &s.vel);
        Observation {
            q: C::quaternion(&s.pose),
            x,
            v,
            omega,
        }
    }

    /// `(omega_body, xdot)` from the velocity state.
    #[inline(always)]
    fn body_velocities(
        &self,
        r: &Matrix3<f64>,
        x: &Vector3<f64>,
        vel: &Vector6<f64>,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let v = vel.fixed_rows::<3>(0).into_owned();
        let w = vel.fixed_rows::<3>(3).into_owned();
        if F::SPATIAL {
            let xdot = if self.body.translates() {
                v + w.cross(x)
            } else {
                Vector3::zeros()
            };
            (r.transpose() * w, xdot)
        } else {
            (w, v)
        }
    }
}

impl<C: PoseChart, F: Formulation> System for RigidSystem<C, F> {
    type State = RigidState<C::Coords>;
    type Tangent = (C::Tangent, Vector6<f64>);
    const LIE: bool = C::LIE;

    #[inline(always)]
    fn rhs(&self, _t: f64, s: &Self::State) -> Self::Tangent {
        let b = &self.body;
        let r = C::rotation(&s.pose);
        let x = C::position(&s.pose);
        let (omega_b, xdot) = self.body_velocities(&r, &x, &s.vel);
        // A body without springs or gravity (free_body) has no wrench: skip it, and the
        // rotation of the torque into the body frame (in the body formulation of most charts
        // the rotation matrix is then not needed at all and is not computed).
        let loaded = b.loaded();
        let (f, tau) = if loaded {
            b.wrench(&r, &x)
        } else {
            (Vector3::zeros(), Vector3::zeros())
        };
        let xddot = if b.translates() {
            f / b.mass
        } else {
            Vector3::zeros()
        };
        // R^T tau - omega x J omega, the body-frame torque both formulations integrate.
        let gyro = -omega_b.cross(&(b.inertia * omega_b));
        let body_torque = if loaded {
            r.transpose() * tau + gyro
        } else {
            gyro
        };
        let acc = if F::SPATIAL {
            let w = s.vel.fixed_rows::<3>(3).into_owned();
            // J_w^{-1} (tau - w x J_w w) = R J^{-1} (R^T tau - omega x J omega)
            let wdot = r * (b.inertia_inv * body_torque);
            let vsdot = if b.translates() {
                xddot - wdot.cross(&x) - w.cross(&xdot)
            } else {
                Vector3::zeros()
            };
            Vector6::new(vsdot.x, vsdot.y, vsdot.z, wdot.x, wdot.y, wdot.z)
        } else {
            let od = b.inertia_inv * body_torque;
            Vector6::new(xddot.x, xddot.y, xddot.z, od.x, od.y, od.z)
        };
        (C::velocity(&s.pose, &r, &omega_b, &xdot, F::SPATIAL), acc)
    }

    #[inline(always)]
    fn retract(&self, s: &Self::State, d: &Self::Tangent) -> Self::State {
        RigidState {
            pose: C::retract(&s.pose, &d.0, F::SPATIAL),
            vel: s.vel + d.1,
        }
    }

    #[inline(always)]
    fn dexp_inv(&self, theta: &Self::Tangent, v: &Self::Tangent) -> Self::Tangent {
        if C::LIE {
            (C::dexp_inv(&theta.0, &v.0, F::SPATIAL), v.1)
        } else {
            *v
        }
    }

    /// The chart's fused retraction and correction (`PoseChart::retract_dexp_inv`) where it
    /// has one: the numbers of `retract`, `rhs` and `dexp_inv` apart.
    #[inline(always)]
    fn rkmk_stage(
        &self,
        t: f64,
        s: &Self::State,
        theta: &Self::Tangent,
    ) -> (Self::State, Self::Tangent, Self::Tangent) {
        if !C::FUSED_RETRACT_DEXP_INV {
            let y = self.retract(s, theta);
            let v = self.rhs(t, &y);
            return (y, v, self.dexp_inv(theta, &v));
        }
        let (pose, dexp_inv) = C::retract_dexp_inv(&s.pose, &theta.0, F::SPATIAL);
        let y = RigidState {
            pose,
            vel: s.vel + theta.1,
        };
        let v = self.rhs(t, &y);
        let k = if C::LIE { (dexp_inv(&v.0), v.1) } else { v };
        (y, v, k)
    }

    #[inline(always)]
    fn normalize(&self, s: &mut Self::State) -> bool {
        C::NORMALIZES && C::normalize(&mut s.pose)
    }

    #[inline]
    fn check(&self, t: f64, s: &Self::State) -> Result<(), Failure> {
        self.check_conditioning(t, s).map(|_| ())
    }

    #[inline]
    fn check_conditioning(&self, t: f64, s: &Self::State) -> Result<f64, Failure> {
        if !C::is_finite(&s.pose) || !s.vel.iter().all(|v| v.is_finite()) {
            return Err(Failure::new(
                FailureKind::NonFinite,
                t,
                "state has a non-finite component",
            ));
        }
        let c = self.conditioning(s);
        if c <= 1e-12 {
            return Err(Failure::new(
                FailureKind::SingularChart,
                t,
                format!("{} chart conditioning {c:.3e} <= 1e-12", C::NAME),
            ));
        }
        Ok(c)
    }

    #[inline(always)]
    fn conditioning(&self, s: &Self::State) -> f64 {
        C::conditioning(&s.pose)
    }
}

impl RigidBody {
    /// The angular-momentum components this body conserves, and `|L|` for scaling: every
    /// world component of `L` about the centre of mass for a torque-free body; for a pinned
    /// body under gravity the vertical world component about the pivot and, when the body is
    /// axisymmetric about the axis through the pivot and the centre of mass, the spin
    /// `J_C,aa Omega_a` about that axis (Lagrange top); none with springs. Returns the number of
    /// components written into the array.
    pub fn conserved_momenta(&self, o: &Observation) -> ([f64; 4], usize, f64) {
        let l = self.angular_momentum(o);
        let mut out = [0.0; 4];
        if !self.springs.is_empty() {
            return (out, 0, l.norm());
        }
        match (self.gravity, self.pivot_com) {
            (None, _) => {
                out[..3].copy_from_slice(l.as_slice());
                (out, 3, l.norm())
            }
            (Some(_), Some(c)) => {
                out[0] = l.z;
                let mut n = 1;
                if let Some(axis) = self.symmetry_axis(&c) {
                    out[1] = (self.inertia * o.omega).dot(&axis);
                    n = 2;
                }
                (out, n, l.norm())
            }
            (Some(_), None) => {
                // Free fall: L about the centre of mass is conserved.
                out[..3].copy_from_slice(l.as_slice());
                (out, 3, l.norm())
            }
        }
    }

    /// The unit axis through the pivot and the centre of mass when the inertia about the pivot
    /// is axisymmetric about it (then the spin about it is conserved), else None.
    fn symmetry_axis(&self, com: &Vector3<f64>) -> Option<Vector3<f64>> {
        let n = com.norm();
        if n == 0.0 {
            return None;
        }
        let a = com / n;
        // Axisymmetric about `a`: J a parallel to a and J equal on the plane normal to a.
        let ja = self.inertia * a;
        let along = ja.dot(&a);
        if (ja - a * along).norm() > 1e-12 * self.inertia.norm() {
            return None;
        }
        let p = if a.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let u = (p - a * a.dot(&p)).normalize();
        let v = a.cross(&u);
        let (juu, jvv, juv) = (
            u.dot(&(self.inertia * u)),
            v.dot(&(self.inertia * v)),
            u.dot(&(self.inertia * v)),
        );
        let s = self.inertia.norm();
        if (juu - jvv).abs() <= 1e-12 * s && juv.abs() <= 1e-12 * s {
            Some(a)
        } else {
            None
        }
    }
}

impl<C: PoseChart, F: Formulation> crate::run::Observable for RigidSystem<C, F> {
    type Obs = Observation;
    fn observe(&self, s: &Self::State) -> Observation {
        RigidSystem::observe(self, s)
    }
    fn residual(&self, s: &Self::State) -> Option<f64> {
        C::residual(&s.pose)
    }
    fn energy(&self, o: &Observation) -> f64 {
        self.body.energy(o)
    }
    fn attitude(o: &Observation) -> Option<UnitQuaternion<f64>> {
        Some(o.q)
    }
}
