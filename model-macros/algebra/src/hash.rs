//! The hash maps and sets of the compiler: keyed by a fast, deterministic hash.
//!
//! The compiler's maps are keyed by its own interned nodes and ids, never by anything an
//! attacker chooses against a running service, so the standard library's SipHash (built to
//! resist hash flooding) buys nothing here and costs a large share of compiling a big model
//! (the 20-link chain spent a fifth of its compile time hashing). This is the multiplicative
//! hash rustc uses for the same purpose (FxHash): one rotate, xor and multiply per word.

use std::hash::{BuildHasherDefault, Hasher};

/// A `HashMap` with [`FxHasher`].
pub type HashMap<K, V> = std::collections::HashMap<K, V, BuildHasherDefault<FxHasher>>;

/// A `HashSet` with [`FxHasher`].
pub type HashSet<T> = std::collections::HashSet<T, BuildHasherDefault<FxHasher>>;

/// The hash state: one word, mixed by a rotate, an xor and a multiplication per word written.
#[derive(Clone, Copy, Debug, Default)]
pub struct FxHasher {
    hash: u64,
}

/// An odd constant with well-spread bits (from rustc's `FxHasher`).
const SEED: u64 = 0x51_7c_c1_b7_27_22_0a_95;

impl FxHasher {
    #[inline]
    fn add(&mut self, word: u64) {
        self.hash = (self.hash.rotate_left(5) ^ word).wrapping_mul(SEED);
    }
}

impl Hasher for FxHasher {
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        let mut chunks = bytes.chunks_exact(8);
        for chunk in &mut chunks {
            self.add(u64::from_le_bytes(chunk.try_into().unwrap_or_default()));
        }
        let rest = chunks.remainder();
        if !rest.is_empty() {
            let mut word = [0u8; 8];
            word[..rest.len()].copy_from_slice(rest);
            self.add(u64::from_le_bytes(word));
        }
    }

    #[inline]
    fn write_u8(&mut self, i: u8) {
        self.add(i as u64);
    }

    #[inline]
    fn write_u16(&mut self, i: u16) {
        self.add(i as u64);
    }

    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.add(i as u64);
    }

    #[inline]
    fn write_u64(&mut self, i: u64) {
        self.add(i);
    }

    #[inline]
    fn write_usize(&mut self, i: usize) {
        self.add(i as u64);
    }

    #[inline]
    fn finish(&self) -> u64 {
        self.hash
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::{BuildHasher, Hash};

    fn hash<T: Hash>(value: &T) -> u64 {
        BuildHasherDefault::<FxHasher>::default().hash_one(value)
    }

    #[test]
    fn equal_values_hash_equally_and_neighbours_apart() {
        assert_eq!(hash(&(3u32, [1u8, 2, 3])), hash(&(3u32, [1u8, 2, 3])));
        let hashes: HashSet<u64> = (0u32..1000).map(|i| hash(&i)).collect();
        assert_eq!(hashes.len(), 1000);
        assert_ne!(hash(&vec![1u8; 9]), hash(&vec![1u8; 10]));
    }
}
