//! Hashing for the EDS reader's maps (section names, snake_case names): rustc-hash's FxHasher,
//! eight bytes per step, where FNV took one byte per multiply and spent a third of a millisecond
//! on the names of a large EDS. Not meant to resist crafted collisions, which only cost time.

use std::hash::{Hash, Hasher};

use rustc_hash::FxHasher;

/// A map keyed by short texts, hashed a word at a time.
pub type WordMap<K, V> = rustc_hash::FxHashMap<K, V>;

/// A map key compared and hashed regardless of ASCII case: EDS files spell names in any case.
#[derive(Debug, Clone, Copy)]
pub struct Caseless<'t>(pub &'t str);

impl PartialEq for Caseless<'_> {
    fn eq(&self, other: &Self) -> bool {
        self.0.eq_ignore_ascii_case(other.0)
    }
}

impl Eq for Caseless<'_> {}

impl Hash for Caseless<'_> {
    fn hash<H: Hasher>(&self, state: &mut H) {
        state.write_u64(caseless_hash(self.0));
    }
}

/// A hash of `text` that ignores ASCII case: bit 5 is set on every byte first (`A` | 0x20 is `a`),
/// so texts equal regardless of case hash alike; the rare other texts that also do (`@` and `` ` ``)
/// are told apart by comparing them.
pub fn caseless_hash(text: &str) -> u64 {
    const CASE: u64 = u64::from_le_bytes([0x20; 8]);
    let mut hasher = FxHasher::default();
    for_words(text.as_bytes(), |word| hasher.write_u64(word | CASE));
    hasher.write_usize(text.len());
    hasher.finish()
}

/// Calls `f` with `bytes` as little-endian words, the last one zero-extended.
fn for_words(bytes: &[u8], mut f: impl FnMut(u64)) {
    let mut words = bytes.chunks_exact(8);
    for chunk in &mut words {
        f(word_at(chunk));
    }
    let rest = words.remainder().len();
    if rest == 0 {
        return;
    }
    // The last bytes as one load: filling a zeroed array byte by byte and reading it back as a
    // word stalled on store forwarding.
    f(match bytes.len().checked_sub(8) {
        Some(last) => word_at(&bytes[last..]) >> (8 * (8 - rest)),
        None => bytes
            .iter()
            .rev()
            .fold(0, |word, &b| word << 8 | u64::from(b)),
    });
}

/// The eight bytes of `chunk` as a little-endian word.
fn word_at(chunk: &[u8]) -> u64 {
    let mut word = [0; 8];
    word.copy_from_slice(chunk);
    u64::from_le_bytes(word)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn caseless_hashes_ignore_ascii_case_only() {
        assert_eq!(caseless_hash("1A00Sub1"), caseless_hash("1a00sub1"));
        assert_eq!(caseless_hash("DeviceInfo"), caseless_hash("DEVICEINFO"));
        assert_ne!(caseless_hash("2000"), caseless_hash("2001"));
        assert_ne!(caseless_hash("a"), caseless_hash("a "));
    }

    #[test]
    fn words_end_zero_extended() {
        let words = |bytes: &[u8]| {
            let mut out = Vec::new();
            for_words(bytes, |w| out.push(w));
            out
        };
        assert_eq!(words(b""), Vec::<u64>::new());
        assert_eq!(words(b"\x01\x02"), [0x0201]);
        assert_eq!(words(b"abcdefgh"), [u64::from_le_bytes(*b"abcdefgh")]);
        assert_eq!(
            words(b"abcdefghij"),
            [
                u64::from_le_bytes(*b"abcdefgh"),
                u64::from_le_bytes(*b"ij\0\0\0\0\0\0")
            ]
        );
    }

    #[test]
    fn texts_are_told_apart_as_keys() {
        let mut map: WordMap<&str, usize> = WordMap::default();
        let names = ["", "a", "a\0", "abcdefgh", "abcdefghi", "abcdefgh\0", "ba"];
        for (i, name) in names.iter().enumerate() {
            map.insert(name, i);
        }
        for (i, name) in names.iter().enumerate() {
            assert_eq!(map.get(name), Some(&i), "{name:?}");
        }
    }
}
