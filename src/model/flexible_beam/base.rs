//! The motion of the beam's base. Prescribed: the spin-up law of Kane, Ryan & Banerjee
//! (J. Guidance 10(2), 1987, eq. 58),
//!
//! ```text
//! theta(t) = (W/T) [t^2/2 + (T/(2 pi))^2 (cos(2 pi t/T) - 1)]     for t < T,
//! theta(t) = W (t - T/2)                                         for t >= T,
//! ```
//!
//! whose rate rises smoothly from 0 to `W` over `[0, T]` and whose acceleration
//! `(W/T)(1 - cos(2 pi t/T))` is continuous at `T` with its derivative jumping there (so `T` is
//! a breakpoint of the scenes: fixed steps divide it, adaptive runs restart there). Free: a
//! rigid hub of inertia `J_hub` about the fixed axis, driven by a torque `torque` on
//! `[0, t_off)` and by nothing after (the hub angle is then a coordinate of the model).
//!
//! Invariants: `theta`, `rate` and `accel` are exact derivatives of each other (tested by
//! differences) and continuous at `T`.

use std::f64::consts::PI;

/// How the base moves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Base {
    /// Prescribed spin-up to the rate `w` (rad/s) over `t_up` (s).
    SpinUp { w: f64, t_up: f64 },
    /// A free hub of inertia `j_hub` (kg m^2) with torque `torque` (N m) on `[0, t_off)`.
    Free { j_hub: f64, torque: f64, t_off: f64 },
}

/// The base angle, rate and acceleration at `t` of a prescribed motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    pub theta: f64,
    pub rate: f64,
    pub accel: f64,
}

impl Base {
    /// The prescribed motion at `t` (None for a free hub).
    ///
    /// # Example
    ///
    /// ```
    /// use mbdbench::model::flexible_beam::base::Base;
    ///
    /// let b = Base::SpinUp { w: 4.0, t_up: 15.0 };
    /// let m = b.motion(15.0).unwrap();
    /// assert!((m.rate - 4.0).abs() < 1e-12 && m.accel.abs() < 1e-12);
    /// assert!((m.theta - 4.0 * 7.5).abs() < 1e-12);
    /// ```
    pub fn motion(&self, t: f64) -> Option<Motion> {
        match *self {
            Base::SpinUp { w, t_up } => Some(if t < t_up {
                let k = 2.0 * PI / t_up;
                let (s, c) = (k * t).sin_cos();
                Motion {
                    theta: (w / t_up) * (0.5 * t * t + (c - 1.0) / (k * k)),
                    rate: (w / t_up) * (t - s / k),
                    accel: (w / t_up) * (1.0 - c),
                }
            } else {
                Motion {
                    theta: w * (t - 0.5 * t_up),
                    rate: w,
                    accel: 0.0,
                }
            }),
            Base::Free { .. } => None,
        }
    }

    /// The torque on a free hub at `t` (0 for a prescribed base).
    pub fn torque(&self, t: f64) -> f64 {
        match *self {
            Base::Free { torque, t_off, .. } if t < t_off => torque,
            _ => 0.0,
        }
    }

    /// The times where the motion's derivatives jump: `T` of the spin-up, `t_off` of the hub.
    /// The base as it acts on the segment `[a, b)` between two breakpoints: a free hub's
    /// torque made constant at its value there, so that no evaluation at the segment's end
    /// (an implicit step's end point, a Runge-Kutta stage) sees the next segment's torque;
    /// a prescribed motion is itself (it is continuous with its rate and acceleration).
    pub fn on_segment(&self, a: f64, b: f64) -> Base {
        match *self {
            Base::Free { j_hub, .. } => Base::Free {
                j_hub,
                torque: self.torque(0.5 * (a + b)),
                t_off: f64::INFINITY,
            },
            s => s,
        }
    }

    pub fn breakpoint(&self) -> f64 {
        match *self {
            Base::SpinUp { t_up, .. } => t_up,
            Base::Free { t_off, .. } => t_off,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rate is the derivative of the angle and the acceleration that of the rate
    /// (central differences, before and after T), and all three are continuous at T.
    #[test]
    fn derivatives_agree_and_are_continuous() {
        let b = Base::SpinUp { w: 6.0, t_up: 15.0 };
        let h = 1e-5;
        for t in [0.3, 4.0, 7.5, 11.0, 14.9, 15.5, 19.0] {
            let (m, p, q) = (
                b.motion(t).unwrap(),
                b.motion(t + h).unwrap(),
                b.motion(t - h).unwrap(),
            );
            assert!(
                ((p.theta - q.theta) / (2.0 * h) - m.rate).abs() < 1e-8,
                "t {t}"
            );
            assert!(
                ((p.rate - q.rate) / (2.0 * h) - m.accel).abs() < 1e-8,
                "t {t}"
            );
        }
        let (a, c) = (b.motion(15.0 - 1e-12).unwrap(), b.motion(15.0).unwrap());
        assert!((a.theta - c.theta).abs() < 1e-9);
        assert!((a.rate - c.rate).abs() < 1e-9);
        assert!((a.accel - c.accel).abs() < 1e-9);
        assert_eq!(b.motion(0.0).unwrap().theta, 0.0);
    }

    /// The hub torque acts on [0, t_off) only.
    #[test]
    fn torque_switches_off() {
        let b = Base::Free {
            j_hub: 130.0,
            torque: 0.1,
            t_off: 5.0,
        };
        assert_eq!(b.torque(4.999), 0.1);
        assert_eq!(b.torque(5.0), 0.0);
        assert!(b.motion(1.0).is_none());
    }
}
