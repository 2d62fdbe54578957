//! The cantilever fiber column (cases/README.md, "fiber_column"): a column of force-based or
//! displacement-based fiber elements in a 3-D corotational frame whose nodal rotations are
//! held in a rotation chart, with hysteretic fiber materials, under static load or
//! displacement control and under a ground-acceleration pulse.
//!
//! Files: `material/` the uniaxial fiber materials (OpenSees' `Concrete01`, `Concrete02`,
//! `Steel01`, `Steel02` and a linear elastic one) with trial, committed and reverted state;
//! `elastica.rs` the exact large-deflection cantilever (Bisshopp & Drucker) and the roll-up's
//! circle, the static scenes' references.
//!
//! The family is not yet in the family table (`model::families!`): its pieces are built
//! and tested here first.
pub mod elastica;
pub mod material;
