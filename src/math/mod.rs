//! Mathematical building blocks: small vector spaces, SO(3)/SE(3) maps, elliptic functions,
//! the dense LU factorisation (`lu`).
pub mod elliptic;
pub mod lu;
pub mod se3;
pub mod so3;
pub mod vector;
