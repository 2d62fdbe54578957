//! The modal formulations of the beam (the record's `formulation` axis besides `fe_exact`),
//! each a basis of `modal.rs` and a way of keeping its constraints:
//!
//! - `modal_linear`: the case's clamped-free bending modes, no stretch and no foreshortening:
//!   every inertial term of the rotating frame is kept (the softening `-Om^2 Mqq q`, the Euler
//!   load `-Om' aq`) and only the centrifugal stiffening is lost, the "conventional" model
//!   that Kane, Ryan & Banerjee (1987) showed to diverge once the rate passes the first
//!   bending frequency;
//! - `modal_stiffened`: clamped-free bending and rod modes with the foreshortening coupling
//!   `u1 = s - 1/2 int u2'^2`, which restores the stiffening `Om^2 Kg` (Kane et al.; Ryan's
//!   imbedded geometric constraint);
//! - `aigc_*`: Haering, Ryan & Scott's augmented imbedded geometric constraint: the same
//!   kinematics on Craig-Bampton sets, the clamped-clamped beam's modes plus the four static
//!   Hermite modes (unit end displacements and slopes) for `u2`, the clamped-clamped rod's
//!   modes plus the two linear static modes for `s`, and the cantilever's boundary conditions
//!   as six linear constraints `s(0) = u2(0) = u2'(0) = 0`, `s'(L) = u2''(L) = u2'''(L) = 0`.
//!   `aigc_baumgarte` (and `_soft`, `_stiff`: the case's three `(alpha, beta)`) solves the
//!   stabilised index-1 form with the Runge-Kutta methods, `aigc_projection` the plain index-1
//!   form with an `M`-orthogonal projection after every step (`ode.rs`, `Stabilised`), and
//!   `aigc_index3` the index-3 DAE with `gen_alpha_i3`.
//!
//! The ODE forms need a fixed-size state per model size (`ode.rs`): [`ODE_SIZES`] lists the
//! registered coordinate counts, and the loader refuses mode counts outside them with the key
//! to change. Where it fails: modes far above the rod's first frequency make the explicit
//! methods' step limit the measure; `modal_linear` diverges by design.
use super::base::Base;
use super::case::Numerics;
use super::modal::{Basis, Bc, Field, Modal};
use super::ode::Stabilised;
use super::shapes::Shape;

/// Coordinate counts of the ODE forms with a registered state size (a free hub adds one).
pub const ODE_SIZES: &[usize] = &[4, 5, 6, 15, 16];

/// The constraint rows' keeping of an AIGC formulation: `(alpha, beta, project)`, or None
/// for the index-3 form (its integrator keeps them).
fn keeping(formulation: &str, n: &Numerics) -> Option<(f64, f64, bool)> {
    let b = n.baumgarte;
    match formulation {
        "aigc_baumgarte" => Some((b[0].0, b[0].1, false)),
        "aigc_baumgarte_soft" => Some((b[1].0, b[1].1, false)),
        "aigc_baumgarte_stiff" => Some((b[2].0, b[2].1, false)),
        "aigc_projection" => Some((0.0, 0.0, true)),
        _ => None,
    }
}

/// The basis of a modal formulation (None for `fe_exact`).
pub fn basis(formulation: &str, n: &Numerics) -> Option<Basis> {
    let cf_bending = (1..=n.bending_modes).map(Shape::ClampedFreeBending).collect();
    match formulation {
        "modal_linear" => Some(Basis {
            stretch: vec![],
            lateral: cf_bending,
            stiffening: false,
            constraints: vec![],
        }),
        "modal_stiffened" => Some(Basis {
            stretch: (1..=n.axial_modes).map(Shape::ClampedFreeRod).collect(),
            lateral: cf_bending,
            stiffening: true,
            constraints: vec![],
        }),
        f if f.starts_with("aigc") => Some(aigc_basis(n.cb_axial_modes, n.cb_bending_modes)),
        _ => None,
    }
}

/// The AIGC basis: `axial` clamped-clamped rod modes and the two linear static modes for the
/// stretch, `bending` clamped-clamped beam modes and the four Hermite static modes for `u2`,
/// with foreshortening, and the cantilever's six boundary conditions as constraints.
pub fn aigc_basis(axial: usize, bending: usize) -> Basis {
    let bc = |field, at_tip, derivative| Bc {
        field,
        at_tip,
        derivative,
    };
    Basis {
        stretch: (1..=axial)
            .map(Shape::ClampedClampedRod)
            .chain([Shape::Linear(0), Shape::Linear(1)])
            .collect(),
        lateral: (1..=bending)
            .map(Shape::ClampedClampedBending)
            .chain((0..4).map(Shape::Hermite))
            .collect(),
        stiffening: true,
        constraints: vec![
            bc(Field::Stretch, false, 0),
            bc(Field::Lateral, false, 0),
            bc(Field::Lateral, false, 1),
            bc(Field::Stretch, true, 1),
            bc(Field::Lateral, true, 2),
            bc(Field::Lateral, true, 3),
        ],
    }
}

/// The coordinate count of a modal formulation on a prescribed base.
pub fn size(formulation: &str, n: &Numerics) -> Option<usize> {
    basis(formulation, n).map(|b| b.stretch.len() + b.lateral.len())
}

/// Every ODE form's size (prescribed, and free with the hub) is registered; else the key to
/// change and why.
pub fn check_sizes(n: &Numerics) -> Result<(), (String, String)> {
    for (f, key) in [
        ("modal_linear", "bending_modes"),
        ("modal_stiffened", "axial_modes"),
        ("aigc_projection", "cb_bending_modes"),
    ] {
        let k = size(f, n).unwrap_or(0);
        for m in [k, k + 1] {
            if !ODE_SIZES.contains(&m) {
                return Err((
                    key.to_string(),
                    format!(
                        "gives {f} {m} coordinates, whose state size is not registered \
                         (registered: {ODE_SIZES:?}, a free hub adding one; src/model/\
                         flexible_beam/formulations.rs)"
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The model of a modal formulation on `base`, with its constraint keeping for the ODE
/// forms.
pub fn model(
    formulation: &str,
    n: &Numerics,
    beam: super::fe::Beam,
    base: Base,
) -> Result<(Modal, Option<Stabilised>), String> {
    let b = basis(formulation, n).ok_or_else(|| format!("{formulation} is not modal"))?;
    let m = Modal::new(beam, base, b)?;
    let stab = keeping(formulation, n).map(|(alpha, beta, project)| Stabilised {
        rows: m.constraint_rows().clone(),
        alpha,
        beta,
        project,
    });
    Ok((m, stab))
}

impl super::observe::Beamlike for Modal {
    fn base(&self) -> Base {
        self.base
    }
    fn tip_deflection(&self, q: &nalgebra::DVector<f64>) -> f64 {
        Modal::tip_deflection(self, q)
    }
    fn tip_axial(&self, q: &nalgebra::DVector<f64>) -> f64 {
        Modal::tip_axial(self, q)
    }
    fn hub(&self, t: f64, q: &nalgebra::DVector<f64>, v: &nalgebra::DVector<f64>) -> [f64; 2] {
        Modal::hub(self, t, q, v)
    }
    fn energy(
        &self,
        t: f64,
        q: &nalgebra::DVector<f64>,
        v: &nalgebra::DVector<f64>,
    ) -> (f64, f64) {
        Modal::energy(self, t, q, v)
    }
    fn momentum(&self, t: f64, q: &nalgebra::DVector<f64>, v: &nalgebra::DVector<f64>) -> f64 {
        Modal::momentum(self, t, q, v)
    }
    fn hub_column(&self, q: &nalgebra::DVector<f64>, col: &mut nalgebra::DVector<f64>) -> bool {
        Modal::hub_column(self, q, col);
        true
    }
    fn constraint(&self, q: &nalgebra::DVector<f64>) -> f64 {
        let r = self.constraint_rows();
        (0..r.nrows())
            .map(|i| (0..r.ncols()).map(|j| r[(i, j)] * q[j]).sum::<f64>().abs())
            .fold(0.0, f64::max)
    }
}
