//! The SLCAN line decoder fed arbitrary lines (what a serial CAN adapter sends).
//!
//! Input: one line, without its `\r`. Asserts that a decoded frame encodes to a line that
//! decodes to the same frame, and that the encoder's line is what was received up to the case
//! of hex digits and a trailing timestamp.
#![no_main]

use drivebus::canopen::backend::slcan::{decode_line, encode_frame};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|line: &[u8]| {
    let Some(Ok(frame)) = decode_line(line) else {
        return;
    };
    let mut encoded = Vec::new();
    encode_frame(&frame, &mut encoded);
    assert_eq!(encoded.pop(), Some(b'\r'), "an SLCAN line ends in CR");
    assert_eq!(decode_line(&encoded), Some(Ok(frame)), "line {encoded:?}");
    let received = line.get(..encoded.len()).map(<[u8]>::to_ascii_uppercase);
    assert_eq!(
        received.as_deref(),
        Some(&encoded.to_ascii_uppercase()[..]),
        "the line decoded as {frame:?} is not its encoding"
    );
});
