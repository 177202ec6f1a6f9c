//! Test support for the codec property tests: one way to damage a frame, shared by all of them.

use proptest::sample::Index;
use std::vec::Vec;

/// XORs `bits` into the byte `flip` picks, then cuts `frame` where `cut` picks.
pub(crate) fn damage(frame: &mut Vec<u8>, flip: Option<(Index, u8)>, cut: Option<Index>) {
    if let Some((at, bits)) = flip {
        let at = at.index(frame.len());
        frame[at] ^= bits;
    }
    if let Some(at) = cut {
        frame.truncate(at.index(frame.len()));
    }
}
