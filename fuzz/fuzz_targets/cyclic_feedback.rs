//! The cyclic synchronous planner (`drivebus::control::cyclic`) fed arbitrary TPDO payloads.
//!
//! Input: a first byte choosing the mode and the following error window, then TPDO payloads,
//! each a length byte (taken modulo 9) and that many bytes; the next sample is derived from the
//! feedback. Asserts that decoding and planning never panic, that a short payload is
//! refused, and that once the planner fails it sends no enable command in its stop.
#![no_main]

use drivebus::control::cyclic::{CyclicAxis, CyclicMode, Feedback};
use drivebus::control::{Millis, Quirks};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let Some((&first, mut rest)) = bytes.split_first() else {
        return;
    };
    let mode = match first % 3 {
        0 => CyclicMode::Position,
        1 => CyclicMode::Velocity,
        _ => CyclicMode::Torque,
    };
    let window = (first & 0x80 != 0).then_some(u32::from(first) * 10);
    let Ok(mut axis) = CyclicAxis::new(mode, 0x0380, Quirks::STANDARD, window) else {
        return;
    };
    let mut now = 0;
    while let Some((&len, tail)) = rest.split_first() {
        let len = usize::from(len % 9).min(tail.len());
        let (payload, next) = tail.split_at(len);
        rest = next;
        now += 1;
        let Some(feedback) = Feedback::from_tpdo(payload) else {
            assert!(payload.len() < 6);
            continue;
        };
        let sample = feedback.actual.wrapping_add(i32::from(first));
        match axis.cycle(feedback, Some(sample), Millis(now)) {
            Ok(command) => {
                let (_, used) = command.rpdo_payload(mode);
                assert!(used == 4 || used == 6);
            }
            Err(_) => {
                assert_eq!(axis.stop(feedback).controlword, 0x0002);
                return;
            }
        }
    }
});
