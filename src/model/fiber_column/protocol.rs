//! The cyclic displacement protocol of a fiber-column scene, held by its amplitudes: `cycles`
//! full cycles `0 -> +a -> -a -> 0` of each amplitude `a` in turn (a whole number of
//! increments, `drift H / increment`), one increment per unit of `t`. The top displacement at
//! an integer `t` is computed from the amplitudes when asked for ([`Protocol::at`]), so a
//! protocol of any length takes a few words of memory (it used to be expanded into a vector
//! while the case loaded: `drifts = [1.0e6]` asked for 384 GB there and aborted even
//! `mbdbench list`).
//!
//! Invariants: every amplitude is at least 1 increment and the protocol's length (its
//! increment count) is at most [`MAX_INCREMENTS`], so every index and position is an exact
//! integer in `u64`, `i64` and `f64`; `at(i)` is `u * increment` with the walk's integer
//! position `u`, bit for bit the value the expanded vector held.
//!
//! # Example
//!
//! ```
//! use mbdbench::model::fiber_column::protocol::Protocol;
//!
//! // Two cycles of 2 increments, then two of 3, 0.5 mm each.
//! let p = Protocol::new(vec![2, 3], 2, 5.0e-4).unwrap();
//! assert_eq!(p.len(), 2 * 8 + 2 * 12);
//! let walk: Vec<f64> = (0..=8).map(|i| p.at(i) / 5.0e-4).collect();
//! assert_eq!(walk, [0.0, 1.0, 2.0, 1.0, 0.0, -1.0, -2.0, -1.0, 0.0]);
//! assert_eq!(p.skipped_reversal(1), None);
//! assert_eq!(p.skipped_reversal(2), Some(16 + 3)); // the first peak of the second drift
//! ```

/// The most increments of a whole protocol: `2^53`, below which every integer is exact in
/// `f64` (the horizon `t_end` must equal the protocol's length).
pub const MAX_INCREMENTS: u64 = 1 << 53;

/// A cyclic protocol by its amplitudes (in increments).
#[derive(Debug, Clone, PartialEq)]
pub struct Protocol {
    amplitudes: Vec<u64>,
    cycles: u64,
    increment: f64,
    len: u64,
}

impl Protocol {
    /// `cycles` cycles of each of `amplitudes` (in increments) of `increment` (m) each.
    /// Errors (naming the amplitude's index) for an amplitude of 0, or when the protocol would
    /// be longer than [`MAX_INCREMENTS`].
    pub fn new(amplitudes: Vec<u64>, cycles: u64, increment: f64) -> Result<Self, String> {
        let mut len: u64 = 0;
        for (j, &a) in amplitudes.iter().enumerate() {
            if a == 0 {
                return Err(format!("amplitude {j} is 0 increments"));
            }
            len = a
                .checked_mul(4)
                .and_then(|x| x.checked_mul(cycles))
                .and_then(|x| x.checked_add(len))
                .filter(|&x| x <= MAX_INCREMENTS)
                .ok_or_else(|| {
                    format!(
                        "with amplitude {j} the protocol passes {MAX_INCREMENTS} increments \
                         (2^53)"
                    )
                })?;
        }
        Ok(Protocol {
            amplitudes,
            cycles,
            increment,
            len,
        })
    }

    /// The protocol's length in increments (its last index; `t_end`).
    pub fn len(&self) -> u64 {
        self.len
    }

    /// Whether the protocol has no increment (never, once loaded).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The displacement per increment (m).
    pub fn increment(&self) -> f64 {
        self.increment
    }

    /// The amplitudes in increments, in order.
    pub fn amplitudes(&self) -> &[u64] {
        &self.amplitudes
    }

    /// The top displacement (m) after `i` increments; `i` past the end reads the end (0).
    pub fn at(&self, i: u64) -> f64 {
        let mut rest = i.min(self.len);
        for &a in &self.amplitudes {
            let block = 4 * a * self.cycles;
            if rest < block {
                let r = (rest % (4 * a)) as i64;
                let a = a as i64;
                let u = if r <= a {
                    r
                } else if r <= 3 * a {
                    2 * a - r
                } else {
                    r - 4 * a
                };
                return u as f64 * self.increment;
            }
            rest -= block;
        }
        0.0
    }

    /// The first reversal or zero crossing (a segment end, inside the protocol) that a step
    /// of `k` increments does not land on, if any: every segment end of an amplitude's
    /// cycles is a multiple of that amplitude after the cycles before it, so a step lands on
    /// them all exactly when it divides every amplitude.
    pub fn skipped_reversal(&self, k: u64) -> Option<u64> {
        let mut offset = 0;
        for &a in &self.amplitudes {
            if k == 0 || a % k != 0 {
                return Some(offset + a);
            }
            offset += 4 * a * self.cycles;
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The walk the loader used to expand: `cycles` times `0 -> a -> -a -> 0` for each
    /// amplitude, one increment per entry.
    fn expanded(amplitudes: &[u64], cycles: u64, increment: f64) -> Vec<f64> {
        let mut out = vec![0.0];
        let mut u: i64 = 0;
        for &a in amplitudes {
            let a = a as i64;
            for _ in 0..cycles {
                for target in [a, -a, 0] {
                    while u != target {
                        u += (target - u).signum();
                        out.push(u as f64 * increment);
                    }
                }
            }
        }
        out
    }

    /// The reversals and zero crossings of an expanded walk (the run's old check).
    fn reversals(p: &[f64]) -> Vec<u64> {
        (1..p.len().saturating_sub(1))
            .filter(|&i| (p[i] - p[i - 1]) * (p[i + 1] - p[i]) <= 0.0 || p[i] == 0.0)
            .map(|i| i as u64)
            .collect()
    }

    /// The protocol by amplitudes reads, bit for bit, what the expanded walk held at every
    /// index (and its end past it), and finds the same first skipped reversal for every step.
    #[test]
    fn matches_the_expanded_walk() {
        for (amps, cycles) in [
            (vec![15u64, 30, 60, 90, 120, 180, 240], 2u64),
            (vec![1], 1),
            (vec![3, 2, 5], 3),
        ] {
            let p = Protocol::new(amps.clone(), cycles, 5.0e-4).unwrap();
            let e = expanded(&amps, cycles, 5.0e-4);
            assert_eq!(p.len() as usize + 1, e.len());
            for (i, x) in e.iter().enumerate() {
                assert_eq!(p.at(i as u64).to_bits(), x.to_bits(), "index {i}");
            }
            assert_eq!(p.at(p.len() + 7).to_bits(), e[e.len() - 1].to_bits());
            let r = reversals(&e);
            for k in 1..=40 {
                let old = r.iter().copied().find(|i| i % k != 0);
                assert_eq!(p.skipped_reversal(k), old, "step {k} of {amps:?}");
            }
        }
    }

    /// An amplitude of 0 and a protocol longer than 2^53 increments are refused, the latter
    /// without expanding anything.
    #[test]
    fn refuses_empty_and_endless_protocols() {
        assert!(Protocol::new(vec![2, 0], 1, 1.0).unwrap_err().contains("amplitude 1"));
        let e = Protocol::new(vec![1 << 50], 1_000_000, 1.0).unwrap_err();
        assert!(e.contains("2^53"), "{e}");
        assert!(Protocol::new(vec![u64::MAX], 1, 1.0).is_err());
    }
}
