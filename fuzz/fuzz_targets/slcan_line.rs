//! The SLCAN line parser fed arbitrary lines (what a serial CAN adapter sends, noise included).
//!
//! Input: one line, without its `\r`. Never panics; a line is a frame, a status answer,
//! something ignored, or a typed error. Asserts that a decoded frame encodes to a line that
//! parses to the same frame, that the encoder's line is what was received up to the case of hex
//! digits, and that what follows it is exactly the 4-digit timestamp the parser reported.
#![no_main]

use drivebus::canopen::can::slcan::{decode_line, encode_frame, parse_line, SlcanLine};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|line: &[u8]| {
    let parsed = parse_line(line);
    // The frame-only view agrees with the full parser.
    match (&parsed, decode_line(line)) {
        (Ok(SlcanLine::Frame { frame, .. }), Some(Ok(decoded))) => assert_eq!(*frame, decoded),
        (Ok(SlcanLine::Frame { .. }), other) => panic!("decode_line disagrees: {other:?}"),
        (Ok(_), None) | (Err(_), Some(Err(_))) => {}
        (parsed, other) => panic!("parse_line {parsed:?}, decode_line {other:?}"),
    }
    let Ok(SlcanLine::Frame { frame, timestamp }) = parsed else {
        return;
    };
    let mut encoded = Vec::new();
    encode_frame(&frame, &mut encoded);
    assert_eq!(encoded.pop(), Some(b'\r'), "an SLCAN line ends in CR");
    assert_eq!(
        parse_line(&encoded),
        Ok(SlcanLine::Frame {
            frame,
            timestamp: None
        }),
        "line {encoded:?}"
    );
    let received = line.get(..encoded.len()).map(<[u8]>::to_ascii_uppercase);
    assert_eq!(
        received.as_deref(),
        Some(&encoded.to_ascii_uppercase()[..]),
        "the line decoded as {frame:?} is not its encoding"
    );
    let rest = &line[encoded.len()..];
    match timestamp {
        None => assert!(rest.is_empty(), "{rest:?} after the frame"),
        Some(millis) => {
            let text = std::str::from_utf8(rest).expect("timestamp digits");
            assert_eq!(u16::from_str_radix(text, 16), Ok(millis));
            assert_eq!(rest.len(), 4);
        }
    }
});
