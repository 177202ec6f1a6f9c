//! The Modbus server side fed arbitrary request PDUs: the request decoder and the simulator's
//! server built from a shipped description.
//!
//! Input: `[device, request PDU...]`; `device % 3` picks the Lafert, Lenze or Kinco description.
//! Asserts that
//! * a decoded request re-encodes (as the client encodes it) to the same PDU, up to the unused
//!   bits of a coil write's last byte;
//! * the simulator always answers, with a PDU of at most `MAX_PDU` bytes that is an exception or
//!   carries the request's function code, and that the client's decoder accepts as the answer
//!   to a request it decoded.
#![no_main]

use drivebus::modbus::pdu::{decode_request, decode_response, Request, MAX_PDU};
use drivebus::BusError;
use fuzz::shipped;
use drivesim::Simulator;
use libfuzzer_sys::fuzz_target;

/// The shipped descriptions with a Modbus map.
const DESCRIPTIONS: [&str; 3] = ["lafert-smartris", "lenze-smd", "kinco-fd"];

fuzz_target!(|data: &[u8]| {
    let Some((&device, pdu)) = data.split_first() else {
        return;
    };
    let request = decode_request(pdu).ok();
    if let Some(request) = &request {
        check_re_encodes(request, pdu);
    }
    let sim = Simulator::new(
        shipped::device(DESCRIPTIONS[usize::from(device) % DESCRIPTIONS.len()]).clone(),
    );
    let server = sim.modbus_server();
    let mut out = [0u8; MAX_PDU];
    let len = sim.with(|drive| server.handle(drive, pdu, &mut out));
    assert!((1..=MAX_PDU).contains(&len), "answer of {len} bytes");
    let answer = &out[..len];
    let Some(request) = request else {
        assert!(
            answer[0] & 0x80 != 0,
            "an undecodable request got a normal answer"
        );
        return;
    };
    match decode_response(&request, answer) {
        Ok(_) | Err(BusError::ModbusException { .. }) => {}
        Err(e) => panic!("the client refuses the simulator's answer {answer:02X?}: {e}"),
    }
});

/// The client's encoding of `request` is `pdu`, but for the unused bits of a coil write.
fn check_re_encodes(request: &Request<'_>, pdu: &[u8]) {
    request
        .validate()
        .expect("a request the server decodes is one the client may send");
    let mut out = [0u8; MAX_PDU];
    let len = request.encode(&mut out).expect("a decoded request encodes");
    let mut expected = pdu.to_vec();
    if let Request::WriteMultipleCoils { values, .. } = request {
        let unused = (8 - values.len() % 8) % 8;
        if let Some(last) = expected.last_mut() {
            *last &= 0xFF >> unused;
        }
    }
    assert_eq!(&out[..len], &expected[..], "decoded {request:?}");
    check_values_encode_alike(request, &out[..len]);
}

/// A write built from the decoded values (as a client builds it, from its own slice) equals the
/// decoded request and encodes to the same PDU `encoded`.
fn check_values_encode_alike(request: &Request<'_>, encoded: &[u8]) {
    let (coils, registers): (Vec<bool>, Vec<u16>) = match request {
        Request::WriteMultipleCoils { values, .. } => (values.iter().collect(), Vec::new()),
        Request::WriteMultipleRegisters { values, .. } => (Vec::new(), values.iter().collect()),
        _ => return,
    };
    let (start, _) = request.span();
    let rebuilt = match request {
        Request::WriteMultipleCoils { .. } => Request::write_coils(start, &coils),
        _ => Request::write_registers(start, &registers),
    };
    assert_eq!(&rebuilt, request);
    let mut out = [0u8; MAX_PDU];
    let len = rebuilt.encode(&mut out).expect("a rebuilt request encodes");
    assert_eq!(&out[..len], encoded, "rebuilt {rebuilt:?}");
}
