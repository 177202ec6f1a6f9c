//! The SRDO consistency rule: the inverted frame carries the bitwise complement of the normal
//! frame (SWD manual line 1661).

/// The mask of the low `bits` bits (all 64 for `bits >= 64`).
const fn low_bits(bits: u32) -> u64 {
    if bits >= 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    }
}

/// The payload as a little-endian word (at most 8 bytes; callers check lengths first).
fn word(payload: &[u8]) -> u64 {
    let mut bytes = [0u8; 8];
    let len = payload.len().min(8);
    bytes[..len].copy_from_slice(&payload[..len]);
    u64::from_le_bytes(bytes)
}

/// Whether the mapped `bits` of `inverted` are the complement of those of `normal`. Padding bits
/// past the mapping are not compared.
pub fn is_complement(normal: &[u8], inverted: &[u8], bits: u32) -> bool {
    let mask = low_bits(bits);
    (word(normal) ^ word(inverted)) & mask == mask
}

/// The inverted frame's payload for `normal`: every byte complemented.
pub fn complement(normal: &[u8]) -> [u8; 8] {
    let mut out = [0u8; 8];
    for (slot, byte) in out.iter_mut().zip(normal) {
        *slot = !byte;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quick_start_pair_is_consistent() {
        // SWD manual line 4111: 11Fh carries FFh, 120h carries 00h.
        assert!(is_complement(&[0xFF], &[0x00], 8));
        assert!(!is_complement(&[0xFF], &[0x01], 8));
        assert!(!is_complement(&[0xFF], &[0xFF], 8));
    }

    #[test]
    fn padding_is_not_compared() {
        assert!(is_complement(&[0x01], &[0x00], 1));
        assert!(!is_complement(&[0x01], &[0x01], 1));
    }

    #[test]
    fn complement_inverts_every_byte() {
        assert_eq!(complement(&[0x0F, 0xA5])[..2], [0xF0, 0x5A]);
    }
}
