//! The Modbus RTU response scanner fed arbitrary received bytes.
//!
//! Input: `[unit, split, request (5 bytes, see src/modbus_request.rs), received bytes...]`.
//! Asserts `fuzz::scan_check::check`, with the RTU frame check (address, CRC).
#![no_main]

use drivebus::modbus::rtu::{self, RtuFraming};
use drivebus::modbus::UnitId;
use fuzz::{modbus_request, scan_check, Cursor};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut input = Cursor::new(data);
    let unit = UnitId(input.u8());
    let split = usize::from(input.u8());
    let Some(request) = modbus_request::read(&mut input) else {
        return;
    };
    let buf = input.rest();
    scan_check::check(&RtuFraming, unit, &request, buf, split, |frame| {
        rtu::open_frame(unit, frame)
    });
});
