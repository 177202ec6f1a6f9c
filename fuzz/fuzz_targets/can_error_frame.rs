//! The decoder of Linux CAN error frames (what a SocketCAN controller driver reports) fed
//! arbitrary identifiers and data.
//!
//! Input: 4 bytes of error class bits (little-endian), then up to 8 data bytes. Never panics;
//! asserts that a bus-off is always reported as bus-off whatever else the frame says, that the
//! classes are the known bits of the identifier, and that counters appear exactly when the
//! frame says they are valid.
#![no_main]

use drivebus::canopen::can::{BusState, CanErrorReport, ErrorClasses};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|input: &[u8]| {
    let Some((bits, rest)) = input.split_first_chunk::<4>() else {
        return;
    };
    let bits = u32::from_le_bytes(*bits);
    let mut data = [0u8; 8];
    let n = rest.len().min(8);
    data[..n].copy_from_slice(&rest[..n]);
    let report = CanErrorReport::from_linux(bits, data);
    assert_eq!(report.classes, ErrorClasses::from_bits_truncate(bits));
    if report.classes.contains(ErrorClasses::BUS_OFF) {
        assert_eq!(report.state, Some(BusState::BusOff));
    }
    assert_eq!(
        report.counters.is_some(),
        report.classes.contains(ErrorClasses::COUNTERS)
    );
    if report.state.is_some() {
        assert!(report
            .classes
            .intersects(ErrorClasses::BUS_OFF | ErrorClasses::RESTARTED | ErrorClasses::CONTROLLER));
    }
});
