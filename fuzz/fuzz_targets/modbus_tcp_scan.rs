//! The Modbus TCP (MBAP) response scanner fed arbitrary received bytes.
//!
//! Input: `[unit, split, transaction (2 bytes, big-endian), request (5 bytes, see
//! src/modbus_request.rs), received bytes...]`. Asserts `fuzz::scan_check::check`, with
//! the MBAP frame check (length, transaction id, unit).
#![no_main]

use drivebus::modbus::framing::Framing;
use drivebus::modbus::tcp::{self, TcpFraming};
use drivebus::modbus::UnitId;
use fuzz::{modbus_request, scan_check, Cursor};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut input = Cursor::new(data);
    let unit = UnitId(input.u8());
    let split = usize::from(input.u8());
    let transaction = input.u16();
    let Some(request) = modbus_request::read(&mut input) else {
        return;
    };
    // The framing numbers its requests: encoding one gives it the transaction id to expect.
    let mut framing = TcpFraming::new(transaction);
    let mut adu = [0u8; tcp::MAX_ADU];
    framing
        .encode_request(unit, &request, &mut adu)
        .expect("a valid request encodes");
    assert_eq!(framing.transaction(), transaction);
    let buf = input.rest();
    scan_check::check(&framing, unit, &request, buf, split, |frame| {
        tcp::open_frame(transaction, unit, frame)
    });
});
