//! 128-bit keys of exact inputs: the words a key is made of (every number by
//! its bit pattern), hashed at once with XXH3's 128-bit hash.
//!
//! The mesh caches look things up by such keys instead of keeping the inputs
//! (a patch's surface and options, a canonical cut's host and placement, a
//! whole mesh); equal inputs give equal keys and different ones collide with
//! probability about 2⁻¹²⁸. The words are gathered first and hashed in one
//! call: a canonical cut's key takes a third of the instructions it took fed
//! word by word to the SipHash and FxHash pair these keys were before. (A
//! region's fingerprint, `cdt::Region::fingerprint`, hashes its coordinates'
//! bytes in place with the same hash.)

/// The words of one key, gathered for [`Key::finish`].
#[derive(Default)]
pub struct Key {
    words: Vec<u64>,
}

impl Key {
    /// A key expecting about `words` words.
    pub fn with_capacity(words: usize) -> Self {
        Self {
            words: Vec::with_capacity(words),
        }
    }

    /// Adds one word.
    pub fn write(&mut self, word: u64) {
        self.words.push(word);
    }

    /// Adds a 128-bit key, as its two halves.
    pub fn write_u128(&mut self, key: u128) {
        self.words.extend([key as u64, (key >> 64) as u64]);
    }

    /// The key of the words added, in order.
    pub fn finish(&self) -> u128 {
        xxhash_rust::xxh3::xxh3_128_with_seed(bytemuck::cast_slice(&self.words), 0x5EED)
    }
}

#[cfg(test)]
mod tests {
    use super::Key;

    fn key(words: &[u64]) -> u128 {
        let mut key = Key::default();
        words.iter().for_each(|&w| key.write(w));
        key.finish()
    }

    #[test]
    fn equal_words_give_equal_keys_and_any_change_another() {
        let base = [1.5f64.to_bits(), 0, u64::MAX, (-0.0f64).to_bits()];
        assert_eq!(key(&base), key(&base));
        // Each word changed in one bit, the order changed, one word more or less.
        for i in 0..base.len() {
            for bit in [0, 31, 63] {
                let mut other = base;
                other[i] ^= 1 << bit;
                assert_ne!(key(&other), key(&base), "word {i}, bit {bit}");
            }
        }
        let mut swapped = base;
        swapped.swap(0, 1);
        assert_ne!(key(&swapped), key(&base));
        assert_ne!(key(&base[..3]), key(&base));
        assert_ne!(key(&[base.as_slice(), &[0]].concat()), key(&base));
        // 0.0 and −0.0 are different inputs.
        assert_ne!(key(&[0.0f64.to_bits()]), key(&[(-0.0f64).to_bits()]));
    }

    #[test]
    fn a_key_of_two_halves_is_the_key_of_its_words() {
        let whole = 0x0123_4567_89AB_CDEF_FEDC_BA98_7654_3210u128;
        let mut a = Key::default();
        a.write_u128(whole);
        assert_eq!(a.finish(), key(&[whole as u64, (whole >> 64) as u64]));
    }
}
