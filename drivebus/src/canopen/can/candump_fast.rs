//! One pass over a well-formed candump line (issue 33: `drivegen trace` reads millions).
//!
//! Each byte is looked at once: candump's own timestamp (`(1700000000.123456)`) is read eight
//! digits at a time, the interface is skipped, the identifier and the data's hex pairs go
//! straight to numbers, and the line's end is found where the frame ends, so a log read from a
//! buffer needs no separate search for each newline. Anything else — a malformed line, a
//! timestamp of over 13 digits of seconds, a line without an interface, a CAN FD frame, text
//! after the frame — gives `None`, and [`super::candump::parse_line`] parses the line field by
//! field, which names the error: what this pass accepts, it reads as that parser does.
//!
//! Its steps are `#[inline(always)]`: called one from the other, each returned its record
//! through memory (45 instructions of a line's 800, by callgrind).

use super::candump::{Record, HEX, INVALID};
use crate::canopen::frame::CanFrame;

/// Digits of seconds this pass takes: 13 (up to year 318,857) keep the microseconds within a
/// `u64` without a checked operation per digit.
const MAX_SECONDS_DIGITS: usize = 13;
/// Digits of the fraction of a second, as the field parser takes them.
const MAX_FRACTION_DIGITS: usize = 6;
/// `10^(6 - n)` for a fraction of `n` digits.
const FRACTION_SCALE: [u64; 7] = [1_000_000, 100_000, 10_000, 1_000, 100, 10, 1];

/// A trimmed line that is not a comment, if it is a compact frame (`123#00`) or a log line
/// (`(1700000000.123456) can0 123#00`) in the forms of candump's output.
pub(super) fn parse_well_formed(line: &[u8]) -> Option<Record> {
    let (record, end) = parse_prefix(line)?;
    (end == line.len()).then_some(record)
}

/// The line at the start of `buf` if it is one [`parse_well_formed`] takes, ended by `\n` or
/// `\r\n` within `buf`: its record and the bytes it takes, line end included. `None` leaves
/// the line to be found and parsed whole.
pub(super) fn parse_line_at(buf: &[u8]) -> Option<(Record, usize)> {
    let (record, end) = parse_prefix(buf)?;
    match buf.get(end..)? {
        [b'\n', ..] => Some((record, end + 1)),
        [b'\r', b'\n', ..] => Some((record, end + 2)),
        _ => None,
    }
}

/// A record at the start of `text` and the index after its frame's last byte. Nothing in the
/// part it takes is a line break, so the caller decides from the byte after it where the line
/// ends.
#[inline(always)]
fn parse_prefix(text: &[u8]) -> Option<(Record, usize)> {
    if text.first() != Some(&b'(') {
        let (frame, end) = parse_compact(text)?;
        let record = Record {
            timestamp_us: None,
            frame,
        };
        return Some((record, end));
    }
    let (timestamp_us, close) = scan_timestamp(text)?;
    let start = frame_start(text, close + 1)?;
    let (frame, len) = parse_compact(text.get(start..)?)?;
    let record = Record {
        timestamp_us: Some(timestamp_us),
        frame,
    };
    Some((record, start + len))
}

/// The value of a hex digit.
fn nibble(byte: u8) -> Option<u8> {
    match HEX[byte as usize] {
        INVALID => None,
        value => Some(value),
    }
}

/// The value of a decimal digit.
fn decimal(byte: u8) -> Option<u64> {
    byte.is_ascii_digit().then(|| u64::from(byte - b'0'))
}

/// Sums the decimal digits of `line` from `start`, at most `max` of them: the value, the
/// number of digits and the index after them. `None` if there are more than `max`.
fn digits(line: &[u8], start: usize, max: usize) -> Option<(u64, usize, usize)> {
    let mut value = 0u64;
    let mut end = start;
    while let Some(digit) = line.get(end).and_then(|&b| decimal(b)) {
        if end - start == max {
            return None;
        }
        value = value * 10 + digit;
        end += 1;
    }
    Some((value, end - start, end))
}

/// `(seconds.fraction)` at the start of `line`: the microseconds and the index of `)`.
#[inline(always)]
fn scan_timestamp(line: &[u8]) -> Option<(u64, usize)> {
    if let Some(stamp) = candump_timestamp(line) {
        return Some(stamp);
    }
    let (seconds, count, dot) = digits(line, 1, MAX_SECONDS_DIGITS)?;
    if count == 0 || line.get(dot) != Some(&b'.') {
        return None;
    }
    let (fraction, count, close) = digits(line, dot + 1, MAX_FRACTION_DIGITS)?;
    if count == 0 || line.get(close) != Some(&b')') {
        return None;
    }
    // Under 10^13 seconds, so under 10^19 + 10^6 microseconds: no overflow.
    Some((
        seconds * 1_000_000 + fraction * FRACTION_SCALE[count],
        close,
    ))
}

/// candump's own timestamp, `(SSSSSSSSSS.UUUUUU)` (ten digits of seconds until 2286): the
/// microseconds and the index of `)`, read as two words of eight digits, the seconds' first
/// eight and then their last two with the six of the fraction.
#[inline(always)]
fn candump_timestamp(line: &[u8]) -> Option<(u64, usize)> {
    let stamp: &[u8; 19] = line.get(..19)?.try_into().ok()?;
    if stamp[11] != b'.' || stamp[18] != b')' {
        return None;
    }
    let word = |at: usize| {
        let mut bytes = [0u8; 8];
        bytes.copy_from_slice(&stamp[at..at + 8]);
        u64::from_le_bytes(bytes)
    };
    // `.` and the fraction's six digits, the dot's byte and the one before it replaced by the
    // seconds' last two digits.
    let last_two = u64::from(stamp[9]) | (u64::from(stamp[10]) << 8);
    let tail = (word(10) & !0xFFFF) | last_two;
    Some((
        eight_digits(word(1))? * 100_000_000 + eight_digits(tail)?,
        18,
    ))
}

/// The number eight ASCII decimal digits write (the first in the lowest byte), if all eight
/// are digits: three multiplications instead of eight steps.
fn eight_digits(word: u64) -> Option<u64> {
    const HIGH_NIBBLES: u64 = 0xF0F0_F0F0_F0F0_F0F0;
    const ZEROS: u64 = 0x3030_3030_3030_3030;
    // Each byte 0x30-0x3F, and 0x30-0x39 once 6 is added (no carry leaves a byte: at most 0x45).
    if word & HIGH_NIBBLES != ZEROS || (word + 0x0606_0606_0606_0606) & HIGH_NIBBLES != ZEROS {
        return None;
    }
    let digits = word - ZEROS;
    // Pairs, then fours, then all eight: each step adds the higher-order half times 10^k to
    // the lower-order one's place; what a product carries past the top byte is not kept.
    let pairs = (digits.wrapping_mul(10 << 8 | 1) >> 8) & 0x00FF_00FF_00FF_00FF;
    let fours = (pairs.wrapping_mul(100 << 16 | 1) >> 16) & 0x0000_FFFF_0000_FFFF;
    Some(fours.wrapping_mul(10_000 << 32 | 1) >> 32)
}

/// The start of the frame after `(ts)` at `from`: past the separators, the interface (bytes
/// other than blanks and control characters) and the separators after it. The frame parsed
/// from there holds no separator, so it is the line's last field, the one the field parser
/// takes.
#[inline(always)]
fn frame_start(line: &[u8], from: usize) -> Option<usize> {
    let separator = |b: u8| b == b' ' || b == b'\t';
    let mut at = from;
    while separator(*line.get(at)?) {
        at += 1;
    }
    let interface = at;
    while *line.get(at)? > b' ' {
        at += 1;
    }
    let after = at;
    while separator(*line.get(at)?) {
        at += 1;
    }
    (after > interface && at > after).then_some(at)
}

/// A compact frame (`123#DEADBEEF`, `123#DE.AD`, `123#R`, `123#R8`) at the start of `text`
/// and the index after it, identifier and data taken digit by digit.
#[inline(always)]
fn parse_compact(text: &[u8]) -> Option<(CanFrame, usize)> {
    let [a, b, c, b'#', payload @ ..] = text else {
        return None;
    };
    let id = (u16::from(nibble(*a)?) << 8) | (u16::from(nibble(*b)?) << 4) | u16::from(nibble(*c)?);
    let (frame, used) = match payload {
        [b'#', ..] => return None,
        [b'R' | b'r', rest @ ..] => match rest.first().and_then(|&len| nibble(len)) {
            Some(len) => (CanFrame::remote(id, len).ok()?, 2),
            None => (CanFrame::remote(id, 0).ok()?, 1),
        },
        _ => {
            let (data, len, used) = hex_payload(payload)?;
            (CanFrame::from_buffer(id, data, len).ok()?, used)
        }
    };
    Some((frame, 4 + used))
}

/// The data bytes at the start of `payload` (its hex digits up to the first other byte): the
/// bytes, their count and the payload bytes taken. A pair of lookups per byte; a dot among
/// the digits (`DE.AD`) leaves it to [`dotted_payload`].
#[inline(always)]
fn hex_payload(payload: &[u8]) -> Option<([u8; 8], usize, usize)> {
    // 17 bytes (a line and the next in a buffer) are read at fixed places, without a bounds
    // check per digit; a shorter payload is first copied into 17 bytes, a zero after it.
    if let Some(window) = payload.first_chunk::<17>() {
        return hex_window(window, payload);
    }
    let mut padded = [0u8; 17];
    padded[..payload.len()].copy_from_slice(payload);
    hex_window(&padded, payload)
}

/// [`hex_payload`] of the first 17 bytes of `payload`, `window`.
#[inline(always)]
fn hex_window(window: &[u8; 17], payload: &[u8]) -> Option<([u8; 8], usize, usize)> {
    let mut data = [0u8; 8];
    let mut len = 0;
    while len < 8 {
        let high = HEX[usize::from(window[2 * len])];
        if high == INVALID {
            break;
        }
        let low = HEX[usize::from(window[2 * len + 1])];
        if low == INVALID {
            return dotted_payload(payload);
        }
        data[len] = (high << 4) | low;
        len += 1;
    }
    match window[2 * len] {
        b'.' => dotted_payload(payload),
        // A ninth byte: more than a classic frame holds.
        byte if HEX[usize::from(byte)] != INVALID => None,
        _ => Some((data, len, 2 * len)),
    }
}

/// [`hex_payload`] of a payload that may have dots between its digits, digit by digit.
fn dotted_payload(payload: &[u8]) -> Option<([u8; 8], usize, usize)> {
    let mut data = [0u8; 8];
    let mut len = 0;
    let mut high = None;
    let mut used = 0;
    for &byte in payload {
        if byte != b'.' {
            let Some(value) = nibble(byte) else { break };
            match high.take() {
                None => high = Some(value),
                Some(high) => {
                    *data.get_mut(len)? = (high << 4) | value;
                    len += 1;
                }
            }
        }
        used += 1;
    }
    if high.is_some() {
        return None;
    }
    Some((data, len, used))
}

#[cfg(test)]
mod tests {
    use std::format;
    use std::vec::Vec;

    use super::*;

    #[test]
    fn eight_digits_read_as_a_loop_would() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        for round in 0..100_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let text = if round % 2 == 0 {
                format!("{:08}", state % 100_000_000).into_bytes()
            } else {
                // Any bytes, most of them near the digits.
                (0..8)
                    .map(|i| 0x28 + (state >> (8 * i)) as u8 % 24)
                    .collect::<Vec<u8>>()
            };
            let word = u64::from_le_bytes(text.clone().try_into().unwrap());
            let expected = std::str::from_utf8(&text)
                .ok()
                .filter(|t| t.bytes().all(|b| b.is_ascii_digit()))
                .map(|t| t.parse::<u64>().unwrap());
            assert_eq!(eight_digits(word), expected, "{text:?}");
        }
    }

    /// A window read pair by pair reads what a digit-by-digit walk reads, over windows of hex
    /// digits, dots, the bytes next to the digits' ranges, blanks and bytes above 0x7F.
    #[test]
    fn hex_pairs_read_as_digit_by_digit() {
        const BYTES: &[u8] = b"0123456789abcdefABCDEF./:@G`g \n\x80\xC1\xE1\xB0";
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut taken = 0;
        for round in 0..200_000 {
            let mut window = [0u8; 17];
            for (i, byte) in window.iter_mut().enumerate() {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                // Mostly digits, so that long runs and whole frames come up.
                let pick = state as usize % (BYTES.len() * 3);
                *byte = BYTES[if pick < BYTES.len() * 2 {
                    pick % 22
                } else {
                    pick % BYTES.len()
                }];
                if round % 4 == 0 && i == 2 * (round / 4 % 9) {
                    *byte = b'\n';
                }
            }
            let mask = |found: Option<([u8; 8], usize, usize)>| {
                found.map(|(mut data, len, used)| {
                    data[len..].fill(0);
                    (data, len, used)
                })
            };
            let read = mask(hex_window(&window, &window));
            assert_eq!(read, mask(dotted_payload(&window)), "{window:?}");
            taken += usize::from(read.is_some());
        }
        assert!(taken > 20_000, "{taken}");
    }

    #[test]
    fn a_line_in_a_buffer_ends_at_its_newline() {
        let buf = b"(1700000000.000100) can0 601#2301\r\n185#01\n";
        let (first, taken) = parse_line_at(buf).unwrap();
        assert_eq!(first.timestamp_us, Some(1_700_000_000_000_100));
        assert_eq!(taken, 35);
        let (second, taken) = parse_line_at(&buf[35..]).unwrap();
        assert_eq!((second.frame.id(), taken), (0x185, 7));
        // Not whole in the buffer, or text after the frame: left to the line parser.
        for buf in [
            &b"185#01"[..],
            b"185#01 x\n",
            b"185#0\n",
            b"(1.5) can0\n185#01\n",
        ] {
            assert_eq!(parse_line_at(buf), None, "{buf:?}");
        }
    }
}
