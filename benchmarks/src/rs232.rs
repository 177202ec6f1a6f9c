//! The floor of the Kinco RS-232 benchmark: the least a host must do to send an upload
//! (read) telegram and accept its answer, by hand: bytes stored in place, the checksum summed in
//! a loop, the answer checked field by field.

/// Encodes the upload request of `index`:`subindex` for `station`.
#[inline]
pub fn encode_upload(station: u8, index: u16, subindex: u8, out: &mut [u8; 10]) {
    let [lo, hi] = index.to_le_bytes();
    *out = [station, 0x40, lo, hi, subindex, 0, 0, 0, 0, 0];
    let mut sum = 0u8;
    for &b in &out[..9] {
        sum = sum.wrapping_add(b);
    }
    out[9] = sum.wrapping_neg();
}

/// The value of an upload answer of 1, 2 or 4 bytes, zero-extended; `None` if `frame` is not the
/// answer to the upload of `index`:`subindex` from `station`.
#[inline]
pub fn decode_upload(station: u8, index: u16, subindex: u8, frame: &[u8]) -> Option<u32> {
    let frame: &[u8; 10] = frame.try_into().ok()?;
    let mut sum = 0u8;
    for &b in frame {
        sum = sum.wrapping_add(b);
    }
    let [lo, hi] = index.to_le_bytes();
    if sum != 0 || frame[0] != station || frame[2] != lo || frame[3] != hi || frame[4] != subindex {
        return None;
    }
    let value = u32::from_le_bytes([frame[5], frame[6], frame[7], frame[8]]);
    match frame[1] {
        0x43 => Some(value),
        0x4B => Some(value & 0xFFFF),
        0x4F => Some(value & 0xFF),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_manuals_statusword_read() {
        let mut out = [0u8; 10];
        encode_upload(1, 0x6041, 0, &mut out);
        assert_eq!(out, [0x01, 0x40, 0x41, 0x60, 0, 0, 0, 0, 0, 0x1E]);
        let answer = [0x01, 0x4B, 0x41, 0x60, 0x00, 0x37, 0x04, 0, 0, 0xD8];
        assert_eq!(decode_upload(1, 0x6041, 0, &answer), Some(0x0437));
        assert_eq!(decode_upload(2, 0x6041, 0, &answer), None);
    }
}
