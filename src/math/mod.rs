//! Mathematical building blocks: small vector spaces, SO(3)/SE(3) maps, elliptic functions.
pub mod elliptic;
pub mod se3;
pub mod so3;
pub mod vector;
