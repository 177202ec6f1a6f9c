//! The SRDO consumer fed arbitrary frames and clock readings.
//!
//! Input: `[bits, sct, srvt, events...]`; the SRDO carries `bits % 64 + 1` bits, SCT and SRVT
//! are in milliseconds (a configuration the consumer refuses ends the run). Each event is
//! `[step, poll, shape, 8 data bytes]`: the clock advances `step` milliseconds, then an odd
//! `poll` checks the timers, and the frame (see src/can_input.rs, on the normal COB-ID or,
//! with `shape >> 4 == 0` and bit 0 set, the inverted one) arrives. Asserts that
//! * a value is released only on an inverted frame, and it is the data of the normal frame
//!   received just before it on the SRDO's COB-IDs, of the mapping's length;
//! * that inverted frame holds its bitwise complement, within SRVT of the normal frame;
//! * a timer expiry is reported only after `next_deadline`.
#![no_main]

use std::time::Duration;

use drivebus::canopen::srdo::{is_complement, SrdoCobIds, SrdoConsumer, SrdoTiming};
use drivebus::canopen::CanFrame;
use fuzz::{can_input, Cursor};
use libfuzzer_sys::fuzz_target;

const NORMAL: u16 = 0x101;
const INVERTED: u16 = 0x102;

fuzz_target!(|data: &[u8]| {
    let mut input = Cursor::new(data);
    let bits = u32::from(input.u8() % 64) + 1;
    let timing = SrdoTiming::from_millis(input.u8().into(), input.u8().into());
    let cob_ids = SrdoCobIds::new(NORMAL, INVERTED).expect("distinct 11-bit ids");
    let (Ok(timing), Ok(mut consumer)) = (
        timing,
        timing.and_then(|t| SrdoConsumer::new(cob_ids, t, bits)),
    ) else {
        return;
    };
    let bytes = bits.div_ceil(8) as usize;
    let mut now = Duration::ZERO;
    consumer.start(now);
    // The last frame on the SRDO's COB-IDs, and when it came.
    let mut last: Option<(CanFrame, Duration)> = None;
    while !input.is_empty() {
        now += Duration::from_millis(input.u8().into());
        if input.u8() & 1 == 1 {
            let deadline = consumer.next_deadline();
            if consumer.poll(now).is_err() {
                assert!(
                    deadline.is_some_and(|d| now > d),
                    "expiry before {deadline:?}"
                );
            }
        }
        let Some(frame) = can_input::read(&mut input, NORMAL) else {
            break;
        };
        let Some(result) = consumer.handle(&frame, now) else {
            assert!(
                frame.id() != NORMAL && frame.id() != INVERTED,
                "ignored {frame:?}"
            );
            continue;
        };
        if let Ok(Some(payload)) = result {
            assert_eq!(frame.id(), INVERTED, "released on {frame:?}");
            let (normal, at) = last.expect("a released pair has a normal frame");
            assert_eq!(normal.id(), NORMAL, "released after {normal:?}");
            assert_eq!(payload.as_bytes(), normal.data(), "released data");
            assert_eq!(payload.as_bytes().len(), bytes, "released length");
            assert!(
                is_complement(normal.data(), frame.data(), bits),
                "not a complement"
            );
            assert!(now - at <= timing.srvt(), "released after SRVT");
        }
        last = Some((frame, now));
    }
});
