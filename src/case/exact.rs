//! Fixed-length arrays in case files are exactly that length. serde's `[T; N]` reads the first
//! `N` elements of a TOML array and drops the rest without a word, whatever their type
//! (`euler_xyz = [0.5, 0.0, 0.3, 99.0, "junk", [1, 2]]` loaded as `[0.5, 0.0, 0.3]`, a 4-row
//! inertia as its first 3 rows); the functions here, used with `#[serde(deserialize_with)]` on
//! a case schema's fields, count every element and refuse any other length with serde's
//! `invalid length N, expected an array of length M`, which the case loader reports
//! with the key path.
//!
//! # Example
//!
//! ```
//! #[derive(serde::Deserialize)]
//! struct S {
//!     #[serde(deserialize_with = "mbdbench::case::exact::array")]
//!     v: [f64; 3],
//! }
//! assert!(toml::from_str::<S>("v = [1.0, 2.0, 3.0]").is_ok());
//! let e = toml::from_str::<S>("v = [1.0, 2.0, 3.0, 4.0]").err().unwrap();
//! assert!(e.to_string().contains("invalid length 4"));
//! ```
use serde::de::{self, Deserialize, Deserializer, IgnoredAny, SeqAccess, Visitor};
use std::marker::PhantomData;

/// An array of exactly `N` elements.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exact<T, const N: usize>(pub [T; N]);

struct ExactVisitor<T, const N: usize>(PhantomData<T>);

impl<'de, T: Deserialize<'de>, const N: usize> Visitor<'de> for ExactVisitor<T, N> {
    type Value = Exact<T, N>;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "an array of length {N}")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut v = Vec::with_capacity(N);
        while v.len() < N {
            match seq.next_element::<T>()? {
                Some(x) => v.push(x),
                None => return Err(de::Error::invalid_length(v.len(), &self)),
            }
        }
        // Count what follows, of any type, so the error says how long the array was.
        let mut extra = 0;
        while seq.next_element::<IgnoredAny>()?.is_some() {
            extra += 1;
        }
        if extra > 0 {
            return Err(de::Error::invalid_length(N + extra, &self));
        }
        match v.try_into() {
            Ok(a) => Ok(Exact(a)),
            Err(v) => Err(de::Error::invalid_length(v.len(), &self)),
        }
    }
}

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Exact<T, N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_seq(ExactVisitor::<T, N>(PhantomData))
    }
}

/// `[T; N]` from an array of exactly `N` elements.
pub fn array<'de, D: Deserializer<'de>, T: Deserialize<'de>, const N: usize>(
    d: D,
) -> Result<[T; N], D::Error> {
    Exact::<T, N>::deserialize(d).map(|e| e.0)
}

/// An optional `[T; N]` (with `#[serde(default)]`).
pub fn option_array<'de, D: Deserializer<'de>, T: Deserialize<'de>, const N: usize>(
    d: D,
) -> Result<Option<[T; N]>, D::Error> {
    Option::<Exact<T, N>>::deserialize(d).map(|o| o.map(|e| e.0))
}

/// An `N x N` matrix (rows), every row exactly `N` long.
pub fn matrix<'de, D: Deserializer<'de>, const N: usize>(d: D) -> Result<[[f64; N]; N], D::Error> {
    Exact::<Exact<f64, N>, N>::deserialize(d).map(|m| m.0.map(|r| r.0))
}

/// An optional `N x N` matrix (with `#[serde(default)]`).
pub fn option_matrix<'de, D: Deserializer<'de>, const N: usize>(
    d: D,
) -> Result<Option<[[f64; N]; N]>, D::Error> {
    Option::<Exact<Exact<f64, N>, N>>::deserialize(d).map(|o| o.map(|m| m.0.map(|r| r.0)))
}
