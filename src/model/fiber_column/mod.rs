//! The cantilever fiber column (cases/README.md, "fiber_column"): a column of force-based or
//! displacement-based fiber elements in a 3-D corotational frame whose nodal rotations are
//! held in a rotation chart (the `param` axis: the rotation module's `RotationChart`s
//! `so3`, `quat_proj`, `rotvec`, `matrix_proj`), with hysteretic fiber materials, under static load or
//! displacement control and under a ground-acceleration pulse.
//!
//! Files, bottom up: `material/` the uniaxial fiber materials (OpenSees' `Concrete01`,
//! `Concrete02`, `Steel01`, `Steel02` and a linear elastic one) with trial, committed and
//! reverted state; `section.rs` the fiber and elastic sections and `layout.rs` their patches
//! and bar layers; `quadrature.rs` the Lobatto and Legendre points; `basic.rs` the
//! force-based and displacement-based elements in their basic system; `corotational.rs` the
//! 3-D corotational transformation; `column.rs` the assembled cantilever as a path-dependent
//! structure of the structural module (its steps solved by `structural::equilibrium`'s
//! Newton, line search or Krylov-accelerated Newton); `dynamic.rs` the ground-motion scene as
//! a system of the structural methods (`newmark`, `hht`, `gen_alpha`, `midpoint`: the
//! structural module's; the energy books; `omega1`);
//! `elastica.rs` the exact large-deflection cantilever (Bisshopp & Drucker) and the roll-up's circle, the
//! static scenes' references. `column_tests.rs` checks the column against the elastica and
//! the roll-up, `rc_tests.rs` and `pulse_tests.rs` against the stored OpenSees runs of the
//! RC column (cyclic, and under the ground-acceleration pulse with Newmark's rule), and
//! `dynamic_tests.rs` the four schemes' pulse runs, energy balances and orders.
//!
//! The family's line in the table is `family.rs`; `case.rs` reads its case files (a cyclic
//! scene's displacement protocol kept by its amplitudes, `protocol.rs`),
//! `run.rs` runs a static or cyclic scene and `run_dynamic.rs` the pulse, `problem.rs` scores it behind the `Problem` seam against
//! `reference.rs`'s references (the exact ones cross-checked by `shooting.rs`; the external
//! ones, OpenSees' runs, checked by `opensees.rs` and compared with the case's model field by
//! field by `opensees_model.rs`); `estimate.rs` says what a run of a scene needs (its
//! budgets) and `meter.rs` holds a run to them.
pub mod basic;
pub mod case;
#[cfg(test)]
mod case_tests;
pub mod column;
#[cfg(test)]
mod column_tests;
pub mod corotational;
pub mod dynamic;
#[cfg(test)]
mod dynamic_tests;
pub mod elastica;
#[cfg(test)]
mod elastica_opensees_tests;
pub mod estimate;
pub mod family;
pub mod layout;
pub mod material;
pub mod meter;
pub mod opensees;
pub mod opensees_model;
#[cfg(test)]
mod opensees_model_tests;
pub mod problem;
pub mod protocol;
#[cfg(test)]
mod pulse_tests;
pub mod quadrature;
pub mod reference;
#[cfg(test)]
mod reference_tests;
pub mod run;
pub mod run_dynamic;
#[cfg(test)]
mod rc_tests;
pub mod section;
pub mod shooting;
