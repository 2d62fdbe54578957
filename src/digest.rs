//! SHA-256 in lower-case hex: the one digest of the crate (physics and settings hashes of
//! case files, stored references, manifests of written outputs, the report's asset names).
//! A leaf module, so every layer can use it (docs/architecture.md).
//!
//! # Example
//!
//! ```
//! assert_eq!(
//!     mbdbench::digest::sha256_hex(b"abc"),
//!     "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
//! );
//! ```
use sha2::{Digest, Sha256};

/// Hex SHA-256 of bytes.
pub fn sha256_hex(bytes: &[u8]) -> String {
    let d = Sha256::digest(bytes);
    d.iter().map(|b| format!("{b:02x}")).collect()
}
