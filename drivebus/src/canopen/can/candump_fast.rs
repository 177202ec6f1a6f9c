//! One pass over a well-formed candump line (issue 33: `drivegen trace` reads millions).
//!
//! Each byte is looked at once: the timestamp's digits are summed as they come, the interface
//! is skipped, the identifier and the data's hex pairs go straight to numbers. Anything else —
//! a malformed line, a long timestamp, a line without an interface, a CAN FD frame — gives
//! `None`, and [`super::candump::parse_line`] parses it field by field, which names the error:
//! what this pass accepts, it reads as that parser does.

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
    if line.first() != Some(&b'(') {
        return Some(Record {
            timestamp_us: None,
            frame: parse_compact(line)?,
        });
    }
    let (timestamp_us, close) = scan_timestamp(line)?;
    let start = frame_start(line, close + 1)?;
    Some(Record {
        timestamp_us: Some(timestamp_us),
        frame: parse_compact(line.get(start..)?)?,
    })
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
fn scan_timestamp(line: &[u8]) -> Option<(u64, usize)> {
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

/// The start of the frame after `(ts)` at `from`: past the separators, the interface and the
/// separators after it. The frame parsed from there holds no separator, so it is the line's
/// last field, the one the field parser takes.
fn frame_start(line: &[u8], from: usize) -> Option<usize> {
    let separator = |b: &u8| *b == b' ' || *b == b'\t';
    let rest = line.get(from..)?;
    let interface = rest.iter().position(|b| !separator(b))?;
    let after = interface + rest[interface..].iter().position(separator)?;
    let frame = after + rest[after..].iter().position(|b| !separator(b))?;
    Some(from + frame)
}

/// A compact frame (`123#DEADBEEF`, `123#DE.AD`, `123#R`, `123#R8`), identifier and data
/// taken digit by digit.
fn parse_compact(text: &[u8]) -> Option<CanFrame> {
    let [a, b, c, b'#', payload @ ..] = text else {
        return None;
    };
    let id = (u16::from(nibble(*a)?) << 8) | (u16::from(nibble(*b)?) << 4) | u16::from(nibble(*c)?);
    match payload {
        [b'#', ..] => return None,
        [b'R' | b'r'] => return CanFrame::remote(id, 0).ok(),
        [b'R' | b'r', len] => return CanFrame::remote(id, nibble(*len)?).ok(),
        [b'R' | b'r', ..] => return None,
        _ => {}
    }
    let mut data = [0u8; 8];
    let mut len = 0;
    let mut high = None;
    for &byte in payload {
        if byte == b'.' {
            continue;
        }
        let value = nibble(byte)?;
        match high.take() {
            None => high = Some(value),
            Some(high) => {
                *data.get_mut(len)? = (high << 4) | value;
                len += 1;
            }
        }
    }
    if high.is_some() {
        return None;
    }
    CanFrame::from_buffer(id, data, len).ok()
}
