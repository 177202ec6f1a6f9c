//! The transport protocol: a telegram of fixed length, station id, 8 data bytes and a checksum.
//!
//! Manual lines 2185–2190: "The transport protocol uses a telegram with a fixed length of 10
//! bytes": byte 0 the id, bytes 1–8 the data, byte 9 `CHKS = −SUM(byte 0 … byte 8)`, so the ten
//! bytes of a good telegram sum to 0 modulo 256.

use super::StationId;

/// Bytes in every telegram (manual line 2185).
pub const TELEGRAM_LEN: usize = 10;

/// Data bytes in a telegram: the data protocol (manual line 2226).
pub const DATA_LEN: usize = 8;

/// The 8 bytes of the data protocol.
pub type Data = [u8; DATA_LEN];

/// One telegram as it travels on the line.
pub type Telegram = [u8; TELEGRAM_LEN];

/// The checksum of the first nine bytes of a telegram: minus their sum, modulo 256.
#[inline]
pub fn checksum(head: &[u8]) -> u8 {
    head.iter()
        .fold(0u8, |sum, byte| sum.wrapping_add(*byte))
        .wrapping_neg()
}

/// The telegram carrying `data` to or from `station`.
#[inline]
pub fn encode(station: StationId, data: &Data) -> Telegram {
    let mut telegram = [0u8; TELEGRAM_LEN];
    telegram[0] = station.0;
    telegram[1..=DATA_LEN].copy_from_slice(data);
    telegram[TELEGRAM_LEN - 1] = checksum(&telegram[..TELEGRAM_LEN - 1]);
    telegram
}

/// A telegram whose checksum does not match its first nine bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BadChecksum {
    /// The checksum byte received.
    pub received: u8,
    /// The checksum of the nine bytes before it.
    pub expected: u8,
}

/// Whether the checksum of `telegram` matches: a good telegram sums to zero.
#[inline]
pub fn sums_to_zero(telegram: &Telegram) -> bool {
    let [head @ .., ninth, tenth] = telegram;
    byte_sum(u64::from_le_bytes(*head))
        .wrapping_add(*ninth)
        .wrapping_add(*tenth)
        == 0
}

/// The sum of the eight bytes of `word`, modulo 256, without taking them apart one by one:
/// adjacent bytes summed into four 16-bit lanes (each at most 510), then the lanes summed into
/// the top lane by one multiplication (at most 2,040, so no lane carries into the next).
#[inline]
fn byte_sum(word: u64) -> u8 {
    const LOW_BYTES: u64 = 0x00FF_00FF_00FF_00FF;
    let lanes = (word & LOW_BYTES) + ((word >> 8) & LOW_BYTES);
    (lanes.wrapping_mul(0x0001_0001_0001_0001) >> 48) as u8
}

/// The station id and data of a telegram, once its checksum is verified.
#[inline]
pub fn decode(telegram: &Telegram) -> Result<(StationId, &Data), BadChecksum> {
    let [station, data @ .., sum] = telegram;
    // The expected checksum is worked out only for the error.
    if !sums_to_zero(telegram) {
        return Err(BadChecksum {
            received: *sum,
            expected: checksum(&telegram[..TELEGRAM_LEN - 1]),
        });
    }
    Ok((StationId(*station), data))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn the_checksum_makes_the_telegram_sum_to_zero() {
        // Manual line 2330: "Set Controlword = 0x2F".
        let telegram = encode(StationId(1), &[0x2B, 0x40, 0x60, 0x00, 0x2F, 0, 0, 0]);
        assert_eq!(telegram[9], 0x05);
        let sum = telegram.iter().fold(0u8, |s, b| s.wrapping_add(*b));
        assert_eq!(sum, 0);
    }

    proptest! {
        #[test]
        fn the_byte_sum_is_the_sum_of_the_bytes(word: u64) {
            let sum = word.to_le_bytes().iter().fold(0u8, |s, b| s.wrapping_add(*b));
            prop_assert_eq!(byte_sum(word), sum);
        }
    }

    #[test]
    fn a_flipped_bit_is_a_bad_checksum() {
        let mut telegram = encode(StationId(1), &[0x40, 0x41, 0x60, 0, 0, 0, 0, 0]);
        telegram[3] ^= 0x01;
        assert_eq!(
            decode(&telegram),
            Err(BadChecksum {
                received: 0x1E,
                expected: 0x1D
            })
        );
    }

    proptest! {
        #[test]
        fn telegrams_round_trip(station: u8, data: [u8; 8]) {
            let telegram = encode(StationId(station), &data);
            prop_assert_eq!(decode(&telegram), Ok((StationId(station), &data)));
        }

        #[test]
        fn any_ten_bytes_decode_or_fail_without_panic(bytes: [u8; 10]) {
            let sum = bytes.iter().fold(0u8, |s, b| s.wrapping_add(*b));
            prop_assert_eq!(decode(&bytes).is_ok(), sum == 0);
        }
    }
}
