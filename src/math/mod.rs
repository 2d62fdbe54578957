//! Mathematical building blocks: small vector spaces, SO(3)/SE(3) maps, elliptic functions,
//! the dense LU factorisation (`lu`), the banded one with a border (`banded`) and the
//! iteration matrix that picks between them by a system's declared pattern (`tangent`).
pub mod banded;
pub mod elliptic;
pub mod lu;
pub mod se3;
pub mod so3;
pub mod tangent;
pub mod vector;
