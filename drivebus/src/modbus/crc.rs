//! CRC-16/MODBUS (poly 0xA001 reflected, init 0xFFFF), sent low byte first.
//!
//! The `crc` crate defines the algorithm (its `CRC_16_MODBUS` catalogue entry) and computes, at
//! compile time, the slice-by-16 tables used here. The combining loop is local: the crate's generic
//! `checksum` spends a fixed ~15 instructions per call on reflecting its initial and final values,
//! which doubled the cost of the 5–8 byte frames most Modbus traffic consists of. The tests check
//! this loop against the crate's own `checksum` for every length up to a full ADU.

use crc::{Crc, Table, CRC_16_MODBUS};

/// The crate's reference implementation, used to build the tables (and in tests).
const REFERENCE: Crc<u16, Table<1>> = Crc::<u16, Table<1>>::new(&CRC_16_MODBUS);

/// `TABLES[k][b]`: the CRC register after byte `b` and then `k` zero bytes, starting from zero.
static TABLES: [[u16; 256]; 16] = tables();

const fn tables() -> [[u16; 256]; 16] {
    let zeros = [0u8; 16];
    let mut tables = [[0u16; 256]; 16];
    let mut k = 0;
    while k < 16 {
        let mut b = 0;
        while b < 256 {
            let mut digest = REFERENCE.digest_with_initial(0);
            digest.update(&[b as u8]);
            let (tail, _) = zeros.split_at(k);
            digest.update(tail);
            tables[k][b] = digest.finalize();
            b += 1;
        }
        k += 1;
    }
    tables
}

/// The CRC-16/MODBUS of `data` (polynomial 0xA001 reflected, from 0xFFFF), sent low byte first.
#[inline]
pub fn crc16_modbus(data: &[u8]) -> u16 {
    let t = &TABLES;
    let mut crc: u16 = 0xFFFF;
    let mut blocks = data.chunks_exact(16);
    for c in &mut blocks {
        let lo = usize::from(c[0] ^ crc as u8);
        let hi = usize::from(c[1] ^ (crc >> 8) as u8);
        let at = |k: usize| usize::from(c[k]);
        crc = t[15][lo]
            ^ t[14][hi]
            ^ t[13][at(2)]
            ^ t[12][at(3)]
            ^ t[11][at(4)]
            ^ t[10][at(5)]
            ^ t[9][at(6)]
            ^ t[8][at(7)]
            ^ t[7][at(8)]
            ^ t[6][at(9)]
            ^ t[5][at(10)]
            ^ t[4][at(11)]
            ^ t[3][at(12)]
            ^ t[2][at(13)]
            ^ t[1][at(14)]
            ^ t[0][at(15)];
    }
    fold_short(crc, blocks.remainder())
}

/// The CRC register after `bytes` (fewer than 16), starting from `crc`, by slicing as many bytes
/// as there are: the lookups are independent of each other, so a short frame costs one lookup's
/// latency instead of one per byte (a byte-wise loop chains one table load per byte, which
/// dominated the cost of the 5–8 byte frames most Modbus traffic consists of).
#[inline]
fn fold_short(crc: u16, bytes: &[u8]) -> u16 {
    let [lo, hi] = crc.to_le_bytes();
    match bytes {
        [] => crc,
        // The register's high byte is shifted down, not consumed.
        [only] => (crc >> 8) ^ TABLES[0][usize::from(only ^ lo)],
        [first, second, rest @ ..] => {
            let mut folded = TABLES[rest.len() + 1][usize::from(first ^ lo)]
                ^ TABLES[rest.len()][usize::from(second ^ hi)];
            // The last byte is followed by no zero bytes, the one before it by one, ...
            for (zeros, &byte) in rest.iter().rev().enumerate() {
                folded ^= TABLES[zeros][usize::from(byte)];
            }
            folded
        }
    }
}

/// Whether `frame` ends in the correct CRC of the bytes before it.
#[inline]
pub fn check(frame: &[u8]) -> bool {
    match frame.len().checked_sub(2) {
        Some(body) if body > 0 => {
            crc16_modbus(&frame[..body]).to_le_bytes() == [frame[body], frame[body + 1]]
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn matches_the_catalogue_check_value_and_a_known_frame() {
        assert_eq!(crc16_modbus(b"123456789"), 0x4B37);
        // Read 1 holding register at 0 from unit 1: the textbook frame 01 03 00 00 00 01 84 0A.
        assert_eq!(
            crc16_modbus(&[1, 3, 0, 0, 0, 1]).to_le_bytes(),
            [0x84, 0x0A]
        );
        assert!(check(&[1, 3, 0, 0, 0, 1, 0x84, 0x0A]));
        assert!(!check(&[1, 3, 0, 0, 0, 1, 0x0A, 0x84]));
        assert!(!check(&[0x84, 0x0A]));
    }

    #[test]
    fn agrees_with_the_crc_crate_for_every_length() {
        let data: std::vec::Vec<u8> = (0..300u32).map(|i| (i * 37 + 11) as u8).collect();
        for len in 0..=data.len() {
            assert_eq!(
                crc16_modbus(&data[..len]),
                REFERENCE.checksum(&data[..len]),
                "{len}"
            );
        }
    }

    proptest! {
        #[test]
        fn agrees_with_the_crc_crate(data in proptest::collection::vec(any::<u8>(), 0..600)) {
            prop_assert_eq!(crc16_modbus(&data), REFERENCE.checksum(&data));
        }
    }
}
